"""Allocating periodic PLC tasks to cores (spec §8, seed 002) — `bitbyte alloc`.

A task (the seed's serialized FBD network) has a period, a WCET, the bytes it reads
before and writes after its execution, and the local memory those take.  A core runs
tasks of one period only (its SCT): one read phase, all executes, one write phase per
scan.  Seed 002 Eq. 2 gives its utilization

    U = (alpha * sum(read_bytes) + sum(wcet_ms) + beta * sum(write_bytes)) / SCT

which must be <= 1 (the seed's condition (1) is printed reversed; it is
T_R + T_E + T_W <= SCT), and sum(mem_bytes) must fit the core's memory bound.

Cores never mix periods, so each period group is a two-dimensional bin-packing
problem of its own (load against SCT, memory against --mem) and the groups only
share the number of cores.  Arithmetic is exact: every load is a Fraction of a ms, and
one instance is scaled to integers (`_Instance`), so `U <= 1` is never a rounding
question.

Algorithms (docs/allocation.md):

* `ffd`: the seed's Algorithms 1 and 2 with the errata fixed: periods in ascending
  order, per period the tasks by WCET, largest first (ties: file order), each onto
  the first core of its period where it fits, a new core when none does.  When a
  task needs a new core and none is left the allocation has *failed* (the seed
  returns the same empty set for "failed" and for "every core used", so it reports a
  failure in the last group as success): the task is listed as unassigned, the
  following (smaller) tasks still try the open cores.
* `best`: per period, the best of ten first-fit / best-fit decreasing packings
  (five sort keys), shortened by a large-neighbourhood search (`_improve`: a few
  cores repacked onto one fewer by `_pack`), then for a period of at most
  EXACT_TASKS tasks a depth-first branch and bound (`_pack`) for k = lower bound,
  lower bound + 1, ... cores, within a node budget: the first k that packs is the
  proved optimum.  The result is never worse than `ffd` (`ffd` is one of the
  candidates, and when the cores run out the variant with fewer unassigned tasks is
  kept).
* `--emit`: a plant file with one generated program per core that burns the core's
  predicted load with bit instructions only (`load_program`).

Everything is deterministic: no clocks, no hashing order, budgets count nodes.
Bad input raises `SourceError` (file:line:col) and nothing else.
"""
from __future__ import annotations

import math
import os
import random
import re
from dataclasses import dataclass, field
from fractions import Fraction

from bitbyte.lang.definition import DEF
from bitbyte.lang.errors import SourceError, read_utf8

ALPHA_MS = Fraction("0.001145")          # seed 002 §V: 1.145 µs per byte read
BETA_MS = Fraction("0.001145")           # ... and written
DEFAULT_MEM = 4096                       # 4 kB of a core's 16 kB hold the I/O data
DEFAULT_BUDGET = 60_000                  # search nodes per period group (`best`)
EXACT_TASKS = 30                         # up to this many tasks a group is solved exactly
LNS_STEP = 2_000                         # nodes per neighbourhood tried by _improve
ALGORITHMS = ("ffd", "best")
GENERATORS = ("becker2015",)

REQUIRED = ("name", "period_ms", "wcet_ms", "read_bytes", "write_bytes")
OPTIONAL = ("mem_bytes", "program")

# seed 002 Table I and §V (becker2015)
BECKER_EXEC_US = (122, 1223)             # execution time 0.122 .. 1.223 ms, 1 µs grid
BECKER_IO_BYTES = (1, 50)                # input and output parameters
BECKER_PERIODS_MS = (10, 20, 100, 200)
BECKER_CORES = 16

# the emitted load program (docs/allocation.md "The emitted plant")
COUNTER_BITS = 20                        # the loop counter: marker bits M0.0 .. M2.3
LOOP_MAX = 2 ** COUNTER_BITS             # iterations of one counted loop
LOOP_ITER = 1000                         # clocks of one iteration (a taken JCN:
JUMP_EXTRA = DEF.jump_taken_clocks - DEF.bit_clocks   # ... this more than not taken)
LOOP_NOPS = LOOP_ITER - 6 * COUNTER_BITS - JUMP_EXTRA   # NOPs in it, besides the counting
LOOP_FIXED = COUNTER_BITS + 2 - JUMP_EXTRA   # presetting the counter; the last JCN: 1
PLANT_HEADROOM = 8                       # clocks left per SCT for an empty precycle
                                         # and postcycle (3 + 2 on the plant harness)
PROG_WORDS = DEF.sizes["prog_words"]       # the program memory (Config.prog_words)


class UsageProblem(ValueError):
    """A command-line mistake found here (the CLI prints it as a usage error)."""


# --------------------------------------------------------------------------------------
# Tasks and the platform
# --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Where:
    """Where a task came from, for messages: file, line, the columns of its cells."""
    path: str
    line: int
    cols: dict = field(default_factory=dict, hash=False, compare=False)
    text: str = ""

    def error(self, column: str, message: str) -> SourceError:
        return SourceError(self.path, self.line, self.cols.get(column, 1), message,
                           self.text)


@dataclass(frozen=True)
class Task:
    name: str
    period_ms: Fraction
    wcet_ms: Fraction
    read_bytes: int
    write_bytes: int
    mem_bytes: int
    program: str | None = None
    where: Where | None = field(default=None, compare=False, hash=False)

    def load_ms(self, p: "Platform") -> Fraction:
        """Read + execute + write time per scan (the numerator of Eq. 2)."""
        return p.alpha * self.read_bytes + self.wcet_ms + p.beta * self.write_bytes


