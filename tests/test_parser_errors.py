"""Every error class of spec §3 "Errors", each at its exact line:col, and a fuzz test
that no input makes the parser (or the encoder) raise anything but SourceError.

Positions are written by hand from the small programs; messages are checked by a
stable substring only, so that wording can improve without breaking the tests.
"""
from __future__ import annotations

import os
import random

import pytest

from bitbyte.lang.config import DEFAULT, Config
from bitbyte.encoding.encoder import encode
from bitbyte.lang.errors import SourceError, format_error
from bitbyte.lang.parser import parse, parse_file
from bitbyte.lang.program import Program


def error_of(text, config=DEFAULT) -> SourceError:
    with pytest.raises(SourceError) as info:
        parse("t.il", text, config)
    return info.value


def check(text, line, col, substring, config=DEFAULT) -> SourceError:
    """The error is at line:col, its message holds `substring`, and it prints
    as `t.il:line:col: message`."""
    err = error_of(text, config)
    assert (err.line, err.col) == (line, col), format_error(err)
    assert substring in err.message, format_error(err)
    assert format_error(err).startswith(f"t.il:{line}:{col}: {err.message}\n")
    return err


# ---------------------------------------------------------------------------------------
# The format
# ---------------------------------------------------------------------------------------

def test_format_is_gcc_like_with_caret_under_the_column():
    err = SourceError("p.il", 3, 5, "unknown mnemonic `LDX`", "\tLD LDX")
    assert format_error(err) == "p.il:3:5: unknown mnemonic `LDX`\n\tLD LDX\n\t   ^"
    assert str(err) == format_error(err)
    assert f"{err}" == format_error(err)


def test_format_without_position():
    assert format_error(SourceError("p.il", 0, 0, "cannot read: gone")) == \
        "p.il: cannot read: gone"


def test_unreadable_file_is_a_source_error(tmp_path):
    with pytest.raises(SourceError) as info:
        parse_file(str(tmp_path / "missing.il"))
    assert "cannot read" in info.value.message


def test_parse_file_reads_bytes(tmp_path):
    path = tmp_path / "p.il"
    path.write_bytes(b"LD I0.0\r\n= Q0.0\r\n")
    program = parse_file(str(path))
    assert [i.mnemonic for i in program.instrs] == ["LD", "=", "END"]
    assert program.path == str(path)


# ---------------------------------------------------------------------------------------
# One test per error class
# ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("text, line, col", [
    ("LD I0.0\n  LDX I0.1\n", 2, 3),
    ("LD I0.0\nLDN( \n", 2, 1),            # only A( AN( O( ON( X( XN( exist
    ("L 1\nL 2\nAN ==I\n", 3, 1),          # compares combine with A or O only
    ("\"Start\" I0.0\n", 1, 1),
    ("(\n", 1, 1),
    ("Foo\n", 1, 1),
])
def test_unknown_mnemonic(text, line, col):
    check(text, line, col, "unknown mnemonic")


@pytest.mark.parametrize("text, col", [
    ("LD I16.0", 4), ("LD I 16.0", 4), ("LD PI0.8", 4), ("LD IR16.0", 4),
    ("LD IF0.9", 4), ("= Q16.0", 3), ("= PQ16.0", 3), ("S M256.0", 3),
    ("LD T64", 4), ("LD C 64", 4), ("LD FBI4", 4), ("= FBY 4", 3), ("L IW16", 3),
    ("T QW16", 3), ("T MW256", 3), ("LD I99999999999999999999999999999999.0", 4),
    ("LD QR16.0", 4), ("A QF0.8", 3), ("L MD254", 3), ("T MD 254", 3),
])
def test_operand_out_of_range(text, col):
    check("NOP\n" + text + "\n", 2, col, "operand out of range")


