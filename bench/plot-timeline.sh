#!/usr/bin/env bash
# Draws a physics-bench --timeline CSV as an SVG: CPU time per step and awake bodies
# over simulated time, one line per engine run of one scene.
#   bench/plot-timeline.sh TIMELINE.csv SCENE OUT.svg
set -euo pipefail
[[ $# -eq 3 ]] || { echo "usage: $0 TIMELINE.csv SCENE OUT.svg" >&2; exit 2; }
csv="$1"; scene="$2"; out="$3"
here="$(cd "$(dirname "$0")" && pwd)"
[[ -r "$csv" ]] || { echo "plot-timeline: cannot read $csv" >&2; exit 1; }
command -v gnuplot >/dev/null || { echo "plot-timeline: gnuplot not found (apt install gnuplot-nox)" >&2; exit 1; }
data="$(mktemp -d)"
trap 'rm -rf "$data"' EXIT
# One file per run: engine-iterations-sleeping (iterations' "/" made "_"), holding
# end_s, awake, cpu_ms_mean.
awk -F, -v scene="$scene" -v dir="$data" 'NR > 1 && $1 == scene {
  name = $2 "-" $3 "-sleep-" $4; gsub("/", "_", name)
  print $5, $7, $9 > (dir "/" name ".dat")
  if (!(name in seen)) { seen[name] = 1; order = order " " name }
} END { print order > (dir "/series") }' "$csv"
series="$(cat "$data/series")"
[[ -n "${series// /}" ]] || { echo "plot-timeline: no rows for scene $scene in $csv" >&2; exit 1; }
gnuplot -e "datadir='$data'; series='$series'; title_text='$scene: cost over simulated time (one run)'; out='$out'" \
  "$here/report/timeline.gp"
echo "plot-timeline: wrote $out"
