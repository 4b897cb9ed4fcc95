"""What the cocotb test benches of tb/ share (imported inside the simulator only)."""
from __future__ import annotations

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge, Timer

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


async def offer(dut, wr=None, rd=False, **inputs):
    """One clock of a channel (cond_ff, cond_queue): offer a write of `wr` (None: no
    write) and/or a read, with the other named inputs set; return (write taken, value
    read or None), sampled before the clock edge."""
    dut.wr_req_i.value = int(wr is not None)
    dut.wr_data_i.value = int(wr or 0)
    dut.rd_req_i.value = int(rd)
    for name, value in inputs.items():
        getattr(dut, name).value = value
    await Timer(1, unit="ns")
    taken = wr is not None and int(dut.wr_ready_o.value)
    got = int(dut.rd_data_o.value) if rd and int(dut.rd_ready_o.value) else None
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    return taken, got
