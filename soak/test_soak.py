"""The soak (`make soak N=10000`, issue 15): N random programs on the Verilator harness
against the reference interpreter, in serial mode and in parallel mode with both
exchanges (the handshake flip-flops, the strict queues), and in free-running mode
against a model of the exchange.  Not part of `make test`
(pyproject's testpaths do not include soak/); `make test`'s random tests are the same
comparisons on a few hundred programs.

What is compared:

* serial: every column of the trace, `t_us` and `cycles` included, against the
  reference interpreter (bitbyte.ref.refsim), with the family's own stimulus (inputs
  changing at any clock, `t_us` rows);
* parallel, handshake and queue: every traced value per scan against the reference
  interpreter in serial mode (spec §2: the modes differ in `t_us` and `cycles` only),
  with scan-keyed inputs, watching every word, timer, counter and marker the
  generators write (PARALLEL_WATCH).  Timers stay in with presets that do not depend
  on either mode's timing (randprog.long_timers: 9000 s, which does not run out
  within a run, or 0 ms, which runs out at once); `L T n` (the time value, which does
  depend on it) reads a timer that the program never starts (value 0 in every mode).
  Counters stay as they are (by scan).

* free-running, free-running queues and marker area: the program of the parallel
  comparison for FREE_SCANS bit scans with `--exchange-log`; every read and the
  queues' loss counts against a model of the queues, every read of the marker area
  within its snapshot bound (tests/exchange_model.py, free_check).

The first BITBYTE_SOAK_COCOTB programs (40) also run through cocotb on Icarus and on
Verilator (test_soak_cocotb_sample), serial and parallel (handshake and queue in turn).

Program i of a run has the seed BITBYTE_SEED * 100000 + i and comes from one of the
generators of tests/randprog.py by i % 4: bit-only, mixed (word instructions, timers,
counters, arithmetic, compares), the parallel generator (rungs that cross sides),
mixed again.  Programs are checked in chunks of CHUNK, one pytest item each, so
pytest-xdist spreads them over the cores.  A mismatch is saved under
build/soak/cases/<name>/ (program, stimulus, both traces, the command that repeats it)
and the chunk goes on with its other programs before it fails.  Each chunk writes
what its programs executed on the hardware in each mode (the harness's line counts,
soak/coverage_count.py) to build/soak/; soak/soak_report.py adds them up into
docs/soak.md.
"""
from __future__ import annotations

import contextlib
import io
import json
import os
import random
import shlex
import time
from pathlib import Path

import pytest

from bitbyte import cli
from bitbyte.lang.stimulus import load_stimulus
from bitbyte.lang.trace import read_trace_rows, trace_text
from bitbyte.ref.refsim import refsim_trace
from bitbyte.run.prepare import prepare
from bitbyte.sim.cocotb_runner import records_from_rows, run_jobs
from coverage_count import Coverage, read_line_counts
from exchange_model import check_marker, check_queues, losses_of, read_log
from randprog import (FULL_WATCH, long_timers, random_mixed_program, random_mixed_stimulus,
                      random_mixed_watch, random_parallel_program, random_program,
                      random_scan_stimulus, random_stimulus, random_watch)

ROOT = Path(__file__).resolve().parents[1]
OUT = Path(os.environ.get("BITBYTE_SOAK_OUT", ROOT / "build" / "soak"))
N = int(os.environ.get("BITBYTE_SOAK_N", "100"))
SEED = int(os.environ["BITBYTE_SEED"])
CHUNK = 25
SCANS = 12
PAR_SCANS = 10
PAR_WATCHDOG = 50_000
EXCHANGES = ("handshake", "queue")
# Parallel mode is compared on everything the generators write (randprog.FULL_WATCH).
PARALLEL_WATCH = FULL_WATCH


class Family:
    """One generator: program, its serial stimulus, watch list, clock and watchdog."""

    def __init__(self, name, program, stimulus, watch, clock_mhz, watchdog):
        self.name, self.program, self.stimulus, self.watch = name, program, stimulus, watch
        self.clock_mhz, self.watchdog = clock_mhz, watchdog


BIT = Family("bit", random_program, lambda s: random_stimulus(s, SCANS), random_watch,
             "100", 600)
# 0.1 MHz: 100 clocks per ms, the timers' 0..25 ms presets run out within a run
MIXED = Family("mixed", random_mixed_program,
               lambda s: random_mixed_stimulus(s, SCANS, 3000), random_mixed_watch,
               "0.1", 20_000)
PARALLEL = Family("par", random_parallel_program,
                  lambda s: random_mixed_stimulus(s, SCANS, 3000), random_mixed_watch,
                  "0.1", 20_000)
FAMILIES = (BIT, MIXED, PARALLEL, MIXED)

def outputs(records):
    return [(r.scan, tuple(sorted(r.values.items()))) for r in records]


class Mismatch(Exception):
    pass


def save_case(name: str, files: dict[str, str], argv: list[str]) -> Path:
    where = OUT / "cases" / name
    where.mkdir(parents=True, exist_ok=True)
    for fname, text in files.items():
        (where / fname).write_text(text)
    (where / "repeat.sh").write_text("bitbyte " + shlex.join(argv) + "\n")
    return where


