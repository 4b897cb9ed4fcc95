"""Helpers shared by `make bench` (bench/run_bench.py) and tests/test_response_bound.py.

Everything here goes through the user's command, `bitbyte run` (spec §4), and reads
what it writes (TRACE.csv, the summary), so the numbers are the ones a user gets.
Static facts about a program (instruction counts, the clock at which an instruction
executes in serial mode) come from the parser and the cost tables of the reference
interpreter, never from the hardware.
"""
from __future__ import annotations

import csv
import math
import os
import random
import re
import subprocess
import sys
import time
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BUILD = ROOT / "build" / "bench"
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "synth"))
from run_synth import git_rev  # noqa: E402,F401  (the tree a figure was measured on)
DEFAULT_CLOCK_MHZ = Fraction(100)


def source_rev() -> str:
    """The commit a bench's figures belong to: `git describe`, with "-dirty" when a
    tracked file outside docs/ differs from it. `make bench` runs its benches one after
    another, each writing its report into docs/: those reports are not the code the
    next bench measures."""
    try:
        head = subprocess.run(["git", "describe", "--always"], cwd=ROOT,
                              capture_output=True, text=True).stdout.strip() or "?"
        changed = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no",
                                  "--", ".", ":(exclude)docs"], cwd=ROOT,
                                 capture_output=True, text=True).stdout.strip()
    except OSError:
        return "?"
    return head + ("-dirty" if changed else "")


# ---------------------------------------------------------------------- progress
_T0 = time.perf_counter()


def progress(msg: str) -> None:
    print(f"[bench {time.perf_counter() - _T0:6.1f} s] {msg}", flush=True)


# ---------------------------------------------------------------------- clock
def splice_section(text: str, lines: list[str]) -> str:
    """text (docs/performance.md) with the section `lines` replaced, found by its first
    and last line (its markers), or added at the end: a benchmark run alone rewrites
    just its own section."""
    begin, end = lines[0], lines[-1]
    block = "\n".join(lines)
    if begin in text and end in text:
        head, rest = text.split(begin, 1)
        return head + block + rest.split(end, 1)[1]
    return text.rstrip("\n") + "\n\n" + block + "\n"


def synth_clock() -> tuple[Fraction, str]:
    """The clock the benchmark states its µs at: `Fmax HX8K: <n> MHz` from
    docs/synthesis.md (make synth), rounded down to whole kHz (bitbyte run's
    --clock-mhz resolution); else 100 MHz. Returns (MHz, where it came from)."""
    path = ROOT / "docs" / "synthesis.md"
    if path.exists():
        m = re.search(r"^Fmax HX8K:\s*([0-9]+(?:\.[0-9]+)?)\s*MHz\s*$", path.read_text(),
                      re.MULTILINE)
        if m:
            f = Fraction(m.group(1))
            f = Fraction(math.floor(f * 1000), 1000)
            return f, f"`Fmax HX8K: {m.group(1)} MHz` in docs/synthesis.md (make synth)"
    return DEFAULT_CLOCK_MHZ, ("100 MHz: docs/synthesis.md has no `Fmax HX8K` line "
                               "(run make synth), so the spec's default clock is used")


def mhz_text(f: Fraction) -> str:
    return f"{float(f):g}"


# ---------------------------------------------------------------------- running
def bitbyte_cmd() -> list[str]:
    return [sys.executable, "-m", "bitbyte.cli"]