def test_operand_out_of_range_follows_the_configuration():
    small = Config(in_bytes=2, out_bytes=1, marker_bytes=4, timers=8, counters=8,
                   channels=2, in_words=2, out_words=2, data_words=16)
    parse("t.il", "LD I1.7\n= Q0.7\nS M3.7\nLD T7\nLD C7\nLD FBI1\n", small)
    parse("t.il", "LD QR0.7\nA QF0.7\n", small)
    for text in ("LD I2.0", "= Q1.0", "LD QR1.0", "A QF1.0", "S M4.0", "LD T8", "LD C8", "LD FBI2",
                 "= FBY2", "L IW2", "T QW2", "T MW16"):
        check(text, 1, text.index(" ") + 2, "operand out of range", small)


def test_out_of_range_in_a_declaration():
    check("VAR\n  Big AT M256.0;\nEND_VAR\n", 2, 10, "operand out of range")


@pytest.mark.parametrize("text", [
    "32768", "-32769", "16#10000", "16#FFFFF", "T#2147483648ms", "T#596h31m23s648ms",
    "T#24856h1m", "99999999999999999999999999999999999", "L#2147483648", "L#-2147483649",
])
def test_constant_out_of_range(text):
    check(f"NOP\n  L {text}\n", 2, 5, "constant out of range")


def test_constants_at_their_limits_are_accepted():
    program = parse("t.il", "L -32768\nL 32767\nL 16#FFFF\nL 16#8000\nL 16#7fff\n"
                            "L T#596h31m23s647ms\nL T#0ms\nL +5\n")
    values = [i.operand.value for i in program.instrs[:-1]]
    assert values == [-32768, 32767, -1, -32768, 32767, 2 ** 31 - 1, 0, 5]
    program = parse("t.il", "L L#2147483647\nL L#-2147483648\nL L#+7\nL MD253\nT MD 0\n")
    assert [i.operand.value for i in program.instrs[:3]] == [2 ** 31 - 1, -2 ** 31, 7]
    assert [i.operand.address() for i in program.instrs[:5]] == [
        "L#2147483647", "L#-2147483648", "L#7", "MD253", "MD0"]


@pytest.mark.parametrize("text", ["L#", "L#x", "L#1.5", "L#--1"])
def test_malformed_dint_constant(text):
    check(f"NOP\n  L {text}\n", 2, 5, "malformed constant")


def test_double_words_are_word_operands_only():
    check("NOP\n  LD MD0\n", 2, 6, "not the double word `MD0`")
    check("NOP\n  = MD0\n", 2, 5, "not the double word `MD0`")
    check("NOP\n  L MD 0.1\n", 2, 5, "malformed address `MD 0.1`")


@pytest.mark.parametrize("text, line, col", [
    ("LD Start\n", 1, 4),
    ("LD \"Start\"\n", 1, 4),                                     # at the quote
    ("LD Start\nVAR Start AT I0.0; END_VAR\n", 1, 4),             # declared too late
    ("VAR Start AT I0.0; END_VAR\nLD Start\nA Stop\n", 3, 3),
])
def test_undeclared_symbol(text, line, col):
    check(text, line, col, "undeclared symbol")


@pytest.mark.parametrize("text, line, col", [
    ("VAR\n  Start AT I0.0;\n  START AT I0.1;\nEND_VAR\n", 3, 3),  # case-insensitive
    ("VAR\n  a1 AT I0.0; a1 AT I0.1;\nEND_VAR\n", 2, 15),
    ("VAR x1 AT M0.0; END_VAR\nNOP\nVAR\n x1 AT M0.1;\nEND_VAR\n", 4, 2),
    ("lbl: NOP\nVAR lbl AT M0.0; END_VAR\n", 2, 5),                # a label's name
    ("VAR\n  a1 AT I0.0;\n  a1 AT I99.0;\nEND_VAR\n", 3, 3),     # before the range
])
def test_duplicate_symbol(text, line, col):
    check(text, line, col, "duplicate symbol")


