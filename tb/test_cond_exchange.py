"""The condition exchange (rtl/cond_exchange.v) in each of its four settings, and
switching between them, against a model made of the three circuits' documented
behaviour: the handshake flip-flops (Fig. 11: one place per channel), the strict queue
(a FIFO of QueueDepth conditions), the free-running queue (slot i holds the i-th
condition of the writer's scan; losses counted, the bus's counts a clock late) and the
marker area (Fig. 17: each reader's snapshot of the writer's cells, taken at its scan
start; with the write buffer, of the cells published at the writer's scan end; cell k
by index through the cell ports, a read's cell a clock later). Every output is
compared in every clock, with random requests, data and scan starts/ends.
The selection takes effect in the clock after exchange_i is set; the comparison starts
when the marker area's RAMs are cleared after reset (4 * cells / 16 clocks)."""
from __future__ import annotations

import random

import cocotb
import pytest
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, Timer

from bitbyte.lang.definition import DEF
from simrun import SIMULATORS, run_cocotb
from tbutil import start_in_reset

CHANNELS = 4           # the module's defaults
DEPTH = 8
CELLS = DEF.sizes["marker_cells"]
ALL = (1 << CHANNELS) - 1
# exchange_i codes: the run-time settings' order (bit_isa.vh's EXCHANGE_*)
CODE = {name: code for code, name in enumerate(DEF.exchanges)}
HANDSHAKE, QUEUE, QUEUE_FREE, MARKER = "handshake", "queue", "queue-free", "marker"
assert set(CODE) == {HANDSHAKE, QUEUE, QUEUE_FREE, MARKER}


class Handshake:
    """One direction's flip-flops: a place per channel, full or empty."""

    def __init__(self):
        self.full = [False] * CHANNELS
        self.data = [0] * CHANNELS

    def outputs(self):
        full = sum(f << k for k, f in enumerate(self.full))
        return {"wr_ready": ALL ^ full, "rd_ready": full, "full": full,
                "rd_data": sum(d << k for k, d in enumerate(self.data))}

    def clock(self, wr: int, data: int, rd: int) -> None:
        for k in range(CHANNELS):
            if rd >> k & 1 and self.full[k]:
                self.full[k] = False
            elif wr >> k & 1 and not self.full[k]:
                self.full[k], self.data[k] = True, data


class Queue:
    """One direction's queue (Fig. 16): DEPTH slots, a write and a read position.
    Strict: a FIFO of up to DEPTH held items; the writer waits while it is full, the
    reader while it is empty. Free-running: nobody waits; each position returns to
    slot 0 at its owner's scan start (that clock's access already at slot 0), so slot
    i takes the i-th write of the writer's scan and gives the reader its i-th read; a
    slot holds an item from its write until it is read. A write over a held item (not
    read in that clock) is an overflow, a read of a slot holding none an underflow (it
    gives the slot's last value); the counts saturate at 65535 and reach the bus a
    clock after the loss (overflows_now_o: at once)."""

    def __init__(self):
        self.data = [0] * DEPTH
        self.held = [False] * DEPTH
        self.wpos = self.rpos = 0
        self.count = 0                        # strict: items in the FIFO
        self.over = self.under = 0            # the bus's counts
        self.over_new = self.under_new = 0    # last clock's losses, counted in this one

    @staticmethod
    def _add(count: int, event: int) -> int:
        return min(count + event, 0xFFFF)

    def slots(self, free: bool, wr_start: int, rd_start: int):
        return (0 if free and wr_start else self.wpos), (0 if free and rd_start else self.rpos)

    def counts(self) -> dict:
        return {"over": self.over, "under": self.under,
                "over_now": self._add(self.over, self.over_new),
                "under_now": self._add(self.under, self.under_new)}

    def outputs(self, free: bool, wr_start: int, rd_start: int) -> dict:
        ws, rs = self.slots(free, wr_start, rd_start)
        wr_ready = free or self.count < DEPTH
        rd_ready = free or self.count > 0
        full = self.held[ws] if free else self.count == DEPTH
        return {"wr_ready": ALL if wr_ready else 0, "rd_ready": ALL if rd_ready else 0,
                "full": int(full), "rd_data": ALL if self.data[rs] else 0}

    def clock(self, free: bool, wr: int, data: int, rd: int, wr_start: int, rd_start: int):
        ws, rs = self.slots(free, wr_start, rd_start)
        do_wr = bool(wr) and (free or self.count < DEPTH)
        do_rd = bool(rd) and (free or self.count > 0)
        overflow = free and do_wr and self.held[ws] and not (do_rd and rs == ws)
        underflow = free and do_rd and not self.held[rs]
        self.over = self._add(self.over, self.over_new)
        self.under = self._add(self.under, self.under_new)
        self.over_new, self.under_new = int(overflow), int(underflow)
        if do_rd:
            self.held[rs] = False
        if do_wr:
            self.data[ws], self.held[ws] = data, True
        self.count += do_wr - do_rd
        self.wpos, self.rpos = (ws + do_wr) % DEPTH, (rs + do_rd) % DEPTH


