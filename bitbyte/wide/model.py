"""The wide bit engine's reference model (issue 18, direction (a)): the serial-mode
reference interpreter (bitbyte/ref/refsim.py) with every compiled unit of the program
run as its LUT program, one LUT instruction per clock, and everything else (cuts,
units that fell back, byte instructions) as the scalar interpreter runs it.

It is what the wide engine's RTL will be checked against, and it checks the compiler
on whole programs over many scans, beyond the per-unit check of lutmap.check: a unit
is entered only at its first instruction (a label cuts, so no jump lands inside one),
reads its inputs from the machine state as the scalar instructions would at that
point, writes back every location it writes, and leaves the RLO as the scalar
instructions would where the next instruction reads it (Unit.rlo_live). Spec §4
(`--bit-engine`): on programs without timers and with scan-keyed stimuli, every trace
column but `t_us` and `cycles` equals the scalar engine's.
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from bitbyte.lang.config import DEFAULT
from bitbyte.lang.definition import DEF
from bitbyte.lang.program import Program
from bitbyte.lang.trace import trace_columns
from bitbyte.ref.refsim import RefSim, refsim_trace
from bitbyte.wide import lutmap as L
from bitbyte.wide.encode import decode_unit, encode_unit
from bitbyte.wide.stretch import RLO, Split, cut_reason, split_program

# the recommendation of docs/wide-engine.md: dual_s, 5 operands
K, VARIANT, FLOW = DEF.lut.k, "dual_s", "abc"     # K: definition.toml [lut]
# Direct PI (and PQ) reads are inputs of a unit (stretch.py cut_reason), each pin read
# once for the whole unit: exact under scan-keyed stimuli, the only ones spec §4
# promises the engines' traces equal for (pins change at latches only); PQ writes
# still cut. The decision: docs/wide-engine.md "Decisions".
ABSORB_DIRECT = True
# The RTL's contract (docs/wide-rtl-plan.md R1/R2): positions 0 and 1 and the
# instruction after a REFRESH stay scalar; and a unit's pins are sampled once, in its
# first word's operand clock, the clock before that word executes (behind a
# dispatched byte instruction: that instruction's first clock), so that every word
# reading a pin sees the one value the unit's network was checked with.
POSITIONS = True
# not bit instructions (the byte processor's, and END): outside the bit part's count
BYTE_SIDE = ("byte", "timer/counter", "end")

_AREA = re.compile(r"[A-Z]+")


def read_location(sim: RefSim, x: str, pin_clock: int) -> int:
    """A unit's input location in the interpreter's state: the RLO, a PI pin (the pins
    of pin_clock), a T/C status bit, or a bit of an image."""
    if x == RLO:
        return sim.rlo
    area = _AREA.match(x).group(0)
    if area == "PI":
        return (sim.pins(pin_clock) >> L._bit_number(x, area)) & 1
    if area in ("T", "C"):
        n = int(x[len(area):])
        return (sim.timer_status(n) if area == "T" else sim.counter_status(n)) & 1
    return (getattr(sim, L._IMAGES[area]) >> L._bit_number(x, area)) & 1


def write_location(sim: RefSim, x: str, v: int) -> None:
    """A unit's output location: the RLO or a bit of an image (M, Q)."""
    if x == RLO:
        sim.rlo = v
        return
    area = _AREA.match(x).group(0)
    attr, b = L._IMAGES[area], L._bit_number(x, area)
    setattr(sim, attr, getattr(sim, attr) & ~(1 << b) | (v << b))


@dataclass
class Compiled:
    """A program split into units, each with its checked LUT program (None: it runs
    scalar)."""

    split: Split
    programs: list[list[L.MInstr] | None]

    @property
    def fallbacks(self) -> int:
        return sum(p is None for p in self.programs)


def compile_programs(programs: list[Program], k: int = K, variant: str = VARIANT,
                     flow: str = FLOW, absorb_direct: bool = ABSORB_DIRECT,
                     positions: bool = POSITIONS) -> list[Compiled]:
    """Each program split and its units compiled (all programs' units in one Yosys
    run: the mapping, not the check, is what takes time)."""
    splits = [split_program(p, absorb_direct=absorb_direct, positions=positions)
              for p in programs]
    every = [u for s in splits for u in s.units]
    progs = L.compile_units(every, k, variant, flow) if every else []
    out, at = [], 0
    for s in splits:
        out.append(Compiled(s, progs[at:at + len(s.units)]))
        at += len(s.units)
    return out


