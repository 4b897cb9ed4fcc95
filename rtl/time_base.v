`default_nettype none
// Time base of one CPU (docs/byte-bus.md: CLOCK, TIME_MS): the clocks since clock 0,
// and TIME_MS = floor(clocks / tick_div_i) without a divider: a sub-counter wraps every
// tick_div_i clocks and then advances the milliseconds. Clock 0 is the first clock in
// which start_i is high (scan 0's latch, or in a plant core the plant's clock 0, so
// that its timers run on plant time); from then on every clock counts.
// TICK_DIV itself is a bus register (byte_port.v); a new value takes effect at the
// sub-counter's next compare.
module time_base (
  input  wire        clk_i,
  input  wire        rst_ni,
  input  wire        start_i,     // clock 0 (later clocks with start_i change nothing)
  input  wire [31:0] tick_div_i,  // clocks per millisecond
  output reg  [31:0] clock_o,     // CLOCK
  output reg  [31:0] ms_o         // TIME_MS
);
  reg        started_q;
  reg [31:0] sub_q;               // clocks into the current millisecond
  wire       counting = started_q || start_i;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      started_q <= 1'b0;
      clock_o   <= 32'd0;
      ms_o      <= 32'd0;
      sub_q     <= 32'd0;
    end else if (counting) begin
      started_q <= 1'b1;
      clock_o   <= clock_o + 32'd1;
      if (sub_q + 32'd1 >= tick_div_i) begin
        sub_q <= 32'd0;
        ms_o  <= ms_o + 32'd1;
      end else begin
        sub_q <= sub_q + 32'd1;
      end
    end
  end

`ifdef FORMAL
  // Proved alone (formal/time_base.sby, any TICK_DIV at any time) and as part of the
  // byte port (formal/byte_port.sby), k-induction. The milliseconds are checked from
  // outside, against CLOCK: a shadow notes CLOCK at each step of TIME_MS, and a step
  // comes exactly when TICK_DIV clocks have passed since the one before (clock 0
  // counting as a step), so that a constant TICK_DIV = D gives TIME_MS = floor(CLOCK / D)
  // (D = 0 counts like 1). Invariants only the induction needs are labelled f_inv_*
  // (the bmc task of time_base.sby, the mutation check's, drops them).
  `include "formal_past.vh"

  // nothing counts before clock 0
  always @(*) if (rst_ni && !started_q)
    assert (clock_o == 32'd0 && ms_o == 32'd0 && sub_q == 32'd0);
  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    // the clock counts every clock from clock 0 on
    if ($past(started_q) || $past(start_i)) assert (clock_o == $past(clock_o) + 32'd1);
    else assert (clock_o == $past(clock_o));
    // the milliseconds advance by one at most, and only from clock 0 on
    if ($past(started_q) || $past(start_i))
      assert (ms_o == $past(ms_o) || ms_o == $past(ms_o) + 32'd1);
    else assert (ms_o == $past(ms_o));
  end

  // f_ms_prev: TIME_MS a clock ago; f_mark: CLOCK at the last step of TIME_MS before
  // the last edge (0: clock 0). Both from the outputs only.
  reg  [31:0] f_ms_prev, f_mark;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_ms_prev <= 32'd0;
      f_mark    <= 32'd0;
    end else begin
      f_ms_prev <= ms_o;
      if (ms_o != f_ms_prev) f_mark <= clock_o;
    end
  wire        f_stepped = ms_o != f_ms_prev;      // TIME_MS stepped at the last edge
  wire [31:0] f_elapsed = clock_o - f_mark;       // clocks since the step before it
  // a step exactly when the divider's clocks have passed (as TICK_DIV was at the edge)
  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni &&
                              ($past(started_q) || $past(start_i)))
    assert (f_stepped == (f_elapsed >= $past(tick_div_i)));
  // the sub-counter holds the clocks into the current millisecond
  always @(*) if (rst_ni)
    f_inv_sub: assert (sub_q == (f_stepped ? 32'd0 : f_elapsed));

  // a millisecond of 3 clocks, then one of 2 (TICK_DIV written in between)
  reg f_three = 1'b0;
  always @(posedge clk_i) if (rst_ni && f_stepped && ms_o == 32'd1 && f_elapsed == 32'd3)
    f_three <= 1'b1;
  always @(*) if (rst_ni) cover (f_three && f_stepped && ms_o == 32'd2 && f_elapsed == 32'd2);
`endif
endmodule
`default_nettype wire
