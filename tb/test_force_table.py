"""Force table (docs/byte-bus.md, FORCE_*): a pending table written over the byte bus,
made active at END's PIO update (at once before RUN); forced inputs and outputs, a
watchdog fault dropping every output. Register addresses from
bitbyte/lang/definition.toml; checked against a model of the registers' text, not of
the RTL's expressions.

The build forces 100 of 104 inputs and 112 outputs: the fourth register of each
window is partly in the table (pins 96..99), and pins from 100 on always pass."""
from __future__ import annotations

import random

import cocotb
import pytest
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from bitbyte.lang.definition import DEF
from simrun import SIMULATORS, run_cocotb
from tbutil import start_in_reset

IN_BITS, OUT_BITS, FORCE_BITS = 104, 112, 100
WINDOWS = ("FORCE_IN_MASK", "FORCE_IN_VAL", "FORCE_OUT_MASK", "FORCE_OUT_VAL")
TABLE = (1 << FORCE_BITS) - 1


class Model:
    """The four windows as docs/byte-bus.md describes them: register n of a window holds
    pins 32n+31..32n; a write goes to the pending table, which is active from the next
    END (or at once while not running)."""

    def __init__(self):
        self.pending = dict.fromkeys(WINDOWS, 0)
        self.active = dict.fromkeys(WINDOWS, 0)

    def clock(self, write, run, swap):
        if write is not None:
            addr, data = write
            for name in WINDOWS:
                base = DEF.bus[name]
                if base <= addr < base + 4:
                    n = addr - base
                    vec = self.pending[name] & ~(0xFFFFFFFF << 32 * n)
                    self.pending[name] = (vec | data << 32 * n) & TABLE
        if swap or not run:
            self.active = dict(self.pending)

    def pins(self, in_pins, out_pins, fault):
        a = self.active
        cpu_in = in_pins & ~a["FORCE_IN_MASK"] | a["FORCE_IN_VAL"] & a["FORCE_IN_MASK"]
        shown = out_pins & ~a["FORCE_OUT_MASK"] | a["FORCE_OUT_VAL"] & a["FORCE_OUT_MASK"]
        return cpu_in, 0 if fault else shown


async def reset(dut):
    await start_in_reset(dut, dut.bus_addr_i, dut.bus_wdata_i, dut.bus_we_i, dut.run_i,
                         dut.swap_i, dut.fault_i, dut.in_pins_i, dut.out_pins_i)


async def clock(dut, write=None, run=1, swap=0, fault=0, in_pins=0, out_pins=0,
                other_addr=None):
    """One clock; `write` = (addr, data) or None. Returns the pins as seen in the
    clock (before its edge). `other_addr` puts an address on the bus without a write."""
    dut.bus_we_i.value = int(write is not None)
    dut.bus_addr_i.value = write[0] if write else (other_addr or 0)
    dut.bus_wdata_i.value = write[1] if write else 0xFFFFFFFF
    dut.run_i.value, dut.swap_i.value, dut.fault_i.value = run, swap, fault
    dut.in_pins_i.value, dut.out_pins_i.value = in_pins, out_pins
    await Timer(1, unit="ns")
    seen = int(dut.in_pins_o.value), int(dut.out_pins_o.value)
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    return seen


@cocotb.test()
async def pending_until_end_while_running(dut):
    """A write while running waits for END; before RUN it applies at once."""
    await reset(dut)
    base_mask, base_val = DEF.bus["FORCE_IN_MASK"], DEF.bus["FORCE_IN_VAL"]
    await clock(dut, (base_mask + 1, 0x8000_0001), run=1)
    await clock(dut, (base_val + 1, 0x8000_0000), run=1)
    pins = (1 << 32)                      # pin 32 high, pin 63 low
    assert await clock(dut, in_pins=pins) == (pins, 0), "forced before END"
    await clock(dut, swap=1, in_pins=pins)
    assert await clock(dut, in_pins=pins) == (1 << 63, 0)
    # not running: at once, in the clock after the write
    await clock(dut, (base_mask + 1, 0), run=0)
    assert await clock(dut, run=0, in_pins=pins) == (pins, 0)


@cocotb.test()
async def outputs_forced_and_fault_drops_them(dut):
    """A forced output shows its value whatever the unit drives; a fault drops all."""
    await reset(dut)
    await clock(dut, (DEF.bus["FORCE_OUT_MASK"] + 3, 0xF), run=0)
    await clock(dut, (DEF.bus["FORCE_OUT_VAL"] + 3, 0x5), run=0)
    drive = (0xFF << 96) | 0b11
    want = (0xF0 << 96) | (0x5 << 96) | 0b11
    assert await clock(dut, out_pins=drive) == (0, want)
    assert await clock(dut, out_pins=drive, fault=1) == (0, 0)


@cocotb.test()
async def every_bit_of_every_register(dut):
    """A walking one through each register of each window, then its complement: the
    table's bit b is register b // 32's bit b % 32, and no other pin moves."""
    await reset(dut)
    model = Model()
    rng = random.Random(7)
    for name in WINDOWS:
        for n in range(4):
            for word in [1 << k for k in range(32)] + [~(1 << k) & 0xFFFFFFFF
                                                      for k in range(0, 32, 5)]:
                write = (DEF.bus[name] + n, word)
                # both masks on for the value windows' bits to show, and the other way
                for other in WINDOWS:
                    if other != name:
                        v = rng.getrandbits(32)
                        await clock(dut, (DEF.bus[other] + n, v), run=0)
                        model.clock((DEF.bus[other] + n, v), 0, 0)
                await clock(dut, write, run=0)
                model.clock(write, 0, 0)
                in_pins, out_pins = rng.getrandbits(IN_BITS), rng.getrandbits(OUT_BITS)
                got = await clock(dut, run=0, in_pins=in_pins, out_pins=out_pins)
                model.clock(None, 0, 0)
                assert got == model.pins(in_pins, out_pins, 0), (name, n, hex(word))


@cocotb.test()
async def random_against_model(dut):
    """Random writes (to the table and to the bus addresses around it), RUN, END and
    faults, against the model."""
    await reset(dut)
    model = Model()
    rng = random.Random(2024)
    lo, hi = DEF.bus["FORCE_IN_MASK"], DEF.bus["FORCE_OUT_VAL"] + 3
    run = 0
    for i in range(3000):
        write = None
        if rng.random() < 0.5:
            addr = rng.randrange(lo - 4, hi + 5) if rng.random() < 0.9 else rng.randrange(256)
            write = (addr, rng.getrandbits(32))
        if rng.random() < 0.02:
            run ^= 1
        swap = int(rng.random() < 0.1)
        fault = int(rng.random() < 0.05)
        in_pins, out_pins = rng.getrandbits(IN_BITS), rng.getrandbits(OUT_BITS)
        want = model.pins(in_pins, out_pins, fault)
        got = await clock(dut, write, run, swap, fault, in_pins, out_pins,
                          other_addr=rng.randrange(256))
        assert got == want, f"clock {i}"
        model.clock(write, run, swap)


@pytest.mark.parametrize("sim", SIMULATORS)
def test_force_table(sim):
    run_cocotb(sim, "force_table", "test_force_table",
               parameters={"InBits": IN_BITS, "OutBits": OUT_BITS, "ForceBits": FORCE_BITS})
