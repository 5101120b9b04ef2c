// spawn - what a shadow-ray spawn strategy adds to the hit unit (hls::hit_shadow, hls/hit.h), for
// the sweep's added-hardware figures (scripts/sweep_area.sh, docs/sweep.md). STRATEGY selects:
//
//   0 none         nothing: the origin is the hit point (a wire; 0 cells)
//   1 skip-origin  the shadow ray's skip id (the triangle's id, or all ones when no ray is spawned)
//                  and the ist's per-test comparison of a candidate id with the ray's skip id
//   2 ulp-offset   per coordinate: |h_i| < 2^-5 (exponent compare), the offset scale * n_i
//                  (fp_mul) converted to an integer (truncating shifter) and added to h_i's bit
//                  pattern with the format's saturation; near zero h_i + fixed * n_i (fp_mul,
//                  fp_add). For the k axis n_k = 1: no multiplier. 4 fp_mul + 3 fp_add.
//   3 error-bound  the bound of hls::hit_shadow's error_bound case (see there) and the move along
//                  the normal: 15 fp_mul + 9 fp_add + 7 fp_add3 in 8 operator levels; the products
//                  t * d_i come from the hit-point computation (inputs), the scalings by 2 and by
//                  the unit roundoff are exponent adds (exact, with the format's saturation/flush).
//   4 skip-offset  1 and 2 together.
//   5 skip-slab    1, and t_min raised to slab / max(|dens|, 1/16) (hls::detail::slab_tmin):
//                  max |h_i| (integer compares), its ulp (exponent subtract), slab = scale *
//                  ulp (fp_mul; in_scale_i = 2 * ulps), 1 / max(|dens|, 1/16) (fp_div), their
//                  product (fp_mul), the larger of it and in_tmin_i (integer compare: both >= 0).
//   6 skip-back    5, and t backed off by in_back_i ulps on its bit pattern (a saturating
//                  subtract, out_t_back_o) before the hit unit's own hit-point multiply-adds.
//
// The same operator count and data flow as the hls function, not a bit-exact twin: three-term
// sums that hls adds in two steps (e_hit, e_move) are one fp_add3 here, so results may differ in
// the last place. It exists to be synthesised (area) and linted; STRATEGY 5 and 6, whose data flow
// is exactly hls's (no fused sums), are checked bit for bit under Icarus Verilog against
// hls::detail::slab_tmin / add_ulps (tb/sweep/tb_spawn_slab.v, ctest RtlIcarus.spawn_s{5,6}_*:
// FP24/FP32 x rtz/rne, random gaps and back-pressure). 1-4 are not simulated.
// Handshake: valid/ready with fp_pipe's stall rule; latency 0 (STRATEGY 0, 1), 2 * STAGES (2, 4,
// 5, 6), 8 * STAGES (3). Inputs a strategy does not need are ignored. Side paths without latency
// (the id travels with the ray in the hit unit's own record): out_skip_id_o and out_cand_skip_o
// (the ist's comparison) follow the inputs of the same cycle, out_t_back_o is computed before the
// hit point (in_h_*_i are the hit point of the backed-off t), and in_tmin_i is the configured
// constant (passed through by every strategy but 5 and 6).
module spawn #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer RNE      = 0,
  parameter integer RAYCORE  = 0,   // rounding mode raycore (hls Rounding::raycore; RNE ignored)
  parameter integer STAGES   = 2,
  parameter integer TAG_BITS = 1,
  parameter integer STRATEGY = 3
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  input  wire                       in_valid_i,
  output wire                       in_ready_o,
  input  wire [1:0]                 in_k_i,        // projection axis of the hit triangle
  input  wire                       in_front_i,    // the light is in front
  input  wire                       in_all_i,      // --shadow-spawn all: a ray for every hit
  input  wire                       in_side_neg_i, // move along -n (sign of n . d_shadow)
  input  wire [31:0]                in_id_i,       // the hit triangle's id
  input  wire [EXP_BITS+MAN_BITS:0] in_h_x_i,      // hit point
  input  wire [EXP_BITS+MAN_BITS:0] in_h_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_h_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_n_u_i,      // plane: x_k + n_u x_u + n_v x_v = n_d
  input  wire [EXP_BITS+MAN_BITS:0] in_n_v_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_n_d_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_o_x_i,      // primary ray origin
  input  wire [EXP_BITS+MAN_BITS:0] in_o_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_o_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_d_x_i,      // primary ray direction
  input  wire [EXP_BITS+MAN_BITS:0] in_d_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_d_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_td_x_i,     // t * d_i (from the hit point's products)
  input  wire [EXP_BITS+MAN_BITS:0] in_td_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_td_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_t_i,        // primary hit distance
  input  wire [EXP_BITS+MAN_BITS:0] in_den_i,      // n . d of the primary ray (from the ist)
  input  wire [EXP_BITS+MAN_BITS:0] in_scale_i,    // ulp-offset: the ulps as a number
  input  wire [EXP_BITS+MAN_BITS:0] in_fixed_i,    // ulp-offset: ulps * ulp(2^-5)
  input  wire [31:0]                in_cand_id_i,  // skip-origin: a candidate triangle (ist)
  input  wire [31:0]                in_ray_skip_i, //   and the skip id of the ray it is tested for
  input  wire [EXP_BITS+MAN_BITS:0] in_dens_i,     // skip-slab: n . d of the shadow ray
  input  wire [EXP_BITS+MAN_BITS:0] in_tmin_i,     // the configured t_min (>= 0)
  input  wire [31:0]                in_back_i,     // skip-back: the back-off in ulps of t
  input  wire [TAG_BITS-1:0]        in_tag_i,
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [EXP_BITS+MAN_BITS:0] out_o_x_o,     // shadow-ray origin
  output wire [EXP_BITS+MAN_BITS:0] out_o_y_o,
  output wire [EXP_BITS+MAN_BITS:0] out_o_z_o,
  output wire [31:0]                out_skip_id_o, // skip-origin: the ray's skip id, else all ones
  output wire                       out_cand_skip_o, // skip-origin: in_cand_id_i == in_ray_skip_i
  output wire [EXP_BITS+MAN_BITS:0] out_tmin_o,    // the shadow ray's t_min
  output wire [EXP_BITS+MAN_BITS:0] out_t_back_o,  // skip-back: t for the hit point, else in_t_i
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer E    = EXP_BITS;
  localparam integer M    = MAN_BITS;
  localparam integer W    = 1 + E + M;
  localparam integer BIAS = (1 << (E - 1)) - 1;

  // ---- helpers ----------------------------------------------------------------------------------
  function [W-1:0] fabs;
    input [W-1:0] x;
    fabs = x & {1'b0, {(W-1){1'b1}}};
  endfunction
  function [W-1:0] fneg;
    input [W-1:0] x;
    fneg = {~x[W-1], x[W-2:0]};
  endfunction
  // x * 2^s, exact: an exponent add with the format's saturation and flush to zero.
  function [W-1:0] scale2;
    input [W-1:0] x;
    input integer s;
    integer e;
    begin
      e = {{(32-E){1'b0}}, x[W-2:M]} + s;
      if (x[W-2:M] == {E{1'b0}})  scale2 = x;
      else if (e > (1 << E) - 1)  scale2 = {x[W-1], {(W-1){1'b1}}};
      else if (e < 1)             scale2 = {x[W-1], {(W-1){1'b0}}};
      else                        scale2 = {x[W-1], e[E-1:0], x[M-1:0]};
    end
  endfunction

  // Coordinates in the triangle's (k, u, v) order: u = (k+1)%3, v = (k+2)%3 (k = 3 as k = 0).
  reg [W-1:0] hk, hu, hv, ok, ou, ov, dk, du, dv, tk, tu, tv;
  always @* begin
    case (in_k_i)
      2'd1: begin
        hk = in_h_y_i;  hu = in_h_z_i;  hv = in_h_x_i;  ok = in_o_y_i;  ou = in_o_z_i;  ov = in_o_x_i;
        dk = in_d_y_i;  du = in_d_z_i;  dv = in_d_x_i;  tk = in_td_y_i; tu = in_td_z_i; tv = in_td_x_i;
      end
      2'd2: begin
        hk = in_h_z_i;  hu = in_h_x_i;  hv = in_h_y_i;  ok = in_o_z_i;  ou = in_o_x_i;  ov = in_o_y_i;
        dk = in_d_z_i;  du = in_d_x_i;  dv = in_d_y_i;  tk = in_td_z_i; tu = in_td_x_i; tv = in_td_y_i;
      end
      default: begin
        hk = in_h_x_i;  hu = in_h_y_i;  hv = in_h_z_i;  ok = in_o_x_i;  ou = in_o_y_i;  ov = in_o_z_i;
        dk = in_d_x_i;  du = in_d_y_i;  dv = in_d_z_i;  tk = in_td_x_i; tu = in_td_y_i; tv = in_td_z_i;
      end
    endcase
  end

  // ulp-offset: p's bit pattern moved by to_int_rtz(off) ulps (hls::detail::add_ulps).
  // Zero, or below one: 0; 2^31 and above: +-(2^31 - 1).
  function [31:0] to_int_mag;  // |to_int_rtz(x)|
    input [W-1:0] x;
    integer ex;
    reg [63:0] sig;
    reg unused_sign;  // the magnitude only
    begin
      unused_sign = x[W-1];
      ex = {{(32-E){1'b0}}, x[W-2:M]} - BIAS;
      sig = {{(63-M){1'b0}}, 1'b1, x[M-1:0]};
      if (x[W-2:M] == {E{1'b0}} || ex < 0) to_int_mag = 32'd0;
      else if (ex >= 31)                     to_int_mag = 32'h7FFF_FFFF;
      else begin
        sig = (sig << ex) >> M;
        to_int_mag = sig[31:0];
      end
    end
  endfunction
  function [W-1:0] add_ulps;
    input [W-1:0] p;
    input [W-1:0] off;  // the offset as a number; its integer part in ulps
    reg [33:0] mag, d, m;
    reg        down;
    begin
      mag  = {{(34-(W-1)){1'b0}}, p[W-2:0]};
      d    = {2'b00, to_int_mag(off)};
      down = off[W-1] != p[W-1];  // toward zero when the offset and p differ in sign
      m    = down ? mag - d : mag + d;
      if (down && d > mag)                                  add_ulps = {W{1'b0}};
      else if (m < (34'd1 << M))                            add_ulps = {W{1'b0}};
      else if (m > {{(34-(W-1)){1'b0}}, {(W-1){1'b1}}})    add_ulps = {p[W-1], {(W-1){1'b1}}};
      else                                                  add_ulps = {p[W-1], m[W-2:0]};
    end
  endfunction

  // (k, u, v) order back to (x, y, z).
  function [3*W-1:0] unpermute;  // {z, y, x}
    input [1:0] k;
    input [W-1:0] ck, cu, cv;
    case (k)
      2'd1:    unpermute = {cu, ck, cv};
      2'd2:    unpermute = {ck, cv, cu};
      default: unpermute = {cv, cu, ck};
    endcase
  endfunction

  generate
    if (STRATEGY == 0 || STRATEGY == 1) begin : g_wire
      // ---- none / skip-origin: no arithmetic ---------------------------------------------------
      assign in_ready_o  = out_ready_i;
      assign out_valid_o = in_valid_i;
      assign {out_o_z_o, out_o_y_o, out_o_x_o} = {in_h_z_i, in_h_y_i, in_h_x_i};
      assign out_tag_o = in_tag_i;
      assign out_tmin_o = in_tmin_i;
      wire unused_in;
      assign unused_in = ^{clk_i, rst_ni, in_k_i, in_side_neg_i, in_n_u_i, in_n_v_i, in_n_d_i,
                           in_o_x_i, in_o_y_i, in_o_z_i, in_d_x_i, in_d_y_i, in_d_z_i, in_td_x_i,
                           in_td_y_i, in_td_z_i, in_t_i, in_den_i, in_scale_i, in_fixed_i,
                           hk, hu, hv, ok, ou, ov, dk, du, dv, tk, tu, tv,
                           in_front_i, in_all_i, in_id_i, in_cand_id_i, in_ray_skip_i, in_dens_i};

    end else if (STRATEGY == 2 || STRATEGY == 4) begin : g_ulp
      // ---- ulp-offset ----------------------------------------------------------------------------
      // Offset direction: n or -n; n = (1, n_u, n_v) in (k, u, v) order.
      wire [W-1:0] nu = in_side_neg_i ? fneg(in_n_u_i) : in_n_u_i;
      wire [W-1:0] nv = in_side_neg_i ? fneg(in_n_v_i) : in_n_v_i;
      wire [W-1:0] pk = in_side_neg_i ? fneg(in_scale_i) : in_scale_i;  // scale * n_k
      wire [W-1:0] fk = in_side_neg_i ? fneg(in_fixed_i) : in_fixed_i;  // fixed * n_k
      // |h| < 2^-5: the exponent field below BIAS - 5.
      localparam integer ENEAR = BIAS - 5;
      wire nk = hk[W-2:M] < ENEAR[E-1:0], nu_near = hu[W-2:M] < ENEAR[E-1:0],
           nv_near = hv[W-2:M] < ENEAR[E-1:0];
      // L1: scale * n_u, scale * n_v, fixed * n_u, fixed * n_v.
      localparam integer S1 = TAG_BITS + 2 + 3 + 5 * W;
      wire [4*W-1:0] l1_res;
      wire           l1_valid, l2_ready, unused_s1_rdy, unused_s1_vld;
      wire [S1-1:0]  s1;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(0), .N(4)) u_l1 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
        .in_a_i({in_fixed_i, in_fixed_i, in_scale_i, in_scale_i}), .in_b_i({nv, nu, nv, nu}),
        .in_c_i({4*W{1'b0}}), .in_sub_i(4'b0), .out_valid_o(l1_valid), .out_ready_i(l2_ready),
        .out_res_o(l1_res)
      );
      fp_pipe #(.WIDTH(S1), .STAGES(STAGES)) u_s1 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(unused_s1_rdy),
        .in_data_i({in_tag_i, in_k_i, nk, nu_near, nv_near, fk, pk, hv, hu, hk}),
        .out_valid_o(unused_s1_vld), .out_ready_i(l2_ready), .out_data_o(s1)
      );
      wire [W-1:0] s1_hk = s1[0 +: W], s1_hu = s1[W +: W], s1_hv = s1[2*W +: W];
      wire [W-1:0] s1_pk = s1[3*W +: W], s1_fk = s1[4*W +: W];
      wire [2:0]   s1_near = s1[5*W +: 3];  // {k, u, v}
      wire [TAG_BITS+1:0] s1_tk = s1[5*W+3 +: TAG_BITS+2];
      wire [W-1:0] p_u = l1_res[0 +: W], p_v = l1_res[W +: W], f_u = l1_res[2*W +: W],
                   f_v = l1_res[3*W +: W];
      // Away from zero: h_i's bit pattern moved by to_int_rtz(scale * n_i) ulps (add_ulps).
      wire [W-1:0] q_k = add_ulps(s1_hk, s1_pk), q_u = add_ulps(s1_hu, p_u), q_v = add_ulps(s1_hv, p_v);
      // L2: h_i + fixed * n_i (used near zero).
      localparam integer S2 = TAG_BITS + 2 + 3 + 3 * W;
      wire [3*W-1:0] l2_res;
      wire           unused_s2_rdy, unused_s2_vld;
      wire [S2-1:0]  s2;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(1), .N(3)) u_l2 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(l1_valid), .in_ready_o(l2_ready),
        .in_a_i({s1_hv, s1_hu, s1_hk}), .in_b_i({f_v, f_u, s1_fk}), .in_c_i({3*W{1'b0}}),
        .in_sub_i(3'b0), .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_res_o(l2_res)
      );
      fp_pipe #(.WIDTH(S2), .STAGES(STAGES)) u_s2 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(l1_valid), .in_ready_o(unused_s2_rdy),
        .in_data_i({s1_tk, s1_near, q_v, q_u, q_k}), .out_valid_o(unused_s2_vld),
        .out_ready_i(out_ready_i), .out_data_o(s2)
      );
      wire [2:0] near = s2[3*W +: 3];
      wire [1:0] k2   = s2[3*W+3 +: 2];
      wire [W-1:0] o_k = near[2] ? l2_res[0 +: W] : s2[0 +: W];
      wire [W-1:0] o_u = near[1] ? l2_res[W +: W] : s2[W +: W];
      wire [W-1:0] o_v = near[0] ? l2_res[2*W +: W] : s2[2*W +: W];
      assign {out_o_z_o, out_o_y_o, out_o_x_o} = unpermute(k2, o_k, o_u, o_v);
      assign out_tag_o       = s2[S2-1 -: TAG_BITS];
      assign out_tmin_o      = in_tmin_i;
      wire unused_in;
      assign unused_in = ^{unused_s1_rdy, unused_s1_vld, unused_s2_rdy, unused_s2_vld, in_n_d_i,
                           ok, ou, ov, dk, du, dv, tk, tu, tv, in_t_i, in_den_i, in_front_i, in_all_i,
                           in_id_i, in_cand_id_i, in_ray_skip_i, in_dens_i};

    end else if (STRATEGY == 5 || STRATEGY == 6) begin : g_slab
      // ---- skip-slab / skip-back: t_min' = scale ulp(max |h_i|) / max(|dens|, 1/16) -------------
      // ulp(max |h_i|) depends on the largest exponent field only.
      wire [E-1:0] ex = in_h_x_i[W-2:M], ey = in_h_y_i[W-2:M], ez = in_h_z_i[W-2:M];
      wire [E-1:0] exy = ex > ey ? ex : ey;
      wire [E-1:0] he  = exy > ez ? exy : ez;
      localparam [31:0] M32 = M;
      localparam [E-1:0] ME = M32[E-1:0];
      localparam integer BIASM4 = BIAS - 4;
      localparam [W-1:0] ONE = {1'b0, BIAS[E-1:0], {M{1'b0}}};
      localparam [W-1:0] SIXTEENTH = {1'b0, BIASM4[E-1:0], {M{1'b0}}};
      // ulp(hmax) (hls::ulp): zero -> the smallest normal, 2^(e - M) when normal, else 0.
      wire [W-1:0] uh = he == {E{1'b0}} ? {1'b0, {(E-1){1'b0}}, 1'b1, {M{1'b0}}}
                      : he > ME         ? {1'b0, he - ME, {M{1'b0}}} : {W{1'b0}};
      wire [W-1:0] ad   = fabs(in_dens_i);
      wire [W-1:0] dmax = ad > SIXTEENTH ? ad : SIXTEENTH;
      // L1: slab = scale * ulp (fp_mul), r = 1 / dmax (fp_div).
      wire [W-1:0] slab, rcp;
      wire         v1, r2, unused_d1_rdy, unused_d1_vld, unused_p1_rdy, unused_p1_vld;
      localparam integer P1 = TAG_BITS + 4 * W;
      wire [P1-1:0] p1;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(0), .N(1)) u_m1 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
        .in_a_i(in_scale_i), .in_b_i(uh), .in_c_i({W{1'b0}}), .in_sub_i(1'b0),
        .out_valid_o(v1), .out_ready_i(r2), .out_res_o(slab)
      );
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(3), .N(1)) u_d1 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(unused_d1_rdy),
        .in_a_i(ONE), .in_b_i(dmax), .in_c_i({W{1'b0}}), .in_sub_i(1'b0),
        .out_valid_o(unused_d1_vld), .out_ready_i(r2), .out_res_o(rcp)
      );
      fp_pipe #(.WIDTH(P1), .STAGES(STAGES)) u_p1 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(unused_p1_rdy),
        .in_data_i({in_tag_i, in_tmin_i, in_h_z_i, in_h_y_i, in_h_x_i}), .out_valid_o(unused_p1_vld),
        .out_ready_i(r2), .out_data_o(p1)
      );
      // L2: t0 = slab * r (fp_mul).
      wire [W-1:0]  t0;
      wire          unused_p2_rdy, unused_p2_vld;
      wire [P1-1:0] p2;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(0), .N(1)) u_m2 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v1), .in_ready_o(r2),
        .in_a_i(slab), .in_b_i(rcp), .in_c_i({W{1'b0}}), .in_sub_i(1'b0),
        .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_res_o(t0)
      );
      fp_pipe #(.WIDTH(P1), .STAGES(STAGES)) u_p2 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v1), .in_ready_o(unused_p2_rdy),
        .in_data_i(p1), .out_valid_o(unused_p2_vld), .out_ready_i(out_ready_i), .out_data_o(p2)
      );
      wire [W-1:0] tmin2 = p2[3*W +: W];
      assign out_tmin_o = tmin2 < t0 ? t0 : tmin2;
      assign {out_o_z_o, out_o_y_o, out_o_x_o} = p2[3*W-1:0];
      assign out_tag_o = p2[P1-1 -: TAG_BITS];
      wire unused_in;
      assign unused_in = ^{unused_d1_rdy, unused_d1_vld, unused_p1_rdy, unused_p1_vld,
                           unused_p2_rdy, unused_p2_vld, clk_i, in_k_i, in_side_neg_i,
                           in_n_u_i, in_n_v_i, in_n_d_i, in_o_x_i, in_o_y_i, in_o_z_i, in_d_x_i,
                           in_d_y_i, in_d_z_i, in_td_x_i, in_td_y_i, in_td_z_i, in_den_i,
                           in_fixed_i, hk, hu, hv, ok, ou, ov, dk, du, dv, tk, tu, tv,
                           in_front_i, in_all_i, in_id_i, in_cand_id_i, in_ray_skip_i};

    end else begin : g_bound
      // ---- error-bound (hls::hit_shadow, Spawn::error_bound) ---------------------------------------
      localparam integer BIAS2 = BIAS + 2, BIAS1 = BIAS + 1;
      localparam [W-1:0] C5 = {1'b0, BIAS2[E-1:0], 2'b01, {(M-2){1'b0}}};  // 5 = 1.25 * 2^2
      localparam [W-1:0] C3 = {1'b0, BIAS1[E-1:0], 1'b1, {(M-1){1'b0}}};   // 3 = 1.5 * 2^1
      // The core that travels through every level: {tag, k, side_neg, n_v, n_u, h_v, h_u, h_k}.
      localparam integer CW = TAG_BITS + 3 + 5 * W;
      wire [CW-1:0] core0 = {in_tag_i, in_k_i, in_side_neg_i, in_n_v_i, in_n_u_i, hv, hu, hk};

      // L1: n_u o_u, n_v o_v, n_u d_u, n_v d_v, t den, n_u h_u, n_v h_v;
      //     |n_d| + |o_k|, |n_d| + |h_k|, |t d_i| + |h_i| (k, u, v).
      wire [7*W-1:0] m1;
      wire [5*W-1:0] a1;
      wire           v1, r2, unused_a1_rdy, unused_a1_vld, unused_p1_rdy, unused_p1_vld;
      localparam integer P1 = CW + 2 * W;
      wire [P1-1:0] p1;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(0), .N(7)) u_m1 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
        .in_a_i({in_n_v_i, in_n_u_i, in_t_i, in_n_v_i, in_n_u_i, in_n_v_i, in_n_u_i}),
        .in_b_i({hv, hu, in_den_i, dv, du, ov, ou}), .in_c_i({7*W{1'b0}}), .in_sub_i(7'b0),
        .out_valid_o(v1), .out_ready_i(r2), .out_res_o(m1)
      );
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(1), .N(5)) u_a1 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(unused_a1_rdy),
        .in_a_i({fabs(tv), fabs(tu), fabs(tk), fabs(in_n_d_i), fabs(in_n_d_i)}),
        .in_b_i({fabs(hv), fabs(hu), fabs(hk), fabs(hk), fabs(ok)}), .in_c_i({5*W{1'b0}}),
        .in_sub_i(5'b0), .out_valid_o(unused_a1_vld), .out_ready_i(r2), .out_res_o(a1)
      );
      fp_pipe #(.WIDTH(P1), .STAGES(STAGES)) u_p1 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(unused_p1_rdy),
        .in_data_i({fabs(in_t_i), fabs(dk), core0}), .out_valid_o(unused_p1_vld), .out_ready_i(r2),
        .out_data_o(p1)
      );
      wire [CW-1:0] core1 = p1[CW-1:0];
      wire [W-1:0]  c1_hk = core1[0 +: W];
      wire [W-1:0]  c1_nu = core1[3*W +: W], c1_nv = core1[4*W +: W];
      wire [W-1:0]  adk = p1[CW +: W], at1 = p1[CW+W +: W];
      wire [W-1:0]  nuou = m1[0 +: W], nvov = m1[W +: W], nudu = m1[2*W +: W], nvdv = m1[3*W +: W];
      wire [W-1:0]  tden = m1[4*W +: W], nuhu = m1[5*W +: W], nvhv = m1[6*W +: W];
      wire [W-1:0]  ndok = a1[0 +: W], ndhk = a1[W +: W], sk = a1[2*W +: W], su = a1[3*W +: W],
                    sv = a1[4*W +: W];

      // L2: e_num, e_den, e_snum, e_move (fp_add3); |n_u| s_u, |n_v| s_v (fp_mul).
      wire [4*W-1:0] e2;
      wire [2*W-1:0] m2;
      wire           v2, r3, unused_m2_rdy, unused_m2_vld, unused_p2_rdy, unused_p2_vld;
      localparam integer P2 = CW + 3 * W;
      wire [P2-1:0] p2;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(2), .N(4)) u_e2 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v1), .in_ready_o(r2),
        .in_a_i({fabs(c1_hk), ndhk, adk, ndok}),
        .in_b_i({fabs(nuhu), fabs(nuhu), fabs(nudu), fabs(nuou)}),
        .in_c_i({fabs(nvhv), fabs(nvhv), fabs(nvdv), fabs(nvov)}), .in_sub_i(4'b0),
        .out_valid_o(v2), .out_ready_i(r3), .out_res_o(e2)
      );
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(0), .N(2)) u_m2 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v1), .in_ready_o(unused_m2_rdy),
        .in_a_i({fabs(c1_nv), fabs(c1_nu)}), .in_b_i({sv, su}), .in_c_i({2*W{1'b0}}),
        .in_sub_i(2'b0), .out_valid_o(unused_m2_vld), .out_ready_i(r3), .out_res_o(m2)
      );
      fp_pipe #(.WIDTH(P2), .STAGES(STAGES)) u_p2 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v1), .in_ready_o(unused_p2_rdy),
        .in_data_i({scale2(fabs(tden), 1), sk, at1, core1}), .out_valid_o(unused_p2_vld),
        .out_ready_i(r3), .out_data_o(p2)
      );
      wire [CW-1:0] core2 = p2[CW-1:0];
      wire [W-1:0]  at2 = p2[CW +: W], sk2 = p2[CW+W +: W], c2tden2 = p2[CW+2*W +: W];
      wire [W-1:0]  e_num = e2[0 +: W], e_den = e2[W +: W], e_snum = e2[2*W +: W],
                    e_move = e2[3*W +: W];

      // L3: e_hit (fp_add3); 5 e_num, |t| e_den, 5 e_snum (fp_mul).
      wire [W-1:0]   e_hit;
      wire [3*W-1:0] m3;
      wire           v3, r4, unused_m3_rdy, unused_m3_vld, unused_p3_rdy, unused_p3_vld;
      localparam integer P3 = CW + 2 * W;
      wire [P3-1:0] p3;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(2), .N(1)) u_e3 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v2), .in_ready_o(r3),
        .in_a_i(sk2), .in_b_i(m2[0 +: W]), .in_c_i(m2[W +: W]), .in_sub_i(1'b0),
        .out_valid_o(v3), .out_ready_i(r4), .out_res_o(e_hit)
      );
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(0), .N(3)) u_m3 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v2), .in_ready_o(unused_m3_rdy),
        .in_a_i({C5, at2, C5}), .in_b_i({e_snum, e_den, e_num}), .in_c_i({3*W{1'b0}}),
        .in_sub_i(3'b0), .out_valid_o(unused_m3_vld), .out_ready_i(r4), .out_res_o(m3)
      );
      fp_pipe #(.WIDTH(P3), .STAGES(STAGES)) u_p3 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v2), .in_ready_o(unused_p3_rdy),
        .in_data_i({c2tden2, e_move, core2}), .out_valid_o(unused_p3_vld), .out_ready_i(r4),
        .out_data_o(p3)
      );
      wire [CW-1:0] core3 = p3[CW-1:0];
      wire [W-1:0]  e_move3 = p3[CW +: W], c2tden3 = p3[CW+W +: W];

      // L4: 3 (|t| e_den) (fp_mul); 5 e_snum + e_move (fp_add).
      wire [W-1:0] c3ted, snmv;
      wire         v4, r5, unused_a4_rdy, unused_a4_vld, unused_p4_rdy, unused_p4_vld;
      localparam integer P4 = CW + 3 * W;
      wire [P4-1:0] p4;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(0), .N(1)) u_m4 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v3), .in_ready_o(r4),
        .in_a_i(C3), .in_b_i(m3[W +: W]), .in_c_i({W{1'b0}}), .in_sub_i(1'b0),
        .out_valid_o(v4), .out_ready_i(r5), .out_res_o(c3ted)
      );
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(1), .N(1)) u_a4 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v3), .in_ready_o(unused_a4_rdy),
        .in_a_i(m3[2*W +: W]), .in_b_i(e_move3), .in_c_i({W{1'b0}}), .in_sub_i(1'b0),
        .out_valid_o(unused_a4_vld), .out_ready_i(r5), .out_res_o(snmv)
      );
      fp_pipe #(.WIDTH(P4), .STAGES(STAGES)) u_p4 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v3), .in_ready_o(unused_p4_rdy),
        .in_data_i({scale2(e_hit, 1), c2tden3, m3[0 +: W], core3}), .out_valid_o(unused_p4_vld),
        .out_ready_i(r5), .out_data_o(p4)
      );
      wire [CW-1:0] core4 = p4[CW-1:0];
      wire [W-1:0]  c5num4 = p4[CW +: W], c2tden4 = p4[CW+W +: W], c2hit4 = p4[CW+2*W +: W];

      // L5: b1 = 5 e_num + 3 |t| e_den + 2 |t den| (fp_add3).
      wire [W-1:0] b1;
      wire         v5, r6, unused_p5_rdy, unused_p5_vld;
      localparam integer P5 = CW + 2 * W;
      wire [P5-1:0] p5;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(2), .N(1)) u_e5 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v4), .in_ready_o(r5),
        .in_a_i(c5num4), .in_b_i(c3ted), .in_c_i(c2tden4), .in_sub_i(1'b0),
        .out_valid_o(v5), .out_ready_i(r6), .out_res_o(b1)
      );
      fp_pipe #(.WIDTH(P5), .STAGES(STAGES)) u_p5 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v4), .in_ready_o(unused_p5_rdy),
        .in_data_i({snmv, c2hit4, core4}), .out_valid_o(unused_p5_vld), .out_ready_i(r6),
        .out_data_o(p5)
      );
      wire [CW-1:0] core5 = p5[CW-1:0];

      // L6: B = b1 + 2 e_hit + (5 e_snum + e_move) (fp_add3).
      wire [W-1:0]  bnd;
      wire          v6, r7, unused_p6_rdy, unused_p6_vld;
      wire [CW-1:0] core6;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(2), .N(1)) u_e6 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v5), .in_ready_o(r6),
        .in_a_i(b1), .in_b_i(p5[CW +: W]), .in_c_i(p5[CW+W +: W]), .in_sub_i(1'b0),
        .out_valid_o(v6), .out_ready_i(r7), .out_res_o(bnd)
      );
      fp_pipe #(.WIDTH(CW), .STAGES(STAGES)) u_p6 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v5), .in_ready_o(unused_p6_rdy),
        .in_data_i(core5), .out_valid_o(unused_p6_vld), .out_ready_i(r7), .out_data_o(core6)
      );
      // delta = 2 u B: u = 2^-M (rtz), 2^-(M+1) (rne) or 2^(1-M) (raycore, hls/hit.h).
      wire [W-1:0] delta = scale2(bnd, RAYCORE != 0 ? 2 - M : (RNE != 0 ? -M : 1 - M));

      // L7: delta n_u, delta n_v (fp_mul); delta n_k = delta.
      wire [2*W-1:0] m7;
      wire           v7, r8, unused_p7_rdy, unused_p7_vld;
      localparam integer P7 = CW + W;
      wire [P7-1:0] p7;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(0), .N(2)) u_m7 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v6), .in_ready_o(r7),
        .in_a_i({delta, delta}), .in_b_i({core6[4*W +: W], core6[3*W +: W]}),
        .in_c_i({2*W{1'b0}}), .in_sub_i(2'b0), .out_valid_o(v7), .out_ready_i(r8), .out_res_o(m7)
      );
      fp_pipe #(.WIDTH(P7), .STAGES(STAGES)) u_p7 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v6), .in_ready_o(unused_p7_rdy),
        .in_data_i({delta, core6}), .out_valid_o(unused_p7_vld), .out_ready_i(r8), .out_data_o(p7)
      );
      wire [CW-1:0] core7 = p7[CW-1:0];
      wire          neg7  = core7[5*W];

      // L8: h_i +- step_i (fp_add; subtract when moving along -n).
      wire [3*W-1:0] o8;
      wire           unused_p8_rdy, unused_p8_vld;
      localparam integer P8 = TAG_BITS + 2;
      wire [P8-1:0] p8;
      spawn_ops #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .OP(1), .N(3)) u_a8 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v7), .in_ready_o(r8),
        .in_a_i(core7[3*W-1:0]), .in_b_i({m7, p7[CW +: W]}), .in_c_i({3*W{1'b0}}),
        .in_sub_i({3{neg7}}), .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_res_o(o8)
      );
      fp_pipe #(.WIDTH(P8), .STAGES(STAGES)) u_p8 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v7), .in_ready_o(unused_p8_rdy),
        .in_data_i(core7[CW-1 -: P8]), .out_valid_o(unused_p8_vld), .out_ready_i(out_ready_i),
        .out_data_o(p8)
      );
      assign {out_o_z_o, out_o_y_o, out_o_x_o} = unpermute(p8[1:0], o8[0 +: W], o8[W +: W], o8[2*W +: W]);
      assign out_tag_o       = p8[P8-1 -: TAG_BITS];
      assign out_tmin_o      = in_tmin_i;
      wire unused_in;
      assign unused_in = ^{unused_a1_rdy, unused_a1_vld, unused_p1_rdy, unused_p1_vld,
                           unused_m2_rdy, unused_m2_vld, unused_p2_rdy, unused_p2_vld,
                           unused_m3_rdy, unused_m3_vld, unused_p3_rdy, unused_p3_vld,
                           unused_a4_rdy, unused_a4_vld, unused_p4_rdy, unused_p4_vld,
                           unused_p5_rdy, unused_p5_vld, unused_p6_rdy, unused_p6_vld,
                           unused_p7_rdy, unused_p7_vld, unused_p8_rdy, unused_p8_vld,
                           core2[W +: 4*W], core3[W +: 4*W], core4[W +: 4*W], core5[W +: 4*W],
                           core1[W +: 2*W], core3[0 +: W], core4[0 +: W], core5[0 +: W],
                           core6[0 +: 3*W], core2[0 +: W], p7[CW-1 -: TAG_BITS + 3],
                           in_front_i, in_all_i, in_id_i, in_cand_id_i, in_ray_skip_i, in_scale_i,
                           in_fixed_i, in_dens_i};
    end
  endgenerate

  // The skip id and the ist's comparison (skip-origin and the strategies built on it).
  generate
    if (STRATEGY == 1 || STRATEGY >= 4) begin : g_skip
      // A shadow ray is spawned when the light is in front, or for every hit with in_all_i
      // (hls::ShadowSetup::spawn); no ray: no skip id.
      assign out_skip_id_o   = (in_front_i | in_all_i) ? in_id_i : 32'hFFFF_FFFF;
      assign out_cand_skip_o = in_cand_id_i == in_ray_skip_i;
    end else begin : g_noskip
      assign out_skip_id_o   = 32'hFFFF_FFFF;
      assign out_cand_skip_o = 1'b0;
    end
    // skip-back: t's bit pattern minus in_back_i (hls::detail::add_ulps with -ulps): below the
    // smallest normal, zero.
    if (STRATEGY == 6) begin : g_back
      wire [32:0] mag = {{(33-(W-1)){1'b0}}, in_t_i[W-2:0]};
      wire [32:0] m   = mag - {1'b0, in_back_i};
      assign out_t_back_o = m[32] || m < (33'd1 << M) ? {in_t_i[W-1], {(W-1){1'b0}}}
                                                      : {in_t_i[W-1], m[W-2:0]};
    end else begin : g_noback
      assign out_t_back_o = in_t_i;
      wire unused_back;
      assign unused_back = ^in_back_i;
    end
  endgenerate

endmodule
