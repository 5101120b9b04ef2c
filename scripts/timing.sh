#!/usr/bin/env bash
# make timing: static timing of the RTL with yosys + OpenSTA on the OSU 0.18 um standard cells
# (qflow-tech-osu018), written to docs/timing.md and docs/timing.json (or the files given as $1 $2).
#
# Designs: every operator of rtl/fp/ (fp_add fp_add3 fp_mul fp_sop fp_div fp_sqrt fp_rcp fp_cmp;
# FP24, rounding rtz where the module has RNE, STAGES 2 unless RAYCORE_TIMING_STAGES says otherwise),
# every unit of AREA_UNITS (scripts/area_lib.sh; the parameters of make area's first table: module
# defaults, FP24 rtz, STAGES 2, ascache the 16 KB node cache) and rtl/units/rtu.v whole at its
# parameter defaults (the cycle model's), FP24 rtz, its hierarchy kept: by default
# (RAYCORE_TIMING_WHOLE_MODE=units) each of its instances mapped flat in a yosys run of its own at
# rtu.v's parameters and rtu.v's own logic in one more, the netlists linked by sta; modules: every
# module mapped once per parameter set (scripts/timing_lib.sh). One yosys + sta run per
# design (scripts/timing_lib.sh, cached in out/timing-cache); FO4 measured first on an INVX1 chain.
#
# Environment: RAYCORE_TIMING_TIMEOUT (s, default 3600) bounds one unit's yosys run,
# RAYCORE_TIMING_WHOLE_TIMEOUT (s, default 7200) rtu.v whole's; a run that does not finish is
# reported as such (and remembered in the cache: a later run with a timeout no longer than the one
# that expired reports it again without rerunning). RAYCORE_TIMING_WHOLE=0 leaves rtu.v whole out
# (reported as not run). RAYCORE_TIMING_DESIGNS="a b": run only these designs (names as in the
# tables: fp_add3, ist, rtu, ...) and print their paths, without writing the documents.
# RAYCORE_TIMING_REV=<commit>: time the rtl/ of that commit instead of the working tree's.
# RAYCORE_TIMING_CACHED_ONLY=1: the documents from the cached results only (a design not in the
# cache is reported as not run). RAYCORE_TIMING_CACHE (default out/timing-cache; none: off),
# RAYCORE_TIMING_SRAM_FO4 (default 40). RAYCORE_TIMING_WHOLE_MODE (units, the default, or modules:
# how rtu.v whole is mapped, above), RAYCORE_TIMING_JOBS (default 2: units mode's yosys runs at a time).
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/timing_lib.sh
. scripts/timing_lib.sh
if why=$(timing_tools_missing); then echo "timing: $why" >&2; exit 1; fi

OUT_MD=$(realpath -m "${1:-docs/timing.md}")
OUT_JSON=$(realpath -m "${2:-docs/timing.json}")
STAGES=${RAYCORE_TIMING_STAGES:-2}
TIMING_TMP=$(mktemp -d "${TMPDIR:-/tmp}/raycore-timing.XXXXXX")
trap 'rm -rf "$TIMING_TMP"' EXIT
# RAYCORE_TIMING_REV=<commit>: the rtl/ of that commit (git archive into a scratch folder, the
# flow run there) instead of the working tree's.
SOURCES="rtl/ of the working tree"
# Absolute: the flow archives sta's reports from inside the design's scratch folder.
[ "$TIMING_CACHE" = none ] || TIMING_CACHE=$(realpath -m "$TIMING_CACHE")
if [ -n "${RAYCORE_TIMING_REV:-}" ]; then
  rev=$(git rev-parse --short "$RAYCORE_TIMING_REV")
  SOURCES="rtl/ at commit $rev (RAYCORE_TIMING_REV)"
  mkdir -p "$TIMING_TMP/src"
  git archive "$rev" rtl | tar -x -C "$TIMING_TMP/src"
  cd "$TIMING_TMP/src"
  echo "timing: $SOURCES"