@dataclass
class Run:
    rc: int
    stdout: str
    stderr: str
    header: list[str] = field(default_factory=list)
    rows: list[list[int]] = field(default_factory=list)   # scan, end_clock, cycles, values...
    wall_s: float = 0.0
    exchange: str | None = None      # the run's exchange (bitbyte.run.prepare.check_mode)

    @property
    def ok(self) -> bool:
        return self.rc == 0

    def column(self, name: str) -> list[int]:
        i = self.header.index(name)
        return [r[i] for r in self.rows]

    @property
    def cycles(self) -> list[int]:
        return [r[2] for r in self.rows]

    def stalls(self) -> tuple[int, int] | None:
        """(bit side, byte side) clocks spent waiting, from the summary."""
        m = re.search(r"stalls\s+bit side (\d+), byte side (\d+)", self.stdout)
        return (int(m.group(1)), int(m.group(2))) if m else None

    def free_running(self) -> dict | None:
        """Free-running mode's own figures from the summary (None in other modes): the
        byte side's scans and its mean scan in clocks (simulated clocks / its scans),
        the exchange, and the queue losses as the summary states them, overflows /
        underflows per direction (None without the line: the marker exchange has no
        queue; a queue-free run without it is an error)."""
        m = re.search(r"byte side\s+(\d+) scans \(free-running\)", self.stdout)
        if not m:
            return None
        scans = int(m.group(1))
        c = re.search(r"simulated\s+[0-9.]+ us, (\d+) clocks", self.stdout)
        clocks = int(c.group(1)) if c else None
        q = re.search(r"queue losses\s+overflows to-byte (\d+) to-bit (\d+), underflows "
                      r"to-byte (\d+) to-bit (\d+)", self.stdout)
        if not q and self.exchange == "queue-free":
            raise RuntimeError("a queue-free run's summary has no 'queue losses' line:\n"
                               + self.stdout)
        losses = [int(x) for x in q.groups()] if q else None
        return dict(byte_scans=scans, clocks=clocks, losses=losses, exchange=self.exchange,
                    byte_scan=clocks / scans if clocks and scans else None)

    def mclocks_per_s(self) -> float | None:
        m = re.search(r"([0-9.]+) M clocks/s", self.stdout)
        return float(m.group(1)) if m else None


def split_mode(spec: str) -> tuple[str, str | None]:
    """A mode of the benchmark's mode list: `serial`, `parallel`, `parallel:queue`
    (mode:exchange), ..."""
    mode, _, exchange = spec.partition(":")
    return mode, exchange or None


def run_bitbyte(program: Path | str, *, mode: str = "serial", clock_mhz: Fraction,
                stimulus: Path | str | None = None, scans: int | None = None,
                until_us: str | None = None, costs: str = "paper", sim: str = "verilator",
                trace: Path | None = None, watch: str = "", extra: list[str] = ()) -> Run:
    """`bitbyte run ...`; reads the trace back with end clocks (cumulative cycles)."""
    from bitbyte.run.prepare import check_mode
    mode, exchange = split_mode(mode)
    cmd = bitbyte_cmd() + ["run", str(program), "--mode", mode, "--sim", sim,
                           "--clock-mhz", str(clock_mhz_text(clock_mhz)),
                           "--costs", costs]
    if exchange:
        cmd += ["--exchange", exchange]
    if stimulus:
        cmd += ["--stimulus", str(stimulus)]
    if scans is not None:
        cmd += ["--scans", str(scans)]
    if until_us is not None:
        cmd += ["--until-us", str(until_us)]
    if watch:
        cmd += ["--watch", watch]
    if trace is not None:
        trace.parent.mkdir(parents=True, exist_ok=True)
        if trace.exists():
            trace.unlink()
        cmd += ["--trace", str(trace)]
    cmd += list(extra)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    run = Run(proc.returncode, proc.stdout, proc.stderr, wall_s=time.perf_counter() - t0,
              exchange=check_mode(mode, exchange))
    if trace is not None and trace.exists():
        run.header, run.rows = read_trace(trace)
    return run


def clock_mhz_text(f: Fraction) -> str:
    """--clock-mhz text: an exact decimal (whole kHz)."""
    if f.denominator == 1:
        return str(f.numerator)
    return f"{float(f):.3f}".rstrip("0").rstrip(".")


