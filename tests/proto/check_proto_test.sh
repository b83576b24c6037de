#!/usr/bin/env bash
# scripts/check-proto.sh on copies of proto/ whose current files are the released
# ones plus one change: a breaking change without a version bump fails; the same
# change with PROTOCOL_VERSION_CURRENT bumped passes; an added field (not breaking)
# passes without a bump; a version below the released one fails; and a lint error
# fails.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
check="$root/scripts/check-proto.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

# A copy of proto/ whose current files are the released ones: version unbumped.
fresh_copy() {
  rm -rf "$work/proto"
  mkdir -p "$work/proto/released"
  cp "$root/proto/buf.yaml" "$work/proto/"
  cp "$root"/proto/released/*.proto "$work/proto/released/"
  cp "$root"/proto/released/*.proto "$work/proto/"
}
released=$(sed -n 's/^ *PROTOCOL_VERSION_CURRENT *= *\([0-9][0-9]*\) *;.*/\1/p' \
  "$root/proto/released/wire.proto")
set_version() {
  sed -i "s/PROTOCOL_VERSION_CURRENT = [0-9]*;/PROTOCOL_VERSION_CURRENT = $1;/" "$work/proto/wire.proto"
}
# A field's type changed: the same number read as another wire type.
break_vec2() {
  grep -q '^  double x = 1;$' "$work/proto/wire.proto"
  sed -i '0,/^  double x = 1;$/s//  float x = 1;/' "$work/proto/wire.proto"
}
expect() {
  local want="$1" what="$2" rc=0
  "$check" "$work/proto" >"$work/out" 2>&1 || rc=$?
  if { [ "$want" = pass ] && [ "$rc" -ne 0 ]; } || { [ "$want" = fail ] && [ "$rc" -ne 1 ]; }; then
    echo "FAILED: $what: expected $want, exit $rc"
    cat "$work/out"
    failures=$((failures + 1))
  else
    echo "ok: $what ($want, exit $rc)"
  fi
}

fresh_copy
expect pass "the released files unchanged"

fresh_copy
break_vec2
expect fail "a breaking change without a version bump"
grep -q 'bump' "$work/out" || { echo "FAILED: no word of the bump"; failures=$((failures + 1)); }

fresh_copy
break_vec2
set_version $((released + 1))
expect pass "the same breaking change with the version bumped"

fresh_copy
sed -i '0,/^  double y = 2;$/s//  double y = 2;\n  double z = 3;/' "$work/proto/wire.proto"
grep -q '^  double z = 3;$' "$work/proto/wire.proto"
expect pass "an added field without a bump"

fresh_copy
set_version $((released - 1))
expect fail "a version below the released one"

fresh_copy
printf '\nmessage lower_case_name {}\n' >>"$work/proto/wire.proto"
expect fail "a lint error"

if [ "$failures" -ne 0 ]; then
  echo "$failures case(s) failed"
  exit 1
fi