@pytest.mark.parametrize("text, line, col", [
    ("loop: NOP\n  JU loop\nLOOP:\n", 3, 1),
    ("a1:\nb1: a1: NOP\n", 2, 5),
    ("VAR x1 AT M0.0; END_VAR\nx1: NOP\n", 2, 1),                # a symbol's name
])
def test_duplicate_label(text, line, col):
    check(text, line, col, "duplicate label")


def test_unknown_label():
    check("JU fine\nfine: NOP\n  JC missing\n", 3, 6, "unknown label")


def test_unknown_label_reported_before_a_later_unclosed_parenthesis():
    check("JU nowhere\nA(\nLD I0.0\n", 1, 4, "unknown label")


@pytest.mark.parametrize("text, line, col", [
    ("LD I0.0\nA(\n  A I0.1\n)\n", 3, 3),
    ("LD I0.0\nO(\n\n// comment\nlbl:\n   NOT\n)\n", 6, 4),
    ("LD I0.0\nA(\n)\n", 3, 1),
    ("LD I0.0\nA(\nEND\n", 3, 1),
])
def test_paren_not_followed_by_load(text, line, col):
    check(text, line, col, "`(` not followed by LD/LDN")


@pytest.mark.parametrize("text, line, col, substring", [
    ("LD I0.0\n  A(\n  LD I0.1\n= Q0.0\n", 2, 3, "not closed"),            # at EOF
    ("LD I0.0\nA(\nLD I0.1\nO(\nLD I0.2\n)\n", 2, 1, "not closed"),
    ("LD I0.0\nA(\nLD I0.1\nA(\nLD I0.2\n", 4, 1, "not closed"),         # innermost
    ("LD I0.0\nX(\nLD I0.1\nEND\n)\n", 2, 1, "not closed"),              # at END
    ("LD I0.0\n  )\n", 2, 3, "without an open"),
    ("LD I0.0\nA(\nLD I0.1\n)\n)\n", 5, 1, "without an open"),
])
def test_unbalanced_parentheses(text, line, col, substring):
    err = check(text, line, col, "unbalanced parentheses")
    assert substring in err.message


def test_nesting_deeper_than_configured():
    deep = "LD I0.0\n" + "A(\nLD I0.0\n" * 9 + ")\n" * 9
    check(deep, 18, 1, "nested deeper than 8")              # the 9th A( on line 18
    ok = "LD I0.0\n" + "A(\nLD I0.0\n" * 8 + ")\n" * 8
    parse("t.il", ok)
    check("LD I0.0\nA(\nLD I0.0\nO(\nLD I0.0\nX(\nLD I0.0\n)\n)\n)\n", 6, 1,
          "nested deeper than 2", Config(nest_depth=2))


@pytest.mark.parametrize("text, line, col", [
    ("NOP\n  LD\n", 2, 3), ("= // no target\n", 1, 1), ("JU ; comment\n", 1, 1),
    ("L\n", 1, 1), ("SD\n", 1, 1), ("VAR x1 AT ; END_VAR\n", 1, 8),
])
def test_missing_operand(text, line, col):
    check(text, line, col, "missing operand")


@pytest.mark.parametrize("text, line, col", [
    ("LD I0.0 I0.1\n", 1, 9), ("NOT I0.0\n", 1, 5), ("A( LD I0.0\n", 1, 4),
    (")  Q0.0\n", 1, 4), ("+I MW0\n", 1, 4), ("JU lbl lbl\nlbl:\n", 1, 8),
    ("LD I 0.0 1\n", 1, 10), ("VAR x1 AT I0.0 y1; END_VAR\n", 1, 16),
    ("REFRESH Q Q\n", 1, 11), ("REFRESH I Q0.0\n", 1, 11),
])
def test_extra_operand(text, line, col):
    check(text, line, col, "extra operand")


