"""Buffered condition flip-flop (paper Fig. 11): full/empty handshake; random traffic
against a one-place mailbox model; nothing lost, duplicated or reordered."""
from __future__ import annotations

import random

import cocotb
import pytest

from simrun import SIMULATORS, run_cocotb
from tbutil import offer, start_in_reset


async def reset(dut):
    await start_in_reset(dut, dut.wr_req_i, dut.wr_data_i, dut.rd_req_i)


async def clock(dut, wr=None, rd=False):
    return await offer(dut, wr, rd)


@cocotb.test()
async def handshake(dut):
    await reset(dut)
    assert int(dut.full_o.value) == 0
    assert await clock(dut, rd=True) == (False, None)      # empty: the reader stalls
    assert await clock(dut, wr=1) == (True, None)
    assert int(dut.full_o.value) == 1
    assert await clock(dut, wr=0) == (False, None)         # full: the writer stalls
    assert await clock(dut, wr=0, rd=True) == (False, 1)   # only the read succeeds
    assert await clock(dut, wr=0, rd=True) == (True, None)  # empty: only the write
    assert await clock(dut, rd=True) == (False, 0)


@cocotb.test()
async def random_traffic(dut):
    """A writer sends a random sequence, a reader takes it at random moments: the
    reader gets exactly the sequence; each side stalls only when it must."""
    await reset(dut)
    rng = random.Random(7)
    sent = [rng.randrange(2) for _ in range(300)]
    received, i, full = [], 0, False
    while len(received) < len(sent):
        wr = sent[i] if i < len(sent) and rng.random() < 0.6 else None
        rd = rng.random() < 0.6
        taken, got = await clock(dut, wr, rd)
        assert taken == (wr is not None and not full)
        assert (got is not None) == (rd and full)
        if got is not None:
            received.append(got)
            full = False
        elif taken:
            i += 1
            full = True
        assert int(dut.full_o.value) == full
    assert received == sent


@pytest.mark.parametrize("sim", SIMULATORS)
def test_cond_ff(sim):
    run_cocotb(sim, "cond_ff", "test_cond_ff")
