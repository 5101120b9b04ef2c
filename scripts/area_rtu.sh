#!/usr/bin/env bash
# scripts/area_rtu.sh [FILE]: the section "One RTU at the cycle model's defaults" of docs/area.md
# (or FILE): every unit of one RTU synthesised alone with yosys at the parameters of the cycle
# model's defaults (systemc/config.h SimConfig), FP24, STAGES 2, summed over the RTU's instances;
# the VTU's share of the sum. Replaces the section (from its heading to the end of FILE) or
# appends it. Called by scripts/area.sh (`make area`), alone by `make area-rtu`.
#
# Then rtl/units/rtu.v synthesised whole (its parameter defaults are the cycle model's defaults):
# the RTU's cells, flip-flops, NAND2 eq. and SRAM bits as one design, and the VTU's share of it
# (vtu.v, and the fill path vtu_unit.v with its line buffers, each synthesised alone, over rtu.v).
# Same measurement as scripts/area.sh (scripts/area_lib.sh: NAND2 weights, memories kept as $mem
# SRAM macros, ltp depth), with `synth -noshare` for every unit. RAYCORE_AREA_RTU_MODES (default
# "rtz rne") the FP24 rounding modes; RAYCORE_AREA_TIMEOUT (s, default 1200) per yosys run of a
# unit, RAYCORE_AREA_WHOLE_TIMEOUT (s, default 7200) for rtu.v whole.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v yosys >/dev/null || { echo "area_rtu: yosys is needed (make deps)" >&2; exit 1; }
# shellcheck source=scripts/area_lib.sh
. scripts/area_lib.sh

OUT=${1:-docs/area.md}
read -r -a MODES <<< "${RAYCORE_AREA_RTU_MODES:-rtz rne}"
AREA_TMP=$(mktemp -d "${TMPDIR:-/tmp}/raycore-area-rtu.XXXXXX")
trap 'rm -rf "$AREA_TMP"' EXIT
HEADING="## One RTU at the cycle model's defaults"
SRAM_BIT_NAND2=0.5  # NAND2 eq. per single-port SRAM bit (as sim/sweep/throughput.cpp)

# The RTU's units: "name|module|instances|format (fmt: EXP_BITS/MAN_BITS/RNE set) or -|parameters".
# The parameters (systemc/config.h defaults): vtu_depth 4, ist_latency 20, hit_latency 48,
# rgu_latency 30 = STAGES 2; 96 rays in flight -> 2^7 = 128 slots; stack_depth 64; trv_pipes 5;
# ist_units 4; list lines of 64 B = 16 words; caches node 32 KB, list 8 KB, tri 32 KB, 4 ways,
# 64 B lines (FP24: two 32-byte triangle records), 8 MSHRs, answering in the access's cycle
# (HIT_LATENCY 0) on 1 port per trv pipe (node: access A; list: a pass reads the list once) or 1
# per ist unit (tri): rtu.v's.
CACHE_P="-set WAYS 4 -set LINE_BYTES 64 -set MSHRS 8 -set HIT_LATENCY 0 -set LINE_W 26 -set TAG_BITS 7"
UNITS=(
  "vtu|vtu|1|fmt|-set STAGES 2 -set TAG_BITS 8"
  "ist|ist|4|fmt|-set STAGES 2 -set TAG_BITS 1 -set FREE 1"
  "trv_unit|trv_unit|1|fmt|-set SLOT_BITS 7 -set DEPTH 64 -set PIPES 5 -set IST 4 -set WORDS 16"
  "hit|hit|1|fmt|-set STAGES 2 -set TAG_BITS 9 -set FREE 1 -set SPAWNS 1"
  "rgu|rgu|1|fmt|-set STAGES 2"
  "ascache node|ascache|1|-|-set SETS 128 -set PORTS 5 $CACHE_P"
  "ascache list|ascache|1|-|-set SETS 32 -set PORTS 5 $CACHE_P"
  "ascache tri|ascache|1|-|-set SETS 128 -set PORTS 4 $CACHE_P"
)
# Shared by the chip, not in the RTU's sum: the bus interface of 6 RTUs x 3 caches.
CHIP="membus_if|membus_if|chip|-|-set N 18 -set DEPTH 32 -set BEAT_BYTES 16"

# "-set A 1 -set B 2" -> "A 1, B 2" (the table's parameter column; the format's are in the heading)
show_params() { sed -e 's/^-set //' -e 's/ -set /, /g' <<< "$1"; }
slug() { tr ' ' '_' <<< "$1"; }

