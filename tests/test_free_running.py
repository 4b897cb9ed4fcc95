"""Free-running mode (paper section 4.3, Fig. 17): each processor loops over its own
part; conditions travel through the marker area (snapshots at the reader's scan
start) or the free-running queues. Nobody waits, so bit-only logic keeps the bit
processor's short scan; a condition that crosses sides arrives at the latest in the
reader's next complete scan."""
from __future__ import annotations

import pytest

from bitbyte import cli
# Bit-only logic (I0.1 -> Q0.1) next to slow word logic; I0.0 crosses to the byte side
# (the jump over word code carries it), which counts it into MW0 (+1 per byte scan
# while I0.0 = 1).
PROGRAM = """\
      LD    I0.1
      =     Q0.1
      LD    I0.0
      JCN   skip
      L     MW0
      L     1
      +I
      T     MW0
skip: L     MW1
      L     MW2
      *I
      T     MW3
      L     MW1
      L     MW2
      *I
      T     MW3
"""


def run(tmp_path, sim, mode, exchange=None, stim="t_us,I0.0,I0.1\n0.3,1,1\n"):
    il = tmp_path / "p.il"
    il.write_text(PROGRAM)
    st = tmp_path / "s.csv"
    st.write_text(stim)
    trace = tmp_path / f"{mode}.csv"
    argv = ["run", str(il), "--mode", mode, "--sim", sim, "--stimulus", str(st),
            "--until-us", "3", "--trace", str(trace), "--watch", "MW0"]
    if exchange:
        argv += ["--exchange", exchange]
    assert cli.main(argv) == 0
    rows = [line.split(",") for line in trace.read_text().splitlines()[1:]]
    return [(float(r[1]), int(r[2]), int(r[3]), int(r[4])) for r in rows]  # t, cycles, Q0.1, MW0


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
@pytest.mark.parametrize("exchange", ["marker", "queue-free"])
def test_bit_only_logic_is_fast_and_crossing_is_bounded(tmp_path, sim, exchange):
    serial = run(tmp_path, sim, "serial")
    free = run(tmp_path, sim, "free", exchange)
    serial_scan = max(c for _, c, _, _ in serial)
    free_scan = max(c for _, c, _, _ in free)
    # the bit processor's scan no longer contains the word instructions
    assert free_scan * 5 <= serial_scan, (free_scan, serial_scan)

    def first(rows, pred):
        return next(t for t, _, q, mw in rows if pred(q, mw))
    # response of the bit-only path (I0.1 -> Q0.1, change at 0.3 us): at least 5x
    # shorter in the worst case = two of its own scans
    assert first(free, lambda q, mw: q == 1) - 0.3 <= 2 * free_scan / 100
    assert first(serial, lambda q, mw: q == 1) - 0.3 <= 2 * serial_scan / 100
    # the crossing condition: I0.0 (latched by the bit side within one bit scan,
    # written to the exchange in the same scan) is taken by the byte side at its
    # next scan start and used in that complete scan; we see MW0 at bit-scan ends.
    byte_scan = 3 + 10 * 12 + 1          # upper bound of one byte-side scan, clocks
    bound_us = (2 * free_scan + 2 * byte_scan + free_scan) / 100
    assert first(free, lambda q, mw: mw > 0) - 0.3 <= bound_us


TWO_COMPARES = "L IW0\nL 0\n>I\n= Q0.0\nL IW1\nL 0\n>I\n= Q0.1\n"


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
@pytest.mark.parametrize("exchange", ["marker", "queue-free"])
def test_first_instruction_uses_the_exchange(tmp_path, sim, exchange):
    """The bit part starts with `LD FBI k` (a compare's result): it runs in the latch
    clock, where the free-running queue's pointer is already back at slot 0 and the
    marker snapshot is the one being taken (review finding: the queue read the old
    slot and swapped the two conditions for good)."""
    il = tmp_path / "c.il"
    il.write_text(TWO_COMPARES)
    st = tmp_path / "c.csv"
    st.write_text("scan,IW0,IW1\n0,1,0\n")
    trace = tmp_path / "c.trace.csv"
    assert cli.main(["run", str(il), "--mode", "free", "--exchange", exchange, "--sim", sim,
                     "--stimulus", str(st), "--scans", "30", "--trace", str(trace)]) == 0
    last = trace.read_text().splitlines()[-5:]
    assert all(line.endswith(",1,0") for line in last), last      # Q0.0 = 1, Q0.1 = 0


