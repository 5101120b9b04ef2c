// tb_chip - a whole frame on chip.v (RTUS = 1): the chip top with its bus, closed-loop with
// a memory timed as systemc/membus.cpp's RTL view (Membus::dram_accept: a line accepted at cycle
// a has its beats on cycles first .. first + beats - 1, first = max(a + LAT, the previous line's
// end); mem_ready_i always high, membus_if bounds the outstanding lines). The frame's registers,
// the image and its regions come from `raycore simulate --rtl rtu` with RAYCORE_CHIP_DUMP=<prefix>
// (systemc/rtu_rtl.cpp); tb/rtl/run_chip.sh runs it and compares. Defines: DUMP (the prefix, a
// string), IMG (the image's bytes), LAT (--mem-latency), L2_SETS (0: no L2, chip.v's membus_if),
// L2_WAYS, L2_LAT (--l2-latency; the L2's line is the caches', 64 bytes, its beats 32 bytes: the
// model's), SPAWNS (chip.v's: the spawn strategies built, from --spawn). Prints every ray leaving the hit unit to
// <prefix>.chip.px (pixel, kind, best record) and "RESULT cycles=<last retire + 1> retired=<n>".
// Verilog-2005 with delays: iverilog -g2005, or verilator --binary --timing.
`timescale 1ns/1ps
module tb_chip;
  localparam integer W = 24, BB = 16, LAT = `LAT, IMG = `IMG;
  localparam integer BW = 67 + 5 * W;
  localparam integer PX = 2 * 16 + 3 + BW + 3 * W + 1 + W + 11 * W;  // chip.v's PX_
  reg clk = 1'b0, rst_n = 1'b1, start = 1'b0;
  reg [12*W-1:0] cam;
  reg [6*W-1:0]  box;
  reg [3*W-1:0]  light, vtu_cam;
  reg [15:0]     width, height, trv_lat, node_hl, list_hl, qcap;
  reg [7:0]      rtus, slots, tri_hl;
  reg [W-1:0]    tmin, eps, one_eps, scale, fixed, slab_scale;
  reg [4:0]      pipes, ist_units;
  reg [6:0]      depth, widen;
  reg [2:0]      strategy;
  reg            fuse, any_hit, empty, segment, all, vtu_on;
  reg [31:0]     back, node_count, tri_count, b_node, b_list, b_tri, img_size;
  wire           mem_valid;
  wire [31:0]    mem_addr;
  wire [11:0]    mem_bytes;
  wire [1:0]     mem_port;
  wire [2:0]     mem_tag;
  reg            beat_valid = 1'b0;
  reg [8*BB-1:0] beat_data = {8*BB{1'b0}};
  wire [PX:0]    px;
  wire           done, err;
  wire [5:0]     outstanding;
  wire [63:0]    cnt;
  chip #(.RTUS(1), .L2_SETS(`L2_SETS), .L2_WAYS(`L2_WAYS), .SPAWNS(`SPAWNS)) dut (
    .clk_i(clk), .rst_ni(rst_n), .start_i(start), .cam_i(cam), .width_i(width), .height_i(height),
    .rtus_i(rtus), .slots_i(slots), .tmin_i(tmin), .trv_lat_i(trv_lat), .node_hl_i(node_hl),
    .list_hl_i(list_hl), .pipes_i(pipes), .fuse_i(fuse), .any_hit_i(any_hit), .empty_i(empty),
    .depth_i(depth), .widen_i(widen), .box_i(box), .eps_i(eps), .one_eps_i(one_eps), .qcap_i(qcap),
    .tri_hl_i(tri_hl), .ist_units_i(ist_units), .light_i(light), .strategy_i(strategy),
    .segment_i(segment), .all_i(all), .back_i(back), .scale_i(scale), .fixed_i(fixed),
    .slab_scale_i(slab_scale), .vtu_on_i(vtu_on), .vtu_cam_i(vtu_cam), .node_count_i(node_count),
    .tri_count_i(tri_count), .base_i({b_tri, b_list, b_node}), .l2_lat_i(16'd`L2_LAT),
    .mem_valid_o(mem_valid), .mem_ready_i(1'b1), .mem_addr_o(mem_addr), .mem_bytes_o(mem_bytes),
    .mem_port_o(mem_port), .mem_tag_o(mem_tag), .beat_valid_i(beat_valid), .beat_data_i(beat_data),
    .px_o(px), .done_o(done), .err_o(err), .outstanding_o(outstanding), .cnt_rtu_i(8'd0),
    .cnt_sel_i(6'd0), .cnt_o(cnt));

  reg [7:0]  img [0:IMG-1];
  reg [31:0] l_addr [0:63];   // the lines accepted and not yet delivered, in order
  reg [63:0] l_first [0:63];
  reg [15:0] l_beats [0:63];
  reg [63:0] now, data_free, first, last_retire;
  integer    fd, r, k, pxf, retired, lw, lr, ld;
  initial begin
    fd = $fopen({`DUMP, ".regs"}, "r");
    if (fd == 0) begin $display("RESULT error: no %s.regs", `DUMP); $finish; end
    r = $fscanf(fd, " %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h %h",
        cam, box, light, vtu_cam, width, height, rtus, slots, tmin, trv_lat, node_hl, list_hl, pipes,
        fuse, any_hit, empty, depth, widen, eps, one_eps, qcap, tri_hl, ist_units, strategy, segment,
        all, back, scale, fixed, slab_scale, vtu_on, node_count, tri_count, b_node, b_list, b_tri,
        img_size);
    $fclose(fd);
    if (r != 37 || img_size != IMG) begin
      $display("RESULT error: %s.regs: %0d fields, image %0d bytes (IMG %0d)", `DUMP, r, img_size, IMG);
      $finish;
    end
    $readmemh({`DUMP, ".img"}, img);
    pxf = $fopen({`DUMP, ".chip.px"}, "w");
    lw = 0; lr = 0; ld = 0; data_free = 0; now = 0; retired = 0; last_retire = 0;
    #1 rst_n = 1'b0;
    #1 clk = 1'b1;  // an edge in the reset: rtu.v's frame registers load the pins
    #1 clk = 1'b0;
    #1 rst_n = 1'b1;
    #1;
    forever begin
      start = (now == 0);
      beat_valid = (lr != lw) && (l_first[lr % 64] + ld == now);  // the memory's beat
      for (k = 0; k < BB; k = k + 1)
        beat_data[8*k +: 8] = (l_addr[lr % 64] + ld * BB + k < IMG) ? img[l_addr[lr % 64] + ld * BB + k]
                                                                  : 8'd0;
      #1;
      if (px[PX]) begin
        $fdisplay(pxf, "%h %h %h", px[PX-1 -: 32], px[PX-33], px[PX-36 -: BW]);
        retired = retired + 1;
        last_retire = now;
      end
      if (mem_valid) begin  // accepted in this cycle
        first = (now + LAT > data_free) ? now + LAT : data_free;
        l_addr[lw % 64] = mem_addr;
        l_first[lw % 64] = first;
        l_beats[lw % 64] = (mem_bytes + BB - 1) / BB;
        data_free = first + (mem_bytes + BB - 1) / BB;
        lw = lw + 1;
      end
      if (beat_valid) begin
        ld = ld + 1;
        if (ld == l_beats[lr % 64]) begin ld = 0; lr = lr + 1; end
      end
      clk = 1'b1; #1; clk = 1'b0; #1;
      if (err) begin $display("RESULT error: a ray overflowed its stack"); $finish; end
      if (done && now > 0) begin
        $display("RESULT cycles=%0d retired=%0d", last_retire + 1, retired);
        $fclose(pxf);
        $finish;
      end
      if (now > last_retire + 1000000) begin $display("RESULT error: hang at %0d", now); $finish; end
      now = now + 1;
    end
  end
endmodule
