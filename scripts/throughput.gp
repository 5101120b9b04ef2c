# Rays per cycle per RTU (left axis) and Mrays/s of the frame at the reports' clock (right axis:
# the same points, scaled by RTUs x clock) against RTU area (NAND2 eq.: rtu.v's synthesised logic
# through the area model, + SRAM), one panel per scene: every configuration, its Pareto front, the
# goal of issue 14 (0.08) and the configurations that meet it.
# gnuplot -e "dir='out/throughput'; out='out/throughput.png'; scenes='sponza-paper corridor'" scripts/throughput.gp
set terminal pngcairo size 1500,520 font ",10"
set output out
n = words(scenes)
set multiplot layout 1, n title "Throughput against RTU area (6 RTUs, 100-cycle memory, FP24 rtz, 800x480; goal: 0.08 rays/cycle per RTU at <= 1.1 GB/s)"
set grid
set xlabel "RTU area (M NAND2 eq.: synthesised logic + 0.5 per SRAM bit)"
set ylabel "rays per cycle per RTU"
set key bottom right font ",8"
do for [i=1:n] {
  s = word(scenes, i)
  f = sprintf("%s/plot-%s.dat", dir, s)
  set title s
  # Mrays/s per rays/cycle/RTU (column 7 / column 2: RTUs x clock, equal for every row); the right
  # axis is the left one times k (both ranges set: this gnuplot's `set link` draws no tics).
  set xrange [*:*]
  set yrange [*:*]
  stats f u ($7/$2) nooutput
  k = STATS_mean
  stats f u 2 nooutput
  lo = (STATS_min < 0.08 ? STATS_min : 0.08) * 0.95
  hi = (STATS_max > 0.08 ? STATS_max : 0.08) * 1.05
  set yrange [lo:hi]
  set y2range [lo*k:hi*k]
  set ytics nomirror
  set y2tics
  set y2label sprintf("Mrays/s at %.0f MHz (docs/timing.json)", k / 6)
  plot f u ($1/1e6):2 w p pt 7 ps 0.8 lc rgb "#999999" t "configuration", \
       f u ($3 == 1 ? $1/1e6 : 1/0):2 w lp pt 7 ps 1.1 lc rgb "#1f77b4" t "Pareto front", \
       f u ($4 == 1 ? $1/1e6 : 1/0):2 w p pt 6 ps 2 lw 2 lc rgb "#d62728" t "meets the goal", \
       f u ($6 == 1 ? $1/1e6 : 1/0):2 w p pt 3 ps 3.5 lw 2 lc rgb "#2ca02c" t "least area meeting the goal", \
       f u ($3 == 1 ? $1/1e6 : 1/0):2:5 w labels offset 0,0.8 font ",8" notitle, \
       0.08 w l dt 2 lc rgb "#d62728" t "goal 0.08"
}
unset multiplot