@pytest.mark.parametrize("text, col", [
    ("= I0.0", 3), ("= PI0.0", 3), ("S IR0.0", 3), ("R IF0.0", 3), ("= T1", 3),
    ("S T1", 3), ("= C1", 3), ("= MW0", 3), ("S IW0", 3), ("R FBI0", 3),
    ("FP I0.0", 4), ("FN PQ0.0", 4), ("FP T1", 4), ("FN MW0", 4),
    ("T IW0", 3), ("T M0.0", 3), ("T T1", 3), ("T 5", 3),
    ("LD MW0", 4), ("A IW0", 3), ("ON QW1", 4), ("LD FBY0", 4), ("LD 5", 4),
    ("A T#5s", 3), ("L I0.0", 3), ("L FBI0", 3),
    ("JU I0.0", 4), ("JC 5", 4), ("JCN T1", 5), ("JU Start", 4),
    ("SD C1", 4), ("SS M0.0", 4), ("CU T1", 4), ("CD 3", 4),
    ("READ FBI0", 6), ("WRITE FBY0", 7), ("READ M0.0", 6),
    # the output edges are read only; REFRESH names an image (I or Q) or nothing
    ("= QR0.0", 3), ("S QF0.0", 3), ("R QR1.1", 3), ("FP QR0.0", 4), ("FN QF0.0", 4),
    ("L QR0.0", 3), ("T QF0.0", 3), ("REFRESH M", 9), ("REFRESH Q0.0", 9),
    ("REFRESH IW0", 9), ("REFRESH 5", 9), ("REFRESH Start", 9),
])
def test_operand_of_the_wrong_kind(text, col):
    check("VAR Start AT I0.0; END_VAR\n" + text + "\n", 2, col, "wrong kind")


def test_wrong_kind_through_a_symbol_names_the_address():
    err = check("VAR\n Speed AT IW0;\nEND_VAR\nA Speed\n", 4, 3, "wrong kind")
    assert "Speed" in err.message and "IW0" in err.message


@pytest.mark.parametrize("text, line, col", [
    ("VAR\n  Start AT I0.0;\n", 1, 1),                           # end of file
    ("NOP\n  var\n  Start AT I0.0;\n  // no END_VAR\n", 2, 3),
    ("VAR\n  Start AT I0.0;\nLD Start\n= Q0.0\n", 3, 1),         # the program starts
    ("VAR\n  Start AT I0.0;\nloop: NOP\n", 3, 1),
    ("VAR\n  Start AT I0.0;\nVAR\n", 3, 1),
])
def test_missing_end_var(text, line, col):
    check(text, line, col, "missing END_VAR")


@pytest.mark.parametrize("data, line, col", [
    (b"LD I0.0\n= Q0\x00.0\n", 2, 5),
    (b"\x80", 1, 1),
    (b"LD I0.0\x7f\n", 1, 8),
    (b"LD I0.0\rNOT\n", 1, 8),                      # CR only right before LF
    (b"LD I0.0\r", 1, 8),
    (b"LD I0.0\r\r\n", 1, 8),
    (b"LDX\n\x0c\n", 2, 1),                          # found before the bad mnemonic
    (b"// caf\xc3\xa9\n", 1, 7),
    ("// é\n", 1, 4),                                 # str input is checked too
    (bytes(range(256)), 1, 1),
])
def test_invalid_byte(data, line, col):
    err = check(data, line, col, "invalid byte")
    assert "\x00" not in format_error(err)


def test_crlf_and_tabs_are_fine():
    program = parse("t.il", b"\tLD\tI0.0\r\n\t=\tQ0.0 // x\r\n")
    assert [(i.mnemonic, i.line, i.col) for i in program.instrs[:2]] == \
        [("LD", 1, 2), ("=", 2, 2)]
    assert program.instrs[0].source == "\tLD\tI0.0"


def test_program_too_large():
    config = Config(prog_words=3)
    check("NOP\nNOP\nNOP\n  NOP\n", 4, 3, "program too large", config)
    err = check("NOP\nNOP\n  NOP\n", 3, 3, "program too large", config)   # + END
    assert "appended END" in err.message
    err = check("NOP\nNOP\n  END\nlbl:\n", 3, 3, "program too large", config)
    assert len(parse("t.il", "NOP\nNOP\n", config).instrs) == 3
    assert len(parse("t.il", "NOP\nNOP\nEND\n", config).instrs) == 3


