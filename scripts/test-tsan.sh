#!/usr/bin/env bash
# ThreadSanitizer over the tests that run a real server on its own thread and talk
# to it over loopback: the server must stay free of data races. The suites are the
# ones labelled `tsan` where they are declared (tests/*/CMakeLists.txt); this builds
# only their executables (the target physics_tsan_tests), into build-tsan/ (Debug
# keeps the reports readable and the build short), and runs `ctest -L tsan`.
# The Tool suite's lockstep golden checks the Debug build's hash on the way.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/compiler-cache.sh
build_dir="${TSAN_BUILD_DIR:-build-tsan}"
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DPHYSICS_TSAN=ON \
  -DPHYSICS_BUILD_BENCH=OFF -DPHYSICS_WARNINGS_AS_ERRORS="$werror" "${compiler_cache[@]}"
cmake --build "$build_dir" -j "$(nproc)" --target physics_tsan_tests
# halt_on_error: the first race fails the run instead of scrolling past.
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1"
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" --timeout 300 -L '^tsan$'
