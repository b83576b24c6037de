#!/usr/bin/env bash
# Builds the libFuzzer harnesses of tests/fuzz in the clang build the three clang
# scripts share (scripts/lib/clang-build.sh, build-clang/) and runs
# each for FUZZ_SECONDS (default 15 s, CI's short run) from its committed seeds in
# tests/fuzz/corpus/NAME/; any crash, leak, sanitizer report or timeout fails the run,
# and the input that did it is left in build-clang/artifacts/.
#   scripts/test-fuzz.sh            build and fuzz, 15 s each
#   scripts/test-fuzz.sh --long     the nightly (or local) run: 600 s each, unless
#                                   FUZZ_SECONDS says otherwise
#   scripts/test-fuzz.sh --seeds    rewrite tests/fuzz/corpus/ from real messages
# FUZZ_HARNESSES="replay scene" runs only those (default: all seven); FUZZ_JOBS=1 runs
# them one at a time (default: as many at once as there are cores).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/clang-build.sh
build_dir="$clang_build_dir"
default_seconds=15
if [ "${1:-}" = "--long" ]; then default_seconds=600; fi
seconds="${FUZZ_SECONDS:-$default_seconds}"
read -r -a harnesses <<<"${FUZZ_HARNESSES:-server_messages client snapshot scene replay world_bytes relay_follow}"

targets=(make_fuzz_seeds)
for name in "${harnesses[@]}"; do targets+=("${name}_fuzz"); done
clang_build "${targets[@]}"

if [ "${1:-}" = "--seeds" ]; then
  # Overwrites the generated seeds; inputs kept by hand (crashes found) stay.
  "$build_dir/tests/fuzz/make_fuzz_seeds" tests/fuzz/corpus scenes
  ls -R tests/fuzz/corpus
  exit 0
fi

mkdir -p "$build_dir/artifacts"
# fuzz NAME: one harness for $seconds from its seeds; its output in $build_dir/NAME.log and
# its exit status in $build_dir/NAME.status. New inputs go to a scratch corpus; the
# committed seeds are only read.
fuzz() {
  local name="$1" work="$build_dir/corpus/$1" status=0
  mkdir -p "$work"
  "$build_dir/tests/fuzz/${name}_fuzz" "$work" "tests/fuzz/corpus/$name" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build_dir/artifacts/$name-" 2>"$build_dir/$name.log" || status=$?
  echo "$status" >"$build_dir/$name.status"
}

# A libFuzzer run uses one core: FUZZ_JOBS harnesses (default: one a core) run side by
# side, each still for its whole time.
jobs_max="${FUZZ_JOBS:-$(nproc)}"
for name in "${harnesses[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do wait -n || true; done
  echo "fuzz: $name for $seconds s"
  rm -f "$build_dir/$name.status"
  fuzz "$name" &
done
wait

failed=0
for name in "${harnesses[@]}"; do
  if [ "$(cat "$build_dir/$name.status" 2>/dev/null)" != 0 ]; then
    tail -n 60 "$build_dir/$name.log"
    echo "fuzz: $name FAILED; the input is in $build_dir/artifacts/" >&2
    failed=1
    continue
  fi
  echo "fuzz: $name $(grep -E '^stat::(number_of_executed_units|peak_rss_mb)' "$build_dir/$name.log" | tr '\n' ' ')"
done
exit "$failed"
