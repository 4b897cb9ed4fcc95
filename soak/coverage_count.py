"""Functional coverage of the soak: instruction x operand area x mode x exchange.

A bin is (mnemonic, operand kind, mode, exchange); beside them, the parenthesis depth
reached, ("(", depth, mode, exchange) for every depth from 1 to the build's
NestDepth (an opening parenthesis executed at that depth).  The operand kind is the operand's
area (`I`, `M`, `T`, ...), `INT` / `TIME` for a constant, `LABEL` for a jump target and
`-` for none.

A bin counts what the *hardware* executed in that mode and exchange: the harness's
retirement counts per program address (`bitbyte run --line-counts`,
bitbyte.run.line_counts), mapped through the run's own listing back to the source
instruction each word was made from (PartInstr.origin) — in parallel and free-running
mode the bit part's and the byte part's words (`A ==I` runs as the byte side's `==I`).  Dead code
does not count, and nothing the reference interpreter did is credited to a mode.  A
parenthesis's depth is its nesting in the program (the generators jump only between
rungs, outside parentheses; source_keys refuses a program that does not).
tests/test_soak_checker.py checks that the hardware's counts equal the reference
interpreter's executions, depths included (Coverage.counting), serially, and in
parallel mode for runs the watchdog did not end (where one did, the two modes'
different timing ends the scan at different points: a loop waiting for an input
runs a different number of rounds).

The legal bins come from the parser's instruction signatures (bitbyte.lang.parser
SIGNATURES, spec §3's operand table), not from what the generator happens to emit:
every mnemonic with every area it accepts, in every mode (the output edges `QR`/`QF`
and `REFRESH Q` included since issue 16).  Left out, and said so in docs/soak.md: the
channel operands (`FBI k`, `FBY k`, `READ`, `WRITE`), which only the partitioning
compiler or hand-partitioned sections write, and the byte part's END_B (its end of scan,
which the firmware records as no instruction).
"""
from __future__ import annotations

import csv
from collections import Counter
from contextlib import contextmanager

from bitbyte.lang.config import DEFAULT
from bitbyte.lang.parser import SIGNATURES
from bitbyte.lang.program import JUMPS, OPENS
from bitbyte.ref.refsim import RefSim

MODES = (("serial", "-"), ("parallel", "handshake"), ("parallel", "queue"),
         ("free", "queue-free"), ("free", "marker"))
CHANNEL_AREAS = ("FBI", "FBY")
CHANNEL_MNEMONICS = ("READ", "WRITE")
CLOSE = ")"


def operand_kind(ins) -> str:
    op = ins.operand
    if op is None:
        return "-"
    if op.kind == "label":
        return "LABEL"
    return op.area


def legal_bins() -> set[tuple[str, str, str, str]]:
    bins = set()
    for mnemonic, sig in SIGNATURES.items():
        if mnemonic in CHANNEL_MNEMONICS:
            continue
        kinds = [a for a in sig.accepts if a not in CHANNEL_AREAS] or ["-"]
        if sig.optional:                # a shift's count may come from ACCU2
            kinds.append("-")
        bins |= {(mnemonic, kind, mode, ex) for kind in kinds for mode, ex in MODES}
    bins |= {("(", str(d), mode, ex) for d in range(1, DEFAULT.nest_depth + 1)
             for mode, ex in MODES}
    return bins


def is_bin(ins) -> bool:
    """An instruction that has a bin: not a channel transfer, not the byte part's end."""
    op = ins.operand
    return not (ins.mnemonic in CHANNEL_MNEMONICS or ins.mnemonic == "END_B"
                or (op is not None and op.area in CHANNEL_AREAS))


def source_keys(program) -> list[list[tuple[str, str]]]:
    """The bins one execution of each source instruction counts: its (mnemonic, kind),
    and for an opening parenthesis ("(", depth) with the depth its nesting in the
    program.  That static depth is the executed one only if no jump leaves or enters
    parentheses: a jump or a label inside them is refused (ValueError)."""
    keys, depth = [], 0
    labelled = set(program.labels.values())
    for i, ins in enumerate(program.instrs):
        if depth and (ins.mnemonic in JUMPS or i in labelled):
            raise ValueError(f"{program.path}:{ins.line}:{ins.col}: a jump or a label "
                             "inside parentheses: the coverage's static depth does not hold")
        here = [(ins.mnemonic, operand_kind(ins))]
        if ins.mnemonic in OPENS:
            depth += 1
            here.append(("(", str(depth)))
        elif ins.mnemonic == CLOSE:
            depth = max(depth - 1, 0)
        keys.append(here)
    return keys


