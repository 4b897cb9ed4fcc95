"""The bit side's schedule: list scheduling of independent rungs inside a basic block by a
compile-time timing model, deadlock-checked (bitbyte.compiler.partition, "Scheduling").
"""
from __future__ import annotations

from dataclasses import dataclass, field

from bitbyte.compiler.walk import BIT_RLO_SETTERS
from bitbyte.lang.costs import byte_kind, resolve_costs
from bitbyte.lang.parts import BYTE_JUMPS, PartInstr, Partition, STATUS_UPDATES
from bitbyte.lang.program import JUMPS, OPENS


_SCHED_AREAS = ("I", "IR", "IF", "Q", "M", "T", "C", "FBI", "FBY")


@dataclass
class _Seg:
    """A rung of the bit part: from an RLO setter at parenthesis depth 0 (or a block's
    start) up to the next one.  Its RLO is its own: nothing before it is read by it,
    nothing it leaves in F_b is read after it (the next rung overwrites F_b first), so
    rungs may change places when their data and the exchange allow it."""

    lo: int                               # bit part indices [lo, hi)
    hi: int
    reads: set = field(default_factory=set)
    writes: set = field(default_factory=set)
    fby: list = field(default_factory=list)      # ordinals of its `= FBY k` (bit order)
    fbi: list = field(default_factory=list)      # ordinals of its `.. FBI k` reads
    updates: list = field(default_factory=list)  # byte indices its bit-16 reads wait for
    status: bool = False                  # reads T n / C n
    barrier: bool = False                 # stays where it is, everything else around it


def _segments(bit: list[PartInstr], lo: int, hi: int, fby_no: dict, fbi_no: dict,
              wait_on: dict) -> list[_Seg] | None:
    """The rungs of the block bit[lo:hi]; None when the block closes a parenthesis
    it did not open (then it is left alone). A block that starts inside parentheses
    is split as usual: its first rung (a barrier) holds everything up to the first
    RLO load at depth 0."""
    segs: list[_Seg] = []
    depth = 0
    for n in range(lo, hi):
        ins = bit[n]
        m, op = ins.mnemonic, ins.operand
        if not segs or (depth == 0 and m in BIT_RLO_SETTERS):
            segs.append(_Seg(n, n + 1, barrier=not (depth == 0 and m in BIT_RLO_SETTERS)))
        seg = segs[-1]
        seg.hi = n + 1
        if m in OPENS:
            depth += 1
        elif m == ")":
            depth -= 1
        if depth < 0:
            return None
        # `= T n` / `= C n` (--tc-path status): in parallel mode the byte side's timer /
        # counter instruction of the same row waits for it, an exchange event the
        # deadlock check does not model, so it keeps the walk's place (a barrier)
        if m in JUMPS or m in ("END", "NOP", "REFRESH", "REFRESH Q") or \
                (m == "=" and op is not None and op.area in ("T", "C")) or \
                (op is not None and op.kind not in ("bit", "index", "label")) or \
                (op is not None and op.kind != "label" and op.area not in _SCHED_AREAS):
            seg.barrier = True
            continue
        if op is None:
            continue
        if op.area == "FBY":
            seg.fby.append(fby_no[n])
        elif op.area == "FBI":
            seg.fbi.append(fbi_no[n])
        elif op.area in ("T", "C"):
            seg.status = True
            if n in wait_on:
                seg.updates.append(wait_on[n])
        else:
            key = (op.area, op.bit_number)
            if m in ("=", "S", "R"):
                seg.writes.add(key)
            elif m in ("FP", "FN"):
                seg.reads.add(key)
                seg.writes.add(key)
            else:
                seg.reads.add(key)
    if segs:
        # the block's last rung stays last: what it leaves (the RLO, an open
        # parenthesis) may be used after the block's end (a label's fall-through)
        segs[-1].barrier = True
    return segs


def _seg_preds(segs: list[_Seg]) -> list[set[int]]:
    """Which rungs each rung must stay behind (indices into segs).

    data: a rung that writes a bit another one reads or writes (either order);
    exchange: `= FBY` writes keep their order, FBI reads keep theirs (the queues pair
    the i-th write with the i-th read), and a rung that waits for the byte side (an
    FBI read, a bit-16 status read) stays behind every `= FBY` that came before it, so
    the byte side never waits for a write placed after a read that waits for it; only
    `= FBY` writes move up past FBI reads.  A T n / C n read keeps its place among the
    rungs that hold transfers (the syncs the compiler chose count on it); barriers
    (jumps, END, REFRESH, REFRESH Q, NOP, PI/PQ, QR/QF, a block's first rung when it
    continues the RLO and its last rung) keep theirs among all."""
    preds: list[set[int]] = [set() for _ in segs]
    for j, b in enumerate(segs):
        for i in range(j):
            a = segs[i]
            if a.barrier or b.barrier:
                dep = True
            elif a.writes & (b.reads | b.writes) or a.reads & b.writes:
                dep = True
            elif (a.fby and b.fby) or (a.fbi and b.fbi):
                dep = True
            elif a.fby and (b.fbi or b.updates):
                dep = True
            elif (b.status or b.updates) and (a.fby or a.fbi):
                dep = True
            elif (a.status or a.updates) and (b.fby or b.fbi):
                dep = True
            else:
                dep = False
            if dep:
                preds[j].add(i)
    return preds


