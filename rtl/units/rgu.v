// rgu - the ray generation unit of one RTU: its pixels in tile order (rgu_walk) through the
// primary-ray datapath (rgu_ray), one ray per cycle.
//
// Twin of the cycle model's primary-ray path (systemc/rgu.h): hls::RguTiles gives the pixel
// order (tile i of the frame to RTU i mod N, row-major within a tile, pixels outside the frame
// skipped) and hls::rgu_primary each ray, bit for bit. The shadow rays that the cycle model's rgu
// also forwards (hit -> trv) are a queue hand-off with no arithmetic; they are not part of this
// module.
//
// Configuration registers, written by the host before start_i and stable while busy_o:
//   cam_*    hls::RguCamera (origin o, d00, dx, dy; numbers of the format)
//   width_i, height_i (>= 1), rtu_i < rtus_i (this RTU and the number of RTUs)
// start_i (while idle) begins the frame. The rays come out with valid/ready and back-pressure:
//   out_o_*, out_d_*, out_inv_* (hls::Ray's o, d, inv; tmin and tmax are the host's registers),
//   out_pixel_o = y * width + x.
// busy_o is high from start_i until the last ray has left.
//
// Latency: the walk's set-up (max(rtu_i, rtus_i) / tiles_x + 1 cycles after start_i, tiles_x =
// ceil(width / 2^TILE_BITS)), one walk register, then 15 * STAGES cycles of datapath (rgu_ray's
// LPS x STAGES); then one ray
// per cycle while out_ready_i is high.
module rgu #(
  parameter integer EXP_BITS   = 7,
  parameter integer MAN_BITS   = 16,
  parameter integer RNE        = 0,
  parameter integer RAYCORE    = 0,   // rounding mode raycore (FP24; overrides RNE): see rgu_ray
  parameter integer STAGES     = 2,
  parameter integer COORD_BITS = 16,
  parameter integer TILE_BITS  = 3,
  parameter integer RTU_BITS   = 8
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  // Configuration.
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
  input  wire                       start_i,
  output wire                       busy_o,
  // Primary rays out.
  output wire                       out_valid_o,
  input  wire                       out_ready_i,
  output wire [EXP_BITS+MAN_BITS:0] out_o_x_o,
  output wire [EXP_BITS+MAN_BITS:0] out_o_y_o,
  output wire [EXP_BITS+MAN_BITS:0] out_o_z_o,
  output wire [EXP_BITS+MAN_BITS:0] out_d_x_o,
  output wire [EXP_BITS+MAN_BITS:0] out_d_y_o,
  output wire [EXP_BITS+MAN_BITS:0] out_d_z_o,
  output wire [EXP_BITS+MAN_BITS:0] out_inv_x_o,
  output wire [EXP_BITS+MAN_BITS:0] out_inv_y_o,
  output wire [EXP_BITS+MAN_BITS:0] out_inv_z_o,
  output wire [2*COORD_BITS-1:0]    out_pixel_o
);

  localparam integer PB = 2 * COORD_BITS;
  // Rays inside the datapath: at most its latency, 15 * STAGES (rgu_ray's LPS x STAGES), + 1 at
  // STAGES = 0 (combinational).
  localparam integer CNT_W = $clog2(15 * STAGES + 2);

  wire                  walk_busy, walk_valid, walk_ready;
  wire [COORD_BITS-1:0] walk_x, walk_y;
  wire [PB-1:0]         walk_pixel;

  rgu_walk #(.COORD_BITS(COORD_BITS), .TILE_BITS(TILE_BITS), .RTU_BITS(RTU_BITS)) u_walk (
    .clk_i(clk_i), .rst_ni(rst_ni), .start_i(start_i), .width_i(width_i), .height_i(height_i),
    .rtu_i(rtu_i), .rtus_i(rtus_i), .busy_o(walk_busy),
    .out_valid_o(walk_valid), .out_ready_i(walk_ready),
    .out_x_o(walk_x), .out_y_o(walk_y), .out_pixel_o(walk_pixel));

  rgu_ray #(.EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES),
            .TAG_BITS(PB), .COORD_BITS(COORD_BITS)) u_ray (
    .clk_i(clk_i), .rst_ni(rst_ni),
    .cam_o_x_i(cam_o_x_i), .cam_o_y_i(cam_o_y_i), .cam_o_z_i(cam_o_z_i),
    .cam_d00_x_i(cam_d00_x_i), .cam_d00_y_i(cam_d00_y_i), .cam_d00_z_i(cam_d00_z_i),
    .cam_dx_x_i(cam_dx_x_i), .cam_dx_y_i(cam_dx_y_i), .cam_dx_z_i(cam_dx_z_i),
    .cam_dy_x_i(cam_dy_x_i), .cam_dy_y_i(cam_dy_y_i), .cam_dy_z_i(cam_dy_z_i),
    .in_valid_i(walk_valid), .in_ready_o(walk_ready),
    .in_x_i(walk_x), .in_y_i(walk_y), .in_tag_i(walk_pixel),
    .out_valid_o(out_valid_o), .out_ready_i(out_ready_i),
    .out_o_x_o(out_o_x_o), .out_o_y_o(out_o_y_o), .out_o_z_o(out_o_z_o),
    .out_d_x_o(out_d_x_o), .out_d_y_o(out_d_y_o), .out_d_z_o(out_d_z_o),
    .out_inv_x_o(out_inv_x_o), .out_inv_y_o(out_inv_y_o), .out_inv_z_o(out_inv_z_o),
    .out_tag_o(out_pixel_o));

  // Rays in the datapath: one more on each pixel taken, one less on each ray leaving.
  wire             ray_in  = walk_valid & walk_ready;
  wire             ray_out = out_valid_o & out_ready_i;
  reg  [CNT_W-1:0] inflight_d, inflight_q;
  always @* begin
    inflight_d = inflight_q;
    if (ray_in && !ray_out)      inflight_d = inflight_q + 1'b1;
    else if (!ray_in && ray_out) inflight_d = inflight_q - 1'b1;
  end
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) inflight_q <= {CNT_W{1'b0}};
    else         inflight_q <= inflight_d;
  end

  assign busy_o = walk_busy | (|inflight_q);

endmodule
