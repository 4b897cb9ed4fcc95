`default_nettype none
`include "param_check.vh"
// A multi-core plant (spec §7, docs/multicore.md): Cores complete bit-byte CPUs, each
// with its own program, scan period, I/O and byte processor, cooperating only through
// one shared memory guarded by a hardware semaphore. Per-core ports are flattened:
// core c's field is [c*W +: W].
module plc_system #(
  parameter integer Cores       = 2,     // cores, 2..8
  parameter integer ProgWords   = 4096,  // program memory per core, instructions
  parameter integer PlanWords   = 1024,  // copy-plan entries per core
  parameter integer SharedWords = 2048,  // shared 32-bit words (per ping-pong buffer)
  parameter integer InBytes     = 16,    // binary inputs per core
  parameter integer OutBytes    = 16,    // binary outputs per core
  parameter integer InWords     = 16,    // input words per core
  parameter integer OutWords    = 16,    // output words per core
  parameter integer MarkerBytes = 256,   // marker bytes per core (M)
  parameter integer MwWords     = 256,   // data words per core (MW)
  parameter integer StatusBits  = 64     // timers and counters per core (T, C)
) (
  input  wire                              clk_i,
  input  wire                              rst_ni,
  // program and copy-plan load (while stopped): the address and data are common
  input  wire [Cores-1:0]                  prog_we_i,
  input  wire [$clog2(ProgWords)-1:0]      prog_waddr_i,
  input  wire [31:0]                       prog_wdata_i,
  input  wire [Cores-1:0]                  plan_we_i,
  input  wire [$clog2(PlanWords)-1:0]      plan_waddr_i,
  input  wire [31:0]                       plan_wdata_i,
  // configuration
  input  wire [1:0]                        protect_i,        // `PROTECTION_* (bit_isa.vh)
  input  wire [31:0]                       watchdog_limit_i,
  input  wire [Cores-1:0]                  parallel_i,
  input  wire [Cores*2-1:0]                exchange_i,
  input  wire [Cores*64-1:0]               period_i,         // 1/1000 clock each (core_seq.v)
  input  wire [Cores*($clog2(PlanWords)+1)-1:0] pre_len_i,
  input  wire [Cores*$clog2(PlanWords)-1:0]     post_base_i,
  input  wire [Cores*($clog2(PlanWords)+1)-1:0] post_len_i,
  // plant RUN: the time base starts in the first clock all cores are ready
  input  wire                              run_i,
  output wire                              ready_o,
  output reg  [63:0]                       time_o,           // clocks since the start
  output wire [Cores-1:0]                  fault_o,
  // process I/O
  input  wire [Cores*InBytes*8-1:0]        in_pins_i,
  output wire [Cores*OutBytes*8-1:0]       out_pins_o,
  input  wire [Cores*InWords*16-1:0]       in_words_i,
  output wire [Cores*OutWords*16-1:0]      out_words_o,
  // byte-side buses
  input  wire [Cores*9-1:0]                bus_addr_i,
  input  wire [Cores*32-1:0]               bus_wdata_i,
  input  wire [Cores-1:0]                  bus_we_i,
  input  wire [Cores-1:0]                  bus_re_i,
  output wire [Cores*32-1:0]               bus_rdata_o,
  output wire [Cores-1:0]                  bus_ready_o,
  output wire [Cores-1:0]                  byte_next_o,      // STATUS.NEXT per core
  // status per core
  output wire [Cores-1:0]                  scan_done_o,
  output wire [Cores*32-1:0]               scan_count_o,
  output wire [Cores*32-1:0]               scan_cycles_o,
  output wire [Cores-1:0]                  cycle_done_o,     // a postcycle ended
  output wire [Cores*32-1:0]               pre_clocks_o,
  output wire [Cores*32-1:0]               post_clocks_o,
  output wire [Cores*32-1:0]               sem_wait_o,
  output wire [Cores-1:0]                  overrun_o,
  output wire [Cores-1:0]                  copy_fail_o,
  output wire [Cores*32-1:0]               overruns_o,
  output wire [Cores*32-1:0]               skips_o,
  output wire                              locked_o,         // the semaphore
  output wire [$clog2(Cores)-1:0]          lock_owner_o,
  // observation per core (plc_core's dbg_*: what the simulation hosts trace besides
  // the ports above; no logic uses them). Core c's marker and word addresses select
  // what its dbg_m_o / dbg_mw_o show, without a clock.
  output wire [Cores*InBytes*8-1:0]        dbg_pii_o,        // I
  output wire [Cores*InBytes*8-1:0]        dbg_rise_o,       // IR
  output wire [Cores*InBytes*8-1:0]        dbg_fall_o,       // IF
  output wire [Cores*OutBytes*8-1:0]       dbg_q_rise_o,     // QR
  output wire [Cores*OutBytes*8-1:0]       dbg_q_fall_o,     // QF
  output wire [Cores*StatusBits-1:0]       dbg_timer_status_o,   // T n
  output wire [Cores*StatusBits-1:0]       dbg_counter_status_o, // C n
  input  wire [Cores*$clog2(MarkerBytes*8)-1:0] dbg_m_addr_i,
  output wire [Cores-1:0]                  dbg_m_o,
  input  wire [Cores*$clog2(MwWords)-1:0]  dbg_mw_addr_i,
  output wire [Cores*16-1:0]               dbg_mw_o
);
  localparam integer PaW = $clog2(PlanWords);
  localparam integer AW  = $clog2(SharedWords) + 1;
  localparam integer MaW = $clog2(MarkerBytes * 8);   // a core's marker bit address
  localparam integer WaW = $clog2(MwWords);           // ... and data word address

  // The toolchain builds, links and runs plants of 2..8 cores (bitbyte/plant/run.py
  // MAX_CORES); the leaves check the rest.
  `PARAM_CHECK(g_bad_cores, Cores < 2 || Cores > 8,
               "plc_system: Cores must be 2..8 (the plants bitbyte link and run build)")

  wire [Cores-1:0]      ready, lock_req, lock_release, grant, sh_we, sh_flip, sel;
  // the read strobes: for the waveforms (the banks read in every clock)
  // verilator lint_off UNUSEDSIGNAL
  wire [Cores-1:0]      sh_re;
  // verilator lint_on UNUSEDSIGNAL
  wire [Cores*AW-1:0]   sh_raddr, sh_waddr;
  wire [Cores*$clog2(Cores)-1:0] sh_rbank;
  wire                  sh_ready;
  wire [Cores*32-1:0]   sh_rdata, sh_wdata;
  reg                   running_q;

  assign ready_o = (&ready) && sh_ready;

  // Common time base: clock 0 is the first clock in which the plant runs.
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      running_q <= 1'b0;
      time_o    <= 64'd0;
    end else begin
      if (run_i && ready_o) running_q <= 1'b1;
      if (running_q) time_o <= time_o + 64'd1;
    end
  end

  hsem #(.Cores(Cores)) u_hsem (
    .clk_i     (clk_i),
    .rst_ni    (rst_ni),
    .lock_req_i(lock_req),
    .release_i (lock_release),
    .grant_o   (grant),
    .locked_o  (locked_o),
    .owner_o   (lock_owner_o)
  );

  shared_mem #(.Cores(Cores), .SharedWords(SharedWords)) u_shared_mem (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .ready_o(sh_ready),
    .raddr_i(sh_raddr),
    .rbank_i(sh_rbank),
    .rdata_o(sh_rdata),
    .we_i   (sh_we),
    .waddr_i(sh_waddr),
    .wdata_i(sh_wdata),
    .flip_i (sh_flip),
    .sel_o  (sel)
  );

  genvar c;
  generate
    for (c = 0; c < Cores; c = c + 1) begin : g_core
      plc_core #(
        .Cores      (Cores),
        .ProgWords  (ProgWords),
        .PlanWords  (PlanWords),
        .SharedWords(SharedWords),
        .InBytes    (InBytes),
        .OutBytes   (OutBytes),
        .InWords    (InWords),
        .OutWords   (OutWords),
        .MarkerBytes(MarkerBytes),
        .MwWords    (MwWords),
        .StatusBits (StatusBits)
      ) u_core (
        .clk_i           (clk_i),
        .rst_ni          (rst_ni),
        .prog_we_i       (prog_we_i[c]),
        .prog_waddr_i    (prog_waddr_i),
        .prog_wdata_i    (prog_wdata_i),
        .plan_we_i       (plan_we_i[c]),
        .plan_waddr_i    (plan_waddr_i),
        .plan_wdata_i    (plan_wdata_i),
        .parallel_i      (parallel_i[c]),
        .exchange_i      (exchange_i[c*2 +: 2]),
        .watchdog_limit_i(watchdog_limit_i),
        .period_i        (period_i[c*64 +: 64]),
        .pre_len_i       (pre_len_i[c*(PaW+1) +: PaW+1]),
        .post_base_i     (post_base_i[c*PaW +: PaW]),
        .post_len_i      (post_len_i[c*(PaW+1) +: PaW+1]),
        .protect_i       (protect_i),
        .run_i           (running_q),
        .time_i          (time_o),
        .ready_o         (ready[c]),
        .fault_o         (fault_o[c]),
        .in_pins_i       (in_pins_i[c*InBytes*8 +: InBytes*8]),
        .out_pins_o      (out_pins_o[c*OutBytes*8 +: OutBytes*8]),
        .in_words_i      (in_words_i[c*InWords*16 +: InWords*16]),
        .out_words_o     (out_words_o[c*OutWords*16 +: OutWords*16]),
        .bus_addr_i      (bus_addr_i[c*9 +: 9]),
        .bus_wdata_i     (bus_wdata_i[c*32 +: 32]),
        .bus_we_i        (bus_we_i[c]),
        .bus_re_i        (bus_re_i[c]),
        .bus_rdata_o     (bus_rdata_o[c*32 +: 32]),
        .bus_ready_o     (bus_ready_o[c]),
        .byte_next_o     (byte_next_o[c]),
        .lock_req_o      (lock_req[c]),
        .release_o       (lock_release[c]),
        .grant_i         (grant[c]),
        .sh_re_o         (sh_re[c]),
        .sh_raddr_o      (sh_raddr[c*AW +: AW]),
        .sh_rbank_o      (sh_rbank[c*$clog2(Cores) +: $clog2(Cores)]),
        .sh_rdata_i      (sh_rdata[c*32 +: 32]),
        .sh_we_o         (sh_we[c]),
        .sh_waddr_o      (sh_waddr[c*AW +: AW]),
        .sh_wdata_o      (sh_wdata[c*32 +: 32]),
        .sh_sel_i        (sel),
        .sh_posting_i    (sh_we),
        .sh_flip_o       (sh_flip[c]),
        .scan_done_o     (scan_done_o[c]),
        .scan_count_o    (scan_count_o[c*32 +: 32]),
        .scan_cycles_o   (scan_cycles_o[c*32 +: 32]),
        .cycle_done_o    (cycle_done_o[c]),
        .pre_clocks_o    (pre_clocks_o[c*32 +: 32]),
        .post_clocks_o   (post_clocks_o[c*32 +: 32]),
        .sem_wait_o      (sem_wait_o[c*32 +: 32]),
        .overrun_o       (overrun_o[c]),
        .copy_fail_o     (copy_fail_o[c]),
        .overruns_o      (overruns_o[c*32 +: 32]),
        .skips_o         (skips_o[c*32 +: 32]),
        .dbg_pii_o           (dbg_pii_o[c*InBytes*8 +: InBytes*8]),
        .dbg_rise_o          (dbg_rise_o[c*InBytes*8 +: InBytes*8]),
        .dbg_fall_o          (dbg_fall_o[c*InBytes*8 +: InBytes*8]),
        .dbg_q_rise_o        (dbg_q_rise_o[c*OutBytes*8 +: OutBytes*8]),
        .dbg_q_fall_o        (dbg_q_fall_o[c*OutBytes*8 +: OutBytes*8]),
        .dbg_timer_status_o  (dbg_timer_status_o[c*StatusBits +: StatusBits]),
        .dbg_counter_status_o(dbg_counter_status_o[c*StatusBits +: StatusBits]),
        .dbg_m_addr_i        (dbg_m_addr_i[c*MaW +: MaW]),
        .dbg_m_o             (dbg_m_o[c]),
        .dbg_mw_addr_i       (dbg_mw_addr_i[c*WaW +: WaW]),
        .dbg_mw_o            (dbg_mw_o[c*16 +: 16])
      );
    end
  endgenerate
endmodule
`default_nettype wire
