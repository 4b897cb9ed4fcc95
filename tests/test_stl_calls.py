"""S7 blocks and calls (`.awl`, spec §9, issue 19): FUNCTION FC n and FUNCTION_BLOCK
FB n with VAR_INPUT / VAR_OUTPUT / VAR_IN_OUT / VAR / VAR_TEMP, instance DBs, `CALL FC
n (...)`, `CALL FB n, DB m (...)`, UC and CC — inlined by the front end
(docs/s7.md, "Blocks and calls").  Every program is compared with awlsim, the
independent S7 simulator (tests/awlsim_oracle.py), scan for scan; the expected values
come from awlsim, never from the front end.  Deliberately wrong inlinings (parameters
swapped, one instance for two DBs, a CALL that keeps /FC) are shown to be caught.
"""
from __future__ import annotations

import os
import random
import re
import textwrap
from pathlib import Path

import pytest

from awlsim_oracle import (EVERY_RUN, SERIAL_REF, awlsim_scans, bitbyte_scans,
                           equal_or_rejected, run_name)
from bitbyte import cli
from bitbyte.lang import stl
from stlgen import IN_WORDS, random_inputs, random_program
from stlgen import WORDS as GEN_WORDS
from tracecmp import first_difference

WORDS = ("MW10", "MW12", "MW14")

# A function with bit and word parameters, a TEMP and the RLO it returns; two
# instances of a function block (edge memory and a count in the instance DB, an
# IN_OUT), nesting FB -> FC -> FC with `#name`s passed on, BEB/BEA in a callee,
# labels of the same name in two blocks, UC and CC.
BLOCKS = """
FUNCTION FC 1 : VOID
TITLE = bits and words
VERSION : 0.1
VAR_INPUT
  a : BOOL ;
  b : BOOL ;
  n : INT ;
END_VAR
VAR_OUTPUT
  q : BOOL ;
  w : INT ;
END_VAR
VAR_TEMP
  t : BOOL ;
END_VAR
BEGIN
NETWORK
TITLE =
      U     #a
      UN    #b
      =     #t
      U     #t
      O     E 1.0
      =     #q
      L     #n
      L     3
      +I
      T     #w
      U     E 0.7              // the RLO the caller gets back
END_FUNCTION

FUNCTION FC 2 : VOID
VAR_INPUT
  x : BOOL ;
END_VAR
VAR_IN_OUT
  io : BOOL ;
END_VAR
BEGIN
NETWORK
TITLE =
      U     #x
      SPB   M1
      U     E 1.1
      BEB                      // ends the block when E 1.1
      S     #io
      BEA
M1:   R     #io
      CALL  FC 3 (z := #io)
END_FUNCTION

FUNCTION FC 3 : VOID
VAR_OUTPUT
  z : BOOL ;
END_VAR
BEGIN
NETWORK
TITLE =
M1:   U     #z
      =     A 1.7
END_FUNCTION

FUNCTION_BLOCK FB 1
TITLE = counts rising edges
VAR_INPUT
  en : BOOL ;
  step : INT ;
END_VAR
VAR_OUTPUT
  cnt : INT ;
  on : BOOL ;
END_VAR
VAR_IN_OUT
  flip : BOOL ;
END_VAR
VAR
  edge : BOOL ;
  c : INT ;
  held : BOOL ;
END_VAR
VAR_TEMP
  tmp : BOOL ;
END_VAR
BEGIN
NETWORK
TITLE =
      U     #en
      FP    #edge
      =     #tmp
      U     #tmp
      SPBN  M1
      L     #c
      L     #step
      +I
      T     #c
      U     #flip
      NOT
      =     #flip
M1:   L     #c
      T     #cnt
      U     #en
      S     #held
      U     E 1.2
      R     #held
      U     #held
      =     #on
      CALL  FC 2 (x := #held, io := #flip)
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
  FB 1
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 2
TITLE = the second conveyor
  FB 1
BEGIN
  c := 0;
END_DATA_BLOCK

FUNCTION FC 4 : VOID
BEGIN
NETWORK
TITLE =
      =     A 1.5              // the RLO the caller left
      U     E 1.3
END_FUNCTION
"""

