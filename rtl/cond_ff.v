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
  // Properties of the mailbox (formal/cond_ff.sby, k-induction), stated against a
  // shadow kept from the ports alone: the conditions taken from the writer and given
  // to the reader, and the value of the last one taken — not against full_q.
`include "formal_past.vh"

  reg [3:0] f_written, f_read;          // handshakes since reset (wrapping)
  reg       f_data;                     // the last condition taken from the writer
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      f_written <= 4'd0;
      f_read    <= 4'd0;
    end else begin
      if (wr_req_i && wr_ready_o) f_written <= f_written + 4'd1;
      if (rd_req_i && rd_ready_o) f_read    <= f_read + 4'd1;
    end
  end
  always @(posedge clk_i) if (wr_req_i && wr_ready_o) f_data <= wr_data_i;
  wire [3:0] f_held = f_written - f_read;   // conditions inside

  always @(*) if (rst_ni) begin
    // one place: a condition is never taken while one is held (none lost), and none is
    // given that was not taken (none duplicated)
    assert (f_held <= 4'd1);
    // a side waits exactly when it must: the writer while one is held, the reader
    // while none is; full_o says which
    assert (wr_ready_o == (f_held == 4'd0));
    assert (rd_ready_o == (f_held == 4'd1));
    assert (full_o == (f_held == 4'd1));
    // what is read is what was written (no change)
    if (rd_ready_o) assert (rd_data_o == f_data);
  end
  // interesting states are reachable
  always @(posedge clk_i) if (rst_ni) cover (f_read == 4'd2);
  always @(posedge clk_i) if (rst_ni) cover (full_o && wr_req_i);
`endif
endmodule
`default_nettype wire
