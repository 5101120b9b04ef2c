#!/usr/bin/env bash
# make lint: every Verilog module under rtl/ through
#   1. `verilator --lint-only -Wall` (top = the module) for the FP24 and FP32 parameter sets, the
#      rounding modes (RNE 0/1; RAYCORE 1 for FP24) and STAGES 0, 1, 2, 4 (parameters a module does
#      not declare are skipped);
#      zero warnings allowed, waivers only in rtl/lint/waivers.vlt;
#   2. a yosys synthesis (`synth -flatten -top <module>`, FP24 and FP32) that must infer no latch
#      ($dlatch/$_DLATCH_* cells or "Latch inferred" in the log) and pass `check -assert`. The
#      biggest units (ELABORATE_ONLY below: whole pipelines of FP operators in one combinational
#      cycle, whose synthesis runs for hours in yosys' SAT-based sharing) are elaborated instead:
#      `hierarchy; proc; flatten; opt_clean`, where latches are inferred (proc_dlatch), then the
#      same latch and `check -assert` tests; `make area` synthesises what it reports. The tops
#      (HIERARCHY_ONLY: rtu, chip) are elaborated with their hierarchy kept (`hierarchy; proc;
#      opt_clean`): every module is checked on its own, as when linted alone; flattened, the trv's
#      cache accesses chained through the caches' ports (rtl/lint/waivers.vlt) are loops between
#      whole vectors, not between bits, which `check` cannot tell apart at that level.
# Exits non-zero on any problem. One dialect everywhere: Verilog-2005 (verilator
# --default-language 1364-2005, yosys read_verilog without -sv, iverilog -g2005).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v verilator >/dev/null && command -v yosys >/dev/null ||
  { echo "lint: verilator and yosys are needed (make deps)" >&2; exit 1; }

mapfile -t SRCS < <(find rtl -name '*.v' | sort)
[ ${#SRCS[@]} -gt 0 ] || { echo "lint: no Verilog files under rtl/" >&2; exit 1; }
WAIVERS=rtl/lint/waivers.vlt
ELABORATE_ONLY=" trv_pass trv_unit hit ist_unit hit_unit "
HIERARCHY_ONLY=" rtu chip "
LOG=$(mktemp -d "${TMPDIR:-/tmp}/raycore-lint.XXXXXX")
trap 'rm -rf "$LOG"' EXIT

# Parameter sets: name -> "PARAM=value ..." (only the parameters a module declares are used).
declare -A FMT=([FP24]="EXP_BITS=7 MAN_BITS=16 WIDTH=24" [FP32]="EXP_BITS=8 MAN_BITS=23 WIDTH=32")

has_param() { grep -Eq "parameter +(integer +)?$2\b" "$1"; }
# Prints the -G flags (verilator) or "-set P V" pairs (yosys chparam) a module accepts.
params_for() {  # file style assignments...
  local file=$1 style=$2; shift 2
  local out=() kv
  for kv in "$@"; do
    if has_param "$file" "${kv%%=*}"; then
      if [ "$style" = G ]; then out+=("-G$kv"); else out+=("-set" "${kv%%=*}" "${kv#*=}"); fi
    fi
  done
  echo "${out[@]}"
}

# Arguments: module names to check (default: every module); the others are still read as sources.
ONLY=" $* "
fail=0 runs=0 checked=0
for src in "${SRCS[@]}"; do
  top=$(basename "$src" .v)
  [ $# -gt 0 ] && [[ "$ONLY" != *" $top "* ]] && continue
  checked=$((checked + 1))
  grep -Eq "^\s*module\s+$top\b" "$src" || { echo "lint: $src does not define module $top" >&2; fail=1; continue; }
  # ---- verilator -Wall ----
  # A file whose header says "lint: FP24 only" (fp_rcp: rounding mode raycore is FP24's) is
  # checked for FP24 alone.
  fmts="FP24 FP32"
  grep -q "^// lint: FP24 only" "$src" && fmts=FP24
  declare -A seen=()
  for fmt in $fmts; do
    # RAYCORE = 1 (rounding mode raycore, FP24 only) overrides RNE: with RNE = 0 only.
    for mode in "RNE=0 RAYCORE=0" "RNE=1 RAYCORE=0" "RNE=0 RAYCORE=1"; do
      [ "$fmt" = FP32 ] && [ "$mode" = "RNE=0 RAYCORE=1" ] && continue
      for st in 0 1 2 4; do
        g=$(params_for "$src" G ${FMT[$fmt]} $mode STAGES=$st)
        [ -n "${seen["x$g"]:-}" ] && continue  # same parameters as an earlier run
        seen["x$g"]=1
        runs=$((runs + 1))
        if ! verilator --lint-only -Wall --default-language 1364-2005 --top-module "$top" \
             $g "$WAIVERS" "${SRCS[@]}" >"$LOG/v.txt" 2>&1; then
          echo "lint: FAIL verilator $top $g" >&2; cat "$LOG/v.txt" >&2; fail=1
        fi
      done
    done
  done
  unset seen
  # Further parameter sets a module names in its header ("// lint: also P=V ..."), e.g. ascache's
  # frame form (HIT_LATENCY 0, several ports, sets not a power of two): verilator -Wall each.
  while read -r extra; do
    [ -n "$extra" ] || continue
    g=$(params_for "$src" G $extra)
    runs=$((runs + 1))
    if ! verilator --lint-only -Wall --default-language 1364-2005 --top-module "$top" \
         $g "$WAIVERS" "${SRCS[@]}" >"$LOG/v.txt" 2>&1; then
      echo "lint: FAIL verilator $top $g" >&2; cat "$LOG/v.txt" >&2; fail=1
    fi
  done < <(sed -n 's|^// lint: also ||p' "$src")
  # ---- yosys synthesis: no latches ----
  for fmt in $fmts; do
    set_args=$(params_for "$src" set ${FMT[$fmt]})
    chparam=""
    [ -n "$set_args" ] && chparam="chparam $set_args $top;"
    flow="synth -flatten -top $top"
    [[ "$ELABORATE_ONLY" == *" $top "* ]] && flow="hierarchy -top $top; proc; flatten; opt_clean"
    [[ "$HIERARCHY_ONLY" == *" $top "* ]] && flow="hierarchy -top $top; proc; opt_clean"
    if ! yosys -q -l "$LOG/y.txt" -p "read_verilog ${SRCS[*]}; $chparam $flow; \
         select -assert-none t:\$dlatch t:\$adlatch t:\$dlatchsr t:\$_DLATCH_* t:\$_DLATCHSR_* t:\$_SR_*; \
         check -assert" >/dev/null 2>&1; then
      echo "lint: FAIL yosys $top $fmt ($set_args)" >&2; grep -iE "error|latch|warning" "$LOG/y.txt" >&2 || true; fail=1
    elif grep -q "^Latch inferred" "$LOG/y.txt"; then
      echo "lint: FAIL yosys $top $fmt: latch inferred" >&2; grep "^Latch inferred" "$LOG/y.txt" >&2; fail=1
    fi
    runs=$((runs + 1))
  done
  echo "lint: $top ok"
done
if [ $fail -ne 0 ]; then echo "lint: FAILED" >&2; exit 1; fi
echo "lint: $checked of ${#SRCS[@]} modules checked, all clean ($runs verilator -Wall and yosys runs, 0 warnings, no latches)"
