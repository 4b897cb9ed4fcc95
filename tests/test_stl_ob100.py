"""OB 100, the startup (issue 19; docs/s7.md "OB 100: the startup"): an S7 source's
OB 100 runs once, in the first hardware scan, before OB 1's scan 0; that scan is no
scan of the trace and its clocks are not scan 0's.  Checked against awlsim (which
runs OB 100 in `startup`, before the first `runCycle`) scan for scan, on the
reference interpreter and on the Verilator harness in serial and parallel mode; the
comparison is shown to catch an OB 100 run every scan, never run, or traced as
scan 0."""
from __future__ import annotations

import json
import re
import textwrap
from pathlib import Path

import pytest

from asmcheck import assert_refused
from awlsim_oracle import awlsim_scans, bitbyte_scans, equal_or_rejected, timer_scans
from stlgen import IN_WORDS, random_inputs, random_program
from stlgen import WORDS as WORDS_RANDOM
from tracecmp import first_difference, transition_difference, transitions

from bitbyte import cli
from bitbyte.lang.config import Config
from bitbyte.lang.definition import DEF
from bitbyte.lang.errors import SourceError
from bitbyte.lang.parser import parse_file
from bitbyte.lang.stimulus import load_stimulus
from bitbyte.ref.refsim import RefSim, refsim_trace
from bitbyte.run.prepare import prepare_run


def block(number: int, body: str, head: str = "") -> str:
    return (f"ORGANIZATION_BLOCK OB {number}\n{head}BEGIN\nNETWORK\nTITLE =\n"
            + textwrap.dedent(body).strip("\n") + "\nEND_ORGANIZATION_BLOCK\n\n")


# OB 100 sets an output and markers, loads words, presets a counter, reads an input
# (scan 0's, as awlsim reads its inputs before OB 100) and jumps over a part with
# `SPBN`/`BEB` at labels also spelt in OB 1; OB 1 reads all of it and goes on from there.
STARTUP_DE = block(100, """
      SET
      =     A 0.1
      S     M 0.0
      L     100
      T     MW 10
      L     C#5
      S     Z 1
      U     E 0.3
      =     M 0.2
      SPBN  M1
      L     -7
      T     MW 12
M1:   U     E 0.2
      BEB
      S     M 0.3
""") + block(1, """
      U     M 0.0
      UN    E 0.2
      =     A 0.0
      U     E 0.0
      ZV    Z 1
      U     E 0.1
      ZR    Z 1
      U     Z 1
      =     A 0.2
      L     Z 1
      T     MW 14
      U     M 0.2
      O     M 0.3
      =     A 0.3
      L     MW 10
      L     MW 12
      +I
      T     MW 10
      U     E 0.1
      SPBN  M1
      R     M 0.0
      L     0
      T     MW 12
M1:   U     E 0.0
      FP    M 1.0
      =     M 0.4
""")

SWAPS = {"U": "A", "UN": "AN", "SPBN": "JCN", "BEB": "BEC", "ZV": "CU", "ZR": "CD",
         "SE": "SD", "SV": "SE"}
AREAS = {"E": "I", "A": "Q", "Z": "C"}


def english(text: str) -> str:
    """The German program in English mnemonics (statement lines only)."""
    out = []
    for line in text.splitlines():
        label, _, rest = line.rpartition(":") if ":" in line else ("", "", line)
        words = rest.split()
        if not words or words[0] in ("ORGANIZATION_BLOCK", "END_ORGANIZATION_BLOCK",
                                     "BEGIN", "NETWORK", "TITLE"):
            out.append(line)
            continue
        words[0] = SWAPS.get(words[0], words[0])
        if len(words) > 1:
            words[1] = AREAS.get(words[1], words[1])
        out.append((label + ": " if label else "      ") + " ".join(words))
    return "\n".join(out) + "\n"


WORDS = ("MW10", "MW12", "MW14")


def inputs(scans: int = 24) -> list[dict[int, int]]:
    """E 0.3 at scans 0 and 1 (OB 100 reads it), pulses on E 0.0 / E 0.1 / E 0.2."""
    rows = []
    for k in range(scans):
        image = 0b1000 if k < 2 else 0
        image |= 1 if k % 3 == 1 else 0
        image |= 2 if k in (5, 6, 14) else 0
        image |= 4 if k in (9, 10) else 0
        rows.append({0: image})
    return rows


def startup_file(tmp: Path, lang: str) -> Path:
    path = tmp / f"startup_{lang}.awl"
    path.write_text(STARTUP_DE if lang == "de" else english(STARTUP_DE))
    return path


def compare(path: Path, lang: str, tmp: Path, stimulus, **kw):
    expected = awlsim_scans(path, stimulus, mnemonics=lang, words=WORDS)
    got = bitbyte_scans(path, stimulus, tmp, words=WORDS, **kw)
    return expected, got, first_difference(expected, got)


