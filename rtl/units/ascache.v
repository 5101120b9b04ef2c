// ascache - one acceleration-structure cache: set-associative, LRU, non-blocking misses with MSHRs.
// Pin-level twin of raycore::sc::Ascache (systemc/ascache.h; the SystemC twin at these pins is
// systemc/pins/ascache.h, which wraps that class, and tb/rtl/test_lockstep_ascache.cpp runs both
// side by side). Lines are addressed by their index within the cache's region (acc_line_i, as
// Ascache::access(line)); the bus adapter turns a line index into a byte address.
//
// One access per cycle, always accepted; its response comes HIT_LATENCY cycles later:
//   hit            rsp_hit_o, rsp_data_o = the line (byte i at bits [8i+7:8i]); LRU updated.
//   miss, merged   rsp_merge_o: an MSHR already fetches the line (Ascache counts mshr_merges).
//   miss, full     rsp_full_o: no MSHR free; nothing is fetched (Ascache counts mshr_full).
//   miss           (none of the three) an MSHR was allocated (the lowest free index) and its
//                  request queued: req_valid_o from the next cycle on, in allocation order.
// Every miss kind returns "no data" (Ascache::access's nullptr): the requester retries later.
// A fill (fill_valid_i, fill_tag_i = the MSHR index, fill_data_i = the whole line) installs the
// MSHR's line in the set's victim way (ascache_victim: first invalid way, else LRU) and frees the
// MSHR; a fill of a free MSHR is ignored (Ascache::fill throws). Fill has no ready: it is always
// taken, as Ascache::fill. A fill comes after its request was taken (req_valid_o && req_ready_i).
//
// Order within one clock edge (the cycle model ticks the vtu's fills before the requesters'
// accesses): request pop, fill, then access. So an access sees the line installed by the fill of
// the same cycle (hit, data through the write-first data array), not a line that fill evicted,
// and may allocate the MSHR that fill freed; the LRU update of the access follows the fill's.
//
// Storage: tags, valid bits and LRU ranks in flip-flops (read combinationally, one set per side);
// the data array is a 1R1W SRAM (ascache_ram, synchronous write-first read, SETS*WAYS lines of
// 8*LINE_BYTES bits) read at the access edge. Latency: HIT_LATENCY >= 1 (1 = the SRAM's output
// register; each further cycle adds a register of the response and its line).
//
// Parameters: SETS and WAYS powers of two (SETS >= 2), MSHRS >= 2, LINE_W = line-index width
// (address width - log2 LINE_BYTES; LINE_W > log2 SETS), TAG_BITS = the requester's sideband
// acc_tag_i -> rsp_tag_o (e.g. a ray slot), CNT_BITS = width of the counters (wrap around).
module ascache #(
  parameter integer SETS        = 8,
  parameter integer WAYS        = 2,
  parameter integer LINE_BYTES  = 64,
  parameter integer MSHRS       = 4,
  parameter integer HIT_LATENCY = 1,
  parameter integer LINE_W      = 26,
  parameter integer TAG_BITS    = 8,
  parameter integer CNT_BITS    = 32
) (
  input  wire                          clk_i,
  input  wire                          rst_ni,
  // Access (Ascache::access): one per cycle, always accepted.
  input  wire                          acc_valid_i,
  input  wire [LINE_W-1:0]             acc_line_i,
  input  wire [TAG_BITS-1:0]           acc_tag_i,
  // Its result, HIT_LATENCY cycles later (no back-pressure).
  output wire                          rsp_valid_o,
  output wire                          rsp_hit_o,
  output wire                          rsp_merge_o,
  output wire                          rsp_full_o,
  output wire [TAG_BITS-1:0]           rsp_tag_o,
  output wire [8*LINE_BYTES-1:0]       rsp_data_o,
  // Line requests to memory (Ascache::req(): MemReq.addr = base + line * LINE_BYTES, tag).
  output wire                          req_valid_o,
  input  wire                          req_ready_i,
  output wire [LINE_W-1:0]             req_line_o,
  output wire [$clog2(MSHRS)-1:0]      req_tag_o,
  // Fills (Ascache::mshr_data(tag) written, then Ascache::fill(tag)).
  input  wire                          fill_valid_i,
  input  wire [$clog2(MSHRS)-1:0]      fill_tag_i,
  input  wire [8*LINE_BYTES-1:0]       fill_data_i,
  // Status (Ascache::mshrs_busy(), Ascache::stats()): after the last edge.
  output wire [$clog2(MSHRS+1)-1:0]    mshr_busy_o,
  output wire [CNT_BITS-1:0]           cnt_hits_o,
  output wire [CNT_BITS-1:0]           cnt_misses_o,
  output wire [CNT_BITS-1:0]           cnt_merges_o,
  output wire [CNT_BITS-1:0]           cnt_full_o,
  output wire [CNT_BITS-1:0]           cnt_fills_o
);

  localparam integer SW = $clog2(SETS);                   // set index bits
  localparam integer TW = LINE_W - SW;                    // tag bits
  localparam integer RW = WAYS > 1 ? $clog2(WAYS) : 1;    // way index / LRU rank bits
  localparam integer MW = $clog2(MSHRS);                  // MSHR index bits
  localparam integer CW = $clog2(MSHRS + 1);              // MSHR count bits
  localparam integer DW = 8 * LINE_BYTES;                 // line bits
  localparam integer NL = SETS * WAYS;                    // lines
  localparam integer AW = SW + (WAYS > 1 ? RW : 0);       // data array address bits
  localparam integer LAST = MSHRS - 1;
  localparam [MW-1:0] LAST_MSHR = LAST[MW-1:0];
  localparam [CNT_BITS-1:0] CNT_ONE = 1;

  // ---------------------------------------------------------------------------------------------
  // State. The per-set arrays are flip-flops (yosys: mem2reg), read combinationally at the
  // access's and the fill's set; only the data array is an SRAM.
  (* mem2reg *) reg [WAYS-1:0]    valid_q [0:SETS-1];   // way w of set s at valid_q[s][w]
  (* mem2reg *) reg [WAYS*TW-1:0] tag_q   [0:SETS-1];   // way w at [w*TW +: TW]
  (* mem2reg *) reg [WAYS*RW-1:0] rank_q  [0:SETS-1];   // LRU ranks, a permutation per set
  reg [MSHRS-1:0]        mv_q, mv_d;          // MSHR valid
  reg [MSHRS*LINE_W-1:0] ml_q, ml_d;          // MSHR line
  reg [MSHRS*MW-1:0]     fifo_q, fifo_d;      // request queue: MSHR indices, allocation order
  reg [MW-1:0]           head_q, head_d, tail_q, tail_d;
  reg [CW-1:0]           count_q, count_d;
  reg [CNT_BITS-1:0]     hits_q, hits_d, misses_q, misses_d, merges_q, merges_d;
  reg [CNT_BITS-1:0]     full_q, full_d, fills_q, fills_d;

  // ---------------------------------------------------------------------------------------------
  // Fill side: the MSHR's line, its set and the victim way.
  reg              fill_go;
  reg [LINE_W-1:0] f_line;
  wire [RW-1:0]    f_way;
  wire [WAYS*RW-1:0] f_rank_new;
  wire [SW-1:0]    f_set = f_line[SW-1:0];
  wire [TW-1:0]    f_tag = f_line[LINE_W-1:SW];

  integer i, s, w;
  always @* begin : p_fill
    fill_go = 1'b0;
    f_line  = {LINE_W{1'b0}};
    for (i = 0; i < MSHRS; i = i + 1)
      if (fill_tag_i == i[MW-1:0]) begin
        fill_go = fill_valid_i && mv_q[i];
        f_line  = ml_q[i*LINE_W +: LINE_W];
      end
  end

  wire [WAYS-1:0]    f_valid = valid_q[f_set];
  wire [WAYS*RW-1:0] f_rank  = rank_q[f_set];

  ascache_victim #(.WAYS(WAYS), .RW(RW)) u_victim (
    .valid_i(f_valid), .rank_i(f_rank), .way_o(f_way));
  ascache_touch #(.WAYS(WAYS), .RW(RW)) u_touch_fill (
    .rank_i(f_rank), .way_i(f_way), .rank_o(f_rank_new));

  // ---------------------------------------------------------------------------------------------
  // Access side: lookup in the set as the fill leaves it.
  wire [SW-1:0]      a_set = acc_line_i[SW-1:0];
  wire [TW-1:0]      a_tag = acc_line_i[LINE_W-1:SW];
  wire               same_set = fill_go && f_set == a_set;
  wire [WAYS-1:0]    a_valid = valid_q[a_set];
  wire [WAYS*TW-1:0] a_tags  = tag_q[a_set];
  wire [WAYS*RW-1:0] a_rank  = rank_q[a_set];
  reg [WAYS-1:0]     a_match;
  reg [WAYS*RW-1:0]  a_rank_pre;
  wire [WAYS*RW-1:0] a_rank_new;
  reg [RW-1:0]       a_way;
  reg                a_hit;
  reg [MSHRS-1:0]    mv_post;      // MSHRs valid after the fill
  reg                a_inflight;   // an MSHR (after the fill) fetches the line
  reg [MW-1:0]       a_free;       // lowest free MSHR after the fill
  reg                acc_hit, acc_merge, acc_full, acc_alloc;

  always @* begin
    a_rank_pre = same_set ? f_rank_new : a_rank;
    a_hit = 1'b0;
    a_way = {RW{1'b0}};
    for (w = 0; w < WAYS; w = w + 1) begin
      if (same_set && f_way == w[RW-1:0]) a_match[w] = f_tag == a_tag;
      else                                a_match[w] = a_valid[w] && a_tags[w*TW +: TW] == a_tag;
      if (a_match[w]) begin
        a_hit = 1'b1;
        a_way = w[RW-1:0];
      end
    end
    // MSHRs: the fill frees its own first.
    mv_post = mv_q;
    for (i = 0; i < MSHRS; i = i + 1)
      if (fill_go && fill_tag_i == i[MW-1:0]) mv_post[i] = 1'b0;
    a_inflight = 1'b0;
    a_free     = {MW{1'b0}};
    for (i = MSHRS - 1; i >= 0; i = i - 1) begin
      if (mv_post[i] && ml_q[i*LINE_W +: LINE_W] == acc_line_i) a_inflight = 1'b1;
      if (!mv_post[i]) a_free = i[MW-1:0];
    end
    acc_hit   = acc_valid_i && a_hit;
    acc_merge = acc_valid_i && !a_hit && a_inflight;
    acc_full  = acc_valid_i && !a_hit && !a_inflight && (&mv_post);
    acc_alloc = acc_valid_i && !a_hit && !a_inflight && !(&mv_post);
  end

  ascache_touch #(.WAYS(WAYS), .RW(RW)) u_touch_acc (
    .rank_i(a_rank_pre), .way_i(a_way), .rank_o(a_rank_new));

  // ---------------------------------------------------------------------------------------------
  // Next state.
  wire req_pop = req_valid_o && req_ready_i;

  // The fill's way: valid, its tag.
  reg [WAYS-1:0]    f_valid_new;
  reg [WAYS*TW-1:0] f_tags_new;
  always @* begin
    f_valid_new = f_valid;
    f_tags_new  = tag_q[f_set];
    for (w = 0; w < WAYS; w = w + 1)
      if (f_way == w[RW-1:0]) begin
        f_valid_new[w] = 1'b1;
        f_tags_new[w*TW +: TW] = f_tag;
      end
  end

  always @* begin
    mv_d = mv_post;
    ml_d = ml_q;
    fifo_d = fifo_q;
    for (i = 0; i < MSHRS; i = i + 1) begin
      if (acc_alloc && a_free == i[MW-1:0]) begin
        mv_d[i] = 1'b1;
        ml_d[i*LINE_W +: LINE_W] = acc_line_i;
      end
      if (acc_alloc && tail_q == i[MW-1:0]) fifo_d[i*MW +: MW] = a_free;
    end
    head_d  = req_pop ? (head_q == LAST_MSHR ? {MW{1'b0}} : head_q + 1'b1) : head_q;
    tail_d  = acc_alloc ? (tail_q == LAST_MSHR ? {MW{1'b0}} : tail_q + 1'b1) : tail_q;
    count_d = count_q;
    if (acc_alloc && !req_pop) count_d = count_q + 1'b1;
    if (!acc_alloc && req_pop) count_d = count_q - 1'b1;

    hits_d   = acc_hit ? hits_q + CNT_ONE : hits_q;
    misses_d = (acc_valid_i && !a_hit) ? misses_q + CNT_ONE : misses_q;
    merges_d = acc_merge ? merges_q + CNT_ONE : merges_q;
    full_d   = acc_full ? full_q + CNT_ONE : full_q;
    fills_d  = fill_go ? fills_q + CNT_ONE : fills_q;
  end

  // Reset: valid bits, LRU ranks (way w of every set has rank w), MSHR valid, queue, counters.
  // Tags, MSHR lines and queue entries are meaningful only under a valid bit and are not reset.
  // The set arrays take the fill's update, then the access's LRU update (a_rank_new already
  // includes the fill's when both are in the same set, so the later assignment is the whole one).
  wire [WAYS*RW-1:0] rank_reset;
  genvar gw;
  generate
    for (gw = 0; gw < WAYS; gw = gw + 1) begin : g_rank_reset
      localparam integer RANK = gw;
      assign rank_reset[gw*RW +: RW] = RANK[RW-1:0];
    end
  endgenerate

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (s = 0; s < SETS; s = s + 1) begin
        valid_q[s] <= {WAYS{1'b0}};
        rank_q[s]  <= rank_reset;
      end
      mv_q     <= {MSHRS{1'b0}};
      head_q   <= {MW{1'b0}};
      tail_q   <= {MW{1'b0}};
      count_q  <= {CW{1'b0}};
      hits_q   <= {CNT_BITS{1'b0}};
      misses_q <= {CNT_BITS{1'b0}};
      merges_q <= {CNT_BITS{1'b0}};
      full_q   <= {CNT_BITS{1'b0}};
      fills_q  <= {CNT_BITS{1'b0}};
    end else begin
      if (fill_go) begin
        valid_q[f_set] <= f_valid_new;
        rank_q[f_set]  <= f_rank_new;
      end
      if (acc_hit) rank_q[a_set] <= a_rank_new;
      mv_q     <= mv_d;
      head_q   <= head_d;
      tail_q   <= tail_d;
      count_q  <= count_d;
      hits_q   <= hits_d;
      misses_q <= misses_d;
      merges_q <= merges_d;
      full_q   <= full_d;
      fills_q  <= fills_d;
    end
  end

  always @(posedge clk_i) begin
    if (fill_go) tag_q[f_set] <= f_tags_new;
    ml_q   <= ml_d;
    fifo_q <= fifo_d;
  end

  // ---------------------------------------------------------------------------------------------
  // Data array: written by the fill, read by a hit at the same edge (write-first).
  wire [AW-1:0] ram_waddr, ram_raddr;
  generate
    if (WAYS > 1) begin : g_addr_ways
      assign ram_waddr = {f_set, f_way};
      assign ram_raddr = {a_set, a_way};
    end else begin : g_addr_direct
      assign ram_waddr = f_set;
      assign ram_raddr = a_set;
      // Direct mapped: the way indices are always 0.
      wire unused_ways = ^{f_way, a_way};
    end
  endgenerate

  wire [DW-1:0] ram_rdata;
  ascache_ram #(.DEPTH(NL), .WIDTH(DW), .ADDR_W(AW)) u_ram (
    .clk_i   (clk_i),
    .we_i    (fill_go),
    .waddr_i (ram_waddr),
    .wdata_i (fill_data_i),
    .re_i    (acc_hit),
    .raddr_i (ram_raddr),
    .rdata_o (ram_rdata)
  );

  // ---------------------------------------------------------------------------------------------
  // Response: HIT_LATENCY registers of (valid, hit, merge, full, tag); the line comes from the
  // SRAM's output register, then through HIT_LATENCY-1 further registers (loaded on hits only).
  localparam integer RSW = 3 + TAG_BITS;
  reg [HIT_LATENCY-1:0]     rv_q;
  reg [HIT_LATENCY*RSW-1:0] rs_q;
  generate
    if (HIT_LATENCY > 1) begin : g_rsp_pipe
      reg [(HIT_LATENCY-1)*DW-1:0] rd_q;
      integer k;
      always @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) rv_q <= {HIT_LATENCY{1'b0}};
        else         rv_q <= {rv_q[HIT_LATENCY-2:0], acc_valid_i};
      end
      always @(posedge clk_i) begin
        if (acc_valid_i) rs_q[RSW-1:0] <= {acc_hit, acc_merge, acc_full, acc_tag_i};
        for (k = 1; k < HIT_LATENCY; k = k + 1)
          if (rv_q[k-1]) rs_q[k*RSW +: RSW] <= rs_q[(k-1)*RSW +: RSW];
        if (rv_q[0] && rs_q[RSW-1]) rd_q[DW-1:0] <= ram_rdata;
        for (k = 2; k < HIT_LATENCY; k = k + 1)
          if (rv_q[k-1] && rs_q[k*RSW-1]) rd_q[(k-1)*DW +: DW] <= rd_q[(k-2)*DW +: DW];
      end
      assign rsp_data_o = rd_q[(HIT_LATENCY-2)*DW +: DW];
    end else begin : g_rsp_one
      always @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) rv_q <= 1'b0;
        else         rv_q <= acc_valid_i;
      end
      always @(posedge clk_i) begin
        if (acc_valid_i) rs_q <= {acc_hit, acc_merge, acc_full, acc_tag_i};
      end
      assign rsp_data_o = ram_rdata;
    end
  endgenerate

  assign rsp_valid_o = rv_q[HIT_LATENCY-1];
  assign {rsp_hit_o, rsp_merge_o, rsp_full_o, rsp_tag_o} = rs_q[(HIT_LATENCY-1)*RSW +: RSW];

  // ---------------------------------------------------------------------------------------------
  // Outputs.
  reg [MW-1:0]     q_tag;
  reg [LINE_W-1:0] q_line;
  reg [CW-1:0]     busy;
  always @* begin
    q_tag = {MW{1'b0}};
    for (i = 0; i < MSHRS; i = i + 1)
      if (head_q == i[MW-1:0]) q_tag = fifo_q[i*MW +: MW];
    q_line = {LINE_W{1'b0}};
    for (i = 0; i < MSHRS; i = i + 1)
      if (q_tag == i[MW-1:0]) q_line = ml_q[i*LINE_W +: LINE_W];
    busy = {CW{1'b0}};
    for (i = 0; i < MSHRS; i = i + 1)
      if (mv_q[i]) busy = busy + 1'b1;
  end

  assign req_valid_o  = count_q != {CW{1'b0}};
  assign req_tag_o    = q_tag;
  assign req_line_o   = q_line;
  assign mshr_busy_o  = busy;
  assign cnt_hits_o   = hits_q;
  assign cnt_misses_o = misses_q;
  assign cnt_merges_o = merges_q;
  assign cnt_full_o   = full_q;
  assign cnt_fills_o  = fills_q;

endmodule
