// fp_sop - sum of two addends and two products, rounded once:
//   out_res_o = in_a_i + in_b_i + in_x1_i * in_y1_i + in_x2_i * in_y2_i.
//
// Bit-exact twin of hls::sop (hls/fp.h) and built the same way: every term exact (a number's
// M+1-bit significand, a product's exact 2M+2-bit one); T = the top of the largest nonzero term by
// exponents only (a number x < 2^(ex+1), a product x*y < 2^(ex+ey+2)); each term aligned to a
// signed accumulator whose lsb is 2^(T-S), S = 3M+7, its bits below that lsb jammed into bit 0 (a
// term entirely below: 1); the four signed terms added exactly (|sum| < 2^(S+2)); rounded once
// (fp_round). Zero terms (a zero number, or a product with a zero factor; exponent field 0) add
// nothing; every term zero gives -0 if every term is negative (a product's sign is the xor of its
// factors'), else +0; an exact zero sum gives +0. Absent terms are signed zeros: the VTU passes
// -0 for an absent addend and -0 * +0 for an absent product (hls/vtu.h).
//
// Exponents: a term's top is kept as U = top + 2*bias (a number: its exponent field + bias + 1; a
// product: the sum of its factors' fields + 2; 0 for a zero term), E+2 bits (U <= 2^(E+1)); the
// accumulator's top magnitude bit (bit S+1) has weight 2^(T+1), i.e. biased exponent U_T - bias + 1
// for fp_round, which normalises, rounds, flushes and saturates.
//
// Phases, each followed by its share of the STAGES pipeline registers (fp_pipe):
//   A: unpack, the two exact (M+1)x(M+1) products, the terms' tops, T = the largest nonzero top,
//      each term's distance below T, the all-zero case and its sign
//   B: align the four terms to the accumulator (jam)   C: four-input signed sum
//   D: absolute value, round once (fp_round), pack
// (The absolute value in D, not C: C's four-input add and a negation in one phase were vtu.v's
// slowest path at STAGES 2, 96.8 FO4; split so, 88.7 FO4, D's.)
// Cut j holds floor(STAGES*(j+1)/4) - floor(STAGES*j/4) registers (STAGES = 1: output register
// only; 2: after B and at the output; 4: one each; 0: combinational). Latency = STAGES cycles, one
// op per cycle. in_tag_i travels along.
//
// RAYCORE = 1 (hls Rounding::raycore; RNE is then ignored): the same datapath, truncated once (as
// rtz: hls::round_pack<raycore> truncates).
// lint: also STAGES=3
// lint: also STAGES=6 RAYCORE=1
module fp_sop #(
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
  input  wire [EXP_BITS+MAN_BITS:0] in_x1_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_y1_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_x2_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_y2_i,
  input  wire [TAG_BITS-1:0]        in_tag_i,
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [EXP_BITS+MAN_BITS:0] out_res_o,
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer E     = EXP_BITS;
  localparam integer M     = MAN_BITS;
  localparam integer W     = 1 + E + M;
  localparam integer RND   = RAYCORE != 0 ? 0 : RNE;  // raycore truncates, as rtz
  localparam integer BIAS  = (1 << (E - 1)) - 1;
  localparam integer S     = 3 * M + 7;              // the accumulator's lsb is 2^(T-S)
  localparam integer P_W   = 2 * M + 2;              // exact product of two (M+1)-bit significands
  localparam integer ACC_W = S + 3;                  // signed accumulator: |sum| < 2^(S+2)
  localparam integer SH_W  = $clog2(S + 1);          // a distance, saturated at S
  // A term's top + 2*bias (0 .. 2^(E+1)) and distances below T: E+2 bits, at least SH_W.
  localparam integer U_W   = E + 2 > SH_W ? E + 2 : SH_W;
  // Signed exponent for fp_round: U_T - bias + 1 (>= 5 - bias) less up to S+1 leading zeros, up to
  // 2^(E+1) - bias + 2 after a rounding carry.
  localparam integer EXP_W = $clog2((1 << (E + 1)) + 3 * M + 16) + 1;
  localparam integer S_A   = STAGES / 4;
  localparam integer S_B   = (2 * STAGES) / 4 - STAGES / 4;
  localparam integer S_C   = (3 * STAGES) / 4 - (2 * STAGES) / 4;
  localparam integer S_D   = STAGES - (3 * STAGES) / 4;
  localparam integer NUM_OFF_I = BIAS + 1;           // a number's U = field + bias + 1
  localparam integer EXP_OFF_I = BIAS - 1;           // fp_round's exp_i = U_T - (bias - 1)
  localparam integer TWO_I     = 2;                  // a product's U = field + field + 2
  localparam [U_W-1:0]   NUM_OFF  = NUM_OFF_I[U_W-1:0];
  localparam [U_W-1:0]   PROD_OFF = TWO_I[U_W-1:0];
  localparam [U_W-1:0]   D_SAT    = S[U_W-1:0];     // distances >= S: the term is entirely below
  localparam [SH_W-1:0]  SH_SAT   = S[SH_W-1:0];
  localparam [EXP_W-1:0] EXP_OFF  = EXP_OFF_I[EXP_W-1:0];

  // ---- A: unpack, products, tops, T, distances --------------------------------------------------
  wire za  = ~|in_a_i[W-2:M];
  wire zb  = ~|in_b_i[W-2:M];
  wire zp1 = ~|in_x1_i[W-2:M] | ~|in_y1_i[W-2:M];
  wire zp2 = ~|in_x2_i[W-2:M] | ~|in_y2_i[W-2:M];
  wire sa  = in_a_i[W-1];
  wire sb  = in_b_i[W-1];
  wire sp1 = in_x1_i[W-1] ^ in_y1_i[W-1];
  wire sp2 = in_x2_i[W-1] ^ in_y2_i[W-1];
  // Every term zero: a signed zero, negative only if every term is.
  wire a_zero  = za & zb & zp1 & zp2;
  wire a_zsign = sa & sb & sp1 & sp2;
  wire [P_W-1:0] a_p1 = {{(M+1){1'b0}}, 1'b1, in_x1_i[M-1:0]}
                      * {{(M+1){1'b0}}, 1'b1, in_y1_i[M-1:0]};
  wire [P_W-1:0] a_p2 = {{(M+1){1'b0}}, 1'b1, in_x2_i[M-1:0]}
                      * {{(M+1){1'b0}}, 1'b1, in_y2_i[M-1:0]};
  // Tops (U = top + 2*bias; 0 for a zero term, below every nonzero one: those are >= 4).
  localparam integer UX = U_W - E;  // zero extension of an exponent field to U_W bits (>= 2)
  wire [U_W-1:0] ua  = za  ? {U_W{1'b0}} : {{UX{1'b0}}, in_a_i[W-2:M]} + NUM_OFF;
  wire [U_W-1:0] ub  = zb  ? {U_W{1'b0}} : {{UX{1'b0}}, in_b_i[W-2:M]} + NUM_OFF;
  wire [U_W-1:0] up1 = zp1 ? {U_W{1'b0}}
                           : {{UX{1'b0}}, in_x1_i[W-2:M]} + {{UX{1'b0}}, in_y1_i[W-2:M]} + PROD_OFF;
  wire [U_W-1:0] up2 = zp2 ? {U_W{1'b0}}
                           : {{UX{1'b0}}, in_x2_i[W-2:M]} + {{UX{1'b0}}, in_y2_i[W-2:M]} + PROD_OFF;
  wire [U_W-1:0] t_ab = ua > ub ? ua : ub;
  wire [U_W-1:0] t_p  = up1 > up2 ? up1 : up2;
  wire [U_W-1:0] a_t  = t_ab > t_p ? t_ab : t_p;
  // Distances below T (a nonzero term's U <= T), saturated at S: a shift by S leaves nothing but
  // the jammed bit.
  wire [U_W-1:0]  da  = a_t - ua;
  wire [U_W-1:0]  db  = a_t - ub;
  wire [U_W-1:0]  dp1 = a_t - up1;
  wire [U_W-1:0]  dp2 = a_t - up2;
  wire [SH_W-1:0] da_s  = da  > D_SAT ? SH_SAT : da[SH_W-1:0];
  wire [SH_W-1:0] db_s  = db  > D_SAT ? SH_SAT : db[SH_W-1:0];
  wire [SH_W-1:0] dp1_s = dp1 > D_SAT ? SH_SAT : dp1[SH_W-1:0];
  wire [SH_W-1:0] dp2_s = dp2 > D_SAT ? SH_SAT : dp2[SH_W-1:0];

  localparam integer PA_W = TAG_BITS + 2 + U_W + 4 + 4 + 4 * SH_W + 2 * M + 2 * P_W;
  wire [PA_W-1:0] pa_out;
  wire            va, ra;
  fp_pipe #(.WIDTH(PA_W), .STAGES(S_A)) u_pipe_a (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
    .in_data_i({in_tag_i, a_zero, a_zsign, a_t, za, zb, zp1, zp2, sa, sb, sp1, sp2,
                da_s, db_s, dp1_s, dp2_s,
                in_a_i[M-1:0], in_b_i[M-1:0], a_p1, a_p2}),
    .out_valid_o(va), .out_ready_i(ra), .out_data_o(pa_out)
  );

  // ---- B: align the four terms to the accumulator, jam ------------------------------------------
  wire [TAG_BITS-1:0] b_tag;
  wire                b_zero, b_zsign, b_za, b_zb, b_zp1, b_zp2, b_sa, b_sb, b_sp1, b_sp2;
  wire [U_W-1:0]      b_t;
  wire [SH_W-1:0]     b_da, b_db, b_dp1, b_dp2;
  wire [M-1:0]        b_ma, b_mb;
  wire [P_W-1:0]      b_p1, b_p2;
  assign {b_tag, b_zero, b_zsign, b_t, b_za, b_zb, b_zp1, b_zp2, b_sa, b_sb, b_sp1, b_sp2,
          b_da, b_db, b_dp1, b_dp2, b_ma, b_mb, b_p1, b_p2} = pa_out;
  // Each term with its top at the accumulator's top (distance 0): a number's significand, a
  // product's, left-justified in S bits.
  wire [S-1:0] top_a  = {1'b1, b_ma, {(S-M-1){1'b0}}};
  wire [S-1:0] top_b  = {1'b1, b_mb, {(S-M-1){1'b0}}};
  wire [S-1:0] top_p1 = {b_p1, {(S-P_W){1'b0}}};
  wire [S-1:0] top_p2 = {b_p2, {(S-P_W){1'b0}}};
  wire [S-1:0] lost_a  = top_a  & ~({S{1'b1}} << b_da);
  wire [S-1:0] lost_b  = top_b  & ~({S{1'b1}} << b_db);
  wire [S-1:0] lost_p1 = top_p1 & ~({S{1'b1}} << b_dp1);
  wire [S-1:0] lost_p2 = top_p2 & ~({S{1'b1}} << b_dp2);
  // A zero term adds nothing; a nonzero one shifted by S is its jammed bit alone.
  wire [S-1:0] ma  = b_za  ? {S{1'b0}} : (top_a  >> b_da)  | {{(S-1){1'b0}}, |lost_a};
  wire [S-1:0] mb  = b_zb  ? {S{1'b0}} : (top_b  >> b_db)  | {{(S-1){1'b0}}, |lost_b};
  wire [S-1:0] mp1 = b_zp1 ? {S{1'b0}} : (top_p1 >> b_dp1) | {{(S-1){1'b0}}, |lost_p1};
  wire [S-1:0] mp2 = b_zp2 ? {S{1'b0}} : (top_p2 >> b_dp2) | {{(S-1){1'b0}}, |lost_p2};

  localparam integer PB_W = TAG_BITS + 2 + U_W + 4 + 4 * S;
  wire [PB_W-1:0] pb_out;
  wire            vb, rb;
  fp_pipe #(.WIDTH(PB_W), .STAGES(S_B)) u_pipe_b (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(va), .in_ready_o(ra),
    .in_data_i({b_tag, b_zero, b_zsign, b_t, b_sa, b_sb, b_sp1, b_sp2, ma, mb, mp1, mp2}),
    .out_valid_o(vb), .out_ready_i(rb), .out_data_o(pb_out)
  );

  // ---- C: signed four-input sum ----------------------------------------------------------------
  wire [TAG_BITS-1:0] c_tag;
  wire                c_zero, c_zsign, c_sa, c_sb, c_sp1, c_sp2;
  wire [U_W-1:0]      c_t;
  wire [S-1:0]        c_ma, c_mb, c_mp1, c_mp2;
  assign {c_tag, c_zero, c_zsign, c_t, c_sa, c_sb, c_sp1, c_sp2, c_ma, c_mb, c_mp1, c_mp2} = pb_out;
  wire [ACC_W-1:0] ta  = {3'b000, c_ma};
  wire [ACC_W-1:0] tb  = {3'b000, c_mb};
  wire [ACC_W-1:0] tp1 = {3'b000, c_mp1};
  wire [ACC_W-1:0] tp2 = {3'b000, c_mp2};
  wire [ACC_W-1:0] sum = (c_sa ? -ta : ta) + (c_sb ? -tb : tb) + (c_sp1 ? -tp1 : tp1)
                         + (c_sp2 ? -tp2 : tp2);
  // The signed sum goes to phase D, which takes its absolute value (a carry chain of its own,
  // kept out of this phase's four-input add).
  wire             c_sign = sum[ACC_W-1];
  wire [ACC_W-2:0] c_mag  = sum[ACC_W-2:0];

  localparam integer PC_W = TAG_BITS + 2 + U_W + 1 + (ACC_W - 1);
  wire [PC_W-1:0] pc_out;
  wire            vc, rc;
  fp_pipe #(.WIDTH(PC_W), .STAGES(S_C)) u_pipe_c (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(vb), .in_ready_o(rb),
    .in_data_i({c_tag, c_zero, c_zsign, c_t, c_sign, c_mag}),
    .out_valid_o(vc), .out_ready_i(rc), .out_data_o(pc_out)
  );

  // ---- D: absolute value, round once, pack ------------------------------------------------------
  wire [TAG_BITS-1:0] d_tag;
  wire                d_zero, d_zsign, d_sign;
  wire [U_W-1:0]      d_t;
  wire [ACC_W-2:0]    d_sum;
  assign {d_tag, d_zero, d_zsign, d_t, d_sign, d_sum} = pc_out;
  // |sum| by fp_mag's prefix OR (not ~d_sum + 1's carry chain, once this phase's slowest path).
  wire [ACC_W-2:0]    d_mag;
  fp_mag #(.WIDTH(ACC_W - 1)) u_mag (.x_i(d_sum), .neg_i(d_sign), .mag_o(d_mag));
  // The accumulator's top magnitude bit has weight 2^(T+1): biased exponent U_T - bias + 1.
  wire [EXP_W-1:0] d_exp_top = {{(EXP_W-U_W){1'b0}}, d_t} - EXP_OFF;  // EXP_W > U_W
  wire [W-1:0]     d_rounded;
  fp_round #(
    .EXP_BITS(E), .MAN_BITS(M), .RNE(RND), .MAG_BITS(ACC_W - 1), .EXP_W(EXP_W)
  ) u_round (
    .sign_i(d_sign), .exp_i(d_exp_top), .mag_i(d_mag), .sticky_i(1'b0), .res_o(d_rounded)
  );
  // Every term zero: -0 iff every term is negative. An exact zero sum: fp_round gives +0.
  wire [W-1:0] d_res = d_zero ? {d_zsign, {(W-1){1'b0}}} : d_rounded;

  fp_pipe #(.WIDTH(TAG_BITS + W), .STAGES(S_D)) u_pipe_d (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(vc), .in_ready_o(rc), .in_data_i({d_tag, d_res}),
    .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_data_o({out_tag_o, out_res_o})
  );

endmodule
