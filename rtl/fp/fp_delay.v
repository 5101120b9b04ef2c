// fp_delay - a pipeline's carry: fp_pipe's interface and timing, its data in a memory when the
// pipeline never stalls.
//
// FREE = 0, or STAGES < MEM_MIN: fp_pipe itself (valid/ready with back-pressure).
// FREE = 1 and STAGES >= MEM_MIN: the caller promises out_ready_i = 1 whenever out_valid_o is set
// (a free-running pipeline: ist.v in ist_unit, hit.v in hit_unit, whose results are never held
// back), so every item leaves exactly STAGES cycles after it entered and the data need no register
// per stage: a memory of STAGES words is written every cycle at a counter modulo STAGES and read
// STAGES - 1 cycles later (the word written then: the counter plus one) into an output register.
// The valid bits travel in an fp_pipe of the same STAGES (bubbles included), so out_valid_o and
// in_ready_o are fp_pipe's. Storage: WIDTH flip-flops and a STAGES x WIDTH one-write one-read
// memory (an SRAM or register file; docs/area.md lists its bits apart) instead of STAGES x WIDTH
// flip-flops. out_data_o is meaningful while out_valid_o is set, as fp_pipe's. If the promise is
// broken (out_ready_i low with an item at the output) the data of the held item is lost: the units
// that set FREE tie out_ready_i to 1.
// lint: also FREE=1 STAGES=3 WIDTH=8
// lint: also FREE=1 STAGES=8 WIDTH=5
module fp_delay #(
  parameter integer WIDTH   = 1,
  parameter integer STAGES  = 1,
  parameter integer FREE    = 0,
  parameter integer MEM_MIN = 3   // the fewest STAGES kept in a memory
) (
  input  wire             clk_i,
  input  wire             rst_ni,
  input  wire             in_valid_i,
  output wire             in_ready_o,
  input  wire [WIDTH-1:0] in_data_i,
  output wire             out_valid_o,
  input  wire             out_ready_i,
  output wire [WIDTH-1:0] out_data_o
);
  generate
    if (FREE == 0 || STAGES < MEM_MIN || STAGES < 2) begin : g_pipe
      fp_pipe #(.WIDTH(WIDTH), .STAGES(STAGES)) u_pipe (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
        .in_data_i(in_data_i), .out_valid_o(out_valid_o), .out_ready_i(out_ready_i),
        .out_data_o(out_data_o));
    end else begin : g_mem
      localparam integer AW = $clog2(STAGES);
      localparam integer LASTI = STAGES - 1;
      localparam [AW-1:0] LAST = LASTI[AW-1:0];
      wire unused_d;
      fp_pipe #(.WIDTH(1), .STAGES(STAGES)) u_valid (
        .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
        .in_data_i(1'b0), .out_valid_o(out_valid_o), .out_ready_i(out_ready_i),
        .out_data_o(unused_d));
      reg [WIDTH-1:0] mem [0:STAGES-1];
      reg [WIDTH-1:0] q;
      reg [AW-1:0]    wa_q;
      // The word read now is the one written STAGES - 1 cycles ago: the next write address.
      wire [AW-1:0]   ra = (wa_q == LAST) ? {AW{1'b0}} : wa_q + 1'b1;
      always @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) wa_q <= {AW{1'b0}};
        else         wa_q <= ra;
      end
      always @(posedge clk_i) begin
        mem[wa_q] <= in_data_i;
        q <= mem[ra];
      end
      assign out_data_o = q;
    end
  endgenerate
endmodule
