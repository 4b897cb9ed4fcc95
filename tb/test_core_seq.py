"""Core sequencer of a plant core (rtl/core_seq.v, docs/multicore.md "The hardware",
"Protection"), its ports driven directly: a fake CPU (ready low for N clocks after the
RUN pulse, then a scan_done pulse), a scripted semaphore grant, the M bits, the MW
words and the shared memory modelled in Python with one clock of read latency.

Every run is checked clock by clock against an independent model written from the
documentation, not from the RTL:
* scan k starts at k * period (back to back with period 0), a late scan right after
  the previous one, counted as an overrun (the grid does not shift);
* a scan is precycle (lock, copy shared -> local), RUN (held until the CPU is ready;
  it latches in that clock), the scan, postcycle (lock, copy local -> shared);
  pre / post / sem_wait counted as documented;
* the copy engine: plan entry j of a list is fetched in copy clock j, its source is
  read in j + 1 and its destination written in j + 2: one entry per clock without
  stalls, so the data of a list of n entries moves in n + 2 clocks. The copy state
  lasts one clock more (n + 3 clocks; n + 2 when the list ends with a descriptor, 1
  when it is empty): the clock that releases the lock (semaphore) or publishes the
  buffer (ping-pong), without reads or writes. The data moved is what the plan says:
  bit items gathered into one whole-word write per run of consecutive bit items of
  one shared word, MW words sign-extended to 32 bits, their low 16 bits copied back;
* semaphore: no shared access before the grant, release in the last copy clock; a
  precycle gives up at the first clock in which
  now + pre_entries + post_entries + last scan's cycles + 6 > nominal start + period
  (no copy, copy_fail sticky, skips counted, the CPU still started); a postcycle waits
  however long;
* ping-pong: reads of writer w use w's select as it was when the precycle began,
  writes go to buffer !sel[own], sh_flip in the last postcycle clock; a read of writer
  w after w began overwriting the buffer being read sets copy_fail.
"""
from __future__ import annotations

import random
from dataclasses import dataclass, field

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from simrun import SIMULATORS, run_cocotb

CORES = 4
SHARED_WORDS = 64
MARKER_BITS = 256
MW_WORDS = 32
OWN = 2                          # this core's id: its postcycles write bank OWN
PLAN_WORDS = 256                 # the main build; the known-bug build uses 128
SEM, PING, NONE = 0, 1, 2
SW_BITS = SHARED_WORDS.bit_length() - 1


def params(plan_words):
    return {"Cores": CORES, "PlanWords": plan_words, "SharedWords": SHARED_WORDS,
            "MarkerBits": MARKER_BITS, "MwWords": MW_WORDS}


# --------------------------------------------------------------------- the copy plan

def desc(writer):
    return (1 << 31) | (writer << 16)


def bit_item(word, pos, local):
    return (1 << 30) | (pos << 25) | (word << 12) | local


def word_item(word, local):
    return (word << 12) | local


def decode(e):
    """('d', writer) | ('b', word, pos, local) | ('w', word, local): the documented
    fields, [31] descriptor, [23:16] writer, [30] bit, [29:25] bit position,
    [24:12] shared word, [11:0] local address."""
    if e >> 31:
        return ("d", (e >> 16) & 0xFF)
    word, local = (e >> 12) & 0x1FFF, e & 0xFFF
    if (e >> 30) & 1:
        return ("b", word, (e >> 25) & 31, local)
    return ("w", word, local)


def copy_clocks(lst):
    """Clocks in the copy state: entry j is fetched in copy clock j, accessed in j + 1,
    written in j + 2; the clock after the last of these ends the copy."""
    if not lst:
        return 1
    last_work = len(lst) + (0 if lst[-1][0] == "d" else 1)   # E - 1 + (1 or 2)
    return last_work + 2


def pre_moves(lst):
    """Precycle items: (j, writer, kind, word, pos, local), the writer from the last
    descriptor before the item."""
    out, writer = [], None
    for j, e in enumerate(lst):
        if e[0] == "d":
            writer = e[1]
        elif e[0] == "b":
            out.append((j, writer, "b", e[1], e[2], e[3]))
        else:
            out.append((j, writer, "w", e[1], 0, e[2]))
    return out


def post_writes(lst):
    """Postcycle shared writes: [j_last, word, [(j, kind, pos, local)]], one per word
    item and one per run of consecutive bit items of the same shared word."""
    out, prev = [], None           # prev: (j, word) of the last bit item
    for j, e in enumerate(lst):
        if e[0] == "b":
            if prev == (j - 1, e[1]):
                out[-1][0] = j
                out[-1][2].append((j, "b", e[2], e[3]))
            else:
                out.append([j, e[1], [(j, "b", e[2], e[3])]])
            prev = (j, e[1])
        else:
            prev = None
            if e[0] == "w":
                out.append([j, e[1], [(j, "w", 0, e[2])]])
    return out


def sext16(v):
    v &= 0xFFFF
    return (v | 0xFFFF0000) if v & 0x8000 else v


# --------------------------------------------------------------------- scenario, model

