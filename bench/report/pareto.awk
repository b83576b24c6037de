# Reads physics-bench CSV; for one scene (-v scene=NAME) prints "cpu_ms_mean error label
# group" per run, and with -v front=1 only the Pareto front (no other run is both
# faster and more accurate), sorted by time. Errors of exactly 0 are shown at 1e-16
# (a log axis has no 0); the CSV keeps the true value.
BEGIN { FS = "," }
NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
$col["scene"] == scene && $col["error"] != "" {
  t = $col["cpu_ms_mean"] + 0; e = $col["error"] + 0; if (e < 1e-16) e = 1e-16
  engine = $col["engine"]
  group = engine == "ours" ? $col["integrator"] : engine
  label = engine == "ours" ? sprintf("%s s%s i%s", $col["integrator"], $col["substeps"], $col["iterations"]) : engine
  n++; T[n] = t; E[n] = e; L[n] = label; G[n] = group
}
END {
  for (i = 1; i <= n; ++i) {
    if (front) {
      dominated = 0
      for (j = 1; j <= n; ++j) if (j != i && T[j] <= T[i] && E[j] <= E[i] && (T[j] < T[i] || E[j] < E[i])) dominated = 1
      if (dominated) continue
    }
    printf "%.9g %.9g \"%s\" %s\n", T[i], E[i], L[i], G[i]
  }
}
