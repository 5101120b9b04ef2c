// vtu - the viewport transfer unit: translates kd-tree nodes and Wald triangle records by the
// camera position as they come off the memory bus. Bit-exact twin of hls::Vtu<F, R>::node / ::tri
// (hls/vtu.h); the SystemC twin is systemc/vtu.h.
//
//   node (in_kind_i = 0)      inner (axis 0..2): split' = sop(split, -c[axis], -0, +0, -0, +0);
//                             leaves (axis 3) pass unchanged. in_node_i is the raw 64-bit node
//                             (hls/image.h).
//   triangle (in_kind_i = 1)  u = (k+1)%3, v = (k+2)%3, constants c0..c8 = nu, nv, nd, bnu, bnv,
//                             bd, cnu, cnv, cd (hls::WaldTri order):
//                             nd' = sop(nd, -c[k], -nu, c[u], -nv, c[v])
//                             bd' = sop(bd, -0, bnu, c[u], bnv, c[v])
//                             cd' = sop(cd, -0, cnu, c[u], cnv, c[v])
//                             k, flags, id and the six other constants pass unchanged.
//   vtu_on_i = 0              the record passes unchanged, with the same latency.
// sop(a, b, x1, y1, x2, y2) = a + b + x1*y1 + x2*y2 with one rounding (fp_sop, hls::sop); -0 is the
// sign bit alone (an absent addend, and -0 * +0 an absent product: they leave an all-zero sum's
// sign to the others); a negation flips the sign bit.
//
// One shared datapath for both kinds: three fp_sop operators side by side, each with 3 * STAGES
// pipeline registers (so the latency is that of the former three operator levels):
//   sop 0   triangle nd'; node split' (its only operator)
//   sop 1   triangle bd'          sop 2   triangle cd'   (idle for nodes: their results unused)
// Per triangle: 3 sops (6 exact products, one rounding each); per node one. The record itself (a
// 64-bit node or the triangle's fields, packed into one payload), the kind and the enable travel
// beside the operators in one fp_pipe of 3 * STAGES registers, and the output selects the
// translated or the original fields. Latency = 3 * STAGES cycles, one record per cycle at full
// rate. The three operators and the side register share in_valid and out_ready and have the same
// number of registers, so they hold identical valid bits (a chain of N fp_pipe registers behaves
// the same however its registers are spread over the operator's phases): the unit's handshake is
// sop 0's. in_ready_o depends combinationally on out_ready_i (fp_pipe's stall rule).
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
  localparam integer ST = 3 * STAGES;  // each operator's registers: the unit's latency
  // Payload: a triangle {id, flags, k, c8 .. c0} (c_i at bits [i*W +: W]) or a node in [63:0].
  localparam integer PW = 42 + 9 * W;
  // Side data: {tag, on, kind, payload}.
  localparam integer SW = TAG_BITS + 2 + PW;
  localparam [W-1:0] NEG = {1'b1, {(W-1){1'b0}}};  // the sign bit: -0, and x ^ NEG = -x

  // ---- input: pack the record, pick the camera coordinates -----------------------------------
  wire [9*W-1:0] in_c = {in_c8_i, in_c7_i, in_c6_i, in_c5_i, in_c4_i, in_c3_i, in_c2_i, in_c1_i,
                         in_c0_i};
  wire [PW-1:0]  node_payload = {{(PW-64){1'b0}}, in_node_i};
  wire [PW-1:0]  tri_payload  = {in_id_i, in_flags_i, in_k_i, in_c};
  wire [PW-1:0]  payload      = in_kind_i ? tri_payload : node_payload;

  // c[u], c[v] for the products; c[k] (triangle) or c[axis] (node) for sop 0's second addend.
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

  // ---- three sops ----------------------------------------------------------------------------
  // sop 0: triangle nd + -c[k] + -nu*c[u] + -nv*c[v]; node split + -c[axis] + -0*+0 + -0*+0.
  // sop 1: bd + -0 + bnu*c[u] + bnv*c[v]; sop 2: cd + -0 + cnu*c[u] + cnv*c[v].
  wire [W-1:0] split = in_node_i[W-1:0];
  wire [3*W-1:0] op_a  = {in_c8_i, in_c5_i, in_kind_i ? in_c2_i : split};
  wire [3*W-1:0] op_b  = {NEG, NEG, cam_sel ^ NEG};
  wire [3*W-1:0] op_x1 = {in_c6_i, in_c3_i, in_kind_i ? in_c0_i ^ NEG : NEG};
  wire [3*W-1:0] op_y1 = {cam_u, cam_u, in_kind_i ? cam_u : {W{1'b0}}};
  wire [3*W-1:0] op_x2 = {in_c7_i, in_c4_i, in_kind_i ? in_c1_i ^ NEG : NEG};
  wire [3*W-1:0] op_y2 = {cam_v, cam_v, in_kind_i ? cam_v : {W{1'b0}}};
  wire [3*W-1:0] res;
  wire [2:0]     op_in_ready, op_out_valid;
  genvar gi;
  generate
    for (gi = 0; gi < 3; gi = gi + 1) begin : g_sop
      fp_sop_nt #(.EXP_BITS(E), .MAN_BITS(M), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(ST)) u_sop (
        .clk_i(clk_i), .rst_ni(rst_ni),
        .in_valid_i(in_valid_i), .in_ready_o(op_in_ready[gi]),
        .in_a_i(op_a[gi*W +: W]), .in_b_i(op_b[gi*W +: W]),
        .in_x1_i(op_x1[gi*W +: W]), .in_y1_i(op_y1[gi*W +: W]),
        .in_x2_i(op_x2[gi*W +: W]), .in_y2_i(op_y2[gi*W +: W]),
        .out_valid_o(op_out_valid[gi]), .out_ready_i(out_ready_i),
        .out_res_o(res[gi*W +: W])
      );
    end
  endgenerate

  wire [SW-1:0] side;
  wire          unused_side_hs, unused_side_valid;
  fp_pipe #(.WIDTH(SW), .STAGES(ST)) u_side (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(in_valid_i), .in_ready_o(unused_side_hs),
    .in_data_i({in_tag_i, vtu_on_i, in_kind_i, payload}),
    .out_valid_o(unused_side_valid), .out_ready_i(out_ready_i), .out_data_o(side)
  );
  assign in_ready_o = op_in_ready[0];

  // ---- output: translated or original fields --------------------------------------------------
  wire [PW-1:0]  o_orig = side[PW-1:0];
  wire           o_kind = side[PW];
  wire           o_on   = side[PW + 1];
  wire [63:0]    res0_ext = {{(64-W){1'b0}}, res[W-1:0]};
  wire           o_leaf = o_orig[57:56] == 2'd3;
  reg  [PW-1:0]  o_payload;
  always @* begin
    o_payload = o_orig;
    if (o_on) begin
      if (o_kind) begin
        o_payload[2*W +: W] = res[W-1:0];
        o_payload[5*W +: W] = res[W +: W];
        o_payload[8*W +: W] = res[2*W +: W];
      end else if (!o_leaf) begin
        o_payload[31:0] = res0_ext[31:0];
      end
    end
  end

  assign out_valid_o = op_out_valid[0];
  assign out_kind_o  = o_kind;
  assign out_tag_o   = side[SW-1 -: TAG_BITS];
  assign out_node_o  = o_payload[63:0];
  assign {out_id_o, out_flags_o, out_k_o, out_c8_o, out_c7_o, out_c6_o, out_c5_o, out_c4_o,
          out_c3_o, out_c2_o, out_c1_o, out_c0_o} = o_payload;

  // Handshakes of the parallel operators and the side register: identical to sop 0's by
  // construction (same number of registers, same in_valid and out_ready); not used.
  wire unused_hs;
  assign unused_hs = ^{op_in_ready[2:1], op_out_valid[2:1], unused_side_hs, unused_side_valid,
                       res0_ext[63:32]};

endmodule