@dataclass
class Scenario:
    protect: int
    period: int
    entries: list                  # plan RAM from address 0
    pre_len: int
    post_base: int
    post_len: int
    scan_len: list                 # per scan: clocks the CPU is busy after the RUN pulse
    pre_wait: list | None = None   # semaphore, per scan: clocks the lock is withheld in
                                   # the precycle, or ("X", d): granted at give-up clock + d
    post_wait: list | None = None  # semaphore, per scan: clocks withheld in the postcycle
    sel_flips: dict = field(default_factory=dict)  # clock -> other writers flipping at its end
    posting: dict = field(default_factory=dict)    # clock -> other writers writing then
    cpu_unready: set = field(default_factory=set)  # clocks the idle CPU is not ready
    seed: int = 0


@dataclass
class Expect:
    lock_req: set = field(default_factory=set)
    grant: set = field(default_factory=set)
    copy_en: set = field(default_factory=set)
    cpu_run: set = field(default_factory=set)
    release: set = field(default_factory=set)
    flip: set = field(default_factory=set)
    done: dict = field(default_factory=dict)        # clock -> status tuple
    pre_reads: dict = field(default_factory=dict)   # clock -> (buf, word, writer)
    local_writes: list = field(default_factory=list)  # (clock, read clock, kind, pos, local)
    post_reads: dict = field(default_factory=dict)  # clock -> (kind, local)
    sh_writes: list = field(default_factory=list)   # (clock, buf, word, [(read clock, kind, pos)])
    starts: list = field(default_factory=list)
    fail_clock: int | None = None                   # first clock copy_fail_o reads 1
    skips: int = 0
    overruns: int = 0
    end: int = 0


def other_sel(sc, t):
    """Select bits of the other writers at clock t (flips take effect after their clock)."""
    sel = 0
    for c, mask in sc.sel_flips.items():
        if c < t:
            sel ^= mask
    return sel & ~(1 << OWN)


def model(sc):
    pre = [decode(e) for e in sc.entries[:sc.pre_len]]
    post = [decode(e) for e in sc.entries[sc.post_base:sc.post_base + sc.post_len]]
    sem, ping = sc.protect == SEM, sc.protect == PING
    n = len(sc.scan_len)
    pre_wait = sc.pre_wait or [0] * n
    post_wait = sc.post_wait or [0] * n
    x = Expect()
    free = nominal = 0
    own_sel = 0
    last_cycles = 0
    for k in range(n):
        # ---- the start: k * period, or right after the previous scan when late
        if k == 0:
            start = nominal = 0
        elif sc.period:
            nominal += sc.period
            start = max(free, nominal)
        else:
            start = nominal = free
        late = k > 0 and sc.period > 0 and start > nominal
        x.overruns += late
        x.starts.append(start)
        snap = other_sel(sc, start) | (own_sel << OWN)
        waits = 0
        t = start + 1
        skipped = False
        # ---- precycle
        if sem and pre:
            need = sc.pre_len + sc.post_len + last_cycles + 6
            give_up_at = max(start + 1, nominal + sc.period - need + 1) if sc.period else None
            w = pre_wait[k]
            free_at = give_up_at + w[1] if isinstance(w, tuple) else start + 1 + w
            while True:
                x.lock_req.add(t)
                if t >= free_at:
                    x.grant.add(t)
                    break
                if give_up_at is not None and t >= give_up_at:
                    skipped = True
                    waits += 1
                    break
                waits += 1
                t += 1
        if skipped:
            x.skips += 1
            run = t + 1
            if x.fail_clock is None:
                x.fail_clock = t + 1
        else:
            c0 = t + 1 if (sem and pre) else start + 1
            nc = copy_clocks(pre)
            x.copy_en.update(range(c0, c0 + nc))
            if sem and pre:
                x.release.add(c0 + nc - 1)
            for j, writer, kind, word, pos, local in pre_moves(pre):
                buf = (snap >> writer) & 1 if ping else 0
                rc = c0 + j + 1
                x.pre_reads[rc] = (buf, word, writer)
                x.local_writes.append((rc + 1, rc, kind, pos, local))
                if ping and writer != OWN:
                    # overtaken: the writer wrote its bank while its select differed from
                    # the snapshot (it writes !sel: the buffer being read), up to this read
                    for c in range(start + 1, rc + 1):
                        if (sc.posting.get(c, 0) >> writer) & 1 and \
                                ((other_sel(sc, c) ^ snap) >> writer) & 1:
                            if x.fail_clock is None or x.fail_clock > rc + 1:
                                x.fail_clock = rc + 1
                            break
            run = c0 + nc
        # ---- RUN until the CPU is ready; it latches at the end of that clock, is busy
        # N clocks, then pulses scan_done
        first = run
        while run in sc.cpu_unready:
            run += 1
        x.cpu_run.update(range(first, run + 1))
        scan_done = run + sc.scan_len[k] + 1
        t = scan_done + 1
        # ---- postcycle
        if sem and post:
            free_at = scan_done + 1 + post_wait[k]
            while t < free_at:
                x.lock_req.add(t)
                waits += 1
                t += 1
            x.lock_req.add(t)
            x.grant.add(t)
            t += 1
        c0 = t
        nc = copy_clocks(post)
        end = c0 + nc - 1
        x.copy_en.update(range(c0, end + 1))
        if sem and post:
            x.release.add(end)
        wbuf = 1 - own_sel if ping else 0
        for jl, word, parts in post_writes(post):
            rparts = []
            for j, kind, pos, local in parts:
                x.post_reads[c0 + j + 1] = (kind, local)
                rparts.append((c0 + j + 1, kind, pos))
            x.sh_writes.append((c0 + jl + 2, wbuf, word, rparts))
        if ping:
            x.flip.add(end)
            own_sel ^= 1
        fail = int(x.fail_clock is not None and x.fail_clock <= end + 1)
        x.done[end + 1] = (run - start + 1, end - scan_done + 1, waits, int(late), fail,
                           x.overruns, x.skips)
        last_cycles = sc.scan_len[k]
        free = end + 1
    x.end = free + 1                 # the clock the next scan would start in
    return x


