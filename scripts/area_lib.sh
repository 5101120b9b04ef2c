# shellcheck shell=bash disable=SC2016,SC2034
# (SC2016: the awk programs are single-quoted on purpose; SC2034: A_* and AREA_UNITS are read by
# the scripts that source this file.)
# scripts/area_lib.sh - the yosys area measurement shared by scripts/area.sh (every module of
# rtl/fp/ and rtl/units/) and scripts/area_rtu.sh (one RTU at the cycle model's defaults).
# Sourced, not run: it defines the unit list, the sources of a module, the cell weights and
# area_synth (one yosys run). The callers set `set -euo pipefail` and cd to the repository root.
#
# One run: read_verilog <sources>; chparam <parameters> <module>; synth [-noshare] -flatten -top
# <module> -run :fine; then synth's `fine` script without memory_map (memories stay $mem_v2
# cells: SRAM macros, counted in bits); stat; ltp -noff. RAYCORE_AREA_TIMEOUT (seconds, default
# 1200) bounds one run: a run that does not finish in time is reported as such, not as a number.

AREA_TIMEOUT=${RAYCORE_AREA_TIMEOUT:-1200}

# The units that get rows: rtl/units/<unit>.v synthesised with <unit> as the top. Every other
# rtl/units/*.v must be a helper that one of them instantiates (checked by area_check_units):
#   ascache_ram/_victim/_touch (ascache), rgu_ray/rgu_walk (rgu), spawn_ops (hit, spawn),
#   trv_pass (trv_unit: one traversal pass, no arithmetic of its own), rr_arb (membus_if).
# trv is the traversal datapath alone (STAGES 2, the pin-level twin's); trv_unit the whole
# traversal unit (slots, stacks, ready queue, PIPES passes, the ist result reduction).
AREA_UNITS=(ascache hit ist ist_watertight membus_if membus_l2 rgu spawn trv trv_unit vtu)
# The tops: rtu (one RTU whole: every unit above, slot_ram, vtu_unit and the wiring) is
# synthesised by scripts/area_rtu.sh at the cycle model's defaults; chip (RTUS rtu + membus_if) is
# only linted and elaborated (scripts/lint.sh): its area is RTUS x the RTU's + membus_if's.
AREA_TOPS=(rtu chip)

