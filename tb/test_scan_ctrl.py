"""Scan controller: INIT -> IDLE -> RUN, scans (latch clock, in which the first
instruction executes, then the program up to END), scan counting, watchdog."""
from __future__ import annotations

import cocotb
import pytest
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from simrun import SIMULATORS, run_cocotb
from tbutil import start_in_reset


async def reset(dut, limit=100):
    await start_in_reset(dut, dut.mem_ready_i, dut.run_i, dut.end_i, watchdog_limit_i=limit)


async def clock(dut, end=False):
    dut.end_i.value = int(end)
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)


def flags(dut):
    return int(dut.latch_o.value), int(dut.exec_o.value)


@cocotb.test()
async def waits_for_memory_then_run(dut):
    await reset(dut)
    for _ in range(5):
        await clock(dut)
        assert int(dut.ready_o.value) == 0 and flags(dut) == (0, 0)
    dut.mem_ready_i.value = 1
    await clock(dut)
    assert int(dut.ready_o.value) == 1
    await clock(dut)
    assert flags(dut) == (0, 0)          # stays stopped without RUN
    dut.run_i.value = 1
    await Timer(1, unit="ns")
    assert int(dut.start_o.value) == 1   # the next clock starts a scan
    await clock(dut)
    assert flags(dut) == (1, 1)          # the latch clock of scan 0 executes too


@cocotb.test()
async def counts_cycles_of_each_scan(dut):
    """A scan = latch clock (first instruction) + more clocks + END clock; the next
    latches right after; END in the latch clock itself makes a 1-clock scan."""
    await reset(dut)
    dut.mem_ready_i.value = 1
    await clock(dut)
    dut.run_i.value = 1
    await clock(dut)
    for scan, body in enumerate([0, 3, 10]):
        assert flags(dut) == (1, 1)
        await clock(dut)                 # latch + first instruction
        for _ in range(body):
            assert flags(dut) == (0, 1)
            await clock(dut)
        assert int(dut.scan_done_o.value) == 0
        await clock(dut, end=True)       # END
        assert int(dut.scan_done_o.value) == 1
        assert int(dut.scan_cycles_o.value) == body + 2
        assert int(dut.scan_count_o.value) == scan + 1
        assert int(dut.scan_cycles_max_o.value) == body + 2     # each scan longer
    assert flags(dut) == (1, 1)
    await clock(dut, end=True)           # END as the first instruction
    assert int(dut.scan_cycles_o.value) == 1 and int(dut.scan_count_o.value) == 4
    assert int(dut.scan_cycles_max_o.value) == 12


@cocotb.test()
async def stop_at_end_of_scan(dut):
    await reset(dut)
    dut.mem_ready_i.value = 1
    await clock(dut)
    dut.run_i.value = 1
    await clock(dut)
    await clock(dut)                     # latch
    dut.run_i.value = 0                  # STOP mid-scan: the scan completes
    await clock(dut)
    await clock(dut, end=True)
    assert int(dut.scan_done_o.value) == 1
    assert int(dut.ready_o.value) == 1 and flags(dut) == (0, 0)


@cocotb.test()
async def watchdog_exactly_at_limit(dut):
    """A scan of exactly `limit` clocks passes; one clock more is a fault."""
    limit = 6
    await reset(dut, limit)
    dut.mem_ready_i.value = 1
    await clock(dut)
    dut.run_i.value = 1
    await clock(dut)
    await clock(dut)                     # latch: 1
    for _ in range(limit - 2):
        await clock(dut)                 # 2 .. limit-1
    await clock(dut, end=True)           # clock `limit` is END: legal
    assert int(dut.scan_done_o.value) == 1 and int(dut.fault_o.value) == 0
    await clock(dut)                     # latch
    for _ in range(limit - 1):
        await clock(dut)                 # no END by clock `limit`
    assert int(dut.fault_o.value) == 1
    assert int(dut.scan_count_o.value) == 1
    await clock(dut, end=True)           # too late: stays in fault
    assert int(dut.fault_o.value) == 1 and int(dut.scan_count_o.value) == 1


async def restart(dut, limit: int) -> None:
    """Reset again with the clock running, a new limit, then RUN: the next clock is
    scan 0's latch."""
    dut.rst_ni.value, dut.run_i.value = 0, 0
    dut.watchdog_limit_i.value = limit
    await clock(dut)
    dut.rst_ni.value = 1
    dut.mem_ready_i.value = 1
    await clock(dut)
    dut.run_i.value = 1
    await clock(dut)


@cocotb.test()
async def watchdog_limit_uses_every_bit(dut):
    """A limit of 2**k + 4 lets scans of 8 clocks run, for every bit k above the
    scan's length (make mutate: a limit bit stuck at 0 fired the watchdog early)."""
    await reset(dut)
    for k in range(4, 32):
        await restart(dut, (1 << k) + 4)
        for _ in range(2):
            for _ in range(7):
                await clock(dut)             # latch + 6 clocks
            await clock(dut, end=True)       # clock 8 is END
        assert int(dut.fault_o.value) == 0 and int(dut.scan_count_o.value) == 2, k


@cocotb.test()
async def watchdog_fires_at_limits_with_low_bits_set(dut):
    """Limits 2**k - 1 (every bit below k set), k = 2 .. 11: the fault comes exactly
    after `limit` clocks without END (make mutate: the limit's bit 17 XORed with its
    bit 6 let a scan run past a limit of 100)."""
    await reset(dut)
    for k in range(2, 12):
        limit = (1 << k) - 1
        await restart(dut, limit)
        for _ in range(limit - 1):
            await clock(dut)                 # latch .. clock limit-1: no END yet
        assert int(dut.fault_o.value) == 0, limit
        await clock(dut)                     # clock `limit` without END
        assert int(dut.fault_o.value) == 1, limit


@cocotb.test()
async def longest_scan_compares_every_bit(dut):
    """Scans of 2**k + 1 clocks, each followed by one of 40: the longest stays the
    long one, for k up to 12 (make mutate: a compare ignoring bit 11 of the longest
    scan took the 40 for longer)."""
    await reset(dut, limit=1 << 20)
    dut.mem_ready_i.value = 1
    await clock(dut)
    dut.run_i.value = 1
    await clock(dut)
    for k in range(6, 13):
        for length in ((1 << k) + 1, 40):
            for _ in range(length - 1):
                await clock(dut)
            await clock(dut, end=True)
            assert int(dut.scan_cycles_o.value) == length
            assert int(dut.scan_cycles_max_o.value) == (1 << k) + 1, (k, length)


@cocotb.test()
async def longest_scan_by_one_clock(dut):
    """The longest scan's edge cases: a first scan of one clock (END in the latch
    clock) and scans one clock longer than the longest so far, each taken; a scan as
    long as the longest, or a 1-clock one after it, changes nothing (issue 20: the
    compare reads cycle_q_o >= longest instead of cycle_q_o + 1 > longest)."""
    await reset(dut)
    dut.mem_ready_i.value = 1
    await clock(dut)
    dut.run_i.value = 1
    await clock(dut)
    for length, longest in ((1, 1), (2, 2), (2, 2), (3, 3), (1, 3), (4, 4)):
        for _ in range(length - 1):
            await clock(dut)
        await clock(dut, end=True)
        assert int(dut.scan_cycles_o.value) == length
        assert int(dut.scan_cycles_max_o.value) == longest, (length, longest)


@pytest.mark.parametrize("sim", SIMULATORS)
def test_scan_ctrl(sim):
    run_cocotb(sim, "scan_ctrl", "test_scan_ctrl")
