"""make bench's free-running figures (issue 15, defect 5): every free-running result
states the byte side's scans and the queue losses, read from the run summary."""
from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
import benchlib as bl  # noqa: E402
import report  # noqa: E402

# Four conditions cross to the byte side every bit scan (the jumps over word code):
# the bit side's short scan outruns the byte side's word work, so the free-running
# queue overflows (and the byte side finds it empty); the marker exchange loses nothing.
PROGRAM = "".join(f"LD I0.{n}\n= M{n}.0\nL MW{n}\nL 1\n+I\nT MW{n}\nLD M{n}.0\nJCN s{n}\n"
                  f"L MW{n}\nL 2\n*I\nT MW{n}\ns{n}: NOP\n" for n in range(4))


def _run(tmp_path, exchange):
    il = tmp_path / "p.il"
    il.write_text(PROGRAM)
    stim = tmp_path / "s.csv"
    stim.write_text("scan,I0.0,I0.1,I0.2,I0.3\n0,1,0,1,0\n3,0,1,1,1\n6,1,1,0,0\n")
    return bl.run_bitbyte(il, mode=f"free:{exchange}", clock_mhz=Fraction(10), scans=40,
                          stimulus=stim, trace=tmp_path / f"{exchange}.csv")


def test_free_running_figures_from_the_summary(tmp_path):
    r = _run(tmp_path, "queue-free")
    assert r.ok, r.stderr
    fr = r.free_running()
    assert fr["byte_scans"] > 0 and fr["clocks"] == r.rows[-1][1]
    assert fr["byte_scan"] == fr["clocks"] / fr["byte_scans"]
    # the summary's own line, read independently of the parser
    line = next(x for x in r.stdout.splitlines() if x.startswith("queue losses"))
    assert [int(w) for w in line.replace(",", " ").split() if w.isdigit()] == fr["losses"]
    assert sum(fr["losses"]) > 0, r.stdout        # the program does overrun the queue
    note = report.free_note(fr)
    assert f"byte side {fr['byte_scans']} scans" in note and "overflows" in note
    assert bl.Run(0, "scans 3\n", "").free_running() is None        # not free-running


def test_marker_exchange_loses_nothing(tmp_path):
    r = _run(tmp_path, "marker")
    assert r.ok, r.stderr
    assert r.free_running()["losses"] == [0, 0, 0, 0]
