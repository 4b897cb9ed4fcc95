`default_nettype none
`include "param_check.vh"
// Binary output unit (paper Fig. 1): the process-image output (PIO) and the output
// register that drives the pins. `= Q` writes the PIO only; the pins follow at END
// (update_i). `= PQ` (direct) writes the pin and the PIO in the same clock, so a later
// read of Q and the next END agree with what the pin already shows. A fault forces
// the pins to 0 and keeps them there.
module output_unit #(
  parameter integer OutBits = 128  // number of binary outputs (OutBytes * 8)
) (
  input  wire                       clk_i,
  input  wire                       rst_ni,
  input  wire                       wr_en_i,      // write one bit in this clock
  input  wire [$clog2(OutBits)-1:0] wr_idx_i,     // byte*8 + bit
  input  wire                       wr_val_i,
  input  wire                       wr_direct_i,  // PQ: pin and PIO at once
  input  wire                       update_i,     // END: PIO -> pins
  input  wire                       fault_i,      // watchdog: pins to 0
  output reg  [OutBits-1:0]         pio_o,
  output reg  [OutBits-1:0]         pins_o
);
  `PARAM_CHECK(g_bad_out_bits, OutBits < 2,
               "output_unit: OutBits must be at least 2 (a write index needs a bit)")

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pio_o  <= {OutBits{1'b0}};
      pins_o <= {OutBits{1'b0}};
    end else begin
      if (wr_en_i) pio_o[wr_idx_i] <= wr_val_i;
      if (fault_i) begin
        pins_o <= {OutBits{1'b0}};
      end else if (update_i) begin
        pins_o <= pio_o;
      end else if (wr_en_i && wr_direct_i) begin
        pins_o[wr_idx_i] <= wr_val_i;
      end
    end
  end
endmodule
`default_nettype wire
