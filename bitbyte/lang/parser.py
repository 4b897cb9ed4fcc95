"""Instruction-list source -> checked `Program` (spec §3).

The way through this module is one direction:

1. `check_bytes`: every byte must be printable ASCII, tab or newline (CR only right
   before LF).  This runs before anything else, so binary garbage gets this error and
   nothing stranger.
2. `lex_token`: a small hand-written lexer.  Tokens are WORD (a maximal run of
   characters that are not blank and not one of `( ) : ; "`), STRING (a quoted
   symbol), LPAREN, RPAREN, COLON, SEMI, EOL and EOF, each with its offset, line and
   column.  `//` comments vanish in the lexer.  `;` is always a SEMI token; the parser
   decides what it means (declaration end inside VAR..END_VAR, comment start in the
   program body), because only the parser knows where it is.
3. `Parser`: line-oriented statements (`label: label: MNEMONIC operand`), VAR blocks,
   operands, symbols, labels, parenthesis structure, sizes.  It stops at the first
   error and raises `SourceError` pointing at the token that is wrong.

Canonical mnemonics (Instr.mnemonic), all upper case:

* bit side: LD LDN A AN O ON X XN, A( AN( O( ON( X( XN( (also written `A (`), `)`,
  NOT SET CLR, = S R, FP FN, JU JC JCN, NOP REFRESH "REFRESH Q" END (`REFRESH I` is
  REFRESH: the image is named only to tell it from the output's);
* byte side: L, T, +I -I *I /I MOD, ==I <>I >I <I >=I <=I, the compare-and-combine
  forms "A ==I" "A <>I" "A >I" "A <I" "A >=I" "A <=I" and "O ==I" ... "O <=I"
  (the logic letter, one blank, the compare: as the spec writes them), SD SS SP SF,
  CU CD, READ, WRITE.  `S C n`, `R C n` and `R T n` keep the mnemonics "S" / "R";
  the operand's area (T or C) tells them from the bit instructions.

Decisions where the spec is silent (see also the tests):

* A declaration ends at `;` or at the end of its line; several share a line.
* VAR blocks may appear anywhere (a symbol must be declared before its first use).
* Symbols and labels share one name space; neither may be a mnemonic, a keyword
  (VAR, END_VAR, VAR_GLOBAL, AT, BIT, BYTE), an area name (I, PI, ... FBY) or an
  address-like word (area name + digits, e.g. `T1`, `M5`).
* Labels at the end of the file, with no instruction after them, mark an appended
  END (appended even when the last instruction already is END).
* An unclosed parenthesis is reported at the innermost open one, when an END (or the
  end of the file) is reached with parentheses open.
* Instr.labels keeps the labels as written (for the listing); Program.labels is keyed
  by the upper-case name.  Operand.text is the operand exactly as written, quotes
  included.  The appended END has line = last line + 1, col 1 and an empty source.
* `BIT:` / `BYTE:` (hand-partitioned programs, parallel mode only): a line starting
  with `BIT:` or `BYTE:` starts a section; its instructions are tagged with it
  (Instr.section) and go verbatim into that processor's part (bitbyte.compiler).
  Once a program has sections, every instruction must be in one; a section may appear
  more than once.  A BIT: section holds bit instructions, `= FBY k` and reads of
  `FBI k` (not `S`/`R FBY k`: a channel write must not depend on the RLO); a BYTE:
  section holds word instructions, `READ FBY k`, `WRITE FBI k`, `JU`/`JC`/`JCN` (the
  byte program's jumps on F_B) and `END`.  A jump reaches only labels of its own
  section.  Labels pending at a section switch mark an END appended to the section
  they follow (as labels at the end of the file do); a parenthesis may not stay open
  across a switch.
* `VAR_GLOBAL ... END_VAR` (spec §7, multi-core plants): declarations
  `Name AT M10.0 : WRITE;` / `Name AT MW20 : READ;`, with the same layout rules as
  VAR (`;` or the end of the line ends one, several per line).  The local copy is a
  bit in M or a word in MW (anything else: operand of the wrong kind); the name is a
  symbol of the program like a VAR symbol (same name rules, no duplicates); two
  shared variables may not share one local copy.  They are kept in source order in
  Program.globals; the plant-wide rules (one writer, same kind) are the linker's
  (bitbyte.plant.link).  A single-core `asm`/`run` treats them as ordinary symbols.
"""
from __future__ import annotations

import bisect
from dataclasses import dataclass, replace

from bitbyte.lang.config import DEFAULT, Config
from bitbyte.lang.definition import DEF
from bitbyte.lang.errors import SourceError
from bitbyte.lang.program import BIT_AREAS, GlobalVar, Instr, Operand, Program
from bitbyte.lang.suggest import did_you_mean

# --------------------------------------------------------------------------------------
# Vocabulary
# --------------------------------------------------------------------------------------

BIT_ADDR_AREAS = BIT_AREAS                                    # byte.bit
INDEX_AREAS = ("T", "C", "FBI", "FBY", "IW", "QW", "MW", "MD")  # number
AREAS = BIT_ADDR_AREAS + INDEX_AREAS

PAREN_OPENERS = ("A", "AN", "O", "ON", "X", "XN")             # + "(" -> "A(" ...
COMBINE_WORDS = ("LD", "LDN") + PAREN_OPENERS                 # + a status condition
COMPARES = DEF.all_compares                                   # ==I ... <=D
ARITHMETIC = DEF.arithmetic                                   # +D ... MODD
WORD_LOGIC = DEF.word_logic                                   # AW ... XOD
SHIFTS = DEF.shifts                                           # SLW ... RRD
MAX_SHIFT = 255
KEYWORDS = ("VAR", "END_VAR", "VAR_GLOBAL", "AT", "BIT", "BYTE")
ACCESS_WORDS = ("READ", "WRITE")                              # VAR_GLOBAL attribute
GLOBAL_AREAS = {"M": "bit", "MW": "word"}                     # local copy -> kind

