"""Response time never exceeds its analytical bound (issue 8; `make bench` measures the
same on a Table-1-sized program with 1000 edges, docs/performance.md §4).

A small program with a direct-access rung (`LD PI1.7` / `= PQ1.6`) and a process-image
rung (`LD I1.7` / `= Q1.7`) between word instructions; input I1.7 toggles at 200
random moments spread over the scan's phases. On the Verilator harness, in clocks:

* process image: every response lies in [min scan, 2 x max scan) -- an edge just after
  a latch waits for the next latch, then a whole scan until END;
* direct access: the pin changes at the end of the `= PQ` clock, known from the serial
  timing model (bench/benchlib.py checks the model against the trace for every
  edge); every response lies in (0, max scan + write - read + 1).
"""
from __future__ import annotations

import random
import re
import sys
from fractions import Fraction
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))

import benchlib as bl  # noqa: E402

PROGRAM = """\
// response-time test program: word work before and after the response rungs
      LD    I0.0
      O     M0.0
      A     I0.1
      =     M0.0
      L     MW1
      SD    T1
      LD    T1
      =     Q0.0
      LD    PI1.7
      =     PQ1.6
      LD    I1.7
      =     Q1.7
      L     IW0
      L     MW0
      A     >=I
      =     Q0.1
"""


def response_program(tmp_path):
    """PROGRAM written out; its static counts, the word cost and the clock offsets of
    the direct read (`LD PI1.7`) and write (`= PQ1.6`) within a scan."""
    prog = tmp_path / "resp.il"
    prog.write_text(PROGRAM)
    st = bl.static_counts(prog)
    word = bl.cost_table("paper")["word"]
    return (prog, st, word, st.offset(st.find("LD", "PI1.7"), word),
            st.offset(st.find("=", "PQ1.6"), word))


@pytest.mark.parametrize("mhz", ["100", "50.5"])
def test_worst_case_response_within_bound(mhz, tmp_path):
    f = Fraction(mhz)
    prog, st, word, read_off, write_off = response_program(tmp_path)
    assert (read_off, write_off) == (4 + 2 * word + 2, 4 + 2 * word + 3)

    pre = bl.run_bitbyte(prog, clock_mhz=f, scans=5, trace=tmp_path / "pre.csv")
    assert pre.ok, pre.stderr
    scan = max(pre.cycles)
    assert scan == st.serial_clocks(word)            # 12 bit + 4 word + END

    edges = bl.random_edges(200, scan, f, random.Random(8))
    stim = tmp_path / "edges.stim.csv"
    bl.write_edge_stimulus(stim, "I1.7", edges)
    until = bl.fmt_us(edges[-1] + Fraction(4 * scan) / f)
    run = bl.run_bitbyte(prog, clock_mhz=f, stimulus=stim, until_us=until,
                         trace=tmp_path / "trace.csv")
    assert run.ok, run.stderr

    img = bl.responses(run, edges, f, "Q1.7", "image")
    drc = bl.responses(run, edges, f, "Q1.6", "direct", write_offset=write_off,
                       read_offset=read_off)
    assert len(img.clocks) == len(drc.clocks) == 200

    # process image, in clocks: one scan at least, less than two at most
    assert img.bound == 2 * max(run.cycles)
    assert max(img.clocks) < img.bound
    assert min(img.clocks) >= min(run.cycles)
    # direct access: after the edge, and within one scan plus the read-to-write span
    assert drc.bound == max(run.cycles) + (write_off - read_off + 1)
    assert max(drc.clocks) < drc.bound
    assert min(drc.clocks) > 0
    # the edges really are spread over the scan (no phase tenth left empty)
    bins = [0] * 10
    for p in img.phase:
        bins[min(9, int(p * 10))] += 1
    assert min(bins) > 0, bins
    # and the worst cases come close to the bounds (the bound is not loose)
    assert max(img.clocks) > img.bound - 0.2 * scan
    assert max(drc.clocks) > drc.bound - 0.2 * scan


def _vcd_changes(path: Path, names: dict[str, int]) -> tuple[int, dict[str, list]]:
    """(timescale in ps, {name: [(time, value)]}) for the first variable of each name
    with the given width, from a VCD written by the harness."""
    ids, changes, t = {}, {}, 0
    text = path.read_text()
    m = re.search(r"\$timescale\s*(\d+)\s*(s|ms|us|ns|ps)\s*\$end", text)
    scale = int(m.group(1)) * {"s": 10**12, "ms": 10**9, "us": 10**6, "ns": 10**3,
                               "ps": 1}[m.group(2)]
    lines = text.splitlines()
    for line in lines:
        parts = line.split()
        if line.startswith("$var") and parts[4] in names and parts[4] not in ids.values() \
                and int(parts[2]) == names[parts[4]]:
            ids[parts[3]] = parts[4]
    for name in names:
        changes[name] = []
    for line in lines:
        if line.startswith("#"):
            t = int(line[1:])
        elif line.startswith("b"):
            v, idc = line[1:].split()
            if idc in ids:
                changes[ids[idc]].append((t, int(v.replace("x", "0"), 2)))
        elif line[:1] in ("0", "1") and line[1:] in ids:
            changes[ids[line[1:]]].append((t, int(line[0])))
    return scale, changes


def test_direct_output_changes_in_the_modelled_clock(tmp_path):
    """The clock the benchmark assigns to a `= PQ` pin change (latch + write offset
    + 1: the pin is written on the edge that ends the write clock) is the one the
    waveform shows."""
    f = Fraction(100)
    prog, st, word, read_off, write_off = response_program(tmp_path)
    scan = st.serial_clocks(word)
    edges = [Fraction(1234, 1000), Fraction(4 * scan + read_off, 100),      # on the read
             Fraction(8 * scan + read_off + 1, 100)]                        # just after
    stim = tmp_path / "edges.stim.csv"
    bl.write_edge_stimulus(stim, "I1.7", edges)
    waves = tmp_path / "w.vcd"
    run = bl.run_bitbyte(prog, clock_mhz=f, stimulus=stim, scans=12,
                         trace=tmp_path / "trace.csv", extra=["--waves", str(waves)])
    assert run.ok, run.stderr
    drc = bl.responses(run, edges, f, "Q1.6", "direct", write_offset=write_off,
                       read_offset=read_off)
    scale, ch = _vcd_changes(waves, {"latch": 1, "out_pins_o": 128})
    period = 10**6 // int(f) // scale                   # one clock in VCD time units
    t0 = next(t for t, v in ch["latch"] if v == 1)      # clock 0 = first latch clock
    pq_bit = 1 * 8 + 6
    seen, last = [], 0
    for t, v in ch["out_pins_o"]:
        if (v >> pq_bit) & 1 != last:
            last = (v >> pq_bit) & 1
            seen.append(Fraction(t - t0, period))      # change at the start of clock n
    modelled = [e * f + r for e, r in zip(edges, drc.clocks)]
    assert seen == modelled
    # the edge on the read clock is answered in 2 clocks, the one just after in a scan
    assert drc.clocks[1] == write_off - read_off + 1
    assert drc.clocks[2] == scan + write_off - read_off