# ---------------------------------------------------------------------------------------
# Names, and what is not an error
# ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("text, line, col, substring", [
    ("VAR\n  LD AT I0.0;\nEND_VAR\n", 2, 3, "is a mnemonic"),
    ("VAR\n  T1 AT I0.0;\nEND_VAR\n", 2, 3, "is an address"),
    ("VAR\n  i AT I0.0;\nEND_VAR\n", 2, 3, "is an address"),
    ("VAR\n  mw3x AT I0.0;\nEND_VAR\n", 2, 3, "is an address"),
    ("VAR\n  at AT I0.0;\nEND_VAR\n", 2, 3, "is a keyword"),
    ("NOP\nJCN: NOP\n", 2, 1, "is a mnemonic"),
    ("NOP\nM0: NOP\n", 2, 1, "is an address"),
    ("VAR: NOP\n", 1, 1, "is a keyword"),
])
def test_a_name_may_not_be_a_mnemonic_or_an_address(text, line, col, substring):
    check(text, line, col, substring)


def test_var_global_declares_shared_variables():
    program = parse("t.il", "NOP\n  VAR_GLOBAL\n  Flag AT M0.0 : WRITE; Cnt AT MW3:read\n"
                            "END_VAR\nLD Flag\n")
    assert [(g.name, g.kind, g.access, g.operand.address(), g.line, g.col)
            for g in program.globals] == [("FLAG", "bit", "WRITE", "M0.0", 3, 3),
                                           ("CNT", "word", "READ", "MW3", 3, 25)]
    assert program.symbols["FLAG"].address() == "M0.0"
    assert program.instrs[1].operand.address() == "M0.0"
    assert parse("t.il", "VAR Start AT I0.0; END_VAR\nNOP\n").globals == []


@pytest.mark.parametrize("text, line, col, substring", [
    ("VAR_GLOBAL\n  Flag AT M0.0 WRITE;\nEND_VAR\n", 2, 15, "missing `:`"),
    ("VAR_GLOBAL\n  Flag AT M0.0;\nEND_VAR\n", 2, 15, "missing `:`"),
    ("VAR_GLOBAL\n  Flag AT M0.0 : ;\nEND_VAR\n", 2, 16, "missing access"),
    ("VAR_GLOBAL\n  Flag AT M0.0 : RW;\nEND_VAR\n", 2, 18, "unknown access `RW`"),
    ("VAR_GLOBAL\n  Flag AT M0.0 : READ WRITE\nEND_VAR\n", 2, 23, "extra operand"),
    ("VAR_GLOBAL\n  Flag : READ;\nEND_VAR\n", 2, 8, "expected `AT`"),
    ("VAR_GLOBAL\n  Flag AT I0.0 : READ;\nEND_VAR\n", 2, 11, "operand of the wrong kind"),
    ("VAR_GLOBAL\n  Flag AT QW1 : READ;\nEND_VAR\n", 2, 11, "operand of the wrong kind"),
    ("VAR_GLOBAL\n  Flag AT T1 : READ;\nEND_VAR\n", 2, 11, "operand of the wrong kind"),
    ("VAR_GLOBAL\n  Flag AT M256.0 : READ;\nEND_VAR\n", 2, 11, "operand out of range"),
    ("VAR_GLOBAL\n  Flag AT M0.0 : READ; flag AT M0.1 : WRITE\nEND_VAR\n", 2, 24,
     "duplicate symbol `flag`"),
    ("VAR Flag AT I0.0; END_VAR\nVAR_GLOBAL\n  Flag AT M0.0 : READ\nEND_VAR\n", 3, 3,
     "duplicate symbol"),
    ("VAR_GLOBAL\n  A1 AT M0.0 : READ; B1 AT M0.0 : WRITE\nEND_VAR\n", 2, 28,
     "duplicate local copy"),
    ("VAR_GLOBAL\n  LD AT M0.0 : READ\nEND_VAR\n", 2, 3, "is a mnemonic"),
    ("VAR_GLOBAL\n  M1 AT M0.0 : READ\nEND_VAR\n", 2, 3, "is an address"),
    ("VAR_GLOBAL\n  Flag AT M0.0 : READ;\n", 1, 1, "missing END_VAR"),
    ("VAR_GLOBAL\n  Flag AT M0.0 : READ;\nLD Flag\n", 3, 1, "missing END_VAR"),
    ("VAR_GLOBAL\n  Flag AT M0.0 : READ;\nVAR\n", 3, 1, "missing END_VAR"),
])
def test_var_global_errors(text, line, col, substring):
    check(text, line, col, substring)


