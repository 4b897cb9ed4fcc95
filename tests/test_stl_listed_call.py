"""A block call written as STEP 7's STL editor shows it — `CALL FB 10, DB 10` and
then one `name :=actual` a line, without parentheses — as the public programs of
docs/s7.md ("Public programs by others", run by `make s7-public`, s7public/) write
it.  awlsim does not read that form: it runs a copy with the list put into
parentheses (`parenthesized`, a rewriting of its own, independent of the front
end's), so the comparison checks the front end's reading of the form."""
from __future__ import annotations

import re
from pathlib import Path

from awlsim_oracle import awlsim_scans, bitbyte_scans
from bitbyte import cli
from tracecmp import first_difference


def parenthesized(text: str) -> str:
    """The same source with every CALL whose parameters follow one a line without
    parentheses written as `CALL ... (p := a, ...);`, the form awlsim reads (comment
    lines and blank lines between the parameters dropped)."""
    lines, out, i = text.split("\n"), [], 0
    param = r"\s*\w+\s*:=[^(),;/]*;?\s*(//.*)?"
    while i < len(lines):
        line = lines[i]
        j, params = i + 1, []
        if re.match(r"\s*CALL\b", line, re.I) and "(" not in line:
            while j < len(lines):
                k = j
                while k < len(lines) and re.fullmatch(r"\s*(//.*)?", lines[k]):
                    k += 1              # comments, blank lines: inside if one follows
                if k == len(lines) or not re.fullmatch(param, lines[k]):
                    break
                params.append(lines[k].split("//")[0].strip().rstrip(";").strip())
                j = k + 1
        if params:
            out.append(line.rstrip().rstrip(";") + " (" + ", ".join(params) + ");")
            i = j
        else:
            out.append(line)
            i += 1
    return "\n".join(out)


def awlsim_copy(path: Path, tmp: Path) -> Path:
    copy = tmp / ("awlsim_" + path.name)
    copy.write_bytes(parenthesized(path.read_bytes().decode("cp1252")).encode("cp1252"))
    return copy


# Our own program in the same form: FB 2 with an instance DB and FC 3, each
# called with one `name :=actual` a line (comments and `;` after some of them, a
# symbol-free constant actual), then a statement that ends the list.
LISTED_CALL = """\
FUNCTION FC 3 : VOID
VAR_INPUT
  a : BOOL ;
  n : INT ;
END_VAR
VAR_OUTPUT
  q : BOOL ;
  w : INT ;
END_VAR
BEGIN
NETWORK
TITLE =
      U     #a
      =     #q
      L     #n
      L     2
      *I
      T     #w
END_FUNCTION

FUNCTION_BLOCK FB 2
VAR_INPUT
  en : BOOL ;
END_VAR
VAR_OUTPUT
  out : BOOL ;
  cnt : INT ;
END_VAR
VAR
  edge : BOOL ;
  c : INT ;
END_VAR
BEGIN
NETWORK
TITLE =
      U     #en
      FP    #edge
      SPBN  m001
      L     #c
      L     1
      +I
      T     #c
m001: L     #c
      T     #cnt
      U     #en
      UN    E      0.3
      =     #out
END_FUNCTION_BLOCK

DATA_BLOCK DB 2
 FB 2
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 3
 FB 2
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE =
      CALL  FB     2 , DB     2
       en                       :=E      0.0
       out                      :=A      0.0
       cnt                      :=MW    10
      CALL  FB     2 , DB     3
       en                       :=E      0.1    // the second belt
       out                      :=A      0.1;
       cnt                      :=MW    12
      NOP   0
NETWORK
TITLE =
      U     E      0.2
      CALL  FC     3
       a                        :=E      0.2
       n                        :=7
       q                        :=A      0.2
       w                        :=MW    14
      =     A      0.3
END_ORGANIZATION_BLOCK
"""