MAX_DURATION_MS = 2 ** 31 - 1
DURATION_UNITS = ("h", "m", "s", "ms")                        # largest first
UNIT_MS = {"h": 3_600_000, "m": 60_000, "s": 1000, "ms": 1}


@dataclass(frozen=True)
class Sig:
    """What one mnemonic takes as operand.

    accepts: the operand areas allowed ("INT"/"TIME" for constants); empty for no
    operand; ("LABEL",) for jumps.  need: how the wrong-kind message names it.
    """

    accepts: tuple[str, ...]
    need: str = ""
    optional: bool = False      # the operand may be left out (shifts: count in ACCU2)


NO_OPERAND = Sig(())
BIT_READ = Sig(("I", "PI", "IR", "IF", "Q", "QR", "QF", "PQ", "M", "T", "C", "FBI"),
               "a bit (I, PI, IR, IF, Q, QR, QF, PQ, M, T, C or FBI)")
ASSIGN = Sig(("Q", "PQ", "M", "FBY"), "a target Q, PQ, M or FBY")
SET = Sig(("Q", "PQ", "M", "FBY", "C"), "a target Q, PQ, M, FBY or a counter C n")
RESET = Sig(("Q", "PQ", "M", "FBY", "T", "C"),
            "a target Q, PQ, M, FBY or a timer T n or counter C n")
EDGE = Sig(("M", "Q"), "an edge memory M or Q")
JUMP = Sig(("LABEL",), "a label")
LOAD = Sig(("IW", "QW", "MW", "MD", "T", "C", "INT", "TIME", "DINT"),
           "a word (IW, QW, MW), a double word MD, a timer, a counter or a constant")
TRANSFER = Sig(("MW", "QW", "MD"), "a target MW, QW or MD")
TIMER = Sig(("T",), "a timer T n")
COUNTER = Sig(("C",), "a counter C n")
SHIFT = Sig(("INT",), f"a shift count 0..{MAX_SHIFT} (or none: ACCU2's low byte)",
            optional=True)

SIGNATURES: dict[str, Sig] = {
    **{m: BIT_READ for m in ("LD", "LDN", "A", "AN", "O", "ON", "X", "XN")},
    **{m + "(": NO_OPERAND for m in PAREN_OPENERS},
    ")": NO_OPERAND, "NOT": NO_OPERAND, "SET": NO_OPERAND, "CLR": NO_OPERAND,
    "NOP": NO_OPERAND, "REFRESH": NO_OPERAND, "REFRESH Q": NO_OPERAND, "END": NO_OPERAND,
    "=": ASSIGN, "S": SET, "R": RESET, "FP": EDGE, "FN": EDGE,
    "JU": JUMP, "JC": JUMP, "JCN": JUMP,
    # byte instructions
    "L": LOAD, "T": TRANSFER,
    **{m: NO_OPERAND for m in ARITHMETIC + WORD_LOGIC},
    **{m: SHIFT for m in SHIFTS},
    **{m: NO_OPERAND for m in COMPARES},
    **{f"{f} {c}": NO_OPERAND for f in ("A", "O") for c in COMPARES},
    **{m: NO_OPERAND for m in DEF.status_reads},          # LD ==0 ... XN UO
    **{m: TIMER for m in ("SD", "SS", "SP", "SF")},
    "CU": COUNTER, "CD": COUNTER,
    "READ": Sig(("FBY",), "a channel FBY k"),
    "WRITE": Sig(("FBI",), "a channel FBI k"),
}
# What a mnemonic looks like at the start of a statement (without "(" forms).
MNEMONICS = frozenset(m for m in SIGNATURES if "(" not in m and " " not in m)


# --------------------------------------------------------------------------------------
# Source text and its positions
# --------------------------------------------------------------------------------------

class Source:
    """The checked text of one file, with offset -> (line, col) and line lookup."""

    def __init__(self, path: str, text: str):
        self.path = path
        self.text = text
        self.line_starts = [0] + [i + 1 for i, ch in enumerate(text) if ch == "\n"]
        self.lines = text.split("\n")

    def position(self, offset: int) -> tuple[int, int]:
        """1-based (line, col) of a character offset."""
        index = bisect.bisect_right(self.line_starts, offset) - 1
        return index + 1, offset - self.line_starts[index] + 1

    def line_text(self, line: int) -> str:
        return self.lines[line - 1] if 1 <= line <= len(self.lines) else ""

    def last_line(self) -> int:
        """Number of the last line that holds text (a final newline ends it)."""
        if self.text == "":
            return 0
        n = len(self.lines)
        return n - 1 if n > 1 and self.lines[-1] == "" else n

    def error(self, line: int, col: int, message: str) -> SourceError:
        return SourceError(self.path, line, col, message, self.line_text(line))


def _printable(ch: str) -> bool:
    return " " <= ch <= "~" or ch == "\t"


def check_bytes(path: str, data: bytes | str) -> str:
    """The text, if every character is printable ASCII, tab or newline (CR allowed
    only right before LF, and then dropped); else SourceError at the first bad one.

    Runs before any other parsing, so that a binary file is reported as such.
    """
    chars = data.decode("latin-1") if isinstance(data, (bytes, bytearray)) else data
    line, line_start = 1, 0
    for i, ch in enumerate(chars):
        if ch == "\n":
            line, line_start = line + 1, i + 1
        elif ch == "\r" and chars[i + 1: i + 2] == "\n":
            continue
        elif not _printable(ch):
            end = chars.find("\n", i)
            shown = chars[line_start: len(chars) if end < 0 else end]
            shown = "".join(c if _printable(c) else "?" for c in shown)
            raise SourceError(path, line, i - line_start + 1, _bad_char_message(ch), shown)
    return chars.replace("\r\n", "\n")


