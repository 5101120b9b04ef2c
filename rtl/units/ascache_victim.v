// ascache_victim - the way a fill replaces in one set of rtl/units/ascache.v: the first invalid way
// (lowest index) if there is one, else the least recently used way that is not pinned (the
// highest rank among the unpinned ways). The same choice as raycore::sc::Ascache::fill: there an
// invalid way ends the search, and among valid unpinned ways the smallest last-use stamp wins
// (stamps of valid ways are distinct, so "oldest" is unique; the ranks of ascache_touch order the
// ways exactly as those stamps do). A pinned way (filled, not hit since) is never the victim;
// ascache.v allocates an MSHR only while its set has a way neither pinned nor awaited, so a fill
// always finds one (if every way were pinned, way_o would be the oldest: unreachable).
// Combinational.
module ascache_victim #(
  parameter integer WAYS = 4,
  parameter integer RW   = 2   // rank / way index width: $clog2(WAYS), at least 1
) (
  input  wire [WAYS-1:0]    valid_i,
  input  wire [WAYS-1:0]    pin_i,    // way w pinned: not a victim
  input  wire [WAYS*RW-1:0] rank_i,   // way w's rank at [w*RW +: RW]; 0 = most recently used
  output reg  [RW-1:0]      way_o
);

  localparam integer LAST = WAYS - 1;
  localparam [RW-1:0] OLDEST = LAST[RW-1:0];

  integer w, r;
  always @* begin
    way_o = {RW{1'b0}};
    for (w = WAYS - 1; w >= 0; w = w - 1)
      if (rank_i[w*RW +: RW] == OLDEST) way_o = w[RW-1:0];
    // The unpinned way of the highest rank (ranks ascending: the last match is the oldest).
    for (r = 0; r < WAYS; r = r + 1)
      for (w = 0; w < WAYS; w = w + 1)
        if (!pin_i[w] && rank_i[w*RW +: RW] == r[RW-1:0]) way_o = w[RW-1:0];
    // Then the lowest invalid way overrides (searched downwards).
    for (w = WAYS - 1; w >= 0; w = w - 1)
      if (!valid_i[w]) way_o = w[RW-1:0];
  end

endmodule