def read_line_counts(path) -> dict[str, dict[int, int]]:
    """`bitbyte run --line-counts` CSV: part -> address -> count (END_B's empty count
    left out)."""
    out: dict[str, dict[int, int]] = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if row["count"] != "":
                out.setdefault(row["part"], {})[int(row["address"])] = int(row["count"])
    return out


class Coverage:
    def __init__(self):
        self.counts: Counter = Counter()

    def add_hardware(self, mode: str, exchange: str, program, parts) -> None:
        """program: the source program (bitbyte.lang.program.Program); parts:
        (listing, address -> count) for each program the hardware ran in this mode
        (serially the whole program; otherwise the bit and the byte part).  A source
        instruction executed as often as the listing's words made from it retired
        (a part's word names its source instruction, PartInstr.origin; a serial
        listing is the program itself), channel transfers and END_B aside; where the
        partitioning compiler mirrors one on both sides (a jump: JC and JC_B), the
        larger count."""
        keys = source_keys(program)
        ran: Counter = Counter()
        for listing, counts in parts:
            for pc, ins in enumerate(listing):
                if not is_bin(ins):
                    continue
                src = getattr(ins, "origin", None)
                if src is None:
                    if program.instrs[pc] is not ins:
                        raise ValueError(f"{program.path}: listing word {pc} is no "
                                         "source instruction and names none")
                    src = pc
                ran[src] = max(ran[src], counts.get(pc, 0))
        for src, n in ran.items():
            for k in keys[src]:
                if n:
                    self.counts[k + (mode, exchange)] += n

    @contextmanager
    def counting(self, *modes: tuple[str, str]):
        """Count what RefSim executes inside the block under each of `modes` (the
        reference side of the check that the hardware's counts are right)."""
        step, end_scan = RefSim._step, RefSim._end_scan
        counts = self.counts

        def counted_step(sim, ins, pc, clock):
            key = (ins.mnemonic, operand_kind(ins))
            result = step(sim, ins, pc, clock)
            keys = [key] + ([("(", str(len(sim.stack)))] if ins.mnemonic in OPENS else [])
            for k in keys:
                for mode, ex in modes:
                    counts[k + (mode, ex)] += 1
            return result

        def counted_end(sim, end, cycles):
            for mode, ex in modes:
                counts[("END", "-", mode, ex)] += 1
            return end_scan(sim, end, cycles)

        RefSim._step, RefSim._end_scan = counted_step, counted_end
        try:
            yield
        finally:
            RefSim._step, RefSim._end_scan = step, end_scan

    def to_json(self) -> list:
        return [list(k) + [v] for k, v in sorted(self.counts.items())]


# ------------------------------------------------------------------ the plant's cross
# Spec §7: protection x layout x contention, counted per reader scan of the plant runs
# the soak makes (tests/test_plant_tearing.py). Contention of a reader scan: `overlap`
# when its precycle (waits included) shares a clock with a postcycle of the other core,
# `apart` when not, `copy_fail` when the scan ran on old copies (the semaphore's skipped
# precycle, ping-pong's overtaken one: the flag is sticky, so the scan it first shows
# in). `none` has no flag: its failure is tearing itself.
PROTECTIONS = ("semaphore", "pingpong", "none")
LAYOUTS = ("compact", "random")
CONTENTIONS = ("apart", "overlap", "copy_fail")


def plant_legal_bins() -> set[tuple[str, str, str]]:
    return {(p, lay, c) for p in PROTECTIONS for lay in LAYOUTS for c in CONTENTIONS
            if c != "copy_fail" or p != "none"}


def _copies(rows, clock_mhz: int) -> list[tuple[int, int, int]]:
    """(scan, precycle, postcycle) as half-open clock intervals, from a core's trace
    (t_us ends the postcycle; the postcycle follows the scan, the scan the precycle)."""
    from fractions import Fraction
    out = []
    for r in rows:
        end = int(Fraction(r["t_us"]) * clock_mhz)
        post, cycles, pre = int(r["post"]), int(r["cycles"]), int(r["pre"])
        out.append(((end - post - cycles - pre, end - post - cycles), (end - post, end)))
    return out


def plant_contention(reader_rows, other_cores, clock_mhz: int = 100) -> list[str]:
    """The contention bin of each reader scan (see above); other_cores: the trace rows
    of each other core."""
    writes = [post for rows in other_cores for _, post in _copies(rows, clock_mhz)]
    bins, failed = [], False
    for (lo, hi), _ in _copies(reader_rows, clock_mhz):
        row = reader_rows[len(bins)]
        first_fail = row["copy_fail"] == "1" and not failed
        failed = failed or row["copy_fail"] == "1"
        if first_fail:
            bins.append("copy_fail")
        else:
            bins.append("overlap" if any(a < hi and lo < b for a, b in writes) else "apart")
    return bins
