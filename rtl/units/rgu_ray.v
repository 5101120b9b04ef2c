// rgu_ray - the ray generation unit's datapath: the primary ray through the centre of pixel (x, y)
// from the camera registers, fully pipelined, one ray per cycle.
//
// Bit-exact twin of hls::rgu_primary (hls/rgu.h): the same operations in the same order, each
// rounded once by the rtl/fp operators. The camera registers (hls::RguCamera: origin o, the
// direction to pixel (0, 0)'s centre d00, the steps per pixel dx and dy; numbers of the format)
// are inputs, written by the host once per frame; they must not change while a ray is in flight
// (o goes to the output combinationally, d00, dx, dy are read by levels 1 and 2).
//
// Levels (the operators of a level run side by side with the same number of pipeline registers,
// S1 .. S8 below: the level's share of the 15 x STAGES by its logic; a per-level fp_pipe of the
// same depth carries the tag and the values needed later):
//   0  fx, fy = the pixel coordinates in the format (combinational, exact below 2^(M+1))
//   1-2  p[c] = d00[c] + fx*dx[c] + fy*dy[c]   3 fp_sop (S1 + S2: the products exact, one
//                                               rounding; issue 27 part 4)
//   3  p[c]*p[c]                                  3 fp_mul
//   4  add3 of the squares                        1 fp_add3
//   5  len = sqrt(...)                            1 fp_sqrt
//   6  rl = 1 / len                               1 fp_div (RAYCORE: fp_rcp)
//   7  d[c] = p[c] * rl                           3 fp_mul
//   8  inv[c] = 1 / d[c]                          3 fp_div (RAYCORE: fp_rcp)
// Latency = 15 * STAGES cycles (STAGES = 0: combinational), one ray per cycle: at STAGES 2 every
// level has the registers its logic needs for 95 FO4 (the weights below).
// RAYCORE = 1 (FP24): rounding mode raycore (hls Rounding::raycore, overrides RNE): the adders'
// raycore windows, truncating conversions, products and square root, raycore's table reciprocal
// (fp_rcp) for 1 / len and 1 / d.
//
// Handshake: valid/ready as every rtl/fp operator. The operators of a level receive the same
// in_valid and out_ready and have the same depth, so their registers hold the same valid bits at
// all times (lockstep): the level's carry pipe stands for all of them, the operators' own
// handshake outputs are equal copies, left unused. in_ready_o depends combinationally on
// out_ready_i (fp_pipe's stall rule). in_tag_i (e.g. the pixel index) travels with the ray.
module rgu_ray #(
  parameter integer EXP_BITS   = 7,
  parameter integer MAN_BITS   = 16,
  parameter integer RNE        = 0,
  parameter integer RAYCORE    = 0,   // rounding mode raycore (hls Rounding::raycore; RNE ignored)
  parameter integer STAGES     = 2,
  parameter integer TAG_BITS   = 32,
  parameter integer COORD_BITS = 16   // pixel coordinates 0 .. 2^COORD_BITS - 1
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  // Camera registers (hls::RguCamera), stable while rays are in flight.
  input  wire [EXP_BITS+MAN_BITS:0] cam_o_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_o_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_o_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_d00_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_d00_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_d00_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dx_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dx_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dx_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dy_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dy_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dy_z_i,
  // Pixels in.
  input  wire                       in_valid_i,
  output wire                       in_ready_o,
  input  wire [COORD_BITS-1:0]      in_x_i,
  input  wire [COORD_BITS-1:0]      in_y_i,
  input  wire [TAG_BITS-1:0]        in_tag_i,
  // Rays out.
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [EXP_BITS+MAN_BITS:0] out_o_x_o,
  output wire [EXP_BITS+MAN_BITS:0] out_o_y_o,
  output wire [EXP_BITS+MAN_BITS:0] out_o_z_o,
  output wire [EXP_BITS+MAN_BITS:0] out_d_x_o,
  output wire [EXP_BITS+MAN_BITS:0] out_d_y_o,
  output wire [EXP_BITS+MAN_BITS:0] out_d_z_o,
  output wire [EXP_BITS+MAN_BITS:0] out_inv_x_o,
  output wire [EXP_BITS+MAN_BITS:0] out_inv_y_o,
  output wire [EXP_BITS+MAN_BITS:0] out_inv_z_o,
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer E     = EXP_BITS;
  localparam integer M     = MAN_BITS;
  localparam integer W     = 1 + E + M;
  localparam integer BIAS  = (1 << (E - 1)) - 1;
  localparam integer EXP_W = E + 3;
  localparam [W-1:0] ONE   = {1'b0, BIAS[E-1:0], {M{1'b0}}};  // 1.0
  localparam integer T     = TAG_BITS;
  localparam integer RND   = RAYCORE != 0 ? 0 : RNE;  // raycore truncates (conversion, sqrt)
  // Registers per level: the L = LPS x STAGES of the latency shared out by the logic each level
  // holds (the registers each needs for 95 FO4, docs/timing.md's operators: the sop with the
  // pixel's conversion 4 over levels 1-2, a mul 1, the add3 3, the square root and each divider
  // 7; QT = 30 in all). LPS = QT / 2, so that at STAGES 2 each level gets its weight: 2 2 1 3 7 7
  // 1 7. Level l takes (L Q_l) / QT - (L Q_l-1) / QT, Q the cumulative weights.
  localparam integer Q1 = 2, Q2 = 4, Q3 = 5, Q4 = 8, Q5 = 15, Q6 = 22, Q7 = 23, QT = 30;
  localparam integer LPS = (QT + 1) / 2;  // rgu.v's and systemc/config.h kRguLevels
  localparam integer L  = LPS * STAGES;
  localparam integer S1 = (L * Q1) / QT;
  localparam integer S2 = (L * Q2) / QT - (L * Q1) / QT;
  localparam integer S3 = (L * Q3) / QT - (L * Q2) / QT;
  localparam integer S4 = (L * Q4) / QT - (L * Q3) / QT;
  localparam integer S5 = (L * Q5) / QT - (L * Q4) / QT;
  localparam integer S6 = (L * Q6) / QT - (L * Q5) / QT;
  localparam integer S7 = (L * Q7) / QT - (L * Q6) / QT;
  localparam integer S8 = L - (L * Q7) / QT;
  wire unused_one = ^ONE;  // not read with RAYCORE = 1 (fp_rcp has its own 1)

  // Level handshakes: v[L] / r[L] = valid / ready at the output of level L (index 0 = the input).
  wire [8:0] v;
  wire [9:1] r;
  assign v[0]       = in_valid_i;
  assign in_ready_o = r[1];
  assign r[9]       = out_ready_i;
  assign out_valid_o = v[8];

  // ---- level 0: the coordinates in the format ---------------------------------------------------
  // value = coord: its top bit (weight 2^(COORD_BITS-1)) has the biased exponent
  // bias + COORD_BITS - 1; M+3 zero bits below make the magnitude wide enough for fp_round.
  localparam integer CM_W = COORD_BITS + M + 3;
  localparam integer COORD_EXP_I = BIAS + COORD_BITS - 1;
  localparam [EXP_W-1:0] COORD_EXP = COORD_EXP_I[EXP_W-1:0];
  wire [W-1:0] fx, fy;
  fp_round #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RND), .MAG_BITS(CM_W), .EXP_W(EXP_W)) u_cvt_x (
    .sign_i(1'b0), .exp_i(COORD_EXP), .mag_i({in_x_i, {(M+3){1'b0}}}), .sticky_i(1'b0),
    .res_o(fx));
  fp_round #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RND), .MAG_BITS(CM_W), .EXP_W(EXP_W)) u_cvt_y (
    .sign_i(1'b0), .exp_i(COORD_EXP), .mag_i({in_y_i, {(M+3){1'b0}}}), .sticky_i(1'b0),
    .res_o(fy));

  // ---- levels 1-2: p[c] = sop(d00[c], -0, fx, dx[c], fy, dy[c]), one rounding ------------------
  // Three fp_sop of S1 + S2 registers each (over its four phases) span levels 1 and 2; the carry
  // pipes of the two levels (S1, S2) hold the same valid bits as the sops' chains.
  localparam [W-1:0] NEG = {1'b1, {(W-1){1'b0}}};  // -0: the absent second addend
  wire [3*W-1:0] l2_d00 = {cam_d00_z_i, cam_d00_y_i, cam_d00_x_i};
  wire [3*W-1:0] l2_dx  = {cam_dx_z_i, cam_dx_y_i, cam_dx_x_i};
  wire [3*W-1:0] l2_dy  = {cam_dy_z_i, cam_dy_y_i, cam_dy_x_i};
  wire [3*W-1:0] l2_p;
  wire [2:0]     l2_unused_v, l2_unused_r;
  wire [T-1:0]   c1_tag, c2_tag;
  fp_pipe #(.WIDTH(T), .STAGES(S1)) u_carry1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(r[1]), .in_data_i(in_tag_i),
    .out_valid_o(v[1]), .out_ready_i(r[2]), .out_data_o(c1_tag));
  fp_pipe #(.WIDTH(T), .STAGES(S2)) u_carry2 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[1]), .in_ready_o(r[2]), .in_data_i(c1_tag),
    .out_valid_o(v[2]), .out_ready_i(r[3]), .out_data_o(c2_tag));
  genvar gj;
  generate
    for (gj = 0; gj < 3; gj = gj + 1) begin : g_l2_sop
      fp_sop_nt #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S1 + S2)) u_sop (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[0]), .in_ready_o(l2_unused_r[gj]),
        .in_a_i(l2_d00[gj*W +: W]), .in_b_i(NEG), .in_x1_i(fx), .in_y1_i(l2_dx[gj*W +: W]),
        .in_x2_i(fy), .in_y2_i(l2_dy[gj*W +: W]), .out_valid_o(l2_unused_v[gj]),
        .out_ready_i(r[3]), .out_res_o(l2_p[gj*W +: W]));
    end
  endgenerate

  // ---- level 3: squares -------------------------------------------------------------------------
  wire [3*W-1:0] l3_sq;
  wire [2:0]     l3_unused_v, l3_unused_r;
  wire [T-1:0]   c3_tag;
  wire [3*W-1:0] c3_p;
  fp_pipe #(.WIDTH(T + 3*W), .STAGES(S3)) u_carry3 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(r[3]),
    .in_data_i({c2_tag, l2_p}), .out_valid_o(v[3]), .out_ready_i(r[4]),
    .out_data_o({c3_tag, c3_p}));
  generate
    for (gj = 0; gj < 3; gj = gj + 1) begin : g_l3_mul
      fp_op2_nt #(.OP("mul"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S3)) u_mul (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[2]), .in_ready_o(l3_unused_r[gj]),
        .in_a_i(l2_p[gj*W +: W]), .in_b_i(l2_p[gj*W +: W]), .out_valid_o(l3_unused_v[gj]),
        .out_ready_i(r[4]), .out_res_o(l3_sq[gj*W +: W]));
    end
  endgenerate

  // ---- level 4: the squared length --------------------------------------------------------------
  wire [W-1:0]   l4_len2;
  wire           l4_unused_v, l4_unused_r;
  wire [T-1:0]   c4_tag;
  wire [3*W-1:0] c4_p;
  fp_pipe #(.WIDTH(T + 3*W), .STAGES(S4)) u_carry4 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[3]), .in_ready_o(r[4]),
    .in_data_i({c3_tag, c3_p}), .out_valid_o(v[4]), .out_ready_i(r[5]),
    .out_data_o({c4_tag, c4_p}));
  fp_add3_nt #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S4)) u_l4_add3 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[3]), .in_ready_o(l4_unused_r),
    .in_a_i(l3_sq[0 +: W]), .in_b_i(l3_sq[W +: W]), .in_c_i(l3_sq[2*W +: W]),
    .out_valid_o(l4_unused_v), .out_ready_i(r[5]), .out_res_o(l4_len2));

  // ---- level 5: the length ----------------------------------------------------------------------
  wire [W-1:0]   l5_len;
  wire           l5_unused_v, l5_unused_r, l5_unused_tag;
  wire [T-1:0]   c5_tag;
  wire [3*W-1:0] c5_p;
  fp_pipe #(.WIDTH(T + 3*W), .STAGES(S5)) u_carry5 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[4]), .in_ready_o(r[5]),
    .in_data_i({c4_tag, c4_p}), .out_valid_o(v[5]), .out_ready_i(r[6]),
    .out_data_o({c5_tag, c5_p}));
  fp_sqrt #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RND), .STAGES(S5)) u_l5_sqrt (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[4]), .in_ready_o(l5_unused_r),
    .in_a_i(l4_len2), .in_tag_i(1'b0), .out_valid_o(l5_unused_v), .out_ready_i(r[6]),
    .out_res_o(l5_len), .out_tag_o(l5_unused_tag));

  // ---- level 6: 1 / length ----------------------------------------------------------------------
  wire [W-1:0]   l6_rl;
  wire           l6_unused_v, l6_unused_r;
  wire [T-1:0]   c6_tag;
  wire [3*W-1:0] c6_p;
  fp_pipe #(.WIDTH(T + 3*W), .STAGES(S6)) u_carry6 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[5]), .in_ready_o(r[6]),
    .in_data_i({c5_tag, c5_p}), .out_valid_o(v[6]), .out_ready_i(r[7]),
    .out_data_o({c6_tag, c6_p}));
  generate
    if (RAYCORE != 0) begin : g_l6_table  // raycore: the table reciprocal (hls::rcp<F, raycore>)
      wire unused_tag;
      fp_rcp #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(S6)) u_l6_rcp (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[5]), .in_ready_o(l6_unused_r),
        .in_a_i(l5_len), .in_tag_i(1'b0), .out_valid_o(l6_unused_v), .out_ready_i(r[7]),
        .out_res_o(l6_rl), .out_tag_o(unused_tag));
    end else begin : g_l6_div  // rtz, rne: 1 / len, rounded once
      fp_op2_nt #(.OP("div"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .STAGES(S6)) u_l6_rcp (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[5]), .in_ready_o(l6_unused_r),
        .in_a_i(ONE), .in_b_i(l5_len), .out_valid_o(l6_unused_v), .out_ready_i(r[7]),
        .out_res_o(l6_rl));
    end
  endgenerate

  // ---- level 7: the normalised direction --------------------------------------------------------
  wire [3*W-1:0] l7_d;
  wire [2:0]     l7_unused_v, l7_unused_r;
  wire [T-1:0]   c7_tag;
  fp_pipe #(.WIDTH(T), .STAGES(S7)) u_carry7 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[6]), .in_ready_o(r[7]), .in_data_i(c6_tag),
    .out_valid_o(v[7]), .out_ready_i(r[8]), .out_data_o(c7_tag));
  generate
    for (gj = 0; gj < 3; gj = gj + 1) begin : g_l7_mul
      fp_op2_nt #(.OP("mul"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(S7)) u_mul (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[6]), .in_ready_o(l7_unused_r[gj]),
        .in_a_i(c6_p[gj*W +: W]), .in_b_i(l6_rl), .out_valid_o(l7_unused_v[gj]),
        .out_ready_i(r[8]), .out_res_o(l7_d[gj*W +: W]));
    end
  endgenerate

  // ---- level 8: the reciprocal direction --------------------------------------------------------
  wire [3*W-1:0] l8_inv;
  wire [2:0]     l8_unused_v, l8_unused_r;
  wire [T-1:0]   c8_tag;
  wire [3*W-1:0] c8_d;
  fp_pipe #(.WIDTH(T + 3*W), .STAGES(S8)) u_carry8 (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[7]), .in_ready_o(r[8]),
    .in_data_i({c7_tag, l7_d}), .out_valid_o(v[8]), .out_ready_i(r[9]),
    .out_data_o({c8_tag, c8_d}));
  generate
    for (gj = 0; gj < 3; gj = gj + 1) begin : g_l8_rcp
      if (RAYCORE != 0) begin : g_table
        wire unused_tag;
        fp_rcp #(.EXP_BITS(E), .MAN_BITS(M), .STAGES(S8)) u_rcp (
          .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[7]), .in_ready_o(l8_unused_r[gj]),
          .in_a_i(l7_d[gj*W +: W]), .in_tag_i(1'b0), .out_valid_o(l8_unused_v[gj]),
          .out_ready_i(r[9]), .out_res_o(l8_inv[gj*W +: W]), .out_tag_o(unused_tag));
      end else begin : g_div
        fp_op2_nt #(.OP("div"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .STAGES(S8)) u_rcp (
          .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(v[7]), .in_ready_o(l8_unused_r[gj]),
          .in_a_i(ONE), .in_b_i(l7_d[gj*W +: W]), .out_valid_o(l8_unused_v[gj]),
          .out_ready_i(r[9]), .out_res_o(l8_inv[gj*W +: W]));
      end
    end
  endgenerate

  // ---- outputs ----------------------------------------------------------------------------------
  assign out_o_x_o   = cam_o_x_i;
  assign out_o_y_o   = cam_o_y_i;
  assign out_o_z_o   = cam_o_z_i;
  assign {out_d_z_o, out_d_y_o, out_d_x_o}       = c8_d;
  assign {out_inv_z_o, out_inv_y_o, out_inv_x_o} = l8_inv;
  assign out_tag_o   = c8_tag;

  // The operators' own handshakes: equal copies of the level's carry pipe's (see above).
  wire unused_hs;
  assign unused_hs = ^{l2_unused_v, l2_unused_r, l3_unused_v,
                       l3_unused_r, l4_unused_v, l4_unused_r, l5_unused_v, l5_unused_r,
                       l5_unused_tag, l6_unused_v, l6_unused_r, l7_unused_v, l7_unused_r,
                       l8_unused_v, l8_unused_r};

endmodule
