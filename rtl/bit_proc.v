`default_nettype none
`include "bit_isa.vh"
`include "param_check.vh"
// Bit processor: one bit instruction per clock, sustained.
//
// Three stages:
//   fetch   the program RAM is addressed with fetch_addr
//   decode  the word comes out of the RAM (d_instr); an M operand's address goes to
//           the marker RAM, whose read data arrives with the instruction in execute
//   execute the operand is selected, the RLO, the parenthesis stack and the targets
//           are updated, jumps are taken
// A taken jump squashes the one instruction in decode (2 clocks). END is recognised
// in decode, so address 0 is fetched while END executes and moves to execute at the
// end of END's clock: the next scan's first instruction executes in its latch clock,
// with the RLO and the parenthesis stack already reset for it. The processor idles
// (fetch held at address 0) whenever the scan controller is not running.
module bit_proc #(
  parameter integer ProgWords   = 4096,  // program memory, instructions (power of two)
  parameter integer InBits      = 128,   // binary inputs (I, PI, IR, IF)
  parameter integer OutBits     = 128,   // binary outputs (Q, PQ)
  parameter integer MarkerBits  = 2048,  // marker bits (M)
  parameter integer StatusBits  = 64,    // timers and counters each (T, C)
  parameter integer Channels    = 4,     // exchange channels (FBI, FBY)
  parameter integer NestDepth   = 8      // parenthesis levels
) (
  input  wire                         clk_i,
  input  wire                         rst_ni,
  // program load port (the byte processor / test bench writes the image)
  input  wire                         prog_we_i,
  input  wire [$clog2(ProgWords)-1:0] prog_waddr_i,
  input  wire [31:0]                  prog_wdata_i,
  // scan control
  input  wire                         start_i,     // the next clock starts a scan
  input  wire                         latch_i,     // this clock starts a scan
  input  wire                         exec_i,      // instructions execute (scan clocks)
  output wire                         mem_ready_o, // marker memory cleared
  output wire                         end_o,       // END executes in this clock
  output wire                         refresh_o,   // REFRESH executes in this clock
  // operand sources
  input  wire [InBits-1:0]            pii_i,
  input  wire [InBits-1:0]            pins_i,
  input  wire [InBits-1:0]            rise_i,
  input  wire [InBits-1:0]            fall_i,
  input  wire [OutBits-1:0]           pio_i,
  input  wire [StatusBits-1:0]        timer_status_i,
  input  wire [StatusBits-1:0]        counter_status_i,
  input  wire [StatusBits-1:0]        timer_updated_i,   // written this scan (parallel)
  input  wire [StatusBits-1:0]        counter_updated_i,
  // exchange channels: F_Bb k read by bit instructions, F_bB k written by `= FBY k`
  output wire [Channels-1:0]          fbi_rd_req_o,
  input  wire [Channels-1:0]          fbi_rd_data_i,
  input  wire [Channels-1:0]          fbi_rd_ready_i,
  output wire [Channels-1:0]          fby_wr_req_o,
  output wire                         fby_wr_data_o,
  input  wire [Channels-1:0]          fby_wr_ready_i,
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
  output wire                         rlo_now_o,      // the RLO execute works with
  output wire [$clog2(ProgWords)-1:0] exec_pc_o,
  output wire                         exec_valid_o
);
  localparam integer PcW   = $clog2(ProgWords);
  localparam integer MW    = $clog2(MarkerBits);
  localparam integer SpW   = $clog2(NestDepth + 1);  // 0..NestDepth levels
  // a level's index and a channel number: one bit at least, also for a single one
  localparam integer IdxW  = (NestDepth > 1) ? $clog2(NestDepth) : 1;
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

  // ---------------------------------------------------------------- fetch / decode
  reg  [PcW-1:0] d_pc_q;        // address of the word now leaving the program RAM
  wire [31:0]    d_instr;       // that word (decode stage)
  reg  [PcW-1:0] fetch_addr;
  reg  [31:0]    e_instr_q;     // execute stage
  reg  [PcW-1:0] e_pc_q;
  reg            e_valid_q;

  // verilator lint_off UNUSEDSIGNAL
  wire [31:0]    unused_prog_peek;  // no host looks at the program
  // verilator lint_on UNUSEDSIGNAL
  sync_ram #(.Words(ProgWords), .Width(32)) u_prog_ram (
    .clk_i  (clk_i),
    .we_i   (prog_we_i),
    .waddr_i(prog_waddr_i),
    .wdata_i(prog_wdata_i),
    .raddr_i(fetch_addr),
    .rdata_o(d_instr),
    .peek_addr_i({PcW{1'b0}}),
    .peek_data_o(unused_prog_peek)
  );

  // ---------------------------------------------------------------- execute decode
  wire [7:0]  e_op     = e_instr_q[`ISA_OPCODE];
  wire [3:0]  e_area   = e_instr_q[`ISA_AREA];
  wire [11:0] e_index  = e_instr_q[`ISA_INDEX];
  wire [PcW-1:0] e_target = e_instr_q[PcW-1:0];
  wire        e_go     = e_valid_q && exec_i;
  // A scan starts with RLO = 0 and an empty stack, also for the instruction that
  // executes in the latch clock itself.
  wire        rlo_cur  = latch_i ? 1'b0 : rlo_o;
  assign rlo_now_o = rlo_cur;

  wire is_logic  = (e_op & `OP_LOGIC_MASK) == `OP_LOGIC;
  wire is_open   = (e_op & `OP_LOGIC_MASK) == `OP_OPEN;
  wire is_close  = e_op == `OP_CLOSE;
  wire is_assign = e_op == `OP_ASSIGN;
  wire is_setbit = e_op == `OP_SETBIT;
  wire is_rstbit = e_op == `OP_RESETBIT;
  wire is_fp     = e_op == `OP_FP;
  wire is_fn     = e_op == `OP_FN;
  wire is_edge   = is_fp || is_fn;
  wire is_byte   = e_op[`OP_BYTE_BIT];

  // ---------------------------------------------------------------- waiting
  // Execute holds its instruction while a channel is empty/full (the buffered
  // condition flip-flops' handshake) or the byte processor works on a dispatched
  // instruction; nothing of the instruction takes effect until the clock it completes.
  // (the index fits when its bits above a channel number are 0: no wide compare; a
  // number past the last channel shifts the one out of the vector)
  wire [Channels-1:0] chan_sel = (e_index[11:ChW] == 0)
      ? ({{(Channels-1){1'b0}}, 1'b1} << e_index[ChW-1:0]) : {Channels{1'b0}};
  wire on_channel = e_area == `AREA_FB;
  wire fbi_read   = e_go && on_channel && is_logic;
  wire fby_write  = e_go && on_channel && (is_assign || ((is_setbit || is_rstbit) && rlo_cur));
  wire chan_wait  = (fbi_read  && !(|(fbi_rd_ready_i & chan_sel))) ||
                    (fby_write && !(|(fby_wr_ready_i & chan_sel)));
  wire end_wait   = e_go && (e_op == `OP_END) && end_hold_i;
  // A read of `T n` / `C n` marked "after the update" (bit 16, set by the partitioning
  // compiler when a byte-side instruction on that timer/counter precedes it in the
  // scan) waits until the byte side has written the status this scan.
  // The updated bits are cleared at the end of the latch clock: a read executing in
  // that clock must not see the previous scan's bits.
  wire [$clog2(StatusBits)-1:0] tc_idx = e_index[$clog2(StatusBits)-1:0];
  wire t_updated  = !latch_i && timer_updated_i[tc_idx];
  wire c_updated  = !latch_i && counter_updated_i[tc_idx];
  wire tc_wait    = e_go && is_logic && e_instr_q[`ISA_WAIT_UPDATE] &&
                    ((e_area == `AREA_T && !t_updated) || (e_area == `AREA_C && !c_updated));
  wire e_stall    = chan_wait || end_wait || tc_wait || (e_go && is_byte && !byte_done_i);
  wire e_done     = e_go && !e_stall;   // the instruction in execute takes effect
  // A stall is a wait on the other processor's condition; a dispatched instruction's
  // own clocks (serial mode) are its execution time, not a stall.
  assign stall_o  = chan_wait || end_wait || tc_wait;

  assign fbi_rd_req_o  = fbi_read  ? chan_sel : {Channels{1'b0}};
  assign fby_wr_req_o  = fby_write ? chan_sel : {Channels{1'b0}};
  assign fby_wr_data_o = !is_rstbit && rlo_cur;        // =: RLO; S: 1; R: 0
  assign byte_req_o    = e_go && is_byte;
  assign byte_instr_o  = e_instr_q;

  wire jump_taken = e_go && ((e_op == `OP_JU) ||
                             (e_op == `OP_JC  &&  rlo_cur) ||
                             (e_op == `OP_JCN && !rlo_cur));
  assign end_o     = e_go && (e_op == `OP_END) && !end_hold_i;
  assign refresh_o = e_go && (e_op == `OP_REFRESH);
  wire   d_is_end  = d_instr[`ISA_OPCODE] == `OP_END;

  // ---------------------------------------------------------------- marker memory
  // Cleared after reset (one bit per clock) so that every marker starts at 0.
  reg  [MW:0]   clear_addr_q;           // MarkerBits when done
  wire          clearing = !clear_addr_q[MW];
  assign mem_ready_o = !clearing;

  wire          m_rdata;
  reg           m_bypass_q;             // last clock wrote the address decode read
  reg           m_bypass_val_q;
  wire          m_target_we;            // execute writes an M bit
  // Between scans the copy engine takes the RAM's ports (nothing executes then).
  wire          copy_we = copy_en_i && copy_we_i;
  wire          m_we    = clearing || m_target_we || copy_we;
  wire [MW-1:0] m_waddr = clearing ? clear_addr_q[MW-1:0] :
                          copy_en_i ? copy_addr_i : e_index[MW-1:0];
  wire          target_val;
  wire          m_wdata = clearing ? 1'b0 : copy_en_i ? copy_wdata_i : target_val;
  wire [MW-1:0] m_raddr = copy_en_i ? copy_addr_i : d_instr[MW-1:0];
  assign copy_rdata_o = m_rdata;

  sync_ram #(.Words(MarkerBits), .Width(1)) u_marker_ram (
    .clk_i  (clk_i),
    .we_i   (m_we),
    .waddr_i(m_waddr),
    .wdata_i(m_wdata),
    .raddr_i(m_raddr),
    .rdata_o(m_rdata),
    .peek_addr_i(m_peek_addr_i),
    .peek_data_o(m_peek_o)
  );

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      clear_addr_q   <= {(MW+1){1'b0}};
      m_bypass_q     <= 1'b0;
      m_bypass_val_q <= 1'b0;
    end else begin
      if (clearing) clear_addr_q <= clear_addr_q + 1'b1;
      // The RAM returns the old bit when decode reads what execute writes.
      m_bypass_q     <= m_we && (m_waddr == m_raddr);
      m_bypass_val_q <= m_wdata;
    end
  end

  // ---------------------------------------------------------------- operand select
  reg operand;
  always @(*) begin
    case (e_area)
      `AREA_I:  operand = pii_i[e_index[$clog2(InBits)-1:0]];   // as of this clock
      `AREA_PI: operand = pins_i[e_index[$clog2(InBits)-1:0]];
      `AREA_IR: operand = rise_i[e_index[$clog2(InBits)-1:0]];
      `AREA_IF: operand = fall_i[e_index[$clog2(InBits)-1:0]];
      `AREA_Q,
      `AREA_PQ: operand = pio_i[e_index[$clog2(OutBits)-1:0]];
      `AREA_M:  operand = m_bypass_q ? m_bypass_val_q : m_rdata;
      `AREA_T:  operand = timer_status_i[tc_idx];
      `AREA_C:  operand = counter_status_i[tc_idx];
      `AREA_FB: operand = |(fbi_rd_data_i & chan_sel);
      default:  operand = 1'b0;
    endcase
  end

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

  reg [NestDepth-1:0] stack_rlo_q;        // saved RLO per level
  reg [NestDepth*3-1:0] stack_op_q;       // saved {f, n} per level
  reg [SpW-1:0] sp_q;                     // levels in use
  wire [SpW-1:0] sp_cur = latch_i ? {SpW{1'b0}} : sp_q;
  wire [SpW-1:0] sp_top = sp_cur - 1'b1;
  wire [IdxW-1:0] top_idx  = sp_top[IdxW-1:0];
  wire [IdxW-1:0] push_idx = sp_cur[IdxW-1:0];
  wire          top_rlo = stack_rlo_q[top_idx];
  wire [2:0]    top_op  = stack_op_q[top_idx*3 +: 3];

  reg rlo_d;
  always @(*) begin
    rlo_d = rlo_cur;
    if (is_logic)        rlo_d = combine(e_op[2:1], rlo_cur, operand ^ e_op[0]);
    else if (is_close)   rlo_d = combine(top_op[2:1], top_rlo, rlo_cur ^ top_op[0]);
    else if (is_fp)      rlo_d = rlo_cur & ~operand;
    else if (is_fn)      rlo_d = ~rlo_cur & operand;
    else if (e_op == `OP_NOT) rlo_d = ~rlo_cur;
    else if (e_op == `OP_SET) rlo_d = 1'b1;
    else if (e_op == `OP_CLR) rlo_d = 1'b0;
  end

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rlo_o       <= 1'b0;
      sp_q        <= {SpW{1'b0}};
      stack_rlo_q <= {NestDepth{1'b0}};
      stack_op_q  <= {(NestDepth*3){1'b0}};
    end else if (e_done) begin
      rlo_o <= (is_byte && byte_rlo_we_i) ? byte_rlo_i : rlo_d;
      sp_q  <= sp_cur;
      // The assembler bounds the nesting; the stack saturates rather than wraps.
      if (is_open && sp_cur != NestDepth[SpW-1:0]) begin
        stack_rlo_q[push_idx]       <= rlo_cur;
        stack_op_q[push_idx*3 +: 3] <= e_op[2:0];
        sp_q                        <= sp_cur + 1'b1;
      end else if (is_close && sp_cur != {SpW{1'b0}}) begin
        sp_q <= sp_top;
      end
    end else if (latch_i) begin
      rlo_o <= 1'b0;                      // every scan starts with RLO = 0
      sp_q  <= {SpW{1'b0}};
    end
  end

  // ---------------------------------------------------------------- targets
  // =, S, R write a target; FP/FN write their edge memory with the old RLO.
  wire target_we = e_done && (is_assign || is_edge || ((is_setbit || is_rstbit) && rlo_cur));
  assign target_val = is_setbit ? 1'b1 : is_rstbit ? 1'b0 : rlo_cur;
  assign m_target_we = target_we && (e_area == `AREA_M);

  assign out_wr_en_o     = target_we && (e_area == `AREA_Q || e_area == `AREA_PQ);
  assign out_wr_idx_o    = e_index[$clog2(OutBits)-1:0];
  assign out_wr_val_o    = target_val;
  assign out_wr_direct_o = (e_area == `AREA_PQ);

  // ---------------------------------------------------------------- pipeline flow
  // Taken jump: squash decode, fetch the target. END in decode: fetch address 0.
  // END in execute: address 0 (in decode) moves on only if a scan follows; the
  // first clock of a scan finds it in execute.
  wire advance = start_i || (exec_i && !end_o && !e_stall);
  always @(*) begin
    if (!advance)        fetch_addr = d_pc_q;
    else if (jump_taken) fetch_addr = e_target;
    else if (d_is_end)   fetch_addr = {PcW{1'b0}};
    else                 fetch_addr = d_pc_q + 1'b1;
  end

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      d_pc_q    <= {PcW{1'b0}};
      e_instr_q <= 32'd0;
      e_pc_q    <= {PcW{1'b0}};
      e_valid_q <= 1'b0;
    end else begin
      d_pc_q <= fetch_addr;
      if (advance) begin
        e_instr_q <= d_instr;
        e_pc_q    <= d_pc_q;
        e_valid_q <= !jump_taken;
      end else if (!e_stall) begin
        e_valid_q <= 1'b0;               // END executed, or stopped: a bubble
      end
    end
  end

  assign exec_pc_o    = e_pc_q;
  assign exec_valid_o = e_go;

  // Reserved instruction bits and the upper index bits of narrow areas are unused.
  // verilator lint_off UNUSEDSIGNAL
  wire unused_bits = ^{e_instr_q[23:17], e_index, sp_top};
  // verilator lint_on UNUSEDSIGNAL
endmodule
`default_nettype wire