# --------------------------------------------------------------------- the environment

ALWAYS = ("lock_req_o", "cpu_run_o", "copy_en_o", "release_o", "sh_flip_o", "cycle_done_o",
          "sh_re_o", "sh_we_o", "m_we_o", "w_we_o", "copy_fail_o")
STATUS = ("pre_clocks_o", "post_clocks_o", "sem_wait_o", "overrun_o", "copy_fail_o",
          "overruns_o", "skips_o")


class Got:
    def __init__(self):
        self.lock_req, self.grant, self.copy_en, self.cpu_run = set(), set(), set(), set()
        self.release, self.flip = set(), set()
        self.done = {}
        self.pre_reads = {}            # clock -> (buf, word, bank)
        self.local_writes = []         # (clock, kind, addr, value)
        self.local_raddr = {}          # clock -> (m_addr, w_addr) while copying
        self.sh_writes = []            # (clock, buf, word, value)
        self.fail = []                 # copy_fail_o per clock


class Env:
    def __init__(self, dut, sc, exp):
        self.dut, self.sc, self.exp = dut, sc, exp
        rng = self.rng = random.Random(sc.seed)
        self.m = [rng.randrange(2) for _ in range(MARKER_BITS)]
        self.mw = [rng.randrange(1 << 16) for _ in range(MW_WORDS)]
        self.sh = [[[rng.randrange(1 << 32) for _ in range(SHARED_WORDS)] for _ in range(2)]
                   for _ in range(CORES)]
        self.sel = 0
        self.sh_rd = self.m_rd = self.w_rd = 0
        self.cpu_latch = None          # clock of the last RUN pulse taken
        self.cpu_n = 0
        self.scan_cycles = 0
        self.k = 0
        self.owned = False
        self.read_val = {}             # model read clock -> the value there
        self.got = Got()
        self.cache = {}

    def set(self, name, value):
        if self.cache.get(name) != value:
            getattr(self.dut, name).value = value
            self.cache[name] = value

    async def run(self):
        d, sc, exp, got = self.dut, self.sc, self.exp, self.got
        for t in range(exp.end):
            busy = self.cpu_latch is not None and t <= self.cpu_latch + self.cpu_n
            done = self.cpu_latch is not None and t == self.cpu_latch + self.cpu_n + 1
            ready = not busy and t not in sc.cpu_unready
            if done:
                self.scan_cycles = self.cpu_n
            self.set("time_i", t)
            self.set("cpu_ready_i", int(ready))
            self.set("cpu_scan_done_i", int(done))
            self.set("cpu_scan_cycles_i", self.scan_cycles)
            self.set("sh_rdata_i", self.sh_rd)
            self.set("m_rdata_i", self.m_rd)
            self.set("w_rdata_i", self.w_rd)
            self.set("sh_sel_i", self.sel)
            self.set("sh_posting_i", sc.posting.get(t, 0) & ~(1 << OWN))
            self.set("grant_i", 0)
            await Timer(1, unit="ns")
            o = {n: int(getattr(d, n).value) for n in ALWAYS}
            if o["lock_req_o"]:
                got.lock_req.add(t)
                if t in exp.grant:
                    self.set("grant_i", 1)
                    got.grant.add(t)
                    await Timer(1, unit="ns")
            for n, s in (("copy_en_o", got.copy_en), ("cpu_run_o", got.cpu_run),
                         ("release_o", got.release), ("sh_flip_o", got.flip)):
                if o[n]:
                    s.add(t)
            got.fail.append(o["copy_fail_o"])
            if o["cycle_done_o"]:
                got.done[t] = tuple(int(getattr(d, n).value) for n in STATUS)
            # semaphore: shared memory only while the lock is owned (from the clock
            # after the grant to the release clock, exclusive)
            if sc.protect == SEM:
                if o["sh_re_o"] or o["sh_we_o"]:
                    assert self.owned and not o["release_o"], f"shared access unlocked at {t}"
                if o["release_o"]:
                    assert self.owned, f"release without the lock at {t}"
            else:
                assert not o["lock_req_o"] and not o["release_o"], t
            if sc.protect != PING:
                assert not o["sh_flip_o"], t
            for n in ("m_we_o", "w_we_o", "sh_re_o", "sh_we_o"):
                assert not o[n] or o["copy_en_o"], f"{n} outside a copy at {t}"
            assert not (busy and o["copy_en_o"]), f"copy while the CPU runs at {t}"

            # ---- the edge: values the model's reads find, then the memories
            if t in exp.pre_reads:
                buf, word, writer = exp.pre_reads[t]
                self.read_val[t] = self.sh[writer][buf][word]
            if t in exp.post_reads:
                kind, local = exp.post_reads[t]
                self.read_val[t] = self.m[local] if kind == "b" else self.mw[local]
            if o["sh_re_o"]:
                raddr, bank = int(d.sh_raddr_o.value), int(d.sh_rbank_o.value)
                buf, word = raddr >> SW_BITS, raddr & (SHARED_WORDS - 1)
                got.pre_reads[t] = (buf, word, bank)
                self.sh_rd = self.sh[bank][buf][word] if bank < CORES else 0
            if o["copy_en_o"]:
                # (X in Icarus in a clock without an item: the plan RAM beyond the list)
                ma, wa = resolved(d.m_addr_o), resolved(d.w_addr_o)
                got.local_raddr[t] = (ma, wa)
                self.m_rd = self.m[ma] if ma is not None else 0
                self.w_rd = self.mw[wa] if wa is not None else 0
                if o["m_we_o"]:
                    v = int(d.m_wdata_o.value)
                    self.m[ma] = v
                    got.local_writes.append((t, "b", ma, v))
                if o["w_we_o"]:
                    v = int(d.w_wdata_o.value)
                    self.mw[wa] = v
                    got.local_writes.append((t, "w", wa, v))
            if o["sh_we_o"]:
                waddr, v = int(d.sh_waddr_o.value), int(d.sh_wdata_o.value)
                buf, word = waddr >> SW_BITS, waddr & (SHARED_WORDS - 1)
                self.sh[OWN][buf][word] = v
                got.sh_writes.append((t, buf, word, v))
            # other writers: posting writes their bank's buffer readers do not read
            for w in range(CORES):
                if w != OWN and (sc.posting.get(t, 0) >> w) & 1:
                    b = 1 - ((self.sel >> w) & 1)
                    self.sh[w][b][self.rng.randrange(SHARED_WORDS)] = self.rng.randrange(1 << 32)
            self.sel ^= sc.sel_flips.get(t, 0) & ~(1 << OWN)
            if o["sh_flip_o"]:
                self.sel ^= 1 << OWN
            if t in got.grant:
                self.owned = True
            if o["release_o"]:
                self.owned = False
            if o["cpu_run_o"] and ready:
                # the CPU latches: it runs N clocks and changes its M bits and MW words;
                # without ping-pong the other writers publish meanwhile (any buffer)
                self.cpu_latch, self.cpu_n = t, sc.scan_len[self.k]
                self.k += 1
                for _ in range(24):
                    self.m[self.rng.randrange(MARKER_BITS)] ^= 1
                for _ in range(8):
                    self.mw[self.rng.randrange(MW_WORDS)] = self.rng.randrange(1 << 16)
                if sc.protect != PING:
                    for _ in range(16):
                        w = self.rng.choice([c for c in range(CORES) if c != OWN])
                        self.sh[w][self.rng.randrange(2)][self.rng.randrange(SHARED_WORDS)] = \
                            self.rng.randrange(1 << 32)
            await RisingEdge(d.clk_i)
            await FallingEdge(d.clk_i)


