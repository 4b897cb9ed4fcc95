"""`bitbyte run PLANT.toml` against the letter of spec §7 (and §3/§4 where §7 refers
to them). Each test is a small plant at a slow clock; every one of them is a
deviation found in review (see the docstrings) and fails until it is fixed.
"""
from __future__ import annotations

import csv
import re
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# A core that only reads a shared bit, and the core that writes it: the smallest
# legal plant (a READ needs a writer).
WRITER = """VAR_GLOBAL
  G AT M0.0 : WRITE;
END_VAR
  LD I0.0
  = G
"""


def _bitbyte(*args, cwd):
    return subprocess.run([sys.executable, "-m", "bitbyte.cli", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd)


def _plant(tmp: Path, program: str, *, period_us: int, clock_mhz="1",
           stimulus: str | None = None, stim_name="a.stim.csv") -> Path:
    (tmp / "a.il").write_text(program)
    (tmp / "g.il").write_text(WRITER)
    stim_line = ""
    if stimulus is not None:
        path = tmp / stim_name
        if isinstance(stimulus, bytes):
            path.write_bytes(stimulus)
        else:
            path.write_text(stimulus)
        stim_line = f'stimulus = "{stim_name}"\n'
    plant = tmp / "plant.toml"
    plant.write_text(f"clock_mhz = {clock_mhz}\n"
                     f'[[core]]\nname = "a"\nprogram = "a.il"\nperiod_us = {period_us}\n'
                     + stim_line +
                     '[[core]]\nname = "b"\nprogram = "g.il"\nperiod_us = 100000\n')
    return plant


def _rows(path: Path) -> list[dict[str, str]]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def _start_us(row, clock_mhz) -> Fraction:
    """Start of a scan's precycle: t_us (end of the postcycle) minus its clocks."""
    clocks = int(row["pre"]) + int(row["cycles"]) + int(row["post"])
    return Fraction(row["t_us"]) - Fraction(clocks) / Fraction(clock_mhz)


READER = """VAR_GLOBAL
  G AT M5.0 : READ;
END_VAR
  LD PI0.0
  = Q0.0
  L IW0
  T QW0
"""


def test_scan_stimulus_watched_pins_are_the_scans_own(tmp_path):
    """§4: a `scan` row applies from the PII latch of that scan, and a trace row holds
    the values after that scan's PIO update. The plant harness applies row k+1 at
    scan k's PIO update (before its postcycle) and samples the row after the
    postcycle, so scan k's watched PI / IW show scan k+1's pins (the single-CPU
    trace of the same program and stimulus shows the scan's own)."""
    stim = "scan,I0.0,IW0\n0,0,5\n1,1,6\n2,0,7\n"
    plant = _plant(tmp_path, READER, period_us=100, stimulus=stim)
    r = _bitbyte("run", plant, "--until-us", "300", "--trace", tmp_path / "T.csv",
                 "--watch", "a.PI0.0,a.IW0", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rows = _rows(tmp_path / "T.a.csv")
    want = {0: ("0", "5"), 1: ("1", "6"), 2: ("0", "7"), 3: ("0", "7")}
    got = {int(row["scan"]): (row["PI0.0"], row["IW0"]) for row in rows}
    assert got == want
    # and the program's own view agrees (Q0.0 := PI0.0, QW0 := IW0 in the scan)
    assert all((row["Q0.0"], row["QW0"]) == got[int(row["scan"])] for row in rows)


def test_waves_vcd_is_a_vcd(tmp_path):
    """§4 `--waves FILE.fst|.vcd` (§7 `--waves FILE`): a single CPU writes a VCD for
    `.vcd` (fst2vcd); the plant harness writes FST bytes under the .vcd name."""
    plant = _plant(tmp_path, READER, period_us=100)
    waves = tmp_path / "plant.vcd"
    r = _bitbyte("run", plant, "--until-us", "10", "--waves", waves, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    head = waves.read_bytes()[:64]
    assert head.lstrip().startswith(b"$"), f"not a VCD: {head!r}"


def test_non_utf8_stimulus_is_an_error_not_a_traceback(tmp_path):
    """Bad input on the plant path ends as `file:line:col: message` and a non-zero
    exit, never a traceback. A stimulus file with a non-UTF-8 byte raises
    UnicodeDecodeError out of stimulus.load_stimulus (the single-CPU path too)."""
    plant = _plant(tmp_path, READER, period_us=100,
                   stimulus=b"scan,I0.0\n0,\xff\n")
    r = _bitbyte("run", plant, "--until-us", "10", cwd=tmp_path)
    assert r.returncode != 0
    assert "Traceback" not in r.stderr, r.stderr
    assert "a.stim.csv:2:3" in r.stderr, r.stderr


def test_timer_now_is_plant_time(tmp_path):
    """§3 Timers: now = floor(t / 1 ms), t the simulated time since reset at which the
    timer instruction executes; §7: core c's scan k starts (precycle) at k·period.
    Scan 1 starts at 985 us, its precycle takes 8 clocks, SET 1 and `L T#10s` 10
    more: SD T0 executes at t = 1004 us, now = 1, while scan 0's SD (t = 19 us)
    started the timer at now = 0, so `L T0` loads elapsed 1. The plant starts each
    core's time base at its own first PII latch (8 us late), giving 0."""
    program = """VAR_GLOBAL
  G AT M5.0 : READ;
END_VAR
  SET
  L T#10s
  SD T0
  L T0
  T MW200
"""
    plant = _plant(tmp_path, program, period_us=985)
    r = _bitbyte("run", plant, "--until-us", "1500", "--trace", tmp_path / "T.csv",
                 "--watch", "a.MW200", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rows = _rows(tmp_path / "T.a.csv")
    s1 = rows[1]
    latch = _start_us(s1, 1) + int(s1["pre"])
    assert _start_us(s1, 1) == 985 and latch + 11 >= 1000      # SD runs after 1 ms
    assert rows[0]["MW200"] == "0" and s1["MW200"] == "1"


def test_scan_k_starts_at_k_times_period(tmp_path):
    """§7: core c starts scan k at t = k·period_us. At 2.5 MHz a 101 us period is
    252.5 clocks; the plant rounds the period once (to 253) and so drifts by half a
    clock per scan: scan 10 starts at 1012 us instead of 1010 us (the first clock at
    or after 1010 us is exactly 1010 us)."""
    plant = _plant(tmp_path, READER, period_us=101, clock_mhz="2.5")
    r = _bitbyte("run", plant, "--until-us", "1011", "--trace", tmp_path / "T.csv",
                 cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    for row in _rows(tmp_path / "T.a.csv"):
        k = int(row["scan"])
        start = _start_us(row, "2.5")
        assert k * 101 <= start < k * 101 + Fraction(2, 5), (k, start)


def test_period_shorter_than_a_clock_still_overruns(tmp_path):
    """§7: a scan still running at the next start makes the next one start right after
    it and counts as an overrun; only period_us = 0 means back to back. At 0.1 MHz
    a 4 us period rounds to 0 clocks and every scan (each 330 us long) is reported
    with overrun 0."""
    plant = _plant(tmp_path, READER, period_us=4, clock_mhz="0.1")
    r = _bitbyte("run", plant, "--until-us", "1000", "--trace", tmp_path / "T.csv",
                 cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rows = _rows(tmp_path / "T.a.csv")
    assert len(rows) >= 2
    assert rows[0]["overrun"] == "0"
    assert all(row["overrun"] == "1" for row in rows[1:])


def test_icarus_bad_trace_path_is_an_error_not_a_traceback(tmp_path):
    """--sim icarus with a --trace in a missing folder dumps the cocotb log, Python
    traceback included (exit 4); the single-CPU icarus path says
    `bitbyte: /missing/T.csv: No such file or directory`."""
    plant = _plant(tmp_path, READER, period_us=100)
    r = _bitbyte("run", plant, "--until-us", "10", "--sim", "icarus",
                 "--trace", tmp_path / "missing" / "T.csv", cwd=tmp_path)
    assert r.returncode != 0
    assert "Traceback" not in r.stdout + r.stderr, r.stderr[-2000:]


def test_summary_gives_scan_time_in_us(tmp_path):
    """§4: `run` prints a summary with the scan time min/mean/max in clocks and µs.
    The plant summary gives `cycles min/mean/max` in clocks only. (READER's scan is
    23 clocks = 23 us at 1 MHz.)"""
    plant = _plant(tmp_path, READER, period_us=100)
    r = _bitbyte("run", plant, "--until-us", "300", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    line = next(l for l in r.stdout.splitlines() if l.startswith("core a"))
    assert re.search(r"(\bus\b|µs|\[us\])", line), line


def test_long_period_is_run_or_rejected_at_the_plant_file(tmp_path):
    """The plant file takes period_us up to 2^31-1 (docs/multicore.md); a 50 s period at
    100 MHz is 5e9 clocks, more than the harness's 32-bit period: the Verilator run
    ends with `plant harness failed (2): /tmp/.../plant.run: period exceeds 32 bits`
    (exit 4, even for --until-us 0, which needs scan 0 only), while --sim icarus
    masks the period to 32 bits and runs. Either run it or reject it as a plant-file
    error (`plant.toml:line:col`)."""
    plant = _plant(tmp_path, READER, period_us=50_000_000, clock_mhz="100")
    r = _bitbyte("run", plant, "--until-us", "0", "--trace", tmp_path / "T.csv",
                 cwd=tmp_path)
    if r.returncode == 0:
        assert len(_rows(tmp_path / "T.a.csv")) == 1
    else:
        assert re.match(r"\S*plant\.toml:\d+:\d+: ", r.stderr), r.stderr