def _bad_char_message(ch: str) -> str:
    code = f"0x{ord(ch):02X}" if ord(ch) < 256 else f"U+{ord(ch):04X}"
    if ch == "\r":
        return (f"invalid byte {code} (carriage return not followed by a newline): "
                "a source file holds only printable ASCII, tab and newline")
    return f"invalid byte {code}: a source file holds only printable ASCII, tab and newline"


# --------------------------------------------------------------------------------------
# Lexer
# --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Token:
    """kind: WORD, STRING, LPAREN, RPAREN, COLON, SEMI, EOL, EOF.
    text: as written (STRING: the name between the quotes).  start/end: offsets."""

    kind: str
    text: str
    start: int
    end: int
    line: int
    col: int

    def is_word(self, *upper: str) -> bool:
        """A WORD equal (case-insensitively) to one of `upper`."""
        return self.kind == "WORD" and self.text.upper() in upper

    @property
    def ends_statement(self) -> bool:
        return self.kind in ("EOL", "EOF", "SEMI")


SINGLE = {"(": "LPAREN", ")": "RPAREN", ":": "COLON", ";": "SEMI", "\n": "EOL"}
WORD_STOP = " \t\n();:\""


def lex_token(src: Source, pos: int) -> Token:
    """The token starting at or after `pos` (blanks and `//` comments skipped)."""
    text = src.text
    while True:
        while pos < len(text) and text[pos] in " \t":
            pos += 1
        if text.startswith("//", pos):
            end = text.find("\n", pos)
            pos = len(text) if end < 0 else end
            continue
        break
    line, col = src.position(pos)
    if pos >= len(text):
        return Token("EOF", "", pos, pos, line, col)
    ch = text[pos]
    if ch in SINGLE:
        return Token(SINGLE[ch], ch, pos, pos + 1, line, col)
    if ch == '"':
        return _lex_string(src, pos, line, col)
    end = pos
    while end < len(text) and text[end] not in WORD_STOP and not text.startswith("//", end):
        end += 1
    return Token("WORD", text[pos:end], pos, end, line, col)


def _lex_string(src: Source, pos: int, line: int, col: int) -> Token:
    """A quoted symbol: `"name"` on one line."""
    end = pos + 1
    while end < len(src.text) and src.text[end] not in '"\n':
        end += 1
    if end >= len(src.text) or src.text[end] != '"':
        raise src.error(line, col, "unterminated quoted name: missing closing `\"`")
    return Token("STRING", src.text[pos + 1:end], pos, end + 1, line, col)


# --------------------------------------------------------------------------------------
# Small word classifiers (one token each)
# --------------------------------------------------------------------------------------

def is_identifier(word: str) -> bool:
    return (word != "" and (word[0].isalpha() or word[0] == "_") and word.isascii()
            and all(c.isalnum() or c == "_" for c in word))


def split_area(word: str) -> tuple[str, str]:
    """("IW", "10") for "iw10": the leading letters upper-cased, and the rest."""
    i = 0
    while i < len(word) and word[i].isascii() and word[i].isalpha():
        i += 1
    return word[:i].upper(), word[i:]


def is_decimal(text: str) -> bool:
    return text != "" and text.isascii() and text.isdigit()


def to_int(digits: str, base: int = 10) -> int:
    """int(digits, base), but a number too long to matter (and too long for
    Python's int() limit) becomes 10**30: out of every range, never an exception."""
    digits = digits.lstrip("0") or "0"
    return int(digits, base) if len(digits) <= 24 else 10 ** 30


def looks_like_address(word: str) -> bool:
    """`I0.0`, `t1`, `MW12x`: an area name followed by a digit (or alone)."""
    area, rest = split_area(word)
    return area in AREAS and (rest == "" or rest[0].isdigit())


def reserved_reason(name: str) -> str | None:
    """Why `name` cannot be a symbol or label, or None if it can."""
    upper = name.upper()
    if upper in MNEMONICS:
        return "is a mnemonic"
    if upper in KEYWORDS:
        return "is a keyword"
    if looks_like_address(name):
        return "is an address"
    return None


# --------------------------------------------------------------------------------------
# Parser
# --------------------------------------------------------------------------------------

@dataclass
class _Name:
    """A declared symbol or a defined label, with where it was defined."""

    line: int
    col: int


# how each kind of name comes to be: "first declared at", "is defined at"
_DEFINED = {"symbol": "declared", "label": "defined"}


