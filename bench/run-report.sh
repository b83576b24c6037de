#!/usr/bin/env bash
# Runs physics-bench over the report's scenes and settings grid, ours and the peers
# in one process, writes the CSVs and the log into docs/ and draws the Pareto plot
# (docs/accuracy-pareto.svg) and the rain's cost over time (docs/accuracy-timeline-rain.svg)
# with gnuplot.
#   bench/run-report.sh [--full] [BUILD_DIR]   (default BUILD_DIR: build)
# The main run is --quick (short stacks, 8 s of rain; ours and the peers); --full
# makes it the issue's lengths for the peers too (slow: tens of minutes). Then ours
# alone runs the long versions into docs/accuracy-long.csv (RUN_LONG=0 skips it).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
length="--quick"
if [[ "${1:-}" == "--full" ]]; then length=""; shift; fi
build="${1:-$root/build}"
bench="$build/bench/physics-bench"
docs="$root/docs"
mkdir -p "$here/results"
[[ -x "$bench" ]] || { echo "run-report: $bench not built (ninja -C $build physics-bench)" >&2; exit 1; }
command -v gnuplot >/dev/null || { echo "run-report: gnuplot not found (apt install gnuplot-nox)" >&2; exit 1; }

echo "run-report: $(nproc) cores, load average: $(cut -d' ' -f1-3 /proc/loadavg)" | tee "$here/results/accuracy-run.log"
# Every scene; the whole grid on the small ones; peers on every scene. The runs of a
# scene take turns of a second of simulated time (--interleave), so that a drift in
# the machine's speed slows ours and the peers alike and the ratios stay steady.
"$bench" $length --scenes all --peers-everywhere --interleave 60 \
  --csv "$docs/accuracy.csv" --ratios "$docs/accuracy-ratios.csv" \
  --timeline "$docs/accuracy-timeline.csv" 2>>"$here/results/accuracy-run.log"
# The long runs the issue's bounds speak of (10,000 resting steps, 30 s of the rains), ours
# only: the peers need about a minute per thousand steps of these scenes.
if [[ -n "$length" && "${RUN_LONG:-1}" == "1" ]]; then
  "$bench" --scenes column,pyramid,rain,pile-rain --engines ours --sleep both \
    --integrators exact --substeps 1 --iterations 4 \
    --csv "$docs/accuracy-long.csv" 2>>"$here/results/accuracy-run.log"
fi
echo "run-report: load average after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$here/results/accuracy-run.log"

data="$(mktemp -d)"
trap 'rm -rf "$data"' EXIT
for scene in projectile-friction bounce-e1 bounce-e0.5 column-50; do
  awk -v scene="$scene" -f "$here/report/pareto.awk" "$docs/accuracy.csv" > "$data/$scene.dat"
  awk -v scene="$scene" -v front=1 -f "$here/report/pareto.awk" "$docs/accuracy.csv" \
    | sort -g > "$data/$scene.front.dat"
done
gnuplot -e "datadir='$data'; out='$docs/accuracy-pareto.svg'" "$here/report/pareto.gp"
"$here/plot-timeline.sh" "$docs/accuracy-timeline.csv" "rain-16000" "$docs/accuracy-timeline-rain.svg"
echo "run-report: wrote docs/accuracy.csv, docs/accuracy-ratios.csv, docs/accuracy-pareto.svg," \
  "docs/accuracy-timeline.csv, docs/accuracy-timeline-rain.svg"
