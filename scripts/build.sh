#!/usr/bin/env bash
# Configures and builds into build/ (Release). Extra arguments go to cmake.
# Under CI=true warnings are errors.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${BUILD_DIR:-build}"
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" \
  -DPHYSICS_WARNINGS_AS_ERRORS="$werror" "$@"
cmake --build "$build_dir" -j "$(nproc)"
