"""docs/s7.md's instruction reference (issue 19): every instruction of Siemens' STL
manual for S7-300/400, supported or rejected as `unsupported:` at its line.

The table in docs/s7.md ("Instruction reference: S7-300/400 STL") is the only list:
each row's German and English statement is put into a small OB 1 (with the lines
around it that the instruction needs, chosen by its English mnemonic) and assembled
with `--mnemonics de` / `en`.  A supported row must assemble; an unsupported one must
fail with `FILE:LINE:COL: unsupported: …` at the statement's own line, naming the
instruction (a `quoted` part of the message starts with its mnemonic or holds its
operand), and never with a traceback.  Each row's German and English mnemonic must
be one instruction in awlsim's tables.
"""
from __future__ import annotations

import contextlib
import io
import re
import shutil
from dataclasses import dataclass
from pathlib import Path

from bitbyte import cli

DOC = Path(__file__).resolve().parent.parent / "docs" / "s7.md"
SECTION = "## Instruction reference: S7-300/400 STL"

# The instructions of the manual's chapters by their English mnemonic (the names
# only): the table must have a row for each.
MANUAL = {
    "bit logic": "A AN O ON X XN A( AN( O( ON( X( XN( ) = R S NOT SET CLR SAVE FN FP",
    "comparison": "==I <>I >I <I >=I <=I ==D <>D >D <D >=D <=D ==R <>R >R <R >=R <=R",
    "conversion": "BTI ITB BTD ITD DTB DTR INVI INVD NEGI NEGD NEGR CAW CAD RND TRUNC "
                  "RND+ RND-",
    "counter": "FR L LC R S CU CD",
    "data block": "OPN CDB L",
    "logic control": "JU JL JC JCN JCB JNB JBI JNBI JO JOS JZ JN JP JM JPZ JMZ JUO LOOP",
    "integer math": "+I -I *I /I + +D -D *D /D MOD",
    "floating point": "+R -R *R /R ABS SQR SQRT EXP LN SIN COS TAN ASIN ACOS ATAN",
    "load/transfer": "L T LAR1 LAR2 TAR1 TAR2 CAR",
    "program control": "BE BEC BEU CALL CC UC MCR( )MCR MCRA MCRD",
    "shift/rotate": "SSI SSD SLW SRW SLD SRD RLD RRD RLDA RRDA",
    "timer": "FR L LC R SP SE SD SS SF",
    "word logic": "AW OW XOW AD OD XOD",
    "accumulator": "TAK PUSH POP ENT LEAVE INC DEC +AR1 +AR2 BLD NOP",
}
# operands the manual names as instructions of their own
MANUAL_OPERANDS = {"bit logic": "BR OV OS UO ==0 <>0 >0 <0 >=0 <=0",
                   "data block": "DBLG DBNO DILG DINO", "load/transfer": "STW"}


@dataclass
class Row:
    line: int           # in docs/s7.md
    de: str
    en: str
    chapter: str
    status: str
    note: str