def run_hw(argv: list[str]) -> int:
    rc = cli.main(argv)
    if rc not in (0, cli.EXIT_WATCHDOG):
        raise Mismatch(f"bitbyte {shlex.join(argv)} exited {rc}")
    return rc


class Case:
    """One program of the run in one mode: its files, the expected result (from the
    reference interpreter) and what runs it on the hardware, which counts its coverage
    (cov, from the harness's line counts).  ref_cov, if given, counts what the
    reference interpreter executed, for the check that the two agree."""

    def __init__(self, tmp: Path, index: int, family: Family, cov: Coverage,
                 parallel: bool, ref_cov: Coverage | None = None):
        seed = SEED * 100000 + index
        self.parallel = parallel
        self.name = f"{family.name}{seed}" + ("p" if parallel else "")
        self.il, self.stim = tmp / f"{self.name}.il", tmp / f"{self.name}.csv"
        if parallel:          # scan-keyed inputs, presets independent of the timing
            self.il.write_text(long_timers(family.program(seed), random.Random(seed)))
            self.stim.write_text(random_scan_stimulus(seed, PAR_SCANS))
            self.watch = ",".join(PARALLEL_WATCH)
            self.scans, self.watchdog, clock = PAR_SCANS, PAR_WATCHDOG, None
        else:
            self.il.write_text(family.program(seed))
            self.stim.write_text(family.stimulus(seed))
            self.watch = ",".join(family.watch(seed))
            self.scans, self.watchdog, clock = SCANS, family.watchdog, family.clock_mhz
        self.clock = clock
        kw = dict(stimulus=str(self.stim), watch=self.watch, scans=self.scans,
                  watchdog=self.watchdog)
        if clock:
            kw["clock_mhz"] = clock
        serial = prepare(str(self.il), **kw)
        self.program, self.columns, self.f = serial.program, serial.columns, serial.f
        self.cov = cov
        self.preps = {ex: prepare(str(self.il), mode="parallel", exchange=ex, **kw)
                      for ex in EXCHANGES} if parallel else {"-": serial}
        self.jobs = {ex: p.job for ex, p in self.preps.items()}
        stimulus = load_stimulus(str(self.stim), self.program.symbols)
        config = cli.Config()
        if clock:
            stimulus.clock_mhz = self.f
            config = cli.Config(clock_mhz=float(self.f))
        modes = [("parallel", ex) for ex in EXCHANGES] if parallel else [("serial", "-")]
        with (ref_cov or Coverage()).counting(*modes):
            _, records, fault = refsim_trace(
                self.program, config=config, stimulus=stimulus,
                watch=self.watch.split(",") if self.watch else [], scans=self.scans,
                watchdog=self.watchdog)
        self.expected = self.view(records, fault)

    def view(self, records, fault: bool) -> str:
        """What must agree: the whole trace serially; parallel mode every traced value
        per scan (spec §2: t_us and cycles differ between the modes)."""
        if self.parallel:
            return "\n".join(map(str, outputs(records))) + f"\nfault={fault}\n"
        return trace_text(self.columns, records, self.f) + f"fault={fault}\n"

    def argv(self, exchange: str, trace: Path) -> list[str]:
        argv = ["run", str(self.il), "--sim", "verilator", "--stimulus", str(self.stim),
                "--scans", str(self.scans), "--watchdog", str(self.watchdog),
                "--trace", str(trace), "--line-counts", str(trace) + ".lines.csv"]
        if self.parallel:
            argv += ["--mode", "parallel", "--exchange", exchange]
        if self.clock:
            argv += ["--clock-mhz", self.clock]
        return argv + (["--watch", self.watch] if self.watch else [])

    def compare(self, got: str, how: str, argv: list[str]) -> str | None:
        if got == self.expected:
            return None
        where = save_case(f"{self.name}-{how}", {
            "program.il": self.il.read_text(), "stimulus.csv": self.stim.read_text(),
            "expected.txt": self.expected, "got.txt": got}, argv)
        return f"{self.name}: {how} differs from the reference ({where})"

    def on_harness(self, tmp: Path) -> list[str]:
        problems = []
        for exchange in self.jobs:
            trace = tmp / f"{self.name}.{exchange}.trace.csv"
            argv = self.argv(exchange, trace)
            rc = run_hw(argv)
            got = self.view(read_trace_rows(trace, self.columns), rc == cli.EXIT_WATCHDOG)
            how = f"parallel-{exchange}" if self.parallel else "serial"
            count_hardware(self.cov, self.preps[exchange], Path(str(trace) + ".lines.csv"),
                           "parallel" if self.parallel else "serial", exchange)
            problem = self.compare(got, how, argv)
            problems += [problem] if problem else []
        return problems


def count_hardware(cov: Coverage, prep, lines: Path, mode: str, exchange: str) -> None:
    """Add one hardware run's line counts (bitbyte run --line-counts) to cov."""
    got = read_line_counts(lines)
    parts = [(prep.listing, got.get("program" if mode == "serial" else "bit", {}))]
    if mode != "serial":
        parts.append((prep.byte_listing, got.get("byte", {})))
    cov.add_hardware(mode, exchange, prep.program, parts)


