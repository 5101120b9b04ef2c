#!/usr/bin/env bash
# rtl/units/spawn.v's skip-slab / skip-back datapath under Icarus Verilog against hls/hit.h (ctest
# "rtl"): vectors from spawn_vecgen, iverilog -g2005 of the operators + spawn + the testbench, vvp;
# passes only if every vector was checked (more than zero) with no mismatch.
#   run_spawn_icarus.sh <spawn_vecgen> <workdir> <FP24|FP32> <rtz|rne|raycore> <strategy 5|6> <count>
set -euo pipefail
[ $# -eq 6 ] || { echo "usage: $0 <spawn_vecgen> <workdir> <FP24|FP32> <rtz|rne|raycore> <5|6> <count>" >&2; exit 2; }
vecgen=$1 work=$2 fmt=$3 mode=$4 st=$5 count=$6
root=$(cd "$(dirname "$0")/../.." && pwd)
. "$root/tb/rtl/icarus_lib.sh"
icarus_setup "$fmt" "$mode"
# skip-slab: the sweep's 2-ulp slab, back-off 0 (t passes); skip-back: its 4-ulp slab, 1-ulp back-off.
case $st in 5) slab=2 back=0 ;; 6) slab=4 back=1 ;; *) echo "bad strategy $st" >&2; exit 2 ;; esac
mkdir -p "$work"
tag="spawn_s${st}_${fmt}_${mode}"
vec="$work/$tag.hex"
n=$("$vecgen" "$fmt" "$mode" "$slab" "$back" "$count" "$vec")
[ "$n" -gt 0 ] || { echo "run_spawn_icarus: no vectors generated" >&2; exit 1; }
iverilog -g2005 -Wall -Wno-timescale -I "$root/tb/rtl" -o "$work/$tag.vvp" -s tb_spawn_slab \
  -P tb_spawn_slab.EXP_BITS=$e -P tb_spawn_slab.MAN_BITS=$m -P tb_spawn_slab.RNE=$rne \
  -P tb_spawn_slab.RAYCORE=$raycore \
  -P tb_spawn_slab.STAGES=2 -P tb_spawn_slab.STRATEGY=$st -P tb_spawn_slab.N=$n \
  "$root"/rtl/fp/fp_add.v "$root"/rtl/fp/fp_add3.v "$root"/rtl/fp/fp_mul.v "$root"/rtl/fp/fp_div.v "$root"/rtl/fp/fp_rcp.v \
  "$root"/rtl/fp/fp_round.v "$root"/rtl/fp/fp_pipe.v "$root"/rtl/fp/fp_padd.v "$root"/rtl/fp/fp_mag.v \
  "$root"/rtl/units/spawn.v "$root"/rtl/units/spawn_ops.v \
  "$root/tb/sweep/tb_spawn_slab.v"
vvp -n "$work/$tag.vvp" +vectors="$vec" +seed=12345 | tee "$work/$tag.log"
icarus_result "$work/$tag.log" "$n" "spawn STRATEGY=$st $fmt $mode"
