// fp_sqrt - floating-point square root: out_res_o = sqrt(in_a_i).
//
// Bit-exact twin of hls::sqrt (hls/fp.h): the root of the significand, digit by digit (restoring,
// one root bit per step), M+4 bits (M+3 or M+4 significant), plus a sticky bit for a nonzero
// remainder, rounded once (fp_round). sqrt(+-0) keeps the zero's sign; the root of a negative
// number is +0 (there is no NaN). The result's exponent is always in range (no flush, no
// saturation).
//
// With e the unbiased exponent and sig the significand with its hidden one, the radicand is
// x = sig << (M+6) for even e and sig << (M+5) for odd e, in 2M+8 bits (so (e - M - shift) is even
// and the root has M+4 bits, the top one zero for odd e: hls starts at x's top pair instead, which
// only skips leading zero digits). x's low M+5 bits are zero; only its top M+3 bits travel. The
// root's top bit has the biased exponent ceil(e/2) + bias = (biased e + bias + 1) / 2.
//
// Phases: step i (i = 0 .. M+3) computes root bit M+3-i (step 0 also unpacks); then round, pack.
// Each is followed by its share of the STAGES pipeline registers (fp_pipe): cut j (j = 0 .. M+4,
// the last one after rounding) holds floor(STAGES*(j+1)/(M+5)) - floor(STAGES*j/(M+5)) registers,
// i.e. evenly spread with the last one at the output (as fp_div). Latency = STAGES cycles,
// throughput one per cycle. in_tag_i travels along.
module fp_sqrt #(
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
  input  wire [TAG_BITS-1:0]        in_tag_i,
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [EXP_BITS+MAN_BITS:0] out_res_o,
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer E     = EXP_BITS;
  localparam integer M     = MAN_BITS;
  localparam integer W     = 1 + E + M;
  localparam integer NQ    = M + 4;      // root bits = steps
  localparam integer NC    = NQ + 1;     // cuts: after each step, after rounding
  localparam integer EXP_W = E + 3;      // exponent width for fp_round
  localparam integer XW    = M + 3;      // the radicand's top bits (the rest are zero)
  localparam integer XZ    = M + 5;      // the radicand's zero low bits
  localparam integer RW    = M + 5;      // remainder (<= 2 * root)
  localparam [EXP_W-1:0] BIAS = (1 << (E - 1)) - 1;

  // Payload between the steps: tag, special, special sign, exponent, radicand's top bits,
  // remainder, root bits so far (in the low bits).
  localparam integer PW = TAG_BITS + 2 + EXP_W + XW + RW + NQ;

  // Index i: before step i (index NQ: the finished root).
  wire [NQ:0]          valid  /* verilator split_var */;
  wire [NQ:0]          ready  /* verilator split_var */;
  wire [(NQ+1)*PW-1:0] stage  /* verilator split_var */;

  // ---- unpack, special cases --------------------------------------------------------------------
  wire za        = ~|in_a_i[W-2:M];
  wire spec      = za | in_a_i[W-1];        // zero or negative: no root to compute
  wire spec_sign = za & in_a_i[W-1];        // sqrt(-0) = -0; sqrt(negative) = +0
  // e odd <=> the biased exponent is even (the bias is odd).
  wire             e_odd   = ~in_a_i[M];
  wire [EXP_W-1:0] exp_top = ({3'b000, in_a_i[W-2:M]} + BIAS + 1'b1) >> 1;
  wire [XW-1:0]    x_top   = e_odd ? {2'b00, 1'b1, in_a_i[M-1:0]}
                                    : {1'b0, 1'b1, in_a_i[M-1:0], 1'b0};
  assign valid[0] = in_valid_i;
  assign in_ready_o = ready[0];
  assign stage[PW-1:0] = {in_tag_i, spec, spec_sign, exp_top, x_top, {RW{1'b0}}, {NQ{1'b0}}};

  // ---- restoring square root: one root bit per step ---------------------------------------------
  genvar i;
  generate
    for (i = 0; i < NQ; i = i + 1) begin : g_step
      localparam integer S_I = (STAGES * (i + 1)) / NC - (STAGES * i) / NC;
      wire [TAG_BITS-1:0] tag;
      wire [1:0]          flags;
      wire [EXP_W-1:0]    exp_q;
      wire [XW-1:0]       x_q;
      wire [RW-1:0]       rem;
      wire [NQ-1:0]       root;
      assign {tag, flags, exp_q, x_q, rem, root} = stage[i*PW +: PW];
      // The radicand's pair for this step: bits [HI : HI-1] of {x_q, XZ zeros}.
      localparam integer HI = XW + XZ - 1 - 2 * i;
      wire [1:0] pair;
      if (HI - 1 >= XZ) begin : g_in
        assign pair = x_q[HI-XZ -: 2];
      end else if (HI >= XZ) begin : g_edge
        assign pair = {x_q[0], 1'b0};
      end else begin : g_zero
        assign pair = 2'b00;
      end
      wire [RW+1:0]    rem2   = {rem, pair};                            // bring down the next pair
      wire [RW+1:0]    trial  = {{(RW-NQ){1'b0}}, root, 2'b01};         // 4 * root + 1
      wire [RW+2:0]    diff   = {1'b0, rem2} - {1'b0, trial};           // with a borrow bit
      wire             r_bit  = ~diff[RW+2];
      wire [RW+1:0]    rem_n  = r_bit ? diff[RW+1:0] : rem2;            // <= 2 * new root
      wire [PW-1:0]    next   = {tag, flags, exp_q, x_q, rem_n[RW-1:0], root[NQ-2:0], r_bit};
      // Always zero: the remainder is at most twice the root, the root's top bit is not yet set.
      wire unused_zero = |rem_n[RW+1:RW] | root[NQ-1];
      fp_pipe #(.WIDTH(PW), .STAGES(S_I)) u_pipe (
        .clk_i(clk_i), .rst_ni(rst_ni),
        .in_valid_i(valid[i]), .in_ready_o(ready[i]), .in_data_i(next),
        .out_valid_o(valid[i+1]), .out_ready_i(ready[i+1]), .out_data_o(stage[(i+1)*PW +: PW])
      );
    end
  endgenerate

  // ---- round once, pack -------------------------------------------------------------------------
  wire [TAG_BITS-1:0] r_tag;
  wire                r_spec, r_spec_sign;
  wire [EXP_W-1:0]    r_exp_top;
  wire [XW-1:0]       r_x;
  wire [RW-1:0]       r_rem;
  wire [NQ-1:0]       r_root;
  assign {r_tag, r_spec, r_spec_sign, r_exp_top, r_x, r_rem, r_root} = stage[NQ*PW +: PW];
  wire [W-1:0] r_rounded;
  fp_round #(
    .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .MAG_BITS(NQ), .EXP_W(EXP_W)
  ) u_round (
    .sign_i(1'b0), .exp_i(r_exp_top), .mag_i(r_root), .sticky_i(|r_rem), .res_o(r_rounded)
  );
  wire [W-1:0] r_res = r_spec ? {r_spec_sign, {(W-1){1'b0}}} : r_rounded;
  // The radicand is not needed after the last step.
  wire unused_x = ^r_x;

  fp_pipe #(.WIDTH(TAG_BITS + W), .STAGES(STAGES - (STAGES * NQ) / NC)) u_pipe_out (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(valid[NQ]), .in_ready_o(ready[NQ]), .in_data_i({r_tag, r_res}),
    .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_data_o({out_tag_o, out_res_o})
  );

endmodule
