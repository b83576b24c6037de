#!/usr/bin/env bash
# The README's test command: install what is missing, build, run every test.
#   scripts/test.sh                  everything (what CI runs)
#   scripts/test.sh --quick [ARGS]   the developer's loop: an incremental build of the
#                                    configured build/, every ctest test but the soak
#                                    runs and the stability cases (-LE 'soak|stability'),
#                                    then, where node is installed, the TypeScript
#                                    client's tests that need no server (npm run
#                                    test:unit in client/web/client, after npm ci the
#                                    first time and npm run build). ARGS go to ctest
#                                    (-L unit, -R '^Seats\.'); an -LE of theirs replaces
#                                    the default one (-LE soak: the stability cases too).
#                                    QUICK_NODE=0 leaves the TypeScript tests out.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${BUILD_DIR:-build}"
if [ "${1:-}" = "--quick" ]; then
  shift
  if [ -f "$build_dir/CMakeCache.txt" ]; then
    cmake --build "$build_dir" -j "$(nproc)"
  else
    scripts/build.sh
  fi
  exclude=(-LE 'soak|stability')
  for arg in "$@"; do
    if [ "$arg" = "-LE" ]; then exclude=(); fi
  done
  failed=0
  ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" --timeout 600 \
    "${exclude[@]}" "$@" || failed=1
  if [ "${QUICK_NODE:-1}" != 0 ] && command -v node >/dev/null && command -v npm >/dev/null; then
    (
      cd client/web/client
      [ -d node_modules ] || npm ci --no-audit --no-fund --loglevel=error
      npm run --silent build
      npm run --silent test:unit
    ) || failed=1
  else
    echo "test.sh: the TypeScript client's tests left out (no node, or QUICK_NODE=0)"
  fi
  exit "$failed"
fi
scripts/install-deps.sh
scripts/build.sh
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" --timeout 600
