"""Random mixed programs in parallel mode: the partitioned program on the hardware
(bit part on the bit processor, byte part on the firmware, with the handshake
flip-flops or the strict queues) leaves the same trace as the reference interpreter
in serial mode — every column but t_us and cycles, which differ by design (spec §2).
Timers stay in with presets that do not depend on either mode's timing
(randprog.long_timers: 9000 s, which does not run out within a run, or 0 ms, which
runs out at once), and inputs change only between scans."""
from __future__ import annotations

import os
import random
from pathlib import Path

import pytest

from bitbyte.compiler.partition import partition
from bitbyte.lang.costs import byte_kind
from bitbyte.lang.parts import STATUS_UPDATES
from bitbyte.run.prepare import prepare_run
from bitbyte.sim.cocotb_runner import records_from_rows
from bitbyte import cli
from bitbyte.ref.refsim import refsim_trace
from bitbyte.sim.cocotb_runner import run_jobs
from bitbyte.lang.stimulus import load_stimulus
from bitbyte.lang.trace import read_trace_rows
from randprog import (FULL_WATCH, long_timers, make_cases, plant_stimulus, random_mixed_program,
                      random_parallel_program, random_scan_stimulus,
                      strip_timers)

PROGRAMS = int(os.environ.get("BITBYTE_PARALLEL_PROGRAMS", "100"))
COCOTB = int(os.environ.get("BITBYTE_PARALLEL_COCOTB", "30"))
SCANS = 10
WATCHDOG = 50_000
BASE_SEED = int(os.environ["BITBYTE_SEED"])


def outputs(records):
    """What must agree between the modes: scan number and every traced value."""
    return [(r.scan, tuple(sorted(r.values.items()))) for r in records]


class Case:
    def __init__(self, tmp: Path, index: int):
        self.seed = BASE_SEED * 1000 + 500 + index
        maker = random_parallel_program if index % 2 else random_mixed_program
        self.il = tmp / f"par{self.seed}.il"
        self.stim = tmp / f"par{self.seed}.csv"
        self.il.write_text(long_timers(maker(self.seed), random.Random(self.seed)))
        self.stim.write_text(random_scan_stimulus(self.seed, SCANS))
        self.watch = ",".join(FULL_WATCH)    # everything the generators write
        kw = dict(stimulus=str(self.stim), watch=self.watch, scans=SCANS, watchdog=WATCHDOG)
        self.program, self.columns, _, _ = prepare_run(str(self.il), **kw)
        self.jobs = {ex: prepare_run(str(self.il), mode="parallel", exchange=ex, **kw)[2]
                     for ex in ("handshake", "queue")}
        stim = load_stimulus(str(self.stim), self.program.symbols)
        _, records, fault = refsim_trace(self.program, stimulus=stim,
                                         watch=self.watch.split(",") if self.watch else [],
                                         scans=SCANS, watchdog=WATCHDOG)
        self.expected = (outputs(records), fault)

    def check(self, records, fault, how):
        assert (outputs(records), fault) == self.expected, (
            f"{how}: program seed {self.seed} ({self.il}) differs from serial mode")


@pytest.fixture(scope="module")
def cases(tmp_path_factory):
    return make_cases(tmp_path_factory, "parallel", PROGRAMS, Case)


def test_cases_exercise_the_exchange(cases):
    """Most random programs do move conditions between the sides (else weak)."""
    def crosses(words):
        return any(w >> 24 < 0x80 and (w >> 12) & 0xF == 9 for w in words)
    moved = sum(crosses(c.jobs["handshake"].prog) for c in cases)
    assert moved > len(cases) // 2, f"only {moved} of {len(cases)} programs transfer"


def test_cases_keep_timers(cases):
    """The timers are in (issue 15: they were stripped): programs start them, and some
    watched timer status is 1 in some scan (SP / SF follow their enable)."""
    starts = sum(i.mnemonic in ("SD", "SS", "SP", "SF") for c in cases for i in c.program.instrs)
    on = sum(1 for c in cases for _, values in c.expected[0]
             for name, v in values if name.startswith("T") and v)
    assert starts > len(cases) // 2 and on > 0, (starts, on)


def run_on_harness(case, exchange: str, tmp_path, capsys, *extra: str) -> None:
    """`bitbyte run` the case in parallel mode on the harness (extra: more options) and
    check its trace against serial mode."""
    trace = tmp_path / f"{case.seed}.csv"
    argv = ["run", str(case.il), "--mode", "parallel", "--exchange", exchange, *extra,
            "--stimulus", str(case.stim), "--scans", str(SCANS),
            "--watchdog", str(WATCHDOG), "--trace", str(trace)]
    if case.watch:
        argv += ["--watch", case.watch]
    rc = cli.main(argv)
    assert rc in (0, cli.EXIT_WATCHDOG), capsys.readouterr().err
    case.check(read_trace_rows(trace, case.columns), rc == cli.EXIT_WATCHDOG,
               " ".join(["harness, parallel,", exchange, *extra]))


@pytest.mark.parametrize("exchange", ["handshake", "queue"])
def test_parallel_on_harness(cases, exchange, tmp_path, capsys):
    for case in cases:
        run_on_harness(case, exchange, tmp_path, capsys)


