// fp_sop_nt - fp_sop (out_res_o = in_a_i + in_b_i + in_x1_i * in_y1_i + in_x2_i * in_y2_i, rounded
// once) without a tag, for units that carry their tag and side data in an fp_pipe beside the
// operators (vtu). The operator's tag (TAG_BITS = its default, 1) is tied to 0 and optimised away.
// RAYCORE: as fp_sop's (truncation). Latency = STAGES cycles.
module fp_sop_nt #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer RNE      = 0,
  parameter integer RAYCORE  = 0,
  parameter integer STAGES   = 2
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
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [EXP_BITS+MAN_BITS:0] out_res_o
);

  wire unused_tag;  // always 0: the tag is not used
  fp_sop #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE),
           .STAGES(STAGES)) u_op (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
    .in_a_i(in_a_i), .in_b_i(in_b_i), .in_x1_i(in_x1_i), .in_y1_i(in_y1_i), .in_x2_i(in_x2_i),
    .in_y2_i(in_y2_i), .in_tag_i(1'b0),
    .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_res_o(out_res_o),
    .out_tag_o(unused_tag));

endmodule
