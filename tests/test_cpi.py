"""CPI 1.00: a 1 000-instruction straight-line bit program over every operand area (I,
IR, IF, PI, Q, M, T, C, parentheses, `= M` and `= Q` read back by the next instruction) runs on
the Verilator harness in exactly N + 1 clocks per scan (N instructions, one clock each,
plus END), counted from the trace's cycles column against the program's own length,
not taken from the reference model. The outputs are compared with the reference
interpreter as well (the forwarding of Q and M writes to the instructions in flight)."""
from __future__ import annotations

import csv

from bitbyte import cli
from bitbyte.lang.config import Config
from bitbyte.lang.parser import parse_file
from bitbyte.lang.stimulus import load_stimulus
from bitbyte.ref.refsim import refsim_trace

BLOCK = """LD I0.0
A IR0.1
O IF0.2
AN PI0.3
= M1.0
LD M1.0
X Q0.1
= Q0.2
A(
LD T1
O C2
)
= M1.1
LDN M1.1
A M1.0
O(
LD Q0.2
XN I0.5
)
= Q0.3
S M2.0
LD M2.0
= Q0.1
R M2.0
ON M2.0""".splitlines()
# Once a scan: Q0.4 toggles and is read back by the very next instruction (the `= Q`
# forwarding: a stale read gives the old, opposite value and Q0.5 = 0), then filler.
TOGGLE = ["LDN Q0.4", "= Q0.4", "A Q0.4", "= Q0.5"] + ["LD I0.1"] * 21
BLOCKS = 39                               # 25 x 39 + 25 = 1000 instructions
WATCH = ["Q0.1", "Q0.2", "Q0.3", "Q0.4", "Q0.5", "M1.0", "M1.1", "M2.0"]
SCANS = 6


def test_straight_line_bit_code_runs_at_one_instruction_per_clock(tmp_path):
    lines = BLOCK * BLOCKS + TOGGLE
    n = len(lines)
    assert n == 1000
    src = tmp_path / "cpi.il"
    src.write_text("\n".join(lines) + "\n")
    stim = tmp_path / "cpi.stim.csv"      # the inputs change from scan to scan
    stim.write_text("scan,I0.0,I0.1,I0.2,I0.3,I0.5\n0,1,1,0,0,1\n1,0,1,1,1,0\n"
                    "2,1,0,1,0,1\n3,1,1,0,1,1\n4,0,0,0,1,0\n")
    trace = tmp_path / "t.csv"
    argv = ["run", str(src), "--stimulus", str(stim), "--clock-mhz", "100", "--scans",
            str(SCANS), "--watch", ",".join(WATCH), "--trace", str(trace)]
    assert cli.main(argv) == 0
    with open(trace, newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == SCANS
    assert [int(r["cycles"]) for r in rows] == [n + 1] * SCANS    # CPI 1.00
    assert [int(r["Q0.5"]) for r in rows] == [1, 0] * (SCANS // 2)  # by hand: the toggle

    program = parse_file(str(src))
    stimulus = load_stimulus(str(stim), program.symbols)
    stimulus.clock_mhz = 100.0
    _, records, fault = refsim_trace(program, config=Config(clock_mhz=100.0),
                                     stimulus=stimulus, watch=WATCH, scans=SCANS)
    assert not fault
    for row, rec in zip(rows, records):
        for name in WATCH:
            assert int(row[name]) == rec.values[name], (row["scan"], name)
