// ist - the intersection unit's datapath: Wald's projected ray/triangle test, fully pipelined,
// one test per cycle.
//
// Bit-exact twin of hls::ist_wald (hls/ist.h): same operations in the same order, each rounded
// once by the rtl/fp operators, so {exit, t, den} equal the C++ reference's for every input.
// In hardware every phase is computed for every test; the early exits of the reference only
// decide the reported exit code (the first failing phase):
//   0 hit, 1 distance (not tmin < t < tmax), 2 beta (< -eps), 3 gamma (< -eps),
//   4 sum (one_eps < beta+gamma).
// Watertightness margins (hls/margins.h): eps_i and one_eps_i are per-frame registers, static
// while tests are in flight (they are read at levels 9 and 10, not carried with a test). A
// coordinate fails iff its sign is set and its magnitude bits, as an integer, exceed eps_i's (a
// zero exponent field meaning zero; eps_i's sign bit is ignored); the sum fails iff one_eps_i <
// beta + gamma. eps_i = 0, one_eps_i = 1.0 is the test without margins.
// k (the projection axis) selects u = (k+1)%3, v = (k+2)%3 with operand muxes; k = 3 is not a
// valid record and is treated as k = 0.
//
// Levels (all operators of a level run side by side with the same number of pipeline registers,
// S1 .. S10 below: the level's share of the 10 x STAGES by its logic; a per-level fp_pipe of the
// same depth carries the values needed later, the tag and the phase flags):
//    1  m_nud = n_u*d_u, m_nvd = n_v*d_v, m_nuo = n_u*o_u, m_nvo = n_v*o_v, s1 = n_d - o_k
//    2  den = add3(d_k, m_nud, m_nvd), s2 = m_nuo + m_nvo
//    3  num = s1 - s2, rcp = 1 / den (fp_div; RAYCORE: fp_rcp, the table reciprocal)
//    4  t = num * rcp
//    5  lt(tmin, t), lt(t, tmax) (fp_cmp), t*d_u, t*d_v
//    6  hu = o_u + t*d_u, hv = o_v + t*d_v
//    7  b_nu*hu, b_nv*hv, c_nu*hu, c_nv*hv
//    8  beta = add3(b_nu*hu, b_nv*hv, b_d), gamma = add3(c_nu*hu, c_nv*hv, c_d)
//    9  sum = beta + gamma
//   10  lt(one_eps, sum) (fp_cmp); the exit code is decoded combinationally at the output.
// Latency = 10 * STAGES cycles (STAGES = 0: combinational), throughput one test per cycle.
//
// Handshake: valid/ready as every rtl/fp operator. The operators of a level receive the same
// in_valid and out_ready and have the same depth, so their fp_pipe registers hold the same valid
// bits at all times (lockstep): the level's carry pipe stands for all of them (its in_ready and
// out_valid are the level's), and the operators' own handshake outputs are equal copies, left
// unused. Back-pressure stalls the whole chain (a register takes a new item if it is empty or its
// item leaves), so in_ready_o depends combinationally on out_ready_i.
// FREE = 1 (ist_unit, which never holds a result back: out_ready_i 1): the carries' data in
// fp_delay memories instead of a register per stage.
// lint: also FREE=1
module ist #(
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
  input  wire [EXP_BITS+MAN_BITS:0] eps_i,      // margin eps >= 0 (static)
  input  wire [EXP_BITS+MAN_BITS:0] one_eps_i,  // 1 + eps rounded once (static)
  input  wire                       in_valid_i,
  output wire                       in_ready_o,
  input  wire [1:0]                 in_k_i,     // projection axis 0..2
  input  wire [EXP_BITS+MAN_BITS:0] in_c0_i,    // n_u
  input  wire [EXP_BITS+MAN_BITS:0] in_c1_i,    // n_v
  input  wire [EXP_BITS+MAN_BITS:0] in_c2_i,    // n_d
  input  wire [EXP_BITS+MAN_BITS:0] in_c3_i,    // b_nu
  input  wire [EXP_BITS+MAN_BITS:0] in_c4_i,    // b_nv
  input  wire [EXP_BITS+MAN_BITS:0] in_c5_i,    // b_d
  input  wire [EXP_BITS+MAN_BITS:0] in_c6_i,    // c_nu
  input  wire [EXP_BITS+MAN_BITS:0] in_c7_i,    // c_nv
  input  wire [EXP_BITS+MAN_BITS:0] in_c8_i,    // c_d
  input  wire [EXP_BITS+MAN_BITS:0] in_o_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_o_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_o_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_d_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_d_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_d_z_i,
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
  localparam integer BIAS = (1 << (E - 1)) - 1;
  // Registers per level: the 10 x STAGES of the latency shared out by the logic each level holds,
  // so that the stages are balanced (a level of one add, mul or compare weighs 1, an add3 3, the
  // divider 7: the registers each needs for 95 FO4, docs/timing.md's operators at STAGES 1-7).
  // Level l takes (STAGES * Q_l) / 2 - (STAGES * Q_l-1) / 2 of them, Q the cumulative weights
  // (20 in all): at STAGES 2 the weights themselves, 1 3 7 1 1 1 1 3 1 1.
  localparam integer Q1 = 1, Q2 = 4, Q3 = 11, Q4 = 12, Q5 = 13, Q6 = 14, Q7 = 15, Q8 = 18, Q9 = 19;
  localparam integer S1  = (STAGES * Q1) / 2;
  localparam integer S2  = (STAGES * Q2) / 2 - (STAGES * Q1) / 2;
  localparam integer S3  = (STAGES * Q3) / 2 - (STAGES * Q2) / 2;
  localparam integer S4  = (STAGES * Q4) / 2 - (STAGES * Q3) / 2;
  localparam integer S5  = (STAGES * Q5) / 2 - (STAGES * Q4) / 2;
  localparam integer S6  = (STAGES * Q6) / 2 - (STAGES * Q5) / 2;
  localparam integer S7  = (STAGES * Q7) / 2 - (STAGES * Q6) / 2;
  localparam integer S8  = (STAGES * Q8) / 2 - (STAGES * Q7) / 2;
  localparam integer S9  = (STAGES * Q9) / 2 - (STAGES * Q8) / 2;
  localparam integer S10 = 10 * STAGES - (STAGES * Q9) / 2;
  localparam [W-1:0] ONE = {1'b0, BIAS[E-1:0], {M{1'b0}}};  // 1.0

  // Level handshakes: v[L] / r[L] = valid / ready at the output of level L (index 0 = the input).
  wire [10:0] v;
  wire [11:1] r;
  assign v[0]       = in_valid_i;
  assign in_ready_o = r[1];

  // ---- operand muxes (u = (k+1)%3, v = (k+2)%3) ----------------------------------------------
  reg [W-1:0] o_k, o_u, o_v, d_k, d_u, d_v;
  always @* begin
    case (in_k_i)
      2'd1: begin
        o_k = in_o_y_i; o_u = in_o_z_i; o_v = in_o_x_i;
        d_k = in_d_y_i; d_u = in_d_z_i; d_v = in_d_x_i;
      end
      2'd2: begin
        o_k = in_o_z_i; o_u = in_o_x_i; o_v = in_o_y_i;
        d_k = in_d_z_i; d_u = in_d_x_i; d_v = in_d_y_i;
      end
      default: begin
        o_k = in_o_x_i; o_u = in_o_y_i; o_v = in_o_z_i;
        d_k = in_d_x_i; d_u = in_d_y_i; d_v = in_d_z_i;
      end
    endcase
  end

  // ---- level 1 ----------------------------------------------------------------------------------
  wire [W-1:0] l1_nud, l1_nvd, l1_nuo, l1_nvo, l1_s1;
  wire [4:0]   l1_unused_v, l1_unused_r;
  // Levels 1 to 4 carry the tag, one value of their own and two groups of six values:
  //   ka = {tmin, tmax, d_u, d_v, o_u, o_v}   (field i at [(5-i)*W +: W])
  //   kb = {b_nu, b_nv, b_d, c_nu, c_nv, c_d} (the same), carried on to level 7.
  localparam integer C_W = TAG_BITS + 13 * W;
  wire [TAG_BITS-1:0] c1_tag, c2_tag, c3_tag, c4_tag;
  wire [6*W-1:0] c1_ka, c2_ka, c3_ka, c4_ka, c1_kb, c2_kb, c3_kb, c4_kb;
  wire [W-1:0] c1_dk, c1_du, c1_dv, c1_ou, c1_ov, c1_tmin, c1_tmax;
  assign c1_ka = {c1_tmin, c1_tmax, c1_du, c1_dv, c1_ou, c1_ov};
  fp_delay #(.WIDTH(C_W), .STAGES(S1), .FREE(FREE)) u_carry1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(r[1]),
    .in_data_i({in_tag_i, in_tmin_i, in_tmax_i, d_k, d_u, d_v, o_u, o_v,
                in_c3_i, in_c4_i, in_c5_i, in_c6_i, in_c7_i, in_c8_i}),
    .out_valid_o(v[1]), .out_ready_i(r[2]),
    .out_data_o({c1_tag, c1_tmin, c1_tmax, c1_dk, c1_du, c1_dv, c1_ou, c1_ov, c1_kb})
  );
  // Products j = 0..3: nud = n_u*d_u, nvd = n_v*d_v, nuo = n_u*o_u, nvo = n_v*o_v.
  wire [4*W-1:0] l1_pa = {in_c1_i, in_c0_i, in_c1_i, in_c0_i};
  wire [4*W-1:0] l1_pb = {o_v, o_u, d_v, d_u};
  wire [4*W-1:0] l1_prod;
  assign {l1_nvo, l1_nuo, l1_nvd, l1_nud} = l1_prod;
  genvar gj;
  generate
    for (gj = 0; gj < 4; gj = gj + 1) begin : g_l1_mul
      fp_op2_nt #(.OP("mul"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S1)) u_mul (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l1_unused_r[gj]),
        .in_a_i(l1_pa[gj*W +: W]), .in_b_i(l1_pb[gj*W +: W]), .out_valid_o(l1_unused_v[gj]),
        .out_ready_i(r[2]), .out_res_o(l1_prod[gj*W +: W]));
    end
  endgenerate
  fp_op2_nt #(.OP("sub"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S1)) u_l1_s1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l1_unused_r[4]),
    .in_a_i(in_c2_i), .in_b_i(o_k), .out_valid_o(l1_unused_v[4]), .out_ready_i(r[2]),
    .out_res_o(l1_s1));

  // ---- level 2 ----------------------------------------------------------------------------------
  wire [W-1:0] l2_den, l2_s2;
  wire [1:0]   l2_unused_v, l2_unused_r;
  wire [W-1:0] c2_s1;
  fp_delay #(.WIDTH(C_W), .STAGES(S2), .FREE(FREE)) u_carry2 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[1]), .in_ready_o(r[2]),
    .in_data_i({c1_tag, c1_ka, l1_s1, c1_kb}), .out_valid_o(v[2]), .out_ready_i(r[3]),
    .out_data_o({c2_tag, c2_ka, c2_s1, c2_kb}));
  fp_add3_nt #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S2)) u_l2_den (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[1]), .in_ready_o(l2_unused_r[0]),
    .in_a_i(c1_dk), .in_b_i(l1_nud), .in_c_i(l1_nvd), .out_valid_o(l2_unused_v[0]),
    .out_ready_i(r[3]), .out_res_o(l2_den));
  fp_op2_nt #(.OP("add"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S2)) u_l2_s2 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[1]), .in_ready_o(l2_unused_r[1]),
    .in_a_i(l1_nuo), .in_b_i(l1_nvo), .out_valid_o(l2_unused_v[1]), .out_ready_i(r[3]),
    .out_res_o(l2_s2));

  // ---- level 3 ----------------------------------------------------------------------------------
  wire [W-1:0] l3_num, l3_rcp;
  wire [1:0]   l3_unused_v, l3_unused_r;
  wire [W-1:0] c3_den;
  fp_delay #(.WIDTH(C_W), .STAGES(S3), .FREE(FREE)) u_carry3 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(r[3]),
    .in_data_i({c2_tag, c2_ka, l2_den, c2_kb}), .out_valid_o(v[3]), .out_ready_i(r[4]),
    .out_data_o({c3_tag, c3_ka, c3_den, c3_kb}));
  fp_op2_nt #(.OP("sub"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S3)) u_l3_num (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(l3_unused_r[0]),
    .in_a_i(c2_s1), .in_b_i(l2_s2), .out_valid_o(l3_unused_v[0]), .out_ready_i(r[4]),
    .out_res_o(l3_num));
  generate
    if (RAYCORE != 0) begin : g_rcp_table  // raycore: the table reciprocal (hls::rcp<F, raycore>)
      wire unused_tag;
      fp_rcp #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(S3)) u_l3_rcp (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(l3_unused_r[1]),
        .in_a_i(l2_den), .in_tag_i(1'b0), .out_valid_o(l3_unused_v[1]),
        .out_ready_i(r[4]), .out_res_o(l3_rcp), .out_tag_o(unused_tag));
    end else begin : g_rcp_div  // rtz, rne: 1 / den, rounded once
      fp_op2_nt #(.OP("div"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .STAGES(S3)) u_l3_rcp (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(l3_unused_r[1]),
        .in_a_i(ONE), .in_b_i(l2_den), .out_valid_o(l3_unused_v[1]),
        .out_ready_i(r[4]), .out_res_o(l3_rcp));
    end
  endgenerate

  // ---- level 4 ----------------------------------------------------------------------------------
  wire [W-1:0] l4_t;
  wire         l4_unused_v, l4_unused_r;
  wire [W-1:0] c4_den;
  fp_delay #(.WIDTH(C_W), .STAGES(S4), .FREE(FREE)) u_carry4 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[3]), .in_ready_o(r[4]),
    .in_data_i({c3_tag, c3_ka, c3_den, c3_kb}), .out_valid_o(v[4]), .out_ready_i(r[5]),
    .out_data_o({c4_tag, c4_ka, c4_den, c4_kb}));
  wire [W-1:0] c4_tmin = c4_ka[5*W +: W];
  wire [W-1:0] c4_tmax = c4_ka[4*W +: W];
  fp_op2_nt #(.OP("mul"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S4)) u_l4_t (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[3]), .in_ready_o(l4_unused_r),
    .in_a_i(l3_num), .in_b_i(l3_rcp), .out_valid_o(l4_unused_v), .out_ready_i(r[5]),
    .out_res_o(l4_t));

  // ---- level 5 ----------------------------------------------------------------------------------
  wire [1:0]   l5_lt;  // {t < tmax, tmin < t}
  wire [3:0]   l5_unused_v, l5_unused_r;
  localparam integer C5_W = TAG_BITS + 10 * W;
  wire [TAG_BITS-1:0] c5_tag;
  wire [W-1:0] c5_ou, c5_ov, c5_den, c5_t;
  wire [6*W-1:0] c5_kb;
  fp_delay #(.WIDTH(C5_W), .STAGES(S5), .FREE(FREE)) u_carry5 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[4]), .in_ready_o(r[5]),
    .in_data_i({c4_tag, c4_ka[0 +: 2*W], c4_den, l4_t, c4_kb}),
    .out_valid_o(v[5]), .out_ready_i(r[6]),
    .out_data_o({c5_tag, c5_ou, c5_ov, c5_den, c5_t, c5_kb})
  );
  // Lanes j = 0, 1: lo = lt(tmin, t), hi = lt(t, tmax); tdu = t*d_u, tdv = t*d_v.
  wire [2*W-1:0] l5_ca = {l4_t, c4_tmin};
  wire [2*W-1:0] l5_cb = {c4_tmax, l4_t};
  wire [2*W-1:0] l5_pb = {c4_ka[2*W +: W], c4_ka[3*W +: W]};  // {d_v, d_u}
  wire [2*W-1:0] l5_prod;       // {tdv, tdu}
  wire [1:0]     l5_unused_eq;
  wire [4*W-1:0] l5_unused_mm;  // min/max: not needed
  generate
    for (gj = 0; gj < 2; gj = gj + 1) begin : g_l5
      fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(S5)) u_lt (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[4]), .in_ready_o(l5_unused_r[gj]),
        .in_a_i(l5_ca[gj*W +: W]), .in_b_i(l5_cb[gj*W +: W]), .out_valid_o(l5_unused_v[gj]),
        .out_ready_i(r[6]), .out_lt_o(l5_lt[gj]), .out_eq_o(l5_unused_eq[gj]),
        .out_min_o(l5_unused_mm[2*gj*W +: W]), .out_max_o(l5_unused_mm[(2*gj+1)*W +: W]));
      fp_op2_nt #(.OP("mul"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S5)) u_mul (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[4]), .in_ready_o(l5_unused_r[2+gj]),
        .in_a_i(l4_t), .in_b_i(l5_pb[gj*W +: W]), .out_valid_o(l5_unused_v[2+gj]),
        .out_ready_i(r[6]), .out_res_o(l5_prod[gj*W +: W]));
    end
  endgenerate

  // ---- level 6 ----------------------------------------------------------------------------------
  wire [1:0]   l6_unused_v, l6_unused_r;
  localparam integer C6_W = TAG_BITS + 8 * W + 1;
  wire [TAG_BITS-1:0] c6_tag;
  wire [W-1:0] c6_den, c6_t, c6_bnu, c6_bnv, c6_bd, c6_cnu, c6_cnv, c6_cd;
  wire         c6_p1;  // phase 1 passed: tmin < t < tmax
  fp_delay #(.WIDTH(C6_W), .STAGES(S6), .FREE(FREE)) u_carry6 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[5]), .in_ready_o(r[6]),
    .in_data_i({c5_tag, c5_den, c5_t, c5_kb, &l5_lt}),
    .out_valid_o(v[6]), .out_ready_i(r[7]),
    .out_data_o({c6_tag, c6_den, c6_t, c6_bnu, c6_bnv, c6_bd, c6_cnu, c6_cnv, c6_cd, c6_p1})
  );
  // hu = o_u + t*d_u, hv = o_v + t*d_v
  wire [2*W-1:0] l6_a = {c5_ov, c5_ou};
  wire [2*W-1:0] l6_sum;  // {hv, hu}
  generate
    for (gj = 0; gj < 2; gj = gj + 1) begin : g_l6_add
      fp_op2_nt #(.OP("add"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S6)) u_add (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[5]), .in_ready_o(l6_unused_r[gj]),
        .in_a_i(l6_a[gj*W +: W]), .in_b_i(l5_prod[gj*W +: W]), .out_valid_o(l6_unused_v[gj]),
        .out_ready_i(r[7]), .out_res_o(l6_sum[gj*W +: W]));
    end
  endgenerate

  // ---- level 7 ----------------------------------------------------------------------------------
  wire [3:0]   l7_unused_v, l7_unused_r;
  localparam integer C7_W = TAG_BITS + 4 * W + 1;
  wire [TAG_BITS-1:0] c7_tag;
  wire [W-1:0] c7_den, c7_t, c7_bd, c7_cd;
  wire         c7_p1;
  fp_delay #(.WIDTH(C7_W), .STAGES(S7), .FREE(FREE)) u_carry7 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[6]), .in_ready_o(r[7]),
    .in_data_i({c6_tag, c6_den, c6_t, c6_bd, c6_cd, c6_p1}),
    .out_valid_o(v[7]), .out_ready_i(r[8]),
    .out_data_o({c7_tag, c7_den, c7_t, c7_bd, c7_cd, c7_p1})
  );
  // Products j = 0..3: bu = b_nu*hu, bv = b_nv*hv, cu = c_nu*hu, cv = c_nv*hv.
  wire [4*W-1:0] l7_pa = {c6_cnv, c6_cnu, c6_bnv, c6_bnu};
  wire [4*W-1:0] l7_prod;  // {cv, cu, bv, bu}
  generate
    for (gj = 0; gj < 4; gj = gj + 1) begin : g_l7_mul
      fp_op2_nt #(.OP("mul"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S7)) u_mul (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[6]), .in_ready_o(l7_unused_r[gj]),
        .in_a_i(l7_pa[gj*W +: W]), .in_b_i(l6_sum[(gj%2)*W +: W]), .out_valid_o(l7_unused_v[gj]),
        .out_ready_i(r[8]), .out_res_o(l7_prod[gj*W +: W]));
    end
  endgenerate

  // ---- level 8 ----------------------------------------------------------------------------------
  wire [W-1:0] l8_beta, l8_gamma;
  wire [1:0]   l8_unused_v, l8_unused_r;
  localparam integer C8_W = TAG_BITS + 2 * W + 1;
  wire [TAG_BITS-1:0] c8_tag;
  wire [W-1:0] c8_den, c8_t;
  wire         c8_p1;
  fp_delay #(.WIDTH(C8_W), .STAGES(S8), .FREE(FREE)) u_carry8 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[7]), .in_ready_o(r[8]),
    .in_data_i({c7_tag, c7_den, c7_t, c7_p1}),
    .out_valid_o(v[8]), .out_ready_i(r[9]),
    .out_data_o({c8_tag, c8_den, c8_t, c8_p1})
  );
  // beta = add3(b_nu*hu, b_nv*hv, b_d), gamma = add3(c_nu*hu, c_nv*hv, c_d)
  wire [2*W-1:0] l8_c = {c7_cd, c7_bd};
  wire [2*W-1:0] l8_sum;
  assign {l8_gamma, l8_beta} = l8_sum;
  generate
    for (gj = 0; gj < 2; gj = gj + 1) begin : g_l8_add3
      fp_add3_nt #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S8)) u_add3 (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[7]), .in_ready_o(l8_unused_r[gj]),
        .in_a_i(l7_prod[2*gj*W +: W]), .in_b_i(l7_prod[(2*gj+1)*W +: W]),
        .in_c_i(l8_c[gj*W +: W]), .out_valid_o(l8_unused_v[gj]), .out_ready_i(r[9]),
        .out_res_o(l8_sum[gj*W +: W]));
    end
  endgenerate

  // ---- level 9 ----------------------------------------------------------------------------------
  // A coordinate fails if it is negative and its magnitude exceeds eps (hls: sign(x) &&
  // lt(|eps|, |x|)): the magnitude bits compare as integers, a zero exponent field meaning zero.
  wire [W-2:0] eps_key   = (|eps_i[W-2:M]) ? eps_i[W-2:0] : {(W-1){1'b0}};
  wire [W-2:0] beta_key  = (|l8_beta[W-2:M]) ? l8_beta[W-2:0] : {(W-1){1'b0}};
  wire [W-2:0] gamma_key = (|l8_gamma[W-2:M]) ? l8_gamma[W-2:0] : {(W-1){1'b0}};
  wire l8_bfail = l8_beta[W-1] & (beta_key > eps_key);
  wire l8_gfail = l8_gamma[W-1] & (gamma_key > eps_key);
  wire [W-1:0] l9_sum;
  wire         l9_unused_v, l9_unused_r;
  localparam integer C9_W = TAG_BITS + 2 * W + 3;
  wire [TAG_BITS-1:0] c9_tag;
  wire [W-1:0] c9_den, c9_t;
  wire         c9_p1, c9_bfail, c9_gfail;
  fp_delay #(.WIDTH(C9_W), .STAGES(S9), .FREE(FREE)) u_carry9 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[8]), .in_ready_o(r[9]),
    .in_data_i({c8_tag, c8_den, c8_t, c8_p1, l8_bfail, l8_gfail}),
    .out_valid_o(v[9]), .out_ready_i(r[10]),
    .out_data_o({c9_tag, c9_den, c9_t, c9_p1, c9_bfail, c9_gfail})
  );
  fp_op2_nt #(.OP("add"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S9)) u_l9_sum (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[8]), .in_ready_o(l9_unused_r),
    .in_a_i(l8_beta), .in_b_i(l8_gamma), .out_valid_o(l9_unused_v), .out_ready_i(r[10]),
    .out_res_o(l9_sum));

  // ---- level 10 ---------------------------------------------------------------------------------
  wire         l10_sfail;  // one_eps < beta + gamma
  wire         l10_unused_v, l10_unused_r;
  localparam integer C10_W = TAG_BITS + 2 * W + 3;
  wire         c10_p1, c10_bfail, c10_gfail;
  fp_delay #(.WIDTH(C10_W), .STAGES(S10), .FREE(FREE)) u_carry10 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[9]), .in_ready_o(r[10]),
    .in_data_i({c9_tag, c9_den, c9_t, c9_p1, c9_bfail, c9_gfail}),
    .out_valid_o(v[10]), .out_ready_i(r[11]),
    .out_data_o({out_tag_o, out_den_o, out_t_o, c10_p1, c10_bfail, c10_gfail})
  );
  wire         l10_unused_eq;
  wire [W-1:0] l10_unused_min, l10_unused_max;
  fp_cmp_nt #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(S10)) u_l10_sum (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[9]), .in_ready_o(l10_unused_r),
    .in_a_i(one_eps_i), .in_b_i(l9_sum), .out_valid_o(l10_unused_v), .out_ready_i(r[11]),
    .out_lt_o(l10_sfail), .out_eq_o(l10_unused_eq), .out_min_o(l10_unused_min),
    .out_max_o(l10_unused_max));

  assign r[11]       = out_ready_i;
  assign out_valid_o = v[10];
  // The first failing phase, as hls::ist_wald returns it.
  assign out_exit_o  = !c10_p1   ? 3'd1 :
                       c10_bfail ? 3'd2 :
                       c10_gfail ? 3'd3 :
                       l10_sfail ? 3'd4 : 3'd0;

  // The operators' handshake outputs equal their level's carry pipe's (lockstep, see header).
  wire unused_hs;
  assign unused_hs = ^{l1_unused_v, l1_unused_r, l2_unused_v, l2_unused_r, l3_unused_v,
                       l3_unused_r, l4_unused_v, l4_unused_r, l5_unused_v, l5_unused_r,
                       l6_unused_v, l6_unused_r, l7_unused_v, l7_unused_r, l8_unused_v,
                       l8_unused_r, l9_unused_v, l9_unused_r, l10_unused_v, l10_unused_r,
                       l5_unused_eq, l5_unused_mm, l10_unused_eq, l10_unused_min, l10_unused_max,
                       eps_i[W-1]};  // eps_i's sign bit is ignored

endmodule
