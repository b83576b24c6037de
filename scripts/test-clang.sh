#!/usr/bin/env bash
# Determinism across compilers: builds the physics core and the suites that hold
# golden state hashes (core unit tests with the determinism test, stability, scene,
# the server's Simulation) with Debian's clang 14, in the sanitized clang build the
# three clang scripts share (scripts/lib/clang-build.sh), and runs them.
# The goldens are gcc's values, so passing means clang's results equal gcc's. Then
# it runs every scene in scenes/ for 600 steps with physics-sim built by gcc
# (build/, or GCC_BUILD_DIR) and by clang, prints both hashes and fails on any
# difference.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/clang-build.sh
build_dir="$clang_build_dir"
gcc_dir="${GCC_BUILD_DIR:-build}"
steps=600

clang_build core_unit_tests stability_tests scene_tests server_tests physics-sim
# Every test of the core and stability suites, the scene suite and physics-sim's golden.
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" --timeout 900 \
  -L '^(unit|stability)$'
"$build_dir/tests/scene/scene_tests"
"$build_dir/tests/server/server_tests" --gtest_filter='Simulation*'
ctest --test-dir "$build_dir" --output-on-failure --timeout 300 -R '^physics_sim_cli$'

# The same scenes, gcc against clang, hash by hash.
if [ ! -f "$gcc_dir/CMakeCache.txt" ]; then
  cmake -S . -B "$gcc_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPHYSICS_BUILD_BENCH=OFF
fi
cmake --build "$gcc_dir" -j "$(nproc)" --target physics-sim
gcc_cxx=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$gcc_dir/CMakeCache.txt")
clang_cxx=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build_dir/CMakeCache.txt")
echo "scene hashes after $steps steps: $gcc_cxx ($gcc_dir) against $clang_cxx ($build_dir)"
failed=0
for scene in scenes/*.textproto; do
  hash_of() {
    "$1/server/sim/physics-sim" --scene "$scene" --steps "$steps" --json |
      sed -n 's/.*"state_hash":"\([0-9a-f]*\)".*/\1/p' | tail -n 1
  }
  gcc_hash=$(hash_of "$gcc_dir")
  clang_hash=$(hash_of "$build_dir")
  verdict=equal
  if [ -z "$gcc_hash" ] || [ "$gcc_hash" != "$clang_hash" ]; then
    verdict=DIFFERENT
    failed=1
  fi
  printf '%-28s gcc %s  clang %s  %s\n' "$(basename "$scene")" "$gcc_hash" "$clang_hash" \
    "$verdict"
done
exit "$failed"
