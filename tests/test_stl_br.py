"""S7's status bit BR in `.awl` sources (spec §9 "the status word where a program
reads it"; docs/s7.md, "BR"): `SAVE`, `SPBB`/`SPBNB` (JCB/JNB) write it, `U BIE` …
(`A BR` …) and `SPBI`/`SPBIN` (JBI/JNBI) read it, 0 at every OB's start, kept across
calls (an FC's `SAVE` is its caller's ENO); checked scan for scan against awlsim on
the reference interpreter and on the Verilator harness in serial and parallel mode;
wrong translations shown to be caught."""
from __future__ import annotations

import pytest

from awlsim_oracle import awlsim_scans, bitbyte_scans
from bitbyte.lang import stl
from test_stl_dint import error_of
from tracecmp import assert_equal_and_varied, first_difference

PROGRAM_DE = """FUNCTION FC 1 : VOID
VAR_INPUT
  x : BOOL;
END_VAR
BEGIN
      U     #x
      UN    E 0.3
      SAVE
      BEA
END_FUNCTION

ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE = BR
      U     BIE
      =     A 1.4
      U     E 0.0
      O     E 0.1
      SAVE
      U     BIE
      =     A 0.0
      UN    BIE
      U     E 0.2
      =     A 0.1
      U     E 0.1
      SPBB  M1
      =     A 0.2
M1:   O     BIE
      X     E 0.3
      =     A 0.3
      U     E 0.2
      SPBNB M2
      SET
      =     A 0.4
M2:   U     E 0.0
      SPBI  M3
      =     A 0.5
      CLR
M3:   =     A 0.6
      U     E 0.3
      O
      U     E 0.1
      SPBIN M4
      S     A 1.0
M4:   R     A 1.1
      CALL  FC 1 (x := E 0.1)
      U     BIE
      =     A 1.2
      ON    BIE
      =     A 1.3
END_ORGANIZATION_BLOCK
"""
ENGLISH = {"U": "A", "UN": "AN", "SPBB": "JCB", "SPBNB": "JNB", "SPBI": "JBI",
           "SPBIN": "JNBI", "BEA": "BEU", "BIE": "BR", "E": "I", "A": "Q"}


def program(lang: str) -> str:
    if lang == "de":
        return PROGRAM_DE
    out = []
    for line in PROGRAM_DE.splitlines():
        words = line.split(" ")
        out.append(" ".join(ENGLISH.get(w, w) for w in words))
    return "\n".join(out) + "\n"


def inputs() -> list[dict[int, int]]:
    return [{0: k % 16} for k in range(32)]


def compare(tmp_path, lang: str, **kw):
    path = tmp_path / f"br_{lang}.awl"
    path.write_text(program(lang))
    expected = awlsim_scans(path, inputs(), mnemonics=lang)
    got = bitbyte_scans(path, inputs(), tmp_path, mnemonics=lang, **kw)
    return expected, got


@pytest.mark.parametrize("lang", ["de", "en"])
def test_br_against_awlsim(tmp_path, lang):
    expected, got = compare(tmp_path, lang)
    assert_equal_and_varied(expected, got, ("Q0.0", "Q0.1", "Q0.3", "Q0.5", "Q0.6", "Q1.2", "Q1.3"))
    assert all(row["Q1.4"] == 0 for row in expected)        # 0 at the OB's start


@pytest.mark.parametrize("mode", ["serial", "parallel"])
def test_br_on_verilator(tmp_path, mode):
    expected, got = compare(tmp_path, "de", sim="verilator", mode=mode)
    assert first_difference(expected, got) is None, first_difference(expected, got)


def test_wrong_translations_are_caught(tmp_path, monkeypatch):
    """BR not reset at the scan start, SPBB not writing BR, SPBI on the inverse."""
    real_emit = stl.StlFrontEnd.emit

    def no_reset(self, mnemonic, operand=None, **kw):
        if mnemonic == "R" and operand is not None and self.scratch_bits.get(
                ("BR",)) is operand:
            return
        real_emit(self, mnemonic, operand, **kw)
    monkeypatch.setattr(stl.StlFrontEnd, "emit", no_reset)
    assert first_difference(*compare(tmp_path, "de")) is not None
    monkeypatch.setattr(stl.StlFrontEnd, "emit", real_emit)

    real_jump = stl.StlFrontEnd.jump
    monkeypatch.setattr(stl.StlFrontEnd, "jump", lambda self, stmt, st, m, edges:
                        real_jump(self, stmt, st, {"JCB": "JC", "JNB": "JCN"}.get(m, m),
                                  edges))
    assert first_difference(*compare(tmp_path, "de")) is not None
    monkeypatch.setattr(stl.StlFrontEnd, "jump", real_jump)

    real_br_jump = stl.StlFrontEnd.br_jump
    monkeypatch.setattr(stl.StlFrontEnd, "br_jump", lambda self, stmt, st, m, edges:
                        real_br_jump(self, stmt, st, {"JBI": "JNBI", "JNBI": "JBI"}[m],
                                     edges))
    assert first_difference(*compare(tmp_path, "de")) is not None


@pytest.mark.parametrize("body, line, needle", [
    ("U E 0.0\nO\nU E 0.1\nSAVE\nU BIE\n= A 0.0", 11, "`SAVE` after `O`"),
    ("U E 0.0\nU(\nU E 0.1\nSPBI M1\n)\nM1: U BIE\n= A 0.0", 11,
     "`SPBI` inside parentheses"),
    ("U E 0.0\n= BIE", 9, "BR is read by U/O/X and SPBI/SPBIN"),
])
def test_rejections(tmp_path, body, line, needle):
    err = error_of(tmp_path, body)
    assert err.line == line and needle in err.message, (err.line, err.message)
