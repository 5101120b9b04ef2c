// trv_mul - multiplier for trv:
// fp_mul with the tag tied off (trv keeps its tag and side data in one carry fp_pipe per level).
// Latency = STAGES cycles, as fp_mul.
module trv_mul #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer RNE      = 0,
  parameter integer STAGES   = 2
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  input  wire                       in_valid_i,
  output wire                       in_ready_o,
  input  wire [EXP_BITS+MAN_BITS:0] in_a_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_b_i,
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [EXP_BITS+MAN_BITS:0] out_res_o
);

  wire unused_tag;  // always 0: the tag is not used
  fp_mul #(
    .EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .STAGES(STAGES), .TAG_BITS(1)
  ) u_op (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
    .in_a_i(in_a_i), .in_b_i(in_b_i), .in_tag_i(1'b0),
    .out_valid_o(out_valid_o), .out_ready_i(out_ready_i),
    .out_res_o(out_res_o), .out_tag_o(unused_tag)
  );

endmodule
