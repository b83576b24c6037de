#!/usr/bin/env bash
# AddressSanitizer and UndefinedBehaviorSanitizer (PHYSICS_SANITIZE) over the wire,
# server and integration suites: the code that reads what peers send. Builds only
# those targets, into build-asan/ (Debug keeps the reports readable and the build
# short); the first report fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${ASAN_BUILD_DIR:-build-asan}"
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DPHYSICS_SANITIZE=ON \
  -DPHYSICS_BUILD_BENCH=OFF -DPHYSICS_WARNINGS_AS_ERRORS="$werror"
cmake --build "$build_dir" -j "$(nproc)" \
  --target wire_tests server_tests server_socket_tests physics_integration_tests
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:strict_string_checks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# Every test of those four executables (their suites, read from the binaries).
suites=$(for t in tests/wire/wire_tests tests/server/server_tests tests/server/server_socket_tests \
  tests/integration/physics_integration_tests; do
  "$build_dir/$t" --gtest_list_tests | sed -n 's/^\([^ ][^ ]*\)\..*$/\1/p'
done | sort -u | paste -sd '|')
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" --timeout 300 \
  -R "^(${suites})\\."
