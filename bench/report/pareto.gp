# Error against mean time per step, log axes, one panel per scene; the line joins
# the Pareto front. Called by bench/run-report.sh with -e "datadir='...'; out='...'".
set terminal svg size 1200,900 dynamic font "sans,11"
set output out
set multiplot layout 2,2 title "physics-bench: error against time per step (one run, this machine)"
set logscale xy
set format y "10^{%L}"
set xlabel "mean CPU time per step (ms)"
set grid
set key below horizontal font ",9"
scenes = "projectile-friction bounce-e1 bounce-e0.5 column-50"
ylabels = "'max position error vs closed form (m)' 'apex error after 36 bounces (relative)' 'worst of first 5 apexes vs e^{2n}h_0 (relative)' 'top box drift (m)'"
groups = "explicit-euler semi-implicit-euler exact box2d chipmunk"
do for [s = 1:words(scenes)] {
  scene = word(scenes, s)
  set title scene
  set ylabel word(ylabels, s)
  file = sprintf("%s/%s.dat", datadir, scene)
  front = sprintf("%s/%s.front.dat", datadir, scene)
  plot for [g = 1:words(groups)] file using 1:(strcol(4) eq word(groups, g) ? $2 : NaN) \
         with points pt (g + 4) ps 0.8 title word(groups, g), \
       front using 1:2 with lines lw 1.5 lc rgb "black" title "Pareto front"
}
unset multiplot
