"""S7 programs written by others (docs/s7.md, "Public programs by others"): each
runs unmodified with `bitbyte run` and its trace equals awlsim's scan for scan
(timer programs: the same transitions, each within one scan), on a stimulus of
our own (examples/s7/public/NAME/NAME.stim.csv).

The sources themselves are not in this tree (code by others stays out of it):
examples/s7/public/NAME/NOTICE names the repository, commit, path, author and
license of each, and PUBLIC below the SHA-256 of the copy these tests were written
on (of its text with CR LF made LF, so that a checkout with either line-end setting
passes; the program and, for the conveyor, its symbol table).  `make s7-public
S7_PUBLIC=DIR` runs this file on DIR/NAME/FILE; a missing file or other bytes is a
failure, not a skip (this file is outside `make test`'s testpaths for that reason:
CI has no copy).

These programs write a block call as STEP 7's STL editor shows it — `CALL FB 10,
DB 10` and then one `name :=actual` a line, without parentheses — which awlsim
does not read; awlsim runs a copy with the list put into parentheses
(`parenthesized`, a rewriting of its own, independent of the front end's), so the
comparison checks the front end's reading of that form too.  The form is also
checked on a program of our own (LISTED_CALL), which always runs.
"""
from __future__ import annotations

import csv
import hashlib
import os
from pathlib import Path

import pytest

from awlsim_oracle import awlsim_scans, bitbyte_scans, timer_scans
from bitbyte import cli
from test_stl_examples import stimulus_inputs
from test_stl_listed_call import awlsim_copy
from tracecmp import transition_difference, transitions

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples" / "s7" / "public"

# name: the file, the SHA-256 of its text with CR LF made LF (lf_sha256), the symbol
# table (or None) and its lf_sha256, mnemonics, scans, --clock-mhz, output bytes,
# marker bytes, words, timers
PUBLIC = {
    "foerderband": dict(
        file="04_SPS_Programm_FB-01.awl",
        sha256="34eacecef0991a9612da92927fed24b624602a2d789e6be508c55d44abbf01d6",
        symbols="05_Symboltabelle_FB-01.sdf",
        symbols_sha256="9974daf609828bfb25dad134efd743b8ef7a39de791096274d4353c504f9c618",
        lang="de", scans=250, clock="0.001",
        in_bytes=1, out_bytes=(4,), marker_bytes=(10,), words=("MW100",),
        timers=(5,)),
    "umroller": dict(
        file="04_SPS_Programm_UR-01.awl",
        sha256="0dd1df1614c031cdb60031ccbb233f2b4b9a1224b54e4734710b3b57b451b682",
        symbols=None, lang="de", scans=210, clock="0.001", in_bytes=3,
        out_bytes=(4, 5), marker_bytes=(10,), words=("MW100",), timers=(20,)),
    "aufrollung": dict(
        file="04_SPS_Programm_PM1-AR.awl",
        sha256="bb8da65911ad7515bb37a3bcd4b9e6b46ed21c0b5565bf90d3e205facb991c66",
        symbols=None, lang="de", scans=270, clock="0.001", in_bytes=3,
        out_bytes=(4, 5), marker_bytes=(10, 30), words=("MW102",),
        timers=(30, 31, 32)),
}


def public_dir() -> Path:
    assert os.environ.get("BITBYTE_S7_PUBLIC"), "set BITBYTE_S7_PUBLIC (make s7-public S7_PUBLIC=DIR)"
    return Path(os.environ["BITBYTE_S7_PUBLIC"])


def lf_sha256(data: bytes) -> str:
    """The SHA-256 of a text with its CR LF line ends made LF: the same for a copy
    checked out with either line-end setting."""
    return hashlib.sha256(data.replace(b"\r\n", b"\n")).hexdigest()


def checked(path: Path, name: str, sha256: str) -> Path:
    """`path`, checked against the SHA-256 of PUBLIC; its absence fails the test."""
    assert path.is_file(), (f"{path} is not here (examples/s7/public/{name}/NOTICE says "
                            "where it is published)")
    assert lf_sha256(path.read_bytes()) == sha256, f"{path} is not the published file"
    return path


def public_source(name: str) -> Path:
    """The published program, checked (lf_sha256)."""
    return checked(public_dir() / name / PUBLIC[name]["file"], name,
                   PUBLIC[name]["sha256"])


