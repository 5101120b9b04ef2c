// rgu_unit - the ray generation unit whole: rgu.v (the tile walk and the primary-ray datapath), the
// shadow-ray hand-off from the hit unit, and the free ray slots. One ray per cycle goes to the trv:
// a shadow ray the hit unit hands over in this cycle first, else the next primary ray into a free
// slot. The RTL view of systemc/rgu.h: bound into the running frame by systemc/rgu_rtl.h (raycore
// simulate --rtl rgu), cycle for cycle and bit for bit the transaction model's.
//
// Per cycle (systemc/rgu.h, Rgu::tick, after the hit unit's cycle):
//   - a slot the hit unit frees in this cycle (free_*) joins the free slots: a stack, whose top is
//     the last slot freed (the cycle model's free-slot vector); slots never used come after every
//     freed one, in order 0, 1, .. slots_i - 1;
//   - a shadow ray the hit unit hands over in this cycle (shadow_*, its slot already holding the
//     ray) goes to the trv (out_*, out_shadow_o); otherwise
//   - rgu.v's next primary ray, once its start-up is over, goes to the trv in the top free slot
//     (the slot freed in this same cycle, if any); without a free slot the unit stalls
//     (cnt_stall_o).
// The ray to the trv carries the interval of every primary ray: tmin_i, and the format's largest
// magnitude as tmax (hls::rgu_interval). start_i starts rgu.v (cycle 0 of the frame).
// lint: also SLOT_BITS=7 STAGES=2
module rgu_unit #(
  parameter integer EXP_BITS   = 7,
  parameter integer MAN_BITS   = 16,
  parameter integer RNE        = 0,
  parameter integer RAYCORE    = 0,
  parameter integer STAGES     = 2,
  parameter integer COORD_BITS = 16,
  parameter integer TILE_BITS  = 3,
  parameter integer RTU_BITS   = 8,
  parameter integer SLOT_BITS  = 3
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  // Configuration (rgu.v's camera and frame registers), static per frame.
  input  wire [EXP_BITS+MAN_BITS:0] cam_o_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_o_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_o_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_d00_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_d00_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_d00_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dx_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dx_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dx_z_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dy_x_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dy_y_i,
  input  wire [EXP_BITS+MAN_BITS:0] cam_dy_z_i,
  input  wire [COORD_BITS-1:0]      width_i,
  input  wire [COORD_BITS-1:0]      height_i,
  input  wire [RTU_BITS-1:0]        rtu_i,
  input  wire [RTU_BITS-1:0]        rtus_i,
  input  wire [EXP_BITS+MAN_BITS:0] tmin_i,
  input  wire [SLOT_BITS:0]         slots_i,     // ray slots in use (1 .. 2^SLOT_BITS)
  input  wire                       start_i,
  output wire                       busy_o,      // rgu.v: primary rays still to come
  // From the hit unit, this cycle.
  input  wire                       free_valid_i,
  input  wire [SLOT_BITS-1:0]       free_slot_i,
  input  wire                       shadow_valid_i,
  input  wire [SLOT_BITS-1:0]       shadow_slot_i,
  // The ray to the trv (trv_unit's in_*): {o xyz, d xyz, inv xyz, tmin, tmax}; a shadow ray's
  // is in its slot already (out_ray_o is then the next primary ray's, unused).
  output wire                       out_valid_o,
  output wire [SLOT_BITS-1:0]       out_slot_o,
  output wire                       out_shadow_o,
  output wire [11*(1+EXP_BITS+MAN_BITS)-1:0] out_ray_o,
  output wire [2*COORD_BITS-1:0]    out_pixel_o,
  // Free slots, and the counters (RtuStats: primary_rays, shadow_rays, rgu_stall_no_slot).
  output wire [SLOT_BITS:0]         free_count_o,
  output reg  [63:0]                cnt_primary_o,
  output reg  [63:0]                cnt_shadow_o,
  output reg  [63:0]                cnt_stall_o
);

  localparam integer W  = 1 + EXP_BITS + MAN_BITS;
  localparam integer NS = 1 << SLOT_BITS;
  localparam [W-1:0] MAX_MAG = {1'b0, {(W-1){1'b1}}};

  // ---- rgu.v ------------------------------------------------------------------------------------
  wire          p_valid, p_ready;
  wire [W-1:0]  p_ox, p_oy, p_oz, p_dx, p_dy, p_dz, p_ix, p_iy, p_iz;
  rgu #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES),
        .COORD_BITS(COORD_BITS), .TILE_BITS(TILE_BITS), .RTU_BITS(RTU_BITS)) u_rgu (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .cam_o_x_i(cam_o_x_i), .cam_o_y_i(cam_o_y_i), .cam_o_z_i(cam_o_z_i),
    .cam_d00_x_i(cam_d00_x_i), .cam_d00_y_i(cam_d00_y_i), .cam_d00_z_i(cam_d00_z_i),
    .cam_dx_x_i(cam_dx_x_i), .cam_dx_y_i(cam_dx_y_i), .cam_dx_z_i(cam_dx_z_i),
    .cam_dy_x_i(cam_dy_x_i), .cam_dy_y_i(cam_dy_y_i), .cam_dy_z_i(cam_dy_z_i),
    .width_i(width_i), .height_i(height_i), .rtu_i(rtu_i), .rtus_i(rtus_i),
    .start_i(start_i), .busy_o(busy_o),
    .out_valid_o(p_valid), .out_ready_i(p_ready),
    .out_o_x_o(p_ox), .out_o_y_o(p_oy), .out_o_z_o(p_oz),
    .out_d_x_o(p_dx), .out_d_y_o(p_dy), .out_d_z_o(p_dz),
    .out_inv_x_o(p_ix), .out_inv_y_o(p_iy), .out_inv_z_o(p_iz),
    .out_pixel_o(out_pixel_o));

  // ---- the free slots: freed ones on a stack, then the never used in order -----------------------
  reg [SLOT_BITS-1:0] stk_q [0:NS-1];
  reg [SLOT_BITS:0]   sp_q;     // freed slots on the stack
  reg [SLOT_BITS:0]   fresh_q;  // slots 0 .. fresh_q - 1 have been used
  wire                have_fresh = (fresh_q < slots_i);
  wire                have_free  = free_valid_i || (sp_q != {(SLOT_BITS+1){1'b0}}) || have_fresh;
  // The stack's top entry (sp_q >= 1), an index of its own width: the tools disagree on the width
  // of an array index like `stk_q[a - 1'b1]` (Verilator wraps it, Icarus does not).
  wire [SLOT_BITS-1:0] sp_top = sp_q[SLOT_BITS-1:0] - 1'b1;
  wire [SLOT_BITS-1:0] top = free_valid_i ? free_slot_i
                           : (sp_q != {(SLOT_BITS+1){1'b0}}) ? stk_q[sp_top]
                                                              : fresh_q[SLOT_BITS-1:0];
  assign free_count_o = sp_q + (slots_i - fresh_q);

  // ---- the ray of this cycle --------------------------------------------------------------------
  wire primary = !shadow_valid_i && p_valid && have_free;
  assign p_ready      = primary;
  assign out_valid_o  = shadow_valid_i || primary;
  assign out_shadow_o = shadow_valid_i;
  assign out_slot_o   = shadow_valid_i ? shadow_slot_i : top;
  assign out_ray_o    = {p_ox, p_oy, p_oz, p_dx, p_dy, p_dz, p_ix, p_iy, p_iz, tmin_i, MAX_MAG};

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sp_q          <= {(SLOT_BITS+1){1'b0}};
      fresh_q       <= {(SLOT_BITS+1){1'b0}};
      cnt_primary_o <= 64'd0;
      cnt_shadow_o  <= 64'd0;
      cnt_stall_o   <= 64'd0;
    end else begin
      // A freed slot is pushed unless this cycle's primary ray takes it at once.
      if (free_valid_i && !primary) begin
        stk_q[sp_q[SLOT_BITS-1:0]] <= free_slot_i;
        sp_q <= sp_q + 1'b1;
      end else if (primary && !free_valid_i) begin
        if (sp_q != {(SLOT_BITS+1){1'b0}}) sp_q <= sp_q - 1'b1;
        else fresh_q <= fresh_q + 1'b1;
      end
      if (primary) cnt_primary_o <= cnt_primary_o + 64'd1;
      if (shadow_valid_i) cnt_shadow_o <= cnt_shadow_o + 64'd1;
      if (!shadow_valid_i && p_valid && !have_free) cnt_stall_o <= cnt_stall_o + 64'd1;
    end
  end

endmodule