OB1 = {
    "fc": """
      CALL  FC 1 (a := E 0.0, b := E 0.1, n := 5,
                  q := A 0.0, w := MW 10)
      =     A 0.1
      U     E 0.2
      CALL  FC 1 (a := M 0.3, b := E 0.0, n := MW 10, q := M 0.3, w := MW 12)
      =     M 0.4
      """,
    "fb": """
      CALL  FB 1, DB 1 (en := E 0.2, step := 1, cnt := MW 12, on := A 0.2,
                        flip := M 0.0)
      U     E 0.4
      CALL  FB 1, DB 2 (en := E 0.3, step := -2, cnt := MW 14, flip := A 0.3)
      CALL  FB 1, DB 1 (en := E 0.5)
      """,
    "fc_nested": """
      U     E 0.0
      U     E 0.1
      CALL  FC 2 (x := E 0.2, io := M 0.1)
      =     A 0.4
      U     E 0.3
      =     M 0.2
      CALL  FC 2 (x := M 0.2, io := A 0.5)
M1:   U     M 0.1
      =     A 0.6
      """,
    "uc_cc": """
      U     E 0.0
      CC    FC 4
      =     A 0.0
      U     E 0.1
      UC    FC 4
      =     A 0.1
      U     E 0.2
      O
      U     E 0.3
      CALL  FC 4
      """,
    "ob_temp": """
      U     E 0.0
      =     #flag
      L     EW 2
      T     #count
      U     #flag
      =     A 0.0
      L     #count
      L     1
      +I
      T     MW 10
      """,
}


def source(name: str) -> str:
    temps = "VAR_TEMP\n  flag : BOOL ;\n  count : INT ;\n  info : BYTE ;\nEND_VAR\n"
    return (BLOCKS + "\nORGANIZATION_BLOCK OB 1\nTITLE = test\n" + temps + "BEGIN\n"
            "NETWORK\nTITLE =\n" + textwrap.dedent(OB1[name]).strip("\n")
            + "\nEND_ORGANIZATION_BLOCK\n")


TO_ENGLISH = [("E ", "I "), ("A 0.", "Q 0."), ("A 1.", "Q 1."), ("U ", "A "),
              ("UN ", "AN "), ("SPBN ", "JCN "), ("SPB ", "JC "), ("BEB", "BEC"),
              ("BEA", "BEU"), ("EW ", "IW "), ("UC ", "UC ")]


def english(text: str) -> str:
    out, body = [], False
    for line in text.split("\n"):
        code = line.split("//")[0]
        body = (body or line.strip() == "BEGIN") and not line.startswith("END_")
        if body and line.strip() and not line.strip().startswith(("NETWORK", "TITLE")):
            for de, en in TO_ENGLISH:
                code = code.replace(de, en).replace(de.strip() + "\t", en.strip() + "\t")
        out.append(code)
    return "\n".join(out)


def inputs(seed: int, scans: int = 40) -> list[dict[int, int]]:
    r = random.Random(seed)
    image = [r.randrange(256), r.randrange(256), 0, 7]
    rows = []
    for _ in range(scans):
        rows.append(dict(enumerate(image)))
        for _ in range(r.randrange(1, 4)):
            image[r.randrange(2)] ^= 1 << r.randrange(8)
        if r.random() < 0.2:
            image[3] = r.randrange(256)
    return rows


def compare(path: Path, lang: str, tmp: Path, seed: int = 1, **kw):
    stim = inputs(seed)
    expected = awlsim_scans(path, stim, mnemonics=lang, words=WORDS)
    got = bitbyte_scans(path, stim, tmp, words=WORDS, in_words=(2,), **kw)
    return expected, got, first_difference(expected, got)


