#!/usr/bin/env bash
# tb/rtl/run_chip.sh - a whole frame on chip.v (make chip): the chip top with its bus (membus_l2.v
# with the frame's L2, the model's default 512 KB unless --l2-kb says otherwise; membus_if.v with
# --l2-kb 0) and one RTU, closed-loop with tb_chip.v's memory, against the transaction model.
#   1. `raycore simulate <frame> --rtl rtu` with RAYCORE_CHIP_DUMP: the frame's registers, the
#      image and the frame's rays (pixel, kind, best record: bit-exact with the golden tracer);
#   2. the transaction model of the same frame: its cycles;
#   3. tb/rtl/tb_chip.v on chip.v, built with `verilator --binary --timing` (SIM=icarus: iverilog,
#      about 30 cycles/s): passes only if its cycles are the model's and its rays the frame's.
# Usage: run_chip.sh <raycore binary> <work dir> [simulate options; default corridor 20x12, VTU off]
# The frame must fit chip.v's build: one RTU, the model's defaults otherwise, FP24 rtz (--l2-kb,
# --l2-ways, --l2-latency and --spawn are taken from the options: chip.v is built with the L2 and the
# spawn strategy the frame uses; the L2's lines and beats are the model's).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
raycore=$1 work=$2
shift 2
[ $# -gt 0 ] || set -- corridor --width 20 --height 12 --vtu off
mkdir -p "$work"
frame=("$@" --rtus 1 --no-reference)
# The memory's and the L2's timing for tb_chip.v, from the options (`--opt value` or `--opt=value`;
# raycore's --rtl rtu run below refuses what no built model runs, before they are used).
lat=100 l2kb=512 l2ways=8 l2lat=20 spawn=none
for ((i = 1; i <= $#; i++)); do
  j=$((i + 1))
  opt=${!i} val=${!j:-}
  [[ "$opt" == --*=* ]] && { val=${opt#*=}; opt=${opt%%=*}; }
  case "$opt" in
    --mem-latency) lat=$val ;;
    --l2-kb) l2kb=$val ;;
    --l2-ways) l2ways=$val ;;
    --l2-latency) l2lat=$val ;;
    --spawn) spawn=$val ;;
  esac
done

cycles_of() { sed -n 's/^hardware *\([0-9]*\) cycles.*/\1/p' "$1"; }
RAYCORE_CHIP_DUMP="$work/frame" "$raycore" simulate "${frame[@]}" --rtl rtu > "$work/rtu.log"
"$raycore" simulate "${frame[@]}" > "$work/model.log"
model=$(cycles_of "$work/model.log")
rtu=$(cycles_of "$work/rtu.log")
grep -q '^golden *match' "$work/rtu.log" || { echo "run_chip: --rtl rtu frame is not golden" >&2; exit 1; }
img=$(wc -l < "$work/frame.img")
# chip.v is built for the frame's spawn strategy (rtu.v's SPAWNS, bit s = hls::Spawn s) besides none;
# --rtl rtu above has refused a name it does not know.
spawns=1 s=0
for name in none skip-origin ulp-offset error-bound skip-offset skip-slab skip-back; do
  [ "$name" = "$spawn" ] && spawns=$((1 | (1 << s)))
  s=$((s + 1))
done
l2sets=$((l2kb * 1024 / (l2ways * 64)))  # accepted by --rtl rtu: the default or the 1 KB L2, or none

# chip.v's sources, as rtl/units/rtu.cmake lists them (written at configure time beside raycore's build).
list=$(dirname "$raycore")/../rtl/chip_sources.txt
[ -f "$list" ] || { echo "run_chip: $list not found (configure with RAYCORE_RTL=ON)" >&2; exit 1; }
mapfile -t srcs < "$list"
defs=(-DDUMP="\"$work/frame\"" -DIMG="$img" -DLAT="$lat" -DL2_SETS="$l2sets" -DL2_WAYS="$l2ways"
      -DL2_LAT="$l2lat" -DSPAWNS="$spawns")
start=$(date +%s)
if [ "${SIM:-verilator}" = icarus ]; then
  iverilog -g2005 -Wno-timescale "${defs[@]}" -o "$work/tb_chip.vvp" -s tb_chip "${srcs[@]}" \
    "$root/tb/rtl/tb_chip.v"
  vvp -n "$work/tb_chip.vvp" > "$work/chip.log"
else
  # The build is cached by the sources' and defines' hash (the image size is a define).
  key=$(cat "${srcs[@]}" "$root/tb/rtl/tb_chip.v" <(echo "${defs[@]}") | sha1sum | cut -c1-12)
  if [ ! -x "$work/obj_$key/tb_chip" ]; then
    verilator --binary --timing -Wno-fatal -Wno-lint -Wno-style --default-language 1364-2005 -O3 \
      --x-assign fast --x-initial unique "${defs[@]}" --Mdir "$work/obj_$key" -o tb_chip \
      --top-module tb_chip "$root/rtl/lint/waivers.vlt" "${srcs[@]}" "$root/tb/rtl/tb_chip.v" \
      -j "${JOBS:-2}" > "$work/verilator.log" 2>&1 ||
      { tail -20 "$work/verilator.log" >&2; exit 1; }
  fi
  "$work/obj_$key/tb_chip" > "$work/chip.log"
fi
secs=$(( $(date +%s) - start ))
line=$(grep '^RESULT ' "$work/chip.log" || true)
chip=$(sed -n 's/^RESULT cycles=\([0-9]*\).*/\1/p' <<<"$line")
norm() { awk '{ for (i = 1; i <= 3; i++) { sub(/^0+/, "", $i); if ($i == "") $i = "0" } print }' "$1" | sort; }
same=no
cmp -s <(norm "$work/frame.px") <(norm "$work/frame.chip.px") && same=yes
echo "run_chip: ${*}: model $model cycles, --rtl rtu $rtu, chip.v (${SIM:-verilator}, ${secs} s) ${chip:-none};" \
     "rays $(wc -l < "$work/frame.chip.px") of $(wc -l < "$work/frame.px"), equal: $same"
[ -n "$chip" ] && [ "$chip" = "$model" ] && [ "$same" = yes ]
