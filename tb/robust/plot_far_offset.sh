#!/bin/sh
# Run by hand: tb/robust/plot_far_offset.sh [build-dir]  (default build-robust)
# Writes docs/far_offset.dat from the FarOffset test's printed table and, if gnuplot is
# installed, docs/far_offset.png: per format a panel of error pixels (self + shadow + primary) vs
# log10 offset, store world/anchored x VTU off/on, total (vs the scene, solid) and arithmetic (vs
# the stored scene, sim/errors.h; dashed).
set -e
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build-robust}
dat=$root/docs/far_offset.dat
{
  echo "# tb/robust FarOffset.VtuKeepsErrorFlat: small scene 160x96 translated by 10^k (1,1,1), spawn none"
  echo "# errors = self + shadow + primary: total (vs the scene) and a_ = arithmetic (vs the stored scene)"
  echo "# k config vtu store self shadow primary total a_self a_shadow a_primary a_total"
  "$build/bin/test_robust" --gtest_filter=FarOffset.VtuKeepsErrorFlat | sed -n 's/^far_offset: \([0-9].*\)/\1/p'
} > "$dat"
echo "wrote $dat"
command -v gnuplot >/dev/null || { echo "gnuplot not installed: no PNG"; exit 0; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/far_offset.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
# One file per format, store and VTU; one panel per format (written out by the shell: a panel
# title set inside a gnuplot do-loop is lost under a multiplot title in gnuplot 5.4).
awk -v d="$tmp" '!/^#/ { print > (d "/" $2 "-" $4 "-" $3 ".dat") }' "$dat"
panels=
for c in fp24-rtz fp24-rne fp32-rtz fp32-rne; do
  panels="$panels
set title '$c' font ',12'
plot for [s in 'world anchored'] for [v in 'off on'] '$tmp/$c-'.s.'-'.v.'.dat' using 1:(\$8+1) \\
       with linespoints lw 2 pt 7 lc rgb col(s, v) title s.' vtu '.v.' total', \\
     for [s in 'world anchored'] for [v in 'off on'] '$tmp/$c-'.s.'-'.v.'.dat' using 1:(\$12+1) \\
       with linespoints lw 1.5 dt 2 pt 6 lc rgb col(s, v) title s.' vtu '.v.' arith.'"
done
gnuplot <<GP
set terminal pngcairo size 1200,900 noenhanced font ",9"
set output "$root/docs/far_offset.png"
set multiplot layout 2,2 title "Far-offset invariance (small scene, 160 x 96 = 15360 pixels, spawn none): error pixels (self + shadow + primary, +1, log) vs offset 10^k.\nSolid: total (vs the scene); dashed: arithmetic (vs the scene as the image stores it). Store world: the image holds world coordinates; anchored: relative to the box centre."
set xlabel "scene and camera translated by 10^k (k)"
set ylabel "error pixels + 1 (log)"
set logscale y
set yrange [0.8:40000]
set grid
set key top left font ",8" samplen 2
col(s, v) = s eq "world" ? (v eq "off" ? 0xd62728 : 0x1f77b4) : (v eq "off" ? 0xff7f0e : 0x2ca02c)
$panels
unset multiplot
GP
echo "wrote $root/docs/far_offset.png"
