#!/usr/bin/env bash
# The adder under Icarus Verilog (ctest "rtl"): generate vectors from hls/fp.h, compile
# rtl/fp/*.v + tb/rtl/tb_fp_add.v with iverilog -g2005, run vvp, pass only if the testbench
# checked every vector (more than zero) with no mismatch.
#   run_icarus.sh <fp_vecgen> <workdir> <FP24|FP32> <rtz|rne> <stages> <count>
set -euo pipefail
[ $# -eq 6 ] || { echo "usage: $0 <fp_vecgen> <workdir> <FP24|FP32> <rtz|rne> <stages> <count>" >&2; exit 2; }
vecgen=$1 work=$2 fmt=$3 mode=$4 stages=$5 count=$6
root=$(cd "$(dirname "$0")/../.." && pwd)
command -v iverilog >/dev/null && command -v vvp >/dev/null ||
  { echo "run_icarus: iverilog/vvp not found (make deps)" >&2; exit 1; }
case $fmt in FP24) e=7 m=16 ;; FP32) e=8 m=23 ;; *) echo "bad format $fmt" >&2; exit 2 ;; esac
case $mode in rtz) rne=0 ;; rne) rne=1 ;; *) echo "bad mode $mode" >&2; exit 2 ;; esac
mkdir -p "$work"
tag="fp_add_${fmt}_${mode}_s${stages}"
vec="$work/$tag.hex"
n=$("$vecgen" "$fmt" "$mode" "$count" "$vec")
[ "$n" -gt 0 ] || { echo "run_icarus: no vectors generated" >&2; exit 1; }
iverilog -g2005 -Wall -Wno-timescale -o "$work/$tag.vvp" -s tb_fp_add \
  -P tb_fp_add.EXP_BITS=$e -P tb_fp_add.MAN_BITS=$m -P tb_fp_add.RNE=$rne \
  -P tb_fp_add.STAGES=$stages -P tb_fp_add.N=$n \
  "$root"/rtl/fp/*.v "$root/tb/rtl/tb_fp_add.v"
start=$(date +%s.%N)
vvp -n "$work/$tag.vvp" +vectors="$vec" +seed=12345 | tee "$work/$tag.log"
end=$(date +%s.%N)
line=$(grep '^RESULT ' "$work/$tag.log" || true)
checked=$(sed -n 's/^RESULT vectors=\([0-9]*\).*/\1/p' <<<"$line")
bad=$(sed -n 's/.* mismatches=\([0-9]*\).*/\1/p' <<<"$line")
echo "ICARUS $fmt fp_add $mode s$stages vectors=${checked:-0} of $n mismatches=${bad:-?}" \
     "($(awk "BEGIN{printf \"%.1f\", $end - $start}") s in vvp)"
[ -n "$checked" ] && [ "$checked" -eq "$n" ] && [ "$checked" -gt 0 ] && [ "$bad" -eq 0 ]
