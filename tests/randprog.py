"""Random bit-only IL programs and stimuli for the differential tests.

Programs are made of top-level blocks (logic chains with nested parentheses,
assignments, edge detection, jumps, REFRESH I / Q, output edges QR / QF); jumps and labels sit between blocks, so
a jump never enters or leaves a parenthesis. A few backward jumps loop for a while
(or forever: then both the hardware and the reference must report the watchdog).
"""
from __future__ import annotations

import os
import random
import re

from bitbyte.lang.config import DEFAULT

READ_AREAS = ["I", "I", "I", "PI", "IR", "IF", "Q", "QR", "QF", "PQ", "M", "M", "M", "T", "C"]
WRITE_AREAS = ["Q", "Q", "PQ", "M", "M"]
COMBINE = ["A", "AN", "O", "ON", "X", "XN"]
OPENS = ["A(", "AN(", "O(", "ON(", "X(", "XN("]
IN_BYTES = 2


def _bit(rng: random.Random, area: str) -> str:
    if area in ("T", "C"):
        return f"{area}{rng.randrange(64)}"
    if area == "M":
        byte = rng.choice([0, 0, 1, 2, 3, 255])
    elif area in ("I", "PI", "IR", "IF"):
        byte = rng.randrange(IN_BYTES)
    else:
        byte = rng.randrange(2)
    sep = " " if rng.random() < 0.1 else ""
    return f"{area}{sep}{byte}.{rng.randrange(8)}"


def emit_blocks(gen, lo: int, hi: int, block) -> None:
    """A generator's body: n = lo..hi-1 random blocks, block(i, n) each, then the
    labels of forward jumps still pending (gen.pending: (index, label)), in order."""
    n = gen.rng.randrange(lo, hi)
    for i in range(n):
        block(i, n)
    for _, label in sorted(gen.pending):
        gen.lines.append(f"{label}:")


def counter_update(rng, k: float, c: int, load, indent: str = "") -> list[str]:
    """The lines that update counter C{c}, picked by the random number k: CU / CD
    (60 %), a load (load()) and S (20 %), or R (20 %)."""
    if k < 0.6:
        return [f"{indent}{rng.choice(['CU', 'CD'])} C{c}"]
    if k < 0.8:
        return [load(), f"{indent}S C{c}"]
    return [f"{indent}R C{c}"]


class Gen:
    def __init__(self, rng: random.Random):
        self.rng = rng
        self.symbols: dict[str, str] = {}
        self.lines: list[str] = []
        self.pending: list[tuple[int, str]] = []   # (block index to land on, label)
        self.nlabels = 0

    def operand(self, areas=READ_AREAS) -> str:
        rng = self.rng
        addr = _bit(rng, rng.choice(areas))
        if rng.random() < 0.15 and not addr.startswith(("T", "C")):
            name = f"Sym{len(self.symbols)}"
            self.symbols[name] = addr.replace(" ", "")
            return f'"{name}"' if rng.random() < 0.5 else name
        return addr

    def chain(self, depth: int, full: bool = False) -> None:
        """A rung's logic; `full` nests parentheses to the maximum depth
        (DEFAULT.nest_depth levels), which random nesting practically never reaches."""
        rng = self.rng
        self.lines.append(f"  {rng.choice(['LD', 'LDN'])} {self.operand()}")
        for step in range(rng.randrange(1 if full else 0, 5)):
            r = -1.0 if full and step == 0 else rng.random()
            if r < 0.15 and depth < DEFAULT.nest_depth:
                self.lines.append(f"  {rng.choice(OPENS)}")
                self.chain(depth + 1, full)
                self.lines.append("  )")
            elif r < 0.22:
                self.lines.append(f"  {rng.choice(['NOT', 'SET', 'CLR', 'NOP'])}")
            else:
                self.lines.append(f"  {rng.choice(COMBINE)} {self.operand()}")

    def block(self, index: int, nblocks: int) -> None:
        rng = self.rng
        for target, label in [p for p in self.pending if p[0] == index]:
            self.lines.append(f"{label}:")
            self.pending.remove((target, label))
        r = rng.random()
        if r < 0.55:
            self.chain(0, full=rng.random() < 0.04)
            for _ in range(rng.randrange(1, 3)):
                op = rng.choice(["=", "=", "S", "R"])
                self.lines.append(f"  {op} {self.operand(WRITE_AREAS)}")
        elif r < 0.65:
            self.chain(0)
            mem = _bit(rng, rng.choice(["M", "M", "Q"]))
            self.lines.append(f"  {rng.choice(['FP', 'FN'])} {mem}")
            self.lines.append(f"  = {self.operand(WRITE_AREAS)}")
        elif r < 0.80 and index + 1 < nblocks:
            self.chain(0)
            label = f"L{self.nlabels}"
            self.nlabels += 1
            self.pending.append((rng.randrange(index + 1, nblocks + 1), label))
            self.lines.append(f"  {rng.choice(['JU', 'JC', 'JCN'])} {label}")
        elif r < 0.84:
            # a loop that runs twice: toggles a marker, jumps back while it is 1
            label = f"L{self.nlabels}"
            self.nlabels += 1
            m = f"M{rng.randrange(4, 8)}.{rng.randrange(8)}"
            self.lines += [f"{label}: LD {m}", "  NOT", f"  = {m}", f"  JC {label}"]
        elif r < 0.85:
            # a backward jump on an input: may loop until the watchdog fires
            label = f"L{self.nlabels}"
            self.nlabels += 1
            self.lines += [f"{label}:", f"  LD {_bit(rng, 'I')}", f"  JC {label}"]
        elif r < 0.89:
            self.lines.append(f"  {rng.choice(['REFRESH', 'REFRESH I'])}")
        elif r < 0.92:
            self.lines.append("  REFRESH Q")
        else:
            self.chain(0)
            self.lines.append(f"  = {_bit(rng, 'PQ')}")

    def program(self) -> str:
        emit_blocks(self, 3, 25, self.block)
        body = self.lines
        if self.rng.random() < 0.7:
            body = body + ["  END"]
        decl = ["VAR"] + [f"  {n} AT {a};" for n, a in self.symbols.items()] + ["END_VAR"]
        return "\n".join((decl if self.symbols else []) + body) + "\n"


