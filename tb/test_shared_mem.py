"""Shared memory of a plant (docs/multicore.md, "The hardware"): banked by writer, one
synchronous RAM per writer/reader pair, the bank named with every read. Cleared after
reset (ready_o exactly 2 x SharedWords clocks after reset), a write of writer w is seen
by every reader naming bank w and by no reader naming another bank, reads have one
clock of latency, flip_i toggles sel_o; random traffic against a Python model. A read
of the word written in the same clock may return either value (the RAMs are
no_rw_check): the model accepts both there and relies on neither."""
from __future__ import annotations

import random

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from simrun import SIMULATORS, run_cocotb

CORES = 3
WORDS = 16                      # words per buffer
AW = WORDS.bit_length()         # {buffer, word}: log2(WORDS) + 1 bits
IDW = (CORES - 1).bit_length()  # bank id bits
DEPTH = 2 * WORDS               # words per bank (both buffers)


def pack(values, width):
    out = 0
    for i, v in enumerate(values):
        out |= (v & ((1 << width) - 1)) << (i * width)
    return out


def unpack(value, width, n):
    return [(value >> (i * width)) & ((1 << width) - 1) for i in range(n)]


async def start(dut):
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    await reset(dut)


async def reset(dut):
    """Asynchronous reset for one clock; returns at a falling edge with rst_ni high
    (the first clock of the clear)."""
    for sig in (dut.raddr_i, dut.rbank_i, dut.we_i, dut.waddr_i, dut.wdata_i, dut.flip_i):
        sig.value = 0
    await FallingEdge(dut.clk_i)
    dut.rst_ni.value = 0
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.rst_ni.value = 1


async def clock(dut, reads=None, writes=None, flip=0):
    """One clock. reads: per reader (addr, bank) or None (reads 0, 0); writes: per
    writer (addr, data) or None. Returns (ready_o, rdata per reader, sel_o) as seen
    during the clock, before the edge (rdata: the reads of the previous clock)."""
    reads = reads or [None] * CORES
    writes = writes or [None] * CORES
    dut.raddr_i.value = pack([r[0] if r else 0 for r in reads], AW)
    dut.rbank_i.value = pack([r[1] if r else 0 for r in reads], IDW)
    dut.we_i.value = pack([int(w is not None) for w in writes], 1)
    dut.waddr_i.value = pack([w[0] if w else 0 for w in writes], AW)
    dut.wdata_i.value = pack([w[1] if w else 0 for w in writes], 32)
    dut.flip_i.value = flip
    await Timer(1, unit="ns")
    ready = int(dut.ready_o.value)
    rdata = unpack(int(dut.rdata_o.value), 32, CORES) if ready else None
    sel = int(dut.sel_o.value)
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    return ready, rdata, sel


async def wait_ready(dut):
    """Counts the clocks from the release of reset until ready_o (checking it stays
    low meanwhile); returns that count."""
    n = 0
    while not (await clock(dut))[0]:
        n += 1
        assert n <= 4 * DEPTH, "ready_o never rose"
    return n


async def read_all(dut):
    """Every reader reads every word of every bank; returns got[reader][bank][addr]."""
    got = [[[None] * DEPTH for _ in range(CORES)] for _ in range(CORES)]
    reqs = [(a, b) for b in range(CORES) for a in range(DEPTH)]
    prev = None
    for i in range(len(reqs) + 1):
        # reader r reads the request list rotated by r, so that in one clock the
        # readers name different banks
        cur = [reqs[(i + r * 7) % len(reqs)] for r in range(CORES)] if i < len(reqs) else None
        _, rdata, _ = await clock(dut, reads=cur)
        if prev is not None:
            for r, (a, b) in enumerate(prev):
                got[r][b][a] = rdata[r]
        prev = cur
    return got


@cocotb.test()
async def cleared_after_reset(dut):
    """ready_o rises exactly 2 x SharedWords clocks after reset; then every word of
    every bank reads 0 on every read port, also after the banks held other data."""
    await start(dut)
    assert await wait_ready(dut) == DEPTH
    # fill every bank with non-zero data, check it is there
    rng = random.Random(1)
    filled = [[rng.randrange(1, 1 << 32) for _ in range(DEPTH)] for _ in range(CORES)]
    for a in range(DEPTH):
        await clock(dut, writes=[(a, filled[w][a]) for w in range(CORES)])
    got = await read_all(dut)
    for r in range(CORES):
        assert got[r] == filled, f"reader {r}"
    # a second reset clears them again, in the same number of clocks
    await reset(dut)
    assert await wait_ready(dut) == DEPTH
    got = await read_all(dut)
    for r in range(CORES):
        assert got[r] == [[0] * DEPTH for _ in range(CORES)], f"reader {r}"