# The modules rtl/units/<name>.v instantiates ("<name> #(" at the start of a line).
area_children() {
  local g n
  for g in rtl/units/*.v; do
    n=$(basename "$g" .v)
    [ "$n" != "$1" ] && grep -Eq "^\s*$n\s+#" "rtl/units/$1.v" && echo "$n"
  done
  return 0
}

# The sources of a module: rtl/fp/*.v, plus for a unit rtl/units/<unit>.v and the rtl/units files
# it instantiates, transitively (trv_unit: trv_pass.v, trv.v; hit: spawn_ops.v). Only those, so an
# unfinished file of another unit cannot break this one.
srcs_for() {
  local f=(rtl/fp/*.v) queue=() n c
  [ -f "rtl/units/$1.v" ] && queue=("$1")
  local seen=" "
  while [ ${#queue[@]} -gt 0 ]; do
    n=${queue[0]}
    queue=("${queue[@]:1}")
    [[ "$seen" == *" $n "* ]] && continue
    seen+="$n "
    f+=("rtl/units/$n.v")
    for c in $(area_children "$n"); do queue+=("$c"); done
  done
  echo "${f[@]}"
}

file_of() { if [ -f "rtl/fp/$1.v" ]; then echo "rtl/fp/$1.v"; else echo "rtl/units/$1.v"; fi; }

# Fails if a file of rtl/units/ is neither a unit nor reached from one (a new unit must be added
# to AREA_UNITS, so that it is not silently left out).
area_check_units() {
  local reached=" " u s g
  for u in "${AREA_UNITS[@]}" "${AREA_TOPS[@]}"; do
    [ -f "rtl/units/$u.v" ] || { echo "area: AREA_UNITS names $u, there is no rtl/units/$u.v" >&2; return 1; }
    for s in $(srcs_for "$u"); do reached+="$s "; done
  done
  for g in rtl/units/*.v; do
    [[ "$reached" == *" $g "* ]] ||
      { echo "area: $g is neither in AREA_UNITS / AREA_TOPS (scripts/area_lib.sh) nor instantiated by one" >&2; return 1; }
  done
}

# Cell weights in NAND2 equivalents (NanGate45 X1 cell area / NAND2_X1 area 0.798 um^2).
# Flip-flops: DFF_X1 5.67, DFFR_X1 (async reset) 6.67, plus MUX2_X1 2.33 for an enable and
# AND2_X1 1.33 for a synchronous reset/set. Prints "cells ffs nand2_eq" ($mem_v2 cells are in
# cells, not in the other two).
WEIGHT_FUNCS='
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
'
WEIGHTS_AWK="$WEIGHT_FUNCS"'
/=== design hierarchy ===/ { cells = 0; ffs = 0; ge = 0; bad = 0 }  # a hierarchy: its totals only
$1 == "Number" && $3 == "cells:" { cells = $4 }
$1 ~ /^\$_/ && NF == 2 {
  t = $1; n = $2
  if (t ~ /DFF/) { ffs += n; ge += n * ff_weight(t) }
  else if (t in g) ge += n * g[t]
  else { print "area: unknown cell type " t > "/dev/stderr"; bad = 1 }
}
END { if (bad) exit 1; printf "%d %d %.0f\n", cells, ffs, ge }
'

# The cells, flip-flops and NAND2 eq. of one instance's subtree in a hierarchical `stat` (area_synth
# ... hier): every module's own cells from its section, its instances of other modules weighted by
# their counts, summed recursively from the module named -v top=<module> (a derived module
# "$paramod$<hash>\<module>" too; the first match). Prints "cells ffs nand2_eq" ($mem_v2 cells in
# cells only). With -v children=1: the module's own cells and each of its instances' subtrees.
SUBTREE_AWK="$WEIGHT_FUNCS"'
/^=== design hierarchy ===/ { done = 1 }
done { next }
/^=== .* ===$/ { mod = $2; mods[mod] = 1; next }
mod != "" && NF == 2 && $2 ~ /^[0-9]+$/ {
  t = $1; n = $2
  if (t ~ /^\$_/ && t ~ /DFF/) { c[mod] += n; f[mod] += n; w[mod] += n * ff_weight(t) }
  else if (t in g) { c[mod] += n; w[mod] += n * g[t] }
  else if (t == "$mem_v2") c[mod] += n
  else { k = ++nk[mod]; sub_t[mod, k] = t; sub_n[mod, k] = n }
}
function total(m,   k, s) {
  if (m in seen) return
  seen[m] = 1
  tc[m] = c[m]; tf[m] = f[m]; tw[m] = w[m]
  for (k = 1; k <= nk[m]; k++) {
    s = sub_t[m, k]
    if (!(s in mods)) { print "area: unknown cell type " s > "/dev/stderr"; bad = 1; continue }
    total(s)
    tc[m] += sub_n[m, k] * tc[s]; tf[m] += sub_n[m, k] * tf[s]; tw[m] += sub_n[m, k] * tw[s]
  }
}
END {
  for (m in mods) { b = m; sub(/.*\\/, "", b); if (b == top) { root = m; break } }
  if (root == "") { print "area: no module " top > "/dev/stderr"; exit 1 }
  total(root)
  if (bad) exit 1
  if (!children) { printf "%d %d %.0f\n", tc[root], tf[root], tw[root]; exit 0 }
  # -v children=1: the root own cells ("glue"), then each instance type below it, one line each:
  # "name instances cells ffs nand2_eq" (the totals over its instances).
  printf "glue 1 %d %d %.0f\n", c[root], f[root], w[root]
  for (k = 1; k <= nk[root]; k++) {
    s = sub_t[root, k]; b = s; sub(/.*\\/, "", b)
    printf "%s %d %d %d %.0f\n", b, sub_n[root, k], sub_n[root, k] * tc[s], sub_n[root, k] * tf[s], sub_n[root, k] * tw[s]
  }
}
'

# Memories (the $mem_v2 cells of `memory -nomap`, from `dump`): SRAM macros, not in cells' FFs or
# NAND2 eq. Prints "bits ported_bits": bits = SIZE x WIDTH summed; ported_bits weights each memory
# by 1 + (p - 1) / 2 for its p = RD_PORTS + WR_PORTS ports (the single-port bits a p-port array
# costs, the rule of the throughput study, sim/sweep/throughput.cpp).
MEM_AWK='
/^ *cell /             { w = s = r = x = 0 }
/parameter .WIDTH /    { w = $3 }
/parameter .SIZE /     { s = $3 }
/parameter .RD_PORTS / { r = $3 }
/parameter .WR_PORTS / { x = $3 }
/^ *end/ { if (w && s) { p = r + x; if (p < 1) p = 1; bits += w * s; ported += w * s * (1 + (p - 1) / 2) }
           w = s = r = x = 0 }
END { printf "%d %.0f\n", bits, ported }
'
# The memories one per line: "name SIZE x WIDTH, R read + W write ports".
MEM_LIST_AWK='
/^ *cell /             { w = s = r = x = 0; id = "" }
/parameter .MEMID /    { id = $3; gsub(/[\\"]/, "", id) }
/parameter .WIDTH /    { w = $3 }
/parameter .SIZE /     { s = $3 }
/parameter .RD_PORTS / { r = $3 }
/parameter .WR_PORTS / { x = $3 }
/^ *end/ { if (w && s) printf "%s %d x %d, %d read + %d write ports\n", id, s, w, r, x; w = s = 0 }
'

# area_synth NAME MODULE SHARE CHPARAM [hier]: one yosys run of MODULE (SHARE: share or noshare;
# CHPARAM: "-set P V ..." or empty) with its logs under $AREA_TMP/NAME.*; with hier the hierarchy
# is kept (each module synthesised once per parameter set, `stat` of the design hierarchy: the
# instances' cells summed; no depth: A_DEPTH 0). Sets A_STATUS (ok or
# timeout), A_SECS (wall seconds of the yosys run), and when ok A_CELLS A_FFS A_GE A_DEPTH A_SRAM
# A_SRAM_PORTED, A_MEMS (the memories, MEM_LIST_AWK's lines) and with hier A_PARTS (SUBTREE_AWK's
# children lines: the top's own cells and each instance type's subtree). Exits on a yosys error.
# Results are cached in $RAYCORE_AREA_CACHE (default out/area-cache) by a hash of the yosys
# version, the script and the sources (A_SECS is then the recorded time of the run that made
# them); RAYCORE_AREA_CACHE=none turns the cache off. Timeouts are not cached.
area_synth() {
  local name=$1 mod=$2 share=$3 chp=$4 hier=${5:-} log="$AREA_TMP/$1" t0 rc=0 noshare="" script
  local srcs key cache=${RAYCORE_AREA_CACHE:-out/area-cache} w m flatten=-flatten stat="stat"
  local ltp="tee -q -o $log.ltp ltp -noff"
  [ "$share" = noshare ] && noshare="-noshare"
  # With the hierarchy kept, ltp sees each instance as a cell from every input to every output and
  # reports millions of false loops: no depth (the units' own rows have theirs).
  [ "$hier" = hier ] && { flatten=""; stat="stat -top $mod"; ltp="tee -q -o $log.ltp log no depth"; }
  srcs=$(srcs_for "$mod")
  script="read_verilog $srcs; \
    ${chp:+chparam $chp $mod;} \
    synth $noshare $flatten -top $mod -run :fine; tee -q -o $log.mem dump t:\$mem_v2; \
    opt -fast -full; opt -full; techmap; opt -fast; abc -fast; opt -fast; hierarchy -check; check; \
    tee -q -o $log.stat $stat; $ltp"
  # shellcheck disable=SC2086  # srcs: a list of file names without spaces
  key=$({ yosys -V; echo "${script//"$log"/LOG}"; cat $srcs; } | sha256sum | cut -c1-16)
  if [ "$cache" != none ] && [ -s "$cache/$key.res" ]; then
    read -r A_CELLS A_FFS A_GE A_DEPTH A_SRAM A_SRAM_PORTED A_SECS < "$cache/$key.res"
    A_MEMS=$(cat "$cache/$key.mems")
    A_PARTS=$(cat "$cache/$key.parts" 2>/dev/null || true)
    A_STATUS=ok
    echo "area: $name: cached ($cache/$key.res)" >&2
    return 0
  fi
  t0=$(date +%s)
  timeout "$AREA_TIMEOUT" yosys -q -l "$log.log" -p "$script" >/dev/null || rc=$?
  A_SECS=$(( $(date +%s) - t0 ))
  if [ $rc -eq 124 ]; then
    A_STATUS=timeout
    return 0
  fi
  [ $rc -eq 0 ] || { echo "area: yosys failed for $name ($mod $chp), see:" >&2; tail -20 "$log.log" >&2; exit 1; }
  A_STATUS=ok
  w=$(awk "$WEIGHTS_AWK" "$log.stat") || exit 1
  m=$(awk "$MEM_AWK" "$log.mem") || exit 1
  read -r A_CELLS A_FFS A_GE <<< "$w"
  read -r A_SRAM A_SRAM_PORTED <<< "$m"
  A_DEPTH=$(sed -n 's/.*length=\([0-9]*\).*/\1/p' "$log.ltp" | sort -n | tail -1)
  A_DEPTH=${A_DEPTH:-0}  # 0: not measured (hier)
  A_MEMS=$(awk "$MEM_LIST_AWK" "$log.mem")
  A_PARTS=""
  if [ "$hier" = hier ]; then A_PARTS=$(awk -v top="$mod" -v children=1 "$SUBTREE_AWK" "$log.stat") || exit 1; fi
  if [ "$cache" != none ]; then
    mkdir -p "$cache"
    printf '%s\n' "$A_MEMS" > "$cache/$key.mems"
    [ -n "$A_PARTS" ] && printf '%s\n' "$A_PARTS" > "$cache/$key.parts"
    echo "$A_CELLS $A_FFS $A_GE $A_DEPTH $A_SRAM $A_SRAM_PORTED $A_SECS" > "$cache/$key.res.tmp"
    mv "$cache/$key.res.tmp" "$cache/$key.res"
  fi
}

# The cell weights as a markdown table (both documents' sections use them).
area_weights_table() {
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
}
