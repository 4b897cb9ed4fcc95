"""TEMPs read before they are written (docs/s7.md, "Blocks and calls"; spec §9).

S7 leaves a block's TEMPs undefined at its start: awlsim 0.77 gives whatever the L
stack last held at that place (0 at first, then the last scan's value or another
block's TEMP), this CPU keeps the block's own marker from the last call.  So a TEMP
read where some path from its block's start has not written it is rejected with
`file:line:col: unsupported:`; programs that write first are compared with awlsim
scan for scan.  German and English.
"""
from __future__ import annotations

import re
import textwrap

import pytest

from awlsim_oracle import awlsim_scans, bitbyte_scans
from bitbyte.lang.errors import SourceError
from bitbyte.lang.stl import parse_stl
from tracecmp import first_difference

TO_EN = {"U": "A", "UN": "AN", "SPB": "JC", "SPBN": "JCN", "SPA": "JU", "SPL": "JL", "BEB": "BEC",
         "E": "I", "A": "Q", "EW": "IW"}


def english(text: str) -> str:
    """The German mnemonics and areas of these sources in English (whole tokens)."""
    out, body = [], False
    for line in text.split("\n"):
        body = (body or line.strip() == "BEGIN") and not line.startswith("END_")
        if body:
            line = re.sub(r"(?<![#\w])[A-Z]+\b", lambda m: TO_EN.get(m.group(), m.group()),
                          line)
        out.append(line)
    return "\n".join(out)


def program(ob1: str, blocks: str = "", temps: str = "t : BOOL ;\n  w : INT ;") -> str:
    return (textwrap.dedent(blocks) + "ORGANIZATION_BLOCK OB 1\nVAR_TEMP\n  " + temps
            + "\nEND_VAR\nBEGIN\nNETWORK\nTITLE =\n" + textwrap.dedent(ob1).strip("\n")
            + "\nEND_ORGANIZATION_BLOCK\n")


def fc(number: int, body: str) -> str:
    """FC n with an output `q` and a TEMP `f`."""
    return (f"FUNCTION FC {number} : VOID\nVAR_OUTPUT\n  q : BOOL ;\nEND_VAR\n"
            "VAR_TEMP\n  f : BOOL ;\nEND_VAR\nBEGIN\nNETWORK\nTITLE =\n" + body
            + "END_FUNCTION\n\n")


FC_TEMPS = fc(1, """\
      U     E 0.3
      SPB   M1
      U     E 0.4
      =     #q
M1:   U     #f
      =     A 1.1
""")

FB_IN = """\
FUNCTION_BLOCK FB 1
VAR_INPUT
  i : BOOL ;
END_VAR
VAR_OUTPUT
  o : BOOL ;
END_VAR
BEGIN
NETWORK
TITLE =
      U     #i
      =     #o
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
  FB 1
BEGIN
END_DATA_BLOCK

"""

JUMP_LIST = """
      L     EW 2
      SPL   M9
      SPA   M1
      SPA   M2
M9:   SPA   M3
M1:   U     E 0.0
      =     #t
      SPA   M4
M2:   SPA   M4
M3:   CLR
      =     #t
M4:   U     #t
      =     A 0.0
      U     E 0.1
      =     A 0.1
      """

# (OB 1's body, blocks before it, the text of the line the error is on, its column
# (the TEMP's `#`), the message's TEMP and block)
REJECTED = {
    "read_first": ("""
      U     #t
      =     A 0.0
      U     E 0.0
      =     #t
      """, "", "U     #t", "#t` of OB 1"),
    "word_read_first": ("""
      L     #w
      T     MW 10
      L     EW 2
      T     #w
      """, "", "L     #w", "#w` of OB 1"),
    "one_branch": ("""
      U     E 0.0
      SPB   M1
      U     E 0.1
      =     #t
M1:   U     #t
      =     A 0.0
      """, "", "M1:   U     #t", "#t` of OB 1"),
    "fp_unwritten": ("""
      U     E 0.0
      FP    #t
      =     A 0.0
      """, "", "FP    #t", "#t` of OB 1"),
    "set_is_no_write": ("""
      U     E 0.0
      S     #t
      U     #t
      =     A 0.0
      """, "", "U     #t", "#t` of OB 1"),
    "loop_write_later": ("""
      L     3
M1:   U     #t
      =     A 0.0
      U     E 0.0
      =     #t
      LOOP  M1
      """, "", "M1:   U     #t", "#t` of OB 1"),
    "fc_own_temp": ("""
      CALL  FC 1 (q := M 0.0)
      """, FC_TEMPS, "M1:   U     #f", "#f` of FC 1"),
    "fc_output_one_path": ("""
      CALL  FC 1 (q := #t)
      U     #t
      =     A 0.0
      """, FC_TEMPS.replace("M1:   U     #f", "M1:   U     E 0.5"),
        "U     #t", "#t` of OB 1"),
    "jump_list_entry": (JUMP_LIST, "", "M4:   U     #t", "#t` of OB 1"),
    "fc_output_after_beb": ("""
      CALL  FC 1 (q := #t)
      U     #t
      =     A 0.0
      """, fc(1, """\
      U     E 0.3
      BEB
      U     E 0.4
      =     #q
"""), "U     #t", "#t` of OB 1"),
    "fb_input_actual": ("""
      CALL  FB 1, DB 1 (i := #t, o := A 0.0)
      """, FB_IN, "CALL  FB 1", "#t` of OB 1"),
}


