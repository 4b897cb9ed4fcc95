"""Multi-core plants (spec §7): the plant file, `bitbyte link`, the shared-memory map.

Expected maps and error positions are written by hand from the rules in
docs/multicore.md; the CLI is exercised in a subprocess as a user runs it.
"""
from __future__ import annotations

import contextlib
import io
import os
import random
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from bitbyte import cli
from bitbyte.lang.errors import SourceError
from bitbyte.lang.parser import parse_file
from bitbyte.plant.link import format_map, link, load_plant

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "plant_6_1"
SEED = int(os.environ.get("BITBYTE_SEED", "1"))


def bitbyte(*args):
    proc = subprocess.run([sys.executable, "-m", "bitbyte.cli", *map(str, args)],
                          capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert "Traceback" not in proc.stderr + proc.stdout, proc.stderr
    return proc


def plant_text(layout="compact", p1="p1.il", p2="p2.il"):
    return (f'layout = "{layout}"\n\n[[core]]\nname = "p1"\nprogram = "{p1}"\n'
            f'period_us = 10000\n\n[[core]]\nname = "p2"\nprogram = "{p2}"\n'
            'period_us = 100000\n')


def rows(shared):
    return [(v.name, v.kind, v.writer, v.readers, v.address(), v.sector)
            for v in shared.variables]


def copies(plan):
    """[(sector, start, length, [(shared, local, name)])] for pre and post."""
    def one(cs):
        return [(c.sector, c.start, c.length, [(i.shared(), i.local, i.name)
                                               for i in c.items]) for c in cs]
    return one(plan.precycle), one(plan.postcycle)


# ---------------------------------------------------------------------------------------
# The seed's §6.1 example
# ---------------------------------------------------------------------------------------

def test_example_programs_declare_table_3():
    p1 = parse_file(str(EXAMPLE / "p1.il"))
    p2 = parse_file(str(EXAMPLE / "p2.il"))
    assert [(g.name, g.kind, g.access, g.operand.address()) for g in p1.globals] == [
        ("IN1", "bit", "WRITE", "M10.0"), ("CNT", "word", "WRITE", "MW20"),
        ("RST", "bit", "READ", "M10.1")]
    assert [(g.name, g.kind, g.access, g.operand.address()) for g in p2.globals] == [
        ("IN1", "bit", "READ", "M0.0"), ("CNT", "word", "READ", "MW0"),
        ("RST", "bit", "WRITE", "M0.1")]
    # the names are symbols of the programs
    assert p1.symbols["CNT"].address() == "MW20" and p2.symbols["RST"].address() == "M0.1"
    first = p1.globals[0]
    assert (first.line, first.col, first.text) == (12, 3, "IN1")
    assert first.source == "  IN1  AT M10.0 : WRITE;   // the input, published for " \
                           "Project 2's TON1"


@pytest.mark.parametrize("name", ["p1", "p2"])
def test_example_assembles_in_serial_mode(tmp_path, name):
    proc = bitbyte("asm", EXAMPLE / f"{name}.il", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / f"{name}.hex").read_text().split()[-1] == "01000000"   # END


def test_example_plant_file():
    plant = load_plant(str(EXAMPLE / "plant.toml"))
    assert (plant.clock_mhz, plant.layout, plant.protection) == (100, "compact",
                                                                 "semaphore")
    assert [(c.name, c.program_text, c.period_us) for c in plant.cores] == [
        ("p1", "p1.il", 10000), ("p2", "p2.il", 100000)]
    assert plant.cores[0].program == str(EXAMPLE / "p1.il")
    assert plant.cores[0].stimulus == str(EXAMPLE / "p1.stim.csv")
    assert plant.cores[1].stimulus is None
    assert (plant.cores[1].line, plant.cores[1].col) == (12, 1)


def test_example_stimulus_is_valid_for_p1():
    from bitbyte.lang.stimulus import load_stimulus
    plant = load_plant(str(EXAMPLE / "plant.toml"))
    program = parse_file(plant.cores[0].program)
    stim = load_stimulus(plant.cores[0].stimulus, program.symbols, plant.config())
    assert stim.kind == "t_us" and len(stim.rows) == 26


def test_p1_alone_counts_the_pulses_of_in1():
    """Project 1 on one core (RST's local copy stays 0): the 10th pulse, rising at
    5 ms + 9 * 40 ms = 365 ms, makes CNT = 10 and OUT1 = 1.  10 kHz clock (a scan
    of a few ms, well inside the 20 ms pulses): 10 clocks per ms."""
    from fractions import Fraction

    from bitbyte.lang.config import Config
    from bitbyte.ref.refsim import refsim_trace
    from bitbyte.lang.stimulus import load_stimulus
    config = Config(clock_mhz=0.01)
    program = parse_file(str(EXAMPLE / "p1.il"), config)
    stim = load_stimulus(str(EXAMPLE / "p1.stim.csv"), program.symbols, config)
    stim.clock_mhz = Fraction(1, 100)
    _, records, fault = refsim_trace(program, config=config, stimulus=stim,
                                     watch=["CNT"], until_us=380000)
    assert not fault
    before = [r for r in records if r.end_clock < 3650]
    assert max(r.values["CNT"] for r in before) == 9
    assert all(r.values["Q0.0"] == 0 for r in before)
    assert (records[-1].values["CNT"], records[-1].values["Q0.0"]) == (10, 1)


def test_p2_alone_sets_rst_after_5_s(tmp_path):
    """Project 2 with its precycle stood in for by two instructions (IN1 := I0.0,
    CNT := IW0): IN1 held from t = 0 gives RST = 1 from the first scan whose SD runs
    at t >= 5 s; OUT2 = (CNT > 3).  1 kHz clock: one clock per ms."""
    from fractions import Fraction

    from bitbyte.lang.config import Config
    from bitbyte.lang.parser import parse
    from bitbyte.ref.refsim import refsim_trace
    from bitbyte.lang.stimulus import load_stimulus
    source = (EXAMPLE / "p2.il").read_text().replace(
        "END_VAR\n      LD    IN1", "END_VAR\n LD I0.0\n = IN1\n L IW0\n T CNT\n"
        "      LD    IN1", 1)
    config = Config(clock_mhz=0.001)
    program = parse("p2x.il", source, config)
    for cnt, out2 in ((4, 1), (3, 0)):
        (tmp_path / "s.csv").write_text(f"t_us,I0.0,IW0\n0,1,{cnt}\n")
        stim = load_stimulus(str(tmp_path / "s.csv"), program.symbols, config)
        stim.clock_mhz = Fraction(1, 1000)
        _, records, _ = refsim_trace(program, config=config, stimulus=stim,
                                     watch=["RST"], until_us=5200000)
        assert all(r.values["RST"] == 0 for r in records if r.end_clock < 5000)
        assert records[-1].values["RST"] == 1
        assert {r.values["Q0.0"] for r in records} == {out2}


def test_example_map_compact():
    shared = link(load_plant(str(EXAMPLE / "plant.toml")))
    # p1 writes IN1 (bit) and CNT (word): sector SH_p1 = bits first (IN1 -> SH0.0,
    # one word for up to 32 bits), then CNT -> SH1; p2 writes RST -> SH_p2 = SH2.
    assert rows(shared) == [
        ("IN1", "bit", "p1", ["p2"], "SH0.0", "SH_p1"),
        ("CNT", "word", "p1", ["p2"], "SH1", "SH_p1"),
        ("RST", "bit", "p2", ["p1"], "SH2.0", "SH_p2"),
    ]
    assert [(s.name, s.writer, s.start, s.length) for s in shared.sectors] == [
        ("SH_p1", "p1", 0, 2), ("SH_p2", "p2", 2, 1)]
    assert shared.size_words == 3
    assert copies(shared.core("p1")) == (
        [("SH_p2", 2, 1, [("SH2.0", "M10.1", "RST")])],
        [("SH_p1", 0, 2, [("SH0.0", "M10.0", "IN1"), ("SH1", "MW20", "CNT")])])
    assert copies(shared.core("p2")) == (
        [("SH_p1", 0, 2, [("SH0.0", "M0.0", "IN1"), ("SH1", "MW0", "CNT")])],
        [("SH_p2", 2, 1, [("SH2.0", "M0.1", "RST")])])
    assert all(c.is_burst for plan in shared.cores for c in plan.precycle + plan.postcycle)


def test_example_map_random(tmp_path):
    plant = tmp_path / "plant.toml"
    plant.write_text(plant_text("random", EXAMPLE / "p1.il", EXAMPLE / "p2.il"))
    shared = link(load_plant(str(plant)))
    # R = 16 words (3 variables, at least 16).  crc32 mod 16, names in alphabetical
    # order: CNT 0x8F611DED -> 13; IN1 0xBF2E0DEC -> 12, next to CNT, so 13 (taken),
    # 14 (next to 13), 15; RST 0x6DE9B8B6 -> 6.
    assert rows(shared) == [
        ("RST", "bit", "p2", ["p1"], "SH6.0", None),
        ("CNT", "word", "p1", ["p2"], "SH13", None),
        ("IN1", "bit", "p1", ["p2"], "SH15.0", None),
    ]
    assert shared.sectors == [] and shared.size_words == 16
    # one copy per variable, in the core's declaration order
    assert copies(shared.core("p1")) == (
        [(None, 6, 1, [("SH6.0", "M10.1", "RST")])],
        [(None, 15, 1, [("SH15.0", "M10.0", "IN1")]),
         (None, 13, 1, [("SH13", "MW20", "CNT")])])
    assert copies(shared.core("p2")) == (
        [(None, 15, 1, [("SH15.0", "M0.0", "IN1")]),
         (None, 13, 1, [("SH13", "MW0", "CNT")])],
        [(None, 6, 1, [("SH6.0", "M0.1", "RST")])])


def test_link_command_prints_the_map_and_the_plan():
    proc = bitbyte("link", EXAMPLE / "plant.toml")
    assert proc.returncode == 0, proc.stderr
    lines = [line.split() for line in proc.stdout.splitlines()]
    assert ["name", "kind", "writer", "readers", "address", "sector"] in lines
    assert ["IN1", "bit", "p1", "p2", "SH0.0", "SH_p1"] in lines
    assert ["CNT", "word", "p1", "p2", "SH1", "SH_p1"] in lines
    assert ["RST", "bit", "p2", "p1", "SH2.0", "SH_p2"] in lines
    assert ["SH_p1", "p1", "SH0", "2"] in lines and ["SH_p2", "p2", "SH2", "1"] in lines
    text = proc.stdout
    assert "p1:\n  precycle:\n    burst SH_p2 [SH2, 1 word]: SH2.0 -> M10.1 (RST)\n" \
           "  postcycle:\n    burst SH_p1 [SH0..SH1, 2 words]: M10.0 -> SH0.0 (IN1), " \
           "MW20 -> SH1 (CNT)\n" in text
    assert "p2:\n  precycle:\n    burst SH_p1 [SH0..SH1, 2 words]: SH0.0 -> M0.0 (IN1), " \
           "SH1 -> MW0 (CNT)\n  postcycle:\n    burst SH_p2 [SH2, 1 word]: M0.1 -> " \
           "SH2.0 (RST)\n" in text
    assert proc.stdout == format_map(link(load_plant(str(EXAMPLE / "plant.toml"))))


def test_run_plant_command_line(tmp_path):
    """`run PLANT.toml` runs the plant; what only a single CPU takes is refused. (The
    example at 1 MHz, plant_sim.toml: its scans as in time, a hundredth of the clocks.)"""
    proc = bitbyte("run", EXAMPLE / "plant_sim.toml", "--until-us", "25000",
                   "--trace", tmp_path / "T.csv", "--watch", "p2.MW0")
    assert proc.returncode == 0, proc.stderr
    assert "core p1" in proc.stdout and "core p2" in proc.stdout
    p1 = (tmp_path / "T.p1.csv").read_text().splitlines()
    p2 = (tmp_path / "T.p2.csv").read_text().splitlines()
    assert p1[0] == "scan,t_us,cycles,pre,post,sem_wait,copy_fail,overrun,Q0.0"
    assert p2[0] == "scan,t_us,cycles,pre,post,sem_wait,copy_fail,overrun,Q0.0,MW0"
    # each core until its first scan that ends at or after 25 ms: 0..3 and 0..1
    assert len(p1) == 1 + 4 and len(p2) == 1 + 2
    for args, message in (
            ((), "running a plant needs --until-us T"),
            (("--until-us", "10", "--mode", "parallel"), "--mode does not apply to a plant"),
            (("--until-us", "10", "--watch", "p3.M0.0"), "--watch: 'p3.M0.0' is not"),
            (("--until-us", "10", "--watch", "MW0"), "--watch: 'MW0' is not")):
        proc = bitbyte("run", EXAMPLE / "plant.toml", *args)
        assert proc.returncode == 2, (args, proc.stderr)
        assert message in proc.stderr, proc.stderr
        assert "Traceback" not in proc.stderr


# ---------------------------------------------------------------------------------------
# Layout rules beyond the example
# ---------------------------------------------------------------------------------------

def write_plant(tmp_path, programs: dict[str, str], layout="compact", extra=""):
    """A plant with one core per program (name -> source), period 1000 µs each."""
    text = f'layout = "{layout}"\n{extra}'
    for name, source in programs.items():
        (tmp_path / f"{name}.il").write_text(source)
        text += f'\n[[core]]\nname = "{name}"\nprogram = "{name}.il"\nperiod_us = 1000\n'
    (tmp_path / "plant.toml").write_text(text)
    return tmp_path / "plant.toml"


def globals_block(*decls):
    return "VAR_GLOBAL\n" + "".join(f"  {d};\n" for d in decls) + "END_VAR\n"


def test_compact_packs_33_bits_into_two_words_then_the_words(tmp_path):
    a = globals_block("W1 AT MW0 : WRITE",
                      *(f"B{i} AT M{i // 8}.{i % 8} : WRITE" for i in range(33)),
                      "W2 AT MW1 : WRITE")
    b = globals_block("B32 AT M0.0 : READ", "W2 AT MW5 : READ", "Own AT MW9 : WRITE")
    shared = link(load_plant(str(write_plant(tmp_path, {"a": a, "b": b}))))
    got = {v.name: (v.address(), v.sector) for v in shared.variables}
    assert got["B0"] == ("SH0.0", "SH_a") and got["B31"] == ("SH0.31", "SH_a")
    assert got["B32"] == ("SH1.0", "SH_a")
    assert got["W1"] == ("SH2", "SH_a") and got["W2"] == ("SH3", "SH_a")
    assert got["OWN"] == ("SH4", "SH_b")
    assert [(s.name, s.start, s.length) for s in shared.sectors] == [
        ("SH_a", 0, 4), ("SH_b", 4, 1)]
    # b reads two variables of SH_a: one burst from the first to the last word it needs
    pre, post = copies(shared.core("b"))
    assert pre == [("SH_a", 1, 3, [("SH1.0", "M0.0", "B32"), ("SH3", "MW5", "W2")])]
    assert post == [("SH_b", 4, 1, [("SH4", "MW9", "OWN")])]
    # a writes its whole sector in one burst
    (post_a,) = shared.core("a").postcycle
    assert (post_a.start, post_a.length, len(post_a.items)) == (0, 4, 35)


def test_three_cores_a_variable_without_readers_and_one_with_two(tmp_path):
    a = globals_block("Alone AT M0.0 : WRITE", "Both AT MW0 : WRITE")
    b = globals_block("Both AT MW3 : READ")
    c = "NOP\n" + globals_block("Both AT MW7 : READ")
    shared = link(load_plant(str(write_plant(tmp_path, {"a": a, "b": b, "c": c}))))
    assert rows(shared) == [("ALONE", "bit", "a", [], "SH0.0", "SH_a"),
                            ("BOTH", "word", "a", ["b", "c"], "SH1", "SH_a")]
    assert copies(shared.core("c"))[0] == [("SH_a", 1, 1, [("SH1", "MW7", "BOTH")])]
    assert shared.core("b").postcycle == [] and shared.core("c").postcycle == []


def test_random_precycle_takes_its_writers_one_after_the_other(tmp_path):
    """A reader declaring two writers' variables interleaved copies them writer by
    writer (plant order), each writer's in its declaration order: one writer's
    variables in one stretch (what keeps ping-pong tear-free)."""
    a = globals_block("A0 AT MW0 : WRITE", "A1 AT MW1 : WRITE")
    b = globals_block("B0 AT MW0 : WRITE", "B1 AT MW1 : WRITE")
    r = globals_block("B1 AT MW11 : READ", "A1 AT MW1 : READ", "B0 AT MW10 : READ",
                      "A0 AT MW0 : READ")
    shared = link(load_plant(str(write_plant(tmp_path, {"a": a, "b": b, "r": r},
                                             "random"))))
    order = [c.items[0].name for c in shared.core("r").precycle]
    assert order == ["A1", "A0", "B1", "B0"]
    assert all(c.sector is None and len(c.items) == 1 for c in shared.core("r").precycle)


def test_random_layout_never_puts_two_variables_side_by_side(tmp_path):
    names = [f"V{i}" for i in range(40)]
    a = globals_block(*(f"{n} AT MW{i} : WRITE" for i, n in enumerate(names)))
    b = globals_block(*(f"{n} AT M{i // 8}.{i % 8} : READ" for i, n in enumerate(names)))
    with pytest.raises(SourceError) as info:                 # kinds differ, at b
        link(load_plant(str(write_plant(tmp_path, {"a": a, "b": b}, "random"))))
    assert (info.value.line, info.value.col) == (2, 3)
    b = globals_block(*(f"{n} AT MW{i} : READ" for i, n in enumerate(names)))
    shared = link(load_plant(str(write_plant(tmp_path, {"a": a, "b": b}, "random"))))
    words = sorted(v.word for v in shared.variables)
    assert shared.size_words == 256                       # 4 * 40 -> 256
    assert len(set(words)) == 40 and all(y - x >= 2 for x, y in zip(words, words[1:]))
    assert len(shared.core("a").postcycle) == 40 and len(shared.core("b").precycle) == 40


# ---------------------------------------------------------------------------------------
# The parser's side: VAR_GLOBAL
# ---------------------------------------------------------------------------------------

def test_var_global_several_per_line_quotes_and_case(tmp_path):
    src = tmp_path / "g.il"
    src.write_text('VAR_GLOBAL // shared\n  in1 AT M 1.0:write; "Cnt" AT mw 2 : Read\n'
                   "END_VAR\nLD IN1\n= Q0.0\nL cnt\nT MW3\n")
    program = parse_file(str(src))
    assert [(g.name, g.text, g.kind, g.access, g.operand.address(), g.line, g.col)
            for g in program.globals] == [
        ("IN1", "in1", "bit", "WRITE", "M1.0", 2, 3),
        ("CNT", "Cnt", "word", "READ", "MW2", 2, 23)]
    assert program.instrs[0].operand.address() == "M1.0"
    assert program.instrs[2].operand.address() == "MW2"


# ---------------------------------------------------------------------------------------
# Every error class: file:line:col, exit 1, never a traceback
# ---------------------------------------------------------------------------------------

A_OK = ("VAR_GLOBAL\n"
        "  IN1 AT M10.0 : WRITE;\n"
        "  CNT AT MW20 : WRITE;\n"
        "  RST AT M10.1 : READ;\n"
        "END_VAR\n"
        "LD IN1\n= Q0.0\n")
B_OK = ("VAR_GLOBAL\n"
        "  IN1 AT M0.0 : READ; CNT AT MW0 : READ\n"
        "  RST AT M0.1 : WRITE\n"
        "END_VAR\n")
PLANT_OK = ('clock_mhz = 100\n'             # 1
            'layout = "compact"\n'          # 2
            'protection = "semaphore"\n'    # 3
            '\n'                            # 4
            '[[core]]\n'                    # 5
            'name = "a"\n'                  # 6
            'program = "a.il"\n'            # 7
            'period_us = 10000\n'           # 8
            '\n'                            # 9
            '[[core]]\n'                    # 10
            'name = "b"\n'                  # 11
            'program = "b.il"\n'            # 12
            'period_us = 100000\n')         # 13

# (what, a.il, b.il, plant.toml, file of the error, line, col, message part)
ERRORS = [
    ("two writers", A_OK, B_OK.replace("CNT AT MW0 : READ", "CNT AT MW0 : WRITE"),
     PLANT_OK, "b.il", 2, 23, "two writers"),
    ("no writer", A_OK, B_OK.replace("RST AT M0.1 : WRITE", "RST AT M0.1 : READ"),
     PLANT_OK, "a.il", 4, 3, "no writer"),
    ("kinds differ", A_OK, B_OK.replace("CNT AT MW0", "CNT AT M0.2"),
     PLANT_OK, "b.il", 2, 23, "kinds differ"),
    ("duplicate name", A_OK.replace("CNT AT MW20 : WRITE;",
                                    "CNT AT MW20 : WRITE; in1 AT M10.2 : READ;"),
     B_OK, PLANT_OK, "a.il", 3, 24, "duplicate symbol `in1`"),
    ("missing END_VAR", "VAR_GLOBAL\n  IN1 AT M10.0 : WRITE;\n", B_OK, PLANT_OK,
     "a.il", 1, 1, "missing END_VAR"),
    ("missing END_VAR before code", A_OK.replace("END_VAR\n", ""), B_OK, PLANT_OK,
     "a.il", 5, 1, "missing END_VAR"),
    ("wrong area", A_OK.replace("M10.0 : WRITE", "Q0.0 : WRITE"), B_OK, PLANT_OK,
     "a.il", 2, 10, "operand of the wrong kind"),
    ("word in M", A_OK.replace("CNT AT MW20", "CNT AT IW2"), B_OK, PLANT_OK,
     "a.il", 3, 10, "operand of the wrong kind"),
    ("missing colon", A_OK.replace("MW20 : WRITE", "MW20 WRITE"), B_OK, PLANT_OK,
     "a.il", 3, 14, "missing `:`"),
    ("unknown access", A_OK.replace("MW20 : WRITE", "MW20 : WRITES"), B_OK, PLANT_OK,
     "a.il", 3, 17, "unknown access `WRITES`"),
    ("TOML syntax", A_OK, B_OK, PLANT_OK.replace('"compact"', "compact"),
     "plant.toml", 2, 10, "TOML syntax error"),
    ("TOML unterminated", A_OK, B_OK, PLANT_OK.replace('"a.il"', '"a.il'),
     "plant.toml", 7, 16, "TOML syntax error"),
    ("unknown key", A_OK, B_OK, PLANT_OK.replace("period_us = 100000", "perod_us = 1"),
     "plant.toml", 13, 1, "unknown key `perod_us`"),
    ("unknown top key", A_OK, B_OK, "clocks = 5\n" + PLANT_OK,
     "plant.toml", 1, 1, "unknown key `clocks`"),
    ("bad enum", A_OK, B_OK, PLANT_OK.replace('"semaphore"', '"mutex"'),
     "plant.toml", 3, 14, "bad value `mutex` for `protection`"),
    ("bad layout", A_OK, B_OK, PLANT_OK.replace('"compact"', '"tight"'),
     "plant.toml", 2, 10, "bad value `tight` for `layout`"),
    ("wrong type", A_OK, B_OK, PLANT_OK.replace("10000\n", '"10 ms"\n'),
     "plant.toml", 8, 13, "`period_us` must be a whole number"),
    ("negative period", A_OK, B_OK, PLANT_OK.replace("10000\n", "-1\n"),
     "plant.toml", 8, 13, "out of range"),
    ("missing program key", A_OK, B_OK, PLANT_OK.replace('program = "b.il"\n', ""),
     "plant.toml", 10, 1, "missing `program`"),
    ("missing program file", A_OK, B_OK, PLANT_OK.replace('"b.il"', '"nope.il"'),
     "plant.toml", 12, 11, "program file `nope.il` not found"),
    ("duplicate core", A_OK, B_OK, PLANT_OK.replace('name = "b"', 'name = "A"'),
     "plant.toml", 11, 8, "duplicate core name `A`"),
    ("bad clock", A_OK, B_OK, PLANT_OK.replace("clock_mhz = 100", "clock_mhz = 0"),
     "plant.toml", 1, 13, "clock_mhz"),
]


@pytest.mark.parametrize("what, a, b, plant, where, line, col, part", ERRORS,
                         ids=[e[0] for e in ERRORS])
def test_error_classes_through_the_cli(tmp_path, what, a, b, plant, where, line, col,
                                       part):
    (tmp_path / "a.il").write_text(a)
    (tmp_path / "b.il").write_text(b)
    (tmp_path / "plant.toml").write_text(plant)
    proc = bitbyte("link", tmp_path / "plant.toml")
    assert proc.returncode == 1, proc.stdout + proc.stderr
    assert proc.stdout == ""
    head, source, caret = proc.stderr.rstrip("\n").split("\n")
    assert head.startswith(f"{tmp_path / where}:{line}:{col}: "), proc.stderr
    assert part in head, proc.stderr
    assert caret == " " * (col - 1) + "^"
    text = (tmp_path / where).read_text().split("\n")
    assert source == text[line - 1]


def test_missing_plant_file_and_two_cores_mentioned_in_conflicts(tmp_path):
    proc = bitbyte("link", tmp_path / "none.toml")
    assert proc.returncode == 1 and "cannot read" in proc.stderr
    (tmp_path / "a.il").write_text(A_OK)
    (tmp_path / "b.il").write_text(B_OK.replace("CNT AT MW0 : READ", "CNT AT MW0 : WRITE"))
    (tmp_path / "plant.toml").write_text(PLANT_OK)
    head = bitbyte("link", tmp_path / "plant.toml").stderr.splitlines()[0]
    assert f"core `a` already writes it ({tmp_path / 'a.il'}:3:3)" in head


def test_first_conflict_in_plant_order_wins(tmp_path):
    # b has two problems: RST (line 3) has no writer, IN1 (line 2) a second writer
    b = B_OK.replace("IN1 AT M0.0 : READ", "IN1 AT M0.0 : WRITE").replace(
        "RST AT M0.1 : WRITE", "RST AT M0.1 : READ")
    (tmp_path / "a.il").write_text(A_OK)
    (tmp_path / "b.il").write_text(b)
    (tmp_path / "plant.toml").write_text(PLANT_OK)
    with pytest.raises(SourceError) as info:
        link(load_plant(str(tmp_path / "plant.toml")))
    # RST's first reader is a (a.il:4:3), before anything in b
    assert (info.value.path, info.value.line, info.value.col) == (
        str(tmp_path / "a.il"), 4, 3)


def test_toml_error_positions_come_from_tomllib(tmp_path):
    path = tmp_path / "plant.toml"
    path.write_text('[[core]]\nname = "a"\nname = "b"\n')
    with pytest.raises(SourceError) as info:
        load_plant(str(path))
    assert (info.value.line, info.value.col) == (3, 11)
    path.write_bytes(b'layout = "\xffcompact"\n')
    with pytest.raises(SourceError) as info:
        load_plant(str(path))
    assert (info.value.line, info.value.col) == (1, 11)
    assert "UTF-8" in info.value.message
    path.write_text("[[core]]\nname = 'a'\n[core]\n")
    with pytest.raises(SourceError) as info:
        load_plant(str(path))
    assert info.value.line == 3 and "TOML syntax error" in info.value.message


def test_inline_core_tables_fall_back_to_the_core_key(tmp_path):
    (tmp_path / "a.il").write_text(A_OK)
    path = tmp_path / "plant.toml"
    path.write_text('clock_mhz = 50\ncore = [{name = "a", program = "a.il", '
                    'period_us = 1, colour = 3}]\n')
    with pytest.raises(SourceError) as info:
        load_plant(str(path))
    assert (info.value.line, info.value.col) == (2, 1)
    assert "unknown key `colour`" in info.value.message


# ---------------------------------------------------------------------------------------
# Fuzz: garbage, truncations, mutations, token soup -> exit 0 or a clean error
# ---------------------------------------------------------------------------------------

TOML_TOKENS = ["[[core]]", "[core]", "[[core", "name", "program", "period_us",
               "stimulus", "layout", "protection", "clock_mhz", "=", " = ", '"p1"',
               '"p2"', '"p1.il"', '"p2.il"', '"compact"', '"random"', '"none"', "10000",
               "-1", "1.5", "1e999", "nan", "true", "[", "]", "{", "}", ",", "\n", "\n",
               "\n", '"""', "'''", "#", "x", ".", "'", '"', "1979-05-27", "\t", " ",
               "\r\n", "\r", "\x00", "é", "9" * 5000, "core.name", "mode", "exchange",
               '"parallel"', '"free"', '"queue"', '"marker"']
POSITION = re.compile(r"^.+?:\d+:\d+: \S")


def run_main(path) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = cli.main(["link", str(path)])
    return code, out.getvalue(), err.getvalue()


def fuzz_inputs(rng: random.Random, count: int):
    good = (EXAMPLE / "plant.toml").read_bytes()
    for n in range(count):
        kind = n % 5
        if kind == 0:
            yield bytes(rng.randrange(256) for _ in range(rng.randrange(60)))
        elif kind == 1:
            yield good[: rng.randrange(len(good) + 1)]
        elif kind == 2:
            data = bytearray(good)
            for _ in range(rng.randrange(1, 4)):
                pos = rng.randrange(len(data) + 1)
                if rng.random() < 0.5 and pos < len(data):
                    del data[pos]
                else:
                    data[pos:pos] = bytes([rng.randrange(256)])
            yield bytes(data)
        else:
            yield "".join(rng.choice(TOML_TOKENS)
                          for _ in range(rng.randrange(40))).encode("utf-8", "replace")


def test_fuzz_link_gives_a_map_or_a_clean_error(tmp_path):
    for name in ("p1", "p2"):
        shutil.copy(EXAMPLE / f"{name}.il", tmp_path / f"{name}.il")
    shutil.copy(EXAMPLE / "p1.stim.csv", tmp_path / "p1.stim.csv")
    path = tmp_path / "plant.toml"
    rng = random.Random(SEED)
    results = {0: 0, 1: 0}
    for data in fuzz_inputs(rng, 400):
        path.write_bytes(data)
        code, out, err = run_main(path)
        assert code in (0, 1), (data, err)
        results[code] += 1
        if code == 1:
            lines = err.rstrip("\n").split("\n")
            assert POSITION.match(lines[0]), (data, err)
            assert lines[0].startswith(str(tmp_path)), (data, err)
            assert len(lines) == 3 and lines[2].endswith("^"), (data, err)
        else:
            assert "shared memory" in out and err == ""
    assert results[1] > 100 and results[0] >= 1, results


def test_fuzz_through_the_real_command(tmp_path):
    """A few of the same inputs as a user runs them: no traceback, exit 0 or 1."""
    for name in ("p1", "p2"):
        shutil.copy(EXAMPLE / f"{name}.il", tmp_path / f"{name}.il")
    shutil.copy(EXAMPLE / "p1.stim.csv", tmp_path / "p1.stim.csv")
    path = tmp_path / "plant.toml"
    rng = random.Random(SEED + 1)
    for data in fuzz_inputs(rng, 15):
        path.write_bytes(data)
        proc = bitbyte("link", path)
        assert proc.returncode in (0, 1), proc.stderr


NAMES = ["Va", "Vb", "Vc", "Vd", "Ve", "Vf"]
CORES = ("a", "b", "c")


def random_plant(rng: random.Random) -> tuple[dict[str, str], str]:
    """Three programs sharing some of NAMES consistently (one writer, one kind),
    then perhaps one fault: "" (none), "two writers", "no writer", "kinds differ"."""
    decls: dict[str, list[tuple[str, str, str]]] = {c: [] for c in CORES}
    for name in rng.sample(NAMES, rng.randrange(1, len(NAMES) + 1)):
        kind = rng.choice(["bit", "word"])
        writer = rng.choice(CORES)
        users = [c for c in CORES if c == writer or rng.random() < 0.5]
        for c in users:
            decls[c].append((name, kind, "WRITE" if c == writer else "READ"))
    fault = rng.choice(["", "", "two writers", "no writer", "kinds differ"])
    core = rng.choice([c for c in CORES if decls[c]])
    i = rng.randrange(len(decls[core]))
    name, kind, access = decls[core][i]
    if fault == "two writers":
        readers = [c for c in CORES if c != core and all(d[0] != name for d in decls[c])]
        if access == "WRITE" and readers:          # a core that had none declares it
            decls[readers[0]].append((name, kind, "WRITE"))
        elif access == "READ":
            decls[core][i] = (name, kind, "WRITE")
        else:
            fault = ""
    elif fault == "no writer":
        for c in CORES:
            decls[c] = [(n, k, "READ") if n == name else (n, k, a) for n, k, a in decls[c]]
    elif fault == "kinds differ":
        users = [c for c in CORES if any(d[0] == name for d in decls[c])]
        if len(users) > 1:
            decls[core][i] = (name, "word" if kind == "bit" else "bit", access)
        else:
            fault = ""
    programs = {}
    for c in CORES:
        order = decls[c][:]
        rng.shuffle(order)
        lines = []
        for n, (name, kind, access) in enumerate(order):
            local = f"M{n // 8}.{n % 8}" if kind == "bit" else f"MW{n}"
            lines.append(f"{name} AT {local} : {access}")
        programs[c] = globals_block(*lines) + "NOP\n"
    return programs, fault


def test_fuzz_random_declarations_link_consistently(tmp_path):
    """Random VAR_GLOBAL sets on three cores, consistent or with one fault: a
    fault gives its error in one of the programs at a declaration, a consistent
    plant a map that keeps every rule of docs/multicore.md."""
    rng = random.Random(SEED + 2)
    seen = {"": 0, "two writers": 0, "no writer": 0, "kinds differ": 0}
    for n in range(200):
        programs, fault = random_plant(rng)
        layout = "compact" if n % 2 else "random"
        path = write_plant(tmp_path, programs, layout)
        seen[fault] += 1
        try:
            shared = link(load_plant(str(path)))
        except SourceError as err:
            assert fault, format(err)
            assert err.message.startswith(fault), (fault, str(err))
            assert err.path in {str(tmp_path / f"{c}.il") for c in programs}
            assert err.line >= 2 and err.col == 3
            continue
        assert not fault, (fault, programs)
        check_map(shared, layout)
    assert all(count >= 10 for count in seen.values()), seen


def check_map(shared, layout):
    decls = {}
    for plan in shared.cores:
        for g in plan.program.globals:
            decls.setdefault(g.name, []).append((plan.name, g))
    assert {v.name for v in shared.variables} == set(decls)
    places = set()
    for v in shared.variables:
        (writer,) = [c for c, g in decls[v.name] if g.access == "WRITE"]
        assert v.writer == writer
        assert v.readers == [c for c, g in decls[v.name] if g.access == "READ"]
        assert {g.kind for _, g in decls[v.name]} == {v.kind}
        assert (v.bit is None) == (v.kind == "word")
        assert (v.word, v.bit) not in places and 0 <= v.word < shared.size_words
        places.add((v.word, v.bit))
    if layout == "compact":
        start = 0
        for s in shared.sectors:
            assert s.start == start and s.length >= 1
            start += s.length
            own = [v for v in shared.variables if v.sector == s.name]
            assert own and all(v.writer == s.writer for v in own)
            assert all(s.start <= v.word < s.start + s.length for v in own)
            bit_words = {v.word for v in own if v.kind == "bit"}
            word_words = [v.word for v in own if v.kind == "word"]
            assert all(b < w for b in bit_words for w in word_words)    # bits first
        assert start == shared.size_words
    else:
        words = sorted(v.word for v in shared.variables)
        assert all(y - x >= 2 for x, y in zip(words, words[1:]))
    by_name = {v.name: v for v in shared.variables}
    for plan in shared.cores:
        for copies_, access in ((plan.precycle, "READ"), (plan.postcycle, "WRITE")):
            items = [i for c in copies_ for i in c.items]
            assert sorted(i.name for i in items) == sorted(
                g.name for g in plan.program.globals if g.access == access)
            for c in copies_:
                assert c.is_burst == (layout == "compact")
                for i in c.items:
                    assert c.start <= i.word < c.start + c.length
                    assert (i.word, i.bit) == (by_name[i.name].word, by_name[i.name].bit)
