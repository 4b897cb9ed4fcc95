`default_nettype none
`include "bit_isa.vh"
`include "param_check.vh"
// The condition exchange between the two processors, in the setting chosen at run
// time (exchange_i, `--exchange`; the codes are `EXCHANGE_* of bit_isa.vh):
//   0 handshake:  Channels buffered condition flip-flops per direction (Fig. 11);
//                 channel k of the instruction (`= FBY k`, `READ FBY k`, ...) is used
//   1 queue:      one strict pointer-based queue per direction (Fig. 16); k ignored
//   2 queue-free: the same queues, free-running (no waits; losses counted)
//   3 marker:     the dual-port marker area with auxiliary buffer (Fig. 17): cell k
//                 per direction, written any time, read from the reader's snapshot;
//                 Cells per direction in block RAM (marker_region.v), reached through
//                 the cell ports below (an index, a read's cell a clock later), not the
//                 channel ports
// Direction "fby": bit side writes, byte side reads; "fbi": byte writes, bit reads.
//
// Exchanges says which circuits are built (a mask: 1 the flip-flops, 2 the queues, 4
// the marker area; 7, all, by default), so that a synthesized CPU carries only the
// exchange it uses. A setting whose circuit is not built is served by one that is (the
// queues, else the marker area, else the flip-flops): a one-circuit build ignores
// exchange_i, except for queue against queue-free.
module cond_exchange #(
  parameter integer Channels   = 4,  // handshake channels per direction
  parameter integer QueueDepth = 8,  // queue depth per direction (a power of two)
  parameter integer Exchanges  = 7,  // circuits built: 1 flip-flops, 2 queues, 4 marker area
  parameter integer Cells      = 128 // marker area cells per direction (a power of two)
) (
  input  wire                clk_i,
  input  wire                rst_ni,
  input  wire [1:0]          exchange_i,
  input  wire                bit_start_i,    // the bit side's scan start (its latch)
  input  wire                bit_snap_i,     // the clock before it (the bit side reads its
                                             // first instruction's cell then)
  input  wire                bit_end_i,      // the bit side's scan end (END)
  input  wire                byte_start_i,   // the byte side's scan start
  input  wire                byte_end_i,     // the byte side's scan end
  input  wire                marker_write_buffer_i,  // marker: writers publish at scan end
  // F_bB: bit side writes, byte side reads
  input  wire [Channels-1:0] fby_wr_req_i,
  input  wire                fby_wr_data_i,
  output wire [Channels-1:0] fby_wr_ready_o,
  input  wire [Channels-1:0] fby_rd_req_i,
  output wire [Channels-1:0] fby_rd_data_o,
  output wire [Channels-1:0] fby_rd_ready_o,
  output wire [Channels-1:0] fby_full_o,
  // F_Bb: byte side writes, bit side reads
  input  wire [Channels-1:0] fbi_wr_req_i,
  input  wire                fbi_wr_data_i,
  output wire [Channels-1:0] fbi_wr_ready_o,
  input  wire [Channels-1:0] fbi_rd_req_i,
  output wire [Channels-1:0] fbi_rd_data_o,
  output wire [Channels-1:0] fbi_rd_ready_o,
  output wire [Channels-1:0] fbi_full_o,
  // marker area (exchange marker): cell k by index. F_bB: the bit side writes, the byte
  // side reads; F_Bb: the byte side writes, the bit side reads. A read's cell comes in
  // the next clock; nothing ever waits.
  output wire                     marker_o,          // the marker exchange is in use
  output wire                     marker_ready_o,    // its RAMs are cleared (after reset)
  input  wire                     bit_cell_we_i,     // `= FBY k`
  input  wire [$clog2(Cells)-1:0] bit_cell_widx_i,
  input  wire                     bit_cell_wdata_i,
  input  wire                     bit_cell_re_i,     // `A FBI k` ...
  input  wire [$clog2(Cells)-1:0] bit_cell_ridx_i,
  output wire                     bit_cell_rdata_o,
  input  wire                     byte_cell_we_i,    // WRITE FBI k
  input  wire [$clog2(Cells)-1:0] byte_cell_widx_i,
  input  wire                     byte_cell_wdata_i,
  input  wire                     byte_cell_re_i,    // READ FBY k
  input  wire [$clog2(Cells)-1:0] byte_cell_ridx_i,
  output wire                     byte_cell_rdata_o,
  // free-running losses: {to-bit, to-byte}; up to one clock late, *_now_o exact
  // (cond_queue.v)
  output wire [31:0]         overflows_o,
  output wire [31:0]         underflows_o,
  output wire [31:0]         overflows_now_o,
  output wire [31:0]         underflows_now_o
);
  localparam [0:0] HasFf     = (Exchanges & 1) != 0;
  localparam [0:0] HasQueue  = (Exchanges & 2) != 0;
  localparam [0:0] HasMarker = (Exchanges & 4) != 0;

  if (Channels < 1) begin : g_bad_channels
    `PARAM_ERROR("cond_exchange: Channels must be at least 1");
  end
  // (marker_region.v checks Cells)
  if (Exchanges < 1 || Exchanges > 7) begin : g_bad_exchanges
    `PARAM_ERROR("cond_exchange: Exchanges must be 1..7 (1 flip-flops, 2 queues, 4 marker area)");
  end

  // What exchange_i asks for, and which built circuit serves it. With all three built
  // this is exactly exchange_i; constants in a one-circuit build, so its selection
  // multiplexers vanish.
  wire want_ff     = exchange_i == `EXCHANGE_HANDSHAKE;
  wire want_queue  = exchange_i == `EXCHANGE_QUEUE || exchange_i == `EXCHANGE_QUEUE_FREE;
  wire want_marker = exchange_i == `EXCHANGE_MARKER;
  wire use_queue_d  = HasQueue && (want_queue || (!(HasFf && want_ff) &&
                                                  !(HasMarker && want_marker)));
  wire use_marker_d = HasMarker && !use_queue_d && (want_marker || !(HasFf && want_ff));
  // The selection is registered, so that the multiplexers below and the queues' mode
  // come from flip-flops: a channel's ready reaches the waiting processor through one
  // multiplexer. A setting takes effect in the clock after it is written (the host
  // sets it before a run; after reset the marker memories take 2 048 clocks to clear).
  reg use_queue, use_marker, use_ff, free;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      {use_queue, use_marker, use_ff, free} <= 4'b0000;
    end else begin
      use_queue  <= use_queue_d;
      use_marker <= use_marker_d;
      use_ff     <= HasFf && !use_queue_d && !use_marker_d;
      free       <= exchange_i == `EXCHANGE_QUEUE_FREE;
    end
  end

  // ------------------------------------------------------------ handshake channels
  wire [Channels-1:0] ff_fby_wr_ready, ff_fby_rd_data, ff_fby_rd_ready, ff_fby_full;
  wire [Channels-1:0] ff_fbi_wr_ready, ff_fbi_rd_data, ff_fbi_rd_ready, ff_fbi_full;
  genvar k;
  if (HasFf) begin : g_ff
    for (k = 0; k < Channels; k = k + 1) begin : g_channel
      cond_ff u_fby (
        .clk_i     (clk_i),
        .rst_ni    (rst_ni),
        .wr_req_i  (fby_wr_req_i[k] && use_ff),
        .wr_data_i (fby_wr_data_i),
        .wr_ready_o(ff_fby_wr_ready[k]),
        .rd_req_i  (fby_rd_req_i[k] && use_ff),
        .rd_data_o (ff_fby_rd_data[k]),
        .rd_ready_o(ff_fby_rd_ready[k]),
        .full_o    (ff_fby_full[k])
      );
      cond_ff u_fbi (
        .clk_i     (clk_i),
        .rst_ni    (rst_ni),
        .wr_req_i  (fbi_wr_req_i[k] && use_ff),
        .wr_data_i (fbi_wr_data_i),
        .wr_ready_o(ff_fbi_wr_ready[k]),
        .rd_req_i  (fbi_rd_req_i[k] && use_ff),
        .rd_data_o (ff_fbi_rd_data[k]),
        .rd_ready_o(ff_fbi_rd_ready[k]),
        .full_o    (ff_fbi_full[k])
      );
    end
  end else begin : g_no_ff
    // never selected
    assign {ff_fby_wr_ready, ff_fby_rd_data, ff_fby_rd_ready, ff_fby_full} = {(4*Channels){1'b0}};
    assign {ff_fbi_wr_ready, ff_fbi_rd_data, ff_fbi_rd_ready, ff_fbi_full} = {(4*Channels){1'b0}};
  end

  // ------------------------------------------------------------ queues
  wire q_fby_wr_ready, q_fby_rd_data, q_fby_rd_ready, q_fby_full, q_fby_empty;
  wire q_fbi_wr_ready, q_fbi_rd_data, q_fbi_rd_ready, q_fbi_full, q_fbi_empty;
  if (HasQueue) begin : g_queue
    cond_queue #(.Depth(QueueDepth)) u_queue_fby (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .free_i      (free),
      .wr_start_i  (bit_start_i),
      .rd_start_i  (byte_start_i),
      .wr_req_i    (use_queue && |fby_wr_req_i),
      .wr_data_i   (fby_wr_data_i),
      .wr_ready_o  (q_fby_wr_ready),
      .rd_req_i    (use_queue && |fby_rd_req_i),
      .rd_data_o   (q_fby_rd_data),
      .rd_ready_o  (q_fby_rd_ready),
      .full_o      (q_fby_full),
      .empty_o     (q_fby_empty),
      .overflows_o (overflows_o[15:0]),
      .underflows_o(underflows_o[15:0]),
      .overflows_now_o (overflows_now_o[15:0]),
      .underflows_now_o(underflows_now_o[15:0])
    );
    cond_queue #(.Depth(QueueDepth)) u_queue_fbi (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .free_i      (free),
      .wr_start_i  (byte_start_i),
      .rd_start_i  (bit_start_i),
      .wr_req_i    (use_queue && |fbi_wr_req_i),
      .wr_data_i   (fbi_wr_data_i),
      .wr_ready_o  (q_fbi_wr_ready),
      .rd_req_i    (use_queue && |fbi_rd_req_i),
      .rd_data_o   (q_fbi_rd_data),
      .rd_ready_o  (q_fbi_rd_ready),
      .full_o      (q_fbi_full),
      .empty_o     (q_fbi_empty),
      .overflows_o (overflows_o[31:16]),
      .underflows_o(underflows_o[31:16]),
      .overflows_now_o (overflows_now_o[31:16]),
      .underflows_now_o(underflows_now_o[31:16])
    );
  end else begin : g_no_queue
    // never selected; no losses to count
    assign {q_fby_wr_ready, q_fby_rd_data, q_fby_rd_ready, q_fby_full, q_fby_empty} = 5'd0;
    assign {q_fbi_wr_ready, q_fbi_rd_data, q_fbi_rd_ready, q_fbi_full, q_fbi_empty} = 5'd0;
    assign overflows_o      = 32'd0;
    assign underflows_o     = 32'd0;
    assign overflows_now_o  = 32'd0;
    assign underflows_now_o = 32'd0;
  end

  // ------------------------------------------------------------ marker area
  // One block-RAM region per direction (marker_region.v): the writer's cells and the
  // reader's snapshot, taken at the reader's scan start; with the write buffer, of the
  // writer's cells as at its last scan end.
  assign marker_o = use_marker;
  if (HasMarker) begin : g_marker
    wire fby_ready, fbi_ready;
    marker_region #(.Cells(Cells)) u_region_fby (
      .clk_i         (clk_i),
      .rst_ni        (rst_ni),
      .write_buffer_i(marker_write_buffer_i),
      .ready_o       (fby_ready),
      .wr_req_i      (bit_cell_we_i && use_marker),
      .wr_idx_i      (bit_cell_widx_i),
      .wr_data_i     (bit_cell_wdata_i),
      .publish_i     (bit_end_i),
      .snap_i        (byte_start_i),
      .rd_req_i      (byte_cell_re_i),      // (a read has no effect)
      .rd_idx_i      (byte_cell_ridx_i),
      .rd_data_o     (byte_cell_rdata_o)
    );
    marker_region #(.Cells(Cells)) u_region_fbi (
      .clk_i         (clk_i),
      .rst_ni        (rst_ni),
      .write_buffer_i(marker_write_buffer_i),
      .ready_o       (fbi_ready),
      .wr_req_i      (byte_cell_we_i && use_marker),
      .wr_idx_i      (byte_cell_widx_i),
      .wr_data_i     (byte_cell_wdata_i),
      .publish_i     (byte_end_i),
      .snap_i        (bit_snap_i),
      .rd_req_i      (bit_cell_re_i),
      .rd_idx_i      (bit_cell_ridx_i),
      .rd_data_o     (bit_cell_rdata_o)
    );
    assign marker_ready_o = fby_ready && fbi_ready;
  end else begin : g_no_marker
    assign marker_ready_o    = 1'b1;    // never selected
    assign bit_cell_rdata_o  = 1'b0;
    assign byte_cell_rdata_o = 1'b0;
  end

  // ------------------------------------------------------------ selection
  wire [Channels-1:0] ones  = {Channels{1'b1}};
  wire [Channels-1:0] zeros = {Channels{1'b0}};
  // (the marker area's cells go through the cell ports: its channels are always ready)
  assign fby_wr_ready_o = use_queue ? {Channels{q_fby_wr_ready}} : use_marker ? ones : ff_fby_wr_ready;
  assign fby_rd_data_o  = use_queue ? {Channels{q_fby_rd_data}}  : use_marker ? zeros : ff_fby_rd_data;
  assign fby_rd_ready_o = use_queue ? {Channels{q_fby_rd_ready}} : use_marker ? ones : ff_fby_rd_ready;
  assign fby_full_o     = use_queue ? {{(Channels-1){1'b0}}, q_fby_full} :
                          use_marker ? {Channels{1'b0}} : ff_fby_full;
  assign fbi_wr_ready_o = use_queue ? {Channels{q_fbi_wr_ready}} : use_marker ? ones : ff_fbi_wr_ready;
  assign fbi_rd_data_o  = use_queue ? {Channels{q_fbi_rd_data}}  : use_marker ? zeros : ff_fbi_rd_data;
  assign fbi_rd_ready_o = use_queue ? {Channels{q_fbi_rd_ready}} : use_marker ? ones : ff_fbi_rd_ready;
  assign fbi_full_o     = use_queue ? {{(Channels-1){1'b0}}, q_fbi_full} :
                          use_marker ? {Channels{1'b0}} : ff_fbi_full;

  // The queues' empty flags are not needed; a build without some circuit leaves its
  // inputs (scan starts and ends, read strobes, the settings) unused.
  // verilator lint_off UNUSEDSIGNAL
  wire unused_absent = ^{q_fby_empty, q_fbi_empty, bit_start_i, bit_end_i, byte_start_i,
                         byte_end_i, marker_write_buffer_i, fby_rd_req_i, fbi_rd_req_i,
                         use_ff, free, bit_snap_i, fby_wr_req_i, fby_wr_data_i,
                         fbi_wr_req_i, fbi_wr_data_i, bit_cell_we_i, bit_cell_widx_i,
                         bit_cell_wdata_i, bit_cell_re_i, bit_cell_ridx_i, byte_cell_we_i,
                         byte_cell_widx_i, byte_cell_wdata_i, byte_cell_re_i,
                         byte_cell_ridx_i};
  // verilator lint_on UNUSEDSIGNAL
endmodule
`default_nettype wire