def test_marker_needs_a_cell_per_condition(tmp_path):
    il = tmp_path / "m.il"
    il.write_text(TWO_COMPARES * 3)
    assert cli.main(["run", str(il), "--mode", "free", "--channels", "4"]) == cli.EXIT_SOURCE
    assert cli.main(["run", str(il), "--mode", "free", "--exchange", "queue-free"]) == 0


# The byte side counts its scans in MW0 and works out "MW0 is even" (RLO)
COUNT_AND_PARITY = """\
      L     MW0
      L     1
      +I
      T     MW0
      L     MW0
      L     2
      MOD
      L     0
      ==I
"""

# ... and hands it to the bit side twice in one scan, word work between the two
# crossings; the bit side sets Q0.0 for good when the two disagree, i.e. when its
# snapshot holds one crossing of a byte scan and not the other, and shows the first
# in Q0.1.
TWO_OF_ONE_SCAN = COUNT_AND_PARITY + """\
      =     M0.0
      L     MW1
      L     MW2
      *I
      T     MW3
      L     MW0
      L     2
      MOD
      L     0
      ==I
      =     M0.1
      LD    M0.0
      X     M0.1
      S     Q0.0
      LD    M0.0
      =     Q0.1
"""


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
def test_marker_write_buffer_gives_whole_scans(tmp_path, sim):
    """--marker-write-buffer (issue 16 item 2): without it the bit side's snapshot,
    taken at its scan start (every 10 clocks here), falls between the byte side's two
    WRITE FBI of one scan (40 clocks of word work apart) and mixes them: Q0.0 goes to 1.
    With it the byte side publishes at its scan end, and no snapshot ever mixes; the
    conditions still arrive (Q0.1 follows MW0's parity both ways)."""
    il = tmp_path / "w.il"
    il.write_text(TWO_OF_ONE_SCAN)
    rows = {}
    for wb in (False, True):
        trace = tmp_path / f"w{int(wb)}.csv"
        argv = ["run", str(il), "--mode", "free", "--sim", sim, "--scans", "300",
                "--trace", str(trace), "--watch", "MW0"]
        assert cli.main(argv + (["--marker-write-buffer"] if wb else [])) == 0
        assert trace.read_text().splitlines()[0] == "scan,t_us,cycles,Q0.0,Q0.1,MW0"
        rows[wb] = [[int(v) for v in line.split(",")[3:]]
                    for line in trace.read_text().splitlines()[1:]]
    for wb in (False, True):
        assert rows[wb][-1][2] >= 8                          # byte scans went by
        assert {q1 for _, q1, _ in rows[wb]} == {0, 1}       # the conditions arrive
    assert rows[False][-1][0] == 1                           # a mixed snapshot
    assert all(q0 == 0 for q0, _, _ in rows[True])           # whole scans only


def test_marker_write_buffer_needs_the_marker_exchange(tmp_path, capsys):
    il = tmp_path / "w.il"
    il.write_text(TWO_OF_ONE_SCAN)
    for extra in (["--mode", "free", "--exchange", "queue-free"], ["--mode", "parallel"]):
        assert cli.main(["run", str(il), "--marker-write-buffer", *extra]) == cli.EXIT_USAGE
        assert "--marker-write-buffer" in capsys.readouterr().err


# 100 conditions cross each way in one scan (issue 16 item 2: the marker area in block
# RAM, 128 cells a direction): input k goes to the byte side (the jump over word code
# carries it), which writes it into MW k and hands `MW k > 0` back for Q k. Every
# crossing has a cell of its own (the 4 flip-flop cells of before refused this).
CROSSINGS = 100


def round_trip_program(n: int) -> str:
    lines = []
    for k in range(n):
        pin = f"{k // 8}.{k % 8}"
        lines += [f"      LD    I{pin}", f"      JCN   z{k}", "      L     1", f"      T     MW{k}",
                  f"      JU    d{k}", f"z{k}:  L     0", f"      T     MW{k}",
                  f"d{k}:  L     MW{k}", "      L     0", "      >I", f"      =     Q{pin}"]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
