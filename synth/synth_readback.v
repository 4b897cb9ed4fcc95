`default_nettype none
// Read-back multiplexer of the FPGA wrapper: word addr_i of the core's status
// outputs, read over SPI (command 0x03).
module synth_readback #(
  parameter integer Words = 1
) (
  input  wire [Words*32-1:0] words_i,
  input  wire [23:0]         addr_i,
  output reg  [31:0]         data_o
);
  integer k;
  always @(*) begin
    data_o = 32'd0;
    for (k = 0; k < Words; k = k + 1)
      if (addr_i == k[23:0]) data_o = words_i[k*32 +: 32];
  end
endmodule
`default_nettype wire
