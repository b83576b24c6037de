#!/usr/bin/env bash
# Determinism in WebAssembly: builds the core, the scene library, physics-hashes and
# the core's WebAssembly package (client/web/core-wasm) alone (no Protobuf) with
# Debian's emscripten into build-wasm/, and runs them under node:
#   - physics-hashes, compared world by world with the native x86-64 build: every
#     scene in scenes/ after 600 steps (loaded from physics-flatten's flat world), the
#     determinism scene, the scene library's golden worlds, a hash of det_math's
#     results; fails on any difference;
#   - the package's tests (node's test runner), whose every scene must end on native
#     physics-sim's hash.
# Debian's emscripten 3.1.6 links at -O0 (its JavaScript optimizer fails at -O2) and
# its output loads under node 20 only with --no-experimental-fetch. Installs
# emscripten (and node where missing) when missing (scripts/install-deps.sh wasm).
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/lib/cross-hashes.sh
cross_dir="${WASM_BUILD_DIR:-build-wasm}"
package=client/web/core-wasm
work="$cross_dir/hashes"

bash scripts/install-deps.sh wasm
native_hashes "$work"

emcmake cmake -S . -B "$cross_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DPHYSICS_CORE_ONLY=ON -DPHYSICS_BUILD_TESTS=OFF -DPHYSICS_BUILD_BENCH=OFF \
  -DPHYSICS_WARNINGS_AS_ERRORS=ON
cmake --build "$cross_dir" -j "$(nproc)" --target physics-hashes physics-core

node=(node --no-experimental-fetch)
"${node[@]}" "$cross_dir/portable/physics-hashes.js" --steps "$steps" "$work"/flat/*.json \
  >"$work/wasm.txt"
"${node[@]}" "$cross_dir/portable/physics-hashes.js" --library >>"$work/wasm.txt"
echo "state hashes: x86-64 (native) against WebAssembly (node $(node --version))"
failed=0
compare_hashes wasm "$work/native.txt" "$work/wasm.txt" || failed=1

# The package: its module in dist/, and a case per scene with native physics-sim's hash.
mkdir -p "$package/dist"
cp "$cross_dir/client/web/core-wasm/physics-core.js" "$cross_dir/client/web/core-wasm/physics-core.wasm" \
  "$package/dist/"
cases="$(pwd)/$work/cases.json"
awk -v flat="$(pwd)/$work/flat" -v steps="$steps" '
  BEGIN { printf "[" }
  $1 ~ /\.json$/ {
    printf "%s{\"scene\":\"%s\",\"flat\":\"%s/%s\",\"steps\":%d,\"hash\":\"%s\"}",
      (n++ ? "," : ""), $1, flat, $1, steps, $2
  }
  END { print "]" }' "$work/native.txt" >"$cases"
(cd "$package" && CORE_WASM_CASES="$cases" "${node[@]}" --test test/) || failed=1
exit "$failed"
