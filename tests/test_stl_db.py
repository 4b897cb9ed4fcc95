"""Global data blocks (issue 19; docs/s7.md "Global data blocks"): `DATA_BLOCK DB n`
with a STRUCT of BOOL/INT/WORD fields and initial values, read and written as
`DB1.DBX 0.0`, `DB1.DBW 2`, `DB1.field` and, after `AUF`/`OPN DB n`, `DBX`/`DBW`.
Checked against awlsim scan for scan (the DBs' effects watched through outputs and
marker words), on the reference interpreter and on the Verilator harness in serial
and parallel mode; the comparison is shown to catch initial values that are ignored
and a layout with the wrong bit order."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from asmcheck import assert_refused
from awlsim_oracle import awlsim_scans, bitbyte_scans
from stlgen import symbol_table
from tracecmp import first_difference

from bitbyte import cli
from bitbyte.lang import stl
from bitbyte.lang.errors import SourceError
from bitbyte.lang.parser import parse_file

DBS = """DATA_BLOCK DB 1
TITLE =
  STRUCT
    run : BOOL;
    seen : BOOL := TRUE;
    edge : BOOL;
    count : INT := 5;
    limit : INT := 3;
    mask : WORD := W#16#00F0;
  END_STRUCT;
BEGIN
  limit := 4;
END_DATA_BLOCK

DATA_BLOCK DB 2
  STRUCT
    a : BOOL;
    b : BOOL;
    n : INT;
    m : INT := -7;
  END_STRUCT;
BEGIN
  a := TRUE;
END_DATA_BLOCK

FUNCTION FC 1 : VOID
BEGIN
NETWORK
TITLE =
      L     DBW 2
      + 1
      T     DBW 2
      U     DBX 0.0
      =     DBX 0.1
END_FUNCTION

"""

# OB 100 goes on from the DBs' initial values (S7 loads them before the startup)
STARTUP_DE = """ORGANIZATION_BLOCK OB 100
BEGIN
NETWORK
TITLE =
      L     DB1.count
      + 10
      T     DB1.count
      U     DB2.a
      =     A 1.0
END_ORGANIZATION_BLOCK

"""

OB1_DE = """ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE =
      U     E 0.0
      FP    DB1.DBX 0.2
      =     M 0.0
      U     M 0.0
      S     DB1.DBX 0.0
      U     E 0.1
      R     DB1.run
      U     DB1.DBX 0.0
      =     A 0.0
      U     DB1.seen
      =     A 0.1
NETWORK
TITLE =
      AUF   DB 1
      U     M 0.0
      SPBN  M1
      L     DBW 2
      + 1
      T     DBW 2
M1:   L     DBW 2
      T     MW 10
      L     DB1.limit
      T     MW 12
      L     DB1.count
      L     DB1.limit
      >I
      =     A 0.2
      L     DB1.DBW 6
      T     MW 14
      L     EW 2
      T     DB1.DBW 6
NETWORK
TITLE =
      AUF   DB 2
      U     DBX 0.0
      =     A 0.3
      U     E 0.2
      SPBN  M2
      CALL  FC 1
M2:   L     DB2.DBW 2
      T     MW 16
      L     DB2.m
      T     MW 18
      U     DB2.b
      =     A 0.4
      U     E 0.3
      =     DB2.DBX 0.0
