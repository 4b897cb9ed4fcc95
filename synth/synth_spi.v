`default_nettype none
// SPI slave of the FPGA wrapper (mode 0, MSB first, 32-bit words), oversampled on
// the core clock through two-flop synchronisers: SCK at most clk/8.
// A frame (CS low) starts with a header word {cmd[7:0], addr[23:0]}; each following
// word is a write (wr_o with cmd, addr, data), and the address counts up after it.
// Before every word slot (after the header and after each word) rd_o asks for the
// word to send back at the slot's address; rd_valid_i with rd_data_i loads it, and it
// leaves on MISO during the slot. The master leaves a few clocks between words.
module synth_spi (
  input  wire        clk_i,
  input  wire        rst_ni,
  input  wire        sck_i,      // asynchronous pins
  input  wire        cs_ni,
  input  wire        mosi_i,
  output wire        miso_o,
  output reg         wr_o,       // a data word arrived
  output reg         rd_o,       // a word slot begins: supply rd_data_i
  output reg  [7:0]  cmd_o,
  output reg  [23:0] addr_o,     // wr_o: the word's address; rd_o: the slot's
  output reg  [31:0] data_o,
  input  wire        rd_valid_i,
  input  wire [31:0] rd_data_i
);
  wire sck, cs_n, mosi;
  synth_sync #(.Width(3)) u_sync (
    .clk_i(clk_i), .d_i({sck_i, cs_ni, mosi_i}), .q_o({sck, cs_n, mosi}));

  reg        sck_prev_q;
  reg        header_q;           // the header word is in
  reg [4:0]  bit_q;
  reg [30:0] in_q;
  reg [31:0] out_q;
  wire       rise = sck && !sck_prev_q && !cs_n;
  wire [31:0] word = {in_q, mosi};
  assign miso_o = out_q[31];

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sck_prev_q <= 1'b0;
      header_q   <= 1'b0;
      bit_q      <= 5'd0;
      in_q       <= 31'd0;
      out_q      <= 32'd0;
      wr_o       <= 1'b0;
      rd_o       <= 1'b0;
      cmd_o      <= 8'd0;
      addr_o     <= 24'd0;
      data_o     <= 32'd0;
    end else begin
      sck_prev_q <= sck;
      wr_o       <= 1'b0;
      rd_o       <= wr_o;         // the slot after a data word, at the next address
      if (rd_valid_i) out_q <= rd_data_i;
      if (cs_n) begin
        header_q <= 1'b0;
        bit_q    <= 5'd0;
      end else if (rise) begin
        in_q  <= word[30:0];
        out_q <= {out_q[30:0], 1'b0};
        bit_q <= bit_q + 5'd1;
        if (bit_q == 5'd31) begin
          if (!header_q) begin
            rd_o     <= 1'b1;       // the first slot, at the header's address
            header_q <= 1'b1;
            cmd_o    <= word[31:24];
            addr_o   <= word[23:0];
          end else begin
            wr_o   <= 1'b1;
            data_o <= word;
          end
        end
      end
      // After a data word, the next slot is at the next address.
      if (wr_o) addr_o <= addr_o + 24'd1;
    end
  end
endmodule
`default_nettype wire