def read_trace(path: Path) -> tuple[list[str], list[list[int]]]:
    """TRACE.csv -> header, rows [scan, end_clock, cycles, values...]. The end clock is
    the running sum of `cycles` (scan 0 latches at clock 0; each scan latches right
    after the previous one's END), which is exact, unlike t_us (rounded to 6 places)."""
    with open(path, newline="") as fh:
        reader = csv.reader(fh)
        header = next(reader)
        rows, end = [], 0
        for rec in reader:
            cycles = int(rec[2])
            end += cycles
            rows.append([int(rec[0]), end, cycles] + [int(v) for v in rec[3:]])
    return header, rows


def partition_report(program: Path | str, outdir: Path) -> dict | None:
    """`bitbyte asm --mode parallel`: sizes of the two parts and the transfers the
    partitioning compiler inserted (from PROG.partition.txt); None if it fails."""
    outdir.mkdir(parents=True, exist_ok=True)
    proc = subprocess.run(bitbyte_cmd() + ["asm", str(program), "--mode", "parallel",
                                           "-o", str(outdir)],
                          capture_output=True, text=True, cwd=ROOT)
    rep = outdir / (Path(program).stem + ".partition.txt")
    if proc.returncode != 0 or not rep.exists():
        return None
    text = rep.read_text()
    out = {}
    for key, pat in (("bit_part", r"bit part:\s+(\d+) instructions"),
                     ("byte_part", r"byte part:\s+(\d+) instructions"),
                     ("to_byte", r"transfers bit -> byte:\s+(\d+)"),
                     ("to_bit", r"transfers byte -> bit:\s+(\d+)")):
        m = re.search(pat, text)
        out[key] = int(m.group(1)) if m else None
    m = re.search(r"bit-side schedule: (\d+) rungs moved .*?(\d+) -> (\d+) clocks", text,
                  re.DOTALL)
    out["schedule"] = [int(g) for g in m.groups()] if m else None
    out["report"] = str(rep.relative_to(ROOT)) if rep.is_relative_to(ROOT) else str(rep)
    return out


def probe_mode(mode: str, clock_mhz: Fraction) -> tuple[bool, str]:
    """Does `bitbyte run --mode MODE` work now? Tried on the paper's Fig. 5 program."""
    r = run_bitbyte(ROOT / "examples" / "fig5.il", mode=mode, clock_mhz=clock_mhz,
                    stimulus=ROOT / "examples" / "fig5.stim.csv", scans=3,
                    trace=BUILD / f"probe_{mode.replace(':', '_')}.csv")
    if r.ok and len(r.rows) == 3:
        return True, "works"
    msg = (r.stderr.strip().splitlines() or [f"exit {r.rc}"])[-1]
    return False, msg


# ---------------------------------------------------------------------- static counts
@dataclass
class Static:
    """What the program text says, serial mode: one entry per instruction (END last)."""
    path: Path
    n_bit: int            # bit-processor instructions (jumps included), END excluded
    n_word: int           # byte-processor instructions
    n_jump: int
    kinds: list[str]      # "bit" | "word" | "end" per instruction
    mnemonics: list[str]
    operands: list[str]

    @property
    def n(self) -> int:
        return self.n_bit + self.n_word

    @property
    def word_share(self) -> float:
        return self.n_word / self.n if self.n else 0.0

    def serial_clocks(self, word_cost: int, bit_cost: int = 1) -> int:
        """Straight-line scan (every instruction once, no jump taken) in serial mode:
        Σ bit + Σ word costs + 1 (END), docs/isa.md "Serial mode timing"."""
        return self.n_bit * bit_cost + self.n_word * word_cost + 1

    def offset(self, index: int, word_cost: int) -> int:
        """Clock of instruction `index` counted from the scan's latch clock (0: the
        first instruction executes in the latch clock), valid when no jump executes
        before it (a jump is checked for)."""
        clk = 0
        for i in range(index):
            if self.mnemonics[i] in ("JU", "JC", "JCN"):
                raise ValueError(f"instruction {i} before {index} is a jump: the clock "
                                 "of a later instruction is not static")
            clk += word_cost if self.kinds[i] == "word" else 1
        return clk

    def find(self, mnemonic: str, operand: str) -> int:
        for i, (m, o) in enumerate(zip(self.mnemonics, self.operands)):
            if m == mnemonic and o.replace(" ", "").upper() == operand.upper():
                return i
        raise KeyError(f"{mnemonic} {operand} not in {self.path}")


