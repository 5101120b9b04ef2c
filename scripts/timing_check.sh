#!/usr/bin/env bash
# scripts/timing_check.sh [DESIGN] [DIR]: the static timing flow of make timing (scripts/timing_lib.sh)
# run on one small design (default fp_add3: FP24 rtz, STAGES 2, a few seconds) into DIR (default a
# temporary folder), without the cache, and its result checked: the liberty's FO4 measured by sta
# within 2x of 0.1 ns; each path sta reported longer than zero and than one FO4, and shorter than
# the period (positive slack); a register-to-register path whose start and end are RTL register
# names. The ctest Timing.fp_add3_flow (tb/rtl/CMakeLists.txt). Exits 77 (ctest SKIP_RETURN_CODE)
# only when yosys, sta, python3 or the liberty is missing (make deps installs them); fails when a
# tool fails or prints nothing.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/timing_lib.sh
. scripts/timing_lib.sh
if why=$(timing_tools_missing); then echo "timing_check: SKIP: $why" >&2; exit 77; fi

DESIGN=${1:-fp_add3}
[ -f "rtl/fp/$DESIGN.v" ] || { echo "timing_check: $DESIGN is not an operator of rtl/fp/" >&2; exit 1; }
if [ -n "${2:-}" ]; then
  TIMING_TMP=$2
  rm -rf "$TIMING_TMP"
  mkdir -p "$TIMING_TMP"
else
  TIMING_TMP=$(mktemp -d "${TMPDIR:-/tmp}/raycore-timing-check.XXXXXX")
  trap 'rm -rf "$TIMING_TMP"' EXIT
fi
TIMING_CACHE=none

TIMING_FO4=$(timing_fo4 "$TIMING_TMP")
echo "timing_check: FO4 = $TIMING_FO4 ns"
python3 -c "import sys; f = float(sys.argv[1]); sys.exit(0 if 0.05 <= f <= 0.2 else 1)" "$TIMING_FO4" ||
  { echo "timing_check: FAIL: FO4 $TIMING_FO4 ns is not within 2x of 0.1 ns" >&2; exit 1; }
TIMING_MACRO=$TIMING_TMP/raycore_sram.lib
timing_macro_lib "$TIMING_MACRO" "$TIMING_FO4"

chp="-set EXP_BITS 7 -set MAN_BITS 16 -set STAGES 2"
grep -Eq "parameter +integer +RNE\b" "rtl/fp/$DESIGN.v" && chp+=" -set RNE 0"
timing_design "$DESIGN" "$DESIGN" "$chp"
[ "$T_STATUS" = ok ] || { echo "timing_check: FAIL: yosys did not finish ($T_STATUS)" >&2; exit 1; }
[ -s "$T_PATHS" ] || { echo "timing_check: FAIL: no paths (sta printed nothing?)" >&2; exit 1; }
cat "$T_PATHS"
python3 - "$T_PATHS" "$TIMING_FO4" "$TIMING_PERIOD" <<'EOF'
import sys
paths, fo4, period = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
rows = [l.rstrip("\n").split("\t") for l in open(paths)]
kinds = {r[0]: r for r in rows if r[0] != "top"}
bad = []
if "r2r" not in kinds:
    bad.append("no register-to-register path")
for k, r in kinds.items():
    ns = float(r[1])
    if not (fo4 < ns < period):
        bad.append("%s path %.4f ns not within (1 FO4 = %.4f, period %g) ns" % (k, ns, fo4, period))
if "r2r" in kinds:
    s, e = kinds["r2r"][3], kinds["r2r"][4]
    for n in (s, e):
        if n.startswith("_") or "$" in n or "_q" not in n:
            bad.append("register-to-register end %r is not an RTL register name" % n)
    if not kinds["r2r"][5].startswith("rtl/"):
        bad.append("register-to-register start has no RTL file: %r" % kinds["r2r"][5])
    print("timing_check: register to register %.3f ns = %.1f FO4: %s -> %s (%s)" % (
        float(kinds["r2r"][1]), float(kinds["r2r"][1]) / fo4, s, e, kinds["r2r"][5]))
if bad:
    print("timing_check: FAIL: " + "; ".join(bad), file=sys.stderr)
    sys.exit(1)
print("timing_check: ok")
EOF
