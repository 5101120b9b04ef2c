#!/usr/bin/env bash
# scripts/lint.sh [--quick|--full] [module...]: Verilog lint of rtl/, two matrices of the same
# checks (zero warnings, waivers only in rtl/lint/waivers.vlt, no latch):
#   full (default; `make lint`, about an hour): the matrix below;
#   quick (--quick or RAYCORE_LINT=quick; ctest Lint.quick in `make test`, a few minutes): each
#      module once at its own defaults (FP24) and, if it has EXP_BITS (and is not FP24 only),
#      once at FP32: verilator -Wall and the yosys step of each, with the modules whose synthesis
#      takes over ~10 s (QUICK_ELABORATE) elaborated instead, and rtu/chip elaborated at their
#      defaults only. No rounding-mode/STAGES sweep, no "lint: also" sets.
#   RAYCORE_LINT_JOBS=n: n modules at a time (default 2 in quick mode, 1 in full mode).
# Full mode: every Verilog module under rtl/ through
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

QUICK=0
case "${RAYCORE_LINT:-full}" in
  quick) QUICK=1 ;;
  full) ;;
  *) echo "lint: RAYCORE_LINT must be quick or full, not '$RAYCORE_LINT'" >&2; exit 2 ;;
esac
MODULES=()
for a in "$@"; do
  case "$a" in
    --quick) QUICK=1 ;;
    --full) QUICK=0 ;;
    -*) echo "usage: scripts/lint.sh [--quick|--full] [module...]" >&2; exit 2 ;;
    *) MODULES+=("$a") ;;
  esac
done

