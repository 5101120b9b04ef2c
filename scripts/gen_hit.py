#!/usr/bin/env python3
"""scripts/gen_hit.py - writes rtl/units/hit.v, the hit unit's pipelined datapath.

The datapath is described below as twelve sublevels of rtl/fp operators (spawn_ops groups, one
kind of operator per group) with the values each reads; the script computes, for every value, the
levels it has to be carried through (from the level that produces it to the last that reads it)
and emits one fp_pipe per sublevel with exactly those values, so the carries cannot drift from the
data flow. Run it after changing the description: python3 scripts/gen_hit.py > rtl/units/hit.v
"""
import re
import sys

W = "W"
# Sublevels: (weight, [groups], [post wires]). The weight is the number of registers the
# sublevel's logic needs for 95 FO4 (docs/timing.md's operators: an add or mul 1, an add3 3, a
# divider or square root 7, the sublevel's slowest operator); the hit unit's LPS x STAGES registers
# (LPS below: 24) are shared out in proportion (cumulative, so that they add up: sublevel l takes
# R Q_l / QT - R Q_l-1 / QT, R = LPS STAGES - IN_REGS, Q the running sum of the weights, QT their
# total). A group is (op, [(out, a, b, c, sub)]); op: mul,
# add (sub = 1'b1 subtracts), add3, rcp (1 / b), sqrt (of a). Expressions name values in braces:
# {x} is x as available at the input of the sublevel (or at its output, for post wires and the
# outputs). Post wires: (name, width, expr), combinational after the sublevel's registers.
Z = "{W{1'b0}}"
LEVELS = [
    # 1 (level 1, first half): the hit point's products and the primary ray's error terms (weight
    #   2: t backed off by back_i ulps, an integer carry chain, comes before the multipliers)
    (2, [
        ("mul", [("td_x", "{th}", "{d_x}"), ("td_y", "{th}", "{d_y}"), ("td_z", "{th}", "{d_z}"),
                 ("nuou", "{nu}", "{ou}"), ("nvov", "{nv}", "{ov}"), ("nudu", "{nu}", "{du}"),
                 ("nvdv", "{nv}", "{dv}"), ("tden", "{t}", "{den}")]),
        ("add", [("ndok", "{and}", "fabs({ok})")]),
    ], []),
    # 2 (level 1, second half): h = o + t d; e_num, e_den
    (3, [
        ("add", [("h_x", "{o_x}", "{td_x}"), ("h_y", "{o_y}", "{td_y}"), ("h_z", "{o_z}", "{td_z}")]),
        ("add3", [("e_num", "{ndok}", "fabs({nuou})", "fabs({nvov})"),
                  ("e_den", "fabs({dk})", "fabs({nudu})", "fabs({nvdv})")]),
    ], []),
    # 3 (level 2): light - h; |t d_i| + |h_i|, |n_i| |h_i|, |n_d| + |h_k|, n_u h_u, n_v h_v,
    #   5 e_num, |t| e_den, 2 |t den|; the slab 2 ulps ulp(max |h_i|)
    (1, [
        ("sub", [("ld_x", "light_x_i", "{h_x}"), ("ld_y", "light_y_i", "{h_y}"),
                 ("ld_z", "light_z_i", "{h_z}")]),
        ("add", [("s_x", "fabs({td_x})", "fabs({h_x})"), ("s_y", "fabs({td_y})", "fabs({h_y})"),
                 ("s_z", "fabs({td_z})", "fabs({h_z})"),
                 ("ndhk", "{and}", "fabs(pk({k}, {h_x}, {h_y}, {h_z}))")]),
        ("mul", [("m_x", "fabs({n_x})", "fabs({h_x})"), ("m_y", "fabs({n_y})", "fabs({h_y})"),
                 ("m_z", "fabs({n_z})", "fabs({h_z})"),
                 ("nuhu", "pu({k}, {n_x}, {n_y}, {n_z})", "pu({k}, {h_x}, {h_y}, {h_z})"),
                 ("nvhv", "pv({k}, {n_x}, {n_y}, {n_z})", "pv({k}, {h_x}, {h_y}, {h_z})"),
                 ("c5num", "C5", "{e_num}"), ("ated", "{at}", "{e_den}"),
                 ("c2tden", "C2", "fabs({tden})"),
                 ("slab", "slab_scale_i", "ulp_max({h_x}[W-2:M], {h_y}[W-2:M], {h_z}[W-2:M])")]),
    ], []),
    # 4 (level 3): squares; |n_i| (|t d_i| + |h_i|); e_move's first sum; e_snum; 3 |t| e_den
    (3, [
        ("mul", [("sq_x", "{ld_x}", "{ld_x}"), ("sq_y", "{ld_y}", "{ld_y}"),
                 ("sq_z", "{ld_z}", "{ld_z}"),
                 ("x_x", "fabs({n_x})", "{s_x}"), ("x_y", "fabs({n_y})", "{s_y}"),
                 ("x_z", "fabs({n_z})", "{s_z}"), ("c3ted", "C3", "{ated}")]),
        ("add", [("em1", "{m_x}", "{m_y}")]),
        ("add3", [("e_snum", "{ndhk}", "fabs({nuhu})", "fabs({nvhv})")]),
    ], []),
    # 5 (level 4): |light - h|^2; b1; e_hit's first sum, e_move; 5 e_snum
    (3, [
        ("add3", [("len2", "{sq_x}", "{sq_y}", "{sq_z}"),
                  ("b1", "{c5num}", "{c3ted}", "{c2tden}")]),
        ("add", [("eh1", "{x_x}", "{x_y}"), ("em", "{em1}", "{m_z}")]),
        ("mul", [("c5snum", "C5", "{e_snum}")]),
    ], []),
    # 6 (level 5): the distance to the light; e_hit; 5 e_snum + e_move
    (7, [
        ("sqrt", [("len", "{len2}")]),
        ("add", [("eh", "{eh1}", "{x_z}"), ("snmv", "{c5snum}", "{em}")]),
    ], []),
    # 7 (level 6): 1 / len; 2 e_hit
    (7, [
        ("rcp", [("rl", "{len}")]),
        ("mul", [("c2hit", "C2", "{eh}")]),
    ], []),
    # 8 (level 7): the unit direction; the bound B. Then the shadow direction (segment: light - h)
    (3, [
        ("mul", [("dd_x", "{ld_x}", "{rl}"), ("dd_y", "{ld_y}", "{rl}"), ("dd_z", "{ld_z}", "{rl}")]),
        ("add3", [("b2", "{b1}", "{c2hit}", "{snmv}")]),
    ], [("ds_x", W, "segment_i ? {ld_x} : {dd_x}"), ("ds_y", W, "segment_i ? {ld_y} : {dd_y}"),
        ("ds_z", W, "segment_i ? {ld_z} : {dd_z}")]),
    # 9 (level 8): 1 / d_i; n_u d_u, n_v d_v; u B
    (7, [
        ("rcp", [("inv_x", "{ds_x}"), ("inv_y", "{ds_y}"), ("inv_z", "{ds_z}")]),
        ("mul", [("nud", "pu({k}, {n_x}, {n_y}, {n_z})", "pu({k}, {ds_x}, {ds_y}, {ds_z})"),
                 ("nvd", "pv({k}, {n_x}, {n_y}, {n_z})", "pv({k}, {ds_x}, {ds_y}, {ds_z})"),
                 ("ub", "UU", "{b2}")]),
    ], []),
    # 10 (level 9): dens = n . d_shadow; delta = 2 u B. Then the light side and the operands of the
    #   last level: n_i or -n_i (the side of the light), max(|dens|, 1/16)
    (3, [
        ("add3", [("dens", "pk({k}, {ds_x}, {ds_y}, {ds_z})", "{nud}", "{nvd}")]),
        ("mul", [("delta", "C2", "{ub}")]),
    ], [("front", "1", "{dens}[W-2:M] != {E{1'b0}} && {den}[W-2:M] != {E{1'b0}} && "
                       "{dens}[W-1] != {den}[W-1]"),
        ("sn_x", W, "{dens}[W-1] ? fneg({n_x}) : {n_x}"),
        ("sn_y", W, "{dens}[W-1] ? fneg({n_y}) : {n_y}"),
        ("sn_z", W, "{dens}[W-1] ? fneg({n_z}) : {n_z}"),
        ("dmax", W, "fmax_sixteenth({dens})")]),
    # 11 (level 10, first half): 1 / max(|dens|, 1/16); delta n_i (error-bound) or fixed * (+-n_i)
    #   (ulp-offset), scale * (+-n_i); then the ulp-offset origin away from zero
    (7, [
        ("rcp", [("rd", "{dmax}")]),
        ("mul", [("ma_x", "s_eb ? {delta} : fixed_i", "s_eb ? {n_x} : {sn_x}"),
                 ("ma_y", "s_eb ? {delta} : fixed_i", "s_eb ? {n_y} : {sn_y}"),
                 ("ma_z", "s_eb ? {delta} : fixed_i", "s_eb ? {n_z} : {sn_z}"),
                 ("ps_x", "scale_i", "{sn_x}"), ("ps_y", "scale_i", "{sn_y}"),
                 ("ps_z", "scale_i", "{sn_z}")]),
    ], [("q_x", W, "add_ulps_num({h_x}, {ps_x})"), ("q_y", W, "add_ulps_num({h_y}, {ps_y})"),
        ("q_z", W, "add_ulps_num({h_z}, {ps_z})")]),
    # 12 (level 10, second half): the slab's t_min; h +- delta n (error-bound), h + fixed n_i
    (1, [
        ("mul", [("t0", "{slab}", "{rd}")]),
        ("add", [("oa_x", "{h_x}", "{ma_x}", None, "s_eb & {dens}[W-1]"),
                 ("oa_y", "{h_y}", "{ma_y}", None, "s_eb & {dens}[W-1]"),
                 ("oa_z", "{h_z}", "{ma_z}", None, "s_eb & {dens}[W-1]")]),
    ], []),
]

