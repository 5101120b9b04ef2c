// membus_if - the memory bus as the units see it: N requesters' line requests, round-robin into
// one request stream to the memory, and the memory's data beats routed back to the requester.
//
// The hardware twin of systemc/membus.* minus the memory itself (its latency and the image's
// bytes are the memory's, on the far side of mem_* / beat_*):
//   - Requests (req_*[i], valid/ready; a requester holds its request until accepted): one request
//     is accepted per cycle, while fewer than DEPTH are outstanding (queue_depth) and the memory
//     takes it (mem_ready_i). Round-robin as Membus::tick: the search starts at the requester
//     after the last one accepted; when DEPTH are outstanding nobody is accepted and the pointer
//     stays. The accepted request leaves on mem_* in the same cycle (combinational), with its
//     requester index (mem_port_o) and tag; the grant may change while mem_ready_i is low.
//   - Responses: the memory returns the lines in acceptance order, each as ceil(bytes /
//     BEAT_BYTES) beats (at least one) of BEAT_BYTES bytes on beat_valid_i / beat_data_i (no
//     back-pressure, as the SystemC bus: a beat is never refused), the first at least one cycle
//     after the request was accepted. Each beat goes to its requester one cycle later (registered):
//     rsp_valid_o is one-hot by requester, with rsp_port_o (its index), the request's tag, the
//     data, the beat index and rsp_last_o on the line's last beat. The line's slot is free at the
//     edge that takes its last beat, so with the memory timed as Membus (beats on cycles first ..
//     first+beats-1, first = max(accept + latency, end of the previous line)) rsp_last_o is high
//     in the cycle Membus calls mem_resp (arrival = first + beats), and a request can be accepted
//     in that cycle again. A beat while nothing is outstanding is ignored. take_*_o show the beat
//     taken in the cycle (its request's tag, its index, whether it is the line's last).
// The round-robin is rr_arb.v (shared with membus_l2.v, which uses this module as its memory
// side).
// Parameters: N requesters (systemc/rtu.h: node, list, tri cache of each RTU), ADDR_BITS,
// LEN_BITS (request length in bytes), TAG_BITS (the requester's MSHR index), DEPTH (outstanding
// requests), BEAT_BYTES (the data bus width, Membus's bandwidth).
module membus_if #(
  parameter integer N          = 3,
  parameter integer ADDR_BITS  = 32,
  parameter integer LEN_BITS   = 12,
  parameter integer TAG_BITS   = 8,
  parameter integer DEPTH      = 32,
  parameter integer BEAT_BYTES = 16
) (
  input  wire                    clk_i,
  input  wire                    rst_ni,
  // N request channels, requester i in bits [i*X +: X]
  input  wire [N-1:0]            req_valid_i,
  output wire [N-1:0]            req_ready_o,
  input  wire [N*ADDR_BITS-1:0]  req_addr_i,
  input  wire [N*LEN_BITS-1:0]   req_bytes_i,
  input  wire [N*TAG_BITS-1:0]   req_tag_i,
  // the arbitrated request stream to the memory
  output wire                    mem_valid_o,
  input  wire                    mem_ready_i,
  output wire [ADDR_BITS-1:0]    mem_addr_o,
  output wire [LEN_BITS-1:0]     mem_bytes_o,
  output wire [((N > 1) ? $clog2(N) : 1)-1:0] mem_port_o,  // PORT_BITS
  output wire [TAG_BITS-1:0]     mem_tag_o,
  // the memory's data beats, lines in acceptance order
  input  wire                    beat_valid_i,
  input  wire [8*BEAT_BYTES-1:0] beat_data_i,
  // the beats routed back (one-hot by requester)
  output wire [N-1:0]            rsp_valid_o,
  output wire [((N > 1) ? $clog2(N) : 1)-1:0] rsp_port_o,  // PORT_BITS
  output wire [TAG_BITS-1:0]     rsp_tag_o,
  output wire [8*BEAT_BYTES-1:0] rsp_data_o,
  output wire [LEN_BITS-1:0]     rsp_beat_o,
  output wire                    rsp_last_o,
  output wire [$clog2(DEPTH + 1)-1:0] outstanding_o, // CNT_BITS: accepted, last beat not taken
  // The memory's beat taken in this cycle (combinational, before its register): its request's
  // tag and beat index, and whether it is the line's last (membus_l2.v writes it into the L2).
  output wire                    take_o,
  output wire [TAG_BITS-1:0]     take_tag_o,
  output wire [LEN_BITS-1:0]     take_beat_o,
  output wire                    take_last_o
);

  localparam integer PORT_BITS = (N > 1) ? $clog2(N) : 1;
  localparam integer PTR_BITS  = (DEPTH > 1) ? $clog2(DEPTH) : 1;
  localparam integer CNT_BITS  = $clog2(DEPTH + 1);
  localparam integer ENT_W     = PORT_BITS + TAG_BITS + LEN_BITS;
  localparam integer LAST_PTR_I  = DEPTH - 1;
  localparam integer BEAT_I      = BEAT_BYTES;
  localparam integer FULL_I      = DEPTH;
  localparam [PTR_BITS-1:0]  LAST_PTR  = LAST_PTR_I[PTR_BITS-1:0];
  localparam [CNT_BITS-1:0]  FULL      = FULL_I[CNT_BITS-1:0];
  localparam [LEN_BITS:0]    BEAT_B    = BEAT_I[LEN_BITS:0];

  // ---- round-robin arbiter ----------------------------------------------------------------------
  wire                 found;
  wire [PORT_BITS-1:0] grant;

  reg  [CNT_BITS-1:0] count_q, count_d;
  wire room   = (count_q != FULL);
  wire accept = found && room && mem_ready_i;
  rr_arb #(.N(N)) u_rr (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(req_valid_i), .adv_i(accept), .found_o(found),
    .grant_o(grant)
  );

  assign mem_valid_o = found && room;
  assign mem_addr_o  = req_addr_i[grant*ADDR_BITS +: ADDR_BITS];
  assign mem_bytes_o = req_bytes_i[grant*LEN_BITS +: LEN_BITS];
  assign mem_tag_o   = req_tag_i[grant*TAG_BITS +: TAG_BITS];
  assign mem_port_o  = grant;

  genvar g;
  generate
    for (g = 0; g < N; g = g + 1) begin : g_ready
      assign req_ready_o[g] = accept && (grant == g);
    end
  endgenerate

  // ---- outstanding requests: {port, tag, bytes} in acceptance order -----------------------------
  reg [ENT_W-1:0]    fifo_q [0:DEPTH-1];
  reg [PTR_BITS-1:0] wr_q, wr_d, rd_q, rd_d;
  reg [LEN_BITS:0]   done_q, done_d;  // bytes of the head line delivered so far
  reg [LEN_BITS-1:0] beat_q, beat_d;  // beat index within the head line

  wire [ENT_W-1:0]    head       = fifo_q[rd_q];
  wire [PORT_BITS-1:0] head_port = head[ENT_W-1 -: PORT_BITS];
  wire [TAG_BITS-1:0] head_tag   = head[LEN_BITS +: TAG_BITS];
  wire [LEN_BITS-1:0] head_bytes = head[LEN_BITS-1:0];
  wire                take       = beat_valid_i && (count_q != {CNT_BITS{1'b0}});
  wire [LEN_BITS:0]   done_next  = done_q + BEAT_B;
  wire                last       = (done_next >= {1'b0, head_bytes});
  wire                pop        = take && last;

  always @* begin
    wr_d    = wr_q;
    rd_d    = rd_q;
    done_d  = done_q;
    beat_d  = beat_q;
    count_d = count_q;
    if (accept) wr_d = (wr_q == LAST_PTR) ? {PTR_BITS{1'b0}} : wr_q + 1'b1;
    if (take) begin
      done_d = last ? {(LEN_BITS + 1){1'b0}} : done_next;
      beat_d = last ? {LEN_BITS{1'b0}} : beat_q + 1'b1;
    end
    if (pop) rd_d = (rd_q == LAST_PTR) ? {PTR_BITS{1'b0}} : rd_q + 1'b1;
    if (accept && !pop) count_d = count_q + 1'b1;
    if (pop && !accept) count_d = count_q - 1'b1;
  end

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wr_q    <= {PTR_BITS{1'b0}};
      rd_q    <= {PTR_BITS{1'b0}};
      done_q  <= {(LEN_BITS + 1){1'b0}};
      beat_q  <= {LEN_BITS{1'b0}};
      count_q <= {CNT_BITS{1'b0}};
    end else begin
      wr_q    <= wr_d;
      rd_q    <= rd_d;
      done_q  <= done_d;
      beat_q  <= beat_d;
      count_q <= count_d;
    end
  end

  // The queue's entries: no reset, written only when a request is accepted.
  always @(posedge clk_i) begin
    if (accept) fifo_q[wr_q] <= {grant, mem_tag_o, mem_bytes_o};
  end

  // ---- the beat to its requester (one register) --------------------------------------------------
  reg  [N-1:0]            rsp_valid_q;
  reg  [PORT_BITS-1:0]    rsp_port_q;
  reg  [TAG_BITS-1:0]     rsp_tag_q;
  reg  [8*BEAT_BYTES-1:0] rsp_data_q;
  reg  [LEN_BITS-1:0]     rsp_beat_q;
  reg                     rsp_last_q;
  wire [N-1:0]            onehot;
  generate
    for (g = 0; g < N; g = g + 1) begin : g_onehot
      assign onehot[g] = take && (head_port == g);
    end
  endgenerate

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) rsp_valid_q <= {N{1'b0}};
    else         rsp_valid_q <= onehot;
  end
  always @(posedge clk_i) begin
    if (take) begin
      rsp_port_q <= head_port;
      rsp_tag_q  <= head_tag;
      rsp_data_q <= beat_data_i;
      rsp_beat_q <= beat_q;
      rsp_last_q <= last;
    end
  end

  assign rsp_valid_o   = rsp_valid_q;
  assign rsp_port_o    = rsp_port_q;
  assign rsp_tag_o     = rsp_tag_q;
  assign rsp_data_o    = rsp_data_q;
  assign rsp_beat_o    = rsp_beat_q;
  assign rsp_last_o    = rsp_last_q;
  assign outstanding_o = count_q;
  assign take_o        = take;
  assign take_tag_o    = head_tag;
  assign take_beat_o   = beat_q;
  assign take_last_o   = last;

endmodule
