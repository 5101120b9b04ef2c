#!/usr/bin/env bash
# The adder under Icarus Verilog (ctest "rtl"): generate vectors from hls/fp.h, compile
# rtl/fp/*.v + tb/rtl/tb_fp_add.v with iverilog -g2005, run vvp, pass only if the testbench
# checked every vector (more than zero) with no mismatch.
#   run_icarus.sh <fp_vecgen> <workdir> <FP24|FP32> <rtz|rne|raycore> <stages> <count>
set -euo pipefail
[ $# -eq 6 ] || { echo "usage: $0 <fp_vecgen> <workdir> <FP24|FP32> <rtz|rne|raycore> <stages> <count>" >&2; exit 2; }
vecgen=$1 work=$2 fmt=$3 mode=$4 stages=$5 count=$6
root=$(cd "$(dirname "$0")/../.." && pwd)
. "$root/tb/rtl/icarus_lib.sh"
icarus_setup "$fmt" "$mode"
mkdir -p "$work"
tag="fp_add_${fmt}_${mode}_s${stages}"
vec="$work/$tag.hex"
n=$("$vecgen" "$fmt" "$mode" "$count" "$vec")
[ "$n" -gt 0 ] || { echo "run_icarus: no vectors generated" >&2; exit 1; }
iverilog -g2005 -Wall -Wno-timescale -I "$root/tb/rtl" -o "$work/$tag.vvp" -s tb_fp_add \
  -P tb_fp_add.EXP_BITS=$e -P tb_fp_add.MAN_BITS=$m -P tb_fp_add.RNE=$rne -P tb_fp_add.RAYCORE=$raycore \
  -P tb_fp_add.STAGES=$stages -P tb_fp_add.N=$n \
  "$root"/rtl/fp/*.v "$root/tb/rtl/tb_fp_add.v"
start=$(date +%s.%N)
vvp -n "$work/$tag.vvp" +vectors="$vec" +seed=12345 | tee "$work/$tag.log"
end=$(date +%s.%N)
icarus_result "$work/$tag.log" "$n" \
  "$fmt fp_add $mode s$stages ($(awk "BEGIN{printf \"%.1f\", $end - $start}") s in vvp)"