def test_marker_area_carries_100_crossings_each_way(tmp_path, sim, capsys):
    """Each crossing is seen within the reader's next complete scan, both ways:
    bit -> byte, the bit side latches input k and writes its cell within two of its
    scans, the byte side takes the cell at its next scan start and writes MW k in
    that scan (two byte scans; one bit scan more to see MW k in the trace, whose rows
    are bit-scan ends); byte -> bit, the compare's cell is written a few word
    instructions after MW k in the same byte scan, the bit side takes it at its next
    scan start and writes Q k in that scan (two bit scans, one more to see it)."""
    n = CROSSINGS
    il = tmp_path / "rt.il"
    il.write_text(round_trip_program(n))
    pattern = [int(k % 3 == 0) for k in range(n)]
    change_us, end_us = 200, 400
    pins = [f"I{k // 8}.{k % 8}" for k in range(n)]
    st = tmp_path / "rt.csv"
    st.write_text("t_us," + ",".join(pins) + "\n0," + ",".join(map(str, pattern)) +
                  f"\n{change_us}," + ",".join(str(1 - v) for v in pattern) + "\n")
    trace = tmp_path / "rt.trace.csv"
    outs = [f"Q{k // 8}.{k % 8}" for k in range(n)]
    words = [f"MW{k}" for k in range(n)]
    assert cli.main(["run", str(il), "--mode", "free", "--exchange", "marker", "--sim", sim,
                     "--stimulus", str(st), "--until-us", str(end_us), "--trace", str(trace),
                     "--watch", ",".join(outs + words)]) == 0
    out = capsys.readouterr().out
    byte_scans = int(out.split("\nbyte side", 1)[1].split()[0])     # its summary line
    rows = [line.split(",") for line in trace.read_text().splitlines()[1:]]
    t = [float(r[1]) for r in rows]
    bit_scan = max(int(r[2]) for r in rows) / 100                      # us at 100 MHz
    # the byte side's scans are alike (each crossing one of two short paths): their
    # mean over the run, with a tenth for the difference
    byte_scan = 1.1 * end_us / byte_scans
    to_byte = 2 * bit_scan + 2 * byte_scan + bit_scan
    to_bit = 0.5 + 2 * bit_scan + bit_scan       # (0.5 us: the word instructions between)
    assert byte_scans >= 5 and to_byte + to_bit < change_us, (byte_scans, to_byte, to_bit)

    def settled(col: int, t0: float, want: int) -> float:
        """When column `col` took `want` for good after t0 (until the next change)."""
        seen = None
        for i, ti in enumerate(t):
            if t0 <= ti < t0 + change_us:
                if int(rows[i][col]) != want:
                    seen = None
                elif seen is None:
                    seen = ti
        assert seen is not None, (col, t0)
        return seen
    for t0, want in ((0, pattern), (change_us, [1 - v for v in pattern])):
        for k in range(n):
            t_mw = settled(3 + n + k, t0, want[k])
            t_q = settled(3 + k, t0, want[k])
            assert t_mw - t0 <= to_byte, (words[k], t0, t_mw)
            assert t_q - t_mw <= to_bit, (outs[k], t0, t_q, t_mw)
            assert t_q + 3 * bit_scan < t0 + change_us      # and stays so for a while


# The byte side flips FBI 0 and FBI 1 every scan (its scans are a few bit scans long);
# the bit side reads each twice in one scan, NOPs between, and sets Q0.0 / Q0.1 for
# good if the two reads of a scan differ: they never may, its snapshot is taken once,
# at its scan start (review finding: with the snapshot a clock late, at the latch, the
# first instruction's read, made a clock early, saw the old one).
ONE_SNAPSHOT = """\
BIT:
      LD    FBI 0
      =     M0.0
      LD    FBI 1
      =     M0.1
      NOP
      NOP
      LD    FBI 0
      X     M0.0
      S     Q0.0
      LD    FBI 1
      X     M0.1
      S     Q0.1
      LD    FBI 0
      =     Q0.2
BYTE:
""" + COUNT_AND_PARITY + """\
      WRITE FBI 0
      WRITE FBI 1
"""


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
def test_marker_bit_side_reads_one_snapshot_per_scan(tmp_path, sim):
    il = tmp_path / "snap.il"
    il.write_text(ONE_SNAPSHOT)
    trace = tmp_path / "snap.trace.csv"
    assert cli.main(["run", str(il), "--mode", "free", "--exchange", "marker", "--sim", sim,
                     "--scans", "200", "--trace", str(trace), "--watch", "Q0.0,Q0.1,Q0.2"]) == 0
    rows = [line.split(",")[3:] for line in trace.read_text().splitlines()[1:]]
    assert all(r[0] == "0" and r[1] == "0" for r in rows)          # never two snapshots
    q2 = [r[2] for r in rows]
    assert sum(a != b for a, b in zip(q2, q2[1:])) >= 20             # the cells do change
