`default_nettype none
`include "param_check.vh"
// One write port and one synchronous read port: the shape of an FPGA block RAM, so
// that Yosys maps program and marker memory onto BRAM instead of flip-flops.
// The peek port is a look at one word without a clock, for the simulation hosts'
// observation ports (dbg_*); no logic uses it, and where its output is left open (as
// the synthesis wrapper leaves dbg_* open) Yosys removes it and the RAM stays a BRAM.
// A read of the address written in the same clock returns the old word; the bit
// processor forwards around that itself. re_i = 0 keeps the last word read (the block
// RAM's read enable; the bit processor's decode stage holds its word with it).
module sync_ram #(
  parameter integer Words = 4096,  // number of words (any; a power of two fills a BRAM)
  parameter integer Width = 32     // bits per word
) (
  input  wire                     clk_i,
  input  wire                     we_i,
  input  wire [$clog2(Words)-1:0] waddr_i,
  input  wire [Width-1:0]         wdata_i,
  input  wire                     re_i,     // read: 0 holds rdata_o (a block RAM's read enable)
  input  wire [$clog2(Words)-1:0] raddr_i,
  output reg  [Width-1:0]         rdata_o,
  input  wire [$clog2(Words)-1:0] peek_addr_i,
  output wire [Width-1:0]         peek_data_o
);
  `PARAM_CHECK(g_bad_words, Words < 2,
               "sync_ram: Words must be at least 2 (an address needs a bit)")
  `PARAM_CHECK(g_bad_width, Width < 1, "sync_ram: Width must be at least 1")

  // no_rw_check: a read of the word written in the same clock may return either
  // value (the users never depend on it: the program is written while stopped, the
  // marker RAM's collisions are forwarded by bit_proc), so Yosys adds no collision
  // logic in front of the read port (it was on the ECP5 critical path).
  (* no_rw_check *)
  reg [Width-1:0] mem [0:Words-1];

  always @(posedge clk_i) begin
    if (we_i) mem[waddr_i] <= wdata_i;
    if (re_i) rdata_o <= mem[raddr_i];
  end
  assign peek_data_o = mem[peek_addr_i];
endmodule
`default_nettype wire
