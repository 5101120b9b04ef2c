// fp_pipe - a chain of STAGES handshake registers (valid/ready with back-pressure).
//
// The generic pipeline register used by every unit in rtl/: data_i travels through STAGES
// registers to data_o. Index i of the internal signals holds the signal after i register stages
// (index 0 = the input, index STAGES = the output). The stall rule is one line: a stage accepts
// new data if it is empty or its content leaves this cycle (ready[i] = !valid[i+1] | ready[i+1]),
// so a full chain moves one item per cycle and the ready path is combinational back to the input.
// STAGES = 0 is a wire (no clock used).
//
// Only the valid bits are reset; data registers load only when a valid item enters (no reset, no
// toggling on bubbles), and their content is meaningful only while the matching valid bit is set.
module fp_pipe #(
  parameter integer WIDTH  = 1,
  parameter integer STAGES = 1
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
    if (STAGES == 0) begin : g_wire
      assign out_valid_o = in_valid_i;
      assign in_ready_o  = out_ready_i;
      assign out_data_o  = in_data_i;
      // No registers: the clock and reset are not needed.
      wire unused_clk_rst;
      assign unused_clk_rst = clk_i ^ rst_ni;
    end else begin : g_regs
      // Index i: after i register stages.
      wire [STAGES:0]             valid;
      reg  [STAGES:0]             ready;
      wire [(STAGES+1)*WIDTH-1:0] data;
      reg  [STAGES-1:0]           valid_d, valid_q;
      reg  [STAGES*WIDTH-1:0]     data_d, data_q;
      integer i, j;

      assign valid[0]                       = in_valid_i;
      assign valid[STAGES:1]                = valid_q;
      assign data[WIDTH-1:0]                = in_data_i;
      assign data[(STAGES+1)*WIDTH-1:WIDTH] = data_q;

      // The stall rule, from the output back to the input: register i (which holds index i+1)
      // takes a new item if it is empty or its item leaves. ready[i] is what index i sees.
      always @* begin
        ready[STAGES] = out_ready_i;
        for (i = STAGES - 1; i >= 0; i = i - 1) ready[i] = !valid_q[i] || ready[i+1];
      end

      always @* begin
        valid_d = valid_q;
        data_d  = data_q;
        for (j = 0; j < STAGES; j = j + 1) begin
          if (ready[j]) begin
            valid_d[j] = valid[j];
            if (valid[j]) data_d[j*WIDTH +: WIDTH] = data[j*WIDTH +: WIDTH];
          end
        end
      end

      always @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) valid_q <= {STAGES{1'b0}};
        else         valid_q <= valid_d;
      end

      always @(posedge clk_i) begin
        data_q <= data_d;
      end

      assign in_ready_o  = ready[0];
      assign out_valid_o = valid[STAGES];
      assign out_data_o  = data[STAGES*WIDTH +: WIDTH];
    end
  endgenerate

endmodule