def static_counts(path: Path | str) -> Static:
    from bitbyte.lang.config import Config
    from bitbyte.lang.parser import parse_file
    from bitbyte.lang.costs import byte_kind
    prog = parse_file(str(path), Config())
    kinds, mns, ops = [], [], []
    nb = nw = nj = 0
    for ins in prog.instrs:
        mns.append(ins.mnemonic)
        ops.append(ins.operand.address() if ins.operand is not None
                   and hasattr(ins.operand, "address") else "")
        if ins.mnemonic == "END":
            kinds.append("end")
        elif byte_kind(ins) is not None:
            kinds.append("word")
            nw += 1
        else:
            kinds.append("bit")
            nb += 1
            nj += ins.mnemonic in ("JU", "JC", "JCN")
    # a program may END early (an explicit END before the last line): count up to it
    return Static(Path(path), nb, nw, nj, kinds, mns, ops)


def cost_table(name: str) -> dict[str, int]:
    from bitbyte.lang.costs import COST_TABLES
    t = COST_TABLES[name]
    return {"word": t["load"], "binary": t["binary"]}


# ---------------------------------------------------------------------- stimuli
def fmt_us(x: Fraction) -> str:
    """A t_us cell: exact decimal with up to 6 places (nanosecond grid is enough)."""
    return f"{float(x):.6f}".rstrip("0").rstrip(".")


def random_edges(n: int, scan_clocks: int, f: Fraction, rng: random.Random,
                 start_scans: float = 3.0, gap_scans: tuple[float, float] = (2.5, 3.5)
                 ) -> list[Fraction]:
    """n edge times (µs, 1 ns grid): gaps uniform over an interval one scan wide, so
    the edges fall at uniformly spread phases of the scan; gaps > 2 scans, so every
    response ends before the next edge."""
    scan_us = Fraction(scan_clocks) / f
    t = scan_us * Fraction(start_scans)
    out = []
    lo, hi = gap_scans
    for _ in range(n):
        t += scan_us * Fraction(lo) + scan_us * Fraction(hi - lo) * Fraction(rng.random())
        t_ns = Fraction(math.ceil(t * 1000), 1000)     # ns grid: 6-decimal µs
        out.append(t_ns)
        t = t_ns
    return out


def write_edge_stimulus(path: Path, pin: str, edges: list[Fraction],
                        background: list[tuple[Fraction, str, int]] = ()) -> None:
    """t_us stimulus: `pin` toggles at each edge time (0 -> 1 -> 0 ...); optional
    background changes (time, other input, value) -- the rest of the plant moving."""
    path.parent.mkdir(parents=True, exist_ok=True)
    others = sorted({c for _, c, _ in background})
    cols = [pin] + others
    events = [(t, pin, (i + 1) % 2) for i, t in enumerate(edges)] + list(background)
    events.sort(key=lambda e: (e[0], e[1] != pin))
    lines = ["t_us," + ",".join(cols), "0," + ",".join("0" for _ in cols)]
    for t, col, val in events:
        lines.append(fmt_us(t) + "," + ",".join(str(val) if c == col else "" for c in cols))
    path.write_text("\n".join(lines) + "\n")


# ---------------------------------------------------------------------- response
@dataclass
class Response:
    """One access kind's responses to the edges, clocks as Fractions of a clock."""
    kind: str                 # "image" (I -> Q) or "direct" (PI -> PQ)
    clocks: list[Fraction]    # response per edge, in clocks
    phase: list[float]        # the edge's phase in the scan it fell in (0..1)
    bound: int                # analytical worst case, clocks
    exact: bool               # True: the output's change clock is known exactly
    note: str = ""
    scan_max: int = 0
    scan_min: int = 0
    local_ok: bool = True     # each response < the two scans it spans (image) / the
                              # previous scan + read-to-write span (direct)


