"""Random bit-only programs: the hardware's trace equals the reference interpreter's,
scan by scan (every column, t_us and cycles included), on the Verilator C++ harness
(`bitbyte run --sim verilator`) and through cocotb on Icarus and on Verilator.

The seed is printed in the pytest header; BITBYTE_SEED=<n> reproduces a run, and a
failing program is written to the test's tmp directory with its seed.
"""
from __future__ import annotations

import os
from pathlib import Path

import pytest

from bitbyte import cli
from bitbyte.refsim import refsim_trace
from bitbyte.sim_cocotb import run_jobs
from bitbyte.stimulus import load_stimulus
from bitbyte.trace import read_trace_rows, trace_text
from randprog import random_program, random_stimulus, random_watch

PROGRAMS = int(os.environ.get("BITBYTE_RANDOM_PROGRAMS", "200"))
SCANS = 12
WATCHDOG = 600
BASE_SEED = int(os.environ["BITBYTE_SEED"])


class Case:
    """One random program written to disk with its stimulus and expected trace."""

    def __init__(self, tmp: Path, index: int):
        self.seed = BASE_SEED * 1000 + index
        self.il = tmp / f"p{self.seed}.il"
        self.stim = tmp / f"p{self.seed}.stim.csv"
        self.il.write_text(random_program(self.seed))
        self.stim.write_text(random_stimulus(self.seed, SCANS))
        self.watch = ",".join(random_watch(self.seed))
        self.program, self.columns, self.job, self.f = cli.prepare_run(
            str(self.il), stimulus=str(self.stim), watch=self.watch, scans=SCANS,
            watchdog=WATCHDOG)
        stim = load_stimulus(str(self.stim), self.program.symbols)
        _, records, self.fault = refsim_trace(
            self.program, stimulus=stim, watch=self.watch.split(",") if self.watch else [],
            scans=SCANS, watchdog=WATCHDOG)
        self.expected = trace_text(self.columns, records, self.f)

    def check(self, records, fault, how: str):
        got = trace_text(self.columns, records, self.f)
        assert (got, fault) == (self.expected, self.fault), (
            f"{how}: program seed {self.seed} ({self.il}) differs from the reference")


@pytest.fixture(scope="module")
def cases(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("random")
    print(f"random programs: BITBYTE_SEED={BASE_SEED}, {PROGRAMS} programs")
    return [Case(tmp, i) for i in range(PROGRAMS)]


def test_generator_covers_the_instruction_set(cases):
    """The random programs do exercise what they claim to (else the test is weak)."""
    mnemonics = {i.mnemonic for c in cases for i in c.program.instrs}
    areas = {i.operand.area for c in cases for i in c.program.instrs if i.operand}
    assert {"LD", "LDN", "A", "AN", "O", "ON", "X", "XN", "NOT", "SET", "CLR", "=",
            "S", "R", "FP", "FN", "A(", "XN(", ")", "JU", "JC", "JCN", "NOP",
            "REFRESH", "END"} <= mnemonics
    assert {"I", "PI", "IR", "IF", "Q", "PQ", "M", "T", "C"} <= areas
    assert any(c.fault for c in cases) and not all(c.fault for c in cases)


def test_verilator_harness(cases, tmp_path, capsys):
    """`bitbyte run --sim verilator` (the C++ harness) against the reference."""
    for case in cases:
        trace = tmp_path / f"{case.seed}.csv"
        argv = ["run", str(case.il), "--sim", "verilator", "--stimulus", str(case.stim),
                "--scans", str(SCANS), "--watchdog", str(WATCHDOG), "--trace", str(trace)]
        if case.watch:
            argv += ["--watch", case.watch]
        rc = cli.main(argv)
        assert rc in (0, cli.EXIT_WATCHDOG), capsys.readouterr().err
        case.check(read_trace_rows(trace, case.columns), rc == cli.EXIT_WATCHDOG,
                   "verilator harness")


@pytest.mark.parametrize("sim", ["icarus", "verilator"])
def test_cocotb(cases, sim):
    """All programs in one cocotb session per simulator (the driver of --sim icarus)."""
    results = run_jobs([c.job for c in cases], sim)
    for case, result in zip(cases, results):
        case.check(cli._records_from_rows(case.columns, result.rows), result.fault,
                   f"cocotb {sim}")
