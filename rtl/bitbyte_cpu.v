`default_nettype none
`include "param_check.vh"
`include "bit_isa.vh"
// One bit-byte CPU, the FPGA part: bit processor, scan controller, binary I/O units,
// the exchange circuits (buffered condition flip-flops, timer/counter status buffer,
// serial dispatch) and the byte-side port through which the byte processor (a
// microcontroller, here firmware_byte/) takes part.
// Wiring only; the logic lives in the leaves (docs/architecture.md has the map).
module bitbyte_cpu #(
  parameter integer ProgWords   = 4096,  // program memory, instructions (power of two)
  parameter integer InBytes     = 16,    // binary input bytes: I/PI/IR/IF 0.0 .. InBytes-1.7
  parameter integer OutBytes    = 16,    // binary output bytes: Q/PQ 0.0 .. OutBytes-1.7
  parameter integer MarkerBytes = 256,   // marker bytes: M 0.0 .. MarkerBytes-1.7
  parameter integer StatusBits  = 64,    // timers T0.. and counters C0.. (status bits each)
  parameter integer Channels    = 4,     // exchange channels FBI k / FBY k (handshake)
  parameter integer MarkerCells = 128,   // marker area cells FBI k / FBY k (exchange marker)
  parameter integer QueueDepth  = 8,     // condition queue depth per direction
  parameter integer Exchanges   = 7,     // exchange circuits built (cond_exchange.v): 1 the
                                         // flip-flops, 2 the queues, 4 the marker area
  parameter integer NestDepth   = 8,     // parenthesis nesting levels
  parameter integer InWords     = 16,    // word inputs IW n (analog)
  parameter integer OutWords    = 16,    // word outputs QW n (analog)
  parameter integer ForceBits   = 128,   // I / Q bits 0..ForceBits-1 can be forced (force_table.v; 1..128)
  parameter integer BitEngine   = 0,     // bit processor: 0 scalar, 1 wide (LUT words; bit_proc.v)
  parameter integer LutWords    = ProgWords  // wide: LUT words at addresses 0..LutWords-1
) (
  input  wire                         clk_i,
  input  wire                         rst_ni,
  // program load (while stopped)
  input  wire                         prog_we_i,
  input  wire [$clog2(ProgWords)-1:0] prog_waddr_i,
  input  wire [31:0]                  prog_wdata_i,
  input  wire [`LUT_EXT_BITS-1:0]     prog_ext_wdata_i,  // its extension word (wide; else unused)
  // control and status
  input  wire                         run_i,             // RUN/STOP switch
  input  wire                         time_start_i,      // plant: its clock 0 starts the time base
  input  wire                         parallel_i,        // parallel mode: parts meet at END
  input  wire                         free_i,            // free-running mode: they never meet
  input  wire                         marker_write_buffer_i,  // marker area: publish at scan end
  input  wire [1:0]                   exchange_i,        // `EXCHANGE_* (bit_isa.vh):
                                                         // handshake, queues, marker area
  input  wire [31:0]                  watchdog_limit_i,  // clocks per scan at most
  output wire                         ready_o,           // stopped, ready to run
  output wire                         fault_o,           // scan watchdog fired
  output wire                         scan_done_o,       // a scan ended at the last edge
  output wire [31:0]                  scan_count_o,
  output wire [31:0]                  scan_cycles_o,     // clocks of the last scan
  output wire [31:0]                  scan_cycles_max_o,
  // process pins
  input  wire [InBytes*8-1:0]         in_pins_i,
  output wire [OutBytes*8-1:0]        out_pins_o,
  // word I/O
  input  wire [InWords*16-1:0]        in_words_i,
  output wire [OutWords*16-1:0]       out_words_o,
  // byte-side bus (docs/byte-bus.md)
  input  wire [7:0]                   bus_addr_i,
  input  wire [31:0]                  bus_wdata_i,
  input  wire                         bus_we_i,
  input  wire                         bus_re_i,
  output wire [31:0]                  bus_rdata_o,
  output wire                         bus_ready_o,
  output wire [31:0]                  stalls_bit_o,
  output wire [31:0]                  stalls_byte_o,
  // marker copy port (plant cores, rtl/plc_core.v; a single CPU ties copy_en_i to 0):
  // while the CPU is between scans the copy engine reads and writes M bits here
  input  wire                         mcopy_en_i,
  input  wire                         mcopy_we_i,
  input  wire [$clog2(MarkerBytes*8)-1:0] mcopy_addr_i,
  input  wire                         mcopy_wdata_i,
  output wire                         mcopy_rdata_o,
  output wire                         byte_next_o,       // STATUS.NEXT (harnesses wait on it)
  // observation (dbg_*): what the simulation hosts trace besides the ports above, so
  // that they read the design through its ports only. No logic uses them; the FPGA
  // wrapper (synth/gen_wrapper.py) ties dbg_* inputs to 0 and leaves the outputs open.
  output wire [InBytes*8-1:0]         dbg_pii_o,         // I: the input image of the last latch
  output wire [InBytes*8-1:0]         dbg_rise_o,        // IR: rising edges at that latch
  output wire [InBytes*8-1:0]         dbg_fall_o,        // IF: falling edges
  output wire [OutBytes*8-1:0]        dbg_q_rise_o,      // QR: outputs the last PIO
  output wire [OutBytes*8-1:0]        dbg_q_fall_o,      // QF: update raised / dropped
  output wire [StatusBits-1:0]        dbg_timer_status_o,    // T n as the bit side reads it
  output wire [StatusBits-1:0]        dbg_counter_status_o,  // C n
  output wire [31:0]                  dbg_queue_overflows_o, // bus QUEUE_OVERFLOWS, exact now
  output wire [31:0]                  dbg_queue_underflows_o, // ... QUEUE_UNDERFLOWS
  input  wire [$clog2(MarkerBytes*8)-1:0] dbg_m_addr_i,  // a marker bit M to look at ...
  output wire                         dbg_m_o,           // ... its value now, without a clock
  output wire                         dbg_ret_valid_o,   // an instruction retired last clock
  output wire [$clog2(ProgWords)-1:0] dbg_ret_pc_o,      // ... at this address,
  output wire                         dbg_ret_opnd_o,    // ... reading this operand bit
  output wire                         dbg_rlo_o          // the RLO (after it, when it retired)
);
  localparam integer InBits  = InBytes * 8;
  localparam integer OutBits = OutBytes * 8;

  // The leaves check the rest; these are the ranges in this module's own units (an
  // operand index is 12 bits: byte * 8 + bit).
  `PARAM_CHECK(g_bad_in_bytes, InBytes < 1 || InBytes > 512,
               "bitbyte_cpu: InBytes must be 1..512 (12-bit operand index)")
  `PARAM_CHECK(g_bad_out_bytes, OutBytes < 1 || OutBytes > 512,
               "bitbyte_cpu: OutBytes must be 1..512 (12-bit operand index)")
  `PARAM_CHECK(g_bad_marker_bytes, MarkerBytes < 1 || MarkerBytes > 512,
               "bitbyte_cpu: MarkerBytes must be 1..512 (12-bit operand index)")
  // the marker area packs 16 cells a block-RAM word, two words at least; the bus
  // window MCELL holds 128
  `PARAM_CHECK(g_bad_marker_cells,
               MarkerCells < 32 || MarkerCells > 128 || (MarkerCells & (MarkerCells - 1)) != 0,
               "bitbyte_cpu: MarkerCells must be a power of two in 32..128")

  wire start, latch, exec, mem_ready, end_exec, refresh;
  wire [InBits-1:0]  pii, rise, fall, rise_pend, fall_pend;
  wire [OutBits-1:0] pio, q_rise, q_fall;
  wire               out_update;
  wire                       out_wr_en, out_wr_val, out_wr_direct;
  wire [$clog2(OutBits)-1:0] out_wr_idx;
  wire [31:0] cycle_now;
  wire        rlo, rlo_now;
  wire [$clog2(ProgWords)-1:0] exec_pc;
  wire        exec_valid;
  // exchange
  wire [StatusBits-1:0] timer_status, counter_status, timer_enable, counter_pulse;
  wire [StatusBits-1:0] timer_updated, counter_updated, timer_written, counter_written;
  wire [Channels-1:0] fbi_rd_req, fbi_rd_data, fbi_rd_ready, fbi_wr_req, fbi_wr_ready, fbi_full;
  wire [Channels-1:0] fby_wr_req, fby_wr_ready, fby_rd_req, fby_rd_data, fby_rd_ready, fby_full;
  wire        fby_wr_data, fbi_wr_data, bit_stall;
  // the marker area's cells (exchange marker)
  localparam integer CellW = $clog2(MarkerCells);
  wire             marker, marker_ready;
  wire             bit_cell_we, bit_cell_wdata, bit_cell_re, bit_cell_rdata;
  wire             byte_cell_we, byte_cell_wdata, byte_cell_re, byte_cell_rdata;
  wire [CellW-1:0] bit_cell_widx, bit_cell_ridx, byte_cell_widx, byte_cell_ridx;
  wire        byte_req, byte_done, byte_rlo, byte_rlo_we;
  wire [31:0] byte_instr, dispatch_instr, dispatch_ctx;
  wire        next, dispatch_next, done_we, byte_scan_done, byte_scan_end;
  wire [1:0]  done_data;
  wire        tc_we, tc_is_counter, tc_val, ctl_we, ctl_is_counter, ctl_val;
  wire [$clog2(StatusBits)-1:0] tc_idx, ctl_idx;
  wire        tcw_we, tcw_is_counter, tcw_val;
  wire [$clog2(StatusBits)-1:0] tcw_idx;
  wire [31:0] queue_overflows, queue_underflows;
  wire [31:0] queue_overflows_now, queue_underflows_now;
  assign byte_next_o = next;

  // ---------------------------------------------------------------- observation
  assign dbg_pii_o              = pii;
  assign dbg_rlo_o              = rlo;
  assign dbg_rise_o             = rise;
  assign dbg_fall_o             = fall;
  assign dbg_q_rise_o           = q_rise;
  assign dbg_q_fall_o           = q_fall;
  assign dbg_timer_status_o     = timer_status;
  assign dbg_counter_status_o   = counter_status;
  assign dbg_queue_overflows_o  = queue_overflows_now;   // the bus registers may lag a clock
  assign dbg_queue_underflows_o = queue_underflows_now;

  scan_ctrl u_scan_ctrl (
    .clk_i            (clk_i),
    .rst_ni           (rst_ni),
    .mem_ready_i      (mem_ready && marker_ready),   // markers and marker area cleared
    .run_i            (run_i),
    .end_i            (end_exec),
    .watchdog_limit_i (watchdog_limit_i),
    .start_o          (start),
    .latch_o          (latch),
    .exec_o           (exec),
    .ready_o          (ready_o),
    .fault_o          (fault_o),
    .scan_done_o      (scan_done_o),
    .scan_count_o     (scan_count_o),
    .scan_cycles_o    (scan_cycles_o),
    .scan_cycles_max_o(scan_cycles_max_o),
    .cycle_q_o        (cycle_now)
  );

  // The force table sits between the pins and the I/O units: what the CPU reads and
  // what the pins show (docs/byte-bus.md, FORCE_*).
  wire [InBits-1:0]  in_pins;           // the input pins as the CPU sees them
  wire [OutBits-1:0] out_unit_pins;     // the output unit's pins, before forcing
  // (a build with fewer pins than ForceBits forces all it has)
  localparam integer ForceMax = InBits < OutBits ? InBits : OutBits;
  localparam integer ForceN   = ForceBits < ForceMax ? ForceBits : ForceMax;
  force_table #(.InBits(InBits), .OutBits(OutBits), .ForceBits(ForceN)) u_force (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .bus_addr_i (bus_addr_i),
    .bus_wdata_i(bus_wdata_i),
    .bus_we_i   (bus_we_i),
    .run_i      (run_i),
    .swap_i     (end_exec),
    .fault_i    (fault_o),
    .in_pins_i  (in_pins_i),
    .out_pins_i (out_unit_pins),
    .in_pins_o  (in_pins),
    .out_pins_o (out_pins_o)
  );

  input_unit #(.InBits(InBits)) u_input_unit (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .pins_i (in_pins),
    .latch_i  (latch),
    .refresh_i(refresh),
    .pii_o     (pii),
    .rise_o    (rise),
    .fall_o    (fall),
    .rise_pend_o(rise_pend),
    .fall_pend_o(fall_pend)
  );

  output_unit #(.OutBits(OutBits)) u_output_unit (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .wr_en_i    (out_wr_en),
    .wr_idx_i   (out_wr_idx),
    .wr_val_i   (out_wr_val),
    .wr_direct_i(out_wr_direct),
    .update_i   (out_update),
    .fault_i    (fault_o),
    .pio_o      (pio),
    .pins_o     (out_unit_pins),
    .rise_o     (q_rise),
    .fall_o     (q_fall)
  );

  bit_proc #(
    .ProgWords (ProgWords),
    .InBits    (InBits),
    .OutBits   (OutBits),
    .MarkerBits(MarkerBytes * 8),
    .StatusBits(StatusBits),
    .Channels  (Channels),
    .NestDepth (NestDepth),
    .Cells     (MarkerCells),
    .BitEngine (BitEngine),
    .LutWords  (LutWords)
  ) u_bit_proc (
    .clk_i           (clk_i),
    .rst_ni          (rst_ni),
    .prog_we_i       (prog_we_i),
    .prog_waddr_i    (prog_waddr_i),
    .prog_wdata_i    (prog_wdata_i),
    .prog_ext_wdata_i(prog_ext_wdata_i),
    .start_i         (start),
    .latch_i         (latch),
    .exec_i          (exec),
    .mem_ready_o     (mem_ready),
    .end_o           (end_exec),
    .refresh_o       (refresh),
    .pii_i           (pii),
    .pins_i          (in_pins),
    .rise_i          (rise),
    .fall_i          (fall),
    .rise_pend_i     (rise_pend),
    .fall_pend_i     (fall_pend),
    .pio_i           (pio),
    .out_pins_i      (out_unit_pins),
    .q_rise_i        (q_rise),
    .q_fall_i        (q_fall),
    .timer_status_i  (timer_status),
    .counter_status_i(counter_status),
    .timer_updated_i (timer_updated),
    .counter_updated_i(counter_updated),
    // the byte side's status write of this clock (forwarded: the bit processor
    // selects its operand a clock before it executes)
    .tc_we_i         (tc_we),
    .tc_is_counter_i (tc_is_counter),
    .tc_idx_i        (tc_idx),
    .tc_val_i        (tc_val),
    .tcw_we_o        (tcw_we),
    .tcw_is_counter_o(tcw_is_counter),
    .tcw_idx_o       (tcw_idx),
    .tcw_val_o       (tcw_val),
    .fbi_rd_req_o    (fbi_rd_req),
    .fbi_rd_data_i   (fbi_rd_data),
    .fbi_rd_ready_i  (fbi_rd_ready),
    .fby_wr_req_o    (fby_wr_req),
    .fby_wr_data_o   (fby_wr_data),
    .fby_wr_ready_i  (fby_wr_ready),
    .marker_i        (marker),
    .cell_re_o       (bit_cell_re),
    .cell_ridx_o     (bit_cell_ridx),
    .cell_rdata_i    (bit_cell_rdata),
    .cell_we_o       (bit_cell_we),
    .cell_widx_o     (bit_cell_widx),
    .cell_wdata_o    (bit_cell_wdata),
    .byte_req_o      (byte_req),
    .byte_instr_o    (byte_instr),
    .byte_done_i     (byte_done),
    .byte_rlo_i      (byte_rlo),
    .byte_rlo_we_i   (byte_rlo_we),
    .stall_o         (bit_stall),
    .end_hold_i      (parallel_i && (latch || !byte_scan_done)),
    .out_wr_en_o     (out_wr_en),
    .out_wr_idx_o    (out_wr_idx),
    .out_wr_val_o    (out_wr_val),
    .out_wr_direct_o (out_wr_direct),
    .out_update_o    (out_update),
    .copy_en_i       (mcopy_en_i),
    .copy_we_i       (mcopy_we_i),
    .copy_addr_i     (mcopy_addr_i),
    .copy_wdata_i    (mcopy_wdata_i),
    .copy_rdata_o    (mcopy_rdata_o),
    .rlo_o           (rlo),
    .rlo_now_o       (rlo_now),
    .exec_pc_o       (exec_pc),
    .exec_valid_o    (exec_valid),
    .ret_valid_o     (dbg_ret_valid_o),
    .ret_pc_o        (dbg_ret_pc_o),
    .ret_opnd_o      (dbg_ret_opnd_o),
    .m_peek_addr_i   (dbg_m_addr_i),
    .m_peek_o        (dbg_m_o)
  );

  // The condition exchange (Fig. 11 flip-flops, Fig. 16 queues or the Fig. 17 marker
  // area, by exchange_i, among the circuits Exchanges builds): F_bB k carries a
  // condition to the byte side (`= FBY k` / READ FBY k), F_Bb k to the bit side
  // (WRITE FBI k / `A FBI k`).
  cond_exchange #(
    .Channels  (Channels),
    .QueueDepth(QueueDepth),
    .Exchanges (Exchanges),
    .Cells     (MarkerCells)
  ) u_exchange (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .exchange_i    (exchange_i),
    .bit_start_i   (latch),
    .bit_end_i     (end_exec),
    // the byte side's scans: they start at the latch in parallel mode, at its own
    // SCAN_DONE write (one scan ends, the next begins) when it runs free; they end at
    // its SCAN_DONE write in both (in parallel mode END waits for it), so the cells it
    // publishes there reach the bit side's next snapshot (taken in the clock END
    // executes). Serial mode has no exchange (the firmware writes no SCAN_DONE there)
    .byte_start_i  (free_i ? byte_scan_end : latch),
    .byte_end_i    (byte_scan_end),
    .marker_write_buffer_i(marker_write_buffer_i),
    .fby_wr_req_i  (fby_wr_req),
    .fby_wr_data_i (fby_wr_data),
    .fby_wr_ready_o(fby_wr_ready),
    .fby_rd_req_i  (fby_rd_req),
    .fby_rd_data_o (fby_rd_data),
    .fby_rd_ready_o(fby_rd_ready),
    .fby_full_o    (fby_full),
    .fbi_wr_req_i  (fbi_wr_req),
    .fbi_wr_data_i (fbi_wr_data),
    .fbi_wr_ready_o(fbi_wr_ready),
    .fbi_rd_req_i  (fbi_rd_req),
    .fbi_rd_data_o (fbi_rd_data),
    .fbi_rd_ready_o(fbi_rd_ready),
    .fbi_full_o    (fbi_full),
    .marker_o      (marker),
    .marker_ready_o(marker_ready),
    .bit_snap_i    (start),
    .bit_cell_we_i (bit_cell_we),
    .bit_cell_widx_i(bit_cell_widx),
    .bit_cell_wdata_i(bit_cell_wdata),
    .bit_cell_re_i (bit_cell_re),
    .bit_cell_ridx_i(bit_cell_ridx),
    .bit_cell_rdata_o(bit_cell_rdata),
    .byte_cell_we_i (byte_cell_we),
    .byte_cell_widx_i(byte_cell_widx),
    .byte_cell_wdata_i(byte_cell_wdata),
    .byte_cell_re_i (byte_cell_re),
    .byte_cell_ridx_i(byte_cell_ridx),
    .byte_cell_rdata_o(byte_cell_rdata),
    .overflows_o   (queue_overflows),
    .underflows_o  (queue_underflows),
    .overflows_now_o (queue_overflows_now),
    .underflows_now_o(queue_underflows_now)
  );

  dispatch #(.StatusBits(StatusBits)) u_dispatch (
    .clk_i           (clk_i),
    .rst_ni          (rst_ni),
    .latch_i         (latch),
    .req_i           (byte_req),
    .instr_i         (byte_instr),
    .rlo_i           (rlo_now),
    .scan_i          (scan_count_o[15:0]),
    .done_o          (byte_done),
    .done_rlo_o      (byte_rlo),
    .done_rlo_we_o   (byte_rlo_we),
    .next_o          (dispatch_next),
    .instr_o         (dispatch_instr),
    .ctx_o           (dispatch_ctx),
    .done_we_i       (done_we),
    .done_data_i     (done_data),
    .ctl_we_o        (ctl_we),
    .ctl_is_counter_o(ctl_is_counter),
    .ctl_idx_o       (ctl_idx),
    .ctl_val_o       (ctl_val)
  );

  // NEXT tells the byte processor to start work: a dispatched instruction (serial
  // mode), or a scan's latch clock (parallel mode: it runs its own part of the scan).
  assign next = dispatch_next || (parallel_i && latch);

  tc_status #(.StatusBits(StatusBits)) u_tc_status (
    .clk_i              (clk_i),
    .rst_ni             (rst_ni),
    .status_we_i        (tc_we),
    .status_is_counter_i(tc_is_counter),
    .status_idx_i       (tc_idx),
    .status_val_i       (tc_val),
    .ctl_we_i           (ctl_we),
    .ctl_is_counter_i   (ctl_is_counter),
    .ctl_idx_i          (ctl_idx),
    .ctl_val_i          (ctl_val),
    // the enable / pulse bits: the dispatch in serial mode, the bit processor's
    // `= T n` / `= C n` otherwise (--tc-path status)
    .partitioned_i      (parallel_i || free_i),
    .bit_we_i           (tcw_we),
    .bit_is_counter_i   (tcw_is_counter),
    .bit_idx_i          (tcw_idx),
    .bit_val_i          (tcw_val),
    .latch_i            (latch),
    .timer_status_o     (timer_status),
    .counter_status_o   (counter_status),
    .timer_enable_o     (timer_enable),
    .counter_pulse_o    (counter_pulse),
    .timer_updated_o    (timer_updated),
    .counter_updated_o  (counter_updated),
    .timer_written_o    (timer_written),
    .counter_written_o  (counter_written)
  );

  byte_port #(
    .StatusBits(StatusBits),
    .Channels  (Channels),
    .InWords   (InWords),
    .OutWords  (OutWords),
    .Cells     (MarkerCells)
  ) u_byte_port (
    .clk_i           (clk_i),
    .rst_ni          (rst_ni),
    .bus_addr_i      (bus_addr_i),
    .bus_wdata_i     (bus_wdata_i),
    .bus_we_i        (bus_we_i),
    .bus_re_i        (bus_re_i),
    .bus_rdata_o     (bus_rdata_o),
    .bus_ready_o     (bus_ready_o),
    .latch_i         (latch),
    .time_start_i    (time_start_i),
    .exec_i          (exec),
    .fault_i         (fault_o),
    .byte_scan_done_o(byte_scan_done),
    .byte_scan_end_o (byte_scan_end),
    .next_i          (next),
    .dispatch_instr_i(dispatch_instr),
    .dispatch_ctx_i  (dispatch_ctx),
    .done_we_o       (done_we),
    .done_data_o     (done_data),
    .tc_we_o         (tc_we),
    .tc_is_counter_o (tc_is_counter),
    .tc_idx_o        (tc_idx),
    .tc_val_o        (tc_val),
    .timer_status_i  (timer_status),
    .counter_status_i(counter_status),
    .timer_enable_i  (timer_enable),
    .counter_pulse_i (counter_pulse),
    .timer_written_i (timer_written),
    .counter_written_i(counter_written),
    .fby_rd_req_o    (fby_rd_req),
    .fby_rd_data_i   (fby_rd_data),
    .fby_rd_ready_i  (fby_rd_ready),
    .fby_full_i      (fby_full),
    .fbi_wr_req_o    (fbi_wr_req),
    .fbi_wr_data_o   (fbi_wr_data),
    .fbi_wr_ready_i  (fbi_wr_ready),
    .fbi_full_i      (fbi_full),
    .marker_i        (marker),
    .cell_re_o       (byte_cell_re),
    .cell_ridx_o     (byte_cell_ridx),
    .cell_rdata_i    (byte_cell_rdata),
    .cell_we_o       (byte_cell_we),
    .cell_widx_o     (byte_cell_widx),
    .cell_wdata_o    (byte_cell_wdata),
    .in_words_i      (in_words_i),
    .out_words_o     (out_words_o),
    .bit_stall_i     (bit_stall),
    .queue_overflows_i (queue_overflows),
    .queue_underflows_i(queue_underflows),
    .stalls_bit_o    (stalls_bit_o),
    .stalls_byte_o   (stalls_byte_o)
  );

  // Observation only: kept for waveforms (sim/bitbyte.gtkw), not used by logic.
  // verilator lint_off UNUSEDSIGNAL
  wire unused_obs = ^{cycle_now, exec_pc, exec_valid};
  // verilator lint_on UNUSEDSIGNAL
endmodule
`default_nettype wire
