"""Shared-memory protection under stress (issue: multi-core plant, spec §7).

Tearing: a writer stamps its scan count into every word of an 8-word group each
scan; the reader's trace shows, per scan, what its precycle copied. With the
semaphore and with ping-pong every copied group must be whole (all words equal) over
READER_SCANS reader scans at random period ratios and phases (30 000 in `make test`,
100 000 in `make soak`: BITBYTE_TEARING_SCANS); with protection switched off the same
runs must show torn groups, so it can fail (it stops at the first run that does).

Contention: both cores copying at once spin on the lock (sem_wait > 0), a waiting
core gets the lock within a bounded number of clocks after the owner's copy ends, and
a precycle that can no longer fit its period is skipped with the sticky copy_fail.
"""
from __future__ import annotations

import json
import os
import random
import sys
from collections import Counter
from pathlib import Path

import pytest

from bitbyte.plant.run import run_plant

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
sys.path.insert(0, str(ROOT / "soak"))
import coverage_count  # noqa: E402
import plantgen  # noqa: E402

SEED = int(os.environ.get("BITBYTE_SEED", "1"))   # printed by make test
GROUP = 8
# per protection mode, summed over the runs
READER_SCANS = int(os.environ.get("BITBYTE_TEARING_SCANS", "30000"))
# make soak: the plant's coverage cross (protection x layout x contention, soak/
# coverage_count.py) of each test goes into this directory for soak/soak_report.py
COVERAGE_OUT = os.environ.get("BITBYTE_PLANT_COVERAGE")
CROSS: Counter = Counter()


def _count(protection: str, layout: str, rows, reader="r") -> None:
    others = [r for core, r in rows.items() if core != reader]
    for c in coverage_count.plant_contention(rows[reader], others):
        CROSS[(protection, layout, c)] += 1


@pytest.fixture(autouse=True)
def _cross(request):
    CROSS.clear()
    yield
    if COVERAGE_OUT:
        Path(COVERAGE_OUT).mkdir(parents=True, exist_ok=True)
        name = request.node.name.replace("[", "_").replace("]", "")
        (Path(COVERAGE_OUT) / f"plant_{name}.json").write_text(json.dumps(
            {"plant_coverage": [list(k) + [v] for k, v in sorted(CROSS.items())]}))


def _tearing_runs(tmp_path, protection: str, seed: int, until_torn: bool = False):
    """Runs with random periods and reader phases until READER_SCANS reader scans (or,
    until_torn, until each layout had a run with a torn group and reader scans both
    apart from and beside a writer's copy: the layouts take turns); returns (reader
    scans, torn scans, distinct values seen). No run may end with the reader's
    copy_fail set (no skip, no ping-pong precycle overtaken by its writer)."""
    rng = random.Random(seed)
    scans = torn = 0
    seen = set()
    run = 0
    torn_in = set()
    while scans < READER_SCANS:
        nops = rng.randrange(0, 40)
        writer, reader = plantgen.tearing_pair(GROUP, reader_nops=nops)
        w_period, r_period = rng.choice([0, 1, 2, 3]), rng.choice([0, 0, 1, 2])
        layout = coverage_count.LAYOUTS[run % 2] if until_torn else rng.choice(
            coverage_count.LAYOUTS)
        plant = plantgen.write_plant(
            tmp_path / f"{protection}{run}",
            [("w", writer, w_period), ("r", reader, r_period)],
            protection=protection, layout=layout)
        status, summary, rows = run_plant(
            str(plant), until_us="400", watch=",".join(f"r.MW{i}" for i in range(GROUP)))
        assert status == 0, summary
        _count(protection, layout, rows)
        if protection != "none":
            assert rows["r"][-1]["copy_fail"] == "0", summary
        for row in rows["r"]:
            group = {row[f"MW{i}"] for i in range(GROUP)}
            torn += len(group) > 1
            torn_in |= {layout} if len(group) > 1 else set()
            seen |= group
        scans += len(rows["r"])
        run += 1
        if until_torn and torn_in == set(coverage_count.LAYOUTS) and _met_both(protection):
            break
    return scans, torn, seen


def _met_both(protection: str) -> bool:
    """The runs so far met reader scans apart from and beside a writer's copy, in
    both layouts."""
    return {(protection, layout, c) for layout in coverage_count.LAYOUTS
            for c in ("apart", "overlap")} <= set(CROSS)


@pytest.mark.parametrize("protection", ["semaphore", "pingpong"])
def test_no_tearing_with_protection(tmp_path, protection):
    seed = SEED + {"semaphore": 1, "pingpong": 2}[protection]
    scans, torn, seen = _tearing_runs(tmp_path, protection, seed)
    assert scans >= READER_SCANS
    assert len(seen) > 200           # the reader really followed the writer
    assert torn == 0, f"{torn} torn groups in {scans} reader scans (seed {seed})"
    # the runs met both: copies apart, and a reader's copy beside the writer's
    assert _met_both(protection), sorted(CROSS.items())


def test_tearing_detected_without_protection(tmp_path):
    seed = 4      # fixed, not the run's seed: that tearing is seen must not be luck
    scans, torn, _ = _tearing_runs(tmp_path, "none", seed, until_torn=True)
    assert torn > 0, f"no torn group in {scans} reader scans: the test cannot fail"
    assert _met_both("none"), sorted(CROSS.items())   # both layouts tear, too


def _clocks_to_end(row, clock_mhz=100):
    from fractions import Fraction
    return int(Fraction(row["t_us"]) * clock_mhz)