@pytest.mark.parametrize("lang", ["de", "en"])
@pytest.mark.parametrize("name", sorted(OB1))
def test_calls_against_awlsim(tmp_path, name, lang):
    text = source(name)
    path = tmp_path / f"{name}.awl"
    path.write_text(text if lang == "de" else english(text))
    expected, _, diff = compare(path, lang, tmp_path)
    assert diff is None, (path.read_text(), diff)
    # the programs do something: outputs and markers change
    assert len({tuple(sorted(r.items())) for r in expected}) > 4


# Review finding: every call of the OB1 table is followed by `=`, so a block end that
# kept /FC (instead of S7's /FC = 0, OR = 0) went unnoticed; here `O`, `U`, `X`, `S`
# and a conditional jump follow calls whose blocks end in every state (an open `O`,
# after `X`/`NOT`).
STATUS_AFTER_CALL = """\
FUNCTION FC 4 : VOID
BEGIN
NETWORK
TITLE =
      U     E 1.0
      U     E 1.1
      O
      U     E 1.2
END_FUNCTION

FUNCTION FC 5 : VOID
BEGIN
NETWORK
TITLE =
      U     E 1.3
      O
END_FUNCTION

FUNCTION FC 6 : VOID
BEGIN
NETWORK
TITLE =
      O     E 1.4
      X     E 1.5
      NOT
END_FUNCTION

ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE =
      U     E 0.0
      CALL  FC 4
      O
      U     E 0.1
      =     A 0.0
      U     E 0.2
      CALL  FC 4
      X     E 0.3
      =     A 0.1
      CALL  FC 5
      =     A 0.2
      U     E 0.4
      O
      CALL  FC 6
      NOT
      =     A 0.3
      CALL  FC 6
      S     A 0.4
      U     E 0.5
      CALL  FC 5
      U     E 0.6
      =     A 0.5
      CALL  FC 4
      SPB   L1
      U     E 0.7
      =     A 0.6
L1:   =     A 0.7
END_ORGANIZATION_BLOCK
"""


def test_status_after_a_block_end_against_awlsim(tmp_path):
    path = tmp_path / "status_after_call.awl"
    path.write_text(STATUS_AFTER_CALL)
    expected, _, diff = compare(path, "de", tmp_path)
    assert diff is None, diff
    assert len({tuple(sorted(r.items())) for r in expected}) > 4


def test_fb_instances_count_apart(tmp_path):
    """Two instance DBs of FB 1 keep their counts apart (awlsim agrees, and so do
    the words: DB 1's count goes up by 1, DB 2's down by 2)."""
    path = tmp_path / "fb.awl"
    path.write_text(source("fb"))
    expected, got, diff = compare(path, "de", tmp_path)
    assert diff is None, diff
    assert max(r["MW12"] for r in got) > 0 and min(r["MW14"] for r in got) < 0


def test_calls_on_verilator_serial_and_parallel(tmp_path):
    for name in ("fb", "fc_nested"):
        path = tmp_path / f"{name}.awl"
        path.write_text(source(name))
        for mode in ("serial", "parallel"):
            _, _, diff = compare(path, "de", tmp_path, sim="verilator", mode=mode)
            assert diff is None, (name, mode, diff)


def run_cli(argv, capsys):
    code = cli.main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_run_with_calls(tmp_path, capsys):
    path = tmp_path / "fb.awl"
    path.write_text(source("fb"))
    code, out, err = run_cli(["run", str(path), "--scans", "3"], capsys)
    assert code == 0, err


FC9 = "FUNCTION FC 9 : VOID\nVAR_INPUT\n  a : BOOL ;\n  r : REAL ;\nEND_VAR\n" \
      "VAR_OUTPUT\n  q : BOOL ;\nEND_VAR\nBEGIN\nNETWORK\nTITLE =\n      U #a\n" \
      "      = #q\nEND_FUNCTION\n"
FC8 = "FUNCTION FC 8 : VOID\nBEGIN\nNETWORK\nTITLE =\n      CALL FC 7\nEND_FUNCTION\n" \
      "FUNCTION FC 7 : VOID\nBEGIN\nNETWORK\nTITLE =\n      CALL FC 8\nEND_FUNCTION\n"
