#!/usr/bin/env bash
# The pictures of docs/VIEWER.md and docs/WEB.md, from a game: goal rush
# (examples/goal-rush) served by physics-server --rules.
#   docs/images/goal-rush.png   physics-view joined as the left player (its body ringed
#                               and labelled), the right player a physics-client
#                               steering left and sending "jump" every 0.9 s (labelled:
#                               it joined after the viewer)
#   docs/images/web-viewer.png  the browser viewer's game test (client/web/viewer/test/
#                               game.test.mjs), through scripts/test-web.sh
# Needs a build with physics-server, physics-view, physics-client and goal rush's rules
# library (build/examples/goal-rush/libgoal_rush.so); builds what is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${BUILD_DIR:-build}"
port="${PORT:-7791}"

missing=()
for target in server/physics-server:physics-server client/viewer/physics-view:physics-view \
  client/physics-client:physics-client examples/goal-rush/libgoal_rush.so:goal_rush_rules_plugin; do
  [ -e "$build_dir/${target%%:*}" ] || missing+=("${target##*:}")
done
if [ "${#missing[@]}" -gt 0 ]; then cmake --build "$build_dir" --target "${missing[@]}"; fi

"$build_dir/server/physics-server" --port "$port" --rules "$build_dir/examples/goal-rush/libgoal_rush.so" \
  --scene examples/goal-rush/goal-rush.textproto --stats-interval-s 0 >/dev/null &
server=$!
trap 'kill "$server" 2>/dev/null || true' EXIT
sleep 1
# The viewer joins first (the left player); its picture is 4 s after it joined.
"$build_dir/client/viewer/physics-view" --port "$port" --play --key space=jump \
  --screenshot docs/images/goal-rush.png --after-ticks 240 --size 960x600 &
view=$!
sleep 1
"$build_dir/client/physics-client" --port "$port" --name right --accel -4,0 \
  --game-message jump --message-every-ms 900 --ticks 600 >/dev/null &
player=$!
wait "$view"
kill "$player" 2>/dev/null || true
wait "$player" 2>/dev/null || true

WEB_VIEWER_GAME_SCREENSHOT="$PWD/docs/images/web-viewer.png" bash scripts/test-web.sh
