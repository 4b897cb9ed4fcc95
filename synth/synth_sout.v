`default_nettype none
// Binary outputs of the FPGA wrapper: writes a chain of 74HC595 serial-in/parallel-
// out registers (the output terminals) over and over: Bits shift clocks, then a latch
// pulse, so every output terminal changes in the same instant.
module synth_sout #(
  parameter integer Bits = 128,  // at least 2
  parameter integer DivW = 3
) (
  input  wire            clk_i,
  input  wire            rst_ni,
  input  wire [Bits-1:0] par_i,     // the terminals; bit Bits-1 leaves first
  output reg             sclk_o,    // 595 SRCLK (rising edge shifts)
  output reg             rclk_o,    // 595 RCLK (rising edge updates the terminals)
  output wire            sdata_o    // 595 SER
);
  localparam integer CntW = $clog2(Bits + 1);

  reg [DivW-1:0] div_q;
  reg [CntW-1:0] bit_q;
  reg [Bits-1:0] sh_q;
  wire tick = &div_q;
  assign sdata_o = sh_q[Bits-1];

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      div_q  <= {DivW{1'b0}};
      bit_q  <= {CntW{1'b0}};
      sh_q   <= {Bits{1'b0}};
      sclk_o <= 1'b0;
      rclk_o <= 1'b0;
    end else begin
      div_q <= div_q + 1'b1;
      if (tick) begin
        if (rclk_o) begin
          rclk_o <= 1'b0;
        end else if (bit_q == {CntW{1'b0}}) begin
          sh_q  <= par_i;                       // take the image, first bit on SER
          bit_q <= Bits[CntW-1:0];
        end else if (!sclk_o) begin
          sclk_o <= 1'b1;
        end else begin
          sclk_o <= 1'b0;
          sh_q   <= {sh_q[Bits-2:0], 1'b0};
          bit_q  <= bit_q - 1'b1;
          if (bit_q == {{(CntW-1){1'b0}}, 1'b1}) rclk_o <= 1'b1;
        end
      end
    end
  end
endmodule
`default_nettype wire
