#!/usr/bin/env bash
# physics-view in a window, under Xvfb (run as: xvfb-run -a bash window_smoke.sh
# SERVER VIEW): it joins a server and draws for two seconds while recording, quits
# with exit 0 on SIGTERM (SDL turns it into a quit event), and the recording it
# wrote plays in a window the same way and gives a picture headless; with --predict
# it joins as a player, draws the predicting client's world in a window and headless.
set -euo pipefail
server=$1
view=$2
dir=$(mktemp -d)
server_pid=
cleanup() {
  if [ -n "$server_pid" ]; then kill "$server_pid" 2>/dev/null || true; fi
  rm -rf "$dir"
}
trap cleanup EXIT

"$server" --port 0 >"$dir/server.out" 2>/dev/null &
server_pid=$!
for _ in $(seq 100); do
  grep -q listening "$dir/server.out" && break
  sleep 0.1
done
port=$(sed -n 's/.*:\([0-9]*\)$/\1/p' "$dir/server.out")
[ -n "$port" ] || { echo "the server did not start"; exit 1; }

# Runs the viewer for two seconds, then asks it to quit; fails unless it exits 0.
in_window() {
  "$view" "$@" &
  local pid=$!
  sleep 2
  kill -TERM "$pid"
  wait "$pid" || { echo "physics-view $* exited with $?"; exit 1; }
}

in_window --port "$port" --size 320x240 --record "$dir/seen.rec"
in_window --replay "$dir/seen.rec" --size 320x240 --speed 4
"$view" --replay "$dir/seen.rec" --screenshot "$dir/seen.png" --after-ticks 30 --size 320x240
[ -s "$dir/seen.png" ] || { echo "no picture from the recording"; exit 1; }
in_window --port "$port" --size 320x240 --predict
"$view" --port "$port" --predict --screenshot "$dir/predicted.png" --after-ticks 30 \
  --size 320x240 >"$dir/predicted.out"
[ -s "$dir/predicted.png" ] || { echo "no picture from the prediction"; exit 1; }
grep -Eq 'bodies [1-9]' "$dir/predicted.out" ||
  { echo "the prediction's picture shows no body: $(cat "$dir/predicted.out")"; exit 1; }
echo "window_smoke: live, replayed and predicted windows ran and quit cleanly"
