// rgu_walk - the ray generation unit's pixel walk: the pixels of one RTU, in the cycle model's
// order, one per cycle.
//
// Twin of hls::RguTiles (hls/rgu.h), the order in which systemc/rgu.h issues primary rays: the
// frame is cut into tiles of T x T pixels (T = 2^TILE_BITS), numbered row-major; tile i belongs
// to RTU i mod N; an RTU walks its tiles in increasing order and each tile row-major, skipping the
// pixels outside the frame (the right and bottom edge tiles are clipped).
//
// start_i (while idle) begins a frame with width_i x height_i pixels (>= 1 each; a zero size
// gives no pixels), rtu_i of rtus_i RTUs (rtus_i >= 1, rtu_i < rtus_i): these inputs must stay
// stable while busy_o is high. The unit first divides rtu_i and rtus_i by the number of tile
// columns (one subtraction per cycle, about max(rtu_i, rtus_i) / tiles_x + 1 cycles), giving its
// first tile (column, row) and the step to its next tile, then walks without bubbles: one pixel
// per cycle (out_valid_o from a register, held until out_ready_i), x, y and the pixel index
// y * width + x (out_pixel_o, kept by additions: no multiplier). The step to the next tile is
// one add of the column step with a single wrap (the step's column is below tiles_x), so every
// pixel, edge tiles included, takes one cycle. busy_o falls after the last pixel is taken.
module rgu_walk #(
  parameter integer COORD_BITS = 16,  // width, height <= 2^COORD_BITS - 1
  parameter integer TILE_BITS  = 3,   // tiles of 2^TILE_BITS x 2^TILE_BITS pixels (8 x 8)
  parameter integer RTU_BITS   = 8    // rtus_i <= 2^RTU_BITS - 1
) (
  input  wire                    clk_i,
  input  wire                    rst_ni,
  input  wire                    start_i,
  input  wire [COORD_BITS-1:0]   width_i,
  input  wire [COORD_BITS-1:0]   height_i,
  input  wire [RTU_BITS-1:0]     rtu_i,
  input  wire [RTU_BITS-1:0]     rtus_i,
  output wire                    busy_o,
  output wire                    out_valid_o,
  input  wire                    out_ready_i,
  output wire [COORD_BITS-1:0]   out_x_o,
  output wire [COORD_BITS-1:0]   out_y_o,
  output wire [2*COORD_BITS-1:0] out_pixel_o
);

  localparam integer CB  = COORD_BITS;
  localparam integer TB  = TILE_BITS;
  localparam integer PB  = 2 * COORD_BITS;               // pixel index
  localparam integer TXW = CB - TB + 1;                  // tile counts: ceil(size / T)
  localparam integer MW  = (RTU_BITS > TXW ? RTU_BITS : TXW) + 1;  // tile rows, remainders
  localparam [1:0] ST_IDLE = 2'd0, ST_INIT = 2'd1, ST_RUN = 2'd2;

  // ---- frame constants --------------------------------------------------------------------------
  wire [CB:0]    w_round  = {1'b0, width_i} + {{(CB+1-TB){1'b0}}, {TB{1'b1}}};
  wire [CB:0]    h_round  = {1'b0, height_i} + {{(CB+1-TB){1'b0}}, {TB{1'b1}}};
  wire [MW-1:0]  tiles_x  = {{(MW-TXW){1'b0}}, w_round[CB:TB]};
  wire [MW-1:0]  tiles_y  = {{(MW-TXW){1'b0}}, h_round[CB:TB]};
  wire [PB-1:0]  w_pix    = {{CB{1'b0}}, width_i};
  wire [PB-1:0]  tile_row = w_pix << TB;                 // T * width: one row of tiles
  wire           empty    = ~|width_i | ~|height_i;
  // The remainders of the rounding up are not needed.
  wire unused_round = ^{w_round[TB-1:0], h_round[TB-1:0]};

  // ---- state ------------------------------------------------------------------------------------
  reg [1:0]    st_d, st_q;
  // INIT: rtu_i = qa * tiles_x + ra, rtus_i = qb * tiles_x + rb; ba = qa * T * width, bb likewise.
  reg [MW-1:0] ra_d, ra_q, qa_d, qa_q, rb_d, rb_q, qb_d, qb_q;
  reg [PB-1:0] ba_d, ba_q, bb_d, bb_q;
  // RUN: the current tile (column tx, row ty, tbase = index of pixel (0, ty * T)), the current
  // pixel (x, y, rbase = y * width, pix = rbase + x).
  reg [MW-1:0] tx_d, tx_q, ty_d, ty_q;
  reg [CB-1:0] x_d, x_q, y_d, y_q;
  reg [PB-1:0] tbase_d, tbase_q, rbase_d, rbase_q, pix_d, pix_q;

  // ---- the next tile of this RTU: tile index + rtus = (ty + qb) * tiles_x + tx + rb -------------
  wire [MW-1:0] ntx_sum  = tx_q + rb_q;                  // < 2 * tiles_x
  wire          ntx_wrap = ntx_sum >= tiles_x;
  wire [MW-1:0] ntx      = ntx_wrap ? ntx_sum - tiles_x : ntx_sum;
  wire [MW-1:0] nty      = ty_q + qb_q + {{(MW-1){1'b0}}, ntx_wrap};
  wire [PB-1:0] ntbase   = tbase_q + bb_q + (ntx_wrap ? tile_row : {PB{1'b0}});

  // The first pixel of tile (tx, ty); its tile is in the frame if ty < tiles_y.
  wire [MW+TB-1:0] ntx_x  = {ntx, {TB{1'b0}}};
  wire [MW+TB-1:0] nty_y  = {nty, {TB{1'b0}}};
  wire [MW+TB-1:0] ra_x   = {ra_q, {TB{1'b0}}};
  wire [MW+TB-1:0] qa_y   = {qa_q, {TB{1'b0}}};
  wire [MW+TB-1:0] tx_x   = {tx_q, {TB{1'b0}}};
  // Always zero where used (inside the frame): the coordinates' bits above COORD_BITS.
  wire unused_hi = ^{ntx_x[MW+TB-1:CB], nty_y[MW+TB-1:CB], ra_x[MW+TB-1:CB], qa_y[MW+TB-1:CB],
                     tx_x[MW+TB-1:CB]};

  wire last_col = (&x_q[TB-1:0]) | (x_q == width_i - 1'b1);
  wire last_row = (&y_q[TB-1:0]) | (y_q == height_i - 1'b1);
  wire init_done = (ra_q < tiles_x) & (rb_q < tiles_x);
  wire take = (st_q == ST_RUN) & out_ready_i;

  always @* begin
    st_d    = st_q;
    ra_d    = ra_q;
    qa_d    = qa_q;
    ba_d    = ba_q;
    rb_d    = rb_q;
    qb_d    = qb_q;
    bb_d    = bb_q;
    tx_d    = tx_q;
    ty_d    = ty_q;
    x_d     = x_q;
    y_d     = y_q;
    tbase_d = tbase_q;
    rbase_d = rbase_q;
    pix_d   = pix_q;
    case (st_q)
      ST_IDLE: begin
        if (start_i && !empty) begin
          st_d = ST_INIT;
          ra_d = {{(MW-RTU_BITS){1'b0}}, rtu_i};
          rb_d = {{(MW-RTU_BITS){1'b0}}, rtus_i};
          qa_d = {MW{1'b0}};
          qb_d = {MW{1'b0}};
          ba_d = {PB{1'b0}};
          bb_d = {PB{1'b0}};
        end
      end
      ST_INIT: begin
        if (init_done) begin
          // The first tile: column ra, row qa.
          st_d    = qa_q < tiles_y ? ST_RUN : ST_IDLE;
          tx_d    = ra_q;
          ty_d    = qa_q;
          x_d     = ra_x[CB-1:0];
          y_d     = qa_y[CB-1:0];
          tbase_d = ba_q;
          rbase_d = ba_q;
          pix_d   = ba_q + {{CB{1'b0}}, ra_x[CB-1:0]};
        end else begin
          if (ra_q >= tiles_x) begin
            ra_d = ra_q - tiles_x;
            qa_d = qa_q + 1'b1;
            ba_d = ba_q + tile_row;
          end
          if (rb_q >= tiles_x) begin
            rb_d = rb_q - tiles_x;
            qb_d = qb_q + 1'b1;
            bb_d = bb_q + tile_row;
          end
        end
      end
      ST_RUN: begin
        if (take) begin
          if (!last_col) begin
            x_d   = x_q + 1'b1;
            pix_d = pix_q + 1'b1;
          end else if (!last_row) begin
            x_d     = tx_x[CB-1:0];
            y_d     = y_q + 1'b1;
            rbase_d = rbase_q + w_pix;
            pix_d   = rbase_q + w_pix + {{CB{1'b0}}, tx_x[CB-1:0]};
          end else begin
            st_d    = nty < tiles_y ? ST_RUN : ST_IDLE;
            tx_d    = ntx;
            ty_d    = nty;
            x_d     = ntx_x[CB-1:0];
            y_d     = nty_y[CB-1:0];
            tbase_d = ntbase;
            rbase_d = ntbase;
            pix_d   = ntbase + {{CB{1'b0}}, ntx_x[CB-1:0]};
          end
        end
      end
      default: st_d = ST_IDLE;
    endcase
  end

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) st_q <= ST_IDLE;
    else         st_q <= st_d;
  end

  // Data registers: no reset (meaningful only in the states that use them).
  always @(posedge clk_i) begin
    ra_q    <= ra_d;
    qa_q    <= qa_d;
    ba_q    <= ba_d;
    rb_q    <= rb_d;
    qb_q    <= qb_d;
    bb_q    <= bb_d;
    tx_q    <= tx_d;
    ty_q    <= ty_d;
    x_q     <= x_d;
    y_q     <= y_d;
    tbase_q <= tbase_d;
    rbase_q <= rbase_d;
    pix_q   <= pix_d;
  end

  assign busy_o      = st_q != ST_IDLE;
  assign out_valid_o = st_q == ST_RUN;
  assign out_x_o     = x_q;
  assign out_y_o     = y_q;
  assign out_pixel_o = pix_q;

endmodule
