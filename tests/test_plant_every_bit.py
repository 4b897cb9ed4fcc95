"""Every core of a two-core plant is the single CPU, bit for bit (spec §7: each core
runs its project as the CPU of §2-§5 does, with its own scan period). Each core runs a
program that touches every bit of every image and a word of every kind: Q := I for all
128 inputs, IR and IF of every input and QR and QF of every output into markers (and
markers at every bit-address line), IW into QW and into MW at every word-address line
and read back,
a counter and a 0 ms on-delay timer on every one of the 64 status bits; each core with
its own random scan-keyed stimulus. Watched: every image bit (the output edges QR/QF
too), marker, word, timer and counter the program touches. Every traced value of every scan of both cores must equal
the reference interpreter's run of that core's program and stimulus on its own
(bitbyte.ref.refsim): the columns but t_us and the plant's pre, post and sem_wait
(a core's scan takes as many clocks as the CPU's: `cycles` is compared too). This is the test that reaches the plant's own wiring (rtl/plc_core.v,
rtl/plc_system.v: each core's slice of every port), which mutation testing's plant
campaign samples; it fails when the two cores' stimuli are swapped."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from bitbyte.lang.parser import parse_file
from bitbyte.lang.stimulus import load_stimulus
from bitbyte.plant.run import run_plant
from bitbyte.ref.refsim import refsim_trace

IN_BITS, WORDS, STATUS = 128, 16, 64
# markers: IR -> M0..15, IF -> M16..31, QR -> M96..111, QF -> M112..127, and one marker
# at each high bit-address line (256, 512, 1024) and the last
QR_AT, QF_AT = 96, 112
MARK_LINES = [(32, 0), (64, 0), (128, 0), (255, 7)]
MW_LINES = [0, 1, 2, 4, 8, 16, 32, 64, 128, 255]
MW_COPY = 200             # MW200.. hold what the program read back from MW_LINES
SCANS = 10
PERIOD_US = 100           # a scan of the program takes about 39 us at 100 MHz
TIMING = ("t_us", "pre", "post", "sem_wait")   # a serial core's `cycles` is the CPU's


def bit(i: int) -> str:
    return f"{i // 8}.{i % 8}"


def every_bit_program() -> str:
    lines = []
    for i in range(IN_BITS):
        lines += [f"LD I{bit(i)}", f"= Q{bit(i)}"]
    for i in range(IN_BITS):
        lines += [f"LD IR{bit(i)}", f"= M{bit(i)}", f"LD IF{bit(i)}", f"= M{bit(128 + i)}"]
    for j, (byte, b) in enumerate(MARK_LINES):
        lines += [f"LD I{j}.{j}", f"= M{byte}.{b}"]
    for k in range(WORDS):
        lines += [f"L IW{k}", f"T QW{k}"]
    for k, addr in enumerate(MW_LINES):
        lines += [f"L IW{k}", f"T MW{addr}"]
    for k, addr in enumerate(MW_LINES):           # and read back (the MW RAM's read port)
        lines += [f"L MW{addr}", f"T MW{MW_COPY + k}"]
    for n in range(STATUS):
        lines += [f"LD I{bit(n)}", f"CU C{n}", f"LD I{bit(64 + n)}", "L T#0ms", f"SD T{n}"]
    for i in range(IN_BITS):
        lines += [f"LD QR{bit(i)}", f"= M{bit(8 * QR_AT + i)}",
                  f"LD QF{bit(i)}", f"= M{bit(8 * QF_AT + i)}"]
    return "".join(f"  {x}\n" for x in lines) + "  END\n"


def watch_list() -> list[str]:
    marks = ([f"M{bit(i)}" for i in range(256)] + [f"M{b}.{n}" for b, n in MARK_LINES]
             + [f"M{bit(8 * a + i)}" for a in (QR_AT, QF_AT) for i in range(IN_BITS)])
    return ([f"{a}{bit(i)}" for a in ("I", "IR", "IF", "QR", "QF") for i in range(IN_BITS)]
            + marks
            + [f"QW{k}" for k in range(WORDS)] + [f"MW{a}" for a in MW_LINES]
            + [f"MW{MW_COPY + k}" for k in range(len(MW_LINES))]
            + [f"{a}{n}" for a in ("T", "C") for n in range(STATUS)])


def stimulus(seed: int) -> str:
    rng = random.Random(seed)
    cols = [f"I{bit(i)}" for i in range(IN_BITS)] + [f"IW{k}" for k in range(WORDS)]
    rows = ["scan," + ",".join(cols)]
    for s in range(SCANS + 1):
        rows.append(f"{s}," + ",".join([str(rng.randrange(2)) for _ in range(IN_BITS)] +
                                       [str(rng.randrange(-32768, 32768))
                                        for _ in range(WORDS)]))
    return "\n".join(rows) + "\n"


def plant(tmp: Path, swap: bool = False) -> Path:
    (tmp / "every.il").write_text(every_bit_program())
    for core, seed in (("a", 1), ("b", 2)):
        (tmp / f"{core}.stim.csv").write_text(stimulus(seed))
    stims = ("b", "a") if swap else ("a", "b")
    path = tmp / "plant.toml"
    path.write_text("clock_mhz = 100\n" + "".join(
        f'[[core]]\nname = "{core}"\nprogram = "every.il"\nperiod_us = {PERIOD_US}\n'
        f'stimulus = "{stim}.stim.csv"\n' for core, stim in zip(("a", "b"), stims)))
    return path


def reference(tmp: Path, core: str, scans: int) -> list[dict[str, str]]:
    """The core's program and stimulus on the reference interpreter alone."""
    program = parse_file(str(tmp / "every.il"))
    stim = load_stimulus(str(tmp / f"{core}.stim.csv"), program.symbols)
    columns, records, fault = refsim_trace(program, stimulus=stim, watch=watch_list(),
                                           scans=scans)
    assert not fault
    return [{c.header: str(r.values[c.header]) for c in columns} for r in records]


def differences(rows: list[dict[str, str]], want: list[dict[str, str]]) -> list[str]:
    out = []
    for scan, (got, ref) in enumerate(zip(rows, want)):
        for col, value in ref.items():
            if col in TIMING or col == "scan":
                continue
            if got.get(col) != value:
                out.append(f"scan {scan} {col}: plant {got.get(col)}, reference {value}")
    return out


@pytest.mark.parametrize("swap", [False, True], ids=["as_wired", "stimuli_swapped"])
def test_every_core_is_the_single_cpu_bit_for_bit(tmp_path, swap):
    watch = ",".join(f"{core}.{w}" for core in ("a", "b") for w in watch_list())
    status, summary, rows = run_plant(str(plant(tmp_path, swap)),
                                      until_us=str(PERIOD_US * SCANS), watch=watch)
    assert status == 0, summary
    diffs = []
    for core in ("a", "b"):
        assert len(rows[core]) >= SCANS - 1, summary
        want = reference(tmp_path, core, len(rows[core]))
        assert set(want[0]) - set(TIMING) <= set(rows[core][0]), "a column is missing"
        diffs += [f"{core}: {d}" for d in differences(rows[core], want)]
    if swap:      # each core's trace is now the other stimulus's: it must show
        assert len(diffs) > 100, diffs[:5]
    else:
        assert diffs == [], diffs[:20]
