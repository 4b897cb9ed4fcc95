"""Straight-line stretches of bit instructions and their scalar semantics as a Boolean
network (issue 18, direction (a): the wide bit engine's compiler, front half).

The stretch rule (docs/wide-engine.md):

* A *pure* bit instruction changes nothing but the RLO, the parenthesis stack and the
  bit images M and Q (the PIO), and reads nothing that can change while the bit
  processor runs straight-line code: `LD`/`LDN`/`A`/`AN`/`O`/`ON`/`X`/`XN` of I, IR,
  IF, Q, QR, QF, M, T, C (a T/C read without the "wait for this scan's update"
  flag, bit 16, docs/isa.md); the opening parentheses and `)`; `NOT`, `SET`, `CLR`, `NOP`;
  `=`, `S`, `R` of Q or M; `FP`/`FN` on M or Q.
* Everything else is a *cut*, executed as today (scalar): labels (a cut before the
  labelled instruction), jumps, `END`, `REFRESH` / `REFRESH Q`, direct `PI`/`PQ`
  accesses (the pin is read or written at that instruction's clock), the channels
  FBI/FBY, byte instructions (L, T, arithmetic, compares, READ/WRITE) and the timer and
  counter instructions (`S`/`R` of T and C included), and a T/C read with the
  wait-for-update flag (the partitioning compiler's parallel mode sets it: the read
  stalls until the byte part has updated T n/C n in this scan): each has an order-dependent
  effect outside the bit images, or reads state that such an effect changes.
* A stretch is a maximal run of pure instructions that ends at the parenthesis depth
  (text order) it starts at and never goes below it: its parentheses are balanced
  within it, so it neither reads nor leaves anything on the parenthesis stack and works
  at whatever depth it is entered at (inside a group whose opening a cut separated from
  it too: `A(`, `LD PI0.0`, `A M0.0`, `A M0.1`, `)` has the stretch `A M0.0`, `A M0.1`
  with the RLO as input).  The opening or `)` a cut separates from its partner stays
  scalar ("paren"): the hardware stack does what it does today.
* A stretch is split into *units*, each compiled and checked on its own, at rung
  boundaries (depth 0, before `LD`/`LDN`/`SET`/`CLR`), greedily, so that a unit has at
  most `max_inputs` inputs (16: the exhaustive check enumerates 2^16 states); a rung
  with more is split at depth-0 instructions (the RLO passes between units); a
  parenthesis group with more keeps its opening and its `)` scalar (the hardware stack
  saves and combines the RLO as today) and its inside, balanced one level deeper, is
  split the same way ("paren"); what is still too wide stays scalar ("wide").

A unit's inputs: the incoming RLO if an instruction reads it before one sets it, and
every bit operand read before the unit writes it (an `S`/`R` target counts as read: not
taken, the bit keeps its old value).  Its outputs: the final value of every bit it
writes, and the final RLO when the next instruction can observe it and the unit
changes it (a unit of NOPs passes the incoming RLO on).  The dialect has no
first-check state (spec §3: an `A` at the scan start combines with the RLO 0; S7's /FC
is compiled away by bitbyte/lang/stl.py), and a unit leaves the parenthesis stack as it
found it, so the RLO is the only other state the next instruction sees.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from bitbyte.lang.definition import DEF
from bitbyte.lang.program import COMBINES, OPENS, Instr, Program

READ_AREAS = ("I", "IR", "IF", "Q", "QR", "QF", "M", "T", "C")
WRITE_AREAS = ("Q", "M")
RLO = "RLO"
# instructions that set the RLO without reading it (the RLO before them is dead)
RLO_SETTERS = ("LD", "LDN", "SET", "CLR")


def loc(op) -> str:
    """The bit location an operand names: `M0.1`, `T3`, `PI0.4`; PQ is the PIO bit
    (a PQ read sees the PIO, a PQ write writes it and the pin)."""
    if op.area == "PQ":
        return f"Q{op.byte}.{op.bit}"
    return op.address()


def cut_reason(ins: Instr, absorb_direct: bool = False) -> str | None:
    """None for a pure bit instruction, else why it cuts a stretch.  absorb_direct:
    PI and PQ reads count as pure (the measured option of docs/wide-engine.md: the pin
    read once per unit, exact under scan-keyed stimuli).  A PQ write always cuts: its
    pin changes at that instruction's clock, with that instruction's value, and only
    when the value differs (spec: QR/QF do not flag it), which a unit's final value
    does not reproduce."""
    m, op = ins.mnemonic, ins.operand
    direct = ("PI", "PQ") if absorb_direct else ()
    if getattr(ins, "wait_update", False):
        return "wait"           # a T/C read that waits for this scan's update (bit 16)
    if ins.section == "BYTE":
        return "byte"
    if m in COMBINES:
        if op.area in READ_AREAS or op.area in direct:
            return None
        return "direct" if op.area in ("PI", "PQ") else "channel"
    if m in OPENS or m in (")", "NOT", "SET", "CLR", "NOP"):
        return None
    if m in ("=", "S", "R", "FP", "FN"):
        if op.area in WRITE_AREAS:
            return None             # a PQ write cuts even with absorb_direct (below)
        if op.area in ("T", "C"):
            # a bit part's `= T n` (--tc-path status): a one-clock bit instruction
            # writing the status buffer, which the byte part reads
            return "status" if m == "=" else "timer/counter"
        return "direct" if op.area == "PQ" else "channel"
    if m in ("JU", "JC", "JCN"):
        return "jump"
    if m == "END":
        return "end"
    if m.startswith("REFRESH"):
        return "refresh"
    if m in ("SD", "SS", "SP", "SF", "CU", "CD"):
        return "timer/counter"
    return "byte"


# --- a hash-consed Boolean network (the scalar semantics, symbolically) --------------

class Net:
    """Nodes: ("c", v), ("v", name), ("not", a), ("and", a, b), ("or", a, b),
    ("xor", a, b); node ids are indices.  Constants fold, equal nodes are shared."""

    def __init__(self):
        self.nodes: list[tuple] = []
        self.index: dict[tuple, int] = {}
        self.C0, self.C1 = self._add(("c", 0)), self._add(("c", 1))

    def _add(self, key: tuple) -> int:
        if key not in self.index:
            self.index[key] = len(self.nodes)
            self.nodes.append(key)
        return self.index[key]

    def var(self, name: str) -> int:
        return self._add(("v", name))

    def NOT(self, a: int) -> int:
        k = self.nodes[a]
        if k[0] == "c":
            return self.C1 if k[1] == 0 else self.C0
        if k[0] == "not":
            return k[1]
        return self._add(("not", a))

    def _bin(self, op: str, a: int, b: int) -> int:
        if a > b:
            a, b = b, a
        ka, kb = self.nodes[a], self.nodes[b]
        if ka[0] == "c":                       # a is C0 or C1 (ids 0, 1: smallest)
            v = ka[1]
            if op == "and":
                return b if v else self.C0
            if op == "or":
                return self.C1 if v else b
            return self.NOT(b) if v else b
        if a == b:
            return {"and": a, "or": a, "xor": self.C0}[op]
        if op != "xor" and (kb == ("not", a) or ka == ("not", b)):
            return self.C0 if op == "and" else self.C1
        return self._add((op, a, b))

    def AND(self, a, b):
        return self._bin("and", a, b)

    def OR(self, a, b):
        return self._bin("or", a, b)

    def XOR(self, a, b):
        return self._bin("xor", a, b)

    def apply(self, func: str | None, rlo: int, x: int) -> int:
        """RLO func x as refsim.combine does; func None loads x."""
        if func is None:
            return x
        return {"A": self.AND, "O": self.OR, "X": self.XOR}[func](rlo, x)

    def cone(self, roots) -> list[int]:
        """The nodes the roots depend on, in topological order (fanins first)."""
        seen: set[int] = set()
        order: list[int] = []
        stack = [(r, False) for r in roots]
        while stack:
            n, done = stack.pop()
            if done:
                order.append(n)
                continue
            if n in seen:
                continue
            seen.add(n)
            stack.append((n, True))
            stack.extend((c, False) for c in self.nodes[n][1:] if self.nodes[n][0] not in ("c", "v"))
        return order

    def evaluate(self, roots, values: dict[str, int], mask: int) -> list[int]:
        """Bit-parallel: each variable a pattern (an int of bits), mask all ones."""
        val: dict[int, int] = {}
        for n in self.cone(roots):
            k = self.nodes[n]
            t = k[0]
            if t == "c":
                val[n] = mask if k[1] else 0
            elif t == "v":
                val[n] = values[k[1]]
            elif t == "not":
                val[n] = ~val[k[1]] & mask
            elif t == "and":
                val[n] = val[k[1]] & val[k[2]]
            elif t == "or":
                val[n] = val[k[1]] | val[k[2]]
            else:
                val[n] = val[k[1]] ^ val[k[2]]
        return [val[r] for r in roots]


# --- stretches and units -------------------------------------------------------------

@dataclass
class Unit:
    """A compiled unit: instrs[start:stop] of the program (all pure, balanced)."""

    start: int
    stop: int
    instrs: list[Instr]
    inputs: list[str] = field(default_factory=list)      # locations, RLO first if read
    outputs: dict[str, int] = field(default_factory=dict)  # location -> net node
    rlo_live: bool = True
    net: Net | None = None
    expected: tuple | None = None     # lutmap.check's exhaustive patterns, once computed

    @property
    def size(self) -> int:
        return self.stop - self.start


@dataclass
class Split:
    """A program split: units (compiled), scalar instructions by reason (index list)."""

    program: Program
    units: list[Unit]
    scalar: dict[str, list[int]]
    stretches: list[tuple[int, int]]

    def count(self, reason: str) -> int:
        return len(self.scalar.get(reason, []))


def syntactic_inputs(instrs: list[Instr]) -> list[str]:
    """The unit's inputs (see the module text), RLO first when read."""
    written: set[str] = set()
    ins_: list[str] = []
    rlo_set = False

    def read(x: str) -> None:
        if x not in written and x not in ins_:
            ins_.append(x)

    for ins in instrs:
        m, op = ins.mnemonic, ins.operand
        if m in RLO_SETTERS:
            if m in ("LD", "LDN"):
                read(loc(op))
            rlo_set = True
            continue
        if not rlo_set and m != "NOP":
            if RLO not in ins_:
                ins_.insert(0, RLO)
            rlo_set = True
        if m in COMBINES or m in ("S", "R", "FP", "FN"):
            read(loc(op))
        if m in ("=", "S", "R", "FP", "FN"):
            written.add(loc(op))
    return ins_


