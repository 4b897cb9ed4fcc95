"""`bitbyte` as a user runs it: a subprocess, exit codes, messages, files."""
from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "interlock.il"
EXAMPLE_STIM = ROOT / "examples" / "interlock.stim.csv"


def bitbyte(*args, cwd=None):
    proc = subprocess.run([sys.executable, "-m", "bitbyte.cli", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert "Traceback" not in proc.stderr, proc.stderr
    return proc


def test_asm_writes_image_listing_json(tmp_path):
    proc = bitbyte("asm", EXAMPLE, "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    words = (tmp_path / "interlock.hex").read_text().split()
    assert words[0] == "08001004"            # LD PI0.4
    assert words[-1] == "01000000"           # END
    listing = (tmp_path / "interlock.lst").read_text()
    assert "0000  08001004" in listing and "no_jog" in listing.lower()


@pytest.mark.parametrize("text,where,what", [
    ("  LD I0.0\n  FOO Q0.0\n", ":2:3:", "unknown mnemonic"),
    ("  LD I16.0\n", ":1:6:", "operand out of range"),
    ("  LD Nope\n", ":1:6:", "undeclared symbol"),
    ("  A(\n  A I0.0\n  )\n", ":2:3:", "not followed by LD/LDN"),
    ("  LD I0.0\n  A(\n  LD I0.1\n", ":2:3:", "unbalanced parentheses"),
    ("  JU nowhere\n", ":1:6:", "unknown label"),
    ("  = I0.0\n", ":1:5:", "wrong kind"),
    ("VAR\n  X1 AT I0.0;\n", ":1:1:", "missing END_VAR"),
    ("  LD I0.0\n  NOT I0.1\n", ":2:", "extra operand"),
    ("  LD I0.0 \x01\n", ":1:11:", "invalid byte"),
])
def test_errors_have_position_and_exit_1(tmp_path, text, where, what):
    src = tmp_path / "bad.il"
    src.write_bytes(text.encode("latin-1"))
    for cmd in (["asm", src], ["run", src, "--sim", "icarus"]):
        proc = bitbyte(*cmd)
        assert proc.returncode == 1
        first = proc.stderr.splitlines()[0]
        assert first.startswith(f"{src}{where}") and what in first, proc.stderr


def test_binary_garbage(tmp_path):
    src = tmp_path / "garbage.il"
    src.write_bytes(bytes(range(256)) * 4)
    proc = bitbyte("asm", src)
    assert proc.returncode == 1 and proc.stderr.startswith(f"{src}:1:1:")


def test_exchange_instructions_need_parallel_mode(tmp_path):
    src = tmp_path / "byte.il"
    src.write_text("  L 10\n  READ FBY 0\n")
    proc = bitbyte("run", src)
    assert proc.returncode == 1 and "parallel mode" in proc.stderr
    assert proc.stderr.startswith(f"{src}:2:3:")


@pytest.mark.parametrize("sim", ["icarus", "verilator"])
def test_worked_example_arithmetic(tmp_path, sim):
    """Spec §3 worked examples: MW0 = 7, Q0.0 = 1; MW1..MW4 = -1, -32768, -3, -1.
    Serial timing: the first instruction runs in the latch clock, END adds one."""
    src = tmp_path / "a.il"
    # 7 byte instructions (70) + `= Q0.0` (1) + END = 72
    src.write_text("L 10\nL 3\n-I\nT MW0\nL 5\nL 3\n>I\n= Q0.0\n")
    trace = tmp_path / "a.csv"
    proc = bitbyte("run", src, "--scans", 2, "--sim", sim, "--trace", trace, "--watch", "MW0")
    assert proc.returncode == 0, proc.stderr
    assert trace.read_text().splitlines() == [
        "scan,t_us,cycles,Q0.0,MW0", "0,0.72,72,1,7", "1,1.44,72,1,7"]
    src.write_text("L 16#FFFF\nT MW1\nL 32767\nL 1\n+I\nT MW2\nL -7\nL 2\n/I\nT MW3\n"
                   "L -7\nL 2\nMOD\nT MW4\n")       # 14 byte instructions: 140 + END
    proc = bitbyte("run", src, "--scans", 1, "--sim", sim, "--trace", trace,
                   "--watch", "MW1,MW2,MW3,MW4")
    assert proc.returncode == 0, proc.stderr
    assert trace.read_text().splitlines()[1] == "0,1.41,141,-1,-32768,-3,-1"


@pytest.mark.parametrize("sim", ["icarus", "verilator"])
def test_divide_by_zero_is_reported(tmp_path, sim):
    src = tmp_path / "d.il"
    src.write_text("L 5\nL 0\n/I\nT MW0\n")
    trace = tmp_path / "d.csv"
    proc = bitbyte("run", src, "--scans", 1, "--sim", sim, "--trace", trace, "--watch", "MW0")
    assert proc.returncode == 0, proc.stderr
    assert trace.read_text().splitlines()[1].endswith(",0")


def test_usage_errors_exit_2(tmp_path):
    assert bitbyte("run", EXAMPLE, "--scans", "0").returncode == 2
    assert bitbyte("run", EXAMPLE, "--clock-mhz", "fast").returncode == 2
    assert bitbyte("run", EXAMPLE, "--watch", "Q99.0").returncode == 2
    assert bitbyte("run", EXAMPLE, "--mode", "free", "--exchange", "handshake").returncode == 2
    assert bitbyte("run", EXAMPLE, "--mode", "parallel", "--exchange", "marker").returncode == 2
    assert bitbyte("frobnicate").returncode == 2


def test_missing_file(tmp_path):
    proc = bitbyte("run", tmp_path / "nope.il")
    assert proc.returncode == 1 and "nope.il" in proc.stderr


def test_icarus_and_verilator_traces_identical(tmp_path):
    traces, summaries = {}, {}
    for sim in ("icarus", "verilator"):
        trace = tmp_path / f"{sim}.csv"
        proc = bitbyte("run", EXAMPLE, "--stimulus", EXAMPLE_STIM, "--scans", 25,
                       "--sim", sim, "--trace", trace, "--watch", "Running,IF0.2,M0.1")
        assert proc.returncode == 0, proc.stderr
        assert "scans            25" in proc.stdout
        traces[sim] = trace.read_text()
        summaries[sim] = proc.stdout.splitlines()[:4]     # scans .. stalls
    assert traces["icarus"] == traces["verilator"]
    assert summaries["icarus"] == summaries["verilator"]
    lines = traces["icarus"].splitlines()
    assert lines[0] == "scan,t_us,cycles,Q0.0,Q0.1,Q0.2,Running,IF0.2,M0.1"
    assert len(lines) == 26


# Word logic that divides by zero (MW2 = 0): the byte side's ARITH flag; MW3 counts the
# byte side's scans (one +1 each), an independent count for `byte side N scans`.
SUMMARY_PROGRAM = """\
      LD    I0.0
      =     Q0.0
      L     MW3
      L     1
      +I
      T     MW3
      L     MW1
      L     MW2
      /I
      T     MW4
"""
# The bit side hands a condition to the byte side every 7-clock scan (the JCN), the
# byte side takes one per much longer scan: the free-running queue to the byte side
# overflows; nothing goes to the bit side.
QUEUE_PROGRAM = """\
      LD    I0.1
      =     Q0.1
      LD    I0.0
      JCN   skip
      L     MW3
      L     1
      +I
      T     MW3
skip: L     MW1
      L     MW2
      /I
      T     MW4
"""


def _summaries(tmp_path, program, *args, stop=("--until-us", 5)):
    src = tmp_path / "p.il"
    src.write_text(program)
    out = {}
    for sim in ("icarus", "verilator"):
        trace = tmp_path / f"{sim}.csv"
        proc = bitbyte("run", src, *stop, "--sim", sim, "--trace", trace,
                       "--watch", "MW3", *args)
        assert proc.returncode == 0, proc.stderr
        out[sim] = ([re.sub(r", [0-9.]+ M clocks/s wall$", "", line)
                     for line in proc.stdout.splitlines() if not line.startswith("trace ")],
                    trace.read_text())
    assert out["icarus"] == out["verilator"]          # the figures and the traces
    lines, trace = out["icarus"]
    return {line[:17].strip(): line[17:] for line in lines}, trace.splitlines()


@pytest.mark.parametrize("mode,exchange,extra,stop", [
    ("serial", None, [], ("--until-us", 5)),
    ("parallel", "queue", [], ("--until-us", 5)),
    ("free", "marker", ["byte side"], ("--until-us", 5)),
    # stops while the byte side announces a scan (SCAN_DONE in flight)
    ("free", "marker", ["byte side"], ("--scans", 41))])
def test_one_summary_for_every_simulator(tmp_path, mode, exchange, extra, stop):
    """The harness (its `stat` lines) and cocotb (its results) give the same figures,
    printed by one printer: the exchange statistics of the mode, the byte flags."""
    args = ["--mode", mode] + (["--exchange", exchange] if exchange else [])
    summary, trace = _summaries(tmp_path, SUMMARY_PROGRAM, *args, stop=stop)
    assert list(summary) == ["scans", "cycles/scan", "scan time [us]", "scan histogram",
                             "watchdog", "stalls", *extra, "byte flags", "simulated"]
    assert summary["byte flags"] == "ARITH (/I, MOD, /D or MODD by 0)"
    assert summary["scans"] == str(len(trace) - 1)
    if mode == "free":
        # the program's own count: MW3 + 1 in each byte scan, before the scan's end
        assert trace[0].endswith(",MW3")
        last_mw3 = int(trace[-1].rsplit(",", 1)[1])
        byte_scans = int(summary["byte side"].removesuffix(" scans (free-running)"))
        assert last_mw3 > 1 and byte_scans <= last_mw3 <= byte_scans + 1


def test_queue_losses_in_the_summary(tmp_path):
    summary, _ = _summaries(tmp_path, QUEUE_PROGRAM, "--mode", "free", "--exchange", "queue-free")
    m = re.fullmatch(r"overflows to-byte (\d+) to-bit (\d+), underflows to-byte (\d+) "
                     r"to-bit (\d+)", summary["queue losses"])
    assert m, summary["queue losses"]
    to_byte, to_bit, under_byte, under_bit = map(int, m.groups())
    bit_scans = int(summary["scans"])
    byte_scans = int(summary["byte side"].split()[0])
    # one condition written per bit scan, one read per byte scan, 8 slots: the rest lost
    assert bit_scans - byte_scans - 8 <= to_byte <= bit_scans - byte_scans + 1
    assert to_bit == 0 and under_bit == 0 and under_byte <= 1


@pytest.mark.parametrize("sim", ["icarus", "verilator"])
def test_fp_fn_worked_example(tmp_path, sim):
    """Spec §3 worked example: I0.0 = 1 in scans 0-2, 0 from scan 3:
    Q0.0 = 1 in scan 0 only, Q0.1 = 1 in scan 3 only."""
    src = tmp_path / "edges.il"
    src.write_text("LD I0.0\nFP M0.0\n= Q0.0\nLD I0.0\nFN M0.1\n= Q0.1\n")
    stim = tmp_path / "edges.csv"
    stim.write_text("scan,I0.0\n0,1\n3,0\n")
    trace = tmp_path / "t.csv"
    proc = bitbyte("run", src, "--stimulus", stim, "--scans", 6, "--sim", sim,
                   "--trace", trace)
    assert proc.returncode == 0, proc.stderr
    rows = [line.split(",") for line in trace.read_text().splitlines()]
    assert rows[0] == ["scan", "t_us", "cycles", "Q0.0", "Q0.1"]
    assert [r[3:] for r in rows[1:]] == [["1", "0"], ["0", "0"], ["0", "0"],
                                         ["0", "1"], ["0", "0"], ["0", "0"]]
    assert [r[2] for r in rows[1:]] == ["7"] * 6          # 6 instructions + END
    assert rows[1][1] == "0.07" and rows[6][1] == "0.42"


def case_files(tmp_path, program: str, stimulus: str):
    """t.il and s.csv written; returns their paths and the trace path t.csv."""
    src, stim = tmp_path / "t.il", tmp_path / "s.csv"
    src.write_text(program)
    stim.write_text(stimulus)
    return src, stim, tmp_path / "t.csv"


# Response time (spec §4: the summary's "response-time figures where inputs changed";
# the definition in docs/toolchain.md). Six bit instructions, two word instructions
# and END: 27 clocks a scan, scan k latches at clock 27k and ends at 27(k+1). Q0.0
# follows I0.0 in the same scan (one scan: 27 clocks); Q0.1 follows I0.1 one scan late
# through M0.0 (two scans: 54 clocks); I0.2 drives nothing.
RESPONSE_PROGRAM = """\
      LD    I0.0
      =     Q0.0
      LD    M0.0
      =     Q0.1
      LD    I0.1
      =     M0.0
      L     MW0
      T     MW1
"""
# change (latch clock) -> the first scan end after it with an output change:
#  scan 2 I0.0 up (54)    -> Q0.0 at the end of scan 2 (81):   27
#  scan 4 I0.1 up (108)   -> Q0.1 at the end of scan 5 (162):  54
#  scan 7 I0.0 down (189) -> Q0.0 at the end of scan 7 (216):  27
#  scan 8: the same inputs, no change
#  scan 9 I0.2 up (243)   -> no output changes before the next change (270): none
#  scan 10 I0.1 down (270)-> Q0.1 at the end of scan 11 (324): 54
#  scan 12 I0.0 up (324)  -> Q0.0 at the end of scan 12 (351): 27
#  scan 13 I0.0 down (351)-> Q0.0 at the end of scan 13 (378), the run's last: 27
#  scan 14: not run, not counted
RESPONSE_SCAN_STIM = """\
scan,I0.0,I0.1,I0.2
0,0,0,0
2,1,0,0
4,1,1,0
7,0,1,0
8,0,1,0
9,0,1,1
10,0,0,1
12,1,0,1
13,0,0,1
14,1,1,1
"""
# t_us rows, measured from the moment itself (a fraction of a clock at 100 MHz):
#  0: scan 0 latches it, Q0.0 up at its end (27) -- against the reset value 0:      27
#  1.005 us = clock 100.5: latched by scan 4 (108), Q0.0 down at its end (135):    34.5
#  2 us = clock 200: latched by scan 8 (216), Q0.0 up at its end (243):              43
#  2.43 us = clock 243 = scan 9's latch, Q0.0 down at its end (270):                 27
#  2.75 us = clock 275, in scan 10: latched by scan 11 (297), Q0.0 up at 324:        49
#  3.24 us = clock 324, the last scan's latch: I0.2 up, no output changes:        none
#  3.3 us: after the last completed scan latched, not counted
RESPONSE_TIME_STIM = """\
t_us,I0.0,I0.2
0,1,0
1.005,0,
2,1,
2.43,0,
2.75,1,
3.24,,1
3.3,0,
"""


@pytest.mark.parametrize("sim", ["icarus", "verilator"])
def test_response_figures_in_the_summary(tmp_path, sim):
    src, stim, _ = case_files(tmp_path, RESPONSE_PROGRAM, RESPONSE_SCAN_STIM)
    proc = bitbyte("run", src, "--stimulus", stim, "--scans", 14, "--sim", sim)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert "cycles/scan      min 27  mean 27  max 27" in lines
    assert ("response [clk]   min 27  median 27  max 54  (6 of 7 input changes changed "
            "an output)") in lines, proc.stdout
    assert "response [us]    min 0.27  median 0.27  max 0.54" in lines, proc.stdout
    stim.write_text(RESPONSE_TIME_STIM)
    proc = bitbyte("run", src, "--stimulus", stim, "--scans", 13, "--sim", sim)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert ("response [clk]   min 27  median 34.5  max 49  (5 of 6 input changes changed "
            "an output)") in lines, proc.stdout
    assert "response [us]    min 0.27  median 0.345  max 0.49" in lines, proc.stdout
    # no input change (no stimulus): no response lines
    proc = bitbyte("run", src, "--scans", 2, "--sim", sim)
    assert proc.returncode == 0 and "response" not in proc.stdout, proc.stdout



# Causal attribution (issue 15 review): a change is answered by the first scan, ending
# after it, whose outputs differ from the reference run with that change withheld.
# RESPONSE_PROGRAM at 100 MHz: scan k latches at 27k, ends at 27(k+1).
#  0.54 us = clock 54 = scan 2's latch, I0.0 up: Q0.0 up at the end of scan 2 (81):  27
#    (scan 1 latched at 27, before it: it cannot answer it)
#  0.60 us = clock 60, in scan 2, I0.1 up: latched by scan 3 (81), M0.0 in scan 3,
#    Q0.1 up at the end of scan 4 (135), later than any other change:               75
RESPONSE_OVERLAP_STIM = "t_us,I0.0,I0.1\n0.54,1,0\n0.60,1,1\n"
#  I0.1 toggles every scan 0..5: each toggle reaches Q0.1 at the end of the scan after
#  the one that latched it, 54 clocks, although the next toggle comes 27 clocks later
#  and Q0.1 changes every scan (8 scans: the last toggle, scan 5's, shows in scan 6)
RESPONSE_TOGGLE_STIM = "scan,I0.1\n0,1\n1,0\n2,1\n3,0\n4,1\n5,0\n"
# A direct read answers in the scan that holds the change: NOP NOP LD PI0.0 = Q0.0 END,
# 5 clocks a scan (latch 5k, the PI read at 5k+2, end 5k+5).
#  0.06 us = clock 6, before scan 1's read (7): Q0.0 up at its end (10):              4
#  0.18 us = clock 18, after scan 3's read (17): scan 4 reads it (22), ends at 25:    7
DIRECT_PROGRAM = "NOP\nNOP\nLD PI0.0\n= Q0.0\n"
DIRECT_STIM = "t_us,I0.0\n0.06,1\n0.18,0\n"
# A word read every other scan: M0.0 toggles, a taken JCN skips L IW0 / T QW0 in odd
# scans (3 + 3 + NOP + END = 8 clocks; even scans 1+1+1+1+10+10+1+1 = 26).  IW0 changes
# at scan 1 (latch 26), which skips it; scan 2 (34..60) copies it to QW0: 60 - 26 = 34
# (scan 1 leaves the same state with or without the change: not yet a verdict).
SKIPPED_READ_PROGRAM = "LD M0.0\nNOT\n= M0.0\nJCN skip\nL IW0\nT QW0\nskip: NOP\n"
SKIPPED_READ_STIM = "scan,IW0\n1,5\n"


# In parallel mode (22 clocks a scan, the run's own figure) both RESPONSE_OVERLAP_STIM
# changes fall in scan 2 (44..66) and scan 3 latches both: I0.0 reaches Q0.0 at its
# end (88): 34; I0.1 reaches Q0.1 at the end of scan 4 (110): 50.  (Withheld, I0.0
# stays 0 although the next row, which scan 3 latches too, holds it at 1.)
PARALLEL_CYCLES = "cycles/scan      min 22  mean 22  max 22"


@pytest.mark.parametrize("program,stimulus,scans,clk,us,more", [
    (RESPONSE_PROGRAM, RESPONSE_OVERLAP_STIM, 8,
     "min 27  median 51  max 75  (2 of 2", "min 0.27  median 0.51  max 0.75", ()),
    (RESPONSE_PROGRAM, RESPONSE_TOGGLE_STIM, 8,
     "min 54  median 54  max 54  (6 of 6", "min 0.54  median 0.54  max 0.54", ()),
    (DIRECT_PROGRAM, DIRECT_STIM, 6,
     "min 4  median 5.5  max 7  (2 of 2", "min 0.04  median 0.055  max 0.07", ()),
    (SKIPPED_READ_PROGRAM, SKIPPED_READ_STIM, 4,
     "min 34  median 34  max 34  (1 of 1", "min 0.34  median 0.34  max 0.34", ()),
    (RESPONSE_PROGRAM, RESPONSE_OVERLAP_STIM, 8,
     "min 34  median 42  max 50  (2 of 2", "min 0.34  median 0.42  max 0.5",
     ("--mode", "parallel"))])
def test_response_is_the_scan_the_change_caused(tmp_path, program, stimulus, scans, clk, us,
                                                more):
    src, stim, _ = case_files(tmp_path, program, stimulus)
    proc = bitbyte("run", src, "--stimulus", stim, "--scans", scans, *more)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    if more:
        assert PARALLEL_CYCLES in lines, proc.stdout
    assert f"response [clk]   {clk} input changes changed an output)" in lines, proc.stdout
    assert f"response [us]    {us}" in lines, proc.stdout


def test_response_not_measured_in_free_running_mode(tmp_path):
    """The byte side's scans are not the reference's: no figure rather than a wrong one."""
    src, stim, _ = case_files(tmp_path, RESPONSE_PROGRAM, RESPONSE_TOGGLE_STIM)
    proc = bitbyte("run", src, "--stimulus", stim, "--scans", 8, "--mode", "free")
    assert proc.returncode == 0, proc.stderr
    assert ("response [clk]   not measured in free-running mode (6 input changes)"
            in proc.stdout.splitlines()), proc.stdout
    assert "response [us]" not in proc.stdout, proc.stdout


def test_response_measuring_stops_at_its_budget(tmp_path):
    """The reference replay is bounded: the summary says how many changes it measured
    and why no more.  RESPONSE_TOGGLE_STIM's first change is answered in scan 1 (54);
    the reference replays scans 0 and 1 (54 clocks) and the counterfactual the same
    (108) before the second change's first scan: a 100-clock budget ends there.  The
    reference's own records stand for the hardware's (serial mode: the same clocks)."""
    from bitbyte.ref.refsim import refsim_trace
    from bitbyte.run.prepare import prepare
    from bitbyte.run.response import response_times
    from bitbyte.run.summary import RunStats, summary_text
    src, stim, _ = case_files(tmp_path, RESPONSE_PROGRAM, RESPONSE_TOGGLE_STIM)
    prep = prepare(str(src), stimulus=str(stim), scans=8)
    _, records, _ = refsim_trace(prep.program, prep.config, prep.stimulus, scans=8)
    for kwargs, count in (
            (dict(replay_clocks=100), "(1 of the first 1 of 6 input changes changed an "
             "output; the reference replays at most 100 clocks)"),
            (dict(max_changes=3), "(3 of the first 3 of 6 input changes changed an "
             "output; at most 3 changes are measured)")):
        text = summary_text(records, prep.f, RunStats(clocks=216),
                            response=response_times(prep, records, **kwargs))
        assert f"response [clk]   min 54  median 54  max 54  {count}\n" in text, text


def test_response_median_of_an_even_count():
    """The median of an even count is the mean of the middle two; none at all: '-'."""
    from fractions import Fraction
    from bitbyte.run.response import Responses
    from bitbyte.run.summary import RunStats, summary_text
    text = summary_text([], Fraction(50), RunStats(clocks=0), response=Responses(
        [Fraction(40), Fraction(10), Fraction(31), Fraction(20)], 5))
    assert "response [clk]   min 10  median 25.5  max 40  (4 of 5 input changes changed " \
           "an output)\nresponse [us]    min 0.2  median 0.51  max 0.8\n" in text
    text = summary_text([], Fraction(50), RunStats(clocks=0), response=Responses([], 2))
    assert "response [clk]   -  (0 of 2 input changes changed an output)\n" \
           "response [us]    -\n" in text

@pytest.mark.parametrize("sim", ["icarus", "verilator"])
def test_watchdog(tmp_path, sim):
    src, stim, trace = case_files(tmp_path, "SET\n= Q0.0\nLD I0.0\nspin: JC spin\n",
                                  "scan,I0.0\n0,0\n2,1\n")
    proc = bitbyte("run", src, "--stimulus", stim, "--scans", 5, "--watchdog", 50,
                   "--sim", sim, "--trace", trace)
    assert proc.returncode == 3
    assert "scan watchdog" in proc.stderr
    # SET, = Q0.0, LD I0.0, JC (not taken), END: 5 clocks while I0.0 = 0
    assert trace.read_text().splitlines()[1:] == ["0,0.05,5,1", "1,0.1,5,1"]


@pytest.mark.parametrize("sim", ["icarus", "verilator"])
def test_until_us_and_time_stimulus(tmp_path, sim):
    """t_us rows: I sees a change at the first latch at or after it; PI at once."""
    # scans are 9 clocks = 0.09 us (scan k latches in clock 9k, LD PI0.0 runs in 9k+4);
    # the pin rises at 0.21 us = clock 21: after scan 2's latch (18), before its LD PI
    src, stim, trace = case_files(tmp_path,
                                  "NOP\nNOP\nNOP\nNOP\nLD PI0.0\n= Q0.0\nLD I0.0\n= Q0.1\n",
                                  "t_us,I0.0\n0.21,1\n")
    proc = bitbyte("run", src, "--stimulus", stim, "--until-us", "0.4", "--sim", sim,
                   "--trace", trace)
    assert proc.returncode == 0, proc.stderr
    assert trace.read_text().splitlines()[1:] == [      # until the scan ending >= 40
        "0,0.09,9,0,0", "1,0.18,9,0,0", "2,0.27,9,1,0", "3,0.36,9,1,1", "4,0.45,9,1,1"]


def test_profile_checks_the_program_against_its_sizes(tmp_path):
    """`--profile hx8k` (definition.toml [profiles], the HX8K build of docs/synthesis.md):
    an IW past the profile's and a program longer than its memory are rejected with
    file:line:col, the default build takes both; the Table-1-sized bench program fits."""
    iw = tmp_path / "iw.il"
    iw.write_text("  L IW8\n  T QW0\n")
    big = tmp_path / "big.il"
    big.write_text("  NOP\n" * 2049)
    for prog, where, what in ((iw, "iw.il:1:5:", "IW8"), (big, "big.il:2049:3:", "2048")):
        assert bitbyte("asm", prog, "-o", tmp_path).returncode == 0
        proc = bitbyte("asm", prog, "--profile", "hx8k", "-o", tmp_path)
        assert proc.returncode == 1 and where in proc.stderr and what in proc.stderr, proc.stderr
    proc = bitbyte("run", iw, "--profile", "hx8k", "--scans", "1")
    assert proc.returncode == 1 and "iw.il:1:5:" in proc.stderr
    proc = bitbyte("asm", ROOT / "bench" / "programs" / "table1.il", "--profile", "hx8k",
                   "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert bitbyte("asm", iw, "--profile", "nosuch").returncode == 2