class _Timing:
    """The compile-time timing model the schedule is chosen with: the straight-line
    path (jumps not taken), the bit side 1 clock per instruction, the byte side its
    cost table, a transfer seen by the reader the clock after the write, a status the
    clock after its update.  Only the choice of the order depends on it; whether an
    order is allowed does not."""

    def __init__(self, byte: list[PartInstr], costs):
        self.table = resolve_costs(costs)
        self.byte = byte
        self.fby_time: dict[int, int] = {}     # FBY ordinal -> clock the byte side sees it
        self.fbi_time: dict[int, int] = {}     # FBI ordinal -> clock the bit side sees it
        self.upd_time: dict[int, int] = {}     # byte index -> clock its status is seen
        self.pc = 0
        self.t = 0                             # byte side's clock
        self.reads = 0
        self.writes = 0

    def clone(self) -> "_Timing":
        other = _Timing.__new__(_Timing)
        other.__dict__.update(self.__dict__)
        other.fby_time, other.fbi_time = dict(self.fby_time), dict(self.fbi_time)
        other.upd_time = dict(self.upd_time)
        return other

    def advance(self) -> None:
        """Run the byte side until it needs a bit -> byte transfer not written yet."""
        while self.pc < len(self.byte):
            ins = self.byte[self.pc]
            m = ins.mnemonic
            if m == "END_B":
                break
            start = self.t
            if m == "READ":
                if self.reads not in self.fby_time:
                    return
                start = max(start, self.fby_time[self.reads])
                self.reads += 1
                cost = self.table["READ"]
            elif m == "WRITE":
                self.fbi_time[self.writes] = start + 1
                self.writes += 1
                cost = self.table["WRITE"]
            elif m in BYTE_JUMPS.values():
                cost = self.table["READ"]
            else:
                cost = self.table[byte_kind(ins)]
            self.t = start + cost
            if byte_kind(ins) in STATUS_UPDATES:
                self.upd_time[self.pc] = self.t
            self.pc += 1

    def run_seg(self, bit: list[PartInstr], seg: _Seg, t: int, fby_no: dict,
                fbi_no: dict, wait_on: dict, commit: bool) -> float:
        """The clock the bit side finishes seg at when it starts at t (inf: it would
        wait for something the byte side cannot produce yet)."""
        for n in range(seg.lo, seg.hi):
            op = bit[n].operand
            ready = t
            if n in fbi_no:
                ready = self.fbi_time.get(fbi_no[n], float("inf"))
            elif n in wait_on:
                ready = self.upd_time.get(wait_on[n], float("inf"))
            t = max(t, ready) + 1
            if t == float("inf"):
                return t
            if commit and op is not None and n in fby_no:
                self.fby_time[fby_no[n]] = t
                self.advance()
        return t


def _transfer_numbers(bit: list[PartInstr]) -> tuple[dict, dict]:
    fby_no, fbi_no = {}, {}
    for n, ins in enumerate(bit):
        op = ins.operand
        if op is not None and op.kind == "index" and op.area == "FBY":
            fby_no[n] = len(fby_no)
        elif op is not None and op.kind == "index" and op.area == "FBI":
            fbi_no[n] = len(fbi_no)
    return fby_no, fbi_no


def _update_waits(part: Partition) -> dict[int, int]:
    """bit index of each bit-16 status read -> byte index of the update it waits for
    (the last update of that timer / counter before it in the rows)."""
    bit_at = {id(ins): n for n, ins in enumerate(part.bit)}
    byte_at = {id(ins): n for n, ins in enumerate(part.byte)}
    last: dict[tuple[str, int], int] = {}
    out = {}
    for row in part.rows:
        y = row.byte
        if y is not None and byte_kind(y) in STATUS_UPDATES:
            last[(y.operand.area, y.operand.index)] = byte_at[id(y)]
        b = row.bit
        if b is not None and b.wait_update:
            out[bit_at[id(b)]] = last[(b.operand.area, b.operand.index)]
    return out


