`default_nettype none
`include "param_check.vh"
// Timer/counter status buffer (paper Fig. 2). The byte processor keeps the timers and
// counters in its own memory and copies each status bit here when a timer or counter
// instruction executes; the bit processor reads `T n` / `C n` from this buffer in one
// clock and never waits for the byte processor to look one up. In the other
// direction the bit side leaves the enable (timers) and count-pulse (counters) bits
// that the byte procedures read. Two writers, one per mode (partitioned_i selects):
// serial mode, the dispatch (ctl_*): the RLO at the moment it dispatches an instruction
// on that timer or counter; parallel and free-running mode, the bit processor's own
// `= T n` / `= C n` (bit_*, `--tc-path status`, docs/exchange.md): one clock, never a
// wait, the byte side's flagged SD/SS/SP/SF/CU/CD/S C/R C read the bit over the bus.
// Parallel mode: an `updated` bit per timer/counter records that the byte side wrote
// its status since this scan's latch, so a bit instruction marked "after the update"
// (docs/isa.md, bit 16) waits exactly until the byte side's timer instruction has run.
// The mirror image for the enable / pulse half: a `written` bit per timer/counter
// records that the bit processor wrote its enable / pulse bit since this scan's latch,
// so that a parallel-mode byte procedure flagged "status wait" (--tc-path status)
// reads the bit of this scan and not the previous one (docs/exchange.md).
module tc_status #(
  parameter integer StatusBits = 64  // timers T0.. and counters C0.. (each)
) (
  input  wire                          clk_i,
  input  wire                          rst_ni,
  // byte side: one status bit per write
  input  wire                          status_we_i,
  input  wire                          status_is_counter_i,
  input  wire [$clog2(StatusBits)-1:0] status_idx_i,
  input  wire                          status_val_i,
  // bit side: enable / pulse bit written at a serial dispatch ...
  input  wire                          ctl_we_i,
  input  wire                          ctl_is_counter_i,
  input  wire [$clog2(StatusBits)-1:0] ctl_idx_i,
  input  wire                          ctl_val_i,
  // ... or by the bit processor's `= T n` / `= C n` (parallel and free-running mode)
  input  wire                          partitioned_i,  // parallel or free-running mode
  input  wire                          bit_we_i,
  input  wire                          bit_is_counter_i,
  input  wire [$clog2(StatusBits)-1:0] bit_idx_i,
  input  wire                          bit_val_i,
  input  wire                          latch_i,        // a scan starts: nothing updated yet
  output reg  [StatusBits-1:0]         timer_status_o,
  output reg  [StatusBits-1:0]         counter_status_o,
  output reg  [StatusBits-1:0]         timer_enable_o,
  output reg  [StatusBits-1:0]         counter_pulse_o,
  output reg  [StatusBits-1:0]         timer_updated_o,
  output reg  [StatusBits-1:0]         counter_updated_o,
  output reg  [StatusBits-1:0]         timer_written_o,
  output reg  [StatusBits-1:0]         counter_written_o
);
  `PARAM_CHECK(g_bad_status_bits, StatusBits < 2,
               "tc_status: StatusBits must be at least 2 (an index needs a bit)")

  // the enable / pulse writer of this mode
  wire                          en_we  = partitioned_i ? bit_we_i : ctl_we_i;
  wire                          en_cnt = partitioned_i ? bit_is_counter_i : ctl_is_counter_i;
  wire [$clog2(StatusBits)-1:0] en_idx = partitioned_i ? bit_idx_i : ctl_idx_i;
  wire                          en_val = partitioned_i ? bit_val_i : ctl_val_i;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      timer_status_o   <= {StatusBits{1'b0}};
      counter_status_o <= {StatusBits{1'b0}};
      timer_enable_o   <= {StatusBits{1'b0}};
      counter_pulse_o  <= {StatusBits{1'b0}};
      timer_updated_o  <= {StatusBits{1'b0}};
      counter_updated_o <= {StatusBits{1'b0}};
      timer_written_o   <= {StatusBits{1'b0}};
      counter_written_o <= {StatusBits{1'b0}};
    end else begin
      if (latch_i) begin
        timer_updated_o   <= {StatusBits{1'b0}};
        counter_updated_o <= {StatusBits{1'b0}};
        timer_written_o   <= {StatusBits{1'b0}};
        counter_written_o <= {StatusBits{1'b0}};
      end
      // a write in the latch clock belongs to the new scan: after the clear
      if (status_we_i && !status_is_counter_i) timer_updated_o[status_idx_i]   <= 1'b1;
      if (status_we_i &&  status_is_counter_i) counter_updated_o[status_idx_i] <= 1'b1;
      if (status_we_i && !status_is_counter_i) timer_status_o[status_idx_i]   <= status_val_i;
      if (status_we_i &&  status_is_counter_i) counter_status_o[status_idx_i] <= status_val_i;
      if (en_we && !en_cnt) timer_enable_o[en_idx]  <= en_val;
      if (en_we &&  en_cnt) counter_pulse_o[en_idx] <= en_val;
      // only the bit processor's own writes count (a serial dispatch needs no wait)
      if (partitioned_i && bit_we_i && !bit_is_counter_i) timer_written_o[bit_idx_i]   <= 1'b1;
      if (partitioned_i && bit_we_i &&  bit_is_counter_i) counter_written_o[bit_idx_i] <= 1'b1;
    end
  end

`ifdef FORMAL
  // Properties of the enable / pulse half (Fig. 2, bit -> byte); formal/tc_status.sby
  // proves them by k-induction. A shadow of the two bit vectors, written from the
  // ports by the mode's writer (the dispatch in serial mode, the bit processor
  // otherwise), must equal the outputs: a write is readable on the byte bus the clock
  // after it (one clock, no handshake), the other writer is ignored, no other bit moves,
  // and the status half (byte -> bit) never touches them nor they it.
