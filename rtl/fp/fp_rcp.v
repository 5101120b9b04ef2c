// fp_rcp - RayCore-style table reciprocal: out_res_o ~ 1 / in_a_i (rounding mode `raycore`).
//
// Bit-exact twin of hls::rcp<F, Rounding::raycore> (hls::detail::rcp_raycore in hls/fp.h): the
// significand m = 1 + f (f = the mantissa field, widened to 16 bits) is split into i = f[15:11]
// and d = f[10:0]; a 32-entry table gives the segment's coefficients c0 (2^-19 units), c1
// (2^-16), c2 (2^-7), and
//   t1 = (c2 * d) >> 7,  p = c1 - t1,  t2 = (p * d) >> 13,  y = c0 - t2   (~ 2^19 / m)
// every shift truncating; y is then truncated to MAN_BITS+1 bits with the exponent -ea (fp_round,
// RNE = 0: flush below the smallest normal). A zero input (exponent field 0) saturates with its
// sign (as hls::div(1, 0)). Worst error over all FP24 mantissas: 1.183 ulp (tb/fp).
// For formats with MAN_BITS <= 16 (FP24: the mode's only format; hls refuses wider ones).
//
// Phases, each followed by its share of the STAGES pipeline registers (fp_pipe):
//   A: unpack, table, t1 = c2 * d, p = c1 - t1    B: t2 = p * d, y = c0 - t2    C: round, pack
// Cut j holds floor(STAGES*(j+1)/3) - floor(STAGES*j/3) registers (STAGES = 1: output register
// only). Latency = STAGES cycles, one operation per cycle. in_tag_i travels along.
// lint: FP24 only
module fp_rcp #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
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
  localparam integer EXP_W = E + 3;      // signed exponent width for fp_round
  localparam integer S_A   = STAGES / 3;
  localparam integer S_B   = (2 * STAGES) / 3 - STAGES / 3;
  localparam integer S_C   = STAGES - (2 * STAGES) / 3;
  localparam [EXP_W-1:0] BIAS2 = 2 * ((1 << (E - 1)) - 1);

  // The coefficients {c0[19:0], c1[16:0], c2[7:0]} of segment i (hls::detail::kRaycoreRcpTable).
  function automatic [44:0] coef(input [4:0] i);
    begin
      case (i)
        5'd0:  coef = {20'd524288, 17'd65502, 8'd122};
        5'd1:  coef = {20'd508400, 17'd61594, 8'd112};
        5'd2:  coef = {20'd493447, 17'd58026, 8'd102};
        5'd3:  coef = {20'd479349, 17'd54759, 8'd94};
        5'd4:  coef = {20'd466033, 17'd51760, 8'd86};
        5'd5:  coef = {20'd453438, 17'd49001, 8'd80};
        5'd6:  coef = {20'd441505, 17'd46457, 8'd74};
        5'd7:  coef = {20'd430185, 17'd44106, 8'd68};
        5'd8:  coef = {20'd419430, 17'd41929, 8'd63};
        5'd9:  coef = {20'd409200, 17'd39909, 8'd59};
        5'd10: coef = {20'd399457, 17'd38032, 8'd55};
        5'd11: coef = {20'd390168, 17'd36284, 8'd51};
        5'd12: coef = {20'd381300, 17'd34654, 8'd48};
        5'd13: coef = {20'd372827, 17'd33131, 8'd45};
        5'd14: coef = {20'd364722, 17'd31707, 8'd42};
        5'd15: coef = {20'd356962, 17'd30372, 8'd39};
        5'd16: coef = {20'd349525, 17'd29120, 8'd37};
        5'd17: coef = {20'd342392, 17'd27944, 8'd35};
        5'd18: coef = {20'd335544, 17'd26838, 8'd33};
        5'd19: coef = {20'd328965, 17'd25796, 8'd31};
        5'd20: coef = {20'd322639, 17'd24813, 8'd29};
        5'd21: coef = {20'd316551, 17'd23886, 8'd27};
        5'd22: coef = {20'd310689, 17'd23010, 8'd26};
        5'd23: coef = {20'd305040, 17'd22181, 8'd25};
        5'd24: coef = {20'd299593, 17'd21396, 8'd23};
        5'd25: coef = {20'd294337, 17'd20652, 8'd22};
        5'd26: coef = {20'd289262, 17'd19946, 8'd21};
        5'd27: coef = {20'd284360, 17'd19276, 8'd20};
        5'd28: coef = {20'd279620, 17'd18639, 8'd19};
        5'd29: coef = {20'd275036, 17'd18033, 8'd18};
        5'd30: coef = {20'd270600, 17'd17456, 8'd17};
        default: coef = {20'd266305, 17'd16906, 8'd16};
      endcase
    end
  endfunction

  // ---- A: unpack, table, first product -----------------------------------------------------------
  wire         za   = ~|in_a_i[W-2:M];
  wire [15:0]  f    = in_a_i[M-1:0] << (16 - M);
  wire [44:0]  cf   = coef(f[15:11]);
  wire [10:0]  d    = f[10:0];
  wire [18:0]  m1   = {11'd0, cf[7:0]} * {8'd0, d};        // c2 * d < 2^19
  wire [16:0]  a_p  = cf[24:8] - {5'd0, m1[18:7]};          // c1 - t1 (>= 16906 - 1950)
  wire [6:0]   unused_m1_lo = m1[6:0];                      // truncated
  // The result's top bit, y's bit 19 (weight 2^0 x 2^-ea), has the biased exponent 2 bias - ef.
  wire [EXP_W-1:0] a_exp = BIAS2 - {3'b000, in_a_i[W-2:M]};

  localparam integer PA_W = TAG_BITS + 2 + EXP_W + 20 + 17 + 11;
  wire [PA_W-1:0] pa_out;
  wire            va, ra;
  fp_pipe #(.WIDTH(PA_W), .STAGES(S_A)) u_pipe_a (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
    .in_data_i({in_tag_i, in_a_i[W-1], za, a_exp, cf[44:25], a_p, d}),
    .out_valid_o(va), .out_ready_i(ra), .out_data_o(pa_out)
  );

  // ---- B: second product, y = c0 - t2 ----------------------------------------------------------
  wire [TAG_BITS-1:0] b_tag;
  wire                b_sign, b_zero;
  wire [EXP_W-1:0]    b_exp;
  wire [19:0]         b_c0;
  wire [16:0]         b_p;
  wire [10:0]         b_d;
  assign {b_tag, b_sign, b_zero, b_exp, b_c0, b_p, b_d} = pa_out;
  wire [27:0] m2  = {11'd0, b_p} * {17'd0, b_d};           // p * d < 2^28
  wire [19:0] b_y = b_c0 - {5'd0, m2[27:13]};               // in (2^18, 2^19]
  wire [12:0] unused_m2_lo = m2[12:0];                      // truncated

  localparam integer PB_W = TAG_BITS + 2 + EXP_W + 20;
  wire [PB_W-1:0] pb_out;
  wire            vb, rb;
  fp_pipe #(.WIDTH(PB_W), .STAGES(S_B)) u_pipe_b (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(va), .in_ready_o(ra), .in_data_i({b_tag, b_sign, b_zero, b_exp, b_y}),
    .out_valid_o(vb), .out_ready_i(rb), .out_data_o(pb_out)
  );

  // ---- C: truncate, flush, pack; zero saturates ------------------------------------------------
  wire [TAG_BITS-1:0] c_tag;
  wire                c_sign, c_zero;
  wire [EXP_W-1:0]    c_exp;
  wire [19:0]         c_y;
  assign {c_tag, c_sign, c_zero, c_exp, c_y} = pb_out;
  wire [W-1:0] c_rounded;
  fp_round #(
    .EXP_BITS(E), .MAN_BITS(M), .RNE(0), .MAG_BITS(20), .EXP_W(EXP_W)
  ) u_round (
    .sign_i(c_sign), .exp_i(c_exp), .mag_i(c_y), .sticky_i(1'b0), .res_o(c_rounded)
  );
  wire [W-1:0] c_res = c_zero ? {c_sign, {(W-1){1'b1}}} : c_rounded;

  fp_pipe #(.WIDTH(TAG_BITS + W), .STAGES(S_C)) u_pipe_c (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(vb), .in_ready_o(rb), .in_data_i({c_tag, c_res}),
    .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_data_o({out_tag_o, out_res_o})
  );

endmodule
