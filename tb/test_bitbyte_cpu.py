"""The CPU's marker copy port (mcopy_*): what a plant's copy engine uses between scans
(docs/multicore.md), and which no single-CPU run drives (the Verilator harness ties it
to 0). Every marker bit written through the port and read back through it (one clock
late) and through the marker peek (no clock), against a pattern of the test's own.
And ready_o after reset: not before the marker RAM and both marker-area regions are
cleared, also in a build with 8 markers, where the regions clear last (every other
build clears its markers last, so a CPU that forgot the regions passed). And the marker
area's write buffer in parallel mode, which the toolchain does not offer (the harness
never runs it): the byte side publishes its cells at its SCAN_DONE (docs/exchange.md).

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


# Spelled out from docs/isa.md and docs/byte-bus.md (not imported from the toolchain)
OP_END, OP_LD, OP_ASSIGN = 0x01, 0x08, 0x18
AREA_Q, AREA_FB = 4, 9
BUS_SCAN_DONE, BUS_FBI = 0x07, 0x28
EXCHANGE_MARKER = 3


async def bus_write(dut, addr: int, data: int) -> None:
    """One bus write in one clock (a write is never refused here: SCAN_DONE, a cell)."""
    dut.bus_addr_i.value, dut.bus_wdata_i.value, dut.bus_we_i.value = addr, data, 1
    await Timer(1, unit="ns")
    assert int(dut.bus_ready_o.value), f"bus write to {addr:#x} refused"
    await clock(dut)
    dut.bus_we_i.value = 0


@cocotb.test()
async def parallel_write_buffer_publishes_the_byte_cells_at_scan_done(dut):
    """Parallel mode, marker exchange, write buffer: `LD FBI 0 / = Q 0.0 / END`. The
    byte side's scan ends at its SCAN_DONE write, so the cells it wrote are published
    then; the bit side's snapshot for its next scan is taken in the clock END executes,
    later (END waits for SCAN_DONE). In scan 1 the byte side writes cell FBI 0 = 1 and
    SCAN_DONE: scan 2 reads it, Q 0.0 is 1 after scans 2 and 3. In scan 2 it writes
    SCAN_DONE and then, in the next clock (the one END executes in, and the snapshot
    is taken in), cell FBI 0 = 0: that write belongs to its scan 3, published at scan
    3's SCAN_DONE, read by scan 4 (Q 0.0 after scan 3: 1, after scan 4: 0). Publishing
    at END instead would show each write a scan later."""
    await start(dut)
    prog = [OP_LD << 24 | AREA_FB << 12, OP_ASSIGN << 24 | AREA_Q << 12, OP_END << 24]
    for addr, word in enumerate(prog):
        dut.prog_we_i.value, dut.prog_waddr_i.value, dut.prog_wdata_i.value = 1, addr, word
        await clock(dut)
    dut.prog_we_i.value = 0
    for _ in range(MARKER_BITS + 64):
        if int(dut.ready_o.value):
            break
        await clock(dut)
    assert int(dut.ready_o.value), "ready_o never rose"
    dut.parallel_i.value = 1
    dut.exchange_i.value = EXCHANGE_MARKER
    dut.marker_write_buffer_i.value = 1
    dut.run_i.value = 1
    seen = []
    for scan in range(1, 6):
        for _ in range(30):          # the bit side reaches END and waits there
            await clock(dut)
        assert int(dut.scan_count_o.value) == scan - 1, "END did not wait for SCAN_DONE"
        if scan == 1:
            await bus_write(dut, BUS_FBI, 1)      # cell 0, within the byte side's scan
        await bus_write(dut, BUS_SCAN_DONE, 1)
        if scan == 2:
            await bus_write(dut, BUS_FBI, 0)      # the clock after SCAN_DONE
        for _ in range(10):
            if int(dut.scan_count_o.value) == scan:
                break
            await clock(dut)
        assert int(dut.scan_count_o.value) == scan, f"scan {scan} did not end"
        seen.append(int(dut.out_pins_o.value) & 1)
    assert seen == [0, 1, 1, 0, 0], f"Q 0.0 after scans 1 to 5: {seen}"


@pytest.mark.parametrize("sim", ["icarus"])
def test_bitbyte_cpu(sim):
    run_cocotb(sim, "bitbyte_cpu", "test_bitbyte_cpu")


@pytest.mark.parametrize("sim", ["icarus"])
def test_bitbyte_cpu_with_8_markers(sim):
    run_cocotb(sim, "bitbyte_cpu", "test_bitbyte_cpu", parameters={"MarkerBytes": 1},
               extra_env={"TB_MARKER_BYTES": "1"},
               testcase="ready_waits_for_the_markers_and_the_marker_area")
