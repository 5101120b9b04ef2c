// membus_l2 - the memory bus with the L2 shared by the RTUs: N requesters' line requests,
// round-robin, each looked up in the L2; a hit is answered from the L2's data array, a miss goes
// to the memory (membus_if.v, one requester: the outstanding queue and the beats routed back) and
// is installed in the L2 as its beats arrive.
//
// The hardware twin of systemc/membus.* with an L2 (SimConfig::l2), minus the memory itself (the
// far side of mem_* / beat_*, as membus_if's), cycle for cycle:
//   - Requests (req_*[i], valid/ready, held until accepted): one is accepted per cycle. The
//     round-robin (rr_arb.v) grants the first requester with a request from the one after the last
//     accepted. The granted line is looked up in the L2 in the same cycle (tags, valid bits and
//     LRU ranks in registers: a combinational read):
//       * a hit (the line present, even while its data is still on its way from the memory: a
//         merge) is accepted into the L2's response queue, whatever the memory queue holds;
//       * a miss is accepted if fewer than DEPTH memory requests are outstanding (else nobody is
//         accepted: the queue is full, the pointer stays) and its set has a way to take the line
//         (else nobody is accepted: stall_o): the first invalid way, else the least recently used
//         of the ways that are neither being filled (pending) nor still to be read by an accepted
//         hit (readers). The line goes to the memory on mem_* in the same cycle, and is installed
//         in the way (tag, valid, pending) at the cycle's edge; it becomes the way most recently
//         used, as a hit's way does.
//   - The memory's beats (in acceptance order, membus_if's rules) are routed to their requester one
//     cycle later on rsp_* (as membus_if's), and each is written into the L2's data array at the
//     edge of the cycle it arrives in; the line's last beat clears its pending bit there, so the
//     line is ready in the cycle its requester sees the last beat (Membus's arrival).
//   - The L2's responses leave in acceptance order on l2_*, L2_BEAT bytes per cycle from the data
//     array (LINE_BYTES / L2_BEAT beats, registered: the array's read register): the queue's head
//     starts in the first cycle that is at least its acceptance + lat_i, in which its line is not
//     pending and the response before it has driven its last beat; it drives one beat per cycle.
//     Its requester sees beat j in cycle first + 1 + j, the last in first + beats = Membus's
//     arrival, max(accept + latency, ready, the previous response's arrival) + beats. The line's
//     reader count drops at the edge of the last beat's read.
// Lines are whole: every request is one L2 line (LINE_BYTES bytes at a multiple of LINE_BYTES;
// systemc/membus.cpp refuses other requests when this RTL runs). A line with readers or pending
// is never chosen as a victim, so the data a response reads and the way a fill writes are never
// another line's. Progress: pending lines fill and responses drain without any new request, so a
// stalled miss is accepted later.
// Storage: tags, valid, pending, ranks and reader counts per way (SETS x WAYS), the data array
// (SETS x WAYS x LINE_BYTES / L2_BEAT rows of L2_BEAT bytes: one write port of BEAT_BYTES at a
// row's offset, one read port of a row), the response queue (QDEPTH entries: requester, tag, way,
// earliest cycle; QDEPTH >= the requesters' MSHRs, so it never fills: systemc/membus.cpp checks).
// now_i is the cycle number (a 32-bit count, compared as a signed difference).
// lint: also N=6 SETS=8 WAYS=4 LINE_BYTES=32 L2_BEAT=8 BEAT_BYTES=8 DEPTH=4 QDEPTH=16
// lint: also N=3 SETS=4 WAYS=2 LINE_BYTES=32 L2_BEAT=32 BEAT_BYTES=16 DEPTH=4 QDEPTH=8
module membus_l2 #(
  parameter integer N          = 3,
  parameter integer ADDR_BITS  = 32,
  parameter integer LEN_BITS   = 12,
  parameter integer TAG_BITS   = 8,
  parameter integer DEPTH      = 32,
  parameter integer BEAT_BYTES = 16,
  parameter integer SETS       = 4,
  parameter integer WAYS       = 2,
  parameter integer LINE_BYTES = 64,
  parameter integer L2_BEAT    = 32,
  parameter integer QDEPTH     = 32,
  // Derived (not to be overridden).
  parameter integer PORT_BITS  = (N > 1) ? $clog2(N) : 1
) (
  input  wire                    clk_i,
  input  wire                    rst_ni,
  input  wire [31:0]             now_i,
  input  wire [15:0]             lat_i,       // the L2's hit latency (static per frame)
  // N request channels, requester i in bits [i*X +: X]
  input  wire [N-1:0]            req_valid_i,
  output wire [N-1:0]            req_ready_o,
  input  wire [N*ADDR_BITS-1:0]  req_addr_i,
  input  wire [N*LEN_BITS-1:0]   req_bytes_i,
  input  wire [N*TAG_BITS-1:0]   req_tag_i,
  // the request accepted in this cycle (combinational): its requester, and whether it hit
  output wire                    acc_valid_o,
  output wire [PORT_BITS-1:0]    acc_port_o,
  output wire                    acc_hit_o,
  output wire                    stall_o,     // a miss waits for a way of its set
  // the misses to the memory
  output wire                    mem_valid_o,
  input  wire                    mem_ready_i,
  output wire [ADDR_BITS-1:0]    mem_addr_o,
  output wire [LEN_BITS-1:0]     mem_bytes_o,
  // the memory's data beats, lines in acceptance order
  input  wire                    beat_valid_i,
  input  wire [8*BEAT_BYTES-1:0] beat_data_i,
  // the memory's beats routed back (one-hot by requester)
  output wire [N-1:0]            rsp_valid_o,
  output wire [PORT_BITS-1:0]    rsp_port_o,
  output wire [TAG_BITS-1:0]     rsp_tag_o,
  output wire [8*BEAT_BYTES-1:0] rsp_data_o,
  output wire [LEN_BITS-1:0]     rsp_beat_o,
  output wire                    rsp_last_o,
  // the L2's beats (one-hot by requester)
  output reg  [N-1:0]            l2_valid_o,
  output reg  [PORT_BITS-1:0]    l2_port_o,
  output reg  [TAG_BITS-1:0]     l2_tag_o,
  output reg  [8*L2_BEAT-1:0]    l2_data_o,
  output reg  [LEN_BITS-1:0]     l2_beat_o,
  output reg                     l2_last_o,
  output wire [$clog2(DEPTH + 1)-1:0] outstanding_o,  // memory requests accepted, not returned
  output wire                    l2_busy_o    // responses accepted and not yet driven
);

  localparam integer SB     = $clog2(SETS);                  // SETS, WAYS: powers of two >= 2
  localparam integer WB     = $clog2(WAYS);
  localparam integer LB     = SB + WB;                       // a way of the L2: {set, way}
  localparam integer LSH    = $clog2(LINE_BYTES);
  localparam integer TW     = ADDR_BITS - LSH - SB;          // the tag
  localparam integer RPL    = LINE_BYTES / L2_BEAT;          // data rows per line (>= 1)
  localparam integer RB     = (RPL > 1) ? $clog2(RPL) : 1;
  localparam integer DB     = (RPL > 1) ? LB + RB : LB;      // a data row's index
  localparam integer SUB    = L2_BEAT / BEAT_BYTES;          // memory beats per row (>= 1)
  localparam integer SUBB   = (SUB > 1) ? $clog2(SUB) : 1;
  localparam integer QB     = $clog2(QDEPTH);
  localparam integer CW     = $clog2(QDEPTH + 1);
  localparam integer MTAG   = LB + PORT_BITS + TAG_BITS;     // a miss's tag at membus_if
  localparam integer QE     = PORT_BITS + TAG_BITS + LB + 32;
  localparam integer CNT_W  = $clog2(DEPTH + 1);
  localparam integer LAST_Q_I   = QDEPTH - 1;
  localparam integer LAST_ROW_I = RPL - 1;
  localparam integer FULL_I     = DEPTH;
  localparam [QB-1:0]    LAST_Q   = LAST_Q_I[QB-1:0];
  localparam [RB-1:0]    LAST_ROW = LAST_ROW_I[RB-1:0];
  localparam [CNT_W-1:0] FULL     = FULL_I[CNT_W-1:0];

  // ---- arbitration and lookup -------------------------------------------------------------------
  wire                 found;
  wire [PORT_BITS-1:0] grant;
  wire [ADDR_BITS-1:0] g_addr = req_addr_i[grant*ADDR_BITS +: ADDR_BITS];
  wire [LEN_BITS-1:0]  g_bytes = req_bytes_i[grant*LEN_BITS +: LEN_BITS];
  wire [TAG_BITS-1:0]  g_tag  = req_tag_i[grant*TAG_BITS +: TAG_BITS];
  wire [SB-1:0]        g_set  = g_addr[LSH +: SB];
  wire [TW-1:0]        g_ltag = g_addr[ADDR_BITS-1 -: TW];

  reg [TW-1:0] tag_q  [0:SETS*WAYS-1];
  reg [WB-1:0] rank_q [0:SETS*WAYS-1];  // 0: most recently used (among the set's valid ways)
  reg [CW-1:0] cnt_q  [0:SETS*WAYS-1];  // readers: hits accepted, last beat not driven
  reg [SETS*WAYS-1:0] valid_q, pend_q;

  reg          hit, inv_any, ev_any;
  reg [WB-1:0] hit_w, inv_w, ev_w;
  reg [WB-1:0] ev_rank;
  reg [LB-1:0] li;
  integer w;
  always @* begin
    hit = 1'b0; inv_any = 1'b0; ev_any = 1'b0;
    hit_w = {WB{1'b0}}; inv_w = {WB{1'b0}}; ev_w = {WB{1'b0}}; ev_rank = {WB{1'b0}};
    for (w = 0; w < WAYS; w = w + 1) begin
      li = {g_set, w[WB-1:0]};
      if (valid_q[li] && tag_q[li] == g_ltag && !hit) begin
        hit = 1'b1;
        hit_w = w[WB-1:0];
      end
      if (!valid_q[li] && !inv_any) begin
        inv_any = 1'b1;
        inv_w = w[WB-1:0];
      end
      // the least recently used way that no fill writes and no response reads
      if (valid_q[li] && !pend_q[li] && cnt_q[li] == {CW{1'b0}} &&
          (!ev_any || rank_q[li] > ev_rank)) begin
        ev_any = 1'b1;
        ev_w = w[WB-1:0];
        ev_rank = rank_q[li];
      end
    end
  end
  wire          victim_ok = inv_any || ev_any;
  wire [WB-1:0] victim    = inv_any ? inv_w : ev_w;

  wire                 d_room;      // membus_if: fewer than DEPTH outstanding
  wire                 d_ready;     // membus_if accepted the miss
  wire                 miss_go   = found && !hit && victim_ok;
  wire                 acc_hit   = found && hit;
  wire                 accept    = acc_hit || d_ready;
  wire [WB-1:0]        touch_w   = hit ? hit_w : victim;
  wire [LB-1:0]        touch_li  = {g_set, touch_w};

  rr_arb #(.N(N)) u_rr (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(req_valid_i), .adv_i(accept), .found_o(found),
    .grant_o(grant)
  );

  genvar g;
  generate
    for (g = 0; g < N; g = g + 1) begin : g_ready
      assign req_ready_o[g] = accept && (grant == g);
    end
  endgenerate
  assign acc_valid_o = accept;
  assign acc_port_o  = grant;
  assign acc_hit_o   = acc_hit;
  assign stall_o     = found && !hit && d_room && !victim_ok;

  // ---- the memory side: membus_if with one requester (the misses) --------------------------------
  wire [MTAG-1:0]     t_tag;
  wire                t_take, t_last;
  wire [LEN_BITS-1:0] t_beat;
  wire [MTAG-1:0]     d_rsp_tag;
  wire                d_rsp_valid;
  wire [CNT_W-1:0]    d_out;
  assign d_room = (d_out != FULL);
  wire                d_port, d_rport;  // its single requester's index
  wire [MTAG-1:0]     d_mtag;
  wire unused_d = ^{d_rsp_tag[MTAG-1 -: LB], d_port, d_rport, d_mtag, t_tag[MTAG-LB-1:0]};
  membus_if #(.N(1), .ADDR_BITS(ADDR_BITS), .LEN_BITS(LEN_BITS), .TAG_BITS(MTAG), .DEPTH(DEPTH),
              .BEAT_BYTES(BEAT_BYTES)) u_mem (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .req_valid_i(miss_go), .req_ready_o(d_ready), .req_addr_i(g_addr), .req_bytes_i(g_bytes),
    .req_tag_i({touch_li, grant, g_tag}),
    .mem_valid_o(mem_valid_o), .mem_ready_i(mem_ready_i), .mem_addr_o(mem_addr_o),
    .mem_bytes_o(mem_bytes_o), .mem_port_o(d_port), .mem_tag_o(d_mtag),
    .beat_valid_i(beat_valid_i), .beat_data_i(beat_data_i),
    .rsp_valid_o(d_rsp_valid), .rsp_port_o(d_rport), .rsp_tag_o(d_rsp_tag), .rsp_data_o(rsp_data_o),
    .rsp_beat_o(rsp_beat_o), .rsp_last_o(rsp_last_o), .outstanding_o(d_out),
    .take_o(t_take), .take_tag_o(t_tag), .take_beat_o(t_beat), .take_last_o(t_last));
  assign outstanding_o = d_out;
  assign rsp_port_o = d_rsp_tag[TAG_BITS +: PORT_BITS];
  assign rsp_tag_o  = d_rsp_tag[TAG_BITS-1:0];
  generate
    for (g = 0; g < N; g = g + 1) begin : g_rsp
      assign rsp_valid_o[g] = d_rsp_valid && (rsp_port_o == g);
    end
  endgenerate

  // ---- the L2's response queue and its beats ----------------------------------------------------
  reg [QE-1:0] q_q [0:QDEPTH-1];   // {requester, tag, way, earliest cycle}
  reg [QB-1:0] qw_q, qr_q;
  reg [CW-1:0] qn_q;
  reg          busy_q;             // the head is driving its beats
  reg [RB-1:0] row_q;              // its next beat
  wire [QE-1:0]        head   = q_q[qr_q];
  wire [PORT_BITS-1:0] h_port = head[QE-1 -: PORT_BITS];
  wire [TAG_BITS-1:0]  h_tag  = head[LB + 32 +: TAG_BITS];
  wire [LB-1:0]        h_li   = head[32 +: LB];
  wire [31:0]          h_at   = head[31:0];
  wire [31:0]          h_wait = now_i - h_at;
  wire unused_wait = ^h_wait[30:0];
  wire start = !busy_q && (qn_q != {CW{1'b0}}) && !h_wait[31] && !pend_q[h_li];
  wire drive = busy_q || start;
  wire [RB-1:0] row = busy_q ? row_q : {RB{1'b0}};
  wire          h_last = (RPL == 1) || (row == LAST_ROW);
  wire          pop  = drive && h_last;
  wire [DB-1:0] rd_row;
  generate
    if (RPL > 1) begin : g_rows
      assign rd_row = {h_li, row};
    end else begin : g_row1
      assign rd_row = h_li;
      wire unused_row = ^row;
    end
  endgenerate
  assign l2_busy_o = (qn_q != {CW{1'b0}});

  // The data array: a memory beat written at its row's offset, a row read per cycle.
  reg [8*L2_BEAT-1:0] data_q [0:SETS*WAYS*RPL-1];
  wire [LB-1:0]     t_li  = t_tag[MTAG-1 -: LB];
  wire [DB-1:0]     t_row;
  wire [SUBB-1:0]   t_sub;
  generate
    if (RPL > 1 && SUB > 1) begin : g_wr_rs
      assign t_row = {t_li, t_beat[SUBB +: RB]};
      assign t_sub = t_beat[SUBB-1:0];
    end else if (RPL > 1) begin : g_wr_r
      assign t_row = {t_li, t_beat[RB-1:0]};
      assign t_sub = 1'b0;
    end else if (SUB > 1) begin : g_wr_s
      assign t_row = t_li;
      assign t_sub = t_beat[SUBB-1:0];
    end else begin : g_wr_1
      assign t_row = t_li;
      assign t_sub = 1'b0;
    end
  endgenerate
  wire unused_beat = ^t_beat;
  always @(posedge clk_i) begin
    if (t_take) data_q[t_row][t_sub * (8 * BEAT_BYTES) +: 8 * BEAT_BYTES] <= beat_data_i;
  end

  integer v;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      qw_q <= {QB{1'b0}};
      qr_q <= {QB{1'b0}};
      qn_q <= {CW{1'b0}};
      busy_q <= 1'b0;
      row_q <= {RB{1'b0}};
      l2_valid_o <= {N{1'b0}};
    end else begin
      if (acc_hit) qw_q <= (qw_q == LAST_Q) ? {QB{1'b0}} : qw_q + 1'b1;
      if (pop) qr_q <= (qr_q == LAST_Q) ? {QB{1'b0}} : qr_q + 1'b1;
      if (acc_hit && !pop) qn_q <= qn_q + 1'b1;
      if (pop && !acc_hit) qn_q <= qn_q - 1'b1;
      busy_q <= drive && !h_last;
      row_q  <= (drive && !h_last) ? row + 1'b1 : {RB{1'b0}};
      for (v = 0; v < N; v = v + 1) l2_valid_o[v] <= drive && ({{(32-PORT_BITS){1'b0}}, h_port} == v);
    end
  end
  always @(posedge clk_i) begin
    if (acc_hit) q_q[qw_q] <= {grant, g_tag, g_set, hit_w, now_i + {16'd0, lat_i}};
    if (drive) begin
      l2_port_o <= h_port;
      l2_tag_o  <= h_tag;
      l2_data_o <= data_q[rd_row];
      l2_beat_o <= {{(LEN_BITS-RB){1'b0}}, row};
      l2_last_o <= h_last;
    end
  end

  // ---- the ways' state --------------------------------------------------------------------------
  // valid and pending: an install sets both; the line's last memory beat clears pending.
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= {(SETS*WAYS){1'b0}};
      pend_q  <= {(SETS*WAYS){1'b0}};
    end else begin
      if (t_take && t_last) pend_q[t_li] <= 1'b0;
      if (d_ready) begin
        valid_q[touch_li] <= 1'b1;
        pend_q[touch_li]  <= 1'b1;
      end
    end
  end
  integer u;
  // Tags, ranks and reader counts: no reset (an invalid way's are never read; an install writes
  // its tag and count, and the ranks of a set's valid ways are 0 .. valid - 1 by recency).
  always @(posedge clk_i) begin
    if (d_ready) begin
      tag_q[touch_li] <= g_ltag;
      cnt_q[touch_li] <= {CW{1'b0}};
    end
    if (acc_hit && !(pop && h_li == touch_li)) cnt_q[touch_li] <= cnt_q[touch_li] + 1'b1;
    if (pop && !(acc_hit && h_li == touch_li)) cnt_q[h_li] <= cnt_q[h_li] - 1'b1;
    if (accept)
      for (u = 0; u < WAYS; u = u + 1)
        if (u[WB-1:0] == touch_w)
          rank_q[{g_set, u[WB-1:0]}] <= {WB{1'b0}};
        else if (valid_q[{g_set, u[WB-1:0]}] &&
                 (!valid_q[touch_li] || rank_q[{g_set, u[WB-1:0]}] < rank_q[touch_li]))
          rank_q[{g_set, u[WB-1:0]}] <= rank_q[{g_set, u[WB-1:0]}] + 1'b1;
  end

endmodule
