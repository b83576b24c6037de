# Sourced by scripts/test-clang.sh, scripts/test-asan.sh and scripts/test-fuzz.sh:
# the one clang build the three share, in CLANG_BUILD_DIR (default build-clang/).
# Clang 14 with AddressSanitizer + UBSan and libFuzzer's coverage (PHYSICS_FUZZ),
# at -O1 with line tables and without NDEBUG (asserts on, readable reports, fast
# enough to fuzz and to run the suites). One build
# instead of three: the server and its tests are compiled once for all of them.
#
# clang_build TARGET...: configures the build directory and builds the targets.
source scripts/lib/compiler-cache.sh
clang_build_dir="${CLANG_BUILD_DIR:-build-clang}"

clang_build() {
  local werror=OFF
  if [ "${CI:-}" = "true" ]; then werror=ON; fi
  cmake -S . -B "$clang_build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DPHYSICS_FUZZ=ON \
    -DPHYSICS_BUILD_BENCH=OFF -DPHYSICS_WARNINGS_AS_ERRORS="$werror" "${compiler_cache[@]}"
  cmake --build "$clang_build_dir" -j "$(nproc)" --target "$@"
}

# The sanitizers' options for every run: the first report fails it.
export ASAN_OPTIONS="${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}"
