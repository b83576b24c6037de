#!/usr/bin/env bash
# Configures and builds into build/ (Release). Extra arguments go to cmake.
# Under CI=true warnings are errors; otherwise the build directory keeps whatever it
# was configured with, so switching between the two does not rebuild everything.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${BUILD_DIR:-build}"
extra=()
if [ "${CI:-}" = "true" ]; then extra+=(-DPHYSICS_WARNINGS_AS_ERRORS=ON); fi
source scripts/lib/compiler-cache.sh
extra+=("${compiler_cache[@]}")
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" \
  "${extra[@]}" "$@"
cmake --build "$build_dir" -j "$(nproc)"