def test_parallel_status_path_on_harness(cases, tmp_path, capsys):
    """--tc-path status (issue 16 item 1, Fig. 2's bit -> byte half): a timer's enable /
    a counter's input through the status buffer, the byte side waiting for this scan's
    write; the same trace as serial mode. Handshake and queue alternate; the path must
    be taken in most programs with a timer or counter (else this proves little)."""
    used = with_tc = 0
    for k, case in enumerate(cases):
        run_on_harness(case, "queue" if k % 2 else "handshake", tmp_path, capsys,
                       "--tc-path", "status")
        with_tc += any(byte_kind(ins) in STATUS_UPDATES for ins in case.program.instrs)
        used += any(ins.status_wait for ins in partition(case.program, tc_path="status").byte)
    assert used > with_tc // 2, f"the status path in {used} of {with_tc} programs"
    print(f"--tc-path status taken in {used} of {with_tc} programs with a timer or counter")


@pytest.mark.parametrize("sim", ["icarus", pytest.param("verilator", marks=pytest.mark.slow)])
def test_parallel_on_cocotb(cases, sim):
    """Handshake and queue alternate over the programs, one cocotb session (Icarus,
    about five times slower, the first half of them)."""
    picked = cases[:COCOTB // 2] if sim == "icarus" else cases[:COCOTB]
    jobs = [c.jobs["queue" if i % 2 else "handshake"] for i, c in enumerate(picked)]
    for i, (case, result) in enumerate(zip(picked, run_jobs(jobs, sim))):
        case.check(records_from_rows(case.columns, result.rows), result.fault,
                   f"cocotb {sim}, parallel, {'queue' if i % 2 else 'handshake'}")


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
def test_status_read_first_in_the_bit_part(tmp_path, sim):
    """Review finding: a bit-16 status read that is the bit part's first instruction
    runs in the latch clock and must not see the previous scan's `updated` bits."""
    il = tmp_path / "s.il"
    il.write_text("L IW0\nL 0\n>I\nL IW1\nS C1\nLD C1\n= Q0.0\n")
    st = tmp_path / "s.csv"
    st.write_text("scan,IW0,IW1\n0,0,0\n1,1,5\n2,0,5\n3,1,0\n4,0,0\n")
    got = {}
    for mode in ("serial", "parallel"):
        trace = tmp_path / f"{mode}.csv"
        assert cli.main(["run", str(il), "--mode", mode, "--sim", sim, "--stimulus",
                         str(st), "--scans", "5", "--trace", str(trace)]) == 0
        got[mode] = [line.split(",")[3] for line in trace.read_text().splitlines()[1:]]
    assert got["parallel"] == got["serial"] == ["0", "1", "1", "0", "0"]


# Plant programs (bench/gen_programs.py rungs, timers stripped): the partitioning
# compiler reorders many of their bit-side rungs (tests/test_partition.py), so they
# check the schedule on the hardware: same trace as serial mode, both exchanges.
PLANT_PROGRAMS = 10


def _plant_case(tmp: Path, index: int, base: int = BASE_SEED):
    import random
    import sys
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
    import gen_programs
    seed = base * 1000 + 900 + index
    rng = random.Random(seed)
    g = gen_programs.generate(rng.randrange(60, 200), rng.randrange(10, 40), seed,
                              jumps=rng.randrange(0, 4))
    il = tmp / f"plant{seed}.il"
    from test_partition import crowd_addresses
    il.write_text(crowd_addresses(strip_timers("\n".join(g.lines) + "\n")))
    stim = tmp / f"plant{seed}.csv"
    stim.write_text(plant_stimulus(rng, SCANS, min_flips=1))
    watch = ",".join(f"M{b}.{n}" for b in range(6) for n in range(8)) + \
        ",MW0,MW1,MW2,MW3,QW0,QW1,C0,C1"
    return seed, il, stim, watch


def test_scheduled_plant_programs_on_harness(tmp_path, capsys):
    from bitbyte.lang.parser import parse_file
    from bitbyte.compiler.partition import partition
    moved = 0
    # two fixed programs the compiler reschedules (seeds 901 and 904), the rest from
    # this run's seed: the check of rescheduled parts on the hardware is never luck
    cases = [(1, 0), (4, 0)] + [(k, BASE_SEED) for k in range(PLANT_PROGRAMS - 2)]
    for n, (index, base) in enumerate(cases):
        seed, il, stim, watch = _plant_case(tmp_path, index, base)
        part = partition(parse_file(str(il)))
        moved += part.schedule is not None
        assert part.schedule is not None or n >= 2, f"fixed program {seed} not rescheduled"
        kw = dict(stimulus=str(stim), watch=watch, scans=SCANS, watchdog=WATCHDOG)
        program, columns, _, _ = prepare_run(str(il), **kw)
        _, records, fault = refsim_trace(program, stimulus=load_stimulus(
            str(stim), program.symbols), watch=watch.split(","), scans=SCANS,
            watchdog=WATCHDOG)
        expected = (outputs(records), fault)
        for exchange in ("handshake", "queue"):
            trace = tmp_path / f"{seed}.{exchange}.csv"
            rc = cli.main(["run", str(il), "--mode", "parallel", "--exchange", exchange,
                           "--stimulus", str(stim), "--scans", str(SCANS), "--watchdog",
                           str(WATCHDOG), "--trace", str(trace), "--watch", watch])
            assert rc in (0, cli.EXIT_WATCHDOG), capsys.readouterr().err
            got = (outputs(read_trace_rows(trace, columns)), rc == cli.EXIT_WATCHDOG)
            assert got == expected, f"plant program seed {seed} ({il}), {exchange}"
    # the point is that rescheduled parts run serial-equivalent on the harness, so some
    # of the programs must have been rescheduled; how many of the run's depends on its
    # seed (4 of 10 at BITBYTE_SEED=156412), the two fixed ones always are
    assert moved >= 2, f"only {moved} of {PLANT_PROGRAMS} rescheduled"
