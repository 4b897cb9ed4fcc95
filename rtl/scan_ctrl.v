`default_nettype none
// Scan controller: the PLC's cycle. After reset it waits for the bit processor to
// clear its memories (INIT), then for the RUN switch (IDLE). A scan (RUN) is the
// clock that latches the PII — in which the first instruction already executes, its
// I/IR/IF operands forwarded from the latch (input_unit.v) — then the program's clocks
// up to the clock in which END executes (PIO -> pins); the next scan latches in the
// clock right after END. So a scan costs 1 + its instructions' clocks, END included.
// The watchdog turns a scan longer than watchdog_limit_i clocks into a FAULT that
// holds the outputs at 0 until reset, so an endless loop cannot hang a simulation.
module scan_ctrl (
  input  wire        clk_i,
  input  wire        rst_ni,
  input  wire        mem_ready_i,       // bit processor finished clearing its memories
  input  wire        run_i,             // RUN/STOP switch; STOP takes effect at END
  input  wire        end_i,             // END executes in this clock
  input  wire [31:0] watchdog_limit_i,  // longest legal scan, in clocks
  output wire        start_o,           // the next clock starts a scan (prefetch)
  output wire        latch_o,           // this clock latches the PII (scan start)
  output wire        exec_o,            // program instructions execute in this clock
  output wire        ready_o,           // initialised; a RUN request starts scan 0
  output wire        fault_o,           // watchdog fired (sticky until reset)
  output reg         scan_done_o,       // a scan ended at the last clock edge
  output reg  [31:0] scan_count_o,      // scans completed since reset
  output reg  [31:0] scan_cycles_o,     // clocks of the last completed scan
  output reg  [31:0] scan_cycles_max_o, // longest completed scan
  output reg  [31:0] cycle_q_o          // clocks of the current scan so far
);
  localparam [1:0] StInit  = 2'd0;
  localparam [1:0] StIdle  = 2'd1;
  localparam [1:0] StRun   = 2'd2;
  localparam [1:0] StFault = 2'd3;

  reg [1:0] state_q, state_d;
  reg       first_q;                    // this is the first (latch) clock of a scan

  assign exec_o  = (state_q == StRun);
  assign latch_o = exec_o && first_q;
  assign ready_o = (state_q == StIdle);
  assign fault_o = (state_q == StFault);

  // Clocks this scan will have used once the current clock ends.
  wire [31:0] cycles_now = latch_o ? 32'd1 : cycle_q_o + 32'd1;
  // cycles_now > scan_cycles_max_o, with the compare straight from the flip-flops: the
  // increment and the compare in series were the HX8K critical path (issue 20).
  // cycle_q_o + 1 > max is cycle_q_o >= max, as cycle_q_o + 1 never wraps while the
  // scan runs (the watchdog ends it before cycle_q_o reaches 2^32 - 1).
  wire        longest = latch_o ? (scan_cycles_max_o == 32'd0)
                                : (cycle_q_o >= scan_cycles_max_o);
  // Without END in this clock the scan needs at least one clock more: past the limit?
  wire watchdog_fire = exec_o && !end_i && (cycles_now >= watchdog_limit_i);
  assign start_o = run_i && ((state_q == StIdle) || (exec_o && end_i));

  always @(*) begin
    state_d = state_q;
    case (state_q)
      StInit:  if (mem_ready_i) state_d = StIdle;
      StIdle:  if (run_i) state_d = StRun;
      StRun: begin
        if (watchdog_fire) state_d = StFault;
        else if (end_i && !run_i) state_d = StIdle;
      end
      default: state_d = StFault;
    endcase
  end

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q           <= StInit;
      first_q           <= 1'b0;
      scan_done_o       <= 1'b0;
      scan_count_o      <= 32'd0;
      scan_cycles_o     <= 32'd0;
      scan_cycles_max_o <= 32'd0;
      cycle_q_o         <= 32'd0;
    end else begin
      state_q     <= state_d;
      first_q     <= start_o;
      scan_done_o <= 1'b0;
      if (exec_o) begin
        cycle_q_o <= cycles_now;
        if (end_i) begin
          scan_done_o   <= 1'b1;
          scan_count_o  <= scan_count_o + 32'd1;
          scan_cycles_o <= cycles_now;
          if (longest) scan_cycles_max_o <= cycles_now;
        end
      end
    end
  end

`ifdef FORMAL
  // formal/scan_ctrl.sby, k-induction, from outside the counters: the clocks of a scan
  // are the executing clocks since its latch (f_exec, wrapping, minus its value at the
  // latch), the longest scan is the largest scan_cycles_o ever reported, the count is
  // the scan_done_o pulses, and the watchdog fires exactly on the clock a scan without
  // END reaches the limit. (The limit is a setting: stable while the CPU runs.)
  `include "formal_past.vh"
  always @(posedge clk_i) if (f_past_valid) assume ($stable(watchdog_limit_i));
  reg [31:0] f_exec, f_at_latch, f_max, f_done;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_exec     <= 32'd0;
      f_at_latch <= 32'd0;
      f_max      <= 32'd0;
      f_done     <= 32'd0;
    end else begin
      if (exec_o)  f_exec     <= f_exec + 32'd1;
      if (latch_o) f_at_latch <= f_exec;
      if (scan_done_o) begin
        f_done <= f_done + 32'd1;
        if (scan_cycles_o > f_max) f_max <= scan_cycles_o;
      end
    end
  // the clocks of the current scan once this clock ends (this one included)
  wire [31:0] f_scan_len = f_exec + 32'd1 - (latch_o ? f_exec : f_at_latch);
  always @(*) if (rst_ni) begin
    assert (cycle_q_o == f_exec - f_at_latch);
    assert (scan_count_o == f_done + {31'd0, scan_done_o});
    assert (scan_cycles_max_o == ((scan_done_o && scan_cycles_o > f_max) ? scan_cycles_o
                                                                          : f_max));
    // a scan still running has not reached the limit (else FAULT): no count wraps
    if (exec_o && !first_q) assert (cycle_q_o < watchdog_limit_i);
    if (first_q) assert (exec_o);                    // (induction)
  end
  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    // a completed scan reports its clocks
    if ($past(exec_o && end_i)) assert (scan_cycles_o == cycle_q_o && scan_done_o);
    // the watchdog: FAULT from the clock after one that, without END, reached the limit
    // (written as <=: a cell apart from the RTL's >=, for make mutate's mapping)
    assert (fault_o == ($past(fault_o) || $past(exec_o && !end_i &&
                                               watchdog_limit_i <= f_scan_len)));
  end
  always @(*) if (rst_ni) begin
    cover (scan_count_o == 32'd2 && scan_cycles_max_o == 32'd3 && scan_cycles_o == 32'd2);
    cover (fault_o && watchdog_limit_i == 32'd3);
  end
`endif
endmodule
`default_nettype wire
