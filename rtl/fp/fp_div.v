// fp_div - floating-point divider: out_res_o = in_a_i / in_b_i.
//
// Bit-exact twin of hls::div (hls/fp.h): the quotient of the significands to M+4 bits (M+3 or M+4
// significant) by restoring division, one quotient bit per step, plus a sticky bit for a nonzero
// remainder, rounded once (fp_round). x / 0 saturates with the sign of the quotient, 0 / 0 is +0,
// 0 / x is a zero signed with the xor of the signs.
//
// Phases: step i (i = 0 .. M+3) computes quotient bit M+3-i (step 0 also unpacks); then round,
// pack. Each is followed by its share of the STAGES pipeline registers (fp_pipe): cut j
// (j = 0 .. M+4, the last one after rounding) holds floor(STAGES*(j+1)/(M+5)) -
// floor(STAGES*j/(M+5)) registers, i.e. evenly spread with the last one at the output.
// Latency = STAGES cycles, throughput one per cycle. in_tag_i travels along.
module fp_div #(
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
  localparam integer NQ    = M + 4;      // quotient bits = division steps
  localparam integer NC    = NQ + 1;     // cuts: after each step, after rounding
  localparam integer EXP_W = E + 3;      // signed exponent width for fp_round
  localparam [EXP_W-1:0] BIAS = (1 << (E - 1)) - 1;

  // Payload between the steps: tag, sign, special, saturate, exponent, divisor mantissa field,
  // partial remainder (< 2 * divisor), quotient bits so far (in the low bits).
  localparam integer PW = TAG_BITS + 3 + EXP_W + M + (M + 2) + NQ;

  // Index i: before step i (index NQ: the finished quotient).
  wire [NQ:0]          valid  /* verilator split_var */;
  wire [NQ:0]          ready  /* verilator split_var */;
  wire [(NQ+1)*PW-1:0] stage  /* verilator split_var */;

  // ---- unpack, special cases ---------------------------------------------------------------------
  wire za   = ~|in_a_i[W-2:M];
  wire zb   = ~|in_b_i[W-2:M];
  wire sign = (in_a_i[W-1] ^ in_b_i[W-1]) & ~(za & zb);  // 0 / 0 = +0
  // The quotient's top bit (weight 2^(ea-eb)) has the biased exponent ea - eb + bias.
  wire [EXP_W-1:0] exp_top = {3'b000, in_a_i[W-2:M]} - {3'b000, in_b_i[W-2:M]} + BIAS;
  assign valid[0] = in_valid_i;
  assign in_ready_o = ready[0];
  assign stage[PW-1:0] = {in_tag_i, sign, za | zb, zb & ~za, exp_top, in_b_i[M-1:0],
                          {1'b0, 1'b1, in_a_i[M-1:0]}, {NQ{1'b0}}};

  // ---- restoring division: one quotient bit per step ---------------------------------------------
  genvar i;
  generate
    for (i = 0; i < NQ; i = i + 1) begin : g_step
      localparam integer S_I = (STAGES * (i + 1)) / NC - (STAGES * i) / NC;
      wire [TAG_BITS-1:0] tag;
      wire [2:0]          flags;
      wire [EXP_W-1:0]    exp_q;
      wire [M-1:0]        d_man;
      wire [M+1:0]        rem;
      wire [NQ-1:0]       quo;
      assign {tag, flags, exp_q, d_man, rem, quo} = stage[i*PW +: PW];
      wire [M+2:0] diff  = {1'b0, rem} - {2'b01, d_man};  // rem - divisor, with a borrow bit
      wire         q_bit = ~diff[M+2];
      wire [M+1:0] rem_n = q_bit ? diff[M+1:0] : rem;    // < divisor
      wire [PW-1:0] next = {tag, flags, exp_q, d_man, rem_n[M:0], 1'b0, quo[NQ-2:0], q_bit};
      // Always zero: the remainder is below the divisor, the quotient's top bit is not yet set.
      wire unused_zero = rem_n[M+1] | quo[NQ-1];
      fp_pipe #(.WIDTH(PW), .STAGES(S_I)) u_pipe (
        .clk_i(clk_i), .rst_ni(rst_ni),
        .in_valid_i(valid[i]), .in_ready_o(ready[i]), .in_data_i(next),
        .out_valid_o(valid[i+1]), .out_ready_i(ready[i+1]), .out_data_o(stage[(i+1)*PW +: PW])
      );
    end
  endgenerate

  // ---- round once, pack -------------------------------------------------------------------------
  wire [TAG_BITS-1:0] r_tag;
  wire                r_sign, r_spec, r_sat;
  wire [EXP_W-1:0]    r_exp_top;
  wire [M-1:0]        r_d_man;
  wire [M+1:0]        r_rem;
  wire [NQ-1:0]       r_quo;
  assign {r_tag, r_sign, r_spec, r_sat, r_exp_top, r_d_man, r_rem, r_quo} = stage[NQ*PW +: PW];
  wire [W-1:0] r_rounded;
  fp_round #(
    .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .MAG_BITS(NQ), .EXP_W(EXP_W)
  ) u_round (
    .sign_i(r_sign), .exp_i(r_exp_top), .mag_i(r_quo), .sticky_i(|r_rem), .res_o(r_rounded)
  );
  wire [W-1:0] r_res = r_spec ? {r_sign, {(W-1){r_sat}}} : r_rounded;
  // The divisor is not needed after the last step.
  wire unused_d_man = ^r_d_man;

  fp_pipe #(.WIDTH(TAG_BITS + W), .STAGES(STAGES - (STAGES * NQ) / NC)) u_pipe_out (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(valid[NQ]), .in_ready_o(ready[NQ]), .in_data_i({r_tag, r_res}),
    .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_data_o({out_tag_o, out_res_o})
  );

endmodule
