// fp_add - floating-point adder/subtractor: out_res_o = in_a_i + (in_sub_i ? -in_b_i : in_b_i).
//
// Bit-exact twin of hls::add / hls::sub (hls/fp.h): align the smaller operand to the larger with
// three guard bits (what falls off is jammed into the lowest bit), add or subtract, round once
// (fp_round). RAYCORE = 1 (hls Rounding::raycore, RayCore's adder; RNE is then ignored): one guard
// bit and no jam (what falls off is dropped), then truncation. Zero = exponent field 0 on input;
// one zero operand returns the other operand's bits;
// two zeros give -0 only if both are -0; an exact cancellation gives +0.
//
// Phases, each followed by its share of the STAGES pipeline registers (fp_pipe):
//   A: unpack, order by magnitude, align + jam     B: add/subtract     C: round, pack
// STAGES registers are spread over the cuts after A, B and C: cut j holds
// floor(STAGES*(j+1)/3) - floor(STAGES*j/3) registers (STAGES = 1: output register only;
// 2: after B and at the output; 3: one each). Latency = STAGES cycles, throughput one per cycle.
// in_tag_i travels with the operands (a sideband for the user, e.g. an index).
module fp_add #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer RNE      = 0,
  parameter integer RAYCORE  = 0,
  parameter integer STAGES   = 2,
  parameter integer TAG_BITS = 1
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  input  wire                       in_valid_i,
  output wire                       in_ready_o,
  input  wire [EXP_BITS+MAN_BITS:0] in_a_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_b_i,
  input  wire                       in_sub_i,
  input  wire [TAG_BITS-1:0]        in_tag_i,
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [EXP_BITS+MAN_BITS:0] out_res_o,
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer E     = EXP_BITS;
  localparam integer M     = MAN_BITS;
  localparam integer W     = 1 + E + M;
  localparam integer G     = RAYCORE != 0 ? 1 : 3;  // guard bits below the larger operand's lsb
  localparam integer RND   = RAYCORE != 0 ? 0 : RNE;
  localparam integer EXP_W = E + 3;      // signed exponent width for fp_round
  localparam integer S_A   = STAGES / 3;
  localparam integer S_B   = (2 * STAGES) / 3 - STAGES / 3;
  localparam integer S_C   = STAGES - (2 * STAGES) / 3;

  // ---- A: unpack, order by magnitude, align ---------------------------------------------------
  wire [W-1:0] b_eff = {in_b_i[W-1] ^ in_sub_i, in_b_i[W-2:0]};
  wire         za    = ~|in_a_i[W-2:M];
  wire         zb    = ~|b_eff[W-2:M];
  wire         swap  = in_a_i[W-2:0] < b_eff[W-2:0];
  wire [W-1:0] hi    = swap ? b_eff : in_a_i;                // the larger magnitude
  wire [W-1:0] lo    = swap ? in_a_i : b_eff;
  wire [E-1:0] diff  = hi[W-2:M] - lo[W-2:M];                // >= 0
  wire [M+G:0] mb_x  = {1'b1, lo[M-1:0], {G{1'b0}}};         // smaller significand, guard bits
  wire [M+G:0] lost  = mb_x & ~({(M+G+1){1'b1}} << diff);    // the bits shifted out
  wire         jam   = RAYCORE == 0 && |lost;                // raycore: no sticky
  wire [M+G:0] a_mb  = (mb_x >> diff) | {{(M+G){1'b0}}, jam};   // aligned and jammed

  // Special results (a zero operand): the other operand, or a zero signed like IEEE's.
  wire         a_spec     = za | zb;
  wire [W-1:0] a_spec_res = (za && zb) ? {in_a_i[W-1] & b_eff[W-1], {(W-1){1'b0}}}
                                       : (za ? b_eff : in_a_i);

  localparam integer PA_W = TAG_BITS + W + 1 + 1 + 1 + E + M + (M + G + 1);
  wire [PA_W-1:0] pa_in = {in_tag_i, a_spec_res, a_spec, hi[W-1], hi[W-1] ^ lo[W-1],
                           hi[W-2:M], hi[M-1:0], a_mb};
  wire [PA_W-1:0] pa_out;
  wire            va, ra;
  fp_pipe #(.WIDTH(PA_W), .STAGES(S_A)) u_pipe_a (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(in_valid_i), .in_ready_o(in_ready_o), .in_data_i(pa_in),
    .out_valid_o(va), .out_ready_i(ra), .out_data_o(pa_out)
  );

  // ---- B: add or subtract (|hi| >= |lo|: no borrow) -----------------------------------------
  wire [TAG_BITS-1:0] b_tag;
  wire [W-1:0]        b_spec_res;
  wire                b_spec, b_sign, b_eff_sub;
  wire [E-1:0]        b_exp;
  wire [M-1:0]        b_man;
  wire [M+G:0]        b_mb;
  assign {b_tag, b_spec_res, b_spec, b_sign, b_eff_sub, b_exp, b_man, b_mb} = pa_out;
  wire [M+G+1:0] ma  = {2'b01, b_man, {G{1'b0}}};
  wire [M+G+1:0] mag = b_eff_sub ? ma - {1'b0, b_mb} : ma + {1'b0, b_mb};

  localparam integer PB_W = TAG_BITS + W + 1 + 1 + E + (M + G + 2);
  wire [PB_W-1:0] pb_out;
  wire            vb, rb;
  fp_pipe #(.WIDTH(PB_W), .STAGES(S_B)) u_pipe_b (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(va), .in_ready_o(ra), .in_data_i({b_tag, b_spec_res, b_spec, b_sign, b_exp, mag}),
    .out_valid_o(vb), .out_ready_i(rb), .out_data_o(pb_out)
  );

  // ---- C: round once, pack --------------------------------------------------------------------
  wire [TAG_BITS-1:0] c_tag;
  wire [W-1:0]        c_spec_res;
  wire                c_spec, c_sign;
  wire [E-1:0]        c_exp;
  wire [M+G+1:0]      c_mag;
  assign {c_tag, c_spec_res, c_spec, c_sign, c_exp, c_mag} = pb_out;
  // The top bit of mag has weight 2^(ea+1): biased exponent field + 1.
  wire signed [EXP_W-1:0] c_exp_top = $signed({3'b000, c_exp}) + 1;
  wire [W-1:0]            c_rounded;
  fp_round #(
    .EXP_BITS(E), .MAN_BITS(M), .RNE(RND), .MAG_BITS(M + G + 2), .EXP_W(EXP_W)
  ) u_round (
    .sign_i(c_sign), .exp_i(c_exp_top), .mag_i(c_mag), .sticky_i(1'b0), .res_o(c_rounded)
  );
  wire [W-1:0] c_res = c_spec ? c_spec_res : c_rounded;

  fp_pipe #(.WIDTH(TAG_BITS + W), .STAGES(S_C)) u_pipe_c (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(vb), .in_ready_o(rb), .in_data_i({c_tag, c_res}),
    .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_data_o({out_tag_o, out_res_o})
  );

endmodule
