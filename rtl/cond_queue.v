`default_nettype none
`include "param_check.vh"
// Pointer-based condition queue (paper Fig. 16): one register file per direction, a
// write pointer advanced by the writer and a read pointer advanced by the reader, so
// both sides reach it in one clock and conditions come out in the order they went in.
//
// Two settings (free_i):
//  * strict (0): a FIFO. The writer stalls while it is full, the reader while it is
//    empty; nothing is lost, duplicated or reordered.
//  * free-running (1), the paper's: nobody waits. Each pointer returns to slot 0 at
//    its owner's scan start, so slot i holds the i-th condition of the scan. A slot
//    is `fresh` from its write to its read: writing a fresh slot overwrites it and
//    counts an overflow, reading a stale one returns its last value and counts an
//    underflow. The counts are sticky (they saturate).
//
// The loss counts lag by one clock (the rule: docs/exchange.md): a loss sets a
// flip-flop and the counter adds it in the next clock, so the 16-bit increment starts
// from a flip-flop instead of the other side's request strobe (a byte-bus write into
// this increment was the FPGA's critical path; issue 20). A queue loses at most one
// condition per kind and clock, so one flip-flop each holds it until it is counted.
module cond_queue #(
  parameter integer Depth = 8  // conditions the queue holds (a power of two, >= 2)
) (
  input  wire        clk_i,
  input  wire        rst_ni,
  input  wire        free_i,       // 0 strict, 1 free-running
  input  wire        wr_start_i,   // writer's scan start (free-running: pointer to 0)
  input  wire        rd_start_i,   // reader's scan start
  input  wire        wr_req_i,
  input  wire        wr_data_i,
  output wire        wr_ready_o,
  input  wire        rd_req_i,
  output wire        rd_data_o,
  output wire        rd_ready_o,
  output wire        full_o,
  output wire        empty_o,
  output reg  [15:0] overflows_o,     // the loss counts, up to one clock late
  output reg  [15:0] underflows_o,
  output wire [15:0] overflows_now_o, // ... with the pending event: exact now
  output wire [15:0] underflows_now_o
);
  localparam integer PtrW = $clog2(Depth);

  // Strict full/empty tell the pointers apart by one extra bit: that needs the slot
  // index to wrap exactly at Depth.
  `PARAM_CHECK(g_bad_depth, Depth < 2 || (Depth & (Depth - 1)) != 0,
               "cond_queue: Depth must be a power of two; at least 2")

  reg [Depth-1:0] data_q;
  reg [Depth-1:0] fresh_q;           // written and not yet read
  reg [PtrW:0]    wr_ptr_q, rd_ptr_q; // one extra bit: full vs empty in strict mode

  // Free-running: in its owner's scan-start clock a pointer is already back at slot 0
  // (the first instruction of a scan may use the queue in that very clock).
  wire            wr_restart = free_i && wr_start_i;
  wire            rd_restart = free_i && rd_start_i;
  wire [PtrW-1:0] wr_slot = wr_restart ? {PtrW{1'b0}} : wr_ptr_q[PtrW-1:0];
  wire [PtrW-1:0] rd_slot = rd_restart ? {PtrW{1'b0}} : rd_ptr_q[PtrW-1:0];
  // Strict full/empty are registers, worked out from the pointers' next values: the
  // writer's and the reader's wait conditions come from flip-flops.
  reg             strict_empty, strict_full;

  assign full_o     = free_i ? fresh_q[wr_slot] : strict_full;
  assign empty_o    = free_i ? !fresh_q[rd_slot] : strict_empty;
  assign wr_ready_o = free_i || !strict_full;
  assign rd_ready_o = free_i || !strict_empty;
  assign rd_data_o  = data_q[rd_slot];

  wire do_wr = wr_req_i && wr_ready_o;
  wire do_rd = rd_req_i && rd_ready_o;
  wire [PtrW:0] wr_ptr_d = wr_restart ? {{PtrW{1'b0}}, do_wr} : wr_ptr_q + {{PtrW{1'b0}}, do_wr};
  wire [PtrW:0] rd_ptr_d = rd_restart ? {{PtrW{1'b0}}, do_rd} : rd_ptr_q + {{PtrW{1'b0}}, do_rd};

  // Loss events of this clock, registered; the counters take them in the next clock.
  wire overflow  = free_i && do_wr && fresh_q[wr_slot] && !(do_rd && rd_slot == wr_slot);
  wire underflow = free_i && do_rd && !fresh_q[rd_slot];
  reg  overflow_q, underflow_q;
  // the count with the pending event added (saturating): the counter's next value
  assign overflows_now_o  = overflows_o + {15'd0, overflow_q && overflows_o != 16'hFFFF};
  assign underflows_now_o = underflows_o + {15'd0, underflow_q && underflows_o != 16'hFFFF};

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      data_q       <= {Depth{1'b0}};
      fresh_q      <= {Depth{1'b0}};
      wr_ptr_q     <= {(PtrW+1){1'b0}};
      rd_ptr_q     <= {(PtrW+1){1'b0}};
      strict_empty <= 1'b1;
      strict_full  <= 1'b0;
      overflow_q   <= 1'b0;
      underflow_q  <= 1'b0;
      overflows_o  <= 16'd0;
      underflows_o <= 16'd0;
    end else begin
      // Read first, then write: a write and a read of the same slot in one clock
      // (free-running) leave it fresh with the new condition.
      if (do_rd) fresh_q[rd_slot] <= 1'b0;
      if (do_wr) begin
        data_q[wr_slot]  <= wr_data_i;
        fresh_q[wr_slot] <= 1'b1;
      end
      overflow_q   <= overflow;
      underflow_q  <= underflow;
      overflows_o  <= overflows_now_o;
      underflows_o <= underflows_now_o;
      // pointers: free-running ones return to slot 0 at their owner's scan start
      wr_ptr_q     <= wr_ptr_d;
      rd_ptr_q     <= rd_ptr_d;
      strict_empty <= wr_ptr_d == rd_ptr_d;
      strict_full  <= wr_ptr_d == (rd_ptr_d ^ {1'b1, {PtrW{1'b0}}});
    end
  end

`ifdef FORMAL
  // formal/cond_queue.sby, by k-induction: both settings (free_i constant while
  // running). Invariants only the induction needs are labelled f_inv_* (the bmc task
  // drops them, so a mutant must break a claim).