def test_english_translation_of_the_program():
    text = english(STARTUP_DE + TIMER_DE)
    assert not re.search(r"\b(U|UN|E|Z|SPBN|BEB|ZV|ZR|SV)\b", text), text
    for statement in ("JCN M1", "BEC", "CU C 1", "A I 0.0", "= Q 0.1", "S C 1",
                      "SD T 1", "SE T 2", "M1: A I 0.2"):
        assert statement in text, statement


@pytest.mark.parametrize("lang", ["de", "en"])
@pytest.mark.parametrize("first", [0b1000, 0b0100, 0])
def test_startup_against_awlsim(tmp_path, lang, first):
    """Outputs, markers, words and the counter OB 100 sets, as OB 1 reads them, equal
    awlsim's scan for scan; with E 0.3 / E 0.2 at scan 0 (OB 100's `SPBN`, `BEB`)."""
    stimulus = inputs()
    stimulus[0] = {0: first}
    path = startup_file(tmp_path, lang)
    expected, got, diff = compare(path, lang, tmp_path, stimulus)
    assert diff is None, diff
    assert expected[0]["Q0.1"] == 1 and expected[0]["MW14"] == 5     # from OB 100
    assert expected[0]["Q0.3"] == (first != 0b0100)      # M 0.2 = E 0.3, or no BEB
    assert expected[0]["MW10"] == 100 + (-7 if first & 0b1000 else 0)


def test_startup_on_verilator_serial_and_parallel(tmp_path):
    stimulus = inputs()
    path = startup_file(tmp_path, "de")
    for mode in ("serial", "parallel"):
        expected, got, diff = compare(path, "de", tmp_path, stimulus, sim="verilator",
                                      mode=mode)
        assert diff is None, (mode, diff)
    ref = bitbyte_scans(path, stimulus, tmp_path, words=WORDS)
    ver = bitbyte_scans(path, stimulus, tmp_path, words=WORDS, sim="verilator")
    assert [r["@latch_s"] for r in ref] == [r["@latch_s"] for r in ver]


# --------------------------------------------------------------------------------------
# The comparison fails on a startup run every scan, never, or traced as scan 0

def ob100_body(text: str) -> str:
    return text.split("BEGIN\nNETWORK\nTITLE =\n", 1)[1].split("END_ORGANIZATION_BLOCK")[0]


def test_comparison_catches_wrong_startups(tmp_path, monkeypatch):
    stimulus = inputs()
    path = startup_file(tmp_path, "de")
    expected = awlsim_scans(path, stimulus, mnemonics="de", words=WORDS)
    ob1_text = STARTUP_DE.split("\n\n", 1)[1].strip() + "\n"
    # never: OB 100 dropped
    never = tmp_path / "never.awl"
    never.write_text(ob1_text)
    got = bitbyte_scans(never, stimulus, tmp_path, words=WORDS)
    assert first_difference(expected, got)[0] == 0
    # every scan: OB 100's statements in front of OB 1's (its BEB then ends the scan)
    body = ob100_body(STARTUP_DE).replace("M1", "M9")
    every = tmp_path / "every.awl"
    every.write_text(ob1_text.replace("TITLE =\n", "TITLE =\n" + body, 1))
    got = bitbyte_scans(every, stimulus, tmp_path, words=WORDS)
    assert first_difference(expected, got) is not None
    # traced: the runner ignores startup_scans (the startup scan is trace row 0)
    from bitbyte.lang import stl
    parse = stl.StlFrontEnd.parse

    def untraced(self):
        program = parse(self)
        program.startup_scans = 0
        return program
    monkeypatch.setattr(stl.StlFrontEnd, "parse", untraced)
    for sim in ("ref", "verilator"):
        got = bitbyte_scans(path, stimulus, tmp_path, words=WORDS, sim=sim)
        assert first_difference(expected, got)[0] == 0, sim
    # inputs of OB 100 all 0 (not scan 0's): awlsim without them differs from awlsim
    zero = awlsim_scans(path, [{0: 0}] + stimulus[1:], mnemonics="de", words=WORDS)
    assert first_difference(expected, zero)[0] == 0


# --------------------------------------------------------------------------------------
# Timers started in OB 100

TIMER_DE = block(100, """
      SET
      L     S5T#50MS
      SE    T 1
      L     S5T#30MS
      SV    T 2
""") + block(1, """
      U     T 1
      =     A 0.0
      U     T 2
      =     A 0.1
      U     E 0.0
      L     S5T#20MS
      SE    T 3
      U     T 3
      =     A 0.2
""")


