// fp_op2_nt - a two-operand rtl/fp operator without a tag, for units that carry their tag and
// side data in one fp_pipe per level beside the operators (ist, trv, vtu):
//   OP = "add": out_res_o = in_a_i + in_b_i   (fp_add)      OP = "mul": in_a_i * in_b_i (fp_mul)
//   OP = "sub": out_res_o = in_a_i - in_b_i   (fp_add)      OP = "div": in_a_i / in_b_i (fp_div)
// Any other OP is an addition. RAYCORE = 1 (rounding mode raycore; RNE ignored): fp_add's raycore
// adder (one guard bit, no jam, truncation), mul truncating (= rtz); raycore's division is not
// this operator (it is fp_rcp then fp_mul: hls::div<F, raycore> = a * rcp(b)), OP = "div" then
// gives rtz division. The operator's tag (TAG_BITS = its default, 1) is tied to 0 and optimised
// away. Latency = STAGES cycles, as the operator's.
module fp_op2_nt #(
  parameter          OP       = "add",
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
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [EXP_BITS+MAN_BITS:0] out_res_o
);

  localparam integer RND = RAYCORE != 0 ? 0 : RNE;  // raycore truncates
  wire unused_tag;  // always 0: the tag is not used
  generate
    if (OP == "mul") begin : g_mul
      fp_mul #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RND), .STAGES(STAGES)) u_op (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
        .in_a_i(in_a_i), .in_b_i(in_b_i), .in_tag_i(1'b0), .out_valid_o(out_valid_o),
        .out_ready_i(out_ready_i), .out_res_o(out_res_o), .out_tag_o(unused_tag));
    end else if (OP == "div") begin : g_div
      fp_div #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RND), .STAGES(STAGES)) u_op (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
        .in_a_i(in_a_i), .in_b_i(in_b_i), .in_tag_i(1'b0), .out_valid_o(out_valid_o),
        .out_ready_i(out_ready_i), .out_res_o(out_res_o), .out_tag_o(unused_tag));
    end else begin : g_add  // "add" or "sub"
      fp_add #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE),
               .STAGES(STAGES)) u_op (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
        .in_a_i(in_a_i), .in_b_i(in_b_i), .in_sub_i(OP == "sub"), .in_tag_i(1'b0),
        .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_res_o(out_res_o),
        .out_tag_o(unused_tag));
    end
  endgenerate

endmodule
