"""S7 jump lists (`SPL l` / `JL l` with its SPA / JU list, spec §9, issue 19):
translated into a compare chain on ACCU1's low byte (the IL has no computed jump;
docs/s7.md, "Jump lists"), compared with awlsim scan for scan — index values in
and out of the list, above 255 and negative (S7 takes the low byte), the RLO and
/FC kept across SPL and SPA.  A translation without the low-byte step is caught.
"""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from awlsim_oracle import awlsim_scans, bitbyte_scans
from bitbyte import cli
from bitbyte.lang import stl
from tracecmp import first_difference

PROGRAM = {"de": """ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE = a jump list on EW 2, taken in the middle of a string
      L     EW 2
      U     E 0.0
      SPL   LST
      SPA   S0
      SPA   S1
      SPA   S2
LST:  =     A 0.7              // not in the list: the RLO of U E 0.0
      SPA   END
S0:   =     A 0.0
      SPA   END
S1:   U     E 0.1              // /FC = 1: combines with E 0.0
      =     A 0.1
      SPA   END
S2:   O     E 0.2
      =     A 0.2
END:  L     EW 2
      L     3
      SPL   L2                 // a list of one entry, ACCU1 known: no low-byte step
      SPA   T0
L2:   SPA   END2
T0:   U     E 0.3
      =     A 0.3
END2: L     EW 2
      L     1
      +I
      T     MW 10
END_ORGANIZATION_BLOCK
"""}
PROGRAM["en"] = (PROGRAM["de"].replace("SPL ", "JL  ").replace("SPA ", "JU  ")
                 .replace("EW ", "IW ").replace("U     E", "A     I")
                 .replace("O     E", "O     I").replace("A 0.", "Q 0."))


def word_inputs(seed: int, scans: int = 60) -> list[dict[int, int]]:
    r = random.Random(seed)
    rows = []
    for _ in range(scans):
        w = r.choice((0, 1, 2, 3, 4, 255, 256, 257, 258, -1, -255, -254, -256, -510,
                      1000, 32767, -32768)) & 0xFFFF
        rows.append({0: r.randrange(256), 1: 0, 2: w >> 8, 3: w & 0xFF})
    return rows


def compare(path: Path, lang: str, tmp: Path, **kw):
    stim = word_inputs(7)
    expected = awlsim_scans(path, stim, mnemonics=lang, words=("MW10",))
    got = bitbyte_scans(path, stim, tmp, words=("MW10",), in_words=(2,), **kw)
    return expected, first_difference(expected, got)


@pytest.mark.parametrize("lang", ["de", "en"])
def test_jump_list_against_awlsim(tmp_path, lang):
    path = tmp_path / "jl.awl"
    path.write_text(PROGRAM[lang])
    expected, diff = compare(path, lang, tmp_path)
    assert diff is None, diff
    # every entry and the default were taken in some scan
    for q in ("Q0.0", "Q0.7"):
        assert {row[q] for row in expected} == {0, 1}, q


def test_jump_list_on_verilator_serial_and_parallel(tmp_path):
    path = tmp_path / "jl.awl"
    path.write_text(PROGRAM["de"])
    for mode in ("serial", "parallel"):
        assert compare(path, "de", tmp_path, sim="verilator", mode=mode)[1] is None, mode


def ob(body: str) -> str:
    return "ORGANIZATION_BLOCK OB 1\nBEGIN\nNETWORK\nTITLE =\n" + body + \
        "\nEND_ORGANIZATION_BLOCK\n"


@pytest.mark.parametrize("body,line,col,message", [
    ("L MW 10\nSPL X\nSPA Y\n= A 0.0\nX: SPA Y\nY: NOP 0", 8, 1,
     "unsupported: `=` in the jump list of `SPL` (line 6)"),
    ("L MW 10\nSPL X\nSPA Y\nY: NOP 0\nX: NOP 0", 8, 4,
     "unsupported: `NOP` in the jump list of `SPL` (line 6): only unlabelled SPA"),
    ("X: NOP 0\nL MW 10\nSPL X\nSPA X", 7, 1, "unsupported: `SPL X`: its label must "
     "end the jump list"),
    ("SPL X\nX: NOP 0", 5, 1, "unsupported: `SPL` reads ACCU1"),
    ("L MW 10\nSPL Q\nQ2: NOP 0", 6, 5, "unknown label `Q`"),
])
def test_jump_list_errors(tmp_path, capsys, body, line, col, message):
    path = tmp_path / "bad.awl"
    path.write_text(ob(body))
    code = cli.main(["asm", str(path), "-o", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 1 and err.startswith(f"{path}:{line}:{col}: {message}"), err


def test_oracle_catches_a_jump_list_without_the_low_byte(tmp_path, monkeypatch):
    """Comparing all 16 bits of ACCU1 with the entries (S7 takes the low byte: 257
    is entry 1) differs from awlsim."""
    original = stl.StlFrontEnd.jump_list

    def sixteen_bits(self, stmt, st, edges):
        if st.acc[0] is not None:
            st.acc = (stl.Known(0), st.acc[1])     # "known to be 0..255"
        return original(self, stmt, st, edges)

    monkeypatch.setattr(stl.StlFrontEnd, "jump_list", sixteen_bits)
    path = tmp_path / "jl.awl"
    path.write_text(PROGRAM["de"])
    assert compare(path, "de", tmp_path)[1] is not None
