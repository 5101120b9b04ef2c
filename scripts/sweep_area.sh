#!/usr/bin/env bash
# scripts/sweep_area.sh: the added hardware of the sweep's options, as yosys generic cells per RTU,
# printed as TSV lines "module format rounding cells" (read by `raycore sweep --collect --area`).
#
# - ist, trv, vtu: the cells column of docs/area.md (scripts/area.sh: synth -flatten at STAGES=2).
#   The sweep counts the VTU as the vtu unit's cells, and a format or rounding change as the ist's
#   and the trv datapath's deltas against FP24 rtz (the hit unit has no RTL: its delta is not counted).
# - spawn-<strategy>: rtl/units/spawn.v (STRATEGY 1 skip-origin, 2 ulp-offset, 3 error-bound,
#   4 skip-offset, 5 skip-slab, 6 skip-back) synthesised here the same way (read_verilog of the
#   rtl/fp operators it uses and rtl/units/spawn*.v; chparam; synth
#   -flatten -top spawn; no latch; check -assert; stat), STAGES=2. Results are cached under
#   out/sweep-area-cache/ by a hash of the sources and parameters (the error-bound unit takes
#   minutes); SWEEP_AREA_JOBS synthesis runs at a time (default nproc).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v yosys >/dev/null || { echo "sweep_area: yosys is needed (make deps)" >&2; exit 1; }
AREA_MD=${SWEEP_AREA_MD:-docs/area.md}
CACHE=${SWEEP_AREA_CACHE:-out/sweep-area-cache}
STAGES=2
mkdir -p "$CACHE"
[ -f "$AREA_MD" ] || { echo "sweep_area: no $AREA_MD (make area)" >&2; exit 1; }

[ "${1:-}" = --one ] || echo "# module format rounding cells (yosys generic cells; ist/trv/vtu from $AREA_MD, spawn-* from rtl/units/spawn.v, STAGES=$STAGES)"
# | ist | FP24 | rtz | 49412 | ...
[ "${1:-}" = --one ] || awk -F'|' '{ for (i = 2; i <= 5; i++) gsub(/ /, "", $i) }
  ($2 == "ist" || $2 == "trv" || $2 == "vtu") && ($4 == "rtz" || $4 == "rne") { print $2 "\t" tolower($3) "\t" $4 "\t" $5 }' "$AREA_MD"

# The operators spawn_ops instantiates and what they use (the cache key is their hash).
srcs=(rtl/fp/fp_add.v rtl/fp/fp_add3.v rtl/fp/fp_mul.v rtl/fp/fp_div.v rtl/fp/fp_round.v rtl/fp/fp_pipe.v
      rtl/fp/fp_padd.v rtl/fp/fp_mag.v
      rtl/units/spawn.v rtl/units/spawn_ops.v)
for f in "${srcs[@]}"; do [ -f "$f" ] || { echo "sweep_area: missing $f" >&2; exit 1; }; done
hash=$(cat "${srcs[@]}" | sha256sum | cut -c1-16)
# One yosys run: strategy format rounding -> the cached stat file.
synth_one() {
  local st=$1 fmt=$2 rnd=$3 e m rne out log
  if [ "$fmt" = fp24 ]; then e=7 m=16; else e=8 m=23; fi
  [ "$rnd" = rne ] && rne=1 || rne=0
  out="$CACHE/spawn-$hash-s$st-$fmt-$rnd.stat"
  [ -s "$out" ] && return 0
  log="$out.log"
  if ! yosys -q -l "$log" -p "read_verilog ${srcs[*]}; \
      chparam -set EXP_BITS $e -set MAN_BITS $m -set STAGES $STAGES -set RNE $rne -set STRATEGY $st spawn; \
      synth -flatten -top spawn; \
      select -assert-none t:\$dlatch t:\$adlatch t:\$dlatchsr t:\$_DLATCH_* t:\$_DLATCHSR_*; \
      check -assert; tee -q -o $out.tmp stat" >/dev/null 2>&1; then
    echo "sweep_area: yosys failed for spawn STRATEGY=$st $fmt $rnd, see $log" >&2
    return 1
  fi
  mv "$out.tmp" "$out"
}
if [ "${1:-}" = --one ]; then  # one run, from the parallel below
  synth_one "$2" "$3" "$4"
  exit
fi
names=([1]=skip-origin [2]=ulp-offset [3]=error-bound [4]=skip-offset [5]=skip-slab [6]=skip-back)
runs=()
for st in 1 2 3 4 5 6; do
  for fr in "fp24 rtz" "fp24 rne" "fp32 rne"; do
    # skip-origin has no arithmetic: one run (FP24 rtz) stands for every format.
    [ $st -eq 1 ] && [ "$fr" != "fp24 rtz" ] && continue
    runs+=("$st $fr")
  done
done
# The longest runs first (error-bound, then the others).
printf '%s\n' "${runs[@]}" | awk '{ print ($1 == 3 ? 0 : 1), $0 }' | sort -k1,1n -k2,2r | cut -d' ' -f2- |
  parallel --will-cite --jobs "${SWEEP_AREA_JOBS:-$(nproc)}" --colsep ' ' \
    ./scripts/sweep_area.sh --one {1} {2} {3} >&2 ||
  { echo "sweep_area: synthesis failed" >&2; exit 1; }
for st in 1 2 3 4 5 6; do
  for fr in "fp24 rtz" "fp24 rne" "fp32 rne"; do
    set -- $fr
    f=$1; r=$2
    [ $st -eq 1 ] && f=fp24 r=rtz
    cells=$(awk '$1 == "Number" && $3 == "cells:" { print $4 }' "$CACHE/spawn-$hash-s$st-$f-$r.stat")
    printf 'spawn-%s\t%s\t%s\t%s\n' "${names[$st]}" "$1" "$2" "$cells"
  done
done
