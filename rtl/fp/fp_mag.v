// fp_mag - magnitude of a two's-complement value: mag_o = neg_i ? -x_i : x_i (mod 2^WIDTH),
// combinational. -x bit i = x[i] ^ (any lower bit of x set), the lower bits' OR by a log-depth
// prefix instead of ~x + 1's carry chain. fp_add3 (phase C) and fp_sop (phase D) take |sum| with it.
module fp_mag #(
  parameter integer WIDTH = 8
) (
  input  wire [WIDTH-1:0] x_i,
  input  wire             neg_i,
  output wire [WIDTH-1:0] mag_o
);

  reg [WIDTH-1:0] below;  // bit i: x[i-1:0] != 0
  integer k;
  always @* begin
    below = x_i << 1;
    for (k = 1; k < WIDTH; k = k * 2) below = below | (below << k);
  end
  assign mag_o = neg_i ? (x_i ^ below) : x_i;

endmodule
