"""Dual-port marker area with auxiliary buffer (paper Fig. 17): readers see the other
side's cells as a snapshot taken at their scan start; with the write buffer a writer's
half-finished scan is never mixed into a snapshot."""
from __future__ import annotations

import random

import cocotb
import pytest
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from simrun import SIMULATORS, run_cocotb
from tbutil import start_in_reset


async def reset(dut, write_buffer):
    await start_in_reset(dut, dut.bit_start_i, dut.bit_end_i, dut.bit_wr_i,
                         dut.bit_wr_data_i, dut.byte_start_i, dut.byte_end_i, dut.byte_wr_i,
                         dut.byte_wr_data_i, write_buffer_i=int(write_buffer))


async def clock(dut, **signals):
    for name, value in signals.items():
        getattr(dut, name).value = value
    await Timer(1, unit="ns")
    seen = int(dut.bit_rd_data_o.value)
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    for name in signals:
        getattr(dut, name).value = 0
    return seen


async def writer_scan_across_reader_start(dut):
    """The byte side sets cells 0 and 1 in one of its scans; the bit side's scan
    starts between the two writes. Returns what the bit side sees in that scan,
    then after its next scan start (the writer's scan has ended by then)."""
    await clock(dut, byte_start_i=1)
    await clock(dut, byte_wr_i=0b01, byte_wr_data_i=1)          # cell 0 := 1
    mid = await clock(dut, bit_start_i=1)                        # the reader's update
    await clock(dut, byte_wr_i=0b10, byte_wr_data_i=1)          # cell 1 := 1
    during = await clock(dut)
    await clock(dut, byte_end_i=1)                               # writer's scan ends
    after = await clock(dut, bit_start_i=1)
    return mid, during, after


@cocotb.test()
async def reader_buffer_only_mixes_a_half_scan(dut):
    """Fig. 17 as drawn: the snapshot holds cell 0 new and cell 1 old."""
    await reset(dut, write_buffer=False)
    mid, during, after = await writer_scan_across_reader_start(dut)
    assert (mid, during, after) == (0b01, 0b01, 0b11)


@cocotb.test()
async def write_buffer_keeps_scans_whole(dut):
    """Writers publish at their scan end: the snapshot has neither write, then both."""
    await reset(dut, write_buffer=True)
    mid, during, after = await writer_scan_across_reader_start(dut)
    assert (mid, during, after) == (0b00, 0b00, 0b11)


@cocotb.test()
async def snapshot_is_stable_and_regions_are_separate(dut):
    """Between its scan starts a reader's view does not move; each side writes only
    its own region (the bit side's writes reach the byte side's reads only)."""
    await reset(dut, write_buffer=False)
    await clock(dut, bit_wr_i=0b1000, bit_wr_data_i=1)
    assert await clock(dut) == 0                                 # not its own cells
    await clock(dut, byte_start_i=1)
    assert int(dut.byte_rd_data_o.value) == 0b1000
    await clock(dut, byte_wr_i=0b0100, byte_wr_data_i=1)
    assert await clock(dut) == 0                                 # no update yet
    assert await clock(dut, bit_start_i=1) == 0b0100            # seen in the start clock
    await clock(dut, byte_wr_i=0b0100, byte_wr_data_i=0)
    for _ in range(3):
        assert await clock(dut) == 0b0100                        # stable until next start


CELLS = 4   # the module's default


async def random_against_model(dut, write_buffer: bool, seed: int):
    """Random writes, scan starts and ends on both sides, every clock against a model
    of Fig. 17: a side's cells as written and as published (at its scan end, that
    clock's write included), each reader's snapshot of the other side's visible cells
    (published ones with the write buffer, else live ones) taken at its scan start and
    already seen in that clock (make mutate: mutants of the bit side's cell 0 write
    and of the write-buffer select survived the directed tests)."""
    await reset(dut, write_buffer=write_buffer)
    rng = random.Random(seed)
    work, pub, snap = {"bit": 0, "byte": 0}, {"bit": 0, "byte": 0}, {"bit": 0, "byte": 0}
    other = {"bit": "byte", "byte": "bit"}
    for _ in range(400):
        drive = {}
        for side in ("bit", "byte"):
            drive[side] = dict(wr=rng.randrange(1 << CELLS) if rng.random() < 0.5 else 0,
                               data=rng.randrange(2), start=rng.random() < 0.15,
                               end=rng.random() < 0.15)
            for name, key in (("wr_i", "wr"), ("wr_data_i", "data"), ("start_i", "start"),
                              ("end_i", "end")):
                getattr(dut, f"{side}_{name}").value = int(drive[side][key])
        await Timer(1, unit="ns")
        visible = {s: pub[s] if write_buffer else work[s] for s in ("bit", "byte")}
        for side in ("bit", "byte"):
            want = visible[other[side]] if drive[side]["start"] else snap[side]
            assert int(getattr(dut, f"{side}_rd_data_o").value) == want, side
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
        for side in ("bit", "byte"):
            d = drive[side]
            if d["start"]:
                snap[side] = visible[other[side]]
            work[side] = (work[side] & ~d["wr"]) | (d["wr"] if d["data"] else 0)
            if d["end"]:
                pub[side] = work[side]


@cocotb.test()
async def random_traffic_live_cells(dut):
    await random_against_model(dut, write_buffer=False, seed=3)


@cocotb.test()
async def random_traffic_write_buffer(dut):
    await random_against_model(dut, write_buffer=True, seed=4)


@pytest.mark.parametrize("sim", SIMULATORS)
def test_marker_area(sim):
    run_cocotb(sim, "marker_area", "test_marker_area")