@pytest.mark.parametrize("lang", ["de", "en"])
@pytest.mark.parametrize("name", sorted(REJECTED))
def test_read_before_write_is_unsupported(name, lang):
    ob1, blocks, at, temp = REJECTED[name]
    text = program(ob1, blocks)
    if lang == "en":
        text, at = english(text), english("BEGIN\n" + at).split("\n")[1]
    lines = text.split("\n")
    line = next(i for i, t in enumerate(lines, 1) if t.strip().startswith(at.strip()))
    col = lines[line - 1].index("#", lines[line - 1].index(at.split()[-1][0])
                                if "#" not in at else 0) + 1
    with pytest.raises(SourceError) as err:
        parse_stl("t.awl", text, mnemonics=lang)
    first = str(err.value).split("\n")[0]
    assert first == (f"t.awl:{line}:{col}: unsupported: TEMP `{temp} may be read "
                     "before it is written (S7 leaves TEMPs undefined at the block's "
                     "start; this CPU keeps the value of the block's last run, 0 at first)"), first


def test_fc_output_bound_to_a_temp_names_the_parameter():
    text = program("""
      CALL  FC 2 (q := #t)
      """, """\
FUNCTION FC 2 : VOID
VAR_OUTPUT
  q : BOOL ;
END_VAR
BEGIN
NETWORK
TITLE =
      U     #q
      =     A 0.0
END_FUNCTION

""")
    with pytest.raises(SourceError) as err:
        parse_stl("t.awl", text)
    assert "TEMP `#t` of OB 1 (as `#q`) may be read" in str(err.value)
    assert str(err.value).startswith("t.awl:8:13:")


def test_start_information_of_ob1():
    text = program("""
      L     #OB1_PREV_CYCLE
      T     MW 10
      """, temps="OB1_PREV_CYCLE : INT ;")
    with pytest.raises(SourceError, match="OB 1's start information is not provided"):
        parse_stl("t.awl", text)


# written before they are read on every path: compared with awlsim
ACCEPTED = {
    "jump_list": JUMP_LIST.replace("M2:   SPA   M4", "M2:   SET\n      =     #t\n"
                                   "      SPA   M4"),
    "write_then_read": """
      U     E 0.0
      UN    E 0.1
      =     #t
      U     #t
      =     A 0.0
      U     #t
      S     A 0.1
      U     E 0.2
      R     A 0.1
      """,
    "both_branches": """
      U     E 0.0
      SPBN  M1
      U     E 0.1
      =     #t
      SPA   M2
M1:   U     E 0.2
      =     #t
M2:   U     #t
      =     A 0.0
      UN    #t
      =     A 0.1
      """,
    "word_then_bit": """
      L     EW 2
      T     #w
      L     #w
      L     5
      >I
      =     #t
      U     #t
      =     A 0.0
      L     #w
      T     MW 10
      """,
    "set_after_write": """
      U     E 0.0
      =     #t
      U     E 0.1
      S     #t
      U     E 0.2
      FP    #t
      =     A 0.0
      U     #t
      =     A 0.1
      """,
    "loop_write_first": """
      L     3
M1:   T     MW 10
      U     E 0.0
      =     #t
      U     #t
      X     A 0.0
      =     A 0.0
      L     MW 10
      LOOP  M1
      """,
    "fc_output_and_fb_output": """
      CALL  FC 2 (q := #t)
      U     #t
      =     A 0.0
      CALL  FB 1, DB 1 (i := E 0.2, o := #t)
      U     #t
      =     A 0.1
      U     E 0.3
      SPB   M1
      CALL  FB 1, DB 1 (i := #t, o := A 0.2)
M1:   U     #t
      =     A 0.3
      """,
}
BLOCKS_OK = FB_IN + fc(2, """\
      U     E 0.0
      SPB   M1
      U     E 0.1
      =     #f
      SPA   M2
M1:   CLR
      =     #f
M2:   U     #f
      =     #q
""")


def inputs(scans: int = 16) -> list[dict[int, int]]:
    rows = []
    for k in range(scans):
        v = (k * 37 + 11) % 256
        rows.append({0: v ^ (k >> 1), 1: 0, 2: k % 3, 3: (k * 5) % 9})
    return rows


@pytest.mark.parametrize("lang", ["de", "en"])
@pytest.mark.parametrize("name", sorted(ACCEPTED))
def test_written_first_against_awlsim(tmp_path, name, lang):
    text = program(ACCEPTED[name], BLOCKS_OK if name.startswith("fc") else "")
    path = tmp_path / f"{name}.awl"
    path.write_text(text if lang == "de" else english(text))
    stim = inputs()
    expected = awlsim_scans(path, stim, mnemonics=lang, words=("MW10",))
    got = bitbyte_scans(path, stim, tmp_path, words=("MW10",), in_words=(2,))
    assert first_difference(expected, got) is None, (path.read_text(),
                                                     first_difference(expected, got))
    assert len({tuple(sorted(r.items())) for r in expected}) >= 2
