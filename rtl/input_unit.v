`default_nettype none
`include "param_check.vh"
// Binary input unit (paper Fig. 1): the process-image input (PII) lives here, in the
// unit, not in the processor. A latch (scan start or REFRESH) copies the pins into the
// PII and publishes the edges seen since the previous latch; between latches the
// edge accumulators keep every rising and falling edge, so a pulse shorter than a
// scan still shows up in IR/IF. Direct reads (PI) take pins_i as it is.
//
// A REFRESH that is a scan's first instruction executes in the scan's latch clock:
// that clock holds two latches, the scan start's and the REFRESH's. The second finds
// no edge since the first (spec §4: "after the previous latch up to and including
// this one"), so IR/IF come out 0, exactly as with any instruction (a NOP) in front
// of the REFRESH when the pins do not move in between.
//
// pins_i must already be synchronous to clk_i (an FPGA top puts a synchroniser in
// front); one pin sample per clock.
module input_unit #(
  parameter integer InBits = 128  // number of binary inputs (InBytes * 8)
) (
  input  wire              clk_i,
  input  wire              rst_ni,
  input  wire [InBits-1:0] pins_i,
  input  wire              latch_i,  // scan start: take the image in this clock
  input  wire              refresh_i,// REFRESH: take the image in this clock
  output reg  [InBits-1:0] pii_o,    // I b.n (the image register)
  output reg  [InBits-1:0] rise_o,   // IR b.n: rose since the previous latch
  output reg  [InBits-1:0] fall_o,   // IF b.n: fell since the previous latch
  // The edges since the previous latch, this clock's included: what a single latch in
  // this clock takes into IR/IF (the bit processor's operand stage reads them). A
  // second latch in the clock (REFRESH in the latch clock) takes none instead: the
  // reader applies that after its bit select, so that refresh_i (late: it comes from
  // the instruction executing now) does not run through the wide select.
  output wire [InBits-1:0] rise_pend_o,
  output wire [InBits-1:0] fall_pend_o
);
  `PARAM_CHECK(g_bad_in_bits, InBits < 1, "input_unit: InBits must be at least 1")

  // Pin value one clock ago. Reset to 0: before the first scan every input counts as
  // having been 0, so an input that is 1 at the first latch shows a rising edge.
  reg  [InBits-1:0] pins_prev_q;
  reg  [InBits-1:0] rise_acc_q, fall_acc_q;  // edges since the last latch
  wire [InBits-1:0] rise_now = pins_i & ~pins_prev_q;
  wire [InBits-1:0] fall_now = ~pins_i & pins_prev_q;

  wire latch  = latch_i || refresh_i;
  wire twice  = latch_i && refresh_i;  // the REFRESH sees no edge since the scan start
  assign rise_pend_o = rise_acc_q | rise_now;
  assign fall_pend_o = fall_acc_q | fall_now;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pins_prev_q <= {InBits{1'b0}};
      rise_acc_q  <= {InBits{1'b0}};
      fall_acc_q  <= {InBits{1'b0}};
      pii_o       <= {InBits{1'b0}};
      rise_o      <= {InBits{1'b0}};
      fall_o      <= {InBits{1'b0}};
    end else begin
      pins_prev_q <= pins_i;
      if (latch) begin
        // The latch clock's own edge belongs to this latch ("up to and including").
        pii_o      <= pins_i;
        rise_o     <= rise_pend_o & {InBits{!twice}};
        fall_o     <= fall_pend_o & {InBits{!twice}};
        rise_acc_q <= {InBits{1'b0}};
        fall_acc_q <= {InBits{1'b0}};
      end else begin
        rise_acc_q <= rise_acc_q | rise_now;
        fall_acc_q <= fall_acc_q | fall_now;
      end
    end
  end
endmodule
`default_nettype wire
