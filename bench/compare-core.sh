#!/usr/bin/env bash
# Times this tree's physics core against another revision's, side by side in one
# process: physics-bench runs both cores (engines "ours" and "baseline") on the same
# scene in turns of 60 steps, so that a drift of a shared machine's speed slows both
# alike. Scenes: rain-1000, rain-16000 and pyramid-5050 (or those RAIN_COUNTS and
# SCENES name), at the server's default settings, with sleeping on (the server's way)
# and off (every body awake: the pyramid asleep costs next to nothing). Writes, per
# scene, sleep mode and repeat, each core's ms/step (thread CPU time, mean over the
# run, and wall time, median), their ratio,
# whether the two runs ended in the same state (state hash, error measures, stage
# counters), and which two cores they were, then each scene's median over the
# repeats, to bench/results/core-comparison.csv, and prints a table of the medians.
# Exits 1 when the two cores ended in different states (unless RESULTS_MAY_DIFFER=1).
# Two identical cores give the run-to-run noise: `bench/compare-core.sh HEAD` while this tree's core is HEAD's.
#
#   bench/compare-core.sh REV
#
# REV is any git revision (HEAD, e3cc9c9, main~3): its server/core is exported with
# `git archive` (no git state changes) and built as the baseline. The environment
# may set:
#   BASELINE_DIR=DIR  the baseline is DIR/server/core instead of REV's (REV is then "-")
#   OURS_DIR=DIR      "ours" is DIR/server/core instead of this tree's: the build is made
#                     from a copy of this tree whose server/core is replaced by it (the
#                     bench of this tree must compile against that core)
#   REPEATS=N         interleaved runs of each scene (default 3); every other repeat
#                     the baseline takes the first turn
#   QUICK=1           physics-bench --quick: 480 rain steps and 300 pyramid steps
#                     instead of 1800 and 10000 (default 1)
#   SLEEP=MODE        on, off or both (default both)
#   RAIN_COUNTS="N.." the circle counts of the small rains, one run each (default 1000)
#   SCENES=LIST       the scenes of the second run (default rain-16000,pyramid-5050;
#                     empty: none)
#   BENCH_FLAGS="..." more physics-bench flags for every run (such as
#                     --relaxed-position-passes, a setting of this tree's core)
#   RESULTS_MAY_DIFFER=1  a change that is meant to change results: report the states
#                     that differ, but exit 0
#   OUT=FILE          the CSV (default bench/results/core-comparison.csv)
#   PROFILE_OUT=FILE  also each core's per-phase profile (StepProfile, wall ms a
#                     step, mean over the run; a core older than its phase names
#                     gives zeros), medians over the repeats, per scene and sleep mode
#   WORK=DIR          exports and the build (default a new temporary directory; kept,
#                     so a second run with the same WORK builds only what changed)
#   BUILD=DIR         the build directory (default WORK/build)
# Cost on a 2-core machine, with the defaults: the build, a few minutes cold (both
# cores and physics-bench; seconds with a warm ccache), then about 20 s of CPU per
# repeat (rain-16000 is most of it): about 1 minute for three repeats on an idle
# machine, 8 minutes at a load average of 13.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2; exit 2; }
[[ $# -eq 1 && "$1" != -* || "${1:-}" == "-" ]] || usage
rev="$1"
repeats="${REPEATS:-3}"
quick="${QUICK:-1}"
sleep="${SLEEP:-both}"
[[ "$sleep" =~ ^(on|off|both)$ ]] || { echo "compare-core: SLEEP must be on, off or both" >&2; exit 2; }
out="${OUT:-$here/results/core-comparison.csv}"
rain_counts="${RAIN_COUNTS:-1000}"
second_scenes="${SCENES-rain-16000,pyramid-5050}"
[[ "$rain_counts" =~ ^[0-9\ ]*$ ]] || { echo "compare-core: RAIN_COUNTS must be counts" >&2; exit 2; }
[[ "$repeats" =~ ^[1-9][0-9]*$ ]] || { echo "compare-core: REPEATS must be a count, not '$repeats'" >&2; exit 2; }
if [[ -z "${BASELINE_DIR:-}" ]]; then
  [[ "$rev" != "-" ]] || { echo "compare-core: REV '-' needs BASELINE_DIR" >&2; exit 2; }
  git -C "$root" rev-parse --verify --quiet "$rev^{commit}" >/dev/null ||
    { echo "compare-core: no revision $rev in $root" >&2; exit 2; }
elif [[ ! -f "$BASELINE_DIR/server/core/include/physics/world.h" ]]; then
  echo "compare-core: $BASELINE_DIR holds no server/core" >&2; exit 2
fi
work="${WORK:-$(mktemp -d "${TMPDIR:-/tmp}/compare-core.XXXXXX")}"
mkdir -p "$work"
work="$(cd "$work" && pwd)"

has_core() { [[ -f "$1/server/core/include/physics/world.h" && -d "$1/server/core/src" ]]; }

# The baseline: REV's server/core, or BASELINE_DIR's.
if [[ -n "${BASELINE_DIR:-}" ]]; then
  baseline="$(cd "$BASELINE_DIR" && pwd)"
else
  baseline="$work/baseline"
  rm -rf "$baseline" && mkdir -p "$baseline"
  git -C "$root" archive "$rev" server/core | tar -x -C "$baseline"
fi
has_core "$baseline" || { echo "compare-core: $baseline holds no server/core" >&2; exit 2; }

# The source physics-bench is built from: this tree, or a copy with OURS_DIR's core.
src="$root"
if [[ -n "${OURS_DIR:-}" ]]; then
  ours_dir="$(cd "$OURS_DIR" && pwd)"
  has_core "$ours_dir" || { echo "compare-core: $ours_dir holds no server/core" >&2; exit 2; }
  src="$work/src"
  rm -rf "$src" && mkdir -p "$src"
  # The tree's files as they are now: tracked and new ones, not ignored ones such as
  # builds, nor tracked ones deleted since.
  (cd "$root" && git ls-files -z --cached --others --exclude-standard |
    while IFS= read -r -d '' f; do [[ -e "$f" ]] && printf '%s\0' "$f"; done |
    tar -c --null -T - -f -) | tar -x -C "$src"
  rm -rf "$src/server/core"
  cp -r "$ours_dir/server/core" "$src/server/core"
fi

build="${BUILD:-$work/build}"
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
echo "compare-core: ours = ${OURS_DIR:-$root}/server/core, baseline = $baseline/server/core" \
     "(${rev}); building in $build" >&2
cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
  -DPHYSICS_BUILD_TESTS=OFF -DPHYSICS_BUILD_BENCH=ON -DPHYSICS_BASELINE_CORE="$baseline" >/dev/null
nice -n 19 cmake --build "$build" -j 2 --target physics-bench >/dev/null
bench="$build/bench/physics-bench"

quick_flag=()
[[ "$quick" == 1 ]] && quick_flag=(--quick)
read -r -a extra_flags <<<"${BENCH_FLAGS:-}"
quick_flag+=("${extra_flags[@]}")
# The server's settings on every scene: the small scenes (column-50) would otherwise
# run physics-bench's whole grid of integrators, substeps and iterations.
quick_flag+=(--integrators exact --substeps 1 --iterations 4)
runs="$work/runs"
rm -rf "$runs" && mkdir -p "$runs"
for r in $(seq 1 "$repeats"); do
  # Each turn runs the engines in the order given: every other repeat the baseline
  # goes first, so that going first or second favours neither core.
  engines=ours,baseline
  (( r % 2 == 0 )) && engines=baseline,ours
  # rain-N takes its count from --rain-count: one run for each small rain, one for
  # the second run's scenes (rain-16000 is the default count).
  for count in $rain_counts; do
    "$bench" "${quick_flag[@]}" --scenes rain --rain-count "$count" --engines "$engines" \
      --sleep "$sleep" --interleave 60 --csv "$runs/$r-a$count.csv" 2>"$runs/$r-a$count.log"
  done
  if [[ -n "$second_scenes" ]]; then
    "$bench" "${quick_flag[@]}" --scenes "$second_scenes" --engines "$engines" \
      --sleep "$sleep" --interleave 60 --csv "$runs/$r-b.csv" 2>"$runs/$r-b.log"
  fi
  echo "compare-core: repeat $r of $repeats done ($engines)" >&2
done

mkdir -p "$(dirname "$out")"
# One row per scene, sleep mode and repeat, then each scene's median over the repeats.
# physics-bench's columns are found by their names in its header; a run's result is
# its error measures, awake count and notes (stage counters, state hash).
for r in $(seq 1 "$repeats"); do
  for f in "$runs/$r"-*.csv; do
    awk -F, -v repeat="$r" '
      NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
      {
        result = ""
        for (i = col["error_name"]; i <= col["awake_end"]; ++i) result = result "," $i
        print repeat "," $col["scene"] "," $col["engine"] "," $col["sleeping"] "," \
              $col["steps"] "," $col["ms_median"] "," $col["cpu_ms_mean"] "," \
              result ";" $col["notes"]
      }' "$f"
  done
done | awk -F, '
  # repeat, scene, engine, sleeping, steps, wall ms, cpu ms, then the result.
  {
    key = $2 "," $4 "," $1
    if (!(key in seen)) { seen[key] = 1; order[++n] = key; scene[key] = $2 "," $4 "," $5 }
    result = $0; for (i = 1; i <= 7; ++i) sub(/^[^,]*,/, "", result)
    cpu[key, $3] = $7; wall[key, $3] = $6; res[key, $3] = result
  }
  END {
    print "scene,sleeping,steps,repeat,ours_cpu_ms,baseline_cpu_ms,baseline_over_ours_cpu," \
          "ours_wall_ms,baseline_wall_ms,baseline_over_ours_wall,same_result"
    for (i = 1; i <= n; ++i) {
      k = order[i]; split(k, part, ",")
      same = (res[k, "ours"] == res[k, "baseline"] && res[k, "ours"] != "") ? "yes" : "no"
      printf "%s,%s,%s,%s,%.4f,%s,%s,%.4f,%s\n", scene[k], part[3], cpu[k, "ours"],
             cpu[k, "baseline"], cpu[k, "baseline"] / cpu[k, "ours"], wall[k, "ours"],
             wall[k, "baseline"], wall[k, "baseline"] / wall[k, "ours"], same
    }
  }' >"$work/rows.csv"
# Each scene's median over the repeats (the middle one, or the mean of the middle two).
awk -F, '
  function median(list, count,   i, j, t, a) {
    split(list, a, " ")
    for (i = 1; i <= count; ++i) for (j = i + 1; j <= count; ++j) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
    return count % 2 ? a[(count + 1) / 2] : (a[count / 2] + a[count / 2 + 1]) / 2
  }
  NR == 1 { print; next }
  {
    print
    key = $1 "," $2 "," $3
    if (!(key in count)) order[++n] = key
    ++count[key]
    for (c = 5; c <= 10; ++c) values[key, c] = values[key, c] " " $c
    if ($11 != "yes") differs[key] = 1
  }
  END {
    for (i = 1; i <= n; ++i) {
      k = order[i]
      printf "%s,median", k
      for (c = 5; c <= 10; ++c) printf ",%.4g", median(values[k, c], count[k])
      printf ",%s\n", (k in differs) ? "no" : "yes"
    }
  }' "$work/rows.csv" >"$work/table.csv"
# Which cores these are: a revision (with "+changes" when this tree's core differs
# from it), or the directory given.
if [[ -n "${OURS_DIR:-}" ]]; then
  ours_label="$ours_dir"
else
  ours_label="$(git -C "$root" rev-parse --short HEAD)"
  [[ -z "$(git -C "$root" status --porcelain -- server/core)" ]] || ours_label+="+changes"
fi
baseline_label="$baseline"
[[ -n "${BASELINE_DIR:-}" ]] || baseline_label="$(git -C "$root" rev-parse --short "$rev^{commit}")"
awk -v ours="$ours_label" -v base="$baseline_label" \
  'NR == 1 { print $0 ",ours_core,baseline_core"; next } { print $0 "," ours "," base }' \
  "$work/table.csv" >"$out"

# Each core's per-phase profile: the median over the repeats of each phase.
if [[ -n "${PROFILE_OUT:-}" ]]; then
  phases="order_and_integrate candidates moves position_passes contact_events velocity_solver bounds_and_sleep"
  for f in "$runs"/*-*.csv; do
    awk -F, -v phases="$phases" '
      NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; n = split(phases, phase, " "); next }
      {
        printf "%s,%s,%s,%s,%s", $col["scene"], $col["sleeping"], $col["steps"], $col["engine"],
               $col["cpu_ms_mean"]
        for (i = 1; i <= n; ++i) printf ",%s", $col["prof_" phase[i] "_ms"]
        printf "\n"
      }' "$f"
  done | awk -F, -v phases="$phases" -v ours="$ours_label" -v base="$baseline_label" '
    function median(list, count,   i, j, t, a) {
      split(list, a, " ")
      for (i = 1; i <= count; ++i) for (j = i + 1; j <= count; ++j) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
      return count % 2 ? a[(count + 1) / 2] : (a[count / 2] + a[count / 2 + 1]) / 2
    }
    {
      key = $1 "," $2 "," $3 "," $4
      if (!(key in count)) order[++n] = key
      ++count[key]
      for (c = 5; c <= NF; ++c) values[key, c] = values[key, c] " " $c
      fields = NF
    }
    END {
      printf "scene,sleeping,steps,engine,core,repeats,cpu_ms"
      m = split(phases, phase, " ")
      for (i = 1; i <= m; ++i) printf ",%s_ms", phase[i]
      printf "\n"
      for (i = 1; i <= n; ++i) {
        k = order[i]; split(k, part, ",")
        printf "%s,%s,%d", k, part[4] == "ours" ? ours : base, count[k]
        for (c = 5; c <= fields; ++c) printf ",%.4g", median(values[k, c], count[k])
        printf "\n"
      }
    }' >"$PROFILE_OUT"
  echo "compare-core: wrote $PROFILE_OUT" >&2
fi

echo "compare-core: wrote $out" >&2
echo
echo "baseline = $rev; ms/step (thread CPU, mean over the run); ratio = baseline/ours, so > 1:"
echo "ours is faster; min and max: the repeats' ratios; same: both ended in the same state"
printf "%-14s %-5s %6s %9s %9s %7s %7s %7s  %s\n" scene sleep steps ours baseline ratio min max same
awk -F, '
  NR > 1 && $4 != "median" {
    k = $1 "," $2; r = $7
    if (!(k in lo) || r < lo[k]) lo[k] = r
    if (!(k in hi) || r > hi[k]) hi[k] = r
  }
  NR > 1 && $4 == "median" { rows[++n] = $0 }
  END {
    for (i = 1; i <= n; ++i) {
      split(rows[i], f, ","); k = f[1] "," f[2]
      printf "%-14s %-5s %6s %9.4f %9.4f %7.4f %7.4f %7.4f  %s\n", f[1], f[2], f[3], f[5], f[6], f[7],
             lo[k], hi[k], f[11]
    }
  }' "$out"
# A core that ends elsewhere is not the same physics, whatever its speed.
if grep -q ',no,[^,]*,[^,]*$' "$out"; then
  echo "compare-core: the two cores ended in different states (same_result=no above)" >&2
  [[ "${RESULTS_MAY_DIFFER:-0}" == 1 ]] || exit 1
fi