def random_program(seed: int) -> str:
    return Gen(random.Random(seed)).program()


def random_stimulus(seed: int, scans: int) -> str:
    """Scan rows or time rows (µs, a scan lasts roughly 0.1–0.6 µs at 100 MHz)."""
    rng = random.Random(seed ^ 0x5EED)
    cols = [f"I{b}.{n}" for b in range(IN_BYTES) for n in range(8)]
    if rng.random() < 0.5:
        rows = ["scan," + ",".join(cols)]
        for s in sorted(rng.sample(range(scans), rng.randrange(1, scans))):
            rows.append(f"{s}," + ",".join(str(rng.randrange(2)) for _ in cols))
    else:
        rows = ["t_us," + ",".join(cols)]
        times = sorted(rng.randrange(0, scans * 40) / 100 for _ in range(rng.randrange(1, 40)))
        for t in times:
            rows.append(f"{t}," + ",".join(str(rng.randrange(2)) for _ in cols))
    return "\n".join(rows) + "\n"


def scan_stimulus(seed: int, scans: int, in_bytes: int = IN_BYTES,
                  fixed: dict[str, int] | None = None) -> str:
    """A row for every scan, every input pin random (or as `fixed` says): the stimuli
    under which the wide engine's trace must equal the scalar one (spec §4)."""
    rng = random.Random(seed)
    cols = [f"I{b}.{n}" for b in range(in_bytes) for n in range(8)]
    rows = ["scan," + ",".join(cols)]
    for s in range(scans):
        rows.append(f"{s}," + ",".join(str((fixed or {}).get(c, rng.randrange(2))) for c in cols))
    return "\n".join(rows) + "\n"


def random_watch(seed: int) -> list[str]:
    rng = random.Random(seed ^ 0xAA)
    return [_bit(rng, rng.choice(["M", "I", "IR", "IF", "PI"])).replace(" ", "")
            for _ in range(rng.randrange(0, 5))]


# ------------------------------------------------------------------ mixed programs
# Word instructions for serial mode: loads, transfers, arithmetic, compares, timers and
# counters, between the bit blocks above. Run at 0.1 MHz (100 clocks per ms) a scan
# lasts a few ms, so timers with presets of 0..25 ms start, run out and stop.

WORD_SOURCES = ["MW", "MW", "IW", "QW", "T", "C", "MD"]
ARITH = ["+I", "-I", "*I", "/I", "MOD", "+I", "-I", "*I", "/I", "MOD",
         "+D", "-D", "*D", "/D", "MODD", "AW", "OW", "XOW", "AD", "OD", "XOD"]
