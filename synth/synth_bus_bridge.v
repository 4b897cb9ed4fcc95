`default_nettype none
// SPI to byte-side bus bridge of the FPGA wrapper: commands 0x04 (write) and 0x05
// (read) become accesses of the core's bus (docs/byte-bus.md); the strobe stays high
// until the core answers ready, as the byte processor's HAL does. This is how an
// external microcontroller (the byte processor) reaches the FPGA part.
module synth_bus_bridge #(
  parameter integer AddrW = 8   // at most 24
) (
  input  wire             clk_i,
  input  wire             rst_ni,
  input  wire             wr_i,        // SPI data word for a bus write
  input  wire             rd_i,        // SPI slot for a bus read
  // verilator lint_off UNUSEDSIGNAL
  input  wire [23:0]      addr_i,       // the bus uses the low AddrW bits
  // verilator lint_on UNUSEDSIGNAL
  input  wire [31:0]      data_i,
  output reg  [AddrW-1:0] bus_addr_o,
  output reg  [31:0] bus_wdata_o,
  output reg              bus_we_o,
  output reg              bus_re_o,
  input  wire [31:0] bus_rdata_i,
  input  wire             bus_ready_i,
  output reg              rd_valid_o,
  output reg  [31:0]      rd_data_o
);
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      bus_addr_o  <= {AddrW{1'b0}};
      bus_wdata_o <= 32'd0;
      bus_we_o    <= 1'b0;
      bus_re_o    <= 1'b0;
      rd_valid_o  <= 1'b0;
      rd_data_o   <= 32'd0;
    end else begin
      // The core's ready reaches the strobes and rd_valid_o only: the read data is
      // taken in every clock of a read, the address and the write data only while no
      // access is under way (a command that comes while one waits is ignored).
      rd_valid_o <= bus_re_o && bus_ready_i;
      if (bus_re_o) rd_data_o <= bus_rdata_i;
      if (bus_we_o || bus_re_o) begin
        if (bus_ready_i) begin
          bus_we_o <= 1'b0;
          bus_re_o <= 1'b0;
        end
      end else if (wr_i) begin
        bus_addr_o  <= addr_i[AddrW-1:0];
        bus_wdata_o <= data_i[31:0];
        bus_we_o    <= 1'b1;
      end else if (rd_i) begin
        bus_addr_o <= addr_i[AddrW-1:0];
        bus_re_o   <= 1'b1;
      end
    end
  end
endmodule
`default_nettype wire