# The spawn strategies that need a value (hls::Spawn: 0 none, 1 skip-origin, 2 ulp-offset,
# 3 error-bound, 4 skip-offset, 5 skip-slab, 6 skip-back), as a 7-bit mask; a value not named
# here is needed by every strategy. hit.v's parameter SPAWNS (the mask of strategies the unit
# supports) keeps an operator and a carry only if a supported strategy needs it: the rest is not
# built (generate), its wires read zero, and an unsupported strategy_i acts as none. An operator
# may read a value of fewer strategies only where the expression selects it by that strategy
# (ma_*: s_eb ? delta : fixed_i), as the check below allows.
EB, ULPEB, ULP, SLAB, SKIP = 0b0001000, 0b0011100, 0b0010100, 0b1100000, 0b1110010
CLASS = {}
for n in ("t", "at", "and", "nu", "nv", "ok", "ou", "ov", "dk", "du", "dv", "nuou", "nvov",
          "nudu", "nvdv", "tden", "ndok", "e_num", "e_den", "s_x", "s_y", "s_z", "ndhk", "m_x",
          "m_y", "m_z", "nuhu", "nvhv", "c5num", "ated", "c2tden", "x_x", "x_y", "x_z", "c3ted",
          "em1", "e_snum", "b1", "eh1", "em", "c5snum", "eh", "snmv", "c2hit", "b2", "ub", "delta"):
    CLASS[n] = EB
