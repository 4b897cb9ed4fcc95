"""What the cocotb test benches of tb/ share (imported inside the simulator only)."""
from __future__ import annotations

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

PERIOD_NS = 10


async def start_in_reset(dut, *zeroed, **values) -> None:
    """Start the clock, hold rst_ni low for one clock with the inputs `zeroed` at 0 and
    the named inputs at `values`, and return at a falling edge with reset released."""
    cocotb.start_soon(Clock(dut.clk_i, PERIOD_NS, unit="ns").start())
    dut.rst_ni.value = 0
    for sig in zeroed:
        sig.value = 0
    for name, value in values.items():
        getattr(dut, name).value = value
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.rst_ni.value = 1