def resolved(sig):
    v = sig.value
    return int(v) if v.is_resolvable else None


def same(what, got, want):
    if got == want:
        return
    if isinstance(want, dict):
        bad = sorted(c for c in set(got) | set(want) if got.get(c) != want.get(c))
        raise AssertionError(f"{what}: first differences (clock, got, want): "
                             f"{[(c, got.get(c), want.get(c)) for c in bad[:4]]}")
    g, w = set(got), set(want)
    raise AssertionError(f"{what}: unexpected {sorted(g - w)[:6]}, missing {sorted(w - g)[:6]}"
                         f" (got {len(got)}, want {len(want)})")


def check(env, status=True):
    """Everything the model predicts, clock by clock."""
    x, got = env.exp, env.got
    same("lock_req_o clocks", got.lock_req, x.lock_req)
    same("grant clocks", got.grant, x.grant)
    same("copy_en_o clocks", got.copy_en, x.copy_en)
    same("cpu_run_o clocks", got.cpu_run, x.cpu_run)
    same("release_o clocks", got.release, x.release)
    same("sh_flip_o clocks", got.flip, x.flip)
    same("shared reads (clock: buf, word, bank)", got.pre_reads, x.pre_reads)
    want = []
    for wc, rc, kind, pos, local in x.local_writes:
        v = env.read_val[rc]
        want.append((wc, kind, local, (v >> pos) & 1 if kind == "b" else v & 0xFFFF))
    same("local writes (clock, kind, addr, value)", got.local_writes, want)
    for c, (kind, local) in x.post_reads.items():
        ma, wa = got.local_raddr[c]
        assert (ma if kind == "b" else wa) == local, (c, kind, local, ma, wa)
    want = []
    for wc, buf, word, parts in x.sh_writes:
        if parts[0][1] == "w":
            v = sext16(env.read_val[parts[0][0]])
        else:
            v = 0
            for rc, _, pos in parts:
                v |= env.read_val[rc] << pos
        want.append((wc, buf, word, v))
    same("shared writes (clock, buf, word, value)", got.sh_writes, want)
    first_fail = got.fail.index(1) if 1 in got.fail else None
    assert first_fail == x.fail_clock, ("copy_fail_o first set", first_fail, x.fail_clock)
    if first_fail is not None:
        assert all(got.fail[first_fail:]), "copy_fail_o is sticky"
    same("cycle_done_o clocks", set(got.done), set(x.done))
    if status:
        same("status at cycle_done (pre, post, sem_wait, overrun, copy_fail, overruns, "
             "skips)", got.done, x.done)


