"""The FPGA wrapper's bus bridge (synth/synth_bus_bridge.v), which `make synth` places
in front of the core: an access stays on the bus until the core answers ready, the read
data is the core's in that clock, a command that comes while an access waits is ignored.
A small Icarus test bench (a simulated core with a ready that comes late); it is shown
to fail on a bridge that takes the read data a clock late."""
from __future__ import annotations

import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BRIDGE = ROOT / "synth" / "synth_bus_bridge.v"

TB = r"""
`timescale 1ns/1ps
module tb;
  reg clk = 0, rst_n = 0, wr = 0, rd = 0, ready = 0;
  reg [23:0] addr = 0; reg [31:0] data = 0, rdata = 0;
  wire [7:0] bus_addr; wire [31:0] bus_wdata, rd_data; wire we, re, rd_valid;
  synth_bus_bridge #(.AddrW(8)) dut (.clk_i(clk), .rst_ni(rst_n), .wr_i(wr), .rd_i(rd),
    .addr_i(addr), .data_i(data), .bus_addr_o(bus_addr), .bus_wdata_o(bus_wdata),
    .bus_we_o(we), .bus_re_o(re), .bus_rdata_i(rdata), .bus_ready_i(ready),
    .rd_valid_o(rd_valid), .rd_data_o(rd_data));
  always #5 clk = !clk;
  integer errors = 0;
  task check(input ok, input [8*40-1:0] what);
    if (!ok) begin errors = errors + 1; $display("FAIL %0s at %0t", what, $time); end
  endtask
  initial begin
    @(negedge clk); rst_n = 1;
    // a write: the core is not ready for two clocks
    wr = 1; addr = 24'h000042; data = 32'hCAFE0001; @(negedge clk); wr = 0;
    check(we && bus_addr == 8'h42 && bus_wdata == 32'hCAFE0001, "write on the bus");
    // a command while it waits is ignored
    rd = 1; addr = 24'h000013; @(negedge clk); rd = 0;
    check(we && !re && bus_addr == 8'h42, "write still on the bus");
    ready = 1; @(negedge clk); ready = 0;
    check(!we && !re, "write done");
    // a read: ready in its second clock, the data of that clock is taken
    rd = 1; addr = 24'h000007; @(negedge clk); rd = 0;
    check(re && bus_addr == 8'h07, "read on the bus");
    rdata = 32'h11111111; @(negedge clk);
    check(re && !rd_valid, "read waits");
    rdata = 32'h22222222; ready = 1; @(negedge clk); ready = 0; rdata = 32'h33333333;
    check(!re && rd_valid && rd_data == 32'h22222222, "read data of the ready clock");
    @(negedge clk);
    check(!rd_valid && rd_data == 32'h22222222, "rd_valid one clock");
    if (errors == 0) $display("PASS");
    $finish;
  end
endmodule
"""


def run_bench(bridge_text: str, tmp: Path) -> str:
    (tmp / "bridge.v").write_text(bridge_text)
    (tmp / "tb.v").write_text(TB)
    subprocess.run(["iverilog", "-g2012", "-o", str(tmp / "sim"), str(tmp / "tb.v"),
                    str(tmp / "bridge.v")], check=True, capture_output=True, text=True)
    return subprocess.run(["vvp", "-n", str(tmp / "sim")], capture_output=True,
                          text=True, timeout=60).stdout


def test_bridge_waits_for_ready_and_takes_that_clocks_data(tmp_path):
    out = run_bench(BRIDGE.read_text(), tmp_path)
    assert "PASS" in out and "FAIL" not in out, out


def test_bridge_bench_fails_on_a_late_read(tmp_path):
    text = BRIDGE.read_text()
    original = "if (bus_re_o) rd_data_o <= bus_rdata_i;"
    assert original in text
    out = run_bench(text.replace(original, "if (rd_valid_o) rd_data_o <= bus_rdata_i;"),
                    tmp_path)
    assert "FAIL" in out and "PASS" not in out, out
