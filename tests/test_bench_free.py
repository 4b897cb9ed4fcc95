"""make bench's free-running figures (issue 15, defect 5): every free-running result
states the byte side's scans and the queue losses, read from the run summary."""
from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

import pytest

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
    """The marker exchange has no queue: its summary states no losses, and the report
    says so from the exchange, not from a default count."""
    r = _run(tmp_path, "marker")
    assert r.ok, r.stderr
    assert "queue losses" not in r.stdout, r.stdout
    fr = r.free_running()
    assert fr["losses"] is None and fr["exchange"] == "marker"
    assert "losses: none (marker exchange)" in report.free_note(fr)


def test_losses_only_as_the_summary_states_them():
    """No `queue losses` line: no loss count.  A queue-free run must have the line."""
    summary = "scans 3\nbyte side        2 scans (free-running)\nsimulated  1 us, 90 clocks\n"
    fr = bl.Run(0, summary, "", exchange="marker").free_running()
    assert fr["losses"] is None
    with pytest.raises(RuntimeError, match="queue losses"):
        bl.Run(0, summary, "", exchange="queue-free").free_running()


def test_saturated_loss_counters_are_a_lower_bound():
    """rtl/cond_queue.v stops each counter at 0xFFFF: that many or more were lost."""
    fr = dict(byte_scans=2, clocks=90, byte_scan=45.0, exchange="queue-free",
              losses=[65535, 3, 0, 65535])
    assert report.free_note(fr) == ("byte side 2 scans, mean 45 clocks; losses: overflows "
                                    "to-byte >= 65535 / to-bit 3, underflows to-byte 0 / "
                                    "to-bit >= 65535")


# The report's rows (issue 15 defect 5, the audit at stop 38: §1's scan-time table and
# §4's response rows showed the bit side alone): every row of a free-running run
# carries the byte side's scans and the losses, other modes a dash.
FREE = dict(byte_scans=7, clocks=700, byte_scan=100.0, exchange="queue-free",
            losses=[5, 0, 2, 0])
NOTE = "byte side 7 scans, mean 100 clocks; losses: overflows to-byte 5 / to-bit 0"


def test_every_free_running_row_states_the_byte_side_and_losses():
    e = dict(name="p", n_bit=3, n_word=1, n_jump=0, static_paper=14)
    run = dict(scans=10, min=9, median=10, max=11)
    image = dict(clocks=[1, 2], min=1, median=1.5, p99=2, max=2, bound=30,
                 within_bound=True, exact=True, scan_min=9, scan_max=11)
    resp = dict(image=image, direct=dict(image, exact=False))
    for free, want in ((FREE, NOTE), (None, "| – |")):
        rows = [report.scan_row(e, "m", dict(run, free=free), 10.0),
                report.response_row("m", "image", dict(resp, free=free), 10.0),
                report.response_row("m", "direct", dict(resp, free=free), 10.0),
                report.fast_row("m", dict(resp, free=free), 10.0)]
        for row in rows:
            assert want in row, row