def _blocks(part: Partition) -> list[tuple[int, int]]:
    """Basic blocks of the bit part: cut at every label and after every jump / END."""
    starts = {0} | set(part.bit_labels.values())
    for n, ins in enumerate(part.bit):
        if ins.mnemonic in JUMPS or ins.mnemonic == "END":
            starts.add(n + 1)
    cuts = sorted(s for s in starts if 0 <= s <= len(part.bit)) + [len(part.bit)]
    return [(a, b) for a, b in zip(cuts, cuts[1:]) if a < b]


def _model_clocks(part: Partition, bit: list[PartInstr], costs) -> float:
    """The timing model's clocks per scan for a bit part order (straight line)."""
    fby_no, fbi_no = _transfer_numbers(bit)
    wait_on = _remap(_update_waits(part), part.bit, bit)
    tm = _Timing(part.byte, costs)
    tm.advance()
    t = 0
    for n in range(len(bit)):
        seg = _Seg(n, n + 1)
        if bit[n].mnemonic == "END":
            tm.advance()
            return max(t, tm.t) + 1
        t = tm.run_seg(bit, seg, t, fby_no, fbi_no, wait_on, True)
        if t == float("inf"):
            return t                  # cannot happen for an order _no_deadlock passed
    return max(t, tm.t) + 1


def _no_deadlock(bit: list[PartInstr], lo: int, hi: int, byte: list[PartInstr],
                 fby_no: dict, fbi_no: dict, wait_on: dict) -> bool:
    """True when the block bit[lo:hi] in its present order cannot deadlock against
    the byte side.  The exchange events
    of the block (its `= FBY` / FBI reads / bit-16 reads; on the byte side the READs,
    WRITEs and updates they pair with, in byte order) are played with one place per
    direction, the tightest exchange there is (a queue of depth 1): whatever the two
    sides' speeds, each event can run once everything it waits for has run.  With
    more places (deeper queues, handshake channels used round-robin) the waits are a
    subset, so no order that passes here can deadlock there."""
    bit_ev = []
    for n in range(lo, hi):
        if n in fby_no:
            bit_ev.append(("w", fby_no[n]))
        elif n in fbi_no:
            bit_ev.append(("r", fbi_no[n]))
        elif n in wait_on:
            bit_ev.append(("u", wait_on[n]))
    if not bit_ev:
        return True
    fbys = {k for e, k in bit_ev if e == "w"}
    fbis = {k for e, k in bit_ev if e == "r"}
    ups = {k for e, k in bit_ev if e == "u"}
    byte_ev = []
    reads = writes = 0
    for y, ins in enumerate(byte):
        if ins.mnemonic == "READ":
            if reads in fbys:
                byte_ev.append(("r", reads))
            reads += 1
        elif ins.mnemonic == "WRITE":
            if writes in fbis:
                byte_ev.append(("w", writes))
            writes += 1
        if y in ups:
            byte_ev.append(("u", y))
    written = {"fby": set(), "fbi": set()}
    consumed = {"fby": set(), "fbi": set()}
    updated: set[int] = set()
    lo_fby, lo_fbi = min(fbys, default=0), min(fbis, default=0)
    i = j = 0
    while i < len(bit_ev) or j < len(byte_ev):
        moved = False
        while i < len(bit_ev):
            e, k = bit_ev[i]
            if e == "w" and not (k == lo_fby or k - 1 in consumed["fby"]):
                break
            if e == "r" and k not in written["fbi"]:
                break
            if e == "u" and k not in updated:
                break
            if e == "w":
                written["fby"].add(k)
            elif e == "r":
                consumed["fbi"].add(k)
            i += 1
            moved = True
        while j < len(byte_ev):
            e, k = byte_ev[j]
            if e == "r" and k not in written["fby"]:
                break
            if e == "w" and not (k == lo_fbi or k - 1 in consumed["fbi"]):
                break
            if e == "r":
                consumed["fby"].add(k)
            elif e == "w":
                written["fbi"].add(k)
            else:
                updated.add(k)
            j += 1
            moved = True
        if not moved:
            return False
    return True


