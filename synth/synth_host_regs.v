`default_nettype none
// Host registers of the FPGA wrapper: words written over SPI (command 0x02) that
// drive the core's configuration inputs, one flip-flop per bit.
module synth_host_regs #(
  parameter integer Words = 1
) (
  input  wire                  clk_i,
  input  wire                  rst_ni,
  input  wire                  we_i,
  input  wire [23:0]           addr_i,
  input  wire [31:0]           data_i,
  output reg  [Words*32-1:0]   q_o
);
  integer k;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      q_o <= {(Words*32){1'b0}};
    end else if (we_i) begin
      for (k = 0; k < Words; k = k + 1)
        if (addr_i == k[23:0]) q_o[k*32 +: 32] <= data_i;
    end
  end
endmodule
`default_nettype wire