class Markers:
    """Both directions' marker cells (marker_region.v each): each side's cells as
    written and as published (at its scan end, that clock's write included), each
    reader's snapshot of the other side's visible cells (published with the write
    buffer, else live) taken at its snapshot clock and seen already by a read in that
    clock; a read's cell comes in the next clock. The bit side's snapshot clock is
    bit_snap_i (the clock before its scan start: it reads its first instruction's cell
    then), the byte side's its scan start. Writes are taken in the marker setting only,
    snapshots, publications and reads whatever the setting."""

    def __init__(self):
        self.work = {"bit": 0, "byte": 0}
        self.pub = {"bit": 0, "byte": 0}
        self.snap = {"bit": 0, "byte": 0}
        # the cell a reader's read of the last clock returns (None: no read then; the
        # port shows a cell only in the clock after its read)
        self.pending = {"bit": None, "byte": None}

    def visible(self, side: str, buffered: int) -> int:
        return self.pub[side] if buffered else self.work[side]

    def outputs(self) -> dict:
        return {"bit_cell": self.pending["bit"], "byte_cell": self.pending["byte"]}

    def clock(self, i: dict, on: bool) -> None:
        buffered = i["buffer"]
        for side, other in (("bit", "byte"), ("byte", "bit")):
            snap = i["bit_snap"] if side == "bit" else i["byte_start"]
            if snap:
                self.snap[side] = self.visible(other, buffered)
            self.pending[side] = (self.snap[side] >> i[f"{side}_cridx"] & 1
                                  if i[f"{side}_cre"] else None)
        for side in ("bit", "byte"):
            if on and i[f"{side}_cwe"]:
                bit = 1 << i[f"{side}_cwidx"]
                self.work[side] = (self.work[side] & ~bit) | (bit if i[f"{side}_cwdata"] else 0)
            if i[f"{side}_end"]:
                self.pub[side] = self.work[side]


class Exchange:
    """cond_exchange with every circuit built. The setting of the clock before selects
    the circuit (after reset: none — the flip-flops' outputs show, and nothing takes a
    request); a circuit not selected keeps its state."""

    def __init__(self):
        self.sel = None
        self.ff = {"fby": Handshake(), "fbi": Handshake()}
        self.queue = {"fby": Queue(), "fbi": Queue()}
        self.markers = Markers()

    @staticmethod
    def _starts(i, d):
        # fby: the bit side writes, the byte side reads; fbi the other way round
        return (i["bit_start"], i["byte_start"]) if d == "fby" else \
            (i["byte_start"], i["bit_start"])

    def outputs(self, i: dict) -> dict:
        out = {}
        free = self.sel == QUEUE_FREE
        for d in ("fby", "fbi"):
            if self.sel in (QUEUE, QUEUE_FREE):
                o = self.queue[d].outputs(free, *self._starts(i, d))
            elif self.sel == MARKER:   # the cells go through the cell ports
                o = {"wr_ready": ALL, "rd_ready": ALL, "full": 0, "rd_data": 0}
            else:
                o = self.ff[d].outputs()
            for k, v in o.items():
                out[f"{d}_{k}"] = v
        out.update(self.markers.outputs(), marker=int(self.sel == MARKER))
        # the loss counts: {to-bit (fbi), to-byte (fby)}
        for name in ("over", "under", "over_now", "under_now"):
            out[name] = self.queue["fbi"].counts()[name] << 16 | self.queue["fby"].counts()[name]
        return out

    def clock(self, i: dict) -> None:
        free = self.sel == QUEUE_FREE
        on_queue = self.sel in (QUEUE, QUEUE_FREE)
        for d in ("fby", "fbi"):
            wr, rd, data = i[f"{d}_wr"], i[f"{d}_rd"], i[f"{d}_data"]
            on_ff = self.sel == HANDSHAKE
            self.ff[d].clock(wr if on_ff else 0, data, rd if on_ff else 0)
            self.queue[d].clock(free, wr if on_queue else 0, data, rd if on_queue else 0,
                                *self._starts(i, d))
        self.markers.clock(i, self.sel == MARKER)
        self.sel = i["exchange"]