def evaluate(instrs: list[Instr], inputs: list[str]) -> tuple[Net, dict[str, int], int]:
    """The scalar semantics (spec §3, bitbyte/ref/refsim.py) symbolically: (net,
    final value of every written location, final RLO), over variables named by the
    input locations."""
    net = Net()
    state: dict[str, int] = {x: net.var(x) for x in inputs}
    # the incoming RLO is a variable even when no instruction reads it: a unit that
    # never sets it (a lone NOP) leaves it as it found it
    rlo = state[RLO] if RLO in state else net.var(RLO)
    stack: list[tuple[int, str, int]] = []
    written: dict[str, int] = {}

    def read(x: str) -> int:
        if x not in state:
            state[x] = net.var(x)
        return state[x]

    def write(x: str, v: int) -> None:
        state[x] = written[x] = v

    for ins in instrs:
        m, op = ins.mnemonic, ins.operand
        if m in COMBINES:
            func, neg = COMBINES[m]
            x = read(loc(op))
            rlo = net.apply(func, rlo, net.NOT(x) if neg else x)
        elif m in OPENS:
            func, neg = OPENS[m]
            stack.append((rlo, func, neg))
        elif m == ")":
            saved, func, neg = stack.pop()
            rlo = net.apply(func, saved, net.NOT(rlo) if neg else rlo)
        elif m == "NOT":
            rlo = net.NOT(rlo)
        elif m == "SET":
            rlo = net.C1
        elif m == "CLR":
            rlo = net.C0
        elif m == "=":
            write(loc(op), rlo)
        elif m == "S":
            write(loc(op), net.OR(rlo, read(loc(op))))
        elif m == "R":
            write(loc(op), net.AND(net.NOT(rlo), read(loc(op))))
        elif m in ("FP", "FN"):
            old, mem = rlo, read(loc(op))
            rlo = net.AND(old, net.NOT(mem)) if m == "FP" else net.AND(net.NOT(old), mem)
            write(loc(op), old)
        elif m != "NOP":
            raise ValueError(f"not a pure bit instruction: {m}")
    assert not stack, "a unit's parentheses are balanced"
    return net, written, rlo


