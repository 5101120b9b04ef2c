# shellcheck shell=bash disable=SC2016,SC2034
# (SC2016: the yosys, Tcl and Python programs are single-quoted on purpose; SC2034: T_* are read by
# the scripts that source this file.)
# scripts/timing_lib.sh - static timing of one design with yosys + OpenSTA, shared by
# scripts/timing.sh (`make timing`) and the ctest Timing.fp_add3_flow (tb/rtl/CMakeLists.txt).
# Sourced, not run: the callers set `set -euo pipefail`, cd to the repository root and set
# TIMING_TMP (a scratch folder). The unit list and the sources of a module are scripts/area_lib.sh's
# (AREA_UNITS, srcs_for, file_of), sourced here.
#
# One design: yosys maps it to the OSU 0.18 um standard cells (qflow-tech-osu018) and writes a
# structural netlist; OpenSTA (`sta`) times it:
#   read_verilog <sources>; chparam <parameters> <module>
#   synth -noshare [-flatten] -top <module> -run :fine      (hierarchy kept for rtu.v whole)
#     rtu.v whole (mode hier), RAYCORE_TIMING_WHOLE_MODE:
#       units (the default): each instance of rtu.v (a unit: rgu_unit, trv_unit, the ascaches, ...)
#         mapped flat in a yosys run of its own at rtu.v's parameters (`hierarchy -top rtu;
#         hierarchy -top <its module>; synth -flatten`), rtu.v's own logic in one more run with
#         the units as black boxes, the netlists linked by sta: each unit's operators optimised
#         together as in the unit alone (what a commercial flow's ungrouping does), the paths
#         between units timed across instances. Runs RAYCORE_TIMING_JOBS (default 2) at a time.
#       modules: every module mapped once per parameter set (each rtl/fp operator alone, no
#         optimisation across its ports: constant operands, fp_pipe carries, lane muxes).
#     (The single run `hierarchy -top rtu; setattr -mod -set keep_hierarchy 1 rtu/c:* %M;
#     synth -flatten` gives the units' netlist too but did not finish: yosys' opt passes remove
#     constant pipeline registers one stage per round over the whole design; stopped at 93 min.)
#   memories: of at most TIMING_MEM_WORDS words, or read-only: memory_map (flip-flops / logic);
#     larger: SRAM macros (TIMING_MEM_V below: the macro's pins are cut by timing cells)
#   opt -fast -full; memory_map; opt -full; techmap; opt -fast
#   rename -wire -suffix _reg t:$_*DFF*     (a flip-flop named after the register it drives)
#   dfflibmap -liberty L; abc -script S -liberty L (S: TIMING_ABC below, buffers high fan-out nets)
#   setundef -zero; opt_clean; write_verilog -noexpr -nohex -nodec (src attributes kept)
# then in sta: read_liberty L and the macro library; read_verilog; link_design; create_clock on
# clk_i (a period no path reaches, TIMING_PERIOD); set_input_delay 0 / set_output_delay 0 on every
# other port; report_checks -path_delay max from/to each kind of start and end point. A path's
# length is what it needs of the period: TIMING_PERIOD - slack (the clock-to-Q, the logic and the
# end flip-flop's setup time; at an output port the arrival).

# shellcheck source=scripts/area_lib.sh
. scripts/area_lib.sh

TIMING_LIBERTY=${RAYCORE_TIMING_LIBERTY:-/usr/share/qflow/tech/osu018/osu018_stdcells.lib}
TIMING_TIMEOUT=${RAYCORE_TIMING_TIMEOUT:-3600}              # s, one yosys run of a unit
TIMING_WHOLE_TIMEOUT=${RAYCORE_TIMING_WHOLE_TIMEOUT:-7200}  # s, rtu.v whole
TIMING_CACHE=${RAYCORE_TIMING_CACHE:-out/timing-cache}      # none: no cache
TIMING_PERIOD=1000        # ns: longer than any path; a path's length = TIMING_PERIOD - slack
TIMING_MEM_WORDS=64       # memories of at most this many words become flip-flops
TIMING_SRAM_FO4=${RAYCORE_TIMING_SRAM_FO4:-40}  # an SRAM macro's read, FO4 (reference.md sec. 5)
TIMING_ABC_D=1000         # ps: ABC's delay target (below any path: delay-oriented mapping)
TIMING_FO4_28NM_PS=10.5   # FO4 at 28 nm (reference.md section 5: about 10-15 ps)
TIMING_MARGIN=2           # slow corners and wires (reference.md section 5)

# Prints why the flow cannot run (and returns 1) when a tool or the liberty is missing.
timing_tools_missing() {
  local t
  for t in yosys sta python3; do
    command -v "$t" >/dev/null || { echo "$t not found (make deps: ./scripts/deps.sh)"; return 0; }
  done
  [ -f "$TIMING_LIBERTY" ] || { echo "$TIMING_LIBERTY not found (package qflow-tech-osu018, make deps)"; return 0; }
  return 1
}

# ABC's script for `abc -script S -liberty L`: yosys' own -liberty script (strash, fraig, scorr,
# dc2, dch, &nf) followed by buffering and sizing: `buffer -p -N 8` splits every net of more than
# 8 loads into a buffer tree (yosys 0.23's `abc -D` does not buffer: one unbuffered enable net made
# a 98 ns path in ist), upsize/dnsize size the gates, stime -p prints ABC's own critical path.
TIMING_ABC="strash
&get -n
&fraig -x
&put
scorr
dc2
strash
&get -n
&dch -f
&nf -D $TIMING_ABC_D
&put
topo
buffer -p -N 8
upsize -D $TIMING_ABC_D
dnsize -D $TIMING_ABC_D
stime -p"

