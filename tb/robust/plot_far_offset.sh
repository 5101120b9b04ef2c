#!/bin/sh
# Run by hand: tb/robust/plot_far_offset.sh [build-dir]  (default build-robust)
# Writes docs/far_offset.dat from the FarOffset test's printed table and, if gnuplot is
# installed, docs/far_offset.png (total errors = self + shadow + primary vs log10 offset).
set -e
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build-robust}
dat=$root/docs/far_offset.dat
{
  echo "# tb/robust FarOffset.VtuKeepsErrorFlat: small scene 160x96 translated by 10^k (1,1,1)"
  echo "# k config vtu self shadow primary total"
  "$build/bin/test_robust" --gtest_filter=FarOffset.* | sed -n 's/^far_offset: \([0-9].*\)/\1/p'
} > "$dat"
echo "wrote $dat"
command -v gnuplot >/dev/null || { echo "gnuplot not installed: no PNG"; exit 0; }
gnuplot <<GP
set terminal pngcairo size 900,560 noenhanced
set output "$root/docs/far_offset.png"
set title "Far-offset invariance: errors (self + shadow + primary, of 15360 pixels) vs offset"
set xlabel "scene and camera translated by 10^k (k)"
set ylabel "error pixels (log)"
set logscale y
set key outside right
plot for [c in "fp24-rtz fp24-rne fp32-rtz fp32-rne"] for [v in "off on"] \
  "< awk '\$2==\"".c."\" && \$3==\"".v."\"' $dat" using 1:(\$7+1) with linespoints title c." vtu ".v
GP
echo "wrote $root/docs/far_offset.png"
