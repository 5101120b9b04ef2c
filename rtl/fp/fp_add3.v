// fp_add3 - three-input floating-point adder: out_res_o = in_a_i + in_b_i + in_c_i, rounded once.
//
// Bit-exact twin of hls::add3 (hls/fp.h) and built the same way: order the operands by magnitude
// (x >= y >= z), place x's leading bit at position WIN = 3M+6 of a signed accumulator, add y
// exactly (or, if it lies entirely below the window, one lsb with y's sign, dropping z), add z
// aligned with its lost bits jammed into the lowest bit, round once (fp_round).
// Special cases as in hls::add3: three zeros give -0 only if all are -0; an exact pair
// cancellation (x + -x) gives the third operand (+0 if that one is a zero); an exact zero sum
// gives +0. Zero operands (exponent field 0) sort below every nonzero and add nothing.
//
// Phases, each followed by its share of the STAGES pipeline registers (fp_pipe):
//   A: compare, order, special cases   B: align   C: three-input add, absolute value   D: round
// Cut j holds floor(STAGES*(j+1)/4) - floor(STAGES*j/4) registers (STAGES = 1: output register
// only; 2: after B and at the output; 4: one each). Latency = STAGES cycles, one op per cycle.
// in_tag_i travels along.
//
// RAYCORE = 1 (hls Rounding::raycore, RayCore's three-input adder; RNE is then ignored): a window
// of two guard bits (WIN = M+2), y and z each aligned and truncated (no jam, no one-lsb tiny
// case), no pair-cancellation special case (only three zeros are special), then truncation: the
// twin of hls::detail::add3_raycore.
module fp_add3 #(
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
  input  wire [EXP_BITS+MAN_BITS:0] in_c_i,
  input  wire [TAG_BITS-1:0]        in_tag_i,
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [EXP_BITS+MAN_BITS:0] out_res_o,
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer E     = EXP_BITS;
  localparam integer M     = MAN_BITS;
  localparam integer W     = 1 + E + M;
  localparam integer RC    = RAYCORE != 0 ? 1 : 0;
  localparam integer RND   = RC != 0 ? 0 : RNE;
  localparam integer WIN   = RC != 0 ? M + 2 : 3 * M + 6;  // x's leading bit in the accumulator
  localparam integer ACC_W = WIN + 4;    // signed accumulator: |sum| < 3 * 2^(WIN+1)
  localparam integer EXP_W = E + 3;      // signed exponent width for fp_round
  localparam integer S_A   = STAGES / 4;
  localparam integer S_B   = (2 * STAGES) / 4 - STAGES / 4;
  localparam integer S_C   = (3 * STAGES) / 4 - (2 * STAGES) / 4;
  localparam integer S_D   = STAGES - (3 * STAGES) / 4;
  localparam integer TINY_I = 2 * M + 5;  // y farther below x than this: one signed lsb
  localparam [E+6:0] TINY_D = TINY_I[E+6:0];

  // ---- A: compare, order by magnitude, special cases ------------------------------------------
  wire za = ~|in_a_i[W-2:M];
  wire zb = ~|in_b_i[W-2:M];
  wire zc = ~|in_c_i[W-2:M];
  wire lt_ab = in_a_i[W-2:0] < in_b_i[W-2:0];
  wire lt_ac = in_a_i[W-2:0] < in_c_i[W-2:0];
  wire lt_bc = in_b_i[W-2:0] < in_c_i[W-2:0];
  // Rank in a stable descending sort (0 = largest); the three ranks are a permutation.
  wire [1:0] rank_a = {1'b0, lt_ab} + {1'b0, lt_ac};
  wire [1:0] rank_b = {1'b0, ~lt_ab} + {1'b0, lt_bc};
  reg  [W-1:0] x, y, z;
  always @* begin
    x = in_c_i;
    y = in_c_i;
    z = in_c_i;
    if (rank_a == 2'd0) x = in_a_i;
    if (rank_a == 2'd1) y = in_a_i;
    if (rank_a == 2'd2) z = in_a_i;
    if (rank_b == 2'd0) x = in_b_i;
    if (rank_b == 2'd1) y = in_b_i;
    if (rank_b == 2'd2) z = in_b_i;
  end
  // Exact pair cancellations (nonzero operands of equal magnitude and opposite signs).
  wire ca_ab = ~za && (in_a_i[W-2:0] == in_b_i[W-2:0]) && (in_a_i[W-1] != in_b_i[W-1]);
  wire ca_bc = ~zb && (in_b_i[W-2:0] == in_c_i[W-2:0]) && (in_b_i[W-1] != in_c_i[W-1]);
  wire ca_ac = ~za && (in_a_i[W-2:0] == in_c_i[W-2:0]) && (in_a_i[W-1] != in_c_i[W-1]);
  reg [W-1:0] a_spec_res;
  always @* begin
    a_spec_res = {za & zb & zc & in_a_i[W-1] & in_b_i[W-1] & in_c_i[W-1], {(W-1){1'b0}}};
    if (RC == 0) begin
      if (ca_ab) a_spec_res = zc ? {W{1'b0}} : in_c_i;
      else if (ca_bc) a_spec_res = za ? {W{1'b0}} : in_a_i;
      else if (ca_ac) a_spec_res = zb ? {W{1'b0}} : in_b_i;
    end
  end
  wire a_spec = (za & zb & zc) | (RC == 0 && (ca_ab | ca_bc | ca_ac));

  localparam integer PA_W = TAG_BITS + W + 1 + 3 * W;
  wire [PA_W-1:0] pa_out;
  wire            va, ra;
  fp_pipe #(.WIDTH(PA_W), .STAGES(S_A)) u_pipe_a (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
    .in_data_i({in_tag_i, a_spec_res, a_spec, x, y, z}),
    .out_valid_o(va), .out_ready_i(ra), .out_data_o(pa_out)
  );

  // ---- B: align y and z to x's window ------------------------------------------------------------
  wire [TAG_BITS-1:0] b_tag;
  wire [W-1:0]        b_spec_res, b_x, b_y, b_z;
  wire                b_spec;
  assign {b_tag, b_spec_res, b_spec, b_x, b_y, b_z} = pa_out;
  wire         zy   = ~|b_y[W-2:M];
  wire         zz   = ~|b_z[W-2:M];
  wire [E-1:0] dy   = b_x[W-2:M] - b_y[W-2:M];  // >= 0
  wire [E-1:0] dz   = b_x[W-2:M] - b_z[W-2:M];  // >= 0
  wire         tiny = {7'b0000000, dy} > TINY_D;
  wire [WIN:0] y_top = {1'b1, b_y[M-1:0], {(WIN-M){1'b0}}};
  wire [WIN:0] z_top = {1'b1, b_z[M-1:0], {(WIN-M){1'b0}}};
  wire [WIN:0] z_lost = z_top & ~({(WIN+1){1'b1}} << dz);
  reg  [WIN:0] my, mz;
  always @* begin
    my = y_top >> dy;                                  // exact: dy <= 2M+5 = WIN-M-1 (raycore: truncated)
    mz = (z_top >> dz) | {{WIN{1'b0}}, RC == 0 && |z_lost};  // jammed (raycore: truncated)
    if (tiny && RC == 0) begin
      my = {{WIN{1'b0}}, 1'b1};                        // y + z: one lsb with y's sign
      mz = {(WIN+1){1'b0}};
    end
    if (zy) my = {(WIN+1){1'b0}};
    if (zz) mz = {(WIN+1){1'b0}};
  end
  wire [WIN:0] mx = {1'b1, b_x[M-1:0], {(WIN-M){1'b0}}};

  localparam integer PB_W = TAG_BITS + W + 1 + E + 3 + 3 * (WIN + 1);
  wire [PB_W-1:0] pb_out;
  wire            vb, rb;
  fp_pipe #(.WIDTH(PB_W), .STAGES(S_B)) u_pipe_b (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(va), .in_ready_o(ra),
    .in_data_i({b_tag, b_spec_res, b_spec, b_x[W-2:M], b_x[W-1], b_y[W-1], b_z[W-1], mx, my, mz}),
    .out_valid_o(vb), .out_ready_i(rb), .out_data_o(pb_out)
  );

  // ---- C: signed three-input sum, absolute value -------------------------------------------------
  wire [TAG_BITS-1:0] c_tag;
  wire [W-1:0]        c_spec_res;
  wire                c_spec, c_sx, c_sy, c_sz;
  wire [E-1:0]        c_ex;
  wire [WIN:0]        c_mx, c_my, c_mz;
  assign {c_tag, c_spec_res, c_spec, c_ex, c_sx, c_sy, c_sz, c_mx, c_my, c_mz} = pb_out;
  wire [ACC_W-1:0] tx = {3'b000, c_mx};
  wire [ACC_W-1:0] ty = {3'b000, c_my};
  wire [ACC_W-1:0] tz = {3'b000, c_mz};
  // sum = (c_sx ? -tx : tx) + (c_sy ? -ty : ty) + (c_sz ? -tz : tz), each -t as ~t + 1: the three
  // inverted-or-not terms and the three +1s through two carry-save levels (the first level's
  // carries take c_sx into their free lsb, the second's c_sz; c_sy is the second level's third
  // input), then one parallel-prefix add (fp_padd) instead of ripple-carry chains.
  wire [ACC_W-1:0] xx = tx ^ {ACC_W{c_sx}};
  wire [ACC_W-1:0] xy = ty ^ {ACC_W{c_sy}};
  wire [ACC_W-1:0] xz = tz ^ {ACC_W{c_sz}};
  wire [ACC_W-1:0] s1 = xx ^ xy ^ xz;
  wire [ACC_W-1:0] k1 = {(xx[ACC_W-2:0] & xy[ACC_W-2:0]) | (xx[ACC_W-2:0] & xz[ACC_W-2:0]) |
                         (xy[ACC_W-2:0] & xz[ACC_W-2:0]), c_sx};
  wire [ACC_W-1:0] s2 = s1 ^ k1 ^ {{(ACC_W-1){1'b0}}, c_sy};
  wire [ACC_W-1:0] k2 = {(s1[ACC_W-2:0] & k1[ACC_W-2:0]) |
                         {{(ACC_W-2){1'b0}}, (s1[0] | k1[0]) & c_sy}, c_sz};
  wire [ACC_W-1:0] sum;
  fp_padd #(.WIDTH(ACC_W)) u_sum (.a_i(s2), .b_i(k2), .ci_i(1'b0), .sum_o(sum));
  wire             c_sign = sum[ACC_W-1];
  wire [ACC_W-2:0] c_mag;
  fp_mag #(.WIDTH(ACC_W - 1)) u_mag (.x_i(sum[ACC_W-2:0]), .neg_i(c_sign), .mag_o(c_mag));

  localparam integer PC_W = TAG_BITS + W + 1 + E + 1 + (ACC_W - 1);
  wire [PC_W-1:0] pc_out;
  wire            vc, rc;
  fp_pipe #(.WIDTH(PC_W), .STAGES(S_C)) u_pipe_c (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(vb), .in_ready_o(rb),
    .in_data_i({c_tag, c_spec_res, c_spec, c_ex, c_sign, c_mag}),
    .out_valid_o(vc), .out_ready_i(rc), .out_data_o(pc_out)
  );

  // ---- D: round once, pack ----------------------------------------------------------------------
  wire [TAG_BITS-1:0] d_tag;
  wire [W-1:0]        d_spec_res;
  wire                d_spec, d_sign;
  wire [E-1:0]        d_ex;
  wire [ACC_W-2:0]    d_mag;
  assign {d_tag, d_spec_res, d_spec, d_ex, d_sign, d_mag} = pc_out;
  // The accumulator's lsb has weight 2^(ex-WIN), its top magnitude bit 2^(ex+2).
  wire [EXP_W-1:0] d_exp_top = {3'b000, d_ex} + 2;
  wire [W-1:0]     d_rounded;
  fp_round #(
    .EXP_BITS(E), .MAN_BITS(M), .RNE(RND), .MAG_BITS(ACC_W - 1), .EXP_W(EXP_W)
  ) u_round (
    .sign_i(d_sign), .exp_i(d_exp_top), .mag_i(d_mag), .sticky_i(1'b0), .res_o(d_rounded)
  );
  wire [W-1:0] d_res = d_spec ? d_spec_res : d_rounded;

  fp_pipe #(.WIDTH(TAG_BITS + W), .STAGES(S_D)) u_pipe_d (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(vc), .in_ready_o(rc), .in_data_i({d_tag, d_res}),
    .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_data_o({out_tag_o, out_res_o})
  );

endmodule
