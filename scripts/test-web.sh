#!/usr/bin/env bash
# The web packages (docs/WEB.md): installs what is missing (Chromium, protoc, node and
# npm: scripts/install-deps.sh web), then in client/web/client (@physics/client) and
# client/web/viewer (the browser viewer) `npm ci` and `npm run build`, and runs their
# node tests against a real physics-server over WebSocket: the client's (the worked
# examples of docs/PROTOCOL.md 5.7, 600 lockstep ticks of moving-1000 with the view
# hash compared on every snapshot, the views, the refusals) and the viewer's in
# headless Chromium (a screenshot's pixels against the server's bodies, the arrow
# keys, a key bound to a game message and the rules' answer in the panel, goal rush's
# sensors and moving platform), and the input pacer through physics-netsim's delayed path. The server is
# $PHYSICS_SERVER, or build/server/physics-server, and the link conditioner
# $PHYSICS_NETSIM, or build/testing/physics-netsim (scripts/test.sh builds both first
# in CI; when one is missing, this builds that one target).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${BUILD_DIR:-build}"

bash scripts/install-deps.sh web

# build_missing BINARY TARGET: builds TARGET in the build directory when BINARY is not there.
build_missing() {
  [ -x "$1" ] && return
  echo "test-web: no $1: building it"
  bash scripts/install-deps.sh
  local extra=()
  if [ "${CI:-}" = "true" ]; then extra+=(-DPHYSICS_WARNINGS_AS_ERRORS=ON); fi
  if [ ! -f "$build_dir/CMakeCache.txt" ]; then
    cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" "${extra[@]}"
  fi
  cmake --build "$build_dir" -j "$(nproc)" --target "$2"
}

server="${PHYSICS_SERVER:-$build_dir/server/physics-server}"
build_missing "$server" physics-server
PHYSICS_SERVER="$(realpath "$server")"
export PHYSICS_SERVER
# The link conditioner the pacer's test runs its path through.
netsim="${PHYSICS_NETSIM:-$build_dir/testing/physics-netsim}"
build_missing "$netsim" physics-netsim
PHYSICS_NETSIM="$(realpath "$netsim")"
export PHYSICS_NETSIM
# The rules the viewer's game test loads: one that answers every game message, and
# goal rush's.
echo_rules="${PHYSICS_ECHO_RULES:-$build_dir/tests/client/libphysics_test_rules_echo.so}"
build_missing "$echo_rules" physics_test_rules_echo
PHYSICS_ECHO_RULES="$(realpath "$echo_rules")"
export PHYSICS_ECHO_RULES
goal_rush_rules="${PHYSICS_GOAL_RUSH_RULES:-$build_dir/examples/goal-rush/libgoal_rush.so}"
build_missing "$goal_rush_rules" goal_rush_rules_plugin
PHYSICS_GOAL_RUSH_RULES="$(realpath "$goal_rush_rules")"
export PHYSICS_GOAL_RUSH_RULES
echo "test-web: node $(node --version), npm $(npm --version), $(protoc --version), $(/usr/bin/chromium --version 2>/dev/null || echo 'no chromium')"

# The viewer depends on the client package (file:../client): the client builds first.
for package in client/web/client client/web/viewer; do
  (cd "$package" && npm ci --no-audit --no-fund --loglevel=error && npm run --silent build)
done

failed=0
(cd client/web/client && npm test) || failed=1
(cd client/web/viewer && npm test) || failed=1
exit "$failed"