FREE_SCANS = 40


def free_check(tmp: Path, index: int, family: Family, cov: Coverage) -> list[str]:
    """Free-running mode (docs/exchange.md): the program of the parallel comparison for
    FREE_SCANS bit scans with every crossing logged. With the free-running queues each
    read must give the value a model of the queues gives and the run's loss counts
    must be the model's; with the marker area each read must keep the snapshot bound
    (tests/exchange_model.py)."""
    seed = SEED * 100000 + index
    name = f"{family.name}{seed}f"
    il, stim = tmp / f"{name}.il", tmp / f"{name}.csv"
    il.write_text(long_timers(family.program(seed), random.Random(seed)))
    stim.write_text(random_scan_stimulus(seed, FREE_SCANS))
    problems = []
    for exchange in ("queue-free", "marker"):
        log = tmp / f"{name}.{exchange}.xlog.csv"
        lines = tmp / f"{name}.{exchange}.lines.csv"
        argv = ["run", str(il), "--sim", "verilator", "--stimulus", str(stim), "--scans",
                str(FREE_SCANS), "--watchdog", str(PAR_WATCHDOG), "--mode", "free",
                "--exchange", exchange, "--exchange-log", str(log), "--line-counts",
                str(lines)]
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            run_hw(argv)
        count_hardware(cov, prepare(str(il), stimulus=str(stim), scans=FREE_SCANS,
                                    watchdog=PAR_WATCHDOG, mode="free", exchange=exchange),
                       lines, "free", exchange)
        crossings, snaps = read_log(log)
        if exchange == "marker":
            problem = check_marker(crossings, snaps)
        else:
            losses = losses_of(out.getvalue())
            if losses is None:
                raise Mismatch(f"{name}: no queue losses in the summary of bitbyte "
                               f"{shlex.join(argv)}")
            problem = check_queues(crossings, losses)
        if problem is not None:
            where = save_case(f"{name}-free-{exchange}", {
                "program.il": il.read_text(), "stimulus.csv": stim.read_text(),
                "exchange-log.csv": log.read_text(), "model.txt": problem + "\n"}, argv)
            problems.append(f"{name}: free-running, {exchange}: {problem} ({where})")
    return problems


def serial_check(tmp: Path, index: int, family: Family, cov: Coverage) -> str | None:
    problems = Case(tmp, index, family, cov, parallel=False).on_harness(tmp)
    return problems[0] if problems else None


def parallel_check(tmp: Path, index: int, family: Family, cov: Coverage) -> list[str]:
    return Case(tmp, index, family, cov, parallel=True).on_harness(tmp)


CHUNKS = range((N + CHUNK - 1) // CHUNK)


@pytest.mark.parametrize("chunk", CHUNKS)
def test_soak_chunk(chunk, tmp_path):
    cov = Coverage()
    problems: list[str] = []
    t0 = time.monotonic()
    indexes = range(chunk * CHUNK, min(N, (chunk + 1) * CHUNK))
    for index in indexes:
        family = FAMILIES[index % len(FAMILIES)]
        try:
            problem = serial_check(tmp_path, index, family, cov)
            if problem:
                problems.append(problem)
            problems += parallel_check(tmp_path, index, family, cov)
            problems += free_check(tmp_path, index, family, cov)
        except Mismatch as exc:
            problems.append(f"program {index}: {exc}")
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"chunk{chunk:05d}.json").write_text(json.dumps({
        "seed": SEED, "chunk": chunk, "programs": len(indexes), "mismatches": problems,
        "seconds": round(time.monotonic() - t0, 1), "coverage": cov.to_json()}))
    assert not problems, "\n".join(problems)


COCOTB = int(os.environ.get("BITBYTE_SOAK_COCOTB", "40"))


@pytest.mark.parametrize("sim", ["icarus", "verilator"])
def test_soak_cocotb_sample(sim, tmp_path):
    """The first COCOTB programs through cocotb on both simulators (one session each):
    serial, and parallel with the handshake and the queue in turn."""
    cov = Coverage()        # the sample's programs are counted by their chunks already
    jobs, cases, problems = [], [], []
    for index in range(min(N, COCOTB)):
        family = FAMILIES[index % len(FAMILIES)]
        for parallel in (False, True):
            case = Case(tmp_path, index, family, cov, parallel)
            exchange = EXCHANGES[index % 2] if parallel else "-"
            jobs.append(case.jobs[exchange])
            cases.append((case, exchange))
    for (case, exchange), result in zip(cases, run_jobs(jobs, sim)):
        got = case.view(records_from_rows(case.columns, result.rows), result.fault)
        how = f"cocotb-{sim}-" + (f"parallel-{exchange}" if case.parallel else "serial")
        problem = case.compare(got, how, case.argv(exchange, tmp_path / "t.csv") +
                               ["--sim", sim])
        problems += [problem] if problem else []
    assert not problems, "\n".join(problems)