`include "formal_past.vh"
  always @(posedge clk_i) if (f_past_valid && rst_ni) assume ($stable(free_i));

  // ================================================================ strict: a lossless FIFO
  wire [PtrW:0] f_fill = wr_ptr_q - rd_ptr_q;
  // the fill level is exact: never more than Depth; full/empty say so
  always @(*) if (rst_ni && !free_i) begin
    assert (f_fill <= Depth);
    assert (full_o  == (f_fill == Depth));
    assert (empty_o == (f_fill == 0));
    assert (wr_ready_o == !full_o && rd_ready_o == !empty_o);
  end
  // a side stalls exactly when it must: it advances iff it asks and may
  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && !free_i) begin
    assert (wr_ptr_q == $past(wr_ptr_q) + {{PtrW{1'b0}}, $past(wr_req_i && !full_o)});
    assert (rd_ptr_q == $past(rd_ptr_q) + {{PtrW{1'b0}}, $past(rd_req_i && !empty_o)});
  end
  // No loss, duplication or reordering: follow one condition, the f_nth to be
  // written (any n). It is read as the f_nth read, with the value it was written with.
  (* anyconst *) reg [7:0] f_nth;
  reg [7:0] f_writes, f_reads;
  reg       f_value, f_written;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      f_writes  <= 8'd0;
      f_reads   <= 8'd0;
      f_written <= 1'b0;
    end else begin
      if (do_wr) f_writes <= f_writes + 8'd1;
      if (do_rd) f_reads  <= f_reads + 8'd1;
      if (do_wr && f_writes == f_nth) begin
        f_value   <= wr_data_i;
        f_written <= 1'b1;
      end
    end
  end
  always @(*) if (rst_ni && !free_i) begin
    assume (f_writes != 8'hFF);                      // a bounded run (256 conditions)
    // the pointers count the conditions that went in and out
    assert (wr_ptr_q == f_writes[PtrW:0] && rd_ptr_q == f_reads[PtrW:0]);
    assert (f_writes - f_reads <= Depth);
    assert (f_written == (f_writes > f_nth));
    // while it is inside, the followed condition sits in its slot, unchanged
    if (f_written && f_reads <= f_nth) assert (data_q[f_nth[PtrW-1:0]] == f_value);
  end
  always @(*) if (rst_ni && !free_i && do_rd && f_reads == f_nth) begin
    assert (f_written);
    assert (rd_data_o == f_value);
  end

  // ================================================================ free-running
  // A shadow of the paper's queue kept from the ports: slot i takes the i-th condition
  // of the writer's scan and gives the reader its i-th read of its scan (positions
  // counted from each side's scan start, mod Depth); a slot holds an item from its write
  // until it is read. An item written into a slot that still holds one drops that one
  // (unless the reader takes it in the same clock): a loss, one overflow; a read of a
  // slot that holds none gets no item: one underflow.
  reg [PtrW-1:0]  f_wpos_q, f_rpos_q;      // next position of the scan, each side
  reg [Depth-1:0] f_holds;                 // slot holds an item not yet read
  wire [PtrW-1:0] f_wpos = wr_start_i ? {PtrW{1'b0}} : f_wpos_q;
  wire [PtrW-1:0] f_rpos = rd_start_i ? {PtrW{1'b0}} : f_rpos_q;
  wire f_taken = rd_req_i && f_holds[f_rpos];                  // an item goes out
  wire f_drop  = wr_req_i && f_holds[f_wpos] && !(f_taken && f_rpos == f_wpos);
  wire f_stale = rd_req_i && !f_holds[f_rpos];                 // a read without one
  // counts of items in, out and dropped (wrapping): each is one of them or inside
  reg [7:0] f_in, f_out, f_dropped;
  integer f_k;
  reg [7:0] f_inside;
  always @(*) begin
    f_inside = 8'd0;
    for (f_k = 0; f_k < Depth; f_k = f_k + 1) f_inside = f_inside + {7'd0, f_holds[f_k]};
  end
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_wpos_q  <= {PtrW{1'b0}};
      f_rpos_q  <= {PtrW{1'b0}};
      f_holds   <= {Depth{1'b0}};
      f_in      <= 8'd0;
      f_out     <= 8'd0;
      f_dropped <= 8'd0;
    end else begin
      f_wpos_q <= f_wpos + {{(PtrW-1){1'b0}}, wr_req_i};
      f_rpos_q <= f_rpos + {{(PtrW-1){1'b0}}, rd_req_i};
      if (f_taken) f_holds[f_rpos] <= 1'b0;
      if (wr_req_i) f_holds[f_wpos] <= 1'b1;
      f_in      <= f_in + {7'd0, wr_req_i};
      f_out     <= f_out + {7'd0, f_taken};
      f_dropped <= f_dropped + {7'd0, f_drop};
    end

  // Follow one item (any: the write in the first clock f_pick is high): it is delivered
  // once, to the read at its position, with its value, or dropped and counted.
  (* anyseq *) reg f_pick;
  reg           f_tracked, f_n_in;         // an item was picked; it is inside
  reg [PtrW-1:0] f_n_slot;
  reg           f_n_val;
  wire          f_n_start = free_i && !f_tracked && f_pick && wr_req_i;
  reg f_restarted;                         // the reader's scan started since the pick
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni)                        f_restarted <= 1'b0;
    else if (f_n_start)                 f_restarted <= 1'b0;
    else if (f_tracked && rd_start_i)   f_restarted <= 1'b1;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_tracked <= 1'b0;
      f_n_in    <= 1'b0;
      f_n_slot  <= {PtrW{1'b0}};
      f_n_val   <= 1'b0;
    end else if (f_n_start) begin
      f_tracked <= 1'b1;
      f_n_in    <= 1'b1;
      f_n_slot  <= f_wpos;
      f_n_val   <= wr_data_i;
    end else if (f_n_in && ((rd_req_i && f_rpos == f_n_slot) ||
                            (wr_req_i && f_wpos == f_n_slot))) begin
      f_n_in    <= 1'b0;                   // delivered, or dropped by the next write
    end

  always @(*) if (rst_ni && free_i) begin
    // nobody waits
    assert (wr_ready_o && rd_ready_o);
    // full / empty: the writer's next slot holds an item, the reader's holds none
    assert (full_o == f_holds[f_wpos]);
    assert (empty_o == !f_holds[f_rpos]);
    // the followed item: read at its position, it comes out with its value (and that
    // read is no underflow); a write over it before that is a loss
    if (f_n_in && rd_req_i && f_rpos == f_n_slot) assert (rd_data_o == f_n_val && !f_stale);
    if (f_n_in && wr_req_i && f_wpos == f_n_slot && !(rd_req_i && f_rpos == f_n_slot))
      assert (f_drop);
    // every item went out once, was dropped, or is inside
    assert (f_in == f_out + f_dropped + f_inside);
  end
  // losses counted exactly once: each clock's exact overflow / underflow count grows
  // by the drop / the read without an item of the clock before (saturating at 65535) ...
  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && free_i) begin
    assert (overflows_now_o == (($past(overflows_now_o) == 16'hFFFF) ? 16'hFFFF :
                                $past(overflows_now_o) + {15'd0, $past(f_drop)}));
    assert (underflows_now_o == (($past(underflows_now_o) == 16'hFFFF) ? 16'hFFFF :
                                 $past(underflows_now_o) + {15'd0, $past(f_stale)}));
  end
  // ... and the bus's counts are those of the clock before: one clock late, no more
  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    assert (overflows_o == $past(overflows_now_o));
    assert (underflows_o == $past(underflows_now_o));
  end
  // strict: nothing is lost, nothing counted
  always @(*) if (rst_ni && !free_i) assert (overflows_now_o == 16'd0 && underflows_now_o == 16'd0);
  // the RTL's state is the shadow's
  always @(*) if (rst_ni && free_i) begin
    f_inv_wpos: assert (wr_ptr_q[PtrW-1:0] == f_wpos_q);
    f_inv_rpos: assert (rd_ptr_q[PtrW-1:0] == f_rpos_q);
    f_inv_holds: assert (fresh_q == f_holds);
    if (f_n_in) f_inv_n_in: assert (f_holds[f_n_slot] && data_q[f_n_slot] == f_n_val);
  end

  always @(posedge clk_i) if (rst_ni) begin
    cover (!free_i && f_reads == 8'd3 && full_o == 1'b0);
    cover (!free_i && full_o && wr_req_i);
    // free-running: a loss and a read without an item counted; the followed item (a 1)
    // delivered from a slot past 0, by a reader whose scan restarted after the write
    cover (free_i && overflows_o == 16'd1 && underflows_o == 16'd1);
    cover (free_i && f_n_in && rd_req_i && f_rpos == f_n_slot && f_n_slot != 0 && f_n_val &&
           f_restarted);
  end
`endif
endmodule
`default_nettype wire
