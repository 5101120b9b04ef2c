// vtu - the viewport transfer unit: translates kd-tree nodes and Wald triangle records by the
// camera position as they come off the memory bus. Bit-exact twin of hls::Vtu<F, R>::node / ::tri
// (hls/vtu.h); the SystemC twin is systemc/vtu.h.
//
//   node (in_kind_i = 0)      four 8-byte nodes (lanes 0..3, in_node0_i .. in_node3_i, each the raw
//                             64-bit node of hls/image.h); lane j is translated if in_nmask_i[j] is
//                             set and the node is inner (axis 0..2):
//                             split' = sop(split, -c[axis], -0, +0, -0, +0) = hls::Vtu::shift;
//                             leaves (axis 3) and unmasked lanes pass unchanged.
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
// One shared datapath for both kinds: three fp_sop operators and one subtractor side by side, each
// with 2 * STAGES pipeline registers (an fp_sop's four phases: at STAGES 2 one register after
// each, its worst phase 96 FO4 as at 3 * STAGES):
//   sop 0   triangle nd'; node lane 0's split'
//   sop 1   triangle bd'; node lane 1's split'
//   sop 2   triangle cd'; node lane 2's split'
//   sub 3   node lane 3's split' = split - c[axis] (fp_op2_nt "sub"; idle for triangles)
// Lane 3's subtractor is hls::Vtu::shift bit for bit: a two-term sop is the sum rounded once, as
// fp_add (rtz, rne; tb/fp Sop.*TwoTermsAreAdd), and raycore's sop truncates as rtz's, so lane 3
// is an rtz subtractor under raycore (RAYCORE 0, RNE 0).
// Per triangle: 3 sops (6 exact products, one rounding each); per node one sop or the subtractor.
// The record itself (the four nodes or the triangle's fields, packed into one payload), the kind
// and the per-lane translate bits travel beside the operators in one fp_pipe of 2 * STAGES
// registers, and the output selects the translated or the original fields. Latency = 2 * STAGES
// cycles, one record per cycle at full rate. The four operators and the side register share
// in_valid and out_ready and have the same number of registers, so they hold identical valid bits
// (a chain of N fp_pipe registers behaves the same however its registers are spread over the
// operator's phases): the unit's handshake is sop 0's. in_ready_o depends combinationally on
// out_ready_i (fp_pipe's stall rule).
//
// cam_x_i, cam_y_i, cam_z_i and vtu_on_i are sampled with the record (when in_valid_i && in_ready_o)
// and travel with it, so they may change at any time. Assumptions (as in every image): k is 0..2
// (k = 3 is treated as k = 0, hls has no meaning for it); an inner node's split has its bits above
// the format width zero (the result's are zero). Outputs of the other kind's fields are don't-care
// (out_node0_o .. out_node3_o are meaningful when out_kind_o = 0, out_k_o..out_id_o when it is 1;
// the node inputs and in_nmask_i are don't-care for a triangle, the triangle inputs for nodes).
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
  input  wire                       in_kind_i,   // 0 = four nodes, 1 = triangle
  input  wire [63:0]                in_node0_i,
  input  wire [63:0]                in_node1_i,
  input  wire [63:0]                in_node2_i,
  input  wire [63:0]                in_node3_i,
  input  wire [3:0]                 in_nmask_i,  // the node lanes to translate
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
  output wire [63:0]                out_node0_o,
  output wire [63:0]                out_node1_o,
  output wire [63:0]                out_node2_o,
  output wire [63:0]                out_node3_o,
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
  localparam integer ST = 2 * STAGES;  // each operator's registers: the unit's latency
  // Payload: a triangle {id, flags, k, c8 .. c0} (c_i at bits [i*W +: W]) or the four nodes
  // {node3, node2, node1, node0} in [255:0]; as wide as the wider of the two.
  localparam integer TPW = 42 + 9 * W;
  localparam integer PW  = (TPW > 256) ? TPW : 256;
  // Side data: {tag, translate[3:0], kind, payload}.
  localparam integer SW = TAG_BITS + 5 + PW;
  localparam [W-1:0] NEG = {1'b1, {(W-1){1'b0}}};  // the sign bit: -0, and x ^ NEG = -x
  localparam integer RND = (RAYCORE != 0) ? 0 : RNE;  // lane 3's subtractor: raycore = rtz

  // ---- input: pack the record, pick the camera coordinates -----------------------------------
  wire [9*W-1:0] in_c = {in_c8_i, in_c7_i, in_c6_i, in_c5_i, in_c4_i, in_c3_i, in_c2_i, in_c1_i,
                         in_c0_i};
  wire [255:0]   nodes = {in_node3_i, in_node2_i, in_node1_i, in_node0_i};
  reg  [PW-1:0]  payload;
  always @* begin
    payload = {PW{1'b0}};
    if (in_kind_i) payload[TPW-1:0] = {in_id_i, in_flags_i, in_k_i, in_c};
    else           payload[255:0]   = nodes;
  end

  // Per lane: the node's axis, its split, whether it is translated, and c[axis] (lane 0: c[k] for
  // a triangle). A triangle's translate bits are all vtu_on_i (its outputs use bit 0).
  reg  [4*W-1:0] cam_sel;
  reg  [4*W-1:0] split;
  reg  [3:0]     tr;
  reg  [W-1:0]   cam_u, cam_v;
  reg  [1:0]     axis;
  integer j;
  always @* begin
    case (in_k_i)
      2'd1:    begin cam_u = cam_z_i; cam_v = cam_x_i; end
      2'd2:    begin cam_u = cam_x_i; cam_v = cam_y_i; end
      default: begin cam_u = cam_y_i; cam_v = cam_z_i; end
    endcase
    for (j = 0; j < 4; j = j + 1) begin
      axis = nodes[j*64 + 56 +: 2];
      split[j*W +: W] = nodes[j*64 +: W];
      tr[j] = vtu_on_i && (in_kind_i || (in_nmask_i[j] && axis != 2'd3));
      if (j == 0 && in_kind_i) axis = in_k_i;
      case (axis)
        2'd1:    cam_sel[j*W +: W] = cam_y_i;
        2'd2:    cam_sel[j*W +: W] = cam_z_i;
        default: cam_sel[j*W +: W] = cam_x_i;
      endcase
    end
  end

  // ---- three sops and a subtractor -----------------------------------------------------------
  // sop 0: triangle nd + -c[k] + -nu*c[u] + -nv*c[v]; sop 1: bd + -0 + bnu*c[u] + bnv*c[v];
  // sop 2: cd + -0 + cnu*c[u] + cnv*c[v];
  // node lane j (sop j): split_j + -c[axis_j] + -0*+0 + -0*+0.
  // sub 3: node lane 3's split_3 - c[axis_3].
  wire [W-1:0] zero = {W{1'b0}};
  wire [3*W-1:0] op_a  = in_kind_i ? {in_c8_i, in_c5_i, in_c2_i} : split[3*W-1:0];
  wire [3*W-1:0] op_b  = in_kind_i ? {NEG, NEG, cam_sel[W-1:0] ^ NEG}
                                   : cam_sel[3*W-1:0] ^ {NEG, NEG, NEG};
  wire [3*W-1:0] op_x1 = in_kind_i ? {in_c6_i, in_c3_i, in_c0_i ^ NEG} : {NEG, NEG, NEG};
  wire [3*W-1:0] op_y1 = in_kind_i ? {cam_u, cam_u, cam_u} : {zero, zero, zero};
  wire [3*W-1:0] op_x2 = in_kind_i ? {in_c7_i, in_c4_i, in_c1_i ^ NEG} : {NEG, NEG, NEG};
  wire [3*W-1:0] op_y2 = in_kind_i ? {cam_v, cam_v, cam_v} : {zero, zero, zero};
  wire [4*W-1:0] res;
  wire [3:0]     op_in_ready, op_out_valid;
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
  fp_op2_nt #(.OP("sub"), .EXP_BITS(E), .MAN_BITS(M), .RNE(RND), .RAYCORE(0), .STAGES(ST)) u_sub (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(in_valid_i), .in_ready_o(op_in_ready[3]),
    .in_a_i(split[3*W +: W]), .in_b_i(cam_sel[3*W +: W]),
    .out_valid_o(op_out_valid[3]), .out_ready_i(out_ready_i),
    .out_res_o(res[3*W +: W])
  );

  wire [SW-1:0] side;
  wire          unused_side_hs, unused_side_valid;
  fp_pipe #(.WIDTH(SW), .STAGES(ST)) u_side (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .in_valid_i(in_valid_i), .in_ready_o(unused_side_hs),
    .in_data_i({in_tag_i, tr, in_kind_i, payload}),
    .out_valid_o(unused_side_valid), .out_ready_i(out_ready_i), .out_data_o(side)
  );
  assign in_ready_o = op_in_ready[0];

  // ---- output: translated or original fields --------------------------------------------------
  wire [PW-1:0]  o_orig = side[PW-1:0];
  wire           o_kind = side[PW];
  wire [3:0]     o_tr   = side[PW+1 +: 4];
  reg  [PW-1:0]  o_payload;
  reg  [31:0]    res_ext;
  integer k;
  always @* begin
    o_payload = o_orig;
    res_ext   = 32'd0;
    if (o_kind && o_tr[0]) begin
      o_payload[2*W +: W] = res[W-1:0];
      o_payload[5*W +: W] = res[W +: W];
      o_payload[8*W +: W] = res[2*W +: W];
    end
    for (k = 0; k < 4; k = k + 1)
      if (!o_kind && o_tr[k]) begin
        res_ext[W-1:0] = res[k*W +: W];
        o_payload[k*64 +: 32] = res_ext;
      end
  end

  assign out_valid_o = op_out_valid[0];
  assign out_kind_o  = o_kind;
  assign out_tag_o   = side[SW-1 -: TAG_BITS];
  assign {out_node3_o, out_node2_o, out_node1_o, out_node0_o} = o_payload[255:0];
  assign {out_id_o, out_flags_o, out_k_o, out_c8_o, out_c7_o, out_c6_o, out_c5_o, out_c4_o,
          out_c3_o, out_c2_o, out_c1_o, out_c0_o} = o_payload[TPW-1:0];

  // Handshakes of the parallel operators and the side register: identical to sop 0's by
  // construction (same number of registers, same in_valid and out_ready); not used.
  wire unused_hs;
  assign unused_hs = ^{op_in_ready[3:1], op_out_valid[3:1], unused_side_hs, unused_side_valid};

endmodule