`include "formal_past.vh"
  reg [StatusBits-1:0] f_en, f_pulse, f_tst, f_cst;
  wire f_w_we = partitioned_i ? bit_we_i : ctl_we_i;
  wire f_w_c  = partitioned_i ? bit_is_counter_i : ctl_is_counter_i;
  wire [$clog2(StatusBits)-1:0] f_w_i = partitioned_i ? bit_idx_i : ctl_idx_i;
  wire f_w_v  = partitioned_i ? bit_val_i : ctl_val_i;
  integer f_k;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      f_en <= {StatusBits{1'b0}};  f_pulse <= {StatusBits{1'b0}};
      f_tst <= {StatusBits{1'b0}}; f_cst <= {StatusBits{1'b0}};
    end else begin
      for (f_k = 0; f_k < StatusBits; f_k = f_k + 1) begin
        if (f_w_we && f_w_i == f_k && !f_w_c) f_en[f_k]    <= f_w_v;
        if (f_w_we && f_w_i == f_k &&  f_w_c) f_pulse[f_k] <= f_w_v;
        if (status_we_i && status_idx_i == f_k && !status_is_counter_i) f_tst[f_k] <= status_val_i;
        if (status_we_i && status_idx_i == f_k &&  status_is_counter_i) f_cst[f_k] <= status_val_i;
      end
    end
  end
  always @(*) if (rst_ni) begin
    assert (timer_enable_o == f_en);
    assert (counter_pulse_o == f_pulse);
    assert (timer_status_o == f_tst);
    assert (counter_status_o == f_cst);
  end
  // in parallel mode the dispatch's port is dead: a serial-mode-only write never lands
  always @(posedge clk_i) if (rst_ni && f_past_valid && $past(rst_ni) && $past(partitioned_i)
                              && !$past(bit_we_i))
    assert (timer_enable_o == $past(timer_enable_o) && counter_pulse_o == $past(counter_pulse_o));
  // reachable: the bit side sets an enable (also inside bit_proc's proof, where the
  // dispatch's port is tied off; tc_status.sby's free ports also reach it with a
  // dispatch offering the other value in the same clock)
  always @(posedge clk_i) if (rst_ni)
    cover (f_past_valid && $past(partitioned_i && bit_we_i && !bit_is_counter_i && bit_val_i)
           && timer_enable_o[$past(bit_idx_i)]);

  // The written bits (the status wait, docs/exchange.md), for any one timer and counter
  // f_n: set in the clock after the bit processor wrote its enable / pulse bit (also
  // in a latch clock: that write is the new scan's), cleared by a latch without such a
  // write, held otherwise; a serial dispatch never sets them. A byte procedure that
  // waits for the bit therefore reads the value written in its own scan.
  (* anyconst *) reg [$clog2(StatusBits)-1:0] f_n;
  wire f_wt = partitioned_i && bit_we_i && !bit_is_counter_i && bit_idx_i == f_n;
  wire f_wc = partitioned_i && bit_we_i &&  bit_is_counter_i && bit_idx_i == f_n;
  always @(posedge clk_i) if (rst_ni && f_past_valid && $past(rst_ni)) begin
    assert (timer_written_o[f_n] ==
            ($past(f_wt) || ($past(timer_written_o[f_n]) && !$past(latch_i))));
    assert (counter_written_o[f_n] ==
            ($past(f_wc) || ($past(counter_written_o[f_n]) && !$past(latch_i))));
  end
  always @(*) if (!rst_ni) assert (timer_written_o == 0 && counter_written_o == 0);
  // What the waiting byte procedure relies on: while the bit is written, the enable /
  // pulse bit holds the value of the bit processor's last write (unless a serial-mode
  // dispatch wrote it since: a mode change inside a scan, which the CPU never makes).
  reg f_tv, f_cv, f_t_own, f_c_own;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_t_own <= 1'b0;
      f_c_own <= 1'b0;
    end else begin
      if (f_wt) begin
        f_tv <= bit_val_i;
        f_t_own <= 1'b1;
      end else if (!partitioned_i && ctl_we_i && !ctl_is_counter_i && ctl_idx_i == f_n)
        f_t_own <= 1'b0;
      if (f_wc) begin
        f_cv <= bit_val_i;
        f_c_own <= 1'b1;
      end else if (!partitioned_i && ctl_we_i && ctl_is_counter_i && ctl_idx_i == f_n)
        f_c_own <= 1'b0;
    end
  always @(*) if (rst_ni) begin
    if (timer_written_o[f_n] && f_t_own) assert (timer_enable_o[f_n] == f_tv);
    if (counter_written_o[f_n] && f_c_own) assert (counter_pulse_o[f_n] == f_cv);
  end
  // reachable: a counter's written bit set, then cleared by the next scan's latch
  always @(posedge clk_i) if (rst_ni)
    cover (f_past_valid && $past(counter_written_o[f_n]) && !counter_written_o[f_n]);
`endif
endmodule
`default_nettype wire
