`default_nettype none
`include "param_check.vh"
// Binary output unit (paper Fig. 1): the process-image output (PIO) and the output
// register that drives the pins. `= Q` writes the PIO only; the pins follow at a PIO
// update (update_i: END, or `REFRESH Q` mid-scan). `= PQ` (direct) writes the pin and
// the PIO in the same clock, so a later read of Q and the next update agree with what
// the pin already shows. A fault forces the pins to 0 and keeps them there.
// The unit's edge detection (the paper's "not shown" half of Fig. 1): every update
// records which pins it changed, rise_o (`QR`) 0 -> 1 and fall_o (`QF`) 1 -> 0, until
// the next update; a PQ write moves its pin outside an update, so no update flags it.
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
  output reg  [OutBits-1:0]         pins_o,
  output reg  [OutBits-1:0]         rise_o,       // QR: rose at the last update
  output reg  [OutBits-1:0]         fall_o        // QF: fell at the last update
);
  `PARAM_CHECK(g_bad_out_bits, OutBits < 2,
               "output_unit: OutBits must be at least 2 (a write index needs a bit)")

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pio_o  <= {OutBits{1'b0}};
      pins_o <= {OutBits{1'b0}};
      rise_o <= {OutBits{1'b0}};
      fall_o <= {OutBits{1'b0}};
    end else begin
      if (wr_en_i) pio_o[wr_idx_i] <= wr_val_i;
      if (fault_i) begin
        pins_o <= {OutBits{1'b0}};
      end else if (update_i) begin
        pins_o <= pio_o;
        rise_o <= pio_o & ~pins_o;
        fall_o <= ~pio_o & pins_o;
      end else if (wr_en_i && wr_direct_i) begin
        pins_o[wr_idx_i] <= wr_val_i;
      end
    end
  end
endmodule
`default_nettype wire
