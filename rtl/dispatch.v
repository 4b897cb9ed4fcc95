`default_nettype none
`include "bit_isa.vh"
`include "param_check.vh"
// Serial-mode dispatch (paper Fig. 6/7, NEXT/GO). The bit processor fetches every
// instruction; a byte instruction reaching execute holds the pipeline and is offered
// to the byte processor (NEXT) together with the RLO and the scan number. The byte
// processor answers with DONE (the paper's GO), carrying the new RLO when the
// instruction produced one (compares). One RLO is shared, as in the paper's serial
// CPU. While a timer or counter instruction is offered, the RLO is also left in the
// instruction's enable / count-pulse bit of the status buffer (Fig. 2).
module dispatch #(
  parameter integer StatusBits = 64  // timers and counters (each)
) (
  // from / to the bit processor
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
  assign ctx_o   = {scan_i, 15'd0, rlo_i};

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
endmodule
`default_nettype wire
