"""One direction of the block-RAM marker area (rtl/marker_region.v, paper Fig. 17): the
reader sees the writer's cells as a snapshot taken at its scan start (snap_i), with the
write buffer as of the writer's last scan end; a read's cell comes a clock later (a
block RAM); reads and writes are taken in every clock they are asked for (the reader
and the writer's merge read copies of their own of the RAM: no arbitration)."""
from __future__ import annotations

import os
import random

import cocotb
import pytest
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from simrun import SIMULATORS, run_cocotb
from tbutil import start_in_reset

INPUTS = ("wr_req_i", "wr_idx_i", "wr_data_i", "publish_i", "snap_i", "rd_req_i", "rd_idx_i")


def cells(dut) -> int:
    return int(os.environ.get("MR_CELLS", "128"))


async def reset_and_clear(dut, write_buffer: bool) -> None:
    await start_in_reset(dut, *(getattr(dut, n) for n in INPUTS),
                         write_buffer_i=int(write_buffer))
    clocks = 0
    while not int(dut.ready_o.value):
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
        clocks += 1
    # the RAM is cleared one word a clock: 3 slots + 1 unused per word of WordBits cells
    assert clocks == 4 * cells(dut) // int(os.environ.get("MR_WORD_BITS", "16"))


async def clock(dut, **signals):
    """One clock with `signals` set (others 0)."""
    for name in INPUTS:
        getattr(dut, name).value = signals.get(name, 0)
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    for name in INPUTS:
        getattr(dut, name).value = 0


async def write(dut, idx, val, **more):
    await clock(dut, wr_req_i=1, wr_idx_i=idx, wr_data_i=val, **more)


async def read(dut, idx, **more) -> int:
    await clock(dut, rd_req_i=1, rd_idx_i=idx, **more)
    await Timer(1, unit="ns")
    return int(dut.rd_data_o.value)


async def writer_scan_across_reader_start(dut):
    """Hand-worked Fig. 17 case: the writer sets cell 0 and cell 17 (another word) in
    one scan, the reader's scan starts between the two writes. Returns what the reader
    sees of both in that scan, and after its next scan start (the writer's scan ended
    in between)."""
    await write(dut, 0, 1)
    await clock(dut, snap_i=1)
    await write(dut, 17, 1)
    during = (await read(dut, 0), await read(dut, 17))
    await clock(dut, publish_i=1)
    after = (await read(dut, 0, snap_i=1), await read(dut, 17))
    return during, after


@cocotb.test()
async def reader_buffer_only_mixes_a_half_scan(dut):
    """Fig. 17 as drawn: the snapshot holds cell 0 new and cell 17 old."""
    await reset_and_clear(dut, write_buffer=False)
    assert await writer_scan_across_reader_start(dut) == ((1, 0), (1, 1))


@cocotb.test()
async def write_buffer_keeps_scans_whole(dut):
    """Writers publish at their scan end: the snapshot has neither write, then both."""
    await reset_and_clear(dut, write_buffer=True)
    assert await writer_scan_across_reader_start(dut) == ((0, 0), (1, 1))


@cocotb.test()
async def words_are_not_torn(dut):
    """Cells 4 and 5 share a RAM word. The reader's snapshot holds cell 4 = 1; the
    writer then sets 5 and clears 4 in back-to-back clocks (the second merge reads the
    first through the bypass): the snapshot keeps 4 = 1, 5 = 0 until the next update,
    which shows 4 = 0, 5 = 1; a write in the update's clock is not in it."""
    await reset_and_clear(dut, write_buffer=False)
    await write(dut, 4, 1)
    await clock(dut, snap_i=1)
    await write(dut, 5, 1)
    await write(dut, 4, 0)
    assert (await read(dut, 4), await read(dut, 5)) == (1, 0)
    assert await read(dut, 4, snap_i=1) == 0          # a read in the update's clock: new
    await write(dut, 6, 1, snap_i=1)                   # not in this update
    assert (await read(dut, 5), await read(dut, 6)) == (1, 0)
    assert await read(dut, 6, snap_i=1) == 1


