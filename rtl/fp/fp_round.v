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
  // never the leading one of a nonzero magnitude): level j merges two groups of 2^j bits, the upper
  // group's count if it has a one, else 2^j + the lower group's. Log depth, so the shifter's
  // stages follow the count instead of each waiting on the previous stage's zero test.
  localparam integer P = 1 << LZ_W;
  reg [P-1:0]      zv, zn;        // per group: all zero
  reg [P*LZ_W-1:0] cv, cn;        // per group: its leading-zero count (LZ_W bits each)
  reg [LZ_W-1:0]   lz;
  integer j, g;
  always @* begin
    zv = ~({mag_i, {(P-MAG_BITS){1'b1}}});
    cv = {(P*LZ_W){1'b0}};
    for (j = 0; j < LZ_W; j = j + 1) begin
      zn = {P{1'b0}};
      cn = {(P*LZ_W){1'b0}};
      for (g = 0; g < (P >> (j + 1)); g = g + 1) begin
        zn[g] = zv[2*g+1] & zv[2*g];
        cn[g*LZ_W +: LZ_W] = zv[2*g+1] ? (cv[(2*g)*LZ_W +: LZ_W] | (1 << j))
                                       : cv[(2*g+1)*LZ_W +: LZ_W];
      end
      zv = zn;
      cv = cn;
    end
    lz = cv[LZ_W-1:0];
  end
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
