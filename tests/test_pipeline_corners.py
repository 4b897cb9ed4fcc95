"""The bit processor's pipeline corners (docs/fmax-plan.md, step 0 of re-pipelining the
operand select): each program reads an image right where a pipeline must get the value
of an image that changes between an instruction's operand select and its execution,
on the harness against the reference interpreter, with the pins changing in every
clock (`t_us` rows, seeded) or at every scan start (`scan` rows). Each is shown to fail
on a broken bit_proc.v (by hand at stop 37): the operand stage's marker forwarding
without this clock's write (gap 0), the two latches of a REFRESH in the latch clock
taken as one (REFRESH first), QR/QF without the update of the clock they are selected in
(REFRESH Q at gap 0, a scan's first reads).

* the scan start and REFRESH: I / IR / IF read by the instructions at addresses 0, 1,
  2 ... of a scan and right behind a REFRESH (REFRESH as the first instruction too),
  each read folded into an XOR chain so that any one wrong read flips an output;
* this processor's own writes read back 1, 2 and 3 instructions later: `= M`, `S`/`R`
  on M, an FP edge memory, `= Q` and `= PQ`, and QR/QF behind `REFRESH Q` at distance
  0 to 2 (and as the first instructions of a scan, behind END's update).
"""
from __future__ import annotations

import random

import pytest

from test_cpu_directed import _harness_equals_reference

PINS = [f"{n}.{m}" for n in range(2) for m in range(8)]      # I0.0 .. I1.7


def _per_clock(stim, clocks: int, seed: int) -> None:
    """Every pin random in every clock (100 MHz: a row every 0.01 µs)."""
    rng = random.Random(seed)
    rows = [f"{c / 100:.2f}," + ",".join(str(rng.getrandbits(1)) for _ in PINS)
            for c in range(clocks)]
    stim.write_text("t_us," + ",".join(f"I{p}" for p in PINS) + "\n" + "\n".join(rows)
                    + "\n")


def _per_scan(stim, scans: int, seed: int) -> None:
    rng = random.Random(seed)
    stim.write_text("scan," + ",".join(f"I{p}" for p in PINS) + "\n" + "".join(
        f"{s}," + ",".join(str(rng.getrandbits(1)) for _ in PINS) + "\n"
        for s in range(scans)))


def _chain(views, pins, out: str) -> str:
    """LD v0 / X v1 / ... / = out: the parity of every read."""
    first, *rest = [f"{v}{p}" for v, p in zip(views, pins)]
    return f"LD {first}\n" + "".join(f"X {r}\n" for r in rest) + f"= {out}\n"


# Where the reads start: the scan's first instruction, behind a NOP, behind a REFRESH
# (the first instruction or the second).
LEADS = {"first": "", "second": "NOP\n", "refresh_first": "REFRESH\n",
         "nop_refresh": "NOP\nREFRESH\n"}
VIEWS = ["I", "IR", "IF"]


def _input_program(lead: str, first: str) -> str:
    # three chains of six reads: the first starts with `first` right behind the lead
    order = VIEWS[VIEWS.index(first):] + VIEWS[:VIEWS.index(first)]
    views = order * 2
    return (lead + _chain(views, PINS[0:6], "Q0.0")
            + _chain(views[1:] + views[:1], PINS[6:12], "Q0.1")
            + "REFRESH\n" + _chain(views[2:] + views[:2], PINS[10:16], "Q0.2"))


@pytest.mark.parametrize("first", VIEWS)
@pytest.mark.parametrize("lead", list(LEADS))
def test_inputs_at_scan_start_and_refresh_every_clock(lead, first, tmp_path):
    il, stim = tmp_path / "p.il", tmp_path / "p.csv"
    il.write_text(_input_program(LEADS[lead], first))
    scans = 30
    _per_clock(stim, scans * 30, seed=list(LEADS).index(lead) * 3 + VIEWS.index(first))
    rows = _harness_equals_reference(il, stim, ["Q0.0", "Q0.1", "Q0.2"], scans)
    # the stimulus reaches every chain: each output takes both values
    assert all(len({r[c] for r in rows}) == 2 for c in range(3)), rows


@pytest.mark.parametrize("mode", ["serial", "parallel"])
@pytest.mark.parametrize("lead", ["first", "second", "refresh_first"])
def test_inputs_at_scan_start_every_scan(lead, mode, tmp_path):
    il, stim = tmp_path / "p.il", tmp_path / "p.csv"
    il.write_text(_input_program(LEADS[lead], "IR"))
    scans = 24
    _per_scan(stim, scans, seed=7)
    extra = ["--mode", "parallel"] if mode == "parallel" else []
    rows = _harness_equals_reference(il, stim, ["Q0.0", "Q0.1", "Q0.2"], scans, *extra)
    assert all(len({r[c] for r in rows}) == 2 for c in range(3)), rows


def _write_back_program(gap: int) -> str:
    """Writes read back `gap` instructions later (NOPs between)."""
    nops = "NOP\n" * gap
    return ("LD I0.0\n= M0.0\n" + nops + "LD M0.0\n= Q0.0\n"
            "LD I0.1\nS M0.1\nLD I0.2\nR M0.1\n" + nops + "LD M0.1\n= Q0.1\n"
            "LD I0.3\nFP M0.2\n" + nops + "LD M0.2\n= Q0.2\n"
            "LD I0.4\n= Q1.0\n" + nops + "LD Q1.0\n= Q0.3\n"
            "LD I0.5\n= PQ1.1\n" + nops + "LD Q1.1\n= Q0.4\n"
            "LD I0.6\n= Q1.2\n" + nops + "REFRESH Q\n" + nops
            + "LD QR1.2\n= Q0.5\nLD QF1.2\n= Q0.6\n")


WRITE_BACK_COLUMNS = [f"Q0.{i}" for i in range(7)]


@pytest.mark.parametrize("gap", [0, 1, 2])
def test_own_writes_read_back_every_clock(gap, tmp_path):
    il, stim = tmp_path / "w.il", tmp_path / "w.csv"
    il.write_text(_write_back_program(gap))
    scans = 20
    _per_clock(stim, scans * 60, seed=11 + gap)
    rows = _harness_equals_reference(il, stim, WRITE_BACK_COLUMNS, scans)
    assert all(len({r[c] for r in rows}) == 2 for c in range(len(WRITE_BACK_COLUMNS))), rows


@pytest.mark.parametrize("mode", ["serial", "parallel"])
def test_output_edges_as_a_scans_first_reads(mode, tmp_path):
    """QR/QF of END's update read by the next scan's first two instructions."""
    il, stim = tmp_path / "e.il", tmp_path / "e.csv"
    il.write_text("LD QR1.0\nX QF1.1\n= Q0.0\nLD QF1.0\n= Q0.1\n"
                  "LD I0.0\n= Q1.0\nLD I0.1\n= Q1.1\n")
    scans = 24
    _per_scan(stim, scans, seed=5)
    extra = ["--mode", "parallel"] if mode == "parallel" else []
    rows = _harness_equals_reference(il, stim, ["Q0.0", "Q0.1"], scans, *extra)
    assert all(len({r[c] for r in rows}) == 2 for c in range(2)), rows
