"""The CPU's marker copy port (mcopy_*): what a plant's copy engine uses between scans
(docs/multicore.md), and which no single-CPU run drives (the Verilator harness ties it
to 0). Every marker bit written through the port and read back through it (one clock
late) and through the marker peek (no clock), against a pattern of the test's own.
And ready_o after reset: not before the marker RAM and both marker-area regions are
cleared, also in a build with 8 markers, where the regions clear last (every other
build clears its markers last, so a CPU that forgot the regions passed).

Icarus only: the whole CPU at its defaults; the harness and the cocotb driver run the
CPU on Verilator in the rest of the regression, and this bench is the mutation
campaign's way to reach the port (make mutate, campaign cpu)."""
from __future__ import annotations

import os

import cocotb
import pytest
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from simrun import run_cocotb
from tbutil import start_in_reset

MARKER_BITS = 256 * 8   # MarkerBytes at its default


ADDRESS_BITS = 11      # 2048 marker bits


def pattern(a: int, k: int) -> int:
    """Bit a of pass k: in pass k < 11 address bit k (every other pass inverted), so any
    two addresses differ in some pass; in pass 11 the parity of the address."""
    return (a >> k & 1) ^ (k & 1) if k < ADDRESS_BITS else bin(a).count("1") & 1


async def clock(dut):
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)


async def start(dut):
    """Every input at 0 (the watchdog off), reset for one clock."""
    await start_in_reset(dut, dut.prog_we_i, dut.run_i, dut.time_start_i, dut.parallel_i,
                         dut.free_i, dut.marker_write_buffer_i, dut.exchange_i,
                         dut.in_pins_i, dut.in_words_i, dut.bus_we_i, dut.bus_re_i,
                         dut.mcopy_en_i, dut.mcopy_we_i, dut.mcopy_addr_i,
                         dut.mcopy_wdata_i, dut.dbg_m_addr_i,
                         watchdog_limit_i=100000)


@cocotb.test()
async def copy_port_writes_and_reads_every_marker(dut):
    await start(dut)
    for _ in range(MARKER_BITS + 16):      # the marker RAM clears itself, a bit a clock
        if int(dut.ready_o.value):
            break
        await clock(dut)
    assert int(dut.ready_o.value), "ready_o never rose"
    # passes 0..10: address bit k (every address bit seen by itself), 11: the parity
    for k in range(ADDRESS_BITS + 1):
        dut.mcopy_en_i.value = 1
        dut.mcopy_we_i.value = 1
        for a in range(MARKER_BITS):
            dut.mcopy_addr_i.value = a
            dut.mcopy_wdata_i.value = pattern(a, k)
            await clock(dut)
        dut.mcopy_we_i.value = 0
        await clock(dut)
        for a in range(MARKER_BITS):
            dut.mcopy_addr_i.value = a
            dut.dbg_m_addr_i.value = a
            await Timer(1, unit="ns")
            assert int(dut.dbg_m_o.value) == pattern(a, k), f"peek M bit {a}, pass {k}"
            await clock(dut)
            assert int(dut.mcopy_rdata_o.value) == pattern(a, k), f"copy read {a}, pass {k}"
        dut.mcopy_en_i.value = 0
        await clock(dut)


# Clocks each clearing takes after reset, as the RTL documents them: the marker RAM a
# bit a clock (bit_proc.v), a marker-area region a RAM word a clock over 4 slots of
# Cells / 16 words (marker_region.v, 16 cells a word; MarkerCells at its default).
MARKER_CELLS = 128
REGION_CLEAR = 4 * MARKER_CELLS // 16


@cocotb.test()
async def ready_waits_for_the_markers_and_the_marker_area(dut):
    marker_bits = int(os.environ.get("TB_MARKER_BYTES", str(MARKER_BITS // 8))) * 8
    await start(dut)
    clocks = 0
    while not int(dut.ready_o.value):
        await clock(dut)
        clocks += 1
        assert clocks < 2 * (marker_bits + REGION_CLEAR) + 64, "ready_o never rose"
    assert clocks >= max(marker_bits, REGION_CLEAR), (clocks, marker_bits, REGION_CLEAR)


@pytest.mark.parametrize("sim", ["icarus"])
def test_bitbyte_cpu(sim):
    run_cocotb(sim, "bitbyte_cpu", "test_bitbyte_cpu")


@pytest.mark.parametrize("sim", ["icarus"])
def test_bitbyte_cpu_with_8_markers(sim):
    run_cocotb(sim, "bitbyte_cpu", "test_bitbyte_cpu", parameters={"MarkerBytes": 1},
               extra_env={"TB_MARKER_BYTES": "1"},
               testcase="ready_waits_for_the_markers_and_the_marker_area")
