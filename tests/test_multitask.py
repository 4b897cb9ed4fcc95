"""Multitask (paper Fig. 14/15): independent tasks with their own exchange channels
do not block each other. examples/two_tasks.il hands two conditions to a busy byte
side; with one channel the second hand-over (and the bit logic after it) waits for
the byte side, with two channels it does not. Outputs equal serial mode either way."""
from __future__ import annotations

from pathlib import Path

import pytest

from bitbyte import cli
EX = Path(__file__).resolve().parents[1] / "examples"


def run(tmp_path, sim, mode, channels=None):
    trace = tmp_path / f"{mode}{channels}.csv"
    argv = ["run", str(EX / "two_tasks.il"), "--stimulus", str(EX / "two_tasks.stim.csv"),
            "--scans", "6", "--mode", mode, "--sim", sim, "--trace", str(trace),
            "--watch", "MW4,C0,C1"]
    if channels:
        argv += ["--channels", str(channels)]
    assert cli.main(argv) == 0
    return [line.split(",") for line in trace.read_text().splitlines()]


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
def test_a_channel_per_task(tmp_path, sim):
    serial = run(tmp_path, sim, "serial")
    one = run(tmp_path, sim, "parallel", 1)
    two = run(tmp_path, sim, "parallel", 2)
    same = [[r[0]] + r[3:] for r in serial]
    assert [[r[0]] + r[3:] for r in one] == same
    assert [[r[0]] + r[3:] for r in two] == same
    c1 = {int(r[2]) for r in one[1:]}
    c2 = {int(r[2]) for r in two[1:]}
    # byte side: 8 word instructions (80) + 2 READ + 2 CU (22) = 102 clocks. With a
    # channel per task the bit side's ~100 instructions run beside it (measured 105
    # clocks per scan); with one channel the second hand-over waits until the byte
    # side takes the first, after its 80 clocks of word work (measured 183; serial 203)
    assert max(c2) + 50 < min(c1), (c1, c2)