END_ORGANIZATION_BLOCK
"""

EN = {"U": "A", "E": "I", "A": "Q", "AUF": "OPN", "SPBN": "JCN", "EW": "IW"}
WORDS = ("MW10", "MW12", "MW14", "MW16", "MW18")


def english(text: str) -> str:
    """The program with English mnemonics and areas (statement lines only)."""
    out = []
    for line in text.split("\n"):
        m = re.fullmatch(r"((?:\w+:)?\s+)(\S+)(\s+)(\S+)(.*)", line)
        if m and m.group(2) in EN | {"L": "", "T": "", "=": "", "S": "", "R": ""}:
            line = (m.group(1) + EN.get(m.group(2), m.group(2)) + m.group(3)
                    + EN.get(m.group(4), m.group(4)) + m.group(5))
        out.append(line)
    return "\n".join(out)


def inputs(scans: int = 16) -> list[dict[int, int]]:
    rows = []
    for k in range(scans):
        image = (1 if k % 3 == 1 else 0) | (2 if k in (7, 8) else 0) \
            | (4 if k % 4 in (1, 2) else 0) | (8 if k in (3, 4, 5, 11) else 0)
        rows.append({0: image, 2: (k * 37) & 0xFF, 3: k})
    return rows


def source(tmp: Path, lang: str, startup: bool = True, name: str = "db") -> Path:
    text = DBS + (STARTUP_DE if startup else "") + OB1_DE
    path = tmp / f"{name}_{lang}.awl"
    path.write_text(text if lang == "de" else english(text))
    return path


def compare(path: Path, lang: str, tmp: Path, **kw):
    stimulus = inputs()
    expected = awlsim_scans(path, stimulus, mnemonics=lang, words=WORDS)
    got = bitbyte_scans(path, stimulus, tmp, words=WORDS, in_words=(2,), **kw)
    return expected, got, first_difference(expected, got)


def ob1(body: str) -> str:
    return "ORGANIZATION_BLOCK OB 1\nBEGIN\nNETWORK\nTITLE =\n" + body + \
        "\nEND_ORGANIZATION_BLOCK\n"


def written(tmp: Path, name: str, text: str, lang: str = "de",
            symbols: list | None = None) -> tuple[Path, Path | None]:
    """The program (German `text`, in `lang`) and its symbol table, if any."""
    path = tmp / f"{name}_{lang}.awl"
    path.write_text(text if lang == "de" else english(text))
    asc = None
    if symbols:
        asc = tmp / "sym.asc"
        asc.write_text(symbol_table(symbols, "asc"))
    return path, asc


def as_awlsim(path: Path, tmp: Path, stimulus: list, words: tuple, lang: str = "de",
              symbols: Path | None = None) -> list[dict]:
    """awlsim's rows, after checking that bitbyte's equal them."""
    expected = awlsim_scans(path, stimulus, mnemonics=lang, words=words, symbols=symbols)
    got = bitbyte_scans(path, stimulus, tmp, words=words, symbols=symbols)
    assert first_difference(expected, got) is None
    return expected


def test_english_translation():
    text = english(DBS + STARTUP_DE + OB1_DE)
    for statement in ("OPN   DB 1", "JCN  M1", "A     DB1.seen", "L     IW 2",
                      "=     Q 0.4", "A     I 0.3"):
        assert statement in text, statement
    assert not re.search(r"\b(U|E|AUF|SPBN|EW)\b", text.split("ORGANIZATION")[1])


@pytest.mark.parametrize("startup", [True, False])
@pytest.mark.parametrize("lang", ["de", "en"])
def test_global_dbs_against_awlsim(tmp_path, lang, startup):
    """Bits and words of two global DBs, fully qualified, by field name and through
    the open DB (also in an FC, which sees its caller's), written by `=`, `S`, `R`,
    `FP`, `T`; initial values from the declaration and from BEGIN; with and without
    an OB 100 that goes on from them."""
    expected, got, diff = compare(source(tmp_path, lang, startup), lang, tmp_path)
    assert diff is None, diff
    first = expected[0]
    assert first["Q0.1"] == 1 and first["Q0.3"] == 1    # seen := TRUE, a := TRUE
    assert first["MW12"] == 4 and first["MW18"] == -7   # limit := 4, m : INT := -7
    assert first["MW14"] == 0xF0
    assert first["MW10"] == (15 if startup else 5)
    assert first["Q1.0"] == int(startup)
    assert len({row["MW10"] for row in expected}) > 3   # the count goes on
    assert len({row["MW16"] for row in expected}) > 3   # FC 1 counts in DB 2


def test_global_dbs_on_verilator_serial_and_parallel(tmp_path):
    path = source(tmp_path, "de")
    for mode in ("serial", "parallel"):
        _, _, diff = compare(path, "de", tmp_path, sim="verilator", mode=mode)
        assert diff is None, (mode, diff)


# S7's layout around a BYTE and a DINT (fields read by name and by address), an FC
# that opens another DB (the caller's stays open after the call, as awlsim restores
# it), a backward jump with the DB register the same on both paths, `FN` on a DBX.
LAYOUT_DE = """DATA_BLOCK DB 1
  STRUCT
    a : BOOL;
    c : BYTE := B#16#12;
    n : INT := 7;
    b : BOOL := TRUE;
    d : DINT;
    w : WORD := W#16#1234;
  END_STRUCT;
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 2
  STRUCT
    x : INT := 100;
  END_STRUCT;
BEGIN
END_DATA_BLOCK

FUNCTION FC 1 : VOID
BEGIN
NETWORK
TITLE =
      AUF   DB 2
      L     DBW 0
      + 1
      T     DBW 0
END_FUNCTION

ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE =
      AUF   DB 1
      CALL  FC 1
      L     DBW 2
      T     MW 10
      L     DB1.DBW 10
      T     MW 12
      U     DB1.DBX 4.0
      =     A 0.0
      L     DB2.x
      T     MW 14
      U     E 0.0
      FN    DB1.DBX 0.1
      =     A 0.1
      L     0
      T     MW 16
M1:   L     MW 16
      + 1
      T     MW 16
      L     DB1.n
      + 1
      T     DBW 2
      L     MW 16
      L     3
      <I
      SPB   M1
END_ORGANIZATION_BLOCK
"""


def test_layout_fc_and_loop_against_awlsim(tmp_path):
    path = tmp_path / "layout.awl"
    path.write_text(LAYOUT_DE)
    stimulus = [{0: k % 2} for k in range(8)]
    words = ("MW10", "MW12", "MW14", "MW16")
    expected = awlsim_scans(path, stimulus, mnemonics="de", words=words)
    got = bitbyte_scans(path, stimulus, tmp_path, words=words)
    assert first_difference(expected, got) is None
    assert [expected[0][k] for k in ("Q0.0", "MW10", "MW12", "MW14")] == [1, 7, 0x1234,
                                                                          101]
    assert expected[2]["MW10"] == 13 and expected[2]["Q0.1"] == 1


SYMBOLIC_DE = """DATA_BLOCK DB 1
  STRUCT
    a : BOOL;
    n : INT := 4;
  END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE =
      U     "Start"
      FP    "Data".a
      SPBN  M1
      L     "Data".n
      + 3
      T     "Data".n
M1:   L     "Data".n
      T     MW 10
END_ORGANIZATION_BLOCK
"""


@pytest.mark.parametrize("lang", ["de", "en"])
def test_db_by_symbol_against_awlsim(tmp_path, lang):
    """`"Data".n` with `Data` a DB in the symbol table (awlsim reads it so too)."""
    path, asc = written(tmp_path, "symbolic", SYMBOLIC_DE, lang, [
        ("Data", "DB 1", "DB 1"), ("Start", "E 0.0" if lang == "de" else "I 0.0",
                                   "BOOL")])
    expected = as_awlsim(path, tmp_path, [{0: int(k % 3 == 1)} for k in range(10)],
                         ("MW10",), lang, asc)
    assert [row["MW10"] for row in expected][:5] == [4, 7, 7, 7, 10]
    assert cli.main(["asm", str(path), "--symbols", str(asc), "-o", str(tmp_path)]) == 0
    assert '"Data".n' in (tmp_path / f"symbolic_{lang}.lst").read_text()
    asc.write_text(symbol_table([("Data", "MW 2", "INT"), ("Start", "E 0.0", "BOOL")],
                                "asc"))
    with pytest.raises(SourceError, match=r':14:13: `"Data".a`: the symbol `"Data"` is '
                       r'`MW 2` \(.*sym.asc:1\), not a DB'):
        parse_file(str(path), symbols=str(asc))


TWO_DBS = """DATA_BLOCK DB 1
  STRUCT
    a : BOOL;
    n : INT := 11;
  END_STRUCT;
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 2
  STRUCT
    a : BOOL := TRUE;
    n : INT := 22;
  END_STRUCT;
BEGIN
END_DATA_BLOCK

"""

# a read of `DB1.n` / `DB1.a` opens DB 1 (awlsim's __fetchDB, S7), in OB 1 and for an
# FC called after it
READ_OPENS_DE = TWO_DBS + """FUNCTION FC 1 : VOID
BEGIN
NETWORK
TITLE =
      L     DBW 2
      T     MW 14
END_FUNCTION

ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE =
      AUF   DB 2
      L     DB1.n
      T     MW 10
      L     DBW 2
      T     MW 12
      U     DBX 0.0
      =     A 0.0
      AUF   DB 2
      U     DB1.a
      =     A 0.1
      CALL  FC 1
      AUF   DB 2
      U     "Data".a
      =     A 0.2
      L     DBW 2
      T     MW 16
END_ORGANIZATION_BLOCK
"""

# a chain of 8 backward jumps to the label that reads DB 2 (more passes than the
# register's iteration once had)
BACKWARD_DE = TWO_DBS + """FUNCTION FC 1 : VOID
BEGIN
NETWORK
TITLE =
      SPA   L9
L1:   L     DBW 2
      T     MW 10
      BEA
L2:   SPA   L1
L3:   SPA   L2
L4:   SPA   L3
L5:   SPA   L4
L6:   SPA   L5
L7:   SPA   L6
L8:   SPA   L7
L9:   AUF   DB 2
      SPA   L8
END_FUNCTION

""" + ob1("      AUF   DB 1\n      CALL  FC 1")


@pytest.mark.parametrize("lang", ["de", "en"])
def test_a_read_of_a_db_field_opens_its_db(tmp_path, lang):
    path, asc = written(tmp_path, "opens", READ_OPENS_DE, lang, [("Data", "DB 1",
                                                                  "DB 1")])
    words = ("MW10", "MW12", "MW14", "MW16")
    expected = as_awlsim(path, tmp_path, [{0: 0}] * 3, words, lang, asc)
    assert [expected[0][k] for k in words] == [11, 11, 11, 11]
    assert expected[0]["Q0.0"] == expected[0]["Q0.1"] == expected[0]["Q0.2"] == 0


def test_the_register_settles_after_many_backward_jumps(tmp_path):
    path, _ = written(tmp_path, "backward", BACKWARD_DE)
    assert as_awlsim(path, tmp_path, [{0: 0}] * 3, ("MW10",))[0]["MW10"] == 22


# a write of the open DB's field first reached by a backward jump (no path to it yet
# in the register's first pass): the register stays known
WRITE_LATER_DE = TWO_DBS + ob1("""      AUF   DB 1
      SPA   L9
L1:   T     DB1.n
      SPA   L2
L9:   L     7
      SPA   L1
L2:   L     DBW 2
      T     MW 10""")


def test_a_write_reached_by_a_backward_jump_keeps_the_register(tmp_path):
    path, _ = written(tmp_path, "later", WRITE_LATER_DE)
    assert as_awlsim(path, tmp_path, [{0: 0}] * 2, ("MW10",))[0]["MW10"] == 7


def test_a_db_field_by_symbol_as_a_call_actual(tmp_path):
    path, asc = written(tmp_path, "actual", DB1 + FC_XW + ob1(
        'CALL FC 1 (x := "Data".x, w := MW 2)'), symbols=[("Data", "DB 1", "DB 1")])
    with pytest.raises(SourceError, match=r':28:17: unsupported: DB field `"Data".x` as '
                       r'a CALL actual'):
        parse_file(str(path), symbols=str(asc))


MEMBERS_DE = """DATA_BLOCK DB 1
  STRUCT
    a : BOOL;
    s : STRUCT
      x : BOOL;
    END_STRUCT;
    arr : ARRAY [1..4] OF INT;
  END_STRUCT;
BEGIN
  s.x := TRUE;
  arr[1] := 5;
  s . x := FALSE;
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE =
      U     E 0.0
      =     A 0.0
END_ORGANIZATION_BLOCK
"""


def test_members_set_after_begin_of_an_unused_db(tmp_path):
    """awlsim takes `s.x := TRUE;` and `arr[1] := 5;`; a DB the program does not use
    takes nothing, and its STRUCT/ARRAY fields are `unsupported:` once it is used."""
    path, _ = written(tmp_path, "members", MEMBERS_DE)
    as_awlsim(path, tmp_path, [{0: k % 2} for k in range(3)], ())
    path.write_text(MEMBERS_DE.replace("U     E 0.0", "U     DB1.a"))
    with pytest.raises(SourceError, match=r":4:5: unsupported: field `s` of type "
                       "STRUCT in DB 1"):
        parse_file(str(path))
    path.write_text(MEMBERS_DE.replace("U     E 0.0", "U     DB1.a").replace(
        "    s : STRUCT\n      x : BOOL;\n    END_STRUCT;\n    arr : ARRAY [1..4] OF "
        "INT;\n", "    s : INT;\n    arr : INT;\n"))
    with pytest.raises(SourceError, match=r":8:3: `s.x`: `s` is INT, not a STRUCT or "
                       "ARRAY"):
        parse_file(str(path))


@pytest.mark.parametrize("decl,message", [
    ("a : BOOL := 1", "malformed initial value `1` of the BOOL `a` (TRUE or FALSE)"),
    ("a : BOOL := W#16#1", "malformed initial value `W#16#1` of the BOOL `a`"),
    ("a : INT := W#16#FFFF", "malformed initial value `W#16#FFFF` of the INT `a` (a "
     "decimal INT constant"),
    ("a : INT := 40000", "initial value `40000` of the INT `a` out of range (INT is "
     "-32768..32767)"),
    ("a : INT := 1.5", "malformed initial value `1.5` of the INT `a`"),
    ("a : INT := TRUE", "malformed initial value `TRUE` of the INT `a`"),
    ("a : WORD := TRUE", "malformed initial value `TRUE` of the WORD `a`"),
])
def test_initial_values_awlsim_rejects(tmp_path, decl, message):
    """Initial values awlsim does not load are plain errors (at the value)."""
    path = tmp_path / "init.awl"
    path.write_text(f"DATA_BLOCK DB 1\n STRUCT\n  {decl};\n END_STRUCT;\nBEGIN\n"
                    "END_DATA_BLOCK\n\n" + ob1("U E 0.0\nSPB M1\nL DB1.a\nT MW 10\n"
                                               "M1: U E 0.0\n= A 0.0"))
    with pytest.raises(Exception, match="(?i)awlsim"):
        awlsim_scans(path, [{0: 0}], mnemonics="de", words=("MW10",))
    col = decl.index(":=") + 6
    with pytest.raises(SourceError, match=re.escape(f":3:{col}: {message}")):
        parse_file(str(path))


def test_a_db_symbol_with_an_address(tmp_path):
    """`"Data".DBW 0`: awlsim's parser rejects it, so does the front end."""
    path, asc = written(tmp_path, "symaddr", DB1 + ob1('L "Data".DBW 2\nT MW 10'),
                        symbols=[("Data", "DB 1", "DB 1")])
    with pytest.raises(Exception, match="(?i)awlsim|parser"):
        awlsim_scans(path, [{0: 0}], mnemonics="de", words=("MW10",), symbols=asc)
    with pytest.raises(SourceError, match=r':14:3: malformed operand `"Data".DBW`: a '
                       r'DB\'s symbol takes a field\'s name'):
        parse_file(str(path), symbols=str(asc))


def test_comparison_catches_ignored_initial_values(tmp_path, monkeypatch):
    for startup in (True, False):
        path = source(tmp_path, "de", startup)
        expected = awlsim_scans(path, inputs(), mnemonics="de", words=WORDS)
        with monkeypatch.context() as m:
            m.setattr(stl.StlFrontEnd, "init_data_blocks", lambda self: None)
            got = bitbyte_scans(path, inputs(), tmp_path, words=WORDS,
                                in_words=(2,))
        assert first_difference(expected, got)[0] == 0


def test_comparison_catches_a_wrong_bit_order(tmp_path, monkeypatch):
    """BOOL fields laid out from bit 7 down (a field's name and its DBX address then
    name different bits)."""
    path = source(tmp_path, "de")
    expected = awlsim_scans(path, inputs(), mnemonics="de", words=WORDS)
    layout = stl.StlFrontEnd.data_block

    def reversed_bits(self, stmt, number, col):
        fresh = number not in self.db_used
        db = layout(self, stmt, number, col)
        if fresh:
            for f in db["fields"]:
                if f.bit is not None:
                    f.bit = 7 - f.bit
        return db
    monkeypatch.setattr(stl.StlFrontEnd, "data_block", reversed_bits)
    got = bitbyte_scans(path, inputs(), tmp_path, words=WORDS, in_words=(2,))
    assert first_difference(expected, got) is not None


def test_listing_names_the_db_operands(tmp_path):
    path = source(tmp_path, "de")
    assert cli.main(["asm", str(path), "-o", str(tmp_path)]) == 0
    lst = (tmp_path / "db_de.lst").read_text()
    assert "DB1.DBX 0.2" in lst and "DB1.limit" in lst and "DB2.DBW 2" in lst
    assert "OB100:" in lst


def test_no_startup_part_when_every_initial_value_is_0(tmp_path):
    path = tmp_path / "zero.awl"
    path.write_text("DATA_BLOCK DB 1\n STRUCT\n  x : BOOL;\n  n : INT := 0;\n "
                    "END_STRUCT;\nBEGIN\n  x := FALSE;\nEND_DATA_BLOCK\n\n"
                    + ob1("U DB1.x\n= A 0.0\nL DB1.n\nT MW 10"))
    assert parse_file(str(path)).startup_scans == 0
    path.write_text(path.read_text().replace("x := FALSE", "x := TRUE"))
    assert parse_file(str(path)).startup_scans == 1


# --------------------------------------------------------------------------------------
# Errors

DB1 = ("DATA_BLOCK DB 1\n STRUCT\n  x : BOOL;\n  n : INT := 3;\n  f : REAL;\n "
       "END_STRUCT;\nBEGIN\nEND_DATA_BLOCK\n\n")             # 9 lines
BIG = ("DATA_BLOCK DB 1\n STRUCT\n" + "".join(f"  i{n} : INT;\n" for n in range(16))
       + " END_STRUCT;\nBEGIN\nEND_DATA_BLOCK\n\n")                 # 22 lines
FB = ("FUNCTION_BLOCK FB 1\nVAR\n  s : BOOL;\nEND_VAR\nBEGIN\nNETWORK\nTITLE =\n"
      "SET\nEND_FUNCTION_BLOCK\n\nDATA_BLOCK DB 2\nFB 1\nBEGIN\nEND_DATA_BLOCK\n\n")


FC_XW = ("FUNCTION FC 1 : VOID\nVAR_INPUT\n  x : BOOL;\n  w : INT;\nEND_VAR\nBEGIN\n"
         "NETWORK\nTITLE =\nU #x\n= A 0.0\nL #w\nT MW 10\nEND_FUNCTION\n\n")  # 14 lines


@pytest.mark.parametrize("text,where", [
    (DB1 + ob1("L DB3.DBW 0\nT MW 10"), "14:3: DB 3 is not in the source"),
    (DB1 + ob1("AUF DB 4"), "14:5: DB 4 is not in the source"),
    (DB1 + ob1("L DB1.DBW 8\nT MW 10"),
     "14:3: operand out of range: `DB1.DBW 8` (DB 1 has 8 bytes, 0..7)"),
    (DB1 + ob1("U DB1.DBX 0.8\n= A 0.0"), "14:3: operand out of range: `DB1.DBX 0.8`"),
    (DB1 + ob1("L DB1.cnt\nT MW 10"), "14:3: unknown field `cnt` in DB 1"),
    (DB1 + ob1("L DBW 2\nT MW 10"), "14:3: unsupported: DB register not known "
     "statically at `L DBW 2` (no DB is open at the start of OB 1"),
    (DB1 + "DATA_BLOCK DB 3\n STRUCT\n  y : INT;\n END_STRUCT;\nBEGIN\nEND_DATA_BLOCK\n\n"
     + ob1("U E 0.0\nSPB M1\nAUF DB 1\nSPA M2\nM1: AUF DB 3\nM2: L DBW 2\nT MW 10"),
     "26:7: unsupported: DB register not known statically at `L DBW 2` (DB 3 on one "
     "path, DB 1 on another"),
    (FB + DB1 + ob1("AUF DB 1\nCALL FB 1, DB 2\nL DBW 2\nT MW 10"),
     "31:3: unsupported: DB register not known statically at `L DBW 2` (after `CALL FB "
     "1, DB 2` the open DB is its instance DB"),
    (DB1 + DB1.replace("DB 1", "DB 3") + ob1("AUF DB 1\nL 5\nT DB3.n\nL DBW 2\n"
                                              "T MW 10"),
     "26:3: unsupported: DB register not known statically at `L DBW 2` (S7 opens DB 3 "
     "at `T DB3.n`, awlsim does not"),
    (FB + DB1 + ob1("U DB2.DBX 0.0\n= A 0.0"),
     "29:3: unsupported: DB 2 is the instance DB of FB 1"),
    (DB1 + ob1("L DB1.DBW 0\nT MW 10"), "14:3: unsupported: `DB1.DBW 0`: not an "
     "INT/WORD field of DB 1"),
    (DB1 + ob1("U DB1.DBX 2.0\n= A 0.0"), "14:3: unsupported: `DB1.DBX 2.0`: not a BOOL "
     "field of DB 1"),
    (DB1 + ob1("U DB1.DBX 5.0\n= A 0.0"), "14:3: unsupported: `DB1.DBX 5.0`: not a "
     "BOOL field of DB 1"),                 # an inner byte of the REAL, no padding
    (DB1.replace("f : REAL", "t : S5TIME") + ob1("U DB1.DBX 1.0\n= A 0.0\nU DB1.DBX "
                                                 "5.0\n= A 0.1"),
     "16:3: unsupported: `DB1.DBX 5.0`: not a BOOL field of DB 1"),
    (DB1 + FC_XW + ob1("CALL FC 1 (x := E 0.0,\n w := DB1.n)"),
     "29:7: unsupported: DB field `DB1.n` as a CALL actual"),
    (DB1 + FC_XW + ob1("AUF DB 1\nCALL FC 1 (x := DBX 0.0, w := MW 2)"),
     "29:17: unsupported: DB field `DBX 0.0` as a CALL actual"),
    (DB1 + FC_XW.replace("FUNCTION FC 1 : VOID", "FUNCTION_BLOCK FB 1").replace(
        "END_FUNCTION", "END_FUNCTION_BLOCK") + "DATA_BLOCK DB 2\nFB 1\nBEGIN\n"
     "END_DATA_BLOCK\n\n" + ob1("CALL FB 1, DB 2 (w := DB1.DBW 2)"),
     "33:23: unsupported: DB field `DB1.DBW 2` as a CALL actual"),
    (DB1 + ob1("AUF DB 1 2\nL DBW 2\nT MW 10"), "14:10: extra operand `2`"),
    (DB1 + ob1("AUF DB1 2\nL DBW 2\nT MW 10"), "14:9: extra operand `2`"),
    (DB1 + ob1("AUF DB\nL DBW 2\nT MW 10"), "14:5: missing operand: `AUF DB` needs "
     "the block's number (`AUF DB n`)"),
    (DB1 + ob1("AUF\nL DBW 2\nT MW 10"), "14:1: missing operand: `AUF` needs a DB "
     "(`AUF DB n`)"),
    (DB1 + ob1("AUF DB1.DBX 0.0\nU E 0.0\n= A 0.0"), "14:5: operand of the wrong "
     "kind: `AUF` opens a data block (`AUF DB n`), not `DB1.DBX 0.0`"),
    (DB1 + ob1("OPN MW 2\nA I 0.0\n= Q 0.0"), "14:5: operand of the wrong kind: `OPN` "
     "opens a data block (`OPN DB n`), not `MW 2`"),
    (DB1 + ob1("AUF DI 1\nU E 0.0\n= A 0.0"), "14:1: unsupported: `AUF DI 1` (the "
     "instance DB register"),
    ("DATA_BLOCK DB 1\n STRUCT\n END_STRUCT;\nBEGIN\nEND_DATA_BLOCK\n\n"
     + ob1("L DB1.DBW 0\nT MW 10"), "11:3: operand out of range: `DB1.DBW 0` (DB 1 has "
     "no fields, no bytes)"),
    (DB1 + ob1("L DB1.n\nT MW 10\nU E 0.0\n= M 255.7"), "17:3: unsupported: `M 255.7` "
     "uses M255.7, which the translation keeps for the started bit of the startup part "
     "that sets the global DBs' initial values"),
    (DB1 + ob1("L DB1.f\nT MW 10"), "14:3: unsupported: `DB1.f`: DBD"),
    (DB1 + ob1("U DB1.x\n= M 224.3"), "15:3: unsupported: `M 224.3` is in M 224 .. "
     "M 231, which this program's global DBs use"),
    (DB1.replace("BEGIN\n", "BEGIN\n  k := 1;\n") + ob1("SET"),
     "8:3: unknown field `k` in DB 1"),
    (BIG + ob1("L DB1.DBW 0\nT MW 10"), "27:3: unsupported: DB 1 (32 bytes) does not "
     "fit into the markers kept for global DBs (M 224 .. M 253"),
    (BIG.replace("  i15 : INT;\n", "") + ob1("L DB1.DBW 28\nT MW 10\nU E 0.0\n"
                                              + "".join(f"L S5T#1S\nSE T {n}\n"
                                                        for n in range(6))),
     "1:1: unsupported: the global DBs need M 224 .. M 253, but the translation keeps M "
     "253 and up"),
    (BIG.replace("  i15 : INT;\n", "").replace("  i14 : INT;\n", "").replace(
        "  i13 : INT;\n", "") + DB1.replace("DB 1", "DB 2").replace("  f : REAL;\n", "")
     + ob1("L DB1.DBW 24\nT MW 10\nL DB2.n\nT MW 12\nU E 0.0\n"
            + "".join(f"L S5T#1S\nSE T {n}\n" for n in range(6))),
     "20:1: unsupported: the global DBs need M 224 .. M 253, but the translation keeps "
     "M 253 and up"),                       # at DB 2, whose bytes reach M 253
])
def test_errors(tmp_path, capsys, text, where):
    assert_refused(tmp_path, capsys, text, where)
