// tb/rtl/tb_fp_add.v - Icarus Verilog testbench for rtl/fp/fp_add.v (the second simulator).
//
// Reads N vectors ({a, b, sub, expected}, 32 bits each, written by fp_vecgen from hls/fp.h) with
// $readmemh from the file given as +vectors=<file>, drives them through fp_add's valid/ready
// handshake with random input gaps and random output back-pressure (seeded by +seed=<n>), checks
// every result and its tag (the vector index) in order, prints the first 10 mismatches and a final
//   RESULT vectors=<checked> mismatches=<k>
// line. Parameters (iverilog -P): EXP_BITS, MAN_BITS, RNE, RAYCORE, STAGES, N.
`timescale 1ns / 1ps
module tb_fp_add;
  parameter integer EXP_BITS = 7;
  parameter integer MAN_BITS = 16;
  parameter integer RNE      = 0;
  parameter integer RAYCORE  = 0;
  parameter integer STAGES   = 2;
  parameter integer N        = 1;
  localparam integer W = 1 + EXP_BITS + MAN_BITS;

  reg [127:0]      vec [0:N-1];
  `include "tb_stream.vh"  // path, seed, counters, clk, rst_n, in_valid, out_ready; reset, clock

  reg              in_sub;
  reg  [W-1:0]     in_a, in_b;
  reg  [15:0]      in_tag;
  wire             in_ready, out_valid;
  wire [W-1:0]     out_res;
  wire [15:0]      out_tag;

  fp_add #(
    .EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .TAG_BITS(16)
  ) dut (
    .clk_i(clk), .rst_ni(rst_n),
    .in_valid_i(in_valid), .in_ready_o(in_ready),
    .in_a_i(in_a), .in_b_i(in_b), .in_sub_i(in_sub), .in_tag_i(in_tag),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_res_o(out_res), .out_tag_o(out_tag)
  );

  // Synchronous driver and checker: samples the DUT's outputs as they are before the clock edge.
  always @(posedge clk) begin
    if (rst_n) begin
      cycles = cycles + 1;
      idle = idle + 1;
      if (out_valid && out_ready) begin
        idle = 0;
        if (n_out >= N) begin
          errors = errors + 1;
          $display("MISMATCH: result with nothing in flight (tag %0d)", out_tag);
        end else begin
          if (out_res !== vec[n_out][W-1:0] || out_tag !== n_out[15:0]) begin
            errors = errors + 1;
            if (errors <= 10)
              $display("MISMATCH #%0d vector %0d: %h %s %h: expected %h, got %h (tag %0d, expected %0d)",
                       errors, n_out, vec[n_out][96 +: W], vec[n_out][32] ? "-" : "+",
                       vec[n_out][64 +: W], vec[n_out][W-1:0], out_res, out_tag, n_out[15:0]);
          end
          n_out = n_out + 1;
        end
      end
      if (in_valid && in_ready) n_in = n_in + 1;  // accepted at this edge
      if (!in_valid || in_ready) begin             // free to present the next one (or a gap)
        if (n_in < N && ($random(seed) & 3) != 0) begin
          in_valid <= 1'b1;
          in_a     <= vec[n_in][96 +: W];
          in_b     <= vec[n_in][64 +: W];
          in_sub   <= vec[n_in][32];
          in_tag   <= n_in[15:0];
        end else begin
          in_valid <= 1'b0;
          in_a     <= $random(seed);  // junk, must be ignored
          in_b     <= $random(seed);
        end
      end
      out_ready <= ($random(seed) & 3) != 0;
      stream_check_end;
    end
  end
endmodule
