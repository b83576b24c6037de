#!/usr/bin/env bash
# AddressSanitizer and UndefinedBehaviorSanitizer over the wire, server and
# integration suites: the code that reads what peers send. Builds only those targets,
# in the clang build that scripts/test-clang.sh and scripts/test-fuzz.sh share
# (scripts/lib/clang-build.sh); the first report fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/clang-build.sh
clang_build wire_tests server_tests server_socket_tests physics_integration_tests
# Every test of those four executables (their suites, read from the binaries).
suites=$(for t in tests/wire/wire_tests tests/server/server_tests tests/server/server_socket_tests \
  tests/integration/physics_integration_tests; do
  "$clang_build_dir/$t" --gtest_list_tests | sed -n 's/^\([^ ][^ ]*\)\..*$/\1/p'
done | sort -u | paste -sd '|')
ctest --test-dir "$clang_build_dir" --output-on-failure -j "$(nproc)" --timeout 300 \
  -R "^(${suites})\\."
