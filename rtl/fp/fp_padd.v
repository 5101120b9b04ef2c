// fp_padd - parallel-prefix adder: sum_o = a_i + b_i + ci_i (mod 2^WIDTH), combinational.
//
// The operators' wide integer sums (fp_add3's three-input accumulator) written as a Kogge-Stone
// prefix network, log2(WIDTH) levels of generate/propagate combines, instead of the `+` that
// yosys 0.23 maps to a ripple-carry chain (58 bits of fp_add3's accumulator: 54 AOI/OAI stages,
// 7.5 ns of a 9.6 ns path at rtl/ 8043638, docs/timing.md). Word-parallel form: each level
// is three operations on whole vectors, so that a Verilated model evaluates it in a few words.
module fp_padd #(
  parameter integer WIDTH = 8
) (
  input  wire [WIDTH-1:0] a_i,
  input  wire [WIDTH-1:0] b_i,
  input  wire             ci_i,
  output wire [WIDTH-1:0] sum_o
);

  wire [WIDTH-1:0] p0 = a_i ^ b_i;
  // g[i] after the levels: the carry out of bits 0..i (ci_i folded into bit 0's generate).
  reg [WIDTH-1:0] g, p;
  integer k;
  always @* begin
    g = (a_i & b_i) | {{(WIDTH-1){1'b0}}, p0[0] & ci_i};
    p = p0;
    for (k = 1; k < WIDTH; k = k * 2) begin
      g = g | (p & (g << k));
      p = p & (p << k);
    end
  end
  wire [WIDTH-1:0] carry = {g[WIDTH-2:0], ci_i};  // into bit i: out of bits 0..i-1
  assign sum_o = p0 ^ carry;

endmodule