class Parser:
    """Parses one source; use `parse()` rather than this class directly."""

    def __init__(self, src: Source, config: Config):
        self.src = src
        self.config = config
        self.pos = 0                      # offset of the next unread token
        self.instrs: list[Instr] = []
        self.symbols: dict[str, Operand] = {}
        self.symbol_defs: dict[str, _Name] = {}
        self.names: dict[str, list[str]] = {"symbol": [], "label": []}  # as spelled, for hints
        self.labels: dict[str, int] = {}
        self.label_defs: dict[str, _Name] = {}
        self.pending_labels: list[str] = []
        self.jumps: list[tuple[Instr, Token]] = []   # label references, resolved last
        self.open_parens: list[Instr] = []
        self.after_open: Instr | None = None
        self.section = ""                 # "", "BIT" or "BYTE" (hand-partitioned)
        self.globals: list[GlobalVar] = []

    # -- token stream -------------------------------------------------------------

    def peek(self, ahead: int = 1) -> Token:
        """The ahead-th next token, without consuming."""
        pos = self.pos
        tok = lex_token(self.src, pos)
        for _ in range(ahead - 1):
            if tok.kind == "EOF":
                break
            tok = lex_token(self.src, tok.end)
        return tok

    def next(self) -> Token:
        tok = lex_token(self.src, self.pos)
        self.pos = tok.end
        return tok

    def skip_line(self) -> None:
        """Drop the rest of the current line (a `;` comment in the program body)."""
        end = self.src.text.find("\n", self.pos)
        self.pos = len(self.src.text) if end < 0 else end

    def error(self, tok: Token, message: str) -> SourceError:
        return self.src.error(tok.line, tok.col, message)

    def error_at(self, instr: Instr, message: str) -> SourceError:
        return self.src.error(instr.line, instr.col, message)

    # -- top level ------------------------------------------------------------------

    def parse(self) -> Program:
        while True:
            tok = self.peek()
            if tok.kind == "EOF":
                break
            if tok.kind == "EOL":
                self.next()
            elif tok.kind == "SEMI":
                self.skip_line()
            elif tok.is_word("BIT", "BYTE") and self.peek(2).kind == "COLON":
                self.parse_section_header()
            elif self.peek(2).kind == "COLON":
                self.parse_statement()          # a label, even one named like a keyword
            elif tok.is_word("VAR", "VAR_GLOBAL"):
                self.parse_var_block()
            elif tok.is_word("END_VAR"):
                raise self.error(tok, "END_VAR without VAR")
            else:
                self.parse_statement()
        return self.finish()

    def finish(self) -> Program:
        """End-of-file checks, the appended END, the size check."""
        problems = [self.unknown_label_error(), self.unclosed_error()]
        problems = [p for p in problems if p is not None]
        if problems:
            raise min(problems, key=lambda e: (e.line, e.col))
        if self.pending_labels or not self.instrs or self.instrs[-1].mnemonic != "END":
            line = self.src.last_line() + 1
            self.add_instr(Instr("END", None, line, 1, ""), appended=True)
        self.check_size(self.instrs[-1], appended=True)
        self.check_jump_sections()
        return Program(self.src.path, self.instrs, dict(self.labels), dict(self.symbols),
                       list(self.globals),
                       {name.upper(): name for name in self.names["symbol"]})

    # -- BIT: / BYTE: sections (hand-partitioned programs) ----------------------------

    def parse_section_header(self) -> None:
        """`BIT:` or `BYTE:`: the instructions that follow belong to that part."""
        tok = self.next()
        self.next()                                      # the colon
        name = tok.text.upper()
        where = f"`{tok.text}:` at {tok.line}:{tok.col}"
        if self.open_parens:
            raise self.unclosed(self.open_parens[-1], where)
        if self.section == "" and (self.instrs or self.pending_labels):
            raise self.error(tok, f"`{tok.text}:` after instructions outside any section: "
                                  "in a hand-partitioned program every instruction "
                                  "stands in a BIT: or BYTE: section")
        if self.pending_labels:                          # they mark the section's end
            self.add_instr(Instr("END", None, tok.line, tok.col, ""), appended=True)
        self.after_open = None
        self.section = name
        if not self.peek().ends_statement:
            self.parse_statement()

    def check_section(self, instr: Instr) -> None:
        """What a BIT: / BYTE: section may hold (module docstring)."""
        m, op = instr.mnemonic, instr.operand
        byte = is_byte_mnemonic(m, op)
        if self.section == "BIT":
            if byte:
                raise self.error_at(instr, f"`{m}` is a byte instruction: it cannot stand "
                                           "in a BIT: section")
            if m in ("S", "R") and op is not None and op.area == "FBY":
                raise self.error_at(instr, f"operand of the wrong kind: `{m} FBY{op.index}`"
                                           ": only `= FBY k` writes a channel (a write "
                                           "must not depend on the RLO)")
        elif self.section == "BYTE" and not byte and m not in ("JU", "JC", "JCN", "END"):
            raise self.error_at(instr, f"`{m}` is a bit instruction: it cannot stand in a "
                                       "BYTE: section (word instructions, READ, WRITE, "
                                       "JU/JC/JCN on F_B and END)")

    def check_jump_sections(self) -> None:
        """A jump of a hand-partitioned program reaches only its own section."""
        for instr, tok in self.jumps:
            target = self.instrs[self.labels[instr.operand.label]]
            if target.section != instr.section:
                raise self.error(tok, f"unknown label `{tok.text}` in this {instr.section}: "
                                      f"section (it is in the {target.section}: section; "
                                      "each processor jumps in its own part)")

    def unknown_label_error(self) -> SourceError | None:
        for instr, tok in self.jumps:
            if instr.operand.label not in self.label_defs:   # incl. ones before EOF
                return self.error(tok, f"unknown label `{tok.text}`"
                                       + did_you_mean(tok.text, self.names["label"]))
        return None

    def unclosed_error(self) -> SourceError | None:
        if not self.open_parens:
            return None
        return self.unclosed(self.open_parens[-1], "the end of the file")

    def unclosed(self, opener: Instr, where: str) -> SourceError:
        return self.error_at(opener, f"unbalanced parentheses: `{opener.mnemonic}` "
                                     f"is not closed by a `)` before {where}")

    # -- declarations ---------------------------------------------------------------

    def parse_var_block(self) -> None:
        """VAR (or VAR_GLOBAL) decl; decl; ... END_VAR  (declarations end at `;` or
        end of line)."""
        var_tok = self.next()
        keyword = var_tok.text.upper()
        is_global = keyword == "VAR_GLOBAL"
        while True:
            tok = self.peek()
            if tok.kind == "EOF":
                raise self.error(var_tok, f"missing END_VAR: this {keyword} is never "
                                          "closed")
            if tok.kind in ("EOL", "SEMI"):
                self.next()
            elif tok.is_word("END_VAR"):
                self.next()
                return
            elif is_global and self.global_without_at(tok):
                self.parse_declaration(is_global)         # reports the missing AT
            elif tok.is_word("VAR", "VAR_GLOBAL") or self.looks_like_statement(tok):
                raise self.error(tok, f"missing END_VAR: the {keyword} at "
                                      f"{var_tok.line}:{var_tok.col} is still open here")
            else:
                self.parse_declaration(is_global)

    def global_without_at(self, tok: Token) -> bool:
        """`Name : WRITE` inside VAR_GLOBAL: a declaration missing its AT, not a label."""
        return (tok.kind in ("WORD", "STRING") and self.peek(2).kind == "COLON"
                and self.peek(3).is_word(*ACCESS_WORDS))

    def looks_like_statement(self, tok: Token) -> bool:
        """Inside VAR: a label or an instruction means END_VAR was forgotten."""
        after = self.peek(2)
        if tok.kind == "RPAREN" or (tok.kind == "WORD" and after.kind == "COLON"):
            return True
        return (tok.kind == "WORD" and tok.text.upper() in MNEMONICS
                and not after.is_word("AT"))

    def parse_declaration(self, is_global: bool = False) -> None:
        """`Name AT address` (VAR_GLOBAL: `Name AT address : READ|WRITE`) followed
        by `;` or the end of the line."""
        form = "`Name AT address : READ|WRITE;`" if is_global else "`Name AT address;`"
        name_tok = self.next()
        name = self.declared_name(name_tok, form)
        at = self.next()
        if not at.is_word("AT"):
            raise self.error(at, f"expected `AT` after `{name}` in a declaration "
                                 f"({form})")
        if self.peek().ends_statement:
            raise self.error(at, f"missing operand: `{name} AT` needs an address")
        addr_tok = self.next()
        operand = self.parse_address(addr_tok, declaring=True)
        access = self.parse_access(name, operand, addr_tok) if is_global else ""
        end = self.peek()
        if end.kind == "SEMI":
            self.next()
        elif end.kind not in ("EOL", "EOF"):
            raise self.error(end, f"extra operand `{end.text}` in the declaration of "
                                  f"`{name}`: expected `;`")
        self.define_symbol(name, name_tok, operand)
        if is_global:
            self.globals.append(GlobalVar(
                name.upper(), GLOBAL_AREAS[operand.area], access, operand,
                name_tok.line, name_tok.col, self.src.line_text(name_tok.line), name))

    def parse_access(self, name: str, operand: Operand, addr_tok: Token) -> str:
        """The `: READ` / `: WRITE` of a VAR_GLOBAL declaration, after checking that
        the local copy is an M bit or an MW word and no other shared variable's."""
        if operand.area not in GLOBAL_AREAS:
            raise self.error(addr_tok, f"operand of the wrong kind: the local copy of a "
                                       f"shared variable is a bit in M or a word in MW, "
                                       f"not {describe(operand)}")
        for other in self.globals:
            if other.operand.address() == operand.address():
                raise self.error(addr_tok, f"duplicate local copy: `{operand.text}` "
                                           f"already holds the shared variable "
                                           f"`{other.text}` (declared at {other.line}:"
                                           f"{other.col})")
        colon = self.peek()
        if colon.kind != "COLON":
            line, col = self.src.position(self.pos)      # right after the address
            what = "found the end of the declaration" if colon.ends_statement \
                else f"found `{colon.text}`"
            raise self.src.error(line, col, f"missing `:` after the address of `{name}`: "
                                            f"a VAR_GLOBAL declaration is `Name AT "
                                            f"address : READ|WRITE;` ({what})")
        self.next()
        word = self.peek()
        if word.ends_statement:
            raise self.error(colon, f"missing access after `:` in the declaration of "
                                    f"`{name}`: READ or WRITE")
        self.next()
        if not word.is_word(*ACCESS_WORDS):
            raise self.error(word, f"unknown access `{word.text}` for `{name}`: READ "
                                   "(another core writes it) or WRITE (this core "
                                   "writes it)")
        return word.text.upper()

    def declared_name(self, tok: Token, form: str = "`Name AT address;`") -> str:
        """The name of a declaration (bare or quoted), checked for reserved words."""
        if tok.kind not in ("WORD", "STRING") or not is_identifier(tok.text):
            raise self.error(tok, f"expected a declaration {form}, "
                                  f"found `{tok.text}`")
        reason = reserved_reason(tok.text)
        if reason:
            raise self.error(tok, f"symbol `{tok.text}` {reason}: a symbol may not be "
                                  "a mnemonic or an address")
        self.check_new_name("symbol", tok.text, tok)
        return tok.text

    def check_new_name(self, kind: str, name: str, tok: Token) -> None:
        """A new symbol or label (kind) `name`: neither a symbol nor a label may have
        it already (names are case-insensitive)."""
        key = name.upper()
        defs = {"symbol": self.symbol_defs, "label": self.label_defs}
        other = "label" if kind == "symbol" else "symbol"
        if key in defs[kind]:
            first = defs[kind][key]
            raise self.error(tok, f"duplicate {kind} `{name}` "
                                  f"(first {_DEFINED[kind]} at {first.line}:{first.col})")
        if key in defs[other]:
            first = defs[other][key]
            raise self.error(tok, f"duplicate {kind} `{name}`: a {other} of that name "
                                  f"is {_DEFINED[other]} at {first.line}:{first.col}")

    def define_symbol(self, name: str, tok: Token, operand: Operand) -> None:
        key = name.upper()
        self.symbols[key] = operand
        self.symbol_defs[key] = _Name(tok.line, tok.col)
        self.names["symbol"].append(name)

    # -- statements -----------------------------------------------------------------

    def parse_statement(self) -> None:
        """`label: label: MNEMONIC operand` up to the end of the line."""
        self.parse_labels()
        tok = self.peek()
        if tok.ends_statement:
            if tok.kind == "SEMI":
                self.skip_line()
            return
        if tok.is_word("VAR", "VAR_GLOBAL", "END_VAR"):
            raise self.error(tok, f"`{tok.text}` cannot follow a label")
        instr = self.parse_instruction()
        self.end_statement(instr)
        self.add_instr(instr)

    def parse_labels(self) -> None:
        while self.peek().kind in ("WORD", "STRING") and self.peek(2).kind == "COLON":
            tok = self.next()
            self.next()
            self.define_label(tok)

    def define_label(self, tok: Token) -> None:
        if tok.is_word("BIT", "BYTE"):
            raise self.error(tok, f"`{tok.text}:` starts a section (hand-partitioned "
                                  "program): it stands at the start of its line")
        if tok.kind != "WORD" or not is_identifier(tok.text):
            raise self.error(tok, f"invalid label name `{tok.text}`")
        reason = reserved_reason(tok.text)
        if reason:
            raise self.error(tok, f"label `{tok.text}` {reason}: a label may not be "
                                  "a mnemonic or an address")
        self.check_new_name("label", tok.text, tok)
        self.label_defs[tok.text.upper()] = _Name(tok.line, tok.col)
        self.names["label"].append(tok.text)
        self.pending_labels.append(tok.text)

    def end_statement(self, instr: Instr) -> None:
        """Anything left on the line but a comment is one operand too many."""
        tok = self.peek()
        if tok.kind == "SEMI":
            self.skip_line()
        elif not tok.ends_statement:
            takes = "no operand" if instr.operand is None else "one operand"
            raise self.error(tok, f"extra operand `{tok.text}`: `{instr.mnemonic}` "
                                  f"takes {takes}")

    def parse_instruction(self) -> Instr:
        tok = self.next()
        mnemonic = self.mnemonic_of(tok)
        instr = Instr(mnemonic, None, tok.line, tok.col, self.src.line_text(tok.line))
        instr.operand = self.parse_operand_for(instr, SIGNATURES[mnemonic])
        return instr

    def mnemonic_of(self, tok: Token) -> str:
        """The canonical mnemonic starting at `tok`; consumes `(` / a compare."""
        if tok.kind == "RPAREN":
            return ")"
        if tok.kind != "WORD":
            raise self.error(tok, f"unknown mnemonic `{tok.text}`")
        word = tok.text.upper()
        nxt = self.peek()
        if nxt.kind == "LPAREN":
            if word not in PAREN_OPENERS:
                raise self.error(tok, f"unknown mnemonic `{tok.text}(`: only "
                                      "A( AN( O( ON( X( XN( open a parenthesis")
            self.next()
            return word + "("
        if word in PAREN_OPENERS and nxt.kind == "WORD" and nxt.text.upper() in COMPARES:
            combined = f"{word} {nxt.text.upper()}"
            if combined not in SIGNATURES:
                raise self.error(tok, f"unknown mnemonic `{tok.text} {nxt.text}`: a "
                                      "compare combines with A or O only")
            self.next()
            return combined
        if word in COMBINE_WORDS and nxt.kind == "WORD" \
                and nxt.text.upper() in DEF.status_conditions:
            self.next()                                   # a status bit: `A ==0`
            return f"{word} {nxt.text.upper()}"
        if word == "REFRESH" and not nxt.ends_statement:
            return self.refresh_of(tok, nxt)
        if word not in MNEMONICS:
            raise self.error(tok, f"unknown mnemonic `{tok.text}`"
                                  + did_you_mean(tok.text, MNEMONICS))
        return word

    def refresh_of(self, tok: Token, nxt: Token) -> str:
        """`REFRESH I` (= `REFRESH`, the input image) or `REFRESH Q` (the output image
        to the pins, paper Fig. 1); the image letter is consumed."""
        image = nxt.text.upper() if nxt.kind == "WORD" else ""
        if image not in ("I", "Q"):
            raise self.error(nxt, f"operand of the wrong kind: `{tok.text}` refreshes "
                                  f"the image `I` or `Q` (or, alone, `I`), not "
                                  f"`{nxt.text}`")
        self.next()
        return "REFRESH Q" if image == "Q" else "REFRESH"

    # -- operands -------------------------------------------------------------------

    def parse_operand_for(self, instr: Instr, sig: Sig) -> Operand | None:
        if not sig.accepts or sig.optional and self.peek().ends_statement:
            return None
        if self.peek().ends_statement:
            raise self.error_at(instr, f"missing operand: `{instr.mnemonic}` needs "
                                       f"{sig.need}")
        tok = self.next()
        if sig.accepts == ("LABEL",):
            return self.parse_label_ref(instr, tok)
        operand = self.parse_value(tok)
        self.check_kind(instr, sig, operand, tok)
        if sig is SHIFT and not 0 <= operand.value <= MAX_SHIFT:
            raise self.error(tok, f"constant out of range: `{operand.text}` (a shift "
                                  f"count is 0..{MAX_SHIFT})")
        return operand

    def check_kind(self, instr: Instr, sig: Sig, op: Operand, tok: Token) -> None:
        if op.area not in sig.accepts:
            raise self.error(tok, f"operand of the wrong kind: `{instr.mnemonic}` needs "
                                  f"{sig.need}, not {describe(op)}")

    def parse_label_ref(self, instr: Instr, tok: Token) -> Operand:
        """A jump target: a label name, resolved when the whole file is read."""
        name = tok.text
        if tok.kind == "STRING" or (tok.kind == "WORD" and is_identifier(name)
                                    and reserved_reason(name) is None):
            if name.upper() in self.symbols:
                raise self.error(tok, f"operand of the wrong kind: `{instr.mnemonic}` "
                                      f"needs a label, not the symbol `{name}`")
            text = self.src.text[tok.start:tok.end]
            operand = Operand("label", label=name.upper(), text=text)
            self.jumps.append((instr, tok))
            return operand
        raise self.error(tok, f"operand of the wrong kind: `{instr.mnemonic}` needs a "
                              f"label, not `{name}`")

    def parse_value(self, tok: Token) -> Operand:
        """A constant, an address or a symbol (any kind; the caller checks it)."""
        if tok.kind == "STRING":
            return self.lookup_symbol(tok)
        if tok.kind != "WORD":
            raise self.error(tok, f"invalid operand `{tok.text}`")
        text = tok.text
        if text[0].isdigit() or (text[0] in "+-" and text[1:2].isdigit()):
            return self.parse_number(tok)
        if text.upper().startswith("T#"):
            return self.parse_duration(tok)
        if text.upper().startswith("L#"):
            return self.parse_dint(tok)
        if looks_like_address(text) or "." in text:
            return self.parse_address(tok, declaring=False)
        if is_identifier(text):
            return self.lookup_symbol(tok)
        raise self.error(tok, f"invalid operand `{text}`")

    def lookup_symbol(self, tok: Token) -> Operand:
        operand = self.symbols.get(tok.text.upper())
        if operand is None:
            raise self.error(tok, f"undeclared symbol `{tok.text}`"
                                  + did_you_mean(tok.text, self.names["symbol"]))
        return replace(operand, text=self.src.text[tok.start:tok.end])

    # -- addresses ------------------------------------------------------------------

    def parse_address(self, tok: Token, declaring: bool) -> Operand:
        """`I0.0`, `I 0.0`, `T1`, `T 1`, `MW10` ... with the configured ranges."""
        area, rest = split_area(tok.text) if tok.kind == "WORD" else ("", "")
        if area not in AREAS or (rest and not rest[0].isdigit()):
            if declaring:
                raise self.error(tok, f"expected an address after AT, found `{tok.text}`")
            raise self.error(tok, f"invalid operand `{tok.text}`")
        end = tok.end
        if rest == "":
            number = self.peek()
            if number.kind != "WORD" or not number.text[0].isdigit():
                raise self.error(tok, f"incomplete address `{tok.text}`: "
                                      f"{address_form(area)} expected")
            self.next()
            rest, end = number.text, number.end
        written = self.src.text[tok.start:end]
        operand = self.address_operand(tok, area, rest, written)
        self.check_range(tok, operand)
        return operand

    def address_operand(self, tok: Token, area: str, rest: str, written: str) -> Operand:
        """Operand from area and the number part ("0.3" or "12")."""
        if area in BIT_ADDR_AREAS:
            byte, dot, bit = rest.partition(".")
            if dot and is_decimal(byte) and is_decimal(bit):
                return Operand("bit", area=area, byte=to_int(byte), bit=to_int(bit),
                               text=written)
        elif is_decimal(rest):
            return Operand("index", area=area, index=to_int(rest), text=written)
        raise self.error(tok, f"malformed address `{written}`: {address_form(area)} expected")

    def check_range(self, tok: Token, op: Operand) -> None:
        limit, what = area_limit(self.config, op.area)
        value = op.byte if op.kind == "bit" else op.index
        if value >= limit:
            raise self.error(tok, f"operand out of range: `{op.text}` ({what} "
                                  f"0..{limit - 1} in this build)")
        if op.kind == "bit" and op.bit > 7:
            raise self.error(tok, f"operand out of range: `{op.text}` (bit 0..7)")

    # -- constants ------------------------------------------------------------------

    def parse_number(self, tok: Token) -> Operand:
        """INT -32768..32767, or 16#0..16#FFFF as a 16-bit pattern (sign-extended)."""
        text = tok.text
        if "#" in text:
            base, _, digits = text.partition("#")
            if base != "16" or not digits or not all(c in "0123456789abcdefABCDEF"
                                                     for c in digits):
                raise self.error(tok, f"malformed constant `{text}`: integers are "
                                      "decimal or 16#hex")
            value = to_int(digits, 16)
            if value > 0xFFFF:
                raise self.error(tok, f"constant out of range: `{text}` "
                                      "(16#0..16#FFFF)")
            value = value - 0x10000 if value & 0x8000 else value
            return Operand("const", area="INT", value=value, text=text)
        sign, digits = (text[0], text[1:]) if text[0] in "+-" else ("", text)
        if not is_decimal(digits):
            raise self.error(tok, f"malformed constant `{text}`")
        value = -to_int(digits) if sign == "-" else to_int(digits)
        if not -32768 <= value <= 32767:
            raise self.error(tok, f"constant out of range: `{text}` (INT is "
                                  "-32768..32767)")
        return Operand("const", area="INT", value=value, text=text)

    def parse_dint(self, tok: Token) -> Operand:
        """L#n: a DINT constant, -2147483648..2147483647 (S7's form)."""
        text = tok.text[2:]
        sign, digits = (text[0], text[1:]) if text[:1] in ("+", "-") else ("", text)
        if not is_decimal(digits):
            raise self.error(tok, f"malformed constant `{tok.text}`: L#<decimal>")
        value = -to_int(digits) if sign == "-" else to_int(digits)
        if not -2 ** 31 <= value < 2 ** 31:
            raise self.error(tok, f"constant out of range: `{tok.text}` (DINT is "
                                  "-2147483648..2147483647)")
        return Operand("const", area="DINT", value=value, text=tok.text)

    def parse_duration(self, tok: Token) -> Operand:
        """T#1h2m3s4ms: parts largest unit first, each at most once -> ms."""
        body = tok.text[2:]
        parts = duration_parts(body)
        if parts is None:
            raise self.error(tok, f"malformed duration `{tok.text}`: parts <n>h <n>m "
                                  "<n>s <n>ms, largest unit first (T#1m30s)")
        value = sum(n * UNIT_MS[unit] for n, unit in parts)
        if value > MAX_DURATION_MS:
            raise self.error(tok, f"constant out of range: `{tok.text}` (at most "
                                  f"{MAX_DURATION_MS} ms)")
        return Operand("const", area="TIME", value=value, text=tok.text)

    # -- the instruction list -------------------------------------------------------

    def add_instr(self, instr: Instr, appended: bool = False) -> None:
        """Append, attach pending labels, follow the parenthesis structure."""
        self.check_parens(instr, appended)
        instr.section = self.section
        if self.section and not appended:
            self.check_section(instr)
        instr.labels = self.pending_labels
        for name in self.pending_labels:
            self.labels[name.upper()] = len(self.instrs)
        self.pending_labels = []
        self.instrs.append(instr)
        if not appended:
            self.check_size(instr, appended=False)

    def check_parens(self, instr: Instr, appended: bool) -> None:
        """`(` then LD/LDN; `)` closes one; END and EOF need none open; depth limit."""
        m = instr.mnemonic
        if self.after_open is not None and not appended:
            opener, self.after_open = self.after_open, None
            if m not in ("LD", "LDN"):
                raise self.error_at(instr, f"`(` not followed by LD/LDN: the instruction "
                                           f"after `{opener.mnemonic}` at {opener.line}:"
                                           f"{opener.col} must be LD or LDN, not `{m}`")
        if m.endswith("("):
            self.open_parens.append(instr)
            self.after_open = instr
            if len(self.open_parens) > self.config.nest_depth:
                raise self.error_at(instr, f"operand out of range: parentheses nested "
                                           f"deeper than {self.config.nest_depth} levels "
                                           "(nest_depth)")
        elif m == ")":
            if not self.open_parens:
                raise self.error_at(instr, "unbalanced parentheses: `)` without an open "
                                           "`(`")
            self.open_parens.pop()
        elif m == "END" and self.open_parens:
            raise self.unclosed(self.open_parens[-1], f"END at {instr.line}:{instr.col}")

    def check_size(self, instr: Instr, appended: bool) -> None:
        """Reported at the first instruction that does not fit; for an appended END
        at the last instruction of the source (1:1 if there is none)."""
        words = len(self.instrs)
        if words <= self.config.prog_words:
            return
        message = (f"program too large: {words} words"
                   f"{' with the appended END' if appended else ''}, program memory "
                   f"holds {self.config.prog_words} (prog_words)")
        if not appended:
            raise self.error_at(instr, message)
        if len(self.instrs) > 1:
            raise self.error_at(self.instrs[-2], message)
        raise self.src.error(1, 1, message)