@pytest.mark.parametrize("lang", ["de", "en"])
def test_timer_started_in_ob100(tmp_path, lang):
    """An on-delay started in OB 100 and never executed again runs out at 50 ms of
    the time base; an extended pulse started there is on from scan 0 for 30 ms."""
    text = TIMER_DE if lang == "de" else english(TIMER_DE)
    path = tmp_path / f"timer_{lang}.awl"
    path.write_text(text)
    stimulus = [{0: 1 if 4 <= k < 30 else 0} for k in range(45)]
    expected, got, _ = timer_scans(path, stimulus, tmp_path, mnemonics=lang,
                                   timers=(1, 2, 3), quiet=False, clock_mhz="0.02")
    assert transition_difference(expected, got) is None, (expected, got)
    for column in ("Q0.0", "Q0.1", "Q0.2"):
        assert transitions(expected, column), column
    assert expected[0]["Q0.1"] == 1 and expected[0]["Q0.0"] == 0


# --------------------------------------------------------------------------------------
# Scan 0's clocks do not include OB 100's

def test_scan0_cycles_exclude_the_startup(tmp_path):
    """OB 100 writes a marker OB 1 never reads: every scan's cycles are those of the
    program without OB 100 plus the guard's 2 (`LDN` the started bit, `JC` not
    taken); scan 0 latches when the startup scan ends, which runs the guard (`LDN`,
    `JC` taken), `CLR` (S7's RLO at a block start), OB 100 and `SET`, `=`, `END`."""
    ob1 = block(1, """
      U     E 0.0
      =     A 0.0
      L     MW 10
      L     1
      +I
      T     MW 10
""")
    ob100 = block(100, """
      SET
      =     M 20.0
      L     5
      T     MW 30
""")
    plain, started = tmp_path / "plain.awl", tmp_path / "started.awl"
    plain.write_text(ob1)
    started.write_text(ob100 + ob1)
    stimulus = tmp_path / "s.csv"
    stimulus.write_text("scan,I0.0\n0,1\n3,0\n")
    runs = {}
    for path in (plain, started):
        program = parse_file(str(path))
        _, records, fault = refsim_trace(program, Config(), load_stimulus(str(stimulus)),
                                         ["MW10", "M20.0", "MW30"], scans=5)
        assert not fault
        runs[path.stem] = records
    assert [r.cycles for r in runs["started"]] == [r.cycles + 2 for r in runs["plain"]]
    # the guard, CLR, SET / =, L / T (10 clocks each), SET / = / END
    startup = 1 + DEF.jump_taken_clocks + 1 + 2 + 2 * 10 + 3
    r0 = runs["started"][0]
    assert r0.end_clock - r0.cycles == startup
    assert runs["plain"][0].end_clock - runs["plain"][0].cycles == 0
    assert [r.values["MW10"] for r in runs["started"]] == [1, 2, 3, 4, 5]
    assert r0.values["M20.0"] == 1 and r0.values["MW30"] == 5
    # the CLI's trace on the Verilator harness: the same rows, t_us counted from reset
    trace = tmp_path / "t.csv"
    assert cli.main(["run", str(started), "--stimulus", str(stimulus), "--scans", "5",
                     "--trace", str(trace), "--watch", "MW10"]) == 0
    rows = trace.read_text().splitlines()
    assert rows[0] == "scan,t_us,cycles,Q0.0,MW10"
    c = r0.cycles
    assert rows[1] == f"0,{(startup + c) / 100:g},{c},1,1"
    assert [row.split(",")[0] for row in rows[1:]] == ["0", "1", "2", "3", "4"]


def test_listing_labels_the_startup_part(tmp_path, capsys):
    path = tmp_path / "l.awl"
    path.write_text(block(100, "SET\n= M 20.0") + block(1, "U E 0.0\n= A 0.0"))
    assert cli.main(["asm", str(path), "-o", str(tmp_path)]) == 0
    lst = (tmp_path / "l.lst").read_text()
    assert "\n                OB100:\n" in lst and "OB100.END:" in lst
    words = re.findall(r"^[0-9A-F]{4}  [0-9A-F]{8} +\d+: (.*?)\s*(?:;.*)?$", lst, re.M)
    assert words[:2] == ["ORGANIZATION_BLOCK OB 100"] * 2     # the guard
    program, _, job, _ = prepare_run(str(path), mode="parallel")
    assert program.startup_scans == 1 and job.startup_scans == 1
    # the .json and .lst say how many startup scans (serial and parallel mode)
    plain = tmp_path / "p.awl"
    plain.write_text(block(1, "U E 0.0\n= A 0.0"))
    for mode in ("serial", "parallel"):
        for source, n in ((path, 1), (plain, 0)):
            out = tmp_path / f"{mode}{n}"
            assert cli.main(["asm", str(source), "--mode", mode, "-o", str(out)]) == 0
            assert json.loads((out / f"{source.stem}.json").read_text())[
                "startup_scans"] == n
            lst = (out / f"{source.stem}.lst").read_text()
            assert ("\n; startup scans: 1 (OB 100" in lst) == bool(n), (mode, n)


# --------------------------------------------------------------------------------------
# Errors

