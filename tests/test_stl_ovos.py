"""S7's status bits OV and OS in `.awl` sources (spec §9 "the status word where a
program reads it"; docs/s7.md, "Status bits"): `U OV` … `XN OS` and the jumps `SPO`
/ `SPS` (English `JO` / `JOS`) after INT arithmetic with and without overflow, a
division by 0, compares; checked scan for scan against awlsim on the reference
interpreter and the Verilator harness in serial and parallel mode; where the
translation does not keep them (after a call, a label reached from `SPS`, which
clears OS only there), rejected; wrong translations caught."""
from __future__ import annotations

import pytest

from awlsim_oracle import awlsim_scans, bitbyte_scans
from bitbyte.lang import stl
from test_stl_dint import error_of
from tracecmp import assert_equal_and_varied, first_difference

PROGRAM_DE = """ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE = OV and OS
      U     OS
      =     A 1.0
      L     EW 2
      L     EW 4
      +I
      T     MW 10
      U     OV
      =     A 0.0
      UN    OS
      =     A 0.1
      L     EW 2
      L     EW 4
      *I
      T     MW 12
      O     OV
      X     E 0.0
      =     A 0.2
      SPO   M1
      CLR
      =     A 0.3
      SPA   M3
M1:   SET
      =     A 0.3
M3:   L     EW 2
      L     EW 4
      /I
      T     MW 14
      U     OS
      =     A 0.4
      L     EW 2
      L     EW 4
      <I
      =     A 0.5
      ON    OV
      =     A 0.6
      XN    OS
      =     A 0.7
      SPS   M2
      CLR
      =     A 1.1
      SPA   M4
M2:   SET
      =     A 1.1
M4:   L     MW 10
      L     1
      -I
      U     OV
      =     A 1.2
END_ORGANIZATION_BLOCK
"""
ENGLISH = {"U": "A", "UN": "AN", "SPO": "JO", "SPS": "JOS", "SPA": "JU", "E": "I",
           "A": "Q", "EW": "IW"}


def program(lang: str) -> str:
    if lang == "de":
        return PROGRAM_DE
    return "\n".join(" ".join(ENGLISH.get(w, w) for w in line.split(" "))
                     for line in PROGRAM_DE.splitlines()) + "\n"


def inputs(scans: int = 40) -> list[dict[int, int]]:
    """IW 2 / IW 4 through sums and products beyond INT, 0 divisors, -32768 / -1."""
    first = (0, 5, -5, 0x7FFF, -32768, 3, -1, 200, 181, 1)
    second = (5, 0, 3, -5, 7, -1, 1, 200, 181, -32768)
    rows = []
    for k in range(scans):
        a, b = first[k % 10] & 0xFFFF, second[(k + k // 10) % 10] & 0xFFFF
        rows.append({0: k % 2, 2: a >> 8, 3: a & 0xFF, 4: b >> 8, 5: b & 0xFF})
    return rows


def compare(tmp_path, lang: str, **kw):
    path = tmp_path / f"ovos_{lang}.awl"
    path.write_text(program(lang))
    expected = awlsim_scans(path, inputs(), mnemonics=lang, words=("MW10",))
    got = bitbyte_scans(path, inputs(), tmp_path, in_words=(2, 4), words=("MW10",),
                        mnemonics=lang, **kw)
    return expected, got


@pytest.mark.parametrize("lang", ["de", "en"])
def test_ov_and_os_against_awlsim(tmp_path, lang):
    expected, got = compare(tmp_path, lang)
    assert_equal_and_varied(expected, got, ("Q0.0", "Q0.1", "Q0.2", "Q0.3", "Q0.4", "Q0.7", "Q1.1"))
    assert all(row["Q1.0"] == 0 for row in expected)        # 0 at the OB's start
    assert all(row["Q0.6"] == 1 for row in expected)        # a compare: OV 0


@pytest.mark.parametrize("mode", ["serial", "parallel"])
def test_ov_and_os_on_verilator(tmp_path, mode):
    expected, got = compare(tmp_path, "de", sim="verilator", mode=mode)
    assert first_difference(expected, got) is None, first_difference(expected, got)


@pytest.mark.parametrize("wrong", [{"JO": ("OS",)}, {"JOS": ("OV",)}])
def test_a_wrong_jump_condition_is_caught(tmp_path, monkeypatch, wrong):
    monkeypatch.setattr(stl, "CC_JUMPS", {**stl.CC_JUMPS, **wrong})
    assert first_difference(*compare(tmp_path, "de")) is not None


@pytest.mark.parametrize("body, line, needle", [
    ("U OV\n= A 0.0", 8, "reads the status bit OV"),        # nothing set it
    # SPS clears OS where it jumps, the IL's stays
    ("L 1\nL 2\n+I\nSPS M1\nM1: U OS\n= A 0.0", 12, "reads the status bit OS"),
    ("L 1\nL 2\n+I\nNEGI\nU OS\n= A 0.0", 12, "reads the status bit OS"),
    ("L 1\nL 2\n+I\nLC Z 1\nU OV\n= A 0.0", 12, "reads the status bit OV"),
    ("L 1\nL 2\n+I\n= OV", 11, "OV is read by U/O/X and SPO"),
])
def test_rejections(tmp_path, body, line, needle):
    err = error_of(tmp_path, body)
    assert err.line == line and needle in err.message, (err.line, err.message)