# --------------------------------------------------------------------------------------
# Helpers without parser state
# --------------------------------------------------------------------------------------

BYTE_MNEMONICS = frozenset(
    ("L", "T") + ARITHMETIC + WORD_LOGIC + SHIFTS + ("SD", "SS", "SP", "SF", "CU", "CD", "READ",
                               "WRITE") + COMPARES + tuple(DEF.status_reads) + tuple(f"{f} {c}" for f in ("A", "O") for c in COMPARES))


def is_byte_mnemonic(mnemonic: str, op: Operand | None) -> bool:
    """A byte-processor instruction (`S C n`, `R C n`, `R T n` included)?"""
    if mnemonic in ("S", "R"):
        return op is not None and op.area in ("T", "C")
    return mnemonic in BYTE_MNEMONICS


def duration_parts(body: str) -> list[tuple[int, str]] | None:
    """[(1, "m"), (30, "s")] for "1m30s"; None if malformed or out of order."""
    parts: list[tuple[int, str]] = []
    i, last_rank = 0, -1
    while i < len(body):
        j = i
        while j < len(body) and body[j].isascii() and body[j].isdigit():
            j += 1
        k = j
        while k < len(body) and body[k].isascii() and body[k].isalpha():
            k += 1
        number, unit = body[i:j], body[j:k].lower()
        if not number or unit not in DURATION_UNITS:
            return None
        rank = DURATION_UNITS.index(unit)
        if rank <= last_rank:
            return None
        parts.append((to_int(number), unit))
        i, last_rank = k, rank
    return parts or None


