// vtu_unit - the fill path of one RTU: the data beats into the MSHR line buffers, and a filled
// line into its cache, node and triangle lines through vtu.v record by record on the way (the RTL
// view of systemc/vtu.h's VtuUnit with the MSHR buffers systemc/ascache.h keeps):
//   1. a data beat of cache p's MSHR t is written into line buffer (p, t) at its beat index; per
//      cycle at most one from the memory (beat_*: membus_if's rsp_*, BEAT_BYTES) and one from the
//      L2 (l2_*: membus_l2's l2_*, L2_BEAT bytes; idle without an L2), each one-hot by cache;
//   2. a line's last beat: up to two lines are done in a cycle (one per channel), taken in the
//      order the bus took their requests (an age matrix over the MSHRs, from the requests taken:
//      the order of systemc/membus.h's responses of one cycle). A list line, or
//      any line with the VTU off, goes to the bypass queue and is installed at once (fill_*_o of its
//      cache in that cycle, the beat merged in) unless its cache's fill is taken in this cycle by
//      the line before it (then it and the lines behind it wait a cycle, as the model's bypass
//      queue); a node or triangle line with the VTU on is queued for vtu.v;
//   3. the queue's head line is driven into vtu.v one record per cycle (a line arriving at an
//      empty queue from the cycle of its last beat on), only what lies inside the image (the
//      line's first record + i < node_count_i / tri_count_i; the MSHR's line index is taken from
//      the cache's request as the bus accepts it): a node line as groups of four 8-byte nodes
//      (vtu.v's four node lanes; with n nodes of the line inside the image, ceil(n/4) groups,
//      group g = nodes 4g .. 4g+3, lane j masked in iff 4g+j < n), a triangle line as its Wald
//      triangle records (hls/wald.h's layout), one per cycle;
//   4. a group or record leaving vtu.v (2 x STAGES cycles later) is written back into its line
//      buffer (a group's masked-in nodes only); when the line's last group or record has left,
//      the line is installed (fill_*_o in that cycle, that group or record merged in).
// One group or record per cycle at full rate (vtu.v never stalls here: out_ready is always high).
// Caches are in port order node 0, list 1, triangle 2 (systemc/vtu.h's Port).
//
// Timing as the transaction model's VtuUnit (systemc/vtu.h) with the membus timing of
// membus_if.v / membus_l2.v (a line's last beat in the cycle Membus calls mem_resp): groups and
// records from that cycle on, one per cycle over all lines in queue order; a line installed in the
// cycle its last group or record leaves (2 x STAGES cycles after it entered), a bypassed line in
// the cycle of its last beat or, behind another line of its cache, later. cnt_busy_o counts the
// cycles a group or record is driven (RtuStats::vtu_busy).
// lint: also STAGES=2 MSHRS=8 NODE_LB=64 LIST_LB=64 TRI_LB=64
// lint: also STAGES=1 MSHRS=2 NODE_LB=32 LIST_LB=16 TRI_LB=48 EXP_BITS=8 MAN_BITS=23 L2_BEAT=16
module vtu_unit #(
  parameter integer EXP_BITS   = 7,
  parameter integer MAN_BITS   = 16,
  parameter integer RNE        = 0,
  parameter integer RAYCORE    = 0,
  parameter integer STAGES     = 2,
  parameter integer MSHRS      = 4,   // per cache
  parameter integer NODE_LB    = 64,  // line bytes of each cache
  parameter integer LIST_LB    = 64,
  parameter integer TRI_LB     = 64,
  parameter integer BEAT_BYTES = 16,  // the memory's beats
  parameter integer L2_BEAT    = 32,  // the L2's beats
  parameter integer LEN_BITS   = 12,
  parameter integer LINE_W     = 26,
  // Derived (not to be overridden): the Wald record of hls/wald.h, the buffers' width.
  parameter integer W_     = 1 + EXP_BITS + MAN_BITS,
  parameter integer CB_    = (W_ <= 24) ? 3 : 4,
  parameter integer IDOFF_ = ((9 * CB_ + 1 + 3) / 4) * 4,
  parameter integer RB_    = ((IDOFF_ + 4 + 15) / 16) * 16,
  parameter integer MAXLB_ = (NODE_LB > LIST_LB) ? ((NODE_LB > TRI_LB) ? NODE_LB : TRI_LB)
                                                 : ((LIST_LB > TRI_LB) ? LIST_LB : TRI_LB),
  parameter integer MB_    = (MSHRS > 1) ? $clog2(MSHRS) : 1
) (
  input  wire                   clk_i,
  input  wire                   rst_ni,
  // Configuration, static per frame.
  input  wire                   vtu_on_i,
  input  wire [W_-1:0]          cam_x_i,
  input  wire [W_-1:0]          cam_y_i,
  input  wire [W_-1:0]          cam_z_i,
  input  wire [31:0]            node_count_i,
  input  wire [31:0]            tri_count_i,
  // The caches' line requests as the bus takes them (port p in bits [p*w +: w]; one per cycle).
  input  wire [2:0]             req_take_i,
  input  wire [3*LINE_W-1:0]    req_line_i,
  input  wire [3*MB_-1:0]       req_tag_i,
  // The memory's data beats of this RTU's caches (membus_if's rsp_*).
  input  wire [2:0]             beat_valid_i,
  input  wire [MB_-1:0]         beat_tag_i,
  input  wire [LEN_BITS-1:0]    beat_idx_i,
  input  wire                   beat_last_i,
  input  wire [8*BEAT_BYTES-1:0] beat_data_i,
  // The L2's data beats of this RTU's caches (membus_l2's l2_*; idle without an L2).
  input  wire [2:0]             l2_valid_i,
  input  wire [MB_-1:0]         l2_tag_i,
  input  wire [LEN_BITS-1:0]    l2_idx_i,
  input  wire                   l2_last_i,
  input  wire [8*L2_BEAT-1:0]   l2_data_i,
  // Fills (ascache.v's fill_*_i), port p's line in fill_data_o[p*8*MAXLB_ +: 8*<its line bytes>].
  output wire [2:0]             fill_valid_o,
  output wire [3*MB_-1:0]       fill_tag_o,
  output wire [3*8*MAXLB_-1:0]  fill_data_o,
  // Cycles a group or record is driven into vtu.v (RtuStats::vtu_busy); groups or records inside.
  output wire [63:0]            cnt_busy_o,
  // Cycles in which two lines were done (RtuStats::vtu_paired); bypassed lines waiting for their
  // cache's fill, summed over the cycles they wait (RtuStats::vtu_fill_waits).
  output wire [31:0]            cnt_pair_o,
  output wire [31:0]            cnt_wait_o,
  output wire                   busy_o
);

  localparam integer W    = W_;
  localparam integer LW   = 8 * MAXLB_;
  localparam integer BB   = 8 * BEAT_BYTES;
  localparam integer LBB  = 8 * L2_BEAT;
  localparam integer NREC = NODE_LB / 8;     // nodes per line
  localparam integer NGRP = (NREC + 3) / 4;  // groups of four nodes per line
  localparam integer TREC = TRI_LB / RB_;    // triangle records per line
  localparam integer MREC = (NGRP > TREC) ? NGRP : TREC;
  localparam integer RIB  = (MREC > 1) ? $clog2(MREC) : 1;
  localparam integer TAGW = 1 + MB_ + RIB + 4 + 1;  // vtu.v's tag: {tri, MSHR, record, mask, last}
  localparam integer QN   = 2 * MSHRS;         // node and triangle lines waiting
  localparam integer QB   = $clog2(QN);
  localparam integer IB   = $clog2(3 * MSHRS);  // a line buffer's index: p * MSHRS + t
  localparam integer NB   = 3 * MSHRS;        // line buffers
  localparam integer BQB  = $clog2(3 * MSHRS);  // the bypass queue: up to 3 x MSHRS lines
  localparam integer BQN  = 1 << BQB;
  localparam integer LBASE = MSHRS;
  localparam integer TBASE = 2 * MSHRS;

  // A line buffer's index from its cache port and MSHR.
  localparam [IB-1:0] LB_IB = LBASE[IB-1:0];
  localparam [IB-1:0] TB_IB = TBASE[IB-1:0];
  function automatic [IB-1:0] bidx(input [1:0] port, input [MB_-1:0] tag);
    bidx = ((port == 2'd0) ? {IB{1'b0}} : (port == 2'd1) ? LB_IB : TB_IB) + {{(IB-MB_){1'b0}}, tag};
  endfunction

  // ---- 1. the line buffers, the MSHRs' line indices and their age order ---------------------------
  reg [LW-1:0]     buf_q  [0:3*MSHRS-1];   // entry p * MSHRS + t
  reg [LINE_W-1:0] line_q [0:3*MSHRS-1];
  // The age matrix: bit NB * i + j set iff buffer j's request was taken before buffer i's (its
  // latest each). A request taken into buffer i sets row i and clears column i: older than it is
  // every other buffer's line, and it is older than none.
  reg [NB*NB-1:0]  older_q;
  wire          tk_v   = |req_take_i;  // one request per cycle at most (the bus takes one)
  wire [1:0]    tk_p   = req_take_i[0] ? 2'd0 : req_take_i[1] ? 2'd1 : 2'd2;
  wire [IB-1:0] tk_idx = bidx(tk_p, req_tag_i[tk_p * MB_ +: MB_]);
  wire [NB-1:0] tk_bit = {{(NB-1){1'b0}}, 1'b1} << tk_idx;
  // The memory's beat (channel A) and the L2's (channel B): each into its line's buffer.
  wire [1:0]    a_port = beat_valid_i[0] ? 2'd0 : beat_valid_i[1] ? 2'd1 : 2'd2;
  wire          a_beat = |beat_valid_i;
  wire [IB-1:0] a_idx  = bidx(a_port, beat_tag_i);
  wire          a_done = a_beat && beat_last_i;
  wire [1:0]    l_port = l2_valid_i[0] ? 2'd0 : l2_valid_i[1] ? 2'd1 : 2'd2;
  wire          l_beat = |l2_valid_i;
  wire [IB-1:0] l_idx  = bidx(l_port, l2_tag_i);
  wire          l_done = l_beat && l2_last_i;
  // Each channel's line with its beat merged in (the two beats are of different lines).
  reg  [LW-1:0] a_line, l_line;
  always @* begin
    a_line = buf_q[a_idx];
    a_line[beat_idx_i * BB +: BB] = beat_data_i;
    l_line = buf_q[l_idx];
    l_line[l2_idx_i * LBB +: LBB] = l2_data_i;
  end

  // ---- 2. the lines done in this cycle, in the order the bus took them ---------------------------
  // The memory's and the L2's last beats can meet in one cycle: the line whose request the bus
  // took first goes first (systemc/membus.h: responses of one cycle in acceptance order), d0 then
  // d1 (the age matrix: this RTU's requests in the order the bus took them).
  wire [NB-1:0] a_row   = older_q[a_idx * NB +: NB];
  wire          l_first = l_done && (!a_done || a_row[l_idx]);
  wire          d0_v    = a_done || l_done;
  wire          d1_v    = a_done && l_done;
  wire [1:0]    d0_port = l_first ? l_port : a_port;
  wire [1:0]    d1_port = l_first ? a_port : l_port;
  wire [MB_-1:0] d0_tag = l_first ? l2_tag_i : beat_tag_i;
  wire [MB_-1:0] d1_tag = l_first ? beat_tag_i : l2_tag_i;
  wire [IB-1:0] d0_idx  = l_first ? l_idx : a_idx;
  wire [IB-1:0] d1_idx  = l_first ? a_idx : l_idx;
  wire [LW-1:0] d0_line = l_first ? l_line : a_line;
  wire [LW-1:0] d1_line = l_first ? a_line : l_line;
  // A list line, or any line with the VTU off, is installed as it is (bypass); the rest queue for
  // vtu.v.
  wire          d0_byp  = !vtu_on_i || (d0_port == 2'd1);
  wire          d1_byp  = !vtu_on_i || (d1_port == 2'd1);
  // The lines for vtu.v in order: f first, s second.
  wire          p0      = d0_v && !d0_byp;
  wire          p1      = d1_v && !d1_byp;
  wire          f_v     = p0 || p1;
  wire          s_v     = p0 && p1;
  wire          f_tri   = p0 ? (d0_port == 2'd2) : (d1_port == 2'd2);
  wire [MB_-1:0] f_tag  = p0 ? d0_tag : d1_tag;
  wire [IB-1:0] f_idx   = p0 ? d0_idx : d1_idx;
  wire [LW-1:0] f_line  = p0 ? d0_line : d1_line;
  wire          s_tri   = d1_port == 2'd2;
  wire [MB_-1:0] s_tag  = d1_tag;
  wire [IB-1:0] s_idx   = d1_idx;
  wire [LW-1:0] s_line  = d1_line;

  reg  [1+MB_-1:0] q_line [0:QN-1];       // {tri, MSHR}
  reg  [QB-1:0]    head_q;
  reg  [QB:0]      cnt_q;
  reg  [RIB-1:0]   rec_q;                 // the head line's next group or record

  // ---- 3. the head line's groups or records ---------------------------------------------------
  // With the queue empty, the first line done in this cycle is the head at once (its first group
  // or record is driven in that cycle, from the buffer with the beat merged in), as the model
  // starts a line in the cycle of its mem_resp. Otherwise the head is the queue's: its buffer,
  // port, MSHR and line index read a cycle ahead into registers (hd_*_q, below), so that the
  // group or record driven into vtu.v comes from registers, not through the queue's and the
  // buffers' read (issue 26's timing; the same cycles and bits).
  reg  [LW-1:0]     hd_buf_q;
  reg               hd_tri_q;
  reg  [MB_-1:0]    hd_tag_q;
  reg  [LINE_W-1:0] hd_line_q;
  wire              qempty = (cnt_q == {(QB+1){1'b0}});
  wire              direct = f_v && qempty;
  wire              h_tri  = direct ? f_tri : hd_tri_q;
  wire [MB_-1:0]    h_tag  = direct ? f_tag : hd_tag_q;
  wire [LW-1:0]     h_buf  = direct ? f_line : hd_buf_q;
  wire [LINE_W-1:0] h_line = direct ? line_q[f_idx] : hd_line_q;
  // Nodes or records of the line inside the image: n = min(per line, count - first); a node line
  // is ceil(n/4) groups (at least one cycle either way, as the model's).
  localparam [31:0] TREC32 = TREC, NREC32 = NREC;
  wire [31:0] per   = h_tri ? TREC32 : NREC32;
  wire [31:0] hl32  = {{(32-LINE_W){1'b0}}, h_line};
  wire [31:0] first = h_tri ? hl32 * TREC32 : hl32 * NREC32;  // by constants
  wire [31:0] avail = (h_tri ? tri_count_i : node_count_i) - first;
  wire [31:0] nrec  = (avail < per) ? avail : per;
  wire [31:0] nunit = h_tri ? nrec : (nrec + 32'd3) >> 2;
  wire [31:0] rec32 = {{(32-RIB){1'b0}}, rec_q};
  wire        last  = (rec32 + 32'd1 >= nunit);
  wire        drive = !qempty || f_v;

  // Group rec_q's four nodes (a line of NREC nodes padded with zeros to whole groups) and its
  // mask: lane j holds node 4 * rec_q + j, masked in iff that is inside the image.
  reg  [256*NGRP-1:0] nline;
  reg  [3:0]          nmask;
  integer j;
  always @* begin
    nline = {(256*NGRP){1'b0}};
    nline[8*NODE_LB-1:0] = h_buf[8*NODE_LB-1:0];
    for (j = 0; j < 4; j = j + 1) nmask[j] = !h_tri && ({rec32[29:0], 2'b00} + j < nrec);
  end
  wire [255:0]     group = nline[rec_q * 256 +: 256];
  wire [8*RB_-1:0] trec = h_buf[rec_q * 8 * RB_ +: 8 * RB_];
  wire [7:0]      kf    = trec[8*9*CB_ +: 8];
  wire            unused_trec = ^trec;  // padding

  wire          in_ready, o_valid, o_kind;
  wire [255:0]  o_group;
  wire [1:0]    o_k;
  wire [7:0]    o_flags;
  wire [W-1:0]  o_c0, o_c1, o_c2, o_c3, o_c4, o_c5, o_c6, o_c7, o_c8;
  wire [31:0]   o_id;
  wire [TAGW-1:0] o_tag;
  wire          take = drive && in_ready;
  vtu #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES),
        .TAG_BITS(TAGW)) u_vtu (
    .clk_i(clk_i), .rst_ni(rst_ni), .vtu_on_i(1'b1),
    .cam_x_i(cam_x_i), .cam_y_i(cam_y_i), .cam_z_i(cam_z_i),
    .in_valid_i(drive), .in_ready_o(in_ready), .in_kind_i(h_tri),
    .in_node0_i(group[0 +: 64]), .in_node1_i(group[64 +: 64]), .in_node2_i(group[128 +: 64]),
    .in_node3_i(group[192 +: 64]), .in_nmask_i(nmask),
    .in_k_i(kf[1:0]), .in_flags_i({kf[7:2], 2'b00}),
    .in_c0_i(trec[0*8*CB_ +: W]), .in_c1_i(trec[1*8*CB_ +: W]), .in_c2_i(trec[2*8*CB_ +: W]),
    .in_c3_i(trec[3*8*CB_ +: W]), .in_c4_i(trec[4*8*CB_ +: W]), .in_c5_i(trec[5*8*CB_ +: W]),
    .in_c6_i(trec[6*8*CB_ +: W]), .in_c7_i(trec[7*8*CB_ +: W]), .in_c8_i(trec[8*8*CB_ +: W]),
    .in_id_i(trec[8*IDOFF_ +: 32]), .in_tag_i({h_tri, h_tag, rec_q, nmask, last}),
    .out_valid_o(o_valid), .out_ready_i(1'b1), .out_kind_o(o_kind),
    .out_node0_o(o_group[0 +: 64]), .out_node1_o(o_group[64 +: 64]),
    .out_node2_o(o_group[128 +: 64]), .out_node3_o(o_group[192 +: 64]),
    .out_k_o(o_k), .out_flags_o(o_flags),
    .out_c0_o(o_c0), .out_c1_o(o_c1), .out_c2_o(o_c2), .out_c3_o(o_c3), .out_c4_o(o_c4),
    .out_c5_o(o_c5), .out_c6_o(o_c6), .out_c7_o(o_c7), .out_c8_o(o_c8), .out_id_o(o_id),
    .out_tag_o(o_tag));

  // ---- 4. a group or record leaving: encoded back (hls::encode_tri: padding zero) ---------------
  wire            t_tri  = o_tag[TAGW-1];
  wire [MB_-1:0]  t_tag  = o_tag[TAGW-2 -: MB_];
  wire [RIB-1:0]  t_rec  = o_tag[5 +: RIB];
  wire [3:0]      t_mask = o_tag[1 +: 4];
  wire            t_last = o_tag[0];
  wire [IB-1:0]   t_idx  = bidx(t_tri ? 2'd2 : 2'd0, t_tag);
  wire            unused_out = ^{o_kind, o_flags[1:0]};  // = t_tri; the flags' low bits are k's
  reg  [8*RB_-1:0] enc;
  always @* begin
    enc = {(8*RB_){1'b0}};
    enc[0*8*CB_ +: W] = o_c0; enc[1*8*CB_ +: W] = o_c1; enc[2*8*CB_ +: W] = o_c2;
    enc[3*8*CB_ +: W] = o_c3; enc[4*8*CB_ +: W] = o_c4; enc[5*8*CB_ +: W] = o_c5;
    enc[6*8*CB_ +: W] = o_c6; enc[7*8*CB_ +: W] = o_c7; enc[8*8*CB_ +: W] = o_c8;
    enc[8*9*CB_ +: 8] = {o_flags[7:2], o_k};
    enc[8*IDOFF_ +: 32] = o_id;
  end

  // ---- fills: one per port per cycle ------------------------------------------------------------
  // A line with its last group or record merged in, leaving vtu.v: the line of the group or record
  // leaving, with it merged in (a group's masked-in nodes). At STAGES 0 a line's only group or
  // record leaves in the cycle of its last beat (taken directly), so that beat is merged in too; at
  // STAGES >= 1 no beat meets a line with records in vtu.v.
  wire [LW-1:0] t_buf;
  generate
    if (STAGES == 0) begin : g_t_direct
      assign t_buf = (a_beat && (a_idx == t_idx)) ? a_line :
                     (l_beat && (l_idx == t_idx)) ? l_line : buf_q[t_idx];
    end else begin : g_t_buf
      assign t_buf = buf_q[t_idx];
    end
  endgenerate
  reg  [LW-1:0] r_line;
  integer m;
  always @* begin
    r_line = t_buf;
    if (t_tri) r_line[t_rec * 8 * RB_ +: 8 * RB_] = enc;
    for (m = 0; m < 4; m = m + 1)
      if (!t_tri && t_mask[m]) r_line[(t_rec * 4 + m) * 64 +: 64] = o_group[m*64 +: 64];
  end
  wire       r_fill = o_valid && t_last;
  wire [1:0] r_port = t_tri ? 2'd2 : 2'd0;

  // The bypassed lines (systemc/vtu.h's bypass queue): installed in queue order, one per cache per
  // cycle; a line that finds its cache's fill taken in this cycle (two lines of one cache done
  // together, from the memory and the L2) waits for the next, and the lines behind it with it. The
  // queue's first three (more cannot go in one cycle: three caches) and this cycle's d0, d1 are the
  // candidates, in order; each goes if all before it went and its cache's fill is free. Node and
  // triangle lines bypass only with the VTU off, when nothing leaves vtu.v, and list lines never
  // enter it: a bypassed line and r_fill never meet on one cache. The queue holds lines with their
  // MSHRs, so at most 3 x MSHRS.
  reg  [2+MB_-1:0] bq_q [0:BQN-1];         // {port, MSHR}
  reg  [BQB-1:0]   bh_q;
  reg  [BQB:0]     bn_q;
  wire             nb0   = d0_v && d0_byp;
  wire             nb1   = d1_v && d1_byp;
  wire [1:0]       n0_port = nb0 ? d0_port : d1_port;
  wire [MB_-1:0]   n0_tag  = nb0 ? d0_tag : d1_tag;
  wire [LW-1:0]    n0_line = nb0 ? d0_line : d1_line;
  wire             bq_more = bn_q > {{(BQB-1){1'b0}}, 2'd3};
  reg  [4:0]       cv;        // candidates: the queue's 0, 1, 2, then n0, n1
  reg  [1:0]       cp [0:4];
  reg  [MB_-1:0]   ct [0:4];
  reg  [4:0]       go;        // candidate k goes
  reg  [2:0]       fb_v;      // cache p installs a bypassed line: candidate fb_k[p]
  reg  [2:0]       fb_k [0:2];
  reg  [MB_-1:0]   fb_tag [0:2];
  reg              open_, hit_;
  integer k, q;
  always @* begin
    for (k = 0; k < 3; k = k + 1) begin
      cv[k] = bn_q > k[BQB:0];
      {cp[k], ct[k]} = bq_q[bh_q + k[BQB-1:0]];
    end
    cv[3] = nb0 || nb1;
    cp[3] = n0_port;
    ct[3] = n0_tag;
    cv[4] = nb0 && nb1;
    cp[4] = d1_port;
    ct[4] = d1_tag;
    open_ = 1'b1;
    fb_v = 3'b000;
    go = 5'b00000;
    for (q = 0; q < 3; q = q + 1) begin
      fb_k[q] = 3'd0;
      fb_tag[q] = {MB_{1'b0}};
    end
    for (k = 0; k < 5; k = k + 1) begin
      if (k == 3 && bq_more) open_ = 1'b0;  // a fourth queued line is ahead of d0, d1
      hit_ = 1'b0;
      for (q = 0; q < 3; q = q + 1) hit_ = hit_ || (fb_v[q] && cp[k] == q[1:0]);
      if (cv[k]) begin
        if (open_ && !hit_) begin
          go[k] = 1'b1;
          for (q = 0; q < 3; q = q + 1)
            if (cp[k] == q[1:0]) begin
              fb_v[q] = 1'b1;
              fb_k[q] = k[2:0];
              fb_tag[q] = ct[k];
            end
        end else begin
          open_ = 1'b0;
        end
      end
    end
  end
  wire [1:0]     bq_pops  = {1'b0, go[0]} + {1'b0, go[1]} + {1'b0, go[2]};
  wire           bq_push0 = cv[3] && !go[3];
  wire           bq_push1 = cv[4] && !go[4];
  wire [BQB-1:0] bq_tail  = bh_q + bn_q[BQB-1:0];
  wire [BQB:0]   bn_next  = bn_q - {{(BQB-1){1'b0}}, bq_pops} + {{BQB{1'b0}}, bq_push0} +
                            {{BQB{1'b0}}, bq_push1};
  genvar p;
  generate
    for (p = 0; p < 3; p = p + 1) begin : g_fill
      localparam integer LB = (p == 0) ? NODE_LB : (p == 1) ? LIST_LB : TRI_LB;
      localparam [1:0]   P2 = p;
      // a queued line has all its beats in its buffer; d0's and d1's have this cycle's merged in
      wire [LW-1:0] b_line = (fb_k[p] == 3'd3) ? n0_line : (fb_k[p] == 3'd4) ? d1_line
                                                         : buf_q[bidx(P2, fb_tag[p])];
      wire [LW-1:0] line   = fb_v[p] ? b_line : r_line;
      assign fill_valid_o[p] = fb_v[p] || (r_fill && (r_port == P2));
      assign fill_tag_o[p*MB_ +: MB_] = fb_v[p] ? fb_tag[p] : t_tag;
      assign fill_data_o[p*LW +: LW] = {{(LW-8*LB){1'b0}}, line[0 +: 8*LB]};
      if (LB < MAXLB_) begin : g_unused
        wire unused_line = ^line[LW-1:8*LB];
      end
    end
  endgenerate

  // Groups or records inside vtu.v.
  reg [7:0] inside_q;
  assign busy_o = (inside_q != 8'd0) || drive || (bn_q != {(BQB+1){1'b0}});

  wire [QB-1:0] tail = head_q + cnt_q[QB-1:0];

  // The head after this edge, read ahead into hd_*_q: in the order [the queue's lines, f, s], the
  // line after the head if the head leaves in this cycle, else the head; loaded when it changes:
  // f or s from their buffers with this cycle's beat merged in, the queue's next entry from its
  // buffer (the queue's lines have all their beats; a head's buffer changes only in records
  // already driven: a record is written back as it leaves vtu.v, after it was driven).
  wire              pop     = take && last;
  wire [QB-1:0]     nx_head = head_q + 1'b1;
  wire [1+MB_-1:0]  nx_ent  = q_line[nx_head];
  wire [IB-1:0]     nx_idx  = bidx(nx_ent[MB_] ? 2'd2 : 2'd0, nx_ent[MB_-1:0]);
  wire              hd_f    = f_v && (qempty ? !pop : (pop && cnt_q == {{QB{1'b0}}, 1'b1}));
  wire              hd_s    = s_v && qempty && pop;
  wire              hd_next = pop && (cnt_q > {{QB{1'b0}}, 1'b1});
  always @(posedge clk_i) begin  // no reset: read only while the queue holds a line
    if (hd_f) begin
      hd_buf_q  <= f_line;
      hd_tri_q  <= f_tri;
      hd_tag_q  <= f_tag;
      hd_line_q <= line_q[f_idx];
    end else if (hd_s) begin
      hd_buf_q  <= s_line;
      hd_tri_q  <= s_tri;
      hd_tag_q  <= s_tag;
      hd_line_q <= line_q[s_idx];
    end else if (hd_next) begin
      hd_buf_q  <= buf_q[nx_idx];
      hd_tri_q  <= nx_ent[MB_];
      hd_tag_q  <= nx_ent[MB_-1:0];
      hd_line_q <= line_q[nx_idx];
    end
  end
  integer i, l, r;
  // The counters: the sums of the cycles before plus the last cycle's registered increments (the
  // same value in every cycle as adding at once; the sums' carry chains off the paths from the
  // age order and the bypass queue).
  reg [63:0]  busy_q;
  reg [31:0]  pair_q, wait_q;
  reg         take_q, pair_inc_q;
  reg [BQB:0] wait_inc_q;
  assign cnt_busy_o = busy_q + {63'd0, take_q};
  assign cnt_pair_o = pair_q + {31'd0, pair_inc_q};
  assign cnt_wait_o = wait_q + {{(31-BQB){1'b0}}, wait_inc_q};
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head_q     <= {QB{1'b0}};
      cnt_q      <= {(QB+1){1'b0}};
      rec_q      <= {RIB{1'b0}};
      inside_q   <= 8'd0;
      busy_q     <= 64'd0;
      take_q     <= 1'b0;
      bh_q       <= {BQB{1'b0}};
      bn_q       <= {(BQB+1){1'b0}};
      pair_q     <= 32'd0;
      wait_q     <= 32'd0;
      pair_inc_q <= 1'b0;
      wait_inc_q <= {(BQB+1){1'b0}};
    end else begin
      cnt_q <= cnt_q + {{QB{1'b0}}, f_v} + {{QB{1'b0}}, s_v} - {{QB{1'b0}}, pop};
      if (take) begin
        rec_q <= last ? {RIB{1'b0}} : rec_q + 1'b1;
        if (last) head_q <= nx_head;
      end
      inside_q   <= inside_q + {7'd0, take} - {7'd0, o_valid};
      busy_q     <= cnt_busy_o;
      take_q     <= take;
      bh_q <= bh_q + {{(BQB-2){1'b0}}, bq_pops};
      bn_q <= bn_next;
      pair_q     <= cnt_pair_o;
      pair_inc_q <= d1_v;
      wait_q     <= cnt_wait_o;
      wait_inc_q <= bn_next;
    end
  end

  // The queues' entries, the buffers (beats, records and groups' masked-in nodes written), the
  // line indices and the age order of the requests taken (no reset: data; a row is written when
  // its buffer's request is taken, before it is read).
  always @(posedge clk_i) begin
    if (tk_v)
      for (r = 0; r < NB; r = r + 1)
        older_q[r * NB +: NB] <= (r[IB-1:0] == tk_idx) ? ~tk_bit : (older_q[r * NB +: NB] & ~tk_bit);
    if (f_v) q_line[tail] <= {f_tri, f_tag};
    if (s_v) q_line[tail + 1'b1] <= {s_tri, s_tag};
    if (bq_push0) bq_q[bq_tail] <= {cp[3], ct[3]};
    if (bq_push1) bq_q[bq_tail + {{(BQB-1){1'b0}}, bq_push0}] <= {cp[4], ct[4]};
    if (a_beat) buf_q[a_idx][beat_idx_i * BB +: BB] <= beat_data_i;
    if (l_beat) buf_q[l_idx][l2_idx_i * LBB +: LBB] <= l2_data_i;
    if (o_valid) begin
      if (t_tri) buf_q[t_idx][t_rec * 8 * RB_ +: 8 * RB_] <= enc;
      else
        for (l = 0; l < 4; l = l + 1)
          if (t_mask[l]) buf_q[t_idx][(t_rec * 4 + l) * 64 +: 64] <= o_group[l*64 +: 64];
    end
    for (i = 0; i < 3; i = i + 1)
      if (req_take_i[i])
        line_q[bidx(i[1:0], req_tag_i[i*MB_ +: MB_])] <= req_line_i[i*LINE_W +: LINE_W];
  end

endmodule