fi
area_check_units

TIMING_FO4=$(timing_fo4 "$TIMING_TMP")
echo "timing: FO4 of $(basename "$TIMING_LIBERTY") = $TIMING_FO4 ns (INVX1 driving 4 INVX1, sta)"
TIMING_MACRO=$TIMING_TMP/raycore_sram.lib
timing_macro_lib "$TIMING_MACRO" "$TIMING_FO4"

# The designs: "name|module|parameters|mode" (mode: flat, or hier for rtu.v whole).
# Parameters as in make area's first table (scripts/area.sh): FP24 (EXP_BITS 7, MAN_BITS 16), RNE 0
# where the module has it, STAGES where it has it; ascache the cycle model's node cache.
declare -A UNIT_PARAMS=([ascache]="-set SETS 64 -set WAYS 4 -set LINE_BYTES 64 -set MSHRS 8")
design_params() {
  local mod=$1 f chp=""
  f=$(file_of "$mod")
  grep -Eq "parameter +integer +EXP_BITS" "$f" && chp="-set EXP_BITS 7 -set MAN_BITS 16"
  grep -Eq "parameter +integer +RNE\b" "$f" && chp+=" -set RNE 0"
  grep -Eq "parameter +integer +STAGES" "$f" && chp+=" -set STAGES $STAGES"
  chp+="${UNIT_PARAMS[$mod]:+ ${UNIT_PARAMS[$mod]}}"
  echo "${chp# }"
}
DESIGNS=()
for mod in fp_add fp_add3 fp_mul fp_sop fp_div fp_sqrt fp_rcp fp_cmp "${AREA_UNITS[@]}"; do
  DESIGNS+=("$mod|$mod|$(design_params "$mod")|flat")
done
# rtu.v whole: its defaults are the cycle model's (scripts/area_rtu.sh's "rtu whole"), FP24 rtz.
DESIGNS+=("rtu|rtu|-set EXP_BITS 7 -set MAN_BITS 16 -set RNE 0|hier")