for n in ("sn_x", "sn_y", "sn_z", "ma_x", "ma_y", "ma_z", "oa_x", "oa_y", "oa_z"):
    CLASS[n] = ULPEB
for n in ("ps_x", "ps_y", "ps_z", "q_x", "q_y", "q_z"):
    CLASS[n] = ULP
for n in ("slab", "dmax", "rd", "t0"):
    CLASS[n] = SLAB
CLASS["id"] = SKIP
ALL = 0b1111111
CLS_NAME = {EB: "eb", ULPEB: "ulpeb", ULP: "ulp", SLAB: "slab", SKIP: "skip"}


def cls_name(c):
    return CLS_NAME.get(c, f"s{c}")


def cls(n):
    return CLASS.get(n, ALL)


# Values available at the input (level 0) and their widths (default W).
INPUTS = {"tag": "TAG_BITS", "id": "32", "k": "2", "th": W, "t": W, "at": W, "and": W, "den": W,
          "nu": W, "nv": W, "n_x": W, "n_y": W, "n_z": W, "o_x": W, "o_y": W, "o_z": W,
          "d_x": W, "d_y": W, "d_z": W, "ok": W, "ou": W, "ov": W, "dk": W, "du": W, "dv": W}
# The outputs (expressions at the last level's output).
OUTPUTS = [
    ("out_h_x_o", "{h_x}"), ("out_h_y_o", "{h_y}"), ("out_h_z_o", "{h_z}"),
    ("out_front_o", "{front}"), ("out_spawn_o", "spawn12"), ("out_dens_o", "{dens}"),
    ("out_o_x_o", "!spawn12 ? {h_x} : s_eb ? {oa_x} : !s_ulp ? {h_x} : "
     "{h_x}[W-2:M] < ENEAR ? {oa_x} : {q_x}"),
    ("out_o_y_o", "!spawn12 ? {h_y} : s_eb ? {oa_y} : !s_ulp ? {h_y} : "
     "{h_y}[W-2:M] < ENEAR ? {oa_y} : {q_y}"),
    ("out_o_z_o", "!spawn12 ? {h_z} : s_eb ? {oa_z} : !s_ulp ? {h_z} : "
     "{h_z}[W-2:M] < ENEAR ? {oa_z} : {q_z}"),
    ("out_d_x_o", "{ds_x}"), ("out_d_y_o", "{ds_y}"), ("out_d_z_o", "{ds_z}"),
    ("out_inv_x_o", "{inv_x}"), ("out_inv_y_o", "{inv_y}"), ("out_inv_z_o", "{inv_z}"),
    ("out_tmin_o", "spawn12 && s_slab && flt(tmin_i, {t0}) ? {t0} : tmin_i"),
    ("out_tmax_o", "segment_i ? ONE : {len}"),
    ("out_skip_id_o", "spawn12 && s_skip ? {id} : 32'hFFFF_FFFF"),
    ("out_tag_o", "{tag}"),
]

