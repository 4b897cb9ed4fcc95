`default_nettype none
`include "param_check.vh"
`include "bit_isa.vh"
// One core of a multi-core plant (docs/multicore.md): a complete bit-byte CPU, its
// word markers MW in a RAM the byte processor reaches over the bus (bus addresses
// 0x100 + n, so that the copy engine can reach them too), and the core sequencer
// (periods, precycle / postcycle copies, lock handling).
module plc_core #(
  parameter integer Cores       = 2,     // cores of the plant
  parameter integer ProgWords   = 4096,  // program memory, instructions
  parameter integer PlanWords   = 1024,  // copy-plan entries
  parameter integer SharedWords = 512,   // shared words per buffer
  parameter integer InBytes     = 16,    // binary inputs I 0.0 .. InBytes-1.7
  parameter integer OutBytes    = 16,    // binary outputs Q 0.0 .. OutBytes-1.7
  parameter integer MarkerBytes = 256,   // M 0.0 .. MarkerBytes-1.7
  parameter integer MwWords     = 256,   // MW 0 .. MwWords-1
  parameter integer InWords     = 16,    // IW n
  parameter integer OutWords    = 16,    // QW n
  parameter integer StatusBits  = 64     // T n, C n
) (
  input  wire                          clk_i,
  input  wire                          rst_ni,
  // program and copy-plan load (while stopped)
  input  wire                          prog_we_i,
  input  wire [$clog2(ProgWords)-1:0]  prog_waddr_i,
  input  wire [31:0]                   prog_wdata_i,
  input  wire                          plan_we_i,
  input  wire [$clog2(PlanWords)-1:0]  plan_waddr_i,
  input  wire [31:0]                   plan_wdata_i,
  // configuration
  input  wire                          parallel_i,
  input  wire [1:0]                    exchange_i,
  input  wire [31:0]                   watchdog_limit_i,
  input  wire [63:0]                   period_i,     // 1/1000 clock (core_seq.v)
  input  wire [$clog2(PlanWords):0]    pre_len_i,
  input  wire [$clog2(PlanWords)-1:0]  post_base_i,
  input  wire [$clog2(PlanWords):0]    post_len_i,
  input  wire [1:0]                    protect_i,
  // plant
  input  wire                          run_i,
  input  wire [63:0]                   time_i,
  output wire                          ready_o,       // memories cleared, idle
  output wire                          fault_o,
  // process I/O
  input  wire [InBytes*8-1:0]          in_pins_i,
  output wire [OutBytes*8-1:0]         out_pins_o,
  input  wire [InWords*16-1:0]         in_words_i,
  output wire [OutWords*16-1:0]        out_words_o,
  // byte-side bus: bit 8 set selects MW (docs/byte-bus.md)
  input  wire [8:0]                    bus_addr_i,
  input  wire [31:0]                   bus_wdata_i,
  input  wire                          bus_we_i,
  input  wire                          bus_re_i,
  output wire [31:0]                   bus_rdata_o,
  output wire                          bus_ready_o,
  output wire                          byte_next_o,   // STATUS.NEXT: a dispatch / a latch
  // lock and shared memory
  output wire                          lock_req_o,
  output wire                          release_o,
  input  wire                          grant_i,
  output wire                          sh_re_o,
  output wire [$clog2(SharedWords):0]  sh_raddr_o,
  output wire [$clog2(Cores)-1:0]      sh_rbank_o,
  input  wire [31:0]                   sh_rdata_i,
  output wire                          sh_we_o,
  output wire [$clog2(SharedWords):0]  sh_waddr_o,
  output wire [31:0]                   sh_wdata_o,
  input  wire [Cores-1:0]              sh_sel_i,
  input  wire [Cores-1:0]              sh_posting_i,  // which cores write shared memory now
  output wire                          sh_flip_o,
  // status
  output wire                          scan_done_o,
  output wire [31:0]                   scan_count_o,
  output wire [31:0]                   scan_cycles_o,
  output wire                          cycle_done_o,
  output wire [31:0]                   pre_clocks_o,
  output wire [31:0]                   post_clocks_o,
  output wire [31:0]                   sem_wait_o,
  output wire                          overrun_o,
  output wire                          copy_fail_o,
  output wire [31:0]                   overruns_o,
  output wire [31:0]                   skips_o,
  // observation (dbg_*, as bitbyte_cpu's): no logic uses them
  output wire [InBytes*8-1:0]          dbg_pii_o,     // I, IR, IF of the last latch
  output wire [InBytes*8-1:0]          dbg_rise_o,
  output wire [InBytes*8-1:0]          dbg_fall_o,
  output wire [OutBytes*8-1:0]         dbg_q_rise_o,
  output wire [OutBytes*8-1:0]         dbg_q_fall_o,
  output wire [StatusBits-1:0]         dbg_timer_status_o,   // T n
  output wire [StatusBits-1:0]         dbg_counter_status_o, // C n
  input  wire [$clog2(MarkerBytes*8)-1:0] dbg_m_addr_i,   // M bit to look at ...
  output wire                          dbg_m_o,       // ... its value now, without a clock
  input  wire [$clog2(MwWords)-1:0]    dbg_mw_addr_i, // MW word to look at ...
  output wire [15:0]                   dbg_mw_o       // ... its value now, without a clock
);
  localparam integer MarkerBits = MarkerBytes * 8;
  localparam integer WaW        = $clog2(MwWords);

  // MW n is bus address 0x100 + n of a 9-bit bus: 8 bits of word number.
  `PARAM_CHECK(g_bad_mw_words, MwWords < 2 || MwWords > 256,
               "plc_core: MwWords must be 2..256 (bus addresses 0x100 + n; 9-bit bus)")

  wire        cpu_run, cpu_ready, copy_en;
  wire        m_we, m_wdata, m_rdata;
  wire [$clog2(MarkerBits)-1:0] m_addr;
  wire        w_we;
  wire [WaW-1:0] w_addr;
  wire [15:0] w_wdata, w_rdata;
  wire [31:0] cpu_rdata;
  wire        cpu_bus_ready;
  // for the waveforms, not needed by the plant
  // verilator lint_off UNUSEDSIGNAL
  wire [31:0] scan_cycles_max, stalls_bit, stalls_byte, queue_overflows, queue_underflows;
  // verilator lint_on UNUSEDSIGNAL

  // ---------------------------------------------------------------- MW word RAM
  // Synchronous, so a bus read takes two clocks (the first answers "not ready");
  // cleared after reset like the marker RAM. Outside the copies the bus owns it.
  reg  [WaW:0]   clear_q;              // MwWords when done
  wire           clearing = !clear_q[WaW];
  wire           bus_mw   = bus_addr_i[8];
  reg            mw_rd_pending_q;      // the last clock started this MW read
  wire           bus_mw_we = bus_mw && bus_we_i && !copy_en;
  wire [WaW-1:0] bus_w_addr = bus_addr_i[WaW-1:0];

  sync_ram #(.Words(MwWords), .Width(16)) u_mw_ram (
    .clk_i  (clk_i),
    .we_i   (clearing || (copy_en ? w_we : bus_mw_we)),
    .waddr_i(clearing ? clear_q[WaW-1:0] : copy_en ? w_addr : bus_w_addr),
    .wdata_i(clearing ? 16'd0 : copy_en ? w_wdata : bus_wdata_i[15:0]),
    .re_i   (1'b1),
    .raddr_i(copy_en ? w_addr : bus_w_addr),
    .rdata_o(w_rdata),
    .peek_addr_i(dbg_mw_addr_i),
    .peek_data_o(dbg_mw_o)
  );

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      clear_q         <= {(WaW+1){1'b0}};
      mw_rd_pending_q <= 1'b0;
    end else begin
      if (clearing) clear_q <= clear_q + 1'b1;
      mw_rd_pending_q <= bus_mw && bus_re_i && !copy_en && !mw_rd_pending_q;
    end
  end

  assign bus_rdata_o = bus_mw ? {16'd0, w_rdata} : cpu_rdata;
  assign bus_ready_o = bus_mw ? (bus_we_i ? !copy_en : mw_rd_pending_q) : cpu_bus_ready;
  assign ready_o     = cpu_ready && !clearing;

  // ---------------------------------------------------------------- the CPU
  // The block status port (bitbyte run --status): the plant hosts do not read it.
  wire                         ret_valid, ret_opnd, ret_rlo;
  wire [$clog2(ProgWords)-1:0] ret_pc;
  // verilator lint_off UNUSEDSIGNAL
  wire unused_ret = ^{ret_valid, ret_pc, ret_opnd, ret_rlo};
  // verilator lint_on UNUSEDSIGNAL

  bitbyte_cpu #(
    .ProgWords  (ProgWords),
    .InBytes    (InBytes),
    .OutBytes   (OutBytes),
    .MarkerBytes(MarkerBytes),
    .StatusBits (StatusBits),
    .InWords    (InWords),
    .OutWords   (OutWords),
    // a plant core runs serial or parallel (spec §7), never free: the handshake
    // flip-flops and the queues, no marker area (its block RAMs would idle)
    .Exchanges  (3)
  ) u_cpu (
    .clk_i                (clk_i),
    .rst_ni               (rst_ni),
    .prog_we_i            (prog_we_i),
    .prog_waddr_i         (prog_waddr_i),
    .prog_wdata_i         (prog_wdata_i),
    .prog_ext_wdata_i     ({`LUT_EXT_BITS{1'b0}}),  // a plant core is scalar
    .run_i                (cpu_run),
    .time_start_i         (run_i),                // timers on plant time
    .parallel_i           (parallel_i),
    .free_i               (1'b0),
    .marker_write_buffer_i(1'b0),
    .exchange_i           (exchange_i),
    .watchdog_limit_i     (watchdog_limit_i),
    .ready_o              (cpu_ready),
    .fault_o              (fault_o),
    .scan_done_o          (scan_done_o),
    .scan_count_o         (scan_count_o),
    .scan_cycles_o        (scan_cycles_o),
    .scan_cycles_max_o    (scan_cycles_max),
    .in_pins_i            (in_pins_i),
    .out_pins_o           (out_pins_o),
    .in_words_i           (in_words_i),
    .out_words_o          (out_words_o),
    .bus_addr_i           (bus_addr_i[7:0]),
    .bus_wdata_i          (bus_wdata_i),
    .bus_we_i             (bus_we_i && !bus_mw),
    .bus_re_i             (bus_re_i && !bus_mw),
    .bus_rdata_o          (cpu_rdata),
    .bus_ready_o          (cpu_bus_ready),
    .stalls_bit_o         (stalls_bit),
    .stalls_byte_o        (stalls_byte),
    .mcopy_en_i           (copy_en),
    .mcopy_we_i           (m_we),
    .mcopy_addr_i         (m_addr),
    .mcopy_wdata_i        (m_wdata),
    .mcopy_rdata_o        (m_rdata),
    .byte_next_o          (byte_next_o),
    .dbg_pii_o            (dbg_pii_o),
    .dbg_rise_o           (dbg_rise_o),
    .dbg_fall_o           (dbg_fall_o),
    .dbg_q_rise_o         (dbg_q_rise_o),
    .dbg_q_fall_o         (dbg_q_fall_o),
    .dbg_timer_status_o   (dbg_timer_status_o),
    .dbg_counter_status_o (dbg_counter_status_o),
    .dbg_queue_overflows_o (queue_overflows),
    .dbg_queue_underflows_o(queue_underflows),
    .dbg_m_addr_i         (dbg_m_addr_i),
    .dbg_m_o              (dbg_m_o),
    .dbg_ret_valid_o      (ret_valid),
    .dbg_ret_pc_o         (ret_pc),
    .dbg_ret_opnd_o       (ret_opnd),
    .dbg_rlo_o            (ret_rlo)
  );

  // ---------------------------------------------------------------- the sequencer
  core_seq #(
    .Cores      (Cores),
    .PlanWords  (PlanWords),
    .SharedWords(SharedWords),
    .MarkerBits (MarkerBits),
    .MwWords    (MwWords)
  ) u_seq (
    .clk_i            (clk_i),
    .rst_ni           (rst_ni),
    .plan_we_i        (plan_we_i),
    .plan_waddr_i     (plan_waddr_i),
    .plan_wdata_i     (plan_wdata_i),
    .period_i         (period_i),
    .pre_len_i        (pre_len_i),
    .post_base_i      (post_base_i),
    .post_len_i       (post_len_i),
    .protect_i        (protect_i),
    .run_i            (run_i),
    .time_i           (time_i),
    .cpu_run_o        (cpu_run),
    .cpu_ready_i      (cpu_ready),
    .cpu_scan_done_i  (scan_done_o),
    .cpu_scan_cycles_i(scan_cycles_o),
    .lock_req_o       (lock_req_o),
    .release_o        (release_o),
    .grant_i          (grant_i),
    .sh_re_o          (sh_re_o),
    .sh_raddr_o       (sh_raddr_o),
    .sh_rbank_o       (sh_rbank_o),
    .sh_rdata_i       (sh_rdata_i),
    .sh_we_o          (sh_we_o),
    .sh_waddr_o       (sh_waddr_o),
    .sh_wdata_o       (sh_wdata_o),
    .sh_sel_i         (sh_sel_i),
    .sh_posting_i     (sh_posting_i),
    .sh_flip_o        (sh_flip_o),
    .copy_en_o        (copy_en),
    .m_we_o           (m_we),
    .m_addr_o         (m_addr),
    .m_wdata_o        (m_wdata),
    .m_rdata_i        (m_rdata),
    .w_we_o           (w_we),
    .w_addr_o         (w_addr),
    .w_wdata_o        (w_wdata),
    .w_rdata_i        (w_rdata),
    .cycle_done_o     (cycle_done_o),
    .pre_clocks_o     (pre_clocks_o),
    .post_clocks_o    (post_clocks_o),
    .sem_wait_o       (sem_wait_o),
    .overrun_o        (overrun_o),
    .copy_fail_o      (copy_fail_o),
    .overruns_o       (overruns_o),
    .skips_o          (skips_o)
  );
endmodule
`default_nettype wire
