"""S7 word logic and shifts in `.awl` sources (issue 19; docs/s7.md, "Word logic and
shifts"): `UW OW XOW UD OD XOD` (English `AW OW XOW AD OD XOD`) with and without a
constant, `SLW SRW SSI SLD SRD SSD RLD RRD` with a count and with the count in ACCU2,
checked scan for scan against awlsim (tests/awlsim_oracle.py) on the reference
interpreter and on the Verilator harness in serial and parallel mode; the oracle
shown to catch a wrong translation."""
from __future__ import annotations

import pytest

from awlsim_oracle import awlsim_scans, bitbyte_scans
from bitbyte.lang import stl
from test_stl import same_as_awlsim, write
from test_stl_dint import error_of
from tracecmp import first_difference

PROGRAM = {
    "logic": """
        L     EW 2
        L     W#16#0FF0
        UW
        T     MW 10
        L     EW 2
        OW    W#16#8001
        T     MW 12
        L     EW 2
        L     EW 4
        XOW
        T     MW 14
        L     EW 4
        ITD
        UD    DW#16#F0F0FFFF
        T     MD 16
        L     EW 2
        ITD
        L     EW 4
        ITD
        OD
        XOD   L#-65536
        T     MD 20
        """,
    "shifts": """
        L     EW 2
        SLW   3
        T     MW 10
        L     EW 2
        SSI   2
        T     MW 12
        L     EW 2
        SRW   17
        T     MW 14
        L     EW 4
        ITD
        SLD   9
        T     MD 16
        L     EW 4
        ITD
        RRD   4
        SSD   3
        T     MD 20
        L     3
        L     EW 2
        SRW
        T     MW 24
        L     EW 2
        ITD
        RLD   0
        T     MD 26
        """,
}
WORDS = tuple(f"MW{n}" for n in range(10, 30, 2))


def inputs(scans: int = 12) -> list[dict[int, int]]:
    values = (0x9234, 0x0005, 0x8107, 0x7FFF, 0xFFFF, 0x8000, 0x00FF, 0x1234)
    rows = []
    for k in range(scans):
        a, b = values[k % len(values)], values[(k * 3 + 2) % len(values)]
        rows.append({2: a >> 8, 3: a & 0xFF, 4: b >> 8, 5: b & 0xFF})
    return rows


def english(body: str) -> str:
    return body.replace("EW", "IW").replace("UW", "AW").replace("UD", "AD")


@pytest.mark.parametrize("lang", ["de", "en"])
@pytest.mark.parametrize("name", sorted(PROGRAM))
def test_word_logic_and_shifts_against_awlsim(tmp_path, name, lang):
    body = PROGRAM[name] if lang == "de" else english(PROGRAM[name])
    rows = same_as_awlsim(write(tmp_path, f"{name}_{lang}.awl", body), lang, inputs(),
                          tmp_path, words=WORDS, in_words=(2, 4))
    if name == "logic":                         # S7's values, stated in words too
        assert rows[0]["MW10"] == 0x0230 and rows[0]["MW12"] == -28107   # 16#9235


def test_on_verilator_serial_and_parallel(tmp_path):
    for name in sorted(PROGRAM):
        path = write(tmp_path, f"{name}.awl", PROGRAM[name])
        for mode in ("serial", "parallel"):
            same_as_awlsim(path, "de", inputs(4), tmp_path, words=WORDS,
                           in_words=(2, 4), sim="verilator", mode=mode)


@pytest.mark.parametrize("wrong", [{"SRW": "SSI"}, {"XOW": "OW"}])
def test_oracle_catches_a_wrong_instruction(tmp_path, monkeypatch, wrong):
    real = stl.StlFrontEnd.emit

    def emit(self, mnemonic, *args, **kw):
        return real(self, wrong.get(mnemonic, mnemonic), *args, **kw)

    monkeypatch.setattr(stl.StlFrontEnd, "emit", emit)
    name = "shifts" if "SRW" in wrong else "logic"
    path = write(tmp_path, "w.awl", PROGRAM[name])
    expected = awlsim_scans(path, inputs(), mnemonics="de", words=WORDS)
    got = bitbyte_scans(path, inputs(), tmp_path, words=WORDS, in_words=(2, 4))
    assert first_difference(expected, got) is not None


@pytest.mark.parametrize("body, line, needle", [
    ("L MW 10\nL L#1\nUD\nT MD 20", 10, "`UD` reads ACCU2 as a DINT"),  # zero-extended
    ("L EW 2\nSLD 3\nT MD 20", 9, "`SLD` reads ACCU1 as a DINT"),
    ("L 1\nL 2\nUW W#16#FF\n+I\nT MW 10", 11, "which the translation of `UW W#16#FF`"),
    ("L 1\nUW W#16#10000", 9, "constant out of range"),
    ("L 1\nUW L#65536", 9, "takes 16 bits"),
    ("L 1\nSLW 256", 9, "a shift count is 0..255"),
    ("L 1\nSLW -1", 9, "a shift count is 0..255"),
    # review findings: operands glued together, an S5TIME taken as a pattern
    ("L 1\nOW B#16#1 0", 9, "extra operand `0`"),
    ("L 1\nUW S5T#1S", 9, "invalid operand `S5T#1S`"),
    ("L 1\nRLDA", 9, "no condition codes"),
])
def test_rejections(tmp_path, body, line, needle):
    err = error_of(tmp_path, body)
    assert err.line == line and needle in err.message, (err.line, err.message)
