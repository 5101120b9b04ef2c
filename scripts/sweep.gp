# scripts/sweep.gp - the sweep's plot: error against throughput, one panel per scene, the Pareto
# front marked. gnuplot -e "dir='out/sweep'; out='out/sweep/sweep.png'" scripts/sweep.gp
# Reads dir/plot.dat (one block per scene: error_pct rays_per_cycle pareto format vtu spawn label
# store, Pareto points first, by error; store anchored points get a black cross over them) and dir/plot_scenes.txt (the blocks' scene names).
if (!exists("dir")) dir = "out/sweep"
if (!exists("out")) out = dir."/sweep.png"
dat = dir."/plot.dat"
scenes = system("tr '\\n' ' ' < ".dir."/plot_scenes.txt")
n = words(scenes)
cols = n < 4 ? n : 4
rows = int(ceil(n / (cols * 1.0)))
set terminal pngcairo size 480*cols, 420*rows + 60 noenhanced font ",9"
set output out
floor = 1e-4   # zero errors are drawn at this error (log axis)
fx(x) = x < floor ? floor : x
fmtc(s) = s eq "fp24-rtz" ? 0xd62728 : (s eq "fp24-rne" ? 0x1f77b4 : (s eq "fp32" ? 0x2ca02c : 0x9467bd))
# point type: spawn (none circle, skip-origin square, ulp-offset triangle, error-bound diamond,
# skip-offset triangle down, skip-slab pentagon, skip-back plus / star), filled when the VTU is on;
# a spawn spec "strategy:ulps" is drawn as its strategy
sbase(s) = strstrt(s, ":") > 0 ? s[1:strstrt(s, ":") - 1] : s
spt0(s) = s eq "none" ? 6 : (s eq "skip-origin" ? 4 : (s eq "ulp-offset" ? 8 : (s eq "error-bound" ? 12 : \
          (s eq "skip-offset" ? 10 : (s eq "skip-slab" ? 14 : (s eq "skip-back" ? 1 : 2))))))
spt(s, v) = spt0(sbase(s)) == 1 ? (v eq "on" ? 3 : 1) : spt0(sbase(s)) + (v eq "on" ? 1 : 0)
set multiplot layout rows, cols title "Error (shadow + primary error pixels, % of pixels) against throughput (rays per cycle, cycle model, 6 RTUs); black line = Pareto front (less error, more rays/cycle). Colour: format; shape: spawn; filled: VTU on"
set logscale x
set format x "%g"
set grid
set xlabel "error pixels, % (0 drawn at 1e-4)"
set ylabel "rays / cycle"
set key top left font ",8" samplen 1 spacing 0.9
do for [i = 1:n] {
  set title word(scenes, i)
  if (i == 1) { set key } else { unset key }
  plot dat index (i-1) using (fx($1)):2:(spt(strcol(6), strcol(5))):(fmtc(strcol(4))) \
         with points pt variable lc rgb variable ps 1.3 notitle, \
       dat index (i-1) using (fx($1)):(strcol(8) eq "anchored" ? $2 : 1/0) with points pt 2 ps 1.8 lc rgb "black" \
         title "store anchored", \
       dat index (i-1) using (fx($1)):($3 == 1 ? $2 : 1/0) with lines lc rgb "black" lw 1.5 title "Pareto front", \
       dat index (i-1) using (fx($1)):($3 == 1 ? $2 : 1/0) with points pt 6 ps 2.4 lc rgb "black" notitle, \
       dat index (i-1) using (fx($1)):($3 == 1 ? $2 : 1/0):7 with labels offset 0, 1.4 font ",7" notitle, \
       1/0 with points pt 7 lc rgb 0xd62728 title "fp24-rtz", \
       1/0 with points pt 7 lc rgb 0x1f77b4 title "fp24-rne", \
       1/0 with points pt 7 lc rgb 0x2ca02c title "fp32 (rne)", \
       1/0 with points pt 6 lc rgb "gray40" title "none", \
       1/0 with points pt 4 lc rgb "gray40" title "skip-origin", \
       1/0 with points pt 8 lc rgb "gray40" title "ulp-offset", \
       1/0 with points pt 12 lc rgb "gray40" title "error-bound", \
       1/0 with points pt 10 lc rgb "gray40" title "skip-offset", \
       1/0 with points pt 14 lc rgb "gray40" title "skip-slab", \
       1/0 with points pt 1 lc rgb "gray40" title "skip-back (+, on: *)", \
       1/0 with points pt 7 lc rgb "gray40" title "filled: VTU on"
}
unset multiplot