@pytest.mark.parametrize("text,where", [
    (block(100, "SET") + block(100, "CLR") + block(1, "SET"),
     "8:1: duplicate block OB 100 (first at line 1)"),
    (block(100, "SET"), "1:1: OB 100 without ORGANIZATION_BLOCK OB 1"),
    (block(1, "SET") + block(35, "SET"),
     "8:1: unsupported: `ORGANIZATION_BLOCK OB 35`"),
    (block(1, "OB100: SET\n= A 0.0") + block(100, "SET"),
     "5:1: unsupported: the label `OB100`"),
    (block(100, "U(\nU E 0.0") + block(1, "SET"), "5:1: unbalanced parentheses"),
    (block(100, "SPA M1") + block(1, "M1: SET"), "5:5: unknown label `M1`"),
    # the translation's own labels are none of the source's (awlsim: no such label)
    (block(100, "SET") + block(1, "SPA OB100.END"), "12:5: unknown label `OB100.END`"),
    (block(100, "M1: SET") + block(1, "SPB OB100.M1"), "12:5: unknown label `OB100.M1`"),
    # a label of OB 100 as written, not as the translation prefixes it (OB100.M1)
    (block(100, "M1: SET\nM1: CLR") + block(1, "SET"),
     "6:1: duplicate label `M1` (first defined at 5:"),
    (block(100, "L MW 10\n+I\nT MW 12") + block(1, "SET"), "6:1: unsupported: `+I` reads"),
])
def test_errors(tmp_path, capsys, text, where):
    assert_refused(tmp_path, capsys, text, where)


def test_ob100_starts_with_rlo_0(tmp_path):
    """S7 starts a block with RLO 0 (and /FC 0): an `=` or `SPBN` first in OB 100
    sees 0, although the guard's jump arrives with 1 (a random program found it)."""
    path = tmp_path / "rlo.awl"
    path.write_text(block(100, """
      =     M 0.6
      SPBN  M2
      S     M 0.7
M2:   NOT
      =     A 0.5
""") + block(1, "=     A 0.6\nU     M 0.6\n=     A 0.7"))
    expected, got, diff = compare(path, "de", tmp_path, [{0: 0}] * 3)
    assert diff is None, diff
    assert expected[0]["Q0.5"] == 0 and expected[0]["M0.7"] == 0


def test_startup_with_calls_temps_and_the_started_bit(tmp_path):
    """OB 100 calls an FC (inlined) and has a TEMP; the started bit M 255.7 and a word
    over it are the translation's."""
    fc = ("FUNCTION FC 1 : VOID\nVAR_INPUT\n  a : BOOL;\nEND_VAR\nVAR_OUTPUT\n"
          "  q : BOOL;\nEND_VAR\nBEGIN\nNETWORK\nTITLE =\n      U     #a\n"
          "      =     #q\nEND_FUNCTION\n\n")
    text = fc + block(100, """
      U     E 0.0
      =     #t
      CALL  FC 1 (a := #t, q := M 0.5)
""", head="VAR_TEMP\n  t : BOOL;\nEND_VAR\n") + block(1, """
      U     M 0.5
      =     A 0.0
      CALL  FC 1 (a := E 0.1, q := A 0.1)
""")
    path = tmp_path / "calls.awl"
    path.write_text(text)
    stimulus = [{0: 1}, {0: 2}, {0: 0}, {0: 3}]
    expected, got, diff = compare(path, "de", tmp_path, stimulus)
    assert diff is None, diff
    assert [r["Q0.0"] for r in expected] == [1, 1, 1, 1]
    for use in ("U M 255.7", "L MW 254"):
        path.write_text(block(100, "SET") + block(1, use + "\n= A 0.0"))
        with pytest.raises(SourceError) as e:
            parse_file(str(path))
        assert "M255.7" in str(e.value), use
        assert "which the translation keeps for OB 100's started bit" in str(e.value), use
    # a timer's scratch bit says so (M 255.7 without OB 100 is the first timer's)
    path.write_text(block(1, "U E 0.0\nL S5T#1S\nSE T 1\nU M 255.7\n= A 0.0"))
    with pytest.raises(SourceError) as e:
        parse_file(str(path))
    assert "which the translation of this program's timers keeps for itself" \
        in str(e.value)


def test_watchdog_in_the_startup_scan(tmp_path, capsys):
    """The startup scan is timed as any scan: OB 100 longer than --watchdog is a
    fault before scan 0, reported as the startup scan (OB 100) with no trace row."""
    path = tmp_path / "long.awl"
    path.write_text(block(100, "L 1\nT MW 10\nL 2\nT MW 12") + block(1, "SET\n= A 0.0"))
    trace = tmp_path / "t.csv"
    code = cli.main(["run", str(path), "--scans", "3", "--watchdog", "30",
                     "--trace", str(trace)])
    out, err = capsys.readouterr()
    assert code == cli.EXIT_WATCHDOG
    assert "scan watchdog: the startup scan (OB 100) exceeded 30 clocks" in err
    assert "limit 30 clocks: exceeded in the startup scan (OB 100)" in out
    assert "scan 0" not in out + err
    assert trace.read_text() == "scan,t_us,cycles,Q0.0\n"
    _, records, fault = refsim_trace(parse_file(str(path)), Config(), scans=3,
                                     watchdog=30)
    assert fault and records == []
    assert cli.main(["run", str(path), "--scans", "3", "--watchdog", "60"]) == 0


