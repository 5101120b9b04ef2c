// ascache - one acceleration-structure cache: set-associative, LRU, non-blocking misses with MSHRs.
// Pin-level twin of raycore::sc::Ascache (systemc/ascache.h; the SystemC twin at these pins is
// systemc/pins/ascache.h, which wraps that class, and tb/rtl/test_lockstep_ascache.cpp runs both
// side by side). Lines are addressed by their index within the cache's region (acc_line_i, as
// Ascache::access(line)); the bus adapter turns a line index into a byte address.
//
// PORTS accesses per cycle, always accepted; port k's response comes HIT_LATENCY cycles later:
//   hit            rsp_hit_o, rsp_data_o = the line (byte i at bits [8i+7:8i]); LRU updated.
//   miss, merged   rsp_merge_o: an MSHR already fetches the line (Ascache counts mshr_merges).
//   miss, full     rsp_full_o: no MSHR free; nothing is fetched (Ascache counts mshr_full).
//   miss, set full rsp_set_full_o: an MSHR is free, but every way of the line's set is pinned or
//                  awaited by an MSHR (pinned + awaited = WAYS); nothing is fetched (set_full).
//   miss           (none of the four) an MSHR was allocated (the lowest free index) and its
//                  request queued: req_valid_o from the next cycle on, in allocation order.
// Every miss kind returns "no data" (Ascache::access's nullptr): the requester retries later.
// Forward progress: a filled line is pinned (pin_q) until its first hit and is never a victim
// while pinned; a miss allocates only while pinned + awaited < WAYS in its set, so a fill always
// has an unpinned victim. The requester that allocated retries the same line until it hits, so
// every fill is hit at least once (systemc/ascache.h, systemc/README.md).
// The accesses of one cycle act in port order, each seeing the LRU ranks and MSHRs as the earlier
// ports leave them: Ascache::access called once per port, port 0 first.
// A fill (fill_valid_i, fill_tag_i = the MSHR index, fill_data_i = the whole line) installs the
// MSHR's line in the set's victim way (ascache_victim: first invalid way, else the LRU unpinned
// way), pins it and frees the MSHR; a fill of a free MSHR is ignored (Ascache::fill throws). Fill
// has no ready: it is always taken, as Ascache::fill. A fill comes after its request was taken
// (req_valid_o && req_ready_i).
//
// The fill acts at the edge that ends its cycle, and nothing an access sees depends on it (the
// fill path is cut from the access path: Ascache::fill chooses its victim when called, before the
// cycle's accesses, and installs when the next cycle starts). The fill's victim is chosen from the
// state at the cycle's start; the cycle's accesses see that state too: the fill's line is not yet
// there (an access to it merges into the fill's MSHR, which is still busy and cannot be allocated
// in the cycle), the victim's old line is (it may hit, its old bytes: the data array is read
// before the write). At the edge the line is written, valid and pinned (after the hits' unpins),
// and the MSHR freed. The fill leaves the LRU ranks as they are: its way is pinned (no victim)
// until its first hit, and that hit makes it the most recent whatever its rank was.
//
// Two response forms:
//   HIT_LATENCY >= 1, PORTS = 1 (the pin-level twin of systemc/pins/ascache.h): the data array is
//     a 1R1W SRAM (ascache_ram, synchronous read-first read) read at the access edge; 1 = the
//     SRAM's output register, each further cycle adds a register of the response and its line.
//   HIT_LATENCY 0, any PORTS (the frame's cache, systemc/ascache_rtl.h): the responses come in the
//     access's own cycle, as Ascache::access answers the cycle model's requesters (which add the
//     configured hit latency to their loop); the data array has PORTS asynchronous read ports.
//     rsp_hit_o and rsp_data_o of a port are the line's presence and bytes whether or not the port
//     accesses (acc_valid_i low: no LRU, pin, MSHR or counter effect), so a requester may look at
//     a line before it decides to access it: no port's response depends on another port's
//     access (trv_unit's pipes; rtu.v).
// Storage: tags, valid bits, pin bits and LRU ranks in flip-flops (read combinationally); data
// SETS*WAYS lines of 8*LINE_BYTES bits.
//
// Parameters: WAYS a power of two, SETS >= 2 (a power of two: the set is the line's low bits and
// the tag the rest; otherwise the set is line % SETS and the tag the whole line, as Ascache's
// line % sets), MSHRS >= 2, LINE_W = line-index width (address width - log2 LINE_BYTES; LINE_W >
// log2 SETS), TAG_BITS = the requester's sideband acc_tag_i -> rsp_tag_o (e.g. a ray slot),
// CNT_BITS = width of the counters (wrap around).
// lint: also PORTS=8 HIT_LATENCY=0 SETS=64 WAYS=4 MSHRS=8
// lint: also PORTS=8 HIT_LATENCY=0 SETS=170 WAYS=4 LINE_BYTES=48 MSHRS=8
// lint: also PORTS=2 HIT_LATENCY=0 SETS=6 WAYS=1 LINE_BYTES=32 MSHRS=2
module ascache #(
  parameter integer SETS        = 8,
  parameter integer WAYS        = 2,
  parameter integer LINE_BYTES  = 64,
  parameter integer MSHRS       = 4,
  parameter integer HIT_LATENCY = 1,
  parameter integer PORTS       = 1,
  parameter integer LINE_W      = 26,
  parameter integer TAG_BITS    = 8,
  parameter integer CNT_BITS    = 32
) (
  input  wire                          clk_i,
  input  wire                          rst_ni,
  // Access (Ascache::access): one per cycle, always accepted.
  input  wire [PORTS-1:0]              acc_valid_i,
  input  wire [PORTS*LINE_W-1:0]       acc_line_i,
  input  wire [PORTS*TAG_BITS-1:0]     acc_tag_i,
  // Its result, HIT_LATENCY cycles later (no back-pressure; HIT_LATENCY 0: in the same cycle).
  output wire [PORTS-1:0]              rsp_valid_o,
  output wire [PORTS-1:0]              rsp_hit_o,
  output wire [PORTS-1:0]              rsp_merge_o,
  output wire [PORTS-1:0]              rsp_full_o,
  output wire [PORTS-1:0]              rsp_set_full_o,
  output wire [PORTS*TAG_BITS-1:0]     rsp_tag_o,
  output wire [PORTS*8*LINE_BYTES-1:0] rsp_data_o,
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
  output wire [CNT_BITS-1:0]           cnt_set_full_o,
  output wire [CNT_BITS-1:0]           cnt_fills_o
);

  localparam integer POW2 = (SETS & (SETS - 1)) == 0 ? 1 : 0;  // set = low line bits, else line % SETS
  localparam integer SW = $clog2(SETS);                   // set index bits
  localparam integer TW = POW2 != 0 ? LINE_W - SW : LINE_W;    // tag bits (the whole line if not POW2)
  localparam integer RW = WAYS > 1 ? $clog2(WAYS) : 1;    // way index / LRU rank bits
  localparam integer MW = $clog2(MSHRS);                  // MSHR index bits
  localparam integer CW = $clog2(MSHRS + 1);              // MSHR count bits
  localparam integer PW = $clog2(WAYS + MSHRS + 1);       // pinned + awaited count bits
  localparam [PW-1:0] NWAYS = WAYS[PW-1:0];
  localparam integer DW = 8 * LINE_BYTES;                 // line bits
  localparam integer NL = SETS * WAYS;                    // lines
  localparam integer AW = SW + (WAYS > 1 ? RW : 0);       // data array address bits
  localparam integer LAST = MSHRS - 1;
  localparam [MW-1:0] LAST_MSHR = LAST[MW-1:0];
  localparam [CNT_BITS-1:0] CNT_ONE = 1;
  localparam integer QW = (MW > CW ? MW : CW) + 1;        // tail + allocations before the wrap
  localparam [QW-1:0] MSHRS_QW = MSHRS[QW-1:0];

  // A line's set and its tag within the set.
  localparam [LINE_W-1:0] NSETS = SETS[LINE_W-1:0];
  /* verilator lint_off UNUSEDSIGNAL */  // the functions' locals are wider than their results
  function automatic [SW-1:0] set_of(input [LINE_W-1:0] line);
    reg [LINE_W-1:0] r;
    begin
      r = POW2 != 0 ? line & (NSETS - 1'b1) : line % NSETS;
      set_of = r[SW-1:0];
    end
  endfunction
  function automatic [TW-1:0] tag_of(input [LINE_W-1:0] line);
    reg [LINE_W-1:0] t;
    begin
      t = POW2 != 0 ? line >> SW : line;
      tag_of = t[TW-1:0];
    end
  endfunction
  function automatic [AW-1:0] addr_of(input [SW-1:0] set, input [RW-1:0] way);
    reg [SW+RW-1:0] a;
    begin
      a = WAYS > 1 ? {set, way} : {{RW{1'b0}}, set};
      addr_of = a[AW-1:0];
    end
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // ---------------------------------------------------------------------------------------------
  // State. The tags are a per-set array, an SRAM like the data array (one write port, the fill;
  // a read port per access and one for the fill, read combinationally at their sets); valid bits,
  // pin bits and ranks are flip-flops (flat vectors: their reset is one assignment).
  reg [SETS*WAYS-1:0]             valid_q;              // way w of set s at [s*WAYS + w]
  reg [SETS*WAYS-1:0]             pin_q;                // filled, not hit since: not a victim
  reg [WAYS*TW-1:0]               tag_q   [0:SETS-1];   // way w at [w*TW +: TW]
  reg [SETS*WAYS*RW-1:0]          rank_q;               // LRU ranks of set s at [s*WAYS*RW +: WAYS*RW]
  reg [MSHRS-1:0]        mv_q, mv_d;          // MSHR valid
  reg [MSHRS*LINE_W-1:0] ml_q, ml_d;          // MSHR line
  reg [MSHRS*SW-1:0]     ms_q, ms_d;          // MSHR line's set
  reg [MSHRS*MW-1:0]     fifo_q, fifo_d;      // request queue: MSHR indices, allocation order
  reg [MW-1:0]           head_q, head_d, tail_q, tail_d;
  reg [CW-1:0]           count_q, count_d;
  reg [CNT_BITS-1:0]     hits_q, hits_d, misses_q, misses_d, merges_q, merges_d;
  reg [CNT_BITS-1:0]     full_q, full_d, sfull_q, sfull_d, fills_q, fills_d;
  // The counters add the cycle's counts a cycle later (registered increments, so that no access
  // decision is followed by a 32-bit sum in its cycle); the outputs are the sums with the
  // increments still to add, the same values as adding at once.
  reg [CNT_BITS-1:0]     hits_i, misses_i, merges_i, full_i, sfull_i, fills_i;

  // ---------------------------------------------------------------------------------------------
  // Fill side: the MSHR's line, its set and the victim way (from the state at the cycle's start).
  reg              fill_go;
  reg [LINE_W-1:0] f_line;
  wire [RW-1:0]    f_way;
  wire [SW-1:0]    f_set = set_of(f_line);
  wire [TW-1:0]    f_tag = tag_of(f_line);

  integer i, w, pk;
  always @* begin : p_fill
    fill_go = 1'b0;
    f_line  = {LINE_W{1'b0}};
    for (i = 0; i < MSHRS; i = i + 1)
      if (fill_tag_i == i[MW-1:0]) begin
        fill_go = fill_valid_i && mv_q[i];
        f_line  = ml_q[i*LINE_W +: LINE_W];
      end
  end

  wire [WAYS-1:0]    f_valid = valid_q[f_set*WAYS +: WAYS];
  wire [WAYS-1:0]    f_pin   = pin_q[f_set*WAYS +: WAYS];
  wire [WAYS*RW-1:0] f_rank  = rank_q[f_set*WAYS*RW +: WAYS*RW];

  ascache_victim #(.WAYS(WAYS), .RW(RW)) u_victim (
    .valid_i(f_valid), .pin_i(f_pin), .rank_i(f_rank), .way_o(f_way));

  // ---------------------------------------------------------------------------------------------
  // Access side: PORTS lookups in port order. Port k sees the set at the cycle's start (not the
  // cycle's fill), the LRU ranks and pins as the hits of ports 0 .. k-1 leave them, and the MSHRs
  // after the allocations of ports 0 .. k-1 (Ascache::access called k times in a cycle). A hit depends on
  // the tags alone; the MSHRs' part is a prefix over the ports (below): each port's allocation
  // needs only which earlier ports allocated (the same line: a merge; their count: the free MSHR
  // it takes and whether any is left; those of its set: set full), not the MSHR arrays as the
  // earlier ports rewrote them.
  wire [PORTS-1:0]           a_hit_v;
  wire [PORTS-1:0]           a_there_v;  // the line is present (valid access or not)
  wire [PORTS-1:0]           a_miss_v;
  wire [PORTS-1:0]           a_merge_v;
  wire [PORTS-1:0]           a_full_v;
  wire [PORTS-1:0]           a_sfull_v;
  wire [PORTS-1:0]           a_alloc_v;
  wire [PORTS*SW-1:0]        a_set_v;
  wire [PORTS*RW-1:0]        a_way_v;
  wire [PORTS*WAYS*RW-1:0]   a_rank_new_v  /* verilator split_var */;
  wire [PORTS*WAYS*RW-1:0]   a_rank_out = a_rank_new_v;  // read at a run-time index
  wire [PORTS-1:0]           a_base;     // a valid miss of no MSHR valid at the start
  wire [PORTS-1:0]           a_infl0;    // its line is fetched by an MSHR valid at the start
  wire [PORTS*PW-1:0]        a_held0;    // its set's ways pinned + awaited at the start
  wire [PORTS*LINE_W-1:0]    a_line_v;

  // The MSHR the fill frees at the edge (busy for the cycle's accesses).
  reg [MSHRS-1:0] f_free;
  always @* begin
    f_free = {MSHRS{1'b0}};
    for (i = 0; i < MSHRS; i = i + 1)
      if (fill_go && fill_tag_i == i[MW-1:0]) f_free[i] = 1'b1;
  end
  // The free MSHRs in index order (fl: the i-th lowest at [i*MW +: MW], i < nfree): an allocation
  // takes the lowest free one, so the port with n allocations before it takes the n-th.
  reg [MSHRS*MW-1:0] fl;
  reg [CW-1:0]       nfree;
  always @* begin
    fl = {(MSHRS*MW){1'b0}};
    nfree = {CW{1'b0}};
    for (i = 0; i < MSHRS; i = i + 1)
      if (!mv_q[i]) begin
        fl[nfree*MW +: MW] = i[MW-1:0];
        nfree = nfree + 1'b1;
      end
  end

  genvar gk, gj;
  generate
    for (gk = 0; gk < PORTS; gk = gk + 1) begin : g_port
      wire [LINE_W-1:0] line = acc_line_i[gk*LINE_W +: LINE_W];
      wire              av   = acc_valid_i[gk];
      wire [SW-1:0]     set  = set_of(line);
      wire [TW-1:0]     tag  = tag_of(line);
      wire [WAYS-1:0]    valid = valid_q[set*WAYS +: WAYS];
      wire [WAYS*TW-1:0] tags  = tag_q[set];
      // The set's ranks: the latest earlier port's that hit in the same set, else the registers'.
      wire [WAYS*RW-1:0] rank_set = rank_q[set*WAYS*RW +: WAYS*RW];
      wire [WAYS*RW-1:0] rank_pre;
      if (gk == 0) begin : g_first
        assign rank_pre = rank_set;
      end else begin : g_chain
        wire [(gk+1)*WAYS*RW-1:0] rchain /* verilator split_var */;
        assign rchain[WAYS*RW-1:0] = rank_set;
        for (gj = 0; gj < gk; gj = gj + 1) begin : g_prev
          assign rchain[(gj+1)*WAYS*RW +: WAYS*RW] =
              (a_hit_v[gj] && a_set_v[gj*SW +: SW] == set) ? a_rank_new_v[gj*WAYS*RW +: WAYS*RW]
                                                            : rchain[gj*WAYS*RW +: WAYS*RW];
        end
        assign rank_pre = rchain[gk*WAYS*RW +: WAYS*RW];
      end
      reg [RW-1:0] way;
      reg          hit;
      integer wk;
      always @* begin
        hit = 1'b0;
        way = {RW{1'b0}};
        for (wk = 0; wk < WAYS; wk = wk + 1)
          if (valid[wk] && tags[wk*TW +: TW] == tag) begin
            hit = 1'b1;
            way = wk[RW-1:0];
          end
      end
      ascache_touch #(.WAYS(WAYS), .RW(RW)) u_touch (
        .rank_i(rank_pre), .way_i(way), .rank_o(a_rank_new_v[gk*WAYS*RW +: WAYS*RW]));
      // The MSHRs valid at the start: one fetching the line (a merge), those of the line's set.
      reg          inflight;
      reg [PW-1:0] awaited;
      integer mk;
      always @* begin
        inflight = 1'b0;
        awaited  = {PW{1'b0}};
        for (mk = 0; mk < MSHRS; mk = mk + 1) begin
          if (mv_q[mk] && ml_q[mk*LINE_W +: LINE_W] == line) inflight = 1'b1;
          if (mv_q[mk] && ms_q[mk*SW +: SW] == set) awaited = awaited + 1'b1;
        end
      end
      // The set's pins as the hits of ports 0 .. k-1 leave them (a hit unpins its way), and how
      // many of its ways are pinned or awaited by an MSHR (the fill's MSHR among them).
      wire [WAYS-1:0] pin_set = pin_q[set*WAYS +: WAYS];
      wire [WAYS-1:0] pin_pre;
      if (gk == 0) begin : g_pin_first
        assign pin_pre = pin_set;
      end else begin : g_pin_chain
        reg [WAYS-1:0] clr;
        integer pj, pw;
        always @* begin
          clr = {WAYS{1'b0}};
          for (pj = 0; pj < gk; pj = pj + 1)
            for (pw = 0; pw < WAYS; pw = pw + 1)
              if (a_hit_v[pj] && a_set_v[pj*SW +: SW] == set && a_way_v[pj*RW +: RW] == pw[RW-1:0])
                clr[pw] = 1'b1;
        end
        assign pin_pre = pin_set & ~clr;
      end
      reg [PW-1:0] held;
      integer hk;
      always @* begin
        held = awaited;
        for (hk = 0; hk < WAYS; hk = hk + 1)
          if (pin_pre[hk]) held = held + 1'b1;
      end
      assign a_hit_v[gk]   = av && hit;
      assign a_there_v[gk] = hit;
      assign a_miss_v[gk]  = av && !hit;
      assign a_base[gk]    = av && !hit && !inflight;
      assign a_infl0[gk]   = inflight;
      assign a_held0[gk*PW +: PW] = held;
      assign a_line_v[gk*LINE_W +: LINE_W] = line;
      assign a_set_v[gk*SW +: SW] = set;
      assign a_way_v[gk*RW +: RW] = way;
    end
  endgenerate

  // The allocations, in port order: port k allocates unless an earlier port allocated its line
  // (then it merges), the earlier allocations took the last free MSHR (full), or its set's ways
  // pinned or awaited reach WAYS with the earlier allocations of its set (set full). a_at: the
  // allocations before port k (the free MSHR it takes: fl's a_at-th; its queue entry: tail + a_at).
  reg [PORTS-1:0]    a_mrg, a_fl, a_sf, a_alc;
  reg [PORTS*CW-1:0] a_at;
  reg [CW-1:0]       n_alloc;
  reg [PW-1:0]       same;
  integer ak, aj;
  always @* begin
    n_alloc = {CW{1'b0}};
    a_mrg = {PORTS{1'b0}};
    a_fl = {PORTS{1'b0}};
    a_sf = {PORTS{1'b0}};
    a_alc = {PORTS{1'b0}};
    a_at = {(PORTS*CW){1'b0}};
    for (ak = 0; ak < PORTS; ak = ak + 1) begin
      same = {PW{1'b0}};
      for (aj = 0; aj < ak; aj = aj + 1) begin
        if (a_alc[aj] && a_line_v[aj*LINE_W +: LINE_W] == a_line_v[ak*LINE_W +: LINE_W])
          a_mrg[ak] = 1'b1;
        if (a_alc[aj] && a_set_v[aj*SW +: SW] == a_set_v[ak*SW +: SW]) same = same + 1'b1;
      end
      a_at[ak*CW +: CW] = n_alloc;
      a_fl[ak] = (n_alloc >= nfree);
      a_sf[ak] = (a_held0[ak*PW +: PW] + same >= NWAYS);
      a_alc[ak] = a_base[ak] && !a_mrg[ak] && !a_fl[ak] && !a_sf[ak];
      if (a_alc[ak]) n_alloc = n_alloc + 1'b1;
    end
  end
  generate
    for (gk = 0; gk < PORTS; gk = gk + 1) begin : g_alloc
      wire miss0 = a_miss_v[gk];
      assign a_alloc_v[gk] = a_alc[gk];
      assign a_merge_v[gk] = miss0 && (a_infl0[gk] || a_mrg[gk]);
      assign a_full_v[gk]  = miss0 && !a_infl0[gk] && !a_mrg[gk] && a_fl[gk];
      assign a_sfull_v[gk] = miss0 && !a_infl0[gk] && !a_mrg[gk] && !a_fl[gk] && a_sf[gk];
    end
  endgenerate

  // ---------------------------------------------------------------------------------------------
  // Next state.
  wire req_pop = req_valid_o && req_ready_i;

  // The fill's way: its tag.
  reg [WAYS*TW-1:0] f_tags_new;
  always @* begin
    f_tags_new  = tag_q[f_set];
    for (w = 0; w < WAYS; w = w + 1)
      if (f_way == w[RW-1:0]) f_tags_new[w*TW +: TW] = f_tag;
  end

  // How many of this cycle's accesses hit, missed, ... (the allocations: n_alloc above).
  reg [CNT_BITS-1:0] n_hit, n_miss, n_merge, n_full, n_sfull;
  always @* begin
    n_hit = {CNT_BITS{1'b0}};
    n_miss = {CNT_BITS{1'b0}};
    n_merge = {CNT_BITS{1'b0}};
    n_full = {CNT_BITS{1'b0}};
    n_sfull = {CNT_BITS{1'b0}};
    for (i = 0; i < PORTS; i = i + 1) begin
      if (a_hit_v[i])   n_hit   = n_hit + CNT_ONE;
      if (a_miss_v[i])  n_miss  = n_miss + CNT_ONE;
      if (a_merge_v[i]) n_merge = n_merge + CNT_ONE;
      if (a_full_v[i])  n_full  = n_full + CNT_ONE;
      if (a_sfull_v[i]) n_sfull = n_sfull + CNT_ONE;
    end
  end

  reg [MW-1:0] a_free;  // an allocation's MSHR
  reg [QW-1:0] a_slot;  // its request queue entry (before the wrap)
  always @* begin
    // Each allocation: its free MSHR takes the line, and its index the queue's entry tail + a_at.
    a_free  = {MW{1'b0}};
    mv_d    = mv_q & ~f_free;
    ml_d    = ml_q;
    ms_d    = ms_q;
    fifo_d  = fifo_q;
    for (i = 0; i < PORTS; i = i + 1)
      if (a_alloc_v[i]) begin
        a_free = fl[a_at[i*CW +: CW]*MW +: MW];
        a_slot = {{(QW-MW){1'b0}}, tail_q} + {{(QW-CW){1'b0}}, a_at[i*CW +: CW]};
        if (a_slot >= MSHRS_QW) a_slot = a_slot - MSHRS_QW;
        mv_d[a_free] = 1'b1;
        ml_d[a_free*LINE_W +: LINE_W] = a_line_v[i*LINE_W +: LINE_W];
        ms_d[a_free*SW +: SW] = a_set_v[i*SW +: SW];
        fifo_d[a_slot[MW-1:0]*MW +: MW] = a_free;
      end
    a_slot  = {{(QW-MW){1'b0}}, tail_q} + {{(QW-CW){1'b0}}, n_alloc};
    if (a_slot >= MSHRS_QW) a_slot = a_slot - MSHRS_QW;
    tail_d  = a_slot[MW-1:0];
    head_d  = req_pop ? (head_q == LAST_MSHR ? {MW{1'b0}} : head_q + 1'b1) : head_q;
    count_d = count_q + n_alloc - {{(CW-1){1'b0}}, req_pop};

    hits_d   = hits_q + hits_i;
    misses_d = misses_q + misses_i;
    merges_d = merges_q + merges_i;
    full_d   = full_q + full_i;
    sfull_d  = sfull_q + sfull_i;
    fills_d  = fills_q + fills_i;
  end

  // Reset: valid and pin bits, LRU ranks (way w of every set has rank w), MSHR valid, queue,
  // counters.
  // Tags, MSHR lines and queue entries are meaningful only under a valid bit and are not reset.
  // The set arrays take the hits' LRU updates in port order (a later hit's ranks include the
  // earlier ones'); every hit's way unpinned, then the fill's way pinned (a hit on the victim's old
  // line in the fill's cycle too). The fill does not touch the LRU ranks: its way is pinned, so
  // never a victim, until its first hit, which makes it the most recent and keeps the others'
  // order, whatever its rank was (Ascache::settle leaves the stamp too).
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
      valid_q  <= {SETS*WAYS{1'b0}};
      pin_q    <= {SETS*WAYS{1'b0}};
      rank_q   <= {SETS{rank_reset}};
      mv_q     <= {MSHRS{1'b0}};
      head_q   <= {MW{1'b0}};
      tail_q   <= {MW{1'b0}};
      count_q  <= {CW{1'b0}};
      hits_q   <= {CNT_BITS{1'b0}};
      misses_q <= {CNT_BITS{1'b0}};
      merges_q <= {CNT_BITS{1'b0}};
      full_q   <= {CNT_BITS{1'b0}};
      sfull_q  <= {CNT_BITS{1'b0}};
      fills_q  <= {CNT_BITS{1'b0}};
      hits_i   <= {CNT_BITS{1'b0}};
      misses_i <= {CNT_BITS{1'b0}};
      merges_i <= {CNT_BITS{1'b0}};
      full_i   <= {CNT_BITS{1'b0}};
      sfull_i  <= {CNT_BITS{1'b0}};
      fills_i  <= {CNT_BITS{1'b0}};
    end else begin
      for (pk = 0; pk < PORTS; pk = pk + 1)  // in port order: a later hit's ranks include earlier
        if (a_hit_v[pk]) rank_q[a_set_v[pk*SW +: SW]*WAYS*RW +: WAYS*RW] <= a_rank_out[pk*WAYS*RW +: WAYS*RW];
      for (pk = 0; pk < PORTS; pk = pk + 1)
        if (a_hit_v[pk]) pin_q[addr_of(a_set_v[pk*SW +: SW], a_way_v[pk*RW +: RW])] <= 1'b0;
      if (fill_go) begin
        valid_q[addr_of(f_set, f_way)] <= 1'b1;
        pin_q[addr_of(f_set, f_way)]   <= 1'b1;
      end
      mv_q     <= mv_d;
      head_q   <= head_d;
      tail_q   <= tail_d;
      count_q  <= count_d;
      hits_q   <= hits_d;
      misses_q <= misses_d;
      merges_q <= merges_d;
      full_q   <= full_d;
      sfull_q  <= sfull_d;
      fills_q  <= fills_d;
      hits_i   <= n_hit;
      misses_i <= n_miss;
      merges_i <= n_merge;
      full_i   <= n_full;
      sfull_i  <= n_sfull;
      fills_i  <= fill_go ? CNT_ONE : {CNT_BITS{1'b0}};
    end
  end

  always @(posedge clk_i) begin
    if (fill_go) tag_q[f_set] <= f_tags_new;
    ml_q   <= ml_d;
    ms_q   <= ms_d;
    fifo_q <= fifo_d;
  end

  // ---------------------------------------------------------------------------------------------
  // Data array, written by the fill at its cycle's edge. HIT_LATENCY >= 1 (one port): an SRAM read
  // by a hit at the same edge (read-first: a hit on the victim's old line reads its old bytes),
  // then the response registers. HIT_LATENCY 0: PORTS asynchronous reads (a register file).
  wire [AW-1:0] ram_waddr = addr_of(f_set, f_way);

  localparam integer RSW = 4 + TAG_BITS;
  generate
    if (HIT_LATENCY == 0) begin : g_comb
      reg [DW-1:0] data_q [0:NL-1];
      always @(posedge clk_i) if (fill_go) data_q[ram_waddr] <= fill_data_i;
      for (gk = 0; gk < PORTS; gk = gk + 1) begin : g_rsp
        wire [AW-1:0] ra = addr_of(a_set_v[gk*SW +: SW], a_way_v[gk*RW +: RW]);
        assign rsp_data_o[gk*DW +: DW] = data_q[ra];
      end
      assign rsp_valid_o = acc_valid_i;
      assign rsp_hit_o   = a_there_v;  // for a port without an access: the line is present
      assign rsp_merge_o = a_merge_v;
      assign rsp_full_o  = a_full_v;
      assign rsp_set_full_o = a_sfull_v;
      assign rsp_tag_o   = acc_tag_i;
    end else begin : g_sram
      if (PORTS != 1) begin : g_bad
        ascache_error_registered_response_has_one_port u_error ();  // elaboration error
      end
      wire [DW-1:0] ram_rdata;
      ascache_ram #(.DEPTH(NL), .WIDTH(DW), .ADDR_W(AW)) u_ram (
        .clk_i   (clk_i),
        .we_i    (fill_go),
        .waddr_i (ram_waddr),
        .wdata_i (fill_data_i),
        .re_i    (a_hit_v[0]),
        .raddr_i (addr_of(a_set_v[SW-1:0], a_way_v[RW-1:0])),
        .rdata_o (ram_rdata)
      );
      // Response: HIT_LATENCY registers of (valid, hit, merge, full, tag); the line comes from
      // the SRAM's output register, then through HIT_LATENCY-1 further registers (hits only).
      reg [HIT_LATENCY-1:0]     rv_q;
      reg [HIT_LATENCY*RSW-1:0] rs_q;
      if (HIT_LATENCY > 1) begin : g_rsp_pipe
        reg [(HIT_LATENCY-1)*DW-1:0] rd_q;
        integer k;
        always @(posedge clk_i or negedge rst_ni) begin
          if (!rst_ni) rv_q <= {HIT_LATENCY{1'b0}};
          else         rv_q <= {rv_q[HIT_LATENCY-2:0], acc_valid_i[0]};
        end
        always @(posedge clk_i) begin
          if (acc_valid_i[0])
            rs_q[RSW-1:0] <= {a_hit_v[0], a_merge_v[0], a_full_v[0], a_sfull_v[0], acc_tag_i};
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
          else         rv_q <= acc_valid_i[0];
        end
        always @(posedge clk_i) begin
          if (acc_valid_i[0])
            rs_q <= {a_hit_v[0], a_merge_v[0], a_full_v[0], a_sfull_v[0], acc_tag_i};
        end
        assign rsp_data_o = ram_rdata;
      end
      assign rsp_valid_o = rv_q[HIT_LATENCY-1];
      assign {rsp_hit_o, rsp_merge_o, rsp_full_o, rsp_set_full_o, rsp_tag_o} =
          rs_q[(HIT_LATENCY-1)*RSW +: RSW];
      wire unused_ports = ^{a_miss_v, a_alloc_v, a_there_v};
    end
  endgenerate

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
  assign cnt_hits_o   = hits_d;
  assign cnt_misses_o = misses_d;
  assign cnt_merges_o = merges_d;
  assign cnt_full_o   = full_d;
  assign cnt_set_full_o = sfull_d;
  assign cnt_fills_o  = fills_d;

endmodule
