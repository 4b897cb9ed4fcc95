"""`bitbyte run PLANT.toml` on the multi-core system (spec §7, seed 000 §6.1).

The seed's pair of projects runs on the Verilator plant harness (rtl/plc_system.v,
two cores, every core's byte processor in its own coroutine). The traces are checked
against the stimulus and against an independent model of the visibility rule: a
value a reader shows for a shared variable in scan j must be one its writer published
(at the end of one of its postcycles) while the reader's precycle j could see it.
"""
from __future__ import annotations

import shutil
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import pytest

from bitbyte.plant.run import run_plant

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "plant_6_1"


def _plant(tmp_path: Path, clock_mhz=1, layout="compact", protection="semaphore") -> Path:
    """The §6.1 example at a slow clock (1 MHz: 6 s are 6 M clocks)."""
    for name in ("p1.il", "p2.il", "p1.stim.csv"):
        shutil.copy(EXAMPLE / name, tmp_path / name)
    text = (EXAMPLE / "plant.toml").read_text()
    text = text.replace("clock_mhz = 100", f"clock_mhz = {clock_mhz}")
    text = text.replace('layout = "compact"', f'layout = "{layout}"')
    text = text.replace('protection = "semaphore"', f'protection = "{protection}"')
    path = tmp_path / "plant.toml"
    path.write_text(text)
    return path


def _clocks(row, clock_mhz):
    """(precycle start, latch, postcycle start, end) of a trace row, in clocks."""
    end = Fraction(row["t_us"]) * clock_mhz
    assert end.denominator == 1
    end = int(end)
    post, cycles, pre = int(row["post"]), int(row["cycles"]), int(row["pre"])
    return end - post - cycles - pre, end - post - cycles, end - post, end


def check_visibility(writer_rows, writer_col, reader_rows, reader_col, clock_mhz):
    """Every value the reader shows was published by the writer at a time its
    precycle could see: the writer's postcycle i began before the reader's precycle
    ended, and its next postcycle had not ended before the reader's precycle began
    (value 0 before the first publication). Returns the number of reader scans."""
    pubs = [(_clocks(r, clock_mhz)[2], _clocks(r, clock_mhz)[3], int(r[writer_col]))
            for r in writer_rows]
    for row in reader_rows:
        pre_start, latch, _, _ = _clocks(row, clock_mhz)
        seen = int(row[reader_col])
        allowed = set()
        if not pubs or pubs[0][1] > pre_start:
            allowed.add(0)                              # nothing published yet
        for i, (post_start, _, value) in enumerate(pubs):
            next_end = pubs[i + 1][1] if i + 1 < len(pubs) else None
            if post_start < latch and (next_end is None or next_end > pre_start):
                allowed.add(value)
        assert seen in allowed, (
            f"reader scan {row['scan']} shows {reader_col}={seen}, the rule allows {allowed}")
    return len(reader_rows)


