// ist_watertight - the intersection unit's watertight datapath (--ist watertight): Wald's
// distance on the record's plane and Woop, Benthin and Wald's sheared inside test on its vertices
// (a watertight record: the plane n_u, n_v, n_d, then the vertices A, B, C), fully pipelined, one
// test per cycle.
//
// Bit-exact twin of hls::ist_watertight (hls/ist.h): same operations in the same order, each
// rounded once by the rtl/fp operators, so {exit, t, den} equal the C++ reference's for every
// input. Every level is computed for every test; the reference's early exits only decide the
// exit code (the first failing phase):
//   0 hit, 1 distance (not tmin < t < tmax), 2 beta (the edge functions' signs differ: outside),
//   4 sum (det = 0: edge-on, or a degenerate record's equal vertices).
// k (the plane's projection axis) selects o_k, o_u, o_v, d_k, d_u, d_v as in ist.v (k = 3 as 0);
// kz = the axis of the largest |d| (magnitude bits compared as integers, a zero exponent field as
// zero; ties to the lower axis), kx = kz + 1, ky = kz + 2 (mod 3) select the sheared coordinates.
// NEG (the sign bit alone, -0) is an absent sop term; x ^ NEG = -x.
// The shear (ox, oy, px, py, the edge functions and det) runs in the shear format of
// hls::ShearFormat: EXP_BITS 8 / MAN_BITS 23 when MAN_BITS < 23 (FP24's inputs widened exactly by
// widen(): the exponent rebiased, the mantissa shifted left), else the format itself; its rounding
// is RNE's, and rtz for RAYCORE (hls::shear_rounding: raycore's sop truncates as rtz's).
//
// Levels (the operators of a level side by side with the same number of pipeline registers, S1 ..
// S5 below: the level's share of the 10 x STAGES by its logic; a per-level fp_pipe of the same
// depth carries the values needed later and the tag):
//    1  den = sop(d_k, -0, n_u, d_u, n_v, d_v), num = sop(n_d, -o_k, -n_u, o_u, -n_v, o_v) (in the
//       format: hls::ist_distance_sop); ox = sop(-0, -0, dz, o_kx, -dx, o_kz), oy (ky)
//    2  px_j = sop(-ox, -0, dz, P_kx, -dx, P_kz), py_j (ky, -oy) for the vertices j = A, B, C
//    3  t = num / den (fp_div; RAYCORE: r = 1 / den by fp_rcp, the table reciprocal); U = E(B, C),
//       V = E(C, A), W = E(A, B), E(P, Q) = sop(-0, -0, qx, py, -qy, px)
//    4  RAYCORE: t = num * r; out = some of U, V, W < 0 and some > 0 (signs and zero tests); det =
//       add3(U, V, W)
//    5  lt(tmin, t), lt(t, tmax) (fp_cmp); det = 0; the exit code is decoded at the output.
// Latency = 10 * STAGES cycles, as ist.v's (STAGES = 0: combinational), one test per cycle.
//
// Handshake: as ist.v's (valid/ready; the operators of a level in lockstep with its carry pipe,
// whose in_ready and out_valid stand for the level; back-pressure stalls the whole chain).
// FREE = 1 (ist_unit, which never holds a result back: out_ready_i 1): the carries' data in
// fp_delay memories instead of a register per stage.
// lint: also FREE=1
module ist_watertight #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer RNE      = 0,
  parameter integer RAYCORE  = 0,   // rounding mode raycore (hls Rounding::raycore; RNE ignored)
  parameter integer STAGES   = 2,
  parameter integer TAG_BITS = 16,
  parameter integer FREE     = 0    // 1: out_ready_i is 1 whenever out_valid_o (fp_delay's FREE)
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  input  wire                       in_valid_i,
  output wire                       in_ready_o,
  input  wire [1:0]                 in_k_i,     // the plane's projection axis 0..2
  input  wire [EXP_BITS+MAN_BITS:0] in_nu_i,    // n_u
  input  wire [EXP_BITS+MAN_BITS:0] in_nv_i,    // n_v
  input  wire [EXP_BITS+MAN_BITS:0] in_nd_i,    // n_d
  input  wire [3*(EXP_BITS+MAN_BITS+1)-1:0] in_va_i,  // vertex A: {z, y, x}
  input  wire [3*(EXP_BITS+MAN_BITS+1)-1:0] in_vb_i,  // vertex B
  input  wire [3*(EXP_BITS+MAN_BITS+1)-1:0] in_vc_i,  // vertex C
  input  wire [3*(EXP_BITS+MAN_BITS+1)-1:0] in_o_i,   // ray origin {z, y, x}
  input  wire [3*(EXP_BITS+MAN_BITS+1)-1:0] in_d_i,   // ray direction {z, y, x}
  input  wire [EXP_BITS+MAN_BITS:0] in_tmin_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_tmax_i,
  input  wire [TAG_BITS-1:0]        in_tag_i,   // sideband, returned with the result
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [2:0]                 out_exit_o, // hls::IstExit
  output wire [EXP_BITS+MAN_BITS:0] out_t_o,
  output wire [EXP_BITS+MAN_BITS:0] out_den_o,
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer E = EXP_BITS;
  localparam integer M = MAN_BITS;
  localparam integer W = 1 + E + M;
  localparam [W-1:0] NEG = {1'b1, {(W-1){1'b0}}};           // -0: an absent term; x ^ NEG = -x
  // The shear format (hls::ShearFormat) and its -0.
  localparam integer SE = MAN_BITS < 23 ? 8 : EXP_BITS;
  localparam integer SM = MAN_BITS < 23 ? 23 : MAN_BITS;
  localparam integer SW = 1 + SE + SM;
  localparam [SW-1:0] SNEG = {1'b1, {(SW-1){1'b0}}};
  // Registers per level, as ist.v: the levels' weights (the registers each needs at STAGES 2 for
  // 95 FO4: one add, mul or compare 1, an add3 3, a sop 4, the divider 7; level 5's compares are
  // given 2, so that the 20 make the latency ist.v's 10 x STAGES), cumulated in Q.
  localparam integer Q1 = 4, Q2 = 8, Q3 = 15, Q4 = 18;
  localparam integer S1 = (STAGES * Q1) / 2;
  localparam integer S2 = (STAGES * Q2) / 2 - (STAGES * Q1) / 2;
  localparam integer S3 = (STAGES * Q3) / 2 - (STAGES * Q2) / 2;
  localparam integer S4 = (STAGES * Q4) / 2 - (STAGES * Q3) / 2;
  localparam integer S5 = 10 * STAGES - (STAGES * Q4) / 2;

  // Level handshakes: v[L] / r[L] = valid / ready at the output of level L (index 0 = the input).
  wire [5:0] v;
  wire [6:1] r;
  assign v[0]       = in_valid_i;
  assign in_ready_o = r[1];

  // ---- operand muxes ------------------------------------------------------------------------------
  function [W-1:0] pick;  // component a (0 x, 1 y, 2 z) of a {z, y, x} vector
    input [3*W-1:0] vec;
    input [1:0] a;
    begin
      pick = a == 2'd2 ? vec[2*W +: W] : (a == 2'd1 ? vec[W +: W] : vec[0 +: W]);
    end
  endfunction
  function [W-2:0] mag;  // a number's magnitude bits as an integer key, a zero exponent field as zero
    input [W-2:0] x;
    begin
      mag = (|x[W-2:M]) ? x : {(W-1){1'b0}};
    end
  endfunction
  // hls::widen<F, ShearFormat<F>>, exact: the exponent rebiased, the mantissa shifted left (the
  // appended bits zero); a zero exponent field stays a zero. The identity when SW = W.
  localparam integer REBIAS = (1 << (SE - 1)) - (1 << (E - 1));
  /* verilator lint_off UNUSEDSIGNAL */  // the locals have one bit more than they give (e's carry, m's pad)
  function [SW-1:0] widen;
    input [W-1:0] x;
    reg [SE:0] e;
    reg [SM:0] m;
    begin
      e = {{(SE + 1 - E){1'b0}}, x[M +: E]} + REBIAS[SE:0];
      m = {x[M-1:0], {(SM - M + 1){1'b0}}};
      widen = (|x[M +: E]) ? {x[W-1], e[SE-1:0], m[SM:1]} : {x[W-1], {(SW - 1){1'b0}}};
    end
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */
  // The plane's axes (k = 3 as 0).
  wire [1:0] pk = in_k_i == 2'd3 ? 2'd0 : in_k_i;
  wire [1:0] pu = pk == 2'd2 ? 2'd0 : pk + 2'd1;
  wire [1:0] pv = pk == 2'd0 ? 2'd2 : pk - 2'd1;
  // The shear axes.
  wire [W-2:0] ax = mag(in_d_i[0 +: W-1]), ay = mag(in_d_i[W +: W-1]), az = mag(in_d_i[2*W +: W-1]);
  // The three compares side by side (not the second after the first's choice): the same kz, one
  // comparator deep ahead of the first sops.
  wire lt_xy = ax < ay, lt_xz = ax < az, lt_yz = ay < az;
  wire [1:0] kz = (lt_xy ? lt_yz : lt_xz) ? 2'd2 : (lt_xy ? 2'd1 : 2'd0);
  wire [1:0] kx = kz == 2'd2 ? 2'd0 : kz + 2'd1;
  wire [1:0] ky = kz == 2'd0 ? 2'd2 : kz - 2'd1;
  wire [W-1:0] d_k = pick(in_d_i, pk), d_u = pick(in_d_i, pu), d_v = pick(in_d_i, pv);
  wire [W-1:0] o_k = pick(in_o_i, pk), o_u = pick(in_o_i, pu), o_v = pick(in_o_i, pv);
  wire [W-1:0] dz = pick(in_d_i, kz), ndx = pick(in_d_i, kx) ^ NEG, ndy = pick(in_d_i, ky) ^ NEG;
  wire [W-1:0] o_kx = pick(in_o_i, kx), o_ky = pick(in_o_i, ky), o_kz = pick(in_o_i, kz);
  // Vertex j's sheared axes, {P_kz, P_ky, P_kx} at [3*W*j +: 3*W] (j = 0 A, 1 B, 2 C).
  wire [9*W-1:0] vs = {pick(in_vc_i, kz), pick(in_vc_i, ky), pick(in_vc_i, kx),
                       pick(in_vb_i, kz), pick(in_vb_i, ky), pick(in_vb_i, kx),
                       pick(in_va_i, kz), pick(in_va_i, ky), pick(in_va_i, kx)};

  genvar gj;

  // ---- level 1: the plane's den and num (one sop each), the ray's sheared origin ------------------
  wire [W-1:0]   l1_den, l1_num;
  wire [SW-1:0]  l1_ox, l1_oy;
  wire [3:0]     l1_unused_v, l1_unused_r;
  localparam integer C1_W = TAG_BITS + 14 * W;
  wire [TAG_BITS-1:0] c1_tag;
  wire [W-1:0] c1_tmin, c1_tmax, c1_dz, c1_ndx, c1_ndy;
  wire [9*W-1:0] c1_vs;
  fp_delay #(.WIDTH(C1_W), .STAGES(S1), .FREE(FREE)) u_carry1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(r[1]),
    .in_data_i({in_tag_i, in_tmin_i, in_tmax_i, dz, ndx, ndy, vs}),
    .out_valid_o(v[1]), .out_ready_i(r[2]),
    .out_data_o({c1_tag, c1_tmin, c1_tmax, c1_dz, c1_ndx, c1_ndy, c1_vs}));
  fp_sop_nt #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S1)) u_l1_den (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l1_unused_r[0]),
    .in_a_i(d_k), .in_b_i(NEG), .in_x1_i(in_nu_i), .in_y1_i(d_u), .in_x2_i(in_nv_i), .in_y2_i(d_v),
    .out_valid_o(l1_unused_v[0]), .out_ready_i(r[2]), .out_res_o(l1_den));
  fp_sop_nt #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S1)) u_l1_num (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l1_unused_r[1]),
    .in_a_i(in_nd_i), .in_b_i(o_k ^ NEG), .in_x1_i(in_nu_i ^ NEG), .in_y1_i(o_u), .in_x2_i(in_nv_i ^ NEG),
    .in_y2_i(o_v), .out_valid_o(l1_unused_v[1]), .out_ready_i(r[2]), .out_res_o(l1_num));
  fp_sop_nt #(.EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S1)) u_l1_ox (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l1_unused_r[2]),
    .in_a_i(SNEG), .in_b_i(SNEG), .in_x1_i(widen(dz)), .in_y1_i(widen(o_kx)), .in_x2_i(widen(ndx)),
    .in_y2_i(widen(o_kz)),
    .out_valid_o(l1_unused_v[2]), .out_ready_i(r[2]), .out_res_o(l1_ox));
  fp_sop_nt #(.EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S1)) u_l1_oy (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l1_unused_r[3]),
    .in_a_i(SNEG), .in_b_i(SNEG), .in_x1_i(widen(dz)), .in_y1_i(widen(o_ky)), .in_x2_i(widen(ndy)),
    .in_y2_i(widen(o_kz)),
    .out_valid_o(l1_unused_v[3]), .out_ready_i(r[2]), .out_res_o(l1_oy));

  // ---- level 2: the vertices' sheared x and y -----------------------------------------------------
  wire [3*SW-1:0] l2_px, l2_py;  // {C, B, A}
  wire [5:0]     l2_unused_v, l2_unused_r;
  localparam integer C2_W = TAG_BITS + 4 * W;
  wire [TAG_BITS-1:0] c2_tag;
  wire [W-1:0] c2_tmin, c2_tmax, c2_den, c2_num;
  fp_delay #(.WIDTH(C2_W), .STAGES(S2), .FREE(FREE)) u_carry2 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[1]), .in_ready_o(r[2]),
    .in_data_i({c1_tag, c1_tmin, c1_tmax, l1_den, l1_num}),
    .out_valid_o(v[2]), .out_ready_i(r[3]),
    .out_data_o({c2_tag, c2_tmin, c2_tmax, c2_den, c2_num}));
  generate
    for (gj = 0; gj < 3; gj = gj + 1) begin : g_l2_shear
      fp_sop_nt #(.EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S2)) u_px (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[1]), .in_ready_o(l2_unused_r[2*gj]),
        .in_a_i(l1_ox ^ SNEG), .in_b_i(SNEG), .in_x1_i(widen(c1_dz)), .in_y1_i(widen(c1_vs[(3*gj)*W +: W])),
        .in_x2_i(widen(c1_ndx)), .in_y2_i(widen(c1_vs[(3*gj+2)*W +: W])),
        .out_valid_o(l2_unused_v[2*gj]), .out_ready_i(r[3]), .out_res_o(l2_px[gj*SW +: SW]));
      fp_sop_nt #(.EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S2)) u_py (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[1]), .in_ready_o(l2_unused_r[1+2*gj]),
        .in_a_i(l1_oy ^ SNEG), .in_b_i(SNEG), .in_x1_i(widen(c1_dz)), .in_y1_i(widen(c1_vs[(3*gj+1)*W +: W])),
        .in_x2_i(widen(c1_ndy)), .in_y2_i(widen(c1_vs[(3*gj+2)*W +: W])),
        .out_valid_o(l2_unused_v[1+2*gj]), .out_ready_i(r[3]), .out_res_o(l2_py[gj*SW +: SW]));
    end
  endgenerate

  // ---- level 3: t = num / den (raycore: 1 / den), the edge functions -------------------------------
  // Edge lane j = 0 U = E(B, C), 1 V = E(C, A), 2 W = E(A, B); E(P, Q) = qx py - qy px.
  wire [W-1:0]   l3_q;  // rtz, rne: t; raycore: the table reciprocal of den
  wire [3*SW-1:0] l3_e;  // {W, V, U}
  wire [3:0]     l3_unused_v, l3_unused_r;
  localparam integer C3_W = TAG_BITS + 4 * W;
  wire [TAG_BITS-1:0] c3_tag;
  wire [W-1:0] c3_tmin, c3_tmax, c3_den, c3_num;
  fp_delay #(.WIDTH(C3_W), .STAGES(S3), .FREE(FREE)) u_carry3 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(r[3]),
    .in_data_i({c2_tag, c2_tmin, c2_tmax, c2_den, c2_num}),
    .out_valid_o(v[3]), .out_ready_i(r[4]),
    .out_data_o({c3_tag, c3_tmin, c3_tmax, c3_den, c3_num}));
  generate
    if (RAYCORE != 0) begin : g_rcp_table  // raycore: the table reciprocal (hls::div<F, raycore>)
      wire unused_tag;
      fp_rcp #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(S3)) u_l3_rcp (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(l3_unused_r[0]),
        .in_a_i(c2_den), .in_tag_i(1'b0), .out_valid_o(l3_unused_v[0]),
        .out_ready_i(r[4]), .out_res_o(l3_q), .out_tag_o(unused_tag));
    end else begin : g_div  // rtz, rne: num / den, rounded once
      fp_op2_nt #(.OP("div"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .STAGES(S3)) u_l3_div (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(l3_unused_r[0]),
        .in_a_i(c2_num), .in_b_i(c2_den), .out_valid_o(l3_unused_v[0]),
        .out_ready_i(r[4]), .out_res_o(l3_q));
    end
    for (gj = 0; gj < 3; gj = gj + 1) begin : g_l3_edge
      localparam integer P = (gj + 1) % 3, Q = (gj + 2) % 3;
      fp_sop_nt #(.EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S3)) u_edge (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(l3_unused_r[1+gj]),
        .in_a_i(SNEG), .in_b_i(SNEG), .in_x1_i(l2_px[Q*SW +: SW]), .in_y1_i(l2_py[P*SW +: SW]),
        .in_x2_i(l2_py[Q*SW +: SW] ^ SNEG), .in_y2_i(l2_px[P*SW +: SW]),
        .out_valid_o(l3_unused_v[1+gj]), .out_ready_i(r[4]), .out_res_o(l3_e[gj*SW +: SW]));
    end
  endgenerate

  // ---- level 4: t, the inside test, det -------------------------------------------------------------
  wire [2:0] l3_nz, l3_neg, l3_pos;  // nonzero (a zero exponent field is zero), < 0, > 0
  generate
    for (gj = 0; gj < 3; gj = gj + 1) begin : g_l4_sign
      assign l3_nz[gj]  = |l3_e[gj*SW + SM +: SE];
      assign l3_neg[gj] = l3_nz[gj] & l3_e[gj*SW + SW - 1];
      assign l3_pos[gj] = l3_nz[gj] & ~l3_e[gj*SW + SW - 1];
    end
  endgenerate
  wire l3_out = (|l3_neg) & (|l3_pos);
  wire [W-1:0] l4_t;
  wire [SW-1:0] l4_det;
  wire [1:0]   l4_unused_v, l4_unused_r;
  localparam integer C4_W = TAG_BITS + 4 * W + 1;
  wire [TAG_BITS-1:0] c4_tag;
  wire [W-1:0] c4_tmin, c4_tmax, c4_den, c4_q;
  wire         c4_out;
  fp_delay #(.WIDTH(C4_W), .STAGES(S4), .FREE(FREE)) u_carry4 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[3]), .in_ready_o(r[4]),
    .in_data_i({c3_tag, c3_tmin, c3_tmax, c3_den, l3_q, l3_out}),
    .out_valid_o(v[4]), .out_ready_i(r[5]),
    .out_data_o({c4_tag, c4_tmin, c4_tmax, c4_den, c4_q, c4_out}));
  wire [W-1:0] unused_q;  // the carried quotient (raycore: its t is the multiply's), or num (rtz, rne)
  generate
    if (RAYCORE != 0) begin : g_t_mul  // raycore: t = num x the table reciprocal (hls::div<F, raycore>)
      fp_op2_nt #(.OP("mul"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S4)) u_l4_t (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[3]), .in_ready_o(l4_unused_r[0]),
        .in_a_i(c3_num), .in_b_i(l3_q), .out_valid_o(l4_unused_v[0]), .out_ready_i(r[5]), .out_res_o(l4_t));
      assign unused_q = c4_q;
    end else begin : g_t_carried  // rtz, rne: t from level 3, carried
      assign l4_t = c4_q;
      assign l4_unused_v[0] = 1'b0;
      assign l4_unused_r[0] = 1'b0;
      assign unused_q = c3_num;
    end
  endgenerate
  fp_add3_nt #(.EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S4)) u_l4_det (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[3]), .in_ready_o(l4_unused_r[1]),
    .in_a_i(l3_e[0 +: SW]), .in_b_i(l3_e[SW +: SW]), .in_c_i(l3_e[2*SW +: SW]),
    .out_valid_o(l4_unused_v[1]), .out_ready_i(r[5]), .out_res_o(l4_det));

  // ---- level 5: tmin < t < tmax ----------------------------------------------------------------------
  wire         l4_dz0 = ~|l4_det[SM +: SE];  // det = 0
  wire [1:0]   l5_lt;  // {t < tmax, tmin < t}
  wire [1:0]   l5_unused_v, l5_unused_r, l5_unused_eq;
  wire [4*W-1:0] l5_unused_mm;
  wire [SW-1:0] unused_det_rest = l4_det;  // only its exponent field is read
  localparam integer C5_W = TAG_BITS + 2 * W + 2;
  wire         c5_out, c5_dz0;
  fp_delay #(.WIDTH(C5_W), .STAGES(S5), .FREE(FREE)) u_carry5 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[4]), .in_ready_o(r[5]),
    .in_data_i({c4_tag, c4_den, l4_t, c4_out, l4_dz0}),
    .out_valid_o(v[5]), .out_ready_i(r[6]),
    .out_data_o({out_tag_o, out_den_o, out_t_o, c5_out, c5_dz0}));
  wire [2*W-1:0] l5_ca = {l4_t, c4_tmin};
  wire [2*W-1:0] l5_cb = {c4_tmax, l4_t};
  generate
    for (gj = 0; gj < 2; gj = gj + 1) begin : g_l5
      fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(S5)) u_lt (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[4]), .in_ready_o(l5_unused_r[gj]),
        .in_a_i(l5_ca[gj*W +: W]), .in_b_i(l5_cb[gj*W +: W]), .out_valid_o(l5_unused_v[gj]),
        .out_ready_i(r[6]), .out_lt_o(l5_lt[gj]), .out_eq_o(l5_unused_eq[gj]),
        .out_min_o(l5_unused_mm[2*gj*W +: W]), .out_max_o(l5_unused_mm[(2*gj+1)*W +: W]));
    end
  endgenerate

  assign r[6]        = out_ready_i;
  assign out_valid_o = v[5];
  // The first failing phase, as hls::ist_watertight returns it.
  assign out_exit_o  = !(&l5_lt) ? 3'd1 : c5_out ? 3'd2 : c5_dz0 ? 3'd4 : 3'd0;

  // The operators' handshake outputs equal their level's carry pipe's (lockstep, see ist.v).
  wire unused_hs;
  assign unused_hs = ^{l1_unused_v, l1_unused_r, l2_unused_v, l2_unused_r, l3_unused_v, l3_unused_r,
                       l4_unused_v, l4_unused_r, l5_unused_v, l5_unused_r, l5_unused_eq, l5_unused_mm,
                       unused_det_rest, unused_q};

endmodule
