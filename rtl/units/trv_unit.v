// trv_unit - the traversal unit whole: the ray slots, the per-ray stacks, the ready queue with
// looping for the next chance, PIPES traversal pipes (trv_pass, each with its trv.v datapath) and
// the reduction of the ist's results. The RTL view of systemc/trv.h plus the result half of
// systemc/ist.h: bound into the running frame by systemc/trv_rtl.h (raycore simulate --rtl trv),
// cycle for cycle and bit for bit the transaction model's.
//
// Per cycle, in the model's order:
//   1. up to IST ist results (res_*): each goes into its ray's leaf record (the closest, ties to
//      the earliest list position; results of one ray in the same cycle reduce in port order);
//      the leaf's last result puts the ray in state leaf_done, and back into the queue in the
//      next cycle (registered; its ready cycle the one after: Ist::leave's deferred push);
//   2. the outcome stage (Trv::out_stage): pipe p's pass of two cycles before (its registers and
//      its node read's registered answer, trv_pass's second half) writes the ray's record,
//      pushes it back with its ready cycle, hands it to the hit unit (fin_*) or asks the next
//      cycle's list stage for a list step;
//   3. the list stage's effects of the cycle before (registers): its hand-offs to the ist
//      (ist_*), its rays back to the queue or waiting for the ist, their new list positions;
//      then the list stage: the list steps the outcomes asked for in the cycle before, one per
//      pipe, each reading its list line through lacc_* / lrsp_* (the list cache, one port per
//      pipe) and deciding its hand-off and its ray's push, registered for the next cycle. The
//      ist queue's room (room_i, at the cycle's start, less the hand-offs entering it at this
//      cycle's end) is taken in stage order: stage p's room is that less what stages 0 .. p-1
//      hand out (with its line present: the entries left, to the line's end; 0 on a miss), so
//      stage p's access valid depends on the earlier stages' line presence (the caller answers
//      them in order);
//   4. the read stage (Trv::read_stage): pipe p's pass of the cycle before reads the node cache
//      through nacc_* at the address it registered (the answer, nrsp_*, is registered for the
//      outcome in the next cycle: no access of this cycle waits for it);
//   5. pipe p (p < pipes_i) takes the queue's entry p if pipes 0 .. p-1 took theirs and its ready
//      cycle has come; its pass (trv_pass's first half) writes the ray's best record and tmax and
//      registers its node read's address and the rest for its read stage and outcome (4., 2.).
//      An inner node's split (trv.v, op 0) follows the outcome: it runs in the outcome's cycle
//      and the next two and writes the ray's node, interval and stack push back a cycle later (the
//      split stage, 7. below). The ray is not taken again before that: its ready cycle is at
//      least the pass's + 6 (trv_latency + the node cache's hit latency >= 6, which the bindings
//      check), and nothing else reads its slot or stack in between. A ray in its read stage or
//      outcome or its list step is in no queue until the step's effects;
//   6. a ray from the rgu (in_*: a new primary ray or a shadow ray in its slot) is written into
//      its slot, registered, and clipped to the scene box over the next five cycles (trv.v, op 1:
//      hls::trv_clip_box; the ray's start pass reads the result: the model clips in that pass,
//      from the same inputs); at the clip's end, five cycles after the entry, it enters the queue,
//      ready the cycle after (systemc/config.h kTrvEntryDelay; the model's Rgu delays its push);
//   7. the split stage: the splits of this cycle's outcomes' inner nodes.
// Queue pushes of a cycle are appended in that order (the last cycle's last results, outcomes
// 0.., list stage's effects, rgu);
// the queue is a FIFO whose head blocks the entries behind it until its ready cycle: the cycle
// model's TimedFifo. Ready cycles are 32-bit cycle numbers compared with now_i as a signed
// difference.
//
// Storage (register arrays here; SRAMs in a chip): per slot the ray (11 words), the state and
// interval, the best and the leaf record, the list fields; per slot DEPTH stack entries of
// {node, tnear, tfar}; the queue (2^SLOT_BITS entries of slot + ready cycle). Parameters:
// SLOT_BITS (2^SLOT_BITS slots), DEPTH (stack entries per slot, depth_i <= DEPTH at run time),
// PIPES (pipes_i <= PIPES at run time), IST (ist results per cycle), WORDS (list words per cache
// read), READS (1: the slot read ports rd_* for the ist and hit units, as rtu.v wires them; 0: none,
// the outputs zero, as the frame's binding reads systemc's slots). Not here: the mailbox
// (--mailbox, refused by the binding). pend_o: a read stage, an outcome or the split stage holds work (a binding
// that skips idle cycles must clock this one).
// lint: also READS=1 SLOT_BITS=7 DEPTH=64 PIPES=4 IST=2 WORDS=16
// lint: also TX=7 READS=1 SLOT_BITS=7 DEPTH=64 PIPES=4 IST=2 WORDS=16
module trv_unit #(
  parameter integer EXP_BITS  = 7,
  parameter integer MAN_BITS  = 16,
  parameter integer RNE       = 0,
  parameter integer RAYCORE   = 0,
  parameter integer SLOT_BITS = 3,
  parameter integer DEPTH     = 8,
  parameter integer PIPES     = 2,
  parameter integer IST       = 2,
  parameter integer WORDS     = 4,
  parameter integer READS     = 0,
  // The closest-hit key's extension bits below F's t (hls::KeyFormat): the slots' tmax, the best
  // and leaf records' t and the ist's results are keys of KW_ = W + TX bits, compared as numbers
  // with MAN_BITS + TX mantissa bits (tfar and tnear widened, {x, TX zeros}); 0: F's t (Wald's
  // records alone: rtu.v's), 7 for FP24 with the watertight test's t.
  parameter integer TX        = 0,
  parameter integer KW_       = 1 + EXP_BITS + MAN_BITS + TX  // derived: the key's width
) (
  input  wire                            clk_i,
  input  wire                            rst_ni,
  input  wire [31:0]                     now_i,
  // Configuration, static per frame.
  input  wire [15:0]                     lat_i,
  input  wire [15:0]                     node_hl_i,
  input  wire [15:0]                     list_hl_i,
  input  wire [6:0]                      lwords_i,    // list cache line: words (<= WORDS)
  input  wire [4:0]                      pipes_i,
  input  wire                            fuse_i,
  input  wire                            any_hit_i,
  input  wire                            empty_i,
  input  wire [6:0]                      depth_i,
  input  wire [6:0]                      widen_i,
  input  wire [6*(1+EXP_BITS+MAN_BITS)-1:0] box_i,       // {hi z y x, lo z y x}
  // A ray from the rgu.
  input  wire                            in_valid_i,
  input  wire [SLOT_BITS-1:0]            in_slot_i,
  input  wire                            in_shadow_i,
  input  wire [11*(1+EXP_BITS+MAN_BITS)-1:0] in_ray_i,   // {o xyz, d xyz, inv xyz, tmin, tmax}
  // ist results (port u in bits [u*w +: w]).
  input  wire [IST-1:0]                  res_valid_i,
  input  wire [IST*SLOT_BITS-1:0]        res_slot_i,
  input  wire [IST-1:0]                  res_hit_i,
  input  wire [IST*(67+4*(1+EXP_BITS+MAN_BITS)+KW_)-1:0] res_rec_i,  // {1, t, den, pos, id, k, nu, nv, nd}
  input  wire [15:0]                     room_i,
  // Node cache, port p = pipe p's pass (the byte of its node; the response: the line's presence
  // and the 64-bit node word at the byte).
  output wire [PIPES-1:0]                nacc_valid_o,
  output wire [PIPES*32-1:0]             nacc_byte_o,
  input  wire [PIPES-1:0]                nrsp_hit_i,
  input  wire [PIPES*64-1:0]             nrsp_node_i,
  // List cache, port p = list stage p (the byte of its list entry; the response: the line's
  // presence and the words from that byte on, at least to the line's end).
  output wire [PIPES-1:0]                lacc_valid_o,
  output wire [PIPES*32-1:0]             lacc_byte_o,
  input  wire [PIPES-1:0]                lrsp_hit_i,
  input  wire [PIPES*32*WORDS-1:0]       lrsp_data_i,
  // Per pipe: the slot it took; the finish of its pass in the cycle before (the ray's slot and
  // best record), to the hit unit with ready cycle fin_ready_o (the same for every pipe).
  output wire [PIPES-1:0]                go_o,
  output wire [PIPES*SLOT_BITS-1:0]      slot_o,
  output wire [PIPES-1:0]                fin_o,
  output wire [PIPES*SLOT_BITS-1:0]      fin_slot_o,
  output wire [31:0]                     fin_ready_o,
  output wire [PIPES*(67+4*(1+EXP_BITS+MAN_BITS)+KW_)-1:0] best_o,
  // Per list stage: the ist hand-off (ist_n_o entries, 0: none).
  output wire [PIPES*6-1:0]              ist_n_o,
  output wire [PIPES*SLOT_BITS-1:0]      ist_slot_o,
  output wire [PIPES*32-1:0]             ist_pos_o,
  output wire [PIPES*32-1:0]             ist_ready_o,
  output wire [PIPES*KW_-1:0]           ist_tmax_o,
  output wire [PIPES*32*WORDS-1:0]       ist_words_o,
  // Slot reads (same cycle, READS = 1), o x lowest: unit u's ist entry {tmax, tmin, d zyx, o zyx};
  // the ray entering the hit unit {shadow, best, d zyx, o zyx}; the best record of the ray leaving.
  input  wire [IST*SLOT_BITS-1:0]        rd_ist_slot_i,
  output wire [IST*(7*(1+EXP_BITS+MAN_BITS)+KW_)-1:0] rd_ist_o,
  input  wire [SLOT_BITS-1:0]            rd_hit_slot_i,
  output wire [1+67+10*(1+EXP_BITS+MAN_BITS)+KW_-1:0] rd_hit_o,
  input  wire [SLOT_BITS-1:0]            rd_px_slot_i,
  output wire [67+4*(1+EXP_BITS+MAN_BITS)+KW_-1:0] rd_px_best_o,
  // The queue's head (the cycle model's next event).
  output wire                            head_valid_o,
  output wire [31:0]                     head_ready_o,
  output wire                            pend_o,
  // Counters (systemc/config.h RtuStats) and the stack-overflow error.
  output wire [63:0]                     cnt_busy_o,
  output wire [63:0]                     cnt_node_miss_o,
  output wire [63:0]                     cnt_list_miss_o,
  output wire [63:0]                     cnt_ist_full_o,
  output wire [63:0]                     cnt_inner_o,
  output wire [63:0]                     cnt_leaf_o,
  output wire [63:0]                     cnt_pops_o,
  output wire [63:0]                     cnt_list_steps_o,
  output wire [63:0]                     cnt_fused_o,
  output reg  [6:0]                      stack_max_o,
  output wire                            err_o
);

  localparam integer W  = 1 + EXP_BITS + MAN_BITS;
  localparam integer KW = KW_;
  localparam integer BW = 67 + 4 * W + KW;
  localparam integer IW = 7 * W + KW;  // an ist slot read {tmax, tmin, d zyx, o zyx}
  localparam integer EW = 32 + 2 * W;
  localparam integer RW = 11 * W;
  localparam integer NS = 1 << SLOT_BITS;
  localparam integer DB = $clog2(DEPTH);  // DEPTH: a power of two
  localparam [2:0] S_START = 3'd0, S_WAIT = 3'd3, S_LEAF_DONE = 3'd4;

  // ---- storage ---------------------------------------------------------------------------------
  reg [2:0]      st_q      [0:NS-1];
  reg            shadow_q  [0:NS-1];
  reg [RW-1:0]   ray_q     [0:NS-1];
  reg [31:0]     node_q    [0:NS-1];
  reg [W-1:0]    tnear_q   [0:NS-1];
  reg [W-1:0]    tfar_q    [0:NS-1];
  reg [KW-1:0]   tmax_q    [0:NS-1];
  reg            clip_q    [0:NS-1];  // the ray meets the scene box (clipped as it entered)
  reg [6:0]      sp_q      [0:NS-1];
  reg [BW-1:0]   best_q    [0:NS-1];
  reg [BW-1:0]   leaf_q    [0:NS-1];
  reg [31:0]     first_q   [0:NS-1];
  reg [31:0]     count_q   [0:NS-1];
  reg [31:0]     pos_q     [0:NS-1];
  reg [31:0]     left_q    [0:NS-1];  // the leaf's results still to come (count - results so far)
  reg [EW-1:0]   stk_q     [0:NS*DEPTH-1];  // slot s, entry e at {s, e}
  reg [SLOT_BITS-1:0] fq_slot [0:NS-1];
  reg [31:0]     fq_ready  [0:NS-1];
  reg [6:0]      fq_sp     [0:NS-1];  // the ray's stack pointer as it entered the queue (= sp_q:
                                      //   only the ray's own passes write it), so the pipe's
                                      //   stack read does not wait for the slot's
  reg [SLOT_BITS-1:0] head_q;
  reg [SLOT_BITS:0]   cnt_q;
  reg            err_q;

  assign head_valid_o = (cnt_q != {(SLOT_BITS+1){1'b0}});

  // ---- the queue's head window -----------------------------------------------------------------
  // The first PIPES entries (head_q + k) in registers, so that a pass starts from its entry
  // without a read of the queue's array: refilled at every edge, each from the array (an entry
  // behind the new head, its stack pointer as the split stage writes it back at that edge) or
  // from this cycle's pushes (an entry that enters the window as it is pushed). Beyond cnt_q the
  // window's entries are not read.
  reg [SLOT_BITS-1:0] w_slot_q  [0:PIPES-1];
  reg [31:0]          w_ready_q [0:PIPES-1];
  reg [6:0]           w_sp_q    [0:PIPES-1];
  assign head_ready_o = w_ready_q[0];

  // ---- slot reads for the ist and hit units (READS = 1) -----------------------------------------
  // A wire ray's {o xyz, d xyz} (its bits [5W +: 6W], o x highest) as {d zyx, o zyx} (o x lowest).
  function automatic [6*W-1:0] dir_org(input [6*W-1:0] r);
    dir_org = {r[0 +: W], r[W +: W], r[2*W +: W], r[3*W +: W], r[4*W +: W], r[5*W +: W]};
  endfunction
  genvar r;
  generate
    if (READS != 0) begin : g_reads
      for (r = 0; r < IST; r = r + 1) begin : g_ist
        wire [SLOT_BITS-1:0] s = rd_ist_slot_i[r*SLOT_BITS +: SLOT_BITS];
        wire [RW-1:0]        ray = ray_q[s];
        wire                 unused_ray = ^{ray[2*W +: 3*W], ray[0 +: W]};  // inv, tmax
        assign rd_ist_o[r*IW +: IW] = {tmax_q[s], ray[W +: W], dir_org(ray[5*W +: 6*W])};
      end
      wire [RW-1:0] hray = ray_q[rd_hit_slot_i];
      wire          unused_hray = ^hray[0 +: 5*W];  // inv, tmin, tmax
      assign rd_hit_o = {shadow_q[rd_hit_slot_i], best_q[rd_hit_slot_i], dir_org(hray[5*W +: 6*W])};
      assign rd_px_best_o = best_q[rd_px_slot_i];
    end else begin : g_no_reads
      wire unused_rd = ^{rd_ist_slot_i, rd_hit_slot_i, rd_px_slot_i};
      assign rd_ist_o = {(IST*IW){1'b0}};
      assign rd_hit_o = {(1+BW+6*W){1'b0}};
      assign rd_px_best_o = {BW{1'b0}};
    end
  endgenerate

  // ---- 1. ist results: the leaf reduction over the ports ---------------------------------------
  // Port u acts on the record as the earlier ports of this cycle left it (same slot): the best of
  // the slot's leaf record and the earlier same-slot ports' hits, as the chain "port by port, each
  // keeping the closer hit (ties to the earlier list position)" leaves it. That best is one of those
  // records, so the port's choice is which: every compare is of port u's hit with one candidate
  // (the leaf record, or an earlier port's hit), all side by side, and the chain runs over one-hot
  // choices (who is best after port v) instead of through a compare per port: one compare deep.
  // Its result is the leaf's last if the results still to come, less the earlier ports' of the
  // same ray, are this one: left_q[s] == m + 1 with m those earlier ports, a compare with a small
  // constant straight from the slot's word (no sum in front of it: res_done starts the queue's
  // pushes and the head window's refill).
  wire [IST*BW-1:0] nl /* verilator split_var */;  // leaf record after port u
  wire [IST*32-1:0] nr /* verilator split_var */;  // results still to come after port u
  wire [IST-1:0]    res_done;
  // A leaf's last result puts its ray back in the queue in the next cycle (registered here; ready
  // the cycle after that): the queue's pushes and the head window start from registers.
  reg  [IST-1:0]            rq_v;
  reg  [IST*SLOT_BITS-1:0]  rq_slot;
  // Who is best after port u, one-hot: bit IST the slot's leaf record, bit v port v's hit.
  wire [IST*(IST+1)-1:0] best_of /* verilator split_var */;
  wire unused_best = ^best_of[(IST-1)*(IST+1) +: IST+1];  // no port after the last
  genvar u, v;
  generate
    for (u = 0; u < IST; u = u + 1) begin : g_res
      wire [SLOT_BITS-1:0] s = res_slot_i[u*SLOT_BITS +: SLOT_BITS];
      wire [BW-1:0] rec = res_rec_i[u*BW +: BW];
      wire [BW-1:0] leaf = leaf_q[s];
      // beats[c]: port u's hit is closer than candidate c (c = IST: the leaf record, if it has
      // one; c = v < u: port v's hit), ties to the earlier list position.
      wire [IST:0] beats;
      // before: who is best before port u (the last earlier same-slot port's choice, else the leaf).
      wire [(u+1)*(IST+1)-1:0] before /* verilator split_var */;
      wire [(u+1)*8-1:0]       mchain /* verilator split_var */;  // m + 1 after the earlier ports
      assign before[IST:0] = {1'b1, {IST{1'b0}}};
      assign mchain[7:0] = 8'd1;
      for (v = 0; v < IST; v = v + 1) begin : g_cand
        if (v < u) begin : g_prev
          wire [BW-1:0] o = res_rec_i[v*BW +: BW];
          wire same = res_valid_i[v] && (res_slot_i[v*SLOT_BITS +: SLOT_BITS] == s);
          assign before[(v+1)*(IST+1) +: IST+1] = same ? best_of[v*(IST+1) +: IST+1]
                                                       : before[v*(IST+1) +: IST+1];
          assign mchain[(v+1)*8 +: 8] = mchain[v*8 +: 8] + {7'd0, same};
          wire lt, eq, c_rdy, c_vld;
          wire [KW-1:0] c_min, c_max;
          fp_cmp_nt #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS+TX), .STAGES(0)) u_cmp (
            .clk_i(1'b0), .rst_ni(1'b1), .in_valid_i(1'b1), .in_ready_o(c_rdy),
            .in_a_i(rec[BW-2 -: KW]), .in_b_i(o[BW-2 -: KW]), .out_valid_o(c_vld),
            .out_ready_i(1'b1), .out_lt_o(lt), .out_eq_o(eq), .out_min_o(c_min), .out_max_o(c_max));
          wire unused = ^{c_min, c_max, c_rdy, c_vld, o[BW-1]};
          // The record's pos field lies below t and den.
          assign beats[v] = lt || (eq && (rec[BW-2-KW-W -: 32] < o[BW-2-KW-W -: 32]));
        end else begin : g_none
          assign beats[v] = 1'b0;
        end
      end
      wire lt, eq, l_rdy, l_vld;
      wire [KW-1:0] l_min, l_max;
      fp_cmp_nt #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS+TX), .STAGES(0)) u_cmp (
        .clk_i(1'b0), .rst_ni(1'b1), .in_valid_i(1'b1), .in_ready_o(l_rdy),
        .in_a_i(rec[BW-2 -: KW]), .in_b_i(leaf[BW-2 -: KW]), .out_valid_o(l_vld),
        .out_ready_i(1'b1), .out_lt_o(lt), .out_eq_o(eq), .out_min_o(l_min), .out_max_o(l_max));
      wire unused = ^{l_min, l_max, l_rdy, l_vld, rec[BW-1]};
      assign beats[IST] = !leaf[BW-1] || lt ||
                          (eq && (rec[BW-2-KW-W -: 32] < leaf[BW-2-KW-W -: 32]));
      wire [IST:0] cur = before[u*(IST+1) +: IST+1];
      wire win = res_hit_i[u] && |(cur & beats);
      wire [IST:0] me = {{(IST-u){1'b0}}, 1'b1, {u{1'b0}}};
      wire [IST:0] bo = win ? me : cur;
      assign best_of[u*(IST+1) +: IST+1] = bo;
      // The record of that choice.
      reg [BW-1:0] pick;
      integer c;
      always @* begin
        pick = bo[IST] ? leaf : {BW{1'b0}};
        for (c = 0; c < IST; c = c + 1)
          if (bo[c]) pick = pick | {1'b1, res_rec_i[c*BW +: BW-1]};
      end
      assign nl[u*BW +: BW] = pick;
      wire [31:0]   left = left_q[s];
      wire [31:0]   m1 = {24'd0, mchain[u*8 +: 8]};
      assign nr[u*32 +: 32] = left - m1;
      assign res_done[u] = res_valid_i[u] && (left == m1);
    end
  endgenerate

  // The chain's results as one word each (read with a variable index below).
  wire [IST*BW-1:0] nl_all = nl;
  wire [IST*32-1:0] nr_all = nr;

  // ---- 4., 5. the pipes: the pass (this cycle), its node read (the next) and its outcome -------
  // Registered at the pass, per pipe: that it took a ray (rv_q), the slot, the node read's address
  // and what the outcome needs (trv_pass's mid); in the read stage the node cache reads at that
  // address (nacc_*), and all of it moves on (mv_q, ms_q, mid_q) with the answer (the line's
  // presence and the word). The outcome's ready cycles, the same for every pipe: from c = now - 2,
  // the pass's cycle.
  localparam integer MW = 177 + 13 * W + KW;  // trv_pass's mid_o
  wire [31:0] o_lbl   = now_i - 32'd1;
  wire [31:0] o_again = now_i - 32'd2 + {16'd0, lat_i};
  wire [31:0] o_nxt   = o_again + {16'd0, node_hl_i};
  wire [31:0] o_lbn   = now_i - 32'd2 + ((node_hl_i == 16'd0) ? 32'd1 : {16'd0, node_hl_i});
  reg  [PIPES-1:0]     rv_q, racc_q, mv_q, mhit_q;
  reg  [SLOT_BITS-1:0] rs_q    [0:PIPES-1];
  reg  [31:0]          rbyte_q [0:PIPES-1];
  reg  [MW-1:0]        rmid_q  [0:PIPES-1];
  reg  [SLOT_BITS-1:0] ms_q    [0:PIPES-1];
  reg  [MW-1:0]        mid_q   [0:PIPES-1];
  reg  [63:0]          mword_q [0:PIPES-1];
  wire [PIPES-1:0]     g_acc;
  wire [PIPES*32-1:0]  g_byte;
  wire [PIPES:0]    go_chain /* verilator split_var */;
  assign go_chain[0] = 1'b1;
  wire [PIPES-1:0] g_busy, g_pops, g_fused;
  wire [PIPES*KW-1:0] g_tmax;
  wire [PIPES*BW-1:0] g_best;
  wire [PIPES*MW-1:0] g_mid;
  wire [PIPES-1:0] p_qpush, p_wr_leaf, p_busy, p_node_miss, p_inner, p_leaf, p_split, p_lreq,
                   p_lfused, p_fin, p_pops, p_fused;
  wire [PIPES*3-1:0] p_st;
  wire [PIPES*7-1:0] p_sp;
  wire [PIPES*32-1:0] p_node, p_first, p_count, p_pos, p_qready, p_lbase;
  wire [PIPES*W-1:0] p_tnear, p_tfar;
  wire [PIPES*KW-1:0] p_tmax;
  wire [PIPES*32-1:0] p_s_node, p_s_child;
  wire [PIPES*W-1:0] p_s_plane, p_s_tnear, p_s_tfar;
  wire [PIPES*3*W-1:0] p_s_ray;
  genvar p;
  generate
    for (p = 0; p < PIPES; p = p + 1) begin : g_pipe
      wire [SLOT_BITS-1:0] s = w_slot_q[p];
      wire [31:0] dt = w_ready_q[p] - now_i;
      wire go = go_chain[p] && (p < pipes_i) && (cnt_q > p) && (dt[31] || dt == 32'd0);
      assign go_chain[p+1] = go;
      assign go_o[p] = go;
      assign slot_o[p*SLOT_BITS +: SLOT_BITS] = s;
      wire [6:0] sp = w_sp_q[p];
      wire [6:0] sp1 = sp - 7'd1;
      wire [6:0] sp2 = sp - 7'd2;
      wire [EW-1:0] e1 = stk_q[{s, sp1[DB-1:0]}];
      wire [EW-1:0] e2 = stk_q[{s, sp2[DB-1:0]}];
      wire unused_sp = ^{sp1[6:DB], sp2[6:DB]};
      wire p_fin_raw, p_qpush_raw, p_lreq_raw, p_split_raw, p_busy_raw, p_miss_raw, p_inner_raw,
           p_leaf_raw, p_pops_raw, p_fused_raw;
      trv_pass #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .TX(TX)) u_pass (
        .go_i(go), .fuse_i(fuse_i), .any_hit_i(any_hit_i), .empty_i(empty_i), .st_i(st_q[s]),
        .clip_i(clip_q[s]), .shadow_i(shadow_q[s]), .ray_i(ray_q[s]),
        .node_i(node_q[s]), .tnear_i(tnear_q[s]), .tfar_i(tfar_q[s]), .tmax_i(tmax_q[s]),
        .sp_i(sp), .best_i(best_q[s]), .leaf_i(leaf_q[s]), .first_i(first_q[s]),
        .count_i(count_q[s]), .pos_i(pos_q[s]), .e1_i(e1), .e2_i(e2),
        .acc_a_valid_o(g_acc[p]), .acc_a_byte_o(g_byte[p*32 +: 32]),
        .best_o(g_best[p*BW +: BW]), .tmax_o(g_tmax[p*KW +: KW]), .mid_o(g_mid[p*MW +: MW]),
        .busy_o(g_busy[p]), .pops_o(g_pops[p]), .fused_o(g_fused[p]),
        .mid_i(mid_q[p]), .rsp_a_hit_i(mhit_q[p]), .rsp_a_node_i(mword_q[p]), .lbl_i(o_lbl),
        .again_i(o_again), .nxt_i(o_nxt), .lbn_i(o_lbn),
        .st_o(p_st[p*3 +: 3]), .node_o(p_node[p*32 +: 32]), .tnear_o(p_tnear[p*W +: W]),
        .tfar_o(p_tfar[p*W +: W]), .sp_o(p_sp[p*7 +: 7]),
        .first_o(p_first[p*32 +: 32]), .count_o(p_count[p*32 +: 32]), .pos_o(p_pos[p*32 +: 32]),
        .out_tmax_o(p_tmax[p*KW +: KW]), .wr_leaf_o(p_wr_leaf[p]),
        .split_o(p_split_raw), .split_node_o(p_s_node[p*32 +: 32]),
        .split_child_o(p_s_child[p*32 +: 32]),
        .split_plane_o(p_s_plane[p*W +: W]), .split_tnear_o(p_s_tnear[p*W +: W]),
        .split_tfar_o(p_s_tfar[p*W +: W]), .split_ray_o(p_s_ray[p*3*W +: 3*W]),
        .q_push_o(p_qpush_raw), .q_ready_o(p_qready[p*32 +: 32]), .fin_o(p_fin_raw),
        .lreq_o(p_lreq_raw), .lfused_o(p_lfused[p]), .lbase_o(p_lbase[p*32 +: 32]),
        .out_busy_o(p_busy_raw), .node_miss_o(p_miss_raw), .inner_o(p_inner_raw),
        .leaf_o(p_leaf_raw), .out_pops_o(p_pops_raw), .out_fused_o(p_fused_raw));
      // The outcome's effects count only for a pipe that took a ray in the cycle before.
      assign p_fin[p]       = mv_q[p] && p_fin_raw;
      assign p_qpush[p]     = mv_q[p] && p_qpush_raw;
      assign p_lreq[p]      = mv_q[p] && p_lreq_raw;
      assign p_split[p]     = mv_q[p] && p_split_raw;
      assign p_busy[p]      = mv_q[p] && p_busy_raw;
      assign p_node_miss[p] = mv_q[p] && p_miss_raw;
      assign p_inner[p]     = mv_q[p] && p_inner_raw;
      assign p_leaf[p]      = mv_q[p] && p_leaf_raw;
      assign p_pops[p]      = mv_q[p] && p_pops_raw;
      assign p_fused[p]     = mv_q[p] && p_fused_raw;
      assign nacc_valid_o[p] = rv_q[p] && racc_q[p];  // the read stage
      assign nacc_byte_o[p*32 +: 32] = rbyte_q[p];
      assign fin_o[p] = p_fin[p];
      assign fin_slot_o[p*SLOT_BITS +: SLOT_BITS] = ms_q[p];
      assign best_o[p*BW +: BW] = best_q[ms_q[p]];
    end
  endgenerate
  wire unused_chain = go_chain[PIPES];
  assign fin_ready_o = o_again;

  // ---- 3. the list stage: the list steps the outcomes asked for in the cycle before ----------
  // Registered at the outcome: the ray's slot, its list entry's index (first + position), the
  // entries left and what the step hands out with the room unlimited (want: the entries left, to
  // the line's end), the position, the base cycle of its ready cycles, whether the step is fused
  // into a node pass (it counts no busy, miss or full), the leaf-entry tmax the ist tests with and
  // the stack pointer for its queue entry. The stage reads the list cache and decides; its
  // effects (the hand-off to the ist, the ray back to the queue or waiting, its new position) are
  // registered and made in the next cycle (3b.).
  reg  [PIPES-1:0]     lv_q, lfused_q;
  reg  [SLOT_BITS-1:0] ls_q     [0:PIPES-1];
  reg  [31:0]          lidx_q   [0:PIPES-1];
  reg  [31:0]          lleft_q  [0:PIPES-1];
  reg  [5:0]           lwant_q  [0:PIPES-1];
  wire [PIPES*32-1:0]  o_idx_v, o_left_v;  // the outcome's, per pipe
  wire [PIPES*6-1:0]   o_want_v;
  reg  [31:0]          lpos_q   [0:PIPES-1];
  reg  [31:0]          lbase_q  [0:PIPES-1];
  reg  [KW-1:0]        ltmax_q  [0:PIPES-1];
  reg  [6:0]           lsp_q    [0:PIPES-1];
  // The ist queue's room for this stage: the ist's (at the cycle's start, with its misses on the
  // way back) less the hand-offs of the stage before, which enter it at this cycle's end.
  reg  [15:0]          hsum;
  integer hq;
  always @* begin
    hsum = 16'd0;
    for (hq = 0; hq < PIPES; hq = hq + 1) hsum = hsum + {10'd0, ist_n_o[hq*6 +: 6]};
  end
  wire [15:0] room_s = (room_i > hsum) ? room_i - hsum : 16'd0;
  wire [16*(PIPES+1)-1:0] lres /* verilator split_var */;  // room taken by stages 0 .. p-1
  wire [PIPES-1:0]     l_qpush, l_wait, l_busy, l_miss, l_full, l_step;
  wire [PIPES*6-1:0]   l_n;
  wire [PIPES*32-1:0]  l_qready;
  assign lres[15:0] = 16'd0;
  genvar l;
  generate
    for (l = 0; l < PIPES; l = l + 1) begin : g_list
      // In the outcome: the step's index, entries left and want (lwords_i a power of two).
      wire [31:0] o_idx   = p_first[l*32 +: 32] + p_pos[l*32 +: 32];
      wire [31:0] o_left  = p_count[l*32 +: 32] - p_pos[l*32 +: 32];
      wire [31:0] o_toend = {25'd0, lwords_i} - (o_idx & ({25'd0, lwords_i} - 32'd1));
      wire [31:0] o_want  = (o_left < o_toend) ? o_left : o_toend;
      assign o_idx_v[l*32 +: 32] = o_idx;
      assign o_left_v[l*32 +: 32] = o_left;
      assign o_want_v[l*6 +: 6] = o_want[5:0];
      wire unused_o = ^{o_want[31:6], o_toend[31:16]};
      // The stage: the earlier stages' sum of want (with their line present) is what they took
      // (each took min(want, room left), so the room left falls by want until it reaches 0; a
      // stage that finds no room makes no access). The hit is the line's presence, access or not.
      wire [31:0] idx    = lidx_q[l];
      wire [15:0] want   = {10'd0, lwant_q[l]};
      wire        hit    = lrsp_hit_i[l];
      wire [15:0] res_l  = lres[l*16 +: 16];
      wire [15:0] room_l = (room_s > res_l) ? room_s - res_l : 16'd0;
      assign lres[(l+1)*16 +: 16] = res_l + ((lv_q[l] && hit) ? want : 16'd0);
      wire        full   = room_l == 16'd0;
      wire [15:0] n      = (room_l < want) ? room_l : want;
      wire [31:0] again  = lbase_q[l] + {16'd0, lat_i};
      wire        took   = lv_q[l] && !full && hit;
      assign lacc_valid_o[l] = lv_q[l] && !full;
      assign lacc_byte_o[l*32 +: 32] = {idx[29:0], 2'd0};
      assign l_busy[l] = took && !lfused_q[l];
      assign l_miss[l] = lv_q[l] && !full && !hit && !lfused_q[l];
      assign l_full[l] = lv_q[l] && full && !lfused_q[l];
      assign l_step[l] = took;
      // All handed out: the ray waits for the ist (no queue push; without a mailbox some entries
      // are always at the ist). Else back at again (+ the list cache's hit latency after a read).
      assign l_wait[l]  = took && ({16'd0, n} == lleft_q[l]);
      assign l_qpush[l] = lv_q[l] && !l_wait[l];
      assign l_qready[l*32 +: 32] = took ? again + {16'd0, list_hl_i} : again;
      assign l_n[l*6 +: 6] = took ? n[5:0] : 6'd0;
      wire unused_l = ^{n[15:6], idx[31:30]};
    end
  endgenerate
  wire unused_lres = ^lres[PIPES*16 +: 16];

  // ---- 3b. the list stage's effects, registered: made in the cycle after its step -------------
  reg  [PIPES-1:0]     ev_q, eqpush_q, ewait_q;
  reg  [SLOT_BITS-1:0] es_q     [0:PIPES-1];
  reg  [31:0]          eqready_q[0:PIPES-1];
  reg  [6:0]           esp_q    [0:PIPES-1];
  reg  [5:0]           en_q     [0:PIPES-1];
  reg  [31:0]          epos_q   [0:PIPES-1];
  reg  [31:0]          eready_q [0:PIPES-1];
  reg  [KW-1:0]        etmax_q  [0:PIPES-1];
  reg  [32*WORDS-1:0]  ewords_q [0:PIPES-1];
  wire [PIPES-1:0]     e_qpush = ev_q & eqpush_q;
  generate
    for (l = 0; l < PIPES; l = l + 1) begin : g_eff
      assign ist_n_o[l*6 +: 6] = ev_q[l] ? en_q[l] : 6'd0;
      assign ist_slot_o[l*SLOT_BITS +: SLOT_BITS] = es_q[l];
      assign ist_pos_o[l*32 +: 32] = epos_q[l];
      assign ist_ready_o[l*32 +: 32] = eready_q[l];
      assign ist_tmax_o[l*KW +: KW] = etmax_q[l];
      assign ist_words_o[l*32*WORDS +: 32*WORDS] = ewords_q[l];
    end
  endgenerate

  // ---- 6. the clip of the entering ray (trv.v, op 1) -------------------------------------------
  // Packing of in_ray_i, lowest bits first: tmax, tmin, inv z, y, x, d z, y, x, o z, y, x.
  // The ray, its state and shadow flag are written into its slot at the entry. The clip runs over
  // the next CL cycles: the entering ray registered (so that rtu.v's choice of the primary or the
  // shadow ray ends at a register), then trv.v with a register after its subtraction, its
  // multiplication, its comparisons (and its comparator tree, CLIP_S4 = 1; the slot rides as its
  // tag). At the clip's end the result is written and the ray enters the queue (ready the next
  // cycle): CL = kTrvEntryDelay cycles after it left the rgu or the hit unit (systemc/config.h;
  // the model's Rgu delays its push the same way).
  localparam integer CLIP_S4 = 1;
  localparam integer CL = 4 + CLIP_S4;
  wire         c_rdy, c_vld, c_op, c_hit, c_below;
  wire [SLOT_BITS-1:0] c_slot;
  wire [1:0]   c_visit;
  wire [W-1:0] c_tsplit, c_tnear, c_tfar, c_far_tfar;
  wire [31:0]  c_node, c_far_node;
  reg  [CL-2:0] cv_q;  // the clips in flight: [0] the registered entry, then between trv.v's registers
  reg  [11*W-1:0]      e_ray_q;
  reg  [SLOT_BITS-1:0] e_slot_q;
  always @(posedge clk_i) begin
    e_ray_q <= in_ray_i;
    e_slot_q <= in_slot_i;
  end
  trv #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(0),
        .S1(1), .S2(1), .S3(1), .S4(CLIP_S4), .TAG_BITS(SLOT_BITS)) u_clip (
    .clk_i(clk_i), .rst_ni(rst_ni), .widen_i(widen_i), .in_valid_i(cv_q[0]), .in_ready_o(c_rdy),
    .in_op_i(1'b1), .in_axis_i(2'd0), .in_split_i({W{1'b0}}), .in_node_i(32'd0),
    .in_child_i(32'd0), .in_o_x_i(e_ray_q[10*W +: W]), .in_o_y_i(e_ray_q[9*W +: W]),
    .in_o_z_i(e_ray_q[8*W +: W]), .in_d_x_i(e_ray_q[7*W +: W]), .in_d_y_i(e_ray_q[6*W +: W]),
    .in_d_z_i(e_ray_q[5*W +: W]), .in_inv_x_i(e_ray_q[4*W +: W]),
    .in_inv_y_i(e_ray_q[3*W +: W]), .in_inv_z_i(e_ray_q[2*W +: W]),
    .in_tnear_i(e_ray_q[W +: W]), .in_tfar_i(e_ray_q[0 +: W]),
    .in_lo_x_i(box_i[0 +: W]), .in_lo_y_i(box_i[W +: W]), .in_lo_z_i(box_i[2*W +: W]),
    .in_hi_x_i(box_i[3*W +: W]), .in_hi_y_i(box_i[4*W +: W]), .in_hi_z_i(box_i[5*W +: W]),
    .in_tag_i(e_slot_q), .out_valid_o(c_vld), .out_ready_i(1'b1), .out_op_o(c_op), .out_hit_o(c_hit),
    .out_visit_o(c_visit), .out_below_o(c_below), .out_tsplit_o(c_tsplit),
    .out_tnear_o(c_tnear), .out_tfar_o(c_tfar), .out_node_o(c_node),
    .out_far_node_o(c_far_node), .out_far_tfar_o(c_far_tfar), .out_tag_o(c_slot));
  wire unused_clip = ^{c_rdy, c_op, c_below, c_visit, c_tsplit, c_node, c_far_node, c_far_tfar};

  // ---- 7. the split stage: this cycle's outcomes' inner nodes (trv.v, op 0, on the node's axis)
  // From the outcome (the registered pass and node word): the split's inputs, the ray's slot, its
  // stack pointer after the pass and where its queue entry goes (its fq_sp follows the split's
  // push). The split runs over three cycles, this one and the next two (trv.v with a register
  // after its subtraction and one after its multiplication; the slot, stack pointer and queue
  // position ride as its tag); its results are registered (s_*, w*_q) and written back at the end
  // of the cycle after that, so the ray is taken at the pass's cycle + 6 at the earliest
  // (trv_latency + the node cache's hit latency >= 6, which the bindings check).
  localparam integer      STW = 2 * SLOT_BITS + 7;  // the split's tag: {slot, sp, queue position}
  wire [PIPES-1:0]         d_vld, d_push, s_err;
  wire [PIPES*STW-1:0]     d_tag;
  wire [PIPES*32-1:0]      d_node;
  wire [PIPES*W-1:0]       d_tnear, d_tfar;
  wire [PIPES*EW-1:0]      d_push_e;
  // The split's results, registered for the write-back: valid, push, slot, stack pointer, queue
  // position, the next node and interval, the pushed entry.
  reg  [PIPES-1:0]         wv_q, s_push;
  reg  [PIPES-1:0]         sv_q;  // a split in its second cycle (between trv.v's two registers)
  reg  [SLOT_BITS-1:0]     ws_q    [0:PIPES-1];
  reg  [6:0]               wsp_q   [0:PIPES-1];
  reg  [SLOT_BITS-1:0]     wat_q   [0:PIPES-1];
  reg  [PIPES*32-1:0]      s_node;
  reg  [PIPES*W-1:0]       s_tnear, s_tfar;
  reg  [PIPES*EW-1:0]      s_push_e;
  integer int_q;
  genvar q;
  generate
    for (q = 0; q < PIPES; q = q + 1) begin : g_split
      wire         d_rdy, d_op, d_hit, d_below;
      wire [1:0]   d_visit;
      wire [W-1:0] d_tsplit, d_far_tfar;
      wire [31:0]  d_far_node;
      wire [3*W-1:0] sr = p_s_ray[q*3*W +: 3*W];  // {o, d, inv} on the node's axis, as lane x
      trv #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(0),
            .S1(1), .S2(1), .TAG_BITS(STW)) u_dp (
        .clk_i(clk_i), .rst_ni(rst_ni), .widen_i(widen_i), .in_valid_i(p_split[q]),
        .in_ready_o(d_rdy),
        .in_op_i(1'b0), .in_axis_i(2'd0), .in_split_i(p_s_plane[q*W +: W]),
        .in_node_i(p_s_node[q*32 +: 32]), .in_child_i(p_s_child[q*32 +: 32]), .in_o_x_i(sr[2*W +: W]), .in_o_y_i({W{1'b0}}),
        .in_o_z_i({W{1'b0}}), .in_d_x_i(sr[W +: W]), .in_d_y_i({W{1'b0}}), .in_d_z_i({W{1'b0}}),
        .in_inv_x_i(sr[0 +: W]), .in_inv_y_i({W{1'b0}}), .in_inv_z_i({W{1'b0}}),
        .in_tnear_i(p_s_tnear[q*W +: W]), .in_tfar_i(p_s_tfar[q*W +: W]), .in_lo_x_i({W{1'b0}}),
        .in_lo_y_i({W{1'b0}}), .in_lo_z_i({W{1'b0}}), .in_hi_x_i({W{1'b0}}),
        .in_hi_y_i({W{1'b0}}), .in_hi_z_i({W{1'b0}}), .in_tag_i({ms_q[q], p_sp[q*7 +: 7], pipe_at[q*SLOT_BITS +: SLOT_BITS]}),
        .out_valid_o(d_vld[q]),
        .out_ready_i(1'b1), .out_op_o(d_op), .out_hit_o(d_hit), .out_visit_o(d_visit),
        .out_below_o(d_below), .out_tsplit_o(d_tsplit), .out_tnear_o(d_tnear[q*W +: W]),
        .out_tfar_o(d_tfar[q*W +: W]), .out_node_o(d_node[q*32 +: 32]),
        .out_far_node_o(d_far_node), .out_far_tfar_o(d_far_tfar), .out_tag_o(d_tag[q*STW +: STW]));
      wire unused_dp = ^{d_rdy, d_op, d_hit, d_below};
      assign d_push[q] = d_vld[q] && (d_visit == 2'd2);
      assign d_push_e[q*EW +: EW] = {d_far_node, d_tsplit, d_far_tfar};
      assign s_err[q] = s_push[q] && (wsp_q[q] >= depth_i);
    end
  endgenerate
  always @(posedge clk_i) begin
    s_node <= d_node;
    s_tnear <= d_tnear;
    s_tfar <= d_tfar;
    s_push_e <= d_push_e;
    for (int_q = 0; int_q < PIPES; int_q = int_q + 1)
      {ws_q[int_q], wsp_q[int_q], wat_q[int_q]} <= d_tag[int_q*STW +: STW];
  end
  assign pend_o = (|rv_q) || (|mv_q) || (|lv_q) || (|ev_q) || (|sv_q) || (|d_vld) || (|wv_q) ||
                  (|rq_v) || (|cv_q) || c_vld;
  assign err_o = err_q || |s_err;

  // ---- 8. state update (with the queue's head window) ----------------------------------------
  // Where each queue push goes: after the live entries, in the order results, the pipes'
  // outcomes, list stage, rgu (the popped entries leave from the head, so the tail does not move
  // with them).
  wire [SLOT_BITS-1:0] tail = head_q + cnt_q[SLOT_BITS-1:0];
  reg  [IST*SLOT_BITS-1:0]   res_at;
  reg  [PIPES*SLOT_BITS-1:0] list_at;
  reg  [PIPES*SLOT_BITS-1:0] pipe_at;
  reg  [SLOT_BITS-1:0]       rgu_at;
  reg  [SLOT_BITS:0]         pushes, pops;
  integer a;
  always @* begin
    pushes = {(SLOT_BITS+1){1'b0}};
    pops = {(SLOT_BITS+1){1'b0}};
    res_at = {(IST*SLOT_BITS){1'b0}};
    list_at = {(PIPES*SLOT_BITS){1'b0}};
    pipe_at = {(PIPES*SLOT_BITS){1'b0}};
    for (a = 0; a < IST; a = a + 1) begin
      res_at[a*SLOT_BITS +: SLOT_BITS] = tail + pushes[SLOT_BITS-1:0];
      if (rq_v[a]) pushes = pushes + 1'b1;
    end
    for (a = 0; a < PIPES; a = a + 1) begin
      pipe_at[a*SLOT_BITS +: SLOT_BITS] = tail + pushes[SLOT_BITS-1:0];
      if (p_qpush[a]) pushes = pushes + 1'b1;
      if (go_o[a]) pops = pops + 1'b1;
    end
    for (a = 0; a < PIPES; a = a + 1) begin
      list_at[a*SLOT_BITS +: SLOT_BITS] = tail + pushes[SLOT_BITS-1:0];
      if (e_qpush[a]) pushes = pushes + 1'b1;
    end
    rgu_at = tail + pushes[SLOT_BITS-1:0];
    if (c_vld) pushes = pushes + 1'b1;
  end

  // The window after the edge: entry k is at head_q + pops + k. An entry already queued is
  // candidate j = pops + k (j < 2 PIPES) of the entries behind the head: the window's own
  // registers for j < PIPES, the array at head_q + j beyond, each with the stack pointer the split
  // stage writes at this edge. The array is read at addresses from registers (head_q), in parallel
  // with the ready compares and the pipes' go chain: only a select by pops follows them (not the
  // array's read at head_q + pops + k).
  reg [SLOT_BITS-1:0] cj_slot [0:2*PIPES-1];
  reg [31:0]          cj_ready[0:2*PIPES-1];
  reg [6:0]           cj_sp   [0:2*PIPES-1];
  reg [SLOT_BITS-1:0] cj_pos;
  integer cj, cx;
  always @* begin
    for (cj = 0; cj < 2 * PIPES; cj = cj + 1) begin
      cj_pos = head_q + cj[SLOT_BITS-1:0];
      if (cj < PIPES) begin
        cj_slot[cj] = w_slot_q[cj];
        cj_ready[cj] = w_ready_q[cj];
        cj_sp[cj] = w_sp_q[cj];
      end else begin
        cj_slot[cj] = fq_slot[cj_pos];
        cj_ready[cj] = fq_ready[cj_pos];
        cj_sp[cj] = fq_sp[cj_pos];
      end
      for (cx = 0; cx < PIPES; cx = cx + 1)
        if (s_push[cx] && wat_q[cx] == cj_pos) cj_sp[cj] = wsp_q[cx] + 7'd1;
    end
  end
  reg [SLOT_BITS-1:0] wn_slot [0:PIPES-1];
  reg [31:0]          wn_ready[0:PIPES-1];
  reg [6:0]           wn_sp   [0:PIPES-1];
  reg [SLOT_BITS-1:0] w_pos;
  reg [SLOT_BITS:0]   w_rel;
  integer j, k, x;
  always @* begin
    j = 0;  // each branch below runs only one of the two loops: no latch for the other's index
    x = 0;
    for (k = 0; k < PIPES; k = k + 1) begin
      w_rel = pops + k[SLOT_BITS:0];
      w_pos = head_q + w_rel[SLOT_BITS-1:0];
      wn_slot[k] = cj_slot[k];
      wn_ready[k] = cj_ready[k];
      wn_sp[k] = cj_sp[k];
      if (w_rel < cnt_q) begin  // an entry already queued
        for (j = 0; j < 2 * PIPES; j = j + 1)
          if (w_rel == j[SLOT_BITS:0]) begin
            wn_slot[k] = cj_slot[j];
            wn_ready[k] = cj_ready[j];
            wn_sp[k] = cj_sp[j];
          end
      end else begin            // one pushed in this cycle (or none: not read)
        for (x = 0; x < IST; x = x + 1)
          if (rq_v[x] && res_at[x*SLOT_BITS +: SLOT_BITS] == w_pos) begin
            wn_slot[k] = rq_slot[x*SLOT_BITS +: SLOT_BITS];
            wn_ready[k] = now_i + 32'd1;
            wn_sp[k] = sp_q[rq_slot[x*SLOT_BITS +: SLOT_BITS]];
          end
        for (x = 0; x < PIPES; x = x + 1)
          if (p_qpush[x] && pipe_at[x*SLOT_BITS +: SLOT_BITS] == w_pos) begin
            wn_slot[k] = ms_q[x];
            wn_ready[k] = p_qready[x*32 +: 32];
            wn_sp[k] = p_sp[x*7 +: 7];
          end
        for (x = 0; x < PIPES; x = x + 1)
          if (e_qpush[x] && list_at[x*SLOT_BITS +: SLOT_BITS] == w_pos) begin
            wn_slot[k] = es_q[x];
            wn_ready[k] = eqready_q[x];
            wn_sp[k] = esp_q[x];
          end
        if (c_vld && rgu_at == w_pos) begin
          wn_slot[k] = c_slot;
          wn_ready[k] = now_i + 32'd1;
          wn_sp[k] = 7'd0;
        end
      end
    end
  end

  // The slot arrays, the stacks and the queue's entries (no reset: written before they are read).
  integer b;
  always @(posedge clk_i) begin
    // The rgu's ray (a free slot, or a shadow ray in its primary ray's slot).
    if (in_valid_i) begin
      st_q[in_slot_i] <= S_START;
      shadow_q[in_slot_i] <= in_shadow_i;
      ray_q[in_slot_i] <= in_ray_i;
    end
    if (c_vld) begin  // the clip of the ray that entered CL cycles before: to the queue
      clip_q[c_slot] <= c_hit;
      tnear_q[c_slot] <= c_tnear;
      tfar_q[c_slot] <= c_tfar;
      fq_slot[rgu_at] <= c_slot;
      fq_ready[rgu_at] <= now_i + 32'd1;
      fq_sp[rgu_at] <= 7'd0;  // a start pass sets its own (the stack is not read)
    end
    // The pipes' rays: the pass writes the best record and tmax (distinct slots, none of them the
    // rgu's) and registers the rest for its read stage, which passes it on to the outcome.
    for (b = 0; b < PIPES; b = b + 1) begin
      mhit_q[b] <= nrsp_hit_i[b];
      mword_q[b] <= nrsp_node_i[b*64 +: 64];
      ms_q[b] <= rs_q[b];
      mid_q[b] <= rmid_q[b];
      if (go_o[b]) begin
        tmax_q[slot_o[b*SLOT_BITS +: SLOT_BITS]] <= g_tmax[b*KW +: KW];
        best_q[slot_o[b*SLOT_BITS +: SLOT_BITS]] <= g_best[b*BW +: BW];
        rs_q[b] <= slot_o[b*SLOT_BITS +: SLOT_BITS];
        rbyte_q[b] <= g_byte[b*32 +: 32];
        rmid_q[b] <= g_mid[b*MW +: MW];
      end
    end
    // The outcomes of the passes of the cycle before (none of this cycle's pipes' or the rgu's
    // rays): the record's other fields and the queue push.
    for (b = 0; b < PIPES; b = b + 1) begin
      if (mv_q[b]) begin
        st_q[ms_q[b]]    <= p_st[b*3 +: 3];
        node_q[ms_q[b]]  <= p_node[b*32 +: 32];
        tnear_q[ms_q[b]] <= p_tnear[b*W +: W];
        tfar_q[ms_q[b]]  <= p_tfar[b*W +: W];
        sp_q[ms_q[b]]    <= p_sp[b*7 +: 7];
        first_q[ms_q[b]] <= p_first[b*32 +: 32];
        count_q[ms_q[b]] <= p_count[b*32 +: 32];
        pos_q[ms_q[b]]   <= p_pos[b*32 +: 32];
        if (p_wr_leaf[b]) begin
          leaf_q[ms_q[b]] <= {BW{1'b0}};
          left_q[ms_q[b]] <= p_count[b*32 +: 32];
        end
        if (p_qpush[b]) begin
          fq_slot[pipe_at[b*SLOT_BITS +: SLOT_BITS]] <= ms_q[b];
          fq_ready[pipe_at[b*SLOT_BITS +: SLOT_BITS]] <= p_qready[b*32 +: 32];
          fq_sp[pipe_at[b*SLOT_BITS +: SLOT_BITS]] <= p_sp[b*7 +: 7];
        end
      end
    end
    // The list stage's effects (the steps of the cycle before: none of this cycle's outcomes' or
    // the rgu's rays): the new position, waiting for the ist, or back to the queue.
    for (b = 0; b < PIPES; b = b + 1) begin
      if (ev_q[b]) begin
        pos_q[es_q[b]] <= epos_q[b] + {26'd0, en_q[b]};
        if (ewait_q[b]) st_q[es_q[b]] <= S_WAIT;
        if (eqpush_q[b]) begin
          fq_slot[list_at[b*SLOT_BITS +: SLOT_BITS]] <= es_q[b];
          fq_ready[list_at[b*SLOT_BITS +: SLOT_BITS]] <= eqready_q[b];
          fq_sp[list_at[b*SLOT_BITS +: SLOT_BITS]] <= esp_q[b];
        end
      end
    end
    // This cycle's outcomes' list steps, for the next cycle's stage; this stage's effects.
    for (b = 0; b < PIPES; b = b + 1) begin
      if (p_lreq[b]) begin
        ls_q[b]    <= ms_q[b];
        lidx_q[b]  <= o_idx_v[b*32 +: 32];
        lleft_q[b] <= o_left_v[b*32 +: 32];
        lwant_q[b] <= o_want_v[b*6 +: 6];
        lpos_q[b]  <= p_pos[b*32 +: 32];
        lbase_q[b] <= p_lbase[b*32 +: 32];
        ltmax_q[b] <= p_tmax[b*KW +: KW];
        lsp_q[b]   <= p_sp[b*7 +: 7];
      end
      if (lv_q[b]) begin
        es_q[b]      <= ls_q[b];
        eqpush_q[b]  <= l_qpush[b];
        ewait_q[b]   <= l_wait[b];
        eqready_q[b] <= l_qready[b*32 +: 32];
        esp_q[b]     <= lsp_q[b];
        en_q[b]      <= l_n[b*6 +: 6];
        epos_q[b]    <= lpos_q[b];
        eready_q[b]  <= lbase_q[b] + 32'd1 + {16'd0, list_hl_i};
        etmax_q[b]   <= ltmax_q[b];
        ewords_q[b]  <= lrsp_data_i[b*32*WORDS +: 32*WORDS];
      end
    end
    // The split stage's write-back (the rays of the pass four cycles ago: none of this cycle's
    // pipes', outcomes', the list stage's or the rgu's).
    for (b = 0; b < PIPES; b = b + 1) begin
      if (wv_q[b]) begin
        node_q[ws_q[b]]  <= s_node[b*32 +: 32];
        tnear_q[ws_q[b]] <= s_tnear[b*W +: W];
        tfar_q[ws_q[b]]  <= s_tfar[b*W +: W];
        if (s_push[b]) begin
          stk_q[{ws_q[b], wsp_q[b][DB-1:0]}] <= s_push_e[b*EW +: EW];
          sp_q[ws_q[b]] <= wsp_q[b] + 7'd1;
          fq_sp[wat_q[b]] <= wsp_q[b] + 7'd1;
        end
      end
    end
    for (b = 0; b < PIPES; b = b + 1) begin
      w_slot_q[b]  <= wn_slot[b];
      w_ready_q[b] <= wn_ready[b];
      w_sp_q[b]    <= wn_sp[b];
    end
    // ist results, in port order (a later port of the same ray holds the reduction so far).
    for (b = 0; b < IST; b = b + 1) begin
      if (res_valid_i[b]) begin
        leaf_q[res_slot_i[b*SLOT_BITS +: SLOT_BITS]] <= nl_all[b*BW +: BW];
        left_q[res_slot_i[b*SLOT_BITS +: SLOT_BITS]] <= nr_all[b*32 +: 32];
      end
      if (res_done[b]) st_q[res_slot_i[b*SLOT_BITS +: SLOT_BITS]] <= S_LEAF_DONE;
      if (rq_v[b]) begin  // the last cycle's last results, the first of this cycle's pushes
        fq_slot[res_at[b*SLOT_BITS +: SLOT_BITS]] <= rq_slot[b*SLOT_BITS +: SLOT_BITS];
        fq_ready[res_at[b*SLOT_BITS +: SLOT_BITS]] <= now_i + 32'd1;
        fq_sp[res_at[b*SLOT_BITS +: SLOT_BITS]] <= sp_q[rq_slot[b*SLOT_BITS +: SLOT_BITS]];
      end
    end
    rq_slot <= res_slot_i;
  end

  // The queue's head and count, the counters and the error. A cycle's counter events (one flag
  // per pipe and source: the pass's, the outcome's, the list stage's) are registered as they are
  // and counted in the next cycle (at most 3 x PIPES per counter in 8 bits), the counts registered
  // in turn and added into the 64-bit sums a cycle later: a counter's output is its sum plus the
  // registered counts plus the count of the registered flags, exact in every cycle (the output's
  // three-operand add goes to rtu.v's counter port, not into a register). (Counting the flags as
  // they are made put the adder trees behind the pass's stack read: 99.5 FO4 with 5 pipes;
  // counting the registered flags into the sums, 95.3 FO4.)
  // Flag f of pipe c at [f*PIPES + c]: the pass's busy 0, pops 1, fused 2; the outcome's busy 3,
  // node miss 4, inner 5, leaf 6, pops 7, fused 8; the list stage's busy 9, list miss 10, ist
  // queue full 11, list step 12.
  localparam integer NF = 13;
  wire [NF*PIPES-1:0] flags;
  reg  [NF*PIPES-1:0] flags_q;
  reg [6:0] smax;
  reg [7:0] d_busy, d_node_miss, d_list_miss, d_ist_full, d_inner, d_leaf, d_pops, d_list_steps,
            d_fused;
  integer c;
  assign flags = {l_step, l_full, l_miss, l_busy, p_fused, p_pops, p_leaf, p_inner, p_node_miss,
                  p_busy, go_o & g_fused, go_o & g_pops, go_o & g_busy};  // p_*: gated by mv_q
  always @* begin
    smax = stack_max_o;
    d_busy = 8'd0; d_node_miss = 8'd0; d_list_miss = 8'd0; d_ist_full = 8'd0; d_inner = 8'd0;
    d_leaf = 8'd0; d_pops = 8'd0; d_list_steps = 8'd0; d_fused = 8'd0;
    for (c = 0; c < PIPES; c = c + 1) begin
      d_busy = d_busy + {7'd0, flags_q[0*PIPES + c]} + {7'd0, flags_q[3*PIPES + c]} +
               {7'd0, flags_q[9*PIPES + c]};
      d_pops = d_pops + {7'd0, flags_q[1*PIPES + c]} + {7'd0, flags_q[7*PIPES + c]};
      d_fused = d_fused + {7'd0, flags_q[2*PIPES + c]} + {7'd0, flags_q[8*PIPES + c]};
      d_node_miss = d_node_miss + {7'd0, flags_q[4*PIPES + c]};
      d_inner = d_inner + {7'd0, flags_q[5*PIPES + c]};
      d_leaf = d_leaf + {7'd0, flags_q[6*PIPES + c]};
      d_list_miss = d_list_miss + {7'd0, flags_q[10*PIPES + c]};
      d_ist_full = d_ist_full + {7'd0, flags_q[11*PIPES + c]};
      d_list_steps = d_list_steps + {7'd0, flags_q[12*PIPES + c]};
      if (s_push[c] && (wsp_q[c] + 7'd1 > smax)) smax = wsp_q[c] + 7'd1;
    end
  end
  localparam integer NC = 9;
  wire [NC*8-1:0]  inc = {d_fused, d_list_steps, d_pops, d_leaf, d_inner, d_ist_full, d_list_miss,
                          d_node_miss, d_busy};
  reg  [NC*8-1:0]  inc_q;
  reg  [NC*64-1:0] sum_q;
  wire [NC*64-1:0] sum_d, cnt_all;
  genvar gc;
  generate
    for (gc = 0; gc < NC; gc = gc + 1) begin : g_cnt
      assign sum_d[gc*64 +: 64] = sum_q[gc*64 +: 64] + {56'd0, inc_q[gc*8 +: 8]};
      assign cnt_all[gc*64 +: 64] = sum_d[gc*64 +: 64] + {56'd0, inc[gc*8 +: 8]};
    end
  endgenerate
  assign {cnt_fused_o, cnt_list_steps_o, cnt_pops_o, cnt_leaf_o, cnt_inner_o, cnt_ist_full_o,
          cnt_list_miss_o, cnt_node_miss_o, cnt_busy_o} = cnt_all;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head_q <= {SLOT_BITS{1'b0}};
      cnt_q <= {(SLOT_BITS+1){1'b0}};
      rv_q <= {PIPES{1'b0}};
      racc_q <= {PIPES{1'b0}};
      lv_q <= {PIPES{1'b0}};
      lfused_q <= {PIPES{1'b0}};
      ev_q <= {PIPES{1'b0}};
      mv_q <= {PIPES{1'b0}};
      wv_q <= {PIPES{1'b0}};
      sv_q <= {PIPES{1'b0}};
      rq_v <= {IST{1'b0}};
      cv_q <= {(CL-1){1'b0}};
      s_push <= {PIPES{1'b0}};
      err_q <= 1'b0;
      flags_q <= {(NF*PIPES){1'b0}};
      inc_q <= {(NC*8){1'b0}};
      sum_q <= {(NC*64){1'b0}};
      stack_max_o <= 7'd0;
    end else begin
      head_q <= head_q + pops[SLOT_BITS-1:0];
      cnt_q <= cnt_q - pops + pushes;
      rv_q <= go_o;
      racc_q <= g_acc;
      lv_q <= p_lreq;
      lfused_q <= p_lfused & p_lreq;
      ev_q <= lv_q;
      mv_q <= rv_q;
      wv_q <= d_vld;
      sv_q <= p_split;
      rq_v <= res_done;
      cv_q <= {cv_q[CL-3:0], in_valid_i};
      s_push <= d_push;
      err_q <= err_o;
      flags_q <= flags;
      inc_q <= inc;
      sum_q <= sum_d;
      stack_max_o <= smax;
    end
  end

endmodule