# The reviewer's program: the startup scan 70 clocks, OB 1's scans 45
LONG_STARTUP = (block(100, "SET\n= A 0.1\nL 100\nT MW 10\nL 200\nT MW 12\nL 300\nT MW 14")
                + block(1, "U E 0.0\n= A 0.0\nL MW 10\nL 1\n+I\nT MW 10"))


def test_summary_shows_the_startup_scan_and_its_watchdog_margin(tmp_path, capsys):
    """The watchdog times the startup scan (70 clocks) as any scan, so the summary's
    margin is against the longer of it and OB 1's longest scan (45), and says which;
    the startup scan has a line of its own.  The reference interpreter keeps its
    startup scan's clocks too."""
    path = tmp_path / "a.awl"
    path.write_text(LONG_STARTUP)
    sim = RefSim(parse_file(str(path)), Config(), watchdog=1000)
    assert [r.cycles for r in sim.run(3)] == [45] * 3 and sim.startup_cycles == [70]
    for sim_name in ("verilator",):
        capsys.readouterr()
        assert cli.main(["run", str(path), "--scans", "3", "--watchdog", "70",
                         "--sim", sim_name]) == 0
        out = capsys.readouterr().out
        assert re.search(r"^startup scan +\(OB 100\) 70 clocks", out, re.M), out
        assert ("limit 70 clocks, longest scan 70 (the startup scan, OB 100): margin 0 "
                "clocks (0 %)") in out
    assert cli.main(["run", str(path), "--scans", "3", "--watchdog", "69"]) == \
        cli.EXIT_WATCHDOG
    capsys.readouterr()
    # a longer OB 1 scan: the margin is against it
    longer = tmp_path / "b.awl"
    longer.write_text(block(100, "SET\n= A 0.1") + block(1, "L 1\nT MW 10\n" * 4))
    assert cli.main(["run", str(longer), "--scans", "2", "--watchdog", "1000"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"longest scan (\d+) \(an OB 1 scan\)", out), out
    # without OB 100: no startup line, the margin as before
    plain = tmp_path / "c.awl"
    plain.write_text(block(1, "U E 0.0\n= A 0.0"))
    assert cli.main(["run", str(plain), "--scans", "2", "--watchdog", "1000"]) == 0
    out = capsys.readouterr().out
    assert "startup" not in out and re.search(r"longest scan \d+: margin", out)


def test_until_us_inside_the_startup_scan(tmp_path):
    """--until-us T before the startup scan ends (0.7 us: clock 70 at 100 MHz, the
    startup scan's end) stops after scan 0, the first scan of the trace ending at or
    after T (spec §4), on the reference interpreter and the Verilator harness alike;
    T in scan 0 or at its end gives the same row, T after it scan 1 too."""
    path = tmp_path / "a.awl"
    path.write_text(LONG_STARTUP)
    program = parse_file(str(path))
    for t, scans in (("0.01", 1), ("0.7", 1), ("1.15", 1), ("1.16", 2)):
        _, records, fault = refsim_trace(program, Config(), until_us=t)
        assert not fault and [r.scan for r in records] == list(range(scans)), t
        trace = tmp_path / "u.csv"
        assert cli.main(["run", str(path), "--until-us", t, "--trace", str(trace)]) == 0
        rows = trace.read_text().splitlines()[1:]
        assert [row.split(",")[:3] for row in rows] == \
            [[str(r.scan), f"{r.end_clock / 100:g}", str(r.cycles)] for r in records], t


def vcd_changes(path: Path, scope: str, names: set[str]) -> list[tuple[int, str, int]]:
    """(time, name, value) of every change of the named variables of `scope`."""
    head, body = path.read_text().split("$enddefinitions", 1)
    ids, scopes = {}, []
    for words in (line.split() for line in head.splitlines()):
        if words[:1] == ["$scope"]:
            scopes.append(words[2])
        elif words[:1] == ["$upscope"]:
            scopes.pop()
        elif words[:1] == ["$var"] and scopes[-1:] == [scope] and words[4] in names:
            ids[words[3]] = words[4]
    out, t = [], 0
    for line in body.splitlines():
        if line.startswith("#"):
            t = int(line[1:])
        elif line[:1] in ("0", "1") and line[1:] in ids:
            out.append((t, ids[line[1:]], int(line[0])))
        elif line.startswith("b") and line.split()[-1] in ids:
            out.append((t, ids[line.split()[-1]], int(line.split()[0][1:], 2)))
    return sorted(out)


def test_waves_layout_opens_at_scan_0_and_names_the_startup_scan(tmp_path):
    """`--waves`: the layout opens at scan 0's latch, the startup scan's 70 clocks
    (10 ns each) after clock 0, the first latch; its scan row shows hardware scan 0
    as `startup`, hardware scan n as the trace's scan n - 1 (a translate filter
    W.scan.txt)."""
    started, plain = tmp_path / "a.awl", tmp_path / "p.awl"
    started.write_text(LONG_STARTUP)
    plain.write_text(block(1, "U E 0.0\n= A 0.0"))
    for path in (started, plain):
        waves = tmp_path / f"{path.stem}.vcd"
        assert cli.main(["run", str(path), "--scans", "3", "--waves", str(waves)]) == 0
        text = (tmp_path / f"{path.stem}.gtkw").read_text()
        t0 = int(re.search(r"^\[timestart\] (\d+)$", text, re.M).group(1))
        changes = vcd_changes(waves, "bitbyte_cpu", {"latch", "scan_count_o"})
        latches = [t for t, name, v in changes if name == "latch" and v]
        counts = {t: v for t, name, v in changes if name == "scan_count_o"}
        if path is started:
            assert t0 == latches[1] == latches[0] + 70 * 10_000 and counts[t0] == 1
        else:
            assert t0 == latches[0]
    assert (tmp_path / "a.scan.txt").read_text().splitlines()[:3] == \
        ["0 startup", "1 0", "2 1"]
    assert f"^1 {tmp_path / 'a.scan.txt'}\n+{{scan}} " in (tmp_path / "a.gtkw").read_text()
    assert not (tmp_path / "p.scan.txt").exists()


def test_parallel_estimate_is_ob1s_and_alloc_refuses_ob100(tmp_path, capsys):
    """`bitbyte asm --mode parallel`'s estimate is of a scan of OB 1: the part before
    the first END / END_B (OB 100 after it runs once), so the program with OB 100
    estimates the guard's 2 clocks more than without it (measured: 46 and 42), not
    OB 100's words too (103).  `bitbyte alloc` refuses a task program with OB 100 at
    its head, as `bitbyte link` refuses a plant's core (both are cores of a plant)."""
    started, plain = tmp_path / "a.awl", tmp_path / "p.awl"
    started.write_text(LONG_STARTUP)
    plain.write_text(block(1, "U E 0.0\n= A 0.0\nL MW 10\nL 1\n+I\nT MW 10"))
    est = {}
    for path in (started, plain):
        out = tmp_path / path.stem
        assert cli.main(["asm", str(path), "--mode", "parallel", "-o", str(out)]) == 0
        est[path.stem] = json.loads((out / f"{path.stem}.json").read_text())["estimate"]
        lst = (out / f"{path.stem}.lst").read_text()
        assert f"estimated clocks per scan: {est[path.stem]['clocks']} " in lst
    assert est["a"]["clocks"] == est["p"]["clocks"] + 2 == 43
    assert est["a"]["byte_clocks"] == est["p"]["byte_clocks"] + 2    # JC_B
    assert est["a"]["serial"] == est["p"]["serial"] + 2
    tasks = tmp_path / "tasks.csv"
    tasks.write_text("name,period_ms,wcet_ms,read_bytes,write_bytes,mem_bytes,program\n"
                     "t1,1,,1,1,8,a.awl\n")
    for mode in ("serial", "parallel"):
        capsys.readouterr()
        assert cli.main(["alloc", str(tasks), "--cores", "1", "--mode", mode]) == \
            cli.EXIT_SOURCE
        assert (f"{started}:1:1: unsupported: OB 100 in a task's program"
                in capsys.readouterr().err), mode


# --------------------------------------------------------------------------------------
# Random programs: a random OB 100 in front of a random OB 1

def random_startup_program(seed: int) -> tuple[str, str]:
    """tests/stlgen.py's OB 1 of `seed`, and another of the same language as OB 100."""
    ob1, lang = random_program(seed)
    other = seed + 1
    while True:
        text, other_lang = random_program(other * 7 + 50_000)
        if other_lang == lang:
            break
        other += 1
    return text.replace("ORGANIZATION_BLOCK OB 1", "ORGANIZATION_BLOCK OB 100", 1) + ob1, lang


def test_random_startup_programs_against_awlsim(tmp_path):
    """20 random OB 100 + OB 1 programs equal awlsim's scans (or are rejected as
    `unsupported:`), two of them on the Verilator harness in parallel mode too; and
    OB 100 changes what OB 1 shows in most of them."""
    compared, changed, on_harness = 0, 0, 0
    for seed in range(20):
        text, lang = random_startup_program(seed)
        path = tmp_path / f"r{seed}.awl"
        path.write_text(text)
        stimulus = random_inputs(seed, 12)
        if not equal_or_rejected(seed, path, lang, stimulus, tmp_path, words=WORDS_RANDOM,
                                 in_words=IN_WORDS):
            continue
        compared += 1
        alone = tmp_path / f"r{seed}_ob1.awl"
        alone.write_text(text[text.index("ORGANIZATION_BLOCK OB 1\n"):])
        expected = awlsim_scans(path, stimulus, mnemonics=lang, words=WORDS_RANDOM)
        changed += first_difference(expected, awlsim_scans(
            alone, stimulus, mnemonics=lang, words=WORDS_RANDOM)) is not None
        if on_harness < 2:
            got = bitbyte_scans(path, stimulus, tmp_path, sim="verilator", mode="parallel",
                                words=WORDS_RANDOM, in_words=IN_WORDS)
            assert first_difference(expected, got) is None, seed
            on_harness += 1
    assert compared >= 14 and changed >= compared // 2 and on_harness == 2, (
        compared, changed)