async def run_scenario(dut, sc, status=True):
    """Reset with sc's configuration, load the plan while stopped, run every scan of sc
    (clock 0 = the first clock with run_i), check against the model; returns the model."""
    plan_words = 1 << len(dut.plan_waddr_i)
    assert len(sc.entries) <= plan_words and sc.post_base + sc.post_len <= plan_words
    exp = model(sc)
    dut.rst_ni.value = 0
    for name in ("plan_we_i", "plan_waddr_i", "plan_wdata_i", "run_i", "time_i",
                 "cpu_ready_i", "cpu_scan_done_i", "cpu_scan_cycles_i", "grant_i",
                 "sh_rdata_i", "sh_sel_i", "sh_posting_i", "m_rdata_i", "w_rdata_i"):
        getattr(dut, name).value = 0
    dut.period_i.value = sc.period * 1000       # the port counts 1/1000 clocks
    dut.pre_len_i.value = sc.pre_len
    dut.post_base_i.value = sc.post_base
    dut.post_len_i.value = sc.post_len
    dut.protect_i.value = sc.protect
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.rst_ni.value = 1
    dut.cpu_ready_i.value = 1
    for a, e in enumerate(sc.entries):
        dut.plan_we_i.value, dut.plan_waddr_i.value, dut.plan_wdata_i.value = 1, a, e
        await FallingEdge(dut.clk_i)
    # the plan bus holds junk while not writing (make mutate: a write enable stuck at 1
    # rewrote the last entry with its own value, unseen)
    dut.plan_we_i.value, dut.plan_waddr_i.value = 0, 0
    dut.plan_wdata_i.value = ~sc.entries[0] & 0xFFFFFFFF if sc.entries else 0x80000000
    for _ in range(3):                               # stopped: nothing starts
        await Timer(1, unit="ns")
        assert not int(dut.copy_en_o.value) and not int(dut.lock_req_o.value)
        await FallingEdge(dut.clk_i)
    dut.run_i.value = 1
    env = Env(dut, sc, exp)
    await env.run()
    check(env, status)
    return exp


async def start_clock(dut):
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())


# --------------------------------------------------------------------- random plans

def random_pre(rng, n_copies, max_items=6):
    out = []
    for _ in range(n_copies):
        out.append(desc(rng.randrange(CORES)))
        for _ in range(rng.choice([0, 1, 1, 2, 3, max_items])):
            word = rng.randrange(SHARED_WORDS)
            if rng.random() < 0.5:
                out.append(bit_item(word, rng.randrange(32), rng.randrange(MARKER_BITS)))
            else:
                out.append(word_item(word, rng.randrange(MW_WORDS)))
    return out


def random_post(rng, n_copies):
    """Postcycle copies (writer: this core): runs of bits of one word (gathered), single
    words, sometimes one word's bits split over two copies (two writes, the later one
    whole), sometimes an empty copy."""
    out, split = [], None
    for _ in range(n_copies):
        out.append(desc(OWN))
        if split is not None:                        # the rest of the last copy's word
            word, poss = split
            for pos in poss:
                out.append(bit_item(word, pos, rng.randrange(MARKER_BITS)))
            split = None
        for _ in range(rng.choice([0, 1, 2, 3])):
            word = rng.randrange(SHARED_WORDS)
            if rng.random() < 0.5:
                poss = rng.sample(range(32), rng.randrange(1, 9))
                cut = rng.randrange(1, len(poss) + 1) if rng.random() < 0.3 else len(poss)
                for pos in poss[:cut]:
                    out.append(bit_item(word, pos, rng.randrange(MARKER_BITS)))
                if cut < len(poss):
                    split = (word, poss[cut:])
            else:
                out.append(word_item(word, rng.randrange(MW_WORDS)))
    return out


def random_scenario(rng, protect, n_scans=4, seed=0):
    """A random plan (junk between the lists), scan lengths, a period the scans
    usually fit in, short lock waits."""
    pre = random_pre(rng, rng.randrange(0, 6)) if rng.random() > 0.1 else []
    post = random_post(rng, rng.randrange(0, 5)) if rng.random() > 0.1 else []
    gap = rng.randrange(0, 6)
    entries = pre + [rng.randrange(1 << 32) for _ in range(gap)] + post
    return Scenario(protect=protect, period=len(pre) + len(post) + rng.randrange(10, 60),
                    entries=entries, pre_len=len(pre), post_base=len(pre) + gap,
                    post_len=len(post), scan_len=[rng.randrange(1, 30) for _ in range(n_scans)],
                    pre_wait=[rng.choice([0, 0, 1, 3]) for _ in range(n_scans)],
                    post_wait=[rng.choice([0, 0, 2, 5]) for _ in range(n_scans)],
                    seed=seed)