@pytest.mark.parametrize("layout", ["compact", "random"])
def test_seed_6_1_example(tmp_path, layout):
    plant = _plant(tmp_path, layout=layout)
    status, summary, rows = run_plant(
        str(plant), until_us="6600000", trace=str(tmp_path / "T.csv"),
        watch="p1.MW20,p1.M10.0,p1.M10.1,p2.MW0,p2.M0.0,p2.M0.1")
    assert status == 0, summary
    p1, p2 = rows["p1"], rows["p2"]
    assert (tmp_path / "T.p1.csv").read_text().splitlines()[0] == (
        "scan,t_us,cycles,pre,post,sem_wait,copy_fail,overrun,Q0.0,MW20,M10.0,M10.1")
    # a plant core's scan takes exactly as long as the same program on a single CPU
    # (the copies are outside it; MW on the bus fits in the word instructions' cost)
    for core, rows_ in (("p1", p1), ("p2", p2)):
        single = subprocess.run([sys.executable, "-m", "bitbyte.cli", "run",
                                 str(tmp_path / f"{core}.il"), "--scans", "2"],
                                capture_output=True, text=True, cwd=ROOT)
        want = single.stdout.split("cycles/scan")[1].split()[1]
        assert {r["cycles"] for r in rows_} == {want}, (core, want)
    # periods: scan k of p1 ends within its 10 ms period, p2 within 100 ms; no overrun
    for rows_, period in ((p1, 10000), (p2, 100000)):
        for r in rows_:
            assert int(r["overrun"]) == 0 and int(r["copy_fail"]) == 0
            start = _clocks(r, 1)[0]
            assert start == int(r["scan"]) * period
    # the visibility rule, in both directions, for every shared variable
    assert check_visibility(p1, "MW20", p2, "MW0", 1) == len(p2)
    assert check_visibility(p1, "M10.0", p2, "M0.0", 1) == len(p2)
    assert check_visibility(p2, "M0.1", p1, "M10.1", 1) == len(p1)
    # Project 1: OUT1 = CNT >= 10; the count follows the rising edges of IN1
    for r in p1:
        assert int(r["Q0.0"]) == (int(r["MW20"]) >= 10)
    first_out1 = next(r for r in p1 if r["Q0.0"] == "1")
    assert first_out1["MW20"] == "10"
    # Project 2: OUT2 = CNT > 3 on its own (older) copy; p2 samples every 100 ms
    # while the pulses come every 40 ms: the count it first sees above 3 is 5 (the
    # seed's "5 pulses switch OUT2 on")
    for r in p2:
        assert int(r["Q0.0"]) == (int(r["MW0"]) > 3)
    first_out2 = next(r for r in p2 if r["Q0.0"] == "1")
    assert first_out2["MW0"] == "5"
    # holding IN1 (from 485 ms on) for 5 s: TON1 -> RST -> CNT cleared
    rst_on = next(r for r in p2 if r["M0.1"] == "1")
    assert 5_485_000 <= _clocks(rst_on, 1)[3] <= 5_485_000 + 2 * 100_000
    cleared = [r for r in p1 if _clocks(r, 1)[0] > _clocks(rst_on, 1)[3]]
    assert cleared and all(r["MW20"] == "0" and r["Q0.0"] == "0" for r in cleared[1:])
    assert max(int(r["MW20"]) for r in p1) == 13


def test_three_cores_and_overruns(tmp_path):
    """Cores is a parameter: a writer and two readers of one group (semaphore: whole
    groups only); and a core whose period is shorter than its scan: every later scan
    starts late, right after the previous one, and is counted as an overrun."""
    sys.path.insert(0, str(ROOT / "bench"))
    import plantgen
    writer, reader = plantgen.tearing_pair(8)
    plant = plantgen.write_plant(tmp_path / "three", [("w", writer, 1), ("r1", reader, 0),
                                                      ("r2", reader, 2)], layout="random")
    status, summary, rows = run_plant(str(plant), until_us="300",
                                      watch="r1.MW0,r1.MW7,r2.MW0,r2.MW7")
    assert status == 0, summary
    assert summary.count("core ") == 3
    for core in ("r1", "r2"):
        assert len(rows[core]) > 100
        assert all(r["MW0"] == r["MW7"] for r in rows[core])
        assert len({r["MW0"] for r in rows[core]}) > 50
    # overruns: a 50-word core (its scan alone is about 2000 clocks = 20 us) every 5 us
    a, b = plantgen.table4_pair(50)
    plant = plantgen.write_plant(tmp_path / "late", [("a", a, 5), ("b", b, 1000)])
    status, summary, rows = run_plant(str(plant), until_us="200")
    assert status == 0, summary
    late = rows["a"]
    assert late[0]["overrun"] == "0" and all(r["overrun"] == "1" for r in late[1:])
    for prev, r in zip(late, late[1:]):      # each starts in the clock after the last ended
        start = _clocks(r, 100)[0]
        assert start == _clocks(prev, 100)[3] and start > int(r["scan"]) * 500
    assert f"overruns {len(late) - 1}," in summary.split("core b")[0]
