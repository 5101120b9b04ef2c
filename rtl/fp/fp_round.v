// fp_round - the shared "raw result -> round once -> flush/saturate -> pack" step.
//
// The twin of hls::round_pack in hls/fp.h. The exact value of the raw result is
//   (-1)^sign_i * (mag_i + s) * 2^(exp_i - bias - (MAG_BITS-1)),   s = 0 if !sticky_i, 0 < s < 1 else,
// i.e. exp_i is the biased exponent the result has if the top bit of mag_i is its leading one.
// The magnitude is normalised (leading zeros counted by a tree, then one log shift), rounded once to
// MAN_BITS+1 significant bits (RNE = 0: toward zero, RNE = 1: to nearest, ties to even), then
// flushed to a signed zero below the smallest normal and saturated to the largest magnitude above
// the largest binade. mag_i == 0 gives +0 (an exact zero sum is +0 in both rounding modes).
// Precondition (as hls::round_pack): if sticky_i, mag_i has at least MAN_BITS+2 significant bits.
// Purely combinational.
module fp_round #(
  parameter integer EXP_BITS = 7,
  parameter integer MAN_BITS = 16,
  parameter integer RNE      = 0,
  parameter integer MAG_BITS = MAN_BITS + 5,  // >= MAN_BITS + 3
  parameter integer EXP_W    = EXP_BITS + 3   // signed width of exp_i, holds every exponent used
) (
  input  wire                         sign_i,
  input  wire signed [EXP_W-1:0]      exp_i,
  input  wire [MAG_BITS-1:0]          mag_i,
  input  wire                         sticky_i,
  output reg  [EXP_BITS+MAN_BITS:0]   res_o
);

  localparam integer LZ_W = $clog2(MAG_BITS);  // 2^LZ_W - 1 >= MAG_BITS - 1: any shift fits

  // ---- normalise: count the leading zeros, then shift left by that count ----------------------
  // The count by a tree over the magnitude padded below with ones to 2^LZ_W bits (a pad bit is
  // never the leading one of a nonzero magnitude): a node merges its two groups, the upper group's
  // count if it has a one, else half the node's width + the lower group's. Log depth, so the
  // shifter's stages follow the count instead of each waiting on the previous stage's zero test.
  // Each node is a wire of its own (split_var), not a slice of a wide level vector rewritten in a
  // loop: the same function, and under half the C++ from Verilator (every FP operator has one;
  // rtu.v's per-cycle C++ 37 -> 18 MB).
  localparam integer P = 1 << LZ_W;
  // Node n of the tree in heap order (root 0, children 2n+1 (upper) and 2n+2 (lower), leaves
  // P-1 .. 2P-2 = the padded magnitude's bits from the top): z[n] the group is all zero, c[n] its
  // leading-zero count; a node at depth d sets bit LZ_W-1-d when its upper child is all zero.
  wire [P-1:0]    xp = {mag_i, {(P-MAG_BITS){1'b1}}};
  wire            z [0:2*P-2] /*verilator split_var*/;
  wire [LZ_W-1:0] c [0:2*P-2] /*verilator split_var*/;
  genvar n;
  generate
    for (n = 0; n < P; n = n + 1) begin : g_leaf
      assign z[P-1+n] = ~xp[P-1-n];
      assign c[P-1+n] = {LZ_W{1'b0}};
    end
    for (n = 0; n < P-1; n = n + 1) begin : g_node
      localparam integer D = $clog2(n + 2) - 1;  // the node's depth
      assign z[n] = z[2*n+1] & z[2*n+2];
      assign c[n] = z[2*n+1] ? (c[2*n+2] | (1 << (LZ_W-1-D))) : c[2*n+1];
    end
  endgenerate
  wire [LZ_W-1:0] lz = c[0];
  wire [MAG_BITS-1:0] norm = mag_i << lz;
  wire                nonzero = |mag_i;

  // ---- round once ------------------------------------------------------------------------------
  // norm = 1.man (the leading one at the top), then the guard bit, then the rest.
  wire [MAN_BITS-1:0] man    = norm[MAG_BITS-2 -: MAN_BITS];
  wire                guard  = norm[MAG_BITS-2-MAN_BITS];
  wire                rest   = (|norm[MAG_BITS-3-MAN_BITS:0]) | sticky_i;
  wire                rnd_up = (RNE != 0) && guard && (rest || man[0]);

  // {exponent, mantissa field} + round: a mantissa carry increments the exponent by itself.
  wire signed [EXP_W-1:0] exp_norm = exp_i - $signed({{(EXP_W-LZ_W){1'b0}}, lz});
  wire [EXP_W+MAN_BITS-1:0] packed_r = {exp_norm, man}
                                        + {{(EXP_W+MAN_BITS-1){1'b0}}, rnd_up};
  wire signed [EXP_W-1:0] exp_r = packed_r[EXP_W+MAN_BITS-1:MAN_BITS];

  localparam signed [EXP_W-1:0] EXP_FIELD_MAX = (1 << EXP_BITS) - 1;
  localparam signed [EXP_W-1:0] EXP_ONE       = 1;

  // ---- flush, saturate, pack -------------------------------------------------------------------
  always @* begin
    res_o = {sign_i, exp_r[EXP_BITS-1:0], packed_r[MAN_BITS-1:0]};
    if (!nonzero) begin
      res_o = {(EXP_BITS+MAN_BITS+1){1'b0}};                   // exact zero: +0
    end else if (exp_r < EXP_ONE) begin
      res_o = {sign_i, {(EXP_BITS+MAN_BITS){1'b0}}};           // flush: no denormals
    end else if (exp_r > EXP_FIELD_MAX) begin
      res_o = {sign_i, {(EXP_BITS+MAN_BITS){1'b1}}};           // saturate: no Inf
    end
  end

endmodule