async def random_against_model(dut, write_buffer: bool, seed: int, clocks: int = 1500,
                               switch_every: int = 0):
    """Random writes, reads, updates and publications, every taken read against a model
    of Fig. 17 (the cells as written, as published at the writer's scan end with that
    clock's write, and the reader's snapshot of the visible ones taken at its update,
    already seen by a read in that clock); a read and a write in the same clock, often of
    the same word, are both taken.
    Indices cluster on few words, so merges meet the bypass and the snapshot often.
    switch_every: the write buffer is switched on or off about that often, in a clock
    with no access, no update and no publication (as a CPU's setting changes between
    runs); the cells written so far count as published at a switch on."""
    await reset_and_clear(dut, write_buffer)
    rng = random.Random(seed)
    n = cells(dut)
    hot = [rng.randrange(n) for _ in range(6)]
    work, pub, snap = [0] * n, [0] * n, [0] * n
    checked = 0
    pending = None
    switches = 0
    for _ in range(clocks):
        if switch_every and rng.random() < 1 / switch_every:
            await Timer(1, unit="ns")
            if pending is not None:             # the last read's cell first
                assert int(dut.rd_data_o.value) == pending[1], f"cell {pending[0]}"
                checked += 1
                pending = None
            write_buffer = not write_buffer
            switches += 1
            if write_buffer:
                pub = list(work)
            dut.write_buffer_i.value = int(write_buffer)
            await clock(dut)                    # an idle clock with the new setting
        pick = (lambda: rng.choice(hot)) if rng.random() < 0.7 else (lambda: rng.randrange(n))
        drive = dict(wr_req_i=int(rng.random() < 0.5), wr_idx_i=pick(),
                     wr_data_i=rng.randrange(2), publish_i=int(rng.random() < 0.1),
                     snap_i=int(rng.random() < 0.1), rd_req_i=int(rng.random() < 0.5),
                     rd_idx_i=pick())
        for name, value in drive.items():
            getattr(dut, name).value = value
        await Timer(1, unit="ns")
        if pending is not None:
            assert int(dut.rd_data_o.value) == pending[1], f"cell {pending[0]}"
            checked += 1
        if drive["snap_i"]:
            snap = list(pub if write_buffer else work)
        pending = ((drive["rd_idx_i"], snap[drive["rd_idx_i"]])
                   if drive["rd_req_i"] else None)
        if drive["wr_req_i"]:
            work[drive["wr_idx_i"]] = drive["wr_data_i"]
        if drive["publish_i"]:
            pub = list(work)
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
    assert checked > clocks // 8
    assert switches >= clocks // switch_every // 2 if switch_every else True


@cocotb.test()
async def random_traffic_live_cells(dut):
    await random_against_model(dut, write_buffer=False, seed=5)


@cocotb.test()
async def random_traffic_write_buffer(dut):
    await random_against_model(dut, write_buffer=True, seed=6)


@cocotb.test()
async def random_traffic_write_buffer_switched(dut):
    """The setting changes between runs (make mutate: two mutants that are harmless
    while it stays as it was at reset — the reader's slot left out of a write's choice
    when it is slot 2, which only the write buffer uses; the published slots not
    following the writer's without the write buffer — break a run after a change)."""
    await random_against_model(dut, write_buffer=True, seed=7, clocks=4000,
                               switch_every=150)


CONFIGS = {
    "default": {},                                            # 128 cells in words of 16
    "small": {"Cells": 32, "WordBits": 4},
}


@pytest.mark.parametrize("config", CONFIGS)
@pytest.mark.parametrize("sim", SIMULATORS)
def test_marker_region(sim, config):
    params = CONFIGS[config]
    env = {"MR_CELLS": str(params.get("Cells", 128)),
           "MR_WORD_BITS": str(params.get("WordBits", 16))}
    run_cocotb(sim, "marker_region", "test_marker_region", parameters=params, extra_env=env)