declare -A R  # results by "name|mode|field"
# run_unit SPEC MODE: synthesise (or reuse the format-less unit's first result) into R.
run_unit() {
  local name mod inst fmt par chp key mode=$2
  IFS='|' read -r name mod inst fmt par <<< "$1"
  key="$name|$mode"
  if [ "$fmt" = - ] && [ -n "${R[$name|${MODES[0]}|status]:-}" ]; then
    local f
    for f in status secs cells ffs ge depth sram ported mems parts; do R[$key|$f]=${R[$name|${MODES[0]}|$f]:-}; done
    return 0
  fi
  chp=$par
  if [ "$fmt" = fmt ]; then
    chp="-set EXP_BITS 7 -set MAN_BITS 16 -set RNE $([ "$mode" = rne ] && echo 1 || echo 0) $par"
  fi
  # rtu.v keeps its hierarchy (each unit synthesised once per parameter set, the instances
  # summed): flattened, yosys' optimisation of the whole RTU runs for hours.
  area_synth "$(slug "$name")-$mode" "$mod" noshare "$chp" "$([ "$mod" = rtu ] && echo hier)"
  R[$key|status]=$A_STATUS
  R[$key|secs]=$A_SECS
  if [ "$A_STATUS" = ok ]; then
    R[$key|cells]=$A_CELLS R[$key|ffs]=$A_FFS R[$key|ge]=$A_GE R[$key|depth]=$A_DEPTH
    R[$key|sram]=$A_SRAM R[$key|ported]=$A_SRAM_PORTED R[$key|mems]=$A_MEMS R[$key|parts]=${A_PARTS:-}
    echo "area_rtu: $name FP24 $mode: cells=$A_CELLS ffs=$A_FFS nand2_eq=$A_GE depth=$A_DEPTH" \
         "sram_bits=$A_SRAM (ported $A_SRAM_PORTED) ${A_SECS}s"
  else
    echo "area_rtu: $name FP24 $mode: did not finish in ${AREA_TIMEOUT}s" >&2
  fi
}

# The whole RTU and its fill path (rtu.v's defaults: the cycle model's; vtu_unit at the RTU's).
# rtu.v's default SPAWNS 1 builds the hit unit for the defaults' --spawn none alone; "all seven
# spawns" builds every strategy (SPAWNS 127, as `--rtl rtu`'s Verilated model is built).
WHOLE=(
  "rtu whole|rtu|1|fmt|"
  "rtu whole, all seven spawns|rtu|1|fmt|-set SPAWNS 127"
  "vtu_unit|vtu_unit|1|fmt|-set STAGES 2 -set MSHRS 8"
)
WHOLE_TIMEOUT=${RAYCORE_AREA_WHOLE_TIMEOUT:-7200}

for mode in "${MODES[@]}"; do
  for u in "${UNITS[@]}" "$CHIP"; do run_unit "$u" "$mode"; done
  unit_timeout=$AREA_TIMEOUT
  AREA_TIMEOUT=$WHOLE_TIMEOUT
  for u in "${WHOLE[@]}"; do run_unit "$u" "$mode"; done
  AREA_TIMEOUT=$unit_timeout
done

# One row: name instances params key.
row() {
  local name=$1 inst=$2 par=$3 k=$4
  if [ "${R[$k|status]}" != ok ]; then
    echo "| $name | $inst | $par | did not finish in $((AREA_TIMEOUT / 60)) min | | | | | | ${R[$k|secs]} |"
    return
  fi
  awk -v n="$name" -v i="$inst" -v p="$par" -v c="${R[$k|cells]}" -v f="${R[$k|ffs]}" \
      -v g="${R[$k|ge]}" -v d="${R[$k|depth]}" -v s="${R[$k|sram]}" -v sp="${R[$k|ported]}" \
      -v b="$SRAM_BIT_NAND2" -v t="${R[$k|secs]}" \
      'BEGIN { printf "| %s | %s | %s | %d | %d | %d | %d | %d | %.0f | %d |\n", n, i, p, c, f, g, d, s, sp * b, t }'
}

