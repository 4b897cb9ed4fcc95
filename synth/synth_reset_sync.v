`default_nettype none
// Reset of the FPGA wrapper: asserted at once (asynchronously), released in step
// with the clock, so that no flip-flop leaves reset in a different clock from another.
module synth_reset_sync (
  input  wire clk_i,
  input  wire rst_ni,   // the reset pin, active low, asynchronous
  output wire rst_no    // the same, deasserted synchronously
);
  // A reset synchroniser is the one place where a flop drives asynchronous resets.
  // verilator lint_off SYNCASYNCNET
  reg [1:0] q;
  // verilator lint_on SYNCASYNCNET
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) q <= 2'b00;
    else         q <= {q[0], 1'b1};
  end
  assign rst_no = q[1];
endmodule
`default_nettype wire