# A memory left as an SRAM macro ($mem_v2 of more than TIMING_MEM_WORDS words with a write port):
# mapped to timing cells of TIMING_MACRO_LIB. Every write-port pin (address, data, enable) and a
# synchronous read port's address and enable end at an RC_SRAM_IN flip-flop (a path end point, no
# setup time); a synchronous read port's data starts at an RC_SRAM_Q flip-flop whose clock-to-Q is
# the SRAM's read (TIMING_SRAM_FO4 FO4; its D pin is tied off); an asynchronous read port (the data in the address's
# cycle) is a combinational arc (the RC_SRAM_IN cells have no output: kept with (* keep *)): its address bits are gathered by RC_SRAM_OR8 cells (no delay) and
# each data bit is an RC_SRAM_RD cell (delay: the SRAM's read). The instance names keep the memory's
# name: <memory>.wr[p].d[b].ff, <memory>.rd[p].g_sync.q[b].ff, <memory>.rd[p].g_async.q[b].rd, ...
TIMING_MEM_V='
(* techmap_celltype = "$mem_v2" *)
module rc_sram_cut #(
  parameter MEMID = "", parameter signed SIZE = 4, parameter signed OFFSET = 0,
  parameter signed ABITS = 2, parameter signed WIDTH = 8, parameter signed INIT = 1'"'"'bx,
  parameter signed RD_PORTS = 1, parameter RD_CLK_ENABLE = 1'"'"'b1, parameter RD_CLK_POLARITY = 1'"'"'b1,
  parameter RD_TRANSPARENCY_MASK = 1'"'"'b0, parameter RD_COLLISION_X_MASK = 1'"'"'b0,
  parameter RD_WIDE_CONTINUATION = 1'"'"'b0, parameter RD_CE_OVER_SRST = 1'"'"'b0,
  parameter RD_ARST_VALUE = 1'"'"'b0, parameter RD_SRST_VALUE = 1'"'"'b0, parameter RD_INIT_VALUE = 1'"'"'b0,
  parameter signed WR_PORTS = 1, parameter WR_CLK_ENABLE = 1'"'"'b1, parameter WR_CLK_POLARITY = 1'"'"'b1,
  parameter WR_PRIORITY_MASK = 1'"'"'b0, parameter WR_WIDE_CONTINUATION = 1'"'"'b0
) (
  input [RD_PORTS-1:0] RD_CLK, input [RD_PORTS-1:0] RD_EN, input [RD_PORTS-1:0] RD_ARST,
  input [RD_PORTS-1:0] RD_SRST, input [RD_PORTS*ABITS-1:0] RD_ADDR, output [RD_PORTS*WIDTH-1:0] RD_DATA,
  input [WR_PORTS-1:0] WR_CLK, input [WR_PORTS*WIDTH-1:0] WR_EN, input [WR_PORTS*ABITS-1:0] WR_ADDR,
  input [WR_PORTS*WIDTH-1:0] WR_DATA
);
  wire _TECHMAP_FAIL_ = ABITS > 64;  // left to memory_map (flip-flops)
  genvar p, b, g;
  generate
    for (p = 0; p < WR_PORTS; p = p + 1) begin : wr
      for (b = 0; b < ABITS; b = b + 1) begin : a
        (* keep *) RC_SRAM_IN ff (.CLK(WR_CLK[p]), .D(WR_ADDR[p*ABITS+b]));
      end
      for (b = 0; b < WIDTH; b = b + 1) begin : d
        (* keep *) RC_SRAM_IN ff (.CLK(WR_CLK[p]), .D(WR_DATA[p*WIDTH+b]));
        (* keep *) RC_SRAM_IN en (.CLK(WR_CLK[p]), .D(WR_EN[p*WIDTH+b]));
      end
    end
    for (p = 0; p < RD_PORTS; p = p + 1) begin : rd
      if (RD_CLK_ENABLE[p]) begin : g_sync
        for (b = 0; b < ABITS; b = b + 1) begin : a
          (* keep *) RC_SRAM_IN ff (.CLK(RD_CLK[p]), .D(RD_ADDR[p*ABITS+b]));
        end
        (* keep *) RC_SRAM_IN en (.CLK(RD_CLK[p]), .D(RD_EN[p]));
        for (b = 0; b < WIDTH; b = b + 1) begin : q
          RC_SRAM_Q ff (.CLK(RD_CLK[p]), .D(1'"'"'b0), .Q(RD_DATA[p*WIDTH+b]));
        end
      end else begin : g_async
        wire [63:0] ad = RD_ADDR[p*ABITS +: ABITS];
        wire [7:0] l1;
        wire root;
        for (g = 0; g < 8; g = g + 1) begin : t
          if (g * 8 < ABITS) begin : g_or
            RC_SRAM_OR8 o (.A0(ad[g*8]), .A1(ad[g*8+1]), .A2(ad[g*8+2]), .A3(ad[g*8+3]),
                           .A4(ad[g*8+4]), .A5(ad[g*8+5]), .A6(ad[g*8+6]), .A7(ad[g*8+7]), .Y(l1[g]));
          end else begin : g_zero
            assign l1[g] = 1'"'"'b0;
          end
        end
        RC_SRAM_OR8 addr (.A0(l1[0]), .A1(l1[1]), .A2(l1[2]), .A3(l1[3]), .A4(l1[4]), .A5(l1[5]),
                          .A6(l1[6]), .A7(l1[7]), .Y(root));
        for (b = 0; b < WIDTH; b = b + 1) begin : q
          RC_SRAM_RD rd (.A(root), .Y(RD_DATA[p*WIDTH+b]));
        end
      end
    end
  endgenerate
endmodule
'

# timing_macro_lib FILE FO4_NS: the liberty of the SRAM macros' timing cells (the read: TIMING_SRAM_FO4
# x FO4_NS; pins without capacitance: yosys gives a write port one enable per bit, a macro has one
# pin, with its own input buffer). Read by yosys as black boxes (read_liberty -lib) and by sta.
timing_macro_lib() {
  local t
  t=$(python3 -c "print('%.4f' % ($TIMING_SRAM_FO4 * $2))")
  cat > "$1" <<EOF
/* raycore SRAM macro cut cells (scripts/timing_lib.sh): read = $TIMING_SRAM_FO4 FO4 = $t ns */
library (raycore_sram) {
  delay_model : table_lookup;
  time_unit : "1ns"; voltage_unit : "1V"; current_unit : "1uA";
  pulling_resistance_unit : "1kohm"; leakage_power_unit : "1nW"; capacitive_load_unit (1,pf);
  slew_upper_threshold_pct_rise : 80; slew_lower_threshold_pct_rise : 20;
  slew_upper_threshold_pct_fall : 80; slew_lower_threshold_pct_fall : 20;
  input_threshold_pct_rise : 50; input_threshold_pct_fall : 50;
  output_threshold_pct_rise : 50; output_threshold_pct_fall : 50;
  nom_process : 1; nom_voltage : 1.8; nom_temperature : 25;
  cell (RC_SRAM_IN) {
    area : 0;
    ff (IQ, IQN) { next_state : "D"; clocked_on : "CLK"; }
    pin (CLK) { direction : input; clock : true; capacitance : 0; }
    pin (D) { direction : input; capacitance : 0;
      timing () { related_pin : "CLK"; timing_type : setup_rising;
        rise_constraint (scalar) { values ("0"); } fall_constraint (scalar) { values ("0"); } } }
  }
  cell (RC_SRAM_Q) {
    area : 0;
    ff (IQ, IQN) { next_state : "D"; clocked_on : "CLK"; }
    pin (CLK) { direction : input; clock : true; capacitance : 0; }
    pin (D) { direction : input; capacitance : 0;
      timing () { related_pin : "CLK"; timing_type : setup_rising;
        rise_constraint (scalar) { values ("0"); } fall_constraint (scalar) { values ("0"); } } }
    pin (Q) { direction : output; function : "IQ";
      timing () { related_pin : "CLK"; timing_type : rising_edge;
        cell_rise (scalar) { values ("$t"); } cell_fall (scalar) { values ("$t"); }
        rise_transition (scalar) { values ("0.1"); } fall_transition (scalar) { values ("0.1"); } } }
  }
  cell (RC_SRAM_OR8) {
    area : 0;
    pin (A0) { direction : input; capacitance : 0; }
    pin (A1) { direction : input; capacitance : 0; }
    pin (A2) { direction : input; capacitance : 0; }
    pin (A3) { direction : input; capacitance : 0; }
    pin (A4) { direction : input; capacitance : 0; }
    pin (A5) { direction : input; capacitance : 0; }
    pin (A6) { direction : input; capacitance : 0; }
    pin (A7) { direction : input; capacitance : 0; }
    pin (Y) { direction : output; function : "A0|A1|A2|A3|A4|A5|A6|A7";
$(for a in A0 A1 A2 A3 A4 A5 A6 A7; do
  echo "      timing () { related_pin : \"$a\"; cell_rise (scalar) { values (\"0\"); } cell_fall (scalar) { values (\"0\"); }"
  echo "        rise_transition (scalar) { values (\"0.1\"); } fall_transition (scalar) { values (\"0.1\"); } }"
done)
    }
  }
  cell (RC_SRAM_RD) {
    area : 0;
    pin (A) { direction : input; capacitance : 0; }
    pin (Y) { direction : output; function : "A";
      timing () { related_pin : "A"; cell_rise (scalar) { values ("$t"); } cell_fall (scalar) { values ("$t"); }
        rise_transition (scalar) { values ("0.1"); } fall_transition (scalar) { values ("0.1"); } } }
  }
}
EOF
}

# timing_fo4 DIR: FO4 of the liberty measured by sta. A chain of 9 INVX1 stages, each driving the
# next stage and 3 more INVX1 loads (fanout 4), from an input port to an output port; FO4 = the
# mean of the delays of stages 5 and 6 (one rising and one falling output; the stages around them
# see the same input slew and load as their neighbours). Prints the FO4 in ns.
timing_fo4() {
  local d=$1 i
  {
    echo "module fo4_chain (a, y);"
    echo "  input a; output y;"
    echo "  wire [9:0] n;"
    echo "  INVX1 drv (.A(a), .Y(n[0]));"
    for i in 1 2 3 4 5 6 7 8 9; do
      echo "  INVX1 s$i (.A(n[$((i - 1))]), .Y(n[$i]));"
      echo "  INVX1 l${i}a (.A(n[$((i - 1))]), .Y()); INVX1 l${i}b (.A(n[$((i - 1))]), .Y()); INVX1 l${i}c (.A(n[$((i - 1))]), .Y());"
    done
    echo "  INVX1 l10a (.A(n[9]), .Y()); INVX1 l10b (.A(n[9]), .Y()); INVX1 l10c (.A(n[9]), .Y());"
    echo "  INVX1 last (.A(n[9]), .Y(y));"
    echo "endmodule"
  } > "$d/fo4.v"
  cat > "$d/fo4.tcl" <<EOF
read_liberty $TIMING_LIBERTY
read_verilog $d/fo4.v
link_design fo4_chain
create_clock -name vclk -period $TIMING_PERIOD
set_input_delay 0 -clock vclk [get_ports a]
set_output_delay 0 -clock vclk [get_ports y]
report_checks -path_delay max -from [get_ports a] -to [get_ports y] -digits 5
EOF
  sta -no_splash -exit "$d/fo4.tcl" > "$d/fo4.rpt" 2>&1 || { cat "$d/fo4.rpt" >&2; return 1; }
  awk '$4 == "s5/Y" || $4 == "s6/Y" { s += $1; n++ } END { if (n != 2 || s <= 0) exit 1; printf "%.5f\n", s / 2 }' \
    "$d/fo4.rpt" || { echo "timing: no FO4 stages in sta's report:" >&2; cat "$d/fo4.rpt" >&2; return 1; }
}

# The Tcl run by sta on a design's netlist: the worst path of each kind into r2r.rpt, i2r.rpt,
# r2o.rpt, i2o.rpt (register to register, input to register, register to output, input to output;
# the memories' RC_SRAM_* cells are registers here: their input cut cells RC_SRAM_IN end paths,
# added to all_registers' data pins by hand since 2026-11-28, before which no path into a memory's
# write port or synchronous read address was timed) and into top.rpt the worst path to each of the
# 10 first distinct end registers (bit and generate indices dropped) among the TIMING_TOP worst
# register-to-register end points.
TIMING_TOP=100000
timing_sta_tcl() {  # NETLIST MODULE MACROLIB OUTDIR
  cat <<EOF
read_liberty $TIMING_LIBERTY
read_liberty $3
read_verilog $1
link_design $2
set clkp [get_ports -quiet clk_i]
if {[llength \$clkp] > 0} { create_clock -name clk -period $TIMING_PERIOD \$clkp } else { create_clock -name clk -period $TIMING_PERIOD }
set ins {}
foreach p [all_inputs] { if {[get_full_name \$p] != "clk_i"} { lappend ins \$p } }
if {[llength \$ins] > 0} { set_input_delay 0 -clock clk \$ins }
if {[llength [all_outputs]] > 0} { set_output_delay 0 -clock clk [all_outputs] }
set rc [all_registers -clock_pins]
set rd [all_registers -data_pins]
# The SRAM macros' input cut cells (RC_SRAM_IN: write address, data and enable; a synchronous
# read's address and enable) are end points too: all_registers leaves them out (a flip-flop
# without an output pin), so without this no path into a memory's write port was timed.
foreach p [get_pins -quiet -of_objects [get_cells -quiet -hierarchical -filter "ref_name == RC_SRAM_IN"] -filter "direction == input"] {
  if {[get_property \$p lib_pin_name] == "D"} { lappend rd \$p }
}
puts "timing: [llength \$ins] inputs, [llength [all_outputs]] outputs, [llength \$rc] register clock pins, [llength \$rd] register data pins"
proc rep {file args} { report_checks -path_delay max -digits 4 -format full {*}\$args > $4/\$file }
if {[llength \$rc] > 0 && [llength \$rd] > 0} {
  rep r2r.rpt -from \$rc -to \$rd
  # the worst paths to distinct end registers (bit and generate indices dropped): the end points
  # worst first (-format end), then one full path to each of the first 10 distinct ones
  report_checks -path_delay max -from \$rc -to \$rd -group_count $TIMING_TOP -endpoint_count 1 -format end > $4/ends.rpt
  set seen {}
  set f [open $4/ends.rpt r]
  while {[gets \$f line] >= 0 && [llength \$seen] < 10} {
    if {![regexp {^(\S+)/(D|R|S) } \$line -> inst pin]} { continue }
    regsub -all {\[[0-9]+\]} \$inst {} key
    if {[lsearch -exact \$seen \$key] >= 0} { continue }
    lappend seen \$key
    set pat [string map {"[" "\\[" "]" "\\]"} \$inst/\$pin]
    report_checks -path_delay max -from \$rc -to [get_pins \$pat] -digits 4 -format full >> $4/top.rpt
  }
  close \$f
}
if {[llength \$ins] > 0 && [llength \$rd] > 0} { rep i2r.rpt -from \$ins -to \$rd }
if {[llength \$rc] > 0 && [llength [all_outputs]] > 0} { rep r2o.rpt -from \$rc -to [all_outputs] }
if {[llength \$ins] > 0 && [llength [all_outputs]] > 0} { rep i2o.rpt -from \$ins -to [all_outputs] }
puts "timing: sta done"
EOF
}

# Parses sta's reports in DIR (python3) with the netlist's src attributes (the RTL file and line of
# each flip-flop) into DIR/paths.tsv: one line per kind (r2r i2r r2o i2o) and per distinct top path
# (kind top): kind, length ns (period - slack), arrival ns, start, end, start src, end src, the
# top-level instances the path crosses, with their modules and the ns spent in each (hierarchical
# netlists, the top module itself as its name; '-' for a flat one),
# the cells on the path.
# Start and end are RTL names: a flip-flop "<register>[bit]_reg" as "<register>[bit]", a port as
# its name, a memory's timing cell as "<memory> (SRAM ...)". Fails when sta printed no path at all.
TIMING_PARSE_PY='
import os, re, sys
d, net, period, top = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
def leaf(n):
    return n.rsplit("/", 1)[-1]
srcs, types = {}, {}  # (module, cell) -> src attribute; (module, instance) -> module
def norm(m):
    return m[1:] if m.startswith("\\") else m
def load_srcs(names, insts):
    # the src attribute of each named cell (the line "(* src = ... *)" before its instance) and the
    # module of each named instance, per module
    pend, mod = None, None
    cell_re = re.compile(r"^\s*(\S+)\s+(\S+)\s+\($")
    with open(net, errors="replace") as f:
        for line in f:
            if line.startswith("module "):
                mod = norm(re.match(r"module\s+(\S+?)\s*\(", line).group(1)); pend = None
                continue
            s = line.strip()
            if s.startswith("(* src ="):
                pend = s.split("\"")[1]
                continue
            if s.startswith("(*"): continue
            m = cell_re.match(line)
            if m:
                n = norm(m.group(2))
                if pend is not None and n in names: srcs.setdefault((mod, n), pend)
                if n in insts: types[(mod, n)] = norm(m.group(1))
            pend = None
def module_of(inst):
    # the module holding the cell inst ("a/b/cell": the module of instance b in the module of a)
    mod = top
    for c in inst.split("/")[:-1]:
        mod = types.get((mod, c))
        if mod is None: return None
    return mod
def src_of(inst):
    # the src entry (file:line) that assigns the register: the one whose lines name it (the others
    # are the instances above it); else the last entry
    s = srcs.get((module_of(inst), leaf(inst)))
    if not s: return "-"
    s = "|".join(e for e in s.split("|") if e.startswith("rtl/"))  # not the techmap file
    if not s: return "-"
    base = re.sub(r"\[\d+\]", "", leaf(inst))
    base = re.sub(r"_reg$", "", base).split(".")[-1]
    best = None
    for e in s.split("|"):
        m = re.match(r"(.*?):(\d+)(?:\.\d+-(\d+))?", e)
        if not m: continue
        f, a = m.group(1), int(m.group(2))
        b = int(m.group(3) or a)
        best = best or "%s:%d" % (f, a)
        try:
            txt = "".join(open(f, errors="replace").readlines()[a - 1:b])
        except OSError:
            continue
        if re.search(r"\b%s\b" % re.escape(base), txt):
            return "%s:%d" % (f, a)
    return "%s:%d" % (m.group(1), int(m.group(2))) if m else (best or s)
def rtl(name):
    # a flip-flop instance: "<register>[b]_reg"; a memory cut cell: "<memory>.wr[p]...", "<memory>.rd[p]..."
    hier, _, l = name.rpartition("/")
    pre = hier + "/" if hier else ""
    m = re.match(r"(.*)\.(wr|rd)\[(\d+)\]\.(g_sync\.|g_async\.)?(a|d|q|en)\[?(\d*)\]?\.(ff|en|rd|o)$", l)
    if m or ".addr" in l:
        if m:
            mem, port, p, mode, pin = m.group(1), m.group(2), m.group(3), m.group(4) or "", m.group(5)
            what = {"a": "address", "d": "write data" if m.group(7) == "ff" else "write enable",
                    "q": "read data", "en": "read enable"}[pin]
            kind = "write" if port == "wr" else ("synchronous read" if mode.startswith("g_sync") else "asynchronous read")
            return "%s%s (SRAM macro, %s port %s: %s)" % (pre, mem, kind, p, what)
        return pre + l
    if l.endswith("_reg"): l = l[:-4]
    return pre + l
def parse(fn):
    out = []
    if not os.path.exists(fn): return out
    txt = open(fn, errors="replace").read()
    for blk in txt.split("Startpoint: ")[1:]:
        lines = blk.splitlines()
        start = lines[0].split()[0]
        end = re.search(r"^Endpoint: (\S+)", blk, re.M).group(1)
        arr = re.search(r"^\s*(-?[\d.]+)\s+data arrival time", blk, re.M)
        sl = re.search(r"^\s*(-?[\d.]+)\s+slack", blk, re.M)
        if not arr or not sl: continue
        pins = re.findall(r"^\s*(-?[\d.]+)\s+-?[\d.]+\s+[v^]\s+(\S+)\s+\((\S+)\)", blk, re.M)
        tops = []  # [instance of the top module, ns spent in it]; "." for the top module itself
        for dl, pin, cell in pins:
            t = pin.split("/")[0] if pin.count("/") >= 2 else "."
            if not tops or tops[-1][0] != t: tops.append([t, 0.0])
            tops[-1][1] += float(dl)
        if all(t == "." for t, _ in tops): tops = []
        ncell = sum(1 for dl, pin, cell in pins if pin.endswith(("/Y", "/YC", "/YS", "/Q")))
        out.append((period - float(sl.group(1)), float(arr.group(1)), start, end, tops, ncell))
    return out
rows = []
found = 0
for k in ("r2r", "i2r", "r2o", "i2o"):
    ps = parse(os.path.join(d, k + ".rpt"))
    if ps:
        found += 1
        n, a, s, e, t, c = ps[0]
        rows.append((k, n, a, s, e, t, c))
seen = set()
for n, a, s, e, t, c in parse(os.path.join(d, "top.rpt")):
    key = (re.sub(r"\[\d+\]", "[]", rtl(s)), re.sub(r"\[\d+\]", "[]", rtl(e)))
    if key in seen: continue
    seen.add(key)
    rows.append(("top", n, a, s, e, t, c))
    if len(seen) >= 10: break
if not found:
    sys.exit("timing: sta reported no path (see %s)" % d)
load_srcs(set(leaf(r[i]) for r in rows for i in (3, 4)),
          set(c for r in rows for i in (3, 4) for c in r[i].split("/")[:-1]) | set(t for r in rows for t, _ in r[5]))
def inst(t, ns):
    # an instance of the top module with its module ("$paramod$<hash>\\<module>": <module>) and the
    # time the path spends in it
    m = types.get((top, t))
    name = top if t == "." else ("%s (%s)" % (t, m.split("\\")[-1]) if m else t)
    return "%s %.2f ns" % (name, ns)
with open(os.path.join(d, "paths.tsv"), "w") as f:
    for k, n, a, s, e, t, c in rows:
        f.write("\t".join([k, "%.4f" % n, "%.4f" % a, rtl(s), rtl(e), src_of(s), src_of(e),
                           ">".join(inst(x, ns) for x, ns in t) or "-", str(c)]) + "\n")
'

# Buffers the nets ABC does not see whole (python3: netlist in, netlist out): a flip-flop's output,
# a module's input port, an instance's output port (the hierarchical netlist: each module was mapped
# alone, so a net that leaves a module or comes from one is not in its ABC run; ABC buffered the
# rest). Every net with more than TIMING_FANOUT loads (input pins of cells and of instances; a
# module output port or an assign counts as one) gets a tree of BUFX4 cells, TIMING_FANOUT loads
# per buffer; clock nets (a load on a CLK pin) are left alone (the clock is ideal). The same rule
# as ABC's `buffer -N 8` inside each module, applied to the nets between them.
TIMING_FANOUT=8
TIMING_BUF_PY='
import re, sys
net, lib_files, out, maxfo = sys.argv[1], sys.argv[2].split(","), sys.argv[3], int(sys.argv[4])
dirs = {}  # cell type -> {pin: "input"|"output"}
for lf in lib_files:
    cell = pin = None
    for m in re.finditer(r"\b(cell|pin)\s*\(\s*\"?(\w+)\"?\s*\)|\bdirection\s*:\s*(\w+)", open(lf, errors="replace").read()):
        if m.group(1) == "cell": cell = m.group(2); dirs[cell] = {}
        elif m.group(1) == "pin": pin = m.group(2)
        elif cell and pin: dirs[cell][pin] = m.group(3)
mod_re = re.compile(r"^module\s+(\S+)\s*\(")
decl_re = re.compile(r"^\s*(input|output|inout)\s+(.*?)\s*;\s*$")
# pass 1: the port directions of every module
cur = None
with open(net, errors="replace") as f:
    for line in f:
        m = mod_re.match(line)
        if m: cur = m.group(1); dirs[cur] = {}; continue
        m = decl_re.match(line)
        if m and cur: dirs[cur][m.group(2).split()[-1]] = m.group(1)
ident = re.compile(r"^(\\\S+|[A-Za-z_][\w$]*(\[\d+\])?)$")
inst_re = re.compile(r"^\s*(\S+)\s+(\S+)\s*\($")
pin_re = re.compile(r"^(\s*)\.(\w+)\((.*)\)(,?)\s*$")
assign_re = re.compile(r"^\s*assign\s+(.*?)\s*=\s*(.*?)\s*;\s*$")
nbuf = 0
fo = open(out, "w")
def flush(lines):
    # one module: loads of each net; rewire the loads of big nets to buffer trees
    global nbuf
    loads, clock, extra, drivers = {}, set(), {}, set()
    typ = None
    for i, line in enumerate(lines):
        m = inst_re.match(line)
        if m and m.group(1) in dirs:
            typ = m.group(1); continue
        m = pin_re.match(line)
        if m and typ:
            n = m.group(3).strip()
            if not ident.match(n): continue
            d = dirs[typ].get(m.group(2), "input")
            if d == "output": drivers.add(n); continue
            loads.setdefault(n, []).append(i)
            if m.group(2) == "CLK": clock.add(n)
            continue
        if line.strip() == ");": typ = None; continue
        m = decl_re.match(line)
        if m and m.group(1) == "output":
            n = m.group(2).split()[-1]; extra[n] = extra.get(n, 0) + 1
            continue
        m = assign_re.match(line)
        if m:
            n = m.group(2).strip(); extra[n] = extra.get(n, 0) + 1
    new_cells, new_wires = [], []
    for n, idx in loads.items():
        if n in clock or len(idx) + extra.get(n, 0) <= maxfo: continue
        level = idx  # line indices of load pins, then buffer cells [type, output, input]
        while len(level) > 1 and len(level) + extra.get(n, 0) > maxfo:
            nxt = []
            for k in range(0, len(level), maxfo):
                nbuf += 1
                w = "_rcbuf_%d_" % nbuf
                new_wires.append("  wire %s;" % w)
                for i in level[k:k + maxfo]:
                    if isinstance(i, int):
                        m = pin_re.match(lines[i])
                        lines[i] = "%s.%s(%s)%s\n" % (m.group(1), m.group(2), w, m.group(4))
                    else:
                        i[2] = w
                cell = ["BUFX4", w, None]
                new_cells.append(cell)
                nxt.append(cell)
            level = nxt
        for c in level:
            if not isinstance(c, int): c[2] = n
    out_lines = []
    for line in lines:
        if line.startswith("endmodule"):
            for w in new_wires: out_lines.append(w + "\n")
            for t, w, a in new_cells:
                out_lines.append("  %s %scell (.A(%s), .Y(%s));\n" % (t, w, a if not a.startswith("\\") else a + " ", w))
        out_lines.append(line)
    fo.writelines(out_lines)
block = []
with open(net, errors="replace") as f:
    for line in f:
        block.append(line)
        if line.startswith("endmodule"):
            flush(block); block = []
fo.writelines(block)
fo.close()
print("timing: %d buffers inserted" % nbuf)
'

# timing_yosys_units DIR TOP TIMEOUT HEAD TAIL: the units mode of rtu.v whole (see the header):
# lists the modules of TOP's instances, maps each flat in a yosys run of its own (RAYCORE_TIMING_JOBS
# at a time; DIR/net_<i>.v, DIR/stat_<i>.txt), TOP's own logic with those modules as black boxes
# (DIR/net_top.v), and joins them into DIR/net.v. Returns 124 if a run did not finish within
# TIMEOUT seconds (of the whole), 1 if one failed (its log printed).
timing_yosys_units() {
  local dir=$1 top=$2 to=$3 head=$4 tail=$5 t_end i=0 kids=() k s rc=0
  t_end=$(( $(date +%s) + to ))
  s="${head//DIR/$dir} hierarchy -top $top; tee -q -o $dir/kids.txt select -list $top/c:* %M"
  timeout "$to" yosys -q -l "$dir/yosys_list.log" -p "$s" >/dev/null || return $?
  # the lines without a "/": the modules (the others are their contents)
  while IFS= read -r k; do [[ "$k" == */* ]] || kids+=("$k"); done < "$dir/kids.txt"
  [ ${#kids[@]} -gt 0 ] || { echo "timing: $top has no instances" >&2; return 1; }
  # the top's own logic first (short; a mistake shows at once), then the instances' modules, each
  # counted by a plain stat (the top is not in its run)
  s="$head hierarchy -top $top; blackbox$(printf ' %s' "${kids[@]}"); synth -noshare -top $top -run :fine; $tail"
  s=${s//STAT/stat_top.txt}; s=${s//NET/net_top.v}; s=${s//DIR/$dir}
  printf '%s\n' "$s" > "$dir/unit_top.ys"
  echo top > "$dir/runs.txt"
  for k in "${kids[@]}"; do
    s="$head hierarchy -top $top; hierarchy -top $k; synth -noshare -flatten -top $k -run :fine; $tail"
    s=${s//STAT/stat_$i.txt}; s=${s//NET/net_$i.v}; s=${s//stat -top $top /stat }; s=${s//DIR/$dir}
    printf '%s\n' "$s" > "$dir/unit_$i.ys"
    echo "$i" >> "$dir/runs.txt"
    i=$((i + 1))
  done
  echo "timing: $top: ${#kids[@]} instances' modules and the top, each mapped alone (${RAYCORE_TIMING_JOBS:-2} at a time)" >&2
  # shellcheck disable=SC2016  # $1 is xargs' argument, expanded by the inner bash
  xargs -P "${RAYCORE_TIMING_JOBS:-2}" -I{} bash -c \
    'left=$(( '"$t_end"' - $(date +%s) )); [ $left -gt 0 ] || exit 124
     timeout $left yosys -q -l "$1/yosys_$2.log" -s "$1/unit_$2.ys" >/dev/null ||
       { rc=$?; [ $rc -eq 124 ] || { echo "timing: yosys failed on $1/unit_$2.ys:" >&2; tail -20 "$1/yosys_$2.log" >&2; }; exit $rc; }' \
    _ "$dir" {} < "$dir/runs.txt" || rc=$?
  # xargs exits 123/124/125 when a command failed; any timeout is a timeout
  if [ $rc -ne 0 ]; then
    grep -qs "^ERROR" "$dir"/yosys_*.log && return 1
    [ "$(date +%s)" -ge "$t_end" ] && return 124
    return 1
  fi
  : > "$dir/net.v"
  for k in $(cat "$dir/runs.txt"); do cat "$dir/net_$k.v" >> "$dir/net.v"; done
  cat "$dir"/yosys_*.log > "$dir/yosys.log"
}

# timing_design NAME MODULE CHPARAM [hier]: map and time one design (CHPARAM: "-set P V ..." or
# empty; hier keeps the hierarchy: rtu.v whole, RAYCORE_TIMING_WHOLE_MODE units (default: each
# instance of the top mapped flat in its own run, the top's own logic with them as black boxes) or
# modules (every module mapped once per parameter set), the netlist hierarchical). Needs
# TIMING_TMP, TIMING_FO4 (timing_fo4's) and TIMING_MACRO (timing_macro_lib's
# file). Sets T_STATUS (ok, or timeout: yosys did not finish in TIMING_TIMEOUT s), T_SECS (yosys
# wall seconds; TIMING_WHOLE_TIMEOUT for hier), T_STA_SECS (the buffering and sta), T_CELLS (standard cells of the netlist) and T_PATHS (the
# paths.tsv file, see TIMING_PARSE_PY). Exits on a yosys or sta error. Cached in TIMING_CACHE: the
# netlist (gzip) by a hash of the yosys version, the script, the liberty and the sources; sta's
# reports by that and sta's version, its Tcl, the buffering and the macro library; the paths by
# that and the parser. A timeout is remembered (NKEY.timeout:
# the seconds): a later run with a timeout no longer than that reports it without rerunning.
# RAYCORE_TIMING_CACHED_ONLY=1: a design whose netlist is not cached is not run (T_STATUS not_run).
# shellcheck disable=SC2153  # TIMING_TMP: set by the caller
timing_design() {
  local name=$1 mod=$2 chp=$3 hier=${4:-} dir="$TIMING_TMP/$1" srcs script nkey skey pkey t0 rc=0
  local flatten=-flatten stat="stat -liberty $TIMING_LIBERTY" to=$TIMING_TIMEOUT
  local wmode=flat head tail
  if [ "$hier" = hier ]; then
    wmode=${RAYCORE_TIMING_WHOLE_MODE:-units}
    case "$wmode" in
      units|modules) ;;
      *) echo "timing: RAYCORE_TIMING_WHOLE_MODE must be units or modules, not '$wmode'" >&2; exit 1 ;;
    esac
    flatten=""; stat="stat -top $mod -liberty $TIMING_LIBERTY"; to=$TIMING_WHOLE_TIMEOUT
  fi
  mkdir -p "$dir"
  printf '%s\n' "$TIMING_ABC" > "$dir/abc.script"
  printf '%s\n' "$TIMING_MEM_V" > "$dir/mem_cut.v"
  cp "$TIMING_MACRO" "$dir/raycore_sram.lib"
  srcs=$(srcs_for "$mod")
  # head: the sources at the design's parameters; tail: from the mapped RTL to the netlist NET
  head="read_liberty -lib $TIMING_LIBERTY; read_liberty -lib DIR/raycore_sram.lib; read_verilog $srcs; \
    ${chp:+chparam $chp $mod;}"
  tail="memory_map r:SIZE<=$TIMING_MEM_WORDS r:WR_PORTS=0; \
    techmap -map DIR/mem_cut.v t:\$mem_v2; \
    opt -fast -full; memory_map; opt -full; techmap; opt -fast; \
    rename -wire -suffix _reg t:\$_*DFF* t:\$_DLATCH*; \
    dfflibmap -liberty $TIMING_LIBERTY; opt_clean; \
    abc -script DIR/abc.script -liberty $TIMING_LIBERTY; \
    setundef -zero; splitnets -ports; opt_clean -purge; hierarchy -check; check; \
    tee -q -o DIR/STAT $stat; \
    write_verilog -noexpr -nohex -nodec DIR/NET"
  script="$head synth -noshare $flatten -top $mod -run :fine; $tail"
  # the key: the same steps, run per instance by timing_yosys_units
  [ "$wmode" = units ] && script="units: $(declare -f timing_yosys_units) $script"
  # shellcheck disable=SC2086  # srcs: a list of file names without spaces
  nkey=$({ yosys -V; echo "$script"; echo "$TIMING_ABC"; echo "$TIMING_MEM_V"; md5sum < "$TIMING_LIBERTY";
           grep -v '^/\*' "$TIMING_MACRO" | grep -v 'values ("[0-9.]*")' ; cat $srcs; } | sha256sum | cut -c1-16)
  T_STATUS=ok
  if [ "$TIMING_CACHE" != none ] && [ -s "$TIMING_CACHE/$nkey.net.v.gz" ]; then
    gunzip -c "$TIMING_CACHE/$nkey.net.v.gz" > "$dir/net.v"
    read -r T_SECS T_CELLS < "$TIMING_CACHE/$nkey.yosys"
    echo "timing: $name: netlist cached ($TIMING_CACHE/$nkey.net.v.gz)" >&2
  elif [ "${RAYCORE_TIMING_CACHED_ONLY:-0}" = 1 ]; then
    T_STATUS=not_run T_SECS=0
    echo "timing: $name: not in the cache, not run (RAYCORE_TIMING_CACHED_ONLY=1)" >&2
    return 0
  elif [ "$TIMING_CACHE" != none ] && [ -s "$TIMING_CACHE/$nkey.timeout" ] &&
       [ "$(cat "$TIMING_CACHE/$nkey.timeout")" -ge "$to" ]; then
    T_STATUS=timeout
    T_SECS=$(cat "$TIMING_CACHE/$nkey.timeout")
    echo "timing: $name: did not finish in $T_SECS s before ($TIMING_CACHE/$nkey.timeout; a longer timeout reruns it)" >&2
    return 0
  else
    t0=$(date +%s)
    if [ "$wmode" = units ]; then
      timing_yosys_units "$dir" "$mod" "$to" "$head" "$tail" || rc=$?
    else
      script=${script//STAT/stat.txt}; script=${script//NET/net.v}
      timeout "$to" yosys -q -l "$dir/yosys.log" -p "${script//DIR/$dir}" >/dev/null || rc=$?
    fi
    T_SECS=$(( $(date +%s) - t0 ))
    if [ $rc -eq 124 ]; then
      T_STATUS=timeout
      if [ "$TIMING_CACHE" != none ]; then mkdir -p "$TIMING_CACHE"; echo "$to" > "$TIMING_CACHE/$nkey.timeout"; fi
      return 0
    fi
    # (units mode: the failing run's log was printed by timing_yosys_units; no yosys.log then)
    [ $rc -eq 0 ] || { echo "timing: yosys failed for $name ($mod $chp), see:" >&2
                       [ ! -f "$dir/yosys.log" ] || tail -20 "$dir/yosys.log" >&2; exit 1; }
    # the cells: the last count of each stat file (flat: the design; units: each instance's module
    # and the top's own logic, whose black boxes are counted as cells too)
    T_CELLS=$(for f in "$dir"/stat*.txt; do
                awk '$1 == "Number" && $3 == "cells:" { n = $4 } END { print n + 0 }' "$f"; done |
              awk '{ n += $1 } END { print n + 0 }')
    if [ "$TIMING_CACHE" != none ]; then
      mkdir -p "$TIMING_CACHE"
      gzip -c "$dir/net.v" > "$TIMING_CACHE/$nkey.net.v.gz.tmp"
      mv "$TIMING_CACHE/$nkey.net.v.gz.tmp" "$TIMING_CACHE/$nkey.net.v.gz"
      echo "$T_SECS $T_CELLS" > "$TIMING_CACHE/$nkey.yosys"
    fi
  fi
  timing_sta_tcl "$dir/net_buf.v" "$mod" "$dir/raycore_sram.lib" "$dir" > "$dir/sta.tcl"
  skey=$({ echo "$nkey"; sta -version; sed "s|$dir|DIR|g" "$dir/sta.tcl"; cat "$TIMING_MACRO";
           echo "$TIMING_BUF_PY $TIMING_FANOUT"; } | sha256sum | cut -c1-16)
  pkey=$({ echo "$skey"; echo "$TIMING_PARSE_PY"; } | sha256sum | cut -c1-16)
  T_PATHS="$dir/paths.tsv"
  if [ "$TIMING_CACHE" != none ] && [ -s "$TIMING_CACHE/$pkey.paths.tsv" ]; then
    cp "$TIMING_CACHE/$pkey.paths.tsv" "$T_PATHS"
    T_STA_SECS=$(cat "$TIMING_CACHE/$skey.sta")
    return 0
  fi
  t0=$(date +%s)
  python3 -c "$TIMING_BUF_PY" "$dir/net.v" "$TIMING_LIBERTY,$TIMING_MACRO" "$dir/net_buf.v" "$TIMING_FANOUT" >&2
  # A top yosys derived from the parameters ("$paramod$<hash>\<module>", trv_unit) is named <module>.
  grep -q "^module $mod(" "$dir/net_buf.v" ||
    sed -i -E "s/^module \\\\\\\$paramod\\\$[0-9a-f]+\\\\$mod \(/module $mod(/" "$dir/net_buf.v"
  if [ "$TIMING_CACHE" != none ] && [ -s "$TIMING_CACHE/$skey.rpt.tar.gz" ]; then
    tar -xzf "$TIMING_CACHE/$skey.rpt.tar.gz" -C "$dir"   # sta's reports of this netlist
    T_STA_SECS=$(cat "$TIMING_CACHE/$skey.sta")
  else
    rc=0
    sta -no_splash -exit "$dir/sta.tcl" > "$dir/sta.log" 2>&1 || rc=$?
    T_STA_SECS=$(( $(date +%s) - t0 ))
    if [ $rc -ne 0 ] || grep -q "^Error" "$dir/sta.log"; then
      echo "timing: sta failed for $name (exit $rc), see $dir/sta.log:" >&2; tail -20 "$dir/sta.log" >&2; exit 1
    fi
    if [ "$TIMING_CACHE" != none ]; then
      mkdir -p "$TIMING_CACHE"
      (cd "$dir" && tar -czf "$TIMING_CACHE/$skey.rpt.tar.gz.tmp" sta.log ./*.rpt)
      mv "$TIMING_CACHE/$skey.rpt.tar.gz.tmp" "$TIMING_CACHE/$skey.rpt.tar.gz"
      echo "$T_STA_SECS" > "$TIMING_CACHE/$skey.sta"
    fi
  fi
  python3 -c "$TIMING_PARSE_PY" "$dir" "$dir/net_buf.v" "$TIMING_PERIOD" "$mod" || { tail -20 "$dir/sta.log" >&2; exit 1; }
  if [ "$TIMING_CACHE" != none ]; then cp "$T_PATHS" "$TIMING_CACHE/$pkey.paths.tsv"; fi
}
