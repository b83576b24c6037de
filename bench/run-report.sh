#!/usr/bin/env bash
# Regenerates the data files that docs/ACCURACY.md and docs/BENCHMARKS.md cite, under
# the names they cite, in bench/results/ (indexed by bench/results/README.md). Each run
# below is one command of physics-bench, physics-microbench or bench/run-netbench.sh;
# the plots are drawn from the CSVs with gnuplot.
#   bench/run-report.sh [BUILD_DIR]                    every run (hours: the Box2D piles take about two)
#   bench/run-report.sh --only grid,pyramid [BUILD_DIR] the named runs only
#   bench/run-report.sh --list                         each run and the files it writes
#   bench/run-report.sh --check                        runs nothing: every data file a doc
#       (README.md, docs/*.md) names exists in bench/results/ and is one of these runs'
#       outputs, every output is named by a doc and listed in the index, and
#       bench/results/ holds nothing else. Exits 1 otherwise (a ctest test runs it).
# BUILD_DIR defaults to build/. Each run prints its one-line summaries and profiles on
# stderr.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
results="$here/results"

# The runs, in the order they run, and the files each writes into bench/results/.
runs=(grid long stages pyramid rain-interleaved rain-iterations rain-timeline
      pile-rain-timeline pile-rain-box2d pile-rain-box2d-mu0.2 micro netbench net-paths
      still-world replay-size contact-events soak core-comparison core-comparison-relaxed
      rain-position-passes det-math-comparison core-speed pair-reuse wasm-speed save-restore relay-bandwidth vocabulary-cost
      web-client prediction rollback-budget ws-vs-tcp lobby-rejoiner query-cost game-prediction)
declare -A writes=(
  [grid]="accuracy.csv accuracy-pareto.svg"
  [long]="accuracy-long.csv"
  [stages]="accuracy-stages.csv accuracy-stages-ratios.csv"
  [pyramid]="accuracy-pyramid.csv accuracy-pyramid-ratios.csv"
  [rain-interleaved]="accuracy-rain-interleaved.csv accuracy-rain-interleaved-ratios.csv
    accuracy-rain-interleaved-seconds.csv accuracy-rain-interleaved-run2-ratios.csv
    accuracy-rain-interleaved-run3-ratios.csv"
  [rain-iterations]="accuracy-rain-iterations.csv accuracy-rain-iterations-ratios.csv
    accuracy-rain-iterations-ours.csv"
  [rain-timeline]="accuracy-rain-timeline.csv accuracy-rain-timeline-ratios.csv
    accuracy-rain-timeline-seconds.csv accuracy-rain-timeline.svg"
  [pile-rain-timeline]="accuracy-pile-rain-timeline.csv accuracy-pile-rain-timeline-ratios.csv
    accuracy-pile-rain-timeline-seconds.csv accuracy-pile-rain-mu0.2-timeline.svg"
  [pile-rain-box2d]="accuracy-pile-rain-box2d-timeline.csv
    accuracy-pile-rain-box2d-timeline-ratios.csv accuracy-pile-rain-box2d-timeline-seconds.csv"
  [pile-rain-box2d-mu0.2]="accuracy-pile-rain-box2d-mu0.2-timeline.csv
    accuracy-pile-rain-box2d-mu0.2-timeline-ratios.csv
    accuracy-pile-rain-box2d-mu0.2-timeline-seconds.csv"
  [micro]="benchmarks-micro.json"
  [net-paths]="netbench-paths.csv netbench-paths-default-jitter.csv"
  [still-world]="still-world-one-driver.csv"
  [replay-size]="replay-size.csv"
  [contact-events]="contact-events.csv"
  [soak]="soak-moving-1000.csv"
  [core-comparison]="core-comparison.csv"
  [core-comparison-relaxed]="core-comparison-relaxed.csv"
  [rain-position-passes]="accuracy-rain-position-passes.csv"
  [det-math-comparison]="core-comparison-det-math.csv"
  [core-speed]="core-speed.csv core-speed-profile.csv"
  [pair-reuse]="core-comparison-pair-reuse.csv"
  [wasm-speed]="wasm-speed.csv"
  [save-restore]="save-restore.json"
  [relay-bandwidth]="netbench-relay.csv"
  [vocabulary-cost]="vocabulary-cost.csv"
  [web-client]="web-client.csv"
  [prediction]="netbench-prediction.csv"
  [rollback-budget]="rollback-budget.json"
  [query-cost]="query-cost.csv"
  [game-prediction]="game-prediction.csv"
  [ws-vs-tcp]="ws-vs-tcp.csv"
  [lobby-rejoiner]="lobby-rejoiner.csv"
  # run-netbench.sh names its files after its own runs: netbench-NAME.csv.
  [netbench]="$(sed -n 's/^run \([^ ]*\) .*/netbench-\1.csv/p' "$here/run-netbench.sh" | tr '\n' ' ')
    netbench-pyramid-one-driver.csv"
)

