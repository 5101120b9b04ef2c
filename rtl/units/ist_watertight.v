// ist_watertight - the intersection unit's watertight datapath (--ist watertight): Woop, Benthin
// and Wald's sheared test on a watertight record's vertices (the record: the plane n_u, n_v, n_d,
// then the vertices A, B, C), inside test and t, fully pipelined, one test per cycle.
//
// Bit-exact twin of hls::ist_watertight (hls/ist.h): same operations in the same order, each
// rounded once by the rtl/fp operators, so {exit, t, den} and the key equal the C++ reference's for
// every input. Every level is computed for every test; the exit code is the first failing phase:
//   0 hit, 2 beta (the edge functions' signs differ: outside), 4 sum (det = 0: edge-on, or a
//   degenerate record's equal vertices), 1 distance (not tmin < t < tmax, compared as keys).
// k (the plane's projection axis) selects d_k, d_u, d_v for den (k = 3 as 0); kz = the axis of the
// largest |d| (magnitude bits compared as integers, a zero exponent field as zero; ties to the
// lower axis), kx = kz + 1, ky = kz + 2 (mod 3) select the sheared coordinates.
// NEG (the sign bit alone, -0) is an absent sop term; x ^ NEG = -x.
// The shear and t (ox, oy, px, py, pz, the edge functions, det, T, t) run in the shear format of
// hls::ShearFormat: EXP_BITS 8 / MAN_BITS 23 when MAN_BITS < 23 (FP24's inputs widened exactly by
// widen(): the exponent rebiased, the mantissa shifted left), else the format itself; its rounding
// is RNE's, and rtz for RAYCORE (hls::shear_rounding: raycore's sop truncates as rtz's). t leaves
// as the closest-hit key (hls::KeyFormat: EXP_BITS / the shear's 23 mantissa bits, KW bits): the
// shear format's t with its exponent narrowed (flushed below, saturated above F's range: narrow());
// in_tmax_i is a key, in_tmin_i an F number (widened to a key: {tmin, zeros}); out_t_o = the key's
// top W bits (hls::key_t).
//
// Levels (the operators of a level side by side with the same number of pipeline registers, S1 ..
// S7 below: the level's share of the 18 x STAGES by its logic; a per-level fp_delay of the same
// depth carries the values needed later and the tag):
//    1  den = sop(d_k, -0, n_u, d_u, n_v, d_v) (in the format); ox = sop(-0, -0, dz, o_kx, -dx,
//       o_kz), oy (ky)
//    2  px_j = sop(-ox, -0, dz, P_kx, -dx, P_kz), py_j (ky, -oy); pz_j = P_kz - o_kz (sub) for the
//       vertices j = A, B, C (here, not at level 1: the shear axes' selects fan out less there)
//    3  U = E(B, C), V = E(C, A), W = E(A, B), E(P, Q) = sop(-0, -0, qx, py, -qy, px)
//    4  out = some of U, V, W < 0 and some > 0 (signs and zero tests); det = add3(U, V, W);
//       wc = W * pz_C
//    5  T = sop(wc, -0, U, pz_A, V, pz_B); dd = det * dz; det = 0
//    6  t = T / dd (fp_div: 28 restoring steps for the 23-bit mantissa, two per register)
//    7  the key = narrow(t); lt(tmin, key), lt(key, tmax) (fp_cmp in the key format)
// Latency = 18 * STAGES cycles (STAGES = 0: combinational), one test per cycle.
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
  parameter integer FREE     = 0,   // 1: out_ready_i is 1 whenever out_valid_o (fp_delay's FREE)
  // The key's width (hls::KeyFormat: 1 + EXP_BITS + the shear format's mantissa bits).
  parameter integer KW       = 1 + EXP_BITS + (MAN_BITS < 23 ? 23 : MAN_BITS)
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  input  wire                       in_valid_i,
  output wire                       in_ready_o,
  input  wire [1:0]                 in_k_i,     // the plane's projection axis 0..2
  input  wire [EXP_BITS+MAN_BITS:0] in_nu_i,    // n_u
  input  wire [EXP_BITS+MAN_BITS:0] in_nv_i,    // n_v
  input  wire [EXP_BITS+MAN_BITS:0] in_nd_i,    // n_d (not read: the plane's offset, the hit unit's)
  input  wire [3*(EXP_BITS+MAN_BITS+1)-1:0] in_va_i,  // vertex A: {z, y, x}
  input  wire [3*(EXP_BITS+MAN_BITS+1)-1:0] in_vb_i,  // vertex B
  input  wire [3*(EXP_BITS+MAN_BITS+1)-1:0] in_vc_i,  // vertex C
  input  wire [3*(EXP_BITS+MAN_BITS+1)-1:0] in_o_i,   // ray origin {z, y, x}
  input  wire [3*(EXP_BITS+MAN_BITS+1)-1:0] in_d_i,   // ray direction {z, y, x}
  input  wire [EXP_BITS+MAN_BITS:0] in_tmin_i,
  input  wire [KW-1:0]              in_tmax_i,  // a key
  input  wire [TAG_BITS-1:0]        in_tag_i,   // sideband, returned with the result
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [2:0]                 out_exit_o, // hls::IstExit
  output wire [EXP_BITS+MAN_BITS:0] out_t_o,    // the key's top bits (hls::key_t)
  output wire [KW-1:0]              out_tk_o,   // t as the key
  output wire [EXP_BITS+MAN_BITS:0] out_den_o,
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer E = EXP_BITS;
  localparam integer M = MAN_BITS;
  localparam integer W = 1 + E + M;
  localparam [W-1:0] NEG = {1'b1, {(W-1){1'b0}}};           // -0: an absent term; x ^ NEG = -x
  // The shear format (hls::ShearFormat) and its -0; the key's mantissa bits.
  localparam integer SE = MAN_BITS < 23 ? 8 : EXP_BITS;
  localparam integer SM = MAN_BITS < 23 ? 23 : MAN_BITS;
  localparam integer SW = 1 + SE + SM;
  localparam [SW-1:0] SNEG = {1'b1, {(SW-1){1'b0}}};
  localparam integer KM = KW - 1 - E;  // = SM
  // Registers per level, as ist.v: the levels' weights (the registers each needs at STAGES 2 for
  // 95 FO4: one add, mul or compare 1, an add3 3 (level 4: 4, its multiply beside it), a sop 4, the
  // shear format's divider 14 (fp_div's 28 steps, two per register: 7 registers gave 138.5 FO4);
  // level 7's narrowing and compares 2), cumulated in Q; 36 in all, so the latency is 18 x STAGES.
  localparam integer Q1 = 4, Q2 = 8, Q3 = 12, Q4 = 16, Q5 = 20, Q6 = 34;
  localparam integer S1 = (STAGES * Q1) / 2;
  localparam integer S2 = (STAGES * Q2) / 2 - (STAGES * Q1) / 2;
  localparam integer S3 = (STAGES * Q3) / 2 - (STAGES * Q2) / 2;
  localparam integer S4 = (STAGES * Q4) / 2 - (STAGES * Q3) / 2;
  localparam integer S5 = (STAGES * Q5) / 2 - (STAGES * Q4) / 2;
  localparam integer S6 = (STAGES * Q6) / 2 - (STAGES * Q5) / 2;
  localparam integer S7 = 18 * STAGES - (STAGES * Q6) / 2;

  // Level handshakes: v[L] / r[L] = valid / ready at the output of level L (index 0 = the input).
  wire [7:0] v;
  wire [8:1] r;
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
  // hls::narrow<ShearFormat<F>, KeyFormat<F>, rtz>: the same mantissa, the exponent rebiased from
  // the shear format's bias to F's; below F's smallest normal a signed zero, above its largest
  // binade the largest magnitude with the sign. The identity when SE = E.
  function [KW-1:0] narrow;
    input [SW-1:0] x;
    reg signed [SE+1:0] e;
    begin
      e = $signed({2'b00, x[SM +: SE]}) - $signed(REBIAS[SE+1:0]);
      if (~|x[SM +: SE] || e < 1) narrow = {x[SW-1], {(KW - 1){1'b0}}};
      else if (e > (1 << E) - 1) narrow = {x[SW-1], {(KW - 1){1'b1}}};
      else narrow = {x[SW-1], e[E-1:0], x[0 +: SM]};
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
  wire [W-1:0] dz = pick(in_d_i, kz), ndx = pick(in_d_i, kx) ^ NEG, ndy = pick(in_d_i, ky) ^ NEG;
  wire [W-1:0] o_kx = pick(in_o_i, kx), o_ky = pick(in_o_i, ky), o_kz = pick(in_o_i, kz);
  // Vertex j's sheared axes, {P_kz, P_ky, P_kx} at [3*W*j +: 3*W] (j = 0 A, 1 B, 2 C).
  wire [9*W-1:0] vs = {pick(in_vc_i, kz), pick(in_vc_i, ky), pick(in_vc_i, kx),
                       pick(in_vb_i, kz), pick(in_vb_i, ky), pick(in_vb_i, kx),
                       pick(in_va_i, kz), pick(in_va_i, ky), pick(in_va_i, kx)};
  wire [W-1:0] unused_nd = in_nd_i;

  genvar gj;

  // ---- level 1: den (one sop), the ray's sheared origin -------------------------------------------------
  wire [W-1:0]   l1_den;
  wire [SW-1:0]  l1_ox, l1_oy;
  wire [2:0]     l1_unused_v, l1_unused_r;
  localparam integer C1_W = TAG_BITS + KW + 14 * W;
  wire [TAG_BITS-1:0] c1_tag;
  wire [W-1:0] c1_tmin, c1_dz, c1_ndx, c1_ndy, c1_okz;
  wire [KW-1:0] c1_tmax;
  wire [9*W-1:0] c1_vs;
  fp_delay #(.WIDTH(C1_W), .STAGES(S1), .FREE(FREE)) u_carry1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(r[1]),
    .in_data_i({in_tag_i, in_tmin_i, in_tmax_i, dz, ndx, ndy, o_kz, vs}),
    .out_valid_o(v[1]), .out_ready_i(r[2]),
    .out_data_o({c1_tag, c1_tmin, c1_tmax, c1_dz, c1_ndx, c1_ndy, c1_okz, c1_vs}));
  fp_sop_nt #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S1)) u_l1_den (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l1_unused_r[0]),
    .in_a_i(d_k), .in_b_i(NEG), .in_x1_i(in_nu_i), .in_y1_i(d_u), .in_x2_i(in_nv_i), .in_y2_i(d_v),
    .out_valid_o(l1_unused_v[0]), .out_ready_i(r[2]), .out_res_o(l1_den));
  fp_sop_nt #(.EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S1)) u_l1_ox (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l1_unused_r[1]),
    .in_a_i(SNEG), .in_b_i(SNEG), .in_x1_i(widen(dz)), .in_y1_i(widen(o_kx)), .in_x2_i(widen(ndx)),
    .in_y2_i(widen(o_kz)),
    .out_valid_o(l1_unused_v[1]), .out_ready_i(r[2]), .out_res_o(l1_ox));
  fp_sop_nt #(.EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S1)) u_l1_oy (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l1_unused_r[2]),
    .in_a_i(SNEG), .in_b_i(SNEG), .in_x1_i(widen(dz)), .in_y1_i(widen(o_ky)), .in_x2_i(widen(ndy)),
    .in_y2_i(widen(o_kz)),
    .out_valid_o(l1_unused_v[2]), .out_ready_i(r[2]), .out_res_o(l1_oy));

  // ---- level 2: the vertices' sheared x, y and z --------------------------------------------------
  wire [3*SW-1:0] l2_px, l2_py, l2_pz;  // {C, B, A}
  wire [8:0]     l2_unused_v, l2_unused_r;
  localparam integer C2_W = TAG_BITS + KW + 3 * W;
  wire [TAG_BITS-1:0] c2_tag;
  wire [W-1:0] c2_tmin, c2_den, c2_dz;
  wire [KW-1:0] c2_tmax;
  fp_delay #(.WIDTH(C2_W), .STAGES(S2), .FREE(FREE)) u_carry2 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[1]), .in_ready_o(r[2]),
    .in_data_i({c1_tag, c1_tmin, c1_tmax, l1_den, c1_dz}),
    .out_valid_o(v[2]), .out_ready_i(r[3]),
    .out_data_o({c2_tag, c2_tmin, c2_tmax, c2_den, c2_dz}));
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
      fp_op2_nt #(.OP("sub"), .EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S2)) u_pz (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[1]), .in_ready_o(l2_unused_r[6+gj]),
        .in_a_i(widen(c1_vs[(3*gj+2)*W +: W])), .in_b_i(widen(c1_okz)), .out_valid_o(l2_unused_v[6+gj]),
        .out_ready_i(r[3]), .out_res_o(l2_pz[gj*SW +: SW]));
    end
  endgenerate

  // ---- level 3: the edge functions ------------------------------------------------------------------
  // Edge lane j = 0 U = E(B, C), 1 V = E(C, A), 2 W = E(A, B); E(P, Q) = qx py - qy px.
  wire [3*SW-1:0] l3_e;  // {W, V, U}
  wire [2:0]     l3_unused_v, l3_unused_r;
  localparam integer C3_W = TAG_BITS + KW + 3 * W + 3 * SW;
  wire [TAG_BITS-1:0] c3_tag;
  wire [W-1:0] c3_tmin, c3_den, c3_dz;
  wire [KW-1:0] c3_tmax;
  wire [3*SW-1:0] c3_pz;
  fp_delay #(.WIDTH(C3_W), .STAGES(S3), .FREE(FREE)) u_carry3 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(r[3]),
    .in_data_i({c2_tag, c2_tmin, c2_tmax, c2_den, c2_dz, l2_pz}),
    .out_valid_o(v[3]), .out_ready_i(r[4]),
    .out_data_o({c3_tag, c3_tmin, c3_tmax, c3_den, c3_dz, c3_pz}));
  generate
    for (gj = 0; gj < 3; gj = gj + 1) begin : g_l3_edge
      localparam integer P = (gj + 1) % 3, Q = (gj + 2) % 3;
      fp_sop_nt #(.EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S3)) u_edge (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(l3_unused_r[gj]),
        .in_a_i(SNEG), .in_b_i(SNEG), .in_x1_i(l2_px[Q*SW +: SW]), .in_y1_i(l2_py[P*SW +: SW]),
        .in_x2_i(l2_py[Q*SW +: SW] ^ SNEG), .in_y2_i(l2_px[P*SW +: SW]),
        .out_valid_o(l3_unused_v[gj]), .out_ready_i(r[4]), .out_res_o(l3_e[gj*SW +: SW]));
    end
  endgenerate

  // ---- level 4: the inside test, det, W * pz_C ---------------------------------------------------------
  wire [2:0] l3_nz, l3_neg, l3_pos;  // nonzero (a zero exponent field is zero), < 0, > 0
  generate
    for (gj = 0; gj < 3; gj = gj + 1) begin : g_l4_sign
      assign l3_nz[gj]  = |l3_e[gj*SW + SM +: SE];
      assign l3_neg[gj] = l3_nz[gj] & l3_e[gj*SW + SW - 1];
      assign l3_pos[gj] = l3_nz[gj] & ~l3_e[gj*SW + SW - 1];
    end
  endgenerate
  wire l3_out = (|l3_neg) & (|l3_pos);
  wire [SW-1:0] l4_det, l4_wc;
  wire [1:0]   l4_unused_v, l4_unused_r;
  localparam integer C4_W = TAG_BITS + KW + 3 * W + 4 * SW + 1;
  wire [TAG_BITS-1:0] c4_tag;
  wire [W-1:0] c4_tmin, c4_den, c4_dz;
  wire [KW-1:0] c4_tmax;
  wire [SW-1:0] c4_u, c4_v, c4_pza, c4_pzb;
  wire         c4_out;
  fp_delay #(.WIDTH(C4_W), .STAGES(S4), .FREE(FREE)) u_carry4 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[3]), .in_ready_o(r[4]),
    .in_data_i({c3_tag, c3_tmin, c3_tmax, c3_den, c3_dz, l3_e[0 +: SW], l3_e[SW +: SW],
                c3_pz[0 +: SW], c3_pz[SW +: SW], l3_out}),
    .out_valid_o(v[4]), .out_ready_i(r[5]),
    .out_data_o({c4_tag, c4_tmin, c4_tmax, c4_den, c4_dz, c4_u, c4_v, c4_pza, c4_pzb, c4_out}));
  fp_add3_nt #(.EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S4)) u_l4_det (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[3]), .in_ready_o(l4_unused_r[0]),
    .in_a_i(l3_e[0 +: SW]), .in_b_i(l3_e[SW +: SW]), .in_c_i(l3_e[2*SW +: SW]),
    .out_valid_o(l4_unused_v[0]), .out_ready_i(r[5]), .out_res_o(l4_det));
  fp_op2_nt #(.OP("mul"), .EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S4)) u_l4_wc (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[3]), .in_ready_o(l4_unused_r[1]),
    .in_a_i(l3_e[2*SW +: SW]), .in_b_i(c3_pz[2*SW +: SW]), .out_valid_o(l4_unused_v[1]),
    .out_ready_i(r[5]), .out_res_o(l4_wc));

  // ---- level 5: T, det * dz, det = 0 ---------------------------------------------------------------------
  wire [SW-1:0] l5_t, l5_dd;
  wire [1:0]   l5_unused_v, l5_unused_r;
  wire         l4_dz0 = ~|l4_det[SM +: SE];  // det = 0
  localparam integer C5_W = TAG_BITS + KW + 2 * W + 2;
  wire [TAG_BITS-1:0] c5_tag;
  wire [W-1:0] c5_tmin, c5_den;
  wire [KW-1:0] c5_tmax;
  wire         c5_out, c5_dz0;
  fp_delay #(.WIDTH(C5_W), .STAGES(S5), .FREE(FREE)) u_carry5 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[4]), .in_ready_o(r[5]),
    .in_data_i({c4_tag, c4_tmin, c4_tmax, c4_den, c4_out, l4_dz0}),
    .out_valid_o(v[5]), .out_ready_i(r[6]),
    .out_data_o({c5_tag, c5_tmin, c5_tmax, c5_den, c5_out, c5_dz0}));
  fp_sop_nt #(.EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S5)) u_l5_t (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[4]), .in_ready_o(l5_unused_r[0]),
    .in_a_i(l4_wc), .in_b_i(SNEG), .in_x1_i(c4_u), .in_y1_i(c4_pza), .in_x2_i(c4_v), .in_y2_i(c4_pzb),
    .out_valid_o(l5_unused_v[0]), .out_ready_i(r[6]), .out_res_o(l5_t));
  fp_op2_nt #(.OP("mul"), .EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S5)) u_l5_dd (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[4]), .in_ready_o(l5_unused_r[1]),
    .in_a_i(l4_det), .in_b_i(widen(c4_dz)), .out_valid_o(l5_unused_v[1]),
    .out_ready_i(r[6]), .out_res_o(l5_dd));

  // ---- level 6: t = T / (det dz) ---------------------------------------------------------------------------
  wire [SW-1:0] l6_q;
  wire         l6_unused_v, l6_unused_r;
  localparam integer C6_W = TAG_BITS + KW + 2 * W + 2;
  wire [TAG_BITS-1:0] c6_tag;
  wire [W-1:0] c6_tmin, c6_den;
  wire [KW-1:0] c6_tmax;
  wire         c6_out, c6_dz0;
  fp_delay #(.WIDTH(C6_W), .STAGES(S6), .FREE(FREE)) u_carry6 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[5]), .in_ready_o(r[6]),
    .in_data_i({c5_tag, c5_tmin, c5_tmax, c5_den, c5_out, c5_dz0}),
    .out_valid_o(v[6]), .out_ready_i(r[7]),
    .out_data_o({c6_tag, c6_tmin, c6_tmax, c6_den, c6_out, c6_dz0}));
  fp_op2_nt #(.OP("div"), .EXP_BITS(SE), .MAN_BITS(SM), .RNE(RNE), .RAYCORE(0), .STAGES(S6)) u_l6_div (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[5]), .in_ready_o(l6_unused_r),
    .in_a_i(l5_t), .in_b_i(l5_dd), .out_valid_o(l6_unused_v), .out_ready_i(r[7]), .out_res_o(l6_q));

  // ---- level 7: the key, tmin < key < tmax ----------------------------------------------------------
  wire [KW-1:0] l6_key = narrow(l6_q);
  wire [KW-1:0] l6_tmin = {c6_tmin, {(KW - W){1'b0}}};  // hls::t_key: F's exponent, the mantissa shifted
  wire [1:0]   l7_lt;  // {key < tmax, tmin < key}
  wire [1:0]   l7_unused_v, l7_unused_r, l7_unused_eq;
  wire [4*KW-1:0] l7_unused_mm;
  localparam integer C7_W = TAG_BITS + KW + W + 2;
  wire         c7_out, c7_dz0;
  fp_delay #(.WIDTH(C7_W), .STAGES(S7), .FREE(FREE)) u_carry7 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[6]), .in_ready_o(r[7]),
    .in_data_i({c6_tag, c6_den, l6_key, c6_out, c6_dz0}),
    .out_valid_o(v[7]), .out_ready_i(r[8]),
    .out_data_o({out_tag_o, out_den_o, out_tk_o, c7_out, c7_dz0}));
  wire [2*KW-1:0] l7_ca = {l6_key, l6_tmin};
  wire [2*KW-1:0] l7_cb = {c6_tmax, l6_key};
  generate
    for (gj = 0; gj < 2; gj = gj + 1) begin : g_l7
      fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(KM), .STAGES(S7)) u_lt (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[6]), .in_ready_o(l7_unused_r[gj]),
        .in_a_i(l7_ca[gj*KW +: KW]), .in_b_i(l7_cb[gj*KW +: KW]), .out_valid_o(l7_unused_v[gj]),
        .out_ready_i(r[8]), .out_lt_o(l7_lt[gj]), .out_eq_o(l7_unused_eq[gj]),
        .out_min_o(l7_unused_mm[2*gj*KW +: KW]), .out_max_o(l7_unused_mm[(2*gj+1)*KW +: KW]));
    end
  endgenerate

  assign r[8]        = out_ready_i;
  assign out_valid_o = v[7];
  assign out_t_o     = out_tk_o[KW-1 -: W];  // hls::key_t: the key's top bits
  // The first failing phase, as hls::ist_watertight returns it.
  assign out_exit_o  = c7_out ? 3'd2 : c7_dz0 ? 3'd4 : !(&l7_lt) ? 3'd1 : 3'd0;

  // The operators' handshake outputs equal their level's carry pipe's (lockstep, see ist.v).
  wire unused_hs;
  assign unused_hs = ^{l1_unused_v, l1_unused_r, l2_unused_v, l2_unused_r, l3_unused_v, l3_unused_r,
                       l4_unused_v, l4_unused_r, l5_unused_v, l5_unused_r, l6_unused_v, l6_unused_r,
                       l7_unused_v, l7_unused_r, l7_unused_eq, l7_unused_mm, unused_nd};

endmodule
