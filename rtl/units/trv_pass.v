// trv_pass - one traversal pass of one ray: what one pipe of the traversal unit does with the ray
// it takes from the ready queue in a cycle (trv_unit holds the slots, the stacks and the queue and
// instantiates PIPES of these side by side). Combinational: the ray's record, its two top stack
// entries and the node cache's response in, the record's next value, the queue push, the finish,
// a list step for trv_unit's list stage and an inner node's split inputs out. The rules are
// systemc/trv.h's (Trv::step and its node_step / ask_list / leaf_end / pop), step for step:
//
//   start      the clip to the scene box was made when the ray entered (trv_unit: clip_i and the
//              clipped interval in tnear_i / tfar_i); empty tree or no hit: finish; else node 0
//              with the clipped interval, back to the queue at now + lat
//   node       node_step: read the node (access A, node cache, byte node * 8). Miss: back at
//              now + extra + lat ("looping for the next chance"). Inner node: back at now + extra
//              + lat + node_hl, and split_o: the split (trv.v, op 0: on to the near / far child,
//              or both with the far child pushed on the stack) is trv_unit's, in the cycle after
//              the pass, from the split_* outputs (nothing else in the pass depends on it, and the
//              ray is not taken again before it is written back). Leaf: empty -> leaf_end; else
//              the list fields, and with fuse its first list line (lreq_o: trv_unit's list stage
//              reads it in the next cycle, from base now + max(node_hl, 1)), else back as an
//              inner node's step
//   list       lreq_o: the list stage makes the list step in the next cycle (base now + 1)
//   leaf_done  the leaf's reduced result becomes the best hit (tmax = its t); leaf_end
//   pop        pop
//   leaf_end   finish if there is a hit and (an any-hit shadow ray, or the hit is not beyond this
//              cell: !(tfar < best.t)); else pop
//   pop        empty stack: finish; else take the top entry; if the best hit is before its tnear
//              the ray stays in state pop (back at now + extra + lat); else the entry's node and
//              interval, and with fuse its node step in the same pass (access A)
//
// `extra` is how far into the pass a step starts (the node cache's hit latency after a node
// read), `fused` that the pass already counted itself busy: every counter moves exactly as the
// model's. A pass makes at most one cache access (A: the node; the node cache answers in the same
// cycle, the cycle model's Ascache::access, with the 64-bit node word: split_or_count, then
// index | axis << 24, as hls::decode_node), asks for at most one list step, makes at most two
// pops (leaf_end -> pop -> fused node step of an empty leaf -> leaf_end -> pop), and four
// comparisons (fp_cmp_nt); no arithmetic of its own.
//
// Ray states (trv_unit's st encoding): 0 start, 1 node, 2 list, 3 wait_ist, 4 leaf_done, 5 pop,
// 6 done. Best record, packed {found, t, den, pos[31:0], id[31:0], k[1:0], nu, nv, nd}.
module trv_pass #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16
) (
  input  wire                          go_i,         // this pipe takes a ray this cycle
  // Configuration (static per frame) and the cycle.
  input  wire [31:0]                   now_i,
  input  wire [15:0]                   lat_i,        // trv_latency
  input  wire [15:0]                   node_hl_i,    // node cache hit latency
  input  wire                          fuse_i,
  input  wire                          any_hit_i,    // shadow rays end at their first leaf hit
  input  wire                          empty_i,      // the tree is empty
  // The ray's record.
  input  wire [2:0]                    st_i,
  input  wire                          clip_i,       // the ray meets the scene box (its clip)
  input  wire                          shadow_i,
  input  wire [11*(1+EXP_BITS+MAN_BITS)-1:0] ray_i,  // {o xyz, d xyz, inv xyz, tmin, tmax}
  input  wire [31:0]                   node_i,
  input  wire [EXP_BITS+MAN_BITS:0]    tnear_i,
  input  wire [EXP_BITS+MAN_BITS:0]    tfar_i,
  input  wire [EXP_BITS+MAN_BITS:0]    tmax_i,
  input  wire [6:0]                    sp_i,
  input  wire [67+5*(1+EXP_BITS+MAN_BITS)-1:0] best_i,
  input  wire [67+5*(1+EXP_BITS+MAN_BITS)-1:0] leaf_i,
  input  wire [31:0]                   first_i,      // leaf list: first index, count, position
  input  wire [31:0]                   count_i,
  input  wire [31:0]                   pos_i,
  input  wire [32+2*(1+EXP_BITS+MAN_BITS)-1:0] e1_i, // stack[sp-1], {node, tnear, tfar} (tfar low)
  input  wire [32+2*(1+EXP_BITS+MAN_BITS)-1:0] e2_i, // stack[sp-2]
  // Access A: the node cache, same-cycle response (the line's presence and the node word).
  output wire                          acc_a_valid_o,
  output wire [31:0]                   acc_a_byte_o,
  input  wire                          rsp_a_hit_i,
  input  wire [63:0]                   rsp_a_node_i,
  // The record's next value (written when go_i), leaf / results cleared when wr_leaf_o.
  output reg  [2:0]                    st_o,
  output reg  [31:0]                   node_o,
  output reg  [EXP_BITS+MAN_BITS:0]    tnear_o,
  output reg  [EXP_BITS+MAN_BITS:0]    tfar_o,
  output reg  [EXP_BITS+MAN_BITS:0]    tmax_o,
  output reg  [6:0]                    sp_o,
  output reg  [67+5*(1+EXP_BITS+MAN_BITS)-1:0] best_o,
  output reg  [31:0]                   first_o,
  output reg  [31:0]                   count_o,
  output reg  [31:0]                   pos_o,
  output reg                           wr_leaf_o,
  // An inner node: the split's inputs (trv.v op 0, in trv_unit the cycle after); its results
  // replace node_o, tnear_o, tfar_o and push the far child at sp_o (sp_o + 1 after).
  output reg                           split_o,
  output wire [31:0]                   split_node_o,   // this node
  output wire [31:0]                   split_child_o,  // the node's other child (Node::index)
  output wire [EXP_BITS+MAN_BITS:0]    split_plane_o,
  output wire [EXP_BITS+MAN_BITS:0]    split_tnear_o,
  output wire [EXP_BITS+MAN_BITS:0]    split_tfar_o,
  output wire [3*(1+EXP_BITS+MAN_BITS)-1:0] split_ray_o, // {o, d, inv} on the axis (o highest)
  output reg                           q_push_o,     // back to the ready queue at q_ready_o
  output reg  [31:0]                   q_ready_o,
  output reg                           fin_o,        // done: to the hit unit
  output reg                           lreq_o,       // a list step for the list stage (with the
  output reg                           lfused_o,     //   record's first_o, count_o, pos_o): fused
  output reg  [31:0]                   lbase_o,      //   into a node pass; its base cycle
  // Counter increments (systemc/config.h RtuStats names).
  output reg                           busy_o,
  output reg                           node_miss_o,
  output reg                           inner_o,
  output reg                           leaf_o,
  output reg  [1:0]                    pops_o,
  output reg  [1:0]                    fused_o
);

  localparam integer W  = 1 + EXP_BITS + MAN_BITS;
  localparam integer BW = 67 + 5 * W;
  localparam integer EW = 32 + 2 * W;
  localparam [2:0] S_START = 3'd0, S_NODE = 3'd1, S_LIST = 3'd2, S_LEAF_DONE = 3'd4,
                   S_POP = 3'd5, S_DONE = 3'd6;

  // Fields of the packed records.
  wire         best_found = best_i[BW-1];
  wire [W-1:0] best_t     = best_i[BW-2 -: W];
  wire         leaf_found = leaf_i[BW-1];
  wire [W-1:0] leaf_t     = leaf_i[BW-2 -: W];
  wire [31:0]  e1_node    = e1_i[EW-1 -: 32];
  wire [W-1:0] e1_tnear   = e1_i[2*W-1 -: W];
  wire [W-1:0] e1_tfar    = e1_i[W-1:0];
  wire [W-1:0] e2_tnear   = e2_i[2*W-1 -: W];
  // Packing of ray_i, lowest bits first: tmax, tmin, inv z, y, x, d z, y, x, o z, y, x.
  wire [W-1:0] r_tmax  = ray_i[0 +: W];
  wire [W-1:0] r_tmin  = ray_i[W +: W];
  wire [W-1:0] r_inv_z = ray_i[2*W +: W];
  wire [W-1:0] r_inv_y = ray_i[3*W +: W];
  wire [W-1:0] r_inv_x = ray_i[4*W +: W];
  wire [W-1:0] r_d_z   = ray_i[5*W +: W];
  wire [W-1:0] r_d_y   = ray_i[6*W +: W];
  wire [W-1:0] r_d_x   = ray_i[7*W +: W];
  wire [W-1:0] r_o_z   = ray_i[8*W +: W];
  wire [W-1:0] r_o_y   = ray_i[9*W +: W];
  wire [W-1:0] r_o_x   = ray_i[10*W +: W];

  // The best hit as the pass sees it: a leaf_done pass takes the leaf's result first.
  wire         take_leaf = (st_i == S_LEAF_DONE) && leaf_found;
  wire         bf = take_leaf ? 1'b1 : best_found;
  wire [W-1:0] bt = take_leaf ? leaf_t : best_t;

  // Four comparisons: leaf_end against the ray's interval or the first popped entry's, pop
  // against the first or the second entry.
  wire c_tfar_lt, c_e1tfar_lt, c_e1_lt, c_e2_lt;
  wire [W-1:0] u_min0, u_max0, u_min1, u_max1, u_min2, u_max2, u_min3, u_max3;
  wire [3:0] u_eq, u_rdy, u_vld;
  fp_cmp_nt #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .STAGES(0)) u_c0 (
    .clk_i(1'b0), .rst_ni(1'b1), .in_valid_i(1'b1), .in_ready_o(u_rdy[0]), .in_a_i(tfar_i),
    .in_b_i(bt), .out_valid_o(u_vld[0]), .out_ready_i(1'b1), .out_lt_o(c_tfar_lt),
    .out_eq_o(u_eq[0]), .out_min_o(u_min0), .out_max_o(u_max0));
  fp_cmp_nt #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .STAGES(0)) u_c1 (
    .clk_i(1'b0), .rst_ni(1'b1), .in_valid_i(1'b1), .in_ready_o(u_rdy[1]), .in_a_i(e1_tfar),
    .in_b_i(bt), .out_valid_o(u_vld[1]), .out_ready_i(1'b1), .out_lt_o(c_e1tfar_lt),
    .out_eq_o(u_eq[1]), .out_min_o(u_min1), .out_max_o(u_max1));
  fp_cmp_nt #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .STAGES(0)) u_c2 (
    .clk_i(1'b0), .rst_ni(1'b1), .in_valid_i(1'b1), .in_ready_o(u_rdy[2]), .in_a_i(bt),
    .in_b_i(e1_tnear), .out_valid_o(u_vld[2]), .out_ready_i(1'b1), .out_lt_o(c_e1_lt),
    .out_eq_o(u_eq[2]), .out_min_o(u_min2), .out_max_o(u_max2));
  fp_cmp_nt #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .STAGES(0)) u_c3 (
    .clk_i(1'b0), .rst_ni(1'b1), .in_valid_i(1'b1), .in_ready_o(u_rdy[3]), .in_a_i(bt),
    .in_b_i(e2_tnear), .out_valid_o(u_vld[3]), .out_ready_i(1'b1), .out_lt_o(c_e2_lt),
    .out_eq_o(u_eq[3]), .out_min_o(u_min3), .out_max_o(u_max3));
  wire unused_cmp = ^{u_min0, u_max0, u_min1, u_max1, u_min2, u_max2, u_min3, u_max3, u_eq, u_rdy,
                      u_vld};

  // Whether the pass's node step starts from the first popped entry (so the split sees its
  // interval): a leaf_done or pop pass whose pop goes on to a node, with fuse.
  wire le1_fin  = bf && ((shadow_i && any_hit_i) || !c_tfar_lt);
  wire pop1     = (st_i == S_POP) || ((st_i == S_LEAF_DONE) && !le1_fin);
  wire pop1_node = pop1 && (sp_i != 7'd0) && !(bf && c_e1_lt);
  wire node_from_e1 = pop1_node && fuse_i;

  // The node read by access A, and an inner node's split inputs.
  wire [31:0]  nd_lo = rsp_a_node_i[31:0];
  wire [31:0]  nd_hi = rsp_a_node_i[63:32];
  wire [31:0]  nd_index = {8'd0, nd_hi[23:0]};
  wire [1:0]   nd_axis = nd_hi[25:24];
  wire [31:0]  this_node = node_from_e1 ? e1_node : node_i;
  wire unused_nd = ^nd_hi[31:26];
  assign split_node_o  = this_node;
  assign split_child_o = nd_index;
  assign split_plane_o = nd_lo[W-1:0];
  assign split_tnear_o = node_from_e1 ? e1_tnear : tnear_i;
  assign split_tfar_o  = node_from_e1 ? e1_tfar : tfar_i;
  assign split_ray_o   = (nd_axis == 2'd2) ? {r_o_z, r_d_z, r_inv_z} :
                         (nd_axis == 2'd1) ? {r_o_y, r_d_y, r_inv_y} : {r_o_x, r_d_x, r_inv_x};
  wire unused_ray = ^r_tmin;  // the clip at entry used it

  // Access A, decided by the pass's inputs alone and never by a response (in rtu.v the node
  // cache answers within the cycle: a response feeding its own access would be a loop): the node
  // of a node pass or of a fused pop (node_step below).
  wire        a_node = go_i && ((st_i == S_NODE) || node_from_e1);
  assign acc_a_valid_o = a_node;
  assign acc_a_byte_o  = {this_node[28:0], 3'd0};

  // The pass, in the model's order.
  reg        do_node, node_fused, le2, pop2;
  reg [31:0] xe, again, nxt;
  reg [6:0]  sp;
  always @* begin
    st_o = st_i;  node_o = node_i;  tnear_o = tnear_i;  tfar_o = tfar_i;  tmax_o = tmax_i;
    sp = sp_i;  best_o = best_i;  first_o = first_i;  count_o = count_i;  pos_o = pos_i;
    wr_leaf_o = 1'b0;  split_o = 1'b0;
    q_push_o = 1'b0;  q_ready_o = 32'd0;  fin_o = 1'b0;
    lreq_o = 1'b0;  lfused_o = 1'b0;  lbase_o = 32'd0;
    busy_o = 1'b0;  node_miss_o = 1'b0;  inner_o = 1'b0;  leaf_o = 1'b0;  pops_o = 2'd0;
    fused_o = 2'd0;
    do_node = 1'b0;  node_fused = 1'b0;  le2 = 1'b0;  pop2 = 1'b0;
    xe = 32'd0;  again = 32'd0;  nxt = 32'd0;
    if (go_i) begin
      case (st_i)
        S_START: begin
          busy_o = 1'b1;
          best_o = {BW{1'b0}};
          sp = 7'd0;
          tmax_o = r_tmax;
          if (empty_i || !clip_i) begin
            st_o = S_DONE;
            fin_o = 1'b1;
          end else begin
            node_o = 32'd0;
            st_o = S_NODE;
            q_push_o = 1'b1;
            q_ready_o = now_i + {16'd0, lat_i};
          end
        end
        S_NODE: do_node = 1'b1;
        S_LIST: begin  // list_step: the list stage's, in the next cycle
          lreq_o = 1'b1;
          lbase_o = now_i + 32'd1;
        end
        S_LEAF_DONE: begin
          busy_o = 1'b1;
          if (leaf_found) begin
            best_o = leaf_i;
            tmax_o = leaf_t;
          end
          if (le1_fin) begin
            st_o = S_DONE;
            fin_o = 1'b1;
          end
        end
        S_POP: busy_o = 1'b1;
        default: ;
      endcase
      // pop #1 (leaf_done without a finish, or pop), with fuse_i.
      if (pop1) begin
        if (sp == 7'd0) begin
          st_o = S_DONE;
          fin_o = 1'b1;
        end else begin
          sp = sp - 7'd1;
          pops_o = pops_o + 2'd1;
          if (bf && c_e1_lt) begin
            st_o = S_POP;
            q_push_o = 1'b1;
            q_ready_o = now_i + {16'd0, lat_i};
          end else begin
            node_o = e1_node;
            tnear_o = e1_tnear;
            tfar_o = e1_tfar;
            st_o = S_NODE;
            if (fuse_i) begin
              fused_o = fused_o + 2'd1;
              do_node = 1'b1;
              node_fused = 1'b1;
            end else begin
              q_push_o = 1'b1;
              q_ready_o = now_i + {16'd0, lat_i};
            end
          end
        end
      end
      // node_step (extra 0): access A, the node.
      if (do_node) begin
        again = now_i + {16'd0, lat_i};
        if (!rsp_a_hit_i) begin  // access A (a_node) read node_o
          if (!node_fused) node_miss_o = 1'b1;
          q_push_o = 1'b1;
          q_ready_o = again;
        end else begin
          if (!node_fused) busy_o = 1'b1;
          xe = {16'd0, node_hl_i};
          nxt = again + {16'd0, node_hl_i};
          if (nd_axis != 2'd3) begin  // inner node: the split follows in trv_unit
            inner_o = 1'b1;
            split_o = 1'b1;
            q_push_o = 1'b1;
            q_ready_o = nxt;
          end else begin
            leaf_o = 1'b1;
            if (nd_lo == 32'd0) begin
              le2 = 1'b1;
            end else begin
              first_o = nd_index;
              count_o = nd_lo;
              pos_o = 32'd0;
              wr_leaf_o = 1'b1;
              st_o = S_LIST;
              if (fuse_i) begin  // the list stage reads the first line in the next cycle
                fused_o = fused_o + 2'd1;
                lreq_o = 1'b1;
                lfused_o = 1'b1;
                lbase_o = now_i + ((node_hl_i == 16'd0) ? 32'd1 : xe);
              end else begin
                q_push_o = 1'b1;
                q_ready_o = nxt;
              end
            end
          end
        end
      end
      // leaf_end of an empty leaf (after its node read), without fuse.
      if (le2) begin
        if (bf && ((shadow_i && any_hit_i) || !(node_from_e1 ? c_e1tfar_lt : c_tfar_lt))) begin
          st_o = S_DONE;
          fin_o = 1'b1;
        end else
          pop2 = 1'b1;
      end
      // pop #2 (or the first pop of a node pass), without fuse: the entry below the first popped
      // one when there was one.
      if (pop2) begin
        if (sp == 7'd0) begin
          st_o = S_DONE;
          fin_o = 1'b1;
        end else begin
          sp = sp - 7'd1;
          pops_o = pops_o + 2'd1;
          if (bf && (pop1 ? c_e2_lt : c_e1_lt)) begin
            st_o = S_POP;
          end else begin
            node_o = pop1 ? e2_i[EW-1 -: 32] : e1_node;
            tnear_o = pop1 ? e2_i[2*W-1 -: W] : e1_tnear;
            tfar_o = pop1 ? e2_i[W-1:0] : e1_tfar;
            st_o = S_NODE;
          end
          q_push_o = 1'b1;
          q_ready_o = now_i + xe + {16'd0, lat_i};
        end
      end
      if (fin_o) begin  // finish: no queue push (a pass finishes at most once, last)
        q_push_o = 1'b0;
        st_o = S_DONE;
      end
    end
    sp_o = sp;
  end

endmodule
