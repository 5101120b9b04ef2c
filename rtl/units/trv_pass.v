// trv_pass - one traversal pass of one ray, over three cycles: what one pipe of the traversal
// unit does with the ray it takes from the ready queue (trv_unit holds the slots, the stacks, the
// queue and the registers between the halves, and instantiates PIPES of these side by side). Two
// combinational halves:
//   the pass (the cycle c the ray is taken): the ray's record and its two top stack entries in;
//     the node read's address (acc_a_*: trv_unit registers it and reads the node cache in c + 1,
//     the read stage), the best record and tmax (written at c's edge) and mid_o, what the
//     outcome needs (trv_unit registers it, twice) out;
//   the outcome (cycle c + 2): mid_i and the node read's registered answer in; the record's other
//     fields (written at c + 2's edge), the queue push, the finish, a list step for c + 3's list
//     stage and an inner node's split inputs out.
// The rules are systemc/trv.h's (Trv::step and its node_step / node_outcome / ask_list /
// leaf_end / pop, Trv::read_stage and Trv::out_stage), step for step:
//
//   start      the clip to the scene box was made when the ray entered (trv_unit: clip_i and the
//              clipped interval in tnear_i / tfar_i); empty tree or no hit: finish; else node 0
//              with the clipped interval, back to the queue at c + lat
//   node       node_step: read the node (access A, node cache, byte node * 8) in the read stage;
//              in the outcome, from the word: a miss, back at c + lat ("looping for the next
//              chance");
//              an inner node, back at c + lat + node_hl, and split_o: the split (trv.v, op 0: on
//              to the near / far child, or both with the far child pushed on the stack) is
//              trv_unit's, from the split_* outputs (nothing else depends on it, and the ray is
//              not taken again before it is written back); a leaf: empty -> leaf_end; else the
//              list fields, and with fuse its first list line (lreq_o: c + 3's list stage reads
//              it, from base c + max(node_hl, 1)), else back as an inner node's step
//   list       lreq_o: c + 3's list stage makes the list step (base c + 1)
//   leaf_done  the leaf's reduced result becomes the best hit (tmax = its t); leaf_end
//   pop        pop
//   leaf_end   finish if there is a hit and (an any-hit shadow ray, or the hit is not beyond this
//              cell: !(tfar < best.t)); else pop
//   pop        empty stack: finish; else take the top entry; if the best hit is before its tnear
//              the ray stays in state pop (back at c + extra + lat); else the entry's node and
//              interval, and with fuse its node step in the same pass (access A)
//
// `extra` is how far into the pass a step starts (the node cache's hit latency after a node
// read), `fused` that the pass already counted itself busy: every counter moves exactly as the
// model's, the pass's in c, the node read's outcome's in c + 1. A pass makes at most one cache
// access (A: the node, the 64-bit node word: split_or_count, then index | axis << 24, as
// hls::decode_node), asks for at most one list step, makes at most two pops (leaf_end -> pop ->
// fused node step of an empty leaf -> leaf_end -> pop: the second in the outcome, its comparisons
// made in the pass) and four comparisons (fp_cmp_nt, all in the pass); no arithmetic of its own.
// The outcome's ready cycles come in from trv_unit, one set for all pipes: again_i = c + lat,
// nxt_i = again_i + node_hl, lbn_i = c + max(node_hl, 1), lbl_i = c + 1. (A push's ready cycle
// below the next cycle's is taken then: trv_unit's head window is refilled at the edge.)
//
// Ray states (trv_unit's st encoding): 0 start, 1 node, 2 list, 3 wait_ist, 4 leaf_done, 5 pop,
// 6 done. Best record, packed {found, t, den, pos[31:0], id[31:0], k[1:0], nu, nv, nd}, its t and
// tmax the closest-hit key (hls::KeyFormat: TX extension bits below F's t, KW = W + TX bits; the
// comparisons with tfar and tnear see those widened, {x, TX zeros}: hls::t_key).
// mid_o / mid_i: {st, node, tnear, tfar, tmax, sp, first, count, pos, push, fin, lreq, node read,
// fused, empty leaf's finish, second pop's skip, second pop's entry, ray o d inv}, 177 + 13 W + KW
// bits.
module trv_pass #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer TX       = 0,   // the key's extension bits (0: the key is F's t)
  parameter integer KW_      = 1 + EXP_BITS + MAN_BITS + TX  // derived: the key's width
) (
  // ---- the pass (cycle c) ----
  input  wire                          go_i,         // this pipe takes a ray this cycle
  input  wire                          fuse_i,       // configuration (static per frame)
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
  input  wire [KW_-1:0]                tmax_i,
  input  wire [6:0]                    sp_i,
  input  wire [67+4*(1+EXP_BITS+MAN_BITS)+KW_-1:0] best_i,
  input  wire [67+4*(1+EXP_BITS+MAN_BITS)+KW_-1:0] leaf_i,
  input  wire [31:0]                   first_i,      // leaf list: first index, count, position
  input  wire [31:0]                   count_i,
  input  wire [31:0]                   pos_i,
  input  wire [32+2*(1+EXP_BITS+MAN_BITS)-1:0] e1_i, // stack[sp-1], {node, tnear, tfar} (tfar low)
  input  wire [32+2*(1+EXP_BITS+MAN_BITS)-1:0] e2_i, // stack[sp-2]
  // Access A: the node cache (the address registered by trv_unit, read in the next cycle, the
  // answer registered for the outcome).
  output wire                          acc_a_valid_o,
  output wire [31:0]                   acc_a_byte_o,
  // The record's best and tmax (written when go_i), what the outcome needs, the pass's counters.
  output reg  [67+4*(1+EXP_BITS+MAN_BITS)+KW_-1:0] best_o,
  output reg  [KW_-1:0]                tmax_o,
  output wire [177+13*(1+EXP_BITS+MAN_BITS)+KW_-1:0] mid_o,
  output reg                           busy_o,
  output reg                           pops_o,
  output reg                           fused_o,
  // ---- the outcome (cycle c + 1) ----
  input  wire [177+13*(1+EXP_BITS+MAN_BITS)+KW_-1:0] mid_i,
  input  wire                          rsp_a_hit_i,  // the node read's answer (registered)
  input  wire [63:0]                   rsp_a_node_i,
  input  wire [31:0]                   lbl_i,
  input  wire [31:0]                   again_i,
  input  wire [31:0]                   nxt_i,
  input  wire [31:0]                   lbn_i,
  // The record's next value (written by trv_unit in c + 1), leaf / results cleared when
  // wr_leaf_o.
  output reg  [2:0]                    st_o,
  output reg  [31:0]                   node_o,
  output reg  [EXP_BITS+MAN_BITS:0]    tnear_o,
  output reg  [EXP_BITS+MAN_BITS:0]    tfar_o,
  output reg  [6:0]                    sp_o,
  output reg  [31:0]                   first_o,
  output reg  [31:0]                   count_o,
  output reg  [31:0]                   pos_o,
  output wire [KW_-1:0]                out_tmax_o,   // tmax after the pass (the ist's hand-off)
  output reg                           wr_leaf_o,
  // An inner node: the split's inputs (trv.v op 0, in trv_unit from here); its results replace
  // node_o, tnear_o, tfar_o and push the far child at sp_o (sp_o + 1 after).
  output reg                           split_o,
  output wire [31:0]                   split_node_o,   // this node
  output wire [31:0]                   split_child_o,  // the node's other child (Node::index)
  output wire [EXP_BITS+MAN_BITS:0]    split_plane_o,
  output wire [EXP_BITS+MAN_BITS:0]    split_tnear_o,
  output wire [EXP_BITS+MAN_BITS:0]    split_tfar_o,
  output wire [3*(1+EXP_BITS+MAN_BITS)-1:0] split_ray_o, // {o, d, inv} on the axis (o highest)
  output reg                           q_push_o,     // back to the ready queue at q_ready_o
  output reg  [31:0]                   q_ready_o,
  output reg                           fin_o,        // done: to the hit unit (ready again_i)
  output reg                           lreq_o,       // a list step for the list stage (with the
  output reg                           lfused_o,     //   record's first_o, count_o, pos_o): fused
  output reg  [31:0]                   lbase_o,      //   into a node pass; its base cycle
  // The outcome's counter increments (systemc/config.h RtuStats names).
  output reg                           out_busy_o,
  output reg                           node_miss_o,
  output reg                           inner_o,
  output reg                           leaf_o,
  output reg                           out_pops_o,
  output reg                           out_fused_o
);

  localparam integer W  = 1 + EXP_BITS + MAN_BITS;
  localparam integer KW = KW_;
  localparam integer BW = 67 + 4 * W + KW;
  localparam integer EW = 32 + 2 * W;
  localparam integer MW = 177 + 13 * W + KW;
  localparam [2:0] S_START = 3'd0, S_NODE = 3'd1, S_LIST = 3'd2, S_LEAF_DONE = 3'd4,
                   S_POP = 3'd5, S_DONE = 3'd6;

  // Fields of the packed records.
  wire         best_found = best_i[BW-1];
  wire [KW-1:0] best_t    = best_i[BW-2 -: KW];
  wire         leaf_found = leaf_i[BW-1];
  wire [KW-1:0] leaf_t    = leaf_i[BW-2 -: KW];
  wire [31:0]  e1_node    = e1_i[EW-1 -: 32];
  wire [W-1:0] e1_tnear   = e1_i[2*W-1 -: W];
  wire [W-1:0] e1_tfar    = e1_i[W-1:0];
  wire [W-1:0] e2_tnear   = e2_i[2*W-1 -: W];
  // Packing of ray_i, lowest bits first: tmax, tmin, inv z, y, x, d z, y, x, o z, y, x (the
  // outcome's split takes o, d and inv; tmin was the entry clip's).
  wire [W-1:0] r_tmax  = ray_i[0 +: W];
  wire unused_ray = ^ray_i[W +: W];

  // The best hit as the pass sees it: a leaf_done pass takes the leaf's result first.
  wire         take_leaf = (st_i == S_LEAF_DONE) && leaf_found;
  wire         bf = take_leaf ? 1'b1 : best_found;
  wire [KW-1:0] bt = take_leaf ? leaf_t : best_t;
  // An F value as a key (hls::t_key): the extension bits zero.
  function automatic [KW-1:0] key(input [W-1:0] x);
    key = {KW{1'b0}};
    key[KW-1 -: W] = x;
  endfunction

  // Four comparisons, of keys: leaf_end against the ray's interval or the first popped entry's,
  // pop against the first or the second entry.
  wire c_tfar_lt, c_e1tfar_lt, c_e1_lt, c_e2_lt;
  wire [KW-1:0] u_min0, u_max0, u_min1, u_max1, u_min2, u_max2, u_min3, u_max3;
  wire [3:0] u_eq, u_rdy, u_vld;
  fp_cmp_nt #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS+TX), .STAGES(0)) u_c0 (
    .clk_i(1'b0), .rst_ni(1'b1), .in_valid_i(1'b1), .in_ready_o(u_rdy[0]), .in_a_i(key(tfar_i)),
    .in_b_i(bt), .out_valid_o(u_vld[0]), .out_ready_i(1'b1), .out_lt_o(c_tfar_lt),
    .out_eq_o(u_eq[0]), .out_min_o(u_min0), .out_max_o(u_max0));
  fp_cmp_nt #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS+TX), .STAGES(0)) u_c1 (
    .clk_i(1'b0), .rst_ni(1'b1), .in_valid_i(1'b1), .in_ready_o(u_rdy[1]), .in_a_i(key(e1_tfar)),
    .in_b_i(bt), .out_valid_o(u_vld[1]), .out_ready_i(1'b1), .out_lt_o(c_e1tfar_lt),
    .out_eq_o(u_eq[1]), .out_min_o(u_min1), .out_max_o(u_max1));
  fp_cmp_nt #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS+TX), .STAGES(0)) u_c2 (
    .clk_i(1'b0), .rst_ni(1'b1), .in_valid_i(1'b1), .in_ready_o(u_rdy[2]), .in_a_i(bt),
    .in_b_i(key(e1_tnear)), .out_valid_o(u_vld[2]), .out_ready_i(1'b1), .out_lt_o(c_e1_lt),
    .out_eq_o(u_eq[2]), .out_min_o(u_min2), .out_max_o(u_max2));
  fp_cmp_nt #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS+TX), .STAGES(0)) u_c3 (
    .clk_i(1'b0), .rst_ni(1'b1), .in_valid_i(1'b1), .in_ready_o(u_rdy[3]), .in_a_i(bt),
    .in_b_i(key(e2_tnear)), .out_valid_o(u_vld[3]), .out_ready_i(1'b1), .out_lt_o(c_e2_lt),
    .out_eq_o(u_eq[3]), .out_min_o(u_min3), .out_max_o(u_max3));
  wire unused_cmp = ^{u_min0, u_max0, u_min1, u_max1, u_min2, u_max2, u_min3, u_max3, u_eq, u_rdy,
                      u_vld};

  // Whether the pass's node step starts from the first popped entry (so the split sees its
  // interval): a leaf_done or pop pass whose pop goes on to a node, with fuse.
  wire le1_fin  = bf && ((shadow_i && any_hit_i) || !c_tfar_lt);
  wire pop1     = (st_i == S_POP) || ((st_i == S_LEAF_DONE) && !le1_fin);
  wire pop1_node = pop1 && (sp_i != 7'd0) && !(bf && c_e1_lt);
  wire node_from_e1 = pop1_node && fuse_i;
  wire [31:0] this_node = node_from_e1 ? e1_node : node_i;

  // Access A, decided by the pass's inputs alone: the node of a node pass or of a fused pop.
  wire        a_node = go_i && ((st_i == S_NODE) || node_from_e1);
  assign acc_a_valid_o = a_node;
  assign acc_a_byte_o  = {this_node[28:0], 3'd0};
  wire unused_node = ^this_node[31:29];

  // ---- the pass, in the model's order, up to the node read ------------------------------------
  reg [2:0]   p_st;
  reg [31:0]  p_node;
  reg [W-1:0] p_tnear, p_tfar;
  reg [6:0]   p_sp;
  reg         p_push, p_fin, p_lreq, p_fused;
  always @* begin
    p_st = st_i;  p_node = node_i;  p_tnear = tnear_i;  p_tfar = tfar_i;  tmax_o = tmax_i;
    p_sp = sp_i;  best_o = best_i;
    p_push = 1'b0;  p_fin = 1'b0;  p_lreq = 1'b0;  p_fused = 1'b0;
    busy_o = 1'b0;  pops_o = 1'b0;  fused_o = 1'b0;
    if (go_i) begin
      case (st_i)
        S_START: begin
          busy_o = 1'b1;
          best_o = {BW{1'b0}};
          p_sp = 7'd0;
          tmax_o = key(r_tmax);
          if (empty_i || !clip_i) begin
            p_fin = 1'b1;
          end else begin
            p_node = 32'd0;
            p_st = S_NODE;
            p_push = 1'b1;
          end
        end
        S_LIST: p_lreq = 1'b1;  // list_step: the list stage's, in the next cycle
        S_LEAF_DONE: begin
          busy_o = 1'b1;
          if (leaf_found) begin
            best_o = leaf_i;
            tmax_o = leaf_t;
          end
          if (le1_fin) p_fin = 1'b1;
        end
        S_POP: busy_o = 1'b1;
        default: ;  // S_NODE: the node read (a_node)
      endcase
      // pop #1 (leaf_done without a finish, or pop), with fuse_i.
      if (pop1) begin
        if (p_sp == 7'd0) begin
          p_fin = 1'b1;
        end else begin
          p_sp = p_sp - 7'd1;
          pops_o = 1'b1;
          if (bf && c_e1_lt) begin
            p_st = S_POP;
            p_push = 1'b1;
          end else begin
            p_node = e1_node;
            p_tnear = e1_tnear;
            p_tfar = e1_tfar;
            p_st = S_NODE;
            if (fuse_i) begin
              fused_o = 1'b1;
              p_fused = 1'b1;  // its node read (a_node), counted busy already
            end else
              p_push = 1'b1;
          end
        end
      end
      if (p_fin) begin  // finish: no queue push (a pass finishes at most once, last)
        p_push = 1'b0;
        p_st = S_DONE;
      end
    end
  end
  // What the outcome needs of an empty leaf's leaf_end and its pop (#2, without fuse): the
  // finish test, the entry below the first popped one when there was one, and its skip test.
  wire         le2_fin = bf && ((shadow_i && any_hit_i) || !(node_from_e1 ? c_e1tfar_lt : c_tfar_lt));
  wire         pop2_lt = bf && (pop1 ? c_e2_lt : c_e1_lt);
  wire [EW-1:0] pop2_e = pop1 ? e2_i : e1_i;
  assign mid_o = {p_st, p_node, p_tnear, p_tfar, tmax_o, p_sp, first_i, count_i, pos_i, p_push,
                  p_fin, p_lreq, a_node, p_fused, le2_fin, pop2_lt, pop2_e, ray_i[2*W +: 9*W]};

  // ---- the outcome (cycle c + 1) ---------------------------------------------------------------
  wire [2:0]   m_st    = mid_i[MW-1 -: 3];
  wire [31:0]  m_node  = mid_i[MW-4 -: 32];
  wire [W-1:0] m_tnear = mid_i[MW-36 -: W];
  wire [W-1:0] m_tfar  = mid_i[MW-36-W -: W];
  wire [KW-1:0] m_tmax = mid_i[MW-36-2*W -: KW];
  wire [6:0]   m_sp    = mid_i[MW-36-2*W-KW -: 7];
  wire [31:0]  m_first = mid_i[MW-43-2*W-KW -: 32];
  wire [31:0]  m_count = mid_i[MW-75-2*W-KW -: 32];
  wire [31:0]  m_pos   = mid_i[MW-107-2*W-KW -: 32];
  wire [6:0]   m_flags = mid_i[EW+9*W +: 7];  // push, fin, lreq, node read, fused, le2_fin, pop2_lt
  wire [EW-1:0] m_e    = mid_i[9*W +: EW];
  wire [9*W-1:0] m_ray = mid_i[0 +: 9*W];
  wire m_push = m_flags[6], m_fin = m_flags[5], m_lreq = m_flags[4], m_node_rd = m_flags[3],
       m_nfused = m_flags[2], m_le2_fin = m_flags[1], m_pop2_lt = m_flags[0];
  assign out_tmax_o = m_tmax;

  // The node read, and an inner node's split inputs.
  wire [31:0]  nd_lo = rsp_a_node_i[31:0];
  wire [31:0]  nd_hi = rsp_a_node_i[63:32];
  wire [31:0]  nd_index = {8'd0, nd_hi[23:0]};
  wire [1:0]   nd_axis = nd_hi[25:24];
  wire unused_nd = ^nd_hi[31:26];
  assign split_node_o  = m_node;
  assign split_child_o = nd_index;
  assign split_plane_o = nd_lo[W-1:0];
  assign split_tnear_o = m_tnear;
  assign split_tfar_o  = m_tfar;
  // m_ray: {o x, o y, o z, d x, d y, d z, inv x, inv y, inv z}, o x highest.
  assign split_ray_o   = (nd_axis == 2'd2) ? {m_ray[6*W +: W], m_ray[3*W +: W], m_ray[0 +: W]} :
                         (nd_axis == 2'd1) ? {m_ray[7*W +: W], m_ray[4*W +: W], m_ray[W +: W]} :
                                             {m_ray[8*W +: W], m_ray[5*W +: W], m_ray[2*W +: W]};

  reg [6:0] sp;
  always @* begin
    st_o = m_st;  node_o = m_node;  tnear_o = m_tnear;  tfar_o = m_tfar;  sp = m_sp;
    first_o = m_first;  count_o = m_count;  pos_o = m_pos;  wr_leaf_o = 1'b0;  split_o = 1'b0;
    q_push_o = m_push;  q_ready_o = again_i;  fin_o = m_fin;
    lreq_o = m_lreq;  lfused_o = 1'b0;  lbase_o = lbl_i;
    out_busy_o = 1'b0;  node_miss_o = 1'b0;  inner_o = 1'b0;  leaf_o = 1'b0;  out_pops_o = 1'b0;
    out_fused_o = 1'b0;
    if (m_node_rd) begin  // node_outcome (extra 0)
      if (!rsp_a_hit_i) begin
        if (!m_nfused) node_miss_o = 1'b1;
        q_push_o = 1'b1;
        q_ready_o = again_i;
      end else begin
        if (!m_nfused) out_busy_o = 1'b1;
        if (nd_axis != 2'd3) begin  // inner node: the split follows in trv_unit
          inner_o = 1'b1;
          split_o = 1'b1;
          q_push_o = 1'b1;
          q_ready_o = nxt_i;
        end else begin
          leaf_o = 1'b1;
          if (nd_lo == 32'd0) begin  // leaf_end of an empty leaf, without fuse
            if (m_le2_fin || sp == 7'd0) begin
              fin_o = 1'b1;
            end else begin  // pop #2
              sp = sp - 7'd1;
              out_pops_o = 1'b1;
              if (m_pop2_lt) begin
                st_o = S_POP;
              end else begin
                node_o = m_e[EW-1 -: 32];
                tnear_o = m_e[2*W-1 -: W];
                tfar_o = m_e[W-1:0];
                st_o = S_NODE;
              end
              q_push_o = 1'b1;
              q_ready_o = nxt_i;
            end
          end else begin
            first_o = nd_index;
            count_o = nd_lo;
            pos_o = 32'd0;
            wr_leaf_o = 1'b1;
            st_o = S_LIST;
            if (fuse_i) begin  // the next cycle's list stage reads the first line
              out_fused_o = 1'b1;
              lreq_o = 1'b1;
              lfused_o = 1'b1;
              lbase_o = lbn_i;
            end else begin
              q_push_o = 1'b1;
              q_ready_o = nxt_i;
            end
          end
        end
      end
    end
    if (fin_o) begin
      q_push_o = 1'b0;
      st_o = S_DONE;
    end
    sp_o = sp;
  end

endmodule
