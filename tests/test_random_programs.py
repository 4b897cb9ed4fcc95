"""Random programs: the hardware's trace equals the reference interpreter's, scan by
scan (every column, t_us and cycles included), on the Verilator C++ harness
(`bitbyte run --sim verilator`) and through cocotb on Icarus and on Verilator.
Two families: bit-only programs, and mixed programs in serial mode (word
instructions, timers and counters executed by the byte processor's firmware).

The seed is printed in the pytest header; BITBYTE_SEED=<n> reproduces a run, and a
failing program is written to the test's tmp directory with its seed.
"""
from __future__ import annotations

import os
from pathlib import Path

import pytest

from bitbyte.run.prepare import prepare_run
from bitbyte.sim.cocotb_runner import records_from_rows
from bitbyte import cli
from bitbyte.ref.refsim import refsim_trace
from bitbyte.sim.cocotb_runner import run_jobs
from bitbyte.lang.stimulus import load_stimulus
from bitbyte.lang.trace import read_trace_rows, trace_text
from randprog import (make_cases, random_mixed_program, random_mixed_stimulus,
                      random_mixed_watch, random_program, random_stimulus, random_watch)

PROGRAMS = int(os.environ.get("BITBYTE_RANDOM_PROGRAMS", "200"))
MIXED_PROGRAMS = int(os.environ.get("BITBYTE_MIXED_PROGRAMS", "200"))
# Icarus runs the random programs about five times slower than Verilator: through
# cocotb it takes the first ICARUS_PROGRAMS of them (BITBYTE_ICARUS_PROGRAMS; Verilator
# takes all), the mixed ones a quarter of that. Every program still meets the reference
# on the Verilator harness.
ICARUS_PROGRAMS = int(os.environ.get("BITBYTE_ICARUS_PROGRAMS", "40"))
SCANS = 12
BASE_SEED = int(os.environ["BITBYTE_SEED"])


class Family:
    """How one family of random programs is made and run."""

    def __init__(self, name, program, stimulus, watch, clock_mhz, watchdog):
        self.name, self.program, self.stimulus, self.watch = name, program, stimulus, watch
        self.clock_mhz, self.watchdog = clock_mhz, watchdog


BIT_ONLY = Family("bit", random_program, lambda seed: random_stimulus(seed, SCANS),
                  random_watch, "100", 600)
# 0.1 MHz: 100 clocks per ms, so the timers' 0..25 ms presets run out within a run
MIXED = Family("mixed", random_mixed_program,
               lambda seed: random_mixed_stimulus(seed, SCANS, 3000), random_mixed_watch,
               "0.1", 20_000)


class Case:
    """One random program written to disk with its stimulus and expected trace."""

    def __init__(self, tmp: Path, index: int, family: Family = BIT_ONLY):
        self.seed = BASE_SEED * 1000 + index
        self.family = family
        self.il = tmp / f"{family.name}{self.seed}.il"
        self.stim = tmp / f"{family.name}{self.seed}.stim.csv"
        self.il.write_text(family.program(self.seed))
        self.stim.write_text(family.stimulus(self.seed))
        self.watch = ",".join(family.watch(self.seed))
        self.program, self.columns, self.job, self.f = prepare_run(
            str(self.il), stimulus=str(self.stim), watch=self.watch, scans=SCANS,
            watchdog=family.watchdog, clock_mhz=family.clock_mhz)
        stim = load_stimulus(str(self.stim), self.program.symbols)
        stim.clock_mhz = self.f
        _, records, self.fault = refsim_trace(
            self.program, config=cli.Config(clock_mhz=float(self.f)), stimulus=stim,
            watch=self.watch.split(",") if self.watch else [],
            scans=SCANS, watchdog=family.watchdog)
        self.expected = trace_text(self.columns, records, self.f)

    def argv(self, trace: Path) -> list[str]:
        argv = ["run", str(self.il), "--sim", "verilator", "--stimulus", str(self.stim),
                "--scans", str(SCANS), "--watchdog", str(self.family.watchdog),
                "--clock-mhz", self.family.clock_mhz, "--trace", str(trace)]
        return argv + (["--watch", self.watch] if self.watch else [])

    def check(self, records, fault, how: str):
        got = trace_text(self.columns, records, self.f)
        assert (got, fault) == (self.expected, self.fault), (
            f"{how}: program seed {self.seed} ({self.il}) differs from the reference")


