# Time per step and awake bodies over simulated time, one line per engine run.
# Called by bench/plot-timeline.sh with -e "datadir='...'; series='...'; title_text='...'; out='...'".
set terminal svg size 1000,800 dynamic font "sans,11"
set output out
set multiplot layout 2,1 title title_text
set grid
set key top right font ",9"
set xlabel "simulated time (s)"
set logscale y
set format y "10^{%L}"
set ylabel "CPU time per step (ms)"
plot for [i = 1:words(series)] sprintf("%s/%s.dat", datadir, word(series, i)) \
       using 1:3 with linespoints pt 7 ps 0.4 title word(series, i) noenhanced
unset logscale y
set format y "%g"
set ylabel "awake bodies"
set yrange [0:*]
set offsets 0, 0, graph 0.06, 0
plot for [i = 1:words(series)] sprintf("%s/%s.dat", datadir, word(series, i)) \
       using 1:2 with lines lw 1.5 title word(series, i) noenhanced
unset multiplot
