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
campaign samples; it fails when the two cores' stimuli are swapped. The same in parallel
mode (one core on the handshake flip-flops, the other on the queue, and the other way
round), the program's conditions crossing between the sides.

Beside it, the rest of the plant's wiring that one scan of that program does not reach:
shared variables crossing intact both ways in both layouts (words of packed bits read
while the other core's read port carries its own; 300 variables spread over 2 048
shared words), and scans of 12 000 to 32 500 clocks whose `cycles` must be the
reference interpreter's (the high bits of the scan counters)."""
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
CROSS, CROSS_MW, CROSS_M = 16, 100, 40    # the crossing conditions' results: MW100.., M40.0..
SCANS = 10
PERIOD_US = 100           # a scan of the program takes about 39 us at 100 MHz
TIMING = ("t_us", "pre", "post", "sem_wait")   # a serial core's `cycles` is the CPU's


def bit(i: int) -> str:
    return f"{i // 8}.{i % 8}"


def il_text(lines: list[str]) -> str:
    """Instructions indented, `label:` lines as they are, END appended."""
    return "".join(x + "\n" if x.endswith(":") else f"  {x}\n" for x in lines) + "  END\n"


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
    # conditions crossing between the sides in parallel mode: a jump over byte code
    # (bit -> byte) and a compare's result (byte -> bit)
    for k in range(CROSS):
        lines += [f"LD I{bit(k)}", f"JC over{k}", f"L IW{k}", f"T MW{CROSS_MW + k}",
                  f"over{k}:"]
    for k in range(CROSS - 1):
        lines += [f"L IW{k}", f"L IW{k + 1}", ">I", f"= M{bit(8 * CROSS_M + k)}"]
    return il_text(lines)


def watch_list() -> list[str]:
    marks = ([f"M{bit(i)}" for i in range(256)] + [f"M{b}.{n}" for b, n in MARK_LINES]
             + [f"M{bit(8 * a + i)}" for a in (QR_AT, QF_AT) for i in range(IN_BITS)])
    return ([f"{a}{bit(i)}" for a in ("I", "IR", "IF", "QR", "QF") for i in range(IN_BITS)]
            + marks
            + [f"QW{k}" for k in range(WORDS)] + [f"MW{a}" for a in MW_LINES]
            + [f"MW{MW_COPY + k}" for k in range(len(MW_LINES))]
            + [f"{a}{n}" for a in ("T", "C") for n in range(STATUS)]
            + [f"MW{CROSS_MW + k}" for k in range(CROSS)]
            + [f"M{bit(8 * CROSS_M + k)}" for k in range(CROSS - 1)])


def stimulus(seed: int) -> str:
    rng = random.Random(seed)
    cols = [f"I{bit(i)}" for i in range(IN_BITS)] + [f"IW{k}" for k in range(WORDS)]
    rows = ["scan," + ",".join(cols)]
    for s in range(SCANS + 1):
        rows.append(f"{s}," + ",".join([str(rng.randrange(2)) for _ in range(IN_BITS)] +
                                       [str(rng.randrange(-32768, 32768))
                                        for _ in range(WORDS)]))
    return "\n".join(rows) + "\n"


# the cores' modes: serial; or parallel, core a on the handshake flip-flops and core b
# on the queue, and the other way round (a queue's reads pop: a byte side's read strobe
# must reach it only when the firmware reads)
MODES = {"serial": ("", ""),
         "parallel_hq": ('mode = "parallel"\nexchange = "handshake"\n',
                         'mode = "parallel"\nexchange = "queue"\n'),
         "parallel_qh": ('mode = "parallel"\nexchange = "queue"\n',
                         'mode = "parallel"\nexchange = "handshake"\n')}


def plant(tmp: Path, swap: bool = False, modes: str = "serial") -> Path:
    (tmp / "every.il").write_text(every_bit_program())
    for core, seed in (("a", 1), ("b", 2)):
        (tmp / f"{core}.stim.csv").write_text(stimulus(seed))
    stims = ("b", "a") if swap else ("a", "b")
    path = tmp / "plant.toml"
    path.write_text("clock_mhz = 100\n" + "".join(
        f'[[core]]\nname = "{core}"\nprogram = "every.il"\nperiod_us = {PERIOD_US}\n'
        f'stimulus = "{stim}.stim.csv"\n{mode}'
        for core, stim, mode in zip(("a", "b"), stims, MODES[modes])))
    return path


