#!/usr/bin/env bash
# The WebAssembly core's step time against the native core's on the same machine:
# physics-hashes built natively (NATIVE_BUILD_DIR, default build/) and by Debian's
# emscripten (WASM_BUILD_DIR, default build-wasm/, as scripts/test-wasm.sh builds it;
# run under node), on rain-1000 (the bench's rain, physics-flatten --rain) and
# moving-1000 (scenes/moving-1000.textproto), native and WebAssembly in turns,
# REPEATS times (default 5). A step's cost is CPU time (user + system of the whole
# process, so a shared machine's waiting is left out): a run of STEPS steps (default
# 600) less a run of 0 steps (loading, building the world, node's start and the
# module's compilation, with V8's optimizing compiler from the start), divided by
# STEPS. Writes bench/results/wasm-speed.csv (scene, repeat, each one's CPU ms per
# step, their ratio, whether both ended on the same state hash) and prints each
# scene's medians. Exits 1 when a hash differs.
set -euo pipefail
cd "$(dirname "$0")/.."
native_dir="${NATIVE_BUILD_DIR:-build}"
wasm_dir="${WASM_BUILD_DIR:-build-wasm}"
repeats="${REPEATS:-5}"
steps="${STEPS:-600}"
out="${OUT:-bench/results/wasm-speed.csv}"
work="$wasm_dir/speed"
mkdir -p "$work"
cmake --build "$native_dir" --target physics-flatten physics-hashes
cmake --build "$wasm_dir" --target physics-hashes
"$native_dir/portable/physics-flatten" --rain 1000 "$work/rain-1000.json"
"$native_dir/portable/physics-flatten" scenes/moving-1000.textproto "$work/moving-1000.json"

# cpu_ms CMD...: user + system CPU milliseconds of CMD (its output discarded).
cpu_ms() {
  local TIMEFORMAT='%U %S' times
  times=$( { time "$@" >/dev/null; } 2>&1 | tail -n 1)
  awk -v t="$times" 'BEGIN { split(t, a, " "); printf "%.1f", 1000 * (a[1] + a[2]) }'
}
per_step() {  # per_step FULL_MS EMPTY_MS
  awk -v f="$1" -v e="$2" -v n="$steps" 'BEGIN { printf "%.4f", (f - e) / n }'
}
native=("$native_dir/portable/physics-hashes")
# --no-liftoff: V8 compiles the module with its optimizing compiler at load (in both
# runs, so subtracted), as a browser runs it once the step is hot; otherwise the
# optimizing compilation of the step's functions lands inside the timed steps.
wasm=(node --no-experimental-fetch --no-liftoff "$wasm_dir/portable/physics-hashes.js")

echo "scene,repeat,native_cpu_ms_per_step,wasm_cpu_ms_per_step,ratio,same_hash" >"$out"
failed=0
for scene in rain-1000 moving-1000; do
  flat="$work/$scene.json"
  for repeat in $(seq 1 "$repeats"); do
    native_ms=$(per_step "$(cpu_ms "${native[@]}" --steps "$steps" "$flat")" \
      "$(cpu_ms "${native[@]}" --steps 0 "$flat")")
    wasm_ms=$(per_step "$(cpu_ms "${wasm[@]}" --steps "$steps" "$flat")" \
      "$(cpu_ms "${wasm[@]}" --steps 0 "$flat")")
    same=yes
    [ "$("${native[@]}" --steps "$steps" "$flat")" = "$("${wasm[@]}" --steps "$steps" "$flat")" ] ||
      { same=no; failed=1; }
    ratio=$(awk -v w="$wasm_ms" -v n="$native_ms" 'BEGIN { printf "%.3f", w / n }')
    echo "$scene,$repeat,$native_ms,$wasm_ms,$ratio,$same" >>"$out"
  done
done
echo "WebAssembly (node $(node --version)) against native, CPU ms per step over $steps steps, median of $repeats:"
median() {  # median of column $2 for scene $1
  awk -F, -v s="$1" -v c="$2" '$1 == s { print $c }' "$out" | sort -g |
    awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'
}
for scene in rain-1000 moving-1000; do
  printf '%-12s native %s ms  wasm %s ms  ratio %s\n' "$scene" "$(median "$scene" 3)" \
    "$(median "$scene" 4)" "$(median "$scene" 5)"
done
exit "$failed"