def responses(run: Run, edges: list[Fraction], f: Fraction, out_col: str, kind: str,
              write_offset: int | None = None, read_offset: int | None = None
              ) -> Response:
    """Response of output `out_col` to each edge of the input (toggling 0/1/0...).

    The output changes at the END of the scan that saw the edge (process image), so
    its moment is the end of that scan: end_clock / f (bitbyte.run.response's
    responding_scan finds it, as for the run summary's response figures). For a direct output (`= PQ`)
    the pin changes at the end of the `= PQ` instruction's clock: latch + write_offset
    + 1 clocks, exact when the instruction's clock is static (serial mode, no jump
    before it); without the offset the scan end is used (an upper bound)."""
    from bitbyte.run.response import responding_scan
    vals = run.column(out_col)
    ends = [r[1] for r in run.rows]
    cycles = run.cycles
    latches = [0] + ends[:-1]
    res, phases = [], []
    local_ok = True
    span = (write_offset - read_offset + 1) if write_offset is not None else None
    for i, t in enumerate(edges):
        level = (i + 1) % 2
        t_clk = t * f                                 # the edge, in clocks (fraction)
        # the scan whose trace first shows the new level, after the edge (the run
        # summary's definition, bitbyte/run/response.py)
        k = responding_scan(t_clk, ends, lambda j, level=level: vals[j] == level)
        if k is None:
            raise RuntimeError(f"{kind}: edge {i} at {float(t)} us never reached "
                               f"{out_col} (run too short?)")
        if write_offset is not None:
            # check the static model against the trace: scan k's PI read is the first
            # read at or after the edge's clock
            n_e = math.ceil(t_clk)
            if read_offset is not None and not (
                    latches[k] + read_offset >= n_e
                    and (k == 0 or latches[k - 1] + read_offset < n_e)):
                raise RuntimeError(f"{kind}: edge {i} (clock {n_e}) shows in scan {k}, "
                                   f"whose PI read is at clock {latches[k] + read_offset}"
                                   ": the static clock model does not hold")
            change = latches[k] + write_offset + 1
        else:
            change = ends[k]
        if change < t_clk:
            raise RuntimeError(f"{kind}: edge {i}: output changed before the edge")
        res.append(change - t_clk)
        prev = cycles[k - 1] if k else 0
        if kind == "image" or span is None:
            local_ok &= change - t_clk < prev + cycles[k]
        else:
            local_ok &= change - t_clk < prev + span
        # phase: position of the edge inside the scan that contains its clock
        n_e = math.ceil(t_clk)
        j = _scan_containing(latches, ends, n_e)
        phases.append((n_e - latches[j]) / cycles[j] if j is not None else 0.0)
    smax, smin = max(cycles), min(cycles)
    if kind == "image":
        bound, note = 2 * smax, ("edge just after a latch: waits for the next scan's "
                                 "latch, then one scan until END: < 2 x max scan")
    else:
        bound = smax + (span if span is not None else smax)
        note = ("edge just after the PI read: the next scan's read, then the PQ write "
                "clock: < max scan + (write - read + 1) clocks")
    return Response(kind, res, phases, bound, write_offset is not None, note, smax, smin,
                    local_ok)


def _scan_containing(latches: list[int], ends: list[int], clk: int) -> int | None:
    lo, hi = 0, len(ends) - 1
    while lo <= hi:
        mid = (lo + hi) // 2
        if clk < latches[mid]:
            hi = mid - 1
        elif clk >= ends[mid]:
            lo = mid + 1
        else:
            return mid
    return None


def quantiles(xs: list[float], qs=(0.0, 0.5, 1.0)) -> list[float]:
    s = sorted(xs)
    out = []
    for q in qs:
        if not s:
            out.append(float("nan"))
            continue
        pos = q * (len(s) - 1)
        lo = int(math.floor(pos))
        hi = min(lo + 1, len(s) - 1)
        out.append(s[lo] + (s[hi] - s[lo]) * (pos - lo))
    return out
