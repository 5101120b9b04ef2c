// trv - the traversal unit's datapath: one ray step per cycle, fully pipelined.
//
// Bit-exact twin of hls::trv_split and hls::trv_clip_box (hls/trv.h), the two arithmetic steps of
// systemc/trv.h's per-ray loop, selected per item by in_op_i:
//   in_op_i = 0 (split, an inner node): tsplit = (split - o[axis]) * inv[axis]; the near child is
//     the one on the origin's side (below: o[axis] < split, or o[axis] == split and d[axis] is
//     negative or zero); visit 0 = first only (tfar < tsplit or !(0 < tsplit)), 1 = second only
//     (tsplit < tnear), 2 = both. The children, first = below ? node+1 : child and second =
//     below ? child : node+1, and the interval update follow systemc/trv.h: the ray goes on to
//     out_node_o (first, or second if visit = 1) with [out_tnear_o, out_tfar_o] = [tnear, tfar],
//     or for visit = 2 [tnear, tsplit], and pushes {out_far_node_o, out_tsplit_o, out_far_tfar_o}
//     = {second, tsplit, tfar}. out_hit_o = 0.
//   in_op_i = 1 (clip, a ray's first step): the slab test of [in_tnear_i, in_tfar_i] = [tmin, tmax]
//     against the box [lo, hi]: out_tnear_o / out_tfar_o = the narrowed interval, out_hit_o =
//     (tnear <= tfar). out_visit_o, out_below_o, out_tsplit_o, out_node_o, out_far_node_o and
//     out_far_tfar_o are don't-care.
// in_axis_i = 3 is not a valid node axis and is treated as 0.
// Interval widening (hls/margins.h): widen_i = N ulps, a per-frame register (static while steps
// are in flight). The split's comparisons see tfar moved N ulps up and tnear N ulps down, the
// clip's hit is !(t1 + N ulps < t0 - N ulps), on the bit patterns (add_ulps below = hls::add_ulps);
// the interval values put out are not widened. N = 0 is the unit without margins.
//
// Levels (the lanes are shared by both operations; every FP operator has STAGES registers and a
// per-level fp_pipe of the same depth carries the values needed later and the tag):
//   1  six subtractions: lo[a] - o[a] and hi[a] - o[a] (split: lane axis computes
//      split - o[axis]); fp_cmp(o[axis], split) for the near child
//   2  six products: (lo[a] - o[a]) * inv[a], (hi[a] - o[a]) * inv[a]  (split: tsplit in lane axis)
//   3  three fp_cmp: clip: th[a] < tl[a] (slab order, swap); split: tfar < tsplit, 0 < tsplit,
//      tsplit < tnear (operand muxes)
//   4  comparator tree (combinational fp_cmp, then STAGES registers): tnear = max(tmin, tl0, tl1,
//      tl2), tfar = min(tmax, th0, th1, th2) as a tree (max/min return the first of equal values,
//      so the tree equals hls' left-to-right chain bit for bit), hit = !(tfar < tnear); the
//      outputs are assembled before the last registers.
// Latency = 4 * STAGES cycles (STAGES = 0: combinational; S1 + S2 + S3 + S4 where the levels'
// registers are given apart), one step per cycle.
//
// Handshake: valid/ready as every rtl/fp operator. The operators of a level receive the same
// in_valid and out_ready and have the same depth, so their registers hold the same valid bits
// (lockstep): the level's carry pipe gives the level's handshake and the operators' own handshake
// outputs are equal copies, left unused. in_ready_o depends combinationally on out_ready_i.
module trv #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer RNE      = 0,
  parameter integer RAYCORE  = 0,   // rounding mode raycore (hls Rounding::raycore; RNE ignored)
  parameter integer STAGES   = 2,
  parameter integer TAG_BITS = 16,
  // Registers after each level (default STAGES each): a caller that needs fewer cycles than
  // 4 x STAGES places its own (trv_unit's split stage: one, after level 1).
  parameter integer S1       = STAGES,
  parameter integer S2       = STAGES,
  parameter integer S3       = STAGES,
  parameter integer S4       = STAGES
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  input  wire [6:0]                 widen_i,     // interval widening in ulps (static)
  input  wire                       in_valid_i,
  output wire                       in_ready_o,
  input  wire                       in_op_i,     // 0 split (inner node), 1 clip (scene box)
  input  wire [1:0]                 in_axis_i,   // split: the node's axis 0..2
  input  wire [EXP_BITS+MAN_BITS:0] in_split_i,  // split: the plane
  input  wire [31:0]                in_node_i,   // split: this node's index
  input  wire [31:0]                in_child_i,  // split: the node's other child (Node::index)
  input  wire [EXP_BITS+MAN_BITS:0] in_o_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_o_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_o_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_d_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_d_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_d_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_inv_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_inv_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_inv_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_tnear_i,  // split: tnear; clip: the ray's tmin
  input  wire [EXP_BITS+MAN_BITS:0] in_tfar_i,   // split: tfar; clip: the ray's tmax
  input  wire [EXP_BITS+MAN_BITS:0] in_lo_x_i,   // clip: the scene box
  input  wire [EXP_BITS+MAN_BITS:0] in_lo_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_lo_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_hi_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_hi_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_hi_z_i,
  input  wire [TAG_BITS-1:0]        in_tag_i,    // sideband (the ray slot), returned
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire                       out_op_o,
  output wire                       out_hit_o,      // clip: tnear <= tfar
  output wire [1:0]                 out_visit_o,    // split: hls::Visit (0 first, 1 second, 2 both)
  output wire                       out_below_o,    // split: the first child is the lower one
  output wire [EXP_BITS+MAN_BITS:0] out_tsplit_o,   // split: distance to the plane
  output wire [EXP_BITS+MAN_BITS:0] out_tnear_o,    // the ray's interval after the step
  output wire [EXP_BITS+MAN_BITS:0] out_tfar_o,
  output wire [31:0]                out_node_o,     // split: the node visited next
  output wire [31:0]                out_far_node_o, // split: the second child (pushed if visit 2)
  output wire [EXP_BITS+MAN_BITS:0] out_far_tfar_o, // split: the pushed entry's tfar
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer E = EXP_BITS;
  localparam integer M = MAN_BITS;
  localparam integer W = 1 + E + M;
  localparam [W-1:0] ZERO = {W{1'b0}};

  // x moved by n ulps on its bit pattern, up (toward +) or down: hls::add_ulps (the magnitude bits
  // plus or minus n; below the smallest normal +0, above the largest magnitude saturated).
  function automatic [W-1:0] add_ulps(input [W-1:0] x, input [6:0] n, input up);
    reg          grow;
    reg [W-1:0]  s;
    begin
      grow = up ^ x[W-1];
      s = grow ? {1'b0, x[W-2:0]} + {{(W-7){1'b0}}, n} : {1'b0, x[W-2:0]} - {{(W-7){1'b0}}, n};
      if (grow && s[W-1])
        add_ulps = {x[W-1], {(W-1){1'b1}}};
      else if (s[W-1] || ~|s[W-2:M])
        add_ulps = ZERO;
      else
        add_ulps = {x[W-1], s[W-2:0]};
    end
  endfunction

  // Level handshakes: v[L] / r[L] = valid / ready at the output of level L (index 0 = the input).
  wire [4:0] v;
  wire [5:1] r;
  assign v[0]       = in_valid_i;
  assign in_ready_o = r[1];

  // ---- input: lane selection -------------------------------------------------------------------
  wire ax1 = (in_axis_i == 2'd1);
  wire ax2 = (in_axis_i == 2'd2);
  wire ax0 = !ax1 && !ax2;  // 0, or 3 treated as 0
  wire split_op = !in_op_i;
  wire [W-1:0] lo_x = (split_op && ax0) ? in_split_i : in_lo_x_i;
  wire [W-1:0] lo_y = (split_op && ax1) ? in_split_i : in_lo_y_i;
  wire [W-1:0] lo_z = (split_op && ax2) ? in_split_i : in_lo_z_i;
  wire [W-1:0] o_ax = ax1 ? in_o_y_i : ax2 ? in_o_z_i : in_o_x_i;
  wire [W-1:0] d_ax = ax1 ? in_d_y_i : ax2 ? in_d_z_i : in_d_x_i;
  // Toward the lower side or along the plane: sign(d) || is_zero(d).
  wire         d_low = d_ax[W-1] | ~|d_ax[W-2:M];
  wire [31:0]  node_p1 = in_node_i + 32'd1;

  // ---- level 1: six differences, the origin's side ---------------------------------------------
  wire         l1_lt, l1_eq;
  wire [W-1:0] l1_unused_min, l1_unused_max;  // not needed (the side is lt/eq)
  wire [6:0]   l1_unused_v, l1_unused_r;
  localparam integer C1_W = TAG_BITS + 3 + 5 * W + 64 + 1;
  wire [TAG_BITS-1:0] c1_tag;
  wire         c1_op, c1_dlow;
  wire [1:0]   c1_axis;
  wire [W-1:0] c1_tnear, c1_tfar, c1_invx, c1_invy, c1_invz;
  wire [31:0]  c1_node_p1, c1_child;
  fp_pipe #(.WIDTH(C1_W), .STAGES(S1)) u_carry1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(r[1]),
    .in_data_i({in_tag_i, in_op_i, in_axis_i, in_tnear_i, in_tfar_i, in_inv_x_i, in_inv_y_i,
                in_inv_z_i, node_p1, in_child_i, d_low}),
    .out_valid_o(v[1]), .out_ready_i(r[2]),
    .out_data_o({c1_tag, c1_op, c1_axis, c1_tnear, c1_tfar, c1_invx, c1_invy, c1_invz,
                 c1_node_p1, c1_child, c1_dlow})
  );
  // Lanes j = 0..5: lo[a] - o[a] (a = x, y, z), then hi[a] - o[a].
  wire [6*W-1:0] l1_a = {in_hi_z_i, in_hi_y_i, in_hi_x_i, lo_z, lo_y, lo_x};
  wire [6*W-1:0] l1_b = {in_o_z_i, in_o_y_i, in_o_x_i, in_o_z_i, in_o_y_i, in_o_x_i};
  wire [6*W-1:0] l1_diff;  // {shz, shy, shx, slz, sly, slx}
  genvar gj;
  generate
    for (gj = 0; gj < 6; gj = gj + 1) begin : g_l1_sub
      fp_op2_nt #(.OP("sub"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S1)) u_sub (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l1_unused_r[gj]),
        .in_a_i(l1_a[gj*W +: W]), .in_b_i(l1_b[gj*W +: W]), .out_valid_o(l1_unused_v[gj]),
        .out_ready_i(r[2]), .out_res_o(l1_diff[gj*W +: W]));
    end
  endgenerate
  fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(S1)) u_l1_side (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l1_unused_r[6]),
    .in_a_i(o_ax), .in_b_i(in_split_i), .out_valid_o(l1_unused_v[6]), .out_ready_i(r[2]),
    .out_lt_o(l1_lt), .out_eq_o(l1_eq), .out_min_o(l1_unused_min), .out_max_o(l1_unused_max));
  wire l1_below = l1_lt | (l1_eq & c1_dlow);

  // ---- level 2: six products (slab distances; split: tsplit in lane axis) ----------------------
  wire [W-1:0] l2_tlx, l2_tly, l2_tlz, l2_thx, l2_thy, l2_thz;
  wire [5:0]   l2_unused_v, l2_unused_r;
  localparam integer C2_W = TAG_BITS + 3 + 2 * W + 64 + 1;
  wire [TAG_BITS-1:0] c2_tag;
  wire         c2_op, c2_below;
  wire [1:0]   c2_axis;
  wire [W-1:0] c2_tnear, c2_tfar;
  wire [31:0]  c2_node_p1, c2_child;
  fp_pipe #(.WIDTH(C2_W), .STAGES(S2)) u_carry2 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[1]), .in_ready_o(r[2]),
    .in_data_i({c1_tag, c1_op, c1_axis, c1_tnear, c1_tfar, c1_node_p1, c1_child, l1_below}),
    .out_valid_o(v[2]), .out_ready_i(r[3]),
    .out_data_o({c2_tag, c2_op, c2_axis, c2_tnear, c2_tfar, c2_node_p1, c2_child, c2_below})
  );
  // Lanes j = 0..5 as level 1's, times inv[a].
  wire [6*W-1:0] l2_b = {c1_invz, c1_invy, c1_invx, c1_invz, c1_invy, c1_invx};
  wire [6*W-1:0] l2_prod;
  assign {l2_thz, l2_thy, l2_thx, l2_tlz, l2_tly, l2_tlx} = l2_prod;
  generate
    for (gj = 0; gj < 6; gj = gj + 1) begin : g_l2_mul
      fp_op2_nt #(.OP("mul"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S2)) u_mul (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[1]), .in_ready_o(l2_unused_r[gj]),
        .in_a_i(l1_diff[gj*W +: W]), .in_b_i(l2_b[gj*W +: W]), .out_valid_o(l2_unused_v[gj]),
        .out_ready_i(r[3]), .out_res_o(l2_prod[gj*W +: W]));
    end
  endgenerate

  // ---- level 3: slab order (clip) or the split decisions ----------------------------------------
  wire         c2_ax1 = (c2_axis == 2'd1);
  wire         c2_ax2 = (c2_axis == 2'd2);
  wire [W-1:0] l2_ts  = c2_ax1 ? l2_tly : c2_ax2 ? l2_tlz : l2_tlx;
  // Comparator j = 0..2: clip: th[j] < tl[j]; split: tfar < tsplit, 0 < tsplit, tsplit < tnear.
  // (tfar and tnear widened by widen_i ulps for the comparisons only.)
  wire [W-1:0] c2_tfar_w  = add_ulps(c2_tfar, widen_i, 1'b1);
  wire [W-1:0] c2_tnear_w = add_ulps(c2_tnear, widen_i, 1'b0);
  wire [3*W-1:0] k_a = c2_op ? l2_prod[3*W +: 3*W] : {l2_ts, ZERO, c2_tfar_w};
  wire [3*W-1:0] k_b = c2_op ? l2_prod[0 +: 3*W] : {c2_tnear_w, l2_ts, l2_ts};
  wire [2:0]   l3_lt;
  wire [2:0]   l3_unused_eq;
  wire [6*W-1:0] l3_unused_mm;  // min/max not needed here
  wire [2:0]   l3_unused_v, l3_unused_r;
  localparam integer C3_W = TAG_BITS + 2 + 9 * W + 64;
  wire [TAG_BITS-1:0] c3_tag;
  wire         c3_op, c3_below;
  wire [W-1:0] c3_tnear, c3_tfar, c3_ts, c3_tlx, c3_tly, c3_tlz, c3_thx, c3_thy, c3_thz;
  wire [31:0]  c3_node_p1, c3_child;
  fp_pipe #(.WIDTH(C3_W), .STAGES(S3)) u_carry3 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(r[3]),
    .in_data_i({c2_tag, c2_op, c2_below, c2_tnear, c2_tfar, l2_ts, l2_tlx, l2_tly, l2_tlz,
                l2_thx, l2_thy, l2_thz, c2_node_p1, c2_child}),
    .out_valid_o(v[3]), .out_ready_i(r[4]),
    .out_data_o({c3_tag, c3_op, c3_below, c3_tnear, c3_tfar, c3_ts, c3_tlx, c3_tly, c3_tlz,
                 c3_thx, c3_thy, c3_thz, c3_node_p1, c3_child})
  );
  generate
    for (gj = 0; gj < 3; gj = gj + 1) begin : g_l3_cmp
      fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(S3)) u_cmp (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(l3_unused_r[gj]),
        .in_a_i(k_a[gj*W +: W]), .in_b_i(k_b[gj*W +: W]), .out_valid_o(l3_unused_v[gj]),
        .out_ready_i(r[4]), .out_lt_o(l3_lt[gj]), .out_eq_o(l3_unused_eq[gj]),
        .out_min_o(l3_unused_mm[2*gj*W +: W]), .out_max_o(l3_unused_mm[(2*gj+1)*W +: W]));
    end
  endgenerate

  // Split: first only if tfar < tsplit or !(0 < tsplit); else second only if tsplit < tnear.
  wire [1:0]   l3_visit = (l3_lt[0] || !l3_lt[1]) ? 2'd0 : l3_lt[2] ? 2'd1 : 2'd2;
  // Clip: each slab's entry and exit in order (swapped if th < tl).
  wire [W-1:0] sl_x = l3_lt[0] ? c3_thx : c3_tlx;
  wire [W-1:0] sh_x = l3_lt[0] ? c3_tlx : c3_thx;
  wire [W-1:0] sl_y = l3_lt[1] ? c3_thy : c3_tly;
  wire [W-1:0] sh_y = l3_lt[1] ? c3_tly : c3_thy;
  wire [W-1:0] sl_z = l3_lt[2] ? c3_thz : c3_tlz;
  wire [W-1:0] sh_z = l3_lt[2] ? c3_tlz : c3_thz;

  // ---- level 4: the comparator tree and the outputs --------------------------------------------
  wire [W-1:0] m01, m23, n01, n23, t0, t1;
  wire         t1_lt_t0;
  wire [W-1:0] t1_unused_min;  // min(t1, t0): not needed
  wire [5:0]   l4_lt, l4_eq;       // the min/max comparators' outcomes (select the widened leaves)
  wire [6:0]   l4_unused_v, l4_unused_r;
  wire         l4_unused_eq;
  wire [7*W-1:0] l4_unused_mm;  // the other of min/max
  fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(0)) u_l4_m01 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(1'b1), .in_ready_o(l4_unused_r[0]),
    .in_a_i(c3_tnear), .in_b_i(sl_x), .out_valid_o(l4_unused_v[0]), .out_ready_i(1'b1),
    .out_lt_o(l4_lt[0]), .out_eq_o(l4_eq[0]), .out_min_o(l4_unused_mm[0*W +: W]),
    .out_max_o(m01));
  fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(0)) u_l4_m23 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(1'b1), .in_ready_o(l4_unused_r[1]),
    .in_a_i(sl_y), .in_b_i(sl_z), .out_valid_o(l4_unused_v[1]), .out_ready_i(1'b1),
    .out_lt_o(l4_lt[1]), .out_eq_o(l4_eq[1]), .out_min_o(l4_unused_mm[1*W +: W]),
    .out_max_o(m23));
  fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(0)) u_l4_t0 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(1'b1), .in_ready_o(l4_unused_r[2]),
    .in_a_i(m01), .in_b_i(m23), .out_valid_o(l4_unused_v[2]), .out_ready_i(1'b1),
    .out_lt_o(l4_lt[2]), .out_eq_o(l4_eq[2]), .out_min_o(l4_unused_mm[2*W +: W]),
    .out_max_o(t0));
  fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(0)) u_l4_n01 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(1'b1), .in_ready_o(l4_unused_r[3]),
    .in_a_i(c3_tfar), .in_b_i(sh_x), .out_valid_o(l4_unused_v[3]), .out_ready_i(1'b1),
    .out_lt_o(l4_lt[3]), .out_eq_o(l4_eq[3]), .out_min_o(n01),
    .out_max_o(l4_unused_mm[3*W +: W]));
  fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(0)) u_l4_n23 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(1'b1), .in_ready_o(l4_unused_r[4]),
    .in_a_i(sh_y), .in_b_i(sh_z), .out_valid_o(l4_unused_v[4]), .out_ready_i(1'b1),
    .out_lt_o(l4_lt[4]), .out_eq_o(l4_eq[4]), .out_min_o(n23),
    .out_max_o(l4_unused_mm[4*W +: W]));
  fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(0)) u_l4_t1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(1'b1), .in_ready_o(l4_unused_r[5]),
    .in_a_i(n01), .in_b_i(n23), .out_valid_o(l4_unused_v[5]), .out_ready_i(1'b1),
    .out_lt_o(l4_lt[5]), .out_eq_o(l4_eq[5]), .out_min_o(t1),
    .out_max_o(l4_unused_mm[5*W +: W]));
  // The hit's operands, tfar N ulps up and tnear N ulps down, widened at the tree's leaves and
  // selected by the tree's own comparisons (max = b if a < b, min = b if b < a): the same muxes
  // with add_ulps applied to each input, so this is add_ulps(t1, N, up) and add_ulps(t0, N, down)
  // bit for bit, with the integer adds beside the comparator tree instead of after it.
  wire [W-1:0] w_sl_x = add_ulps(sl_x, widen_i, 1'b0), w_sl_y = add_ulps(sl_y, widen_i, 1'b0);
  wire [W-1:0] w_sl_z = add_ulps(sl_z, widen_i, 1'b0), w_tn = add_ulps(c3_tnear, widen_i, 1'b0);
  wire [W-1:0] w_sh_x = add_ulps(sh_x, widen_i, 1'b1), w_sh_y = add_ulps(sh_y, widen_i, 1'b1);
  wire [W-1:0] w_sh_z = add_ulps(sh_z, widen_i, 1'b1), w_tf = add_ulps(c3_tfar, widen_i, 1'b1);
  wire [W-1:0] w_m01 = l4_lt[0] ? w_sl_x : w_tn;
  wire [W-1:0] w_m23 = l4_lt[1] ? w_sl_z : w_sl_y;
  wire [W-1:0] w_t0  = l4_lt[2] ? w_m23 : w_m01;
  wire [W-1:0] w_n01 = (!l4_lt[3] && !l4_eq[3]) ? w_sh_x : w_tf;
  wire [W-1:0] w_n23 = (!l4_lt[4] && !l4_eq[4]) ? w_sh_z : w_sh_y;
  wire [W-1:0] w_t1  = (!l4_lt[5] && !l4_eq[5]) ? w_n23 : w_n01;
  fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(0)) u_l4_hit (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(1'b1), .in_ready_o(l4_unused_r[6]),
    .in_a_i(w_t1), .in_b_i(w_t0),
    .out_valid_o(l4_unused_v[6]), .out_ready_i(1'b1),
    .out_lt_o(t1_lt_t0), .out_eq_o(l4_unused_eq), .out_min_o(t1_unused_min),
    .out_max_o(l4_unused_mm[6*W +: W]));

  // Outputs (split: systemc/trv.h's child order and interval update).
  wire         o_hit      = c3_op & ~t1_lt_t0;
  wire [31:0]  o_first    = c3_below ? c3_node_p1 : c3_child;
  wire [31:0]  o_second   = c3_below ? c3_child : c3_node_p1;
  wire [31:0]  o_node     = (l3_visit == 2'd1) ? o_second : o_first;
  wire [W-1:0] o_tnear    = c3_op ? t0 : c3_tnear;
  wire [W-1:0] o_tfar     = c3_op ? t1 : (l3_visit == 2'd2) ? c3_ts : c3_tfar;
  localparam integer C4_W = TAG_BITS + 5 + 4 * W + 64;
  fp_pipe #(.WIDTH(C4_W), .STAGES(S4)) u_carry4 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[3]), .in_ready_o(r[4]),
    .in_data_i({c3_tag, c3_op, o_hit, l3_visit, c3_below, c3_ts, o_tnear, o_tfar, c3_tfar,
                o_node, o_second}),
    .out_valid_o(v[4]), .out_ready_i(r[5]),
    .out_data_o({out_tag_o, out_op_o, out_hit_o, out_visit_o, out_below_o, out_tsplit_o,
                 out_tnear_o, out_tfar_o, out_far_tfar_o, out_node_o, out_far_node_o})
  );
  assign r[5]        = out_ready_i;
  assign out_valid_o = v[4];

  // The operators' handshake outputs equal their level's carry pipe's (lockstep, see header);
  // the level-4 comparators are combinational (their handshake is a wire).
  wire unused_ok;
  assign unused_ok = ^{l1_unused_v, l1_unused_r, l1_unused_min, l1_unused_max, l2_unused_v,
                       l2_unused_r, l3_unused_eq, l3_unused_mm, l3_unused_v, l3_unused_r,
                       l4_unused_eq, l4_eq[2:0], l4_unused_v, l4_unused_r, l4_unused_mm,
                       t1_unused_min};

endmodule
