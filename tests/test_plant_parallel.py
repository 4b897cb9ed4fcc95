"""Plant cores in parallel mode (spec §7, issue 16 item 4).

A `[[core]]` of a plant file takes `mode` (serial | parallel) and `exchange` (handshake |
queue), checked where the single CPU's `run --mode --exchange` is checked
(bitbyte.run.prepare.MODE_EXCHANGES); free-running cores and exchanges are rejected at
the value, `file:line:col`.  A parallel core's program is partitioned as `run --mode
parallel` does and keeps the read-at-start / write-at-end rule: its postcycle follows
the PIO update that comes after both sides finished the scan.

The reference is the serial plant: the seed's §6.1 plant (examples/plant_6_1) with
both projects in parallel mode must give every trace column but t_us, cycles, pre,
post and sem_wait as the serial plant does.  Spec §7 lets a timer's transitions move
by a period; in this plant they do not (p2 scans on the 1 ms grid, and its scan's
offsets in both modes are far less than 1 ms), so the traces must be equal.
The cocotb case is in tests/test_plant_cocotb.py.
"""
from __future__ import annotations

import contextlib
import io
import shutil
from fractions import Fraction
from pathlib import Path

import pytest

from bitbyte import cli
from bitbyte.plant.link import load_plant
from bitbyte.plant.run import run_plant
from bitbyte.run.prepare import prepare
from bitbyte.sim.verilator import run_harness
from test_plant_run import check_visibility
from tracecmp import first_difference, numeric

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "plant_6_1"
# what parallel mode may change in a plant's trace (spec §7, issue 16)
TIMING = ("t_us", "cycles", "pre", "post", "sem_wait")
WATCH = "p1.MW20,p1.M10.0,p1.M10.1,p1.C0,p2.MW0,p2.M0.0,p2.M0.1,p2.T0"
UNTIL_US = "6600000"           # the stimulus's 12 pulses, then IN1 held past TON1's 5 s
PARALLEL = {"mode": "parallel"}


def with_core_keys(toml: str, keys: list[dict[str, str]]) -> str:
    """The plant text with keys[i] added to its i-th [[core]] (string values)."""
    head, *cores = toml.split("[[core]]")
    assert len(cores) == len(keys)
    return head + "".join(
        "[[core]]" + block.rstrip("\n") + "\n"
        + "".join(f'{k} = "{v}"\n' for k, v in extra.items()) + "\n"
        for block, extra in zip(cores, keys))


def plant_6_1(tmp_path: Path, name: str, keys=({}, {})) -> Path:
    """examples/plant_6_1 at 0.1 MHz (6.6 s are 660 k clocks; p1's scan of 78 clocks
    is 0.78 ms of its 10 ms period), with `keys` added to its cores."""
    for f in ("p1.il", "p2.il", "p1.stim.csv"):
        if not (tmp_path / f).exists():
            shutil.copy(EXAMPLE / f, tmp_path / f)
    text = (EXAMPLE / "plant.toml").read_text()
    assert "clock_mhz = 100\n" in text
    path = tmp_path / f"{name}.toml"
    path.write_text(with_core_keys(text.replace("clock_mhz = 100\n", "clock_mhz = 0.1\n"),
                                   list(keys)))
    return path


def run(plant: Path, **kw):
    status, summary, rows = run_plant(str(plant), until_us=UNTIL_US, watch=WATCH, **kw)
    assert status == 0, summary
    return summary, {core: numeric(r) for core, r in rows.items()}


