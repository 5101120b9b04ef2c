// slot_ram - the fields of a ray slot that trv_unit.v does not keep (systemc/slot.h's Slot::pixel
// and Slot::skip_id): what the ist and the frame buffer's pixel write read of a ray in flight. The
// ray itself, its kind, the ist's tmax and the best record are trv_unit.v's slot arrays, read
// through its rd_* ports (READS = 1).
//   pixel    written when a primary ray from the rgu takes the slot; a shadow ray keeps it;
//   skip_id  all ones for a primary ray; for a shadow ray the primary hit's triangle, which the
//            ist does not test it against (hit.v's out_skip_id_o).
// Reads are asynchronous (same-cycle read ports, as the units' bindings read systemc's slots); the
// writes of a cycle are seen from the next one. The rgu and the hit unit never write one slot in
// one cycle (the rgu takes a free slot; the hit unit's is in flight).
// lint: also SLOT_BITS=7 IST=4
module slot_ram #(
  parameter integer SLOT_BITS  = 3,
  parameter integer IST        = 2,
  parameter integer COORD_BITS = 16
) (
  input  wire                        clk_i,
  // A primary ray from the rgu.
  input  wire                        pri_valid_i,
  input  wire [SLOT_BITS-1:0]        pri_slot_i,
  input  wire [2*COORD_BITS-1:0]     pri_pixel_i,
  // A shadow ray the hit unit leaves in its slot.
  input  wire                        shd_valid_i,
  input  wire [SLOT_BITS-1:0]        shd_slot_i,
  input  wire [31:0]                 shd_skip_id_i,
  // Read ports: the skip id of ist unit u's entry, the pixel of the ray leaving the hit unit.
  input  wire [IST*SLOT_BITS-1:0]    ist_slot_i,
  output wire [IST*32-1:0]           ist_skip_id_o,
  input  wire [SLOT_BITS-1:0]        px_slot_i,
  output wire [2*COORD_BITS-1:0]     px_pixel_o
);

  localparam integer NS = 1 << SLOT_BITS;

  reg [2*COORD_BITS-1:0] pixel_q [0:NS-1];
  reg [31:0]             skip_q  [0:NS-1];

  always @(posedge clk_i) begin
    if (pri_valid_i) begin
      pixel_q[pri_slot_i] <= pri_pixel_i;
      skip_q[pri_slot_i]  <= 32'hFFFF_FFFF;
    end
    if (shd_valid_i) skip_q[shd_slot_i] <= shd_skip_id_i;
  end

  genvar u;
  generate
    for (u = 0; u < IST; u = u + 1) begin : g_ist
      assign ist_skip_id_o[u*32 +: 32] = skip_q[ist_slot_i[u*SLOT_BITS +: SLOT_BITS]];
    end
  endgenerate
  assign px_pixel_o = pixel_q[px_slot_i];

endmodule
