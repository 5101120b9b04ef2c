// tb/sweep/tb_spawn_slab.v - Icarus Verilog testbench for rtl/units/spawn.v's skip-slab (5) and
// skip-back (6) datapaths against hls/hit.h (vectors from spawn_vecgen).
//
// Reads N vectors (ten 32-bit words: h_x h_y h_z dens tmin scale t back | tmin' t_back) with
// $readmemh from +vectors=<file>; drives them through the valid/ready handshake with random input
// gaps and random output back-pressure (+seed=<n>); checks at the output, in order, the shadow
// ray's t_min, the origin (= the hit point) and the tag; checks out_t_back_o (a side path without
// latency) when a vector is accepted (STRATEGY 6; = t for 5). Prints the first 10 mismatches and
//   RESULT vectors=<checked> mismatches=<k>
// Parameters (iverilog -P): EXP_BITS, MAN_BITS, RNE, RAYCORE, STAGES, STRATEGY, N.
`timescale 1ns / 1ps
module tb_spawn_slab;
  parameter integer EXP_BITS = 7;
  parameter integer MAN_BITS = 16;
  parameter integer RNE      = 0;
  parameter integer RAYCORE  = 0;
  parameter integer STAGES   = 2;
  parameter integer STRATEGY = 6;
  parameter integer N        = 1;
  localparam integer W = 1 + EXP_BITS + MAN_BITS;

  reg [319:0]      vec [0:N-1];
  `include "tb_stream.vh"  // path, seed, counters, clk, rst_n, in_valid, out_ready; reset, clock

  reg  [W-1:0]     hx, hy, hz, dens, tmin, scale, t;
  reg  [31:0]      back;
  reg  [15:0]      in_tag;
  wire             in_ready, out_valid, unused_cand;
  wire [W-1:0]     ox, oy, oz, out_tmin, out_t_back;
  wire [31:0]      unused_skip;
  wire [15:0]      out_tag;
  wire [W-1:0]     z = {W{1'b0}};

  spawn #(
    .EXP_BITS(EXP_BITS), .MAN_BITS(MAN_BITS), .RNE(RNE), .RAYCORE(RAYCORE), .STAGES(STAGES), .TAG_BITS(16),
    .STRATEGY(STRATEGY)
  ) dut (
    .clk_i(clk), .rst_ni(rst_n), .in_valid_i(in_valid), .in_ready_o(in_ready),
    .in_k_i(2'd0), .in_front_i(1'b1), .in_all_i(1'b0), .in_side_neg_i(1'b0), .in_id_i(32'd7),
    .in_h_x_i(hx), .in_h_y_i(hy), .in_h_z_i(hz), .in_n_u_i(z), .in_n_v_i(z), .in_n_d_i(z),
    .in_o_x_i(z), .in_o_y_i(z), .in_o_z_i(z), .in_d_x_i(z), .in_d_y_i(z), .in_d_z_i(z),
    .in_td_x_i(z), .in_td_y_i(z), .in_td_z_i(z), .in_t_i(t), .in_den_i(z), .in_scale_i(scale),
    .in_fixed_i(z), .in_cand_id_i(32'd0), .in_ray_skip_i(32'd0), .in_dens_i(dens),
    .in_tmin_i(tmin), .in_back_i(back), .in_tag_i(in_tag),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_o_x_o(ox), .out_o_y_o(oy),
    .out_o_z_o(oz), .out_skip_id_o(unused_skip), .out_cand_skip_o(unused_cand),
    .out_tmin_o(out_tmin), .out_t_back_o(out_t_back), .out_tag_o(out_tag)
  );

  // Word k (0 = h_x ... 9 = t_back) of a vector, low W bits.
  function [W-1:0] word;
    input [319:0] v;
    input integer k;
    word = v[(9 - k) * 32 +: W];
  endfunction

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
          if (out_tmin !== word(vec[n_out], 8) || ox !== word(vec[n_out], 0) || oy !== word(vec[n_out], 1) ||
              oz !== word(vec[n_out], 2) || out_tag !== n_out[15:0]) begin
            errors = errors + 1;
            if (errors <= 10)
              $display("MISMATCH #%0d vector %0d: h %h %h %h dens %h: tmin expected %h, got %h; origin %h %h %h; tag %0d",
                       errors, n_out, word(vec[n_out], 0), word(vec[n_out], 1), word(vec[n_out], 2),
                       word(vec[n_out], 3), word(vec[n_out], 8), out_tmin, ox, oy, oz, out_tag);
          end
          n_out = n_out + 1;
        end
      end
      if (in_valid && in_ready) begin  // accepted at this edge; the side path is checked here
        if (out_t_back !== (STRATEGY == 6 ? word(vec[n_in], 9) : word(vec[n_in], 6))) begin
          errors = errors + 1;
          if (errors <= 10)
            $display("MISMATCH #%0d vector %0d: t %h back %0d: expected %h, got %h", errors, n_in,
                     word(vec[n_in], 6), back, word(vec[n_in], 9), out_t_back);
        end
        n_in = n_in + 1;
      end
      if (!in_valid || in_ready) begin
        if (n_in < N && ($random(seed) & 3) != 0) begin
          in_valid <= 1'b1;
          hx <= word(vec[n_in], 0);
          hy <= word(vec[n_in], 1);
          hz <= word(vec[n_in], 2);
          dens <= word(vec[n_in], 3);
          tmin <= word(vec[n_in], 4);
          scale <= word(vec[n_in], 5);
          t <= word(vec[n_in], 6);
          back <= vec[n_in][64 +: 32];
          in_tag <= n_in[15:0];
        end else begin
          in_valid <= 1'b0;
          hx <= $random(seed);  // junk, must be ignored
          dens <= $random(seed);
        end
      end
      out_ready <= ($random(seed) & 3) != 0;
      stream_check_end;
    end
  end
endmodule
