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
  // Proved as part of the byte port (formal/byte_port.sby, k-induction).
  reg f_past_valid = 1'b0;
  always @(posedge clk_i) f_past_valid <= 1'b1;

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
`endif
endmodule
`default_nettype wire