def make_unit(program: Program, start: int, stop: int, rlo_live: bool) -> Unit:
    instrs = program.instrs[start:stop]
    inputs = syntactic_inputs(instrs)
    net, written, rlo = evaluate(instrs, inputs)
    outputs = {x: v for x, v in written.items() if v != net.index.get(("v", x))}
    if rlo_live and rlo != net.index.get(("v", RLO)):   # unchanged: nothing to write
        outputs[RLO] = rlo
    # every variable the outputs depend on is an input (the RLO too when it only
    # passes through to an output)
    used = [net.nodes[n][1] for n in net.cone(list(outputs.values()))
            if net.nodes[n][0] == "v"]
    for x in used:
        if x not in inputs:
            inputs = [RLO] + inputs if x == RLO else inputs + [x]
    return Unit(start, stop, instrs, inputs, outputs, rlo_live, net)


def _text_depths(program: Program) -> list[int]:
    """Parenthesis depth before each instruction, in text order."""
    d, out = 0, []
    for ins in program.instrs:
        out.append(d)
        if ins.mnemonic in OPENS:
            d += 1
        elif ins.mnemonic == ")":
            d -= 1
    return out


def _depth_at(depth: list[int], p: int, n: int) -> int:
    """The text depth before instruction p (after the last: 0)."""
    return depth[p] if p < n else 0


