`default_nettype none
// Two flip-flops per bit in front of an asynchronous input (FPGA wrapper, synth/).
module synth_sync #(
  parameter integer Width = 1
) (
  input  wire             clk_i,
  input  wire [Width-1:0] d_i,
  output wire [Width-1:0] q_o
);
  (* async_reg = "true" *) reg [Width-1:0] meta_q;
  (* async_reg = "true" *) reg [Width-1:0] sync_q;
  always @(posedge clk_i) begin
    meta_q <= d_i;
    sync_q <= meta_q;
  end
  assign q_o = sync_q;
endmodule
`default_nettype wire
