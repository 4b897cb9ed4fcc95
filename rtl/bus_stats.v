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
endmodule
`default_nettype wire