def _rlo_read_next(instrs: list[Instr], i: int) -> bool:
    """Can the instruction at i (after a unit) observe the RLO?  Conservative: yes
    unless it sets the RLO without reading it, or is END (the next scan starts at 0)."""
    if i >= len(instrs):
        return False
    m = instrs[i].mnemonic
    return not (m in RLO_SETTERS or m == "END" or m in DEF.all_compares or m == "READ")


REFRESHES = ("REFRESH", "REFRESH Q")


def position_reason(instrs: list[Instr], i: int) -> str | None:
    """Why the instruction at program position i stays scalar by where it stands (the
    RTL's contract, docs/wide-rtl-plan.md R1/R2), else None: positions 0 and 1 of a
    scan (a LUT word's operand stage would see the scan-start latch) and the
    instruction after `REFRESH` / `REFRESH Q` (it would see that latch or PIO update)."""
    if i < 2:
        return "scan-start"
    if instrs[i - 1].mnemonic in REFRESHES:
        return "after-refresh"
    return None


def split_program(program: Program, max_inputs: int = 16,
                  absorb_direct: bool = False, positions: bool = False) -> Split:
    """The stretches of `program` and their units (module text); absorb_direct: see
    cut_reason; positions: position_reason keeps the first two positions and the
    instruction after a REFRESH scalar (the RTL's contract; the model sets it)."""
    instrs = program.instrs
    depth = _text_depths(program)
    scalar: dict[str, list[int]] = {}
    stretches: list[tuple[int, int]] = []
    n = len(instrs)

    def reason_at(k: int) -> str | None:
        return cut_reason(instrs[k], absorb_direct) or (
            position_reason(instrs, k) if positions else None)
    i = 0
    while i < n:
        reason = reason_at(i)
        if reason is not None:
            scalar.setdefault(reason, []).append(i)
            i += 1
            continue
        j = i + 1                               # the run of pure instructions [i, j)
        while j < n and reason_at(j) is None and not instrs[j].labels:
            j += 1
        # stretches: maximal sub-runs that never go below the depth they start at
        # and end at it (balanced); a `)` that closes a group a cut interrupted
        # (or its opening, left behind) stays scalar
        a = i
        while a < j:
            base = _depth_at(depth, a, n)
            b, q = a, a
            while q < j and _depth_at(depth, q + 1, n) >= base:
                q += 1
                if _depth_at(depth, q, n) == base:
                    b = q
            if b == a:
                scalar.setdefault("paren", []).append(a)
                a += 1
                continue
            stretches.append((a, b))
            a = b
        i = j
    units: list[Unit] = []
    for a, b in stretches:
        units += _units(program, a, b, depth, max_inputs, scalar, _depth_at(depth, a, n))
    units.sort(key=lambda u: u.start)
    _set_liveness(program, units)
    return Split(program, units, scalar, stretches)