def public_symbols(name: str) -> Path:
    """The published symbol table of a program, checked (lf_sha256)."""
    case = PUBLIC[name]
    return checked(public_dir() / name / case["symbols"], name, case["symbols_sha256"])


def rows_of(name: str, path: Path, tmp: Path, stimulus: Path | None = None, **kw):
    case = PUBLIC[name]
    inputs = stimulus_inputs(stimulus or EXAMPLES / name / f"{name}.stim.csv",
                             case["scans"])
    expected, got, _ = timer_scans(
        path, inputs, tmp, mnemonics=case["lang"], timers=case["timers"],
        clock_mhz=case["clock"], words=case["words"], quiet=False,
        in_bytes=case["in_bytes"], out_bytes=case["out_bytes"], marker_bytes=case["marker_bytes"],
        awlsim_path=awlsim_copy(path, tmp), **kw)
    return expected, got, transition_difference(expected, got)


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_public_program_against_awlsim(tmp_path, name):
    expected, _, diff = rows_of(name, public_source(name), tmp_path)
    assert diff is None, (name, diff)


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_public_program_one_liner(tmp_path, name, capsys):
    """`bitbyte run` as docs/s7.md writes it, with the program's symbol table."""
    case, path = PUBLIC[name], public_source(name)
    argv = ["run", str(path), "--stimulus", str(EXAMPLES / name / f"{name}.stim.csv"),
            "--scans", str(case["scans"]), "--clock-mhz", case["clock"],
            "--trace", str(tmp_path / "T.csv")]
    if case["symbols"]:
        argv += ["--symbols", str(public_symbols(name))]
    assert cli.main(argv) == 0, capsys.readouterr().err


def test_foerderband_watched_by_its_symbol_table(tmp_path, capsys):
    """The program's own .sdf table names the watched operands: K1_Vorwaerts is
    A 4.0, H2_Stoerung A 4.3, Stueckzahl MW 100 (equal to the columns by address)."""
    case, path = PUBLIC["foerderband"], public_source("foerderband")
    symbols = public_symbols("foerderband")
    trace = tmp_path / "T.csv"
    argv = ["run", str(path), "--symbols", str(symbols), "--stimulus",
            str(EXAMPLES / "foerderband" / "foerderband.stim.csv"), "--scans", "250",
            "--clock-mhz", case["clock"], "--trace", str(trace),
            "--watch", "Q4.0,Q4.3,MW100,K1_Vorwaerts,H2_Stoerung,Stueckzahl"]
    assert cli.main(argv) == 0, capsys.readouterr().err
    rows = list(csv.DictReader(trace.open()))
    assert all(r["K1_Vorwaerts"] == r["Q4.0"] and r["H2_Stoerung"] == r["Q4.3"]
               and r["Stueckzahl"] == r["MW100"] for r in rows)
    assert rows[-1]["Stueckzahl"] == "3" and {r["H2_Stoerung"] for r in rows} == {"0", "1"}


def test_foerderband_behaviour(tmp_path):
    """Start (scan 2) runs the belt; parts leaving at scans 14 and 20 are counted;
    a part held at the infeed from scan 30 is a blockage after 20 s (T 5; scans
    of 129 clocks at 1 kHz): the fault lamp, the belt stops; acknowledged with
    Start (scan 230) it runs again; Stop (240) stops it."""
    expected, _, _ = rows_of("foerderband", public_source("foerderband"), tmp_path)
    assert transitions(expected, "Q4.0") == [(2, 1), (187, 0), (231, 1), (240, 0)]
    assert transitions(expected, "Q4.3") == [(186, 1), (230, 0)]
    assert transitions(expected, "MW100") == [(14, 1), (20, 2), (236, 3)]


def test_umroller_behaviour(tmp_path):
    """Start (scan 3) enables the five drives; a finished log (scan 10) feeds a
    core (K3) and pushes the log off 3 s later (K4, T 20) until the end switch; a
    parent roll at its minimum (50) stops its unwinder alone; a web break (80),
    a drive not ready (110) and a motor protection trip (180) are faults with the
    horn until acknowledged; jogging (195) runs embosser and perforator alone."""
    expected, _, _ = rows_of("umroller", public_source("umroller"), tmp_path)
    assert transitions(expected, "Q4.6")[:2] == [(25, 1), (35, 0)]
    assert transitions(expected, "Q4.0")[:3] == [(3, 1), (50, 0), (60, 1)]
    assert [k for k, v in transitions(expected, "Q5.2") if v] == [80, 110, 180]
    assert expected[195]["Q4.2"] == expected[195]["Q4.3"] == 1
    assert expected[195]["Q4.4"] == 0
    assert transitions(expected, "MW100") == [(10, 1), (150, 2)]