mapfile -t SRCS < <(find rtl -name '*.v' | sort)
[ ${#SRCS[@]} -gt 0 ] || { echo "lint: no Verilog files under rtl/" >&2; exit 1; }
WAIVERS=rtl/lint/waivers.vlt
ELABORATE_ONLY=" trv_pass trv_unit hit ist_unit hit_unit "
HIERARCHY_ONLY=" rtu chip "
# --quick: the modules whose synthesis takes more than about 10 s (ascache_ram at its default
# WIDTH = 512; the units with whole FP pipelines) are elaborated like ELABORATE_ONLY's.
QUICK_ELABORATE=" ascache_ram ist rgu rgu_ray rgu_unit spawn trv vtu vtu_unit "
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

# The two checks, the same in both modes; each adds to the module's run count ($runs) and sets
# $mfail on a problem. vlint <top> <-G flags>: verilator -Wall, zero warnings.
vlint() {
  local top=$1 g=$2
  runs=$((runs + 1))
  if ! verilator --lint-only -Wall --default-language 1364-2005 --top-module "$top" \
       $g "$WAIVERS" "${SRCS[@]}" >"$LOG/$top.v.txt" 2>&1; then
    echo "lint: FAIL verilator $top ${g:-(defaults)}"; cat "$LOG/$top.v.txt"; mfail=1
  fi
}
# ysys <top> <label> <chparam -set pairs> <flow>: no latch, `check -assert`.
ysys() {
  local top=$1 label=$2 set_args=$3 flow=$4 chparam="" y=$LOG/$1.y.txt
  [ -n "$set_args" ] && chparam="chparam $set_args $top;"
  runs=$((runs + 1))
  if ! yosys -q -l "$y" -p "read_verilog ${SRCS[*]}; $chparam $flow; \
       select -assert-none t:\$dlatch t:\$adlatch t:\$dlatchsr t:\$_DLATCH_* t:\$_DLATCHSR_* t:\$_SR_*; \
       check -assert" >/dev/null 2>&1; then
    echo "lint: FAIL yosys $top $label ($set_args)"; grep -iE "error|latch|warning" "$y" || true; mfail=1
  elif grep -q "^Latch inferred" "$y"; then
    echo "lint: FAIL yosys $top $label: latch inferred"; grep "^Latch inferred" "$y"; mfail=1
  fi
}

# check_module <file>: every run of one module (top = the file's name) in the chosen mode; its
# messages on stdout, "<runs> <failed 0|1>" in $LOG/<top>.done.
check_module() {
  local src=$1 top fmts flow g fmt mode st extra runs=0 mfail=0 t0=$SECONDS
  top=$(basename "$src" .v)
  if ! grep -Eq "^\s*module\s+$top\b" "$src"; then
    echo "lint: $src does not define module $top"; echo "0 1" >"$LOG/$top.done"; return 0
  fi
  # A file whose header says "lint: FP24 only" (fp_rcp: rounding mode raycore is FP24's) is
  # checked for FP24 alone.
  fmts="FP24 FP32"
  grep -q "^// lint: FP24 only" "$src" && fmts=FP24
  flow="synth -flatten -top $top"
  [[ "$ELABORATE_ONLY" == *" $top "* ]] && flow="hierarchy -top $top; proc; flatten; opt_clean"
  [[ "$HIERARCHY_ONLY" == *" $top "* ]] && flow="hierarchy -top $top; proc; opt_clean"
  if [ "$QUICK" -eq 1 ]; then
    # ---- quick: the module's own defaults (FP24), then FP32 if it has a number format ----
    [[ "$QUICK_ELABORATE" == *" $top "* ]] && flow="hierarchy -top $top; proc; flatten; opt_clean"
    vlint "$top" ""
    ysys "$top" defaults "" "$flow"
    if [ "$fmts" = "FP24 FP32" ] && has_param "$src" EXP_BITS; then
      vlint "$top" "$(params_for "$src" G ${FMT[FP32]})"
      # The hierarchy tops (rtu, chip: a minute each) are elaborated at their defaults only.
      [[ "$HIERARCHY_ONLY" == *" $top "* ]] ||
        ysys "$top" FP32 "$(params_for "$src" set ${FMT[FP32]})" "$flow"
    fi
  else
    # ---- verilator -Wall ----
    local -A seen=()
    for fmt in $fmts; do
      # RAYCORE = 1 (rounding mode raycore, FP24 only) overrides RNE: with RNE = 0 only.
      for mode in "RNE=0 RAYCORE=0" "RNE=1 RAYCORE=0" "RNE=0 RAYCORE=1"; do
        [ "$fmt" = FP32 ] && [ "$mode" = "RNE=0 RAYCORE=1" ] && continue
        for st in 0 1 2 4; do
          g=$(params_for "$src" G ${FMT[$fmt]} $mode STAGES=$st)
          [ -n "${seen["x$g"]:-}" ] && continue  # same parameters as an earlier run
          seen["x$g"]=1
          vlint "$top" "$g"
        done
      done
    done
    # Further parameter sets a module names in its header ("// lint: also P=V ..."), e.g.
    # ascache's frame form (HIT_LATENCY 0, several ports, sets not a power of two): verilator
    # -Wall each.
    while read -r extra; do
      [ -n "$extra" ] || continue
      vlint "$top" "$(params_for "$src" G $extra)"
    done < <(sed -n 's|^// lint: also ||p' "$src")
    # ---- yosys synthesis: no latches ----
    for fmt in $fmts; do
      ysys "$top" "$fmt" "$(params_for "$src" set ${FMT[$fmt]})" "$flow"
    done
  fi
  if [ $mfail -eq 0 ]; then echo "lint: $top ok ($((SECONDS - t0)) s)"; else echo "lint: $top FAILED"; fi
  echo "$runs $mfail" >"$LOG/$top.done"
}

# Arguments: module names to check (default: every module); the others are still read as sources.
# RAYCORE_LINT_JOBS modules at a time (default: 2 in quick mode, 1 in full mode), each module's
# messages printed whole and in file order.
JOBS=${RAYCORE_LINT_JOBS:-$((QUICK ? 2 : 1))}
ONLY=" ${MODULES[*]} "
TOPS=()
declare -A SRC_OF=()
for src in "${SRCS[@]}"; do
  top=$(basename "$src" .v)
  [ ${#MODULES[@]} -gt 0 ] && [[ "$ONLY" != *" $top "* ]] && continue
  TOPS+=("$top") SRC_OF[$top]=$src
done
for m in "${MODULES[@]}"; do
  [ -n "${SRC_OF[$m]:-}" ] || { echo "lint: no module $m under rtl/" >&2; exit 2; }
done
fail=0 runs=0 printed=0
flush() {  # prints the finished modules' messages, in order (a failed one's on stderr)
  local top n f
  while [ $printed -lt ${#TOPS[@]} ] && [ -e "$LOG/${TOPS[$printed]}.done" ]; do
    top=${TOPS[$printed]}
    read -r n f <"$LOG/$top.done"
    runs=$((runs + n))
    if [ "$f" -eq 0 ]; then cat "$LOG/$top.out"; else cat "$LOG/$top.out" >&2; fail=1; fi
    printed=$((printed + 1))
  done
}
start=$SECONDS
for top in "${TOPS[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n || true; flush; done
  check_module "${SRC_OF[$top]}" >"$LOG/$top.out" 2>&1 &
done
wait
flush
name=full; [ "$QUICK" -eq 1 ] && name=quick
if [ $fail -ne 0 ]; then echo "lint ($name): FAILED" >&2; exit 1; fi
echo "lint ($name): ${#TOPS[@]} of ${#SRCS[@]} modules checked, all clean ($runs verilator -Wall and" \
     "yosys runs, 0 warnings, no latches, $((SECONDS - start)) s)"
