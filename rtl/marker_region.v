`default_nettype none
`include "param_check.vh"
// One direction of the dual-port marker area (paper Fig. 17) in a block RAM: the
// writer's condition cells and the reader's auxiliary buffer, docs/exchange.md.
//
// The cells are packed WordBits to a RAM word, and every word has three slots in the
// RAM (address {slot, word}) with three 2-bit slot pointers in flip-flops:
//   w: the slot with the writer's cells as written (its latest values),
//   p: the slot a snapshot takes (with the write buffer: the writer's cells as of its
//      last scan end; without it p follows w),
//   r: the reader's snapshot, taken at its scan start (snap_i): the auxiliary buffer.
// The update of Fig. 17 is r := p (or w) for every word at once: one clock, whatever
// the size, and a pointer copy, not a data copy. A write never goes to the slots r or
// p point to, so no snapshot is ever torn: it goes to w if w is neither, else to the
// slot that is neither (three slots always leave one). The pointers are per word, not
// per cell, so the flip-flops cost 6 per word (48 for 128 cells), not 2..6 per cell;
// the price is that a write changes one cell of a word and must rewrite the word:
// it reads the word from w (the read port, one clock) and writes the merged word in
// the next clock. Writes pipeline, one per clock (a merge reads the one before it
// through the bypass).
//
// The RAM is kept twice, written alike: the reader reads its copy, the writer's merge
// reads the other, so the two sides never share a port and neither ever waits for the
// other (spec §1: a write region per side, no arbitration). The price is a second
// block RAM per direction (one 256 x 16 iCE40 RAM each at 128 cells).
//
// After reset the RAM is cleared, one word a clock (4 * Words clocks): all cells read
// 0 then, and writes are dropped (ready_o low: the CPU starts no scan, and its hosts
// write nothing, before it is ready).
module marker_region #(
  parameter integer Cells       = 128,  // condition cells (a power of two; 100 crossings fit)
  parameter integer WordBits    = 16    // cells per RAM word (16: the iCE40's 256 x 16)
) (
  input  wire                     clk_i,
  input  wire                     rst_ni,
  input  wire                     write_buffer_i,  // 1: snapshots take published cells
  output wire                     ready_o,         // cleared after reset
  // writer: a write is taken in every clock with wr_req_i once ready_o (after reset)
  input  wire                     wr_req_i,
  input  wire [$clog2(Cells)-1:0] wr_idx_i,
  input  wire                     wr_data_i,
  input  wire                     publish_i,       // writer's scan end (this clock's write in)
  // reader: a read is taken in every clock with rd_req_i; its cell is on rd_data_o in
  // the next clock (only then: a block RAM's output register)
  input  wire                     snap_i,          // reader's scan start: reads from this
                                                   // clock on see the cells of before it
  input  wire                     rd_req_i,
  input  wire [$clog2(Cells)-1:0] rd_idx_i,
  output wire                     rd_data_o
);
  `PARAM_CHECK(g_bad_word_bits, WordBits < 2 || WordBits > 16 || (WordBits & (WordBits - 1)) != 0,
               "marker_region: WordBits must be 2, 4, 8 or 16 (a block RAM word)")
  `PARAM_CHECK(g_bad_cells, Cells < 2 * WordBits || Cells > 4096 || (Cells & (Cells - 1)) != 0,
               "marker_region: Cells must be a power of two, 2*WordBits..4096")

  localparam integer Words = Cells / WordBits;
  localparam integer IW    = $clog2(Cells);
  localparam integer BW    = $clog2(WordBits);   // bit in a word
  localparam integer WW    = IW - BW;            // word index (>= 1: Cells >= 2*WordBits)
  localparam integer AW    = WW + 2;             // RAM address {slot, word}

  // ---------------------------------------------------------------- clearing
  reg  [AW:0] clear_q;                  // next address to clear; bit AW: done
  wire        clearing = !clear_q[AW];
  assign ready_o = !clearing;

  // ---------------------------------------------------------------- slot pointers
  reg  [2*Words-1:0] r_q, p_q, w_q;
  wire [WW-1:0] w_word = wr_idx_i[IW-1:BW];
  wire [WW-1:0] r_word = rd_idx_i[IW-1:BW];
  wire [1:0] w_of_w = w_q[2*w_word +: 2];
  // the reader's slots after this clock's update (a read in the snap clock sees the new
  // snapshot). snap_i is the latest input (the bit side's scan start): each slot below
  // is picked per word from the pointer registers first, for both cases, and snap_i
  // chooses last.
  wire [2*Words-1:0] r_snap = write_buffer_i ? p_q : w_q;
  wire [2*Words-1:0] r_next = snap_i ? r_snap : r_q;
  wire [1:0] r_keep_r = r_q[2*r_word +: 2];
  wire [1:0] r_new_r  = r_snap[2*r_word +: 2];
  wire [1:0] r_of_r = snap_i ? r_new_r : r_keep_r;

  // ---------------------------------------------------------------- the two sides
  // a read is always taken (while clearing it answers 0); a write once cleared
  wire rd_take = rd_req_i;
  wire wr_take = wr_req_i && !clearing;

  // The slot a write goes to: not the reader's (after this clock's update) and, with
  // the write buffer, not the published one; w itself if it is neither (three slots
  // always leave one). Worked out for the reader's slot with and without this clock's
  // update; snap_i picks last.
  function automatic [1:0] write_slot(input [1:0] r, input [1:0] p, input [1:0] w,
                                      input wb);
    reg [2:0] busy;
    begin
      busy = (3'b001 << r) | (wb ? (3'b001 << p) : 3'b000);
      write_slot = !busy[w] ? w : !busy[0] ? 2'd0 : !busy[1] ? 2'd1 : 2'd2;
    end
  endfunction
  wire [1:0] w_p = p_q[2*w_word +: 2];
  wire [1:0] w_slot_keep = write_slot(r_q[2*w_word +: 2], w_p, w_of_w, write_buffer_i);
  wire [1:0] w_slot_new  = write_slot(r_snap[2*w_word +: 2], w_p, w_of_w, write_buffer_i);
  wire [1:0] w_slot = snap_i ? w_slot_new : w_slot_keep;

  // ---------------------------------------------------------------- the RAM, twice
  // no_rw_check: a read of the word written in the same clock may return either value;
  // the bypasses below give the new one (a merge reads the word the merge before it
  // writes; a snapshot taken in a clock may point the reader at a word being merged).
  (* no_rw_check *)
  reg  [WordBits-1:0] mem_r [0:(1 << AW)-1];   // the reader's copy
  (* no_rw_check *)
  reg  [WordBits-1:0] mem_w [0:(1 << AW)-1];   // the writer's copy (merge reads)
  reg  [WordBits-1:0] ram_r_q, ram_w_q;
  wire [AW-1:0] r_raddr = {r_of_r, r_word};
  wire [AW-1:0] w_raddr = {w_of_w, w_word};
  // the merge of a write taken last clock (pend_*): the word it read, one bit new
  reg           pend_q, pend_data_q;
  reg  [AW-1:0] pend_addr_q;
  reg  [BW-1:0] pend_bit_q;
  reg           byp_r_q, byp_w_q;        // the last read's address was written in its clock
  reg  [WordBits-1:0] byp_data_q;        // ... with this word (one write a clock)
  wire [WordBits-1:0] merge_in = byp_w_q ? byp_data_q : ram_w_q;
  wire [WordBits-1:0] read_word = byp_r_q ? byp_data_q : ram_r_q;
  wire [WordBits-1:0] merged = (merge_in & ~({{(WordBits-1){1'b0}}, 1'b1} << pend_bit_q)) |
                               ({{(WordBits-1){1'b0}}, pend_data_q} << pend_bit_q);
  wire          we    = clearing || pend_q;
  wire [AW-1:0] waddr = clearing ? clear_q[AW-1:0] : pend_addr_q;
  wire [WordBits-1:0] wdata = clearing ? {WordBits{1'b0}} : merged;

  always @(posedge clk_i) begin
    if (we) begin
      mem_r[waddr] <= wdata;
      mem_w[waddr] <= wdata;
    end
    if (rd_take) ram_r_q <= mem_r[r_raddr];
    if (wr_take) ram_w_q <= mem_w[w_raddr];
  end

  // ---------------------------------------------------------------- state
  reg [BW-1:0] rd_bit_q;
  reg          rd_zero_q;                 // read while clearing: every cell is 0
  integer i;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      clear_q     <= {(AW+1){1'b0}};
      r_q         <= {(2*Words){1'b0}};
      p_q         <= {(2*Words){1'b0}};
      w_q         <= {(2*Words){1'b0}};
      pend_q      <= 1'b0;
      pend_data_q <= 1'b0;
      pend_addr_q <= {AW{1'b0}};
      pend_bit_q  <= {BW{1'b0}};
      byp_r_q     <= 1'b0;
      byp_w_q     <= 1'b0;
      byp_data_q  <= {WordBits{1'b0}};
      rd_bit_q    <= {BW{1'b0}};
      rd_zero_q   <= 1'b0;
    end else begin
      if (clearing) clear_q <= clear_q + 1'b1;
      r_q <= r_next;
      for (i = 0; i < Words; i = i + 1) begin
        if (wr_take && w_word == i[WW-1:0]) w_q[2*i +: 2] <= w_slot;
        // published: at the writer's scan end with this clock's write, else unchanged;
        // without the write buffer p follows w (and no write avoids it)
        if (!write_buffer_i || publish_i)
          p_q[2*i +: 2] <= (wr_take && w_word == i[WW-1:0]) ? w_slot : w_q[2*i +: 2];
      end
      pend_q      <= wr_take;
      pend_data_q <= wr_data_i;
      pend_addr_q <= {w_slot, w_word};
      pend_bit_q  <= wr_idx_i[BW-1:0];
      // one write a clock: both bypasses take the same word
      byp_data_q <= wdata;
      if (rd_take) byp_r_q <= we && (waddr == r_raddr);
      if (wr_take) byp_w_q <= we && (waddr == w_raddr);
      if (rd_take) begin
        rd_bit_q  <= rd_idx_i[BW-1:0];
        rd_zero_q <= clearing;
      end
    end
  end
  assign rd_data_o = !rd_zero_q && read_word[rd_bit_q];

`ifdef FORMAL
  // formal/marker_region.sby proves, for all time by k-induction, that every read
  // returns the cell of the reader's snapshot as the shadow model below defines it
  // (the old flip-flop marker area's semantics), whatever the interleaving of writes,
  // snapshots and publications.
`include "formal_past.vh"
  always @(posedge clk_i) if (f_past_valid) assume ($stable(write_buffer_i));

  // the shadow: the cells as written, as published, and the reader's snapshot
  reg [Cells-1:0] f_work, f_pub, f_snap;
  reg             f_rd_q;
  reg [IW-1:0]    f_ridx_q;
  wire [Cells-1:0] f_work_d = wr_take ? ((f_work & ~({{(Cells-1){1'b0}}, 1'b1} << wr_idx_i)) |
                                         ({{(Cells-1){1'b0}}, wr_data_i} << wr_idx_i))
                                      : f_work;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      f_work <= {Cells{1'b0}};
      f_pub  <= {Cells{1'b0}};
      f_snap <= {Cells{1'b0}};
      f_rd_q <= 1'b0;
      f_ridx_q <= {IW{1'b0}};
    end else begin
      f_work <= f_work_d;
      if (publish_i) f_pub <= f_work_d;
      if (snap_i) f_snap <= write_buffer_i ? f_pub : f_work;
      f_rd_q   <= rd_take;
      f_ridx_q <= rd_idx_i;
    end
  end

  // clocks since reset, saturating where the clearing must have ended (a clearing that
  // stalled would read every cell as 0 and refuse every write, and keep the read claim)
  reg [AW:0] f_age;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) f_age <= {(AW+1){1'b0}};
    else if (!f_age[AW]) f_age <= f_age + 1'b1;

  always @(*) if (rst_ni) begin
    // the claim: a read returns its cell of the snapshot taken at the last update
    if (f_rd_q) assert (rd_data_o == f_snap[f_ridx_q]);
    // the clearing takes one clock per RAM address, then ends
    assert (clear_q == f_age);
    // invariants for the induction (f_inv_*: the bmc task drops them, so a mutant
    // must break a claim)
    if (clearing) begin
      f_inv_clear_shadow: assert (f_work == 0 && f_pub == 0 && f_snap == 0 && !pend_q);
      f_inv_clear_ptr: assert (r_q == 0 && p_q == 0 && w_q == 0);
      if (f_rd_q) f_inv_clear_read: assert (rd_zero_q);
    end
    if (pend_q) f_inv_pend: assert (w_q[2*pend_addr_q[WW-1:0] +: 2] == pend_addr_q[AW-1:WW]);
  end
  // per word (and per RAM address while clearing), gathered into one assertion each
  wire [(1 << AW)-1:0] f_cleared, f_copies;
  wire [Words-1:0]     f_slots_ok, f_r_ok, f_w_ok, f_p_ok;
  genvar f_a, f_w;
  for (f_a = 0; f_a < (1 << AW); f_a = f_a + 1) begin : g_f_clear
    assign f_cleared[f_a] = !(clearing && f_a < clear_q[AW-1:0]) || mem_r[f_a] == 0;
    assign f_copies[f_a]  = (clearing && f_a >= clear_q[AW-1:0]) || mem_r[f_a] == mem_w[f_a];
  end
  // what each pointer's slot holds: the RAM, or the merge being written this clock
  for (f_w = 0; f_w < Words; f_w = f_w + 1) begin : g_f_word
    localparam [WW-1:0] Wd = f_w;
    wire [1:0] r = r_q[2*f_w +: 2], p = p_q[2*f_w +: 2], w = w_q[2*f_w +: 2];
    wire [WordBits-1:0] r_has = (pend_q && pend_addr_q == {r, Wd}) ? merged : mem_r[{r, Wd}];
    wire [WordBits-1:0] p_has = (pend_q && pend_addr_q == {p, Wd}) ? merged : mem_r[{p, Wd}];
    wire [WordBits-1:0] w_has = (pend_q && pend_addr_q == {w, Wd}) ? merged : mem_r[{w, Wd}];
    assign f_slots_ok[f_w] = r != 2'd3 && p != 2'd3 && w != 2'd3;
    assign f_r_ok[f_w] = r_has == f_snap[f_w*WordBits +: WordBits];
    assign f_w_ok[f_w] = w_has == f_work[f_w*WordBits +: WordBits];
    assign f_p_ok[f_w] = write_buffer_i ? (p_has == f_pub[f_w*WordBits +: WordBits]) : (p == w);
  end
  always @(*) if (rst_ni) begin
    f_inv_cleared: assert (&f_cleared);
    f_inv_copies: assert (&f_copies);        // both copies are written alike
    f_inv_slots: assert (&f_slots_ok);
    if (!clearing) begin
      f_inv_r: assert (&f_r_ok);
      f_inv_w: assert (&f_w_ok);
      f_inv_p: assert (&f_p_ok);
    end
  end
  // the write buffer shows whole scans: a snapshot differs from the live cells
  always @(posedge clk_i) if (rst_ni) begin
    cover (f_rd_q && write_buffer_i && rd_data_o && !f_work[f_ridx_q]);
    cover (f_rd_q && !write_buffer_i && rd_data_o && !f_work[f_ridx_q]);
  end
`endif
endmodule
`default_nettype wire