FB9 = "FUNCTION_BLOCK FB 9\nVAR_INPUT\n  a : BOOL ;\nEND_VAR\nVAR\n  s : INT ;\n" \
      "END_VAR\nBEGIN\nNETWORK\nTITLE =\n      U #a\n      = A 0.0\n" \
      "END_FUNCTION_BLOCK\nDATA_BLOCK DB 9\n  FB 9\nBEGIN\nEND_DATA_BLOCK\n" \
      "DATA_BLOCK DB 8\n  FB 1\nBEGIN\nEND_DATA_BLOCK\n"


def ob(body: str, blocks: str = FC9) -> str:
    return blocks + ("ORGANIZATION_BLOCK OB 1\nBEGIN\nNETWORK\nTITLE =\n"
                     + textwrap.dedent(body).strip("\n") + "\nEND_ORGANIZATION_BLOCK\n")


FC1 = "FUNCTION FC 1 : VOID\nVAR_INPUT\n  a : BOOL ;\nEND_VAR\nBEGIN\nNETWORK\n" \
      "      U #a\n      = A 0.0\nEND_FUNCTION\n"

CALL_ERRORS = [
    # (source, the line the message points at (its first line with this text),
    #  column, message start)
    (ob("CALL FC 9 (a := E 0.0, q := A 0.0)"), "CALL", 1,
     "`CALL FC 9` without the parameter `r`"),
    (ob("CALL FC 9 (a := E 0.0, r := MD 0, q := A 0.0, x := E 0.1)"), "CALL", 29,
     "unsupported: parameter `r` of type REAL"),
    (ob("CALL FC 9 (a := E 0.0, b := E 0.1)"), "CALL", 24,
     "`b` is not a parameter of FC 9"),
    (ob("CALL FC 9 (a := MW 2, q := A 0.0)"), "CALL", 17, "operand of the wrong kind: "
     "`a` is BOOL"),
    (ob("CALL FC 1 (a := TRUE)", FC1), "CALL", 12, "unsupported: `a := TRUE`"),
    (ob("CALL FC 5"), "CALL", 1, "`CALL FC 5`: FC 5 is not in the source"),
    (ob("CALL FC 8", FC8), "CALL FC 8", 7, "unsupported: `CALL FC 8` is a recursive "
     "call (FC 8 -> FC 7 -> FC 8)"),
    (ob("CALL FB 9", FB9), "CALL FB", 1, "`CALL FB 9` needs an instance DB"),
    (ob("CALL FB 9, DB 8 (a := E 0.0)", FB9), "CALL FB", 1, "`CALL FB 9, DB 8`: DB 8 "
     "is not an instance DB of FB 9"),
    (ob("UC FC 9"), "UC", 1, "unsupported: `UC FC 9`: UC/CC pass no parameters"),
    (ob("UC FB 9", FB9), "UC", 1, "unsupported: `UC FB 9` (UC/CC of an FB"),
    (ob("U(\nU E 0.0\nCALL FB 9, DB 9\n)", FB9), "CALL FB", 1,
     "unsupported: `CALL` inside parentheses"),
    (ob("CALL FB 9, DB 9 (a := E 0.0)\nU M 130.0\n= A 0.1", FB9), "U M 130", 3,
     "unsupported: `M 130.0` is in M 128 .. M 223"),
    (ob("CALL FB 9, DB 9 (a := M 200.0)", FB9), "CALL FB", 23,
     "unsupported: `M 200.0` is in M 128 .. M 223"),
    (ob("U #nope\n= A 0.0"), "#nope", 3, "undeclared local `#nope`"),
    (ob("CALL \"Motor\""), "CALL", 6, "unsupported: `CALL \"Motor\"`"),
    ("FUNCTION_BLOCK FB 1\nVAR\n  s : INT := 5;\nEND_VAR\nBEGIN\nEND_FUNCTION_BLOCK\n"
     + ob("SET"), ":= 5", 14, "unsupported: initial value `5`"),
    (FB9 + "DATA_BLOCK DB 7\n  FB 9\nBEGIN\n  s := 3;\nEND_DATA_BLOCK\n" + ob("SET"),
     "s := 3", 3, "unsupported: initial value `3` in DB 7"),
    ("FUNCTION FC 1 : VOID\nVAR\n  s : INT ;\nEND_VAR\nBEGIN\nEND_FUNCTION\n" + ob("SET"),
     "VAR", 1, "unsupported: VAR in FC 1"),
    (ob("CALL FC 1 (a := 1)", FC1), "CALL", 17, "operand of the wrong kind: `a` is BOOL"),
    ("FUNCTION FC 1 : VOID\nVAR_INPUT\n  a : INT ;\nEND_VAR\nBEGIN\nNETWORK\n"
     "      L 1\n      T #a\nEND_FUNCTION\n" + ob("CALL FC 1 (a := 7)"), "T #a", 9,
     "unsupported: `T` writes `#a`, which is bound to a constant"),
    ("FUNCTION FC 1 : VOID\nVAR_OUTPUT\n  a : INT ;\nEND_VAR\nBEGIN\nEND_FUNCTION\n"
     + ob("CALL FC 1 (a := 7)"), "CALL", 12, "a constant for the output parameter `a`"),
    ("FUNCTION FC 1 : VOID\nBEGIN\nEND_FUNCTION\nFUNCTION FC 1 : VOID\nBEGIN\n"
     "END_FUNCTION\n" + ob("SET"), "FUNCTION FC", 1, "duplicate block FC 1"),
    ("FUNCTION FC 1 : VOID\nBEGIN\nEND_FUNCTION\n", None, 0,
     "no ORGANIZATION_BLOCK OB 1"),
    # review findings (tracebacks before): an argument in the other language, a call
    # without a block; and a silent collision of a call's copy with a timer's scratch bit
    (ob("CALL FC 1 (a := I 0.0)", FC1), "U #a", 9,
     "mixed mnemonics: `#a = I 0.0` is English, but this source is German"),
    (ob("UC"), "UC", 1, "missing operand: `UC` needs a block"),
    (ob("U E 0.0\nL S5T#1S\nSE T 1\nU T 1\n= A 0.0\nCALL FB 9, DB 9 (a := M 255.7)", FB9),
     "CALL FB", 23, "unsupported: `M 255.7` uses M255.7, which the translation"),
    (ob("L DB1.DBW 2\nT MW 0"), "DB1", 3, "DB 1 is not in the source"),
    (ob("U M [MD 0]\n= A 0.0"), "[MD", 3, "unsupported: indirect addressing `M [MD 0]`"),
]


