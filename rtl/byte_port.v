`default_nettype none
`include "byte_bus.vh"
`include "param_check.vh"
// Byte-side port: the one synchronous bus through which the byte processor (a
// microcontroller) reaches the FPGA part. Register map: docs/byte-bus.md.
// A read returns data in the clock of its strobe; an access that cannot complete
// (a condition channel empty/full) drops bus_ready_o and is repeated by the byte
// processor in the next clock, each such clock counted as a byte-side stall.
// This module is the register map and the dispatch snapshot; the time base
// (time_base.v) and the stall counters (bus_stats.v) are its submodules.
module byte_port #(
  parameter integer StatusBits = 64,  // timers and counters (each); 2..64
  parameter integer Channels   = 4,   // condition channels per direction; 1..8
  parameter integer InWords    = 16,  // IW n; 1..16
  parameter integer OutWords   = 16,  // QW n; 1..16
  parameter integer Cells      = 128  // marker area cells per direction; 8..128
) (
  input  wire                          clk_i,
  input  wire                          rst_ni,
  // the bus
  input  wire [7:0]                    bus_addr_i,
  input  wire [31:0]                   bus_wdata_i,
  input  wire                          bus_we_i,
  input  wire                          bus_re_i,
  output wire [31:0]                   bus_rdata_o,
  output wire                          bus_ready_o,
  // scan state
  input  wire                          latch_i,      // a PII latch (clock 0 starts the time base)
  input  wire                          time_start_i, // a plant's clock 0: start it already
  input  wire                          exec_i,
  input  wire                          fault_i,
  // parallel mode: the byte side reports the end of its part of the scan
  output reg                           byte_scan_done_o,
  output wire                          byte_scan_end_o,   // SCAN_DONE written this clock
  // serial dispatch
  input  wire                          next_i,
  input  wire [31:0]                   dispatch_instr_i,
  input  wire [31:0]                   dispatch_ctx_i,
  output wire                          done_we_o,
  output wire [1:0]                    done_data_o,
  // timer/counter status buffer
  output wire                          tc_we_o,
  output wire                          tc_is_counter_o,
  output wire [$clog2(StatusBits)-1:0] tc_idx_o,
  output wire                          tc_val_o,
  input  wire [StatusBits-1:0]         timer_status_i,
  input  wire [StatusBits-1:0]         counter_status_i,
  input  wire [StatusBits-1:0]         timer_enable_i,
  input  wire [StatusBits-1:0]         counter_pulse_i,
  input  wire [StatusBits-1:0]         timer_written_i,   // enable written this scan
  input  wire [StatusBits-1:0]         counter_written_i, // pulse written this scan
  // condition channels: FBY k (bit -> byte) are read here, FBI k (byte -> bit) written
  output wire [Channels-1:0]           fby_rd_req_o,
  input  wire [Channels-1:0]           fby_rd_data_i,
  input  wire [Channels-1:0]           fby_rd_ready_i,
  input  wire [Channels-1:0]           fby_full_i,
  output wire [Channels-1:0]           fbi_wr_req_o,
  output wire                          fbi_wr_data_o,
  input  wire [Channels-1:0]           fbi_wr_ready_i,
  input  wire [Channels-1:0]           fbi_full_i,
  // the marker exchange (marker_i, a register): READ FBY k / WRITE FBI k are cell k of
  // the marker area, at FBY k / FBI k (k < 8) and in the MCELL window; a read takes two
  // clocks (block RAM: the first answers not ready, no stall), a write one
  input  wire                          marker_i,
  output wire                          cell_re_o,
  output wire [$clog2(Cells)-1:0]      cell_ridx_o,
  input  wire                          cell_rdata_i,
  output wire                          cell_we_o,
  output wire [$clog2(Cells)-1:0]      cell_widx_o,
  output wire                          cell_wdata_o,
  // word I/O (analog), no process image
  input  wire [InWords*16-1:0]         in_words_i,
  output reg  [OutWords*16-1:0]        out_words_o,
  // statistics
  input  wire                          bit_stall_i,  // the bit side waits this clock
  input  wire [31:0]                   queue_overflows_i,   // {to-bit, to-byte}
  input  wire [31:0]                   queue_underflows_i,
  output wire [31:0]                   stalls_bit_o,
  output wire [31:0]                   stalls_byte_o
);
  // Register addresses: rtl/byte_bus.vh, generated from bitbyte/lang/definition.toml. The
  // windows are decoded by their high address bits.
  localparam [7:0] AddrFby = `BUS_FBY;
  localparam [7:0] AddrFbi = `BUS_FBI;
  localparam [7:0] AddrIw  = `BUS_IW;
  localparam [7:0] AddrQw  = `BUS_QW;
  localparam [7:0] AddrMc  = `BUS_MCELL;

  // The register map fixes the sizes this port can serve (TC_BIT carries a 6-bit index,
  // the status registers are LO/HI pairs).
  `PARAM_CHECK(g_bad_status_bits, StatusBits < 2 || StatusBits > 64,
               "byte_port: StatusBits must be 2..64 (the bus has LO/HI status registers only)")
  `PARAM_CHECK(g_bad_channels, Channels < 1 || Channels > 8,
               "byte_port: Channels must be 1..8 (the bus decodes 8 FBY/FBI channels)")
  `PARAM_CHECK(g_bad_cells, Cells < 8 || Cells > 128 || (Cells & (Cells - 1)) != 0,
               "byte_port: Cells must be a power of two in 8..128 (the MCELL window)")
  `PARAM_CHECK(g_bad_in_words, InWords < 1 || InWords > 16,
               "byte_port: InWords must be 1..16 (the bus window IW has 16 registers)")
  `PARAM_CHECK(g_bad_out_words, OutWords < 1 || OutWords > 16,
               "byte_port: OutWords must be 1..16 (the bus window QW has 16 registers)")

  // ---------------------------------------------------------------- time base
  // Clock 0 is scan 0's latch, or in a plant core the plant's clock 0 (time_start_i,
  // so that its timers run on plant time). TICK_DIV is a register of the map below.
  reg  [31:0] tick_div_q;
  wire [31:0] clock_q, ms_q;           // registers of u_time_base (sim/bitbyte.gtkw: ms_q)
  time_base u_time_base (
    .clk_i     (clk_i),
    .rst_ni    (rst_ni),
    .start_i   (latch_i || time_start_i),
    .tick_div_i(tick_div_q),
    .clock_o   (clock_q),
    .ms_o      (ms_q)
  );

  // ---------------------------------------------------------------- dispatch snapshot
  // A byte instruction samples its inputs in its first clock (docs/isa.md): the time
  // base and the input word it names are captured when a dispatch begins, so the
  // firmware may read them later within the instruction's cost.
  reg        pending_q;                  // a dispatch began and DONE has not come
  reg [31:0] disp_ms_q;
  reg [15:0] disp_iw_q;
  wire       disp_first = next_i && !pending_q;
  wire [3:0] disp_word  = dispatch_instr_i[3:0];
  // the input words widened to the 16 the bus and the instruction can name (no compare)
  wire [16*16-1:0] in_words16 = {{((16-InWords)*16){1'b0}}, in_words_i};
  wire [15:0] named_iw  = in_words16[disp_word*16 +: 16];
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pending_q <= 1'b0;
      disp_ms_q <= 32'd0;
      disp_iw_q <= 16'd0;
    end else begin
      pending_q <= next_i && !done_we_o;
      if (disp_first) begin
        disp_ms_q <= ms_q;
        disp_iw_q <= named_iw;
      end
    end
  end
  // In the first clock itself the snapshot is the live value: the read data takes it
  // last (below), since next_i comes late from the bit side.

  // ---------------------------------------------------------------- latch snapshot
  // LATCH_MS: the time base in the clock of the bit side's last scan latch. S7's timers
  // (the word's at-latch bit) take their time from it, so every timer of a scan sees the
  // scan's latch time, as S7 gives each cycle one time (docs/s7.md "Timers"). In the
  // latch clock itself the read data takes the live value, as for DISPATCH_MS.
  reg [31:0] latch_ms_q;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)      latch_ms_q <= 32'd0;
    else if (latch_i) latch_ms_q <= ms_q;
  end

  // ---------------------------------------------------------------- decode
  wire [2:0] chan   = bus_addr_i[2:0];
  wire is_fby_rd    = bus_re_i && (bus_addr_i[7:3] == AddrFby[7:3]);   // 8 channels
  wire is_fbi_wr    = bus_we_i && (bus_addr_i[7:3] == AddrFbi[7:3]);
  // one-hot over the 8 channels the bus decodes, cut to the build's (no compare)
  // verilator lint_off UNUSEDSIGNAL
  wire [7:0] chan_sel8 = 8'd1 << chan;     // bits of channels the build lacks unused
  // verilator lint_on UNUSEDSIGNAL
  wire [Channels-1:0] chan_sel = chan_sel8[Channels-1:0];
  wire is_qw        = bus_addr_i[7:4] == AddrQw[7:4];
  wire [3:0] word   = bus_addr_i[3:0];

  // the marker exchange: cell k at FBY k / FBI k and in the window (its top address bit)
  localparam integer CW = $clog2(Cells);
  wire       in_mc     = bus_addr_i[7] == AddrMc[7];
  wire [6:0] mc_k      = in_mc ? bus_addr_i[6:0] : {4'd0, chan};
  wire       mc_ok     = (mc_k >> CW) == 7'd0;       // a cell the build has
  wire       mc_rd     = bus_re_i && marker_i && (in_mc || is_fby_rd);
  wire       mc_wr     = bus_we_i && marker_i && (in_mc || is_fbi_wr);
  reg        mc_pend_q;                          // the last clock read this cell
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) mc_pend_q <= 1'b0;
    else         mc_pend_q <= mc_rd && !mc_pend_q;
  assign cell_re_o    = mc_rd && !mc_pend_q;
  assign cell_ridx_o  = mc_k[CW-1:0];
  assign cell_we_o    = mc_wr && mc_ok;
  assign cell_widx_o  = mc_k[CW-1:0];
  assign cell_wdata_o = bus_wdata_i[0];
  wire       mc_data   = mc_ok && cell_rdata_i;

  assign fby_rd_req_o  = (is_fby_rd && !marker_i) ? chan_sel : {Channels{1'b0}};
  assign fbi_wr_req_o  = (is_fbi_wr && !marker_i) ? chan_sel : {Channels{1'b0}};
  assign fbi_wr_data_o = bus_wdata_i[0];

  assign done_we_o   = bus_we_i && (bus_addr_i == `BUS_DONE);
  assign done_data_o = bus_wdata_i[1:0];

  assign tc_we_o         = bus_we_i && (bus_addr_i == `BUS_TC_BIT);
  assign tc_is_counter_o = bus_wdata_i[6];
  assign tc_idx_o        = bus_wdata_i[$clog2(StatusBits)-1:0];
  assign tc_val_o        = bus_wdata_i[8];

  // Status vectors widened to 64 bits so the LO/HI registers exist for any size.
  wire [63:0] t_stat  = {{(64-StatusBits){1'b0}}, timer_status_i};
  wire [63:0] c_stat  = {{(64-StatusBits){1'b0}}, counter_status_i};
  wire [63:0] t_en    = {{(64-StatusBits){1'b0}}, timer_enable_i};
  wire [63:0] c_pulse = {{(64-StatusBits){1'b0}}, counter_pulse_i};
  wire [63:0] t_wr    = {{(64-StatusBits){1'b0}}, timer_written_i};
  wire [63:0] c_wr    = {{(64-StatusBits){1'b0}}, counter_written_i};
  // TC_WAIT (parallel mode's status wait, docs/exchange.md): the byte side selects a
  // timer / counter with a write, then reads its enable / pulse bit; the read is not
  // ready until the bit side has written that bit in this scan (its written bit). A
  // bus-level wait, as an empty channel's, so every runner's stall loop serves it.
  reg  [6:0]  tc_wait_sel_q;                       // bit 6 counter, bits 5..0 n
  // BYTE_FLAGS: the firmware's sticky flags, kept for a host to read; no logic uses them
  reg  [31:0] byte_flags_q;
  wire [63:0] tc_wait_en = tc_wait_sel_q[6] ? c_pulse : t_en;
  wire [63:0] tc_wait_wr = tc_wait_sel_q[6] ? c_wr : t_wr;
  wire        tc_wait_val     = tc_wait_en[tc_wait_sel_q[5:0]];
  wire        tc_wait_written = tc_wait_wr[tc_wait_sel_q[5:0]];
  wire        is_tc_wait_rd   = bus_re_i && bus_addr_i == `BUS_TC_WAIT;
  wire [16*16-1:0] out_words16 = {{((16-OutWords)*16){1'b0}}, out_words_o};
  wire [7:0]  fby_data8 = {{(8-Channels){1'b0}}, fby_rd_data_i};
  wire [7:0]  fby_full8 = {{(8-Channels){1'b0}}, fby_full_i};
  wire [7:0]  fbi_full8 = {{(8-Channels){1'b0}}, fbi_full_i};

  // Read data: one table entry per address, indexed by the address, so that Yosys
  // builds a balanced multiplexer on the eight address bits (the many zero entries
  // fold away). The former range compares (carry chains) and priority chain of windows
  // made this path, from the FPGA wrapper's bus registers through here and back, the
  // HX8K's critical path. Which address holds what is settled at elaboration, from the
  // register map and the parameters; the channels and words the build lacks read 0.
  wire [31:0] rd_tab [0:255];
  genvar ga;
  generate
    for (ga = 0; ga < 256; ga = ga + 1) begin : g_rd
      localparam [7:0] A = ga[7:0];
      if (A[7:3] == AddrFby[7:3]) begin : g_fby
        // a channel's condition, only under the read strobe (a write reads 0)
        assign rd_tab[ga] = {31'd0, bus_re_i && (marker_i ? mc_data : fby_data8[ga % 8])};
      end else if (A[7] == AddrMc[7]) begin : g_mcell
        assign rd_tab[ga] = {31'd0, bus_re_i && marker_i && mc_data};
      end else if (A[7:4] == AddrIw[7:4] || A[7:4] == AddrQw[7:4]) begin : g_word
        // a word window, sign-extended
        wire [15:0] word_v = (A[7:4] == AddrIw[7:4]) ? in_words16[(ga % 16)*16 +: 16]
                                                     : out_words16[(ga % 16)*16 +: 16];
        assign rd_tab[ga] = {{16{word_v[15]}}, word_v};
      end else begin : g_reg
        assign rd_tab[ga] =
            (A == `BUS_ID)               ? `BUS_ID_VALUE :
            (A == `BUS_STATUS)           ? {28'd0, byte_scan_done_o, fault_i, exec_i, 1'b0} :
            (A == `BUS_DISPATCH_INSTR)   ? dispatch_instr_i :
            (A == `BUS_DISPATCH_CTX)     ? dispatch_ctx_i :
            (A == `BUS_DISPATCH_MS)      ? disp_ms_q :
            (A == `BUS_DISPATCH_IW)      ? {{16{disp_iw_q[15]}}, disp_iw_q} :
            (A == `BUS_TIME_MS)          ? ms_q :
            (A == `BUS_TICK_DIV)         ? tick_div_q :
            (A == `BUS_CLOCK)            ? clock_q :
            (A == `BUS_LATCH_MS)         ? latch_ms_q :
            (A == `BUS_T_STATUS_LO)      ? t_stat[31:0] :
            (A == `BUS_T_STATUS_HI)      ? t_stat[63:32] :
            (A == `BUS_C_STATUS_LO)      ? c_stat[31:0] :
            (A == `BUS_C_STATUS_HI)      ? c_stat[63:32] :
            (A == `BUS_T_ENABLE_LO)      ? t_en[31:0] :
            (A == `BUS_T_ENABLE_HI)      ? t_en[63:32] :
            (A == `BUS_C_PULSE_LO)       ? c_pulse[31:0] :
            (A == `BUS_C_PULSE_HI)       ? c_pulse[63:32] :
            (A == `BUS_T_WRITTEN_LO)     ? t_wr[31:0] :
            (A == `BUS_T_WRITTEN_HI)     ? t_wr[63:32] :
            (A == `BUS_C_WRITTEN_LO)     ? c_wr[31:0] :
            (A == `BUS_C_WRITTEN_HI)     ? c_wr[63:32] :
            (A == `BUS_TC_WAIT)          ? {31'd0, tc_wait_val} :
            (A == `BUS_CHAN_STATUS)      ? {16'd0, fbi_full8, fby_full8} :
            (A == `BUS_STALLS_BIT)       ? stalls_bit_o :
            (A == `BUS_STALLS_BYTE)      ? stalls_byte_o :
            (A == `BUS_BYTE_FLAGS)       ? byte_flags_q :
            (A == `BUS_QUEUE_OVERFLOWS)  ? queue_overflows_i :
            (A == `BUS_QUEUE_UNDERFLOWS) ? queue_underflows_i : 32'd0;
      end
    end
  endgenerate
  // What depends on next_i (STATUS.NEXT, and the live snapshot in a dispatch's first
  // clock) joins at the end, so that the bit side's late request does not also pass
  // through the whole multiplexer.
  wire rd_status = bus_addr_i == `BUS_STATUS;
  wire rd_ms_now = disp_first && bus_addr_i == `BUS_DISPATCH_MS;
  wire rd_iw_now = disp_first && bus_addr_i == `BUS_DISPATCH_IW;
  wire rd_latch_now = latch_i && bus_addr_i == `BUS_LATCH_MS;
  assign bus_rdata_o = (rd_ms_now || rd_latch_now) ? ms_q
                     : rd_iw_now ? {{16{named_iw[15]}}, named_iw}
                     : rd_tab[bus_addr_i] | {31'd0, rd_status && next_i};

  // Ready: only a condition channel (a channel the build lacks never does) and TC_WAIT
  // can refuse an access. Widened to the 8 channels the bus decodes and indexed by the channel
  // number, again without a compare.
  wire [7:0] fby_ready8 = {{(8-Channels){1'b1}}, fby_rd_ready_i};
  wire [7:0] fbi_ready8 = {{(8-Channels){1'b1}}, fbi_wr_ready_i};
  // (a marker cell's read is not ready in its first clock: the RAM's, not a wait)
  assign bus_ready_o = !(is_fby_rd && !marker_i && !fby_ready8[chan])
                    && !(is_fbi_wr && !marker_i && !fbi_ready8[chan])
                    && !(is_tc_wait_rd && !tc_wait_written) && !(mc_rd && !mc_pend_q);

  // ---------------------------------------------------------------- statistics
  // Every clock in which an access is refused is one byte-side stall (it is repeated).
  wire byte_refused = (bus_re_i || bus_we_i) && !bus_ready_o && !mc_rd;
  bus_stats u_bus_stats (
    .clk_i        (clk_i),
    .rst_ni       (rst_ni),
    .bit_stall_i  (bit_stall_i),
    .byte_stall_i (byte_refused),
    .stalls_bit_o (stalls_bit_o),
    .stalls_byte_o(stalls_byte_o)
  );

  // ---------------------------------------------------------------- registers
  assign byte_scan_end_o = bus_we_i && bus_addr_i == `BUS_SCAN_DONE;

  // SCAN_DONE: set by the byte side's write, cleared when the next scan latches.
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) byte_scan_done_o <= 1'b0;
    else if (bus_we_i && bus_addr_i == `BUS_SCAN_DONE) byte_scan_done_o <= 1'b1;
    else if (latch_i) byte_scan_done_o <= 1'b0;
  end

  integer w;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tick_div_q    <= `BUS_TICK_DIV_RESET;   // 100 MHz
      out_words_o   <= {(OutWords*16){1'b0}};
      byte_flags_q  <= 32'd0;
      tc_wait_sel_q <= 7'd0;
    end else begin
      if (bus_we_i && bus_addr_i == `BUS_TC_WAIT) tc_wait_sel_q <= bus_wdata_i[6:0];
      if (bus_we_i && bus_addr_i == `BUS_TICK_DIV) tick_div_q <= bus_wdata_i;
      if (bus_we_i && bus_addr_i == `BUS_BYTE_FLAGS) byte_flags_q <= bus_wdata_i;
      for (w = 0; w < OutWords; w = w + 1)
        if (bus_we_i && is_qw && word == w[3:0]) out_words_o[w*16 +: 16] <= bus_wdata_i[15:0];
    end
  end

`ifdef FORMAL
  wire chan_ok = ({29'd0, chan} < Channels);
  // Bus protocol properties (formal/byte_port.sby, k-induction; the time base's own
  // are in time_base.v).
  reg f_past_valid = 1'b0;
  always @(posedge clk_i) f_past_valid <= 1'b1;
  always @(*) if (!f_past_valid) assume (!rst_ni);
  always @(*) assume (!(bus_re_i && bus_we_i));          // one access per clock

  // The byte processor repeats a refused access (the bus protocol, docs/byte-bus.md).
  reg        f_refused_q = 1'b0;
  reg [7:0]  f_addr_q;
  reg        f_re_q, f_we_q;
  always @(posedge clk_i) begin
    f_refused_q <= rst_ni && (bus_re_i || bus_we_i) && !bus_ready_o;
    f_addr_q    <= bus_addr_i;
    f_re_q      <= bus_re_i;
    f_we_q      <= bus_we_i;
  end
  always @(*) if (f_refused_q && rst_ni)
    assume (bus_addr_i == f_addr_q && bus_re_i == f_re_q && bus_we_i == f_we_q);
  always @(posedge clk_i) if (f_past_valid) assume ($stable(marker_i) || !f_refused_q);

  // LATCH_MS: the time base as it was at the bit side's last scan latch, the live value
  // in the latch clock itself (a shadow of TIME_MS taken at each latch).
  reg [31:0] f_latch_ms = 32'd0;
  always @(posedge clk_i) if (!rst_ni) f_latch_ms <= 32'd0; else if (latch_i) f_latch_ms <= ms_q;
  always @(*) if (rst_ni && f_past_valid && bus_addr_i == `BUS_LATCH_MS)
    assert (bus_rdata_o == (latch_i ? ms_q : f_latch_ms));
  always @(*) if (rst_ni && f_past_valid) assert (latch_ms_q == f_latch_ms);  // induction

  // The marker exchange's cells: at FBY k / FBI k (k < 8) and in the MCELL window.
  wire       f_in_win = bus_addr_i >= `BUS_MCELL;
  wire [6:0] f_k      = f_in_win ? bus_addr_i - `BUS_MCELL : {4'd0, bus_addr_i[2:0]};
  wire       f_cell_rd = rst_ni && bus_re_i && marker_i && (f_in_win || is_fby_rd);
  wire       f_cell_wr = rst_ni && bus_we_i && marker_i && (f_in_win || is_fbi_wr);
  wire       f_cell_ok = f_k < Cells;

  // An access waits only on a condition channel the build has (not with the marker
  // exchange), and exactly while that channel cannot take / give a condition, or on
  // TC_WAIT, exactly while the timer / counter its last write selected is not written
  // in this scan; a marker cell's read is refused in its first clock (the RAM's).
  always @(*) if (rst_ni && !bus_ready_o)
    assert (((is_fby_rd || is_fbi_wr) && chan_ok && !marker_i) ||
            (bus_re_i && bus_addr_i == `BUS_TC_WAIT) || (f_cell_rd && !f_refused_q));
  always @(*) if (f_cell_rd) begin
    // the first clock reads the RAM, the second answers with its cell
    assert (bus_ready_o == f_refused_q);
    assert (cell_re_o == !f_refused_q);
    if (!f_refused_q) assert (cell_ridx_o == f_k[$clog2(Cells)-1:0]);
    if (f_refused_q) assert (bus_rdata_o == {31'd0, f_cell_ok && cell_rdata_i});
  end else if (rst_ni) assert (!cell_re_o);
  always @(*) if (rst_ni) begin
    // a cell's write is taken at once (never refused), a cell the build lacks dropped
    if (f_cell_wr) assert (bus_ready_o);
    assert (cell_we_o == (f_cell_wr && f_cell_ok));
    if (cell_we_o) assert (cell_widx_o == f_k[$clog2(Cells)-1:0] &&
                           cell_wdata_o == bus_wdata_i[0]);
  end
  always @(posedge clk_i) if (rst_ni)
    cover (f_past_valid && $past(f_cell_rd && !bus_ready_o) && f_cell_rd && bus_ready_o &&
           f_in_win && f_k == 7'd100 && bus_rdata_o[0]);
  reg [6:0] f_sel;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) f_sel <= 7'd0;
    else if (bus_we_i && bus_addr_i == `BUS_TC_WAIT) f_sel <= bus_wdata_i[6:0];
  wire [63:0] f_wr = f_sel[6] ? {{(64-StatusBits){1'b0}}, counter_written_i}
                              : {{(64-StatusBits){1'b0}}, timer_written_i};
  wire [63:0] f_en = f_sel[6] ? {{(64-StatusBits){1'b0}}, counter_pulse_i}
                              : {{(64-StatusBits){1'b0}}, timer_enable_i};
  always @(*) if (rst_ni) assert (tc_wait_sel_q == f_sel);    // induction invariant
  always @(*) if (rst_ni && bus_re_i && bus_addr_i == `BUS_TC_WAIT) begin
    assert (bus_ready_o == f_wr[f_sel[5:0]]);
    assert (bus_rdata_o == {31'd0, f_en[f_sel[5:0]]});
  end
  always @(posedge clk_i) if (rst_ni)
    cover (f_past_valid && $past(bus_re_i && bus_addr_i == `BUS_TC_WAIT && !bus_ready_o)
           && bus_re_i && bus_addr_i == `BUS_TC_WAIT && bus_ready_o && f_sel[6]);
  always @(*) if (rst_ni && is_fby_rd && chan_ok && !marker_i)
    assert (bus_ready_o == |(fby_rd_ready_i & chan_sel));
  always @(*) if (rst_ni && is_fbi_wr && chan_ok && !marker_i)
    assert (bus_ready_o == |(fbi_wr_ready_i & chan_sel));
  // A channel is asked only by an access to it; strobes name exactly one channel.
  always @(*) begin
    assert ((fby_rd_req_o == {Channels{1'b0}}) ||
            (is_fby_rd && !marker_i && $onehot(fby_rd_req_o)));
    assert ((fbi_wr_req_o == {Channels{1'b0}}) ||
            (is_fbi_wr && !marker_i && $onehot(fbi_wr_req_o)));
    assert (!done_we_o || (bus_we_i && bus_addr_i == `BUS_DONE));
    assert (!tc_we_o || (bus_we_i && bus_addr_i == `BUS_TC_BIT));
  end
  // Stall counting, against the byte processor's view rather than the refusal logic:
  // every clock with an access either completes it or is a stall (it is repeated),
  // except a marker cell read's first clock (the RAM's read, not a wait for the other
  // side), so the stalls are the access clocks minus the completed accesses and the
  // cell reads (each count wraps at 32 bits, like the counter).
  reg [31:0] f_access_clocks, f_completed, f_cell_reads;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_access_clocks <= 32'd0;
      f_completed     <= 32'd0;
      f_cell_reads    <= 32'd0;
    end else begin
      if (bus_re_i || bus_we_i)                f_access_clocks <= f_access_clocks + 32'd1;
      if ((bus_re_i || bus_we_i) && bus_ready_o) f_completed   <= f_completed + 32'd1;
      if (f_cell_rd && !f_refused_q)           f_cell_reads    <= f_cell_reads + 32'd1;
    end
  always @(*) if (rst_ni) begin
    assert (stalls_byte_o == f_access_clocks - f_completed - f_cell_reads);
    assert (mc_pend_q == (f_refused_q && f_cell_rd));   // induction helper
  end
  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    // SCAN_DONE: set by its write, cleared by the next latch, held otherwise
    if ($past(bus_we_i) && $past(bus_addr_i) == `BUS_SCAN_DONE) assert (byte_scan_done_o);
    else if ($past(latch_i)) assert (!byte_scan_done_o);
    else assert (byte_scan_done_o == $past(byte_scan_done_o));
  end
  always @(posedge clk_i) if (rst_ni) cover (stalls_byte_o == 32'd2);
`endif

  // verilator lint_off UNUSEDSIGNAL
  wire unused_bus = ^{bus_wdata_i[31:9], bus_wdata_i[7], bus_wdata_i[5:0]};
  // verilator lint_on UNUSEDSIGNAL
endmodule
`default_nettype wire