def stress_scenario(rng, n_scans, seed):
    """Anything goes: any protection, a tight, loose or no period, long lock waits and
    waits ending around the give-up clock, a CPU sometimes not ready for the RUN pulse,
    with ping-pong other writers that publish (write, then flip) at random."""
    protect = rng.choice([SEM, SEM, PING, NONE])
    sc = random_scenario(rng, protect, n_scans, seed)
    sc.pre_len = min(sc.pre_len, len(sc.entries))
    busy = sc.pre_len + sc.post_len + 30
    sc.period = rng.choice([0, busy // 2, busy, 2 * busy, 4 * busy])
    sc.scan_len = [rng.choice([1, 5, 20, 40, 120]) for _ in range(n_scans)]
    sc.pre_wait = [rng.choice([0, 1, 7, 40, 200, ("X", -1), ("X", 0), ("X", 1), ("X", 30)])
                   for _ in range(n_scans)]
    if sc.period == 0:                               # no give-up clock: plain waits
        sc.pre_wait = [w if isinstance(w, int) else 250 + w[1] for w in sc.pre_wait]
    sc.post_wait = [rng.choice([0, 0, 3, 30, 300]) for _ in range(n_scans)]
    exp = model(sc)
    horizon = exp.end + 600
    sc.cpu_unready = set()
    for r in sorted(exp.cpu_run):                    # around some of the RUN pulses
        if rng.random() < 0.2:
            sc.cpu_unready.update(range(r - rng.randrange(3), r + rng.randrange(1, 6)))
    if protect == PING:
        for w in (c for c in range(CORES) if c != OWN):
            t = rng.randrange(40)
            while t < horizon:
                n = rng.randrange(1, 4)
                for c in range(t, t + n):
                    sc.posting[c] = sc.posting.get(c, 0) | (1 << w)
                sc.sel_flips[t + n - 1] = sc.sel_flips.get(t + n - 1, 0) | (1 << w)
                t += n + rng.randrange(2, 30)
    return sc


@cocotb.test()
async def random_plans_copy_as_planned(dut):
    """Random plans (bits and words, any writer, gathered and split bit runs, empty
    copies and lists) with the semaphore (short waits) and without protection: every
    shared read, local write and shared write at its clock with its value."""
    await start_clock(dut)
    rng = random.Random(11)
    for i in range(30):
        sc = random_scenario(rng, SEM if i % 2 == 0 else NONE, seed=100 + i)
        await run_scenario(dut, sc)


@cocotb.test()
async def postcycle_list_at_the_top_of_the_plan(dut):
    """The postcycle's list far up in the plan, every bit of post_base_i used between
    the scenarios (make mutate: post_base_i bit 7 stuck at 0 went unseen, every random
    plan's lists start below 128)."""
    await start_clock(dut)
    rng = random.Random(15)
    for base in (0x80, 0xC0, 0xAA, 0x55, 0xF0):
        sc = random_scenario(rng, SEM, seed=400 + base)
        post = sc.entries[sc.post_base:sc.post_base + sc.post_len] or [desc(OWN)]
        pre = sc.entries[:sc.pre_len]
        base = max(base, len(pre))
        sc.entries = pre + [rng.randrange(1 << 32) for _ in range(base - len(pre))] + post
        sc.post_base, sc.post_len = base, len(post)
        await run_scenario(dut, sc)


@cocotb.test()
async def random_stress(dut):
    """stress_scenario: the model decides the skips, overruns and copy_fails."""
    await start_clock(dut)
    rng = random.Random(14)
    seen = {"skip": 0, "overrun": 0, "overtaken": 0, "unready": 0}
    for i in range(80):
        sc = stress_scenario(rng, 6, seed=300 + i)
        exp = await run_scenario(dut, sc)
        seen["skip"] += exp.skips > 0
        seen["overrun"] += exp.overruns > 0
        seen["overtaken"] += sc.protect == PING and exp.fail_clock is not None
        seen["unready"] += any(c + 1 in exp.cpu_run for c in exp.cpu_run)
    assert min(seen.values()) >= 3, seen


@cocotb.test()
async def long_burst_one_item_per_clock(dut):
    """A compact sector: one descriptor and 60 word items in, 40 bit items of two words
    and 20 words out: 1 item per clock, the list done in entries + 2 clocks."""
    await start_clock(dut)
    pre = [desc(1)] + [word_item(w, w % MW_WORDS) for w in range(60)]
    post = ([desc(OWN)] + [bit_item(40 + i // 20, (i * 7) % 32, 3 * i) for i in range(40)]
            + [word_item(42 + i, (i * 5) % MW_WORDS) for i in range(20)])
    sc = Scenario(protect=SEM, period=0, entries=pre + post, pre_len=len(pre),
                  post_base=len(pre), post_len=len(post), scan_len=[5, 9], seed=3)
    exp = model(sc)
    assert len(exp.sh_writes) == 2 * (2 + 20)     # per scan: two gathered words, 20 words
    await run_scenario(dut, sc)


@cocotb.test()
async def the_whole_plan_as_one_list(dut):
    """A precycle, then a postcycle, of all PLAN_WORDS entries: the issue count's top
    bit set at the end of a list (make mutate: the done compare's bit 4 flipped when
    bit 8 is set, and the count's bit 4 flipped from entry 64 on, both went unseen;
    the longest list before was 61 entries)."""
    await start_clock(dut)
    rng = random.Random(16)

    def items(n):
        return [word_item(rng.randrange(SHARED_WORDS), rng.randrange(MW_WORDS))
                if rng.random() < 0.3 else
                bit_item(rng.randrange(SHARED_WORDS), rng.randrange(32),
                         rng.randrange(MARKER_BITS)) for _ in range(n)]
    for writer, pre in ((1, True), (OWN, False)):
        lst = [desc(writer)] + items(PLAN_WORDS - 1)
        sc = Scenario(protect=SEM, period=0, entries=lst,
                      pre_len=len(lst) if pre else 0, post_base=0,
                      post_len=0 if pre else len(lst), scan_len=[7, 3], seed=16 + pre)
        await run_scenario(dut, sc)


# --------------------------------------------------------------------- timing

def burst_plan():
    pre = [desc(0)] + [word_item(w, w) for w in range(6)] + [desc(3), bit_item(5, 31, 200)]
    post = [desc(OWN)] + [bit_item(9, b, 100 + b) for b in range(4)] + [word_item(10, 7)]
    return pre, post


@cocotb.test()
async def periods_and_overruns(dut):
    """Scan k starts at k * period; a scan that is still running then makes the next
    start right after it, counted as an overrun; the grid does not shift."""
    await start_clock(dut)
    pre, post = burst_plan()
    # (no lock) start 1 + copy 12 + RUN 1, scan N, scan_done 1 + copy 9: a scan of N
    # clocks takes N + 24 clocks; the period is 70
    lens = [10, 10, 60, 10, 100, 5, 5, 44, 45, 46, 5, 5]
    for protect in (NONE, SEM):
        sc = Scenario(protect=protect, period=70, entries=pre + post, pre_len=len(pre),
                      post_base=len(pre), post_len=len(post), scan_len=lens, seed=5)
        exp = model(sc)
        assert exp.overruns >= 3 and sum(s % 70 == 0 for s in exp.starts) >= 6
        await run_scenario(dut, sc)


@cocotb.test()
async def run_waits_for_ready(dut):
    """RUN is held until the CPU is ready; the CPU latches in the first clock it is
    ready with RUN high, and pre counts up to that clock."""
    await start_clock(dut)
    pre, post = burst_plan()
    for protect in (NONE, SEM):
        sc = Scenario(protect=protect, period=100, entries=pre + post, pre_len=len(pre),
                      post_base=len(pre), post_len=len(post), scan_len=[10, 10, 10],
                      seed=15)
        exp = model(sc)
        run0, run1 = sorted(exp.cpu_run)[:2]
        sc.cpu_unready = set(range(run0 - 3, run0 + 4)) | {run1}
        exp = model(sc)
        # RUN in run0 .. run0 + 4 (latched there), twice in scan 1, once in scan 2
        assert len(exp.cpu_run) == 5 + 2 + 1 and exp.done[min(exp.done)][0] == run0 + 5
        await run_scenario(dut, sc)


@cocotb.test()
async def semaphore_waits(dut):
    """The lock is withheld (another core holds it) for random times in precycles and
    postcycles, within the period: no shared access before the grant, the copy starts
    in the clock after it, release in the last copy clock, sem_wait the clocks spent
    asking."""
    await start_clock(dut)
    rng = random.Random(12)
    pre, post = burst_plan()
    n = 12
    sc = Scenario(protect=SEM, period=400, entries=pre + post, pre_len=len(pre),
                  post_base=len(pre), post_len=len(post),
                  scan_len=[rng.randrange(1, 40) for _ in range(n)],
                  pre_wait=[rng.choice([0, 1, 2, 17, 60]) for _ in range(n)],
                  post_wait=[rng.choice([0, 1, 5, 33, 90]) for _ in range(n)], seed=6)
    exp = model(sc)
    assert exp.skips == 0 and exp.overruns == 0
    await run_scenario(dut, sc)


@cocotb.test()
async def give_up_and_postcycles_wait(dut):
    """Fig. 8: a precycle that would have to wait past the give-up point is skipped in
    exactly that clock (no local writes, copy_fail sticky, skips counted, the CPU still
    started); granted in that very clock it copies; a postcycle waits however long (here
    longer than a period), making the next scan late, which may then give up at once."""
    await start_clock(dut)
    pre, post = burst_plan()
    X = "X"
    sc = Scenario(protect=SEM, period=150, entries=pre + post, pre_len=len(pre),
                  post_base=len(pre), post_len=len(post),
                  scan_len=[20, 30, 25, 25, 40, 20, 20, 20, 20],
                  pre_wait=[0, (X, 1), (X, 0), (X, -1), 3, (X, 400), 0, (X, 1), 0],
                  post_wait=[0, 4, 0, 0, 260, 0, 0, 0, 0], seed=7)
    exp = model(sc)
    # scans 1, 5 (late after scan 4's long postcycle) and 7 skip
    assert exp.skips == 3 and exp.overruns >= 1 and exp.fail_clock is not None
    await run_scenario(dut, sc)


@cocotb.test()
async def back_to_back_never_gives_up(dut):
    """period 0: scans back to back (the next precycle in the clock after the last
    postcycle clock), a precycle waits however long (nothing is skipped). The overrun
    fields are checked by the known-bug test below."""
    await start_clock(dut)
    pre, post = burst_plan()
    sc = Scenario(protect=SEM, period=0, entries=pre + post, pre_len=len(pre),
                  post_base=len(pre), post_len=len(post), scan_len=[50, 3, 7, 200, 1],
                  pre_wait=[0, 300, 2, 500, 0], post_wait=[0, 0, 100, 0, 1], seed=8)
    exp = model(sc)
    assert exp.skips == 0
    await run_scenario(dut, sc)


@cocotb.test()
async def back_to_back_counts_no_overruns(dut):
    """period 0 (back to back) has no nominal starts, so no scan is late: overrun_o 0,
    overruns_o 0 (docs/multicore.md: a scan is an overrun when the core is still busy
    at its nominal start k * period)."""
    await start_clock(dut)
    pre, post = burst_plan()
    for protect in (NONE, SEM):
        sc = Scenario(protect=protect, period=0, entries=pre + post, pre_len=len(pre),
                      post_base=len(pre), post_len=len(post), scan_len=[10, 10, 10], seed=9)
        await run_scenario(dut, sc)


# --------------------------------------------------------------------- ping-pong

@cocotb.test()
async def pingpong_buffers(dut):
    """Random plans with ping-pong: no lock; reads of writer w from the buffer w had
    published when the precycle began, though the other writers flip (publish) at
    random clocks, also during the precycle; writes to !sel[own]; sh_flip in the last
    postcycle clock (the bench flips sel[own] then, as shared_mem does)."""
    await start_clock(dut)
    rng = random.Random(13)
    for i in range(5):
        sc = random_scenario(rng, PING, n_scans=5, seed=200 + i)
        sc.pre_wait = sc.post_wait = None
        horizon = model(sc).end
        others = [c for c in range(CORES) if c != OWN]
        sc.sel_flips = {}
        for t in rng.sample(range(horizon), horizon // 6):
            sc.sel_flips[t] = sc.sel_flips.get(t, 0) | (1 << rng.choice(others))
        exp = model(sc)
        assert exp.fail_clock is None
        await run_scenario(dut, sc)


@cocotb.test()
async def pingpong_overtaken(dut):
    """copy_fail with ping-pong: writer 1 overwrites the buffer a precycle reads (it
    published after the precycle began, then writes again) before the precycle has read
    all it reads of writer 1. Not when it only publishes, when it writes the other
    buffer (not yet published), or when it writes after the last read of writer 1."""
    await start_clock(dut)
    # precycle copy from clock 1: [d1, 4 words of writer 1, d0, 2 words of writer 0,
    # d1, 1 word of writer 1]: entry j is read in clock j + 2, so writer 1 in clocks
    # 3..6 and 11, writer 0 in 8 and 9
    pre = ([desc(1)] + [word_item(w, w) for w in range(4)] + [desc(0)]
           + [word_item(w, 8 + w) for w in range(2)] + [desc(1), word_item(20, 20)])
    post = [desc(OWN), word_item(30, 1)]
    w0, w1 = 1 << 0, 1 << 1
    cases = [  # (flips, posting, first clock of copy_fail: the overtaken read + 1)
        ({2: w1}, {}, None),                          # publishes only
        ({}, {2: w1, 3: w1}, None),                   # writes its unpublished buffer
        ({2: w1}, {4: w1}, 5),                        # publishes, overwrites; read in 4
        ({2: w1}, {7: w1}, 12),                       # overwrites between the stretches
        ({2: w1}, {12: w1, 13: w1}, None),            # after the last read of writer 1
        ({2: w0}, {5: w0}, 9),                        # writer 0, before its reads
        ({2: w0}, {10: w0}, None),                    # writer 0, after its reads
    ]
    for flips, posting, fail in cases:
        sc = Scenario(protect=PING, period=0, entries=pre + post, pre_len=len(pre),
                      post_base=len(pre), post_len=len(post), scan_len=[4, 4],
                      sel_flips=flips, posting=posting, seed=10)
        exp = model(sc)
        assert exp.fail_clock == fail, (flips, posting, exp.fail_clock)
        await run_scenario(dut, sc)


# --------------------------------------------------------------------- pytest

@pytest.mark.parametrize("sim", SIMULATORS)
def test_core_seq(sim):
    run_cocotb(sim, "core_seq", "test_core_seq", parameters=params(PLAN_WORDS))
