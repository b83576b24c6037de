# Sourced by scripts/test-aarch64.sh and scripts/test-wasm.sh: the native hashes a
# cross build must equal, and the comparison.
#
# native_hashes WORK: builds physics-sim, physics-flatten and physics-hashes natively
# (NATIVE_BUILD_DIR, default build/), writes WORK/flat/NAME.json for every
# scenes/NAME.textproto, and WORK/native.txt: "NAME.json HASH" after $steps steps as
# physics-sim prints it, then "NAME HASH" for each golden world (physics-hashes
# --library). Fails when physics-hashes on the flat worlds disagrees with
# physics-sim on the scene files (a flat world that lost something). The results are
# kept in NATIVE_BUILD_DIR/native-hashes/ and reused by the next cross build's run
# while the three programs and scenes/ are older than them (CI runs both cross builds).
#
# compare_hashes PLATFORM NATIVE CROSS: a table of both, one line a world; returns 1
# when any differs or is missing.
steps=600

native_hashes() {
  local work="$1" native_dir="${NATIVE_BUILD_DIR:-build}"
  mkdir -p "$work/flat"
  if [ ! -f "$native_dir/CMakeCache.txt" ]; then
    cmake -S . -B "$native_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPHYSICS_BUILD_BENCH=OFF
  fi
  cmake --build "$native_dir" -j "$(nproc)" --target physics-sim physics-flatten physics-hashes
  local kept="$native_dir/native-hashes"
  if [ -f "$kept/native.txt" ] && [ -z "$(find "$native_dir/server/sim/physics-sim" \
    "$native_dir/portable/physics-flatten" "$native_dir/portable/physics-hashes" scenes \
    -newer "$kept/native.txt" -print -quit)" ]; then
    echo "native hashes: the ones in $kept (nothing they come from changed since)"
    cp "$kept"/flat/*.json "$work/flat/"
    cp "$kept/native.txt" "$work/native.txt"
    return 0
  fi
  : >"$work/native.txt"
  local scene name hash
  for scene in scenes/*.textproto; do
    name="$(basename "$scene" .textproto).json"
    "$native_dir/portable/physics-flatten" "$scene" "$work/flat/$name"
    hash=$("$native_dir/server/sim/physics-sim" --scene "$scene" --steps "$steps" --json |
      sed -n 's/.*"state_hash":"\([0-9a-f]*\)".*/\1/p' | tail -n 1)
    echo "$name $hash" >>"$work/native.txt"
  done
  "$native_dir/portable/physics-hashes" --steps "$steps" "$work"/flat/*.json >"$work/native-flat.txt"
  if ! cmp -s "$work/native.txt" "$work/native-flat.txt"; then
    echo "physics-hashes on the flat worlds differs from physics-sim on the scene files:" >&2
    diff "$work/native.txt" "$work/native-flat.txt" >&2 || true
    return 1
  fi
  "$native_dir/portable/physics-hashes" --library >>"$work/native.txt"
  rm -rf "$kept"
  mkdir -p "$kept/flat"
  cp "$work"/flat/*.json "$kept/flat/"
  cp "$work/native.txt" "$kept/native.txt"
}

compare_hashes() {
  local platform="$1" native="$2" cross="$3" failed=0 name hash other verdict
  printf '%-28s %-16s  %-16s\n' "world" "x86-64" "$platform"
  while read -r name hash; do
    other=$(awk -v n="$name" '$1 == n { print $2 }' "$cross")
    verdict=equal
    if [ -z "$hash" ] || [ "$hash" != "$other" ]; then
      verdict=DIFFERENT
      failed=1
    fi
    printf '%-28s %-16s  %-16s  %s\n' "$name" "$hash" "${other:-missing}" "$verdict"
  done <"$native"
  return "$failed"
}