def read_table(text: str) -> list[Row]:
    """The rows of the reference section of `text` (docs/s7.md)."""
    lines = text.splitlines()
    start = lines.index(SECTION)
    rows = []
    for n, line in enumerate(lines[start + 1:], start + 2):
        if line.startswith("## "):
            break
        if not line.startswith("| `"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        assert len(cells) == 5, f"docs/s7.md:{n}: {len(cells)} cells, not 5: {line}"
        de, en, chapter, status, note = cells
        rows.append(Row(n, de.strip("`"), en.strip("`"), chapter, status, note))
    return rows


def context(en: str, lang: str) -> tuple[list[str], list[str], str]:
    """(lines before, lines after, blocks after OB 1) for a statement whose English
    form is `en`; the lines are words of both languages, but for `{JU}`."""
    word = en.split()[0]
    before = ["O     M 0.0", "L     1", "L     2"]       # an RLO, ACCU1 = 2, ACCU2 = 1
    after = ["=     M 0.1"]
    blocks = ""
    if word in ("A(", "AN(", "O(", "ON(", "X(", "XN("):
        after = ["O     M 0.2", ")", "=     M 0.1"]
    elif word == ")":
        before = ["O     M 0.0", "O(", "O     M 0.2"]
    elif word == "O" and len(en.split()) == 1:
        after = ["O     M 0.2", "=     M 0.1"]
    elif word == "JL":
        after = ["{JU}   M2", "M1:   SET", "M2:   =     M 0.1"]
    elif word.startswith("J") or word == "LOOP":
        after = ["M1:   SET", "=     M 0.1"]
    elif word in ("CALL", "UC", "CC"):
        blocks = ("FUNCTION FC 1 : VOID\nBEGIN\nNETWORK\nTITLE =\nO     M 0.0\n"
                  "=     M 0.3\nEND_FUNCTION\n\nFUNCTION_BLOCK FB 1\nBEGIN\nNETWORK\n"
                  "TITLE =\nO     M 0.0\n=     M 0.4\nEND_FUNCTION_BLOCK\n\n"
                  "DATA_BLOCK DB 1\nFB 1\nBEGIN\nEND_DATA_BLOCK\n\n"
                  "FUNCTION FC 2 : INT\nBEGIN\nNETWORK\nTITLE =\nL     7\n"
                  "T     #RET_VAL\nEND_FUNCTION\n")
    if re.search(r"\bDB[XW] |\bDB\d+\.|^OPN DB", en):     # a global DB 1 to use
        if not re.search(r"\bDB\d+\.|^OPN", en):         # opened first (`DBW 0`)
            before = before + [{"de": "AUF", "en": "OPN"}[lang] + "   DB 1"]
        blocks = ("DATA_BLOCK DB 1\n STRUCT\n  " + ("x : BOOL" if "DBX" in en else
                                                    "w : INT") +
                  ";\n END_STRUCT;\nBEGIN\nEND_DATA_BLOCK\n")
    if en.split()[-1] in ("==0", "<>0", ">0", "<0", ">=0", "<=0", "UO", "OV", "OS") or \
            word in ("JZ", "JN", "JP", "JM", "JPZ", "JMZ", "JUO", "JO", "JOS"):
        before = before + ["+I"]          # status bits set right before (docs/s7.md)
    ju = {"de": "SPA", "en": "JU"}[lang]
    return before, [a.replace("{JU}", ju) for a in after], blocks


def program(statement: str, en: str, lang: str) -> tuple[str, int]:
    """An OB 1 with `statement` (and its context): (source, the statement's line)."""
    before, after, blocks = context(en, lang)
    head = ["ORGANIZATION_BLOCK OB 1", "TITLE = reference", "VERSION : 0.1", "",
            "BEGIN", "NETWORK", "TITLE ="] + before
    line = len(head) + 1
    body = head + [statement] + after + ["END_ORGANIZATION_BLOCK", ""]
    return "\n".join(body) + ("\n" + blocks if blocks else ""), line


def assemble(path: Path, lang: str, outdir: Path) -> tuple[int | str, str]:
    """`bitbyte asm` in-process: (exit status or 'traceback', stderr)."""
    err = io.StringIO()
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            code = cli.main(["asm", str(path), "--mnemonics", lang, "-o", str(outdir)])
    except Exception as e:          # noqa: BLE001 - a traceback is what is checked
        return "traceback", f"Traceback: {type(e).__name__}: {e}"
    return code, err.getvalue()


def check_row(row: Row, tmp: Path) -> list[str]:
    """What is wrong with one row against the front end ([] when nothing)."""
    problems = []
    if row.status not in ("supported", "unsupported"):
        return [f"docs/s7.md:{row.line}: status `{row.status}`"]
    for lang, statement in (("de", row.de), ("en", row.en)):
        source, line = program(statement, row.en, lang)
        path = tmp / f"ref_{row.line}_{lang}.awl"
        path.write_text(source)
        code, err = assemble(path, lang, tmp)
        where = f"docs/s7.md:{row.line}: `{statement}` ({lang}, {row.status})"
        if code == "traceback" or "Traceback" in err:
            problems.append(f"{where}: {err}")
        elif row.status == "supported":
            if code != 0:
                problems.append(f"{where}: exit {code}: {err.strip()}")
        else:
            first = err.splitlines()[0] if err else ""
            m = re.match(rf"{re.escape(str(path))}:(\d+):(\d+): unsupported: (.*)", first)
            words = [w.upper() for w in statement.split()]
            if code == 0 or not m:
                problems.append(f"{where}: exit {code}: {first or 'no message'}")
            elif int(m.group(1)) != line:
                problems.append(f"{where}: message at line {m.group(1)}, the "
                                f"statement is at {line}: {first}")
            elif not names_it(m.group(3), words):
                problems.append(f"{where}: the message does not name it: {first}")
    return problems


def names_it(message: str, words: list[str]) -> bool:
    """Does an error message name the statement (upper-case `words`): a `quoted`
    part that starts with its mnemonic, or that holds its operand?  (A bare
    substring test would find a one-letter mnemonic in any message.)"""
    for quoted in re.findall(r"`([^`]+)`", message.upper()):
        if quoted.split()[0] == words[0] or len(words) > 1 and words[1] in quoted:
            return True
    return False


def check_table(rows: list[Row], tmp: Path) -> list[str]:
    problems = []
    for row in rows:
        problems += check_row(row, tmp)
    return problems


def test_every_row_of_the_reference_table(tmp_path):
    rows = read_table(DOC.read_text())
    assert len(rows) > 200
    problems = check_table(rows, tmp_path)
    assert not problems, "\n".join(problems)


def test_the_table_covers_the_manual():
    rows = read_table(DOC.read_text())
    for chapter, names in list(MANUAL.items()) + list(MANUAL_OPERANDS.items()):
        written = {w for r in rows if r.chapter == chapter
                   for w in r.en.replace(",", " ").split()[:2]}
        missing = [n for n in names.split() if n not in written]
        assert not missing, f"{chapter}: no row for {missing}"
    for r in rows:
        assert r.note, f"docs/s7.md:{r.line}: no note"
    assert {r.chapter for r in rows} == set(MANUAL)
    # and awlsim's (the oracle's) instruction set, both languages
    from awlsim.core.instructions.types import AwlInsnTypes
    for lang, names, col in (("de", AwlInsnTypes.name2type_german, "de"),
                             ("en", AwlInsnTypes.name2type_english, "en")):
        have = {getattr(r, col).split()[0] for r in rows}
        missing = sorted(n for n in names if not n.startswith("__") and n not in have)
        assert not missing, f"awlsim's {lang} instructions without a row: {missing}"
    stated = re.search(r"(\d+) rows: (\d+) supported, (\d+) unsupported",
                       DOC.read_text())
    counts = [len(rows)] + [sum(r.status == s for r in rows)
                            for s in ("supported", "unsupported")]
    assert stated and [int(g) for g in stated.groups()] == counts, counts
    # each row's German and English mnemonic are one instruction in awlsim's tables
    for r in rows:
        de = AwlInsnTypes.name2type_german.get(r.de.split()[0])
        en = AwlInsnTypes.name2type_english.get(r.en.split()[0])
        assert de is not None and de == en, \
            f"docs/s7.md:{r.line}: `{r.de}` / `{r.en}` are not one instruction in awlsim"
    pairs = [(r.de, r.en) for r in rows]
    assert len(pairs) == len(set(pairs)), "a row is there twice"


def not_yet_key(statement: str) -> str:
    """The word of an unsupported row's statement that the "Not yet" section
    names: the mnemonic, or for `U`/`L`/`T`/`CALL`… the operand's kind."""
    words = statement.replace(",", " ").split()
    if any("[" in w for w in words):
        return "indirect"
    if words[0] not in ("U", "A", "L", "T", "CALL", "UC", "CC", "FR", "LC") \
            or len(words) == 1:
        return words[0]
    op = words[1]
    if op.startswith("#") and "." in op:
        return "STRUCT"
    for start, key in (("2#", "2#"), ("P#", "P#"), ("T#", "T#"), ("'", "'..'"),
                       ("#", "multi-instances"),
                       ('"', "by symbol")):
        if op.startswith(start):
            return key
    return op


def test_not_yet_names_every_unsupported_row():
    text = DOC.read_text()
    not_yet = text[text.index("## Not yet"):]
    missing = [f"{r.de} ({not_yet_key(r.de)})" for r in read_table(text)
               if r.status == "unsupported" and not_yet_key(r.de) not in not_yet]
    assert not missing, f"docs/s7.md's Not yet does not name {missing}"


def test_a_wrong_row_is_reported(tmp_path):
    """Flip one supported and one unsupported row in a copy of docs/s7.md: the check
    reports both, at their rows (and passes the same rows unflipped)."""
    copy = tmp_path / "s7.md"
    shutil.copy(DOC, copy)
    text = copy.read_text()
    rows = read_table(text)
    sup = next(r for r in rows if r.en == "+I")
    uns = next(r for r in rows if r.en == "BTD")
    lines = text.splitlines()
    for row, old, new in ((sup, "| supported |", "| unsupported |"),
                          (uns, "| unsupported |", "| supported |")):
        assert old in lines[row.line - 1]
        lines[row.line - 1] = lines[row.line - 1].replace(old, new)
    copy.write_text("\n".join(lines) + "\n")
    flipped = {r.en: r for r in read_table(copy.read_text())}
    assert (flipped["+I"].status, flipped["BTD"].status) == ("unsupported", "supported")
    assert check_table([sup, uns], tmp_path) == []
    problems = check_table([flipped["+I"], flipped["BTD"]], tmp_path)
    assert any(f":{sup.line}: `+I` (de, unsupported): exit 0" in p for p in problems)
    assert any(f":{sup.line}: `+I` (en, unsupported): exit 0" in p for p in problems)
    assert any(f":{uns.line}: `BTD` (de, supported): exit 1" in p for p in problems)
    assert any(f":{uns.line}: `BTD` (en, supported): exit 1" in p for p in problems)


def test_names_it():
    """The message check needs the mnemonic or the operand in backticks."""
    assert names_it("`= E 0.0` writes the input image", ["=", "E", "0.0"])
    assert names_it("STRUCT/ARRAY member `#s.a`", ["U", "#S.A"])
    assert not names_it("operand `M 0.0` in a string", ["U", "E", "0.0"])
    assert not names_it("a message with U and = in it", ["U", "E"])
