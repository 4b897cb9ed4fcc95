"""S7 DINT in `.awl` sources (spec §9 "INT and DINT arithmetic and compares", issue 19;
docs/s7.md, DINT): `L L#n`, `L/T MD n`, `+D -D *D /D MOD`, `==D` … `<=D`, `ITD`, `NEGD`,
`INVD`, `+ L#n` and the 32-bit constant forms, checked scan for scan against awlsim
(tests/awlsim_oracle.py) on the reference interpreter and on the Verilator harness in
serial and parallel mode; the high-word rule (an accumulator S7 would hold with
another high word is not read as a DINT) checked by its rejections; the oracle shown
to catch a translation that reads INT where S7 reads DINT."""
from __future__ import annotations

import pytest

from awlsim_oracle import awlsim_scans, bitbyte_scans
from bitbyte.lang import stl
from bitbyte.lang.errors import SourceError
from bitbyte.lang.parser import parse_file
from test_stl import same_as_awlsim, to_english, write
from tracecmp import first_difference

DINT_PROGRAM = {
    # DINT arithmetic through double words, with 32-bit wrap, division toward zero,
    # the remainder's sign, a word sign-extended by ITD, the compares
    "arithmetic": """
        L     EW 2
        ITD
        L     L#100000
        +D
        T     MD 10
        L     MD 10
        L     EW 4
        ITD
        *D
        T     MD 14
        L     MD 14
        L     L#-7
        /D
        T     MD 18
        L     MD 14
        L     L#7
        MOD
        T     MD 22
        L     L#2147483647
        L     MD 10
        +D
        T     MD 26
        L     MD 10
        L     L#100100
        >D
        =     A 0.0
        L     MD 14
        L     L#0
        <D
        =     A 0.1
        L     EW 2
        ITD
        L     EW 4
        ITD
        ==D
        =     A 0.2
        """,
    # NEGD, INVD, + L#n change ACCU1 in place; ITD after a DINT result (the IL's
    # ACCU1 may hold more than an INT there); the other 32-bit constant forms
    "in_place": """
        L     EW 2
        ITD
        NEGD
        T     MD 10
        L     MD 10
        INVD
        + L#-65536
        T     MD 14
        L     L#123456
        ITD
        T     MD 18
        L     DW#16#8000FFFF
        L     B#(1,2,3,4)
        -D
        T     MD 22
        L     2#10000000000000001
        L     5
        *D
        T     MD 26
        """,
}
WORDS = tuple(f"MW{n}" for n in range(10, 30, 2))


def dint_inputs(scans: int = 16) -> list[dict[int, int]]:
    """IW 2 and IW 4 through values around 0 and the ends of INT."""
    values = (0, 1, 100, 0xFFFF, 0x8000, 0x7FFF, 0xFFFB, 0x1234, 7, 0xFFF9)
    rows = []
    for k in range(scans):
        a, b = values[k % len(values)], values[(k * 3 + 1) % len(values)]
        rows.append({2: a >> 8, 3: a & 0xFF, 4: b >> 8, 5: b & 0xFF})
    return rows


@pytest.mark.parametrize("lang", ["de", "en"])
@pytest.mark.parametrize("name", sorted(DINT_PROGRAM))
def test_dint_against_awlsim(tmp_path, name, lang):
    body = DINT_PROGRAM[name]
    if lang == "en":
        body = to_english(body.replace("EW", "IW"))
    rows = same_as_awlsim(write(tmp_path, f"{name}_{lang}.awl", body), lang,
                          dint_inputs(), tmp_path, words=WORDS, in_words=(2, 4))
    if name == "arithmetic":                # S7's values, stated in words too
        assert (rows[0]["MW10"], rows[0]["MW12"]) == (1, -31072)    # 100000
        assert (rows[0]["MW26"], rows[0]["MW28"]) == (-32767, -31073)  # wrapped


def test_dint_on_verilator_serial_and_parallel(tmp_path):
    for name in sorted(DINT_PROGRAM):
        path = write(tmp_path, f"{name}.awl", DINT_PROGRAM[name])
        for mode in ("serial", "parallel"):
            same_as_awlsim(path, "de", dint_inputs(6), tmp_path, words=WORDS,
                           in_words=(2, 4), sim="verilator", mode=mode)


def test_oracle_catches_int_for_dint(tmp_path, monkeypatch):
    """`+D` translated as the IL's `+I` (16 bits): awlsim disagrees."""
    monkeypatch.setattr(stl, "IL_DINT", {**stl.IL_DINT, "+D": "+I"})
    path = write(tmp_path, "arith.awl", DINT_PROGRAM["arithmetic"])
    expected = awlsim_scans(path, dint_inputs(4), mnemonics="de", words=WORDS)
    got = bitbyte_scans(path, dint_inputs(4), tmp_path, words=WORDS, in_words=(2, 4))
    assert first_difference(expected, got) is not None


def error_of(tmp_path, body: str) -> SourceError:
    """The error of `body` in an OB 1 (its first statement is line 8)."""
    path = write(tmp_path, "bad.awl", body)
    with pytest.raises(SourceError) as info:
        parse_file(str(path), lang="stl")
    return info.value


