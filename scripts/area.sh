#!/usr/bin/env bash
# make area: yosys `synth` + `stat` of every floating-point module of rtl/fp/ and of the units of
# rtl/units/ (vtu, ist, trv, rgu, ...) for FP24 and FP32, each rounding mode, at a fixed pipeline
# depth (STAGES=2 unless RAYCORE_AREA_STAGES says otherwise), written as a markdown table to
# docs/area.md (or the file given as $1).
#
# Columns: yosys generic cells after `synth -flatten`, flip-flops among them, a NAND2-equivalent
# estimate (each generic cell weighted by the area of the matching NanGate 45 nm Open Cell Library
# X1 cell divided by NAND2_X1's, see the table in the output), and the logic depth (`ltp -noff`:
# the longest path in cells between registers or ports). Fails on an unknown cell type (so the
# estimate never silently leaves cells out) and on any yosys error.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v yosys >/dev/null || { echo "area: yosys is needed (make deps)" >&2; exit 1; }

STAGES=${RAYCORE_AREA_STAGES:-2}
OUT=${1:-docs/area.md}
# Units: every rtl/units/<unit>.v whose name is not <another unit>_* (those are its helpers).
UNITS=()
for f in rtl/units/*.v; do
  n=$(basename "$f" .v) helper=0
  for g in rtl/units/*.v; do
    p=$(basename "$g" .v)
    [ "$p" != "$n" ] && [[ "$n" == "${p}_"* ]] && helper=1
  done
  [ $helper -eq 0 ] && UNITS+=("$n")
done
MODULES=(fp_add fp_add3 fp_mul fp_div fp_sqrt fp_rcp fp_cmp "${UNITS[@]}")
# The sources a module is read from: rtl/fp/*.v, plus for a unit rtl/units/<unit>.v and its
# helpers rtl/units/<unit>_*.v (so an unfinished file of another unit cannot break this one).
srcs_for() {
  local f=(rtl/fp/*.v)
  if [ -f "rtl/units/$1.v" ]; then f+=("rtl/units/$1.v"); f+=($(ls rtl/units/"$1"_*.v 2>/dev/null || true)); fi
  # and another unit's helper it instantiates (hit.v: spawn_ops.v)
  local g
  for g in rtl/units/*_*.v; do
    [[ " ${f[*]} " == *" $g "* ]] && continue
    grep -Eq "^\s*$(basename "$g" .v)\s+#" "rtl/units/$1.v" 2>/dev/null && f+=("$g")
  done
  echo "${f[@]}"
}
file_of() { [ -f "rtl/fp/$1.v" ] && echo "rtl/fp/$1.v" || echo "rtl/units/$1.v"; }
TMP=$(mktemp -d "${TMPDIR:-/tmp}/raycore-area.XXXXXX")
trap 'rm -rf "$TMP"' EXIT

# Cell weights in NAND2 equivalents (NanGate45 X1 cell area / NAND2_X1 area 0.798 um^2).
# Flip-flops: DFF_X1 5.67, DFFR_X1 (async reset) 6.67, plus MUX2_X1 2.33 for an enable and
# AND2_X1 1.33 for a synchronous reset/set.
WEIGHTS_AWK='
function ff_weight(t,   w) {
  w = (t ~ /^\$_DFF_[PN][NP][01]_$/ || t ~ /^\$_DFFE_[PN][NP][01][PN]_$/ || t ~ /^\$_DFFSR/) ? 6.67 : 5.67
  if (t ~ /^\$_(DFFE|SDFFE|SDFFCE|DFFSRE)_/) w += 2.33
  if (t ~ /^\$_SDFF/) w += 1.33
  return w
}
BEGIN {
  g["$_NOT_"] = 0.67; g["$_BUF_"] = 1.00; g["$_NAND_"] = 1.00; g["$_NOR_"] = 1.00
  g["$_AND_"] = 1.33; g["$_OR_"] = 1.33; g["$_ANDNOT_"] = 1.33; g["$_ORNOT_"] = 1.33
  g["$_XOR_"] = 2.00; g["$_XNOR_"] = 2.00; g["$_MUX_"] = 2.33; g["$_NMUX_"] = 2.33
  g["$_AOI3_"] = 1.33; g["$_OAI3_"] = 1.33; g["$_AOI4_"] = 1.67; g["$_OAI4_"] = 1.67
}
$1 == "Number" && $3 == "cells:" { cells = $4 }
$1 ~ /^\$_/ && NF == 2 {
  t = $1; n = $2
  if (t ~ /DFF/) { ffs += n; ge += n * ff_weight(t) }
  else if (t in g) ge += n * g[t]
  else { print "area: unknown cell type " t > "/dev/stderr"; bad = 1 }
}
END { if (bad) exit 1; printf "%d %d %.0f\n", cells, ffs, ge }
'

fmt_params() { [ "$1" = FP24 ] && echo "7 16" || echo "8 23"; }
# Parameters of a unit without a number format, for its row: ascache = the cycle model's node
# cache (16 KB: 64 sets x 4 ways x 64 B lines, 8 MSHRs; the module's defaults are a 1 KB cache).
declare -A UNIT_PARAMS=([ascache]="-set SETS 64 -set WAYS 4 -set LINE_BYTES 64 -set MSHRS 8")
# Memories (the $mem_v2 cells of `memory -nomap`) are SRAM macros: not mapped to flip-flops, not
# in cells/FFs/NAND2 eq.; their bits (SIZE x WIDTH) are listed in their own column.
MEM_AWK='
/^ *cell /          { w = 0; s = 0 }
/parameter .WIDTH / { w = $3 }
/parameter .SIZE /  { s = $3 }
/^ *end/            { if (w && s) bits += w * s; w = s = 0 }
END { printf "%d\n", bits }
'

rows=()
for mod in "${MODULES[@]}"; do
  fmts=(FP24 FP32)
  grep -q "^// lint: FP24 only" "$(file_of "$mod")" && fmts=(FP24)  # fp_rcp: raycore's, FP24
  for fmt in "${fmts[@]}"; do
    read -r e m < <(fmt_params "$fmt")
    modes=(rtz rne)
    grep -Eq "parameter +integer +RNE\b" "$(file_of "$mod")" || modes=(-)
    # Rounding mode raycore (FP24 only): RAYCORE = 1 where the module has the parameter.
    [ "$fmt" = FP24 ] && grep -Eq "parameter +integer +RAYCORE\b" "$(file_of "$mod")" && modes+=(raycore)
    [ "$mod" = fp_rcp ] && modes=(raycore)
    for mode in "${modes[@]}"; do
      set_rne=""
      [ "$mode" = rtz ] && set_rne="-set RNE 0"
      [ "$mode" = rne ] && set_rne="-set RNE 1"
      [ "$mode" = raycore ] && [ "$mod" != fp_rcp ] && set_rne="-set RNE 0 -set RAYCORE 1"
      log="$TMP/$mod-$fmt-$mode"
      yosys -q -l "$log.log" -p "read_verilog $(srcs_for "$mod"); \
        $(grep -Eq "parameter +integer +EXP_BITS" "$(file_of "$mod")" && echo "chparam -set EXP_BITS $e -set MAN_BITS $m -set STAGES $STAGES $set_rne $mod;") \
        $([ -n "${UNIT_PARAMS[$mod]:-}" ] && echo "chparam ${UNIT_PARAMS[$mod]} $mod;") \
        synth -flatten -top $mod -run :fine; tee -q -o $log.mem dump t:\$mem_v2; \
        opt -fast -full; opt -full; techmap; opt -fast; abc -fast; opt -fast; hierarchy -check; check; \
        tee -q -o $log.stat stat; tee -q -o $log.ltp ltp -noff" >/dev/null ||
        { echo "area: yosys failed for $mod $fmt $mode, see:" >&2; tail -20 "$log.log" >&2; exit 1; }
      read -r cells ffs ge < <(awk "$WEIGHTS_AWK" "$log.stat")
      depth=$(sed -n 's/.*length=\([0-9]*\).*/\1/p' "$log.ltp" | head -1)
      sram=$(awk "$MEM_AWK" "$log.mem")
      rows+=("| $mod | $fmt | $mode | $cells | $ffs | $ge | $depth | $sram |")
      echo "area: $mod $fmt $mode: cells=$cells ffs=$ffs nand2_eq=$ge depth=$depth sram_bits=$sram"
    done
  done
