`default_nettype none
`include "param_check.vh"
// Copy engine of a plant core (docs/multicore.md): streams one list of the copy plan
// between the shared memory and the core's local memories (M bits through bit_proc's
// copy port, MW words in plc_core's word RAM). The core sequencer (core_seq.v) loads a
// list when a precycle or postcycle begins, runs it while it owns the memories and
// waits for done_o; when a copy may hold the lock, and how long, is the sequencer's.
//
// The copy plan (plan RAM, written by the toolchain) is a list of copies, each a
// descriptor followed by its items; the precycle's list starts at 0 (pre_len_i
// entries), the postcycle's at post_base_i (post_len_i entries):
//   descriptor [31] = 1, [23:16] the writing core (ping-pong buffer select)
//   item       [31] = 0, [30] bit (1) / word (0), [29:25] bit in the shared word,
//              [24:12] shared word, [11:0] local address (M bit index or MW index)
// Entries stream through a 3-stage pipeline (fetch the entry, access the source,
// write the destination), one per clock without stalls: a copy of n items takes
// 1 + n clocks, a list 2 more (fill, drain). A precycle reads the shared word in stage
// I and writes the local memory in stage C; a postcycle reads the local memory in
// stage I and writes the shared word in stage C, gathering consecutive bit items of
// one shared word into one write (the writer owns the word).
// Ping-pong (ping_i): a reader reads, for each writer, the buffer that writer had
// published when the precycle began (the selects are taken at load_pre_i); a writer
// writes the buffer readers do not read. If a writer starts overwriting the buffer a
// precycle reads before the precycle has read all it reads from it (a very fast
// writer), the read could be torn: overtaken_o.
module copy_engine #(
  parameter integer Cores       = 2,     // cores of the plant (writer ids)
  parameter integer PlanWords   = 1024,  // copy-plan entries (power of two)
  parameter integer SharedWords = 4096,  // shared 32-bit words SH0.. (power of two)
  parameter integer MarkerBits  = 2048,  // the core's M bits
  parameter integer MwWords     = 256    // the core's MW words
) (
  input  wire                          clk_i,
  input  wire                          rst_ni,
  // copy plan load (while stopped)
  input  wire                          plan_we_i,
  input  wire [$clog2(PlanWords)-1:0]  plan_waddr_i,
  input  wire [31:0]                   plan_wdata_i,
  // configuration, constant while running
  input  wire [$clog2(PlanWords):0]    pre_len_i,    // precycle entries (from plan address 0)
  input  wire [$clog2(PlanWords)-1:0]  post_base_i,  // first postcycle entry
  input  wire [$clog2(PlanWords):0]    post_len_i,   // postcycle entries
  input  wire                          ping_i,       // ping-pong protection
  // the sequencer
  input  wire                          load_pre_i,   // a precycle begins: its list, the selects
  input  wire                          load_post_i,  // a postcycle begins: its list
  input  wire                          run_i,        // copy the loaded list (it owns the memories)
  output wire                          done_o,       // ... and it is copied (pipeline drained)
  output wire                          empty_o,      // the loaded list has no entries
  output reg                           post_o,       // the loaded list is a postcycle's
  output wire                          overtaken_o,  // ping-pong: this read may be torn
  // shared memory (shared_mem.v): read port, write port, ping-pong selects
  output wire                          sh_re_o,
  output wire [$clog2(SharedWords):0]  sh_raddr_o,   // {buffer, word}
  output wire [$clog2(Cores)-1:0]      sh_rbank_o,   // the word's writer: its bank
  input  wire [31:0]                   sh_rdata_i,   // the word read the clock before
  output wire                          sh_we_o,
  output wire [$clog2(SharedWords):0]  sh_waddr_o,
  output wire [31:0]                   sh_wdata_o,
  input  wire [Cores-1:0]              sh_sel_i,     // per writer: the buffer to read
  input  wire [Cores-1:0]              sh_posting_i, // per core: writes shared memory now
  // local memories: M bits, MW words (valid while run_i)
  output wire                          m_we_o,
  output wire [$clog2(MarkerBits)-1:0] m_addr_o,
  output wire                          m_wdata_o,
  input  wire                          m_rdata_i,
  output wire                          w_we_o,
  output wire [$clog2(MwWords)-1:0]    w_addr_o,
  output wire [15:0]                   w_wdata_o,
  input  wire [15:0]                   w_rdata_i
`ifdef FORMAL
  ,
  // for the sequencer's proof (core_seq.v): the list has begun; a local read this
  // clock; the clocks this list has run before this one, and its length
  output wire                          f_started_o,
  output wire                          f_local_rd_o,
  output reg  [$clog2(PlanWords)+2:0]  f_runs_o,
  output wire [$clog2(PlanWords):0]    f_len_o
`endif
);
  localparam integer PaW = $clog2(PlanWords);
  localparam integer ShW = $clog2(SharedWords);
  localparam integer MaW = $clog2(MarkerBits);
  localparam integer WaW = $clog2(MwWords);
  localparam integer IdW = (Cores > 1) ? $clog2(Cores) : 1;

  // The copy plan's fields bound the sizes: descriptor [23:16] a writer, item [24:12]
  // a shared word, [11:0] a local address.
  if (Cores < 2 || Cores > 256) begin : g_bad_cores
    `PARAM_ERROR("copy_engine: Cores must be 2..256 (8-bit writer field of a descriptor)");
  end
  if (PlanWords < 2 || (PlanWords & (PlanWords - 1)) != 0) begin : g_bad_plan_words
    `PARAM_ERROR("copy_engine: PlanWords must be a power of two, at least 2");
  end
  if (SharedWords < 2 || SharedWords > 8192 || (SharedWords & (SharedWords - 1)) != 0)
  begin : g_bad_shared_words
    `PARAM_ERROR("copy_engine: SharedWords must be a power of two in 2..8192 (13-bit item field)");
  end
  if (MarkerBits < 2 || MarkerBits > 4096) begin : g_bad_marker_bits
    `PARAM_ERROR("copy_engine: MarkerBits must be 2..4096 (12-bit local address of an item)");
  end
  if (MwWords < 2 || MwWords > 4096) begin : g_bad_mw_words
    `PARAM_ERROR("copy_engine: MwWords must be 2..4096 (12-bit local address of an item)");
  end

  reg  [PaW:0]   issued_q;             // entries fetched of the current list
  reg  [PaW-1:0] base_q;
  reg  [PaW:0]   len_q;
  reg            f_valid_q;            // a plan entry arrives this clock (stage I)
  reg            c_valid_q;            // stage C holds an item
  reg            c_bit_q;
  reg [4:0]      c_pos_q;              // bit position in the shared word
  reg [ShW-1:0]  c_word_q;
  // verilator lint_off UNUSEDSIGNAL
  reg [11:0]     c_local_q;            // M bit index or MW index (fewer bits)
  // verilator lint_on UNUSEDSIGNAL
  reg [31:0]     gather_q;             // postcycle: bits of the shared word so far
  reg [IdW-1:0]  writer_q;             // the current copy's writer
  reg [Cores-1:0] sel_snap_q;          // ping-pong selects when the precycle began
  reg [Cores-1:0] dirty_q;             // ping-pong: writers that began overwriting them
  wire [31:0]    entry;

  // the peek port is left open (no cell of it is left): no host looks at the plan
  // verilator lint_off PINCONNECTEMPTY
  sync_ram #(.Words(PlanWords), .Width(32)) u_plan_ram (
    .clk_i  (clk_i),
    .we_i   (plan_we_i),
    .waddr_i(plan_waddr_i),
    .wdata_i(plan_wdata_i),
    .re_i   (1'b1),
    .raddr_i(base_q + issued_q[PaW-1:0]),
    .rdata_o(entry),
    .peek_addr_i(),
    .peek_data_o()
  );
  // verilator lint_on PINCONNECTEMPTY

  wire fetch = run_i && (issued_q != len_q);
  assign done_o  = run_i && (issued_q == len_q) && !f_valid_q && !c_valid_q;
  assign empty_o = (len_q == {(PaW+1){1'b0}});

  // stage I: the entry fetched in the last clock
  wire           i_item  = f_valid_q && !entry[31];
  wire           i_desc  = f_valid_q &&  entry[31];
  wire           i_bit   = entry[30];
  wire [ShW-1:0] i_word  = entry[12 +: ShW];
  wire [11:0]    i_local = entry[11:0];
  // ping-pong: readers read what each writer published last; a writer writes the other
  wire           rd_buf  = ping_i && sel_snap_q[writer_q];
  wire           own_sel = sh_sel_i[writer_q];
  wire           wr_buf  = ping_i && !own_sel;

  assign sh_re_o    = i_item && !post_o;
  // Ping-pong: writer w overwrites the buffer this precycle reads once it has published
  // again (its select moved) and writes; a read of w after that may mix two postcycles.
  wire [Cores-1:0] overwrite = sh_posting_i & (sh_sel_i ^ sel_snap_q);
  assign overtaken_o = ping_i && sh_re_o && (dirty_q[writer_q] || overwrite[writer_q]);
  assign sh_raddr_o = {rd_buf, i_word};
  assign sh_rbank_o = writer_q;

  // stage C: finish the item of the last clock
  wire        c_pre  = c_valid_q && !post_o;
  wire        c_post = c_valid_q &&  post_o;
  wire [31:0] gathered = gather_q | ({31'd0, m_rdata_i} << c_pos_q);
  // the gathered word is complete unless the next item adds a bit to the same word
  wire        gather_more = i_item && i_bit && (i_word == c_word_q);
  assign sh_we_o    = c_post && (!c_bit_q || !gather_more);
  assign sh_waddr_o = {wr_buf, c_word_q};
  assign sh_wdata_o = c_bit_q ? gathered : {{16{w_rdata_i[15]}}, w_rdata_i};

  // Local ports: a precycle writes in stage C, a postcycle reads in stage I.
  assign m_we_o    = c_pre && c_bit_q;
  assign m_addr_o  = post_o ? i_local[MaW-1:0] : c_local_q[MaW-1:0];
  assign m_wdata_o = sh_rdata_i[c_pos_q];
  assign w_we_o    = c_pre && !c_bit_q;
  assign w_addr_o  = post_o ? i_local[WaW-1:0] : c_local_q[WaW-1:0];
  assign w_wdata_o = sh_rdata_i[15:0];

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      issued_q   <= {(PaW+1){1'b0}};
      base_q     <= {PaW{1'b0}};
      len_q      <= {(PaW+1){1'b0}};
      post_o     <= 1'b0;
      f_valid_q  <= 1'b0;
      c_valid_q  <= 1'b0;
      c_bit_q    <= 1'b0;
      c_pos_q    <= 5'd0;
      c_word_q   <= {ShW{1'b0}};
      c_local_q  <= 12'd0;
      gather_q   <= 32'd0;
      writer_q   <= {IdW{1'b0}};
      sel_snap_q <= {Cores{1'b0}};
      dirty_q    <= {Cores{1'b0}};
    end else begin
      f_valid_q <= fetch;
      if (fetch) issued_q <= issued_q + 1'b1;
      if (i_desc) writer_q <= entry[16 +: IdW];
      c_valid_q <= i_item;
      if (i_item) begin
        c_bit_q   <= i_bit;
        c_pos_q   <= entry[29:25];
        c_word_q  <= i_word;
        c_local_q <= i_local;
      end
      if (c_post && c_bit_q) gather_q <= sh_we_o ? 32'd0 : gathered;
      if (run_i && !post_o) dirty_q <= dirty_q | overwrite;
      // a new list (the sequencer loads one only while nothing is copied)
      if (load_pre_i) begin
        base_q     <= {PaW{1'b0}};
        len_q      <= pre_len_i;
        issued_q   <= {(PaW+1){1'b0}};
        post_o     <= 1'b0;
        sel_snap_q <= sh_sel_i;
        dirty_q    <= {Cores{1'b0}};
      end else if (load_post_i) begin
        base_q   <= post_base_i;
        len_q    <= post_len_i;
        issued_q <= {(PaW+1){1'b0}};
        post_o   <= 1'b1;
      end
    end
  end

  // verilator lint_off UNUSEDSIGNAL
  wire unused_entry = ^entry;          // not every field is used by every entry kind
  // verilator lint_on UNUSEDSIGNAL

`ifdef FORMAL
  // Proved as part of the core sequencer (formal/core_seq.sby, k-induction): what the
  // engine guarantees, given how the sequencer drives it (also asserted here).
  reg f_past_valid = 1'b0;
  always @(posedge clk_i) f_past_valid <= 1'b1;

  wire f_busy = f_valid_q || c_valid_q;
  assign f_started_o  = (issued_q != {(PaW+1){1'b0}});
  assign f_local_rd_o = post_o && i_item;       // postcycle: local reads in stage I

  always @(*) if (rst_ni) begin
    // ---- the sequencer: a list is loaded only while nothing runs, one at a time
    if (load_pre_i || load_post_i) assert (!run_i && !f_busy && !(load_pre_i && load_post_i));
    // ---- the pipeline: empty unless running; never past the list's end
    if (!run_i) assert (!f_busy);
    assert (issued_q <= len_q);
    if (f_busy) assert (f_started_o);
    // a gathered postcycle word is pending only while stage C holds its next bit
    if (gather_q != 32'd0) assert (c_post && c_bit_q);
  end
  // ---- the sequencer runs a list until it is copied
  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni)
    if ($past(run_i) && !run_i) assert ($past(done_o));

  // ---- a list of n entries is done in its clock n + 2 at the latest (n fetch clocks,
  // then stage I and stage C drain), counted from its first running clock (0) by a
  // counter of the property's own; an empty list in its clock 0. (core_seq.v: the lock
  // is therefore held at most n + 3 clocks.)
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni)                        f_runs_o <= 0;
    else if (load_pre_i || load_post_i) f_runs_o <= 0;
    else if (run_i && !done_o)          f_runs_o <= f_runs_o + 1'b1;
  wire [PaW+2:0] f_len = {2'b00, len_q};
  assign f_len_o = len_q;
  always @(*) if (rst_ni && run_i) begin
    assert (f_runs_o <= f_len + 2);
    if (f_runs_o == f_len + 2 || (len_q == 0)) assert (done_o);
    // the pipeline's position: one fetch a clock, then the drain
    if (issued_q != len_q) f_inv_fetch: assert (f_runs_o == {2'b00, issued_q});
    if (issued_q == len_q && len_q != 0 && f_valid_q) f_inv_drain_i: assert (f_runs_o == f_len);
    if (issued_q == len_q && len_q != 0 && !f_valid_q) f_inv_drain_c: assert (f_runs_o > f_len);
    if (issued_q == len_q && len_q != 0 && !f_valid_q && c_valid_q)
      f_inv_drain_c2: assert (f_runs_o == f_len + 1);
  end
  // between lists: freshly loaded (nothing run yet), or done with the last one
  always @(*) if (rst_ni && !run_i)
    f_inv_idle: assert ((f_runs_o == 0 && issued_q == 0) ||
                        (issued_q == len_q && (len_q == 0 ? f_runs_o == 0 :
                                               (f_runs_o > f_len && f_runs_o <= f_len + 2))));
  always @(posedge clk_i) if (rst_ni)
    cover (!ping_i && sh_we_o && !sh_re_o && !m_we_o && gather_q != 32'd0);
`endif
endmodule
`default_nettype wire
