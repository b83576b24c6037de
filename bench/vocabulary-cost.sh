#!/usr/bin/env bash
# What the physics vocabulary (filters, sensors, kinematic bodies; docs/PHYSICS.md)
# costs, in instructions counted by callgrind (repeatable on a shared machine, where
# times are not). Every scene of scenes/ is flattened (physics-flatten) and stepped by
# physics-hashes, the core alone, as built from another revision's tree
# (BASELINE_HASHES) and from this one; then this tree's physics-hashes steps
# large-4000 with one piece of the vocabulary added. Writes
# bench/results/vocabulary-cost.csv and prints it: scene, steps, the baseline's and
# this tree's instructions (the whole process: reading the flat world is the same in
# both), their ratio. The large-4000 variants have no baseline: their ratio is to
# this tree's plain large-4000.
#
#   BASELINE_HASHES=../other/build/portable/physics-hashes bench/vocabulary-cost.sh
#
# STEPS (default 300) steps per scene; BUILD_DIR (default build) holds this tree's
# physics-flatten and physics-hashes.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build}"
ours="$build/portable/physics-hashes"
flatten="$build/portable/physics-flatten"
baseline="${BASELINE_HASHES:?BASELINE_HASHES=path to the baseline physics-hashes}"
steps="${STEPS:-300}"
out=bench/results/vocabulary-cost.csv
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

instructions() {
  valgrind --tool=callgrind --callgrind-out-file="$work/out" "$1" --steps "$steps" "$2" \
    >/dev/null 2>"$work/log"
  sed -n 's/^==[0-9]*== Collected : //p' "$work/log"
}

# large-4000 with one thing added: a sensor over the left half of the pile; a
# kinematic box moving along the top (away from the pile); every grid body in
# category 2 (filtering on, every pair still colliding).
large=scenes/large-4000.textproto
cp "$large" "$work/large-sensor.textproto"
cat >>"$work/large-sensor.textproto" <<'SCENE'
bodies { name: "zone" box { half_extents { x: 20 y: 10 } } is_static: true is_sensor: true
         position { x: -20 y: 10 } }
SCENE
cp "$large" "$work/large-kinematic.textproto"
cat >>"$work/large-kinematic.textproto" <<'SCENE'
bodies { name: "shuttle" box { half_extents { x: 1 y: 0.5 } } is_kinematic: true
         position { x: -35 y: 115 } velocity { x: 1 y: 0 } }
SCENE
sed 's/^    mass: \([12]\)$/    mass: \1\n    category_bits: 2/' "$large" >"$work/large-filtered.textproto"
grep -q category_bits "$work/large-filtered.textproto"

echo "scene,steps,baseline_instructions,instructions,ratio" >"$out"
for scene in scenes/*.textproto; do
  name=$(basename "$scene" .textproto)
  "$flatten" "$scene" "$work/$name.json"
  # A world the baseline cannot read (version 2: the vocabulary) has no baseline.
  old=""
  if grep -q '^\[1,' "$work/$name.json"; then old=$(instructions "$baseline" "$work/$name.json"); fi
  new=$(instructions "$ours" "$work/$name.json")
  echo "$name,$steps,$old,$new,$(awk -v a="$old" -v b="$new" \
    'BEGIN { if (a > 0) printf "%.4f", b / a }')" >>"$out"
done
plain=$(awk -F, '$1 == "large-4000" { print $4 }' "$out")
for variant in large-sensor large-kinematic large-filtered; do
  "$flatten" "$work/$variant.textproto" "$work/$variant.json"
  new=$(instructions "$ours" "$work/$variant.json")
  echo "$variant,$steps,,$new,$(awk -v a="$plain" -v b="$new" 'BEGIN { printf "%.4f", b / a }')" \
    >>"$out"
done
cat "$out"