def reference(tmp: Path, core: str, scans: int) -> list[dict[str, str]]:
    """The core's program and stimulus on the reference interpreter alone."""
    program = parse_file(str(tmp / "every.il"))
    stim = load_stimulus(str(tmp / f"{core}.stim.csv"), program.symbols)
    columns, records, fault = refsim_trace(program, stimulus=stim, watch=watch_list(),
                                           scans=scans)
    assert not fault
    return [{c.header: str(r.values[c.header]) for c in columns} for r in records]


def differences(rows: list[dict[str, str]], want: list[dict[str, str]],
                timing: tuple[str, ...] = TIMING) -> list[str]:
    out = []
    for scan, (got, ref) in enumerate(zip(rows, want)):
        for col, value in ref.items():
            if col in timing or col == "scan":
                continue
            if got.get(col) != value:
                out.append(f"scan {scan} {col}: plant {got.get(col)}, reference {value}")
    return out


@pytest.mark.parametrize("swap,modes", [(False, "serial"), (True, "serial"),
                                        (False, "parallel_hq"), (False, "parallel_qh")],
                         ids=["as_wired", "stimuli_swapped", "parallel_hq", "parallel_qh"])
def test_every_core_is_the_single_cpu_bit_for_bit(tmp_path, swap, modes):
    """Parallel cores: every column but the timing ones and `cycles` (spec §7: a
    parallel core's trace is its serial trace but for timing)."""
    watch = ",".join(f"{core}.{w}" for core in ("a", "b") for w in watch_list())
    timing = TIMING if modes == "serial" else TIMING + ("cycles",)
    status, summary, rows = run_plant(str(plant(tmp_path, swap, modes)),
                                      until_us=str(PERIOD_US * SCANS), watch=watch)
    assert status == 0, summary
    diffs = []
    for core in ("a", "b"):
        assert len(rows[core]) >= SCANS - 1, summary
        want = reference(tmp_path, core, len(rows[core]))
        assert set(want[0]) - set(TIMING) <= set(rows[core][0]), "a column is missing"
        diffs += [f"{core}: {d}" for d in differences(rows[core], want, timing)]
    if swap:      # each core's trace is now the other stimulus's: it must show
        assert len(diffs) > 100, diffs[:5]
    else:
        assert diffs == [], diffs[:20]


# ---- the plant's shared-memory path, bit by bit: many variables each way, in both
# layouts. Each core writes SHARED bit variables from its inputs (the second 128 of
# them inverted) and reads the other core's into markers. The stimulus is constant, so
# from the first scan whose precycle follows the other core's first postcycle on, every
# copy equals the writer's value, worked out here from the stimulus alone. Compact:
# words of 32 packed bits, read while the other core's read port carries its own
# words; random: a word of its own per variable spread over 2 048 shared words (300
# variables), so that every bit of a copy item's word field is used.
SHARED = 150
COPY_AT = 8 * 40                  # the reader's copies: M40.0..


def shared_program(me: str, other: str) -> str:
    decl = "".join(f"  {me}{i} AT M{bit(i)} : WRITE;\n" for i in range(SHARED))
    decl += "".join(f"  {other}{i} AT M{bit(COPY_AT + i)} : READ;\n" for i in range(SHARED))
    body = "".join(f"  {'LD' if i < IN_BITS else 'LDN'} I{bit(i % IN_BITS)}\n  = {me}{i}\n"
                   for i in range(SHARED))
    return f"VAR_GLOBAL\n{decl}END_VAR\n{body}  END\n"


def shared_value(stim: list[int], i: int) -> int:
    return stim[i % IN_BITS] ^ (i >= IN_BITS)