@dataclass(frozen=True)
class Platform:
    cores: int
    mem: int = DEFAULT_MEM
    alpha: Fraction = ALPHA_MS
    beta: Fraction = BETA_MS


# --------------------------------------------------------------------------------------
# The task file
# --------------------------------------------------------------------------------------

def _read_text(path: str) -> str:
    """UTF-8 text without control characters (tab allowed); else SourceError."""
    text = read_utf8(path, "a task file is UTF-8 text (CSV)")
    for n, line in enumerate(text.split("\n"), start=1):
        line = line[:-1] if line.endswith("\r") else line
        for c, ch in enumerate(line, start=1):
            if ch < " " and ch != "\t" or ch == "\x7f":
                raise SourceError(path, n, c, f"invalid character 0x{ord(ch):02X}: a task "
                                  "file is text (CSV)", line)
    return text


def _cells(line: str) -> list[tuple[str, int]]:
    """Comma-separated cells, stripped, with the column where each starts (1-based).
    No quoting: names and paths in a task file have no commas."""
    cells, start = [], 0
    for part in line.split(","):
        lead = len(part) - len(part.lstrip())
        cells.append((part.strip(), start + lead + 1))
        start += len(part) + 1
    return cells


_DECIMAL = re.compile(r"\d+(\.\d*)?|\.\d+")


def _decimal(text: str) -> Fraction | None:
    """A plain non-negative decimal (12, 0.5, .25) as an exact Fraction, else None."""
    return Fraction(text) if _DECIMAL.fullmatch(text) else None


def load_tasks(path: str, clock_mhz: Fraction = Fraction(100),
               mode: str = "serial") -> list[Task]:
    """Read TASKS.csv (spec §8).  Every problem is a SourceError at its cell."""
    return parse_tasks(_read_text(path), path, clock_mhz, mode)


def parse_tasks(text: str, path: str = "<tasks>", clock_mhz: Fraction = Fraction(100),
                mode: str = "serial") -> list[Task]:
    """The parser behind load_tasks.  Blank lines and lines starting with `#` are
    skipped (as in a stimulus file); the first other line is the header."""
    base = os.path.dirname(path)
    header: list[str] | None = None
    tasks: list[Task] = []
    first_line: dict[str, int] = {}
    for n, raw in enumerate(text.split("\n"), start=1):
        line = raw[:-1] if raw.endswith("\r") else raw
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        cells = _cells(line)
        if header is None:
            header = _header(path, n, line, cells)
            continue
        where = Where(path, n, {h: c for h, (_, c) in zip(header, cells)}, line)
        if len(cells) > len(header):
            raise SourceError(path, n, cells[len(header)][1],
                              f"more values than columns ({len(header)})", line)
        values = {h: t for h, (t, _) in zip(header, cells)}
        for h in REQUIRED:
            if h not in values:
                raise SourceError(path, n, len(line) + 1,
                                  f"missing value for column '{h}'", line)
        task = _task(where, values, base, clock_mhz, mode)
        if task.name in first_line:
            raise where.error("name", f"duplicate task name '{task.name}' (first on line "
                                      f"{first_line[task.name]})")
        first_line[task.name] = n
        tasks.append(task)
    if header is None:
        raise SourceError(path, 1, 1, "empty task file: expected the header "
                          f"'{','.join(REQUIRED)}[,mem_bytes][,program]'", "")
    return tasks


def _header(path: str, n: int, line: str, cells: list[tuple[str, int]]) -> list[str]:
    names = [t.lower() for t, _ in cells]
    for i, want in enumerate(REQUIRED):
        if i >= len(names) or names[i] != want:
            col = cells[i][1] if i < len(cells) else len(line) + 1
            got = f"'{cells[i][0]}'" if i < len(cells) else "the end of the line"
            raise SourceError(path, n, col, f"bad header: column {i + 1} must be "
                              f"'{want}', not {got} (header: "
                              f"{','.join(REQUIRED)}[,mem_bytes][,program])", line)
    for (text, col), name in zip(cells[len(REQUIRED):], names[len(REQUIRED):]):
        if name not in OPTIONAL:
            raise SourceError(path, n, col, f"bad header: unknown column '{text}' "
                              "(after the five required ones: mem_bytes, program)", line)
        if names.count(name) > 1:
            raise SourceError(path, n, col, f"bad header: column '{text}' twice", line)
    return names


def _task(where: Where, v: dict[str, str], base: str, clock_mhz: Fraction,
          mode: str) -> Task:
    name = v["name"]
    if not name:
        raise where.error("name", "empty task name")

    def number(col: str, what: str) -> Fraction:
        text = v[col]
        if text.startswith("-") and _decimal(text[1:]) is not None:
            raise where.error(col, f"{col} must not be negative: '{text}'")
        value = _decimal(text)
        if value is None:
            raise where.error(col, f"{col}: '{text}' is not {what}")
        return value

    def whole(col: str) -> int:
        value = number(col, "a whole number of bytes")
        if value.denominator != 1:
            raise where.error(col, f"{col}: '{v[col]}' is not a whole number of bytes")
        return int(value)

    if not v["period_ms"]:
        raise where.error("period_ms", "missing period_ms")
    period = number("period_ms", "a period in ms (a positive decimal)")
    if period == 0:
        raise where.error("period_ms", "period_ms must be positive")
    read, write = whole("read_bytes"), whole("write_bytes")
    mem = whole("mem_bytes") if v.get("mem_bytes") else read + write
    # where a task too large for --mem is reported: its memory, or the bytes it defaults to
    where.cols["mem"] = where.cols["mem_bytes" if v.get("mem_bytes") else "read_bytes"]
    program = v.get("program") or None
    if v["wcet_ms"]:
        wcet = number("wcet_ms", "a time in ms (a non-negative decimal)")
    elif program is None:
        raise where.error("wcet_ms", "wcet_ms is empty and there is no program to take "
                                     "the WCET from")
    else:
        wcet = program_wcet_ms(os.path.join(base, program), clock_mhz, mode, where)
        where.cols["wcet"] = where.cols.get("program", 1)   # a U > 1 is the program's
    return Task(name, period, wcet, read, write, mem, program, where)