all_outputs() { for r in "${runs[@]}"; do for f in ${writes[$r]}; do echo "$f"; done; done; }

check() {
  local failed=0 docs=("$root/README.md" "$root"/docs/*.md) outputs name f
  outputs="$(all_outputs | sort -u)"
  # Every data file a doc names. A name is a path ending in a data extension; links
  # from docs/ reach the folder as ../bench/results/.
  while read -r name; do
    [[ -n "$name" ]] || continue
    f="${name##*bench/results/}"
    if [[ "$name" != *bench/results/"$f" ]]; then
      echo "run-report --check: a doc names $name, which is not in bench/results/" >&2
      failed=1
    elif ! grep -qxF "$f" <<<"$outputs"; then
      echo "run-report --check: a doc names bench/results/$f, which no run writes" >&2
      failed=1
    elif [[ ! -f "$results/$f" ]]; then
      echo "run-report --check: a doc names bench/results/$f, which does not exist" >&2
      failed=1
    fi
  done < <(grep -ohE '[A-Za-z0-9_./-]+\.(csv|svg|json|log|dat)\b' "${docs[@]}" | sort -u)
  # Every output exists, is cited, and is in the index.
  while read -r f; do
    [[ -f "$results/$f" ]] || { echo "run-report --check: bench/results/$f is missing" >&2; failed=1; }
    grep -qF "bench/results/$f" "${docs[@]}" ||
      { echo "run-report --check: no doc cites bench/results/$f" >&2; failed=1; }
    grep -qF "$f" "$results/README.md" ||
      { echo "run-report --check: bench/results/README.md does not list $f" >&2; failed=1; }
  done <<<"$outputs"
  # Nothing else in the folder.
  for f in "$results"/*; do
    f="$(basename "$f")"
    [[ "$f" == README.md ]] || grep -qxF "$f" <<<"$outputs" ||
      { echo "run-report --check: bench/results/$f is written by no run" >&2; failed=1; }
  done
  [[ $failed -eq 0 ]] && echo "run-report --check: $(wc -l <<<"$outputs") data files, each cited and written by a run"
  return "$failed"
}

only=""
case "${1:-}" in
  --check) check; exit ;;
  --list) for r in "${runs[@]}"; do echo "$r:" ${writes[$r]}; done; exit 0 ;;
  --only) only=",${2:?--only needs a list of runs},"; shift 2 ;;
esac
build="$(cd "${1:-$root/build}" && pwd)"
bench="$build/bench/physics-bench"
if [[ -n "$only" ]]; then
  for r in ${only//,/ }; do [[ -v "writes[$r]" ]] || { echo "run-report: no run $r (--list)" >&2; exit 2; }; done
fi
wanted() { [[ -z "$only" || "$only" == *",$1,"* ]]; }
# physics-bench and gnuplot are needed by the runs of physics-bench only.
bench_runs=(grid long stages pyramid rain-interleaved rain-iterations rain-timeline
            pile-rain-timeline pile-rain-box2d pile-rain-box2d-mu0.2 rain-position-passes)
needs_bench=0
for r in "${bench_runs[@]}"; do wanted "$r" && needs_bench=1; done
if [[ $needs_bench -eq 1 ]]; then
  [[ -x "$bench" ]] || { echo "run-report: $bench not built (ninja -C $build physics-bench)" >&2; exit 1; }
  command -v gnuplot >/dev/null || { echo "run-report: gnuplot not found (apt install gnuplot-nox)" >&2; exit 1; }
fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
out="$results"
# The settings every run of the large scenes shares: the server's defaults, ours exact.
ours=(--integrators exact --substeps 1 --iterations 4)

run_grid() {  # every scene; the whole grid on the small ones; the peers on every scene
  "$bench" --quick --scenes all --peers-everywhere --interleave 60 --csv "$out/accuracy.csv"
  for scene in projectile-friction bounce-e1 bounce-e0.5 column-50; do
    awk -v scene="$scene" -f "$here/report/pareto.awk" "$out/accuracy.csv" >"$tmp/$scene.dat"
    awk -v scene="$scene" -v front=1 -f "$here/report/pareto.awk" "$out/accuracy.csv" |
      sort -g >"$tmp/$scene.front.dat"
  done
  gnuplot -e "datadir='$tmp'; out='$out/accuracy-pareto.svg'" "$here/report/pareto.gp"
}
run_long() {  # the stacks over 10,000 steps, ours, sleeping on and off
  "$bench" --scenes column,pyramid --engines ours --sleep both "${ours[@]}" \
    --csv "$out/accuracy-long.csv"
}
run_stages() {
  "$bench" --quick --scenes stages --peers-everywhere --sleep on \
    --csv "$out/accuracy-stages.csv" --ratios "$out/accuracy-stages-ratios.csv"
}
run_pyramid() {
  "$bench" --quick --scenes pyramid-5050 --engines ours,box2d,chipmunk "${ours[@]}" --sleep both \
    --csv "$out/accuracy-pyramid.csv" --ratios "$out/accuracy-pyramid-ratios.csv"
}
run_rain-interleaved() {  # three runs of ours and Chipmunk taking turns of a second
  local common=(--scenes rain-16000 --engines ours,chipmunk "${ours[@]}" --sleep on --interleave 60)
  "$bench" "${common[@]}" --csv "$out/accuracy-rain-interleaved.csv" \
    --ratios "$out/accuracy-rain-interleaved-ratios.csv" \
    --timeline "$out/accuracy-rain-interleaved-seconds.csv"
  for n in 2 3; do
    "$bench" "${common[@]}" --csv "$tmp/run$n.csv" \
      --ratios "$out/accuracy-rain-interleaved-run$n-ratios.csv"
  done
}
run_rain-iterations() {  # fewer iterations of ours against Chipmunk, and below what holds
  local common=(--scenes rain-16000 --integrators exact --substeps 1 --full-grid --sleep on --interleave 60)
  "$bench" "${common[@]}" --engines ours,chipmunk --iterations 1,4 --velocity-iterations 2,8 \
    --csv "$out/accuracy-rain-iterations.csv" --ratios "$out/accuracy-rain-iterations-ratios.csv"
  "$bench" "${common[@]}" --engines ours --iterations 1 --velocity-iterations 1,2,4 \
    --csv "$out/accuracy-rain-iterations-ours.csv"
}
run_rain-timeline() {  # all three engines, one after another, second by second
  "$bench" --scenes rain-16000 --engines ours,chipmunk,box2d --integrators exact --substeps 1 \
    --iterations 1,4 --velocity-iterations 4,8 --full-grid --sleep on \
    --csv "$out/accuracy-rain-timeline.csv" --ratios "$out/accuracy-rain-timeline-ratios.csv" \
    --timeline "$out/accuracy-rain-timeline-seconds.csv"
  "$here/plot-timeline.sh" "$out/accuracy-rain-timeline-seconds.csv" rain-16000 \
    "$out/accuracy-rain-timeline.svg"
}
run_pile-rain-timeline() {  # the 16,000-circle pile at three frictions, ours and Chipmunk
  "$bench" --scenes pile-rain --pile-friction 0,0.2,0.5 --engines ours,chipmunk "${ours[@]}" \
    --sleep on --csv "$out/accuracy-pile-rain-timeline.csv" \
    --ratios "$out/accuracy-pile-rain-timeline-ratios.csv" \
    --timeline "$out/accuracy-pile-rain-timeline-seconds.csv"
  "$here/plot-timeline.sh" "$out/accuracy-pile-rain-timeline-seconds.csv" pile-rain-16000-mu0.2 \
    "$out/accuracy-pile-rain-mu0.2-timeline.svg"
}
run_pile-rain-box2d() {  # the same pile, ours and Box2D (about an hour)
  "$bench" --scenes pile-rain --pile-friction 0,0.5 --engines ours,box2d "${ours[@]}" --sleep on \
    --csv "$out/accuracy-pile-rain-box2d-timeline.csv" \
    --ratios "$out/accuracy-pile-rain-box2d-timeline-ratios.csv" \
    --timeline "$out/accuracy-pile-rain-box2d-timeline-seconds.csv"
}
run_pile-rain-box2d-mu0.2() {  # (about 50 minutes)
  "$bench" --scenes pile-rain --pile-friction 0.2 --engines ours,box2d "${ours[@]}" --sleep on \
    --csv "$out/accuracy-pile-rain-box2d-mu0.2-timeline.csv" \
    --ratios "$out/accuracy-pile-rain-box2d-mu0.2-timeline-ratios.csv" \
    --timeline "$out/accuracy-pile-rain-box2d-mu0.2-timeline-seconds.csv"
}
run_micro() {
  local micro="$build/bench/physics-microbench"
  [[ -x "$micro" ]] || { echo "run-report: $micro not built (ninja -C $build physics-microbench)" >&2; return 1; }
  "$micro" --benchmark_filter='StepPile|Collide|Intersect|Grid|Brute' --benchmark_min_time=0.5 \
    --benchmark_out="$out/benchmarks-micro.json" --benchmark_out_format=json
}
run_save-restore() {  # the world's saved state: save, restore, bytes (about a minute)
  local micro="$build/bench/physics-microbench"
  [[ -x "$micro" ]] || { echo "run-report: $micro not built (ninja -C $build physics-microbench)" >&2; return 1; }
  "$micro" --benchmark_filter='SaveInto|Restore|ToBytes|FromBytes|StepForScale' \
    --benchmark_min_time=0.2 --benchmark_out="$out/save-restore.json" --benchmark_out_format=json
}
run_relay-bandwidth() {  # 8 players, the input relay beside the snapshot encodings (about 8 minutes)
  local netbench="$build/bench/physics-netbench"
  [[ -x "$netbench" ]] || { echo "run-report: $netbench not built" >&2; return 1; }
  # Inputs changed every tick, and held for 500 ms as a player holds a key; a snapshot
  # every tick, and every third.
  "$netbench" --scenes scenes/moving-1000.textproto,scenes/large-4000.textproto --bots 8 \
    --encodings inputs,predicted --input-change-ms 0,500 --snapshot-intervals 1,3 --duration 5 \
    --warmup 1 --csv "$out/netbench-relay.csv"
}
run_prediction() {  # the thin and the predicting client through one 100 ms path (about 2 minutes)
  local netbench="$build/bench/physics-netbench"
  [[ -x "$netbench" ]] || { echo "run-report: $netbench not built" >&2; return 1; }
  "$netbench" --prediction \
    --prediction-scenes "$root/scenes/moving-1000.textproto,$root/scenes/large-4000.textproto" \
    --prediction-bots 4 --prediction-predicting-bots 1 --prediction-one-way-ms 50 \
    --prediction-jitter-ms 10 \
    --prediction-input-change-ms 500 --seed 1 --tick-rate 60 --settle 2 --duration 20 \
    --csv "$out/netbench-prediction.csv"
}
run_rollback-budget() {  # restore and 8 steps on rains and rained piles of 1,000 to 16,000 circles
  local micro="$build/bench/physics-microbench"
  [[ -x "$micro" ]] || { echo "run-report: $micro not built (ninja -C $build physics-microbench)" >&2; return 1; }
  "$micro" --benchmark_filter='Rollback8' --benchmark_min_time=0.5 \
    --benchmark_out="$out/rollback-budget.json" --benchmark_out_format=json
}
run_query-cost() {  # each world query on rained piles of 1,000 and 16,000 circles (about 2 minutes)
  local micro="$build/bench/physics-microbench"
  [[ -x "$micro" ]] || { echo "run-report: $micro not built (ninja -C $build physics-microbench)" >&2; return 1; }
  "$micro" --benchmark_filter='BM_Query' --benchmark_min_time=0.2 \
    --benchmark_out="$out/query-cost.csv" --benchmark_out_format=csv
}
run_game-prediction() {  # goal rush's messages predicted by the rules against not (about 11 minutes)
  "$here/game-prediction.sh" "$build" 300
}
run_netbench() { BUILD_DIR="$build" "$here/run-netbench.sh"; }
run_net-paths() {  # lockstep and fixed rate through the link conditioner (about 8 minutes)
  local netbench="$build/bench/physics-netbench"
  "$netbench" --paths --duration 5 --csv "$out/netbench-paths.csv"
  # Where a driving player's snapshots go on the default scene through a jittered path.
  "$netbench" --paths --modes fixed --fixed-scene "$root/scenes/default.textproto" \
    --one-way-ms 50 --jitter-ms 10 --stall-ms 0 --duration 20 \
    --csv "$out/netbench-paths-default-jitter.csv"
}
run_still-world() { BUILD_DIR="$build" "$here/run-still-world.sh"; }
run_replay-size() {  # server recordings of 8 clients at 60 Hz, 10 minutes each (seconds)
  local size="$build/tests/replay/physics-replay-size"
  [[ -x "$size" ]] || { echo "run-report: $size not built (ninja -C $build physics-replay-size)" >&2; return 1; }
  "$size" --clients 8 --tick-rate 60 --seconds 600 >"$out/replay-size.csv"
}
run_contact-events() {  # the step with contact events off and on: a rain, a pile
  local contact="$build/bench/physics-contact-bench"
  [[ -x "$contact" ]] || { echo "run-report: $contact not built (ninja -C $build physics-contact-bench)" >&2; return 1; }
  { "$contact" --scene rain --count 4000 --steps 600 --repeats 5
    "$contact" --scene pile --count 4000 --steps 600 --repeats 5 | tail -n +2; } >"$out/contact-events.csv"
}
run_core-comparison() {  # this tree's core against CORE_BASELINE's (default HEAD), in turns
  OUT="$out/core-comparison.csv" "$here/compare-core.sh" "${CORE_BASELINE:-HEAD}"
}
run_core-comparison-relaxed() {  # the relaxed position passes against CORE_BASELINE's core
  RAIN_COUNTS="1000 4000" SCENES="rain-16000,pyramid-5050,column-50" \
    BENCH_FLAGS=--relaxed-position-passes RESULTS_MAY_DIFFER=1 \
    OUT="$out/core-comparison-relaxed.csv" "$here/compare-core.sh" "${CORE_BASELINE:-HEAD}"
}
run_rain-position-passes() {  # what the position passes after the first cost, rain-4000 awake
  "$bench" --quick --scenes rain --rain-count 4000 --engines ours --integrators exact \
    --substeps 1 --iterations 1,2,4 --full-grid --sleep off --interleave 60 \
    --csv "$out/accuracy-rain-position-passes.csv"
}
run_det-math-comparison() {  # the core with its own exp/expm1/log against the one with libm's
  OUT="$out/core-comparison-det-math.csv" "$here/compare-core.sh" "${DET_MATH_BASELINE:-0da0b44}"
}
run_core-speed() {  # this core against 0da0b44's at full step counts, with both profiles
  QUICK=0 RAIN_COUNTS="1000 4000" SCENES="rain-16000,pyramid-5050,column-50" \
    OUT="$out/core-speed.csv" PROFILE_OUT="$out/core-speed-profile.csv" \
    "$here/compare-core.sh" "${SPEED_BASELINE:-0da0b44}"
}
run_pair-reuse() {  # pairs kept through a new order against the core before it (78386ff)
  QUICK=0 RAIN_COUNTS="1000 4000" SCENES="rain-16000,pyramid-5050,column-50" \
    OUT="$out/core-comparison-pair-reuse.csv" "$here/compare-core.sh" "${PAIR_REUSE_BASELINE:-78386ff}"
}
run_vocabulary-cost() {  # filters, sensors, kinematic bodies in instructions (needs BASELINE_HASHES)
  BUILD_DIR="$build" "$here/vocabulary-cost.sh"
}
run_wasm-speed() {  # the WebAssembly core's step time against native (needs build-wasm/)
  OUT="$out/wasm-speed.csv" "$here/wasm-speed.sh"
}
run_web-client() {  # the TypeScript client's cost per snapshot received, in node (needs npm)
  OUT="$out/web-client.csv" "$here/web-client.sh"
}
run_ws-vs-tcp() {  # 64 clients on moving-1000, the WebSocket port against TCP (needs npm; 2 minutes)
  BUILD_DIR="$build" OUT="$out/ws-vs-tcp.csv" "$here/ws-vs-tcp.sh"
}
run_lobby-rejoiner() {  # a lockstep stranger who sits again after each drop, beside an honest bot (2 minutes)
  python3 "$here/lobby-rejoiner.py" --build-dir "$build" --seconds 60 --csv "$out/lobby-rejoiner.csv"
}
run_soak() {  # 64 churning clients on moving-1000 for 10 minutes, replayed (physics-soak)
  local soak="$build/tests/soak/physics-soak"
  [[ -x "$soak" ]] || { echo "run-report: $soak not built (ninja -C $build physics-soak)" >&2; return 1; }
  rm -f "$out/soak-moving-1000.csv"
  nice -n 19 "$soak" --scene "$root/scenes/moving-1000.textproto" --duration 600 --warmup 30 \
    --encoding full --csv "$out/soak-moving-1000.csv" >&2
}

mkdir -p "$out"
echo "run-report: $(nproc) cores, load average: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
for r in "${runs[@]}"; do
  wanted "$r" || continue
  echo "run-report: $r" >&2
  "run_$r"
  echo "run-report: wrote" ${writes[$r]} >&2
done
echo "run-report: load average after: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
