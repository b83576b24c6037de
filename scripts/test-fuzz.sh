#!/usr/bin/env bash
# Builds the libFuzzer harnesses of tests/fuzz with clang 14 into build-fuzz/ and runs
# each for FUZZ_SECONDS (default 15 s, CI's short run) from its committed seeds in
# tests/fuzz/corpus/NAME/; any crash, leak, sanitizer report or timeout fails the run,
# and the input that did it is left in build-fuzz/artifacts/.
#   scripts/test-fuzz.sh            build and fuzz, 15 s each
#   scripts/test-fuzz.sh --long     the nightly (or local) run: 600 s each, unless
#                                   FUZZ_SECONDS says otherwise
#   scripts/test-fuzz.sh --seeds    rewrite tests/fuzz/corpus/ from real messages
# FUZZ_HARNESSES="replay scene" runs only those (default: all five).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${FUZZ_BUILD_DIR:-build-fuzz}"
default_seconds=15
if [ "${1:-}" = "--long" ]; then default_seconds=600; fi
seconds="${FUZZ_SECONDS:-$default_seconds}"
read -r -a harnesses <<<"${FUZZ_HARNESSES:-server_messages client snapshot scene replay}"
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi

# -O1 -g without NDEBUG: fast enough to fuzz, asserts on, readable stacks.
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DPHYSICS_FUZZ=ON \
  -DPHYSICS_BUILD_BENCH=OFF -DPHYSICS_WARNINGS_AS_ERRORS="$werror"
targets=(make_fuzz_seeds)
for name in "${harnesses[@]}"; do targets+=("${name}_fuzz"); done
cmake --build "$build_dir" -j "$(nproc)" --target "${targets[@]}"

if [ "${1:-}" = "--seeds" ]; then
  # Overwrites the generated seeds; inputs kept by hand (crashes found) stay.
  "$build_dir/tests/fuzz/make_fuzz_seeds" tests/fuzz/corpus scenes
  ls -R tests/fuzz/corpus
  exit 0
fi

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
mkdir -p "$build_dir/artifacts"
for name in "${harnesses[@]}"; do
  # New inputs go to a scratch corpus; the committed seeds are only read.
  work="$build_dir/corpus/$name"
  mkdir -p "$work"
  echo "fuzz: $name for $seconds s"
  "$build_dir/tests/fuzz/${name}_fuzz" "$work" "tests/fuzz/corpus/$name" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build_dir/artifacts/$name-" 2>"$build_dir/$name.log" || {
    tail -n 60 "$build_dir/$name.log"
    echo "fuzz: $name FAILED; the input is in $build_dir/artifacts/" >&2
    exit 1
  }
  grep -E '^stat::(number_of_executed_units|peak_rss_mb)' "$build_dir/$name.log" | tr '\n' ' '
  echo
done