def test_plant_file_takes_mode_and_exchange(tmp_path):
    plant = plant_6_1(tmp_path, "mixed", ({"mode": "parallel", "exchange": "queue"},
                                          {"exchange": "queue"}))
    cores = load_plant(str(plant)).cores
    # p2: serial ignores its exchange, as `run --mode serial --exchange queue` does
    assert [(c.mode, c.exchange) for c in cores] == [("parallel", "queue"),
                                                      ("serial", "handshake")]
    assert load_plant(str(plant_6_1(tmp_path, "par", (PARALLEL, {})))).cores[0].exchange \
        == "handshake"                                         # parallel's default
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert cli.main(["link", str(plant)]) == 0
    lines = [line.split() for line in out.getvalue().splitlines()]
    assert ["core", "program", "period_us", "stimulus", "mode", "exchange"] in lines
    assert lines[lines.index(["core", "program", "period_us", "stimulus", "mode",
                              "exchange"]) + 1][-2:] == ["parallel", "queue"]
    assert ["p2", str(tmp_path / "p2.il"), "100000", "-", "serial", "-"] in lines


# (the line added to core p2, the message); free-running values say why not
BAD = [
    ('mode = "free"', 'bad value `free` for `mode`: serial | parallel (free-running '
                      'plant cores are not built)'),
    ('mode = "Parallel"', "bad value `Parallel` for `mode`: serial | parallel"),
    ("mode = 2", "`mode` must be a string (serial | parallel), not an integer"),
    ('exchange = "marker"', "bad value `marker` for `exchange`: handshake | queue (a "
                            "free-running exchange"),
    ('exchange = "queue-free"', "bad value `queue-free` for `exchange`: handshake | queue "
                                "(a free-running exchange"),
    ('exchange = "fifo"', "bad value `fifo` for `exchange`: handshake | queue"),
]


@pytest.mark.parametrize("line, message", BAD, ids=[b[0] for b in BAD])
@pytest.mark.parametrize("command", ["run", "link"])
def test_bad_mode_or_exchange_is_an_error_at_the_value(tmp_path, command, line, message):
    plant = plant_6_1(tmp_path, "plant", (PARALLEL, {}))
    text = plant.read_text().rstrip("\n") + "\n" + line + "\n"
    plant.write_text(text)
    where = f"{plant}:{len(text.splitlines())}:{line.index('=') + 3}: "
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        code = cli.main([command, str(plant)] + (["--until-us", "1"] if command == "run"
                                                 else []))
    assert code == cli.EXIT_SOURCE and err.getvalue().startswith(where + message), \
        err.getvalue()


@pytest.mark.parametrize("command", ["run", "link"])
def test_exchange_on_a_serial_core_is_a_warning(tmp_path, command):
    """`exchange` on a core without `mode = "parallel"` is ignored: a warning at the
    key, `file:line:col`, on stderr; the exit code and stdout are those without it."""
    quiet = plant_6_1(tmp_path, "quiet", (PARALLEL, {}))
    noisy = plant_6_1(tmp_path, "noisy", (PARALLEL, {"exchange": "queue"}))
    lines = noisy.read_text().splitlines()
    line = lines.index('exchange = "queue"') + 1      # p2's: the only one in the file
    args = ["--until-us", "1"] if command == "run" else []
    results = []
    for plant in (quiet, noisy):
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
            code = cli.main([command, str(plant)] + args)
        results.append((code, out.getvalue().replace(str(plant), "PLANT"), err.getvalue()))
    (code0, out0, err0), (code1, out1, err1) = results
    assert code0 == code1 == 0 and out0 == out1 and err0 == ""
    assert err1.startswith(f"{noisy}:{line}:1: warning: `exchange` is ignored: core `p2` "
                           "runs in serial mode"), err1
    assert err1.count("warning:") == 1, err1


