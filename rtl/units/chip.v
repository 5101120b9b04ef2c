// chip - the chip top: RTUS ray-tracing units (rtu.v) and the memory bus they share, as
// systemc/top.h connects the cycle model's RTUs to its Membus: with L2_SETS 0 membus_if.v (no L2:
// the caches' line requests go to the memory directly, the cycle model with --l2-kb 0), else
// membus_l2.v (the L2 of L2_SETS x L2_WAYS lines of the caches' line bytes, L2_BEAT bytes per cycle
// to the RTUs' second beat port, its hit latency l2_lat_i; the model's default: 512 x 8 x 64 bytes,
// 32 bytes per cycle, 20 cycles). The memory (the image's bytes and its latency) is outside, on
// mem_* / beat_* (the testbench's, as Membus's); so is the frame buffer, written from each RTU's
// px_* (the host's pixel write and shade).
//
// Requester 3 r + p of membus_if is RTU r's cache p (node 0, list 1, triangle 2): its line request
// becomes the byte address base_p + line x line bytes of p (the image's regions, hls/image.h), for
// a whole line, tagged with the MSHR; the beats routed back go to that RTU's fill path.
// The frame registers are the same for every RTU but its index (rtu_i = r). Status: done_o when
// every RTU is done, err_o when any overflowed its stack; counters by RTU and index (rtu.v's).
// lint: also RTUS=2 SLOT_BITS=4 DEPTH=8 PIPES=2 IST=2 WORDS=4 QBITS=3 NODE_SETS=4 LIST_SETS=2 TRI_SETS=4 WAYS=2 MSHRS=2 NODE_LB=32 LIST_LB=16 TRI_LB=32
// lint: also RTUS=2 SLOT_BITS=4 DEPTH=8 PIPES=2 IST=2 WORDS=4 QBITS=3 NODE_SETS=4 LIST_SETS=2 TRI_SETS=4 WAYS=2 MSHRS=2 NODE_LB=32 LIST_LB=32 TRI_LB=32 L2_SETS=4 L2_WAYS=2 L2_BEAT=16
module chip #(
  parameter integer RTUS       = 6,
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
  parameter integer BEAT_BYTES = 16,
  parameter integer LEN_BITS   = 12,
  parameter integer ADDR_BITS  = 32,
  parameter integer BUS_DEPTH  = 32,
  parameter integer L2_SETS    = 0,   // 0: no L2
  parameter integer L2_WAYS    = 8,
  parameter integer L2_BEAT    = 32,
  parameter integer SPAWNS     = 1,   // rtu.v's: the spawn strategies built (1: none, the defaults)
  // Derived (not to be overridden).
  parameter integer W_  = 1 + EXP_BITS + MAN_BITS,
  parameter integer MB_ = (MSHRS > 1) ? $clog2(MSHRS) : 1,
  parameter integer PB_ = $clog2(3 * RTUS),                       // membus_if's PORT_BITS
  parameter integer PX_ = 2 * COORD_BITS + 3 + (67 + 5 * W_) + 3 * W_ + 1 + W_ + 11 * W_
) (
  input  wire                        clk_i,
  input  wire                        rst_ni,
  // ---- frame registers (rtu.v's, the same for every RTU) ----------------------------------------
  input  wire                        start_i,
  input  wire [12*W_-1:0]            cam_i,
  input  wire [COORD_BITS-1:0]       width_i,
  input  wire [COORD_BITS-1:0]       height_i,
  input  wire [RTU_BITS-1:0]         rtus_i,
  input  wire [SLOT_BITS:0]          slots_i,
  input  wire [W_-1:0]               tmin_i,
  input  wire [15:0]                 trv_lat_i,
  input  wire [15:0]                 node_hl_i,
  input  wire [15:0]                 list_hl_i,
  input  wire [4:0]                  pipes_i,
  input  wire                        fuse_i,
  input  wire                        any_hit_i,
  input  wire                        empty_i,
  input  wire [6:0]                  depth_i,
  input  wire [6:0]                  widen_i,
  input  wire [6*W_-1:0]             box_i,
  input  wire [W_-1:0]               eps_i,
  input  wire [W_-1:0]               one_eps_i,
  input  wire [15:0]                 qcap_i,
  input  wire [7:0]                  tri_hl_i,
  input  wire [4:0]                  ist_units_i,
  input  wire [3*W_-1:0]             light_i,
  input  wire [2:0]                  strategy_i,
  input  wire                        segment_i,
  input  wire                        all_i,
  input  wire [31:0]                 back_i,
  input  wire [W_-1:0]               scale_i,
  input  wire [W_-1:0]               fixed_i,
  input  wire [W_-1:0]               slab_scale_i,
  input  wire                        vtu_on_i,
  input  wire [3*W_-1:0]             vtu_cam_i,
  input  wire [31:0]                 node_count_i,
  input  wire [31:0]                 tri_count_i,
  // The image's regions: byte addresses of the node, list and triangle arrays.
  input  wire [3*ADDR_BITS-1:0]      base_i,        // {tri, list, node}
  input  wire [15:0]                 l2_lat_i,      // the L2's hit latency (unused without one)
  // ---- the memory: requests (membus_if's mem_*) and data beats ----------------------------------
  output wire                        mem_valid_o,
  input  wire                        mem_ready_i,
  output wire [ADDR_BITS-1:0]        mem_addr_o,
  output wire [LEN_BITS-1:0]         mem_bytes_o,
  output wire [PB_-1:0]              mem_port_o,
  output wire [MB_-1:0]              mem_tag_o,
  input  wire                        beat_valid_i,
  input  wire [8*BEAT_BYTES-1:0]     beat_data_i,
  // ---- the rays leaving the hit units: RTU r's rtu.v px_* record in bits [r*PX_ +: PX_] ---------
  // {valid, pixel, shadow, found, spawn, best, h, front, dens, ray} (valid highest)
  output wire [RTUS*(1+PX_)-1:0]     px_o,
  // ---- status -----------------------------------------------------------------------------------
  output wire                        done_o,
  output wire                        err_o,
  output wire [$clog2(BUS_DEPTH+1)-1:0] outstanding_o,
  input  wire [RTU_BITS-1:0]         cnt_rtu_i,
  input  wire [5:0]                  cnt_sel_i,
  output wire [63:0]                 cnt_o
);

  localparam integer N = 3 * RTUS;
  localparam integer RB  = ((((9 * ((W_ <= 24) ? 3 : 4) + 1 + 3) / 4) * 4 + 4 + 15) / 16) * 16;
  localparam integer TLB = (TRI_LB != 0) ? TRI_LB : ((64 + RB / 2) / RB) * RB;

  wire [N-1:0]           req_valid, req_ready, rsp_valid;
  wire [N*LINE_W-1:0]    req_line;
  wire [N*MB_-1:0]       req_tag;
  wire [N*ADDR_BITS-1:0] req_addr;
  wire [N*LEN_BITS-1:0]  req_bytes;
  wire [PB_-1:0]         rsp_port;
  wire [MB_-1:0]         rsp_tag;
  wire [8*BEAT_BYTES-1:0] rsp_data;
  wire [LEN_BITS-1:0]    rsp_beat;
  wire                   rsp_last;
  wire [RTUS-1:0]        done, err, primaries;
  wire [RTUS*64-1:0]     cnt;

  // Line index -> byte address and length, per requester.
  genvar i;
  generate
    for (i = 0; i < N; i = i + 1) begin : g_req
      localparam integer P  = i % 3;
      localparam integer LB = (P == 0) ? NODE_LB : (P == 1) ? LIST_LB : TLB;
      wire [ADDR_BITS-1:0] line = {{(ADDR_BITS-LINE_W){1'b0}}, req_line[i*LINE_W +: LINE_W]};
      assign req_addr[i*ADDR_BITS +: ADDR_BITS] = base_i[P*ADDR_BITS +: ADDR_BITS] + line * LB;
      assign req_bytes[i*LEN_BITS +: LEN_BITS] = LB[LEN_BITS-1:0];
    end
  endgenerate

  // The RTUs' second beat port: the L2's beats (idle without an L2).
  wire [N-1:0]           l2_valid;
  wire [MB_-1:0]         l2_tag;
  wire [8*L2_BEAT-1:0]   l2_data;
  wire [LEN_BITS-1:0]    l2_beat;
  wire                   l2_last;
  generate
    if (L2_SETS == 0) begin : g_no_l2
      wire                take, take_last;
      wire [MB_-1:0]      take_tag;
      wire [LEN_BITS-1:0] take_beat;
      membus_if #(.N(N), .ADDR_BITS(ADDR_BITS), .LEN_BITS(LEN_BITS), .TAG_BITS(MB_),
                  .DEPTH(BUS_DEPTH), .BEAT_BYTES(BEAT_BYTES)) u_bus (
        .clk_i(clk_i), .rst_ni(rst_ni),
        .req_valid_i(req_valid), .req_ready_o(req_ready), .req_addr_i(req_addr),
        .req_bytes_i(req_bytes), .req_tag_i(req_tag),
        .mem_valid_o(mem_valid_o), .mem_ready_i(mem_ready_i), .mem_addr_o(mem_addr_o),
        .mem_bytes_o(mem_bytes_o), .mem_port_o(mem_port_o), .mem_tag_o(mem_tag_o),
        .beat_valid_i(beat_valid_i), .beat_data_i(beat_data_i),
        .rsp_valid_o(rsp_valid), .rsp_port_o(rsp_port), .rsp_tag_o(rsp_tag), .rsp_data_o(rsp_data),
        .rsp_beat_o(rsp_beat), .rsp_last_o(rsp_last), .outstanding_o(outstanding_o),
        .take_o(take), .take_tag_o(take_tag), .take_beat_o(take_beat), .take_last_o(take_last));
      wire unused_take = ^{take, take_tag, take_beat, take_last, l2_lat_i};  // membus_l2.v's
      assign {l2_valid, l2_tag, l2_data, l2_beat, l2_last} = {(N+MB_+8*L2_BEAT+LEN_BITS+1){1'b0}};
    end else begin : g_l2
      // The cycle number the L2's responses are timed by (membus_l2's now_i).
      reg [31:0] now_q;
      always @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) now_q <= 32'd0;
        else         now_q <= now_q + 32'd1;
      end
      wire acc_valid, acc_hit, stall, l2_busy;
      wire [PB_-1:0] acc_port, l2_port;
      membus_l2 #(.N(N), .ADDR_BITS(ADDR_BITS), .LEN_BITS(LEN_BITS), .TAG_BITS(MB_),
                  .DEPTH(BUS_DEPTH), .BEAT_BYTES(BEAT_BYTES), .SETS(L2_SETS), .WAYS(L2_WAYS),
                  .LINE_BYTES(NODE_LB), .L2_BEAT(L2_BEAT), .QDEPTH(N * MSHRS)) u_bus (
        .clk_i(clk_i), .rst_ni(rst_ni), .now_i(now_q), .lat_i(l2_lat_i),
        .req_valid_i(req_valid), .req_ready_o(req_ready), .req_addr_i(req_addr),
        .req_bytes_i(req_bytes), .req_tag_i(req_tag),
        .acc_valid_o(acc_valid), .acc_port_o(acc_port), .acc_hit_o(acc_hit), .stall_o(stall),
        .mem_valid_o(mem_valid_o), .mem_ready_i(mem_ready_i), .mem_addr_o(mem_addr_o),
        .mem_bytes_o(mem_bytes_o),
        .beat_valid_i(beat_valid_i), .beat_data_i(beat_data_i),
        .rsp_valid_o(rsp_valid), .rsp_port_o(rsp_port), .rsp_tag_o(rsp_tag), .rsp_data_o(rsp_data),
        .rsp_beat_o(rsp_beat), .rsp_last_o(rsp_last),
        .l2_valid_o(l2_valid), .l2_port_o(l2_port), .l2_tag_o(l2_tag), .l2_data_o(l2_data),
        .l2_beat_o(l2_beat), .l2_last_o(l2_last), .outstanding_o(outstanding_o),
        .l2_busy_o(l2_busy));
      // The memory's side tags are membus_l2's own (its miss queue); every line is one L2 line
      // (the caches' lines are the L2's: NODE_LB = LIST_LB = the triangle lines).
      assign mem_port_o = {PB_{1'b0}};
      assign mem_tag_o  = {MB_{1'b0}};
      wire unused_l2 = ^{acc_valid, acc_port, acc_hit, stall, l2_busy, l2_port};
    end
  endgenerate
  wire unused_port = ^rsp_port;  // rsp_valid_o is one-hot by requester already

  genvar r;
  generate
    for (r = 0; r < RTUS; r = r + 1) begin : g_rtu
      localparam [RTU_BITS-1:0] R = r;
      wire [PX_-1:0] px;
      wire           px_valid;
      rtu #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE),
            .STAGES(STAGES), .SLOT_BITS(SLOT_BITS), .DEPTH(DEPTH), .PIPES(PIPES), .IST(IST),
            .WORDS(WORDS), .QBITS(QBITS), .HLBITS(HLBITS), .COORD_BITS(COORD_BITS),
            .TILE_BITS(TILE_BITS), .RTU_BITS(RTU_BITS), .NODE_SETS(NODE_SETS),
            .LIST_SETS(LIST_SETS), .TRI_SETS(TRI_SETS), .WAYS(WAYS), .NODE_LB(NODE_LB),
            .LIST_LB(LIST_LB), .TRI_LB(TRI_LB), .MSHRS(MSHRS), .LINE_W(LINE_W),
            .BEAT_BYTES(BEAT_BYTES), .L2_BEAT(L2_BEAT), .LEN_BITS(LEN_BITS), .SPAWNS(SPAWNS)) u_rtu (
        .clk_i(clk_i), .rst_ni(rst_ni), .start_i(start_i), .cam_i(cam_i), .width_i(width_i),
        .height_i(height_i), .rtu_i(R), .rtus_i(rtus_i), .slots_i(slots_i), .tmin_i(tmin_i),
        .trv_lat_i(trv_lat_i), .node_hl_i(node_hl_i), .list_hl_i(list_hl_i), .pipes_i(pipes_i),
        .fuse_i(fuse_i), .any_hit_i(any_hit_i), .empty_i(empty_i), .depth_i(depth_i),
        .widen_i(widen_i), .box_i(box_i), .eps_i(eps_i), .one_eps_i(one_eps_i), .qcap_i(qcap_i),
        .tri_hl_i(tri_hl_i), .ist_units_i(ist_units_i), .light_i(light_i),
        .strategy_i(strategy_i), .segment_i(segment_i), .all_i(all_i), .back_i(back_i),
        .scale_i(scale_i), .fixed_i(fixed_i), .slab_scale_i(slab_scale_i), .vtu_on_i(vtu_on_i),
        .vtu_cam_i(vtu_cam_i), .node_count_i(node_count_i), .tri_count_i(tri_count_i),
        .req_valid_o(req_valid[3*r +: 3]), .req_ready_i(req_ready[3*r +: 3]),
        .req_line_o(req_line[3*r*LINE_W +: 3*LINE_W]), .req_tag_o(req_tag[3*r*MB_ +: 3*MB_]),
        .beat_valid_i(rsp_valid[3*r +: 3]), .beat_tag_i(rsp_tag), .beat_idx_i(rsp_beat),
        .beat_last_i(rsp_last), .beat_data_i(rsp_data),
        .l2_valid_i(l2_valid[3*r +: 3]), .l2_tag_i(l2_tag), .l2_idx_i(l2_beat),
        .l2_last_i(l2_last), .l2_data_i(l2_data),
        .px_valid_o(px_valid), .px_pixel_o(px[PX_-1 -: 2*COORD_BITS]),
        .px_shadow_o(px[PX_-1-2*COORD_BITS]), .px_found_o(px[PX_-2-2*COORD_BITS]),
        .px_spawn_o(px[PX_-3-2*COORD_BITS]),
        .px_best_o(px[15*W_+1 +: 67+5*W_]), .px_h_o(px[12*W_+1 +: 3*W_]),
        .px_front_o(px[12*W_]), .px_dens_o(px[11*W_ +: W_]), .px_ray_o(px[0 +: 11*W_]),
        .done_o(done[r]), .primaries_o(primaries[r]), .err_o(err[r]), .cnt_sel_i(cnt_sel_i), .cnt_o(cnt[r*64 +: 64]));
      assign px_o[r*(1+PX_) +: 1+PX_] = {px_valid, px};
    end
  endgenerate

  assign done_o = &done;
  assign err_o  = |err;
  wire   unused_primaries = ^primaries;  // per RTU; the host polls done_o
  wire [31:0] cr = {{(32-RTU_BITS){1'b0}}, cnt_rtu_i};
  assign cnt_o  = (cr < RTUS) ? cnt[cr[PB_-1:0]*64 +: 64] : 64'd0;

endmodule