# --------------------------------------------------------------------------------------
# The CLI on every engine, --force and --status

def cli_trace(tmp: Path, path: Path, name: str, *args: str) -> str:
    trace = tmp / f"{name}.csv"
    assert cli.main(["run", str(path), "--scans", "8", "--trace", str(trace), "--watch",
                     "MW10,MW12,MW14,M0.0,M0.2,M0.3,M0.4", *args]) == 0
    return trace.read_text()


def stimulus_file(tmp: Path, rows: list[dict[int, int]]) -> Path:
    from awlsim_oracle import scan_inputs_csv
    path = tmp / f"stim{len(list(tmp.iterdir()))}.csv"
    path.write_text(scan_inputs_csv(rows, 1))
    return path


def test_cli_on_verilator_and_cocotb_force_and_status(tmp_path, capsys):
    """`bitbyte run` on the Verilator harness and on cocotb (Icarus): identical
    traces in serial and parallel mode; `--force I0.3=0@0` is what OB 100 reads
    too (the table before RUN holds through the startup scan); `--status 0` is OB
    1's first scan, OB 100's lines not executed in it."""
    path = startup_file(tmp_path, "de")
    stim = stimulus_file(tmp_path, inputs(8))
    for mode in ("serial", "parallel"):
        traces = {sim: cli_trace(tmp_path, path, f"{mode}_{sim}", "--stimulus", str(stim),
                                 "--mode", mode, "--sim", sim)
                  for sim in ("verilator", "icarus")}
        assert traces["verilator"] == traces["icarus"], mode
    forced = cli_trace(tmp_path, path, "forced", "--stimulus", str(stim),
                       "--force", "I0.3=0@0")
    zero = inputs(8)
    zero[0] = {0: 0}
    assert forced == cli_trace(tmp_path, path, "zero", "--stimulus",
                               str(stimulus_file(tmp_path, zero)))
    assert forced != traces["verilator"]
    capsys.readouterr()
    assert cli.main(["run", str(path), "--stimulus", str(stim), "--scans", "3",
                     "--status", "0"]) == 0
    status = capsys.readouterr().out
    lines = {m.group(1): m.group(2) for m in re.finditer(
        r"^\s+(\d+)  \S.*?\s{2,}(not executed|\d.*)$", status, re.M)}
    assert lines["5"] == "not executed" and lines["26"] != "not executed"   # SET / U M 0.0