@cocotb.test()
async def a_write_is_seen_in_its_bank_only(dut):
    """All writers write the same addresses with values unique to the writer: every
    reader naming bank w reads writer w's value, never another writer's."""
    await start(dut)
    await wait_ready(dut)
    rng = random.Random(2)
    addrs = rng.sample(range(DEPTH), 6)
    vals = {(w, a): (w << 24) | (a << 8) | rng.randrange(256) | 0x8000_0000
            for w in range(CORES) for a in addrs}
    for a in addrs:
        await clock(dut, writes=[(a, vals[w, a]) for w in range(CORES)])
    # only writer 1 writes one more address: the other banks keep 0 there
    lone = next(a for a in range(DEPTH) if a not in addrs)
    await clock(dut, writes=[None, (lone, 0x1234_5678), None])
    got = await read_all(dut)
    for r in range(CORES):
        for b in range(CORES):
            for a in range(DEPTH):
                want = vals.get((b, a), 0x1234_5678 if (b, a) == (1, lone) else 0)
                assert got[r][b][a] == want, f"reader {r} bank {b} addr {a}"


@cocotb.test()
async def read_latency_and_bank_per_read(dut):
    """The data of a read arrives in the next clock, from the bank named with that
    read (not the bank named in the clock the data arrives)."""
    await start(dut)
    await wait_ready(dut)
    for w in range(CORES):
        writes = [None] * CORES
        writes[w] = (5, 0xA0 + w)
        await clock(dut, writes=writes)
    banks = [0, 2, 1, 1, 0, 2, 2, 0]
    prev = None
    for b in banks:
        _, rdata, _ = await clock(dut, reads=[(5, b), (5, (b + 1) % CORES), (4, b)])
        if prev is not None:
            assert rdata == [0xA0 + prev, 0xA0 + (prev + 1) % CORES, 0], (prev, b)
        prev = b


@cocotb.test()
async def flip_toggles_sel(dut):
    await start(dut)
    rng = random.Random(3)
    sel = 0
    for _ in range(200):
        flip = rng.randrange(1 << CORES) if rng.random() < 0.5 else 0
        _, _, got = await clock(dut, flip=flip)
        assert got == sel
        sel ^= flip
    await reset(dut)
    assert (await clock(dut))[2] == 0                   # reset: buffer 0 everywhere


@cocotb.test()
async def random_traffic(dut):
    """Random writes (any writer, any word, both buffers, often the same word) and
    random reads (any bank) against a model of Cores banks; a read of the word its
    bank writes in the same clock may return the old or the new value."""
    await start(dut)
    await wait_ready(dut)
    rng = random.Random(4)
    mem = [[0] * DEPTH for _ in range(CORES)]
    hot = rng.sample(range(DEPTH), 3)                   # collisions on purpose
    sel = 0
    pending = None           # per reader: the set of values its last read may return
    collisions = 0
    for _ in range(2500):
        def addr():
            return rng.choice(hot) if rng.random() < 0.5 else rng.randrange(DEPTH)
        writes = [(addr(), rng.randrange(1 << 32)) if rng.random() < 0.6 else None
                  for _ in range(CORES)]
        reads = [(addr(), rng.randrange(CORES)) for _ in range(CORES)]
        flip = rng.randrange(1 << CORES) if rng.random() < 0.1 else 0
        ready, rdata, got_sel = await clock(dut, reads=reads, writes=writes, flip=flip)
        assert ready == 1 and got_sel == sel
        if pending is not None:
            for r in range(CORES):
                assert rdata[r] in pending[r], (r, hex(rdata[r]), pending[r])
        pending = []
        for a, b in reads:
            ok = {mem[b][a]}
            if writes[b] is not None and writes[b][0] == a:
                ok.add(writes[b][1])                    # either value: not relied upon
                collisions += 1
            pending.append(ok)
        for w, wr in enumerate(writes):
            if wr is not None:
                mem[w][wr[0]] = wr[1]
        sel ^= flip
    _, rdata, _ = await clock(dut)
    for r in range(CORES):
        assert rdata[r] in pending[r]
    assert collisions > 100
    got = await read_all(dut)
    for r in range(CORES):
        assert got[r] == mem, f"reader {r}"


@pytest.mark.parametrize("sim", SIMULATORS)
def test_shared_mem(sim):
    run_cocotb(sim, "shared_mem", "test_shared_mem",
               parameters={"Cores": CORES, "SharedWords": WORDS})
