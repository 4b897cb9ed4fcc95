"""Timer/counter status buffer (paper Fig. 2): byte side writes status bits one at a
time; the enable/pulse bits are written by the serial dispatch (ctl_*) or, in parallel
and free-running mode (partitioned_i), by the bit processor (bit_*), the other writer
ignored; each set is independent. The `updated` bits
(parallel mode's "after the update" wait): a status write sets its bit, a scan's latch
clears them all, and a write in the latch clock itself belongs to the new scan. The
`written` bits (parallel mode's status wait, --tc-path status) likewise for the bit
processor's enable / pulse writes; a serial dispatch never sets them."""
from __future__ import annotations

import random

import cocotb
import pytest
from cocotb.triggers import FallingEdge, RisingEdge

from simrun import SIMULATORS, run_cocotb
from tbutil import start_in_reset

N = 64


@cocotb.test()
async def random_writes_against_model(dut):
    await start_in_reset(dut, dut.status_we_i, dut.ctl_we_i, dut.bit_we_i,
                         dut.partitioned_i, dut.latch_i)
    model = {"ts": 0, "cs": 0, "te": 0, "cp": 0, "tu": 0, "cu": 0, "tw": 0, "cw": 0}
    rng = random.Random(3)
    latches = latch_writes = 0
    part = 0
    taken = {0: 0, 1: 0}
    for _ in range(4000):
        if rng.random() < 0.01:                 # the mode changes now and then
            part ^= 1
        sw, cw, bw = rng.random() < 0.5, rng.random() < 0.5, rng.random() < 0.5
        latch = rng.random() < 0.1
        s_cnt, s_idx, s_val = rng.randrange(2), rng.randrange(N), rng.randrange(2)
        c_cnt, c_idx, c_val = rng.randrange(2), rng.randrange(N), rng.randrange(2)
        b_cnt, b_idx, b_val = rng.randrange(2), rng.randrange(N), rng.randrange(2)
        dut.partitioned_i.value = part
        dut.bit_we_i.value, dut.bit_is_counter_i.value = int(bw), b_cnt
        dut.bit_idx_i.value, dut.bit_val_i.value = b_idx, b_val
        dut.status_we_i.value, dut.status_is_counter_i.value = int(sw), s_cnt
        dut.status_idx_i.value, dut.status_val_i.value = s_idx, s_val
        dut.ctl_we_i.value, dut.ctl_is_counter_i.value = int(cw), c_cnt
        dut.ctl_idx_i.value, dut.ctl_val_i.value = c_idx, c_val
        dut.latch_i.value = int(latch)
        if latch:
            model["tu"] = model["cu"] = model["tw"] = model["cw"] = 0
            latches += 1
            latch_writes += sw
        if sw:
            upd = "cu" if s_cnt else "tu"
            model[upd] |= 1 << s_idx
            key = "cs" if s_cnt else "ts"
            model[key] = (model[key] & ~(1 << s_idx)) | (s_val << s_idx)
        # one writer of the enable/pulse bits, by mode; the other's offer is ignored
        we, cnt, idx, val = (bw, b_cnt, b_idx, b_val) if part else (cw, c_cnt, c_idx, c_val)
        if we:
            key = "cp" if cnt else "te"
            model[key] = (model[key] & ~(1 << idx)) | (val << idx)
            taken[part] += 1
        if part and bw:                         # the bit processor's own write only
            model["cw" if b_cnt else "tw"] |= 1 << b_idx
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
        got = {"ts": int(dut.timer_status_o.value), "cs": int(dut.counter_status_o.value),
               "te": int(dut.timer_enable_o.value), "cp": int(dut.counter_pulse_o.value),
               "tu": int(dut.timer_updated_o.value), "cu": int(dut.counter_updated_o.value),
               "tw": int(dut.timer_written_o.value), "cw": int(dut.counter_written_o.value)}
        assert got == model
    assert latches > 100 and latch_writes > 50        # the cases the model separates
    assert min(taken.values()) > 300                  # both writers, in their modes


@cocotb.test()
async def a_write_changes_its_own_bit_only(dut):
    """Each of the four vectors filled bit by bit and emptied bit by bit, in both
    orders, checked after every write: a write of bit j leaves every other bit as it
    was (the random test meets few of the 64 x 63 pairs: make mutate found a mutant
    whose write of enable bit 24 cleared enable bit 50)."""
    await start_in_reset(dut, dut.status_we_i, dut.ctl_we_i, dut.bit_we_i,
                         dut.partitioned_i, dut.latch_i)
    ports = {("status", 0): "timer_status_o", ("status", 1): "counter_status_o",
             ("ctl", 0): "timer_enable_o", ("ctl", 1): "counter_pulse_o",
             ("bit", 0): "timer_enable_o", ("bit", 1): "counter_pulse_o"}
    for (kind, counter), out in ports.items():
        for other in {"status", "ctl", "bit"} - {kind}:
            getattr(dut, f"{other}_we_i").value = 0
        dut.partitioned_i.value = int(kind == "bit")
        want = 0                                 # every pass ends with all bits 0
        for order in (range(N), range(N - 1, -1, -1)):
            for val in (1, 0):
                for j in order:
                    getattr(dut, f"{kind}_we_i").value = 1
                    getattr(dut, f"{kind}_is_counter_i").value = counter
                    getattr(dut, f"{kind}_idx_i").value = j
                    getattr(dut, f"{kind}_val_i").value = val
                    await RisingEdge(dut.clk_i)
                    await FallingEdge(dut.clk_i)
                    want = (want & ~(1 << j)) | (val << j)
                    assert int(getattr(dut, out).value) == want, (out, j, val)
        getattr(dut, f"{kind}_we_i").value = 0


@cocotb.test()
async def each_updated_and_written_bit_by_itself(dut):
    """The set-only vectors (updated: the byte side's status writes; written: the bit
    processor's own enable / pulse writes in parallel mode), each filled bit by bit in
    both orders from a latch, checked after every write: a write sets its own bit and
    no other (the random test latches every ten clocks or so, so these vectors hold
    few bits at a time: make mutate found mutants that set a second bit of them)."""
    await start_in_reset(dut, dut.status_we_i, dut.ctl_we_i, dut.bit_we_i,
                         dut.partitioned_i, dut.latch_i)
    ports = {("status", 0): "timer_updated_o", ("status", 1): "counter_updated_o",
             ("bit", 0): "timer_written_o", ("bit", 1): "counter_written_o"}
    for (kind, counter), out in ports.items():
        dut.partitioned_i.value = int(kind == "bit")
        for order in (range(N), range(N - 1, -1, -1)):
            dut.status_we_i.value = dut.bit_we_i.value = dut.ctl_we_i.value = 0
            dut.latch_i.value = 1                # clears the vectors
            await RisingEdge(dut.clk_i)
            await FallingEdge(dut.clk_i)
            dut.latch_i.value = 0
            want = 0
            for j in order:
                getattr(dut, f"{kind}_we_i").value = 1
                getattr(dut, f"{kind}_is_counter_i").value = counter
                getattr(dut, f"{kind}_idx_i").value = j
                getattr(dut, f"{kind}_val_i").value = j % 2
                await RisingEdge(dut.clk_i)
                await FallingEdge(dut.clk_i)
                want |= 1 << j
                assert int(getattr(dut, out).value) == want, (out, j)
        getattr(dut, f"{kind}_we_i").value = 0


@pytest.mark.parametrize("sim", SIMULATORS)
def test_tc_status(sim):
    run_cocotb(sim, "tc_status", "test_tc_status")
