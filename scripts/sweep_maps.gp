# scripts/sweep_maps.gp - error-map montage of one scene: the full maps on top, the worst windows
# (enlarged) below. gnuplot -e "list='out/sweep/maps-S.tsv'; scene='S'; out='...png'" scripts/sweep_maps.gp
# list: lines "scene<TAB>map png<TAB>crop png<TAB>label<TAB>error pixels" (raycore sweep --collect).
n = int(system("wc -l < ".list))
set terminal pngcairo size 420*n, 600 noenhanced font ",9"
set output out
set datafile separator "\t"
maps(i)  = system(sprintf("awk -F'\\t' 'NR==%d {print $2}' %s", i, list))
crops(i) = system(sprintf("awk -F'\\t' 'NR==%d {print $3}' %s", i, list))
label(i) = system(sprintf("awk -F'\\t' 'NR==%d {print $4 \" (\" $5 \" error px)\"}' %s", i, list))
unset border; unset tics; unset key
set size ratio -1
set multiplot layout 2, n title scene.": error maps (yellow primary, red false shadow from a self-intersection, magenta other false shadow, cyan light leak, orange self-intersection without a pixel error); below: the window with the most error pixels, enlarged"
do for [i = 1:n] {
  set title label(i)
  plot maps(i) binary filetype=png with rgbimage
}
do for [i = 1:n] {
  set title "worst window"
  plot crops(i) binary filetype=png with rgbimage
}
unset multiplot
