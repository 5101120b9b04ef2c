// ascache_ram - the data array of rtl/units/ascache.v: DEPTH lines of WIDTH bits, one write port
// and one synchronous read port (a 1R1W SRAM macro; yosys infers a $mem cell from it).
//
// The read is write-first (transparent): a read of the line written at the same edge returns the
// new data. ascache.v needs exactly that: a fill and an access are ordered fill first within a
// cycle (as the cycle model ticks them), so an access that hits the line being installed reads the
// fill's data. rdata_o holds the last read until the next one (no reset: it is meaningful only
// for a hit, and only lines that were written can hit).
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
    if (re_i) begin
      if (we_i && waddr_i == raddr_i) rdata_q <= wdata_i;
      else                            rdata_q <= mem_q[raddr_i];
    end
  end

  assign rdata_o = rdata_q;

endmodule