@pytest.fixture(scope="module")
def cases(tmp_path_factory):
    return make_cases(tmp_path_factory, "random", PROGRAMS, Case)


@pytest.fixture(scope="module")
def mixed_cases(tmp_path_factory):
    return make_cases(tmp_path_factory, "mixed", MIXED_PROGRAMS, Case, MIXED)


def test_generator_covers_the_instruction_set(cases):
    """The random programs do exercise what they claim to (else the test is weak)."""
    mnemonics = {i.mnemonic for c in cases for i in c.program.instrs}
    areas = {i.operand.area for c in cases for i in c.program.instrs if i.operand}
    assert {"LD", "LDN", "A", "AN", "O", "ON", "X", "XN", "NOT", "SET", "CLR", "=",
            "S", "R", "FP", "FN", "A(", "XN(", ")", "JU", "JC", "JCN", "NOP",
            "REFRESH", "REFRESH Q", "END"} <= mnemonics
    assert {"I", "PI", "IR", "IF", "Q", "QR", "QF", "PQ", "M", "T", "C"} <= areas
    assert any(c.fault for c in cases) and not all(c.fault for c in cases)


def check_on_harness(cases, tmp_path, capsys, what: str) -> None:
    """Every case through `bitbyte run --sim verilator`, checked against the reference."""
    for case in cases:
        trace = tmp_path / f"{case.seed}.csv"
        rc = cli.main(case.argv(trace))
        assert rc in (0, cli.EXIT_WATCHDOG), capsys.readouterr().err
        case.check(read_trace_rows(trace, case.columns), rc == cli.EXIT_WATCHDOG, what)


def test_verilator_harness(cases, tmp_path, capsys):
    """`bitbyte run --sim verilator` (the C++ harness) against the reference."""
    check_on_harness(cases, tmp_path, capsys, "verilator harness")


@pytest.mark.parametrize("sim", ["icarus", "verilator"])
def test_cocotb(cases, sim):
    """The programs in one cocotb session per simulator (the driver of --sim icarus):
    all on Verilator, the first ICARUS_PROGRAMS on Icarus."""
    cases = cases[:ICARUS_PROGRAMS] if sim == "icarus" else cases
    results = run_jobs([c.job for c in cases], sim)
    for case, result in zip(cases, results):
        case.check(records_from_rows(case.columns, result.rows), result.fault,
                   f"cocotb {sim}")


def test_mixed_generator_covers_the_byte_instructions(mixed_cases):
    mnemonics = {i.mnemonic for c in mixed_cases for i in c.program.instrs}
    assert {"L", "T", "+I", "-I", "*I", "/I", "MOD", "==I", ">=I", "SD", "SS", "SP",
            "SF", "CU", "CD", "S", "R"} <= mnemonics
    assert any(m.startswith("A ") for m in mnemonics) and \
        any(m.startswith("O ") for m in mnemonics)
    # the timers do run out within the runs: some timer status is 1 somewhere
    assert any(",1" in c.expected and "T" in c.watch for c in mixed_cases)


def test_mixed_verilator_harness(mixed_cases, tmp_path, capsys):
    """Serial mode, `bitbyte run --sim verilator`, against the reference."""
    check_on_harness(mixed_cases, tmp_path, capsys, "verilator harness, serial mode")


@pytest.mark.parametrize("sim", ["icarus", "verilator"])
def test_mixed_cocotb(mixed_cases, sim):
    """Serial mode through cocotb with the firmware in a bridged thread."""
    count = int(os.environ.get("BITBYTE_MIXED_COCOTB", "40"))
    count = min(count, ICARUS_PROGRAMS // 4) if sim == "icarus" else count
    results = run_jobs([c.job for c in mixed_cases[:count]], sim)
    for case, result in zip(mixed_cases, results):
        case.check(records_from_rows(case.columns, result.rows), result.fault,
                   f"cocotb {sim}, serial mode")
