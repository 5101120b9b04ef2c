// rr_arb - the bus's round-robin over N requesters (membus_if, membus_l2; Membus::tick's rule):
// the search starts at the requester after the last one granted and accepted; found_o and grant_o
// are combinational from valid_i. The pointer moves past the grant at the edge of a cycle with
// adv_i (the grant was accepted), and stays otherwise.
module rr_arb #(
  parameter integer N = 3,
  // Derived (not to be overridden).
  parameter integer PORT_BITS = (N > 1) ? $clog2(N) : 1
) (
  input  wire                 clk_i,
  input  wire                 rst_ni,
  input  wire [N-1:0]         valid_i,
  input  wire                 adv_i,
  output reg                  found_o,
  output reg  [PORT_BITS-1:0] grant_o
);

  localparam integer LAST_PORT_I = N - 1;
  localparam [PORT_BITS-1:0] LAST_PORT = LAST_PORT_I[PORT_BITS-1:0];

  reg [PORT_BITS-1:0] rr_q;  // the requester searched first
  reg [PORT_BITS-1:0] idx;
  integer k;
  always @* begin
    found_o = 1'b0;
    grant_o = {PORT_BITS{1'b0}};
    idx     = rr_q;
    for (k = 0; k < N; k = k + 1) begin
      if (!found_o && valid_i[idx]) begin
        found_o = 1'b1;
        grant_o = idx;
      end
      idx = (idx == LAST_PORT) ? {PORT_BITS{1'b0}} : idx + 1'b1;
    end
  end

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)    rr_q <= {PORT_BITS{1'b0}};
    else if (adv_i) rr_q <= (grant_o == LAST_PORT) ? {PORT_BITS{1'b0}} : grant_o + 1'b1;
  end

endmodule