section() {
  local mode name mod inst fmt par k u
  echo "$HEADING"
  echo
  echo "Generated by \`make area\` / \`make area-rtu\` (\`./scripts/area_rtu.sh\`) with $(yosys -V | head -1)"
  echo "on $(date -u +%Y-%m-%d). Do not edit by hand."
  echo
  echo "Every unit of one RTU synthesised alone at the parameters of the cycle model's defaults"
  echo "(\`systemc/config.h\` SimConfig), FP24 (EXP_BITS 7, MAN_BITS 16), STAGES 2 for the pipelined"
  echo "datapaths (vtu_depth 4 = 2 x 2: the fp_sops' four phases, ist_latency 20 = 10 x 2, hit_latency 48 = 24 x 2,"
  echo "rgu_latency 30 = 15 x 2), then summed over the RTU's instances. Same measurement as the table above"
  echo "(NAND2 weights, \`ltp\` depth, memories kept as \`\$mem\` SRAM macros), but with \`synth -noshare\`."
  echo
  echo "- **The table sums separately synthesised units**; the RTU synthesised whole (rtl/units/rtu.v,"
  echo "  with the glue between the units: slot_ram, vtu_unit, the trv's slot read ports, the cache"
  echo "  responses' alignment) follows below the tables. Not counted anywhere: the L2 shared by the"
  echo "  RTUs (512 KB by default: membus_l2.v, not synthesised here) and the chip's membus_if (its row: once per chip)."
  echo "- Parameters: vtu TAG_BITS 8 (cache port 2 + MSHR 3 + record in the line 3 bits); ist as in"
  echo "  ist_unit (TAG_BITS 1: the side data travel beside it in one fp_delay memory; FREE 1: its"
  echo "  carries in fp_delay memories, ist_unit never holding a result back), hit as in hit_unit"
  echo "  (TAG_BITS 9 = slot 7 + 2, FREE 1, SPAWNS 1: the defaults' spawn none alone, as rtu.v's default); trv_unit 2^7 = 128 slots (the model's 96 ray"
  echo "  slots rounded up: the RTL has 2^SLOT_BITS), 64 stack entries, 5 pipes, IST 4 results per cycle"
  echo "  (ist_units), 16 list words per read; caches 4 ways, 64 B lines, 8 MSHRs, HIT_LATENCY 0"
  echo "  (the frame's caches answer in the access's cycle: asynchronous data-array read ports), PORTS"
  echo "  5 for node (access A of each trv pipe's node pass), 5 for list (access A of a list pass or B"
  echo "  of a node pass: one list read per pass) and 4 for tri (1 per ist unit), line index"
  echo "  LINE_W 26, requester tag 7 bits, 32-bit counters; rgu at its defaults (16-bit coordinates,"
  echo "  8 x 8 tiles, up to 255 RTUs)."
  echo "- **SRAM bits**: the \`\$mem\` cells yosys keeps (SIZE x WIDTH). **SRAM NAND2 eq.**: $SRAM_BIT_NAND2"
  echo "  NAND2 eq. per single-port bit (about 0.4 um^2 in 45 nm: a 6T bit cell of 0.25-0.35 um^2 plus"
  echo "  periphery; the assumption of the throughput study in docs/results.md), a p-port array"
  echo "  weighted by 1 + (p - 1) / 2 single-port bits per bit, p = its read + write ports as yosys"
  echo "  leaves them (the same rule as sim/sweep/throughput.cpp). Arrays of many ports (the trv_unit's"
  echo "  slot arrays, the caches' data with 4 or 5 read ports) are register files in practice and cost more"
  echo "  per bit than this linear rule says; the single-port figure is a lower bound."
  echo "- **depth** (\`ltp -noff\`, cells): trv_unit's is a traversal pass in one cycle (the cycle"
  echo "  model's one-cycle pass, not a pipeline; an inner node's split is a cycle later, from registers);"
  echo "  the total's is the largest. The caches' includes the accesses of a cycle in port order (their"
  echo "  MSHR allocations a prefix over the ports)."
  echo "- **yosys s**: wall seconds of the run (one run at a time on a 2-core machine shared with other"
  echo "  work; recorded when it ran, results are cached in out/area-cache)."
  echo
  for mode in "${MODES[@]}"; do
    echo "### FP24 $mode"
    echo
    echo "| unit | instances | parameters | cells | FFs | NAND2 eq. | depth | SRAM bits | SRAM NAND2 eq. | yosys s |"
    echo "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|"
    local tc=0 tf=0 tg=0 td=0 ts=0 tp=0 tt=0 missing="" vge=0
    for u in "${UNITS[@]}"; do
      IFS='|' read -r name mod inst fmt par <<< "$u"
      k="$name|$mode"
      row "$name" "$inst" "$(show_params "$par")" "$k"
      tt=$((tt + ${R[$k|secs]}))
      if [ "${R[$k|status]}" != ok ]; then missing+=" $name"; continue; fi
      tc=$((tc + inst * ${R[$k|cells]})) tf=$((tf + inst * ${R[$k|ffs]})) tg=$((tg + inst * ${R[$k|ge]}))
      ts=$((ts + inst * ${R[$k|sram]})) tp=$((tp + inst * ${R[$k|ported]}))
      [ "${R[$k|depth]}" -gt "$td" ] && td=${R[$k|depth]}
      [ "$name" = vtu ] && vge=${R[$k|ge]}
    done
    local total="**RTU total** (sum over instances)"
    [ -n "$missing" ] && total="**RTU total without${missing}** (did not finish: not counted)"
    awk -v n="$total" -v c="$tc" -v f="$tf" -v g="$tg" -v d="$td" -v s="$ts" -v sp="$tp" \
        -v b="$SRAM_BIT_NAND2" -v t="$tt" \
        'BEGIN { printf "| %s | | | **%d** | **%d** | **%d** | %d | **%d** | **%.0f** | %d |\n", n, c, f, g, d, s, sp * b, t }'
    IFS='|' read -r name mod inst fmt par <<< "$CHIP"
    row "$name (chip, not in the total)" "1 per chip" "$(show_params "$par")" "$name|$mode"
    echo
    if [ "$vge" -gt 0 ] && [ "$tg" -gt 0 ]; then
      awk -v v="$vge" -v g="$tg" -v s="$ts" -v sp="$tp" -v b="$SRAM_BIT_NAND2" -v miss="$missing" \
          -v mode="$mode" 'BEGIN {
        printf "**The VTU share of the RTU (FP24 %s)%s:** %.1f%% of the logic (%d of %d NAND2 eq.); ", \
          mode, (miss != "" ? ", an upper bound (without" miss ")" : ""), 100 * v / g, v, g
        printf "%.1f%% of logic + SRAM (%.2f M NAND2 eq., SRAM port-weighted), %.1f%% with every SRAM bit ", \
          100 * v / (g + sp * b), (g + sp * b) / 1e6, 100 * v / (g + s * b)
        printf "single-port (%.2f M NAND2 eq.). In 45 nm at 0.798 um^2 per NAND2 eq. (no placement overhead): ", \
          (g + s * b) / 1e6
        printf "logic %.2f mm^2, logic + SRAM %.2f mm^2 per RTU, the VTU %.3f mm^2.\n", \
          g * 0.798e-6, (g + sp * b) * 0.798e-6, v * 0.798e-6 }'
      echo
    fi
  done
  whole_section
  echo "Memories kept as SRAM (\`\$mem\` cells; per instance, SIZE x WIDTH, ports as yosys leaves them):"
  echo
  for u in "${UNITS[@]}" "$CHIP" "${WHOLE[@]}"; do
    IFS='|' read -r name mod inst fmt par <<< "$u"
    k="$name|${MODES[0]}"
    [ "${R[$k|status]}" = ok ] || continue
    if [ -z "${R[$k|mems]}" ]; then echo "- $name: none"; continue; fi
    echo "- $name: $(paste -sd';' <<< "${R[$k|mems]}" | sed 's/;/; /g')"
  done
}

