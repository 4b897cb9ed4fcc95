`default_nettype none
`include "param_check.vh"
`include "byte_bus.vh"
// Forcing (docs/byte-bus.md, FORCE_*): the I/O units' force table, as S7 engineers
// use it to test wiring and programs. A forced input is what the CPU reads at that
// pin (the PII latches it, edges follow it, a direct PI read sees it); a forced output
// is what the pin shows whatever the program writes (a watchdog fault still takes
// every output to 0).
//
// The table is written over the byte bus (write-only: a host keeps its own copy, and
// the byte bus's read multiplexer stays as short as it is) into a pending copy, which
// takes effect at a scan boundary: at the PIO update (END) the pending table becomes
// active, so a change written during scan k shows on the outputs from scan k's PIO
// update and is latched by scan k+1. Before RUN the pending table is active at once
// (a host sets the table for scan 0 there). ForceBits sets how many of the lowest
// pins can be forced (a small FPGA build forces fewer: a bit costs four flip-flops).
module force_table #(
  parameter integer InBits    = 128,
  parameter integer OutBits   = 128,
  parameter integer ForceBits = 128  // the pins 0..ForceBits-1 of each side can be forced
) (
  input  wire               clk_i,
  input  wire               rst_ni,
  input  wire [7:0]         bus_addr_i,
  input  wire [31:0]        bus_wdata_i,
  input  wire               bus_we_i,
  input  wire               run_i,       // 0: not running, the table applies at once
  input  wire               swap_i,      // END's PIO update (not REFRESH Q's): pending -> active
  input  wire               fault_i,     // watchdog fault: forced outputs drop too
  input  wire [InBits-1:0]  in_pins_i,   // the pins as wired
  input  wire [OutBits-1:0] out_pins_i,  // the output unit's pins
  output wire [InBits-1:0]  in_pins_o,   // the pins as the CPU sees them
  output wire [OutBits-1:0] out_pins_o   // the pins as driven
);
  `PARAM_CHECK(g_bad_force_bits, ForceBits < 1 || ForceBits > 128 || ForceBits > InBits ||
               ForceBits > OutBits,
               "force_table: ForceBits must be 1..128 and at most InBits and OutBits (FORCE_* are four registers each)")

  // the four windows (four registers each, register n holds pins 32n+31..32n)
  localparam [7:0] InMaskAddr  = `BUS_FORCE_IN_MASK;
  localparam [7:0] InValAddr   = `BUS_FORCE_IN_VAL;
  localparam [7:0] OutMaskAddr = `BUS_FORCE_OUT_MASK;
  localparam [7:0] OutValAddr  = `BUS_FORCE_OUT_VAL;
  wire we_in_mask  = bus_we_i && bus_addr_i[7:2] == InMaskAddr[7:2];
  wire we_in_val   = bus_we_i && bus_addr_i[7:2] == InValAddr[7:2];
  wire we_out_mask = bus_we_i && bus_addr_i[7:2] == OutMaskAddr[7:2];
  wire we_out_val  = bus_we_i && bus_addr_i[7:2] == OutValAddr[7:2];

  // v with register n's pins (32n+31..32n, those below ForceBits) taken from w
  function automatic [ForceBits-1:0] put(input [ForceBits-1:0] v, input [1:0] n,
                                         input [31:0] w);
    integer b;
    begin
      put = v;
      for (b = 0; b < ForceBits; b = b + 1)
        if (b[6:5] == n) put[b] = w[b[4:0]];
    end
  endfunction

  reg  [ForceBits-1:0] pend_in_mask_q, pend_in_val_q, pend_out_mask_q, pend_out_val_q;
  reg  [ForceBits-1:0] in_mask_q, in_val_q, out_mask_q, out_val_q;
  wire [ForceBits-1:0] pend_in_mask_d  = we_in_mask  ? put(pend_in_mask_q, bus_addr_i[1:0], bus_wdata_i) : pend_in_mask_q;
  wire [ForceBits-1:0] pend_in_val_d   = we_in_val   ? put(pend_in_val_q, bus_addr_i[1:0], bus_wdata_i) : pend_in_val_q;
  wire [ForceBits-1:0] pend_out_mask_d = we_out_mask ? put(pend_out_mask_q, bus_addr_i[1:0], bus_wdata_i) : pend_out_mask_q;
  wire [ForceBits-1:0] pend_out_val_d  = we_out_val  ? put(pend_out_val_q, bus_addr_i[1:0], bus_wdata_i) : pend_out_val_q;
  wire                 take            = swap_i || !run_i;   // a write in this clock counts too

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pend_in_mask_q  <= {ForceBits{1'b0}};
      pend_in_val_q   <= {ForceBits{1'b0}};
      pend_out_mask_q <= {ForceBits{1'b0}};
      pend_out_val_q  <= {ForceBits{1'b0}};
      in_mask_q       <= {ForceBits{1'b0}};
      in_val_q        <= {ForceBits{1'b0}};
      out_mask_q      <= {ForceBits{1'b0}};
      out_val_q       <= {ForceBits{1'b0}};
    end else begin
      pend_in_mask_q  <= pend_in_mask_d;
      pend_in_val_q   <= pend_in_val_d;
      pend_out_mask_q <= pend_out_mask_d;
      pend_out_val_q  <= pend_out_val_d;
      if (take) begin
        in_mask_q  <= pend_in_mask_d;
        in_val_q   <= pend_in_val_d;
        out_mask_q <= pend_out_mask_d;
        out_val_q  <= pend_out_val_d;
      end
    end
  end

  // the table covers the lowest ForceBits pins; the others pass
  wire [InBits-1:0]  in_mask, in_val;
  wire [OutBits-1:0] out_mask, out_val;
  assign in_mask[ForceBits-1:0]  = in_mask_q;
  assign in_val[ForceBits-1:0]   = in_val_q;
  assign out_mask[ForceBits-1:0] = out_mask_q;
  assign out_val[ForceBits-1:0]  = out_val_q;
  if (InBits > ForceBits) begin : g_in_rest
    assign in_mask[InBits-1:ForceBits] = {(InBits - ForceBits){1'b0}};
    assign in_val[InBits-1:ForceBits]  = {(InBits - ForceBits){1'b0}};
  end
  if (OutBits > ForceBits) begin : g_out_rest
    assign out_mask[OutBits-1:ForceBits] = {(OutBits - ForceBits){1'b0}};
    assign out_val[OutBits-1:ForceBits]  = {(OutBits - ForceBits){1'b0}};
  end
  assign in_pins_o  = (in_pins_i & ~in_mask) | (in_val & in_mask);
  assign out_pins_o = fault_i ? {OutBits{1'b0}} : (out_pins_i & ~out_mask) | (out_val & out_mask);
endmodule
`default_nettype wire
