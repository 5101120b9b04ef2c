// fp_mul - floating-point multiplier: out_res_o = in_a_i * in_b_i.
//
// Bit-exact twin of hls::mul (hls/fp.h): the exact 2M+2-bit product of the significands, rounded
// once (fp_round), flushed or saturated. A zero operand (exponent field 0) gives a zero signed
// with the xor of the signs.
//
// Phases, each followed by its share of the STAGES pipeline registers (fp_pipe):
//   A: unpack, multiply the significands, add the exponents     B: round, pack
// Cut j holds floor(STAGES*(j+1)/2) - floor(STAGES*j/2) registers (STAGES = 1: output register
// only; 2: one each). Latency = STAGES cycles, throughput one per cycle. in_tag_i travels along.
module fp_mul #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer RNE      = 0,
  parameter integer STAGES   = 2,
  parameter integer TAG_BITS = 1
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  input  wire                       in_valid_i,
  output wire                       in_ready_o,
  input  wire [EXP_BITS+MAN_BITS:0] in_a_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_b_i,
  input  wire [TAG_BITS-1:0]        in_tag_i,
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [EXP_BITS+MAN_BITS:0] out_res_o,
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer E     = EXP_BITS;
  localparam integer M     = MAN_BITS;
  localparam integer W     = 1 + E + M;
  localparam integer P_W   = 2 * M + 2;  // exact product of two (M+1)-bit significands
  localparam integer EXP_W = E + 3;      // signed exponent width for fp_round
  localparam [EXP_W-1:0] BIAS_M1 = (1 << (E - 1)) - 2;  // bias - 1
  localparam integer S_A   = STAGES / 2;
  localparam integer S_B   = STAGES - STAGES / 2;

  // ---- A: unpack, multiply ----------------------------------------------------------------------
  wire           a_sign = in_a_i[W-1] ^ in_b_i[W-1];
  wire           a_spec = ~|in_a_i[W-2:M] | ~|in_b_i[W-2:M];  // a zero operand: a signed zero
  wire [P_W-1:0] a_prod = {{(M+1){1'b0}}, 1'b1, in_a_i[M-1:0]} * {{(M+1){1'b0}}, 1'b1, in_b_i[M-1:0]};
  // The top bit of the product has weight 2^(ea+eb+1): biased ea + eb - bias + 1.
  wire [EXP_W-1:0] a_exp_top = {3'b000, in_a_i[W-2:M]} + {3'b000, in_b_i[W-2:M]} - BIAS_M1;

  localparam integer PA_W = TAG_BITS + 1 + 1 + EXP_W + P_W;
  wire [PA_W-1:0] pa_out;
  wire            va, ra;
  fp_pipe #(.WIDTH(PA_W), .STAGES(S_A)) u_pipe_a (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
    .in_data_i({in_tag_i, a_spec, a_sign, a_exp_top, a_prod}),
    .out_valid_o(va), .out_ready_i(ra), .out_data_o(pa_out)
  );

  // ---- B: round once, pack ----------------------------------------------------------------------
  wire [TAG_BITS-1:0]     b_tag;
  wire                    b_spec, b_sign;
  wire [EXP_W-1:0]        b_exp_top;
  wire [P_W-1:0]          b_prod;
  assign {b_tag, b_spec, b_sign, b_exp_top, b_prod} = pa_out;
  wire [W-1:0] b_rounded;
  fp_round #(
    .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .MAG_BITS(P_W), .EXP_W(EXP_W)
  ) u_round (
    .sign_i(b_sign), .exp_i(b_exp_top), .mag_i(b_prod), .sticky_i(1'b0), .res_o(b_rounded)
  );
  wire [W-1:0] b_res = b_spec ? {b_sign, {(W-1){1'b0}}} : b_rounded;

  fp_pipe #(.WIDTH(TAG_BITS + W), .STAGES(S_B)) u_pipe_b (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(va), .in_ready_o(ra), .in_data_i({b_tag, b_res}),
    .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_data_o({out_tag_o, out_res_o})
  );

endmodule
