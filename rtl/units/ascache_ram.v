// ascache_ram - the data array of rtl/units/ascache.v: DEPTH lines of WIDTH bits, one write port
// and one synchronous read port (a 1R1W SRAM macro; yosys infers a $mem cell from it).
//
// The read is read-first: a read of the line written at the same edge returns the old data.
// ascache.v needs exactly that: a fill acts at the edge that ends its cycle, so an access in the
// fill's cycle that hits the victim's old line reads the old line. rdata_o holds the last read
// until the next one (no reset: it is meaningful only for a hit, and only lines that were written
// can hit).
module ascache_ram #(
  parameter integer DEPTH  = 256,
  parameter integer WIDTH  = 512,
  parameter integer ADDR_W = 8
) (
  input  wire              clk_i,
  input  wire              we_i,
  input  wire [ADDR_W-1:0] waddr_i,
  input  wire [WIDTH-1:0]  wdata_i,
  input  wire              re_i,
  input  wire [ADDR_W-1:0] raddr_i,
  output wire [WIDTH-1:0]  rdata_o
);

  reg [WIDTH-1:0] mem_q [0:DEPTH-1];
  reg [WIDTH-1:0] rdata_q;

  always @(posedge clk_i) begin
    if (we_i) mem_q[waddr_i] <= wdata_i;
    if (re_i) rdata_q <= mem_q[raddr_i];
  end

  assign rdata_o = rdata_q;

endmodule