@pytest.mark.parametrize("text, line, col, substring", [
    ("END_VAR\n", 1, 1, "END_VAR without VAR"),
    ("VAR\n  Start I0.0;\nEND_VAR\n", 2, 9, "expected `AT`"),
    ("VAR\n  Start AT 5;\nEND_VAR\n", 2, 12, "expected an address"),
    ("LD \"Start\n", 1, 4, "unterminated"),
    ("LD I0\n", 1, 4, "malformed address"),
    ("LD I\n", 1, 4, "incomplete address"),
    ("L MW0.1\n", 1, 3, "malformed address"),
    ("L T#5s1m\n", 1, 3, "malformed duration"),
    ("L T#5d\n", 1, 3, "malformed duration"),
    ("L 2#101\n", 1, 3, "malformed constant"),
    ("L 12ab\n", 1, 3, "malformed constant"),
    ("LD I0.0\nBIT:\nLD I0.1\n", 2, 1, "outside any section"),
])
def test_other_malformed_input(text, line, col, substring):
    check(text, line, col, substring)


def test_dialect_features_that_are_not_errors():
    text = (
        "// header comment\n"
        "VAR\n"
        "  Start AT I0.0; Stop AT I 0.1;   // several on a line\n"
        "  Timer1 AT T1\n"                      # end of line ends a declaration
        "END_VAR\n"
        "top: again: LD \"start\"  ; body comment with ; and \" and //\n"
        "  a ( \n"
        "  ldn STOP\n"
        "  jc inside\n"                         # jumps into/out of parentheses: fine
        "  )\n"
        "inside: x( \n"
        "  LD Timer1\n"
        "  )\n"
        "  = q 0.0\n"
        "  END\n"
        "  NOP\n"                               # still part of the program
        "  JU TOP\n"
        "tail:\n"                               # marks the appended END
    )
    program = parse("t.il", text)
    mnemonics = [i.mnemonic for i in program.instrs]
    assert mnemonics == ["LD", "A(", "LDN", "JC", ")", "X(", "LD", ")", "=", "END",
                         "NOP", "JU", "END"]
    assert program.labels == {"TOP": 0, "AGAIN": 0, "INSIDE": 5, "TAIL": 12}
    assert program.instrs[0].labels == ["top", "again"]
    assert program.instrs[0].operand.address() == "I0.0"
    assert program.instrs[0].operand.text == '"start"'
    assert program.instrs[2].operand.address() == "I0.1"
    assert program.instrs[6].operand.address() == "T1"
    assert program.instrs[8].operand.text == "q 0.0"
    assert (program.instrs[1].line, program.instrs[1].col) == (7, 3)
    assert program.instrs[-1].line == 19 and program.instrs[-1].source == ""
    assert set(program.symbols) == {"START", "STOP", "TIMER1"}