def test_seed_6_1_parallel_plant_traces_equal_the_serial_plant(tmp_path):
    """Both projects in parallel mode, with either exchange, on the Verilator plant
    harness: the serial plant's traces but for the timing columns."""
    _, serial = run(plant_6_1(tmp_path, "serial"), trace=str(tmp_path / "S.csv"))
    p1, p2 = serial["p1"], serial["p2"]
    # the reference does what the seed says (tests/test_plant_run.py checks it in
    # detail): counts to 13, OUT2 on, TON1 -> RST clears the count; p1 reads RST
    assert len(p1) == 661 and len(p2) == 67 and max(r["MW20"] for r in p1) == 13
    assert any(r["Q0.0"] for r in p2) and any(r["M0.1"] for r in p2)
    assert any(r["M10.1"] for r in p1) and p1[-1]["MW20"] == 0
    for exchange in ("handshake", "queue"):
        keys = {"mode": "parallel", "exchange": exchange}
        summary, par = run(plant_6_1(tmp_path, exchange, (keys, keys)),
                           trace=str(tmp_path / f"{exchange}.csv"))
        assert summary.count(f"parallel/{exchange}, scans") == 2, summary
        for core in ("p1", "p2"):
            assert first_difference(serial[core], par[core], TIMING) is None, (
                exchange, core, first_difference(serial[core], par[core], TIMING))
        # read at scan start, write at scan end (tests/test_plant_run.py's model)
        q = {k: [{c: str(v) for c, v in r.items()} for r in rows]
             for k, rows in par.items()}
        assert check_visibility(q["p1"], "MW20", q["p2"], "MW0", Fraction(1, 10))
        assert check_visibility(q["p2"], "M0.1", q["p1"], "M10.1", Fraction(1, 10))


def single_cpu_cycles(program: Path, mode: str, costs: str) -> int:
    """The scan of `program` on one CPU (sim/harness.cpp) in `mode`, in clocks."""
    prep = prepare(str(program), scans=1, mode=mode, costs=costs)
    records, fault, _ = run_harness(prep.job, prep.columns)
    assert not fault
    return records[0].cycles


def test_parallel_core_scans_as_the_single_cpu_in_parallel_mode(tmp_path):
    """With the C320's cost table a parallel scan of either project is longer than a
    serial one (its transfers): each plant core's `cycles` is the single CPU's in its
    own mode, so the mode reaches the hardware, and the other columns stay the serial
    plant's."""
    _, serial = run(plant_6_1(tmp_path, "serial"), costs="c320")
    _, par = run(plant_6_1(tmp_path, "parallel", (PARALLEL, PARALLEL)), costs="c320")
    for core in ("p1", "p2"):
        want = {mode: single_cpu_cycles(tmp_path / f"{core}.il", mode, "c320")
                for mode in ("serial", "parallel")}
        assert want["serial"] != want["parallel"], want
        assert {r["cycles"] for r in serial[core]} == {want["serial"]}
        assert {r["cycles"] for r in par[core]} == {want["parallel"]}
        assert first_difference(serial[core], par[core], TIMING) is None


WRITER = """VAR_GLOBAL
  N AT MW2 : WRITE;       // the scans this core has finished
END_VAR
      LD    I0.0
      =     Q0.0
      L     N             // the byte side's work goes on after the bit side's END
      L     1
      +I
      T     N
      END
"""
READER = """VAR_GLOBAL
  N AT MW0 : READ;
END_VAR
      L     N
      T     QW0
      END
"""


def test_postcycle_follows_both_sides(tmp_path):
    """The writer's bit part ends long before its byte part counts N: the postcycle
    waits for both (spec §7), so reader scan k, whose precycle starts after writer
    scan k - 1 ended, shows writer scan k - 1's N (= k), in either mode of either core."""
    (tmp_path / "w.il").write_text(WRITER)
    (tmp_path / "r.il").write_text(READER)
    text = ('clock_mhz = 1\n\n[[core]]\nname = "w"\nprogram = "w.il"\nperiod_us = 100\n'
            '\n[[core]]\nname = "r"\nprogram = "r.il"\nperiod_us = 100\n')
    traces = {}
    for modes in (({}, {}), (PARALLEL, {}), (PARALLEL, PARALLEL)):
        path = tmp_path / "plant.toml"
        path.write_text(with_core_keys(text, list(modes)))
        status, summary, rows = run_plant(str(path), until_us="2000", watch="w.MW2,r.MW0")
        assert status == 0, summary
        w, r = numeric(rows["w"]), numeric(rows["r"])
        assert [row["MW2"] for row in w] == list(range(1, len(w) + 1))
        for k in range(1, len(r)):
            assert w[k - 1]["t_us"] < 100 * k, "writer scan k-1 ends before reader scan k"
            assert r[k]["MW0"] == w[k - 1]["MW2"] == k, (modes, k)
            assert r[k]["QW0"] == r[k]["MW0"]
        traces[str(modes)] = (w, r)
    serial_w, serial_r = traces[str(({}, {}))]
    for w, r in traces.values():
        assert first_difference(serial_w, w, TIMING) is None
        assert first_difference(serial_r, r, TIMING) is None