INPUTS = {"exchange": "exchange_i", "buffer": "marker_write_buffer_i",
          "bit_start": "bit_start_i", "bit_end": "bit_end_i",
          "byte_start": "byte_start_i", "byte_end": "byte_end_i",
          "fby_wr": "fby_wr_req_i", "fby_data": "fby_wr_data_i", "fby_rd": "fby_rd_req_i",
          "fbi_wr": "fbi_wr_req_i", "fbi_data": "fbi_wr_data_i", "fbi_rd": "fbi_rd_req_i",
          "bit_snap": "bit_snap_i",
          **{f"{side}_{k}": f"{side}_cell_{port}_i" for side in ("bit", "byte")
             for k, port in (("cwe", "we"), ("cwidx", "widx"), ("cwdata", "wdata"),
                             ("cre", "re"), ("cridx", "ridx"))}}
OUTPUTS = {f"{d}_{k}": f"{d}_{k}_o" for d in ("fby", "fbi")
           for k in ("wr_ready", "rd_ready", "full", "rd_data")}
OUTPUTS.update(over="overflows_o", under="underflows_o", over_now="overflows_now_o",
               under_now="underflows_now_o", bit_cell="bit_cell_rdata_o",
               byte_cell="byte_cell_rdata_o", marker="marker_o")


def requests(rng: random.Random, one_hot: bool) -> int:
    """A side's request vector: none, one channel, or (the circuit must cope) any."""
    r = rng.random()
    if r < 0.45:
        return 0
    if one_hot or r < 0.85:
        return 1 << rng.randrange(CHANNELS)
    return rng.randrange(1, ALL + 1)


async def against_model(dut, model: Exchange, settings, rng: random.Random,
                        buffer: int, busy: float = 0.5) -> None:
    """One clock per entry of `settings` (the exchange setting of that clock), random
    traffic; every output against the model before each edge."""
    for clk, setting in enumerate(settings):
        i = {"exchange": setting, "buffer": buffer}
        for side in ("bit", "byte"):
            i[f"{side}_start"] = int(rng.random() < 0.08)
            i[f"{side}_end"] = int(rng.random() < 0.08)
            # cells: indices clustered on a few words (merges meet), any cell at times
            pick = (lambda: rng.choice((0, 1, 17, 18, CELLS - 1))) if rng.random() < 0.7 \
                else (lambda: rng.randrange(CELLS))
            i[f"{side}_cwe"] = int(rng.random() < busy)
            i[f"{side}_cwidx"], i[f"{side}_cwdata"] = pick(), rng.getrandbits(1)
            i[f"{side}_cre"] = int(rng.random() < busy)
            i[f"{side}_cridx"] = pick()
        i["bit_snap"] = int(rng.random() < 0.08)
        for d in ("fby", "fbi"):
            i[f"{d}_wr"] = requests(rng, False) if rng.random() < busy else 0
            i[f"{d}_rd"] = requests(rng, False) if rng.random() < busy else 0
            i[f"{d}_data"] = rng.getrandbits(1)
        for key, sig in INPUTS.items():
            getattr(dut, sig).value = CODE[i[key]] if key == "exchange" else i[key]
        await Timer(1, unit="ns")
        want = model.outputs(i)
        got = {k: int(getattr(dut, sig).value) if want[k] is not None else None
               for k, sig in OUTPUTS.items()}
        diff = {k: (got[k], want[k]) for k in OUTPUTS
                if want[k] is not None and got[k] != want[k]}
        assert not diff, (clk, setting, model.sel, i, diff)
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
        model.clock(i)