def test_byte_instructions_parse_with_canonical_mnemonics():
    text = ("VAR Speed AT IW0; Cnt AT C2; END_VAR\n"
            "L Speed\nL 16#00FF\nL T#1h2m3s4ms\nL T 3\nL Cnt\n+I\n-I\n*I\n/I\nMOD\nT MW0\n"
            "T QW1\n==I\n<>I\n>I\n<I\n>=I\n<=I\nA ==I\nO <>I\na >i\no <I\nA >=I\nO <=I\n"
            "SD T1\nSS T2\nSP T3\nSF T4\nR T4\nCU C1\nCD Cnt\nS C1\nR C1\n"
            "READ FBY0\nWRITE FBI3\n= FBY1\nLD FBI0\n")
    program = parse("t.il", text)
    got = [(i.mnemonic, i.operand.address() if i.operand else None)
           for i in program.instrs]
    assert got == [
        ("L", "IW0"), ("L", "255"), ("L", "3723004"), ("L", "T3"), ("L", "C2"),
        ("+I", None), ("-I", None), ("*I", None), ("/I", None), ("MOD", None),
        ("T", "MW0"), ("T", "QW1"), ("==I", None), ("<>I", None), (">I", None),
        ("<I", None), (">=I", None), ("<=I", None), ("A ==I", None), ("O <>I", None),
        ("A >I", None), ("O <I", None), ("A >=I", None), ("O <=I", None),
        ("SD", "T1"), ("SS", "T2"), ("SP", "T3"), ("SF", "T4"), ("R", "T4"),
        ("CU", "C1"), ("CD", "C2"), ("S", "C1"), ("R", "C1"), ("READ", "FBY0"),
        ("WRITE", "FBI3"), ("=", "FBY1"), ("LD", "FBI0"), ("END", None)]
    assert program.instrs[2].operand.area == "TIME"
    assert program.instrs[1].operand.area == "INT"


def test_empty_program_is_one_end():
    program = parse("t.il", b"")
    assert [(i.mnemonic, i.line, i.col) for i in program.instrs] == [("END", 1, 1)]
    assert [i.mnemonic for i in parse("t.il", "// nothing\n\n").instrs] == ["END"]


# ---------------------------------------------------------------------------------------
# Fuzz: any input gives a Program or a SourceError, never anything else
# ---------------------------------------------------------------------------------------

ALPHABET = [
    "LD", "LDN", "A", "AN", "O", "ON", "X", "XN", "A(", "AN(", "O(", "X(", "(", ")",
    "NOT", "SET", "CLR", "=", "S", "R", "FP", "FN", "JU", "JC", "JCN", "NOP", "END",
    "REFRESH", "L", "T", "+I", "-I", "*I", "/I", "MOD", "==I", "<>I", ">=I", "SD", "SF",
    "CU", "CD", "READ", "WRITE", "I0.0", "I 15.7", "I16.0", "PI0.1", "IR", "IF1.1",
    "Q0.0", "PQ", "M255.7", "M", "T1", "T", "C63", "C", "FBI0", "FBY3", "FBY", "IW0",
    "QW15", "MW", "MW255", "0.0", "7", "-7", "32768", "16#FFFF", "16#", "T#1m30s",
    "T#", "T#99999999h", "VAR", "END_VAR", "VAR_GLOBAL", "AT", "Start", '"Start"',
    '"', "loop", "loop:", ":", ";", "//", "// c", "\n", "\n", "\n", "\r\n", "\t", " ",
    " ", " ", "BIT:", "x1", "9" * 5000, "I" + "9" * 5000 + ".0",
]


def random_input(rng: random.Random) -> bytes | str:
    kind = rng.random()
    if kind < 0.1:
        return bytes(rng.randrange(256) for _ in range(rng.randrange(40)))
    tokens = [rng.choice(ALPHABET) for _ in range(rng.randrange(60))]
    joiner = "" if kind < 0.3 else " "
    text = joiner.join(tokens)
    if kind > 0.9:
        pos = rng.randrange(len(text) + 1)
        text = text[:pos] + chr(rng.randrange(256)) + text[pos:]
    return text.encode("latin-1") if rng.random() < 0.5 else text