def compile_program(program: Program, k: int = K, variant: str = VARIANT,
                    flow: str = FLOW, absorb_direct: bool = ABSORB_DIRECT) -> Compiled:
    return compile_programs([program], k, variant, flow, absorb_direct)[0]


class WideRefSim(RefSim):
    """RefSim whose compiled units run as LUT programs. lut_clocks counts the LUT
    instructions executed, unit_il the scalar instructions they stood for; bit_il and
    bit_clocks the bit part's IL instructions executed (units' included) and the
    clocks they took (a unit's: its LUT instructions)."""

    def __init__(self, program: Program, compiled: Compiled, *args, **kwargs):
        super().__init__(program, *args, **kwargs)
        # each unit runs as the LUT words it encodes to (bitbyte/wide/encode.py): the
        # words the RTL will read, decoded
        self.units = {u.start: (u, decode_unit(encode_unit(p)))
                      for u, p in zip(compiled.split.units, compiled.programs) if p is not None}
        self.lut_clocks = 0
        self.unit_il = 0
        self.bit_il = 0
        self.bit_clocks = 0
        self._byte_start: int | None = None   # the last step, if a byte instruction: its clock

    def _get(self, x: str, clock: int) -> int:
        return read_location(self, x, clock)

    def _set(self, x: str, v: int) -> None:
        write_location(self, x, v)

    def pin_clock(self, clock: int) -> int:
        """The clock whose pins a unit starting at `clock` reads (once, for all its
        words): its first word's operand clock, the one before it executes; behind a
        dispatched byte instruction, that instruction's first clock (the word waits
        in execute while it completes)."""
        return self._byte_start if self._byte_start is not None else clock - 1

    def _step(self, ins, pc, clock):
        hit = self.units.get(pc)
        if hit is None:
            nxt, clocks = super()._step(ins, pc, clock)
            reason = cut_reason(ins)
            self._byte_start = clock if reason in ("byte", "timer/counter") else None
            if reason not in BYTE_SIDE:
                self.bit_il += 1
                self.bit_clocks += clocks
            return nxt, clocks
        unit, prog = hit
        at = self.pin_clock(clock)
        state = L.execute(prog, {x: self._get(x, at if x.startswith("PI") else clock)
                                 for x in unit.inputs}, 1)
        if prog:                # a unit of no word is not in the image: the next word
            self._byte_start = None     # still stands right behind the byte instruction
        for x in unit.outputs:
            if x != RLO or unit.rlo_live:
                self._set(x, state[x])
        self.lut_clocks += len(prog)
        self.unit_il += unit.size
        self.bit_il += unit.size
        self.bit_clocks += len(prog)
        return unit.stop, len(prog)


def wide_trace(program: Program, compiled: Compiled, config=None, stimulus=None,
               watch=(), scans: int | None = None, watchdog: int = 100000):
    """(columns, records, fault?, sim) of a serial-mode run of the wide model, as
    refsim_trace gives the scalar one (its columns)."""
    config = config or DEFAULT
    columns = trace_columns(program, list(watch), program.symbols, config)
    sim = WideRefSim(program, compiled, config, stimulus, watchdog, columns)
    records = sim.run(scans)
    return columns, records, sim.watchdog_fault, sim


def compare(program: Program, stimulus, watch=(), scans: int = 8,
            compiled: Compiled | None = None) -> tuple[list[str], WideRefSim]:
    """The wide model against the scalar interpreter: the differences (column, scan:
    wide vs scalar) of every trace column but t_us and cycles, empty when equal."""
    compiled = compiled or compile_program(program)
    cols, ref, ref_fault = refsim_trace(program, stimulus=stimulus, watch=watch, scans=scans)
    _, wide, wide_fault, sim = wide_trace(program, compiled, stimulus=stimulus,
                                          watch=watch, scans=scans)
    diffs = []
    if ref_fault != wide_fault or len(ref) != len(wide):
        diffs.append(f"fault/scans: wide {wide_fault}/{len(wide)}, scalar {ref_fault}/{len(ref)}")
    for r, w in zip(ref, wide):
        for c in cols:
            if r.values[c.header] != w.values[c.header]:
                diffs.append(f"{c.header} scan {r.scan}: wide {w.values[c.header]}, "
                             f"scalar {r.values[c.header]}")
    return diffs, sim
