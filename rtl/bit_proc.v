`default_nettype none
`include "bit_isa.vh"
`include "param_check.vh"
// Bit processor: one bit instruction per clock, sustained.
//
// Four stages, each with its valid bit:
//   fetch   the program RAM is addressed with fetch_addr
//   decode  the word comes out of the RAM (d_instr); an M operand's address goes to
//           the marker RAM
//   operand the instruction register (o_*) selects the operand from the registered
//           images a clock early, from their next-state value (what the register
//           holds in the execute clock), with the execute stage's own write to Q/PQ
//           forwarded; the marker RAM's word is captured in m_hold_q (no logic
//           between the RAM and that register) and every marker write since the
//           read is tracked (o_mfwd_*)
//   execute the RLO, the parenthesis stack and the targets are updated, jumps are
//           taken. The RLO logic sees registers only, except the live pins (PI, and
//           I/IR/IF in the latch clock: a one-hot select registered in operand and
//           an AND-OR over the pins) and the FBI channel data (one bit per channel)
// A taken jump squashes the instructions in decode and operand (3 clocks). END is
// recognised in decode (one bit of the stored word, set as the program is written), so
// address 0 is fetched while END is in decode, reaches
// operand while END executes and moves to execute at the end of END's clock: the next
// scan's first instruction executes in its latch clock. END leaves RLO = 0 and an
// empty stack for it. A wait in execute holds decode through the program RAM's read
// enable, so no wait condition steers the fetch address. Between scans the pipeline holds (address 0 in operand,
// address 1 in decode) until the scan controller starts the next scan; it fills
// itself after reset and after a program write.
// An instruction that waits for the byte side's answer (a channel not ready, a
// dispatched byte instruction) and does not get it in its first execute clock moves
// into the wait slot (w_*), and the next instruction enters execute behind it,
// blocked until the clock after the answer: the clock it would have entered execute
// in. So the answer (DONE written over the bus, a channel's ready) reaches the slot
// and the RLO, never the pipeline's enables, which see registers only.
// An instruction held in execute (blocked behind the slot, a T/C read waiting for the
// update, END waiting for the byte side) sees the operand of the clock it completes
// in: the byte side's writes to its T/C status and updated bit are caught every clock
// while it waits, its marker bit is kept (nothing writes markers then), FBI data is
// read live.
module bit_proc #(
  parameter integer ProgWords   = 4096,  // program memory, instructions (power of two)
  parameter integer InBits      = 128,   // binary inputs (I, PI, IR, IF)
  parameter integer OutBits     = 128,   // binary outputs (Q, PQ)
  parameter integer MarkerBits  = 2048,  // marker bits (M)
  parameter integer StatusBits  = 64,    // timers and counters each (T, C)
  parameter integer Channels    = 4,     // exchange channels (FBI, FBY)
  parameter integer NestDepth   = 8,     // parenthesis levels
  parameter integer Cells       = 128,   // marker area cells per direction (FBI/FBY k)
  parameter integer BitEngine   = 0,     // 0: scalar (one IL instruction a clock); 1: wide
                                         // (LUT words, issue 18; docs/wide-rtl-plan.md)
  parameter integer LutWords    = ProgWords  // wide: extension words (LUT words at 0..LutWords-1)
) (
  input  wire                         clk_i,
  input  wire                         rst_ni,
  // program load port (the byte processor / test bench writes the image)
  input  wire                         prog_we_i,
  input  wire [$clog2(ProgWords)-1:0] prog_waddr_i,
  input  wire [31:0]                  prog_wdata_i,
  input  wire [`LUT_EXT_BITS-1:0]     prog_ext_wdata_i, // a LUT word's extension (wide; else unused)
  // scan control
  input  wire                         start_i,     // the next clock starts a scan
  input  wire                         latch_i,     // this clock starts a scan
  input  wire                         exec_i,      // instructions execute (scan clocks)
  output wire                         mem_ready_o, // marker memory cleared
  output wire                         end_o,       // END executes in this clock
  output wire                         refresh_o,   // REFRESH executes in this clock
  // operand sources
  // operand sources (the operand stage selects a clock before execute and works out
  // what the registers will hold then: a latch at this clock's edge, a write)
  input  wire [InBits-1:0]            pii_i,       // I: the input unit's image register
  input  wire [InBits-1:0]            pins_i,      // PI: the pins now
  input  wire [InBits-1:0]            rise_i,      // IR (register)
  input  wire [InBits-1:0]            fall_i,      // IF (register)
  input  wire [InBits-1:0]            rise_pend_i, // edges since the last latch, this
  input  wire [InBits-1:0]            fall_pend_i, // clock's included (what a latch takes)
  input  wire [OutBits-1:0]           pio_i,       // Q/PQ: the PIO register (its only writer
                                                   // is this processor: forwarded here)
  input  wire [OutBits-1:0]           out_pins_i,  // the output unit's pins (registers)
  input  wire [OutBits-1:0]           q_rise_i,    // QR / QF: what the last PIO update
  input  wire [OutBits-1:0]           q_fall_i,    // changed (registers)
  input  wire [StatusBits-1:0]        timer_status_i,    // the status buffer (registers)
  input  wire [StatusBits-1:0]        counter_status_i,
  input  wire [StatusBits-1:0]        timer_updated_i,   // written this scan (parallel)
  input  wire [StatusBits-1:0]        counter_updated_i,
  // the byte side's status write in this clock (tc_status.v takes it at the clock
  // edge; forwarded to the instructions in operand and execute)
  input  wire                         tc_we_i,
  input  wire                         tc_is_counter_i,
  input  wire [$clog2(StatusBits)-1:0] tc_idx_i,
  input  wire                         tc_val_i,
  // `= T n` / `= C n` (parallel and free-running mode, --tc-path status): the enable
  // of timer n / the input of counter n, into the status buffer (tc_status.v, Fig. 2)
  output wire                         tcw_we_o,
  output wire                         tcw_is_counter_o,
  output wire [$clog2(StatusBits)-1:0] tcw_idx_o,
  output wire                         tcw_val_o,
  // exchange channels: F_Bb k read by bit instructions, F_bB k written by `= FBY k`
  output wire [Channels-1:0]          fbi_rd_req_o,
  input  wire [Channels-1:0]          fbi_rd_data_i,
  input  wire [Channels-1:0]          fbi_rd_ready_i,
  output wire [Channels-1:0]          fby_wr_req_o,
  output wire                         fby_wr_data_o,
  input  wire [Channels-1:0]          fby_wr_ready_i,
  // the marker exchange (marker_i, a register): FBI k / FBY k are cell k of the marker
  // area (cond_exchange.v), never waiting. The cell of an FBI read is read while the
  // instruction is in operand and comes in its first execute clock; `= FBY k` writes
  // cell k in the clock it completes.
  input  wire                         marker_i,
  output wire                         cell_re_o,
  output wire [$clog2(Cells)-1:0]     cell_ridx_o,
  input  wire                         cell_rdata_i,
  output wire                         cell_we_o,
  output wire [$clog2(Cells)-1:0]     cell_widx_o,
  output wire                         cell_wdata_o,
  // serial dispatch of byte instructions (dispatch.v)
  output wire                         byte_req_o,     // a byte instruction waits in execute
  output wire [31:0]                  byte_instr_o,
  input  wire                         byte_done_i,    // ... and completes this clock
  input  wire                         byte_rlo_i,
  input  wire                         byte_rlo_we_i,
  output wire                         stall_o,        // execute waits for the byte side
  // parallel mode: END waits until the byte side has finished its part of the scan
  input  wire                         end_hold_i,
  // output unit write port (Q, PQ)
  output wire                         out_wr_en_o,
  output wire [$clog2(OutBits)-1:0]   out_wr_idx_o,
  output wire                         out_wr_val_o,
  output wire                         out_wr_direct_o,
  output wire                         out_update_o,   // PIO -> pins now (END, REFRESH Q)
  // marker copy port (plant cores: the copy engine, between scans, while the
  // processor idles; tie copy_en_i to 0 in a single CPU)
  input  wire                         copy_en_i,      // the copy engine owns the marker RAM
  input  wire                         copy_we_i,
  input  wire [$clog2(MarkerBits)-1:0] copy_addr_i,   // read and write address
  input  wire                         copy_wdata_i,
  output wire                         copy_rdata_o,   // M[copy_addr_i] of the last clock
  // marker peek: M[m_peek_addr_i] now, without a clock (simulation hosts only)
  input  wire [$clog2(MarkerBits)-1:0] m_peek_addr_i,
  output wire                         m_peek_o,
  // observation (waveforms, test benches)
  output reg                          rlo_o,
  output wire                         rlo_now_o,      // the RLO execute works with (= rlo_o)
  output wire [$clog2(ProgWords)-1:0] exec_pc_o,
  output wire                         exec_valid_o,
  // retirement (the block status, docs/toolchain.md): an instruction completed in the
  // last clock, where it was and the operand bit it read; rlo_o is now its RLO after
  output reg                          ret_valid_o,
  output reg  [$clog2(ProgWords)-1:0] ret_pc_o,
  output reg                          ret_opnd_o
);
  localparam integer PcW   = $clog2(ProgWords);
  localparam integer MW    = $clog2(MarkerBits);
  localparam integer SpW   = $clog2(NestDepth + 1);  // 0..NestDepth levels
  // a channel number: one bit at least, also for a single one
  // the one-hot index select: as wide as the widest bit-indexed image
  localparam integer SelW  = (InBits > OutBits) ?
      ((InBits > StatusBits) ? InBits : StatusBits) :
      ((OutBits > StatusBits) ? OutBits : StatusBits);
  localparam integer ChW   = (Channels > 1) ? $clog2(Channels) : 1;

  // ---------------------------------------------------------------- parameter checks
  // The instruction's index field is 12 bits (`ISA_INDEX`), a jump target 16 bits
  // (`ISA_TARGET`); an area needs at least one index bit. The fetch address wraps at
  // ProgWords only if it is a power of two.
  `PARAM_CHECK(g_bad_prog_words,
               ProgWords < 2 || ProgWords > 65536 || (ProgWords & (ProgWords - 1)) != 0,
               "bit_proc: ProgWords must be a power of two in 2..65536 (16-bit jump target)")
  `PARAM_CHECK(g_bad_in_bits, InBits < 2 || InBits > 4096,
               "bit_proc: InBits must be 2..4096 (12-bit operand index)")
  `PARAM_CHECK(g_bad_out_bits, OutBits < 2 || OutBits > 4096,
               "bit_proc: OutBits must be 2..4096 (12-bit operand index)")
  `PARAM_CHECK(g_bad_marker_bits, MarkerBits < 2 || MarkerBits > 4096,
               "bit_proc: MarkerBits must be 2..4096 (12-bit operand index)")
  `PARAM_CHECK(g_bad_status_bits, StatusBits < 2 || StatusBits > 4096,
               "bit_proc: StatusBits must be 2..4096 (12-bit operand index)")
  `PARAM_CHECK(g_bad_channels, Channels < 1 || Channels > 4096,
               "bit_proc: Channels must be 1..4096 (12-bit operand index)")
  `PARAM_CHECK(g_bad_nest_depth, NestDepth < 1, "bit_proc: NestDepth must be at least 1")
  `PARAM_CHECK(g_bad_cells, Cells < 2 || Cells > 4096,
               "bit_proc: Cells must be 2..4096 (12-bit operand index)")
  `PARAM_CHECK(g_bad_bit_engine, BitEngine != 0 && BitEngine != 1,
               "bit_proc: BitEngine must be 0 (scalar) or 1 (wide)")
  // A LUT word's operand and destination index is 11 bits (`LUT_OPND_INDEX`); its
  // extension RAM is addressed with the low bits of the program address.
  `PARAM_CHECK(g_bad_lut_words, BitEngine == 1 && (LutWords < 2 || LutWords > ProgWords ||
                                                   (LutWords & (LutWords - 1)) != 0),
               "bit_proc: LutWords must be a power of two in 2..ProgWords")
  `PARAM_CHECK(g_bad_wide_sizes, BitEngine == 1 && (InBits > 2048 || OutBits > 2048 ||
                                                    MarkerBits > 2048 || StatusBits > 2048),
               "bit_proc: the wide engine's operands index at most 2048 bits an area")

  // ---------------------------------------------------------------- fetch / decode
  reg  [PcW-1:0] d_pc_q;        // address of the word now leaving the program RAM
  reg            d_valid_q;     // ... which is that word (not after reset / a load)
  wire [31:0]    d_instr;       // that word (decode stage)
  reg  [PcW-1:0] fetch_addr;
  wire           d_move;        // decode takes the next word (pipeline flow, below)

  // verilator lint_off UNUSEDSIGNAL
  wire [31:0]    unused_prog_peek;  // no host looks at the program
  // verilator lint_on UNUSEDSIGNAL
  // END is marked as the word is written: bit 23 (reserved in a bit instruction, 0 in
  // the image) is stored as "this is END", so that decode sees END in one bit and
  // the fetch address of the next scan's first instruction does not wait for an
  // opcode compare behind the RAM's clock-to-out. Byte instructions keep bit 23.
  wire        prog_byte  = prog_wdata_i[24 + `OP_BYTE_BIT];
  wire        prog_end   = prog_wdata_i[`ISA_OPCODE] == `OP_END;
  wire [31:0] prog_word  = {prog_wdata_i[31:24], prog_byte ? prog_wdata_i[23] : prog_end,
                            prog_wdata_i[22:0]};
`ifdef FORMAL
  (* anyconst *) reg [PcW-1:0] f_pa;  // the proof looks at the program word at f_pa
`endif
  sync_ram #(.Words(ProgWords), .Width(32)) u_prog_ram (
    .clk_i  (clk_i),
    .we_i   (prog_we_i),
    .waddr_i(prog_waddr_i),
    .wdata_i(prog_word),
    .re_i   (d_move),     // decode holds: the RAM keeps its word (no address mux)
    .raddr_i(fetch_addr),
    .rdata_o(d_instr),
`ifdef FORMAL
    .peek_addr_i(f_pa),
`else
    .peek_addr_i({PcW{1'b0}}),
`endif
    .peek_data_o(unused_prog_peek)
  );
  wire d_is_end = d_valid_q && d_instr[23] && !d_instr[24 + `OP_BYTE_BIT];

  // ---------------------------------------------------------------- LUT words (wide)
  // The wide engine (BitEngine 1; docs/wide-rtl-plan.md): an address holds the base
  // word above and an extension word in a RAM of its own, written with it and read
  // with the same address and enable, so that both leave their RAMs in the same clock
  // and fetch, jumps and END stay the scalar engine's. A LUT word's base word (tag 01:
  // opcodes 0x40..0x7F, which the scalar decode below knows nothing of, bit 23 0, area
  // field 0) passes the scalar decode as a NOP; in execute, lut_unit.v (g_lut, at the
  // end) reads its operands and evaluates its tables, and its one bit write goes
  // through the scalar write ports below (M, Q, RLO). It never waits: a unit's words
  // run one a clock. The scalar build has neither and leaves the port unused.
  wire [`LUT_EXT_BITS-1:0] d_ext;       // the extension word of d_instr
  generate if (BitEngine == 1) begin : g_ext
    localparam integer LwW = $clog2(LutWords);
    // verilator lint_off UNUSEDSIGNAL
    wire [`LUT_EXT_BITS-1:0] unused_ext_peek;   // no host looks at it
    // verilator lint_on UNUSEDSIGNAL
    sync_ram #(.Words(LutWords), .Width(`LUT_EXT_BITS)) u_ext_ram (
      .clk_i      (clk_i),
      .we_i       (prog_we_i && (prog_waddr_i >> LwW) == 0),  // no LUT word above
      .waddr_i    (prog_waddr_i[LwW-1:0]),
      .wdata_i    (prog_ext_wdata_i),
      .re_i       (d_move),
      .raddr_i    (fetch_addr[LwW-1:0]),   // a scalar word above: its word is not used
      .rdata_o    (d_ext),
      .peek_addr_i({LwW{1'b0}}),
      .peek_data_o(unused_ext_peek)
    );
  end else begin : g_scalar
    assign d_ext = {`LUT_EXT_BITS{1'b0}};
    // verilator lint_off UNUSEDSIGNAL
    wire unused_ext_port = ^prog_ext_wdata_i;
    // verilator lint_on UNUSEDSIGNAL
  end endgenerate
  wire e_lut;                           // a LUT word is in execute (0: scalar build)
  wire lut_res_a;                       // its table A's result (port A's write)

  // ---------------------------------------------------------------- operand stage
  reg  [31:0]    o_instr_q;
  reg  [PcW-1:0] o_pc_q;
  reg            o_valid_q;
  reg            o_first_q;     // the instruction entered operand at the last edge
  wire [7:0]  o_op    = o_instr_q[`ISA_OPCODE];
  wire [3:0]  o_area  = o_instr_q[`ISA_AREA];
  wire [11:0] o_index = o_instr_q[`ISA_INDEX];
  wire [$clog2(OutBits)-1:0]    o_out = o_index[$clog2(OutBits)-1:0];
  wire [MW-1:0]                 o_mi  = o_index[MW-1:0];
  wire [$clog2(StatusBits)-1:0] o_tc  = o_index[$clog2(StatusBits)-1:0];
  wire o_logic = (o_op & `OP_LOGIC_MASK) == `OP_LOGIC;
  wire o_on_io = (o_area == `AREA_I) || (o_area == `AREA_IR) || (o_area == `AREA_IF);
  // Decoded from the word leaving the program RAM as it moves to operand: the index
  // one-hot (an index past an image's size selects nothing: the assembler rejects it)
  // and the area one-hot, so that operand selects with AND-OR trees of few levels.
  reg  [SelW-1:0] o_sel_q;
  reg  [7:0]      o_asel_q;      // I, IR, IF, Q/PQ, T, C, QR, QF
  wire [11:0]     d_index = d_instr[`ISA_INDEX];
  wire [3:0]      d_area  = d_instr[`ISA_AREA];
  wire [SelW-1:0] d_sel   = ((d_index >> $clog2(SelW)) == 12'd0)
      ? ({{(SelW-1){1'b0}}, 1'b1} << d_index[$clog2(SelW)-1:0]) : {SelW{1'b0}};
  wire [7:0]      d_asel  = {d_area == `AREA_QF, d_area == `AREA_QR,
                             d_area == `AREA_C, d_area == `AREA_T,
                             (d_area == `AREA_Q) || (d_area == `AREA_PQ),
                             d_area == `AREA_IF, d_area == `AREA_IR, d_area == `AREA_I};
  wire [InBits-1:0]     o_sel_in = o_sel_q[InBits-1:0];
  wire [OutBits-1:0]    o_sel_out = o_sel_q[OutBits-1:0];
  wire [StatusBits-1:0] o_sel_tc = o_sel_q[StatusBits-1:0];

  // ---------------------------------------------------------------- execute stage
  reg  [31:0]    e_instr_q;
  reg  [PcW-1:0] e_pc_q;
  reg            e_valid_q;
  // decoded in operand
  reg e_logic_q, e_open_q, e_close_q, e_fp_q, e_fn_q, e_not_q, e_set_q, e_clr_q;
  reg e_assign_q, e_setbit_q, e_rstbit_q, e_edge_q, e_byte_q, e_end_q, e_refresh_q;
  reg e_refresh_q_q;                    // REFRESH Q
  reg e_ju_q, e_jc_q, e_jcn_q;
  reg e_on_m_q, e_on_q_q, e_on_pq_q, e_on_fb_q, e_on_tc_q, e_tcw_q;
  reg [Channels-1:0] e_chan_q;          // the channel, one-hot (none if out of range)
  // operand sources
  reg              e_opnd_q;            // the registered images' bit, as of execute
  reg              e_src_m_q, e_src_live_q, e_src_fb_q;
  reg [InBits-1:0] e_pinsel_q;          // live pins: the pin, one-hot (0: not live)
  reg              e_live1_q, e_live0_q;  // the operand if that pin is 1 / 0
  reg              e_mfwd_q, e_mfwd_val_q;  // a marker write the RAM read missed
  reg              m_hold_q;            // the marker RAM's word for this instruction
  reg              e_upd_q;             // T/C updated this scan, as of execute

  wire [PcW-1:0] e_target = e_instr_q[PcW-1:0];
  wire [2:0]     e_fn3    = e_instr_q[26:24];   // opcode bits 2:0: {f, n}
  wire           e_go     = e_valid_q && exec_i;

  // ---------------------------------------------------------------- waiting
  // Nothing of an instruction takes effect until the clock it completes. A channel
  // empty/full (the buffered condition flip-flops' handshake, the queues) or a
  // dispatched byte instruction not done in the first clock: the instruction moves
  // into the wait slot at the clock's end and waits there (below). A read of `T n` / `C n` marked "after the update" (bit 16, set by the partitioning
  // compiler when a byte-side instruction on that timer/counter precedes it in the
  // scan) waits until the byte side has written the status this scan (the updated
  // bits are cleared at the end of the latch clock: a read executing in that clock
  // does not see the previous scan's bits).
  // The slot holds a byte instruction (w_bwait_q) or a channel access (w_fwait_q):
  // two flip-flops, so that NEXT (byte_req_o) comes from one register in the slot.
  reg                w_bwait_q, w_fwait_q;
  reg                w_fbr_q;      // the channel access is an FBI read (else FBY write)
  reg [31:0]         w_instr_q;
  reg [PcW-1:0]      w_pc_q;
  reg [Channels-1:0] w_chan_q;
  reg                w_data_q;     // the FBY write's condition

  wire w_busy     = w_bwait_q || w_fwait_q;
  // exec_i falls (FAULT): the waiting instruction ends at once, as one held in execute
  wire w_bact     = w_bwait_q && exec_i;
  wire w_fact     = w_fwait_q && exec_i;
  wire e_act      = e_go && !w_busy;     // not blocked behind the wait slot
  wire e_blocked  = e_go && w_busy;
  // (with the marker exchange an FB access is a cell's, never a channel's: no wait)
  wire fbi_read   = e_act && e_on_fb_q && e_logic_q && !marker_i;
  wire fby_cell   = e_act && e_on_fb_q && (e_assign_q || ((e_setbit_q || e_rstbit_q) && rlo_o));
  wire fby_write  = fby_cell && !marker_i;
  wire e_fby_data = !e_rstbit_q && rlo_o;               // =: RLO; S: 1; R: 0
  wire chan_wait  = (fbi_read  && !(|(fbi_rd_ready_i & e_chan_q))) ||
                    (fby_write && !(|(fby_wr_ready_i & e_chan_q)));
  wire byte_first = e_act && e_byte_q;                  // its first clock in execute
  wire to_slot    = chan_wait || (byte_first && !byte_done_i);
  wire end_wait   = e_act && e_end_q && end_hold_i;
  wire tc_wait    = e_act && e_tcw_q && !e_upd_q;
  // execute keeps its instruction (registers only: no answer of the byte side)
  wire e_hold     = end_wait || tc_wait || e_blocked;
  wire e_wait     = to_slot || end_wait || tc_wait;   // the acting instruction waits
  wire e_done     = e_act && !e_wait;                  // ... or takes effect

  // The wait slot: loaded from execute (whenever it is free, so that only w_busy_q
  // depends on the wait), done in the clock the answer comes.
  wire w_fbr_ready = |(fbi_rd_ready_i & w_chan_q);
  wire w_fbw_ready = |(fby_wr_ready_i & w_chan_q);
  wire w_done      = w_bwait_q ? byte_done_i
                             : w_fwait_q && (w_fbr_q ? w_fbr_ready : w_fbw_ready);
  wire w_end       = w_done || !exec_i;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      w_bwait_q <= 1'b0;
      w_fwait_q <= 1'b0;
      w_fbr_q   <= 1'b0;
      w_instr_q <= 32'd0;
      w_pc_q    <= {PcW{1'b0}};
      w_chan_q  <= {Channels{1'b0}};
      w_data_q  <= 1'b0;
    end else if (w_busy) begin
      if (w_end) {w_bwait_q, w_fwait_q} <= 2'b00;
    end else begin
      w_bwait_q <= byte_first && !byte_done_i;
      w_fwait_q <= chan_wait;
      w_fbr_q   <= e_logic_q;
      w_instr_q <= e_instr_q;
      w_pc_q    <= e_pc_q;
      w_chan_q  <= e_chan_q;
      w_data_q  <= e_fby_data;
    end
  end

  // A stall is a wait on the other processor's condition; a dispatched instruction's
  // own clocks (serial mode) are its execution time, not a stall.
  assign stall_o  = chan_wait || (w_fact && !w_done) || end_wait || tc_wait;

  assign fbi_rd_req_o  = (fbi_read  ? e_chan_q : {Channels{1'b0}}) |
                         ((w_fact && w_fbr_q) ? w_chan_q : {Channels{1'b0}});
  assign fby_wr_req_o  = (fby_write ? e_chan_q : {Channels{1'b0}}) |
                         ((w_fact && !w_fbr_q) ? w_chan_q : {Channels{1'b0}});
  assign fby_wr_data_o = w_fwait_q ? w_data_q : e_fby_data;
  assign byte_req_o    = byte_first || w_bact;
  assign byte_instr_o  = w_bwait_q ? w_instr_q : e_instr_q;

  wire jump_taken = e_act && (e_ju_q || (e_jc_q && rlo_o) || (e_jcn_q && !rlo_o));
  assign end_o     = e_act && e_end_q && !end_hold_i;
  assign refresh_o = e_act && e_refresh_q;
  assign out_update_o = end_o || (e_act && e_refresh_q_q);
  assign rlo_now_o = rlo_o;     // END leaves 0 for the next scan's first instruction

  // ---------------------------------------------------------------- marker memory
  // Cleared after reset (one bit per clock) so that every marker starts at 0.
  reg  [MW:0]   clear_addr_q;           // MarkerBits when done
  wire          clearing = !clear_addr_q[MW];
  assign mem_ready_o = !clearing;

  wire          m_rdata;
  wire          m_target_we;            // execute writes an M bit
  // Between scans the copy engine takes the RAM's ports (nothing executes then).
  wire          copy_we = copy_en_i && copy_we_i;
  wire          m_we    = clearing || m_target_we || copy_we;
  wire [MW-1:0] m_waddr = clearing ? clear_addr_q[MW-1:0] :
                          copy_en_i ? copy_addr_i : e_instr_q[MW-1:0];
  wire          target_val;
  wire          wr_val;                 // the target's value (a LUT word's: table A)
  wire          m_wdata = clearing ? 1'b0 : copy_en_i ? copy_wdata_i : wr_val;
  wire [MW-1:0] m_raddr = copy_en_i ? copy_addr_i : d_instr[MW-1:0];
  assign copy_rdata_o = m_rdata;

  sync_ram #(.Words(MarkerBits), .Width(1)) u_marker_ram (
    .clk_i  (clk_i),
    .we_i   (m_we),
    .waddr_i(m_waddr),
    .wdata_i(m_wdata),
    .re_i   (1'b1),
    .raddr_i(m_raddr),
    .rdata_o(m_rdata),
    .peek_addr_i(m_peek_addr_i),
    .peek_data_o(m_peek_o)
  );

  // The RAM read for the instruction in operand happened at the edge it entered
  // operand; the write at that same edge is kept in lw_* (the RAM may return either
  // value then), every later write to its address until it executes is caught here.
  reg           lw_we_q, lw_val_q;
  reg  [MW-1:0] lw_addr_q;
  reg           o_mfwd_q, o_mfwd_val_q;
  wire          m_hit_now  = m_we && (m_waddr == o_mi);
  wire          m_hit_base = o_first_q ? (lw_we_q && (lw_addr_q == o_mi)) : o_mfwd_q;
  wire          m_val_base = o_first_q ? lw_val_q : o_mfwd_val_q;
  wire          m_fwd_next = m_hit_now || m_hit_base;
  wire          m_fwd_val  = m_hit_now ? m_wdata : m_val_base;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      clear_addr_q <= {(MW+1){1'b0}};
      lw_we_q      <= 1'b0;
      lw_val_q     <= 1'b0;
      lw_addr_q    <= {MW{1'b0}};
      o_mfwd_q     <= 1'b0;
      o_mfwd_val_q <= 1'b0;
      m_hold_q     <= 1'b0;
    end else begin
      if (clearing) clear_addr_q <= clear_addr_q + 1'b1;
      lw_we_q      <= m_we;
      lw_val_q     <= m_wdata;
      lw_addr_q    <= m_waddr;
      o_mfwd_q     <= m_fwd_next;
      o_mfwd_val_q <= m_fwd_val;
      if (o_first_q) m_hold_q <= m_rdata;   // straight from the RAM, no logic between
    end
  end

  // ---------------------------------------------------------------- targets
  // =, S, R write a target; FP/FN write their edge memory with the old RLO. None of
  // them waits (a write to FBY goes through the channel, fby_write above).
  wire target_we = e_act && (e_assign_q || e_edge_q || ((e_setbit_q || e_rstbit_q) && rlo_o));
  assign target_val  = e_setbit_q ? 1'b1 : e_rstbit_q ? 1'b0 : rlo_o;
  // a LUT word's port A writes its destination (M, Q, the RLO, a scratch bit) with
  // table A; its index sits where a scalar instruction's does
  wire       lut_done   = e_done && e_lut;
  wire [3:0] lut_dst    = e_instr_q[`LUT_DST_AREA];
  wire       lut_wr_m   = lut_done && (lut_dst == `AREA_M);
  wire       lut_wr_q   = lut_done && (lut_dst == `AREA_Q);
  wire       lut_wr_rlo = lut_done && (lut_dst == `LAREA_RLO);
  assign wr_val      = e_lut ? lut_res_a : target_val;
  assign m_target_we = (target_we && e_on_m_q) || lut_wr_m;

  assign out_wr_en_o     = (target_we && e_on_q_q) || lut_wr_q;
  assign out_wr_idx_o    = e_instr_q[$clog2(OutBits)-1:0];
  assign out_wr_val_o    = wr_val;
  assign out_wr_direct_o = e_on_pq_q;

  // ---------------------------------------------------------------- operand select
  // From the registered images, as they will be in the clock the instruction executes
  // in: I/IR/IF come in as next-state values; the PIO and the T/C status buffer are
  // the registers with this clock's write forwarded (this processor's `= Q`, the byte
  // side's status write).
  wire q_fwd = out_wr_en_o && (out_wr_idx_o == o_out);
  wire o_is_c = o_area == `AREA_C;
  wire tc_fwd = tc_we_i && (tc_idx_i == o_tc) && (tc_is_counter_i == o_is_c);
  // The input unit latches at this clock's edge (scan start or REFRESH): the image
  // takes the pins and the pending edges. A REFRESH executing now (refresh_o) is the
  // latest signal here (it waits for exec_i and the wait slot): the I/IR/IF operand is
  // selected for all three cases from registers and pins — no latch, one latch, two
  // (a REFRESH in the latch clock: no edge since the scan start's, IR/IF 0) — and
  // refresh_o picks one last, after the wide selects.
  wire latching  = latch_i || refresh_o;
  wire o_pin_bit = |(pins_i & o_sel_in);
  wire o_rp_bit  = |(rise_pend_i & o_sel_in);   // what one latch takes
  wire o_fp_bit  = |(fall_pend_i & o_sel_in);
  wire o_q_bit  = q_fwd ? out_wr_val_o : |(pio_i & o_sel_out);
  wire o_t_bit  = tc_fwd ? tc_val_i : |(timer_status_i & o_sel_tc);
  wire o_c_bit  = tc_fwd ? tc_val_i : |(counter_status_i & o_sel_tc);
  // QR/QF: the output unit's flags, or, when it updates at this clock's edge (END,
  // REFRESH Q: no PIO write in that clock), the change the update makes. Both are
  // worked out from registers; out_update_o (late: it waits for exec_i, the wait slot
  // and, for END, the byte side) picks one last, after the wide selects.
  wire o_qpio_bit = |(pio_i & o_sel_out);
  wire o_qpin_bit = |(out_pins_i & o_sel_out);
  wire o_qe_keep  = |(o_asel_q[7:6] & {|(q_fall_i & o_sel_out), |(q_rise_i & o_sel_out)});
  wire o_qe_upd   = |(o_asel_q[7:6] & {!o_qpio_bit && o_qpin_bit, o_qpio_bit && !o_qpin_bit});
  wire o_tcq    = |(o_asel_q[5:3] & {o_c_bit, o_t_bit, o_q_bit}) ||
                  (out_update_o ? o_qe_upd : o_qe_keep);
  wire o_in_keep = |(o_asel_q[2:0] & {|(fall_i & o_sel_in), |(rise_i & o_sel_in),
                                      |(pii_i & o_sel_in)});
  wire o_in_one  = |(o_asel_q[2:0] & {o_fp_bit, o_rp_bit, o_pin_bit});
  wire o_in_two  = o_asel_q[0] && o_pin_bit;
  wire o_in_bit  = refresh_o ? (latch_i ? o_in_two : o_in_one)
                             : (latch_i ? o_in_one : o_in_keep);
  wire o_opnd   = o_tcq || o_in_bit;
  // updated in the execute clock: the bits are cleared at the end of the latch clock,
  // a write sets one; an instruction executing in the latch clock sees none (start_i)
  wire o_upd = (!latch_i && |((o_is_c ? counter_updated_i : timer_updated_i) & o_sel_tc)) ||
               tc_fwd;
  // the same for the instruction held in execute: the byte side's writes to its T/C
  wire [$clog2(StatusBits)-1:0] e_tc = e_instr_q[$clog2(StatusBits)-1:0];
  wire e_is_c = e_instr_q[`ISA_AREA] == `AREA_C;
  wire e_tc_fwd = e_on_tc_q && tc_we_i && (tc_idx_i == e_tc) && (tc_is_counter_i == e_is_c);
  // `= T n` / `= C n`: the status buffer's enable / pulse bit, in the clock it executes
  assign tcw_we_o         = target_we && e_assign_q && e_on_tc_q;
  assign tcw_is_counter_o = e_is_c;
  assign tcw_idx_o        = e_tc;
  assign tcw_val_o        = target_val;

  wire [ChW-1:0] o_ch = o_index[ChW-1:0];
  // (the index fits when its bits above a channel number are 0: no wide compare; a
  // number past the last channel shifts the one out of the vector)
  // the marker exchange: the cell of an FBI read in operand (read every clock it is
  // there: the last read before it moves on is the one that comes in its first
  // execute clock; the reader's snapshot is taken in the start clock, the read of that
  // clock included)
  localparam integer CW = $clog2(Cells);
  // (not gated by marker_i: a read has no effect, and the setting may arrive with the
  // scan's start)
  assign cell_re_o   = o_valid_q && (o_area == `AREA_FB);
  assign cell_ridx_o = o_index[CW-1:0];
  assign cell_we_o    = fby_cell && marker_i;
  assign cell_widx_o  = e_instr_q[CW-1:0];
  assign cell_wdata_o = e_fby_data;
  wire [Channels-1:0] o_chan = (o_index[11:ChW] == 0)
      ? ({{(Channels-1){1'b0}}, 1'b1} << o_ch) : {Channels{1'b0}};

  // Live operands (PI; the first instruction of a scan reads I/IR/IF as they are being
  // latched): the operand for the pin at 1 / 0 in execute. IR then: the edge
  // accumulator after this clock (a latch now clears it) or the pin rising from this
  // clock's value; IF: falling.
  // (not a byte instruction: its operand field is no bit operand, and a compare's
  // zero field reads as I 0 in the latch clock — the live path would drop its RLO)
  wire o_live  = !o_op[`OP_BYTE_BIT] && ((o_area == `AREA_PI) || (start_i && o_on_io));
  // The accumulator after this clock is empty if the unit latches now: both cases are
  // worked out from registers and pins, and `latching` (late, refresh_o) picks last.
  wire o_lacc  = (o_area == `AREA_IR) ? o_rp_bit : o_fp_bit;   // no latch now
  wire o_ir_l  = start_i && (o_area == `AREA_IR);
  wire o_if_l  = start_i && (o_area == `AREA_IF);
  wire o_live1_n = o_ir_l ? (o_lacc | !o_pin_bit) : o_if_l ? o_lacc : 1'b1;
  wire o_live0_n = o_ir_l ? o_lacc : o_if_l ? (o_lacc | o_pin_bit) : 1'b0;
  wire o_live1_l = o_ir_l ? !o_pin_bit : !o_if_l;              // a latch now
  wire o_live0_l = !o_ir_l && o_if_l && o_pin_bit;
  wire o_live1 = latching ? o_live1_l : o_live1_n;
  wire o_live0 = latching ? o_live0_l : o_live0_n;

  // ---------------------------------------------------------------- operand in execute
  // The live pin enters last: the RLO is worked out for the pin at 1 and at 0 from
  // registers, and the pin (an AND-OR over the pins, 0 unless the operand is live)
  // picks one. PI: the pin; I in the latch clock: the pin being latched; IR/IF then:
  // the pending edge or the edge between the last clock's pin and this one.
  wire pin_live  = |(pins_i & e_pinsel_q);
  wire m_opnd    = e_mfwd_q ? e_mfwd_val_q : m_hold_q;
  // a cell: as read for the first execute clock, kept for the clocks it is held there
  reg  e_first_q, cell_hold_q;
  wire cell_bit  = e_first_q ? cell_rdata_i : cell_hold_q;
  wire fb_opnd   = marker_i ? cell_bit : |(fbi_rd_data_i & e_chan_q);
  wire operand   = e_src_m_q ? m_opnd : e_src_fb_q ? fb_opnd : e_opnd_q;

  // ---------------------------------------------------------------- RLO and stack
  // RLO := RLO f (x xor n), the one combiner shared by the eight loads/combines and
  // by ")" (which combines the saved RLO with the parenthesis' result).
  function automatic combine(input [1:0] f, input acc, input x);
    case (f)
      `FN_LOAD: combine = x;
      `FN_AND:  combine = acc & x;
      `FN_OR:   combine = acc | x;
      default:  combine = acc ^ x;
    endcase
  endfunction

  // A shift register: the top level is always entry 0 (no multiplexer on the RLO path).
  reg [NestDepth-1:0]   stack_rlo_q;      // saved RLO per level, top first
  reg [NestDepth*3-1:0] stack_op_q;       // saved {f, n} per level
  reg [SpW-1:0]         sp_q;             // levels in use
  wire       top_rlo = stack_rlo_q[0];
  wire [2:0] top_op  = stack_op_q[2:0];

  // the new RLO for the operand at 1 (rlo_x1) and at 0 (rlo_x0), from registers
  reg rlo_x1, rlo_x0;
  always @(*) begin
    rlo_x1 = rlo_o;
    rlo_x0 = rlo_o;
    if (e_logic_q) begin
      rlo_x1 = combine(e_fn3[2:1], rlo_o, ~e_fn3[0]);
      rlo_x0 = combine(e_fn3[2:1], rlo_o, e_fn3[0]);
    end else if (e_close_q) begin
      rlo_x1 = combine(top_op[2:1], top_rlo, rlo_o ^ top_op[0]);
      rlo_x0 = rlo_x1;
    end else if (e_fp_q) begin
      rlo_x1 = 1'b0;
      rlo_x0 = rlo_o;
    end else if (e_fn_q) begin
      rlo_x1 = ~rlo_o;
      rlo_x0 = 1'b0;
    end else if (e_not_q) begin
      rlo_x1 = ~rlo_o;
      rlo_x0 = ~rlo_o;
    end else if (e_set_q) begin
      rlo_x1 = 1'b1;
      rlo_x0 = 1'b1;
    end else if (e_clr_q || e_end_q) begin  // END: every scan starts with RLO = 0
      rlo_x1 = 1'b0;
      rlo_x0 = 1'b0;
    end
  end
  // a dispatched compare's RLO comes with DONE
  wire rlo_reg  = (e_byte_q && byte_rlo_we_i) ? byte_rlo_i : (operand ? rlo_x1 : rlo_x0);
  wire rlo_pin1 = e_live1_q ? rlo_x1 : rlo_x0;
  wire rlo_pin0 = e_src_live_q ? (e_live0_q ? rlo_x1 : rlo_x0) : rlo_reg;
  wire rlo_d    = pin_live ? rlo_pin1 : rlo_pin0;

  // the wait slot's instruction completes: a compare's RLO with DONE, an FBI read's
  // combine with the channel's bit
  wire w_fb_bit = |(fbi_rd_data_i & w_chan_q);
  wire w_rlo    = w_bwait_q ? byte_rlo_i
                            : combine(w_instr_q[26:25], rlo_o, w_fb_bit ^ w_instr_q[24]);
  wire w_rlo_we = w_done && exec_i && (w_bwait_q ? byte_rlo_we_i : w_fbr_q);

  integer lvl;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rlo_o       <= 1'b0;
      sp_q        <= {SpW{1'b0}};
      stack_rlo_q <= {NestDepth{1'b0}};
      stack_op_q  <= {(NestDepth*3){1'b0}};
    end else if (w_busy) begin
      if (w_rlo_we) rlo_o <= w_rlo;
    end else if (e_done) begin
      rlo_o <= lut_wr_rlo ? lut_res_a : rlo_d;
      // The assembler bounds the nesting; the stack saturates rather than wraps.
      if (e_end_q) begin
        sp_q <= {SpW{1'b0}};              // ... and with an empty stack
      end else if (e_open_q && sp_q != NestDepth[SpW-1:0]) begin
        for (lvl = NestDepth - 1; lvl > 0; lvl = lvl - 1) begin
          stack_rlo_q[lvl]       <= stack_rlo_q[lvl-1];
          stack_op_q[lvl*3 +: 3] <= stack_op_q[(lvl-1)*3 +: 3];
        end
        stack_rlo_q[0]  <= rlo_o;
        stack_op_q[2:0] <= e_fn3;
        sp_q            <= sp_q + 1'b1;
      end else if (e_close_q && sp_q != {SpW{1'b0}}) begin
        for (lvl = 0; lvl < NestDepth - 1; lvl = lvl + 1) begin
          stack_rlo_q[lvl]       <= stack_rlo_q[lvl+1];
          stack_op_q[lvl*3 +: 3] <= stack_op_q[(lvl+1)*3 +: 3];
        end
        sp_q <= sp_q - 1'b1;
      end
    end
  end

  // ---------------------------------------------------------------- pipeline flow
  // Execute takes the next instruction when its own completes (or a scan starts);
  // operand and decode move up when the stage above takes theirs or is empty.
  // Taken jump: squash operand and decode, fetch the target. END in decode: fetch
  // address 0. END in execute: address 0 (in operand) moves on only if a scan follows.
  wire e_load = start_i || (exec_i && !e_hold && !end_o);
  // the marker cell of the instruction in execute, kept after its first clock there
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      e_first_q   <= 1'b0;
      cell_hold_q <= 1'b0;
    end else begin
      e_first_q <= e_load;
      if (e_first_q) cell_hold_q <= cell_rdata_i;
    end
  wire o_move = e_load || !o_valid_q;
  assign d_move = o_move || !d_valid_q;
  // The waits reach the program RAM's read enable and d_pc_q's enable only, not the
  // read address. The address is a jump's target or the next word, worked out from
  // registers; END leaving the RAM forces it to 0 through one AND per bit, the only
  // logic between the RAM's output and its address.
  wire [PcW-1:0] seq_addr  = jump_taken ? e_target : !d_valid_q ? d_pc_q : d_pc_q + 1'b1;
  wire           end_fetch = d_is_end && !jump_taken;   // END in decode: address 0
  always @(*) fetch_addr = seq_addr & {PcW{!end_fetch}};

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      d_pc_q    <= {PcW{1'b0}};
      d_valid_q <= 1'b0;
      o_instr_q <= 32'd0;
      o_sel_q   <= {SelW{1'b0}};
      o_asel_q  <= 8'd0;
      o_pc_q    <= {PcW{1'b0}};
      o_valid_q <= 1'b0;
      o_first_q <= 1'b0;
    end else if (prog_we_i) begin       // a program write: refill from address 0
      d_pc_q    <= {PcW{1'b0}};
      d_valid_q <= 1'b0;
      o_valid_q <= 1'b0;
      o_first_q <= 1'b0;
    end else begin
      if (d_move) d_pc_q <= fetch_addr;
      d_valid_q <= 1'b1;
      o_first_q <= o_move;
      if (o_move) begin
        o_instr_q <= d_instr;
        o_sel_q   <= d_sel;
        o_asel_q  <= d_asel;
        o_pc_q    <= d_pc_q;
        o_valid_q <= d_valid_q && !jump_taken;
      end
    end
  end

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      e_instr_q <= 32'd0;
      e_pc_q    <= {PcW{1'b0}};
      e_valid_q <= 1'b0;
      {e_logic_q, e_open_q, e_close_q, e_fp_q, e_fn_q, e_not_q, e_set_q, e_clr_q} <= 8'd0;
      {e_assign_q, e_setbit_q, e_rstbit_q, e_edge_q, e_byte_q, e_end_q, e_refresh_q} <= 7'd0;
      e_refresh_q_q <= 1'b0;
      {e_ju_q, e_jc_q, e_jcn_q} <= 3'd0;
      {e_on_m_q, e_on_q_q, e_on_pq_q, e_on_fb_q, e_on_tc_q, e_tcw_q} <= 6'd0;
      e_chan_q     <= {Channels{1'b0}};
      e_opnd_q     <= 1'b0;
      {e_src_m_q, e_src_live_q, e_src_fb_q} <= 3'd0;
      e_pinsel_q   <= {InBits{1'b0}};
      {e_live1_q, e_live0_q} <= 2'd0;
      e_mfwd_q     <= 1'b0;
      e_mfwd_val_q <= 1'b0;
      e_upd_q      <= 1'b0;
    end else begin
      if (e_load) begin
        e_instr_q   <= o_instr_q;
        e_pc_q      <= o_pc_q;
        e_valid_q   <= o_valid_q && !jump_taken;
        e_logic_q   <= o_logic;
        e_open_q    <= (o_op & `OP_LOGIC_MASK) == `OP_OPEN;
        e_close_q   <= o_op == `OP_CLOSE;
        e_fp_q      <= o_op == `OP_FP;
        e_fn_q      <= o_op == `OP_FN;
        e_not_q     <= o_op == `OP_NOT;
        e_set_q     <= o_op == `OP_SET;
        e_clr_q     <= o_op == `OP_CLR;
        e_assign_q  <= o_op == `OP_ASSIGN;
        e_setbit_q  <= o_op == `OP_SETBIT;
        e_rstbit_q  <= o_op == `OP_RESETBIT;
        e_edge_q    <= (o_op == `OP_FP) || (o_op == `OP_FN);
        e_byte_q    <= o_op[`OP_BYTE_BIT];
        e_end_q     <= o_op == `OP_END;
        e_refresh_q <= o_op == `OP_REFRESH;
        e_refresh_q_q <= o_op == `OP_REFRESH_Q;
        e_ju_q      <= o_op == `OP_JU;
        e_jc_q      <= o_op == `OP_JC;
        e_jcn_q     <= o_op == `OP_JCN;
        e_on_m_q    <= o_area == `AREA_M;
        e_on_q_q    <= (o_area == `AREA_Q) || (o_area == `AREA_PQ);
        e_on_pq_q   <= o_area == `AREA_PQ;
        e_on_fb_q   <= o_area == `AREA_FB;
        e_on_tc_q   <= (o_area == `AREA_T) || (o_area == `AREA_C);
        e_tcw_q     <= o_logic && o_instr_q[`ISA_WAIT_UPDATE] &&
                       ((o_area == `AREA_T) || (o_area == `AREA_C));
        e_chan_q    <= o_chan;
        e_opnd_q    <= o_opnd;
        e_src_m_q   <= o_area == `AREA_M;
        e_src_fb_q  <= o_area == `AREA_FB;
        // the first instruction of a scan reads I/IR/IF as they are being latched
        e_src_live_q <= o_live;
        e_pinsel_q  <= o_live ? o_sel_in : {InBits{1'b0}};
        e_live1_q   <= o_live1;
        e_live0_q   <= o_live0;
        e_mfwd_q     <= m_fwd_next;
        e_mfwd_val_q <= m_fwd_val;
        e_upd_q     <= !start_i && o_upd;
      end else begin
        if (!e_hold) e_valid_q <= 1'b0;  // END executed, or stopped: a bubble
        // held (or idle) in execute: T/C status and updated follow the byte side; the
        // marker bit is kept (m_hold_q takes the next instruction's)
        if (e_tc_fwd) e_opnd_q <= tc_val_i;
        e_mfwd_q     <= 1'b1;
        e_mfwd_val_q <= m_opnd;
        e_upd_q <= (e_upd_q && !latch_i) || e_tc_fwd;
      end
    end
  end

  assign exec_pc_o    = w_busy ? w_pc_q : e_pc_q;
  assign exec_valid_o = (w_busy && exec_i) || e_go;

  // Retirement, one clock late (observation only: no logic reads it, and where the
  // outputs stay open, as in the synthesis wrapper, Yosys removes it). An instruction
  // completes in execute (e_done) or in the wait slot (w_done); a live operand is the
  // one its pin picked, an FBI read in the slot the channel's bit.
  wire e_opnd_eff = e_src_live_q ? (pin_live ? e_live1_q : e_live0_q) : operand;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ret_valid_o <= 1'b0;
      ret_pc_o    <= {PcW{1'b0}};
      ret_opnd_o  <= 1'b0;
    end else begin
      ret_valid_o <= e_done || (w_busy && w_done && exec_i);
      ret_pc_o    <= w_busy ? w_pc_q : e_pc_q;
      ret_opnd_o  <= w_busy ? (w_fwait_q && w_fbr_q && w_fb_bit) : e_opnd_eff;
    end
  end

  // ---------------------------------------------------------------- LUT words (wide)
  // The wide build's LUT word in execute: lut_unit.v picks its operands there and
  // evaluates its tables; the writes are the ports above (M, Q, RLO) and the scratch
  // file's (port A with area S, port B).
  generate if (BitEngine == 1) begin : g_lut
    wire o_lut = o_instr_q[`LUT_TAG] == `LUT_TAG_VALUE;
    reg  e_lut_q;
    // verilator lint_off UNUSEDSIGNAL
    wire lut_res_b;
    // verilator lint_on UNUSEDSIGNAL
    always @(posedge clk_i or negedge rst_ni)
      if (!rst_ni) e_lut_q <= 1'b0;
      else if (e_load) e_lut_q <= o_lut;
    assign e_lut = e_lut_q;
    lut_unit #(
      .InBits    (InBits),
      .OutBits   (OutBits),
      .MarkerBits(MarkerBits),
      .StatusBits(StatusBits)
    ) u_lut (
      .clk_i           (clk_i),
      .rst_ni          (rst_ni),
      .d_ext_i         (d_ext),
      .o_move_i        (o_move),
      .o_first_i       (o_first_q),
      .e_load_i        (e_load),
      .o_unit_first_i  (o_lut && o_instr_q[`LUT_FIRST]),
      .m_we_i          (m_we),
      .m_waddr_i       (m_waddr),
      .m_wdata_i       (m_wdata),
      .lw_we_i         (lw_we_q),
      .lw_addr_i       (lw_addr_q),
      .lw_val_i        (lw_val_q),
      .pins_i          (pins_i),
      .pii_i           (pii_i),
      .rise_i          (rise_i),
      .fall_i          (fall_i),
      .pio_i           (pio_i),
      .q_rise_i        (q_rise_i),
      .q_fall_i        (q_fall_i),
      .timer_status_i  (timer_status_i),
      .counter_status_i(counter_status_i),
      .rlo_i           (rlo_o),
      .out_wr_en_i     (out_wr_en_o),
      .out_wr_idx_i    (out_wr_idx_o),
      .out_wr_val_i    (out_wr_val_o),
      .tc_we_i         (tc_we_i),
      .tc_is_counter_i (tc_is_counter_i),
      .tc_idx_i        (tc_idx_i),
      .tc_val_i        (tc_val_i),
      .scr_a_we_i      (lut_done && (lut_dst == `LAREA_S)),
      .scr_a_idx_i     (e_instr_q[4:0]),
      .scr_b_we_i      (lut_done && e_instr_q[`LUT_SCR_EN]),
      .scr_b_idx_i     (e_instr_q[`LUT_SCR_INDEX]),
      .res_a_o         (lut_res_a),
      .res_b_o         (lut_res_b)      // port B: the scratch file's write, inside
    );
  end else begin : g_no_lut
    assign e_lut     = 1'b0;
    assign lut_res_a = 1'b0;
    // verilator lint_off UNUSEDSIGNAL
    wire unused_lut = ^d_ext;
    // verilator lint_on UNUSEDSIGNAL
  end endgenerate

  // Reserved instruction bits and the upper index bits of narrow areas are unused;
    // verilator lint_off UNUSEDSIGNAL
  wire unused_bits = ^{e_instr_q, o_instr_q[23:17]};
  // verilator lint_on UNUSEDSIGNAL
`ifdef FORMAL
  // ================================================================ formal properties
  // formal/bit_proc.sby (docs/verification.md): a reference model of the ISA
  // (docs/isa.md) checks every retired instruction against the architectural state,
  // by k-induction at small parameters. The environment below is the CPU's: the scan
  // controller is modelled here, the input unit, the output unit and the T/C status
  // buffer are the CPU's own modules; the program is any program (the RAM's contents
  // are free, image words may be written under reset or while stopped); the byte
  // side, the channels, the pins and END's hold are free inputs.
`include "formal_past.vh"
  reg f_rst_past = 1'b0;                // rst_ni was high in the last clock
  always @(posedge clk_i) f_rst_past <= rst_ni;
  wire f_ok = f_past_valid && f_rst_past && rst_ni;    // a clock with a past

  // ---------------------------------------------------------------- the environment
  // scan controller (scan_ctrl.v): a scan starts from idle (memories cleared) or at
  // END; exec from the latch clock to END's clock; no watchdog
  reg f_exec, f_latch;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_exec  <= 1'b0;
      f_latch <= 1'b0;
    end else begin
      f_exec  <= start_i || (f_exec && !end_o);
      f_latch <= start_i;
    end
  always @(*) begin
    assume (exec_i == f_exec);
    assume (latch_i == f_latch);
    if (start_i) assume (f_exec ? end_o : (mem_ready_o && f_since_wr >= 2'd2));
    // the copy engine works between scans, on a cleared memory
    if (copy_en_i) assume (!f_exec && !start_i && mem_ready_o);
    // the program is loaded under reset or while stopped (docs/isa.md), words of the
    // assembler's image; after a write while stopped, the refill (f_since_wr)
    if (prog_we_i) assume ((!rst_ni || (!f_exec && !start_i)) && f_image_word(prog_wdata_i));
    if (copy_en_i) assume (f_since_wr >= 2'd2);
  end

  // the marker area (exchange marker): the reader's snapshot, any cells, constant here
  // (the snapshot's timing is marker_region.v's proof); a read's cell comes in the next
  // clock, and only then. The setting changes between scans only (the host writes it
  // before RUN: it may arrive in the clock a scan starts in).
  (* anyconst *) reg [Cells-1:0] f_cells;
  reg            f_cre_q = 1'b0;
  reg [CW-1:0]   f_cidx_q;
  always @(posedge clk_i) begin
    f_cre_q  <= cell_re_o;
    f_cidx_q <= cell_ridx_o;
  end
  always @(*) if (f_cre_q) assume (cell_rdata_i == f_cells[f_cidx_q]);
  always @(posedge clk_i) if (f_past_valid && f_exec) assume ($stable(marker_i));

  // the CPU's own input unit (latched at a scan start and by REFRESH), output unit
  // (its PIO register) and T/C status buffer (written by the byte side at any time)
  wire [InBits-1:0]     f_pii, f_rise, f_fall, f_rpend, f_fpend;
  wire [OutBits-1:0]    f_pio, f_opins, f_qrise, f_qfall;
  wire [StatusBits-1:0] f_tst, f_cst, f_tupd, f_cupd;
  // verilator lint_off PINCONNECTEMPTY
  input_unit #(.InBits(InBits)) f_in (
    .clk_i(clk_i), .rst_ni(rst_ni), .pins_i(pins_i), .latch_i(latch_i), .refresh_i(refresh_o),
    .pii_o(f_pii), .rise_o(f_rise), .fall_o(f_fall),
    .rise_pend_o(f_rpend), .fall_pend_o(f_fpend));
  output_unit #(.OutBits(OutBits)) f_out (
    .clk_i(clk_i), .rst_ni(rst_ni), .wr_en_i(out_wr_en_o), .wr_idx_i(out_wr_idx_o),
    .wr_val_i(out_wr_val_o), .wr_direct_i(out_wr_direct_o),
    .update_i(e_done && (e_instr_q[`ISA_OPCODE] == `OP_END ||
                         e_instr_q[`ISA_OPCODE] == `OP_REFRESH_Q)), .fault_i(1'b0), .pio_o(f_pio), .pins_o(f_opins),
    .rise_o(f_qrise), .fall_o(f_qfall));
  tc_status #(.StatusBits(StatusBits)) f_tc (
    .clk_i(clk_i), .rst_ni(rst_ni), .status_we_i(tc_we_i),
    .status_is_counter_i(tc_is_counter_i), .status_idx_i(tc_idx_i),
    .status_val_i(tc_val_i), .ctl_we_i(1'b0), .ctl_is_counter_i(1'b0),
    .ctl_idx_i({$clog2(StatusBits){1'b0}}), .ctl_val_i(1'b0), .partitioned_i(1'b1),
    .bit_we_i(tcw_we_o), .bit_is_counter_i(tcw_is_counter_o), .bit_idx_i(tcw_idx_o),
    .bit_val_i(tcw_val_o), .latch_i(latch_i),
    .timer_status_o(f_tst), .counter_status_o(f_cst), .timer_enable_o(),
    .counter_pulse_o(), .timer_updated_o(f_tupd), .counter_updated_o(f_cupd),
    .timer_written_o(), .counter_written_o());
  // verilator lint_on PINCONNECTEMPTY
  always @(*) begin
    assume (pii_i == f_pii && rise_i == f_rise && fall_i == f_fall);
    assume (rise_pend_i == f_rpend && fall_pend_i == f_fpend);
    assume (pio_i == f_pio && out_pins_i == f_opins);
    assume (q_rise_i == f_qrise && q_fall_i == f_qfall);
    assume (timer_status_i == f_tst && counter_status_i == f_cst);
    assume (timer_updated_i == f_tupd && counter_updated_i == f_cupd);
  end

  // ---------------------------------------------------------------- the program
  // Any program: the RAM's contents are free, words may be written under reset or
  // while stopped;
  // f_pw is the word at the anyconst address f_pa (the RAM's peek port). A word of the
  // assembler's image has bit 23 = 0 in a bit instruction and its operand index
  // inside its area (the assembler rejects the others); stored, bit 23 of a bit
  // instruction marks END (f_wellformed), for the words never written it is assumed.
  wire [31:0] f_pw = unused_prog_peek;
  function automatic f_in_range(input [31:0] w);
    reg [3:0] a;
    reg [11:0] i;
    begin
      a = w[`ISA_AREA];
      i = w[`ISA_INDEX];
      f_in_range = 1'b1;
      if (!w[24 + `OP_BYTE_BIT] && (w[`ISA_OPCODE] & 8'hE0) != 8'h20) begin  // an operand
        if ((a <= `AREA_IF) && i >= InBits) f_in_range = 1'b0;
        if ((a == `AREA_Q || a == `AREA_PQ || a == `AREA_QR || a == `AREA_QF) &&
            i >= OutBits) f_in_range = 1'b0;
        if ((a == `AREA_M) && i >= MarkerBits) f_in_range = 1'b0;
        if ((a == `AREA_T || a == `AREA_C) && i >= StatusBits) f_in_range = 1'b0;
        if ((a == `AREA_FB) && i >= Channels) f_in_range = 1'b0;
      end
    end
  endfunction
  function automatic f_image_word(input [31:0] w);
    f_image_word = f_in_range(w) && (w[24 + `OP_BYTE_BIT] || !w[23]);
  endfunction
  function automatic f_wellformed(input [31:0] w);
    f_wellformed = f_in_range(w) &&
                   (w[24 + `OP_BYTE_BIT] || w[23] == (w[`ISA_OPCODE] == `OP_END));
  endfunction
  // clocks since a program write while stopped (saturating): the pipeline refills
  // from address 0 in two, a scan may start (and the copy port work) from the third
  reg [1:0] f_since_wr = 2'd0;
  always @(posedge clk_i)
    if (prog_we_i && rst_ni)    f_since_wr <= 2'd0;
    else if (f_since_wr != 2'd3) f_since_wr <= f_since_wr + 1'b1;
  // the image word last written to f_pa
  reg        f_pa_written = 1'b0;
  reg [31:0] f_pimg;
  always @(posedge clk_i)
    if (prog_we_i && prog_waddr_i == f_pa) begin
      f_pa_written <= 1'b1;
      f_pimg       <= prog_wdata_i;
    end
  always @(*) begin
    if (!f_pa_written) assume (f_wellformed(f_pw));
    // (every word decode sees is one of the RAM's: this constrains the contents, it
    // cannot make decode see a word the RAM does not hold)
    if (d_valid_q) assume (f_wellformed(d_instr));
  end
  // the stored word is the image's, END marked in bit 23 as it is written
  always @(*) if (f_pa_written)
    assert (f_wellformed(f_pw) && f_pw[31:24] == f_pimg[31:24] && f_pw[22:0] == f_pimg[22:0] &&
            (!f_pimg[24 + `OP_BYTE_BIT] || f_pw[23] == f_pimg[23]));

  // ---------------------------------------------------------------- the reference
  // Decoded from the instruction in execute, independently of the e_* flags.
  wire [7:0]  f_op   = e_instr_q[`ISA_OPCODE];
  wire [3:0]  f_area = e_instr_q[`ISA_AREA];
  wire [11:0] f_idx  = e_instr_q[`ISA_INDEX];
  wire f_isbyte  = f_op[`OP_BYTE_BIT];
  wire f_islogic = (f_op & 8'hF8) == 8'h08;
  wire f_isopen  = (f_op & 8'hF8) == 8'h10;
  wire f_isclose = f_op == `OP_CLOSE;
  wire f_isfp    = f_op == `OP_FP;
  wire f_isfn    = f_op == `OP_FN;
  wire f_isend   = f_op == `OP_END;
  wire f_isref   = f_op == `OP_REFRESH;
  wire f_isrefq  = f_op == `OP_REFRESH_Q;
  wire f_isassign = f_op == `OP_ASSIGN;
  wire f_isset   = f_op == `OP_SETBIT;
  wire f_isrst   = f_op == `OP_RESETBIT;
  wire f_uses_x  = f_islogic || f_isfp || f_isfn;   // reads its operand
  wire f_on_m    = f_area == `AREA_M;
  wire f_on_q    = (f_area == `AREA_Q) || (f_area == `AREA_PQ);
  wire f_on_fb   = f_area == `AREA_FB;
  wire f_on_tc   = (f_area == `AREA_T) || (f_area == `AREA_C);
  wire f_taken   = e_act && ((f_op == `OP_JU) || (f_op == `OP_JC && rlo_o) ||
                            (f_op == `OP_JCN && !rlo_o));
  // a write of the target: =, S / R if RLO, FP / FN (the edge memory, the old RLO)
  wire f_writes  = f_isassign || f_isfp || f_isfn || ((f_isset || f_isrst) && rlo_o);
  wire f_wval    = f_isset ? 1'b1 : f_isrst ? 1'b0 : rlo_o;

  // the marker at f_ma: its architectural value (every retired write, the copy port)
  (* anyconst *) reg [MW-1:0] f_ma;
  reg f_m;
  wire f_mcl = !clearing || clear_addr_q[MW-1:0] > f_ma;   // f_ma is cleared
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) f_m <= 1'b0;             // the clear after reset writes 0
    else if (copy_we && copy_addr_i == f_ma) f_m <= copy_wdata_i;
    else if (e_done && f_writes && f_on_m && f_idx[MW-1:0] == f_ma) f_m <= f_wval;

  // the operand as the ISA defines it in the clock the instruction completes in: the
  // first instruction of a scan reads I/IR/IF as they are being latched; a marker
  // other than f_ma is taken from the pipeline (f_ma, any address, checks it)
  wire [$clog2(InBits)-1:0]     f_ii = f_idx[$clog2(InBits)-1:0];
  wire [$clog2(OutBits)-1:0]    f_qi = f_idx[$clog2(OutBits)-1:0];
  wire [$clog2(StatusBits)-1:0] f_ti = f_idx[$clog2(StatusBits)-1:0];
  wire [ChW-1:0]                f_ci = f_idx[ChW-1:0];
  wire f_m_hit = f_on_m && f_idx[MW-1:0] == f_ma;
  reg  f_x;
  always @(*) begin
    case (f_area)
      `AREA_I:  f_x = latch_i ? pins_i[f_ii] : f_pii[f_ii];
      `AREA_PI: f_x = pins_i[f_ii];
      `AREA_IR: f_x = latch_i ? f_rpend[f_ii] : f_rise[f_ii];
      `AREA_IF: f_x = latch_i ? f_fpend[f_ii] : f_fall[f_ii];
      `AREA_Q, `AREA_PQ: f_x = f_pio[f_qi];
      `AREA_QR: f_x = f_qrise[f_qi];
      `AREA_QF: f_x = f_qfall[f_qi];
      `AREA_M:  f_x = f_m_hit ? f_m : m_opnd;
      `AREA_T:  f_x = f_tst[f_ti];
      `AREA_C:  f_x = f_cst[f_ti];
      `AREA_FB: f_x = marker_i ? f_cells[f_idx[CW-1:0]] : fbi_rd_data_i[f_ci];
      default:  f_x = 1'b0;
    endcase
  end
  // RLO := RLO f (x xor n) and the other updates (docs/isa.md, opcode table)
  function automatic f_comb(input [1:0] f, input acc, input x);
    f_comb = (f == 2'b00) ? x : (f == 2'b01) ? (acc & x) : (f == 2'b10) ? (acc | x) : (acc ^ x);
  endfunction
  reg f_rlo_nx;
  always @(*) begin
    f_rlo_nx = rlo_o;
    if (f_isbyte)                f_rlo_nx = byte_rlo_we_i ? byte_rlo_i : rlo_o;
    else if (f_islogic)          f_rlo_nx = f_comb(f_op[2:1], rlo_o, f_x ^ f_op[0]);
    else if (f_isclose)          f_rlo_nx = f_comb(stack_op_q[2:1], stack_rlo_q[0],
                                                   rlo_o ^ stack_op_q[0]);
    else if (f_isfp)             f_rlo_nx = rlo_o && !f_x;
    else if (f_isfn)             f_rlo_nx = !rlo_o && f_x;
    else if (f_op == `OP_NOT)    f_rlo_nx = !rlo_o;
    else if (f_op == `OP_SET)    f_rlo_nx = 1'b1;
    else if (f_op == `OP_CLR || f_isend) f_rlo_nx = 1'b0;
  end
  // when the instruction must wait (docs/isa.md; spec §5): a channel not ready, a T/C
  // read marked "after the update" before the update (none counts in the latch
  // clock), a byte instruction until DONE, END while the byte side holds it
  wire f_fbwr = f_on_fb && (f_isassign || ((f_isset || f_isrst) && rlo_o));
  wire f_upd  = !latch_i && ((f_area == `AREA_C) ? f_cupd[f_ti] : f_tupd[f_ti]);
  wire f_wait = (f_on_fb && f_islogic && !marker_i && !fbi_rd_ready_i[f_ci]) ||
                (f_fbwr && !marker_i && !fby_wr_ready_i[f_ci]) ||
                (f_islogic && f_on_tc && e_instr_q[`ISA_WAIT_UPDATE] && !f_upd) ||
                (f_isbyte && !byte_done_i) || (f_isend && end_hold_i);

  // the wait slot's instruction (a byte instruction, an FBI read, an FBY write that did
  // not complete in its first clock), decoded from its word
  wire [7:0]     fw_op     = w_instr_q[`ISA_OPCODE];
  wire           fw_isbyte = fw_op[`OP_BYTE_BIT];
  wire           fw_isread = (fw_op & 8'hF8) == 8'h08;          // A/O/X... FBI k
  wire [ChW-1:0] fw_ci     = w_instr_q[ChW-1:0];
  wire           fw_wval   = (fw_op == `OP_SETBIT) ? 1'b1 : (fw_op == `OP_RESETBIT) ? 1'b0 : rlo_o;
  wire           fw_wait   = fw_isbyte ? !byte_done_i :
                             fw_isread ? !fbi_rd_ready_i[fw_ci] : !fby_wr_ready_i[fw_ci];
  wire           fw_rlo_nx = fw_isbyte ? (byte_rlo_we_i ? byte_rlo_i : rlo_o) :
                             fw_isread ? f_comb(fw_op[2:1], rlo_o, fbi_rd_data_i[fw_ci] ^ fw_op[0])
                                       : rlo_o;
  wire [Channels-1:0] fw_chan = {{(Channels-1){1'b0}}, 1'b1} << fw_ci;

  // the next instruction to retire (program order: taken jumps, END -> address 0) and
  // the squash of a taken jump (the two instructions behind it)
  reg [PcW-1:0] f_npc;
  reg [1:0]     f_squash;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_npc    <= {PcW{1'b0}};
      f_squash <= 2'd0;
    end else begin
      if (e_done) f_npc <= f_taken ? e_target : f_isend ? {PcW{1'b0}} : e_pc_q + 1'b1;
      else if (w_done) f_npc <= w_pc_q + 1'b1;
      if (e_done && f_taken) f_squash <= 2'd2;
      else if (f_squash != 2'd0) f_squash <= f_squash - 1'b1;
    end

  // ---------------------------------------------------------------- properties
  // (5, and the ISA) the instruction in execute is the program's word at its address,
  // the operand it reads is the architectural value (every write of the instructions
  // ahead of it included), the RLO, the stack and the targets follow the ISA
  always @(*) if (rst_ni) begin
    if (e_valid_q && e_pc_q == f_pa) assert (e_instr_q == f_pw);
    if (e_go && f_m_hit && (f_islogic || f_isfp || f_isfn)) assert (m_opnd == f_m);
    if (e_act && !f_isbyte) assert (rlo_d == f_rlo_nx);
    if (e_done && f_isbyte) assert (rlo_d == f_rlo_nx);
    // targets: only at retirement
    assert (m_target_we == (e_done && f_writes && f_on_m && !f_isbyte));
    if (m_target_we) assert (m_waddr == f_idx[MW-1:0] && m_wdata == f_wval);
    assert (out_wr_en_o == (e_done && f_writes && f_on_q && !f_isbyte));
    if (out_wr_en_o) assert (out_wr_idx_o == f_qi && out_wr_val_o == f_wval &&
                             out_wr_direct_o == (f_area == `AREA_PQ));
    assert (tcw_we_o == (e_done && f_isassign && f_on_tc && !f_isbyte));
    if (tcw_we_o) assert (tcw_idx_o == f_ti && tcw_val_o == f_wval &&
                          tcw_is_counter_o == (f_area == `AREA_C));
    // channel requests: the acting instruction's, in its first clock from execute, then
    // from the wait slot (a blocked instruction asks for nothing)
    if (w_busy) begin
      assert (fby_wr_req_o == ((w_fwait_q && !fw_isread) ? fw_chan : {Channels{1'b0}}));
      assert (fbi_rd_req_o == ((w_fwait_q && fw_isread) ? fw_chan : {Channels{1'b0}}));
      if (w_fwait_q && !fw_isread) assert (fby_wr_data_o == fw_wval);
    end else begin
      assert (fby_wr_req_o == ((e_go && f_fbwr && !f_isbyte && !marker_i) ?
                               ({{(Channels-1){1'b0}}, 1'b1} << f_ci) : {Channels{1'b0}}));
      if (f_fbwr) assert (fby_wr_data_o == f_wval);
      assert (fbi_rd_req_o == ((e_go && f_on_fb && f_islogic && !marker_i) ?
                               ({{(Channels-1){1'b0}}, 1'b1} << f_ci) : {Channels{1'b0}}));
    end
    // the marker exchange: `= FBY k` (S / R with RLO 1) writes cell k as it completes;
    // no cell access ever waits (the slot holds none)
    assert (cell_we_o == (e_done && f_fbwr && marker_i && !f_isbyte));
    if (cell_we_o) assert (cell_widx_o == f_idx[CW-1:0] && cell_wdata_o == f_wval);
    if (w_fwait_q) assert (!marker_i);
    // (induction helpers) a cell read in execute was read for it as it entered, and
    // is kept from then on
    if (e_valid_q && f_on_fb && marker_i) begin
      if (e_first_q) f_inv_cell_rd: assert (f_cre_q && f_cidx_q == f_idx[CW-1:0]);
      else f_inv_cell_hold: assert (cell_hold_q == f_cells[f_idx[CW-1:0]]);
    end
    assert (end_o == (e_done && f_isend));
    assert (refresh_o == (e_done && f_isref));
    assert (out_update_o == (e_done && (f_isend || f_isrefq)));
    assert (byte_req_o == ((e_act && f_isbyte) || (w_busy && fw_isbyte)));
    if (byte_req_o) assert (byte_instr_o == (w_busy ? w_instr_q : e_instr_q));
    // a byte instruction's clocks are no stall
    assert (stall_o == (w_busy ? (!fw_isbyte && fw_wait) : (e_go && f_wait && !f_isbyte)));
    // (1, 2) the instruction waits exactly when the ISA says so: in execute (it moves
    // into the slot if it waits for the byte side's answer), then in the slot
    if (e_act) assert (e_wait == f_wait &&
                       to_slot == ((f_on_fb && f_islogic && !marker_i && !fbi_rd_ready_i[f_ci]) ||
                                   (f_fbwr && !marker_i && !fby_wr_ready_i[f_ci]) ||
                                   (f_isbyte && !byte_done_i)));
    if (w_busy) assert (w_done == !fw_wait);
    // the slot holds its instruction's decode, the next instruction (if any) behind it
    if (w_busy) begin
      assert (f_exec && f_squash == 2'd0 && w_pc_q == f_npc && !(w_bwait_q && w_fwait_q));
      assert (w_bwait_q == fw_isbyte && w_fbr_q == fw_isread);
      assert (fw_isbyte || w_instr_q[`ISA_AREA] == `AREA_FB);
      if (!fw_isbyte) assert (w_chan_q == fw_chan);
      if (!fw_isbyte && !fw_isread)
        assert (fw_op == `OP_ASSIGN || fw_op == `OP_SETBIT || fw_op == `OP_RESETBIT);
      if (w_fwait_q && !fw_isread) assert (w_data_q == fw_wval);
      assert (f_wellformed(w_instr_q));
      if (w_pc_q == f_pa) assert (w_instr_q == f_pw);
      if (e_valid_q) assert (e_pc_q == w_pc_q + 1'b1);
    end
    // the marker RAM holds the architectural value (once cleared)
    if (f_mcl) assert (m_peek_o == f_m);
    if (clearing) assert (!f_exec && f_m == 1'b0);
  end
  always @(*) assume (m_peek_addr_i == f_ma);   // the peek port looks at f_ma

  // (2) the architectural state changes only when an instruction retires: a stalled
  // (or idle) clock leaves the RLO, the stack and the pipeline as they are
  always @(posedge clk_i) if (f_ok) begin
    if ($past(w_done)) begin
      assert (rlo_o == $past(fw_rlo_nx));
      assert (sp_q == $past(sp_q) && stack_rlo_q == $past(stack_rlo_q) &&
              stack_op_q == $past(stack_op_q));
    end else if ($past(e_done)) begin
      assert (rlo_o == $past(f_rlo_nx));
      if ($past(f_isend))
        assert (sp_q == 0 && stack_rlo_q == $past(stack_rlo_q) && stack_op_q == $past(stack_op_q));
      else if ($past(f_isopen) && $past(sp_q) != NestDepth)
        assert (sp_q == $past(sp_q) + 1'b1 && stack_rlo_q[0] == $past(rlo_o) &&
                stack_op_q[2:0] == $past(f_op[2:0]) &&
                stack_rlo_q[NestDepth-1:1] == $past(stack_rlo_q[NestDepth-2:0]) &&
                stack_op_q[NestDepth*3-1:3] == $past(stack_op_q[NestDepth*3-4:0]));
      else if ($past(f_isclose) && $past(sp_q) != 0)
        assert (sp_q == $past(sp_q) - 1'b1 &&
                stack_rlo_q[NestDepth-2:0] == $past(stack_rlo_q[NestDepth-1:1]) &&
                stack_op_q[NestDepth*3-4:0] == $past(stack_op_q[NestDepth*3-1:3]));
      else
        assert (sp_q == $past(sp_q) && stack_rlo_q == $past(stack_rlo_q) &&
                stack_op_q == $past(stack_op_q));
    end else begin
      assert (rlo_o == $past(rlo_o) && sp_q == $past(sp_q));
      assert (stack_rlo_q == $past(stack_rlo_q) && stack_op_q == $past(stack_op_q));
    end
    // a stalled or blocked instruction stays in execute, the instructions behind it
    // stay put; one waiting for the byte side moves into the slot and stays there
    if ($past(e_blocked || (e_act && (end_wait || tc_wait))))
      assert (e_valid_q && e_pc_q == $past(e_pc_q) && e_instr_q == $past(e_instr_q) &&
              o_valid_q == $past(o_valid_q) && o_pc_q == $past(o_pc_q) &&
              d_valid_q == $past(d_valid_q) && d_pc_q == $past(d_pc_q));
    if ($past(e_act && to_slot))
      assert (w_busy && w_pc_q == $past(e_pc_q) && w_instr_q == $past(e_instr_q));
    if ($past(w_busy && !w_done))
      assert (w_busy && w_pc_q == $past(w_pc_q) && w_instr_q == $past(w_instr_q));
    if ($past(w_done)) assert (!w_busy);
  end
  // the copy port reads the marker it addressed in the last clock
  always @(posedge clk_i) if (f_ok && $past(copy_en_i && copy_addr_i == f_ma && !copy_we_i))
    assert (copy_rdata_o == f_m);
  always @(*) if (rst_ni && (w_busy || (e_act && e_wait)))
    assert (!m_target_we && !out_wr_en_o && !end_o && !refresh_o && !jump_taken);

  // (1, 3) program order, one instruction per clock: in a scan every clock executes
  // one (the next in program order) except the two clocks after a taken jump, whose
  // instructions (fetched behind it: in operand and decode) are squashed
  always @(*) if (rst_ni) begin
    if (e_valid_q && !w_busy) assert (e_pc_q == f_npc && f_exec);
    if (f_exec && f_squash == 2'd0) assert (e_valid_q || w_busy);
    if (f_squash != 2'd0) assert (f_exec && !e_valid_q);
    if (jump_taken) assert (f_taken && (!o_valid_q || o_pc_q == e_pc_q + 1'b1));
    if (f_squash == 2'd1) assert (!o_valid_q || o_pc_q == f_npc);
    if (f_squash == 2'd2) assert (!o_valid_q && d_valid_q && d_pc_q == f_npc);
  end
  // (4) END hands over to the next scan: its first instruction (address 0) executes in
  // the latch clock, with RLO = 0 and an empty stack
  always @(*) if (rst_ni && latch_i)
    assert (e_valid_q && e_pc_q == 0 && rlo_o == 1'b0 && sp_q == 0 && !w_busy);


  // ---------------------------------------------------------------- covers
  // (the properties are not vacuous: each situation they speak of is reachable)
  reg [2:0] f_mw_hist, f_qw_hist, f_done_hist;  // retired: a write of f_ma / of Q, any
  reg [2:0] f_stall_hist;
  reg       f_jumped, f_ended;
  wire      f_qw_hit = out_wr_en_o && out_wr_idx_o == f_qi && f_on_q;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      {f_mw_hist, f_qw_hist, f_done_hist, f_stall_hist} <= 12'd0;
      {f_jumped, f_ended} <= 2'b00;
    end else begin
      f_mw_hist    <= {f_mw_hist[1:0], e_done && f_writes && f_m_hit};
      f_qw_hist    <= {f_qw_hist[1:0], out_wr_en_o};
      f_done_hist  <= {f_done_hist[1:0], e_done};
      f_stall_hist <= {f_stall_hist[1:0], w_busy ? !w_done : (e_act && e_wait)};
      f_jumped     <= jump_taken;
      f_ended      <= end_o && start_i;
    end
  wire f_rd_m = e_done && f_m_hit && f_uses_x;
  wire f_rd_q = e_done && f_on_q && f_uses_x;
  always @(posedge clk_i) if (rst_ni) begin
    // straight-line code: four instructions retire in four consecutive clocks
    cover (e_done && f_done_hist == 3'b111 && !f_jumped);
    // a marker written by the instruction 1, 2, 3 ahead of the one reading it
    cover (f_rd_m && f_mw_hist[0] && f_islogic);
    cover (f_rd_m && f_mw_hist[0] && f_isfp);    // an FP on the edge memory just written
    cover (f_rd_m && f_mw_hist[1] && !f_mw_hist[0]);
    cover (f_rd_m && f_mw_hist[2] && f_mw_hist[1:0] == 2'b00);
    // = Q / = PQ read back by the next instruction
    cover (f_rd_q && f_qw_hist[0] && $past(out_wr_idx_o) == f_qi && f_area == `AREA_Q);
    cover (f_rd_q && f_qw_hist[0] && $past(out_wr_idx_o) == f_qi && f_area == `AREA_PQ);
    // a stall of two clocks, then the instruction retires (T after the update, FBI)
    cover (e_done && f_stall_hist[1:0] == 2'b11 && f_on_tc && f_islogic);
    cover (w_done && f_stall_hist[1:0] == 2'b11 && fw_isread);
    cover (w_done && f_stall_hist[0] && fw_isbyte && byte_rlo_we_i);
    cover (w_done && f_stall_hist[0] && !fw_isbyte && !fw_isread);
    // the instruction blocked behind the slot reads the marker the one before wrote
    cover (f_rd_m && $past(e_blocked) && f_mw_hist[2]);
    // a taken jump: two clocks squashed, the target retires in the third
    cover (e_done && f_done_hist == 3'b100 && $past(f_squash, 2) == 2'd2 && f_uses_x);
    cover (e_done && f_taken && $past(f_squash, 2) == 2'd2);  // the target jumps again
    // END, and the next scan's first instruction retires in the latch clock
    cover (f_ended && e_done && latch_i && f_on_m);
    cover (e_done && latch_i && f_area == `AREA_IR && f_x);
    // REFRESH, then an I read of the new image; a copy-port write read by a scan
    cover (e_done && f_isref && f_x);
    // an output edge read right behind the update that sets it (REFRESH Q, END)
    cover (e_done && f_area == `AREA_QR && f_x && $past(out_update_o && !end_o));
    cover (e_done && f_area == `AREA_QF && f_x && $past(end_o));
    // REFRESH as a scan's first instruction (a second latch in the latch clock), then
    // an I read of the image it took
    cover (e_done && f_area == `AREA_I && f_x && $past(latch_i && refresh_o));
    cover (e_done && latch_i && f_rd_m && $past(copy_we, 2));
    // a scan starting as early as it may after a program write while stopped
    cover (e_done && latch_i && $past(f_since_wr) == 2'd2 && $past(prog_we_i, 4) && $past(rst_ni, 4));
    // a word loaded under reset executes: END (marked as it was written), a jump
    cover (e_done && f_pa_written && e_pc_q == f_pa && f_isend && e_pc_q != 0);
    cover (e_done && f_pa_written && e_pc_q == f_pa && f_taken);
  end

  // ---------------------------------------------------------------- invariants
  function automatic [SelW-1:0] d_sel_of(input [31:0] w);
    d_sel_of = ((w[`ISA_INDEX] >> $clog2(SelW)) == 12'd0)
        ? ({{(SelW-1){1'b0}}, 1'b1} << w[$clog2(SelW)-1:0]) : {SelW{1'b0}};
  endfunction
  function automatic [7:0] d_asel_of(input [31:0] w);
    reg [3:0] a;
    begin
      a = w[`ISA_AREA];
      d_asel_of = {a == `AREA_QF, a == `AREA_QR, a == `AREA_C, a == `AREA_T, (a == `AREA_Q) || (a == `AREA_PQ),
                   a == `AREA_IF, a == `AREA_IR, a == `AREA_I};
    end
  endfunction
  // (for the induction) the stages hold consecutive words of the program, decoded
  wire [PcW-1:0] f_e_succ = e_end_q ? {PcW{1'b0}} : e_pc_q + 1'b1;
  wire [PcW-1:0] f_o_succ = (o_op == `OP_END) ? {PcW{1'b0}} : o_pc_q + 1'b1;
  always @(*) if (rst_ni) begin
    if (d_valid_q && d_pc_q == f_pa) assert (d_instr == f_pw);
    if (o_valid_q && o_pc_q == f_pa) assert (o_instr_q == f_pw);
    if (o_valid_q) assert (f_wellformed(o_instr_q));
    if (e_valid_q) assert (f_wellformed(e_instr_q));
    if (o_valid_q && d_valid_q) assert (d_pc_q == f_o_succ);
    if (o_valid_q && e_valid_q) assert (o_pc_q == f_e_succ);
    if (o_valid_q && !e_valid_q && f_squash == 2'd0 && !w_busy) assert (o_pc_q == f_npc);
    if (!f_exec && mem_ready_o && f_since_wr >= 2'd2) assert (o_valid_q && d_valid_q);
    // between scans: the next scan starts at 0 with RLO = 0 and an empty stack
    if (!f_exec) assert (!e_valid_q && f_npc == 0 && rlo_o == 1'b0 && sp_q == 0 &&
                         f_squash == 2'd0 && !latch_i && !w_busy);
    if (o_valid_q) assert (o_sel_q == d_sel_of(o_instr_q) && o_asel_q == d_asel_of(o_instr_q));
  end
  // the e_* flags are the decode of e_instr_q; the registered operand is the image's
  // bit as of now
  wire f_live = !f_isbyte && ((f_area == `AREA_PI) ||
                (latch_i && (f_area == `AREA_I || f_area == `AREA_IR || f_area == `AREA_IF)));
  always @(*) if (rst_ni && e_valid_q) begin
    assert (e_logic_q == f_islogic && e_open_q == f_isopen && e_close_q == f_isclose);
    assert (e_fp_q == f_isfp && e_fn_q == f_isfn && e_edge_q == (f_isfp || f_isfn));
    assert (e_not_q == (f_op == `OP_NOT) && e_set_q == (f_op == `OP_SET) &&
            e_clr_q == (f_op == `OP_CLR));
    assert (e_assign_q == f_isassign && e_setbit_q == f_isset && e_rstbit_q == f_isrst);
    assert (e_byte_q == f_isbyte && e_end_q == f_isend && e_refresh_q == f_isref &&
            e_refresh_q_q == f_isrefq);
    assert (e_ju_q == (f_op == `OP_JU) && e_jc_q == (f_op == `OP_JC) &&
            e_jcn_q == (f_op == `OP_JCN));
    assert (e_on_m_q == f_on_m && e_on_q_q == f_on_q && e_on_pq_q == (f_area == `AREA_PQ));
    assert (e_on_fb_q == f_on_fb && e_on_tc_q == f_on_tc && e_src_m_q == f_on_m &&
            e_src_fb_q == f_on_fb);
    assert (e_tcw_q == (f_islogic && f_on_tc && e_instr_q[`ISA_WAIT_UPDATE]));
    assert (e_chan_q == ((f_idx[11:ChW] == 0) ?
                         ({{(Channels-1){1'b0}}, 1'b1} << f_ci) : {Channels{1'b0}}));
    // (the operand fields of the instructions without an operand are don't-cares)
    if (f_uses_x) begin
      assert (e_src_live_q == f_live);
      assert (e_pinsel_q == (f_live ? d_sel_of(e_instr_q) : {SelW{1'b0}}));
      // PI (and I in the latch clock): the operand is the pin (the instruction may wait
      // blocked behind the slot for any number of clocks)
      if (f_live && (f_area == `AREA_PI || f_area == `AREA_I)) assert (e_live1_q && !e_live0_q);
      if (!f_live && !f_on_m && !f_on_fb) assert (e_opnd_q == f_x);
    end
    if (f_isbyte) assert (!e_src_live_q && e_pinsel_q == {SelW{1'b0}});
    if (e_tcw_q) assert (e_upd_q == f_upd);
  end
  // the marker forwarding: the instruction in operand has f_ma's value (the RAM word
  // read as it entered operand, or a write since)
  reg [MW-1:0] f_mraddr;
  always @(posedge clk_i) f_mraddr <= m_raddr;
  always @(*) if (rst_ni && f_mcl && o_valid_q && o_area == `AREA_M && o_mi == f_ma) begin
    if (!o_first_q) assert ((o_mfwd_q ? o_mfwd_val_q : m_hold_q) == f_m);
    else begin
      assert (f_mraddr == f_ma);
      if (lw_we_q && lw_addr_q == f_ma) assert (lw_val_q == f_m);
      else                              assert (m_rdata == f_m);
    end
  end
`endif
endmodule
`default_nettype wire
