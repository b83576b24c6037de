#!/usr/bin/env bash
# AddressSanitizer and UndefinedBehaviorSanitizer over the suites labelled `asan` where
# they are declared (tests/*/CMakeLists.txt): the wire, server, integration and
# predicting client's suites and the link conditioner's, the code that reads what peers
# send. Builds only their executables (the target physics_asan_tests), in the clang
# build that scripts/test-clang.sh and scripts/test-fuzz.sh share
# (scripts/lib/clang-build.sh), and runs `ctest -L asan`; the first report fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/clang-build.sh
clang_build physics_asan_tests
ctest --test-dir "$clang_build_dir" --output-on-failure -j "$(nproc)" --timeout 300 -L '^asan$'