def test_a_line_of_only_a_semicolon(tmp_path, capsys):
    """Review finding: a line holding only `;` (awlsim runs it) raised an IndexError."""
    path = tmp_path / "semi.awl"
    path.write_text(ob("U E 0.0\n;\n= A 0.0"))
    code, out, err = run_cli(["run", str(path), "--scans", "1"], capsys)
    assert code == 0 and "Traceback" not in err, err


@pytest.mark.parametrize("text,at,col,message", CALL_ERRORS)
def test_call_errors(tmp_path, capsys, text, at, col, message):
    path = tmp_path / "bad.awl"
    path.write_text(text)
    code, out, err = run_cli(["asm", str(path), "-o", str(tmp_path)], capsys)
    assert code == 1, (out, err)
    if at is None:
        assert err.startswith(f"{path}: {message}"), err
    else:
        lines = text.split("\n")
        line = next(i for i, t in enumerate(lines, 1) if at in t)
        if message.startswith("duplicate"):
            line = [i for i, t in enumerate(lines, 1) if at in t][1]
        assert err.startswith(f"{path}:{line}:{col}: {message}"), err
    assert "Traceback" not in err


# --------------------------------------------------------------------------------------
# The comparison can fail: deliberately wrong inlinings are caught by awlsim
# --------------------------------------------------------------------------------------

