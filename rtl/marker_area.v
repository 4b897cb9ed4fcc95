`default_nettype none
`include "param_check.vh"
// Dual-port marker area for free-running exchange (paper Fig. 17). Each side owns a
// write region of `Cells` condition cells (the bit side's cells carry `= FBY k`, the
// byte side's `WRITE FBI k`), so the two never write the same cell and need no
// arbitration. A reader sees the other side's conditions like inputs: through an
// auxiliary buffer that it updates at its own scan start (the paper's "update"), so
// one scan works on one consistent set — as far as the writer's cells were
// consistent when the copy was taken.
//
// Fig. 17 buffers the reader only: a writer half-way through its scan may have
// updated some cells and not others, and one snapshot can mix them. With
// WriteBuffer = 1 (write_buffer_i) the writer also keeps its writes in a private
// buffer and publishes them all at its own scan end, so a snapshot never sees half of
// a writer's scan.
module marker_area #(
  parameter integer Cells = 4  // condition cells per direction
) (
  input  wire             clk_i,
  input  wire             rst_ni,
  input  wire             write_buffer_i,  // 1: writers publish at their scan end
  // bit side: writes its cells (F_bB k), reads the byte side's (F_Bb k)
  input  wire             bit_start_i,     // bit scan start: update its snapshot
  input  wire             bit_end_i,       // bit scan end: publish (write buffer)
  input  wire [Cells-1:0] bit_wr_i,
  input  wire             bit_wr_data_i,
  output wire [Cells-1:0] bit_rd_data_o,   // snapshot of the byte side's cells
  // byte side: the mirror image
  input  wire             byte_start_i,
  input  wire             byte_end_i,
  input  wire [Cells-1:0] byte_wr_i,
  input  wire             byte_wr_data_i,
  output wire [Cells-1:0] byte_rd_data_o
);
  `PARAM_CHECK(g_bad_cells, Cells < 1, "marker_area: Cells must be at least 1")

  // Each side's region: the cells as written (`work`) and as published (`pub`).
  reg [Cells-1:0] bit_work_q, bit_pub_q, byte_work_q, byte_pub_q;
  // Each reader's auxiliary buffer.
  reg [Cells-1:0] bit_snap_q, byte_snap_q;

  wire [Cells-1:0] bit_work_d  = (bit_work_q & ~bit_wr_i) | ({Cells{bit_wr_data_i}} & bit_wr_i);
  wire [Cells-1:0] byte_work_d = (byte_work_q & ~byte_wr_i) |
                                 ({Cells{byte_wr_data_i}} & byte_wr_i);
  // What the other side may copy: the live cells (Fig. 17) or the published ones.
  wire [Cells-1:0] bit_visible  = write_buffer_i ? bit_pub_q  : bit_work_q;
  wire [Cells-1:0] byte_visible = write_buffer_i ? byte_pub_q : byte_work_q;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      bit_work_q  <= {Cells{1'b0}};
      bit_pub_q   <= {Cells{1'b0}};
      byte_work_q <= {Cells{1'b0}};
      byte_pub_q  <= {Cells{1'b0}};
      bit_snap_q  <= {Cells{1'b0}};
      byte_snap_q <= {Cells{1'b0}};
    end else begin
      bit_work_q  <= bit_work_d;
      byte_work_q <= byte_work_d;
      if (bit_end_i)    bit_pub_q   <= bit_work_d;   // this clock's write included
      if (byte_end_i)   byte_pub_q  <= byte_work_d;
      if (bit_start_i)  bit_snap_q  <= byte_visible;
      if (byte_start_i) byte_snap_q <= bit_visible;
    end
  end

  // A read in the scan-start clock itself sees the copy being taken (the first
  // instruction of a scan runs in its latch clock).
  assign bit_rd_data_o  = bit_start_i  ? byte_visible : bit_snap_q;
  assign byte_rd_data_o = byte_start_i ? bit_visible  : byte_snap_q;

`ifdef FORMAL
  // formal/marker_area.sby proves these for all time by k-induction.
`include "formal_past.vh"
  always @(posedge clk_i) if (f_past_valid) assume ($stable(write_buffer_i));

  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    // a reader's view moves only at its own scan start (the "update" of Fig. 17)
    if (!$past(bit_start_i))  assert (bit_snap_q  == $past(bit_snap_q));
    if (!$past(byte_start_i)) assert (byte_snap_q == $past(byte_snap_q));
    // ... and then it is what the writer had made visible
    if ($past(bit_start_i))   assert (bit_snap_q  == $past(byte_visible));
    if ($past(byte_start_i))  assert (byte_snap_q == $past(bit_visible));
    // a side's cells change only by its own writes: no cross-writes, no arbitration
    if ($past(bit_wr_i) == {Cells{1'b0}})  assert (bit_work_q  == $past(bit_work_q));
    if ($past(byte_wr_i) == {Cells{1'b0}}) assert (byte_work_q == $past(byte_work_q));
    // write buffer: what a reader can see changes only at the writer's scan end, and
    // then to the whole of that scan's writes
    if ($past(write_buffer_i) && !$past(byte_end_i)) assert (byte_pub_q == $past(byte_pub_q));
    if ($past(write_buffer_i) && !$past(bit_end_i))  assert (bit_pub_q  == $past(bit_pub_q));
    if ($past(byte_end_i)) assert (byte_pub_q == byte_work_q);
    if ($past(bit_end_i))  assert (bit_pub_q  == bit_work_q);
  end
  always @(posedge clk_i) if (rst_ni) cover (write_buffer_i && bit_snap_q != byte_work_q);
`endif
endmodule
`default_nettype wire