def test_contention_spin_bounded_grant_and_skip(tmp_path):
    # 1. two cores copying back to back: they spin on the lock
    writer, reader = plantgen.tearing_pair(GROUP)
    plant = plantgen.write_plant(tmp_path / "spin", [("w", writer, 0), ("r", reader, 0)])
    status, summary, rows = run_plant(str(plant), until_us="200")
    assert status == 0, summary
    waits = [int(r["sem_wait"]) for core in rows.values() for r in core]
    assert sum(w > 0 for w in waits) > 10
    # A waiting core is granted the lock at the latest in the clock after the owner's
    # copy ends: a copy of n plan entries holds it n + 3 clocks (lock clock, n
    # entries, fill and drain), and a scan waits at most once in its precycle and once
    # in its postcycle. Plans: w posts 1 + 8 entries, r reads 1 + 8.
    hold = 1 + GROUP + 3
    assert max(waits) <= 2 * hold, max(waits)
    assert max(waits) >= 2                # real waiting, not just a clock of skew

    # 2. a long postcycle (a 200-word writer) against a reader whose period leaves no
    # room for waiting: its precycle is skipped, copy_fail is set and stays set; in
    # both layouts (random: one copy per variable, no bursts, so the reader's own copy
    # takes 406 clocks and its period is 5 us, not 3)
    big_w, big_r = plantgen.table4_pair(200, back=0)
    for layout, period in (("compact", 3), ("random", 5)):
        plant = plantgen.write_plant(tmp_path / f"skip_{layout}",
                                     [("a", big_w, 0), ("b", big_r, period)], layout=layout)
        status, summary, rows = run_plant(str(plant), until_us="600")
        assert status == 0, summary
        _count("semaphore", layout, rows, reader="b")
        b = rows["b"]
        first = next(i for i, r in enumerate(b) if r["copy_fail"] == "1")
        assert all(r["copy_fail"] == "1" for r in b[first:])      # sticky
        assert all(r["copy_fail"] == "0" for r in b[:first])
        skipped = int(summary.split("core b")[1].split("skipped precycles ")[1].split(",")[0])
        # the count, scan by scan: b's postcycle copies nothing (post 2: its begin and
        # end clock, no lock), so its waiting is its precycle's; a precycle that copied
        # took its whole list beyond the waiting (the same length every scan), one that
        # gave up only its first clock and the give-up clock
        spent = Counter(int(r["pre"]) - int(r["sem_wait"]) for r in b)
        assert set(r["post"] for r in b) == {"2"}, summary
        assert len(spent) == 2 and spent[2] > 0, spent
        assert skipped == spent[2], (skipped, spent)      # the summary counts them all
        # every scan of b still ends within its period (that is what skipping buys)
        for r in b:
            start = _clocks_to_end(r) - int(r["post"]) - int(r["cycles"]) - int(r["pre"])
            assert start % (100 * period) == 0 and r["overrun"] == "0"
        # the writer's postcycle always waits (never skipped): its data keeps flowing
        a = rows["a"]
        assert int(a[-1]["scan"]) >= 5 and all(r["copy_fail"] == "0" for r in a)
    assert {("semaphore", layout, "copy_fail") for layout in coverage_count.LAYOUTS} \
        <= set(CROSS)


def test_pingpong_overtaken_by_a_fast_bit_writer_is_flagged(tmp_path):
    """Ping-pong's limit: a writer that publishes 32 bit variables from a 2-instruction
    scan can begin overwriting the buffer a reader (copying them in the opposite
    order) is still reading. The reader's precycle notices it and sets copy_fail:
    a possibly mixed copy is never silent. Two cores overtake with the random layout
    only (compact copies the reader's 32 bits in fewer clocks than the writer needs to
    publish twice); with a third core whose 64 words the reader copies too, in both."""
    names = [f"B{i}" for i in range(32)]
    writer = ("VAR_GLOBAL\n" + "".join(f"  {n} AT M{i // 8}.{i % 8} : WRITE;\n"
                                       for i, n in enumerate(names))
              + "END_VAR\n      NOP\n      END\n")
    reader = ("VAR_GLOBAL\n" + "".join(f"  {n} AT M{i // 8}.{i % 8} : READ;\n"
                                       for i, n in reversed(list(enumerate(names))))
              + "END_VAR\n      NOP\n      END\n")
    flagged = Counter()
    for run, (w_period, r_period) in enumerate([(0, 0), (0, 1), (1, 0), (0, 2)]):
        plant = plantgen.write_plant(tmp_path / f"fast{run}",
                                     [("w", writer, w_period), ("r", reader, r_period)],
                                     protection="pingpong", layout="random")
        status, summary, rows = run_plant(str(plant), until_us="100")
        assert status == 0, summary
        _count("pingpong", "random", rows)
        flagged["two cores"] += rows["r"][-1]["copy_fail"] == "1"
        assert all(r["copy_fail"] == "0" for r in rows["w"])   # the writer reads nothing
    def words(kind):
        return "".join(f"  W{i} AT MW{10 + i} : {kind};\n" for i in range(64))
    slow = "VAR_GLOBAL\n" + words("WRITE") + "END_VAR\n      NOP\n      END\n"
    reader3 = reader.replace("VAR_GLOBAL\n", "VAR_GLOBAL\n" + words("READ"))
    for layout in coverage_count.LAYOUTS:
        plant = plantgen.write_plant(tmp_path / f"three_{layout}",
                                     [("v", slow, 0), ("w", writer, 0), ("r", reader3, 0)],
                                     protection="pingpong", layout=layout)
        status, summary, rows = run_plant(str(plant), until_us="100")
        assert status == 0, summary
        _count("pingpong", layout, rows)
        flagged[layout] += rows["r"][-1]["copy_fail"] == "1"
    assert all(flagged[k] > 0 for k in ("two cores", *coverage_count.LAYOUTS)), flagged