@pytest.mark.parametrize("layout", ["compact", "random"])
def test_shared_variables_cross_intact(tmp_path, layout):
    names = {"a": "XA", "b": "XB"}
    stims = {}
    for core, other, seed in (("a", "b", 3), ("b", "a", 4)):
        (tmp_path / f"{core}.il").write_text(shared_program(names[core], names[other]))
        rng = random.Random(seed)
        stims[core] = [rng.randrange(2) for _ in range(IN_BITS)]
        (tmp_path / f"{core}.stim.csv").write_text(
            "scan," + ",".join(f"I{bit(i)}" for i in range(IN_BITS)) + "\n0,"
            + ",".join(map(str, stims[core])) + "\n")
    (tmp_path / "plant.toml").write_text(
        f'clock_mhz = 100\nlayout = "{layout}"\n' + "".join(
            f'[[core]]\nname = "{c}"\nprogram = "{c}.il"\nperiod_us = {p}\n'
            f'stimulus = "{c}.stim.csv"\n' for c, p in (("a", 20), ("b", 25))))
    watch = ",".join(f"{c}.M{bit(COPY_AT + i)}" for c in ("a", "b") for i in range(SHARED))
    status, summary, rows = run_plant(str(tmp_path / "plant.toml"), until_us="300",
                                      watch=watch)
    assert status == 0 and "overruns 0, skipped precycles 0" in summary, summary
    for core, other in (("a", "b"), ("b", "a")):
        want = [str(shared_value(stims[other], i)) for i in range(SHARED)]
        got = [[r[f"M{bit(COPY_AT + i)}"] for i in range(SHARED)] for r in rows[core]]
        assert len(got) >= 10 and got[0] == ["0"] * SHARED, summary  # nothing published yet
        assert all(g == want for g in got[2:]), \
            [(s, i) for s, g in enumerate(got) for i in range(SHARED) if s >= 2 and g[i] != want[i]][:10]
    assert len({v for c in stims.values() for v in c}) == 2      # both values cross


# ---- long scans: a scan's clock count (`cycles`) through the plant's wiring in every
# bit that a scan of up to 32 767 clocks sets. Blocks of 2^k word transfers (10 clocks
# each in serial mode), each jumped over when its input is 1: with random inputs the
# scans' lengths take many values from 12 000 to 32 500 clocks. Compared with the
# reference interpreter's `cycles` (a serial core's scan is the CPU's).
LONG_BLOCKS = 11
LONG_BASE = 1200


def long_program() -> str:
    lines = ["L IW0", "T MW0"] * (LONG_BASE // 2)
    for k in range(LONG_BLOCKS):
        lines += [f"LD I0.{k % 8}" if k < 8 else f"LD I1.{k - 8}", f"JC skip{k}"]
        lines += ["L IW1", "T MW1"] * (2 ** k // 2 or 1)
        lines += [f"skip{k}:"]
    return il_text(lines)


def test_long_scans_cycles_through_the_plant(tmp_path):
    (tmp_path / "long.il").write_text(long_program())
    cols = [f"I0.{n}" for n in range(8)] + [f"I1.{n}" for n in range(3)] + ["IW0", "IW1"]
    for core, seed in (("a", 5), ("b", 6)):
        rng = random.Random(seed)
        (tmp_path / f"{core}.stim.csv").write_text("scan," + ",".join(cols) + "\n" + "".join(
            f"{s}," + ",".join([str(rng.randrange(2)) for _ in range(11)] + ["7", "9"]) + "\n"
            for s in range(9)))
    (tmp_path / "plant.toml").write_text("clock_mhz = 100\n" + "".join(
        f'[[core]]\nname = "{c}"\nprogram = "long.il"\nperiod_us = 350\n'
        f'stimulus = "{c}.stim.csv"\n' for c in ("a", "b")))
    status, summary, rows = run_plant(str(tmp_path / "plant.toml"), until_us="2800")
    assert status == 0, summary
    seen = 0
    for core in ("a", "b"):
        program = parse_file(str(tmp_path / "long.il"))
        stim = load_stimulus(str(tmp_path / f"{core}.stim.csv"), program.symbols)
        _, records, fault = refsim_trace(program, stimulus=stim, scans=len(rows[core]))
        assert not fault and len(rows[core]) >= 7
        want = [r.cycles for r in records]
        got = [int(r["cycles"]) for r in rows[core]]
        assert got == want, (core, got, want)
        for c in got:
            seen |= c
    assert seen >> 14 & 1 and max(max(int(r["cycles"]) for r in rs) for rs in rows.values()) < 35_000
