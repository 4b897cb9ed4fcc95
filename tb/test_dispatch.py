"""Serial dispatch (paper Fig. 6/7): NEXT while a byte instruction waits, DONE (GO)
with the RLO, enable/pulse bits for timer and counter instructions (Fig. 2), and
DISPATCH_CTX: RLO, FIRST (no DONE since the scan latched), the scan number."""
from __future__ import annotations

import cocotb
import pytest
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from simrun import SIMULATORS, run_cocotb
from tbutil import start_in_reset

# DISPATCH_CTX (docs/byte-bus.md): bit 0 RLO, bit 1 FIRST, bits 31..16 the scan number
RLO, FIRST = 1, 2


async def settle():
    await Timer(1, unit="ns")


async def reset(dut):
    await start_in_reset(dut, dut.req_i, dut.instr_i, dut.rlo_i, dut.scan_i, dut.latch_i,
                         dut.done_we_i, dut.done_data_i)


async def clock(dut):
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.latch_i.value, dut.done_we_i.value = 0, 0


@cocotb.test()
async def next_done_and_ctx(dut):
    await reset(dut)
    await settle()
    assert int(dut.next_o.value) == 0 and int(dut.done_o.value) == 0
    dut.req_i.value, dut.instr_i.value, dut.rlo_i.value, dut.scan_i.value = 1, 0x90000000, 1, 7
    await settle()
    assert int(dut.next_o.value) == 1 and int(dut.ctx_o.value) == (7 << 16) | FIRST | RLO
    assert int(dut.instr_o.value) == 0x90000000
    assert int(dut.ctl_we_o.value) == 0          # a compare is no timer/counter
    assert int(dut.done_o.value) == 0            # waiting: no DONE before DONE is written
    dut.done_we_i.value, dut.done_data_i.value = 1, 0b10
    await settle()
    assert (int(dut.done_o.value), int(dut.done_rlo_o.value),
            int(dut.done_rlo_we_o.value)) == (1, 0, 1)
    dut.req_i.value = 0                          # DONE without a request: ignored
    await settle()
    assert int(dut.done_o.value) == 0


@cocotb.test()
async def first_is_no_done_since_the_latch(dut):
    """FIRST: set by the latch, cleared by a DONE, whatever the scan number does (it
    wraps: 16 bits), so a scan 65 536 later is still a new one."""
    await reset(dut)
    dut.req_i.value, dut.scan_i.value = 1, 3
    await settle()
    assert int(dut.ctx_o.value) == (3 << 16) | FIRST       # none since reset
    dut.done_we_i.value = 1
    await clock(dut)                                        # the first one completes
    await settle()
    assert int(dut.ctx_o.value) == 3 << 16                  # the second of scan 3
    dut.done_we_i.value = 1
    await clock(dut)
    assert int(dut.ctx_o.value) == 3 << 16
    dut.req_i.value = 0
    dut.latch_i.value = 1                                   # scan 3 + 65 536 latches
    await clock(dut)
    dut.req_i.value = 1
    await settle()
    assert int(dut.ctx_o.value) == (3 << 16) | FIRST        # same number, new scan
    await clock(dut)                                        # waiting: no DONE yet
    assert int(dut.ctx_o.value) == (3 << 16) | FIRST
    dut.done_we_i.value = 1
    await clock(dut)
    assert int(dut.ctx_o.value) == 3 << 16
    dut.req_i.value = 0                                     # DONE without a request:
    dut.latch_i.value = 1                                   # no completion
    await clock(dut)
    dut.done_we_i.value = 1
    await clock(dut)
    assert int(dut.ctx_o.value) == (3 << 16) | FIRST


@cocotb.test()
async def enable_and_pulse_bits(dut):
    dut.req_i.value, dut.rlo_i.value, dut.done_we_i.value, dut.scan_i.value = 1, 1, 0, 0
    dut.done_data_i.value = 0
    for op, counter in [(0xB0, 0), (0xB3, 0), (0xB4, 0), (0xB8, 1), (0xBB, 1)]:
        dut.instr_i.value = (op << 24) | (7 << 12) | 42
        await settle()
        assert (int(dut.ctl_we_o.value), int(dut.ctl_is_counter_o.value),
                int(dut.ctl_idx_o.value), int(dut.ctl_val_o.value)) == (1, counter, 42, 1)
    for op in (0x80, 0x88, 0xAF, 0xB5, 0xBC, 0xC0):
        dut.instr_i.value = op << 24
        await settle()
        assert int(dut.ctl_we_o.value) == 0, hex(op)


@pytest.mark.parametrize("sim", SIMULATORS)
def test_dispatch(sim):
    run_cocotb(sim, "dispatch", "test_dispatch")