def _units(program, a, b, depth, max_inputs, scalar, base: int = 0) -> list[Unit]:
    """[a, b) at depth `base` (balanced) split into units; a parenthesis group too wide
    for one unit keeps its opening and `)` scalar (the stack does what it does today)
    and its inside is split the same way, one level deeper."""
    instrs = program.instrs
    atoms: list[tuple[int, int]] = []           # depth-base atoms: instruction or group
    p = a
    while p < b:
        q = p + 1
        while q < b and depth[q] != base:
            q += 1
        atoms.append((p, q))
        p = q
    rungs: list[list[tuple[int, int]]] = []
    for at in atoms:
        if not rungs or instrs[at[0]].mnemonic in RLO_SETTERS:
            rungs.append([])
        rungs[-1].append(at)

    def fits(s: int, e: int) -> bool:
        return len(syntactic_inputs(instrs[s:e])) <= max_inputs

    spans: list[tuple[int, int]] = []
    inner: list[Unit] = []
    cur: tuple[int, int] | None = None

    def extend(e: int) -> bool:
        """The current unit grown to end at e if it still fits, else closed."""
        nonlocal cur
        if cur is not None and fits(cur[0], e):
            cur = (cur[0], e)
            return True
        if cur is not None:
            spans.append(cur)
        cur = None
        return False

    for rung in rungs:
        rs, re_ = rung[0][0], rung[-1][1]
        if extend(re_):
            continue
        if fits(rs, re_):
            cur = (rs, re_)
            continue
        for s, e in rung:                       # a rung too wide: atom by atom
            if extend(e):
                continue
            if fits(s, e):
                cur = (s, e)
            elif e - s > 2 and instrs[s].mnemonic in OPENS:
                scalar.setdefault("paren", []).extend((s, e - 1))
                inner += _units(program, s + 1, e - 1, depth, max_inputs, scalar, base + 1)
            else:
                scalar.setdefault("wide", []).extend(range(s, e))
    if cur is not None:
        spans.append(cur)
    return [Unit(s, e, instrs[s:e]) for s, e in spans] + inner


def _set_liveness(program: Program, units: list[Unit]) -> None:
    """Evaluate each unit, its RLO live if the next unit reads it, or passes it on
    untouched to whatever reads it after (a unit of NOPs: the jump-target idiom
    `label: NOP`), or the instruction after it may read it. Back to front, so that the
    next unit's liveness is known."""
    for k in range(len(units) - 1, -1, -1):
        u = units[k]
        nxt = units[k + 1] if k + 1 < len(units) else None
        if nxt is not None and nxt.start == u.stop:
            passes = not any(i.mnemonic in RLO_SETTERS for i in nxt.instrs) and nxt.rlo_live
            live = RLO in syntactic_inputs(nxt.instrs) or passes
        else:
            live = _rlo_read_next(program.instrs, u.stop)
        units[k] = make_unit(program, u.start, u.stop, live)