OPCODE = {"mul": 0, "add": 1, "sub": 1, "add3": 2, "rcp": 3, "sqrt": 4}
NL = len(LEVELS)

produced = {n: 0 for n in INPUTS}
width = dict(INPUTS)
for li, (_, groups, posts) in enumerate(LEVELS, 1):
    for op, items in groups:
        for it in items:
            produced[it[0]] = li
            width[it[0]] = W
    for name, w, _ in posts:
        produced[name] = li
        width[name] = w
last = {}  # value -> the last level at whose output it is needed


def refs(expr):
    return re.findall(r"\{([a-z_0-9]+)\}", expr)


reads = {}  # value -> [(level at whose output it is read, the strategies of the reader)]


def need(name, at, by=ALL):
    if name not in produced:
        raise SystemExit(f"unknown value {name}")
    if at < produced[name]:
        raise SystemExit(f"{name} used at {at} before it is produced at {produced[name]}")
    last[name] = max(last.get(name, 0), at)
    reads.setdefault(name, []).append((at, by & cls(name)))


for li, (_, groups, posts) in enumerate(LEVELS, 1):
    for op, items in groups:
        for it in items:
            for e in it[1:]:
                if e:
                    for n in refs(e):
                        need(n, li - 1, cls(it[0]))
    for name, w, e in posts:
        for n in refs(e):
            need(n, li, cls(name))
for _, e in OUTPUTS:
    for n in refs(e):
        need(n, NL)
need("front", NL)


def carry_cls(n, lvl):
    """The strategies that need value n carried through level lvl (its reads at lvl or later)."""
    c = 0
    for at_, by in reads.get(n, []):
        if at_ >= lvl:
            c |= by
    return c