def assert_only_source_errors(data, config=DEFAULT):
    try:
        program = parse("fuzz.il", data, config)
    except SourceError as err:
        assert err.line >= 1 and err.col >= 1, repr(data)
        format_error(err)
        return
    assert isinstance(program, Program)
    assert program.instrs and program.instrs[-1].mnemonic == "END" or \
        any(i.mnemonic == "END" for i in program.instrs)
    try:
        words, _ = encode(program, config)
    except SourceError as err:
        assert "needs the" in err.message, err.message
        return
    assert len(words) == len(program.instrs)
    assert all(0 <= w < 2 ** 32 for w in words)


def test_fuzz_random_token_soup_and_bytes():
    rng = random.Random(20240611)
    small = Config(prog_words=8, nest_depth=2)
    for n in range(2000):
        assert_only_source_errors(random_input(rng), small if n % 5 == 0 else DEFAULT)


MNEMONICS = ["LD", "LDN", "A", "AN", "O", "ON", "X", "XN", "=", "S", "R", "FP", "FN",
             "A(", "O(", "XN(", ")", ")", "NOT", "SET", "CLR", "NOP", "END", "JU", "JC",
             "JCN", "L", "T", "+I", "A >=I", "SD", "CU", "READ", "WRITE"]
OPERANDS = ["I0.0", "Q1.7", "PQ0.0", "M3.3", "M3.3", "T1", "C2", "FBI0", "FBY1", "MW0",
            "QW0", "IW3", "5", "T#5s", "l1", "l2", "l3", "Sym", '"Sym"', ""]


def random_program(rng: random.Random) -> str:
    """Lines that mostly look right: labels, mnemonics, operands, a VAR block."""
    lines = ["VAR Sym AT M0.0; END_VAR"] if rng.random() < 0.7 else []
    for _ in range(rng.randrange(1, 25)):
        label = rng.choice(["", "", "", "l1: ", "l2: ", "l3: "])
        operand = rng.choice(OPERANDS)
        lines.append(f"{label}{rng.choice(MNEMONICS)} {operand}".rstrip())
    return "\n".join(lines)


def test_fuzz_plausible_programs():
    rng = random.Random(11)
    small = Config(prog_words=12, nest_depth=2)
    for n in range(1000):
        assert_only_source_errors(random_program(rng), small if n % 3 == 0 else DEFAULT)


GOOD = (b"VAR\r\n  Start AT I0.0; Stop AT I0.1; // c\r\nEND_VAR\r\nloop: LD \"Start\"\r\n"
        b"A(\r\nLD Stop\r\nO M1.0\r\n)\r\nJC loop\r\n= Q0.0 ; c\r\nL T#1m30s\r\nEND\r\n")


def test_fuzz_truncated_and_mutated_program():
    for end in range(len(GOOD) + 1):
        assert_only_source_errors(GOOD[:end])
    rng = random.Random(7)
    for _ in range(300):
        data = bytearray(GOOD)
        for _ in range(rng.randrange(1, 4)):
            data[rng.randrange(len(data))] = rng.randrange(32, 127)
        assert_only_source_errors(bytes(data))


def test_examples_in_the_repository_parse_or_fail_cleanly():
    root = os.path.join(os.path.dirname(__file__), "..", "examples")
    if not os.path.isdir(root):
        pytest.skip("no examples/")
    for name in sorted(os.listdir(root)):
        if name.endswith(".il"):
            with open(os.path.join(root, name), "rb") as f:
                assert_only_source_errors(f.read())


def test_constant_pool_overflow_is_program_too_large():
    """Review finding: constants beyond imm24 go to the byte processor's pool of
    DEF.firmware["pool_words"]; one more was written and dropped by the firmware."""
    from bitbyte.lang.definition import DEF
    n = DEF.firmware["pool_words"]
    text = "".join(f"L L#{20_000_000 + i}\nT MD0\n" for i in range(n))
    encode(parse("t.il", text + "L L#20000000\n"))     # a full pool, one used twice
    with pytest.raises(SourceError) as info:
        encode(parse("t.il", text + "L L#30000000\n"))
    err = info.value
    assert (err.line, err.col) == (2 * n + 1, 1) and "program too large" in err.message
