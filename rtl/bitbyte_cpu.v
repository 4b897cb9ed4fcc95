`default_nettype none
// One bit-byte CPU: bit processor, scan controller and the binary I/O units.
// Wiring only; the logic lives in the leaves (docs/architecture.md has the map).
module bitbyte_cpu #(
  parameter integer ProgWords   = 4096,  // program memory, instructions (power of two)
  parameter integer InBytes     = 16,    // binary input bytes: I/PI/IR/IF 0.0 .. InBytes-1.7
  parameter integer OutBytes    = 16,    // binary output bytes: Q/PQ 0.0 .. OutBytes-1.7
  parameter integer MarkerBytes = 256,   // marker bytes: M 0.0 .. MarkerBytes-1.7
  parameter integer StatusBits  = 64,    // timers T0.. and counters C0.. (status bits each)
  parameter integer Channels    = 4,     // exchange channels FBI k / FBY k
  parameter integer NestDepth   = 8      // parenthesis nesting levels
) (
  input  wire                         clk_i,
  input  wire                         rst_ni,
  // program load (while stopped)
  input  wire                         prog_we_i,
  input  wire [$clog2(ProgWords)-1:0] prog_waddr_i,
  input  wire [31:0]                  prog_wdata_i,
  // control and status
  input  wire                         run_i,             // RUN/STOP switch
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
  // byte-side status read by bit instructions (timer/counter buffer, F_Bb channels)
  input  wire [StatusBits-1:0]        timer_status_i,
  input  wire [StatusBits-1:0]        counter_status_i,
  input  wire [Channels-1:0]          fbi_i
);
  localparam integer InBits  = InBytes * 8;
  localparam integer OutBits = OutBytes * 8;

  wire latch, exec, mem_ready, end_exec, refresh;
  wire [InBits-1:0]  pii, rise, fall;
  wire [OutBits-1:0] pio;
  wire                       out_wr_en, out_wr_val, out_wr_direct;
  wire [$clog2(OutBits)-1:0] out_wr_idx;
  wire [31:0] cycle_now;
  wire        rlo;
  wire [$clog2(ProgWords)-1:0] exec_pc;
  wire        exec_valid;

  scan_ctrl u_scan_ctrl (
    .clk_i            (clk_i),
    .rst_ni           (rst_ni),
    .mem_ready_i      (mem_ready),
    .run_i            (run_i),
    .end_i            (end_exec),
    .watchdog_limit_i (watchdog_limit_i),
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

  input_unit #(.InBits(InBits)) u_input_unit (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .pins_i (in_pins_i),
    .latch_i(latch || refresh),
    .pii_o  (pii),
    .rise_o (rise),
    .fall_o (fall)
  );

  output_unit #(.OutBits(OutBits)) u_output_unit (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .wr_en_i    (out_wr_en),
    .wr_idx_i   (out_wr_idx),
    .wr_val_i   (out_wr_val),
    .wr_direct_i(out_wr_direct),
    .update_i   (end_exec),
    .fault_i    (fault_o),
    .pio_o      (pio),
    .pins_o     (out_pins_o)
  );

  bit_proc #(
    .ProgWords (ProgWords),
    .InBits    (InBits),
    .OutBits   (OutBits),
    .MarkerBits(MarkerBytes * 8),
    .StatusBits(StatusBits),
    .Channels  (Channels),
    .NestDepth (NestDepth)
  ) u_bit_proc (
    .clk_i           (clk_i),
    .rst_ni          (rst_ni),
    .prog_we_i       (prog_we_i),
    .prog_waddr_i    (prog_waddr_i),
    .prog_wdata_i    (prog_wdata_i),
    .latch_i         (latch),
    .exec_i          (exec),
    .mem_ready_o     (mem_ready),
    .end_o           (end_exec),
    .refresh_o       (refresh),
    .pii_i           (pii),
    .pins_i          (in_pins_i),
    .rise_i          (rise),
    .fall_i          (fall),
    .pio_i           (pio),
    .timer_status_i  (timer_status_i),
    .counter_status_i(counter_status_i),
    .fbi_i           (fbi_i),
    .out_wr_en_o     (out_wr_en),
    .out_wr_idx_o    (out_wr_idx),
    .out_wr_val_o    (out_wr_val),
    .out_wr_direct_o (out_wr_direct),
    .rlo_o           (rlo),
    .exec_pc_o       (exec_pc),
    .exec_valid_o    (exec_valid)
  );

  // Observation only: kept for waveforms (sim/bitbyte.gtkw), not used by logic.
  // verilator lint_off UNUSEDSIGNAL
  wire unused_obs = ^{cycle_now, rlo, exec_pc, exec_valid};
  // verilator lint_on UNUSEDSIGNAL
endmodule
`default_nettype wire
