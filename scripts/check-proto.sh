#!/usr/bin/env bash
# The protocol's contract, checked by buf (tools/buf, installed from its lock file):
#   1. buf lint of proto/ (proto/buf.yaml: STANDARD, less the rules its exceptions
#      give reasons for);
#   2. buf breaking of proto/ against the last released protocol version's files
#      (proto/released/), WIRE_JSON rules: a change that a peer of that version could
#      misread, in the binary or the JSON form. Such a change fails, unless
#      PROTOCOL_VERSION_CURRENT in wire.proto is above the released one (peers of
#      the old version are then refused in their Hello); a version below the
#      released one always fails.
#   scripts/check-proto.sh          checks proto/
#   scripts/check-proto.sh DIR      checks DIR instead: a copy of proto/ with its
#                                   buf.yaml and released/ (tests/proto uses it)
# Exit 0: the contract holds; 1: it does not (the reason is printed); 2: usage.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
proto_dir="${1:-$root/proto}"
if [ ! -f "$proto_dir/buf.yaml" ] || [ ! -d "$proto_dir/released" ]; then
  echo "check-proto: $proto_dir holds no buf.yaml and released/" >&2
  exit 2
fi

tools="$root/tools/buf"
buf="$tools/node_modules/.bin/buf"
if [ ! -x "$buf" ]; then
  command -v npm >/dev/null || "$root/scripts/install-deps.sh" web
  (cd "$tools" && npm ci --no-audit --no-fund --loglevel=error)
fi

version_of() {
  sed -n 's/^ *PROTOCOL_VERSION_CURRENT *= *\([0-9][0-9]*\) *;.*/\1/p' "$1"
}
current=$(version_of "$proto_dir/wire.proto")
released=$(version_of "$proto_dir/released/wire.proto")
if [ -z "$current" ] || [ -z "$released" ]; then
  echo "check-proto: no PROTOCOL_VERSION_CURRENT in wire.proto or released/wire.proto" >&2
  exit 1
fi

echo "check-proto: buf $("$buf" --version) lint"
if ! (cd "$proto_dir" && "$buf" lint); then
  echo "check-proto: buf lint failed (proto/buf.yaml lists the rules)" >&2
  exit 1
fi

# The released files are compared from a copy: inside proto/ they belong to its module.
against=$(mktemp -d)
trap 'rm -rf "$against"' EXIT
cp "$proto_dir"/released/*.proto "$against/"
# buf exits 100 when it finds breaking changes; any other failure is an error.
breaking=0
findings=$(cd "$proto_dir" && "$buf" breaking --against "$against" 2>&1) || breaking=$?
if [ "$breaking" -ne 0 ] && [ "$breaking" -ne 100 ]; then
  printf '%s\n' "$findings" >&2
  echo "check-proto: buf breaking failed (exit $breaking)" >&2
  exit 1
fi
[ "$breaking" -eq 100 ] && breaking=1
if [ "$current" -lt "$released" ]; then
  echo "check-proto: PROTOCOL_VERSION_CURRENT is $current, below the released $released" >&2
  exit 1
fi
if [ "$breaking" -eq 1 ] && [ "$current" -eq "$released" ]; then
  printf '%s\n' "$findings" >&2
  echo "check-proto: the changes above break peers of protocol version $released; bump" \
    "PROTOCOL_VERSION_CURRENT in wire.proto (and the CHANGELOG's version list)" >&2
  exit 1
fi
if [ "$breaking" -eq 1 ]; then
  echo "check-proto: breaking changes against version $released, under version $current:"
  printf '%s\n' "$findings"
else
  echo "check-proto: nothing breaks peers of version $released (this is version $current)"
fi
