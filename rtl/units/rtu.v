// rtu - one ray-tracing unit whole: rgu -> trv <-> ist -> hit (-> rgu for shadow rays), the three
// AS caches (node, list, triangle) and the fill path with the VTU (vtu_unit). The RTL view of
// systemc/rtu.h: every unit is the module that `raycore simulate --rtl <unit>` binds into the
// running frame (rgu_unit, trv_unit, ist_unit, hit_unit, ascache, vtu.v), wired here as the cycle
// model's channels connect them, plus the two pieces those bindings keep in C++:
//   - the ray slots' pixel and skip id (slot_ram; the ray, its kind, the ist's tmax and the best
//     record are trv_unit's slot arrays, read through its rd_* ports, READS = 1);
//   - the fill path (vtu_unit: the MSHR line buffers, records through vtu.v, the fills).
// Outside, in the chip (chip.v): membus_if and the memory. The frame buffer stays the host's: each
// ray leaving the hit unit is put out on px_* (its pixel, kind, best record and hit.v's results)
// for the host's pixel write and shade, as systemc/hit.h's finish() takes them.
//
// Per cycle, as Rtu::tick orders the units: the fills (vtu_unit); the hit unit's ray leaving
// (hit_unit out_*: its slot freed, or the shadow ray kept in it and handed to the rgu in the same
// cycle); the ist (ist_unit: queue heads, triangle-cache reads, results leaving) and its results
// into the trv (trv_unit res_*); the trv's list stage and pipes (cache reads, hand-offs to the ist,
// finished rays to the hit unit's queue at now + lat_i); the rgu's ray into the trv (a shadow ray from the hit
// unit's out_ray_o, or the next primary ray in the free slot that rgu_unit picks). The trv's
// passes read the node cache (one port per pipe, the node word at the byte read), its list stage
// the list cache (one port per pipe, up to WORDS 32-bit words from the byte read on); no access's
// address depends on a cache's answer (a list stage's valid on the earlier stages' line presence).
//
// now: the RTU's cycle counter from reset, the units' ready cycles are compared with it.
// Counters (cnt_sel_i -> cnt_o, systemc/config.h RtuStats): 0 now, 1 trv_busy, 2 trv_node_miss,
// 3 trv_list_miss, 4 trv_ist_full, 5 inner_steps, 6 leaf_visits, 7 pops, 8 list_steps,
// 9 trv_fused, 10 stack_max, 11 ist_busy, 12 ist_tri_miss, 13 tri_tests, 14 hit_busy,
// 15 primary_rays, 16 shadow_rays, 17 rgu_stall_no_slot, 18 vtu_busy, then per cache (node 19,
// list 24, triangle 29): hits, misses, mshr_merges, mshr_full, fills; set_full per cache (node 34,
// list 35, triangle 36); 37 vtu_paired, 38 vtu_fill_waits; others 0.
//
// Parameters: the cycle model's defaults (systemc/config.h SimConfig) for FP24: 128 slots (96 rays
// in flight), 64 stack entries, 5 trv pipes, 4 ist units, 16 list words per read, an ist queue of
// up to 32 entries (the model's ist_queue: the queue never holds more than its capacity, misses on
// their way back included), caches of 32 / 8 / 32 KB (4 ways, 64-byte lines, 8 MSHRs each). SPAWNS (the
// hit unit's spawn strategies, hit.v) 1: the defaults' --spawn none alone, as every other parameter
// is the defaults' (the chip is built for the strategy it runs; chip.v and make chip take SPAWNS
// from the frame's --spawn). `--rtl rtu`'s one Verilated model is built with SPAWNS 127, all seven,
// so that it runs every --spawn (rtl/units/rtu.cmake); `make area-rtu` synthesises both.
// lint: also SLOT_BITS=4 DEPTH=8 PIPES=2 IST=2 WORDS=4 QBITS=3 NODE_SETS=4 LIST_SETS=2 TRI_SETS=4 WAYS=2 MSHRS=2 NODE_LB=32 LIST_LB=16 TRI_LB=32
// lint: also SLOT_BITS=4 DEPTH=8 PIPES=2 IST=2 WORDS=4 QBITS=3 NODE_SETS=4 LIST_SETS=2 TRI_SETS=4 WAYS=2 MSHRS=2 NODE_LB=32 LIST_LB=16 TRI_LB=32 BEAT_REG=1
module rtu #(
  parameter integer EXP_BITS   = 7,
  parameter integer MAN_BITS   = 16,
  parameter integer RNE        = 0,
  parameter integer RAYCORE    = 0,
  parameter integer STAGES     = 2,
  parameter integer SLOT_BITS  = 7,
  parameter integer DEPTH      = 64,
  parameter integer PIPES      = 5,
  parameter integer IST        = 4,
  parameter integer WORDS      = 16,
  parameter integer QBITS      = 5,
  parameter integer HLBITS     = 4,
  parameter integer COORD_BITS = 16,
  parameter integer TILE_BITS  = 3,
  parameter integer RTU_BITS   = 8,
  parameter integer NODE_SETS  = 128,
  parameter integer LIST_SETS  = 32,
  parameter integer TRI_SETS   = 128,
  parameter integer WAYS       = 4,
  parameter integer NODE_LB    = 64,
  parameter integer LIST_LB    = 64,
  parameter integer TRI_LB     = 0,   // 0: whole records nearest 64 bytes (the model's)
  parameter integer MSHRS      = 8,
  parameter integer LINE_W     = 26,
  parameter integer BEAT_BYTES = 16,  // the memory's beats
  parameter integer L2_BEAT    = 32,  // the L2's beats
  parameter integer LEN_BITS   = 12,
  parameter integer BEAT_REG   = 0,   // 1: beat_*_i and l2_*_i are the next cycle's, registered here
  parameter integer SPAWNS     = 1,   // the hit unit's spawn strategies (bit s: hls::Spawn s; 127: all)
  // Derived (not to be overridden).
  parameter integer W_     = 1 + EXP_BITS + MAN_BITS,
  parameter integer CB_    = (W_ <= 24) ? 3 : 4,
  parameter integer IDOFF_ = ((9 * CB_ + 1 + 3) / 4) * 4,
  parameter integer RB_    = ((IDOFF_ + 4 + 15) / 16) * 16,
  parameter integer MB_    = (MSHRS > 1) ? $clog2(MSHRS) : 1
) (
  input  wire                        clk_i,
  input  wire                        rst_ni,
  // ---- frame registers (static per frame) -------------------------------------------------------
  input  wire                        start_i,       // the rgu starts (rgu.v's start_i)
  // rgu: the camera {o xyz, d00 xyz, dx xyz, dy xyz} (o x highest), the frame, this RTU's index.
  input  wire [12*W_-1:0]            cam_i,
  input  wire [COORD_BITS-1:0]       width_i,
  input  wire [COORD_BITS-1:0]       height_i,
  input  wire [RTU_BITS-1:0]         rtu_i,
  input  wire [RTU_BITS-1:0]         rtus_i,
  input  wire [SLOT_BITS:0]          slots_i,       // ray slots in use (rays in flight)
  input  wire [W_-1:0]               tmin_i,
  // trv (trv_unit's configuration).
  input  wire [15:0]                 trv_lat_i,
  input  wire [15:0]                 node_hl_i,
  input  wire [15:0]                 list_hl_i,
  input  wire [4:0]                  pipes_i,
  input  wire                        fuse_i,
  input  wire                        any_hit_i,
  input  wire                        empty_i,
  input  wire [6:0]                  depth_i,
  input  wire [6:0]                  widen_i,
  input  wire [6*W_-1:0]             box_i,         // {hi z y x, lo z y x}
  // ist (ist_unit's).
  input  wire [W_-1:0]               eps_i,
  input  wire [W_-1:0]               one_eps_i,
  input  wire [15:0]                 qcap_i,
  input  wire [7:0]                  tri_hl_i,
  input  wire [4:0]                  ist_units_i,
  // hit (hit_unit's): the light {z, y, x}, the spawn strategy and its registers.
  input  wire [3*W_-1:0]             light_i,
  input  wire [2:0]                  strategy_i,
  input  wire                        segment_i,
  input  wire                        all_i,
  input  wire [31:0]                 back_i,
  input  wire [W_-1:0]               scale_i,
  input  wire [W_-1:0]               fixed_i,
  input  wire [W_-1:0]               slab_scale_i,
  // vtu: on, the camera {z, y, x} it translates by, the image's record counts.
  input  wire                        vtu_on_i,
  input  wire [3*W_-1:0]             vtu_cam_i,
  input  wire [31:0]                 node_count_i,
  input  wire [31:0]                 tri_count_i,
  // ---- memory: the caches' line requests (node 0, list 1, triangle 2) and the data beats --------
  output wire [2:0]                  req_valid_o,
  input  wire [2:0]                  req_ready_i,
  output wire [3*LINE_W-1:0]         req_line_o,    // line index within the cache's region
  output wire [3*MB_-1:0]            req_tag_o,     // the MSHR
  input  wire [2:0]                  beat_valid_i,  // one-hot by cache (BEAT_REG: next cycle's)
  input  wire [MB_-1:0]              beat_tag_i,
  input  wire [LEN_BITS-1:0]         beat_idx_i,
  input  wire                        beat_last_i,
  input  wire [8*BEAT_BYTES-1:0]     beat_data_i,
  input  wire [2:0]                  l2_valid_i,    // the L2's beats (membus_l2's l2_*), as beat_*
  input  wire [MB_-1:0]              l2_tag_i,
  input  wire [LEN_BITS-1:0]         l2_idx_i,
  input  wire                        l2_last_i,
  input  wire [8*L2_BEAT-1:0]        l2_data_i,
  // ---- the ray leaving the hit unit (the host's pixel write) ------------------------------------
  output wire                        px_valid_o,
  output wire [2*COORD_BITS-1:0]     px_pixel_o,
  output wire                        px_shadow_o,   // a shadow ray (else the primary)
  output wire                        px_found_o,    // it hit a triangle
  output wire                        px_spawn_o,    // a primary hit whose slot holds its shadow ray
  output wire [67+5*W_-1:0]          px_best_o,     // {found, t, den, pos, id, k, nu, nv, nd}
  output wire [3*W_-1:0]             px_h_o,        // the hit point {z, y, x}
  output wire                        px_front_o,
  output wire [W_-1:0]               px_dens_o,
  output wire [11*W_-1:0]            px_ray_o,      // the shadow ray {o xyz, d xyz, inv xyz, tmin, tmax}
  // ---- status -----------------------------------------------------------------------------------
  output wire                        done_o,        // every primary ray issued, every slot free
  output wire                        primaries_o,   // primary rays still to come (rgu.v busy)
  output wire                        err_o,         // a ray needed more than depth_i stack entries
  input  wire [5:0]                  cnt_sel_i,
  output reg  [63:0]                 cnt_o
);

  localparam integer TLB  = (TRI_LB != 0) ? TRI_LB : ((64 + RB_ / 2) / RB_) * RB_;
  localparam integer W    = W_;
  localparam integer BW   = 67 + 5 * W;
  localparam integer RPL  = TLB / RB_;             // triangle records per line
  localparam integer NLB  = $clog2(NODE_LB);
  localparam integer LLB  = $clog2(LIST_LB);
  localparam [31:0]  LIST_WORDS = LIST_LB / 4;     // the list stage's words per line
  localparam integer MAXLB = (NODE_LB > LIST_LB) ? ((NODE_LB > TLB) ? NODE_LB : TLB)
                                                 : ((LIST_LB > TLB) ? LIST_LB : TLB);

  // ---- the cycle counter ------------------------------------------------------------------------
  reg [31:0] now_q;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) now_q <= 32'd0;
    else         now_q <= now_q + 32'd1;
  end

  // ---- the frame registers --------------------------------------------------------------------
  // The frame's configuration, from the pins into registers at every edge (no reset, no enable):
  // the chip sets the pins before reset and holds them through the frame, so the units see only
  // registers, never a pin (no path from outside into a datapath). The host clocks the RTU once
  // while it holds the reset (systemc/rtu_rtl.cpp, tb/rtl/tb_chip.v) to load them.
  reg  [12*W_-1:0]            cam_q;
  reg  [COORD_BITS-1:0]       width_q;
  reg  [COORD_BITS-1:0]       height_q;
  reg  [RTU_BITS-1:0]         rtu_q;
  reg  [RTU_BITS-1:0]         rtus_q;
  reg  [SLOT_BITS:0]          slots_q;
  reg  [W_-1:0]               tmin_q;
  reg  [15:0]                 trv_lat_q;
  reg  [15:0]                 node_hl_q;
  reg  [15:0]                 list_hl_q;
  reg  [4:0]                  pipes_q;
  reg                         fuse_q;
  reg                         any_hit_q;
  reg                         empty_q;
  reg  [6:0]                  depth_q;
  reg  [6:0]                  widen_q;
  reg  [6*W_-1:0]             box_q;
  reg  [W_-1:0]               eps_q;
  reg  [W_-1:0]               one_eps_q;
  reg  [15:0]                 qcap_q;
  reg  [7:0]                  tri_hl_q;
  reg  [4:0]                  ist_units_q;
  reg  [3*W_-1:0]             light_q;
  reg  [2:0]                  strategy_q;
  reg                         segment_q;
  reg                         all_q;
  reg  [31:0]                 back_q;
  reg  [W_-1:0]               scale_q;
  reg  [W_-1:0]               fixed_q;
  reg  [W_-1:0]               slab_scale_q;
  reg                         vtu_on_q;
  reg  [3*W_-1:0]             vtu_cam_q;
  reg  [31:0]                 node_count_q;
  reg  [31:0]                 tri_count_q;
  always @(posedge clk_i) begin
    cam_q <= cam_i;
    width_q <= width_i;
    height_q <= height_i;
    rtu_q <= rtu_i;
    rtus_q <= rtus_i;
    slots_q <= slots_i;
    tmin_q <= tmin_i;
    trv_lat_q <= trv_lat_i;
    node_hl_q <= node_hl_i;
    list_hl_q <= list_hl_i;
    pipes_q <= pipes_i;
    fuse_q <= fuse_i;
    any_hit_q <= any_hit_i;
    empty_q <= empty_i;
    depth_q <= depth_i;
    widen_q <= widen_i;
    box_q <= box_i;
    eps_q <= eps_i;
    one_eps_q <= one_eps_i;
    qcap_q <= qcap_i;
    tri_hl_q <= tri_hl_i;
    ist_units_q <= ist_units_i;
    light_q <= light_i;
    strategy_q <= strategy_i;
    segment_q <= segment_i;
    all_q <= all_i;
    back_q <= back_i;
    scale_q <= scale_i;
    fixed_q <= fixed_i;
    slab_scale_q <= slab_scale_i;
    vtu_on_q <= vtu_on_i;
    vtu_cam_q <= vtu_cam_i;
    node_count_q <= node_count_i;
    tri_count_q <= tri_count_i;
  end

  // ---- wires between the units ------------------------------------------------------------------
  // rgu -> trv, slot_ram
  wire                 r_valid, r_shadow, rgu_busy;
  wire [SLOT_BITS-1:0] r_slot;
  wire [11*W-1:0]      r_ray;
  wire [2*COORD_BITS-1:0] r_pixel;
  wire [SLOT_BITS:0]   free_count;
  wire [63:0]          c_primary, c_shadow, c_stall;
  // hit -> rgu, slot_ram, px
  wire                 h_valid, h_shadow, h_found, h_free, h_spawn, h_front;
  wire [SLOT_BITS-1:0] h_slot;
  wire [3*W-1:0]       h_h;
  wire [W-1:0]         h_dens;
  wire [11*W-1:0]      h_ray;
  wire [31:0]          h_skip;
  wire                 h_head_valid, h_busy;
  wire [31:0]          h_head_ready;
  wire [63:0]          c_hit_busy;
  wire                 h_rd_valid;
  wire [SLOT_BITS-1:0] h_rd_slot;
  wire [1+BW+6*W-1:0]  h_rd;
  // trv <-> ist, trv -> hit, trv <-> caches
  wire [PIPES-1:0]     t_go, t_fin;
  wire [PIPES*SLOT_BITS-1:0] t_slot, t_fin_slot, t_ist_slot;
  wire [31:0]          t_fin_ready;
  wire [PIPES*BW-1:0]  t_best;
  wire [PIPES*6-1:0]   t_ist_n;
  wire [PIPES*32-1:0]  t_ist_pos, t_ist_ready;
  wire [PIPES*W-1:0]   t_ist_tmax;
  wire [PIPES*32*WORDS-1:0] t_ist_words;
  wire [PIPES-1:0]     t_nacc_valid, t_lacc_valid, n_hit, l_hit;
  wire [PIPES*32-1:0]  t_nacc_byte, t_lacc_byte;
  wire [PIPES*64-1:0]  t_node_word;
  wire [PIPES*32*WORDS-1:0] t_list_words;
  wire                 t_head_valid, t_pend;
  wire [31:0]          t_head_ready;
  wire [63:0]          c_trv_busy, c_node_miss, c_list_miss, c_ist_full, c_inner, c_leaf, c_pops,
                       c_list_steps, c_fused;
  wire [6:0]           c_stack_max;
  wire [IST*SLOT_BITS-1:0] i_ray_slot;
  wire [IST*8*W-1:0]   i_ray_trv;
  wire [IST*32-1:0]    i_skip;
  wire [IST-1:0]       i_acc_valid, i_rsp_hit, i_res_valid, i_res_hit;
  wire [IST*32-1:0]    i_acc_line;
  wire [IST*8*TLB-1:0] i_rsp_data;
  wire [IST*SLOT_BITS-1:0] i_res_slot;
  wire [IST*BW-1:0]    i_res_rec;
  wire [15:0]          i_room, i_count;
  wire                 i_head_valid, i_busy;
  wire [31:0]          i_head_ready;
  wire [63:0]          c_ist_busy, c_ist_miss, c_tests;
  wire [BW-1:0]        px_best;

  // ---- rgu --------------------------------------------------------------------------------------
  rgu_unit #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE),
             .STAGES(STAGES), .COORD_BITS(COORD_BITS), .TILE_BITS(TILE_BITS),
             .RTU_BITS(RTU_BITS), .SLOT_BITS(SLOT_BITS)) u_rgu (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .cam_o_x_i(cam_q[11*W +: W]), .cam_o_y_i(cam_q[10*W +: W]), .cam_o_z_i(cam_q[9*W +: W]),
    .cam_d00_x_i(cam_q[8*W +: W]), .cam_d00_y_i(cam_q[7*W +: W]), .cam_d00_z_i(cam_q[6*W +: W]),
    .cam_dx_x_i(cam_q[5*W +: W]), .cam_dx_y_i(cam_q[4*W +: W]), .cam_dx_z_i(cam_q[3*W +: W]),
    .cam_dy_x_i(cam_q[2*W +: W]), .cam_dy_y_i(cam_q[W +: W]), .cam_dy_z_i(cam_q[0 +: W]),
    .width_i(width_q), .height_i(height_q), .rtu_i(rtu_q), .rtus_i(rtus_q), .tmin_i(tmin_q),
    .slots_i(slots_q), .start_i(start_i), .busy_o(rgu_busy),
    .free_valid_i(h_free), .free_slot_i(h_slot), .shadow_valid_i(h_spawn),
    .shadow_slot_i(h_slot),
    .out_valid_o(r_valid), .out_slot_o(r_slot), .out_shadow_o(r_shadow), .out_ray_o(r_ray),
    .out_pixel_o(r_pixel), .free_count_o(free_count),
    .cnt_primary_o(c_primary), .cnt_shadow_o(c_shadow), .cnt_stall_o(c_stall));

  // ---- the slots' pixel and skip id -------------------------------------------------------------
  slot_ram #(.SLOT_BITS(SLOT_BITS), .IST(IST), .COORD_BITS(COORD_BITS)) u_slots (
    .clk_i(clk_i),
    .pri_valid_i(r_valid && !r_shadow), .pri_slot_i(r_slot), .pri_pixel_i(r_pixel),
    .shd_valid_i(h_spawn), .shd_slot_i(h_slot), .shd_skip_id_i(h_skip),
    .ist_slot_i(i_ray_slot), .ist_skip_id_o(i_skip),
    .px_slot_i(h_slot), .px_pixel_o(px_pixel_o));

  // ---- trv --------------------------------------------------------------------------------------
  // A shadow ray comes from the hit unit in this cycle (its out_ray_o); a primary ray from rgu.v.
  trv_unit #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE),
             .SLOT_BITS(SLOT_BITS), .DEPTH(DEPTH), .PIPES(PIPES), .IST(IST), .WORDS(WORDS),
             .READS(1)) u_trv (
    .clk_i(clk_i), .rst_ni(rst_ni), .now_i(now_q),
    .lat_i(trv_lat_q), .node_hl_i(node_hl_q), .list_hl_i(list_hl_q),
    .lwords_i(LIST_WORDS[6:0]), .pipes_i(pipes_q),
    .fuse_i(fuse_q), .any_hit_i(any_hit_q), .empty_i(empty_q), .depth_i(depth_q),
    .widen_i(widen_q), .box_i(box_q),
    .in_valid_i(r_valid), .in_slot_i(r_slot), .in_shadow_i(r_shadow),
    .in_ray_i(r_shadow ? h_ray : r_ray),
    .res_valid_i(i_res_valid), .res_slot_i(i_res_slot), .res_hit_i(i_res_hit),
    .res_rec_i(i_res_rec), .room_i(i_room),
    .nacc_valid_o(t_nacc_valid), .nacc_byte_o(t_nacc_byte), .nrsp_hit_i(n_hit),
    .nrsp_node_i(t_node_word), .lacc_valid_o(t_lacc_valid), .lacc_byte_o(t_lacc_byte),
    .lrsp_hit_i(l_hit), .lrsp_data_i(t_list_words),
    .go_o(t_go), .slot_o(t_slot), .fin_o(t_fin), .fin_slot_o(t_fin_slot),
    .fin_ready_o(t_fin_ready), .best_o(t_best), .ist_n_o(t_ist_n),
    .ist_slot_o(t_ist_slot), .ist_pos_o(t_ist_pos), .ist_ready_o(t_ist_ready), .ist_tmax_o(t_ist_tmax),
    .ist_words_o(t_ist_words),
    .rd_ist_slot_i(i_ray_slot), .rd_ist_o(i_ray_trv), .rd_hit_slot_i(h_rd_slot),
    .rd_hit_o(h_rd), .rd_px_slot_i(h_slot), .rd_px_best_o(px_best),
    .head_valid_o(t_head_valid), .head_ready_o(t_head_ready), .pend_o(t_pend),
    .cnt_busy_o(c_trv_busy), .cnt_node_miss_o(c_node_miss), .cnt_list_miss_o(c_list_miss),
    .cnt_ist_full_o(c_ist_full), .cnt_inner_o(c_inner), .cnt_leaf_o(c_leaf), .cnt_pops_o(c_pops),
    .cnt_list_steps_o(c_list_steps), .cnt_fused_o(c_fused), .stack_max_o(c_stack_max),
    .err_o(err_o));

  // The pipes' finished rays (their outcomes', a cycle after the pass), all with one ready cycle.
  wire [PIPES*32-1:0] fin_ready;
  genvar gp;
  generate
    for (gp = 0; gp < PIPES; gp = gp + 1) begin : g_pipe
      assign fin_ready[gp*32 +: 32] = t_fin_ready;
    end
  endgenerate
  // The hand-off's tmax and the finished ray's best record are in trv_unit's slots already (read
  // through rd_*); the queue's head is the cycle model's next event.
  wire unused_trv = ^{t_go, t_slot, t_ist_tmax, t_best, t_head_valid, t_head_ready, t_pend};

  // ---- the node and list caches: the trv's accesses, in port order ------------------------------
  // One port per pipe in each: the node cache takes pipe p's pass's node read, the list cache list
  // stage p's list read. A port's response is the presence and bytes of its line whether or not
  // it accesses, for the access the trv looks at.
  wire [PIPES*8*NODE_LB-1:0] n_data;
  wire [PIPES*8*LIST_LB-1:0] l_data;
  wire [PIPES*LINE_W-1:0]  n_line, l_line;
  genvar ga;
  generate
    for (ga = 0; ga < PIPES; ga = ga + 1) begin : g_acc
      wire [31:0] nbyte = t_nacc_byte[ga*32 +: 32];
      wire [31:0] lbyte = t_lacc_byte[ga*32 +: 32];
      wire [31:0] nl32  = nbyte >> NLB;
      wire [31:0] ll32  = lbyte >> LLB;
      assign n_line[ga*LINE_W +: LINE_W] = nl32[LINE_W-1:0];
      assign l_line[ga*LINE_W +: LINE_W] = ll32[LINE_W-1:0];
      wire unused_line = ^{nl32[31:LINE_W], ll32[31:LINE_W]};
      // The node word at the byte read (node reads are 8-byte aligned).
      wire [8*NODE_LB-1:0] nw = n_data[ga*8*NODE_LB +: 8*NODE_LB] >> {nbyte[NLB-1:0], 3'b000};
      assign t_node_word[ga*64 +: 64] = nw[63:0];
      wire unused_nw = ^nw[8*NODE_LB-1:64];
      // The list words from the byte on (to the line's end; WORDS >= the line's words).
      wire [32*WORDS+8*LIST_LB-1:0] wide = {{(32*WORDS){1'b0}}, l_data[ga*8*LIST_LB +: 8*LIST_LB]};
      wire [32*WORDS+8*LIST_LB-1:0] shifted = wide >> {lbyte[LLB-1:0], 3'b000};
      assign t_list_words[ga*32*WORDS +: 32*WORDS] = shifted[0 +: 32*WORDS];
      wire unused_rsp = ^shifted[32*WORDS +: 8*LIST_LB];
    end
  endgenerate

  // Per cache: {valid, ready, line, tag} of its request, the fill, the counters.
  wire [2:0]        fill_valid;
  wire [3*MB_-1:0]  fill_tag;
  wire [3*8*MAXLB-1:0] fill_data;
  wire [3*32-1:0]   c_hits, c_misses, c_merges, c_full, c_sfull, c_fills;
  wire [PIPES-1:0]  n_unused_v, n_unused_m, n_unused_f, n_unused_s, n_unused_t;
  wire [PIPES-1:0]  l_unused_v, l_unused_m, l_unused_f, l_unused_s;
  wire [IST-1:0]    t_unused_v, t_unused_m, t_unused_f, t_unused_s;
  wire [PIPES-1:0]  l_unused_t;
  wire [IST-1:0]    t_unused_t;
  wire [3*($clog2(MSHRS+1))-1:0] mshr_busy;

  ascache #(.SETS(NODE_SETS), .WAYS(WAYS), .LINE_BYTES(NODE_LB), .MSHRS(MSHRS), .HIT_LATENCY(0),
            .PORTS(PIPES), .LINE_W(LINE_W), .TAG_BITS(1), .CNT_BITS(32)) u_node (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .acc_valid_i(t_nacc_valid), .acc_line_i(n_line), .acc_tag_i({PIPES{1'b0}}),
    .rsp_valid_o(n_unused_v), .rsp_hit_o(n_hit), .rsp_merge_o(n_unused_m),
    .rsp_full_o(n_unused_f), .rsp_set_full_o(n_unused_s), .rsp_tag_o(n_unused_t), .rsp_data_o(n_data),
    .req_valid_o(req_valid_o[0]), .req_ready_i(req_ready_i[0]),
    .req_line_o(req_line_o[0 +: LINE_W]), .req_tag_o(req_tag_o[0 +: MB_]),
    .fill_valid_i(fill_valid[0]), .fill_tag_i(fill_tag[0 +: MB_]),
    .fill_data_i(fill_data[0 +: 8*NODE_LB]),
    .mshr_busy_o(mshr_busy[0 +: $clog2(MSHRS+1)]),
    .cnt_hits_o(c_hits[0 +: 32]), .cnt_misses_o(c_misses[0 +: 32]),
    .cnt_merges_o(c_merges[0 +: 32]), .cnt_full_o(c_full[0 +: 32]),
    .cnt_set_full_o(c_sfull[0 +: 32]), .cnt_fills_o(c_fills[0 +: 32]));

  ascache #(.SETS(LIST_SETS), .WAYS(WAYS), .LINE_BYTES(LIST_LB), .MSHRS(MSHRS), .HIT_LATENCY(0),
            .PORTS(PIPES), .LINE_W(LINE_W), .TAG_BITS(1), .CNT_BITS(32)) u_list (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .acc_valid_i(t_lacc_valid), .acc_line_i(l_line), .acc_tag_i({PIPES{1'b0}}),
    .rsp_valid_o(l_unused_v), .rsp_hit_o(l_hit), .rsp_merge_o(l_unused_m),
    .rsp_full_o(l_unused_f), .rsp_set_full_o(l_unused_s), .rsp_tag_o(l_unused_t), .rsp_data_o(l_data),
    .req_valid_o(req_valid_o[1]), .req_ready_i(req_ready_i[1]),
    .req_line_o(req_line_o[LINE_W +: LINE_W]), .req_tag_o(req_tag_o[MB_ +: MB_]),
    .fill_valid_i(fill_valid[1]), .fill_tag_i(fill_tag[MB_ +: MB_]),
    .fill_data_i(fill_data[8*MAXLB +: 8*LIST_LB]),
    .mshr_busy_o(mshr_busy[$clog2(MSHRS+1) +: $clog2(MSHRS+1)]),
    .cnt_hits_o(c_hits[32 +: 32]), .cnt_misses_o(c_misses[32 +: 32]),
    .cnt_merges_o(c_merges[32 +: 32]), .cnt_full_o(c_full[32 +: 32]),
    .cnt_set_full_o(c_sfull[32 +: 32]), .cnt_fills_o(c_fills[32 +: 32]));

  // The triangle cache: one access per ist unit (the line of its entry's record).
  wire [IST*LINE_W-1:0] i_line;
  genvar gu;
  generate
    for (gu = 0; gu < IST; gu = gu + 1) begin : g_tri
      assign i_line[gu*LINE_W +: LINE_W] = i_acc_line[gu*32 +: LINE_W];
      wire unused_line = ^i_acc_line[gu*32 + LINE_W +: 32 - LINE_W];
    end
  endgenerate
  ascache #(.SETS(TRI_SETS), .WAYS(WAYS), .LINE_BYTES(TLB), .MSHRS(MSHRS), .HIT_LATENCY(0),
            .PORTS(IST), .LINE_W(LINE_W), .TAG_BITS(1), .CNT_BITS(32)) u_tri (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .acc_valid_i(i_acc_valid), .acc_line_i(i_line), .acc_tag_i({IST{1'b0}}),
    .rsp_valid_o(t_unused_v), .rsp_hit_o(i_rsp_hit), .rsp_merge_o(t_unused_m),
    .rsp_full_o(t_unused_f), .rsp_set_full_o(t_unused_s), .rsp_tag_o(t_unused_t), .rsp_data_o(i_rsp_data),
    .req_valid_o(req_valid_o[2]), .req_ready_i(req_ready_i[2]),
    .req_line_o(req_line_o[2*LINE_W +: LINE_W]), .req_tag_o(req_tag_o[2*MB_ +: MB_]),
    .fill_valid_i(fill_valid[2]), .fill_tag_i(fill_tag[2*MB_ +: MB_]),
    .fill_data_i(fill_data[2*8*MAXLB +: 8*TLB]),
    .mshr_busy_o(mshr_busy[2*$clog2(MSHRS+1) +: $clog2(MSHRS+1)]),
    .cnt_hits_o(c_hits[64 +: 32]), .cnt_misses_o(c_misses[64 +: 32]),
    .cnt_merges_o(c_merges[64 +: 32]), .cnt_full_o(c_full[64 +: 32]),
    .cnt_set_full_o(c_sfull[64 +: 32]), .cnt_fills_o(c_fills[64 +: 32]));
  wire unused_cache = ^{n_unused_v, n_unused_m, n_unused_f, n_unused_s, n_unused_t, l_unused_v,
                        l_unused_m, l_unused_f, l_unused_s, l_unused_t, t_unused_v, t_unused_m,
                        t_unused_f, t_unused_s, t_unused_t, mshr_busy};

  // ---- ist --------------------------------------------------------------------------------------
  wire [IST*(32+8*W)-1:0] i_ray;
  generate
    for (gu = 0; gu < IST; gu = gu + 1) begin : g_iray
      assign i_ray[gu*(32+8*W) +: 32+8*W] = {i_skip[gu*32 +: 32], i_ray_trv[gu*8*W +: 8*W]};
    end
  endgenerate
  ist_unit #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE),
             .STAGES(STAGES), .SLOT_BITS(SLOT_BITS), .IST(IST), .PIPES(PIPES), .WORDS(WORDS),
             .QBITS(QBITS), .RPL(RPL), .HLBITS(HLBITS)) u_ist (
    .clk_i(clk_i), .rst_ni(rst_ni), .now_i(now_q),
    .eps_i(eps_q), .one_eps_i(one_eps_q), .qcap_i(qcap_q), .hl_i(tri_hl_q), .units_i(ist_units_q),
    .hin_n_i(t_ist_n), .hin_slot_i(t_ist_slot), .hin_pos_i(t_ist_pos), .hin_ready_i(t_ist_ready),
    .hin_words_i(t_ist_words), .room_o(i_room),
    .ray_slot_o(i_ray_slot), .ray_i(i_ray),
    .acc_valid_o(i_acc_valid), .acc_line_o(i_acc_line), .rsp_hit_i(i_rsp_hit),
    .rsp_data_i(i_rsp_data),
    .res_valid_o(i_res_valid), .res_slot_o(i_res_slot), .res_hit_o(i_res_hit),
    .res_rec_o(i_res_rec),
    .head_valid_o(i_head_valid), .head_ready_o(i_head_ready), .busy_o(i_busy),
    .count_o(i_count),
    .cnt_busy_o(c_ist_busy), .cnt_miss_o(c_ist_miss), .cnt_tests_o(c_tests));

  // ---- hit --------------------------------------------------------------------------------------
  hit_unit #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE),
             .STAGES(STAGES), .SLOT_BITS(SLOT_BITS), .PIPES(PIPES), .SPAWNS(SPAWNS)) u_hit (
    .clk_i(clk_i), .rst_ni(rst_ni), .now_i(now_q),
    .light_x_i(light_q[0 +: W]), .light_y_i(light_q[W +: W]), .light_z_i(light_q[2*W +: W]),
    .tmin_i(tmin_q), .strategy_i(strategy_q), .segment_i(segment_q), .all_i(all_q),
    .back_i(back_q), .scale_i(scale_q), .fixed_i(fixed_q), .slab_scale_i(slab_scale_q),
    .fin_valid_i(t_fin), .fin_slot_i(t_fin_slot), .fin_ready_i(fin_ready),
    .rd_valid_o(h_rd_valid), .rd_slot_o(h_rd_slot), .rd_i(h_rd),
    .out_valid_o(h_valid), .out_slot_o(h_slot), .out_shadow_o(h_shadow), .out_found_o(h_found),
    .out_free_o(h_free), .out_spawn_o(h_spawn), .out_h_o(h_h), .out_front_o(h_front),
    .out_dens_o(h_dens), .out_ray_o(h_ray), .out_skip_id_o(h_skip),
    .head_valid_o(h_head_valid), .head_ready_o(h_head_ready), .busy_o(h_busy),
    .cnt_busy_o(c_hit_busy));
  wire unused_status = ^{h_rd_valid, h_head_valid, h_head_ready, h_busy, i_head_valid,
                         i_head_ready, i_busy, i_count};

  assign px_valid_o  = h_valid;
  assign px_shadow_o = h_shadow;
  assign px_found_o  = h_found;
  assign px_spawn_o  = h_spawn;
  assign px_best_o   = px_best;
  assign px_h_o      = h_h;
  assign px_front_o  = h_front;
  assign px_dens_o   = h_dens;
  assign px_ray_o    = h_ray;

  // ---- the fill path ----------------------------------------------------------------------------
  // The beats the fill path takes in this cycle: the memory's (beat_*) and the L2's (l2_*, idle
  // without an L2). In the chip they come from the bus's response registers (chip.v, BEAT_REG = 0;
  // membus_if's rsp_*, membus_l2's l2_*). A host that steps rtu.v alone (systemc/rtu_rtl.cpp) sets
  // BEAT_REG = 1 and drives the next cycle's beat, registered here: the same beat in the same
  // cycle, from flip-flops as in the chip. It was needed for Verilator 5.006 while the trv's cache
  // accesses were chained through the caches' ports (an UNOPTFLAT loop, until the trv's list
  // stage): with the beat a top-level input, the fill reached that chain in the input region,
  // where the --cc model settled it differently from Icarus and from the same RTL Verilated with
  // the beat from a register (a list-cache miss at cycle 6,303 of corridor 20x12, VTU off).
  wire [2:0]            b_valid, l2_valid;
  wire [MB_-1:0]        b_tag, l2_tag;
  wire [LEN_BITS-1:0]   b_idx, l2_idx;
  wire                  b_last, l2_last;
  wire [8*BEAT_BYTES-1:0] b_data;
  wire [8*L2_BEAT-1:0]  l2_data;
  generate
    if (BEAT_REG != 0) begin : g_beat_reg
      reg [2:0]            bv_q, lv_q;
      reg [MB_-1:0]        bt_q, lt_q;
      reg [LEN_BITS-1:0]   bi_q, li_q;
      reg                  bl_q, ll_q;
      reg [8*BEAT_BYTES-1:0] bd_q;
      reg [8*L2_BEAT-1:0]  ld_q;
      always @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) begin
          bv_q <= 3'b000;
          lv_q <= 3'b000;
        end else begin
          bv_q <= beat_valid_i;
          lv_q <= l2_valid_i;
        end
      end
      always @(posedge clk_i) begin
        bt_q <= beat_tag_i;
        bi_q <= beat_idx_i;
        bl_q <= beat_last_i;
        bd_q <= beat_data_i;
        lt_q <= l2_tag_i;
        li_q <= l2_idx_i;
        ll_q <= l2_last_i;
        ld_q <= l2_data_i;
      end
      assign {b_valid, b_tag, b_idx, b_last, b_data} = {bv_q, bt_q, bi_q, bl_q, bd_q};
      assign {l2_valid, l2_tag, l2_idx, l2_last, l2_data} = {lv_q, lt_q, li_q, ll_q, ld_q};
    end else begin : g_beat_in
      assign {b_valid, b_tag, b_idx, b_last, b_data} =
          {beat_valid_i, beat_tag_i, beat_idx_i, beat_last_i, beat_data_i};
      assign {l2_valid, l2_tag, l2_idx, l2_last, l2_data} =
          {l2_valid_i, l2_tag_i, l2_idx_i, l2_last_i, l2_data_i};
    end
  endgenerate
  wire [63:0] c_vtu_busy;
  wire [31:0] c_vtu_pair, c_vtu_wait;
  wire        v_busy;
  vtu_unit #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE),
             .STAGES(STAGES), .MSHRS(MSHRS), .NODE_LB(NODE_LB), .LIST_LB(LIST_LB),
             .TRI_LB(TLB), .BEAT_BYTES(BEAT_BYTES), .L2_BEAT(L2_BEAT), .LEN_BITS(LEN_BITS),
             .LINE_W(LINE_W)) u_vtu (
    .clk_i(clk_i), .rst_ni(rst_ni), .vtu_on_i(vtu_on_q),
    .cam_x_i(vtu_cam_q[0 +: W]), .cam_y_i(vtu_cam_q[W +: W]), .cam_z_i(vtu_cam_q[2*W +: W]),
    .node_count_i(node_count_q), .tri_count_i(tri_count_q),
    .req_take_i(req_valid_o & req_ready_i), .req_line_i(req_line_o), .req_tag_i(req_tag_o),
    .beat_valid_i(b_valid), .beat_tag_i(b_tag), .beat_idx_i(b_idx),
    .beat_last_i(b_last), .beat_data_i(b_data),
    .l2_valid_i(l2_valid), .l2_tag_i(l2_tag), .l2_idx_i(l2_idx), .l2_last_i(l2_last),
    .l2_data_i(l2_data),
    .fill_valid_o(fill_valid), .fill_tag_o(fill_tag), .fill_data_o(fill_data),
    .cnt_busy_o(c_vtu_busy), .cnt_pair_o(c_vtu_pair), .cnt_wait_o(c_vtu_wait), .busy_o(v_busy));
  wire unused_vtu = ^{v_busy, fill_data};  // a cache's line may be narrower than the widest

  // ---- status and counters ----------------------------------------------------------------------
  assign done_o = !rgu_busy && (free_count == slots_q);
  assign primaries_o = rgu_busy;
  always @* begin
    case (cnt_sel_i)
      6'd0:  cnt_o = {32'd0, now_q};
      6'd1:  cnt_o = c_trv_busy;
      6'd2:  cnt_o = c_node_miss;
      6'd3:  cnt_o = c_list_miss;
      6'd4:  cnt_o = c_ist_full;
      6'd5:  cnt_o = c_inner;
      6'd6:  cnt_o = c_leaf;
      6'd7:  cnt_o = c_pops;
      6'd8:  cnt_o = c_list_steps;
      6'd9:  cnt_o = c_fused;
      6'd10: cnt_o = {57'd0, c_stack_max};
      6'd11: cnt_o = c_ist_busy;
      6'd12: cnt_o = c_ist_miss;
      6'd13: cnt_o = c_tests;
      6'd14: cnt_o = c_hit_busy;
      6'd15: cnt_o = c_primary;
      6'd16: cnt_o = c_shadow;
      6'd17: cnt_o = c_stall;
      6'd18: cnt_o = c_vtu_busy;
      6'd19: cnt_o = {32'd0, c_hits[0 +: 32]};
      6'd20: cnt_o = {32'd0, c_misses[0 +: 32]};
      6'd21: cnt_o = {32'd0, c_merges[0 +: 32]};
      6'd22: cnt_o = {32'd0, c_full[0 +: 32]};
      6'd23: cnt_o = {32'd0, c_fills[0 +: 32]};
      6'd24: cnt_o = {32'd0, c_hits[32 +: 32]};
      6'd25: cnt_o = {32'd0, c_misses[32 +: 32]};
      6'd26: cnt_o = {32'd0, c_merges[32 +: 32]};
      6'd27: cnt_o = {32'd0, c_full[32 +: 32]};
      6'd28: cnt_o = {32'd0, c_fills[32 +: 32]};
      6'd29: cnt_o = {32'd0, c_hits[64 +: 32]};
      6'd30: cnt_o = {32'd0, c_misses[64 +: 32]};
      6'd31: cnt_o = {32'd0, c_merges[64 +: 32]};
      6'd32: cnt_o = {32'd0, c_full[64 +: 32]};
      6'd33: cnt_o = {32'd0, c_fills[64 +: 32]};
      6'd34: cnt_o = {32'd0, c_sfull[0 +: 32]};
      6'd35: cnt_o = {32'd0, c_sfull[32 +: 32]};
      6'd36: cnt_o = {32'd0, c_sfull[64 +: 32]};
      6'd37: cnt_o = {32'd0, c_vtu_pair};
      6'd38: cnt_o = {32'd0, c_vtu_wait};
      default: cnt_o = 64'd0;
    endcase
  end

endmodule