@pytest.mark.parametrize("body, line, needle", [
    # S7's L of a word zero-extends: its high word is not the IL's
    ("L MW 10\nL L#5\n+D\nT MD 20", 10, "`+D` reads ACCU2 as a DINT"),
    # a negative INT constant: S7 holds 16#0000FFFB, the IL -5
    ("L -5\nL L#5\n==D\n= A 0.0", 10, "`==D` reads ACCU2 as a DINT"),
    # S7's +I leaves ACCU1-H as it was
    ("L 1\nL 2\n+I\nT MD 20", 11, "`T` reads ACCU1 as a DINT"),
    ("L MW 10\nNEGD\nT MD 20", 9, "`NEGD` reads ACCU1 as a DINT"),
    # the translation of NEGD changes ACCU2, which S7 leaves alone
    ("L L#1\nL L#2\nNEGD\n+D\nT MD 20", 11, "which the translation of `NEGD`"),
    ("L 40000\nT MW 10", 8, "write the DINT as `L#40000`"),
    ("L L#2147483648\nT MD 10", 8, "constant out of range"),
    ("L MD 10\nT MW 11", 9, "overlap"),     # MW 12 is MD 10's low half: fine
    ("BTD", 8, "BCD conversion of a DINT"),
])
def test_dint_rejections(tmp_path, body, line, needle):
    err = error_of(tmp_path, body)
    assert err.line == line and needle in err.message, (err.line, err.message)


def test_int_constants_at_least_0_are_dints_already(tmp_path):
    """S7's `L 5` is 16#00000005, which the IL holds too: no ITD needed."""
    path = write(tmp_path, "ok.awl", "L 5\nL L#70000\n+D\nT MD 10\nL W#16#7FFF\nL MD 10\n"
                 "<D\n= A 0.0")
    same_as_awlsim(path, "de", [{}] * 2, tmp_path, words=("MW10", "MW12"))


def test_the_high_word_rule_is_needed(tmp_path, monkeypatch):
    """Without the rule (every loaded accumulator read as a DINT), `L EW 2`, `L L#5`,
    `+D` differs from awlsim for a negative EW 2 (S7 zero-extends the word, the IL
    sign-extends it): the rejection guards a real difference."""
    monkeypatch.setattr(stl.StlFrontEnd, "read_dint", stl.StlFrontEnd.read_acc)
    path = write(tmp_path, "hi.awl", "L EW 2\nL L#5\n+D\nT MD 10")
    inputs = [{2: 0xFF, 3: 0xFB}]                       # EW 2 = -5
    words = ("MW10", "MW12")
    expected = awlsim_scans(path, inputs, mnemonics="de", words=words)
    got = bitbyte_scans(path, inputs, tmp_path, words=words, in_words=(2,))
    assert (expected[0]["MW10"], expected[0]["MW12"]) == (1, 0)   # 16#0000FFFB + 5
    assert first_difference(expected, got) is not None


# Review findings (each a silent difference or a wrong rejection before its fix)

def test_lc_keeps_accu2_as_an_int_of_the_old_accu1(tmp_path):
    """`LC` moves the old ACCU1 into ACCU2 through a 16-bit scratch word: after a DINT
    it is no longer S7's 32 bits, so `+D` on it is rejected, not computed wrongly."""
    err = error_of(tmp_path, "L L#100000\nLC Z 1\nITD\n+D\nT MD 10")
    assert err.line == 11 and "`+D` reads ACCU2 as a DINT" in err.message


@pytest.mark.parametrize("body, needle", [
    # MD 126 is bytes 126..129: its low half is the translation's scratch word MW 128
    ("L L#65537\nT MD 126\nL 5\nLC Z 1\nT MW 10", "M 128"),
])
def test_double_words_in_the_local_region_are_rejected(tmp_path, body, needle):
    err = error_of(tmp_path, body)
    assert err.message.startswith("unsupported:") and needle in err.message, err.message


def test_a_long_backward_jump_chain_settles(tmp_path):
    """Five backward SPA hops into a label that one path reaches with a word: the
    label's state settles to 'not a DINT' and `+D` is rejected (it was accepted with
    the state of a pass that had not settled)."""
    body = ("L -5\nT MW 0\nL L#1\nL L#2\nU E 0.0\nSPB STRT\nL6: +D\nT MD 10\nBEA\n"
            "L5: SPA L6\nL4: SPA L5\nL3: SPA L4\nL2: SPA L3\nL1: SPA L2\n"
            "STRT: L MW 0\nSPA L1")
    err = error_of(tmp_path, body)
    assert err.line == 14 and "`+D` reads ACCU1 as a DINT" in err.message, err.message


def test_a_dint_read_at_a_label_reached_by_a_later_jump(tmp_path):
    """The label's state is not known in the first pass: no rejection then."""
    path = write(tmp_path, "back.awl", "L L#1\nL L#2\nSPA M2\nM1: +D\nT MD 10\nBEA\n"
                 "M2: SPA M1")
    rows = same_as_awlsim(path, "de", [{}] * 2, tmp_path, words=("MW10", "MW12"))
    assert (rows[0]["MW10"], rows[0]["MW12"]) == (0, 3)


@pytest.mark.parametrize("actual", ["MD 10", "L#100000", "DW#16#1"])
def test_an_int_parameter_takes_no_32_bit_actual(tmp_path, actual):
    text = ("FUNCTION FC 1 : VOID\nVAR_INPUT\n  x : INT;\nEND_VAR\nBEGIN\nNETWORK\n"
            "TITLE =\nL #x\nT MW 20\nEND_FUNCTION\n\n"
            "ORGANIZATION_BLOCK OB 1\nBEGIN\nNETWORK\nTITLE =\n"
            f"CALL FC 1 (x := {actual});\nEND_ORGANIZATION_BLOCK\n")
    path = tmp_path / "fc.awl"
    path.write_text(text)
    with pytest.raises(SourceError) as info:
        parse_file(str(path), lang="stl")
    assert info.value.line == 16 and "is INT (16 bits), not the 32-bit" in \
        info.value.message, info.value.message
