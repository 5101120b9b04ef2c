// vtu - the viewport transfer unit: translates kd-tree nodes and Wald triangle records by the
// camera position as they come off the memory bus. Bit-exact twin of hls::Vtu<F, R>::node / ::tri
// (hls/vtu.h); the SystemC twin is systemc/vtu.h.
//
//   node (in_kind_i = 0)      inner (axis 0..2): split' = sub(split, c[axis]); leaves (axis 3)
//                             pass unchanged. in_node_i is the raw 64-bit node (hls/image.h).
//   triangle (in_kind_i = 1)  u = (k+1)%3, v = (k+2)%3, constants c0..c8 = nu, nv, nd, bnu, bnv,
//                             bd, cnu, cnv, cd (hls::WaldTri order):
//                             nd' = sub(nd, add3(c[k], mul(nu, c[u]), mul(nv, c[v])))
//                             bd' = add3(bd, mul(bnu, c[u]), mul(bnv, c[v]))
//                             cd' = add3(cd, mul(cnu, c[u]), mul(cnv, c[v]))
//                             k, flags, id and the six other constants pass unchanged.
//   vtu_on_i = 0              the record passes unchanged, with the same latency.
//
// One shared datapath for both kinds, three levels of FP operators, all with the same STAGES:
//   L1: 6 x fp_mul            (triangle products; idle for nodes)
//   L2: 3 x fp_add3           (c[k] + products, bd + products, cd + products)
//   L3: 1 x fp_add (sub)      triangle: nd - L2's first sum; node: split - c[axis]
// The record itself (a 64-bit node or the triangle's fields, packed into one payload), the kind,
// the enable and the one camera coordinate needed later (c[k] for a triangle, c[axis] for a node)
// travel beside the operators in fp_pipe registers of the same STAGES, and the L3 output selects
// the translated or the original fields. Latency = 3 * STAGES cycles, one record per cycle at full
// rate. Every operator and side register of a level shares the level's in_valid and out_ready, so
// they hold identical valid bits (a chain of STAGES fp_pipe registers behaves the same however its
// registers are spread over the operator's phases): the level's handshake is its first
// operator's. in_ready_o depends combinationally on out_ready_i (fp_pipe's stall rule).
//
// cam_x_i, cam_y_i, cam_z_i and vtu_on_i are sampled with the record (when in_valid_i && in_ready_o)
// and travel with it, so they may change at any time. Assumptions (as in every image): k is 0..2
// (k = 3 is treated as k = 0, hls has no meaning for it); an inner node's split has its bits above
// the format width zero (the result's are zero). Outputs of the other kind's fields are don't-care
// (out_node_o is meaningful when out_kind_o = 0, out_k_o..out_id_o when it is 1).
// in_tag_i travels with the record (a sideband, e.g. the port and line of the fill).
module vtu #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer RNE      = 0,
  parameter integer RAYCORE  = 0,   // rounding mode raycore (hls Rounding::raycore; RNE ignored)
  parameter integer STAGES   = 2,
  parameter integer TAG_BITS = 1
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  // Configuration, sampled with each record.
  input  wire                       vtu_on_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_z_i,
  // Records in.
  input  wire                       in_valid_i,
  output wire                       in_ready_o,
  input  wire                       in_kind_i,   // 0 = node, 1 = triangle
  input  wire [63:0]                in_node_i,
  input  wire [1:0]                 in_k_i,
  input  wire [7:0]                 in_flags_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_c0_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_c1_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_c2_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_c3_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_c4_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_c5_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_c6_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_c7_i,
  input  wire [EXP_BITS+MAN_BITS:0] in_c8_i,
  input  wire [31:0]                in_id_i,
  input  wire [TAG_BITS-1:0]        in_tag_i,
  // Records out.
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire                       out_kind_o,
  output wire [63:0]                out_node_o,
  output wire [1:0]                 out_k_o,
  output wire [7:0]                 out_flags_o,
  output wire [EXP_BITS+MAN_BITS:0] out_c0_o,
  output wire [EXP_BITS+MAN_BITS:0] out_c1_o,
  output wire [EXP_BITS+MAN_BITS:0] out_c2_o,
  output wire [EXP_BITS+MAN_BITS:0] out_c3_o,
  output wire [EXP_BITS+MAN_BITS:0] out_c4_o,
  output wire [EXP_BITS+MAN_BITS:0] out_c5_o,
  output wire [EXP_BITS+MAN_BITS:0] out_c6_o,
  output wire [EXP_BITS+MAN_BITS:0] out_c7_o,
  output wire [EXP_BITS+MAN_BITS:0] out_c8_o,
  output wire [31:0]                out_id_o,
  output wire [TAG_BITS-1:0]        out_tag_o
);

  localparam integer E  = EXP_BITS;
  localparam integer M  = MAN_BITS;
  localparam integer W  = 1 + E + M;
  // Payload: a triangle {id, flags, k, c8 .. c0} (c_i at bits [i*W +: W]) or a node in [63:0].
  localparam integer PW = 42 + 9 * W;
  // Side data of a level: {tag, on, kind, csel, payload}; L3 adds the two add3 sums.
  localparam integer SW = TAG_BITS + 2 + W + PW;

  // ---- input: pack the record, pick the camera coordinates -----------------------------------
  wire [9*W-1:0] in_c = {in_c8_i, in_c7_i, in_c6_i, in_c5_i, in_c4_i, in_c3_i, in_c2_i, in_c1_i,
                         in_c0_i};
  wire [PW-1:0]  node_payload = {{(PW-64){1'b0}}, in_node_i};
  wire [PW-1:0]  tri_payload  = {in_id_i, in_flags_i, in_k_i, in_c};
  wire [PW-1:0]  payload      = in_kind_i ? tri_payload : node_payload;

  // c[u], c[v] for the products; c[k] (triangle) or c[axis] (node) for later levels.
  reg  [W-1:0] cam_u, cam_v, cam_sel;
  wire [1:0]   axis = in_node_i[57:56];
  always @* begin
    case (in_k_i)
      2'd1:    begin cam_u = cam_z_i; cam_v = cam_x_i; end
      2'd2:    begin cam_u = cam_x_i; cam_v = cam_y_i; end
      default: begin cam_u = cam_y_i; cam_v = cam_z_i; end
    endcase
    case (in_kind_i ? in_k_i : axis)
      2'd1:    cam_sel = cam_y_i;
      2'd2:    cam_sel = cam_z_i;
      default: cam_sel = cam_x_i;
    endcase
  end

  // ---- L1: six products -----------------------------------------------------------------------
  wire [6*W-1:0] l1_a = {in_c7_i, in_c6_i, in_c4_i, in_c3_i, in_c1_i, in_c0_i};
  wire [6*W-1:0] l1_b = {cam_v, cam_u, cam_v, cam_u, cam_v, cam_u};
  wire [6*W-1:0] l1_prod;
  wire [5:0]     l1_in_ready, l1_out_valid;
  wire           l1_valid, l2_ready;
  genvar gi;
  generate
    for (gi = 0; gi < 6; gi = gi + 1) begin : g_mul
      fp_op2_nt #(.OP("mul"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES)) u_mul (
        .clk_i(clk_i), .rst_ni(rst_ni),
        .in_valid_i(in_valid_i), .in_ready_o(l1_in_ready[gi]),
        .in_a_i(l1_a[gi*W +: W]), .in_b_i(l1_b[gi*W +: W]),
        .out_valid_o(l1_out_valid[gi]), .out_ready_i(l2_ready),
        .out_res_o(l1_prod[gi*W +: W])
      );
    end
  endgenerate

  wire [SW-1:0] l1_side;
  wire          unused_l1_side_hs, unused_l1_side_valid;
  fp_pipe #(.WIDTH(SW), .STAGES(STAGES)) u_side1 (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(in_valid_i), .in_ready_o(unused_l1_side_hs),
    .in_data_i({in_tag_i, vtu_on_i, in_kind_i, cam_sel, payload}),
    .out_valid_o(unused_l1_side_valid), .out_ready_i(l2_ready), .out_data_o(l1_side)
  );
  assign in_ready_o = l1_in_ready[0];
  assign l1_valid   = l1_out_valid[0];

  // ---- L2: three sums -------------------------------------------------------------------------
  // add3(c[k], nu*cu, nv*cv); add3(bd, bnu*cu, bnv*cv); add3(cd, cnu*cu, cnv*cv)
  wire [3*W-1:0] l2_a = {l1_side[8*W +: W], l1_side[5*W +: W], l1_side[PW +: W]};
  wire [3*W-1:0] l2_sum;
  wire [2:0]     l2_in_ready, l2_out_valid;
  wire           l2_valid, l3_ready;
  generate
    for (gi = 0; gi < 3; gi = gi + 1) begin : g_add3
      fp_add3_nt #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES)) u_add3 (
        .clk_i(clk_i), .rst_ni(rst_ni),
        .in_valid_i(l1_valid), .in_ready_o(l2_in_ready[gi]),
        .in_a_i(l2_a[gi*W +: W]), .in_b_i(l1_prod[2*gi*W +: W]),
        .in_c_i(l1_prod[(2*gi+1)*W +: W]),
        .out_valid_o(l2_out_valid[gi]), .out_ready_i(l3_ready),
        .out_res_o(l2_sum[gi*W +: W])
      );
    end
  endgenerate

  wire [SW-1:0] l2_side;
  wire          unused_l2_side_hs, unused_l2_side_valid;
  fp_pipe #(.WIDTH(SW), .STAGES(STAGES)) u_side2 (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(l1_valid), .in_ready_o(unused_l2_side_hs), .in_data_i(l1_side),
    .out_valid_o(unused_l2_side_valid), .out_ready_i(l3_ready), .out_data_o(l2_side)
  );
  assign l2_ready = l2_in_ready[0];
  assign l2_valid = l2_out_valid[0];

  // ---- L3: one subtraction (triangle nd, or node split) ------------------------------------------
  wire [PW-1:0] l2_payload = l2_side[PW-1:0];
  wire [W-1:0]  l2_cam_sel = l2_side[PW +: W];
  wire          l2_kind    = l2_side[PW + W];
  wire [W-1:0]  l3_a = l2_kind ? l2_payload[2*W +: W] : l2_payload[W-1:0];
  wire [W-1:0]  l3_b = l2_kind ? l2_sum[W-1:0] : l2_cam_sel;
  wire [W-1:0]  l3_diff;
  wire          unused_l3_side_valid;
  wire          l3_valid;
  fp_op2_nt #(.OP("sub"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES)) u_sub (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(l2_valid), .in_ready_o(l3_ready),
    .in_a_i(l3_a), .in_b_i(l3_b),
    .out_valid_o(l3_valid), .out_ready_i(out_ready_i),
    .out_res_o(l3_diff)
  );

  // The camera coordinate is no longer needed: L3's side data carries the two other sums.
  localparam integer S3W = TAG_BITS + 2 + 2 * W + PW;
  wire [S3W-1:0] l3_side;
  wire           unused_l3_side_hs;
  fp_pipe #(.WIDTH(S3W), .STAGES(STAGES)) u_side3 (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(l2_valid), .in_ready_o(unused_l3_side_hs),
    .in_data_i({l2_side[SW-1 -: TAG_BITS + 2], l2_sum[W +: 2*W], l2_payload}),
    .out_valid_o(unused_l3_side_valid), .out_ready_i(out_ready_i), .out_data_o(l3_side)
  );

  // ---- output: translated or original fields --------------------------------------------------
  wire [PW-1:0]  o_orig = l3_side[PW-1:0];
  wire [2*W-1:0] o_sums = l3_side[PW +: 2*W];           // {cd', bd'}
  wire           o_kind = l3_side[PW + 2*W];
  wire           o_on   = l3_side[PW + 2*W + 1];
  wire [63:0]    diff_ext = {{(64-W){1'b0}}, l3_diff};
  wire           o_leaf = o_orig[57:56] == 2'd3;
  reg  [PW-1:0]  o_payload;
  always @* begin
    o_payload = o_orig;
    if (o_on) begin
      if (o_kind) begin
        o_payload[2*W +: W] = l3_diff;
        o_payload[5*W +: W] = o_sums[W-1:0];
        o_payload[8*W +: W] = o_sums[2*W-1:W];
      end else if (!o_leaf) begin
        o_payload[31:0] = diff_ext[31:0];
      end
    end
  end

  assign out_valid_o = l3_valid;
  assign out_kind_o  = o_kind;
  assign out_tag_o   = l3_side[S3W-1 -: TAG_BITS];
  assign out_node_o  = o_payload[63:0];
  assign {out_id_o, out_flags_o, out_k_o, out_c8_o, out_c7_o, out_c6_o, out_c5_o, out_c4_o,
          out_c3_o, out_c2_o, out_c1_o, out_c0_o} = o_payload;

  // Handshakes of the parallel operators and side registers: identical to the first operator's of
  // each level by construction (same STAGES, same in_valid and out_ready); not used.
  wire unused_hs;
  assign unused_hs = ^{l1_in_ready[5:1], l1_out_valid[5:1], l2_in_ready[2:1], l2_out_valid[2:1],
                       unused_l1_side_hs, unused_l2_side_hs, unused_l3_side_hs,
                       unused_l1_side_valid, unused_l2_side_valid, unused_l3_side_valid,
                       diff_ext[63:32]};

endmodule