# Every value an operator or wire reads is built whenever the operator is (or, for a value of
# fewer strategies, shares one with it: the expression selects it by that strategy).
for li, (_, groups, posts) in enumerate(LEVELS, 1):
    items = [it for _, its in groups for it in its] + [(nm, e) for nm, _, e in posts]
    for it in items:
        for e in it[1:]:
            if e and isinstance(e, str):
                for n in refs(e):
                    if cls(it[0]) & cls(n) == 0:
                        raise SystemExit(f"{it[0]} reads {n}, built for no strategy of its own")


def at(name, lvl):
    """The wire holding `name` at the output of level lvl."""
    p = produced[name]
    if lvl == p:
        return name if p > 0 else name + "_0"
    return f"{name}_c{lvl}"


def sub(expr, lvl):
    return re.sub(r"\{([a-z_0-9]+)\}", lambda m: at(m.group(1), lvl), expr)


def carried(lvl):
    """Values carried through level lvl (produced before, needed at its output or later)."""
    return [n for n in produced if produced[n] < lvl and last.get(n, -1) >= lvl]


out = []
w = out.append
import os
QT = sum(lv[0] for lv in LEVELS)
# Registers per STAGES: at STAGES 2 the weights plus hit_unit's registered slot read (QT + 1),
# rounded up to a whole number per STAGES, so every sublevel gets at least its weight.
LPS = (QT + 1 + 1) // 2
head = open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "gen_hit_head.v")).read()
head = head.replace("@LPS@", str(LPS)).replace("@QT@", str(QT)).replace("@LAT2@", str(2 * LPS))
w(head.rstrip("\n") + "\n")
unused = []
v = lambda i: f"v[{i}]"
q = 0
w(f"  // Registers per sublevel: the {LPS} x STAGES - IN_REGS of the latency shared out by the weights of")
w(f"  // scripts/gen_hit.py (the registers each needs for 95 FO4; {QT} in all), cumulatively.")
w(f"  localparam integer R = {LPS} * STAGES - IN_REGS;")
for li, (wt, _, _) in enumerate(LEVELS, 1):
    lo = f"(R * {q}) / {QT}"
    q += wt
    hi = f"(R * {q}) / {QT}"
    w(f"  localparam integer S{li} = {hi} - {lo};  // weight {wt}")
w("")
def use(c):
    """The generate condition of a class of strategies."""
    return f"(SPAWNS & {c}) != 0"