# The RTU synthesised whole: rtu.v against the sum of its parts, and the VTU's share of it.
whole_section() {
  local mode k v f
  echo "### rtu.v synthesised whole"
  echo
  echo "\`rtl/units/rtu.v\` (one RTU: rgu_unit, trv_unit with its slot read ports, 4 x ist in ist_unit, hit_unit,"
  echo "the three ascaches, slot_ram, vtu_unit with vtu.v, and the wiring: the trv's cache responses"
  echo "aligned to the byte read, the hand-offs) synthesised as one design at its parameter defaults ="
  echo "the cycle model's (the parameters of the table above), its hierarchy kept: every module once"
  echo "per parameter set, \`stat -top rtu\` summing the instances (flattened, yosys' optimisation of"
  echo "the whole RTU ran for more than 40 minutes without finishing on this machine). No depth: with"
  echo "the hierarchy kept, \`ltp\` takes every instance for a cell from each input to each output."
  echo "The VTU's rows are synthesised alone: **vtu.v** (the datapath) and **vtu_unit** (the fill path: the MSHR line buffers of the"
  echo "three caches, 24 lines, the record queue and vtu.v). Only vtu.v exists for the VTU's sake: without"
  echo "a VTU the fill path keeps its line buffers (a line is installed whole) and loses vtu.v and the"
  echo "record queue; so vtu.v's share is the VTU's cost and vtu_unit's an upper bound of it."
  echo "**rtu whole** has rtu.v's default \`SPAWNS 1\`: the hit unit built for the defaults' \`--spawn none\`"
  echo "alone (hit.v leaves out the other strategies' operators and carries). **rtu whole, all seven"
  echo "spawns**: the same with \`SPAWNS 127\`, every spawn strategy built, as \`--rtl rtu\`'s one Verilated"
  echo "model is (so that it runs every \`--spawn\`)."
  echo
  for mode in "${MODES[@]}"; do
    echo "#### FP24 $mode"
    echo
    echo "| design | cells | FFs | NAND2 eq. | depth | SRAM bits | SRAM NAND2 eq. | yosys s |"
    echo "|---|---:|---:|---:|---:|---:|---:|---:|"
    for v in "rtu whole" "rtu whole, all seven spawns" vtu_unit vtu; do
      k="$v|$mode"
      if [ "${R[$k|status]:-}" != ok ]; then
        echo "| $v | did not finish in $((WHOLE_TIMEOUT / 60)) min | | | | | | ${R[$k|secs]:-} |"
        continue
      fi
      awk -v n="$v" -v c="${R[$k|cells]}" -v f="${R[$k|ffs]}" -v g="${R[$k|ge]}" -v d="${R[$k|depth]}" \
          -v s="${R[$k|sram]}" -v sp="${R[$k|ported]}" -v b="$SRAM_BIT_NAND2" -v t="${R[$k|secs]}" \
          'BEGIN { printf "| %s | %d | %d | %d | %s | %d | %.0f | %d |\n", n, c, f, g, (d > 0 ? d : "-"), s, sp * b, t }'
    done
    echo
    for v in "rtu whole" "rtu whole, all seven spawns"; do
      k="$v|$mode"
      [ -n "${R[$k|parts]:-}" ] || continue
      echo "$v by instance (each instance's subtree in the same synthesis; glue: rtu.v's own"
      echo "logic: the trv's cache responses aligned to the byte read, the hand-offs, the counter mux):"
      echo
      echo "| instance | cells | FFs | NAND2 eq. | share of the RTU's logic |"
      echo "|---|---:|---:|---:|---:|"
      awk -v tot="${R[$k|ge]}" '{ printf "| %s | %d | %d | %d | %.1f%% |\n", $1, $3, $4, $5, 100 * $5 / tot }' \
        <<< "${R[$k|parts]}" | sort -t'|' -k5,5nr
      echo
    done
    k="rtu whole|$mode"
    if [ "${R[$k|status]:-}" = ok ] && [ "${R[vtu|$mode|status]:-}" = ok ] &&
       [ "${R[vtu_unit|$mode|status]:-}" = ok ]; then
      awk -v r="${R[$k|ge]}" -v rs="${R[$k|ported]}" -v rs1="${R[$k|sram]}" -v v="${R[vtu|$mode|ge]}" \
          -v u="${R[vtu_unit|$mode|ge]}" -v us="${R[vtu_unit|$mode|ported]}" -v b="$SRAM_BIT_NAND2" \
          -v mode="$mode" 'BEGIN {
        printf "**The VTU share of the RTU (FP24 %s), measured on rtu.v whole:** vtu.v %.1f%% of the logic ", mode, 100 * v / r
        printf "(%d of %d NAND2 eq.), %.1f%% of logic + SRAM (%.2f M NAND2 eq., SRAM port-weighted), ", v, r, 100 * v / (r + rs * b), (r + rs * b) / 1e6
        printf "%.1f%% with every SRAM bit single-port; the whole fill path (vtu_unit, with the line buffers) ", 100 * v / (r + rs1 * b)
        printf "%.1f%% of the logic, %.1f%% of logic + SRAM. ", 100 * u / r, 100 * (u + us * b) / (r + rs * b)
        printf "In 45 nm at 0.798 um^2 per NAND2 eq.: the RTU %.2f mm^2 of logic, %.2f mm^2 with SRAM; vtu.v %.3f mm^2.\n", r * 0.798e-6, (r + rs * b) * 0.798e-6, v * 0.798e-6 }'
      echo
    fi
  done
}

section > "$AREA_TMP/section.md"
if [ -f "$OUT" ] && grep -qxF "$HEADING" "$OUT"; then
  # Keep what precedes the heading (and the blank line before it), replace the rest.
  awk -v h="$HEADING" '$0 == h { exit } { print }' "$OUT" > "$AREA_TMP/head.md"
  cat "$AREA_TMP/head.md" "$AREA_TMP/section.md" > "$OUT"
else
  { [ -f "$OUT" ] && cat "$OUT" && echo; cat "$AREA_TMP/section.md"; } > "$AREA_TMP/new.md"
  mv "$AREA_TMP/new.md" "$OUT"
fi
echo "area_rtu: wrote the section to $OUT"
