// fp_cmp - floating-point comparison: less-than, equal, minimum and maximum of in_a_i, in_b_i.
//
// Bit-exact twin of hls::lt, hls::eq, hls::min, hls::max (hls/fp.h): numbers order by value;
// every zero (exponent field 0, either sign, any mantissa field) equals every other zero.
// min/max return one of the operands' bit patterns, the first (in_a_i) on equal values.
//
// One combinational phase followed by the STAGES pipeline registers (fp_pipe).
// Latency = STAGES cycles, throughput one per cycle. in_tag_i travels along.
module fp_cmp #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer STAGES   = 1,
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
  output wire                       out_lt_o,   // a < b
  output wire                       out_eq_o,   // a == b
  output wire [EXP_BITS+MAN_BITS:0] out_min_o,  // b if b < a, else a
  output wire [EXP_BITS+MAN_BITS:0] out_max_o,  // b if a < b, else a
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer W = 1 + EXP_BITS + MAN_BITS;

  // Sign and magnitude with every zero made +0.
  wire         za    = ~|in_a_i[W-2:MAN_BITS];
  wire         zb    = ~|in_b_i[W-2:MAN_BITS];
  wire         sa    = in_a_i[W-1] & ~za;
  wire         sb    = in_b_i[W-1] & ~zb;
  wire [W-2:0] mag_a = za ? {(W-1){1'b0}} : in_a_i[W-2:0];
  wire [W-2:0] mag_b = zb ? {(W-1){1'b0}} : in_b_i[W-2:0];

  reg lt, eq;
  always @* begin
    eq = (sa == sb) && (mag_a == mag_b);
    lt = sa;                         // signs differ: a < b iff a is negative
    if (sa == sb) lt = sa ? (mag_b < mag_a) : (mag_a < mag_b);
  end
  wire         gt      = !lt && !eq;
  wire [W-1:0] min_res = gt ? in_b_i : in_a_i;
  wire [W-1:0] max_res = lt ? in_b_i : in_a_i;

  fp_pipe #(.WIDTH(TAG_BITS + 2 + 2 * W), .STAGES(STAGES)) u_pipe (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
    .in_data_i({in_tag_i, lt, eq, min_res, max_res}),
    .out_valid_o(out_valid_o), .out_ready_i(out_ready_i),
    .out_data_o({out_tag_o, out_lt_o, out_eq_o, out_min_o, out_max_o})
  );

endmodule