SHIFTS = ["SLW", "SRW", "SSI", "SLD", "SRD", "SSD", "RLD", "RRD"]
SHIFT_COUNTS = [0, 1, 3, 15, 16, 17, 31, 32, 40, 255]
STATUS_READS = ["LD", "LDN", "A", "AN", "O", "ON", "X", "XN"]     # + a condition
STATUS_CONDITIONS = ["==0", "<>0", ">0", "<0", ">=0", "<=0", "UO"]
COMPARES = ["==I", "<>I", ">I", "<I", ">=I", "<=I", "==I", "<>I", ">I", "<I", ">=I", "<=I",
            "==D", "<>D", ">D", "<D", ">=D", "<=D"]
TIMERS = ["SD", "SS", "SP", "SF"]


class MixedGen(Gen):
    def overflow(self, cond: str) -> str:
        """Every third status read reads OV or OS instead (chosen by the program's
        length, not by the random stream, so that the programs stay as they were
        otherwise)."""
        k = len(self.lines)
        return cond if k % 3 else ("OV", "OS")[k // 3 % 2]

    def load(self) -> str:
        rng = self.rng
        r = rng.random()
        if r < 0.35:
            value = rng.choice([0, 1, 2, 3, 7, -7, 100, -1, 32767, -32768,
                                rng.randrange(-300, 300)])
            return f"  L {value}"
        if r < 0.42:
            return f"  L 16#{rng.randrange(0x10000):X}"
        if r < 0.5:
            return f"  L T#{rng.randrange(0, 26)}ms"
        if r < 0.55:                     # DINT constants, S7's form
            value = rng.choice([65536, -65536, 100000, 2**31 - 1, -2**31,
                                rng.randrange(-2**31, 2**31)])
            return f"  L L#{value}"
        area = rng.choice(WORD_SOURCES)
        n = rng.randrange(4 if area in ("IW", "QW") else 6 if area == "MD" else 8)
        return f"  L {area}{n}"

    def word_block(self) -> None:
        rng = self.rng
        r = rng.random()
        if r < 0.3:                      # arithmetic into a word
            self.lines += [self.load(), self.load(), f"  {rng.choice(ARITH)}"]
            if rng.random() < 0.3:       # a shift by a count, or by ACCU2's low byte
                count = f" {rng.choice(SHIFT_COUNTS)}" if rng.random() < 0.7 else ""
                self.lines.append(f"  {rng.choice(SHIFTS)}{count}")
            self.lines.append(f"  T {rng.choice(['MW', 'MW', 'QW', 'MD'])}{rng.randrange(4)}")
            if rng.random() < 0.3:       # S7's status bits of the result
                self.lines += [f"  {rng.choice(STATUS_READS)} "
                               f"{self.overflow(rng.choice(STATUS_CONDITIONS))}",
                               f"  = {self.operand(WRITE_AREAS)}"]
        elif r < 0.5:                    # compare into the RLO, combined or not
            if rng.random() < 0.5:
                self.lines += [self.load(), self.load(), f"  {rng.choice(COMPARES)}"]
            else:
                self.chain(0)
                self.lines += [self.load(), self.load(),
                               f"  {rng.choice('AO')} {rng.choice(COMPARES)}"]
            self.lines.append(f"  = {self.operand(WRITE_AREAS)}")
            if rng.random() < 0.3:       # the compare's status bits
                self.lines += [f"  {rng.choice(STATUS_READS)} "
                               f"{self.overflow(rng.choice(STATUS_CONDITIONS))}",
                               f"  = {self.operand(WRITE_AREAS)}"]
        elif r < 0.75:                   # a timer, then its status
            t = rng.randrange(8)
            self.chain(0)
            self.lines += [self.load() if rng.random() < 0.3 else
                           f"  L T#{rng.randrange(0, 26)}ms", f"  {rng.choice(TIMERS)} T{t}"]
            if rng.random() < 0.15:
                self.chain(0)
                self.lines.append(f"  R T{t}")
            self.lines += [f"  LD T{t}", f"  = {self.operand(WRITE_AREAS)}"]
        else:                            # a counter
            c = rng.randrange(8)
            self.chain(0)
            self.lines += counter_update(rng, rng.random(), c, self.load, "  ")
            self.lines += [f"  A C{c}", f"  = {self.operand(WRITE_AREAS)}"]
            if rng.random() < 0.3:
                self.lines += [f"  L C{c}", f"  T MW{rng.randrange(8)}"]

    def block(self, index: int, nblocks: int) -> None:
        if self.rng.random() < 0.45:
            for target, label in [p for p in self.pending if p[0] == index]:
                self.lines.append(f"{label}:")
                self.pending.remove((target, label))
            self.word_block()
        else:
            super().block(index, nblocks)


def random_mixed_program(seed: int) -> str:
    return MixedGen(random.Random(seed)).program()


def random_mixed_stimulus(seed: int, scans: int, us_per_scan: float) -> str:
    """Input bits and the input words IW0..IW3, by scan or by time."""
    rng = random.Random(seed ^ 0x5EED)
    cols = [f"I{b}.{n}" for b in range(IN_BYTES) for n in range(8)] + \
        [f"IW{n}" for n in range(4)]

    def row():
        return [str(rng.randrange(2)) for _ in range(8 * IN_BYTES)] + \
            [str(rng.choice([0, 1, -1, 5, 100, -32768, 32767, rng.randrange(-500, 500)]))
             for _ in range(4)]
    if rng.random() < 0.5:
        rows = ["scan," + ",".join(cols)]
        for s in sorted(rng.sample(range(scans), rng.randrange(1, scans))):
            rows.append(f"{s}," + ",".join(row()))
    else:
        rows = ["t_us," + ",".join(cols)]
        for t in sorted(rng.randrange(0, int(scans * us_per_scan)) for _ in range(25)):
            rows.append(f"{t}," + ",".join(row()))
    return "\n".join(rows) + "\n"


# Everything the generators write: every word, timer and counter they use, every marker
# byte they touch (_bit), the output words; for comparisons across modes.
FULL_WATCH = ([f"MW{n}" for n in range(8)] + [f"QW{n}" for n in range(4)] +
              [f"T{n}" for n in range(8)] + [f"C{n}" for n in range(8)] +
              [f"M{b}.{n}" for b in (0, 1, 2, 3, 255) for n in range(8)])


def random_mixed_watch(seed: int) -> list[str]:
    rng = random.Random(seed ^ 0xAB)
    pick = [f"MW{n}" for n in range(8)] + [f"T{n}" for n in range(8)] + \
        [f"C{n}" for n in range(8)] + ["QW0", "IW1", "M0.1"]
    return rng.sample(pick, rng.randrange(1, 6))


# ------------------------------------------------------------------ parallel-mode programs
# Mixed programs with the shapes the partitioning compiler (bitbyte/compiler/) treats
# specially, on top of the mixed blocks: compares feeding timers/counters directly (the
# RLO on the byte side at an update), A/O compares inside parentheses, jumps right after
# compares, loops with word code (on a toggled marker or on a compare), a status read at
# the top of a loop whose bottom updates it, a conditional END, REFRESH after word code.
# Every loop ends within 3 iterations.

class ParallelGen(MixedGen):
    def cmp_lines(self, combine: str = "") -> list[str]:
        rng = self.rng
        head = f"  {combine} " if combine else "  "
        return [self.load(), self.load(), f"{head}{rng.choice(COMPARES)}".replace("   ", "  ")]

    def new_label(self) -> str:
        label = f"P{self.nlabels}"
        self.nlabels += 1
        return label

    def parallel_block(self, index: int, nblocks: int) -> None:
        rng = self.rng
        r = rng.random()
        c, t = rng.randrange(4), rng.randrange(4)
        out = self.operand(WRITE_AREAS)
        if r < 0.14:                     # compare straight into an update, after a read
            if rng.random() < 0.6:
                self.lines += [f"  {rng.choice(['LD', 'A', 'ON'])} C{c}", f"  = {out}"]
            self.lines += self.cmp_lines()
            self.lines.append(f"  {rng.choice(['CU', 'CD', 'S', 'R'])} C{c}")
            if rng.random() < 0.5:
                self.lines += [f"  L T#{rng.randrange(0, 12)}ms", self.load()]
                self.lines += self.cmp_lines() + [f"  {rng.choice(TIMERS)} T{t}"]
            self.lines += [f"  {rng.choice(['A', 'X', 'LD'])} C{c}",
                           f"  = {self.operand(WRITE_AREAS)}"]
        elif r < 0.28:                   # compares inside parentheses
            self.chain(0)
            self.lines += [f"  {rng.choice(OPENS)}", f"  LD {self.operand()}"]
            self.lines += self.cmp_lines(rng.choice(["A", "O", ""]))
            if rng.random() < 0.5:
                self.lines += self.cmp_lines(rng.choice(["A", "O"]))
            self.lines += ["  )", f"  = {out}"]
        elif r < 0.42 and index + 1 < nblocks:   # a jump on a compare
            label = self.new_label()
            self.pending.append((rng.randrange(index + 1, nblocks + 1), label))
            self.lines += self.cmp_lines(rng.choice(["", "", "A", "O"]))
            self.lines.append(f"  {rng.choice(['JC', 'JCN', 'JU'])} {label}")
        elif r < 0.52:                   # a loop with word code on a toggled marker
            label, m = self.new_label(), f"M{rng.randrange(8, 12)}.{rng.randrange(8)}"
            w = rng.randrange(4)
            self.lines += [f"{label}: L MW{w}", "  L 1", "  +I", f"  T MW{w}"]
            if rng.random() < 0.5:
                self.lines += self.cmp_lines() + [f"  = {out}"]
            self.lines += [f"  LD {m}", "  NOT", f"  = {m}", f"  JC {label}"]
        elif r < 0.60:                   # a loop on a compare (at most 3 turns)
            label = self.new_label()
            self.lines += [f"{label}: L MW7", "  L 1", "  +I", "  T MW7", "  L MW7", "  L 3",
                           "  MOD", "  L 0", "  <>I", f"  JC {label}"]
        elif r < 0.70:                   # status read at the top, update at the bottom
            label, m = self.new_label(), f"M{rng.randrange(12, 14)}.{rng.randrange(8)}"
            area, n = rng.choice([("C", c), ("T", t)])
            update = f"CU C{c}" if area == "C" else f"{rng.choice(TIMERS)} T{t}"
            self.lines += [f"{label}: {rng.choice(['LD', 'LDN'])} {area}{n}",
                           f"  A {self.operand()}", f"  = {out}"]
            if area == "T":
                self.lines.append(f"  L T#{rng.randrange(0, 12)}ms")
            self.lines += [f"  LD {self.operand()}", f"  {update}",
                           f"  LD {m}", "  NOT", f"  = {m}", f"  JC {label}"]
        elif r < 0.78 and index + 1 < nblocks:   # a conditional end of the scan
            label = self.new_label()
            self.pending.append((index + 1, label))
            self.chain(0)
            self.lines += [f"  JCN {label}", f"  L {rng.randrange(100)}",
                           f"  T MW{rng.randrange(4)}", "  END"]
        elif r < 0.86:                   # REFRESH after word code, then edge flags
            self.lines += [f"  L {rng.randrange(100)}", f"  T MW{rng.randrange(4)}",
                           "  REFRESH", f"  LD IR{rng.randrange(2)}.{rng.randrange(8)}",
                           f"  O IF{rng.randrange(2)}.{rng.randrange(8)}", f"  = {out}"]
        elif r < 0.93:                   # compare left in the RLO for what follows
            self.lines += self.cmp_lines(rng.choice(["", "A", "O"]))
        else:                            # use the RLO the previous block left
            kind = rng.random()
            if kind < 0.4:
                self.lines.append(f"  CU C{c}")
            elif kind < 0.6:
                self.lines += [f"  L T#{rng.randrange(0, 12)}ms", f"  {rng.choice(TIMERS)} T{t}"]
            elif kind < 0.8:
                self.lines += self.cmp_lines(rng.choice(["A", "O"]))
            self.lines.append(f"  = {out}")

    def block(self, index: int, nblocks: int) -> None:
        if self.rng.random() < 0.4:
            for target, label in [p for p in self.pending if p[0] == index]:
                self.lines.append(f"{label}:")
                self.pending.remove((target, label))
            self.parallel_block(index, nblocks)
        else:
            super().block(index, nblocks)


def random_parallel_program(seed: int) -> str:
    return ParallelGen(random.Random(seed)).program()


TIMER_LINE = re.compile(r"^\s*(?:\w+:\s*)?(?:SD|SS|SP|SF|R\s+T\s*\d+)\b", re.IGNORECASE)


def strip_timers(text: str) -> str:
    """Drop SD/SS/SP/SF and R T n (a label on such a line moves to its own line):
    timers depend on time, which differs between serial and parallel mode."""
    out = []
    for line in text.split("\n"):
        if TIMER_LINE.match(line):
            label = re.match(r"^\s*(\w+):", line)
            if label:
                out.append(f"{label.group(1)}:")
            continue
        out.append(line)
    return "\n".join(out)


TIMER_START = re.compile(r"^(\s*(?:\w+:\s*)?)(SD|SS|SP|SF)(\s+T\s*\d+.*)$", re.IGNORECASE)
TIMER_VALUE = re.compile(r"\bL\s+T\s*(\d+)\b")
TIMER_INDEX = re.compile(r"\b(?:SD|SS|SP|SF|R)\s+T\s*(\d+)", re.IGNORECASE)
LONG_PRESET = "T#9000s"


def long_timers(text: str, rng: random.Random | None = None) -> str:
    """For comparisons across modes (parallel against serial), whose timing differs:
    every timer start gets a preset that does not depend on it, right before the
    start: `L T#9000s`, which does not run out within a run (SD / SS stay off, SP / SF
    are on from their start until they are reset or their enable ends them), or, with
    `rng`, half of the time `L T#0ms`, which runs out at once (SD follows its enable,
    SS is on from its start). `L T n` (the time value, which depends on the mode's
    timing) reads a timer the program never starts instead (its value is 0 in every
    mode)."""
    started = {int(m.group(1)) for m in TIMER_INDEX.finditer(text)}
    idle = next(n for n in range(8, 64) if n not in started)
    out = []
    for line in text.split("\n"):
        start = TIMER_START.match(line)
        if start:
            label, kind, rest = start.groups()
            if label.strip():
                out.append(label.rstrip())
            preset = "T#0ms" if rng is not None and rng.random() < 0.5 else LONG_PRESET
            out += [f"  L {preset}", f"  {kind}{rest}"]
            continue
        out.append(TIMER_VALUE.sub(f"L T{idle}", line))
    return "\n".join(out)


def random_scan_stimulus(seed: int, scans: int) -> str:
    """Input bits and IW0..IW3 keyed by scan only: inputs are constant within a scan,
    so PI, IW and REFRESH read the same values in every mode."""
    rng = random.Random(seed ^ 0x5CA7)
    cols = [f"I{b}.{n}" for b in range(IN_BYTES) for n in range(8)] + \
        [f"IW{n}" for n in range(4)]
    rows = ["scan," + ",".join(cols)]
    for s in sorted(rng.sample(range(scans), rng.randrange(1, scans))):
        rows.append(f"{s}," + ",".join(
            [str(rng.randrange(2)) for _ in range(8 * IN_BYTES)] +
            [str(rng.choice([0, 1, -1, 5, 100, 32767, rng.randrange(-500, 500)]))
             for _ in range(4)]))
    return "\n".join(rows) + "\n"


def plant_stimulus(rng, scans: int, min_flips: int = 0, word_p: float | None = None) -> str:
    """A scan-keyed stimulus over I0.0..I11.7 and IW0..IW7 (the Table-1-sized programs'
    inputs): each scan flips min_flips..11 random inputs and sets one random IW (with
    probability word_p; None: always)."""
    cols = [f"I{b}.{n}" for b in range(12) for n in range(8)] + [f"IW{n}" for n in range(8)]
    state = dict.fromkeys(cols, 0)
    rows = ["scan," + ",".join(cols)]
    for s in range(scans):
        for _ in range(rng.randrange(min_flips, 12)):
            c = rng.choice(cols[:96])
            state[c] ^= 1
        if word_p is None or rng.random() < word_p:
            state[rng.choice(cols[96:])] = rng.randrange(-200, 2000)
        rows.append(f"{s}," + ",".join(str(state[c]) for c in cols))
    return "\n".join(rows) + "\n"


def matches_serial(sim, expected, scans: int, where, view: str) -> None:
    """Run a ParSim scan by scan against the serial reference `expected` (per scan:
    trace values and state snapshot, bitbyte.ref.parsim.serial_states): equal scans,
    and both hit the watchdog / step limit at the same scan.  where(scan) names the
    case in a failure, view is the side-by-side listing shown with it."""
    from bitbyte.ref.parsim import state_snapshot
    for scan in range(scans):
        rec = sim.run_scan()
        if scan >= len(expected):
            assert rec is None, f"{where(scan)}: serial hit the watchdog, parallel not"
            break
        assert rec is not None, f"{where(scan)}: parallel hit its step limit"
        assert (rec.values, state_snapshot(sim)) == expected[scan], f"{where(scan)}\n{view}"


def make_cases(tmp_path_factory, tag: str, count: int, make, *args) -> list:
    """A module fixture's cases: make(tmp, i, *args) for i < count, in a fresh tmp
    directory `tag`; the run's seed printed with them."""
    tmp = tmp_path_factory.mktemp(tag)
    print(f"{tag} programs: BITBYTE_SEED={os.environ['BITBYTE_SEED']}, {count} programs")
    return [make(tmp, i, *args) for i in range(count)]
