`default_nettype none
// One buffered condition flip-flop (paper Fig. 11): a one-place mailbox for a logic
// condition between the two processors. The writer may put a condition only when the
// flip-flop is empty, the reader take one only when it is full; otherwise that side
// stalls (the caller holds its request and retries). So no condition is lost,
// duplicated or reordered, and a side waits only when it really must.
// A write and a read in the same clock cannot both succeed: the flip-flop is either
// empty (only the write succeeds) or full (only the read does).
module cond_ff (
  input  wire clk_i,
  input  wire rst_ni,
  input  wire wr_req_i,    // writer offers a condition this clock
  input  wire wr_data_i,
  output wire wr_ready_o,  // ... and it is taken (else: writer stalls)
  input  wire rd_req_i,    // reader wants a condition this clock
  output wire rd_data_o,
  output wire rd_ready_o,  // ... and rd_data_o is it (else: reader stalls)
  output wire full_o
);
  reg full_q, data_q;

  assign full_o     = full_q;
  assign wr_ready_o = !full_q;
  assign rd_ready_o = full_q;
  assign rd_data_o  = data_q;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      full_q <= 1'b0;
      data_q <= 1'b0;
    end else if (wr_req_i && !full_q) begin
      full_q <= 1'b1;
      data_q <= wr_data_i;
    end else if (rd_req_i && full_q) begin
      full_q <= 1'b0;
    end
  end

`ifdef FORMAL
  // Properties of the mailbox; formal/cond_ff.sby proves them by k-induction.
`include "formal_past.vh"

  // Count conditions written and read since reset: the difference is the fill level.
  reg [3:0] f_written, f_read;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      f_written <= 4'd0;
      f_read    <= 4'd0;
    end else begin
      if (wr_req_i && wr_ready_o) f_written <= f_written + 4'd1;
      if (rd_req_i && rd_ready_o) f_read    <= f_read + 4'd1;
    end
  end
  // full is exact: one condition held iff one more was written than read
  always @(*) if (rst_ni) assert (full_q == ((f_written - f_read) == 4'd1));
  always @(*) if (rst_ni) assert ((f_written - f_read) <= 4'd1);
  // never both in one clock; a side is refused exactly when it must be
  always @(*) assert (!(wr_ready_o && rd_ready_o));
  always @(*) assert (wr_ready_o == !full_q && rd_ready_o == full_q);
  // what is read is what was written (no loss, no change)
  reg f_data;
  always @(posedge clk_i) if (wr_req_i && wr_ready_o) f_data <= wr_data_i;
  always @(*) if (rst_ni && full_q) assert (data_q == f_data);
  // interesting states are reachable
  always @(posedge clk_i) if (rst_ni) cover (f_read == 4'd2);
  always @(posedge clk_i) if (rst_ni) cover (full_q && wr_req_i);
`endif
endmodule
`default_nettype wire