def test_aufrollung_behaviour(tmp_path):
    """The reel change runs its step chain (M 30.0 .. 30.3): arm out (Y1), cut for
    2 s (Y3, T 32), arm back (Y2) until home, counted in MW 102; a web break, low
    oil, no hydraulic pressure 5 s after the pump starts (T 31) and low oil 10 s
    after the lubrication restarts (T 30) are faults."""
    expected, _, _ = rows_of("aufrollung", public_source("aufrollung"), tmp_path)
    assert transitions(expected, "Q4.4")[:2] == [(40, 1), (51, 0)]
    assert transitions(expected, "Q4.6")[:2] == [(50, 1), (58, 0)]
    assert transitions(expected, "M30.3")[:2] == [(57, 1), (70, 0)]
    assert [k for k, v in transitions(expected, "Q5.0") if v] == [115, 140, 172, 190,
                                                                   243]
    assert transitions(expected, "MW102") == [(0, 1), (70, 2), (105, 3)]


def test_foerderband_on_verilator_serial_and_parallel(tmp_path):
    path = public_source("foerderband")
    for mode in ("serial", "parallel"):
        _, _, diff = rows_of("foerderband", path, tmp_path, sim="verilator", mode=mode)
        assert diff is None, (mode, diff)


def test_comparison_fails_on_a_wrong_stimulus(tmp_path):
    """The comparison can fail: bitbyte run on a stimulus with the part at the
    outfeed one scan late differs from awlsim on the right one (MW100)."""
    name, path = "foerderband", public_source("foerderband")
    case = PUBLIC[name]
    right = stimulus_inputs(EXAMPLES / name / f"{name}.stim.csv", case["scans"])
    wrong = [dict(image) for image in right]
    wrong[14][0] &= ~0x20                       # E 0.5 comes at scan 15, not 14
    got = bitbyte_scans(path, wrong, tmp_path, clock_mhz=case["clock"], in_bytes=1,
                        out_bytes=case["out_bytes"], marker_bytes=case["marker_bytes"],
                        words=case["words"])
    expected = awlsim_scans(awlsim_copy(path, tmp_path), right, mnemonics="de",
                            out_bytes=case["out_bytes"],
                            marker_bytes=case["marker_bytes"], words=case["words"])
    assert transition_difference(expected, got) is not None


def test_the_checks_hash_the_text_with_lf_line_ends(tmp_path, monkeypatch):
    """Review findings: the .sdf's SHA-256 was never checked, and a checkout with
    other line ends failed.  The symbol table is checked where it is opened; a copy
    with CR LF or with LF passes, a changed one fails."""
    original = public_dir()
    for name in ("foerderband",):
        for f in (PUBLIC[name]["file"], PUBLIC[name]["symbols"]):
            data = (original / name / f).read_bytes().replace(b"\r\n", b"\n")
            for ends, text in (("lf", data), ("crlf", data.replace(b"\n", b"\r\n"))):
                (tmp_path / ends / name).mkdir(parents=True, exist_ok=True)
                (tmp_path / ends / name / f).write_bytes(text)
    for ends in ("lf", "crlf"):
        monkeypatch.setenv("BITBYTE_S7_PUBLIC", str(tmp_path / ends))
        public_source("foerderband")
        public_symbols("foerderband")
    table = tmp_path / "lf" / "foerderband" / PUBLIC["foerderband"]["symbols"]
    table.write_bytes(table.read_bytes().replace(b'"A 4.0"', b'"A 4.1"'))
    assert table.read_bytes() != (original / "foerderband" / table.name).read_bytes()
    monkeypatch.setenv("BITBYTE_S7_PUBLIC", str(tmp_path / "lf"))
    with pytest.raises(AssertionError, match="is not the published file"):
        public_symbols("foerderband")