async def reset(dut, setting: str):
    """Reset with `setting`; return at the clock the marker area's RAMs are cleared
    (4 * CELLS / 16 clocks), the setting taken, with the model of that state."""
    await start_in_reset(dut, *(getattr(dut, s) for s in INPUTS.values()),
                         exchange_i=CODE[setting])
    assert int(dut.marker_ready_o.value) == 0
    clocks = 0
    while not int(dut.marker_ready_o.value):
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
        clocks += 1
    assert clocks == 4 * CELLS // 16
    model = Exchange()
    model.sel = setting
    return model


async def one_setting(dut, setting: str, buffer: int, seed: int, clocks: int = 500):
    model = await reset(dut, setting)
    await against_model(dut, model, [setting] * clocks, random.Random(seed), buffer)


@cocotb.test()
async def handshake_channels(dut):
    await one_setting(dut, HANDSHAKE, 0, 1)


@cocotb.test()
async def strict_queue(dut):
    await one_setting(dut, QUEUE, 0, 2)


@cocotb.test()
async def strict_queue_fills(dut):
    """Mostly writes: the queue fills, the writer waits; then mostly reads."""
    model = await reset(dut, QUEUE)
    rng = random.Random(5)
    await against_model(dut, model, [QUEUE] * 40, rng, 0, busy=0.9)
    await against_model(dut, model, [QUEUE] * 40, rng, 0, busy=0.3)


@cocotb.test()
async def free_running_queue(dut):
    await one_setting(dut, QUEUE_FREE, 0, 3, clocks=800)


@cocotb.test()
async def marker_live_cells(dut):
    await one_setting(dut, MARKER, 0, 4)


@cocotb.test()
async def marker_write_buffer(dut):
    await one_setting(dut, MARKER, 1, 6)


@cocotb.test()
async def switching_settings(dut):
    """The setting changed at random clocks: each circuit keeps its state while not
    selected and takes no request then; the free queue's losses stay counted."""
    model = await reset(dut, HANDSHAKE)
    rng = random.Random(8)
    settings, setting = [], HANDSHAKE
    for _ in range(1500):
        if rng.random() < 0.02:
            setting = rng.choice([HANDSHAKE, QUEUE, MARKER, MARKER])
        settings.append(setting)
    # then free-running from the strict queue's state, and the others again (not the
    # strict queue: its fill level is not defined after free-running)
    settings += [QUEUE_FREE] * 300 + [HANDSHAKE] * 100 + [MARKER] * 100
    await against_model(dut, model, settings, rng, rng.getrandbits(1))


async def counts_every_bit(dut, kind: str):
    """Free-running, one loss per clock in both directions (reads of an empty queue,
    or writes into a full one): both counts, at the bus and exact, pass 0x0555, 0x0AAA,
    0x1555 and 0x2AAA (bits 13..0 each at 1 and at 0, beside its neighbours; bits 15..14
    and the saturation take 65 535 clocks: tb/test_cond_queue.py's saturation test)."""
    await reset(dut, QUEUE_FREE)
    req = "rd" if kind == "under" else "wr"
    for d in ("fby", "fbi"):
        getattr(dut, f"{d}_{req}_req_i").value = 1
    now_sig, bus_sig = (dut.underflows_now_o, dut.underflows_o) if kind == "under" else \
        (dut.overflows_now_o, dut.overflows_o)
    await ClockCycles(dut.clk_i, 2 * DEPTH)        # the setting taken, the slots full
    await FallingEdge(dut.clk_i)
    for target in (0x0555, 0x0AAA, 0x1555, 0x2AAA):
        now = int(now_sig.value)
        assert now >> 16 == now & 0xFFFF, hex(now)
        await ClockCycles(dut.clk_i, target - (now & 0xFFFF))
        await FallingEdge(dut.clk_i)
        assert int(now_sig.value) == target << 16 | target
        assert int(bus_sig.value) == (target - 1) << 16 | (target - 1)   # a clock late


@cocotb.test()
async def underflow_counts_every_bit(dut):
    await counts_every_bit(dut, "under")


@cocotb.test()
async def overflow_counts_every_bit(dut):
    await counts_every_bit(dut, "over")


@pytest.mark.parametrize("sim", SIMULATORS)
def test_cond_exchange(sim):
    run_cocotb(sim, "cond_exchange", "test_cond_exchange")
