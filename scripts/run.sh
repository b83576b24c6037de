#!/usr/bin/env bash
# The README's run command: install what is missing, build, start the server on
# its built-in default scene. Arguments go to physics-server (try --help).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
echo "run: building (the first build takes several minutes)" >&2
scripts/build.sh >&2
exec "${BUILD_DIR:-build}/server/physics-server" "$@"
