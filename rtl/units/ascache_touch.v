// ascache_touch - the LRU update of one set of rtl/units/ascache.v when way way_i is used (a hit
// or a fill): way_i gets rank 0 (most recent) and every way that was more recent than it ages by
// one. The ranks of a set are always a permutation of 0..WAYS-1 (reset: way w has rank w), so
// among the ways used since reset their order is the order of last use: exactly the order of
// raycore::sc::Ascache's stamps. Combinational.
module ascache_touch #(
  parameter integer WAYS = 4,
  parameter integer RW   = 2   // rank / way index width: $clog2(WAYS), at least 1
) (
  input  wire [WAYS*RW-1:0] rank_i,
  input  wire [RW-1:0]      way_i,
  output reg  [WAYS*RW-1:0] rank_o
);

  localparam [RW-1:0] ONE = 1;

  reg [RW-1:0] sel;
  integer w;
  always @* begin
    sel = {RW{1'b0}};
    for (w = 0; w < WAYS; w = w + 1)
      if (way_i == w[RW-1:0]) sel = rank_i[w*RW +: RW];
    for (w = 0; w < WAYS; w = w + 1) begin
      if (way_i == w[RW-1:0])          rank_o[w*RW +: RW] = {RW{1'b0}};
      else if (rank_i[w*RW +: RW] < sel) rank_o[w*RW +: RW] = rank_i[w*RW +: RW] + ONE;
      else                             rank_o[w*RW +: RW] = rank_i[w*RW +: RW];
    end
  end

endmodule