read -r -a ONLY <<< "${RAYCORE_TIMING_DESIGNS:-}"
selected() { [ ${#ONLY[@]} -eq 0 ] || [[ " ${ONLY[*]} " == *" $1 "* ]]; }

RES=$TIMING_TMP/designs.tsv
: > "$RES"
for spec in "${DESIGNS[@]}"; do
  IFS='|' read -r name mod chp mode <<< "$spec"
  selected "$name" || continue
  if [ "$mode" = hier ] && [ "${RAYCORE_TIMING_WHOLE:-1}" = 0 ]; then
    printf '%s\t%s\t%s\t%s\tnot_run\t0\t0\t0\t-\n' "$name" "$mod" "$(file_of "$mod")" "$chp" >> "$RES"
    echo "timing: $name: not run (RAYCORE_TIMING_WHOLE=0)"
    continue
  fi
  echo "timing: $name ($mod $chp, $mode) ..."
  timing_design "$name" "$mod" "$chp" "$([ "$mode" = hier ] && echo hier)"
  if [ "$T_STATUS" != ok ]; then
    printf '%s\t%s\t%s\t%s\t%s\t%s\t0\t0\t-\n' "$name" "$mod" "$(file_of "$mod")" "$chp" "$T_STATUS" "$T_SECS" >> "$RES"
    [ "$T_STATUS" = timeout ] && echo "timing: $name: yosys did not finish in ${T_SECS} s"
    continue
  fi
  printf '%s\t%s\t%s\t%s\tok\t%s\t%s\t%s\t%s\n' "$name" "$mod" "$(file_of "$mod")" "$chp" "$T_SECS" \
    "$T_STA_SECS" "$T_CELLS" "$T_PATHS" >> "$RES"
  awk -F'\t' -v n="$name" -v f="$TIMING_FO4" '$1 != "top" {
    printf "timing: %s %s %.3f ns = %.1f FO4: %s -> %s\n", n, $1, $2, $2 / f, $4, $5 }' "$T_PATHS"
  echo "timing: $name: yosys ${T_SECS} s, sta ${T_STA_SECS} s, ${T_CELLS} cells"
done

if [ ${#ONLY[@]} -gt 0 ]; then
  echo "timing: RAYCORE_TIMING_DESIGNS set: documents not written"
  exit 0
fi

# The documents (python3): docs/timing.md and docs/timing.json from designs.tsv and paths.tsv.
python3 - "$RES" "$OUT_MD" "$OUT_JSON" "$TIMING_FO4" "$TIMING_FO4_28NM_PS" "$TIMING_MARGIN" \
  "$TIMING_SRAM_FO4" "$TIMING_LIBERTY" "$(yosys -V | head -1)" "$(sta -version)" "$STAGES" \
  "$TIMING_TIMEOUT" "$TIMING_WHOLE_TIMEOUT" "$TIMING_MEM_WORDS" "$(srcs_for rtu)" "$SOURCES" \
  "${RAYCORE_TIMING_WHOLE_MODE:-units}" <<'EOF'
import datetime, json, sys
(res, out_md, out_json, fo4, fo4_28, margin, sram_fo4, liberty, yosys_v, sta_v, stages,
 t_unit, t_whole, mem_words, rtu_srcs, sources, whole_mode) = sys.argv[1:]
WHOLE_DESC = {"units": "each of its instances (the units) mapped flat at rtu.v's parameters, rtu.v's own logic apart, "
                       "the netlists linked (RAYCORE_TIMING_WHOLE_MODE=units)",
              "modules": "every module mapped once per parameter set (RAYCORE_TIMING_WHOLE_MODE=modules)"}
fo4, fo4_28, margin, sram_fo4 = float(fo4), float(fo4_28), float(margin), float(sram_fo4)
KINDS = [("r2r", "reg_to_reg", "register to register"), ("i2r", "in_to_reg", "input to register"),
         ("r2o", "reg_to_out", "register to output"), ("i2o", "in_to_out", "input to output")]
def mhz(fo4s):  # the 28 nm clock of a path of fo4s FO4
    return 1e6 / (margin * fo4s * fo4_28)
def path(f):
    return {"ns": round(float(f[1]), 4), "fo4": round(float(f[1]) / fo4, 1), "arrival_ns": round(float(f[2]), 4),
            "start": f[3], "end": f[4], "start_src": f[5], "end_src": f[6],
            "through": [] if f[7] == "-" else f[7].split(">"), "cells": int(f[8])}
designs = {}
order = []
for line in open(res):
    name, mod, file, params, status, ysecs, ssecs, cells, pfile = line.rstrip("\n").split("\t")
    desc = ("%s whole at its parameter defaults (the cycle model's), %s" % (file, WHOLE_DESC[whole_mode]) if mod == "rtu"
            else "%s alone%s" % (file, ", " + params if params else ""))
    d = {"design": desc, "module": mod, "file": file, "params": params, "status": status, "yosys_s": int(ysecs),
         "sta_s": int(ssecs), "cells": int(cells), "fo4_ns": fo4, "paths": {}, "top_paths": []}
    if status == "ok":
        for l in open(pfile):
            f = l.rstrip("\n").split("\t")
            if f[0] == "top":
                d["top_paths"].append(path(f))
            else:
                d["paths"][dict((k, j) for k, j, _ in KINDS)[f[0]]] = path(f)
        # The clock: the slowest register-to-register path (a standalone unit's input and output
        # paths combine with its neighbour's); without registers the slowest path of any kind.
        basis = "reg_to_reg" if "reg_to_reg" in d["paths"] else max(d["paths"], key=lambda k: d["paths"][k]["ns"])
        w = d["paths"][basis]
        d.update({"clock_path": basis, "worst_ns": w["ns"], "worst_fo4": round(w["ns"] / fo4, 1),
                  "clock_mhz_28nm": round(mhz(w["ns"] / fo4), 1), "start": w["start"], "end": w["end"]})
    else:
        d.update({"clock_path": None, "worst_ns": None, "worst_fo4": None, "clock_mhz_28nm": None,
                  "start": None, "end": None})
    designs[name] = d
    order.append(name)

# The RTU's clock: rtu.v whole's slowest register-to-register path; if it did not finish, the slowest
# of the units it contains (each timed alone, at make area's parameters): a lower bound on the period.
rtu = {"status": designs.get("rtu", {}).get("status", "not_run")}
if rtu["status"] == "ok":
    r = designs["rtu"]
    rtu.update({"basis": "rtu.v whole, slowest register-to-register path", "clock_mhz_28nm": r["clock_mhz_28nm"],
                "worst_ns": r["worst_ns"], "worst_fo4": r["worst_fo4"], "start": r["start"], "end": r["end"]})
else:
    units = [n for n in order if designs[n]["status"] == "ok" and designs[n]["file"] in rtu_srcs.split()
             and designs[n]["file"].startswith("rtl/units/")]
    if units:
        u = max(units, key=lambda n: designs[n]["worst_ns"])
        rtu.update({"basis": "LOWER BOUND on the period (upper bound on the clock): rtu.v whole did not finish; "
                             "the slowest unit of the RTU timed alone (%s)" % u,
                    "clock_mhz_28nm": designs[u]["clock_mhz_28nm"], "worst_ns": designs[u]["worst_ns"],
                    "worst_fo4": designs[u]["worst_fo4"], "start": designs[u]["start"], "end": designs[u]["end"],
                    "upper_bound": True, "from_design": u})
date = datetime.datetime.utcnow().strftime("%Y-%m-%d")
doc = {"generated_by": "make timing (scripts/timing.sh, scripts/timing_lib.sh)", "date": date, "sources": sources,
       "tools": {"yosys": yosys_v, "sta": "OpenSTA " + sta_v}, "liberty": liberty,
       "library": "OSU 0.18 um standard cells (qflow-tech-osu018), typical corner",
       "fo4_ns": fo4,
       "assumptions": {"fo4_28nm_ps": fo4_28, "margin": margin, "sram_read_fo4": sram_fo4,
                       "clock_mhz_28nm": "1e6 / (margin * worst_fo4 * fo4_28nm_ps)"},
       "designs": designs, "rtu": rtu}
with open(out_json, "w") as f:
    json.dump(doc, f, indent=1)
    f.write("\n")

def fmt_path(p):
    return "%.2f | %.1f" % (p["ns"], p["fo4"]) if p else "- | -"
def fmt_src(s):
    return "" if s == "-" else " (%s)" % s
def show_params(p):  # "-set A 1 -set B 2" -> "A 1, B 2"
    return ", ".join(x.strip() for x in p.split("-set") if x.strip())
def md_name(s):
    return "`%s`" % s
L = []
A = L.append
A("# Static timing of the RTL (rtl/fp/, rtl/units/)")
A("")
A("Generated by `make timing` (`./scripts/timing.sh`, `scripts/timing_lib.sh`) with %s and OpenSTA %s" % (yosys_v, sta_v))
A("on %s, from %s. Do not edit by hand; the same numbers are in `docs/timing.json`." % (date, sources))
A("")
A("## Method")
A("")
A("- **Library**: `%s`, the OSU 0.18 um standard cells of Debian's qflow-tech-osu018 (32 cells, typical" % liberty)
A("  corner, 1.8 V, time unit 1 ns), with OpenSTA's default wire model (no wire load: the cells' pin")
A("  capacitances only). **FO4 = %.4f ns**, measured by the same flow: a structural chain of INVX1" % fo4)
A("  stages each driving the next and 3 more INVX1 (fanout 4), timed by `sta`; FO4 is the mean of the")
A("  delays of two middle stages (one rising, one falling output). Not assumed.")
A("- **Mapping** (yosys, one run per design): `read_verilog` the module's sources (scripts/area_lib.sh")
A("  `srcs_for`), `chparam`, `synth -noshare -flatten -top M -run :fine` (rtu.v whole: without")
A("  `-flatten`, see below), memories (below), `opt; memory_map; opt; techmap; opt`, `rename -wire -suffix _reg`")
A("  on the flip-flops (each flip-flop instance named after the register it drives), `dfflibmap")
A("  -liberty L`, `abc -script S -liberty L` with S = yosys' own liberty script (strash, fraig, scorr,")
A("  dc2, dch, `&nf -D 1000`) followed by **`topo; buffer -p -N 8; upsize -D 1000; dnsize -D 1000;")
A("  stime -p`**: ABC's buffering (every net of more than 8 loads becomes a buffer tree; yosys 0.23's")
A("  `abc -D` alone does not buffer) and gate sizing, delay-oriented (target 1 ns, below every path).")
A("  Then `setundef -zero; splitnets -ports; opt_clean -purge` and `write_verilog -noexpr`: a structural")
A("  netlist (flat; rtu.v whole hierarchical, so that OpenSTA links the hierarchy and times paths across")
A("  instances).")
if whole_mode == "units":
    A("- **rtu.v whole, unit by unit** (`RAYCORE_TIMING_WHOLE_MODE=units`, the default since 2026-12-01): each")
    A("  instance of rtu.v (rgu_unit, slot_ram, trv_unit, the three ascaches, ist_unit, hit_unit, vtu_unit)")
    A("  is mapped flat in a yosys run of its own at rtu.v's parameters (`hierarchy -top rtu; hierarchy -top")
    A("  <its module>; synth -flatten`, the steps above), rtu.v's own logic in one more run with the units as")
    A("  black boxes, and sta links the netlists: a unit's operators are optimised together as in the unit")
    A("  alone (what a commercial flow's ungrouping of the operators does), the paths between units are timed")
    A("  across the instances. `RAYCORE_TIMING_WHOLE_MODE=modules` maps every module of rtu.v once per")
    A("  parameter set instead (each rtl/fp operator alone, no optimisation across its ports): at rtl/ 8043638")
    A("  10.11 ns = 101.9 FO4 that way against 9.63 ns = 97.1 FO4 unit by unit (the single yosys run")
    A("  `setattr -mod -set keep_hierarchy 1 rtu/c:* %M; synth -flatten`, the same kind of netlist,")
    A("  did not finish in 93 minutes).")
else:
    A("- **rtu.v whole, module by module** (`RAYCORE_TIMING_WHOLE_MODE=modules`): every module of rtu.v")
    A("  mapped once per parameter set, each rtl/fp operator alone.")
A("- **Buffering between ABC runs**: ABC sees one module's logic at a time, without the flip-flops,")
A("  so a flip-flop's output, a module's input port or (rtu.v whole) a net between instances can")
A("  drive hundreds of loads unbuffered (vtu_unit hierarchical: a 12 ns clock-to-Q). A pass over the")
A("  netlist (python, scripts/timing_lib.sh TIMING_BUF_PY) gives every net of more than 8 loads a")
A("  tree of BUFX4 cells, 8 loads each (the rule of ABC's `buffer -N 8`); clock nets are left alone.")
A("- **Timing** (OpenSTA `sta`): `read_liberty`, `read_verilog`, `link_design`, `create_clock` on `clk_i`")
A("  (ideal clock), `set_input_delay 0` on every other input, `set_output_delay 0` on every output,")
A("  then `report_checks -path_delay max` from/to each kind of start and end point: register to")
A("  register, input to register, register to output, input to output. A path's length is what it")
A("  needs of the period: clock-to-Q + logic + the end flip-flop's setup time (at an output: the")
A("  arrival). Inputs are driven ideally (no driving cell) and outputs are unloaded.")
A("- **Memories**: a memory of at most %s words, or a ROM, becomes flip-flops / logic (`memory_map`);" % mem_words)
A("  a larger one stays an SRAM macro, cut for timing: its write port's pins and a synchronous read's")
A("  address end paths (no setup time), a synchronous read's data starts %.0f FO4 (%.2f ns) after the" % (sram_fo4, sram_fo4 * fo4))
A("  clock, and an asynchronous read (data in the address's cycle) is an arc of %.0f FO4 from every" % sram_fo4)
A("  address bit to every data bit (reference.md section 5: a 16 KB SRAM read is about 35-45 FO4 by")
A("  CACTI; one figure for every size, a register file of 128 words is faster, a 64 KB array slower).")
A("  Such paths name the memory: `<memory> (SRAM macro, ... port p: ...)`. The macros' input cut")
A("  cells are added to sta's register data pins by hand (`all_registers` leaves out a flip-flop")
A("  without an output pin): until 2026-11-28 no path into a memory's write port or synchronous")
A("  read address was timed, and rtu.v whole's clock was too fast (24ba861: 165.6 FO4 reported,")
A("  309.8 FO4 with them, the entering ray's clip into the slot arrays).")
A("- **Names**: start and end points are RTL names: a register bit (`u_pipe_b.g_regs.data_q[165]`:")
A("  the instance path of the flattened design and the register), with the RTL file and line of")
A("  the register (yosys' `src` attribute of the flip-flop; the innermost module's), or a port.")
A("  A flip-flop yosys merged or renamed keeps its src but gets a generated name (`_123_`).")
A("- **Clock at 28 nm**: assuming FO4 = %.1f ps at 28 nm and a %gx margin for slow corners and wires" % (fo4_28, margin))
A("  (reference.md section 5: FO4 about 10-15 ps at 28 nm; with a 2x margin about 100 FO4 closes")
A("  500 MHz), **clock_mhz_28nm = 1e6 / (%g x worst_fo4 x %.1f)** (95 FO4: %.0f MHz). A design's" % (margin, fo4_28, mhz(95)))
A("  worst path is its slowest register-to-register path (without registers: its slowest path):")
A("  a unit's input and output paths end or start in its neighbour, with whose logic they combine")
A("  (listed, not in its clock). In rtu.v whole the units' hand-offs are register-to-register paths")
A("  across instances; its own ports face the chip (membus_if) and are listed separately.")
A("- Parameters: FP24 (EXP_BITS 7, MAN_BITS 16), rounding rtz (RNE 0; fp_rcp is raycore's reciprocal,")
A("  fp_cmp has no rounding), STAGES %s (make area's first table: every unit at its module's defaults" % stages)
A("  otherwise, ascache the 16 KB node cache: SETS 64, WAYS 4, LINE_BYTES 64, MSHRS 8, its pin-level")
A("  twin's HIT_LATENCY 1); rtu.v whole at its defaults = the cycle model's (docs/area.md, \"One RTU\").")
A("- **yosys s / sta s**: wall seconds of the run when it ran (cached in out/timing-cache by a hash of")
A("  the sources, parameters, scripts, tools and library; 2 cores shared with other work). Timeouts:")
A("  %s s per unit, %s s for rtu.v whole." % (t_unit, t_whole))
A("")
A("## Summary")
A("")
A("| design | file | worst path (clock) ns | FO4 | clock at 28 nm MHz | reg->reg ns / FO4 | in->reg ns / FO4 | reg->out ns / FO4 | in->out ns / FO4 | cells | yosys s | sta s |")
A("|---|---|---:|---:|---:|---|---|---|---|---:|---:|---:|")
for n in order:
    d = designs[n]
    if d["status"] != "ok":
        why = {"timeout": "did not finish in %d s" % d["yosys_s"], "not_run": "not run"}[d["status"]]
        A("| %s | %s | %s | | | | | | | | %s | |" % (n, d["file"], why, d["yosys_s"] or ""))
        continue
    cols = []
    for k, j, _ in KINDS:
        p = d["paths"].get(j)
        cols.append("%.2f / %.1f" % (p["ns"], p["fo4"]) if p else "-")
    A("| %s | %s | %.2f | %.1f | %.0f | %s | %s | %s | %s | %d | %d | %d |" % (
        n, d["file"], d["worst_ns"], d["worst_fo4"], d["clock_mhz_28nm"], *cols, d["cells"], d["yosys_s"], d["sta_s"]))
A("")
A("## The RTU's clock")
A("")
if rtu["status"] == "ok":
    w = designs["rtu"]["paths"]["reg_to_reg"]
    A("**rtu.v whole: %.2f ns = %.1f FO4, %.0f MHz at 28 nm**: its slowest register-to-register path," % (
        rtu["worst_ns"], rtu["worst_fo4"], rtu["clock_mhz_28nm"]))
    A("from `%s`%s to `%s`%s, %d cells, through %s." % (w["start"], fmt_src(w["start_src"]), w["end"],
        fmt_src(w["end_src"]), w["cells"], " -> ".join(w["through"]) or "rtu.v's own logic"))
elif "clock_mhz_28nm" in rtu:
    A("**rtu.v whole %s.** A lower bound on the RTU's period (an upper bound on its clock), from the" % (
        "did not finish" if rtu["status"] == "timeout" else "was not run"))
    A("slowest of its units timed alone (%s, at make area's parameters): **%.2f ns = %.1f FO4, at most %.0f MHz" % (
        rtu["from_design"], rtu["worst_ns"], rtu["worst_fo4"], rtu["clock_mhz_28nm"]))
    A("at 28 nm** (`%s` -> `%s`). Paths across the units (e.g. trv_unit -> ascache -> trv_unit in" % (rtu["start"], rtu["end"]))
    A("one cycle) are not in it.")
else:
    A("No result: rtu.v whole %s and none of its units is timed." % (
        "did not finish" if rtu["status"] == "timeout" else "was not run"))
A("")
if designs.get("rtu", {}).get("status") == "ok":
    A("### The ten worst paths of rtu.v whole")
    A("")
    A("Distinct start/end register pairs (bit and generate indices dropped), worst first; *through*: the")
    A("instances of rtu.v the path crosses, in order, with the time it spends in each (clock-to-Q and")
    A("setup in the first and last; `rtu`: rtu.v's own wiring logic).")
    A("")
    for i, p in enumerate(designs["rtu"]["top_paths"][:10], 1):
        thr = " -> ".join(p["through"]) if p["through"] else "rtu.v's own logic"
        A("%d. **%.2f ns (%.1f FO4)**: from `%s`%s to `%s`%s, through %s; %d cells." % (
            i, p["ns"], p["fo4"], p["start"], fmt_src(p["start_src"]), p["end"], fmt_src(p["end_src"]), thr, p["cells"]))
    A("")
A("## Worst paths per design")
A("")
for n in order:
    d = designs[n]
    if d["status"] != "ok":
        continue
    A("### %s (`%s`; %s)" % (n, d["file"], show_params(d["params"]) or "module defaults"))
    A("")
    A("| kind | ns | FO4 | start | end | cells |")
    A("|---|---:|---:|---|---|---:|")
    for k, j, words in KINDS:
        p = d["paths"].get(j)
        if not p:
            A("| %s | - | - | no such path | | |" % words)
            continue
        A("| %s | %.2f | %.1f | %s%s | %s%s | %d |" % (words, p["ns"], p["fo4"], md_name(p["start"]), fmt_src(p["start_src"]),
                                                      md_name(p["end"]), fmt_src(p["end_src"]), p["cells"]))
    A("")
with open(out_md, "w") as f:
    f.write("\n".join(L))
EOF
echo "timing: wrote $OUT_MD and $OUT_JSON"