done

{
  echo "# Area of the RTL (rtl/fp/, rtl/units/)"
  echo
  echo "Generated by \`make area\` (\`./scripts/area.sh\`; STAGES=$STAGES, \`RAYCORE_AREA_STAGES=N\` to change) with"
  echo "$(yosys -V | head -1) on $(date -u +%Y-%m-%d). Do not edit by hand."
  echo
  echo "Each module is synthesised alone: \`read_verilog rtl/fp/*.v [rtl/units/<unit>*.v]; chparam -set EXP_BITS E -set MAN_BITS M"
  echo "-set STAGES $STAGES [-set RNE 0|1] [-set RAYCORE 1] <module>; synth -flatten -top <module>; stat; ltp -noff\`."
  echo "Rounding raycore (FP24 only): RAYCORE = 1 (RNE = 0); fp_rcp is raycore's reciprocal alone."
  echo "TAG_BITS = each module's default (fp_* and vtu 1; ist 16: its ray/slot tag). A unit's STAGES"
  echo "is per FP operator (vtu: 3 operator levels, latency 3 x STAGES, flattened with its operators)."
  echo
  echo "- **cells**: yosys generic gates and flip-flops after \`synth\` (\`stat\`)."
  echo "- **FFs**: flip-flops among them (pipeline registers: valid bits with asynchronous reset, data"
  echo "  with enable and no reset)."
  echo "- **NAND2 eq.**: each generic cell weighted by the area of the corresponding cell of the NanGate"
  echo "  45 nm Open Cell Library (FreePDK45), drive X1, divided by NAND2_X1's 0.798 um^2 (table"
  echo "  below). An estimate for comparing modules and modes, not a sign-off number: a real"
  echo "  mapping with a liberty file and timing constraints would merge gates (AOI/OAI, full-adder"
  echo "  cells) and upsize critical paths; expect +-30 %."
  echo "- **depth**: the longest combinational path in cells between registers or ports (\`ltp -noff\`),"
  echo "  a rough indicator of the cycle time at this STAGES."
  echo
  echo "- **SRAM bits**: memories yosys infers (\`memory -nomap\`: \`\$mem\` cells, e.g. ascache's data array),"
  echo "  SIZE x WIDTH, kept as macros: not in FFs or NAND2 eq. (\`synth\` runs up to \`fine\`, then its"
  echo "  \`fine\` script without \`memory_map\`; modules without memories come out as before)."
  echo
  echo "| module | format | rounding | cells | FFs | NAND2 eq. | depth | SRAM bits |"
  echo "|---|---|---|---:|---:|---:|---:|---:|"
  printf '%s\n' "${rows[@]}"
  echo
  echo "Weights (NAND2 equivalents):"
  echo
  echo "| yosys cell | NanGate45 cell | weight |"
  echo "|---|---|---:|"
  echo "| \$_NOT_ | INV_X1 (0.532 um^2) | 0.67 |"
  echo "| \$_BUF_ | BUF_X1 (0.798) | 1.00 |"
  echo "| \$_NAND_, \$_NOR_ | NAND2_X1, NOR2_X1 (0.798) | 1.00 |"
  echo "| \$_AND_, \$_OR_ | AND2_X1, OR2_X1 (1.064) | 1.33 |"
  echo "| \$_ANDNOT_, \$_ORNOT_ | as AND2/OR2 (no single NanGate cell) | 1.33 |"
  echo "| \$_AOI3_, \$_OAI3_ / \$_AOI4_, \$_OAI4_ | AOI21/OAI21 (1.064) / AOI22/OAI22 (1.330) | 1.33 / 1.67 |"
  echo "| \$_XOR_, \$_XNOR_ | XOR2_X1, XNOR2_X1 (1.596) | 2.00 |"
  echo "| \$_MUX_ | MUX2_X1 (1.862) | 2.33 |"
  echo "| \$_DFF_P_ | DFF_X1 (4.522) | 5.67 |"
  echo "| \$_DFF_PN0_ (async reset) | DFFR_X1 (5.320) | 6.67 |"
  echo "| ...E_ (enable) | + MUX2_X1 | + 2.33 |"
  echo "| \$_SDFF*_ (sync reset) | + AND2_X1 | + 1.33 |"
} > "$OUT"
echo "area: wrote $OUT"