def caught(tmp_path, names=("fc", "fb", "fc_nested", "uc_cc")) -> int:
    found = 0
    for name in names:
        path = tmp_path / f"{name}.awl"
        path.write_text(source(name))
        try:
            found += compare(path, "de", tmp_path)[2] is not None
        except AssertionError:
            found += 1
    return found


def test_oracle_catches_swapped_parameters(tmp_path, monkeypatch):
    """The inliner binding each FC/FB parameter to the actual of the one before
    of the same kind (a wrong parameter mapping) differs from awlsim."""
    original = stl.StlFrontEnd.inline

    def swapped(self, stmt, labels, scope, stack):
        params = stmt.extra.params
        decls = self.blocks[(stmt.extra.kind, stmt.extra.number)].decls
        kinds = [(decls[p[0].text.upper()].section, decls[p[0].text.upper()].type)
                 for p in params]
        if len(params) >= 2 and kinds[0] == kinds[1]:
            stmt.extra.params = [(params[0][0], params[1][1]), (params[1][0],
                                                                params[0][1])] + params[2:]
        try:
            return original(self, stmt, labels, scope, stack)
        finally:
            stmt.extra.params = params

    monkeypatch.setattr(stl.StlFrontEnd, "inline", swapped)
    assert caught(tmp_path, ("fc",)) == 1


def one_instance(monkeypatch) -> None:
    """Mutate the inliner: FB statics kept per FB, not per instance DB."""
    original = stl.StlFrontEnd.cell

    def shared(self, stmt, binding, col):
        if binding.cell and str(binding.cell[0]).startswith("DB "):
            binding = stl.Binding(decl=binding.decl, cell=("DB", binding.cell[1]))
        return original(self, stmt, binding, col)

    monkeypatch.setattr(stl.StlFrontEnd, "cell", shared)


def test_oracle_catches_one_instance_for_two_dbs(tmp_path, monkeypatch):
    """FB statics kept per FB instead of per instance DB differ from awlsim."""
    one_instance(monkeypatch)
    assert caught(tmp_path, ("fb",)) == 1


def test_oracle_catches_a_call_that_keeps_the_first_check(tmp_path, monkeypatch):
    """A CALL that leaves /FC as it was (the callee's first `U` combining with the
    caller's string instead of loading) differs from awlsim."""
    original = stl.StlFrontEnd.statement

    def keep(self, stmt, st, edges):
        ner = st.ner
        result = original(self, stmt, st, edges)
        if stmt.canon == "@CALL":
            st.ner = ner
        return result

    monkeypatch.setattr(stl.StlFrontEnd, "statement", keep)
    assert caught(tmp_path, ("fc_nested",)) == 1


# --------------------------------------------------------------------------------------
# Random programs with calls (tests/stlgen.py, calls=True)
# --------------------------------------------------------------------------------------

CALL_PROGRAMS = int(os.environ.get("BITBYTE_STL_CALL_PROGRAMS", "6"))
BASE_SEED = int(os.environ.get("BITBYTE_SEED", "0"))


def random_call_programs(tmp: Path, count: int, offset: int = 0,
                         base_seed: int | None = None, runs=SERIAL_REF
                         ) -> tuple[int, list[int], set[str]]:
    """(compared, rejected seeds, the call mnemonics seen in compared programs);
    asserts 0 mismatches against awlsim in every run of `runs` (awlsim_oracle:
    SERIAL_REF, the reference interpreter; EVERY_RUN, the Verilator harness in serial
    and parallel mode too, each parallel exchange).  Program i has the seed BITBYTE_SEED * 10000 + i."""
    compared, rejected, seen = 0, [], set()
    for index in range(offset, offset + count):
        seed = (BASE_SEED if base_seed is None else base_seed) * 10_000 + index
        text, lang = random_program(seed, calls=True)
        path = tmp / f"call{seed}.awl"
        path.write_text(text)
        if not equal_or_rejected(seed, path, lang, random_inputs(seed, 12), tmp,
                                 words=GEN_WORDS, in_words=IN_WORDS, runs=runs):
            rejected.append(seed)
            continue
        compared += 1
        seen |= {line.split()[0] for line in text.splitlines()
                 if line.startswith("\t") and line.split()[0] in ("CALL", "UC", "CC")}
        seen |= {"FB" for line in text.splitlines() if "CALL\tFB" in line}
    return compared, rejected, seen