def area_limit(config: Config, area: str) -> tuple[int, str]:
    """(number of bytes/elements the build has, what they are called) for an area."""
    what = "byte" if area in BIT_ADDR_AREAS else "number"
    return config.area_size(area), what


def address_form(area: str) -> str:
    return f"{area}<byte>.<bit>" if area in BIT_ADDR_AREAS else f"{area}<number>"


def describe(op: Operand) -> str:
    """`the word MW0`, `the bit I0.0`, ... for wrong-kind messages."""
    if op.kind == "const":
        return f"the {'duration' if op.area == 'TIME' else 'constant'} `{op.text}`"
    kinds = {"T": "timer", "C": "counter", "FBI": "channel", "FBY": "channel",
             "IW": "word", "QW": "word", "MW": "word", "MD": "double word"}
    kind = kinds.get(op.area, "bit")
    if op.text.upper().replace(" ", "") == op.address():
        return f"the {kind} `{op.text}`"
    return f"the {kind} `{op.text}` (= {op.address()})"


# --------------------------------------------------------------------------------------
# Entry points
# --------------------------------------------------------------------------------------

def parse(path: str, text: bytes | str, config: Config = DEFAULT) -> Program:
    """Check and parse one source file's content.  Raises only SourceError."""
    src = Source(path, check_bytes(path, text))
    return Parser(src, config).parse()