def _schedule_bit_part(part: Partition, costs="paper") -> None:
    """Reorder the rungs of the bit part inside each basic block so that the bit side
    waits less (paper §4.3: "the program should be written and compiled in such a way
    that the load of both processors is equally distributed").  The byte part and
    the transfers' order stay as they are; what moves is bit-side work:

    * a rung that reads a condition from the byte side (a compare result) goes where
      its condition is there, and the independent rungs after it run meanwhile
      (independent bit work hoisted past the wait);
    * the rungs a `= FBY` (a timer enable, a counter pulse, a jump condition the byte
      side needs) depends on go first when the byte side would otherwise wait for it.

    The order is a list schedule driven by _Timing; the dependencies (_seg_preds) keep
    every scan's result the serial one, _no_deadlock keeps every exchange deadlock-free;
    a block whose new order fails that keeps its old one, and the whole new order is
    kept only when the model says it is faster."""
    bit = part.bit
    fby_no, fbi_no = _transfer_numbers(bit)
    wait_on = _update_waits(part)
    if not fby_no and not fbi_no and not wait_on:
        return
    tm = _Timing(part.byte, costs)
    tm.advance()
    t = 0
    new: list[PartInstr] = []
    moved = 0
    for lo, hi in _blocks(part):
        segs = _segments(bit, lo, hi, fby_no, fbi_no, wait_on)
        order = list(range(len(segs))) if segs else None
        if segs and len(segs) > 2:
            order = _list_schedule(bit, segs, tm, t, fby_no, fbi_no, wait_on)
            block = [bit[n] for s in order for n in range(segs[s].lo, segs[s].hi)]
            trial = bit[:lo] + block + bit[hi:]
            if not _no_deadlock(trial, lo, hi, part.byte, *_transfer_numbers(trial),
                                _remap(wait_on, bit, trial)):
                order = list(range(len(segs)))
        if segs is None:
            new += bit[lo:hi]
            for n in range(lo, hi):
                t = tm.run_seg(bit, _Seg(n, n + 1), t, fby_no, fbi_no, wait_on, True)
            continue
        for s in order:
            t = tm.run_seg(bit, segs[s], t, fby_no, fbi_no, wait_on, True)
            new += bit[segs[s].lo:segs[s].hi]
        moved += sum(1 for k, s in enumerate(order) if s != k)
    if moved == 0:
        return
    assert sorted(map(id, new)) == sorted(map(id, bit))
    before, after = _model_clocks(part, bit, costs), _model_clocks(part, new, costs)
    if after >= before:
        return
    labels = [ins.labels for ins in bit]          # labels are positions: they stay
    for ins, names in zip(new, labels):
        ins.labels = names
    part.bit[:] = new
    part.schedule = (moved, before, after)


def _remap(wait_on: dict, old: list, new: list) -> dict:
    """wait_on (bit index -> update) for the instructions of `old` placed as in `new`."""
    where = {id(ins): n for n, ins in enumerate(new)}
    return {where[id(old[n])]: u for n, u in wait_on.items()}


def _list_schedule(bit, segs, tm: _Timing, t: int, fby_no, fbi_no, wait_on) -> list[int]:
    """The order of one block's rungs (see _schedule_bit_part).  Simulates the block
    on a copy of the timing model; at each step takes, among the rungs whose
    predecessors are placed: the ancestors of the next `= FBY` when the byte side
    would otherwise wait for it, else the first (in program order) that runs without
    waiting, else the one that finishes first."""
    preds = _seg_preds(segs)
    succs: list[set[int]] = [set() for _ in segs]
    for j, ps in enumerate(preds):
        for i in ps:
            succs[i].add(j)
    left = [len(ps) for ps in preds]
    ready = {j for j, c in enumerate(left) if c == 0}
    done: set[int] = set()
    sim = tm.clone()
    order = []
    fby_seg = {k: j for j, s in enumerate(segs) for k in s.fby}
    size = [s.hi - s.lo for s in segs]
    while ready:
        pick = None
        need = sim.reads                        # the byte side's next READ
        if need in fby_seg and fby_seg[need] not in done:
            anc, todo = set(), [fby_seg[need]]
            while todo:
                j = todo.pop()
                if j in anc or j in done:
                    continue
                anc.add(j)
                todo.extend(preds[j])
            work = sum(size[j] for j in anc)
            if sim.pc < len(sim.byte) and sim.byte[sim.pc].mnemonic == "READ" and \
                    t + work >= sim.t:
                pick = min(j for j in anc if j in ready)
        if pick is None:
            best = None
            for j in sorted(ready):
                end = sim.run_seg(bit, segs[j], t, fby_no, fbi_no, wait_on,
                                             False)
                if end <= t + size[j]:
                    pick = j
                    break
                if best is None or end < best[0]:
                    best = (end, j)
            if pick is None:
                pick = best[1]
        t = sim.run_seg(bit, segs[pick], t, fby_no, fbi_no, wait_on, True)
        order.append(pick)
        done.add(pick)
        ready.discard(pick)
        for j in succs[pick]:
            left[j] -= 1
            if left[j] == 0:
                ready.add(j)
    assert len(order) == len(segs)
    return order
