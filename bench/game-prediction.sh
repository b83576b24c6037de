#!/usr/bin/env bash
# Goal rush (physics-server --rules libgoal_rush.so, 60 Hz) through physics-netsim at
# 50 ms one way with 10 ms of jitter, two predicting physics-client bots sending the
# "jump" message every 250 ms with their inputs, run twice: with the game's rules in
# their prediction (--rules) and without (the rules' effects relayed, shown once the
# server's tick comes back). Writes bench/results/game-prediction.csv: per run, the
# own message and own input from sending to the first state shown that holds it
# (median, p99, ms), rollbacks a second, desyncs, and the bytes a second each bot
# received (the relay with game messages against the relay with the rules' changes).
#   bench/game-prediction.sh [BUILD_DIR] [SECONDS]     defaults: build, 20
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
seconds="${2:-20}"
out="$root/bench/results/game-prediction.csv"
plugin="$build/examples/goal-rush/libgoal_rush.so"
scene="$root/examples/goal-rush/goal-rush.textproto"
work=$(mktemp -d)
# shellcheck source=lib/servers.sh
source "$root/bench/lib/servers.sh"
trap 'bench_stop_all; rm -rf "$work"' EXIT

echo "run,own_message_visible_ms_median,own_message_visible_ms_p99,own_input_visible_ms_median,own_input_visible_ms_p99,rollbacks_per_second,desyncs,bytes_per_second" >"$out"
run() {
  local name="$1"
  shift
  local server_port netsim_port
  bench_start server_port "$work/server" "$build/server/physics-server" --port 0 --ws-port 0 \
    --rules "$plugin" --scene "$scene"
  bench_start netsim_port "$work/netsim" "$build/testing/physics-netsim" --listen 0 \
    --to "127.0.0.1:$server_port" --latency-ms 50 --jitter-ms 10
  "$build/client/physics-client" --port "$netsim_port" --predict --bots 2 \
    --duration "$seconds" --game-message jump --message-every-ms 250 --json "$@" \
    >"$work/report.json"
  bench_stop_all
  python3 - "$name" "$work/report.json" "$out" <<'PY'
import json, sys
r = json.load(open(sys.argv[2]))
row = [sys.argv[1], r["own_message_visible_ms_median"], r["own_message_visible_ms_p99"],
       r["own_input_visible_ms_median"], r["own_input_visible_ms_p99"],
       r["rollbacks_per_second"], r["desyncs"], r["bytes_per_second"]]
open(sys.argv[3], "a").write(",".join(str(v) for v in row) + "\n")
print(f"{sys.argv[1]}: message shown median {row[1]:.3f} ms, p99 {row[2]:.3f} ms; input shown "
      f"median {row[3]:.3f} ms; {row[5]:.1f} rollbacks/s; {row[6]} desyncs; {row[7]} B/s")
PY
}

run "rules in the prediction" --rules "$plugin" --scene "$scene"
run "rules on the server only"
echo "game-prediction: wrote $out"
