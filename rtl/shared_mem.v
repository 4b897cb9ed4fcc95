`default_nettype none
// Shared memory of a plant (docs/multicore.md): SharedWords 32-bit words SH0.., twice
// (two buffers for ping-pong protection; the semaphore and `none` use buffer 0).
// Every core has its own synchronous read port and its own write port, so copies of
// different cores never wait for each other here: only the protection (the lock)
// orders them, and with `none` a reader can really see half of a writer's
// postcycle. Writes of different cores never hit one word: every shared word has
// exactly one writer (the linker's rule). sel_o[c] is the buffer core c published
// last (ping-pong): flip_i[c] toggles it at the end of c's postcycle.
module shared_mem #(
  parameter integer Cores       = 2,    // ports
  parameter integer SharedWords = 512   // words per buffer (a power of two)
) (
  input  wire                                clk_i,
  input  wire                                rst_ni,
  input  wire [Cores-1:0]                    re_i,
  input  wire [Cores*($clog2(SharedWords)+1)-1:0] raddr_i,  // per core {buffer, word}
  output reg  [Cores*32-1:0]                 rdata_o,       // the word read the clock before
  input  wire [Cores-1:0]                    we_i,
  input  wire [Cores*($clog2(SharedWords)+1)-1:0] waddr_i,
  input  wire [Cores*32-1:0]                 wdata_i,
  input  wire [Cores-1:0]                    flip_i,
  output reg  [Cores-1:0]                    sel_o
);
  localparam integer AW = $clog2(SharedWords) + 1;

  reg [31:0] mem [0:2*SharedWords-1];

  integer c, w;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (w = 0; w < 2 * SharedWords; w = w + 1) mem[w] <= 32'd0;
      rdata_o <= {(Cores*32){1'b0}};
      sel_o   <= {Cores{1'b0}};
    end else begin
      for (c = 0; c < Cores; c = c + 1) begin
        if (we_i[c]) mem[waddr_i[c*AW +: AW]] <= wdata_i[c*32 +: 32];
        // a read returns the word as it was before this clock's writes
        if (re_i[c]) rdata_o[c*32 +: 32] <= mem[raddr_i[c*AW +: AW]];
        if (flip_i[c]) sel_o[c] <= !sel_o[c];
      end
    end
  end
endmodule
`default_nettype wire