def test_time_stimulus_plants_and_free_mode(tmp_path, capsys):
    """A `t_us` stimulus: the startup scan sees the pins at t = 0 (reference
    interpreter and harness alike); a plant's core and free-running mode refuse OB
    100 (their scans are not one startup scan and then OB 1's)."""
    path = tmp_path / "t.awl"
    path.write_text(block(100, "U E 0.0\n= M 0.1\nL 3\nT MW 10")
                    + block(1, "U M 0.1\n= A 0.0\nU E 0.0\n= A 0.1\nL MW 10\nT MW 12"))
    stim = tmp_path / "t.csv"
    stim.write_text("t_us,I0.0\n0,1\n0.2,0\n")
    program = parse_file(str(path))
    _, records, _ = refsim_trace(program, Config(), load_stimulus(str(stim)),
                                 ["M0.1", "MW12"], scans=3)
    trace = tmp_path / "trace.csv"
    assert cli.main(["run", str(path), "--stimulus", str(stim), "--scans", "3",
                     "--trace", str(trace), "--watch", "M0.1,MW12"]) == 0
    rows = [line.split(",") for line in trace.read_text().splitlines()[1:]]
    assert [(r.cycles, r.values["Q0.0"], r.values["Q0.1"], r.values["MW12"])
            for r in records] == [(int(c), int(q0), int(q1), int(w))
                                  for _, _, c, q0, q1, _, w in rows]
    assert records[0].values["M0.1"] == 1 and records[0].values["Q0.1"] == 0
    plant = tmp_path / "plant.toml"
    plant.write_text('[[core]]\nname = "a"\nprogram = "t.awl"\nperiod_us = 1000\n')
    capsys.readouterr()
    assert cli.main(["link", str(plant)]) == cli.EXIT_SOURCE
    assert "unsupported: OB 100 in a plant's core (a)" in capsys.readouterr().err
    assert cli.main(["run", str(path), "--mode", "free"]) == cli.EXIT_USAGE
    assert "--mode free: this program has an OB 100" in capsys.readouterr().err


