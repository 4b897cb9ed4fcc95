// Included first inside the `ifdef FORMAL block of a module with clk_i and rst_ni
// (hand-written; not generated): f_past_valid marks the clocks that have a past, and
// the proof starts in reset, so $past() is only read where it means something.
  reg f_past_valid = 1'b0;
  always @(posedge clk_i) f_past_valid <= 1'b1;
  always @(*) if (!f_past_valid) assume (!rst_ni);