def test_listed_call_parameters_against_awlsim(tmp_path):
    path = tmp_path / "listed.awl"
    path.write_text(LISTED_CALL)
    inputs = [{0: k % 2 | (k // 3 % 2) << 1 | (k // 5 % 2) << 2 | (k // 7 % 2) << 3}
              for k in range(40)]
    words = ("MW10", "MW12", "MW14")
    expected = awlsim_scans(awlsim_copy(path, tmp_path), inputs, mnemonics="de",
                            words=words)
    got = bitbyte_scans(path, inputs, tmp_path, words=words)
    assert first_difference(expected, got) is None
    assert {row["MW10"] for row in expected} > {0, 1} and expected[-1]["MW14"] == 14
    assert expected[-1]["MW10"] != expected[-1]["MW12"]       # two instances apart


def test_a_parameter_line_without_a_call_is_an_error(tmp_path, capsys):
    path = tmp_path / "stray.awl"
    path.write_text("ORGANIZATION_BLOCK OB 1\nBEGIN\n      NOP   0\n"
                    "       en :=E 0.0\nEND_ORGANIZATION_BLOCK\n")
    assert cli.main(["asm", str(path)]) == 1
    assert "stray.awl:4:8:" in capsys.readouterr().err


def test_comment_and_blank_lines_inside_the_list(tmp_path):
    """Review finding: a comment-only or blank line inside the list ended it, and the
    parameters after it gave misleading errors (`extra operand`, `unknown mnemonic
    'en'`).  They are skipped; the run equals awlsim's on the parenthesized copy."""
    text = LISTED_CALL.replace(
        "       out                      :=A      0.0\n",
        "       // the outputs\n\n       out                      :=A      0.0\n")
    text = text.replace("       n                        :=7\n",
                        "       n                        :=7\n   // w: the product\n")
    path = tmp_path / "commented.awl"
    path.write_text(text)
    assert parenthesized(text) == parenthesized(LISTED_CALL)
    inputs = [{0: k % 2 | (k // 3 % 2) << 1 | (k // 5 % 2) << 2} for k in range(20)]
    words = ("MW10", "MW12", "MW14")
    expected = awlsim_scans(awlsim_copy(path, tmp_path), inputs, mnemonics="de",
                            words=words)
    got = bitbyte_scans(path, inputs, tmp_path, words=words)
    assert first_difference(expected, got) is None
    assert expected[-1]["MW14"] == 14


FC4 = ("FUNCTION FC 4 : VOID\nVAR_INPUT\n  a : BOOL ;\n  en : BOOL ;\nEND_VAR\nBEGIN\n"
       "NETWORK\nTITLE =\n      U #a\n      U #en\n      = A 0.0\nEND_FUNCTION\n")


def errors_of(tmp: Path, body: str, capsys) -> str:
    path = tmp / "bad.awl"
    path.write_text(FC4 + "ORGANIZATION_BLOCK OB 1\nBEGIN\nNETWORK\nTITLE =\n" + body
                    + "\nEND_ORGANIZATION_BLOCK\n")
    assert cli.main(["asm", str(path), "-o", str(tmp)]) == 1
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return err.split("bad.awl:", 1)[1].splitlines()[0]


def test_parameter_errors_name_the_parameters_line(tmp_path, capsys):
    """Review finding: an error in a parameter on a line of its own was reported at
    the CALL's line; it names the parameter's line and column now, in both forms."""
    body_line = FC4.count("\n") + 5          # the first line of the OB's body
    assert errors_of(tmp_path, "CALL FC 4\n a :=E 0.0\n xx :=E 0.1", capsys) == \
        f"{body_line + 2}:2: `xx` is not a parameter of FC 4"
    assert errors_of(tmp_path, "CALL FC 4\n a :=E 0.0\n en :=MW 2", capsys) == \
        f"{body_line + 2}:7: operand of the wrong kind: `en` is BOOL, not `MW 2`"
    assert errors_of(tmp_path, "CALL FC 4 (a := E 0.0,\n   xx := E 0.1)", capsys) == \
        f"{body_line + 1}:4: `xx` is not a parameter of FC 4"
    err = errors_of(tmp_path, "CALL FC 4 (a := E 0.0,\n   en = E 0.1)", capsys)
    assert err.startswith(f"{body_line + 1}:4: malformed parameter `en = E 0.1`")


def test_a_parameter_line_outside_a_list(tmp_path, capsys):
    """Review finding: `a :=E 0.0` after a statement that is no CALL gave `unknown
    mnemonic`; it says what it is now."""
    body_line = FC4.count("\n") + 5
    assert errors_of(tmp_path, "U E 0.0\n a :=E 0.0", capsys) == (
        f"{body_line + 1}:2: parameter line outside a CALL's list (`a :=E 0.0`: such "
        "lines follow a `CALL` without parentheses, with only comments or blank lines "
        "between)")


def test_fb_parameter_errors_name_the_parameters_line(tmp_path, capsys):
    """The same for an FB's parameters, whose copies are checked after the call is
    read: an input bit as an output's target, a marker in the block-local region."""
    fb = ("FUNCTION_BLOCK FB 9\nVAR_INPUT\n  a : BOOL ;\nEND_VAR\nVAR_OUTPUT\n"
          "  q : BOOL ;\nEND_VAR\nBEGIN\nNETWORK\nTITLE =\n      U #a\n      = #q\n"
          "END_FUNCTION_BLOCK\nDATA_BLOCK DB 9\n  FB 9\nBEGIN\nEND_DATA_BLOCK\n")
    for actual, message in (("E 0.1", "unsupported: `= E 0.1` writes the input image"),
                            ("M 200.0", "unsupported: `M 200.0` is in M 128 .. M 223")):
        path = tmp_path / "fb.awl"
        path.write_text(fb + "ORGANIZATION_BLOCK OB 1\nBEGIN\nNETWORK\nTITLE =\n"
                        "      CALL FB 9, DB 9\n        a :=E 0.0\n"
                        f"        q :={actual}\nEND_ORGANIZATION_BLOCK\n")
        assert cli.main(["asm", str(path), "-o", str(tmp_path)]) == 1
        line = fb.count("\n") + 7
        assert capsys.readouterr().err.startswith(f"{path}:{line}:13: {message}")
