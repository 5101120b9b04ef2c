// vtu_unit - the fill path of one RTU: the memory's data beats into the MSHR line buffers, and a
// filled line into its cache, node and triangle lines through vtu.v record by record on the way
// (the RTL view of systemc/vtu.h's VtuUnit with the MSHR buffers systemc/ascache.h keeps):
//   1. a data beat of cache p's MSHR t (one-hot beat_valid_i, from membus_if's rsp_*) is written
//      into line buffer (p, t) at its beat index;
//   2. on a line's last beat: a list line, or any line with the VTU off, is installed as it is
//      (fill_*_o of its cache in that cycle, the beat merged in); a node or triangle line with the
//      VTU on is queued for vtu.v;
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
// membus_if.v (a line's last beat in the cycle Membus calls mem_resp): groups and records from
// that cycle on, one per cycle over all lines in queue order; a line installed in the cycle its
// last group or record leaves (2 x STAGES cycles after it entered), a bypassed line in the cycle of
// its last beat. cnt_busy_o counts the cycles a group or record is driven (RtuStats::vtu_busy).
// lint: also STAGES=2 MSHRS=8 NODE_LB=64 LIST_LB=64 TRI_LB=64
// lint: also STAGES=1 MSHRS=2 NODE_LB=32 LIST_LB=16 TRI_LB=48 EXP_BITS=8 MAN_BITS=23
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
  parameter integer BEAT_BYTES = 16,
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
  // The caches' line requests as the bus takes them (port p in bits [p*w +: w]).
  input  wire [2:0]             req_take_i,
  input  wire [3*LINE_W-1:0]    req_line_i,
  input  wire [3*MB_-1:0]       req_tag_i,
  // The memory's data beats of this RTU's caches.
  input  wire [2:0]             beat_valid_i,
  input  wire [MB_-1:0]         beat_tag_i,
  input  wire [LEN_BITS-1:0]    beat_idx_i,
  input  wire                   beat_last_i,
  input  wire [8*BEAT_BYTES-1:0] beat_data_i,
  // Fills (ascache.v's fill_*_i), port p's line in fill_data_o[p*8*MAXLB_ +: 8*<its line bytes>].
  output wire [2:0]             fill_valid_o,
  output wire [3*MB_-1:0]       fill_tag_o,
  output wire [3*8*MAXLB_-1:0]  fill_data_o,
  // Cycles a group or record is driven into vtu.v (RtuStats::vtu_busy); groups or records inside.
  output reg  [63:0]            cnt_busy_o,
  output wire                   busy_o
);

  localparam integer W    = W_;
  localparam integer LW   = 8 * MAXLB_;
  localparam integer BB   = 8 * BEAT_BYTES;
  localparam integer NREC = NODE_LB / 8;     // nodes per line
  localparam integer NGRP = (NREC + 3) / 4;  // groups of four nodes per line
  localparam integer TREC = TRI_LB / RB_;    // triangle records per line
  localparam integer MREC = (NGRP > TREC) ? NGRP : TREC;
  localparam integer RIB  = (MREC > 1) ? $clog2(MREC) : 1;
  localparam integer TAGW = 1 + MB_ + RIB + 4 + 1;  // vtu.v's tag: {tri, MSHR, record, mask, last}
  localparam integer QN   = 2 * MSHRS;         // node and triangle lines waiting
  localparam integer QB   = $clog2(QN);
  localparam integer IB   = $clog2(3 * MSHRS);  // a line buffer's index: p * MSHRS + t
  localparam integer LBASE = MSHRS;
  localparam integer TBASE = 2 * MSHRS;
  wire [IB-1:0] LIST_BASE = LBASE[IB-1:0];
  wire [IB-1:0] TRI_BASE  = TBASE[IB-1:0];

  // ---- 1. the line buffers and the MSHRs' line indices -------------------------------------------
  reg [LW-1:0]     buf_q  [0:3*MSHRS-1];   // entry p * MSHRS + t
  reg [LINE_W-1:0] line_q [0:3*MSHRS-1];
  wire [1:0] bport = beat_valid_i[0] ? 2'd0 : beat_valid_i[1] ? 2'd1 : 2'd2;
  wire       beat  = |beat_valid_i;

  // ---- 2. the lines done, and the queue of lines for vtu.v ----------------------------------------
  wire       bypass = !vtu_on_i || (bport == 2'd1);
  reg  [1+MB_-1:0] q_line [0:QN-1];       // {tri, MSHR}
  reg  [QB-1:0]    head_q;
  reg  [QB:0]      cnt_q;
  reg  [RIB-1:0]   rec_q;                 // the head line's next group or record

  // The line of this cycle's beat with the beat merged in.
  wire [IB-1:0] b_idx = ((bport == 2'd0) ? {IB{1'b0}} : (bport == 2'd1) ? LIST_BASE : TRI_BASE) +
                       {{(IB-MB_){1'b0}}, beat_tag_i};
  reg  [LW-1:0] b_line;
  always @* begin
    b_line = buf_q[b_idx];
    b_line[beat_idx_i * BB +: BB] = beat_data_i;
  end

  // ---- 3. the head line's groups or records ---------------------------------------------------
  // With the queue empty, the line whose last beat arrives is the head at once (its first group
  // or record is driven in that cycle, from the buffer with the beat merged in), as the model
  // starts a line in the cycle of its mem_resp. Otherwise the head is the queue's: its buffer,
  // port, MSHR and line index read a cycle ahead into registers (hd_*_q, below), so that the
  // group or record driven into vtu.v comes from registers, not through the queue's and the
  // buffers' read (issue 26's timing; the same cycles and bits).
  reg  [LW-1:0]     hd_buf_q;
  reg               hd_tri_q;
  reg  [MB_-1:0]    hd_tag_q;
  reg  [LINE_W-1:0] hd_line_q;
  wire              push   = beat && beat_last_i && !bypass;
  wire              direct = push && (cnt_q == {(QB+1){1'b0}});
  wire              h_tri  = direct ? (bport == 2'd2) : hd_tri_q;
  wire [MB_-1:0]    h_tag  = direct ? beat_tag_i : hd_tag_q;
  wire [LW-1:0]     h_buf  = direct ? b_line : hd_buf_q;
  wire [LINE_W-1:0] h_line = direct ? line_q[b_idx] : hd_line_q;  // direct: b_idx is the head's
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
  wire        drive = (cnt_q != {(QB+1){1'b0}}) || push;
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
  wire [IB-1:0]   t_idx  = (t_tri ? TRI_BASE : {IB{1'b0}}) + {{(IB-MB_){1'b0}}, t_tag};
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

  // ---- fills: one per port per cycle, in the cycle the line is complete --------------------------
  // A bypassed line with its last beat merged in, or a line with its last group or record merged
  // in (the two never meet on one port: node and triangle lines bypass only with the VTU off, when
  // nothing is in vtu.v, and list lines never enter it). The line of the group or record leaving,
  // with it merged in (a group's masked-in nodes). At STAGES 0 a line's only group or record
  // leaves in the cycle of its last beat (taken directly), so that beat is merged in too; at
  // STAGES >= 1 no beat meets a line with records in vtu.v.
  wire [LW-1:0] t_buf;
  generate
    if (STAGES == 0) begin : g_t_direct
      assign t_buf = (beat && (b_idx == t_idx)) ? b_line : buf_q[t_idx];
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
  wire       b_fill = beat && beat_last_i && bypass;
  wire       r_fill = o_valid && t_last;
  wire [1:0] r_port = t_tri ? 2'd2 : 2'd0;
  genvar p;
  generate
    for (p = 0; p < 3; p = p + 1) begin : g_fill
      localparam integer LB = (p == 0) ? NODE_LB : (p == 1) ? LIST_LB : TRI_LB;
      localparam [1:0]   P2 = p;
      wire          from_b = b_fill && (bport == P2);
      wire [LW-1:0] line   = from_b ? b_line : r_line;
      assign fill_valid_o[p] = from_b || (r_fill && (r_port == P2));
      assign fill_tag_o[p*MB_ +: MB_] = from_b ? beat_tag_i : t_tag;
      assign fill_data_o[p*LW +: LW] = {{(LW-8*LB){1'b0}}, line[0 +: 8*LB]};
      if (LB < MAXLB_) begin : g_unused
        wire unused_line = ^line[LW-1:8*LB];
      end
    end
  endgenerate

  // Groups or records inside vtu.v.
  reg [7:0] inside_q;
  assign busy_o = (inside_q != 8'd0) || drive;

  wire [QB-1:0] tail = head_q + cnt_q[QB-1:0];

  // The head after this edge, read ahead into hd_*_q: the line of this cycle's last beat when it
  // becomes the head (the queue empty, or its one line leaving, and the beat's line not done in
  // this cycle), else the queue's next entry when the head line leaves and another waits; else
  // the head stays (its buffer changes only in records already driven: a record is written back
  // as it leaves vtu.v, after it was driven; the queue's lines have all their beats).
  wire              pop     = take && last;
  wire [QB-1:0]     nx_head = head_q + 1'b1;
  wire [1+MB_-1:0]  nx_ent  = q_line[nx_head];
  wire [IB-1:0]     nx_idx  = (nx_ent[MB_] ? TRI_BASE : {IB{1'b0}}) + {{(IB-MB_){1'b0}}, nx_ent[MB_-1:0]};
  wire              hd_beat = push && ((cnt_q == {(QB+1){1'b0}}) ? !pop
                                                                  : (pop && cnt_q == {{QB{1'b0}}, 1'b1}));
  wire              hd_next = pop && (cnt_q > {{QB{1'b0}}, 1'b1});
  always @(posedge clk_i) begin  // no reset: read only while the queue holds a line
    if (hd_beat) begin
      hd_buf_q  <= b_line;
      hd_tri_q  <= bport == 2'd2;
      hd_tag_q  <= beat_tag_i;
      hd_line_q <= line_q[b_idx];
    end else if (hd_next) begin
      hd_buf_q  <= buf_q[nx_idx];
      hd_tri_q  <= nx_ent[MB_];
      hd_tag_q  <= nx_ent[MB_-1:0];
      hd_line_q <= line_q[nx_idx];
    end
  end
  integer i, l;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head_q     <= {QB{1'b0}};
      cnt_q      <= {(QB+1){1'b0}};
      rec_q      <= {RIB{1'b0}};
      inside_q   <= 8'd0;
      cnt_busy_o <= 64'd0;
    end else begin
      if (push) q_line[tail] <= {bport == 2'd2, beat_tag_i};
      cnt_q <= cnt_q + {{QB{1'b0}}, push} - {{QB{1'b0}}, take && last};
      if (take) begin
        rec_q <= last ? {RIB{1'b0}} : rec_q + 1'b1;
        if (last) head_q <= nx_head;
      end
      inside_q   <= inside_q + {7'd0, take} - {7'd0, o_valid};
      cnt_busy_o <= cnt_busy_o + {63'd0, take};
    end
  end

  // The buffers: beats, records and groups' masked-in nodes written, line indices taken (no
  // reset: data).
  always @(posedge clk_i) begin
    if (beat) buf_q[b_idx][beat_idx_i * BB +: BB] <= beat_data_i;
    if (o_valid) begin
      if (t_tri) buf_q[t_idx][t_rec * 8 * RB_ +: 8 * RB_] <= enc;
      else
        for (l = 0; l < 4; l = l + 1)
          if (t_mask[l]) buf_q[t_idx][(t_rec * 4 + l) * 64 +: 64] <= o_group[l*64 +: 64];
    end
    for (i = 0; i < 3; i = i + 1)
      if (req_take_i[i])
        line_q[((i == 0) ? {IB{1'b0}} : (i == 1) ? LIST_BASE : TRI_BASE) +
               {{(IB-MB_){1'b0}}, req_tag_i[i*MB_ +: MB_]}] <= req_line_i[i*LINE_W +: LINE_W];
  end

endmodule
