// hit_unit - the hit unit whole: the hit queue of finished rays, the slot read of the ray entering
// (its ray, best record and kind), hit.v, and the decision when it leaves: the slot freed (a
// shadow ray, a primary miss, a primary hit without a shadow ray) or holding the shadow ray that
// hit.v made (a primary hit that spawns one, handed to the rgu). The RTL view of systemc/hit.h's
// control with its datapath: bound into the running frame by systemc/hit_rtl.h (raycore simulate
// --rtl hit), cycle for cycle and bit for bit the transaction model's. The frame buffer (the
// pixel's hit, light side and shade) stays the host's: it reads out_* when a ray leaves.
//
// Per cycle, in the model's order (systemc/hit.h, Hit::tick):
//   1. the ray hit.v puts out (hit_latency = 24 x STAGES cycles after it entered) leaves on out_*:
//      out_free_o or out_spawn_o, with hit.v's results (the hit point, the light side, dens and
//      the shadow ray);
//   2. the queue's head enters the hit pipeline if its ready cycle has come (one ray per cycle):
//      the slot's ray, best record and kind are read (rd_slot_o / rd_i, same cycle) into a
//      register (STAGES > 0: the first of the latency's 24 x STAGES, hit.v's IN_REGS) and carried;
//   3. the trv's finished rays of this cycle (fin_*, one per pipe, each with its ready cycle) are
//      appended in pipe order.
// The queue is a FIFO whose head blocks the entries behind it until its ready cycle (the cycle
// model's TimedFifo); it holds up to 2^SLOT_BITS entries (every slot at most once). Ready cycles
// are 32-bit cycle numbers compared with now_i as a signed difference.
// Storage: NB banks (PIPES rounded up to a power of two, at most 2^SLOT_BITS), bank b holding the
// entries e with e mod NB = b, each a memory of one write and one read port: a cycle's pushes are
// consecutive from the tail, so at most one lands in each bank (the pipes' rays compacted and
// rotated by the tail: bank b takes one fixed element). The head is a register (w_*_q), refilled
// at every edge with the entry after the head (read from its bank at an address from registers;
// this cycle's push when one lands there) when the head leaves, so the ready test and the slot
// read start from registers. (The queue in registers written from every pipe cost about 156 k
// NAND2 eq. at the RTU's 128 entries and 5 pipes: docs/architecture.md, "The twelfth levers".)
// lint: also SLOT_BITS=7 PIPES=4 STAGES=2
// lint: also SLOT_BITS=1 PIPES=1 STAGES=1
// lint: also SLOT_BITS=7 PIPES=4 STAGES=2 SPAWNS=1
module hit_unit #(
  parameter integer EXP_BITS  = 7,
  parameter integer MAN_BITS  = 16,
  parameter integer RNE       = 0,
  parameter integer RAYCORE   = 0,
  parameter integer STAGES    = 2,
  parameter integer SLOT_BITS = 3,
  parameter integer PIPES     = 2,
  parameter integer SPAWNS    = 127  // hit.v's: the spawn strategies built (bit s: hls::Spawn s)
) (
  input  wire                            clk_i,
  input  wire                            rst_ni,
  input  wire [31:0]                     now_i,
  // hit.v's per-frame registers (static).
  input  wire [EXP_BITS+MAN_BITS:0]      light_x_i,
  input  wire [EXP_BITS+MAN_BITS:0]      light_y_i,
  input  wire [EXP_BITS+MAN_BITS:0]      light_z_i,
  input  wire [EXP_BITS+MAN_BITS:0]      tmin_i,
  input  wire [2:0]                      strategy_i,
  input  wire                            segment_i,
  input  wire                            all_i,
  input  wire [31:0]                     back_i,
  input  wire [EXP_BITS+MAN_BITS:0]      scale_i,
  input  wire [EXP_BITS+MAN_BITS:0]      fixed_i,
  input  wire [EXP_BITS+MAN_BITS:0]      slab_scale_i,
  // The trv's finished rays (pipe p in bits [p*w +: w]).
  input  wire [PIPES-1:0]                fin_valid_i,
  input  wire [PIPES*SLOT_BITS-1:0]      fin_slot_i,
  input  wire [PIPES*32-1:0]             fin_ready_i,
  // The slot of the ray entering: {shadow, best {found, t, den, pos, id, k, nu, nv, nd}, d zyx,
  // o zyx} (o x lowest).
  output wire                            rd_valid_o,
  output wire [SLOT_BITS-1:0]            rd_slot_o,
  input  wire [1+67+5*(1+EXP_BITS+MAN_BITS)+6*(1+EXP_BITS+MAN_BITS)-1:0] rd_i,
  // The ray leaving.
  output wire                            out_valid_o,
  output wire [SLOT_BITS-1:0]            out_slot_o,
  output wire                            out_shadow_o,  // it was a shadow ray
  output wire                            out_found_o,   // it hit a triangle
  output wire                            out_free_o,    // its slot is free
  output wire                            out_spawn_o,   // its slot holds the shadow ray below
  output wire [3*(1+EXP_BITS+MAN_BITS)-1:0] out_h_o,    // {z, y, x}
  output wire                            out_front_o,
  output wire [EXP_BITS+MAN_BITS:0]      out_dens_o,
  output wire [11*(1+EXP_BITS+MAN_BITS)-1:0] out_ray_o, // {o xyz, d xyz, inv xyz, tmin, tmax}
  output wire [31:0]                     out_skip_id_o,
  // The queue's head (the cycle model's next event), rays inside hit.v, the counter hit_busy.
  output wire                            head_valid_o,
  output wire [31:0]                     head_ready_o,
  output wire                            busy_o,
  output wire [63:0]                     cnt_busy_o
);

  localparam integer W  = 1 + EXP_BITS + MAN_BITS;
  localparam integer BW = 67 + 5 * W;
  localparam integer TW = SLOT_BITS + 2;  // hit.v's tag: {slot, shadow, found}
  localparam integer RDW = 1 + BW + 6 * W; // the slot read: {shadow, best, d zyx, o zyx}
  localparam [SLOT_BITS-1:0] ONE = 1;

  // ---- the queue --------------------------------------------------------------------------------
  localparam integer PB  = (PIPES > 1) ? $clog2(PIPES) : 0;
  localparam integer NBB = (PB < SLOT_BITS) ? PB : SLOT_BITS;   // log2 of the banks
  localparam integer NB  = 1 << NBB;
  localparam integer DB  = SLOT_BITS - NBB;                     // log2 of a bank's entries
  localparam integer QW  = SLOT_BITS + 32;                      // an entry: {slot, ready}
  reg [SLOT_BITS-1:0] head_q;
  reg [SLOT_BITS:0]   cnt_q;
  reg [SLOT_BITS-1:0] w_slot_q;   // the head entry (meaningful while cnt_q > 0)
  reg [31:0]          w_ready_q;

  assign head_valid_o = (cnt_q != {(SLOT_BITS+1){1'b0}});
  assign head_ready_o = w_ready_q;
  wire [31:0] dt   = w_ready_q - now_i;
  wire        take = head_valid_o && ($signed(dt) <= 0);

  // ---- 2. the ray entering --------------------------------------------------------------------
  assign rd_valid_o = take;
  assign rd_slot_o  = w_slot_q;
  // The slot read and the ray's slot, registered (STAGES > 0): so no path runs from the hit
  // queue through the slot arrays into hit.v's first level.
  localparam integer IR = (STAGES > 0) ? 1 : 0;
  wire               in_valid;
  wire [RDW-1:0]     rd;
  wire [SLOT_BITS-1:0] in_slot;
  generate
    if (IR != 0) begin : g_in_reg
      reg               v_q;
      reg [RDW-1:0]     rd_q;
      reg [SLOT_BITS-1:0] s_q;
      always @(posedge clk_i or negedge rst_ni)
        if (!rst_ni) v_q <= 1'b0;
        else v_q <= take;
      always @(posedge clk_i) begin
        rd_q <= rd_i;
        s_q <= w_slot_q;
      end
      assign in_valid = v_q;
      assign rd = rd_q;
      assign in_slot = s_q;
    end else begin : g_in_wire
      assign in_valid = take;
      assign rd = rd_i;
      assign in_slot = w_slot_q;
    end
  endgenerate
  wire [6*W-1:0] ray    = rd[6*W-1:0];
  wire [BW-1:0]  best   = rd[6*W +: BW];
  wire           shadow = rd[6*W + BW];
  // best: {found, t, den, pos, id, k, nu, nv, nd}, nd lowest
  wire [W-1:0]   b_nd = best[0 +: W], b_nv = best[W +: W], b_nu = best[2*W +: W];
  wire [1:0]     b_k  = best[3*W +: 2];
  wire [31:0]    b_id = best[3*W+2 +: 32];
  wire [W-1:0]   b_den = best[3*W+66 +: W], b_t = best[4*W+66 +: W];
  wire           b_found = best[5*W+66];
  wire           unused_pos = ^best[3*W+34 +: 32];

  wire          o_valid, o_ready_unused;
  wire [TW-1:0] o_tag;
  wire [W-1:0]  o_hx, o_hy, o_hz, o_dens, o_ox, o_oy, o_oz, o_dx, o_dy, o_dz, o_ix, o_iy, o_iz;
  wire [W-1:0]  o_tmin, o_tmax;
  wire          o_front, o_spawn;
  hit #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES),
        .IN_REGS(IR), .TAG_BITS(TW), .SPAWNS(SPAWNS), .FREE(1)) u_hit (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .light_x_i(light_x_i), .light_y_i(light_y_i), .light_z_i(light_z_i), .tmin_i(tmin_i),
    .strategy_i(strategy_i), .segment_i(segment_i), .all_i(all_i), .back_i(back_i),
    .scale_i(scale_i), .fixed_i(fixed_i), .slab_scale_i(slab_scale_i),
    .in_valid_i(in_valid), .in_ready_o(o_ready_unused),
    .in_o_x_i(ray[0 +: W]), .in_o_y_i(ray[W +: W]), .in_o_z_i(ray[2*W +: W]),
    .in_d_x_i(ray[3*W +: W]), .in_d_y_i(ray[4*W +: W]), .in_d_z_i(ray[5*W +: W]),
    .in_t_i(b_t), .in_k_i(b_k), .in_nu_i(b_nu), .in_nv_i(b_nv), .in_nd_i(b_nd), .in_den_i(b_den),
    .in_id_i(b_id), .in_tag_i({in_slot, shadow, b_found}),
    .out_valid_o(o_valid), .out_ready_i(1'b1),
    .out_h_x_o(o_hx), .out_h_y_o(o_hy), .out_h_z_o(o_hz), .out_front_o(o_front),
    .out_spawn_o(o_spawn), .out_dens_o(o_dens), .out_o_x_o(o_ox), .out_o_y_o(o_oy),
    .out_o_z_o(o_oz), .out_d_x_o(o_dx), .out_d_y_o(o_dy), .out_d_z_o(o_dz),
    .out_inv_x_o(o_ix), .out_inv_y_o(o_iy), .out_inv_z_o(o_iz), .out_tmin_o(o_tmin),
    .out_tmax_o(o_tmax), .out_skip_id_o(out_skip_id_o), .out_tag_o(o_tag));

  // ---- 1. the ray leaving: free its slot, or keep it with the shadow ray ------------------------
  wire t_shadow = o_tag[1];
  wire t_found  = o_tag[0];
  assign out_valid_o  = o_valid;
  assign out_slot_o   = o_tag[TW-1 -: SLOT_BITS];
  assign out_shadow_o = t_shadow;
  assign out_found_o  = t_found;
  assign out_spawn_o  = o_valid && !t_shadow && t_found && o_spawn;
  assign out_free_o   = o_valid && !out_spawn_o;
  assign out_h_o      = {o_hz, o_hy, o_hx};
  assign out_front_o  = o_front;
  assign out_dens_o   = o_dens;
  assign out_ray_o    = {o_ox, o_oy, o_oz, o_dx, o_dy, o_dz, o_ix, o_iy, o_iz, o_tmin, o_tmax};

  // ---- 3. pushes: the finished rays in pipe order, to tail .. tail + npush - 1 ------------------
  // The valid pipes' rays compacted (element k the k-th in pipe order; k < npush <= PIPES <= NB
  // when NB = PIPES rounded up, and NB = 2^SLOT_BITS holds every entry), then rotated by the
  // tail: element b of wrot goes to bank b (entry tail + ((b - tail) mod NB)).
  wire [SLOT_BITS-1:0] tail = head_q + cnt_q[SLOT_BITS-1:0];
  reg  [SLOT_BITS:0]   npush;
  reg  [NB*QW-1:0]     wrot;
  integer p, l;
  always @* begin
    npush = {(SLOT_BITS+1){1'b0}};
    wrot = {(NB*QW){1'b0}};
    for (p = 0; p < PIPES; p = p + 1)
      if (fin_valid_i[p]) begin
        wrot = wrot | ({{((NB-1)*QW){1'b0}}, fin_slot_i[p*SLOT_BITS +: SLOT_BITS],
                        fin_ready_i[p*32 +: 32]} << (npush * QW));
        npush = npush + 1'b1;
      end
    for (l = 0; l < NBB; l = l + 1)
      if (tail[l]) wrot = (wrot << ((1 << l) * QW)) | (wrot >> ((NB - (1 << l)) * QW));
  end

  // The banks, and the entry after the head after this edge (the window's refill when the head
  // leaves): read from its bank, or this cycle's push to it.
  localparam [31:0] NB1 = NB - 1;
  localparam [SLOT_BITS-1:0] BMASK = NB1[SLOT_BITS-1:0];
  wire [SLOT_BITS-1:0] nx = head_q + ONE;
  wire [NB*QW-1:0]     rdat;     // bank b's entry at nx's address
  genvar gb;
  generate
    for (gb = 0; gb < NB; gb = gb + 1) begin : g_bank
      localparam [SLOT_BITS:0] B = gb;
      wire [SLOT_BITS-1:0] k = (B[SLOT_BITS-1:0] - tail) & BMASK;   // its place among the pushes
      wire                 we = ({1'b0, k} < npush);
      if (DB > 0) begin : g_mem
        wire [SLOT_BITS-1:0] e = tail + k;                          // the entry it writes
        wire                 unused_e = ^e;                         // its bank: gb
        reg  [QW-1:0] mem [0:(1<<DB)-1];
        always @(posedge clk_i)
          if (we) mem[e[SLOT_BITS-1:NBB]] <= wrot[gb*QW +: QW];
        assign rdat[gb*QW +: QW] = mem[nx[SLOT_BITS-1:NBB]];
      end else begin : g_reg   // one entry per bank
        reg  [QW-1:0] r_q;
        always @(posedge clk_i)
          if (we) r_q <= wrot[gb*QW +: QW];
        assign rdat[gb*QW +: QW] = r_q;
      end
    end
  endgenerate
  // Element h mod NB of v.
  function automatic [QW-1:0] at_bank(input [NB*QW-1:0] v, input [SLOT_BITS-1:0] h);
    integer i;
    begin
      at_bank = {QW{1'b0}};
      for (i = 0; i < NB; i = i + 1)
        at_bank = at_bank | ({QW{(h & BMASK) == i[SLOT_BITS-1:0]}} & v[i*QW +: QW]);
    end
  endfunction
  wire [SLOT_BITS-1:0] nk = nx - tail;
  wire [QW-1:0] nx_entry = ({1'b0, nk} < npush) ? at_bank(wrot, nx) : at_bank(rdat, nx);
  wire [QW-1:0] hd_entry = at_bank(wrot, head_q);   // the push to the head of an empty queue

  // Rays inside hit.v.
  reg [7:0] inside_q;
  assign busy_o = (inside_q != 8'd0);
  // hit_busy: the count and the last cycle's take, added at the output (the same value in every
  // cycle as one register counting take; the 64-bit increment off the path from the queue's head).
  reg [63:0] busy_q;
  reg        take_q;
  assign cnt_busy_o = busy_q + {63'd0, take_q};

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head_q     <= {SLOT_BITS{1'b0}};
      cnt_q      <= {(SLOT_BITS+1){1'b0}};
      inside_q   <= 8'd0;
      busy_q     <= 64'd0;
      take_q     <= 1'b0;
    end else begin
      head_q     <= head_q + (take ? ONE : {SLOT_BITS{1'b0}});
      cnt_q      <= cnt_q - {{SLOT_BITS{1'b0}}, take} + npush;
      inside_q   <= inside_q + {7'd0, take} - {7'd0, o_valid};
      busy_q     <= cnt_busy_o;
      take_q     <= take;
    end
  end
  // The head entry after this edge (no reset: read only while cnt_q > 0).
  always @(posedge clk_i)
    if (take) {w_slot_q, w_ready_q} <= nx_entry;
    else if (!head_valid_o) {w_slot_q, w_ready_q} <= hd_entry;

endmodule