def program_clocks(path: str, mode: str = "serial", costs: str = "paper") -> int:
    """Clocks of one scan of an IL program along its straight line (no jump taken):
    serial: sum(bit) + sum(word costs) + 1 (docs/isa.md "Serial mode timing");
    parallel: the partitioning compiler's estimate, max(byte part + bit tail, bit
    part) (bitbyte.compiler.estimate).  Raises the program's SourceError; an S7 OB 100
    is one too (a task is a plant's core, and a plant runs every core's scans from
    t = 0: bitbyte.plant.link refuses it the same way)."""
    from bitbyte.lang.config import Config
    from bitbyte.lang.parser import parse_file
    from bitbyte.lang.costs import serial_cost
    program = parse_file(path, Config())
    if program.startup_scans:
        first = program.instrs[program.labels["OB100"]]
        raise SourceError(path, first.line, first.col,
                          "unsupported: OB 100 in a task's program: a task is a plant's "
                          "core, and the plant runs every core's scans from t = 0 (OB 100 "
                          "runs with `bitbyte run` of one program)", first.source)
    if mode == "serial":
        return serial_cost(program, costs) + 1
    from bitbyte.compiler.estimate import estimate
    from bitbyte.compiler.partition import partition
    return estimate(partition(program, Config().channels), costs).clocks


def program_wcet_ms(path: str, clock_mhz: Fraction, mode: str,
                    where: Where | None = None) -> Fraction:
    if not os.path.isfile(path):
        if where is None:
            raise SourceError(path, 0, 0, "cannot read: no such file")
        raise where.error("program", f"program '{path}' not found")
    return Fraction(program_clocks(path, mode)) / (clock_mhz * 1000)


def misfit(t: Task, p: Platform) -> SourceError | None:
    """Why `t` fits no empty core (spec §8: U > 1 on its own, or more memory than a
    core has), as the error at its line; None when it fits one."""
    where = t.where or Where("<tasks>", 0)
    load = t.load_ms(p)
    if load > t.period_ms:
        col = "wcet" if "wcet" in where.cols else "wcet_ms"
        return where.error(col, f"task '{t.name}' fits no core: U = {_f(load)} / "
                           f"{_f(t.period_ms)} ms = {float(load / t.period_ms):.3f} > 1 "
                           f"(read {_f(p.alpha * t.read_bytes)} + execute "
                           f"{_f(t.wcet_ms)} + write {_f(p.beta * t.write_bytes)} ms)")
    if t.mem_bytes > p.mem:
        return where.error("mem", f"task '{t.name}' fits no core: {t.mem_bytes} bytes of "
                                  f"memory > --mem {p.mem}")
    return None


def _f(x: Fraction) -> str:
    """A time in ms for messages: exact if short, else 6 significant digits."""
    return str(x.numerator) if x.denominator == 1 else f"{float(x):.6g}"


# --------------------------------------------------------------------------------------
# The seed's workload (Table I)
# --------------------------------------------------------------------------------------

def generate_becker2015(networks: int, seed: int) -> list[Task]:
    """Seed 002 §V: per network, uniformly and independently, an execution time of
    0.122 .. 1.223 ms (on a 1 µs grid), 1 .. 50 input bytes, 1 .. 50 output bytes and a
    SCT of 10, 20, 100 or 200 ms; memory = input + output bytes.  Python's
    random.Random(seed), whose integer draws are stable across Python versions."""
    rng = random.Random(seed)
    width = len(str(networks))
    tasks = []
    for i in range(networks):
        exec_us = rng.randint(*BECKER_EXEC_US)
        read = rng.randint(*BECKER_IO_BYTES)
        write = rng.randint(*BECKER_IO_BYTES)
        period = BECKER_PERIODS_MS[rng.randrange(len(BECKER_PERIODS_MS))]
        name = f"n{i + 1:0{width}d}"
        tasks.append(Task(name, Fraction(period), Fraction(exec_us, 1000), read, write,
                          read + write, None,
                          Where(f"<becker2015 seed {seed}>", i + 1)))
    return tasks


def tasks_csv(tasks: list[Task]) -> str:
    """The tasks as a task file (spec §8), e.g. to keep a generated workload."""
    rows = ["name,period_ms,wcet_ms,read_bytes,write_bytes,mem_bytes"]
    for t in tasks:
        rows.append(f"{t.name},{_dec(t.period_ms)},{_dec(t.wcet_ms)},{t.read_bytes},"
                    f"{t.write_bytes},{t.mem_bytes}")
    return "\n".join(rows) + "\n"