def test_random_programs_with_calls_against_awlsim(tmp_path):
    """Random programs that call generated FCs and an FB with two instance DBs
    (bodies of random networks over `#name`s, strings before and assignments after
    the calls, UC/CC): 0 mismatches; rejections stay `unsupported:` and rare.
    BITBYTE_STL_CALL_PROGRAMS=<n> for a soak (docs/s7.md)."""
    compared, rejected, seen = random_call_programs(tmp_path, CALL_PROGRAMS)
    # (6 programs at about 15 % rejected: 5 or more in about one run of 2 500; the
    # soak holds the 25 % bound over 1 000)
    assert len(rejected) <= max(4, CALL_PROGRAMS * 0.25), rejected
    if CALL_PROGRAMS >= 50:
        assert {"CALL", "UC", "CC", "FB"} <= seen, seen
    print(f"{compared} random STL programs with calls equal awlsim's, "
          f"{len(rejected)} rejected as unsupported")


def test_random_call_programs_catch_one_instance_for_two_dbs(tmp_path, monkeypatch):
    """The random comparison fails when the inliner keeps FB statics per FB instead
    of per instance DB (the mutation of test_oracle_catches_one_instance_for_two_dbs)."""
    one_instance(monkeypatch)
    with pytest.raises(AssertionError, match="differs from awlsim"):
        random_call_programs(tmp_path, 40, base_seed=0)    # (seed 6 shows it)


def test_random_call_programs_on_verilator_parallel(tmp_path, monkeypatch):
    """The S7 soak's comparison (soak/test_stl_soak.py, awlsim_oracle.EVERY_RUN): a few
    random programs with calls equal awlsim's on the reference interpreter and on the
    Verilator harness in serial and in parallel mode (handshake and queue exchange).
    And it can fail: with the partitioning compiler inverting each condition it moves
    to the bit side (`LDN` / `AN` / `ON FBI k` for `LD` / `A` / `O FBI k`: the RLO
    fetched back from the byte side, a compare's result), a wrong partition that
    serial mode never sees, program 1 still equals awlsim's on the reference
    interpreter and the harness in serial mode, and differs on the harness in
    parallel mode with either exchange."""
    compared, _, _ = random_call_programs(tmp_path, 6, base_seed=0, runs=EVERY_RUN)
    assert compared >= 4
    from bitbyte.compiler import walk

    original = walk._Builder.to_bit

    def inverted(self, reason, bit_mnemonic="LD", plain=False):
        if not plain:
            bit_mnemonic = {"LD": "LDN", "A": "AN", "O": "ON", "X": "XN"}[bit_mnemonic]
        return original(self, reason, bit_mnemonic, plain)

    monkeypatch.setattr(walk._Builder, "to_bit", inverted)
    for parallel in EVERY_RUN[2:]:
        with pytest.raises(AssertionError, match=re.escape(
                f"differs from awlsim on {run_name(*parallel)}: ")):
            random_call_programs(tmp_path, 1, 1, base_seed=0,
                                 runs=EVERY_RUN[:2] + (parallel,))


