// spawn_ops - N floating-point operators of one kind side by side, one level of the spawn unit's
// pipeline (rtl/units/spawn.v): OP = 0 fp_mul (a * b), 1 fp_add (a + b, or a - b where in_sub_i),
// 2 fp_add3 (a + b + c), 3 fp_div (a / b; RAYCORE = 1: fp_rcp, 1 / b, a unused: raycore's
// reciprocal, as the spawn unit divides only 1 by something), 4 fp_sqrt (sqrt(a); raycore: rtz's
// root). Also the levels of the hit unit (rtl/units/hit.v). Every operator gets the same in_valid_i and out_ready_i and has the same
// STAGES, so all hold identical valid bits; the level's handshake is the first operator's.
// Operand i is at bits [i*W +: W] of each bus, W = 1 + EXP_BITS + MAN_BITS.
module spawn_ops #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer RNE      = 0,
  parameter integer RAYCORE  = 0,  // rounding mode raycore (RNE ignored)
  parameter integer STAGES   = 2,
  parameter integer OP       = 0,
  parameter integer N        = 1
) (
  input  wire                                  clk_i,
  input  wire                                  rst_ni,
  input  wire                                  in_valid_i,
  output wire                                  in_ready_o,
  input  wire [N*(1+EXP_BITS+MAN_BITS)-1:0]    in_a_i,
  input  wire [N*(1+EXP_BITS+MAN_BITS)-1:0]    in_b_i,
  input  wire [N*(1+EXP_BITS+MAN_BITS)-1:0]    in_c_i,    // OP = 2 only
  input  wire [N-1:0]                          in_sub_i,  // OP = 1 only
  output wire                                  out_valid_o,
  input  wire                                  out_ready_i,
  output wire [N*(1+EXP_BITS+MAN_BITS)-1:0]    out_res_o
);

  localparam integer W = 1 + EXP_BITS + MAN_BITS;
  localparam integer RND = RAYCORE != 0 ? 0 : RNE;
  wire [N-1:0] rdy, vld, unused_tag;
  genvar gi;
  generate
    for (gi = 0; gi < N; gi = gi + 1) begin : g_op
      if (OP == 0) begin : g_mul
        fp_mul #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RND), .STAGES(STAGES), .TAG_BITS(1)) u_op (
          .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(rdy[gi]),
          .in_a_i(in_a_i[gi*W +: W]), .in_b_i(in_b_i[gi*W +: W]), .in_tag_i(1'b0),
          .out_valid_o(vld[gi]), .out_ready_i(out_ready_i), .out_res_o(out_res_o[gi*W +: W]),
          .out_tag_o(unused_tag[gi])
        );
      end else if (OP == 1) begin : g_add
        fp_add #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES),
                 .TAG_BITS(1)) u_op (
          .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(rdy[gi]),
          .in_a_i(in_a_i[gi*W +: W]), .in_b_i(in_b_i[gi*W +: W]), .in_sub_i(in_sub_i[gi]),
          .in_tag_i(1'b0), .out_valid_o(vld[gi]), .out_ready_i(out_ready_i),
          .out_res_o(out_res_o[gi*W +: W]), .out_tag_o(unused_tag[gi])
        );
      end else if (OP == 3 && RAYCORE != 0) begin : g_rcp
        fp_rcp #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .STAGES(STAGES), .TAG_BITS(1)) u_op (
          .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(rdy[gi]),
          .in_a_i(in_b_i[gi*W +: W]), .in_tag_i(1'b0),
          .out_valid_o(vld[gi]), .out_ready_i(out_ready_i), .out_res_o(out_res_o[gi*W +: W]),
          .out_tag_o(unused_tag[gi])
        );
      end else if (OP == 3) begin : g_div
        fp_div #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .STAGES(STAGES), .TAG_BITS(1)) u_op (
          .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(rdy[gi]),
          .in_a_i(in_a_i[gi*W +: W]), .in_b_i(in_b_i[gi*W +: W]), .in_tag_i(1'b0),
          .out_valid_o(vld[gi]), .out_ready_i(out_ready_i), .out_res_o(out_res_o[gi*W +: W]),
          .out_tag_o(unused_tag[gi])
        );
      end else if (OP == 4) begin : g_sqrt
        fp_sqrt #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RND), .STAGES(STAGES), .TAG_BITS(1)) u_op (
          .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(rdy[gi]),
          .in_a_i(in_a_i[gi*W +: W]), .in_tag_i(1'b0),
          .out_valid_o(vld[gi]), .out_ready_i(out_ready_i), .out_res_o(out_res_o[gi*W +: W]),
          .out_tag_o(unused_tag[gi])
        );
      end else begin : g_add3
        fp_add3 #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES),
                  .TAG_BITS(1)) u_op (
          .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(rdy[gi]),
          .in_a_i(in_a_i[gi*W +: W]), .in_b_i(in_b_i[gi*W +: W]), .in_c_i(in_c_i[gi*W +: W]),
          .in_tag_i(1'b0), .out_valid_o(vld[gi]), .out_ready_i(out_ready_i),
          .out_res_o(out_res_o[gi*W +: W]), .out_tag_o(unused_tag[gi])
        );
      end
    end
  endgenerate
  assign in_ready_o  = rdy[0];
  assign out_valid_o = vld[0];

  // The other operators' handshakes equal the first's; the operand buses of other kinds and the
  // operators' tags are not used.
  wire unused_ops;
  assign unused_ops = ^{rdy, vld, unused_tag, in_c_i, in_sub_i, in_a_i, in_b_i};

endmodule
