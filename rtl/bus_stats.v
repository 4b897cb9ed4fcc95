`default_nettype none
// Stall statistics of one CPU (docs/byte-bus.md: STALLS_BIT, STALLS_BYTE): the clocks
// in which the bit side waited for the byte side (a condition channel, SCAN_DONE at
// END, a timer/counter update), and the clocks in which the byte side's bus access was
// refused and had to be repeated. 32 bits each, wrapping; only reset clears them.
module bus_stats (
  input  wire        clk_i,
  input  wire        rst_ni,
  input  wire        bit_stall_i,   // the bit side waits this clock
  input  wire        byte_stall_i,  // a byte-side access is refused this clock
  output reg  [31:0] stalls_bit_o,
  output reg  [31:0] stalls_byte_o
);
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      stalls_bit_o  <= 32'd0;
      stalls_byte_o <= 32'd0;
    end else begin
      if (bit_stall_i)  stalls_bit_o  <= stalls_bit_o + 32'd1;
      if (byte_stall_i) stalls_byte_o <= stalls_byte_o + 32'd1;
    end
  end

`ifdef FORMAL
  // Proved alone (formal/bus_stats.sby) and as part of the byte port
  // (formal/byte_port.sby), k-induction, against the clocks since reset rather than the
  // counters' own increments: every clock is a stall of a side or not, so each count
  // plus the clocks without that side's stall is the clocks since reset (all wrapping
  // at 32 bits, like the counters).
  `include "formal_past.vh"
  reg [31:0] f_clocks, f_bit_idle, f_byte_idle;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_clocks    <= 32'd0;
      f_bit_idle  <= 32'd0;
      f_byte_idle <= 32'd0;
    end else begin
      f_clocks <= f_clocks + 32'd1;
      if (!bit_stall_i)  f_bit_idle  <= f_bit_idle + 32'd1;
      if (!byte_stall_i) f_byte_idle <= f_byte_idle + 32'd1;
    end
  always @(*) if (rst_ni) begin
    assert (stalls_bit_o + f_bit_idle == f_clocks);
    assert (stalls_byte_o + f_byte_idle == f_clocks);
  end
  always @(*) if (rst_ni) cover (stalls_bit_o == 32'd2 && stalls_byte_o == 32'd1 && f_clocks == 32'd4);
`endif
endmodule
`default_nettype wire
