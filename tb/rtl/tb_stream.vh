// tb/rtl/tb_stream.vh - the part of an Icarus stream testbench that does not depend on the DUT
// (included inside the module by tb/rtl/tb_fp_add.v and tb/sweep/tb_spawn_slab.v; iverilog -I tb/rtl).
// The including module declares N (the vector count) and `vec`, and its posedge block drives and
// checks the DUT with these variables, calling stream_check_end at the end of every cycle:
//   path/seed from +vectors=<file> / +seed=<n>; vec loaded with $readmemh; reset for 20 ns; a 10 ns
//   clock; n_in / n_out = vectors accepted / results checked; errors; cycles; idle = cycles since
//   the last result.
  reg [8*512-1:0]  path;
  integer          seed, n_in, n_out, errors, cycles, idle;
  reg              clk, rst_n, in_valid, out_ready;

  initial begin
    if (!$value$plusargs("vectors=%s", path)) begin
      $display("RESULT vectors=0 mismatches=0 error: no +vectors=<file>");
      $finish;
    end
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    $readmemh(path, vec);
    n_in = 0;
    n_out = 0;
    errors = 0;
    cycles = 0;
    idle = 0;
    clk = 1'b0;
    rst_n = 1'b1;
    in_valid = 1'b0;
    out_ready = 1'b0;
    #1 rst_n = 1'b0;
    #20 rst_n = 1'b1;
  end

  always #5 clk = ~clk;

  // Every result checked, or none for 1000 cycles (a deadlock): print RESULT and stop.
  task stream_check_end;
    begin
      if (n_out == N || idle > 1000) begin
        if (n_out != N) begin
          errors = errors + 1;
          $display("MISMATCH: no result for %0d cycles, %0d of %0d checked (deadlock)", idle, n_out, N);
        end
        $display("RESULT vectors=%0d mismatches=%0d cycles=%0d", n_out, errors, cycles);
        $finish;
      end
    end
  endtask
