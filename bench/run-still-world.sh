#!/usr/bin/env bash
# The "One player in a still world" figures of docs/BENCHMARKS.md: the box pyramid
# asleep and one player driving its own body in a circle of 5 m/s² (a new input every
# tick, as physics-client --bots does), 10 s of snapshots framed exactly as the
# server writes them, in-process (the FeedRun harness of tests/server/), once with
# the view hash in every snapshot (view_hash_interval 1) and once with the default
# (4). Writes bench/results/still-world-one-driver.csv. Needs build/tests/server/server_tests.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build}"
out=bench/results/still-world-one-driver.csv
"$build/tests/server/server_tests" \
  --gtest_filter='Views.AStillWorldWithOneMovingPlayerCostsAtMost16Kbits' |
  awk 'BEGIN { print "view_hash_interval,bytes_per_snapshot,snapshots,seconds,kbit_per_s" }
       /^view hash every/ {
         k = $4; sub(":", "", k); bytes = $5; n = $9
         printf "%s,%s,%s,10,%.2f\n", k, bytes, n, bytes * n * 8 / 10 / 1000 }' >"$out"
cat "$out"
