#!/usr/bin/env bash
# The network figures of docs/BENCHMARKS.md ("Network: snapshots by encoding"):
# physics-netbench on each scene, with 1, 8, 32 and 64 clients, for the three
# snapshot encodings side by side in one run (full is the baseline: every body,
# exact, every tick). Writes bench/results/netbench-<scene>.csv, the tracked files
# docs/BENCHMARKS.md cites (overwritten: `git diff bench/results` shows what moved),
# or OUT/netbench-<scene>.csv when OUT is set, and prints the tables.
#   bench/run-netbench.sh            # everything (about 12 minutes)
#   OUT=/tmp/nb BOTS=1,8 DURATION=2 bench/run-netbench.sh   # a quick look, elsewhere
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build}"
netbench="$build/bench/physics-netbench"
out="${OUT:-bench/results}"
bots="${BOTS:-1,8,32,64}"
duration="${DURATION:-5}"
encodings=full,predicted,exact
mkdir -p "$out"
run() {  # name, warm-up seconds (the server alone), extra flags...
  local name=$1 warmup=$2
  shift 2
  echo "## $name"
  "$netbench" --bots "$bots" --duration "$duration" --warmup "$warmup" --encodings "$encodings" \
    --csv "$out/netbench-$name.csv" "$@" 2>/dev/null
}
# Watchers (no inputs): the moving scene, the rain, the default room once settled,
# the pyramid once asleep (the watchers' own bodies settle for 6 s before the
# measurement starts).
run moving-1000 0 --still --scenes scenes/moving-1000.textproto
run rain-4000 0 --still --scenes scenes/large-4000.textproto
run default-settled 3 --still --settle 6 --scenes default
run pyramid-asleep 10 --still --settle 6 --scenes scenes/box-pyramid.textproto
# Players driving their bodies every tick: input-to-snapshot latency.
run default-driving 0 --scenes default
# One player driving in a still world (the pyramid asleep after 10 s): what a
# snapshot's header and the player's own record cost, its join included.
echo "## pyramid-one-driver"
"$netbench" --bots 1 --duration "$duration" --warmup 10 --encodings predicted \
  --csv "$out/netbench-pyramid-one-driver.csv" --scenes scenes/box-pyramid.textproto 2>/dev/null