def source_language(path: str, lang: str | None = None) -> str:
    """"il" or "stl": `lang` if given (--lang), else from the suffix (`.awl`: S7
    statement list, spec §9; anything else: the IL dialect of §3)."""
    if lang is not None:
        return lang
    return "stl" if path.lower().endswith(".awl") else "il"


def parse_file(path: str, config: Config = DEFAULT, *, lang: str | None = None,
               mnemonics: str | None = None, symbols: str | None = None) -> Program:
    """Read and parse `path`.  A file that cannot be read is a SourceError too.
    S7 sources (`.awl` or lang="stl") go through bitbyte.lang.stl, with mnemonics
    "de" / "en" forced or (None) detected from the source, and the STEP 7 symbol
    table `symbols` (a path) if given; for an IL source a symbol table is an error."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as exc:
        raise SourceError(path, 0, 0, f"cannot read: {exc.strerror or exc}") from None
    if source_language(path, lang) == "stl":
        from bitbyte.lang.stl import parse_stl
        return parse_stl(path, data, config, mnemonics, symbols)
    if symbols is not None:
        raise SourceError(symbols, 0, 0, "--symbols: a STEP 7 symbol table goes with an "
                          "S7 source (.awl or --lang stl); an IL source declares its "
                          "symbols in VAR … END_VAR")
    return parse(path, data, config)