for li, (_, groups, posts) in enumerate(LEVELS, 1):
    stg = f"S{li}"
    w(f"  // ---- sublevel {li} " + "-" * 78)
    cs = carried(li)
    base = [n for n in cs if carry_cls(n, li) == ALL]
    if not base:
        raise SystemExit(f"sublevel {li} carries nothing for every strategy (its handshake)")
    cw = " + ".join(width[n] for n in base)
    w(f"  localparam integer C{li}_W = {cw};")
    for n in cs:
        w(f"  wire [{width[n]}-1:0] {at(n, li)};")
    w(f"  fp_delay #(.WIDTH(C{li}_W), .STAGES({stg}), .FREE(FREE)) u_c{li} (")
    w(f"    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[{li-1}]), .in_ready_o(r[{li}]),")
    w(f"    .in_data_i({{{', '.join(at(n, li - 1) for n in base)}}}),")
    w(f"    .out_valid_o(v[{li}]), .out_ready_i(r[{li+1}]),")
    w(f"    .out_data_o({{{', '.join(at(n, li) for n in base)}}}));")
    # The carries of fewer strategies: one fp_delay per class, built if the class is supported.
    for c in sorted({carry_cls(n, li) for n in cs} - {ALL}):
        part = [n for n in cs if carry_cls(n, li) == c]
        nm = f"c{li}_{cls_name(c)}"
        w(f"  wire {nm}_ur, {nm}_uv;")
        unused += [f"{nm}_ur", f"{nm}_uv"]
        w(f"  generate if ({use(c)}) begin : g_{nm}")
        w(f"    fp_delay #(.WIDTH({' + '.join(width[n] for n in part)}), .STAGES({stg}), .FREE(FREE)) u_{nm} (")
        w(f"      .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[{li-1}]), .in_ready_o({nm}_ur),")
        w(f"      .in_data_i({{{', '.join(at(n, li - 1) for n in part)}}}),")
        w(f"      .out_valid_o({nm}_uv), .out_ready_i(r[{li+1}]),")
        w(f"      .out_data_o({{{', '.join(at(n, li) for n in part)}}}));")
        w(f"  end else begin : g_{nm}_none")
        zw = " + ".join(["2"] + [width[n] for n in part])
        w(f"    assign {{{nm}_ur, {nm}_uv, {', '.join(at(n, li) for n in part)}}} = {{({zw}){{1'b0}}}};")
        w("  end endgenerate")
    for op, all_items in groups:
        for c in sorted({cls(it[0]) for it in all_items}, reverse=True):
            items = [it for it in all_items if cls(it[0]) == c]
            g = f"g{li}_{op}" + (f"_{cls_name(c)}" if c != ALL else "")
            n = len(items)
            a = [sub(it[1], li - 1) for it in items]
            b = [sub(it[2], li - 1) if len(it) > 2 and it[2] else Z for it in items]
            c3 = [sub(it[3], li - 1) if len(it) > 3 and it[3] else Z for it in items]
            s = [sub(it[4], li - 1) if len(it) > 4 and it[4] else ("1'b1" if op == "sub" else "1'b0")
                 for it in items]
            if op == "rcp":  # 1 / x: spawn_ops' divider takes (ONE, x); raycore's table takes x
                b = a
                a = ["ONE"] * n
            w(f"  wire [{n}*W-1:0] {g}_res;")
            w(f"  wire {g}_ur, {g}_uv;")
            unused += [f"{g}_ur", f"{g}_uv"]
            ind = "  "
            if c != ALL:
                w(f"  generate if ({use(c)}) begin : u_{g}_on")
                ind = "    "
            w(f"{ind}spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES({stg}),")
            w(f"{ind}            .OP({OPCODE[op]}), .N({n})) u_{g} (")
            w(f"{ind}  .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[{li-1}]), .in_ready_o({g}_ur),")
            rev = lambda xs: "{" + ", ".join(reversed(xs)) + "}"
            w(f"{ind}  .in_a_i({rev(a)}),")
            w(f"{ind}  .in_b_i({rev(b)}),")
            w(f"{ind}  .in_c_i({rev(c3)}), .in_sub_i({rev(s)}),")
            w(f"{ind}  .out_valid_o({g}_uv), .out_ready_i(r[{li+1}]), .out_res_o({g}_res));")
            if c != ALL:
                w(f"  end else begin : u_{g}_off")
                w(f"    assign {{{g}_ur, {g}_uv, {g}_res}} = {{(2 + {n} * W){{1'b0}}}};")
                w("  end endgenerate")
            for i, it in enumerate(items):
                w(f"  wire [W-1:0] {it[0]} = {g}_res[{i}*W +: W];")
    for name, wd, e in posts:
        w(f"  wire [{wd}-1:0] {name} = {sub(e, li)};")
    w("")
w("  // ---- outputs " + "-" * 84)
w(f"  assign out_valid_o = v[{NL}];")
w(f"  assign r[{NL+1}] = out_ready_i;")
w(f"  wire spawn12 = {at('front', NL)} | all_i;  // a shadow ray: light in front, or every hit")
for o, e in OUTPUTS:
    w(f"  assign {o} = {sub(e, NL)};")
w("")
# Values of fewer strategies, read by nothing where their strategies are not built.
part = [at(n, l) for n in produced
        for l in range(produced[n], max(last.get(n, produced[n]), produced[n]) + 1)
        if cls(n) != ALL or carry_cls(n, l) != ALL]
w("  wire unused_spawns;")
w("  assign unused_spawns = ^{" + ", ".join(part + ["strategy_i", "scale_i", "fixed_i", "slab_scale_i",
                                                  "back_i", "bk_m", "bk_u"]) + "};")
w("  wire unused_hs;")
w("  assign unused_hs = ^{" + ", ".join(unused) + "};")
w("")
w("endmodule")
print("\n".join(out))
