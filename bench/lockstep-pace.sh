#!/usr/bin/env bash
# A lockstep lobby of two physics-client bots through physics-netsim at 50 ms one way
# (no jitter), once per pace: physics-server --lockstep-players 2 with the default
# pace (realtime), then with --lockstep-pace asap. One line each: the pace, the ticks
# a second the bots saw, the input delay in ticks (the median over the run; each
# bot's at the end, least and largest), and the inputs the server applied late.
#   bench/lockstep-pace.sh [BUILD_DIR] [SECONDS]     defaults: build, 10
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
seconds="${2:-10}"
work=$(mktemp -d)
# shellcheck source=lib/servers.sh
source "$root/bench/lib/servers.sh"
trap 'bench_stop_all; rm -rf "$work"' EXIT

run() {
  local name="$1"
  shift
  local server_port netsim_port
  bench_start server_port "$work/server" "$build/server/physics-server" --port 0 \
    --lockstep-players 2 "$@"
  bench_start netsim_port "$work/netsim" "$build/testing/physics-netsim" --listen 0 \
    --to "127.0.0.1:$server_port" --latency-ms 50
  "$build/client/physics-client" --port "$netsim_port" --bots 2 --duration "$seconds" --json \
    >"$work/report.json"
  bench_stop_all
  python3 - "$name" "$work/report.json" <<'EOF'
import json, sys
r = json.load(open(sys.argv[2]))
late = 100.0 * r["late_inputs"] / max(1, r["inputs_sent"])
print(f"{sys.argv[1]}: {r['ticks_per_second']:.1f} ticks/s, input delay median "
      f"{r['input_delay_ticks_median']:.1f} ticks, at the end {r['input_delay_ticks_final_min']}"
      f"-{r['input_delay_ticks_final_max']}; late inputs {r['late_inputs']} of "
      f"{r['inputs_sent']} ({late:.0f}%)")
EOF
}

run "default (realtime)"
run "asap" --lockstep-pace asap
