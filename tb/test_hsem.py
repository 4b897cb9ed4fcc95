"""Hardware semaphore (seed 000's HSEM): contention provoked on purpose — a core
spins while another holds the lock, a released lock is granted to a waiting core in
the next clock, round-robin keeps every waiting core's wait bounded, and only the
owner can release."""
from __future__ import annotations

import random

import cocotb
import pytest
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from simrun import SIMULATORS, run_cocotb
from tbutil import start_in_reset

CORES = 3


async def reset(dut):
    await start_in_reset(dut, dut.lock_req_i, dut.release_i)


async def clock(dut, req=0, rel=0):
    dut.lock_req_i.value, dut.release_i.value = req, rel
    await Timer(1, unit="ns")
    grant = int(dut.grant_o.value)
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    return grant


@cocotb.test()
async def spin_then_grant_after_release(dut):
    await reset(dut)
    assert await clock(dut, req=0b001) == 0b001           # core 0 takes it at once
    assert int(dut.locked_o.value) == 1 and int(dut.owner_o.value) == 0
    for _ in range(5):
        assert await clock(dut, req=0b010) == 0            # core 1 spins
    assert await clock(dut, req=0b010, rel=0b010) == 0     # not the owner: ignored
    assert int(dut.locked_o.value) == 1
    assert await clock(dut, req=0b010, rel=0b001) == 0     # owner releases ...
    assert await clock(dut, req=0b010) == 0b010            # ... granted the next clock
    assert int(dut.owner_o.value) == 1


@cocotb.test()
async def round_robin_bounds_the_wait(dut):
    """All cores spin all the time; each owner holds for a random time: every core
    is served at least once every CORES grants."""
    await reset(dut)
    rng = random.Random(4)
    owner, hold, waited = None, 0, [0] * CORES
    for _ in range(2000):
        rel = 0
        if owner is not None:
            hold -= 1
            if hold == 0:
                rel = 1 << owner
        grant = await clock(dut, req=(1 << CORES) - 1, rel=rel)
        if rel:
            owner = None
            assert grant == 0                              # free from the next clock
        elif owner is None:
            assert grant != 0                              # granted at once
            owner = grant.bit_length() - 1
            hold = rng.randrange(1, 6)
            for c in range(CORES):
                waited[c] = 0 if c == owner else waited[c] + 1
                assert waited[c] < CORES, waited
        else:
            assert grant == 0


@pytest.mark.parametrize("sim", SIMULATORS)
def test_hsem(sim):
    run_cocotb(sim, "hsem", "test_hsem", parameters={"Cores": CORES})
