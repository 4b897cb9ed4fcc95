`default_nettype none
`include "param_check.vh"
// Shared memory of a plant (docs/multicore.md): SharedWords 32-bit words SH0.., twice
// (two buffers for ping-pong protection; the semaphore and `none` use buffer 0).
//
// Every shared word has exactly one writer (the linker's rule), so the memory is
// banked by writer: core w writes only bank w, through its own write port. Every core
// also has its own read port into every bank (one synchronous block RAM per writer and
// reader pair, Cores^2 in all) and names the bank with each read: the word's writer,
// which its copy plan carries. So copies of different cores never wait for each other
// here, only the protection orders them (with `none` a reader really can see half of
// a postcycle), and everything maps onto plain 1-write 1-read block RAMs.
// After reset the banks are cleared (2 * SharedWords clocks; ready_o), so that a word
// nobody has published yet reads 0. sel_o[c] is the buffer core c published last
// (ping-pong); flip_i[c] toggles it at the end of c's postcycle.
module shared_mem #(
  parameter integer Cores       = 2,    // cores: writers and readers (at least 2)
  parameter integer SharedWords = 512   // words per buffer (a power of two)
) (
  input  wire                                     clk_i,
  input  wire                                     rst_ni,
  output wire                                     ready_o,   // cleared after reset
  input  wire [Cores*($clog2(SharedWords)+1)-1:0] raddr_i,   // per core {buffer, word}
  input  wire [Cores*$clog2(Cores)-1:0]           rbank_i,   // per core: the word's writer
  output wire [Cores*32-1:0]                      rdata_o,   // the word read the clock before
  input  wire [Cores-1:0]                         we_i,
  input  wire [Cores*($clog2(SharedWords)+1)-1:0] waddr_i,
  input  wire [Cores*32-1:0]                      wdata_i,
  input  wire [Cores-1:0]                         flip_i,
  output reg  [Cores-1:0]                         sel_o
);
  localparam integer AW  = $clog2(SharedWords) + 1;
  localparam integer IdW = $clog2(Cores);

  `PARAM_CHECK(g_bad_cores, Cores < 2,
               "shared_mem: Cores must be at least 2 (a bank number needs a bit)")
  `PARAM_CHECK(g_bad_shared_words, SharedWords < 1 || (SharedWords & (SharedWords - 1)) != 0,
               "shared_mem: SharedWords must be a power of two (buffer bit above the word)")

  reg  [AW:0]            clear_q;             // 2 * SharedWords when done
  wire                   clearing = !clear_q[AW];
  reg  [Cores*IdW-1:0]   rbank_q;             // the bank each read port read last clock
  wire [Cores*Cores*32-1:0] bank_rdata;      // [(w*Cores + r)*32 +: 32]

  assign ready_o = !clearing;

  genvar w, r;
  generate
    for (w = 0; w < Cores; w = w + 1) begin : g_writer
      for (r = 0; r < Cores; r = r + 1) begin : g_reader
        // the peek port is left open (no cell of it is left to mutate or to synthesize):
        // the hosts see shared words through the cores
        // verilator lint_off PINCONNECTEMPTY
        sync_ram #(.Words(2 * SharedWords), .Width(32)) u_bank (
          .clk_i  (clk_i),
          .we_i   (clearing || we_i[w]),
          .waddr_i(clearing ? clear_q[AW-1:0] : waddr_i[w*AW +: AW]),
          .wdata_i(clearing ? 32'd0 : wdata_i[w*32 +: 32]),
          .re_i   (1'b1),
          .raddr_i(raddr_i[r*AW +: AW]),
          .rdata_o(bank_rdata[(w*Cores + r)*32 +: 32]),
          .peek_addr_i(),
          .peek_data_o()
        );
        // verilator lint_on PINCONNECTEMPTY
      end
    end
    for (r = 0; r < Cores; r = r + 1) begin : g_read
      assign rdata_o[r*32 +: 32] =
        bank_rdata[({{(32-IdW){1'b0}}, rbank_q[r*IdW +: IdW]} * Cores + r) * 32 +: 32];
    end
  endgenerate

  integer c;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      clear_q <= {(AW+1){1'b0}};
      rbank_q <= {(Cores*IdW){1'b0}};
      sel_o   <= {Cores{1'b0}};
    end else begin
      if (clearing) clear_q <= clear_q + 1'b1;
      rbank_q <= rbank_i;
      for (c = 0; c < Cores; c = c + 1)
        if (flip_i[c]) sel_o[c] <= !sel_o[c];
    end
  end
endmodule
`default_nettype wire