def test_timer_started_in_ob100_on_the_harness_in_parallel_mode(tmp_path):
    path = tmp_path / "timer.awl"
    path.write_text(TIMER_DE)
    stimulus = [{0: 1 if 4 <= k < 30 else 0} for k in range(45)]
    expected, got, _ = timer_scans(path, stimulus, tmp_path, mnemonics="de",
                                   timers=(1, 2, 3), quiet=False, clock_mhz="0.02",
                                   sim="verilator", mode="parallel")
    assert transition_difference(expected, got) is None, (expected, got)


def test_response_times_with_a_startup(tmp_path, capsys):
    """The summary's response times replay the startup scan: an input change answered
    in the scan that latches it takes that scan's clocks, 2 more than without OB 100."""
    ob1 = block(1, "U E 0.0\n= A 0.0\nL MW 10\nL 1\n+I\nT MW 10")
    plain, started = tmp_path / "plain.awl", tmp_path / "started.awl"
    plain.write_text(ob1)
    started.write_text(block(100, "SET\n= M 20.0\nL 5\nT MW 30") + ob1)
    stim = tmp_path / "r.csv"
    stim.write_text("scan,I0.0\n0,0\n2,1\n4,0\n")
    clocks = {}
    for path in (plain, started):
        capsys.readouterr()
        assert cli.main(["run", str(path), "--stimulus", str(stim), "--scans", "6"]) == 0
        m = re.search(r"response \[clk\]\s+min (\d+)\s+median (\d+)\s+max (\d+)\s+\(2 of 2",
                      capsys.readouterr().out)
        assert m and len(set(m.groups())) == 1, path
        clocks[path.stem] = int(m.group(1))
    assert clocks["started"] == clocks["plain"] + 2


def test_response_times_of_a_time_stimulus_with_a_startup(tmp_path, capsys):
    """A `t_us` stimulus on the reviewer's program (startup scan 70 clocks, OB 1's
    scans 45, OB 1 `U E 0.0  = A 0.0`), by hand at 100 MHz:
      I0.0 rises at 0.3 us = clock 30, inside the startup scan (latched at 0, it saw
      0); scan 0 latches at clock 70 and sets Q0.0 at its END, end clock 70 + 45 =
      115: 115 - 30 = 85;
      it falls at 2.3 us = clock 230: scans latch at 70 + 45k, so scan 4 at 250 takes
      it in and ends at 295: 65;
      it rises at 3.1 us = clock 310: scan 6 latches at 340, ends at 385: 75.
    The replay must latch scan 0 after the startup (not at 0: 130) and run the
    startup scan from clock 0 (bitbyte/run/response.py's `latches[0]` and its
    `in_startup` guard; reverting either fails here)."""
    path = tmp_path / "a.awl"
    path.write_text(LONG_STARTUP)
    stim = tmp_path / "ts2.csv"
    stim.write_text("t_us,I0.0\n0.3,1\n2.3,0\n3.1,1\n")
    assert cli.main(["run", str(path), "--stimulus", str(stim), "--scans", "8"]) == 0
    out = capsys.readouterr().out
    assert ("response [clk]   min 65  median 75  max 85  (3 of 3 input changes changed "
            "an output)") in out, out
    # the startup scan latches at clock 0 in the replay too: OB 100 reads I0.0 before
    # its rise at 0.1 us = clock 10 (inside the 30-clock startup scan), so M1.0 stays
    # 0 and Q0.0 = M1.0 AND I0.0 never changes (a replayed startup latching at scan
    # 0's latch, clock 30, would see the rise and report 36 - 10 = 26 clocks)
    guarded = tmp_path / "g.awl"
    guarded.write_text(block(100, "U E 0.0\n= M 1.0\nL 100\nT MW 10")
                       + block(1, "U M 1.0\nU E 0.0\n= A 0.0"))
    stim.write_text("t_us,I0.0\n0.1,1\n")
    trace = tmp_path / "g.csv"
    assert cli.main(["run", str(guarded), "--stimulus", str(stim), "--scans", "4",
                     "--trace", str(trace)]) == 0
    out = capsys.readouterr().out
    assert trace.read_text().splitlines()[1] == "0,0.36,6,0"   # scan 0 latches at 30
    assert "response [clk]   -  (0 of 1 input changes changed an output)" in out, out

