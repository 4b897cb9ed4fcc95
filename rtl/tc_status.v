`default_nettype none
`include "param_check.vh"
// Timer/counter status buffer (paper Fig. 2). The byte processor keeps the timers and
// counters in its own memory and copies each status bit here when a timer or counter
// instruction executes; the bit processor reads `T n` / `C n` from this buffer in one
// clock and never waits for the byte processor to look one up. In the other
// direction the bit side leaves the enable (timers) and count-pulse (counters) bits
// that the byte procedures read: the RLO at the moment it dispatches an instruction
// on that timer or counter.
// Parallel mode: an `updated` bit per timer/counter records that the byte side wrote
// its status since this scan's latch, so a bit instruction marked "after the update"
// (docs/isa.md, bit 16) waits exactly until the byte side's timer instruction has run.
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
  // bit side: enable / pulse bit written at dispatch
  input  wire                          ctl_we_i,
  input  wire                          ctl_is_counter_i,
  input  wire [$clog2(StatusBits)-1:0] ctl_idx_i,
  input  wire                          ctl_val_i,
  input  wire                          latch_i,        // a scan starts: nothing updated yet
  output reg  [StatusBits-1:0]         timer_status_o,
  output reg  [StatusBits-1:0]         counter_status_o,
  output reg  [StatusBits-1:0]         timer_enable_o,
  output reg  [StatusBits-1:0]         counter_pulse_o,
  output reg  [StatusBits-1:0]         timer_updated_o,
  output reg  [StatusBits-1:0]         counter_updated_o
);
  `PARAM_CHECK(g_bad_status_bits, StatusBits < 2,
               "tc_status: StatusBits must be at least 2 (an index needs a bit)")

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      timer_status_o   <= {StatusBits{1'b0}};
      counter_status_o <= {StatusBits{1'b0}};
      timer_enable_o   <= {StatusBits{1'b0}};
      counter_pulse_o  <= {StatusBits{1'b0}};
      timer_updated_o  <= {StatusBits{1'b0}};
      counter_updated_o <= {StatusBits{1'b0}};
    end else begin
      if (latch_i) begin
        timer_updated_o   <= {StatusBits{1'b0}};
        counter_updated_o <= {StatusBits{1'b0}};
      end
      // a write in the latch clock belongs to the new scan: after the clear
      if (status_we_i && !status_is_counter_i) timer_updated_o[status_idx_i]   <= 1'b1;
      if (status_we_i &&  status_is_counter_i) counter_updated_o[status_idx_i] <= 1'b1;
      if (status_we_i && !status_is_counter_i) timer_status_o[status_idx_i]   <= status_val_i;
      if (status_we_i &&  status_is_counter_i) counter_status_o[status_idx_i] <= status_val_i;
      if (ctl_we_i && !ctl_is_counter_i) timer_enable_o[ctl_idx_i]  <= ctl_val_i;
      if (ctl_we_i &&  ctl_is_counter_i) counter_pulse_o[ctl_idx_i] <= ctl_val_i;
    end
  end
endmodule
`default_nettype wire