def test_symbols_as_actual_parameters(tmp_path):
    """`CALL FC 1 (a := "Start", q := "Motor")` with a STEP 7 symbol table: equal to
    awlsim's scans (awlsim loads the same .asc table)."""
    from stlgen import symbol_table

    table = tmp_path / "symbols.asc"
    table.write_text(symbol_table([("Start", "E 0.0", "BOOL"), ("Stop", "E 0.1", "BOOL"),
                                   ("Motor", "A 0.0", "BOOL")], "asc"))
    path = tmp_path / "sym.awl"
    path.write_text(BLOCKS + "\nORGANIZATION_BLOCK OB 1\nBEGIN\nNETWORK\nTITLE =\n"
                    "      CALL  FC 1 (a := \"Start\", b := \"Stop\", n := 1,\n"
                    "                  q := \"Motor\", w := MW 10)\n"
                    "END_ORGANIZATION_BLOCK\n")
    stim = inputs(5)
    expected = awlsim_scans(path, stim, mnemonics="de", words=WORDS, symbols=table)
    got = bitbyte_scans(path, stim, tmp_path, words=WORDS, symbols=table)
    assert first_difference(expected, got) is None
    assert {row["Q0.0"] for row in expected} == {0, 1}


def test_random_call_programs_catch_a_jump_list_without_the_low_byte(tmp_path,
                                                                     monkeypatch):
    """The random programs' jump lists (SPL/JL on constants and words, 257 and -255
    among them) can catch a chain that compares all 16 bits of ACCU1 — rarely: 1 of
    the first 900 programs of seed 0 (program 236) show it, since the entries and
    the default often lead to the same effect; test_stl_jumplist.py's program is
    the strong check."""
    original = stl.StlFrontEnd.jump_list

    def sixteen_bits(self, stmt, st, edges):
        if st.acc[0] is not None:
            st.acc = (stl.Known(0), st.acc[1])
        return original(self, stmt, st, edges)

    monkeypatch.setattr(stl.StlFrontEnd, "jump_list", sixteen_bits)
    with pytest.raises(AssertionError, match="differs from awlsim"):
        random_call_programs(tmp_path, 1, offset=236, base_seed=0)


# --------------------------------------------------------------------------------------
# FC return values: RET_VAL, an implicit VAR_OUTPUT of the declared type
# --------------------------------------------------------------------------------------

RET_BLOCKS = """
FUNCTION FC 4 : INT
VAR_INPUT
  a : INT ;
END_VAR
BEGIN
NETWORK
TITLE =
      L     #a
      L     3
      +I
      T     #RET_VAL
END_FUNCTION

FUNCTION FC 5 : BOOL
BEGIN
NETWORK
TITLE =
      U     E 0.1
      UN    E 0.2
      =     #RET_VAL
END_FUNCTION

FUNCTION FC 6 : WORD
BEGIN
NETWORK
TITLE =
      L     W#16#00F0
      T     #RET_VAL
END_FUNCTION
"""


@pytest.mark.parametrize("lang", ["de", "en"])
def test_fc_return_value_against_awlsim(tmp_path, lang):
    """Review finding: `FUNCTION FC 4 : INT` had its type ignored and RET_VAL was
    neither a local nor a parameter.  Now RET_VAL is an output of that type."""
    text = ob("CALL FC 4 (a := EW 2, RET_VAL := MW 10)\n"
              "CALL FC 5 (RET_VAL := A 0.0)\n"
              "CALL FC 6 (RET_VAL := MW 14)\n"
              "CALL FC 4 (a := MW 10,\n           RET_VAL := MW 12)", RET_BLOCKS)
    path = tmp_path / "ret.awl"
    path.write_text(text if lang == "de" else english(text))
    expected, got, diff = compare(path, lang, tmp_path)
    assert diff is None, diff
    assert {r["MW12"] for r in expected} != {0}
    assert {r["Q0.0"] for r in expected} == {0, 1}


def test_fc_return_value_of_another_type_is_unsupported(tmp_path, capsys):
    path = tmp_path / "ret.awl"
    path.write_text(ob("SET", RET_BLOCKS.replace("FC 6 : WORD", "FC 6 : REAL")))
    code, _, err = run_cli(["asm", str(path), "-o", str(tmp_path)], capsys)
    line = next(i for i, t in enumerate(path.read_text().split("\n"), 1) if "REAL" in t)
    assert code == 1 and err.startswith(
        f"{path}:{line}:17: unsupported: FC with a return value of type REAL"), err
