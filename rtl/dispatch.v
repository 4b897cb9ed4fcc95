`default_nettype none
`include "bit_isa.vh"
`include "byte_bus.vh"
`include "param_check.vh"
// Serial-mode dispatch (paper Fig. 6/7, NEXT/GO). The bit processor fetches every
// instruction; a byte instruction reaching execute holds the pipeline and is offered
// to the byte processor (NEXT) together with the RLO and the scan number. The byte
// processor answers with DONE (the paper's GO), carrying the new RLO when the
// instruction produced one (compares). One RLO is shared, as in the paper's serial
// CPU. While a timer or counter instruction is offered, the RLO is also left in the
// instruction's enable / count-pulse bit of the status buffer (Fig. 2).
// DISPATCH_CTX's FIRST bit tells the byte processor that no byte instruction of this
// scan has completed yet, i.e. that its accumulators start from 0 (spec §3). A flag,
// not the scan number: the 16 bits of the number in the word wrap, and a program whose
// byte instructions are skipped for a multiple of 65 536 scans would look like one scan.
module dispatch #(
  parameter integer StatusBits = 64  // timers and counters (each)
) (
  input  wire                          clk_i,
  input  wire                          rst_ni,
  // from / to the bit processor
  input  wire                          latch_i,      // this clock starts a scan
  input  wire                          req_i,        // byte instruction in execute
  input  wire [31:0]                   instr_i,
  input  wire                          rlo_i,
  input  wire [15:0]                   scan_i,       // scan number (low bits)
  output wire                          done_o,       // GO: the instruction completes
  output wire                          done_rlo_o,
  output wire                          done_rlo_we_o,
  // from / to the byte-side port
  output wire                          next_o,       // STATUS.NEXT
  output wire [31:0]                   instr_o,      // DISPATCH_INSTR
  output wire [31:0]                   ctx_o,        // DISPATCH_CTX
  input  wire                          done_we_i,    // DONE written this clock
  input  wire [1:0]                    done_data_i,  // {write RLO, RLO}
  // to the timer/counter status buffer
  output wire                          ctl_we_o,
  output wire                          ctl_is_counter_o,
  output wire [$clog2(StatusBits)-1:0] ctl_idx_o,
  output wire                          ctl_val_o
);
  `PARAM_CHECK(g_bad_status_bits, StatusBits < 2 || StatusBits > 4096,
               "dispatch: StatusBits must be 2..4096 (12-bit operand index)")

  wire [7:0] op = instr_i[`ISA_OPCODE];
  // 0xB0..0xB4: SD SS SP SF, R T n; 0xB8..0xBB: CU CD, S C n, R C n
  wire is_timer   = (op >= `OP_B_SD) && (op <= `OP_B_RT);
  wire is_counter = (op >= `OP_B_CU) && (op <= `OP_B_RC);

  assign next_o  = req_i;
  assign instr_o = instr_i;
  // no DONE since the last scan latch (the latch clock itself: a DONE cannot fall in
  // it, and the firmware reads the word a clock after the dispatch begins at the
  // earliest, so a register is enough)
  reg first_q;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)      first_q <= 1'b1;
    else if (latch_i) first_q <= 1'b1;
    else if (done_o)  first_q <= 1'b0;
  end

  assign ctx_o = ({16'd0, scan_i} << `BUS_CTX_SCAN_SHIFT)
               | (first_q ? `BUS_CTX_FIRST : 32'd0) | (rlo_i ? `BUS_CTX_RLO : 32'd0);

  assign done_o        = req_i && done_we_i;
  assign done_rlo_o    = done_data_i[0];
  assign done_rlo_we_o = done_data_i[1];

  assign ctl_we_o         = req_i && (is_timer || is_counter);
  assign ctl_is_counter_o = is_counter;
  assign ctl_idx_o        = instr_i[$clog2(StatusBits)-1:0];
  assign ctl_val_o        = rlo_i;

  // verilator lint_off UNUSEDSIGNAL
  wire unused_instr = ^instr_i[23:$clog2(StatusBits)];
  // verilator lint_on UNUSEDSIGNAL

`ifdef FORMAL
  // Properties of the context word; formal/dispatch.sby proves them by k-induction.
`include "formal_past.vh"

  // The byte processor's view of a scan: every dispatched instruction ends in one DONE.
  // The shadow model counts the DONEs since the scan latched (saturating) from the
  // inputs -- a DONE written while an instruction is offered -- not from done_o, so a
  // done_o that fires without a request breaks it. FIRST is set exactly while there
  // was none, whatever the scan number does (scan_i is a free input here).
  wire f_done = req_i && done_we_i;
  reg [1:0] f_dones;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)                          f_dones <= 2'd0;
    else if (latch_i)                     f_dones <= 2'd0;
    else if (f_done && f_dones != 2'd3)   f_dones <= f_dones + 2'd1;
  end
  wire f_first = (ctx_o & `BUS_CTX_FIRST) != 32'd0;
  always @(*) if (rst_ni) assert (f_first == (f_dones == 2'd0));
  // the rest of the word: the RLO, the scan number, zeros between
  always @(*) assert (((ctx_o & `BUS_CTX_RLO) != 32'd0) == rlo_i);
  always @(*) assert ((ctx_o >> `BUS_CTX_SCAN_SHIFT) == {16'd0, scan_i});
  always @(*) assert ((ctx_o & ~(`BUS_CTX_RLO | `BUS_CTX_FIRST)
                       & ((32'd1 << `BUS_CTX_SCAN_SHIFT) - 32'd1)) == 32'd0);

  // reachable: a second dispatch of a scan (FIRST clear), and a later scan's first
  // dispatch (FIRST set again after a DONE) carrying the scan number of that DONE --
  // the case a 16-bit scan number cannot tell from the same scan. No wrap is modelled
  // (in the CPU it takes 65 536 scans); scan_i being free covers every sequence.
  reg [15:0] f_done_scan;
  reg        f_done_seen;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      f_done_scan <= 16'd0;
      f_done_seen <= 1'b0;
    end else if (f_done) begin
      f_done_scan <= scan_i;
      f_done_seen <= 1'b1;
    end
  end
  always @(posedge clk_i) if (rst_ni) cover (req_i && !f_first);
  always @(posedge clk_i)
    if (rst_ni) cover (req_i && f_first && f_done_seen && scan_i == f_done_scan);
`endif
endmodule
`default_nettype wire
