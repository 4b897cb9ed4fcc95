`default_nettype none
`include "bit_isa.vh"
`include "param_check.vh"
// The wide bit engine's LUT word datapath (issue 18, docs/wide-rtl-plan.md): the
// operands of the LUT word in execute and its two truth tables' results. bit_proc.v
// instantiates it in its wide build (BitEngine 1) and keeps the pipeline control: it
// says when a word moves on and does the writes (M, Q, RLO through its own ports; the
// scratch file here).
//
// A LUT word reads up to `LUT_K operands, each an area and an index of its extension
// word (definition.toml [lut]); its result is table[x], x = {operand K-1 .. operand 0}.
// Every operand is what holds it in the execute clock, so that a word sees the writes
// of the words before it as the scalar instructions they stand for would. The image
// registers are picked a clock early, in the operand stage, as they will be then (the
// wide selects stay out of the execute clock); the rest in execute:
//   I, IR, IF, QR, QF   in operand (a LUT word is never in operand or execute across a
//        latch or a PIO update: the compiler keeps program positions 0 and 1 and the
//        word after REFRESH scalar, R1/R2)
//   Q (and PQ reads)    in operand, the write of the instruction in execute forwarded
//   T, C in operand, the byte side's write of this clock forwarded; while the word is
//        held in execute (blocked behind the wait slot), its writes are caught there
//   PI   the pins of the operand clock of a unit's first word, one value for all words
//        of the unit (a snapshot taken as that word moves into execute; §2.3)
//   M    one copy of the marker RAM per operand (written with the marker RAM, read with
//        the operand's address as the word leaves decode), and every marker write since
//        that read forwarded, as bit_proc does for its own marker read
//   S    in execute: the scratch file (flip-flops), written by the words before
//   RLO  in execute: the RLO register (rlo_i); ZERO  0
module lut_unit #(
  parameter integer InBits     = 128,
  parameter integer OutBits    = 128,
  parameter integer MarkerBits = 2048,
  parameter integer StatusBits = 64
) (
  input  wire                          clk_i,
  input  wire                          rst_ni,
  // the pipeline (bit_proc.v): the extension word leaving the program RAM in decode,
  // decode -> operand, the word in operand entered it at the last edge, operand ->
  // execute; the word moving into execute is a unit's first
  input  wire [`LUT_EXT_BITS-1:0]      d_ext_i,
  input  wire                          o_move_i,
  input  wire                          o_first_i,
  input  wire                          e_load_i,
  input  wire                          o_unit_first_i,
  // every marker write, as the marker RAM takes it (clearing, execute, copy engine),
  // and the one of the last clock (lw_*: the write at the edge a read happened at)
  input  wire                          m_we_i,
  input  wire [$clog2(MarkerBits)-1:0] m_waddr_i,
  input  wire                          m_wdata_i,
  input  wire                          lw_we_i,
  input  wire [$clog2(MarkerBits)-1:0] lw_addr_i,
  input  wire                          lw_val_i,
  // operand sources (registers)
  input  wire [InBits-1:0]             pins_i,
  input  wire [InBits-1:0]             pii_i,
  input  wire [InBits-1:0]             rise_i,
  input  wire [InBits-1:0]             fall_i,
  input  wire [OutBits-1:0]            pio_i,
  input  wire [OutBits-1:0]            q_rise_i,
  input  wire [OutBits-1:0]            q_fall_i,
  input  wire [StatusBits-1:0]         timer_status_i,
  input  wire [StatusBits-1:0]         counter_status_i,
  input  wire                          rlo_i,
  // the writes of this clock the registers take at its edge: the instruction in
  // execute's to Q/PQ (bit_proc's output-unit port), the byte side's to T/C
  input  wire                          out_wr_en_i,
  input  wire [$clog2(OutBits)-1:0]    out_wr_idx_i,
  input  wire                          out_wr_val_i,
  input  wire                          tc_we_i,
  input  wire                          tc_is_counter_i,
  input  wire [$clog2(StatusBits)-1:0] tc_idx_i,
  input  wire                          tc_val_i,
  // the word in execute completes: its scratch writes (port A with area S, port B)
  input  wire                          scr_a_we_i,
  input  wire [4:0]                    scr_a_idx_i,
  input  wire                          scr_b_we_i,
  input  wire [4:0]                    scr_b_idx_i,
  output wire                          res_a_o,     // table A at the operands
  output wire                          res_b_o      // table B
);
  localparam integer K   = `LUT_K;
  localparam integer EW  = `LUT_EXT_BITS;
  localparam integer MW  = $clog2(MarkerBits);
  localparam integer OB  = `LUT_OPND_BITS;
  localparam integer TW  = 1 << K;               // a truth table's bits

  `PARAM_CHECK(g_bad_k, K != 5 || `LUT_SCRATCH_BITS != 32,
               "lut_unit: built for K = 5 operands and 32 scratch bits (definition.toml [lut])")
  `PARAM_CHECK(g_bad_sizes, InBits < 2 || InBits > 2048 || OutBits < 2 || OutBits > 2048 ||
                            MarkerBits < 2 || MarkerBits > 2048 ||
                            StatusBits < 2 || StatusBits > 2048,
               "lut_unit: every area 2..2048 bits (the 11-bit operand index)")

  // operand j's area and index in an extension word
  function automatic [3:0] f_area(input [EW-1:0] ext, input integer j);
    f_area = ext[`LUT_OPND_BASE + OB * j + 11 +: 4];
  endfunction
  function automatic [10:0] f_index(input [EW-1:0] ext, input integer j);
    f_index = ext[`LUT_OPND_BASE + OB * j +: 11];
  endfunction

  // ---------------------------------------------------------------- the word's stages
  reg [EW-1:0] o_ext_q, e_ext_q;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      o_ext_q <= {EW{1'b0}};
      e_ext_q <= {EW{1'b0}};
    end else begin
      if (o_move_i) o_ext_q <= d_ext_i;
      if (e_load_i) e_ext_q <= o_ext_q;
    end

  // ---------------------------------------------------------------- PI snapshot
  reg [InBits-1:0] pi_snap_q;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) pi_snap_q <= {InBits{1'b0}};
    else if (e_load_i && o_unit_first_i) pi_snap_q <= pins_i;

  // ---------------------------------------------------------------- scratch file
  reg [31:0] scr_q;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) scr_q <= 32'd0;
    else begin
      if (scr_a_we_i) scr_q[scr_a_idx_i] <= res_a_o;
      if (scr_b_we_i) scr_q[scr_b_idx_i] <= res_b_o;
    end

  // ---------------------------------------------------------------- operands
  // every area as 2048 bits (the 11-bit index; what is past an area reads 0); PI: the
  // pins now for a unit's first word, else its unit's snapshot
  localparam integer PadW = 2048;
  wire [PadW-1:0] x_i, x_pi, x_ir, x_if, x_q, x_qr, x_qf, x_t, x_c;
  wire [InBits-1:0] o_pins = o_unit_first_i ? pins_i : pi_snap_q;
  generate
    if (InBits < PadW) begin : g_pad_in
      wire [PadW-InBits-1:0] z = {(PadW - InBits){1'b0}};
      assign {x_i, x_pi, x_ir, x_if} = {z, pii_i, z, o_pins, z, rise_i, z, fall_i};
    end else begin : g_in
      assign {x_i, x_pi, x_ir, x_if} = {pii_i, o_pins, rise_i, fall_i};
    end
    if (OutBits < PadW) begin : g_pad_out
      wire [PadW-OutBits-1:0] z = {(PadW - OutBits){1'b0}};
      assign {x_q, x_qr, x_qf} = {z, pio_i, z, q_rise_i, z, q_fall_i};
    end else begin : g_out
      assign {x_q, x_qr, x_qf} = {pio_i, q_rise_i, q_fall_i};
    end
    if (StatusBits < PadW) begin : g_pad_tc
      wire [PadW-StatusBits-1:0] z = {(PadW - StatusBits){1'b0}};
      assign {x_t, x_c} = {z, timer_status_i, z, counter_status_i};
    end else begin : g_tc
      assign {x_t, x_c} = {timer_status_i, counter_status_i};
    end
  endgenerate

`ifdef FORMAL
  // ================================================================ formal environment
  // formal/lut_unit.sby: the pipeline around this module as bit_proc drives it, and a
  // shadow of the marker memory (every write the RAM takes); each port's property is
  // in g_port below.
`include "formal_past.vh"
  reg [MarkerBits-1:0] f_mem;          // the marker memory, as written
  (* anyconst *) reg [MW-1:0] f_pa;    // the proof follows the bit at this address
  // a word in operand, a word in execute; the word in execute leaves it in this clock
  // (completes, or moves into the wait slot): any clock, as bit_proc decides
  reg f_o_valid, f_e_valid;
  (* anyseq *) reg f_leave;
  always @(posedge clk_i)                // every write the RAM copies take, reset or not
    if (m_we_i) f_mem[m_waddr_i] <= m_wdata_i;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      {f_o_valid, f_e_valid} <= 2'b00;
    end else begin
      if (o_move_i) f_o_valid <= 1'b1;
      else if (e_load_i) f_o_valid <= 1'b0;
      if (e_load_i) f_e_valid <= f_o_valid;
      else if (f_leave) f_e_valid <= 1'b0;
    end
  // bit_proc: lw_* is the last clock's marker write (registers); o_first_q the last
  // clock's o_move; the operand stage passes its word on only into execute (o_move with
  // a word there is e_load); a word stays in execute until it leaves; a marker write
  // is the leaving word's own (its target, written as it completes) or comes while
  // execute is empty (the clearing, the copy engine: between scans)
  reg f_lw_we = 1'b0, f_lw_val, f_o_first = 1'b0;
  reg [MW-1:0] f_lw_addr;
  always @(posedge clk_i) begin
    f_lw_we   <= rst_ni && m_we_i;
    f_lw_addr <= m_waddr_i;
    f_lw_val  <= m_wdata_i;
    f_o_first <= rst_ni && o_move_i;
  end
  always @(*) begin
    if (rst_ni) begin
      assume (lw_we_i == f_lw_we);
      if (f_lw_we) assume (lw_addr_i == f_lw_addr && lw_val_i == f_lw_val);
      assume (o_first_i == f_o_first);
      if (o_move_i && f_o_valid) assume (e_load_i);
      if (f_e_valid && !f_leave) assume (!e_load_i);
      if (m_we_i) assume (!f_e_valid || f_leave);
    end
  end
`endif

  wire [K-1:0] x;                                // the operands, in execute
  genvar j;
  generate for (j = 0; j < K; j = j + 1) begin : g_port
    // M: this operand's copy of the marker RAM, read as the word leaves decode
    wire [10:0] d_idx = f_index(d_ext_i, j);
    wire [10:0] o_idx = f_index(o_ext_q, j);
    wire        rdata;
    // verilator lint_off UNUSEDSIGNAL
    wire        unused_peek;
    wire [21:0] unused_idx = {d_idx, o_idx};    // above MW: 0 in a word of the compiler
    // verilator lint_on UNUSEDSIGNAL
    sync_ram #(.Words(MarkerBits), .Width(1)) u_m_copy (
      .clk_i      (clk_i),
      .we_i       (m_we_i),
      .waddr_i    (m_waddr_i),
      .wdata_i    (m_wdata_i),
      .re_i       (1'b1),
      .raddr_i    (d_idx[MW-1:0]),
      .rdata_o    (rdata),
`ifdef FORMAL
      .peek_addr_i(f_pa),
`else
      .peek_addr_i({MW{1'b0}}),
`endif
      .peek_data_o(unused_peek)
    );
    // the writes the read missed: the one at the read's edge (lw_*), then every one
    // while the word is in operand; in execute the value is kept (bit_proc writes no
    // marker while a word waits there)
    reg  hold_q, o_fwd_q, o_fwd_val_q, e_fwd_q, e_fwd_val_q;
    wire hit_now  = m_we_i && (m_waddr_i == o_idx[MW-1:0]);
    wire hit_base = o_first_i ? (lw_we_i && (lw_addr_i == o_idx[MW-1:0])) : o_fwd_q;
    wire val_base = o_first_i ? lw_val_i : o_fwd_val_q;
    wire fwd_next = hit_now || hit_base;
    wire fwd_val  = hit_now ? m_wdata_i : val_base;
    wire m_val    = e_fwd_q ? e_fwd_val_q : hold_q;
    always @(posedge clk_i or negedge rst_ni)
      if (!rst_ni) begin
        {hold_q, o_fwd_q, o_fwd_val_q, e_fwd_q, e_fwd_val_q} <= 5'd0;
      end else begin
        if (o_first_i) hold_q <= rdata;
        o_fwd_q     <= fwd_next;
        o_fwd_val_q <= fwd_val;
        if (e_load_i) begin
          e_fwd_q     <= fwd_next;
          e_fwd_val_q <= fwd_val;
        end else begin
          e_fwd_q     <= 1'b1;          // hold_q takes the next word's
          e_fwd_val_q <= m_val;
        end
      end

    // a register area, picked in operand as it will be in execute: this clock's write
    // to Q (the instruction in execute) or T/C (the byte side) forwarded
    wire [3:0]  o_area = f_area(o_ext_q, j);
    wire        o_q_fwd = out_wr_en_i && (out_wr_idx_i == o_idx[$clog2(OutBits)-1:0]);
    wire        o_tc_fwd = tc_we_i && (tc_idx_i == o_idx[$clog2(StatusBits)-1:0]) &&
                           (tc_is_counter_i == (o_area == `AREA_C));
    reg pre;
    always @(*) begin
      case (o_area)
        `AREA_I:  pre = x_i[o_idx];
        `AREA_PI: pre = x_pi[o_idx];
        `AREA_IR: pre = x_ir[o_idx];
        `AREA_IF: pre = x_if[o_idx];
        `AREA_Q:  pre = o_q_fwd ? out_wr_val_i : x_q[o_idx];
        `AREA_QR: pre = x_qr[o_idx];
        `AREA_QF: pre = x_qf[o_idx];
        `AREA_T:  pre = o_tc_fwd ? tc_val_i : x_t[o_idx];
        `AREA_C:  pre = o_tc_fwd ? tc_val_i : x_c[o_idx];
        default:  pre = 1'b0;
      endcase
    end
    // in execute: held there, the byte side's writes to its T/C follow it
    wire [3:0]  area = f_area(e_ext_q, j);
    // verilator lint_off UNUSEDSIGNAL
    wire [10:0] idx  = f_index(e_ext_q, j);     // (the bits of the widest area in use)
    // verilator lint_on UNUSEDSIGNAL
    wire        e_tc_fwd = tc_we_i && (tc_idx_i == idx[$clog2(StatusBits)-1:0]) &&
                           (((area == `AREA_T) && !tc_is_counter_i) ||
                            ((area == `AREA_C) && tc_is_counter_i));
    // (the area decoded in operand too: no compare in front of the tables)
    reg e_pre_q, e_is_m_q, e_is_s_q, e_is_rlo_q;
    always @(posedge clk_i or negedge rst_ni)
      if (!rst_ni) {e_pre_q, e_is_m_q, e_is_s_q, e_is_rlo_q} <= 4'd0;
      else if (e_load_i) begin
        e_pre_q    <= pre;
        e_is_m_q   <= o_area == `AREA_M;
        e_is_s_q   <= o_area == `LAREA_S;
        e_is_rlo_q <= o_area == `LAREA_RLO;
      end else if (e_tc_fwd) e_pre_q <= tc_val_i;
    assign x[j] = e_is_m_q   ? m_val :
                  e_is_s_q   ? scr_q[idx[4:0]] :
                  e_is_rlo_q ? rlo_i : e_pre_q;
`ifdef FORMAL
    // the marker operand of the word in execute is the memory's bit at its address,
    // in every clock it is there (the read in decode, the writes of the words before it
    // at distance 1, 2 and 3 and the one at the read's edge, and a hold)
    always @(*) begin
      // the shadow starts as the copy's contents
      if (!f_past_valid) assume (unused_peek == f_mem[f_pa]);
`ifndef F_NO_INV
      else assert (unused_peek == f_mem[f_pa]);
`endif
      if (rst_ni && f_past_valid && f_e_valid && idx[MW-1:0] == f_pa)
        assert (m_val == f_mem[f_pa]);
      // (helper invariants for the induction, left out by the bmc task (F_NO_INV) so
      // that a mutant must break the claim above: the copy holds what was written; the
      // same claim for the word in operand: in its first clock there the copy's read
      // and the write at its edge, later the hold and the forwarding)
`ifndef F_NO_INV
      if (rst_ni && f_past_valid && f_o_valid && o_idx[MW-1:0] == f_pa) begin
        if (o_first_i) assert (((lw_we_i && lw_addr_i == f_pa) ? lw_val_i : rdata) == f_mem[f_pa]);
        else assert ((o_fwd_q ? o_fwd_val_q : hold_q) == f_mem[f_pa]);
      end
`endif
    end
    // the cases (port 0): the copy's own read; a write the read missed forwarded; a
    // word held in execute for a second clock
    if (j == 0) begin : g_cover
      reg f_held = 1'b0;
      always @(posedge clk_i) f_held <= rst_ni && f_e_valid && !f_leave && !e_load_i;
      always @(*)
        if (rst_ni && f_e_valid && idx[MW-1:0] == f_pa) begin
          cover (!e_fwd_q && hold_q != f_mem[f_pa ^ 1'b1]);
          cover (e_fwd_q && e_fwd_val_q != hold_q);
          cover (f_held && e_fwd_q && f_mem[f_pa]);
        end
    end
`endif
  end endgenerate

  // ---------------------------------------------------------------- the tables
  wire [TW-1:0] table_a = e_ext_q[`LUT_TABLE_A];
  wire [TW-1:0] table_b = e_ext_q[`LUT_TABLE_B];
  assign res_a_o = table_a[x];
  assign res_b_o = table_b[x];

  // verilator lint_off UNUSEDSIGNAL
  wire unused_ext = ^{o_ext_q[EW-1:`LUT_OPND_BASE + OB * K], o_ext_q[`LUT_OPND_BASE-1:0],
                      e_ext_q[EW-1:`LUT_OPND_BASE + OB * K]};
  // verilator lint_on UNUSEDSIGNAL
endmodule
`default_nettype wire