def test_waves_layout_shows_a_parallel_cores_bit_part(tmp_path):
    """--waves: a parallel core's `executing` row names its bit part's instructions
    (with its channel transfers), as a single CPU's in parallel mode; a serial core
    keeps its program and its `byte busy` row."""
    plant = plant_6_1(tmp_path, "plant", (PARALLEL, {}))
    status, summary, _ = run_plant(str(plant), until_us="1000",
                                   waves=str(tmp_path / "w.fst"))
    assert status == 0, summary
    text = (tmp_path / "w.gtkw").read_text()
    assert "{p1: executing}" in text and "{p1: byte busy}" not in text
    assert "{p2: byte busy}" in text
    assert "FBY" in (tmp_path / "w.p1.instr.txt").read_text()
    assert "FBY" not in (tmp_path / "w.p2.instr.txt").read_text()


# eight conditions written in a row (CU C0..C7: one to-byte transfer each), then bit
# work: with 4 handshake channels the fifth write waits for the byte side to read
# channel 0; the queue (QueueDepth 8) takes all eight, and the bit work goes on at once
BURST = ("".join(f"      LD    I0.{n}\n      CU    C{n}\n" for n in range(8))
         + "".join(f"      LD    I1.{n % 8}\n      =     M{n // 8}.{n % 8}\n"
                   for n in range(40)) + "      END\n")
IDLE = "      LD    I0.0\n      =     Q0.0\n      END\n"


def burst_plant(tmp_path: Path, exchange: str) -> Path:
    """A plant at 1 MHz: core b runs BURST in parallel mode with `exchange`, core i
    runs IDLE serially; both every 200 µs."""
    (tmp_path / "b.il").write_text(BURST)
    (tmp_path / "i.il").write_text(IDLE)
    text = ('clock_mhz = 1\n\n[[core]]\nname = "b"\nprogram = "b.il"\nperiod_us = 200\n'
            '\n[[core]]\nname = "i"\nprogram = "i.il"\nperiod_us = 200\n')
    path = tmp_path / f"{exchange}.toml"
    path.write_text(with_core_keys(text, [{"mode": "parallel", "exchange": exchange}, {}]))
    return path


def test_queue_and_handshake_differ_on_the_plant_harness(tmp_path):
    """The exchange reaches the plant's hardware: a core whose bit part writes more
    conditions in a row than there are handshake channels scans as long as the single
    CPU does with that exchange (sim/harness.cpp), and those differ (the handshake
    stalls, the queue does not); the summary names the exchange the harness drove."""
    (tmp_path / "b.il").write_text(BURST)
    want = {}
    for exchange in ("handshake", "queue"):
        prep = prepare(str(tmp_path / "b.il"), scans=1, mode="parallel", exchange=exchange)
        records, fault, _ = run_harness(prep.job, prep.columns)
        assert not fault
        want[exchange] = records[0].cycles
    assert want["handshake"] > want["queue"], want
    for exchange in ("handshake", "queue"):
        status, summary, rows = run_plant(str(burst_plant(tmp_path, exchange)),
                                          until_us="1000")
        assert status == 0, summary
        assert {int(r["cycles"]) for r in rows["b"]} == {want[exchange]}, (exchange, want)
        assert f"core b           parallel/{exchange}, scans 6," in summary, summary
        assert "core i           serial, scans 6," in summary, summary
