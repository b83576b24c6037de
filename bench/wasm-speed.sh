#!/usr/bin/env bash
# The WebAssembly core's step time against the native core's on the same machine:
# physics-hashes --time built natively (NATIVE_BUILD_DIR, default build/) and by
# Debian's emscripten (WASM_BUILD_DIR, default build-wasm/, as scripts/test-wasm.sh
# builds it; run under node), on rain-1000 (the bench's rain, physics-flatten --rain)
# and moving-1000 (scenes/moving-1000.textproto), 600 steps each, native and
# WebAssembly in turns, REPEATS times (default 3). Writes
# bench/results/wasm-speed.csv (scene, repeat, each one's mean wall ms per step,
# their ratio, whether both ended on the same state hash) and prints each scene's
# median ratio. Exits 1 when a hash differs.
set -euo pipefail
cd "$(dirname "$0")/.."
native_dir="${NATIVE_BUILD_DIR:-build}"
wasm_dir="${WASM_BUILD_DIR:-build-wasm}"
repeats="${REPEATS:-3}"
out="${OUT:-bench/results/wasm-speed.csv}"
work="$wasm_dir/speed"
mkdir -p "$work"
cmake --build "$native_dir" --target physics-flatten physics-hashes
cmake --build "$wasm_dir" --target physics-hashes
"$native_dir/portable/physics-flatten" --rain 1000 "$work/rain-1000.json"
"$native_dir/portable/physics-flatten" scenes/moving-1000.textproto "$work/moving-1000.json"

echo "scene,repeat,native_ms_per_step,wasm_ms_per_step,ratio,same_hash" >"$out"
failed=0
for scene in rain-1000 moving-1000; do
  for repeat in $(seq 1 "$repeats"); do
    read -r _ native_hash native_ms < <("$native_dir/portable/physics-hashes" --time "$work/$scene.json")
    read -r _ wasm_hash wasm_ms < <(node --no-experimental-fetch \
      "$wasm_dir/portable/physics-hashes.js" --time "$work/$scene.json")
    same=yes
    [ "$native_hash" = "$wasm_hash" ] || { same=no; failed=1; }
    ratio=$(awk -v w="$wasm_ms" -v n="$native_ms" 'BEGIN { printf "%.3f", w / n }')
    echo "$scene,$repeat,$native_ms,$wasm_ms,$ratio,$same" >>"$out"
  done
done
echo "WebAssembly (node $(node --version)) against native, wall ms per step, median of $repeats:"
median() {  # median of column $2 for scene $1
  awk -F, -v s="$1" -v c="$2" '$1 == s { print $c }' "$out" | sort -g |
    awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'
}
for scene in rain-1000 moving-1000; do
  printf '%-12s native %s ms  wasm %s ms  ratio %s\n' "$scene" "$(median "$scene" 3)" \
    "$(median "$scene" 4)" "$(median "$scene" 5)"
done
exit "$failed"