def _dec(x: Fraction) -> str:
    """Exact decimal text of x when it has one (else 12 digits)."""
    d = x.denominator
    while d % 2 == 0:
        d //= 2
    while d % 5 == 0:
        d //= 5
    if d != 1:
        return f"{float(x):.12g}"
    s = 0
    while (x * 10 ** s).denominator != 1:
        s += 1
    whole = x.numerator * 10 ** s // x.denominator
    if s == 0:
        return str(whole)
    digits = str(whole).rjust(s + 1, "0")
    return digits[:-s] + "." + digits[-s:]


# --------------------------------------------------------------------------------------
# The instance in integers
# --------------------------------------------------------------------------------------

class _Instance:
    """The tasks scaled to integers: load[i] and cap[period] in units of 1/scale ms.

    groups: period -> task indices in file order, periods ascending."""

    def __init__(self, tasks: list[Task], p: Platform):
        self.tasks, self.p = tasks, p
        loads = [t.load_ms(p) for t in tasks]
        scale = 1
        for x in loads + [t.period_ms for t in tasks]:
            scale = math.lcm(scale, x.denominator)
        self.scale = scale
        self.load = [int(x * scale) for x in loads]
        self.mem = [t.mem_bytes for t in tasks]
        self.wcet = [t.wcet_ms for t in tasks]
        self.groups: dict[Fraction, list[int]] = {}
        for i, t in enumerate(tasks):
            self.groups.setdefault(t.period_ms, []).append(i)
        self.groups = dict(sorted(self.groups.items()))

    def cap(self, period: Fraction) -> int:
        return int(period * self.scale)

    def util_bound(self, period: Fraction) -> int:
        """ceil(sum U) of one period group: spec §8's lower bound."""
        return -(-sum(self.load[i] for i in self.groups[period]) // self.cap(period))

    def group_bound(self, period: Fraction) -> int:
        """A lower bound on the group's cores: utilization, memory, and the tasks
        that each take more than half of a core in one dimension (no two share)."""
        idx, cap, mcap = self.groups[period], self.cap(period), self.p.mem
        mem_bound = -(-sum(self.mem[i] for i in idx) // mcap) if mcap else 0
        big = max(sum(2 * self.load[i] > cap for i in idx),
                  sum(2 * self.mem[i] > mcap for i in idx))
        return max(self.util_bound(period), mem_bound, big, 1 if idx else 0)


# --------------------------------------------------------------------------------------
# The allocation
# --------------------------------------------------------------------------------------

@dataclass
class Core:
    index: int
    sct_ms: Fraction
    tasks: list[Task]
    p: Platform

    @property
    def u_read(self) -> Fraction:
        return self.p.alpha * sum(t.read_bytes for t in self.tasks) / self.sct_ms

    @property
    def u_exec(self) -> Fraction:
        return sum((t.wcet_ms for t in self.tasks), Fraction(0)) / self.sct_ms

    @property
    def u_write(self) -> Fraction:
        return self.p.beta * sum(t.write_bytes for t in self.tasks) / self.sct_ms

    @property
    def u(self) -> Fraction:
        return self.u_read + self.u_exec + self.u_write

    @property
    def load_ms(self) -> Fraction:
        return self.u * self.sct_ms

    @property
    def mem_bytes(self) -> int:
        return sum(t.mem_bytes for t in self.tasks)


@dataclass
class GroupResult:
    """One period's packing and what is known about it."""
    period: Fraction
    cores: int                # cores this period uses
    util_bound: int           # ceil(sum U)
    bound: int                # group_bound (utilization, memory, big tasks)
    optimal: bool             # the count is proved minimal (best only)
    tasks: int = 0


@dataclass
class Allocation:
    algorithm: str
    platform: Platform
    tasks: list[Task]
    cores: list[Core]
    unassigned: list[Task]
    lower_bound: int          # spec §8: sum over periods of ceil(sum U)
    groups: list[GroupResult]
    # the tasks no empty core can take, each with its error (unassigned as well)
    misfits: list[tuple[Task, SourceError]] = field(default_factory=list)

    @property
    def cores_used(self) -> int:
        return len(self.cores)

    @property
    def ok(self) -> bool:
        return not self.unassigned and self.cores_used <= self.platform.cores

    def reason(self) -> str:
        """Why the allocation failed for want of cores ('' when no task is left
        out for that; the misfits have their own errors)."""
        unfit = {t.name for t, _ in self.misfits}
        short = [t for t in self.unassigned if t.name not in unfit]
        if not short and self.cores_used <= self.platform.cores:
            return ""
        need = sum(g.bound for g in self.groups)
        periods = sorted({t.period_ms for t in short})
        return (f"the tasks do not fit on {_n(self.platform.cores, 'core')}: "
                f"{len(short)} of {len(self.tasks)} unassigned (periods "
                f"{', '.join(_f(x) + ' ms' for x in periods)}); at least {need} cores are "
                "needed (per period: ceil(sum U), ceil(sum mem / --mem), tasks over half "
                "a core)")


def allocate(tasks: list[Task], p: Platform, algorithm: str = "best",
             budget: int = DEFAULT_BUDGET) -> Allocation:
    """Allocate `tasks` to at most p.cores cores.  Never raises for an allocation that
    does not fit: the result lists the unassigned tasks.  A task that fits no empty
    core (`misfit`) is unassigned with its error in `misfits` and the others are
    allocated without it (spec §8: the allocation of the rest is still wanted)."""
    if algorithm not in ALGORITHMS:
        raise UsageProblem(f"--algorithm: unknown {algorithm!r} (known: ffd, best)")
    errors = [misfit(t, p) for t in tasks]
    keep = [k for k, e in enumerate(errors) if e is None]    # file index of each fitting
    fitting = [tasks[k] for k in keep]
    inst = _Instance(fitting, p)
    bins, unassigned = _ffd(inst)
    groups = {per: GroupResult(per, 0, inst.util_bound(per), inst.group_bound(per), False,
                               len(idx)) for per, idx in inst.groups.items()}
    if algorithm == "best":
        bins, unassigned = _best(inst, bins, unassigned, groups, budget)
    for per, _ in bins:
        groups[per].cores += 1
    for g in groups.values():
        if g.cores == g.bound and not any(fitting[i].period_ms == g.period
                                          for i in unassigned):
            g.optimal = True
    cores = [Core(k, per, [fitting[i] for i in sorted(members)], p)
             for k, (per, members) in enumerate(bins)]
    left = sorted([keep[i] for i in unassigned]
                  + [k for k, e in enumerate(errors) if e is not None])
    # spec §8's lower bound is over the file's tasks, the misfits included
    every = _Instance(tasks, p)
    return Allocation(algorithm, p, tasks, cores, [tasks[k] for k in left],
                      sum(every.util_bound(per) for per in every.groups),
                      list(groups.values()),
                      [(t, e) for t, e in zip(tasks, errors) if e is not None])


# --- the seed's first-fit decreasing (Alg. 1 and 2, errata fixed) ----------------------

def _ffd(inst: _Instance) -> tuple[list[tuple[Fraction, list[int]]], list[int]]:
    """Alg. 2: periods ascending; Alg. 1: by WCET, largest first, first fit, a new core
    when none fits.  A task that needs a core when all are taken is unassigned (the
    fixed erratum: failure is not "all cores used"); later tasks still try."""
    free = inst.p.cores
    out: list[tuple[Fraction, list[int]]] = []
    unassigned: list[int] = []
    for per, idx in inst.groups.items():
        order = sorted(idx, key=lambda i: (-inst.wcet[i], i))
        bins, unplaced = _first_fit(inst, order, inst.cap(per), free)
        free -= len(bins)
        out += [(per, b) for b in bins]
        unassigned += unplaced
    return out, unassigned


def _first_fit(inst: _Instance, order: list[int], cap: int,
               limit: int | None) -> tuple[list[list[int]], list[int]]:
    loads: list[int] = []
    mems: list[int] = []
    bins: list[list[int]] = []
    unplaced = []
    mcap = inst.p.mem
    for i in order:
        li, mi = inst.load[i], inst.mem[i]
        for b in range(len(bins)):
            if loads[b] + li <= cap and mems[b] + mi <= mcap:
                loads[b] += li
                mems[b] += mi
                bins[b].append(i)
                break
        else:
            if limit is None or len(bins) < limit:
                loads.append(li)
                mems.append(mi)
                bins.append([i])
            else:
                unplaced.append(i)
    return bins, unplaced


def _best_fit(inst: _Instance, order: list[int], cap: int) -> list[list[int]]:
    """Onto the open core with the least slack left (load and memory normalised)."""
    mcap = inst.p.mem
    loads: list[int] = []
    mems: list[int] = []
    bins: list[list[int]] = []
    for i in order:
        li, mi = inst.load[i], inst.mem[i]
        best, best_slack = -1, None
        for b in range(len(bins)):
            if loads[b] + li <= cap and mems[b] + mi <= mcap:
                slack = (cap - loads[b] - li) * mcap + (mcap - mems[b] - mi) * cap
                if best_slack is None or slack < best_slack:
                    best, best_slack = b, slack
        if best < 0:
            loads.append(li)
            mems.append(mi)
            bins.append([i])
        else:
            loads[best] += li
            mems[best] += mi
            bins[best].append(i)
    return bins


# --- best: heuristics, then branch and bound --------------------------------------------

def _orders(inst: _Instance, idx: list[int], cap: int) -> list[list[int]]:
    """Five decreasing orders: WCET (the seed's), load, memory, and the sum and the
    max of the two normalised sizes (integers: load * mem_cap vs mem * cap)."""
    m = inst.p.mem or 1
    keys = [lambda i: inst.wcet[i], lambda i: inst.load[i], lambda i: inst.mem[i],
            lambda i: inst.load[i] * m + inst.mem[i] * cap,
            lambda i: max(inst.load[i] * m, inst.mem[i] * cap)]
    return [sorted(idx, key=lambda i, k=k: (-k(i), i)) for k in keys]


def best_group(inst: _Instance, per: Fraction, budget: int = DEFAULT_BUDGET,
               exact: bool = True) -> tuple[list[list[int]], bool]:
    """The fewest cores found for one period group, and whether that is proved optimal.

    Ten greedy packings give a first packing, `_improve` (a large-neighbourhood
    search) shortens it, and for a group of at most EXACT_TASKS tasks `_pack` tries
    k = lower bound, lower bound + 1, ... below that: the first k that packs is
    optimal when every smaller k was proved infeasible within the node budget.
    exact=False skips that last step (the heuristics alone, for the benchmark)."""
    idx, cap = inst.groups[per], inst.cap(per)
    lb = inst.group_bound(per)
    best: list[list[int]] | None = None
    for order in _orders(inst, idx, cap):
        for packing in (_first_fit(inst, order, cap, None)[0], _best_fit(inst, order, cap)):
            if best is None or len(packing) < len(best):
                best = packing
    if len(best) > lb:
        best = _improve(inst, best, cap, lb, budget)
    if len(best) == lb:
        return best, True
    if len(idx) > EXACT_TASKS or not exact:
        return best, False
    left, k = budget, lb
    while k < len(best) and left > 0:
        found, nodes, complete = _pack(inst, idx, cap, k, left)
        left -= nodes
        if found is not None:
            return found, True              # every smaller k was proved infeasible
        if not complete:
            return best, False              # budget gone: k stays open
        k += 1
    return best, True                       # every k below len(best) is infeasible


def _improve(inst: _Instance, bins: list[list[int]], cap: int, lb: int,
             budget: int) -> list[list[int]]:
    """Large-neighbourhood search: take one of the six emptiest cores and s - 1 others
    (s = 2..5, in order of fill), and let `_pack` put their tasks on s - 1 cores
    (at most LNS_STEP nodes each).  Every success saves a core; start again until a
    whole round saves nothing, the lower bound is reached or the budget is used."""
    mcap = inst.p.mem

    def fill(b: list[int]) -> int:
        return sum(inst.load[i] * mcap + inst.mem[i] * cap for i in b)

    bins = [sorted(b) for b in bins]
    left = budget
    while left > 0 and len(bins) > lb:
        bins.sort(key=lambda b: (fill(b), b))
        saved = None
        for e in range(min(6, len(bins))):
            others = bins[:e] + bins[e + 1:]
            for s in range(2, 6):
                for j in range(len(others) - s + 2):
                    group = [bins[e]] + others[j:j + s - 1]
                    items = [i for b in group for i in b]
                    found, nodes, _ = _pack(inst, items, cap, s - 1, min(LNS_STEP, left))
                    left -= nodes
                    if found is not None:
                        saved = (group, found)
                    if saved or left <= 0:
                        break
                if saved or left <= 0:
                    break
            if saved or left <= 0:
                break
        if saved is None:
            break
        group, found = saved
        bins = [b for b in bins if not any(b is g for g in group)] + \
            [sorted(b) for b in found]
    return bins


class _Budget(Exception):
    pass


def _pack(inst: _Instance, idx: list[int], cap: int, k: int, budget: int
          ) -> tuple[list[list[int]] | None, int, bool]:
    """Depth-first search for a packing of `idx` into k cores.

    Tasks go in decreasing max-normalised size; each onto an open core where it fits,
    tightest first (cores with equal load and memory tried once), or onto one new core
    (empty cores are interchangeable).  Pruned when the tasks left exceed the room
    left on cores that can still take the smallest of them.  Returns (bins or None,
    nodes used, search complete: None then proves k infeasible)."""
    mcap = inst.p.mem
    order = _orders(inst, idx, cap)[4]
    n = len(order)
    L = [inst.load[i] for i in order]
    M = [inst.mem[i] for i in order]
    suf_l, suf_m = [0] * (n + 1), [0] * (n + 1)
    min_l, min_m = [0] * (n + 1), [0] * (n + 1)
    min_l[n] = min_m[n] = 0
    for j in range(n - 1, -1, -1):
        suf_l[j], suf_m[j] = suf_l[j + 1] + L[j], suf_m[j + 1] + M[j]
        min_l[j] = L[j] if j == n - 1 else min(L[j], min_l[j + 1])
        min_m[j] = M[j] if j == n - 1 else min(M[j], min_m[j + 1])
    loads, mems, where = [0] * k, [0] * k, [0] * n
    nodes = 0

    def dfs(j: int, used: int) -> bool:
        nonlocal nodes
        if j == n:
            return True
        nodes += 1
        if nodes > budget:
            raise _Budget
        ml, mm = min_l[j], min_m[j]
        room_l = room_m = (k - used)
        room_l *= cap
        room_m *= mcap
        for b in range(used):
            fl, fm = cap - loads[b], mcap - mems[b]
            if fl >= ml and fm >= mm:
                room_l += fl
                room_m += fm
        if suf_l[j] > room_l or suf_m[j] > room_m:
            return False
        lj, mj = L[j], M[j]
        cands = [((cap - loads[b] - lj) * mcap + (mcap - mems[b] - mj) * cap, b)
                 for b in range(used) if loads[b] + lj <= cap and mems[b] + mj <= mcap]
        cands.sort()
        seen = set()
        for _, b in cands:
            state = (loads[b], mems[b])
            if state in seen:
                continue
            seen.add(state)
            loads[b] += lj
            mems[b] += mj
            where[j] = b
            if dfs(j + 1, used):
                return True
            loads[b] -= lj
            mems[b] -= mj
        if used < k:
            loads[used], mems[used], where[j] = lj, mj, used
            if dfs(j + 1, used + 1):
                return True
            loads[used] = mems[used] = 0
        return False

    try:
        ok = dfs(0, 0)
    except _Budget:
        return None, budget, False
    if not ok:
        return None, nodes, True
    bins: list[list[int]] = [[] for _ in range(max(where) + 1 if n else 0)]
    for j, b in enumerate(where):
        bins[b].append(order[j])
    return bins, nodes, True


def _best(inst: _Instance, ffd_bins, ffd_unassigned, groups: dict, budget: int):
    """Per period the best packing found; when they need more cores than there are,
    the periods take cores in ascending order (as Alg. 2) and keep their fullest cores;
    the variant (this or ffd's) with fewer unassigned tasks, then fewer cores, wins."""
    packs: dict[Fraction, list[list[int]]] = {}
    for per in inst.groups:
        bins, proved = best_group(inst, per, budget)
        packs[per] = [sorted(b) for b in bins]
        groups[per].optimal = proved
    bins: list[tuple[Fraction, list[int]]] = []
    unassigned: list[int] = []
    free = inst.p.cores
    for per, pack in packs.items():
        pack = sorted(pack, key=lambda b: (-sum(inst.load[i] for i in b), b[0]))
        if len(pack) > free:
            # keep the cores with the most tasks, first-fit the rest onto them
            pack.sort(key=lambda b: (-len(b), b[0]))
            kept, rest = pack[:free], [i for b in pack[free:] for i in b]
            rest.sort(key=lambda i: (-inst.wcet[i], i))
            kept, unplaced = _refill(inst, kept, rest, inst.cap(per))
            pack = kept
            unassigned += unplaced
            groups[per].optimal = False
        free -= len(pack)
        bins += [(per, b) for b in pack]
    mine = (len(unassigned), len(bins))
    theirs = (len(ffd_unassigned), len(ffd_bins))
    if theirs < mine:
        for g in groups.values():
            g.optimal = False
        return ffd_bins, ffd_unassigned
    return bins, unassigned


def _refill(inst: _Instance, bins: list[list[int]], rest: list[int], cap: int):
    mcap = inst.p.mem
    loads = [sum(inst.load[i] for i in b) for b in bins]
    mems = [sum(inst.mem[i] for i in b) for b in bins]
    bins = [list(b) for b in bins]
    unplaced = []
    for i in rest:
        for b in range(len(bins)):
            if loads[b] + inst.load[i] <= cap and mems[b] + inst.mem[i] <= mcap:
                loads[b] += inst.load[i]
                mems[b] += inst.mem[i]
                bins[b].append(i)
                break
        else:
            unplaced.append(i)
    return bins, unplaced


# --------------------------------------------------------------------------------------
# Output: JSON, the table, the plant
# --------------------------------------------------------------------------------------

def _num(x: Fraction) -> int | float:
    return int(x) if x.denominator == 1 else float(x)


def to_json(a: Allocation) -> dict:
    """Spec §8's schema, nothing more."""
    return {"cores_used": a.cores_used, "lower_bound": a.lower_bound,
            "unassigned": [t.name for t in a.unassigned],
            "cores": [{"core": c.index, "sct_ms": _num(c.sct_ms),
                       "tasks": [t.name for t in c.tasks], "u": float(c.u),
                       "u_read": float(c.u_read), "u_exec": float(c.u_exec),
                       "u_write": float(c.u_write), "mem_bytes": c.mem_bytes}
                      for c in a.cores]}


def format_table(a: Allocation) -> str:
    """One row per core (SCT, tasks, U split into read / execute / write, memory),
    the task names under it, then the summary per period."""
    p = a.platform
    out = [f"{'core':>4}  {'sct_ms':>7}  {'tasks':>5}  {'u':>6}  {'read':>6}  "
           f"{'exec':>6}  {'write':>6}  {'mem_bytes':>11}"]
    for c in a.cores:
        out.append(f"{c.index:>4}  {_f(c.sct_ms):>7}  {len(c.tasks):>5}  {float(c.u):6.3f}  "
                   f"{float(c.u_read):6.3f}  {float(c.u_exec):6.3f}  {float(c.u_write):6.3f}"
                   f"  {c.mem_bytes:>5} / {p.mem:<4}")
        out += _wrap("      ", [t.name for t in c.tasks])
    out.append("")
    # the cores used place only the tasks that fit: their own bound is the one to
    # hold them against (the groups are theirs)
    misfits = (f", the {_n(len(a.misfits), 'task')} that fit no core included; "
               f"{sum(g.util_bound for g in a.groups)} without them") if a.misfits else ""
    out.append(f"algorithm {a.algorithm}: {a.cores_used} of {p.cores} cores used, lower "
               f"bound {a.lower_bound} (sum per period of ceil(sum U){misfits})")
    for g in a.groups:
        note = "optimal" if g.optimal else f"bound {g.bound}"
        out.append(f"  {_f(g.period):>6} ms: {_n(g.tasks, 'task'):>10} on "
                   f"{_n(g.cores, 'core'):>9} "
                   f"(ceil(sum U) = {g.util_bound}, with memory and big tasks {g.bound}; "
                   f"{note})")
    if a.unassigned:
        out.append(f"unassigned ({len(a.unassigned)}):")
        out += _wrap("  ", [t.name for t in a.unassigned])
    return "\n".join(out) + "\n"


def _n(count: int, noun: str) -> str:
    return f"{count} {noun}{'' if count == 1 else 's'}"


def _wrap(indent: str, names: list[str], width: int = 88) -> list[str]:
    lines, cur = [], indent
    for name in names:
        if len(cur) + len(name) + 1 > width and cur.strip():
            lines.append(cur.rstrip())
            cur = indent
        cur += name + " "
    if cur.strip():
        lines.append(cur.rstrip())
    return lines


def load_program(clocks: int, header: list[str] = ()) -> str:
    """IL text whose every scan takes exactly `clocks` clocks, with bit instructions
    only: a counted loop of LOOP_ITER clocks an iteration, NOPs for the rest.  Bit
    instructions take one clock in every mode and with every byte-processor cost
    table, so the load does not depend on them (docs/allocation.md).

    The counter is a COUNTER_BITS-bit binary number in markers (bit i at M i/8 . i%8),
    preset to 2^b - n and incremented once an iteration; the carry out of its top bit
    (all ones before the increment) ends the loop after exactly n iterations:

        SET; = the counter bits that are 1;  CLR; = the bits that are 0
        loop: LOOP_NOPS x NOP (878 with a 3-clock taken jump)
              carries from the old bits: c1 = m0, c(i+1) = c(i) AND m(i)  (markers M8..)
              new bits: m0 = NOT m0, m(i) = m(i) XOR c(i)
              LD c(b); JCN loop

    n iterations take (b + 2) + 1000 n - JUMP_EXTRA clocks (the last JCN is not taken)."""
    if clocks < 1:
        raise ValueError("a scan takes at least 1 clock (END)")
    b = COUNTER_BITS

    def m(i: int) -> str:                    # counter bit i
        return f"M{i // 8}.{i % 8}"

    def c(i: int) -> str:                    # carry into bit i (1..b), from M8.1 on
        return f"M{(64 + i) // 8}.{(64 + i) % 8}"

    body: list[str] = []
    rem = clocks - 1
    loops = 0
    while rem >= LOOP_ITER + LOOP_FIXED:
        n = min(LOOP_MAX, (rem - LOOP_FIXED) // LOOP_ITER)
        start = 2 ** b - n
        body += ["      SET"] + [f"      =     {m(i)}" for i in range(b) if start >> i & 1]
        body += ["      CLR"] + [f"      =     {m(i)}" for i in range(b)
                                 if not start >> i & 1]
        body += [f"loop{loops}:"] + ["      NOP"] * LOOP_NOPS
        body += [f"      LD    {m(0)}", f"      =     {c(1)}"]
        for i in range(1, b):
            body += [f"      LD    {c(i)}", f"      A     {m(i)}", f"      =     {c(i + 1)}"]
        body += [f"      LDN   {m(0)}", f"      =     {m(0)}"]
        for i in range(1, b):
            body += [f"      LD    {m(i)}", f"      X     {c(i)}", f"      =     {m(i)}"]
        body += [f"      LD    {c(b)}", f"      JCN   loop{loops}"]
        rem -= LOOP_ITER * n + LOOP_FIXED
        loops += 1
    body += ["      NOP"] * rem                  # the rest (< LOOP_ITER + LOOP_FIXED)
    body.append("      END")
    if len(body) > PROG_WORDS:
        raise UsageProblem(f"a load of {clocks} clocks per scan needs {len(body)} "
                           f"instructions (> {PROG_WORDS}): lower --clock-mhz")
    return "\n".join([f"// {h}" for h in header] + body) + "\n"


def emit_plant(a: Allocation, path: str, clock_mhz: Fraction) -> list[str]:
    """Write PLANT.toml (docs/multicore.md) with one [[core]] per used core,
    period_us = SCT, and beside it one generated program per core whose scan takes
    floor(load * f) clocks (load = the core's read + execute + write time: the plant
    has no shared variables, so its precycle and postcycle are empty and the program
    stands for all three phases), at most SCT * f - PLANT_HEADROOM clocks so that
    the empty copies still fit.  Returns the files written."""
    if (clock_mhz * 1000).denominator != 1 or not 0 < clock_mhz <= 10_000:
        raise UsageProblem("--emit: the plant's clock_mhz must be a whole number of kHz "
                           "up to 10000")
    folder = os.path.dirname(path) or "."
    stem = os.path.splitext(os.path.basename(path))[0]
    os.makedirs(folder, exist_ok=True)
    head = ["# Generated by `bitbyte alloc` (docs/allocation.md): one core per used core of",
            f"# the allocation ({a.algorithm}); each program burns its core's predicted "
            "read + execute +",
            "# write time per scan (no shared variables: the copies are part of the load).",
            f"clock_mhz = {_dec(clock_mhz)}", 'layout = "compact"', 'protection = "semaphore"']
    written = []
    for c in a.cores:
        period_us = c.sct_ms * 1000
        if period_us.denominator != 1:
            raise UsageProblem(f"--emit: SCT {_f(c.sct_ms)} ms is not a whole number of µs")
        # the load, but leave the plant's empty precycle and postcycle room in the SCT
        clocks = max(1, min(math.floor(c.load_ms * clock_mhz * 1000),
                            math.floor(c.sct_ms * clock_mhz * 1000) - PLANT_HEADROOM))
        name = f"core{c.index}"
        prog = f"{stem}_{name}.il"
        text = load_program(clocks, [
            f"generated by bitbyte alloc: core {c.index}, SCT {_f(c.sct_ms)} ms, "
            f"{len(c.tasks)} tasks: {' '.join(t.name for t in c.tasks)}",
            f"predicted U = {float(c.u):.6f} (read {float(c.u_read):.6f}, execute "
            f"{float(c.u_exec):.6f}, write {float(c.u_write):.6f}); load "
            f"{_f(c.load_ms)} ms",
            f"every scan takes {clocks} clocks at {_dec(clock_mhz)} MHz (bit instructions "
            "only: the same in every mode and with every cost table)"])
        with open(os.path.join(folder, prog), "w") as f:
            f.write(text)
        written.append(os.path.join(folder, prog))
        head += ["", "[[core]]", f'name = "{name}"', f'program = "{prog}"',
                 f"period_us = {int(period_us)}"
                 f"    # U = {float(c.u):.4f}, {clocks} clocks per scan"]
    with open(path, "w") as f:
        f.write("\n".join(head) + "\n")
    return [path] + written
