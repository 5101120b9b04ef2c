// ist_unit - the intersection unit whole: the ist input queue with looping on a triangle-cache
// miss, the triangle-cache accesses and the record decode, IST ist.v pipelines, and the result
// delay of the triangle cache's hit latency. The RTL view of systemc/ist.h's control (its pin-level
// view) with its datapaths: bound into the running frame by systemc/ist_rtl.h (raycore simulate
// --rtl ist), cycle for cycle and bit for bit the transaction model's.
//
// Per cycle, in the model's order (systemc/ist.h, Ist::tick):
//   1. the results the ist.v pipelines put out at the last edge enter the delay ring, due
//      hl_i - ENTRY_REG cycles later (0: this cycle); the results due now leave on res_* (lane
//      u = unit u's result of the access at cycle now - hl_i), in the model's order: the trv
//      reduces them (trv_unit's res_*);
//   2. unit u (u < units_i) takes the queue's entry u if units 0 .. u-1 took theirs and its ready
//      cycle has come: it reads the triangle cache (acc_* / rsp_*, same-cycle response) and the
//      ray of the entry's slot (ray_slot_o / ray_i, same cycle); on a hit the test enters its
//      ist.v (a record whose id is the ray's skip id too: its result reads as no hit; with
//      ENTRY_REG, from a register in the next cycle), on a miss the entry is registered and goes
//      to the back of the queue at the end of the next cycle, ready the cycle after (the
//      triangle cache's answer decides no push of its own cycle);
//   3. the misses of the cycle before (their registers), in unit order, then the trv's hand-offs
//      of this cycle (hin_*, one run of consecutive list positions of one slot per trv pipe, with
//      its ready cycle) in pipe order, are appended at the queue's tail.
// room_o is the queue's room at the cycle's start less the misses on their way back (qcap_i -
// entries - misses registered), for the trv's hand-offs of the same cycle: the queue holds them
// and the misses. count_o counts those misses as entries. The queue is a
// FIFO whose head blocks the entries behind it until its ready cycle (the cycle model's
// TimedFifo); ready cycles are 32-bit cycle numbers compared with now_i as a signed difference.
// Unit u's access depends only on the queue's registers, not on the responses to units 0 .. u-1:
// the caller answers the accesses in unit order. The counters add a cycle's registered increments
// (their outputs the sums plus the increments still registered: exact in every cycle).
//
// Storage: the queue, 2^QBITS registers of {slot, list position (its run's start and its place
// in the run), triangle index, ready cycle} (qcap_i <= 2^QBITS at run time, IST <= 2^QBITS); the
// delay ring, 2^HLBITS x IST results (hl_i < 2^HLBITS).
// A cycle's pushes are consecutive from the tail (misses, then pipe 0's run, pipe 1's ...), so an
// entry is written from one of 1 + PIPES sources, never from every pipe's every word: pipe p's
// words are rotated once by the run's start modulo J (J >= WORDS, a power of two dividing
// 2^QBITS), and entry e, inside pipe p's run, takes position e mod J of the rotation, a fixed
// wire; the misses are compacted and rotated by the tail alike. A mux per entry over all PIPES x
// WORDS words cost 2.4 M NAND2 eq. at the RTU's parameters (64 entries, 4 pipes x 16 words); see
// docs/area.md. Each ist.v carries its test's side data (slot, skip,
// list position, the record's id, k and plane) as its tag. Parameters: SLOT_BITS, IST, PIPES and
// WORDS (the hand-off: trv_unit's), RPL (triangle records per cache line, a power of two),
// WATERTIGHT (0: Wald's records and ist.v, latency 10 x STAGES; 1: watertight records, the plane
// and the vertices, and ist_watertight.v: --ist watertight, latency 18 x STAGES, the margin
// registers unused, tmax and the results' t as keys of 7 more mantissa bits for FP24: TX_).
// lint: also SLOT_BITS=7 IST=4 PIPES=4 WORDS=16 QBITS=6 RPL=2 HLBITS=4 STAGES=2
// lint: also EXP_BITS=8 MAN_BITS=23 RNE=1 SLOT_BITS=7 IST=4 PIPES=4 WORDS=16 QBITS=6 RPL=1 HLBITS=4 STAGES=2
// lint: also IST=1 PIPES=1 WORDS=1 RPL=1 HLBITS=1 STAGES=0 ENTRY_REG=0
// lint: also SLOT_BITS=7 IST=4 PIPES=4 WORDS=16 QBITS=6 RPL=1 HLBITS=4 STAGES=2 WATERTIGHT=1
// lint: also EXP_BITS=8 MAN_BITS=23 RNE=1 RPL=1 WATERTIGHT=1
module ist_unit #(
  parameter integer EXP_BITS  = 7,
  parameter integer MAN_BITS  = 16,
  parameter integer RNE       = 0,
  parameter integer RAYCORE   = 0,
  parameter integer STAGES    = 2,
  parameter integer SLOT_BITS = 3,
  parameter integer IST       = 2,
  parameter integer PIPES     = 2,
  parameter integer WORDS     = 4,
  parameter integer QBITS     = 3,
  parameter integer RPL       = 2,
  parameter integer HLBITS    = 2,
  // 1: a test enters ist.v from a register, a cycle after its triangle-cache access (the record
  // and the ray registered), and its result waits hl_i - 1 cycles in the ring instead of hl_i:
  // the same cycles, hl_i >= 1. 0: it enters in the access's cycle (hl_i >= 0).
  parameter integer ENTRY_REG = 1,
  parameter integer WATERTIGHT = 0,
  // Derived (not to be overridden): the record layout of hls/wald.h and the widths.
  parameter integer W_        = 1 + EXP_BITS + MAN_BITS,
  // The closest-hit key's extension bits below t (hls::KeyFormat): ist_watertight.v's t carries
  // the shear format's mantissa (7 more bits for FP24); Wald's t is F's (TX 0, the key = t).
  parameter integer TX_       = (WATERTIGHT != 0 && MAN_BITS < 23) ? 23 - MAN_BITS : 0,
  parameter integer KW_       = W_ + TX_,
  parameter integer CB_       = (W_ <= 24) ? 3 : 4,               // bytes per constant
  parameter integer NC_       = (WATERTIGHT != 0) ? 12 : 9,       // constants per record
  parameter integer IDOFF_    = ((NC_ * CB_ + 1 + 3) / 4) * 4,    // the id's byte offset
  parameter integer RB_       = ((IDOFF_ + 4 + 15) / 16) * 16,    // bytes per record
  parameter integer LINE_W_   = 8 * RPL * RB_                     // bits per cache line
) (
  input  wire                            clk_i,
  input  wire                            rst_ni,
  input  wire [31:0]                     now_i,
  // Configuration, static per frame.
  input  wire [W_-1:0]                   eps_i,       // ist.v's margin registers (Wald's)
  input  wire [W_-1:0]                   one_eps_i,
  input  wire [15:0]                     qcap_i,      // the queue's capacity (<= 2^QBITS)
  input  wire [7:0]                      hl_i,        // the triangle cache's hit latency
  input  wire [4:0]                      units_i,     // ist units in use (1 .. IST)
  // The trv's hand-offs (pipe p in bits [p*w +: w]): n entries, list positions pos .. pos+n-1.
  input  wire [PIPES*6-1:0]              hin_n_i,
  input  wire [PIPES*SLOT_BITS-1:0]      hin_slot_i,
  input  wire [PIPES*32-1:0]             hin_pos_i,
  input  wire [PIPES*32-1:0]             hin_ready_i,
  input  wire [PIPES*32*WORDS-1:0]       hin_words_i,
  output wire [15:0]                     room_o,
  // The ray of unit u's entry: {skip_id[31:0], tmax, tmin, d z y x, o z y x} (o x lowest; tmax a
  // key of KW_ bits).
  output wire [IST*SLOT_BITS-1:0]        ray_slot_o,
  input  wire [IST*(32+7*W_+KW_)-1:0]    ray_i,
  // Triangle-cache accesses, one per unit (line index), same-cycle responses (the whole line).
  output wire [IST-1:0]                  acc_valid_o,
  output wire [IST*32-1:0]               acc_line_o,
  input  wire [IST-1:0]                  rsp_hit_i,
  input  wire [IST*LINE_W_-1:0]          rsp_data_i,
  // Results leaving (trv_unit's res_*): {1, t, den, pos, id, k, nu, nv, nd} (t the key, KW_ bits),
  // zero but pos and the top bit when not a hit.
  output wire [IST-1:0]                  res_valid_o,
  output wire [IST*SLOT_BITS-1:0]        res_slot_o,
  output wire [IST-1:0]                  res_hit_o,
  output wire [IST*(67+4*W_+KW_)-1:0]    res_rec_o,
  // The queue's head (the cycle model's next event) and tests or results inside.
  output wire                            head_valid_o,
  output wire [31:0]                     head_ready_o,
  output wire                            busy_o,
  output wire [15:0]                     count_o,     // entries in the queue (misses too)
  // Counters (systemc/config.h RtuStats: ist_busy, ist_tri_miss, tri_tests).
  output wire [63:0]                     cnt_busy_o,
  output wire [63:0]                     cnt_miss_o,
  output wire [63:0]                     cnt_tests_o
);

  localparam integer W   = W_;
  localparam integer KW  = KW_;
  localparam integer LV  = (WATERTIGHT != 0) ? 18 : 10;  // ist_watertight.v's or ist.v's levels
  localparam integer BW  = 67 + 4 * W + KW;
  localparam integer QN  = 1 << QBITS;
  localparam integer HN  = 1 << HLBITS;
  localparam integer RW  = 32 + 7 * W + KW;
  localparam integer TW  = SLOT_BITS + 1 + 32 + 32 + 2 + 3 * W;  // ist.v's tag: the side data
  localparam integer RESW = 1 + SLOT_BITS + BW;                  // a result: {hit, slot, rec}
  localparam integer RPLB = (RPL > 1) ? $clog2(RPL) : 1;
  localparam integer SW  = SLOT_BITS + 1 + 32 + 32;              // {slot, skip, pos, id}
  localparam integer NC  = NC_;
  localparam integer EW  = 2 + NC * W + 7 * W + KW + SW;              // a test entering the datapath

  // ---- the queue --------------------------------------------------------------------------------
  // Entry e's values after this edge (its registers, or what this cycle's pushes write into them:
  // g_q[e], below), read through these by the head window.
  // An entry's list position is pb + off: a pipe's run stores its start pb and the entry's place
  // in it off (< J, below), so that the run's words are rotated without their positions; a miss
  // goes back with the pb and off it had.
  localparam integer WB = (WORDS > 1) ? $clog2(WORDS) : 0;
  localparam integer JB = (WB < QBITS) ? WB : QBITS;
  localparam integer J  = 1 << JB;
  localparam integer OW = (JB > 0) ? JB : 1;   // off's width
  wire [SLOT_BITS-1:0] n_slot  [0:QN-1];
  wire [31:0]          n_pb    [0:QN-1];
  wire [OW-1:0]        n_off   [0:QN-1];
  wire [31:0]          n_tri   [0:QN-1];
  wire [31:0]          n_ready [0:QN-1];
  reg [QBITS-1:0]     head_q;
  reg [QBITS:0]       cnt_q;

  // The head window: entries head_q + u (u < IST) in registers, refilled at every edge from the
  // entries' values after it (at the new head, this cycle's pushes included), so that the units'
  // triangle-cache accesses and ray reads start from registers, not from a read of the queue
  // (issue 26's timing; the same cycles and bits). Beyond cnt_q the window is not read.
  reg [SLOT_BITS-1:0] w_slot_q  [0:IST-1];
  reg [31:0]          w_pb_q    [0:IST-1];
  reg [OW-1:0]        w_off_q   [0:IST-1];
  reg [31:0]          w_tri_q   [0:IST-1];
  reg [31:0]          w_ready_q [0:IST-1];

  assign head_valid_o = (cnt_q != {(QBITS+1){1'b0}});
  assign head_ready_o = w_ready_q[0];
  assign count_o      = {{(15-QBITS){1'b0}}, cnt_q} + {10'd0, nmq};

  // ---- 2. issue: unit u takes entry u while every unit before it took its entry -----------------
  wire [IST-1:0]      take, hit, miss, test;
  wire [IST-1:0]      rdy;       // entry u present, ready and unit u in use
  wire [IST-1:0]      g_out_v;   // unit u's ist.v result of this cycle
  wire [IST*RESW-1:0] g_out_r;
  wire [IST*32-1:0]   u_pb, u_tri;
  wire [IST*OW-1:0]   u_off;
  genvar u;
  generate
    for (u = 0; u < IST; u = u + 1) begin : g_issue
      localparam [4:0] U5 = u;
      wire [31:0] dt = w_ready_q[u] - now_i;
      assign rdy[u] = ({{(31-QBITS){1'b0}}, cnt_q} > u) && ($signed(dt) <= 0) && (U5 < units_i);
      assign take[u] = &rdy[u:0];
      assign hit[u]   = take[u] && rsp_hit_i[u];
      assign miss[u]  = take[u] && !rsp_hit_i[u];
      assign acc_valid_o[u] = take[u];
      assign ray_slot_o[u*SLOT_BITS +: SLOT_BITS] = w_slot_q[u];  // a miss copies it to the tail
      assign u_pb[u*32 +: 32] = w_pb_q[u];
      assign u_off[u*OW +: OW] = w_off_q[u];
      wire [31:0] upos = w_pb_q[u] + {{(32-OW){1'b0}}, w_off_q[u]};  // the entry's list position
      // The record: line tri / RPL, record tri % RPL of it.
      wire [31:0] tidx = w_tri_q[u];
      assign u_tri[u*32 +: 32] = tidx;
      if (RPL > 1) begin : g_line
        assign acc_line_o[u*32 +: 32] = tidx >> RPLB;
      end else begin : g_line1
        assign acc_line_o[u*32 +: 32] = tidx;
      end
      wire [LINE_W_-1:0] line = rsp_data_i[u*LINE_W_ +: LINE_W_];
      reg  [8*RB_-1:0]   rec;
      integer r;
      always @* begin
        rec = line[0 +: 8*RB_];
        for (r = 1; r < RPL; r = r + 1)
          if (RPL > 1 && tidx[RPLB-1:0] == r[RPLB-1:0]) rec = line[r*8*RB_ +: 8*RB_];
      end
      wire          unused_rec = ^rec;  // flags and padding
      // The constants c_{NC-1} .. c_0, packed (c_i at [i*W +: W]).
      wire [NC*W-1:0] cs;
      genvar gr;
      for (gr = 0; gr < NC; gr = gr + 1) begin : g_rc
        assign cs[gr*W +: W] = rec[gr*8*CB_ +: W];
      end
      wire [1:0]    k  = rec[NC*8*CB_ +: 2];
      wire [31:0]   id = rec[8*IDOFF_ +: 32];
      wire [RW-1:0] ray = ray_i[u*RW +: RW];
      wire          skip = (id == ray[7*W+KW +: 32]);
      // The test entering the datapath: {k, c_{NC-1} .. c_0, the ray, slot, skip, list position,
      // id}; the side data rides as its tag (with k and the plane c0 .. c2, taken from the record
      // here).
      wire [EW-1:0] ein = {k, cs, ray[0 +: 7*W+KW], w_slot_q[u], skip, upos, id};
      wire          ev;
      wire [EW-1:0] ed;
      if (ENTRY_REG != 0) begin : g_ereg  // registered: ist.v's level 1 starts from a register
        reg           v_q;
        reg [EW-1:0]  d_q;
        always @(posedge clk_i or negedge rst_ni)
          if (!rst_ni) v_q <= 1'b0;
          else v_q <= hit[u];
        always @(posedge clk_i) d_q <= ein;
        assign ev = v_q;
        assign ed = d_q;
      end else begin : g_ewire
        assign ev = hit[u];
        assign ed = ein;
      end
      wire [7*W+KW-1:0] eray = ed[SW +: 7*W+KW];  // the ray without its skip id
      // A test counts as it enters ist.v (with ENTRY_REG a cycle after the access: the skip
      // test's compare is off the triangle cache's path).
      assign test[u] = ev && !ed[64];  // ed[0 +: SW] = {slot, skip, pos, id}
      wire [NC*W-1:0] ec = ed[SW + 7*W+KW +: NC*W];
      wire [TW-1:0] itag = {ed[0 +: SW], ed[EW-1 -: 2], ec[0 +: W], ec[W +: W], ec[2*W +: W]};
      // The datapath.
      wire          o_valid, o_ready_unused;
      wire [2:0]    o_exit;
      wire [W-1:0]  o_den;
      wire [KW-1:0] o_tk;  // t as the key
      wire [TW-1:0] o_tag;
      // The side data beside the test, not through it: ist.v never stalls here (out_ready 1), so
      // its latency is exactly LV x STAGES and one fp_delay memory of that depth holds the tag
      // (ist.v's own carries are fp_delay memories too, FREE = 1).
      wire          s_valid_unused, s_ready_unused, o_tag0_unused;
      fp_delay #(.WIDTH(TW), .STAGES(LV * STAGES), .FREE(1)) u_side (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(ev), .in_ready_o(s_ready_unused),
        .in_data_i(itag), .out_valid_o(s_valid_unused), .out_ready_i(1'b1), .out_data_o(o_tag));
      if (WATERTIGHT != 0) begin : g_wt  // the plane, then the vertices A, B, C ({z, y, x} each)
        ist_watertight #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE),
                         .STAGES(STAGES), .TAG_BITS(1), .FREE(1)) u_ist (
          .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(ev), .in_ready_o(o_ready_unused),
          .in_k_i(ed[EW-1 -: 2]), .in_nu_i(ec[0 +: W]), .in_nv_i(ec[W +: W]), .in_nd_i(ec[2*W +: W]),
          .in_va_i(ec[3*W +: 3*W]), .in_vb_i(ec[6*W +: 3*W]), .in_vc_i(ec[9*W +: 3*W]),
          .in_o_i(eray[0 +: 3*W]), .in_d_i(eray[3*W +: 3*W]),
          .in_tmin_i(eray[6*W +: W]), .in_tmax_i(eray[7*W +: KW]), .in_tag_i(1'b0),
          .out_valid_o(o_valid), .out_ready_i(1'b1), .out_exit_o(o_exit), .out_t_o(o_t_unused),
          .out_tk_o(o_tk), .out_den_o(o_den), .out_tag_o(o_tag0_unused));
        wire [W-1:0] o_t_unused;  // the key's top bits: the key goes on whole
        wire unused_eps = ^{eps_i, one_eps_i, o_t_unused};  // Wald's margin registers
      end else begin : g_wald
        ist #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES),
              .TAG_BITS(1), .FREE(1)) u_ist (
          .clk_i(clk_i), .rst_ni(rst_ni), .eps_i(eps_i), .one_eps_i(one_eps_i),
          .in_valid_i(ev), .in_ready_o(o_ready_unused), .in_k_i(ed[EW-1 -: 2]),
          .in_c0_i(ec[0 +: W]), .in_c1_i(ec[W +: W]), .in_c2_i(ec[2*W +: W]), .in_c3_i(ec[3*W +: W]),
          .in_c4_i(ec[4*W +: W]), .in_c5_i(ec[5*W +: W]), .in_c6_i(ec[6*W +: W]),
          .in_c7_i(ec[7*W +: W]), .in_c8_i(ec[8*W +: W]),
          .in_o_x_i(eray[0 +: W]), .in_o_y_i(eray[W +: W]), .in_o_z_i(eray[2*W +: W]),
          .in_d_x_i(eray[3*W +: W]), .in_d_y_i(eray[4*W +: W]), .in_d_z_i(eray[5*W +: W]),
          .in_tmin_i(eray[6*W +: W]), .in_tmax_i(eray[7*W+KW-W +: W]), .in_tag_i(1'b0),
          .out_valid_o(o_valid), .out_ready_i(1'b1), .out_exit_o(o_exit), .out_t_o(o_tk[KW-1 -: W]),
          .out_den_o(o_den), .out_tag_o(o_tag0_unused));
        // Wald's t as the key: F's value, the extension bits zero (hls::t_key); its tmax is the
        // key's top bits (a Wald frame's keys are F values).
        if (KW > W) begin : g_ext
          assign o_tk[KW-W-1:0] = {(KW-W){1'b0}};
          wire unused_ext = ^eray[7*W +: KW-W];
        end
      end
      // The result as the trv takes it: {hit, slot, {1, t, den, pos, id, k, nu, nv, nd}}.
      wire [SLOT_BITS-1:0] t_slot = o_tag[TW-1 -: SLOT_BITS];
      wire          t_skip = o_tag[TW-1-SLOT_BITS];
      wire [31:0]   t_pos  = o_tag[3*W+2+32 +: 32];
      wire          t_hit  = !t_skip && (o_exit == 3'd0);
      wire [BW-1:0] t_rec  = t_hit ? {1'b1, o_tk, o_den, t_pos, o_tag[3*W +: 34], o_tag[0 +: 3*W]}
                                   : {1'b1, {(KW+W){1'b0}}, t_pos, {(34+3*W){1'b0}}};
      assign g_out_v[u] = o_valid;
      assign g_out_r[u*RESW +: RESW] = {t_hit, t_slot, t_rec};
    end
  endgenerate

  // This cycle's misses, registered: they go back to the queue in the next cycle (3.).
  reg  [IST-1:0]           mq_v;
  reg  [IST*SLOT_BITS-1:0] mq_slot;
  reg  [IST*32-1:0]        mq_pb, mq_tri;
  reg  [IST*OW-1:0]        mq_off;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) mq_v <= {IST{1'b0}};
    else mq_v <= miss;
  always @(posedge clk_i) begin
    mq_slot <= ray_slot_o;
    mq_pb   <= u_pb;
    mq_off  <= u_off;
    mq_tri  <= u_tri;
  end

  // Counts of this cycle's pops (a prefix of the units), misses, hits and tests, and of the
  // misses of the cycle before.
  reg [5:0] npop, nmiss, nhit, ntest, nmq;
  integer a;
  always @* begin
    npop = 6'd0; nmiss = 6'd0; nhit = 6'd0; ntest = 6'd0; nmq = 6'd0;
    for (a = 0; a < IST; a = a + 1) begin
      npop  = npop + {5'd0, take[a]};
      nmiss = nmiss + {5'd0, miss[a]};
      nhit  = nhit + {5'd0, hit[a]};
      ntest = ntest + {5'd0, test[a]};
      nmq   = nmq + {5'd0, mq_v[a]};
    end
  end
  wire [15:0] npop16 = {10'd0, npop};
  wire [15:0] left = {{(15-QBITS){1'b0}}, cnt_q} - npop16 + {10'd0, nmq};
  // The room for the trv's hand-offs of this cycle: the queue's at the cycle's start less the
  // misses on their way back (this cycle's pops do not make room before the next; this cycle's
  // misses come back in the next): registers' values, so no path runs from the triangle cache's
  // answer into the trv.
  assign room_o = qcap_i - count_o;

  // ---- 3. pushes: the misses in unit order, then each pipe's run --------------------------------
  // The misses go to tail .. tail + nmq - 1, pipe p's run from base[p].
  wire [QBITS-1:0] tail = head_q + cnt_q[QBITS-1:0];
  reg  [(PIPES+1)*QBITS-1:0] base;   // where pipe p's run starts: [p*QBITS +: QBITS]
  reg  [15:0]                pushes, nb;
  integer p;
  always @* begin
    base = {((PIPES+1)*QBITS){1'b0}};
    base[0 +: QBITS] = tail + nmq[QBITS-1:0];
    pushes = 16'd0;  // the trv's entries (the misses are in left already)
    for (p = 0; p < PIPES; p = p + 1) begin
      nb = {10'd0, hin_n_i[p*6 +: 6]};
      base[(p+1)*QBITS +: QBITS] = base[p*QBITS +: QBITS] + nb[QBITS-1:0];
      pushes = pushes + nb;
    end
  end

  wire [15:0] cnt_next = left + pushes;
  wire        unused_cnt = ^cnt_next[15:QBITS+1];             // < 2^QBITS entries

  // ---- 1. the delay ring: results due hl_i cycles after their access (hl_i - ENTRY_REG after
  // they leave ist.v) -----------------------------------------------------------------------------
  localparam [31:0]   ER32 = ENTRY_REG;
  wire [7:0]          hd = hl_i - ER32[7:0];  // hl_i >= ENTRY_REG (the binding checks)
  reg  [IST-1:0]      ring_v [0:HN-1];
  reg  [IST*RESW-1:0] ring_r [0:HN-1];
  // The entry due in the next cycle is read in this one into out_*_q (the next cycle's results
  // start at registers, not at now_i's slot decode; with hd 1 it is this cycle's ist.v result,
  // written to the ring in the same edge).
  wire [HLBITS-1:0]   rd1 = now_i[HLBITS-1:0] + {{(HLBITS-1){1'b0}}, 1'b1};
  wire [HLBITS-1:0]   wr = now_i[HLBITS-1:0] + hd[HLBITS-1:0];
  wire                bypass = (hd == 8'd0);
  wire                next_now = (hd == 8'd1);
  wire                unused_hd = ^hd;
  reg  [IST-1:0]      out_v_q;
  reg  [IST*RESW-1:0] out_r_q;
  wire [IST-1:0]      out_v = bypass ? g_out_v : out_v_q;
  wire [IST*RESW-1:0] out_r = bypass ? g_out_r : out_r_q;
  generate
    for (u = 0; u < IST; u = u + 1) begin : g_res
      assign res_valid_o[u] = out_v[u];
      assign {res_hit_o[u], res_slot_o[u*SLOT_BITS +: SLOT_BITS], res_rec_o[u*BW +: BW]} =
          out_r[u*RESW +: RESW];
    end
  endgenerate
  // Tests in ist.v plus results in the ring.
  reg [15:0] pend_q;
  reg [5:0]  nout;
  always @* begin
    nout = 6'd0;
    for (a = 0; a < IST; a = a + 1) nout = nout + {5'd0, out_v[a]};
  end
  assign busy_o = (pend_q != 16'd0) || (|mq_v);

  // ---- state ------------------------------------------------------------------------------------
  // The counters: the sums of the cycles before plus the last cycle's registered increments.
  reg [17:0]   inc_q;   // {tests, misses, hits}
  reg [3*64-1:0] sum_q;
  assign cnt_busy_o  = sum_q[0 +: 64] + {58'd0, inc_q[0 +: 6]};
  assign cnt_miss_o  = sum_q[64 +: 64] + {58'd0, inc_q[6 +: 6]};
  assign cnt_tests_o = sum_q[128 +: 64] + {58'd0, inc_q[12 +: 6]};
  integer j;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head_q      <= {QBITS{1'b0}};
      cnt_q       <= {(QBITS+1){1'b0}};
      pend_q      <= 16'd0;
      inc_q       <= 18'd0;
      sum_q       <= {(3*64){1'b0}};
      for (j = 0; j < HN; j = j + 1) ring_v[j] <= {IST{1'b0}};
      out_v_q     <= {IST{1'b0}};
    end else begin
      head_q <= head_q + npop16[QBITS-1:0];
      cnt_q  <= cnt_next[QBITS:0];
      pend_q <= pend_q + {10'd0, nhit} - {10'd0, nout};
      inc_q       <= {ntest, nmiss, nhit};
      sum_q       <= {cnt_tests_o, cnt_miss_o, cnt_busy_o};
      out_v_q <= {IST{1'b0}};
      if (!bypass) begin
        out_v_q    <= next_now ? g_out_v : ring_v[rd1];
        ring_v[rd1] <= {IST{1'b0}};
        ring_v[wr] <= g_out_v;
      end
    end
  end

  // The results themselves: a memory of HN words, one write and one (registered) read per cycle,
  // meaningful where ring_v is set (written in reset too: harmless, ring_v is cleared).
  always @(posedge clk_i) begin
    if (!bypass) ring_r[wr] <= g_out_r;
    out_r_q <= next_now ? g_out_r : ring_r[rd1];
  end

  // The head window's refill: entry head_q + npop + u after this edge (no reset: read only below
  // cnt_q, and refilled at every edge).
  generate
    for (u = 0; u < IST; u = u + 1) begin : g_window
      localparam [QBITS-1:0] UQ = u;
      wire [QBITS-1:0] w_at = head_q + npop16[QBITS-1:0] + UQ;
      always @(posedge clk_i) begin
        w_slot_q[u]  <= n_slot[w_at];
        w_pb_q[u]    <= n_pb[w_at];
        w_off_q[u]   <= n_off[w_at];
        w_tri_q[u]   <= n_tri[w_at];
        w_ready_q[u] <= n_ready[w_at];
      end
    end
  endgenerate

  // ---- the queue's registers: each entry written from one of this cycle's push sources ---------
  // Pipe p's run rotated: element i of g_rot[p] is the triangle index of word (i - base_p) mod J
  // (J: WORDS rounded up to a power of two, at most the queue: a run is no longer than the
  // queue's room); the entry taking it stores off = that word's place. The misses compacted (element k the k-th
  // of the registered misses in unit order) and rotated alike by the tail: element i of mrot is
  // miss (i - tail) mod MJ. So every entry takes one source per pipe and one for the misses, each
  // a fixed wire.
  localparam integer MQW = SLOT_BITS + 32 + OW + 32;            // a miss: {slot, pb, off, tri}
  localparam integer MB  = (IST > 1) ? $clog2(IST) : 0;
  localparam integer MJB = (MB < QBITS) ? MB : QBITS;
  localparam integer MJ  = 1 << MJB;
  genvar gp, gi, ge;
  wire [PIPES*J*32-1:0] rot;   // pipe p's element i: [(p*J + i)*32 +: 32]
  generate
    for (gp = 0; gp < PIPES; gp = gp + 1) begin : g_rot
      wire [J*32-1:0] run;   // element i: word i
      for (gi = 0; gi < J; gi = gi + 1) begin : g_in
        if (gi < WORDS) begin : g_w
          assign run[gi*32 +: 32] = hin_words_i[(gp*WORDS + gi)*32 +: 32];
        end else begin : g_z
          assign run[gi*32 +: 32] = 32'd0;
        end
      end
      // A barrel rotator: level l moves every element 2^l up (modulo J) if bit l of the start is set.
      reg [J*32-1:0] r;
      integer l;
      always @* begin
        r = run;
        for (l = 0; l < JB; l = l + 1)
          if (base[gp*QBITS + l]) r = (r << ((1 << l) * 32)) | (r >> ((J - (1 << l)) * 32));
      end
      assign rot[gp*J*32 +: J*32] = r;
    end
  endgenerate

  reg [MJ*MQW-1:0] mrot;   // element i: [i*MQW +: MQW]
  reg [MB:0]       mk;     // misses before unit m
  integer mi, ml;
  always @* begin
    mrot = {(MJ*MQW){1'b0}};
    mk = {(MB+1){1'b0}};
    for (mi = 0; mi < IST; mi = mi + 1) begin
      // Unit mi's miss is element mk: OR'd in (the elements' sources are disjoint).
      mrot = mrot | ({(MJ*MQW){mq_v[mi]}} &
                     ({{((MJ-1)*MQW){1'b0}}, mq_slot[mi*SLOT_BITS +: SLOT_BITS], mq_pb[mi*32 +: 32],
                       mq_off[mi*OW +: OW], mq_tri[mi*32 +: 32]} << (mk * MQW)));
      mk = mk + {{MB{1'b0}}, mq_v[mi]};
    end
    for (ml = 0; ml < MJB; ml = ml + 1)
      if (tail[ml]) mrot = (mrot << ((1 << ml) * MQW)) | (mrot >> ((MJ - (1 << ml)) * MQW));
  end

  generate
    for (ge = 0; ge < QN; ge = ge + 1) begin : g_q
      localparam [QBITS-1:0] E = ge;
      reg [SLOT_BITS-1:0] slot_q;
      reg [31:0]          pb_q, tri_q, ready_q;
      reg [OW-1:0]        off_q;
      // The sources are disjoint (consecutive ranges of one cycle's pushes): their values OR'd.
      reg                 we;
      reg [SLOT_BITS-1:0] w_slot;
      reg [31:0]          w_pb, w_tri, w_ready;
      reg [OW-1:0]        w_off;
      reg [QBITS-1:0]     d;
      reg                 sel;
      integer             pp;
      always @* begin
        d = E - tail;
        sel = ({{(16-QBITS){1'b0}}, d} < {10'd0, nmq});
        we = sel;
        {w_slot, w_pb, w_off, w_tri} = {MQW{sel}} & mrot[(ge % MJ)*MQW +: MQW];
        w_ready = {32{sel}} & (now_i + 32'd1);
        for (pp = 0; pp < PIPES; pp = pp + 1) begin
          d = E - base[pp*QBITS +: QBITS];
          sel = ({{(16-QBITS){1'b0}}, d} < {10'd0, hin_n_i[pp*6 +: 6]});
          we = we | sel;
          w_slot  = w_slot | ({SLOT_BITS{sel}} & hin_slot_i[pp*SLOT_BITS +: SLOT_BITS]);
          w_pb    = w_pb | ({32{sel}} & hin_pos_i[pp*32 +: 32]);
          w_off   = w_off | ({OW{sel}} & d[OW-1:0]);   // d < the run's length <= J
          w_tri   = w_tri | ({32{sel}} & rot[(pp*J + ge % J)*32 +: 32]);
          w_ready = w_ready | ({32{sel}} & hin_ready_i[pp*32 +: 32]);
        end
      end
      always @(posedge clk_i)
        if (we) begin
          slot_q  <= w_slot;
          pb_q    <= w_pb;
          off_q   <= w_off;
          tri_q   <= w_tri;
          ready_q <= w_ready;
        end
      // The entry after this edge (the head window's refill reads it).
      assign n_slot[ge]  = we ? w_slot : slot_q;
      assign n_pb[ge]    = we ? w_pb : pb_q;
      assign n_off[ge]   = we ? w_off : off_q;
      assign n_tri[ge]   = we ? w_tri : tri_q;
      assign n_ready[ge] = we ? w_ready : ready_q;
    end
  endgenerate

endmodule
