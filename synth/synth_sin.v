`default_nettype none
// Binary inputs of the FPGA wrapper: reads a chain of 74HC165 parallel-in/serial-out
// registers (the input terminals) over and over: a load pulse, then Bits shift clocks.
// The sampled image is handed to the core all at once when the last bit is in, so
// the core never sees half an update. One step every 2**DivW clocks; QH passes a
// two-flop synchroniser.
module synth_sin #(
  parameter integer Bits = 128,  // at least 2
  parameter integer DivW = 3
) (
  input  wire            clk_i,
  input  wire            rst_ni,
  output reg             load_no,   // 165 SH/LD (low: take the terminals)
  output reg             sclk_o,    // 165 CLK (rising edge shifts)
  input  wire            sdata_i,   // 165 QH, asynchronous
  output reg  [Bits-1:0] par_o      // the terminals, bit 0 first in the chain
);
  localparam integer CntW = $clog2(Bits);
  localparam integer Last = Bits - 1;

  wire sdata;
  synth_sync #(.Width(1)) u_sync (.clk_i(clk_i), .d_i(sdata_i), .q_o(sdata));

  reg [DivW-1:0] div_q;
  reg [CntW-1:0] bit_q;
  reg [Bits-2:0] sh_q;                 // the samples so far, newest on top
  wire [Bits-1:0] image = {sdata, sh_q};
  wire tick = &div_q;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      div_q   <= {DivW{1'b0}};
      bit_q   <= {CntW{1'b0}};
      sh_q    <= {(Bits-1){1'b0}};
      par_o   <= {Bits{1'b0}};
      load_no <= 1'b0;
      sclk_o  <= 1'b0;
    end else begin
      div_q <= div_q + 1'b1;
      if (tick) begin
        if (!load_no) begin
          load_no <= 1'b1;                     // image taken; QH shows bit 0
          bit_q   <= {CntW{1'b0}};
        end else if (!sclk_o) begin
          sh_q   <= image[Bits-1:1];           // sample, then shift the chain
          sclk_o <= 1'b1;
          if (bit_q == Last[CntW-1:0]) begin
            par_o   <= image;
            load_no <= 1'b0;
          end
          bit_q <= bit_q + 1'b1;
        end else begin
          sclk_o <= 1'b0;
        end
      end
    end
  end
endmodule
`default_nettype wire
