#!/usr/bin/env bash
# The README's test command: install what is missing, build, run every test.
#   scripts/test.sh                  everything (what CI runs)
#   scripts/test.sh --quick [ARGS]   the developer's loop: an incremental build of the
#                                    configured build/ and every test but the soak
#                                    runs; ARGS go to ctest (-L unit, -R '^Seats\.'),
#                                    an -LE of theirs replacing '-LE soak'
#                                    (-LE 'soak|stability': the minutes-long cases too)
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
  exclude=(-LE soak)
  for arg in "$@"; do
    if [ "$arg" = "-LE" ]; then exclude=(); fi
  done
  exec ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" --timeout 600 \
    "${exclude[@]}" "$@"
fi
scripts/install-deps.sh
scripts/build.sh
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" --timeout 600
