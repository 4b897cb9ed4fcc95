"""Output unit (paper Fig. 1): PIO, output register at a PIO update (END, REFRESH Q),
direct PQ writes, fault, and the update's edge flags (QR rose / QF fell)."""
from __future__ import annotations

import random

import cocotb
import pytest
from cocotb.triggers import FallingEdge, RisingEdge

from simrun import SIMULATORS, run_cocotb
from tbutil import start_in_reset

OUT_BITS = 16


async def reset(dut):
    await start_in_reset(dut, dut.wr_en_i, dut.wr_idx_i, dut.wr_val_i, dut.wr_direct_i,
                         dut.update_i, dut.fault_i)


async def clock(dut, wr=None, direct=False, update=False, fault=False):
    """One clock; wr = (index, value) or None."""
    dut.wr_en_i.value = int(wr is not None)
    dut.wr_idx_i.value = wr[0] if wr else 0
    dut.wr_val_i.value = wr[1] if wr else 0
    dut.wr_direct_i.value = int(direct)
    dut.update_i.value = int(update)
    dut.fault_i.value = int(fault)
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)


def state(dut):
    return int(dut.pio_o.value), int(dut.pins_o.value)


def edges(dut):
    return int(dut.rise_o.value), int(dut.fall_o.value)


@cocotb.test()
async def update_flags_the_pins_it_changes(dut):
    """QR / QF: the pins the last update changed, held until the next update; a PQ
    write moves its pin outside an update, so the update after it sees no change."""
    await reset(dut)
    await clock(dut, wr=(2, 1))
    await clock(dut, wr=(4, 1))
    assert edges(dut) == (0, 0)                # no update yet
    await clock(dut, update=True)
    assert edges(dut) == (0b10100, 0)
    await clock(dut, wr=(2, 0))
    await clock(dut, wr=(7, 1), direct=True)   # pin 7 now, PIO 7 too
    assert edges(dut) == (0b10100, 0)          # held between updates
    await clock(dut, update=True)
    assert edges(dut) == (0, 0b100)            # 2 fell; 7 moved before the update
    await clock(dut, update=True)
    assert edges(dut) == (0, 0)                # nothing changed


@cocotb.test()
async def q_waits_for_end(dut):
    """`= Q` changes the PIO at once and the pin only at END."""
    await reset(dut)
    await clock(dut, wr=(3, 1))
    assert state(dut) == (0b1000, 0)
    await clock(dut)
    assert state(dut) == (0b1000, 0)
    await clock(dut, update=True)
    assert state(dut) == (0b1000, 0b1000)


@cocotb.test()
async def pq_updates_pin_and_pio(dut):
    """`= PQ` writes the pin and the PIO in the same clock."""
    await reset(dut)
    await clock(dut, wr=(5, 1), direct=True)
    assert state(dut) == (0b100000, 0b100000)
    await clock(dut, wr=(5, 0), direct=True)
    assert state(dut) == (0, 0)


@cocotb.test()
async def fault_forces_zero(dut):
    """The watchdog fault drives every pin to 0; END cannot bring them back."""
    await reset(dut)
    await clock(dut, wr=(0, 1), direct=True)
    await clock(dut, wr=(1, 1))
    await clock(dut, update=True)
    assert state(dut)[1] == 0b11
    await clock(dut, fault=True)
    assert state(dut)[1] == 0
    await clock(dut, update=True, fault=True)
    assert state(dut)[1] == 0


@cocotb.test()
async def random_against_model(dut):
    rng = random.Random(99)
    await reset(dut)
    pio = pins = rise = fall = 0
    for _ in range(1500):
        wr = (rng.randrange(OUT_BITS), rng.randrange(2)) if rng.random() < 0.6 else None
        direct = rng.random() < 0.3
        update = rng.random() < 0.1 and not (wr and direct)
        fault = rng.random() < 0.03         # pins to 0, whatever else this clock does
        if wr:
            bit = 1 << wr[0]
            new_pio = (pio & ~bit) | (bit if wr[1] else 0)
        else:
            new_pio = pio
        if fault:
            pins = 0                        # the edge flags keep what they held
        elif update:
            rise, fall = pio & ~pins, pins & ~pio
            pins = pio
        elif wr and direct:
            pins = (pins & ~(1 << wr[0])) | (wr[1] << wr[0])
        pio = new_pio
        await clock(dut, wr, direct, update, fault)
        assert state(dut) == (pio, pins)
        assert edges(dut) == (rise, fall)


@pytest.mark.parametrize("sim", SIMULATORS)
def test_output_unit(sim):
    run_cocotb(sim, "output_unit", "test_output_unit", parameters={"OutBits": OUT_BITS})
