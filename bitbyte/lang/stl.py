"""S7 statement list (STL, German AWL) -> the toolchain's `Program` (spec §9).

A `.awl` source is read as STEP 7 Classic exports it and awlsim reads it, and
translated into the instruction-list program model (bitbyte.lang.program) that the
encoder, the partitioning compiler and the reference interpreter already run.  What
this slice supports, and why each translation is S7's meaning, is docs/s7.md; in
short:

* one `ORGANIZATION_BLOCK OB 1` (header lines, `VAR_TEMP`, `BEGIN`, `NETWORK`,
  `TITLE =`, `END_ORGANIZATION_BLOCK`), and `FUNCTION FC n`, `FUNCTION_BLOCK FB n`
  with their instance `DATA_BLOCK`s, called with CALL / UC / CC and inlined
  (expand_calls); every other block is `unsupported:`;
* German or English mnemonics and addresses, detected from the source (one language
  per source) or forced with mnemonics="de" / "en";
* bit logic with S7's status bits /FC (first check) and OR, resolved statically:
  the first U/UN/O/ON/X/XN of a logic string becomes LD/LDN; `O` without operand
  (AND before OR) opens an `O(` around the AND term that follows; `U(` ... `)`
  nesting; jumps SPA/SPB/SPBN (JU/JC/JCN), block ends BE, BEA/BEB (BEU/BEC);
* everything else an S7 CPU knows is rejected with `file:line:col: unsupported: ...`.

The translation keeps one invariant: the IL RLO equals S7's RLO at every point,
except inside an AND term after `O` (then S7's RLO is `earlier terms OR this term`
and the IL RLO is the term, the earlier terms being on the IL parenthesis stack).
The compiler knows /FC and the OR bit at every instruction (straight-line code: they
depend only on the instruction sequence); where a jump target is reached with
different /FC states and its first instruction depends on /FC, the program is
rejected (`unsupported:`), never run with a different meaning.
"""
from __future__ import annotations

import re
from dataclasses import replace, dataclass, field

from bitbyte.lang.config import DEFAULT, Config
from bitbyte.lang.definition import DEF
from bitbyte.lang.errors import SourceError
from bitbyte.lang.program import TIMER_STARTS as IL_TIMER_STARTS, Instr, Operand, Program
from bitbyte.lang.s7symbols import Symbol, read_symbol_table
from bitbyte.lang.suggest import did_you_mean

# --------------------------------------------------------------------------------------
# Vocabulary: mnemonic as written -> {language: canonical (English S7) mnemonic}
# --------------------------------------------------------------------------------------

_BOTH = ("O ON X XN O( ON( X( XN( ) = S R FP FN NOT SET CLR SAVE BE NOP BLD "
         "+ L T LC SS FR LOOP CALL UC CC TAK PUSH POP ENT LEAVE INC DEC +I -I *I /I +D -D "
         "*D /D MOD +R -R *R /R +AR1 +AR2 ==I <>I >I <I >=I <=I ==D <>D >D <D >=D <=D "
         "==R <>R >R <R >=R <=R ITD ITB BTI BTD DTB DTR RND RND+ RND- TRUNC INVI INVD "
         "NEGI NEGD NEGR ABS SQR SQRT EXP LN SIN COS TAN ASIN ACOS ATAN CAW CAD SLW SRW "
         "SLD SRD RLD RRD RLDA RRDA SSI SSD OW XOW OD XOD LAR1 LAR2 TAR1 TAR2 "
         "MCRA MCRD MCR( )MCR").split()
_DE_ONLY = {
    "U": "A", "UN": "AN", "U(": "A(", "UN(": "AN(", "SPA": "JU", "SPB": "JC",
    "SPBN": "JCN", "SPBB": "JCB", "SPBNB": "JNB", "SPBI": "JBI", "SPBIN": "JNBI",
    "SPO": "JO", "SPS": "JOS", "SPZ": "JZ", "SPN": "JN", "SPP": "JP", "SPM": "JM",
    "SPPZ": "JPZ", "SPMZ": "JMZ", "SPU": "JUO", "SPL": "JL", "ZV": "CU", "ZR": "CD",
    "SI": "SP", "SV": "SE", "SA": "SF", "AUF": "OPN", "TDB": "CDB", "TAW": "CAW",
    "TAD": "CAD", "BEB": "BEC", "BEA": "BEU", "UW": "AW", "UD": "AD", "TAR": "CAR",
}
_EN_ONLY = {m: m for m in (
    "A", "AN", "A(", "AN(", "JU", "JC", "JCN", "JCB", "JNB", "JBI", "JNBI", "JO",
    "JOS", "JZ", "JN", "JP", "JM", "JPZ", "JMZ", "JUO", "JL", "CU", "CD", "SP", "SD",
    "SF", "OPN", "CDB", "BEC", "BEU", "AW", "AD", "CAR")}
# SE is both: German SE is the on-delay (English SD), English SE the extended pulse.
MNEMONIC_TABLE: dict[str, dict[str, str]] = {m: {"de": m, "en": m} for m in _BOTH}
for _m, _c in _DE_ONLY.items():
    MNEMONIC_TABLE.setdefault(_m, {})["de"] = _c
for _m, _c in _EN_ONLY.items():
    MNEMONIC_TABLE.setdefault(_m, {})["en"] = _c
MNEMONIC_TABLE["SE"] = {"de": "SD", "en": "SE"}

# Address areas as written -> {language: canonical (English) area}
_AREAS_BOTH = "M MB MW MD T DB DI DBX DBB DBW DBD DIX DIB DIW DID L LB LW LD".split()
_AREAS_DE = {"E": "I", "A": "Q", "EB": "IB", "EW": "IW", "ED": "ID", "AB": "QB",
             "AW": "QW", "AD": "QD", "PEB": "PIB", "PEW": "PIW", "PED": "PID",
             "PAB": "PQB", "PAW": "PQW", "PAD": "PQD", "Z": "C"}
_AREAS_EN = {c: c for c in _AREAS_DE.values()} | {"I": "I", "Q": "Q"}
AREA_TABLE: dict[str, dict[str, str]] = {a: {"de": a, "en": a} for a in _AREAS_BOTH}
for _a, _c in _AREAS_DE.items():
    AREA_TABLE.setdefault(_a, {})["de"] = _c
for _a, _c in _AREAS_EN.items():
    AREA_TABLE.setdefault(_a, {})["en"] = _c

LANGUAGE_NAME = {"de": "German", "en": "English"}
AREA_NAME = {"de": {"C": "Z"}, "en": {"C": "C"}}     # an English area as written

# Canonical mnemonics this slice translates.
STATUS_AREAS = ("T", "C")   # status bits a combine reads (timers, counters)
TIMER_STARTS = ("SP", "SE", "SD", "SS", "SF")  # canonical: S7 SI, SV, SE, SS, SA
IL_TIMER = {"SP": "SD", "SE": "SS", "SD": "SD", "SS": "SS", "SF": "SF"}
COMBINE = {"A": ("A", 0), "AN": ("A", 1), "O": ("O", 0), "ON": ("O", 1),
           "X": ("X", 0), "XN": ("X", 1)}
OPEN = {"A(": ("A", 0), "AN(": ("A", 1), "O(": ("O", 0), "ON(": ("O", 1),
        "X(": ("X", 0), "XN(": ("X", 1)}
BIT_AREAS = ("I", "Q", "M")
# instructions that neither read /FC nor the OR bit, and leave /FC = 0 (a jump
# target starting with one of them may be reached with any /FC)
COMPARES = ("==I", "<>I", ">I", "<I", ">=I", "<=I")
ARITHMETIC = ("+I", "-I", "*I", "/I")
# DINT (docs/s7.md, DINT): the same over all 32 bits of the accumulators; S7's MOD is
# the DINT remainder, the IL's MODD
COMPARES_D = ("==D", "<>D", ">D", "<D", ">=D", "<=D")
ARITHMETIC_D = ("+D", "-D", "*D", "/D", "MOD")
IL_DINT = {"MOD": "MODD"}
# word logic and shifts (docs/s7.md, "Word logic and shifts"): canonical English
LOGIC_W = ("AW", "OW", "XOW")           # on ACCU1-L (S7 keeps ACCU1-H)
LOGIC_D = ("AD", "OD", "XOD")           # on 32 bits
SHIFT_W = ("SLW", "SRW", "SSI")         # ACCU1-L
SHIFT_D = ("SLD", "SRD", "SSD", "RLD", "RRD")
# status bits CC 1 / CC 0 (docs/s7.md, "Status bits"): the conditions a combine reads
# and the jumps on them (the conditions whose OR decides the jump; SPN/JN is A1 XOR
# A0, which is >0 OR <0)
CC_CONDITIONS = DEF.status_conditions          # ==0 ... UO, and OV, OS
CC_JUMPS = {"JZ": ("==0",), "JN": (">0", "<0"), "JP": (">0",), "JM": ("<0",),
            "JPZ": (">=0",), "JMZ": ("<=0",), "JUO": ("UO",), "JO": ("OV",),
            "JOS": ("OS",)}
# which of the IL's status bits are S7's (_State.cc_ok): CC 1/CC 0, OV, OS
STATUS_BITS = frozenset({"CC", "OV", "OS"})
CC_OV = frozenset({"CC", "OV"})


def status_bit(cond: str) -> str:
    """The status bit a condition of CC_CONDITIONS reads."""
    return cond if cond in ("OV", "OS") else "CC"


def meet_status(oks) -> frozenset:
    """The status bits S7's on every path (none: all, as TOP)."""
    return frozenset.intersection(STATUS_BITS, *oks)
FC_BLIND = ("=", "S", "R", "SET", "CLR", "JC", "JCN", "BE", "BEU", "BEC") + COMPARES \
    + COMPARES_D \
    + TIMER_STARTS + ("CU", "CD") + ("@CALL", "@LEAVE", "@END", "@RET")
# instructions that neither read nor change /FC, the OR bit or the RLO: a jump
# target starting with them is judged by the first statement after them
# ACCU1-L changed in place, ACCU2 left alone in S7 (here: IL steps that change
# ACCU2 too, a constant or an IL arithmetic instruction each; `+ n` reads its n)
IN_PLACE = {"NEGI": (-1, "*I"), "INVI": (-1, "*I", -1, "+I"), "+": ("n", "+I"),
            "NEGD": (-1, "*D"), "INVD": (-1, "*D", -1, "+D")}
# (LOOP and the jumps on the status bits pass /FC on to their target too: see
# check_edges)
FC_PASS = ("L", "T", "LC", "LOOP", "NOP", "BLD", "SAVE", "ITD") + tuple(IN_PLACE) \
    + tuple(CC_JUMPS) + ARITHMETIC + ARITHMETIC_D + LOGIC_W + LOGIC_D + SHIFT_W + SHIFT_D
WORD_AREAS = {"IW": "I", "QW": "Q", "MW": "M"}     # word area -> the bit area it overlaps
# operands that name a register or a status word bit rather than an address: what
# each is, and why this CPU has none (rejected as `unsupported:` by name)
_NO_CC = "a status condition is read by a combine (`U ==0`), not written"
REGISTER_OPERANDS = {
    "BR": "status bit", "BIE": "status bit", "OV": "status bit", "OS": "status bit",
    "UO": "status bit", "==0": "status bit", "<>0": "status bit", ">0": "status bit",
    "<0": "status bit", ">=0": "status bit", "<=0": "status bit",
    "STW": "status word", "DBLG": "DB register", "DBNO": "DB register",
    "DILG": "DB register", "DINO": "DB register", "AR1": "address register",
    "AR2": "address register"}
# why the instructions this front end rejects by name have no translation (canonical
# English mnemonics; docs/s7.md's instruction reference has the same, row by row)
_WHY = {
    "BCD conversion of a DINT: no such word instruction": "BTD DTB",
    "REAL: no floating point in the byte processor":
        "==R <>R >R <R >=R <=R +R -R *R /R ABS SQR SQRT EXP LN SIN COS TAN ASIN ACOS "
        "ATAN DTR NEGR RND RND+ RND- TRUNC",
    "BCD conversion: no such word instruction": "BTI ITB",
    "rotations through CC 1: the byte processor keeps no condition codes": "RLDA RRDA",
    "byte access to the accumulator: the byte processor has none": "CAW CAD",
    "it changes the low byte of ACCU1 alone: the IL's words have no byte arithmetic":
        "INC DEC",
    "accumulator moves: the byte processor has no exchange, two accumulators":
        "TAK PUSH POP ENT LEAVE",
    "address registers: the bit and byte processors address directly":
        "LAR1 LAR2 TAR1 TAR2 CAR +AR1 +AR2",
    "data block registers: known statically (`OPN DB n`), not kept; instance DBs "
    "are inlined": "OPN CDB",
    "master control relay: every assignment would depend on it": "MCR( )MCR MCRA MCRD",
}
UNSUPPORTED_WHY = {m: why for why, names in _WHY.items() for m in names.split()}
REGISTER_REASONS = {
    "BR": "BR is read by A/O/X and SPBI/SPBIN, written by SAVE, SPBB, SPBNB",
    "BIE": "BR is read by U/O/X and SPBI/SPBIN, written by SAVE, SPBB, SPBNB",
    "OV": "OV is read by U/O/X and SPO (JO) only",
    "OS": "OS is read by U/O/X and SPS (JOS) only",
    "STW": "only the RLO and /FC exist here, /FC known statically",
    "DB register": "the DB registers are known statically, not kept",
    "address register": "the bit and byte processors address directly"}
END_LABEL = "OB1.END"        # the appended END; no S7 label can be spelt so
# OB 100 (docs/s7.md, "OB 100: the startup"): translated after OB 1's END as the
# startup part, which the first hardware scan runs (and only it: a marker bit the
# translation keeps, set at the part's end, guards it); the runner does not trace
# that scan (Program.startup_scans).  Its labels are prefixed `OB100.`.
STARTUP_LABEL = "OB100"
STARTUP_END = "OB100.END"

# Blocks (docs/s7.md, "Blocks and calls")
BLOCK_HEADS = {"ORGANIZATION_BLOCK": "OB", "FUNCTION": "FC", "FUNCTION_BLOCK": "FB",
               "DATA_BLOCK": "DB"}
BLOCK_ENDS = {"OB": "END_ORGANIZATION_BLOCK", "FC": "END_FUNCTION",
              "FB": "END_FUNCTION_BLOCK", "DB": "END_DATA_BLOCK"}
SECTIONS = {"VAR_INPUT": "IN", "VAR_OUTPUT": "OUT", "VAR_IN_OUT": "IN_OUT",
            "VAR": "STAT", "VAR_TEMP": "TEMP"}
BLOCK_SECTIONS = {"OB": ("TEMP",), "FC": ("IN", "OUT", "IN_OUT", "TEMP"),
                  "FB": ("IN", "OUT", "IN_OUT", "STAT", "TEMP"), "DB": ()}
PARAMETERS = ("IN", "OUT", "IN_OUT")
LOCAL_TYPES = ("BOOL", "INT", "WORD")
WRITES = ("=", "S", "R", "FP", "FN", "T")    # statements that write their operand
# The marker region the front end keeps for block-local data (FB instances, TEMPs,
# the RLO saved around a call's copies): bits from M 192.0 up to M 223.7, words
# MW 128, 130, ... MW 190 (S7 bytes 128..191); the timers' scratch bits are above it
# (M 255.7 down).  A program with such data may not use M bytes 128..223 itself.
LOCAL_BYTES = (128, 224)
LOCAL_BIT_BASE, LOCAL_BIT_END = 192 * 8, 224 * 8
LOCAL_WORD_BASE, LOCAL_WORD_END = 128, 192


@dataclass
class Decl:
    """One declaration of a block's interface: `name : TYPE [:= value];`."""

    name: str
    section: str        # IN OUT IN_OUT STAT TEMP
    type: str           # upper case: BOOL INT WORD, or any other (rejected when used)
    line: int
    col: int


@dataclass(eq=False)
class Block:
    kind: str           # OB FC FB DB
    number: int
    line: int
    col: int
    decls: dict[str, Decl] = field(default_factory=dict)   # upper-case name ->
    stmts: list = field(default_factory=list)
    instance_of: int | None = None      # a DB: the FB it is an instance of
    begin: int = 0
    end: int = 0                        # the line of its END_... statement

    @property
    def name(self) -> str:
        return f"{self.kind} {self.number}"


@dataclass
class CallInfo:
    """`CALL FC n (p := a, ...)`, `CALL FB n, DB m (...)`, `UC FC n`, `CC FC n`."""

    kind: str
    number: int
    db: int | None
    params: list        # [(name Word, [actual Words])]


@dataclass
class Binding:
    """What a `#name` of a block stands for where it is inlined: the words of an
    address (`E 0.0`, a marker the front end allocated) or of a constant."""

    words: list | None = None
    const: bool = False         # a constant (awlsim copies it; writing it is an error)
    boolean: str | None = None  # TRUE / FALSE
    copy: bool = False          # awlsim passes a copy (an FB's instance data, a
                                # constant): an FC writing it as an input differs
    decl: Decl | None = None
    cell: tuple | None = None   # the key of a block-local cell, allocated on first use


# --------------------------------------------------------------------------------------
# Statements of the block body
# --------------------------------------------------------------------------------------

@dataclass
class Word:
    text: str
    col: int            # 1-based
    shown: str = ""     # how messages name it (a symbol: `"Motor"` for `A4.0`)
    local: bool = False  # a marker the front end allocated for a block-local variable
    line: int = 0       # a CALL's parameter on a line of its own: that line (else 0)


@dataclass(eq=False)
class Stmt:
    """One statement: labels, the mnemonic as written, the operand words.  (Compared
    by identity: an FC inlined twice gives equal copies at different places.)"""

    line: int
    col: int
    source: str
    mnemonic: Word
    operands: list[Word]
    labels: list[Word] = field(default_factory=list)
    canon: str = ""     # canonical (English) mnemonic, once the language is known
    extra: object = None  # CALL: its CallInfo; @CALL/@END: the copies; @RET: the label
    callee: str = ""    # @CALL: the called block's name (its TEMPs start undefined)


_CALL_START = re.compile(r"\s*(?:[A-Za-z_]\w*\s*:(?!=)\s*)*(CALL|UC|CC)\b", re.I)
_CALL_STMT = re.compile(r"\s*(CALL|UC|CC)\s+(.*?)\s*$", re.I | re.S)
_CALLEE = re.compile(r"(FC|FB)\s*(\d+)\s*(?:,\s*(DB)\s*(\d+))?\s*(\((.*)\))?", re.I | re.S)
_PARAM = re.compile(r"\s*([A-Za-z_]\w*)\s*:=\s*(.*?)\s*", re.S)
# one parameter a line after a CALL without parentheses, as STEP 7's STL editor shows
# a call (`CALL FB 10, DB 10` / `Start :=E 0.0` / ...): read as `CALL ... (Start := ...)`
_PARAM_LINE = re.compile(r'\s*[A-Za-z_]\w*\s*:=\s*(?:"[^"]*"|[^\s;(),"][^;(),"]*?)\s*;?\s*')
_DECL = re.compile(r"\s*([A-Za-z_]\w*)\s*(?:\{[^}]*\}\s*)?:\s*([^:;]+?)\s*"
                   r"(?::=\s*([^;]+?))?\s*;?\s*$")
_TOKEN = re.compile(r'"[^"]*"|\(|\)|[^\s()"]+')
_LABEL = re.compile(r"\s*([A-Za-z_][A-Za-z0-9_]*)\s*:(?!=)")


def _strip_comment(text: str) -> str:
    """The line without its `//` comment (a `//` inside quotes does not count)."""
    quoted = False
    for i, ch in enumerate(text):
        if ch == '"':
            quoted = not quoted
        elif not quoted and text.startswith("//", i):
            return text[:i]
    return text


def _initial(value: str) -> int | None:
    """The number of an initial value (FALSE 0, TRUE 1, INT, W#16#/16#/B#16#), or
    None if it is none of them."""
    v = value.strip().upper()
    if v in ("FALSE", "TRUE"):
        return int(v == "TRUE")
    prefix, _, digits = v.rpartition("#")
    try:
        return int(digits, 16 if prefix in ("W#16", "16", "B#16") else
                   2 if prefix in ("2", "W#2", "B#2") else 10) if prefix in (
            "", "W#16", "16", "B#16", "2", "W#2", "B#2") else None
    except ValueError:
        return None


def _joined(pieces: list[tuple[int, int, str]], sep: str) -> tuple[str, list]:
    """Pieces (line, column of its first character, text) joined by `sep`: the text
    and the (line, column) of each of its characters."""
    text, where = [], []
    for k, (line, col, piece) in enumerate(pieces):
        if k:
            text.append(sep)
            before = pieces[k - 1]
            where += [(before[0], before[1] + len(before[2]))] * len(sep)
        text.append(piece)
        where += [(line, col + i) for i in range(len(piece))]
    return "".join(text), where


def _split_statements(text: str, sep: str = ";") -> list[tuple[int, str]]:
    """(offset, piece) for the `;`-separated pieces of a line, or the `,`-separated
    ones of a parameter list (quotes respected)."""
    pieces, start, quoted = [], 0, False
    for i, ch in enumerate(text):
        if ch == '"':
            quoted = not quoted
        elif ch == sep and not quoted:
            pieces.append((start, text[start:i]))
            start = i + 1
    pieces.append((start, text[start:]))
    return pieces


# --------------------------------------------------------------------------------------
# The front end
# --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Known:
    """An accumulator whose value the compiler knows: the 16-bit pattern S7 holds
    (`value`, signed), and what it means to a timer (`s5t_ms`, from `S5T#`) or a
    counter (`count`, from `C#`)."""

    value: int
    s5t_ms: int | None = None
    count: int | None = None
    il_value: int | None = None     # the IL's accumulator holds this instead (a
                                    # timer's preset in ms, a counter's binary count)


ANY = "defined"         # an accumulator loaded in this scan, value not known; the IL
                        # holds INT(S7's value) sign-extended (S7's high word may differ)
DINT = "dint"           # loaded, the IL's 32 bits are S7's (L#, MD, +D ..., ITD)
WIDE = "wide"           # loaded, the IL's 32 bits neither S7's nor a sign-extended INT
CLOBBERED = "clobbered"  # changed by this translation where S7 leaves it alone
TOP = "top"             # not known yet (a label reached only by a later jump)


@dataclass(frozen=True)
class ChangedBy:
    """ACCU2 changed by the translation of one in-place statement (`+ n`, NEGI,
    INVI) where S7 leaves it alone: as CLOBBERED, but messages name the statement."""

    what: str


def _meet(a, b):
    if a == TOP:
        return b
    if b == TOP or a == b:
        return a
    if a is None or b is None:
        return None
    if CLOBBERED in (a, b) or any(isinstance(v, Known) and v.il_value is not None
                                  or isinstance(v, ChangedBy) for v in (a, b)):
        return CLOBBERED
    if DINT in (a, b) or WIDE in (a, b):       # one path may hold more than an INT
        return WIDE
    return ANY


class _State:
    """What the compiler knows at a point of the statement sequence.

    ner: S7's /FC (0: the next combine loads).  orm: the OR bit's role — "none",
    "pending" (`O` seen, no AND term yet: S7's OR = /FC = RLO) or "term" (an IL
    `O(` is open around the AND term).  parens: the open S7 parentheses, innermost
    last, each (canonical opener, statement, virtual?, orm outside it); a virtual
    one was opened with /FC = 0 and has no IL parenthesis.
    """

    def __init__(self):
        self.ner = 0
        self.orm = "none"
        self.parens: list[tuple[str, Stmt, bool, str]] = []
        self.il_depth = 0
        self.need_set = False           # IL RLO must be made 1 (after SPB/SPBN/BEB)
        # ACCU1, ACCU2: None (S7: the previous scan's value; here: cleared), ANY,
        # CLOBBERED, TOP or a Known value
        self.acc: tuple = (None, None)
        # which of the IL's status bits are S7's (STATUS_BITS): CC 1 / CC 0 and OV
        # right after an arithmetic, compare, word logic or shift instruction, OS
        # from there on while every one that may change it is S7's own, until a
        # label or a translation that changes them
        self.cc_ok: frozenset = frozenset({"OS"})   # (S7 starts every OB with 0)

    def key(self) -> tuple:
        return (self.ner, self.orm, len(self.parens))


class StlFrontEnd:
    def __init__(self, path: str, text: str, config: Config = DEFAULT,
                 mnemonics: str | None = None, symbols: str | None = None):
        self.path = path
        self.config = config
        self.lines = text.split("\n")
        self.forced = mnemonics
        self.lang = mnemonics or "de"
        self.stmts: list[Stmt] = []
        self.temps: dict[str, int] = {}
        self.symbol_path = symbols
        self.symbol_table: dict[str, Symbol] = {}
        self.db_fields: dict[int, list] = {}   # a global DB's fields (Global data blocks)
        self.db_used: dict[int, dict] = {}     # the DBs operands use: their layouts

    # -- errors --------------------------------------------------------------------

    def error(self, line: int, col: int, message: str) -> SourceError:
        text = self.lines[line - 1] if 1 <= line <= len(self.lines) else ""
        return SourceError(self.path, line, col, message, text)

    def unsupported(self, stmt: Stmt, what: str, col: int | None = None) -> SourceError:
        return self.error(stmt.line, col or stmt.mnemonic.col, f"unsupported: {what}")

    # -- block structure -------------------------------------------------------------

    def parse(self) -> Program:
        self.read_blocks()
        self.detect_language()
        self.resolve_symbols()
        for stmt in self.stmts:
            self.canonical(stmt)
        self.expand_calls()
        self.init_data_blocks()
        self.prepare_timers()
        self.check_db_region()
        program = self.translate()
        self.check_temps()
        program.symbols = self.symbol_operands()
        program.startup_scans = 1 if self.startup else 0
        return program

    # -- TEMPs: written before they are read -----------------------------------------

    def check_temps(self) -> None:
        """S7 leaves a block's TEMPs undefined at its start (the L stack holds what
        an earlier block left there; awlsim: the stack's last contents, 0 at first);
        here a TEMP is a marker that keeps its value from the last call.  So a TEMP
        read where some path from its block's start has not written it is rejected
        (docs/s7.md, "Blocks and calls").  A must analysis over the inlined program:
        the set of TEMP markers written on every path, the states at the labels
        iterated to their fixed point (they only shrink).  `=` and `T` write; `S`/`R`
        write only when the RLO is 1, so not for sure; `FP`/`FN` and everything else
        that names a TEMP read it; an FB's copies read the actuals in and write them
        out; an FC's parameters are the actuals themselves (its reads and writes of
        them are the caller's); a CALL starts the callee's TEMPs unwritten."""
        owner: dict[str, tuple[Block, Decl]] = {}
        for block in self.blocks.values():
            for key, decl in block.decls.items():
                word = self.cells.get((block.name, "TEMP", key))
                if decl.section == "TEMP" and word is not None:
                    owner[word.text.upper()] = (block, decl)
        if not owner:
            return
        temps: dict[str, frozenset] = {}
        for text, (block, _) in owner.items():
            temps[block.name] = temps.get(block.name, frozenset()) | {text}

        def meet(a, b):
            return b if a is None else a if b is None else a & b

        def temp_words(words):
            return [w for w in words or [] if w.local and w.text.upper() in owner]

        at: dict[str, frozenset] = {}       # label -> written on every path there
        while True:
            changed, errors = False, []
            state, entries = frozenset(), None      # OB 1's start: none written

            def reads(stmt: Stmt, words) -> None:
                errors.extend((stmt, w) for w in temp_words(words)
                              if w.text.upper() not in state)

            def jump(label: str) -> None:
                nonlocal changed
                new = meet(at.get(label.upper()), state)
                changed |= new != at.get(label.upper())
                at[label.upper()] = new

            for stmt in self.stmts:
                m = stmt.canon
                if m == "@STARTUP":                 # OB 100 starts: none written
                    state, entries = frozenset(), None
                    continue
                if stmt.labels:
                    entries = None
                    for w in stmt.labels:
                        state = meet(state, at.get(w.text.upper()))
                elif state is None and entries is not None and m == "JU":
                    state = entries                 # an entry of a jump list
                if state is None or not stmt.mnemonic.text:
                    continue                        # not reached
                if m == "@CALL":
                    for _, src, _ in stmt.extra:
                        reads(self.param_stmt(stmt, src[0]) if src else stmt, src)
                    state -= temps.get(stmt.callee, frozenset())
                elif m == "@END":
                    state |= {w.text.upper() for _, _, dst in stmt.extra
                              for w in temp_words(dst)}
                elif m in ("=", "T"):
                    state |= {w.text.upper() for w in temp_words(stmt.operands)}
                elif m not in ("S", "R") and not self.is_jump(stmt):
                    reads(stmt, stmt.operands)
                if m in ("JC", "JCN", "LOOP"):
                    jump(stmt.operands[0].text)
                elif m == "JL":
                    jump(stmt.operands[0].text)
                    state, entries = None, state
                elif m == "JU":
                    jump(stmt.operands[0].text)
                    state = None
                elif m == "@RET":
                    jump(stmt.extra)
                    state = None
                elif m in ("BE", "BEU", "@STARTED"):
                    state = None
            if not changed:
                break
        if errors:
            stmt, w = errors[0]
            block, decl = owner[w.text.upper()]
            name = f"#{decl.name}"
            via = w.shown.split(" = ")[0] if w.shown else name
            through = f" (as `{via}`)" if via.upper() != name.upper() else ""
            start = (f"; {block.name}'s start information is not provided here"
                     if block.kind == "OB" and decl.name.upper().startswith(
                         f"OB{block.number}_") else "")
            raise self.error(stmt.line, w.col, f"unsupported: TEMP `{name}` of "
                             f"{block.name}{through} may be read before it is written "
                             "(S7 leaves TEMPs undefined at the block's start; this CPU "
                             f"keeps the value of the block's last run, 0 at first{start})")

    # -- symbols -------------------------------------------------------------------

    def resolve_symbols(self) -> None:
        """`"Motor"` -> the address of the symbol table (--symbols), in the source's
        language; the operand keeps the symbol's name for messages."""
        if self.symbol_path is not None:
            self.symbol_table = read_symbol_table(self.symbol_path)
            self.table_lang = self.symbol_language()
        for stmt in self.stmts:
            if not stmt.operands or not stmt.operands[0].text.startswith('"'):
                continue
            if self.db_symbol(stmt):            # `"Data".count`: a global DB's field
                continue
            stmt.operands[0] = self.resolve_word(stmt, stmt.operands[0])

    def resolve_word(self, stmt: Stmt, word: Word) -> Word:
        """A quoted symbol -> its address (a Word that remembers the symbol)."""
        if True:
            name = word.text.strip('"')
            sym = self.symbol_table.get(name.upper())
            if sym is None:
                where = (f"not in the symbol table {self.symbol_path}" if
                         self.symbol_path else "no symbol table: --symbols FILE")
                raise self.error(stmt.line, word.col,
                                 f"undeclared symbol `{word.text}` ({where})"
                                 + did_you_mean(name, [s.name for s in
                                                       self.symbol_table.values()]))
            address = self.symbol_address(sym)
            if address is None:
                raise self.unsupported(stmt, f"symbol `{word.text}` is `{sym.address}` "
                                       f"({self.symbol_path}:{sym.line}), not an "
                                       "address of this slice", word.col)
            return Word(address, word.col, f"{word.text} = {sym.address}")

    def symbol_language(self) -> str:
        """The table's mnemonics: from its German-only or English-only areas (a table
        with neither means the same in both: the source's)."""
        first = None
        for sym in self.symbol_table.values():
            area = _split_area(sym.address.replace(" ", ""))[0]
            langs = AREA_TABLE.get(area, {})
            if len(langs) != 1:
                continue
            lang = next(iter(langs))
            if first is None:
                first = (lang, sym)
            elif lang != first[0]:
                raise SourceError(self.symbol_path, sym.line, 1,
                                  f"mixed mnemonics: `{sym.address}` is "
                                  f"{LANGUAGE_NAME[lang]}, but this symbol table is "
                                  f"{LANGUAGE_NAME[first[0]]} (`{first[1].address}` at "
                                  f"line {first[1].line})")
        return first[0] if first else self.lang

    def symbol_address(self, sym: Symbol) -> str | None:
        """The symbol's address spelt in the source's language ("E0.0"), or None
        for what is not an address (FC 1, DB 1, VAT 1 ...)."""
        area, rest = _split_area(sym.address.replace(" ", ""))
        canon = AREA_TABLE.get(area, {}).get(self.table_lang)
        if canon is None or not rest:
            return None
        spelt = {c: a for a, c in _AREAS_DE.items()}.get(canon, canon) \
            if self.lang == "de" else canon
        return spelt + rest

    def symbol_operands(self) -> dict[str, Operand]:
        """The table's symbols that name an address this CPU has, for --watch and
        stimuli: {upper-case name: Operand}."""
        out = {}
        for key, sym in self.symbol_table.items():
            area, rest = _split_area(sym.address.replace(" ", ""))
            canon = AREA_TABLE.get(area, {}).get(self.table_lang)
            try:
                if canon in BIT_AREAS:
                    byte, bit = (int(x) for x in rest.split("."))
                    if bit > 7 or byte >= self.config.area_size(canon):
                        continue
                    op = Operand("bit", area=canon, byte=byte, bit=bit, text=sym.name)
                elif canon in ("IW", "QW", "MW", "T", "C"):
                    if int(rest) >= self.config.area_size(canon):
                        continue
                    op = Operand("index", area=canon, index=int(rest), text=sym.name)
                else:
                    continue
            except ValueError:
                continue
            out[key] = op
        return out

    # -- blocks and calls: inlining ------------------------------------------------

    def expand_calls(self) -> None:
        """Replace every call by the called block's statements (docs/s7.md, "Blocks
        and calls"): its `#name`s bound to the actual operands (FC), to markers of
        the instance DB (FB) or of the block's TEMPs; its labels renamed, its block
        ends made jumps to the end of the inlined body.  Pseudo-statements carry
        what S7's CALL does: @CALL (/FC = 0, OR = 0, an FB's inputs copied in),
        @LEAVE (the block end: /FC = 0, OR = 0), @END (an FB's outputs copied out,
        the label the block's BEA/BEB jump to), @RET (BEA/BE)."""
        self.cells: dict[tuple, Word] = {}
        self.first_local: tuple[Stmt, tuple] | None = None   # who opened the region
        self.local_bits = 0
        self.local_words = 0
        self.inlined = 0
        ob1 = self.blocks[("OB", 1)]
        scope = {"block": ob1, "prefix": "", "bindings": self.temp_bindings(ob1),
                 "ret": None, "returns": False}
        self.stmts = self.expand(ob1.stmts, scope, [ob1])
        ob100 = self.blocks.get(("OB", 100))
        self.startup = ob100 is not None
        if ob100 is not None:               # the startup part, after OB 1 (translate)
            scope = {"block": ob100, "prefix": STARTUP_LABEL, "ret": STARTUP_END,
                     "bindings": self.temp_bindings(ob100), "returns": False}
            body = self.expand(ob100.stmts, scope, [ob100])

            def mark(line: int, canon: str, labels: list[Word]) -> Stmt:
                source = self.lines[line - 1].rstrip("\r")
                col = len(source) - len(source.lstrip()) + 1
                return Stmt(line, col, source, Word(source.split()[0], col), [], labels,
                            canon)
            self.stmts += [mark(ob100.line, "@STARTUP", [])] + body + [
                mark(ob100.end, "@STARTED", [Word(STARTUP_END, 1)])]

    def temp_bindings(self, block: Block) -> dict[str, Binding]:
        return {key: Binding(decl=d, cell=(block.name, "TEMP", key))
                for key, d in block.decls.items() if d.section == "TEMP"}

    def cell(self, stmt: Stmt, binding: Binding, col: int) -> list[Word]:
        """The marker of a block-local variable, allocated on its first use."""
        decl = binding.decl
        if binding.cell in self.cells:
            return [self.cells[binding.cell]]
        if decl.type not in LOCAL_TYPES:
            raise self.error(stmt.line, col, f"unsupported: `#{decl.name}` of type "
                             f"{decl.type} (block-local data of this slice: BOOL, INT, "
                             "WORD)")
        bit = decl.type == "BOOL"
        used = self.local_bits if bit else self.local_words
        k = LOCAL_BIT_BASE + used if bit else LOCAL_WORD_BASE + 2 * used
        if k >= (LOCAL_BIT_END if bit else LOCAL_WORD_END):
            raise self.unsupported(stmt, f"more than {used} block-local "
                                   + ("bits (M 192.0 .. M 223.7)" if bit else
                                      "words (MW 128 .. MW 190)"))
        if bit:
            self.local_bits += 1
        else:
            self.local_words += 1
        text = f"M{k // 8}.{k % 8}" if bit else f"MW{k}"
        word = Word(text, 0, "", True)
        self.cells[binding.cell] = word
        if self.first_local is None:
            self.first_local = (stmt, binding.cell)
        return [word]

    def bound_words(self, stmt: Stmt, word: Word, scope: dict) -> tuple[Binding,
                                                                         list[Word]]:
        """`#name` in `stmt` -> (its binding, the words it stands for)."""
        name = word.text[1:]
        if re.search(r"[.\[]", name):
            raise self.error(stmt.line, word.col, f"unsupported: STRUCT/ARRAY member "
                             f"`{word.text}` (block-local data of this slice: BOOL, "
                             "INT, WORD)")
        binding = scope["bindings"].get(name.upper())
        if binding is None:
            block = scope["block"]
            raise self.error(stmt.line, word.col, f"undeclared local `{word.text}` (not "
                             f"declared in {block.name})")
        if binding.boolean is not None:
            raise self.error(stmt.line, word.col, f"unsupported: `{word.text}` bound to "
                             f"the constant {binding.boolean} (no bit constant here)")
        words = binding.words if binding.cell is None else self.cell(stmt, binding,
                                                                     word.col)
        shown = f"{word.text} = {' '.join(w.shown or w.text for w in words)}" \
            if binding.cell is None else word.text
        out = [Word(w.text, word.col, shown if i == 0 else "", w.local, word.line)
               for i, w in enumerate(words)]
        return binding, out

    def expand(self, stmts: list[Stmt], scope: dict, stack: list[Block]) -> list[Stmt]:
        out: list[Stmt] = []
        prefix = scope["prefix"]
        registers = self.db_registers(stmts, scope)
        for stmt, register in zip(stmts, registers):
            stmt = self.db_operands(stmt, register)
            labels = [Word(f"{prefix}.{w.text}" if prefix else w.text, w.col)
                      for w in stmt.labels]
            if self.is_jump(stmt):
                for w in stmt.operands:     # the labels the translation makes have a
                    if "." in w.text:       # `.` (OB100.END, FC1.0.M1): none of them
                        raise self.error(stmt.line, w.col, f"unknown label `{w.text}`")
            if stmt.canon in ("CALL", "UC", "CC"):
                out += self.inline(stmt, labels, scope, stack)
                continue
            operands = []
            for w in stmt.operands:
                if self.is_jump(stmt) and prefix:
                    operands.append(Word(f"{prefix}.{w.text}", w.col, w.shown or w.text))
                elif w.text.startswith("#"):
                    binding, words = self.bound_words(stmt, w, scope)
                    if stmt.canon in WRITES and binding.const:
                        raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` writes "
                                               f"`{w.text}`, which is bound to a "
                                               "constant", w.col)
                    if stmt.canon in WRITES and binding.copy and binding.decl and \
                            binding.decl.section == "IN" and binding.cell is None:
                        raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` writes the "
                                               f"input `{w.text}`, whose actual S7 "
                                               "passes as a copy (a constant or an "
                                               "FB's instance data)", w.col)
                    operands += words
                else:
                    operands.append(w)
            new = Stmt(stmt.line, stmt.col, stmt.source, stmt.mnemonic, operands, labels,
                       stmt.canon)
            if scope["ret"] is not None and stmt.canon in ("BE", "BEU", "BEC"):
                self.no_operand(stmt)
                scope["returns"] = True
                if stmt.canon == "BEC":         # BEB: SPB to the block end
                    new.canon, new.operands = "JC", [Word(scope["ret"], stmt.col)]
                else:
                    new.canon, new.extra = "@RET", scope["ret"]
            out.append(new)
        return out

    def inline(self, stmt: Stmt, labels: list[Word], scope: dict,
               stack: list[Block]) -> list[Stmt]:
        info: CallInfo = stmt.extra
        m = stmt.canon
        if info is None:                    # `UC` alone: the call pattern did not match
            raise self.error(stmt.line, stmt.mnemonic.col,
                             f"missing operand: `{stmt.mnemonic.text}` needs a block")
        written = f"{stmt.mnemonic.text} {info.kind} {info.number}"
        callee = self.blocks.get((info.kind, info.number))
        if callee is None:
            raise self.error(stmt.line, stmt.col, f"`{written}`: {info.kind} "
                             f"{info.number} is not in the source")
        if callee in stack:
            chain = " -> ".join(b.name for b in stack[stack.index(callee):] + [callee])
            raise self.unsupported(stmt, f"`{written}` is a recursive call ({chain}): "
                                   "calls are inlined, and recursion cannot be")
        params = [d for d in callee.decls.values() if d.section in PARAMETERS]
        if m in ("UC", "CC"):
            if info.kind == "FB":
                raise self.unsupported(stmt, f"`{written}` (UC/CC of an FB: its instance "
                                       "DB would be the open DI; use CALL FB n, DB m)")
            if params or info.params or info.db is not None:
                raise self.unsupported(stmt, f"`{written}`: UC/CC pass no parameters, "
                                       f"and {callee.name} has some (use CALL)")
        if info.kind == "FB" and info.db is None:
            raise self.error(stmt.line, stmt.col, f"`{written}` needs an instance DB: "
                             f"CALL FB {info.number}, DB m")
        if info.kind == "FC" and info.db is not None:
            raise self.error(stmt.line, stmt.col, f"`{written}`: an FC has no instance "
                             "DB")
        if info.kind == "FB":
            db = self.blocks.get(("DB", info.db))
            if db is None or db.instance_of != info.number:
                what = "is not in the source" if db is None else \
                    f"is not an instance DB of FB {info.number}"
                raise self.error(stmt.line, stmt.col, f"`{written}, DB {info.db}`: DB "
                                 f"{info.db} {what}")
        self.inlined += 1
        prefix = f"{info.kind}{info.number}.{self.inlined}"
        given: dict[str, tuple[Word, Binding]] = {}
        for name, actual in info.params:
            at = self.param_stmt(stmt, name)     # errors name the parameter's line
            decl = callee.decls.get(name.text.upper())
            if decl is None or decl.section not in PARAMETERS:
                raise self.error(at.line, name.col, f"`{name.text}` is not a parameter "
                                 f"of {callee.name}")
            if name.text.upper() in given:
                raise self.error(at.line, name.col, f"parameter `{name.text}` given "
                                 "twice")
            if not actual:
                raise self.error(at.line, name.col, f"missing actual for "
                                 f"`{name.text}`")
            given[name.text.upper()] = (name, self.actual(at, decl, actual, scope))
        bindings = self.temp_bindings(callee)
        copy_in, copy_out = [], []
        if info.kind == "FC":
            seen: dict[str, Word] = {}
            for decl in params:
                if decl.name.upper() not in given:
                    raise self.error(stmt.line, stmt.col, f"`{written}` without the "
                                     f"parameter `{decl.name}` (an FC needs all of them)")
                name, b = given[decl.name.upper()]
                if b.boolean is not None:
                    raise self.unsupported(self.param_stmt(stmt, name),
                                           f"`{name.text} := {b.boolean}`: a bit "
                                           "constant for an FC parameter", name.col)
                if b.copy and not b.const:
                    key = " ".join(w.text for w in b.words)
                    if key in seen:
                        raise self.unsupported(self.param_stmt(stmt, name),
                                               f"`{name.text}` and `{seen[key].text}` "
                                               "get the same instance variable, which "
                                               "S7 passes as two copies", name.col)
                    seen[key] = name
                bindings[decl.name.upper()] = Binding(b.words, b.const, None, b.copy,
                                                      decl)
        else:
            instance = f"DB {info.db}"
            for key, decl in callee.decls.items():
                if decl.section != "TEMP":
                    bindings[key] = Binding(decl=decl, cell=(instance, key), copy=True)
            for key, (name, b) in given.items():
                decl = callee.decls[key]
                field_words = self.cell(self.param_stmt(stmt, name), bindings[key],
                                        name.col)
                kind = "bit" if decl.type == "BOOL" else "word"
                if decl.section in ("IN", "IN_OUT"):
                    copy_in.append((b.boolean.lower() if b.boolean else kind, b.words,
                                    field_words))
                if decl.section in ("OUT", "IN_OUT"):
                    copy_out.append((kind, field_words, b.words))
        for name, b in given.values():
            decl = callee.decls[name.text.upper()]
            if decl.section != "IN" and (b.const or b.boolean):
                raise self.error(self.param_stmt(stmt, name).line, name.col,
                                 "a constant for the "
                                 f"{'output' if decl.section == 'OUT' else 'in/out'} "
                                 f"parameter `{name.text}`")
        inner = {"block": callee, "prefix": prefix, "bindings": bindings, "ret": prefix,
                 "returns": m == "CC"}
        body = self.expand(callee.stmts, inner, stack + [callee])
        where = (stmt.line, stmt.col, stmt.source, stmt.mnemonic)
        out = []
        if m == "CC":                   # S7: called when RLO = 1; RLO := 1 either way
            out.append(Stmt(*where, [Word(prefix, stmt.col)], labels, "JCN"))
            labels = []
        out.append(Stmt(*where, [], labels, "@CALL", copy_in, callee.name))
        out += body
        out.append(Stmt(*where, [], [], "@LEAVE"))
        out.append(Stmt(*where, [], [Word(prefix, stmt.col)] if inner["returns"] else [],
                        "@END", copy_out))
        return out

    def param_stmt(self, stmt: Stmt, name: Word) -> Stmt:
        """`stmt` (a CALL), or for a parameter on a line of its own a copy at that
        line, so that messages about the parameter point at it."""
        if not name.line or name.line == stmt.line:
            return stmt
        return Stmt(name.line, stmt.col, self.lines[name.line - 1].rstrip("\r"),
                    stmt.mnemonic, [], [], stmt.canon, stmt.extra)

    def actual(self, stmt: Stmt, decl: Decl, words: list[Word], scope: dict) -> Binding:
        """The actual operand of a parameter: an address, a constant, TRUE/FALSE, a
        symbol or a `#name` of the calling block."""
        first = words[0]
        up = first.text.upper()
        if decl.type not in LOCAL_TYPES:
            raise self.error(stmt.line, first.col, f"unsupported: parameter "
                             f"`{decl.name}` of type {decl.type} (parameters of this "
                             "slice: BOOL, INT, WORD)")
        joined = "".join(w.text for w in words)
        if re.match(r"DB\d+\.|DB[XBWD]\d", joined, re.I) or first.text.startswith(
                '"') and len(words) > 1 and words[1].text.startswith("."):
            shown = " ".join(w.text for w in words).replace('" .', '".')
            raise self.unsupported(stmt, f"DB field `{shown}` as a CALL actual",
                                   first.col)
        if first.text.startswith("#"):
            binding, out = self.bound_words(stmt, first, scope)
            if len(words) > 1:
                raise self.error(stmt.line, words[1].col, f"extra operand "
                                 f"`{words[1].text}`")
            return Binding(out, binding.const, None, binding.copy)
        if first.text.startswith('"'):
            resolved = [self.resolve_word(stmt, first)] + words[1:]
            self.check_width(stmt, decl, resolved)
            return Binding(resolved)
        if up in ("TRUE", "FALSE"):
            if decl.type != "BOOL":
                raise self.error(stmt.line, first.col, f"operand of the wrong kind: "
                                 f"`{decl.name}` is {decl.type}, not `{first.text}`")
            return Binding(None, True, up, True)
        bit = "." in first.text or len(words) > 1 and "." in words[1].text
        const = up[0].isdigit() or up[0] in "+-" or "#" in up
        if (decl.type == "BOOL") != (bit and not const):
            raise self.error(stmt.line, first.col, f"operand of the wrong kind: "
                             f"`{decl.name}` is {decl.type}, not "
                             f"`{' '.join(w.text for w in words)}`")
        self.check_width(stmt, decl, words)
        return Binding(words, const, None, const)

    def check_width(self, stmt: Stmt, decl: Decl, words: list[Word]) -> None:
        """An INT/WORD parameter takes 16 bits: a double word or a 32-bit constant is
        the wrong kind (as in STEP 7 and awlsim, which reject the type mismatch)."""
        if decl.type not in ("INT", "WORD"):
            return
        first = words[0]
        area, _ = _split_area("".join(w.text for w in words[:2]))
        canon = AREA_TABLE.get(area.upper(), {}).get(self.lang, "")
        up = "".join(w.text for w in words).upper()
        const = up[:1].isdigit() or up[:1] in "+-" or "#" in up
        wide = canon in ("MD", "ID", "QD", "PID", "PQD", "DBD", "DID", "LD") or const \
            and self.dint_constant(stmt, Word(up, first.col)) is not None
        if wide:
            raise self.error(stmt.line, first.col, f"operand of the wrong kind: "
                             f"`{decl.name}` is {decl.type} (16 bits), not the 32-bit "
                             f"`{' '.join(w.text for w in words)}`")

    def used_operands(self, stmt: Stmt):
        """The operand word lists a statement uses: its own and, for a block call's
        copies in and out, each copy's two sides (not the block's own locals, not a
        jump's label)."""
        if self.is_jump(stmt):
            return
        for ops in [stmt.operands] + [w for c in (stmt.extra if stmt.canon in (
                "@CALL", "@END") else []) for w in (c[1] or [], c[2])]:
            if ops and not ops[0].local:
                yield ops

    def check_local_region(self) -> None:
        """The program's own operands stay out of the region the block-local data
        lives in (M bytes 128..223), once there is such data."""
        if not self.cells:
            return
        for stmt, ops, lo, hi in self.marker_uses():
            if lo < LOCAL_BYTES[1] and hi >= LOCAL_BYTES[0]:
                shown = ops[0].shown or " ".join(w.text for w in ops[:2])
                raise self.unsupported(self.param_stmt(stmt, ops[0]),
                                       f"`{shown}` is in M {LOCAL_BYTES[0]} .. "
                                       f"M {LOCAL_BYTES[1] - 1}, which this program's "
                                       "block-local data (FB instances, TEMPs) uses"
                                       + self.first_local_user(), ops[0].col)

    def first_local_user(self) -> str:
        """What put the first cell into the block-local region, for the message above
        (a program without FBs or TEMPs opens it with an `SPL`, `LC` or `LOOP`)."""
        stmt, key = self.first_local
        if key[0] == "@":
            return (f" (first: the translation of `{stmt.mnemonic.text}` at line "
                    f"{stmt.line} keeps a scratch cell there)")
        return f" (first: `#{key[-1]}` of {key[0]}, line {stmt.line})"

    def marker_uses(self):
        """(statement, operand words, first byte, last byte) of every marker bit or
        word the program's own statements use."""
        for stmt in self.stmts:
            for ops in self.used_operands(stmt):
                text = "".join(w.text for w in ops[:2]).upper()
                area, rest = _split_area(text)
                canon = AREA_TABLE.get(area, {}).get(self.lang)
                lo = hi = None
                if canon == "M" and re.fullmatch(r"\d+\.\d", rest):
                    lo = hi = int(rest.split(".")[0])
                elif canon == "MW" and rest.isdigit():
                    lo, hi = int(rest), int(rest) + 1
                elif canon == "MD" and rest.isdigit():     # bytes n..n+3
                    lo, hi = int(rest), int(rest) + 3
                if lo is not None:
                    yield stmt, ops, lo, hi

    def local_bit(self, stmt: Stmt, key: tuple) -> Operand:
        """A bit of the block-local region the translation keeps for itself."""
        word = self.cell(stmt, Binding(decl=Decl(key[1], "TEMP", "BOOL", 0, 0),
                                       cell=key), stmt.col)[0]
        byte, bit = word.text[1:].split(".")
        return Operand("bit", area="M", byte=int(byte), bit=int(bit), text=word.text)

    def outside_label(self, stmt: Stmt, st: _State) -> str:
        """The label of `SPL` / `LOOP`, which may not stand inside a parenthesis or
        after `O` (their translation saves and restores the IL's RLO)."""
        label = self.label_operand(stmt)
        if label not in self.label_defs:
            raise self.error(stmt.line, stmt.operands[0].col,
                             f"unknown label `{stmt.operands[0].shown or stmt.operands[0].text}`")
        if st.parens or st.orm != "none":
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` inside parentheses or "
                                   "after `O`")
        return label

    def jump_list(self, stmt: Stmt, st: _State, edges) -> bool:
        """SPL (JL) l with its list of SPA (JU) up to the label l: S7 jumps to the
        k-th SPA for k = ACCU1's low byte below the list's length, else to l, and
        changes no status bit.  The IL has no computed jump, so this is a compare
        chain: the RLO saved, the low byte ((ACCU1 MOD 256 + 256) MOD 256, unless the
        compiler knows it is 0..255) in a local word, `L` it, `L k`, `==I`, `JC` to
        the k-th SPA, which restores the RLO; both accumulators count as changed."""
        label = self.outside_label(stmt, st)
        i = self.stmts.index(stmt)
        entries = []
        for entry in self.stmts[i + 1:]:
            if label in (w.text.upper() for w in entry.labels):
                break
            if entry.canon != "JU" or entry.labels:
                raise self.unsupported(entry, f"`{entry.mnemonic.text or 'a label'}` in "
                                       f"the jump list of `{stmt.mnemonic.text}` (line "
                                       f"{stmt.line}): only unlabelled "
                                       f"{'SPA' if self.lang == 'de' else 'JU'} up to "
                                       f"its label `{stmt.operands[0].text}`")
            entries.append(entry)
        else:
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text} "
                                   f"{stmt.operands[0].text}`: its label must end the "
                                   "jump list after it")
        if len(entries) > 255:
            raise self.unsupported(stmt, "a jump list of more than 255 entries")
        known = st.acc[0]
        self.read_acc(stmt, st, 1)
        rlo = self.local_bit(stmt, ("@", "RLO"))
        index = self.cell(stmt, Binding(decl=Decl("SPL", "TEMP", "INT", 0, 0),
                                        cell=("@", "SPL")), stmt.col)[0]
        index_op = Operand("index", area="MW", index=int(index.text[2:]),
                           text=index.text)

        def const(value: int) -> Operand:
            return Operand("const", area="INT", value=value, text=str(value))

        self.emit("=", rlo)
        if not (isinstance(known, Known) and known.il_value is None
                and 0 <= known.value <= 255):
            for mnem, op in (("L", const(256)), ("MOD", None), ("L", const(256)),
                             ("+I", None), ("L", const(256)), ("MOD", None)):
                self.emit(mnem, op)
        self.emit("T", index_op)
        for k, entry in enumerate(entries):
            entry.extra = f"JL{i}.{k}"
            self.emit("L", index_op)
            self.emit("L", const(k))
            self.emit("==I")
            self.emit("JC", Operand("label", label=entry.extra, text=entry.extra))
        st.acc = (CLOBBERED, CLOBBERED)
        self.emit("LD", rlo)
        edges[label].append((st.ner, stmt, "JU"))
        self.acc_edges[label].append(st.acc)
        st.cc_ok -= CC_OV                   # the compare chain changed them
        self.cc_edges[label].append(st.cc_ok)
        fix = self.assumed.get(label, (0, ""))[1]
        if fix and st.ner == 0:
            self.emit(fix)
        self.emit("JU", Operand("label", label=label, text=stmt.operands[0].text))
        return False

    def cc_jump(self, stmt: Stmt, st: _State, m: str, edges) -> bool:
        """SPZ SPN SPP SPM SPPZ SPMZ SPU (English JZ JN JP JM JPZ JMZ JUO) jump on
        CC 1 / CC 0, SPO (JO) on OV, SPS (JOS) on OS, and change no status bit but
        SPS's OS, 0 where it jumps (awlsim's insn_spz.py ... insn_sps.py).  Here, as
        `LOOP`: the RLO saved in a local bit, the condition read into the RLO (`LD
        ==0`; SPN: `LD >0`, `O <0`), `JCN` past the jump, the RLO restored on both
        paths; /FC and the accumulators pass unchanged."""
        label = self.outside_label(stmt, st)
        self.need_cc(stmt, st, {status_bit(c) for c in CC_JUMPS[m]})
        rlo = self.local_bit(stmt, ("@", "RLO"))
        skip = f"CCJ.{self.stmts.index(stmt)}"
        self.emit("=", rlo)
        first, *more = CC_JUMPS[m]
        self.emit(f"LD {first}")
        for cond in more:
            self.emit(f"O {cond}")
        if m != "JOS":
            return self.jump_and_restore(stmt, st, label, skip, rlo, edges)
        # SPS (JOS) clears OS where it jumps; the IL's stays: not S7's at the target
        kept = st.cc_ok
        st.cc_ok = kept - {"OS"}
        falls = self.jump_and_restore(stmt, st, label, skip, rlo, edges)
        st.cc_ok = kept                         # not taken: OS was 0 in both
        return falls

    def br_jump(self, stmt: Stmt, st: _State, m: str, edges) -> bool:
        """SPBI / SPBIN (JBI / JNBI) jump on BR = 1 / 0; S7 ends the logic string
        (OR 0, /FC 0) and keeps the RLO (awlsim's insn_spbi.py): the RLO saved in a
        local bit, BR read into the RLO, `JCN` past the jump, the RLO restored on
        both paths (jump_and_restore)."""
        if st.parens:
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` inside parentheses")
        self.close_term(st)                     # (a term after `O` ends here)
        label = self.outside_label(stmt, st)
        st.ner = 0
        rlo = self.local_bit(stmt, ("@", "RLO"))
        self.emit("=", rlo)
        self.emit("LD" if m == "JBI" else "LDN", self.scratch(("BR",)))
        return self.jump_and_restore(stmt, st, label, f"BRJ.{self.stmts.index(stmt)}",
                                     rlo, edges)

    def jump_and_restore(self, stmt: Stmt, st: _State, label: str, skip: str,
                         rlo: Operand, edges) -> bool:
        """The condition in the IL's RLO: `JCN skip`, then the saved RLO back and a
        jump to `label`, and at `skip` the saved RLO back (LOOP, SPZ ...)."""
        self.emit("JCN", Operand("label", label=skip, text=skip))
        self.emit("LD", rlo)
        edges[label].append((st.ner, stmt, "JU"))
        self.acc_edges[label].append(st.acc)
        self.cc_edges[label].append(st.cc_ok)
        fix = self.assumed.get(label, (0, ""))[1]
        if fix and st.ner == 0:
            self.emit(fix)                  # this path arrives with /FC = 0
        self.emit("JU", Operand("label", label=label, text=stmt.operands[0].text))
        self.pending.append(skip)
        self.emit("LD", rlo)
        return True

    def loop(self, stmt: Stmt, st: _State, edges) -> bool:
        """`LOOP l`: S7 decrements ACCU1-L (wrapping) and jumps to l while it is not
        0, changing no status bit and not ACCU2 (awlsim's insn_loop.py).  Here: the
        RLO saved in a local bit, `L 1`, `<>I` (x <> 1 is x - 1 <> 0), `-I`
        (ACCU1 = x - 1), `JCN` past the jump, the RLO restored on both paths.  /FC
        and the OR bit's role pass unchanged to both; ACCU2 then holds x where S7's
        is unchanged, so an instruction that reads it before the next load is
        rejected."""
        label = self.outside_label(stmt, st)
        self.read_acc(stmt, st, 1)
        rlo = self.local_bit(stmt, ("@", "RLO"))
        skip = f"LOOP.{self.stmts.index(stmt)}"
        self.emit("=", rlo)
        self.emit("L", Operand("const", area="INT", value=1, text="1"))
        self.emit("<>I")
        self.emit("-I")
        written = f"`{stmt.mnemonic.text} {stmt.operands[0].text}` (line {stmt.line})"
        st.acc = (ANY, None if st.acc[1] is None else ChangedBy(written))
        st.cc_ok = frozenset()              # <>I, -I changed them (-I may set OS)
        return self.jump_and_restore(stmt, st, label, skip, rlo, edges)

    def copy(self, stmt: Stmt, st: _State, pairs: list) -> None:
        """An FB call's parameters copied in or out: (kind, source words, target
        words), kind bit / word / true / false.  S7 copies without touching the RLO
        or the accumulators; here the RLO is saved around bit copies (unless the next
        statement overwrites it) and the accumulators count as changed."""
        if not pairs:
            return

        def tmp(mnemonic: str, words: list[Word]) -> Stmt:
            at = self.param_stmt(stmt, words[0])    # a parameter's own line
            return Stmt(at.line, stmt.col, stmt.source, Word(mnemonic, stmt.col),
                        words, canon=mnemonic)

        nxt = self.next_stmt(stmt)
        keep = any(kind != "word" for kind, _, _ in pairs) and nxt is not None and not (
            nxt.canon in COMBINE and nxt.operands or nxt.canon in OPEN
            or nxt.canon in ("SET", "CLR") + COMPARES + COMPARES_D)
        save_op = self.local_bit(stmt, ("@", "RLO")) if keep else None
        if keep:
            self.emit("=", save_op)
        for kind, src, dst in pairs:
            if kind == "word":
                op, _ = self.load_operand(tmp("L", src))
                self.emit("L", op)
                self.emit("T", self.word_operand(tmp("T", dst), ("QW", "MW")))
                st.acc = (CLOBBERED, CLOBBERED)
                continue
            if kind == "bit":
                self.emit("LD", self.bit_operand(tmp("A", src)))
            else:
                self.emit("SET" if kind == "true" else "CLR")
            self.emit("=", self.bit_operand(tmp("=", dst), ("Q", "M")))
        if keep:
            self.emit("LD", save_op)

    # -- timers --------------------------------------------------------------------

    def scratch(self, key: tuple) -> Operand:
        """A marker bit the translation keeps for itself (from the top of M down)."""
        if key not in self.scratch_bits:
            k = self.config.marker_bytes * 8 - 1 - len(self.scratch_bits)
            self.scratch_bits[key] = Operand("bit", area="M", byte=k // 8, bit=k % 8,
                                             text=f"M{k // 8}.{k % 8}")
        return self.scratch_bits[key]

    def check_scratch(self) -> None:
        """No statement of the source may use a marker bit the translation keeps,
        nor a word over one."""
        if not self.scratch_bits:
            return
        taken = {(op.byte, op.bit): op for op in self.scratch_bits.values()}
        started = "OB 100's started bit" if ("OB", 100) in self.blocks else \
            "the started bit of the startup part that sets the global DBs' initial values"
        purpose = {(op.byte, op.bit): started if key == ("started",)
                   else "this program's timers" for key, op in self.scratch_bits.items()}
        for stmt, ops in ((s, o) for s in self.stmts for o in self.used_operands(s)):
            text = "".join(w.text for w in ops[:2]).upper()
            area, rest = _split_area(text)
            canon = AREA_TABLE.get(area, {}).get(self.lang)
            hit = None
            if canon == "M" and re.fullmatch(r"\d+\.\d", rest):
                b, n = map(int, rest.split("."))
                hit = taken.get((b, n))
            elif canon == "MW" and rest.isdigit():
                hit = next((op for (b, _), op in sorted(taken.items(), reverse=True)
                            if b in (int(rest), int(rest) + 1)), None)
            if hit is not None:
                first = ops[0].text
                written = " ".join(w.text for w in ops[:2]) if \
                    _split_area(first)[1] == "" else first
                what = purpose[hit.byte, hit.bit]
                keeps = (f"of {what} keeps for itself" if what.endswith("timers")
                         else f"keeps for {what}")
                raise self.unsupported(self.param_stmt(stmt, ops[0]), f"`{written}` uses "
                                       f"{hit.text}, which the translation {keeps} (the "
                                       "top marker bits)", ops[0].col)

    def prepare_timers(self) -> None:
        """One S7 kind per timer, and its scratch bits: the status S7 shows (V, the
        view), the enable of this and of the last execution (E, P), and for a timer
        that `R T n` resets, a block bit (B: S7 keeps the edge memory across the
        reset, this CPU clears it)."""
        self.scratch_bits: dict[tuple, Operand] = {}
        if self.startup:                # set once the startup part (OB 100) has run
            self.scratch(("started",))
        self.timer_kinds: dict[int, tuple[str, Stmt]] = {}
        resets: dict[int, Stmt] = {}
        for stmt in self.stmts:
            if stmt.canon in TIMER_STARTS:
                n = self.timer_operand(stmt).index
                kind = self.timer_kinds.setdefault(n, (stmt.canon, stmt))
                if kind[0] != stmt.canon:
                    raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` on a timer "
                                           f"started as `{kind[1].mnemonic.text}` at "
                                           f"line {kind[1].line} (one kind per timer)")
            elif stmt.canon == "R" and stmt.operands and _split_area(
                    stmt.operands[0].text)[0] == "T":
                resets.setdefault(self.timer_operand(stmt).index, stmt)
        self.timer_resets = set(resets)
        for n, stmt in resets.items():
            kind = self.timer_kinds.get(n)
            if kind and kind[0] == "SF":
                raise self.unsupported(stmt, f"`{stmt.mnemonic.text} "
                                       f"{self.timer_operand(stmt).text}` on an "
                                       "off-delay timer "
                                       "(S7 keeps its edge memory, this CPU clears it)")
        for n in sorted(self.timer_kinds):
            extra = ("pulse",) if self.timer_kinds[n][0] == "SE" else \
                ("blocked",) if n in self.timer_resets else ()
            for purpose in ("view", "enable", "previous") + extra:
                self.scratch((purpose, n))
        up = sorted({self.counter_operand(stmt).index for stmt in self.stmts
                     if stmt.canon == "CU"})
        for n in up:
            for purpose in ("cu-enable", "cu-previous", "cu-pulse"):
                self.scratch((purpose, n))
        # timers whose time value the program loads (`L T n`, `LC T n`): the bit
        # that says the IL timer's elapsed time means S7's remaining time (TIME_VALUE)
        self.timer_reads: dict[int, set[str]] = {}
        for stmt in self.stmts:
            if stmt.canon in ("L", "LC") and stmt.operands:
                area, rest = _split_area(stmt.operands[0].text)
                if area == "T" and not rest.startswith("#"):
                    n = self.timer_operand(stmt).index
                    self.timer_reads.setdefault(n, set()).add(stmt.canon)
        for n in sorted(self.timer_reads):
            kind = self.timer_kinds.get(n, ("",))[0]
            if kind in ("SS", "SE", "SF"):
                self.scratch(("armed" if kind == "SF" else "run", n))
        # FR (docs/s7.md, "FR"): its own edge memory; a timer's `freed` bit says an
        # FR rose since the timer's last instruction (S7's edge memory is then 0)
        self.timer_frees: set[int] = set()
        self.counter_frees: set[int] = set()
        for stmt in self.stmts:
            if stmt.canon != "FR" or not stmt.operands:
                continue
            area = _split_area(stmt.operands[0].text)[0]
            if area == "T":
                n = self.timer_operand(stmt).index
                kind = self.timer_kinds.get(n, ("",))[0]
                if kind == "SF":
                    raise self.unsupported(stmt, f"`{stmt.mnemonic.text} "
                                           f"{self.timer_operand(stmt).text}` on an "
                                           "off-delay timer (S7 then skips the start "
                                           "at the input's fall; the IL's off-delay "
                                           "starts at every fall)")
                self.timer_frees.add(n)
                for purpose in ("fr-previous", "freed") + (
                        ("held",) if kind == "SD" else ()):
                    self.scratch((purpose, n))
            else:
                n = self.counter_operand(stmt).index
                self.counter_frees.add(n)
                self.scratch(("cfr-previous", n))
        for n in sorted(self.counter_frees):    # S7's edges of ZR and S as CU's
            for purpose in ("cd-enable", "cd-previous", "cd-pulse", "s-enable",
                            "s-previous", "s-pulse"):
                self.scratch((purpose, n))
        # BR (docs/s7.md, "BR"): a marker bit the translation keeps, where it is read
        if any(stmt.canon in ("JBI", "JNBI") or any(
                w.text.upper() in ("BR", "BIE") for w in stmt.operands[:1])
                for stmt in self.stmts):
            self.scratch(("BR",))
        self.check_scratch()

    def read_blocks(self) -> None:
        """Read every block of the source: OB 1, FC n, FB n (their interfaces and
        bodies) and DB n (instance DBs; global ones with their fields and initial
        values: Global data blocks).  Other OBs and TYPE are unsupported."""
        self.blocks: dict[tuple[str, int], Block] = {}
        state, block, section = "outside", None, ""
        struct_depth, call, listed = 0, None, None
        for n, raw in enumerate(self.lines, start=1):
            text = _strip_comment(raw.rstrip("\r"))
            if call is not None:                # a CALL's parameters over lines
                call[1].append((n, 1, text))
                joined = " ".join(t for _, _, t in call[1])
                if joined.count("(") <= joined.count(")"):
                    self.read_statements(call[0], *_joined(call[1], " "))
                    call = None
                continue
            if listed is not None:              # `name :=actual` lines, no parentheses
                if _PARAM_LINE.fullmatch(text):
                    param = text.strip().rstrip(";").strip()
                    listed[2].append((n, text.index(param) + 1, param))
                    continue
                if not text.strip():            # a comment or a blank line inside it
                    continue
                self.stmts = listed[3]
                self.read_listed(listed)
                listed = None
            stripped = text.strip()
            if not stripped:
                continue
            col = len(text) - len(text.lstrip()) + 1
            words = stripped.replace(";", " ").split()
            if not words:                       # a line holding only `;`
                continue
            head = words[0].upper()
            if state == "outside":
                block = self.block_head(n, col, stripped, words)
                state = "header"
            elif state == "header":
                if head == "BEGIN":
                    state, block.begin = ("dbinit" if block.kind == "DB" else "body"), n
                elif head in SECTIONS:
                    section = SECTIONS[head]
                    if section not in BLOCK_SECTIONS[block.kind]:
                        raise self.error(n, col, f"unsupported: {head} in {block.name}"
                                         + (" (only VAR_TEMP)" if block.kind == "OB"
                                            else ""))
                    state = "decl"
                elif block.kind == "DB" and head == "STRUCT":
                    state, struct_depth = "struct", 1
                elif block.kind == "DB" and re.fullmatch(r"FB\s*\d+", " ".join(words),
                                                         re.I):
                    block.instance_of = int(re.sub(r"\D", "", " ".join(words)))
                elif head.startswith(("TITLE", "AUTHOR", "FAMILY", "NAME", "VERSION",
                                      "KNOW_HOW_PROTECT", "CODE_VERSION", "{")):
                    pass
                else:
                    raise self.error(n, col, f"expected BEGIN, found `{words[0]}`")
            elif state == "decl":
                if head == "END_VAR":
                    state = "header"
                elif head == "END_STRUCT" and struct_depth:
                    struct_depth -= 1
                elif not struct_depth:
                    struct_depth = self.read_decl(block, section, n, col, stripped)
                elif head.endswith("STRUCT") or stripped.upper().rstrip(
                        "; ").endswith(": STRUCT"):
                    struct_depth += 1
            elif state == "struct":
                if struct_depth == 1 and head not in ("END_STRUCT", "STRUCT"):
                    self.read_db_field(block, n, col, stripped)
                if head == "END_STRUCT":
                    struct_depth -= 1
                    state = "header" if not struct_depth else state
                elif stripped.upper().rstrip("; ").endswith("STRUCT"):
                    struct_depth += 1
            elif state == "dbinit":
                if head == "END_DATA_BLOCK":
                    state, block.end = "outside", n
                else:
                    self.read_db_value(block, n, col, stripped)
            elif state == "body":
                if head == BLOCK_ENDS[block.kind]:
                    state, block.end = "outside", n
                elif head in ("NETWORK",) or head.startswith("TITLE"):
                    pass
                elif head.startswith("END_"):
                    raise self.error(n, col, f"expected {BLOCK_ENDS[block.kind]}, "
                                     f"found `{words[0]}`")
                else:
                    self.stmts = block.stmts
                    if _PARAM_LINE.fullmatch(text):
                        raise self.error(n, col, f"parameter line outside a CALL's list "
                                         f"(`{stripped.rstrip(';').strip()}`: such lines "
                                         "follow a `CALL` without parentheses, with "
                                         "only comments or blank lines between)")
                    if _CALL_START.match(text) and text.count("(") > text.count(")"):
                        call = (n, [(n, 1, text)])
                    elif _CALL_START.match(text) and "(" not in text \
                            and self.param_line_follows(n):
                        listed = (n, text, [], block.stmts)
                    else:
                        self.read_statements(n, text)
        if listed is not None:
            self.stmts = listed[3]
            self.read_listed(listed)
        if call is not None:
            raise self.error(call[0], 1, "unbalanced parentheses: the parameter list of "
                             "this CALL is never closed")
        if state in ("header", "decl", "struct"):
            raise self.error(len(self.lines), 1, f"missing BEGIN in {block.name}")
        if state in ("body", "dbinit"):
            raise self.error(block.begin, 1, f"missing {BLOCK_ENDS[block.kind]} for "
                             f"the {block.name} that begins here")
        if ("OB", 1) not in self.blocks:
            ob100 = self.blocks.get(("OB", 100))
            if ob100 is not None:
                raise self.error(ob100.line, ob100.col, "OB 100 without ORGANIZATION_BLOCK "
                                 "OB 1: OB 100 runs once before the first scan of OB 1, "
                                 "the cyclic program, which this source lacks")
            raise SourceError(self.path, 0, 0, "no ORGANIZATION_BLOCK OB 1 in the source")
        self.stmts = [st for b in self.blocks.values() for st in b.stmts]

    def param_line_follows(self, n: int) -> bool:
        """Is the first line after line n that holds more than a comment a
        `name :=actual` line (a CALL's list without parentheses)?"""
        for raw in self.lines[n:]:
            text = _strip_comment(raw.rstrip("\r"))
            if text.strip():
                return bool(_PARAM_LINE.fullmatch(text))
        return False

    def read_listed(self, listed: tuple) -> None:
        """`CALL ...` and its `name :=actual` lines, read as `CALL ... (name :=
        actual, ...)` with each parameter's own line and column."""
        n, text, params = listed[0], listed[1].rstrip().rstrip(";"), listed[2]
        pieces = [(n, 1, text + " (")] + [(ln, c, p + ",") for ln, c, p in params[:-1]]
        if params:
            ln, c, p = params[-1]
            pieces.append((ln, c, p + ")"))
        else:
            pieces[0] = (n, 1, text + " ()")
        self.read_statements(n, *_joined(pieces, " "))

    def block_head(self, n: int, col: int, stripped: str, words: list[str]) -> Block:
        head = words[0].upper()
        kind = BLOCK_HEADS.get(head)
        if kind is not None and len(words) > 1 and words[1].startswith('"'):
            raise self.error(n, col + stripped.index(words[1]), "unsupported: block "
                             f"named by a symbol `{words[1]}` (this slice reads blocks "
                             f"by number: `{head} {kind} n`)")
        if kind is None:
            if head in ("TYPE", "VAR_GLOBAL"):
                raise self.error(n, col, f"unsupported: {head} (this slice reads "
                                 "ORGANIZATION_BLOCK OB 1, FUNCTION, FUNCTION_BLOCK and "
                                 "DATA_BLOCK)")
            raise self.error(n, col, f"expected ORGANIZATION_BLOCK OB 1, FUNCTION, "
                             f"FUNCTION_BLOCK or DATA_BLOCK, found `{words[0]}`")
        m = re.fullmatch(kind + r"\s*(\d+)\s*(:\s*\w+)?", " ".join(words[1:]), re.I)
        if kind == "OB" and (m is None or int(m.group(1)) not in (1, 100)):
            raise self.error(n, col, "unsupported: `" + stripped + "` (this slice runs "
                             "ORGANIZATION_BLOCK OB 1 and OB 100 only)")
        if m is None:
            raise self.error(n, col, f"expected `{head} {kind} <number>`, found "
                             f"`{stripped}`")
        number = int(m.group(1))
        if (kind, number) in self.blocks:
            first = self.blocks[(kind, number)]
            raise self.error(n, col, f"duplicate block {kind} {number} (first at line "
                             f"{first.line})")
        block = Block(kind, number, n, col)
        self.blocks[(kind, number)] = block
        ret = (m.group(2) or "").lstrip(":").strip().upper()
        if kind == "FC" and ret and ret != "VOID":
            # RET_VAL: an implicit VAR_OUTPUT of the return type (awlsim, STEP 7)
            if ret not in LOCAL_TYPES:
                raise self.error(n, col + stripped.upper().rindex(ret), "unsupported: "
                                 f"FC with a return value of type {ret} (return values "
                                 "of this slice: BOOL, INT, WORD)")
            block.decls["RET_VAL"] = Decl("RET_VAL", "OUT", ret, n, col)
        return block

    def read_decl(self, block: Block, section: str, n: int, col: int,
                  text: str) -> int:
        """`name : TYPE [:= value];` (1 when it opens a STRUCT, else 0)."""
        m = _DECL.match(text)
        if not m:
            raise self.error(n, col, f"malformed declaration `{text}`: name : type; "
                             "expected")
        name, type_, value = m.group(1), m.group(2).strip().upper(), m.group(3)
        if name.upper() in block.decls:
            raise self.error(n, col, f"duplicate declaration `{name}` in {block.name}")
        block.decls[name.upper()] = Decl(name, section, type_, n, col)
        if value is not None and type_ in LOCAL_TYPES and _initial(value) != 0:
            raise self.error(n, text.index(value) + col, f"unsupported: initial value "
                             f"`{value.strip()}` (block-local data lives in markers, "
                             "which start at 0)")
        return 1 if type_ == "STRUCT" else 0

    def read_db_value(self, block: Block, n: int, col: int, text: str) -> None:
        """An instance DB's `name := value;` after BEGIN (0 / FALSE only)."""
        if block.instance_of is None:           # a global DB's (Global data blocks)
            return self.read_db_assignment(block, n, col, text)
        m = re.fullmatch(r"\s*([A-Za-z_][\w.\[\], ]*?)\s*:=\s*([^;]+?)\s*;?\s*", text)
        if not m:
            raise self.error(n, col, f"malformed initial value `{text}`")
        if _initial(m.group(2)) != 0:
            raise self.error(n, col, f"unsupported: initial value `{m.group(2)}` in "
                             f"{block.name} (block-local data lives in markers, which "
                             "start at 0)")

    def read_statements(self, n: int, text: str, where: list | None = None) -> None:
        """The statements of line n (`text`; `where`: the (line, column) of each of
        its characters when it is a CALL joined from several lines)."""
        source = self.lines[n - 1].rstrip("\r")
        for offset, piece in _split_statements(text):
            labels: list[Word] = []
            pos = 0
            while True:
                m = _LABEL.match(piece, pos)
                if not m:
                    break
                labels.append(Word(m.group(1), offset + m.start(1) + 1))
                pos = m.end()
            call = _CALL_STMT.match(piece, pos)
            if call:
                self.read_call(n, source, offset, piece, labels, call, where)
                continue
            words = [Word(t.group(0), offset + t.start() + 1)
                     for t in _TOKEN.finditer(piece, pos)]
            if not words:
                if labels:      # a label alone on its line marks the next statement
                    self.stmts.append(Stmt(n, labels[0].col, source, Word("", 0), [],
                                           labels))
                continue
            mnem = words[0]
            rest = words[1:]
            if rest and rest[0].text == "(" and mnem.text.upper() in (
                    "U", "UN", "A", "AN", "O", "ON", "X", "XN", "MCR"):
                mnem = Word(mnem.text + "(", mnem.col)
                rest = rest[1:]
            elif mnem.text == ")" and rest and rest[0].text.upper() == "MCR" \
                    and rest[0].col == mnem.col + 1:
                mnem = Word(")" + rest[0].text, mnem.col)
                rest = rest[1:]
            self.stmts.append(Stmt(n, mnem.col, source, mnem, rest, labels))

    def read_call(self, n: int, source: str, offset: int, piece: str,
                  labels: list[Word], call, where: list | None = None) -> None:
        """`CALL FC n (p := a, ...)`, `CALL FB n, DB m (...)`, `UC FC n`, `CC FC n`
        (the parameter list may go on over lines: `where` gives each character's
        line and column; a parameter's words keep their line)."""
        width = len(source)

        def col(i: int) -> int:
            if where is not None:
                return where[min(offset + i, len(where) - 1)][1]
            return offset + i + 1 if offset + i < width else offset + call.start(1) + 1

        def line(i: int) -> int:
            return n if where is None else where[min(offset + i, len(where) - 1)][0]

        mnem = Word(call.group(1), col(call.start(1)))
        target = call.group(2)
        m = _CALLEE.fullmatch(target)
        if m is None and re.match(r"F[CB](?![A-Z_])", target, re.I) \
                and not re.search(r'["#\[]', target):
            raise self.error(line(call.start(2)), col(call.start(2)),
                             f"malformed call `{call.group(1)} "
                             f"{' '.join(target.split())}`: {call.group(1)} FC n or "
                             f"{call.group(1)} FB n, DB m expected")
        if m is None:
            raise self.error(line(call.start(2)), col(call.start(2)),
                             f"unsupported: `{call.group(1)} "
                             f"{' '.join(target.split())}` (this slice calls FC n and "
                             "FB n, DB m by number)")
        params = []
        if m.group(5) is not None:
            inner_start = call.start(2) + m.start(6)
            for p_start, text in _split_statements(m.group(6), ","):
                if not text.strip():
                    if m.group(6).strip():
                        raise self.error(line(inner_start + p_start),
                                         col(inner_start + p_start),
                                         "malformed parameter list")
                    continue
                pm = _PARAM.fullmatch(text)
                if pm is None:
                    at = inner_start + p_start + len(text) - len(text.lstrip())
                    raise self.error(line(at), col(at), f"malformed "
                                     f"parameter `{text.strip()}`: name := actual "
                                     "expected")
                base = inner_start + p_start
                actual = [Word(t.group(0), col(base + pm.start(2) + t.start()),
                               line=line(base + pm.start(2) + t.start()))
                          for t in re.finditer(r'"[^"]*"|\S+', pm.group(2))]
                params.append((Word(pm.group(1), col(base + pm.start(1)),
                                    line=line(base + pm.start(1))), actual))
        info = CallInfo(m.group(1).upper(), int(m.group(2)),
                        int(m.group(4)) if m.group(4) else None, params)
        self.stmts.append(Stmt(n, mnem.col, source, mnem, [], labels, extra=info))

    # -- mnemonics -----------------------------------------------------------------

    def evidence(self) -> list[tuple[str, Stmt, Word]]:
        """(language, statement, word) for every word that belongs to one language."""
        found = []
        for stmt in self.stmts:
            if not stmt.mnemonic.text:
                continue
            langs = MNEMONIC_TABLE.get(stmt.mnemonic.text.upper(), {})
            if len(langs) == 1:
                found.append((next(iter(langs)), stmt, stmt.mnemonic))
            if stmt.operands and not self.is_jump(stmt) \
                    and "#" not in stmt.operands[0].text:
                area = _split_area(stmt.operands[0].text)[0]
                alangs = AREA_TABLE.get(area, {})
                if len(alangs) == 1:
                    found.append((next(iter(alangs)), stmt, stmt.operands[0]))
        return found

    @staticmethod
    def is_jump(stmt: Stmt) -> bool:
        langs = MNEMONIC_TABLE.get(stmt.mnemonic.text.upper(), {})
        return any(c.startswith("J") or c == "LOOP" for c in langs.values())

    def detect_language(self) -> None:
        """One language per source: the first word that is German-only or
        English-only decides (forced: mnemonics=...); a word of the other one is
        an error."""
        first = None
        for lang, stmt, word in self.evidence():
            if self.forced and lang != self.forced:
                raise self.error(stmt.line, word.col,
                                 f"`{word.text}` is {LANGUAGE_NAME[lang]}, but the "
                                 f"mnemonics are {LANGUAGE_NAME[self.forced]} "
                                 f"(--mnemonics {self.forced})")
            if first is None:
                first = (lang, stmt, word)
                self.lang = lang
            elif lang != first[0]:
                f_lang, f_stmt, f_word = first
                raise self.error(stmt.line, word.col,
                                 f"mixed mnemonics: `{word.text}` is "
                                 f"{LANGUAGE_NAME[lang]}, but this source is "
                                 f"{LANGUAGE_NAME[f_lang]} (`{f_word.text}` at "
                                 f"{f_stmt.line}:{f_word.col}); use one language, or "
                                 "--mnemonics de|en")
        if first is None and not self.forced:
            se = next((s for s in self.stmts if s.mnemonic.text.upper() == "SE"), None)
            if se is not None:      # the one word whose meaning depends on the language
                raise self.error(se.line, se.mnemonic.col, "ambiguous: `SE` is the "
                                 "German on-delay and the English extended pulse; no "
                                 "other word decides the language: give --mnemonics "
                                 "de|en")

    def canonical(self, stmt: Stmt) -> None:
        if not stmt.mnemonic.text:
            return
        word = stmt.mnemonic.text.upper()
        langs = MNEMONIC_TABLE.get(word)
        if langs is None:
            raise self.error(stmt.line, stmt.mnemonic.col,
                             f"unknown mnemonic `{stmt.mnemonic.text}`"
                             + did_you_mean(word, MNEMONIC_TABLE))
        stmt.canon = langs[self.lang]

    # -- operands ------------------------------------------------------------------

    def address(self, stmt: Stmt, kind: str) -> tuple[Word, str, str, str]:
        """The address operand of `stmt` (`E 0.0`, `MW10`, `EW 2`): (its first word,
        the canonical English area, the rest after the area, the text written)."""
        ops = stmt.operands
        if not ops:
            raise self.error(stmt.line, stmt.mnemonic.col,
                             f"missing operand: `{stmt.mnemonic.text}` needs a {kind}")
        first = ops[0]
        text = first.text
        if text.startswith("#"):
            raise self.unsupported(stmt, f"local variable `{text}`", first.col)
        kind = REGISTER_OPERANDS.get(text.upper())
        if kind:
            why = REGISTER_REASONS.get(text.upper(), REGISTER_REASONS.get(kind, _NO_CC))
            raise self.unsupported(stmt, f"{kind} `{text}` in `{stmt.mnemonic.text}` "
                                   f"({why})", first.col)
        # a data block operand with a space (`DB1.DBW 2`) or indirect addressing
        # (`M [MD 0]`): named as what it is, not as an extra operand
        if re.fullmatch(r"DB\d+\.D[BI][XBWD]?", text, re.I):
            raise self.unsupported(stmt, "data block operand `" + " ".join(
                w.text for w in ops[:2]) + f"` in `{stmt.mnemonic.text}`", first.col)
        if any(w.text.startswith("[") for w in ops):
            raise self.unsupported(stmt, "indirect addressing `" + " ".join(
                w.text for w in ops) + f"` in `{stmt.mnemonic.text}`", first.col)
        area, rest = _split_area(text)
        used = 1
        if area and rest == "" and len(ops) > 1:
            rest, used = ops[1].text, 2
        written = first.shown or " ".join(w.text for w in ops[:used])
        if len(ops) > used:
            raise self.error(stmt.line, ops[used].col,
                             f"extra operand `{ops[used].text}`")
        langs = AREA_TABLE.get(area)
        if langs is None or not area:
            raise self.error(stmt.line, first.col, f"invalid operand `{written}`")
        if self.lang not in langs:          # e.g. a CALL argument in the other language
            other = next(iter(langs))
            raise self.error(stmt.line, first.col,
                             f"mixed mnemonics: `{written}` is {LANGUAGE_NAME[other]}, "
                             f"but this source is {LANGUAGE_NAME[self.lang]}")
        return first, langs[self.lang], rest, written

    def bit_operand(self, stmt: Stmt, targets: tuple[str, ...] = BIT_AREAS) -> Operand:
        """`E 0.0` / `I0.0` / `A 4.1` / `M 10.7` -> a bit Operand (English area)."""
        first, canon, rest, written = self.address(stmt, "bit")
        area = _split_area(first.text)[0]
        if canon in STATUS_AREAS and canon in targets:
            return self.numbered(stmt, first, canon, rest, written)
        if canon not in BIT_AREAS:
            what = {"T": "timer status", "C": "counter status"}.get(canon, "operand")
            if canon.endswith(("B", "W", "D")) and canon not in ("DB",):
                what = "byte/word operand"
            raise self.unsupported(stmt, f"{what} `{written}` in "
                                   f"`{stmt.mnemonic.text}`", first.col)
        if canon == "I" and "I" not in targets:
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text} {written}` writes the "
                                   "input image (inputs come from the stimulus)",
                                   first.col)
        if canon not in targets:
            raise self.error(stmt.line, first.col,
                             f"operand of the wrong kind: `{stmt.mnemonic.text}` needs "
                             f"{' or '.join(_english_area_names(targets, self.lang))}, "
                             f"not `{written}`")
        byte, dot, bit = rest.partition(".")
        if not (dot and byte.isdigit() and bit.isdigit()):
            raise self.error(stmt.line, first.col,
                             f"malformed address `{written}`: {area} <byte>.<bit> expected")
        b, n = int(byte), int(bit)
        if n > 7:
            raise self.error(stmt.line, first.col,
                             f"operand out of range: `{written}` (bit 0..7)")
        limit = self.config.area_size(canon)
        if b >= limit:
            raise self.error(stmt.line, first.col,
                             f"operand out of range: `{written}` (byte 0..{limit - 1} "
                             "in this build)")
        return Operand("bit", area=canon, byte=b, bit=n, text=written)

    def numbered(self, stmt: Stmt, first: Word, canon: str, rest: str,
                 written: str) -> Operand:
        """`T 1` / `Z 3` -> a timer or counter Operand."""
        if not rest.isdigit():
            raise self.error(stmt.line, first.col, f"malformed address `{written}`: "
                             f"{_split_area(first.text)[0]} <number> expected")
        n = int(rest)
        limit = self.config.area_size(canon)
        if n >= limit:
            raise self.error(stmt.line, first.col,
                             f"operand out of range: `{written}` (0..{limit - 1} in "
                             "this build)")
        return Operand("index", area=canon, index=n, text=written)

    def counter_operand(self, stmt: Stmt) -> Operand:
        return self.status_operand(stmt, "C", "counter")

    def timer_operand(self, stmt: Stmt) -> Operand:
        return self.status_operand(stmt, "T", "timer")

    def status_operand(self, stmt: Stmt, area: str, kind: str) -> Operand:
        first, canon, rest, written = self.address(stmt, kind)
        if canon != area:
            raise self.error(stmt.line, first.col,
                             f"operand of the wrong kind: `{stmt.mnemonic.text}` needs "
                             f"a {kind}, not `{written}`")
        return self.numbered(stmt, first, canon, rest, written)

    def no_operand(self, stmt: Stmt) -> None:
        if stmt.operands:
            raise self.error(stmt.line, stmt.operands[0].col,
                             f"extra operand `{stmt.operands[0].text}`: "
                             f"`{stmt.mnemonic.text}` takes no operand")

    def label_operand(self, stmt: Stmt) -> str:
        if not stmt.operands:
            raise self.error(stmt.line, stmt.mnemonic.col,
                             f"missing operand: `{stmt.mnemonic.text}` needs a label")
        if len(stmt.operands) > 1:
            raise self.error(stmt.line, stmt.operands[1].col,
                             f"extra operand `{stmt.operands[1].text}`")
        return stmt.operands[0].text.upper()

    # -- translation ---------------------------------------------------------------

    def translate(self) -> Program:
        """Translate with assumed states at the labels, until the assumptions hold
        (a label reached only by a later backward jump learns its state in the
        first pass)."""
        self.label_defs: dict[str, Stmt] = {}
        for stmt in self.stmts:
            for w in stmt.labels:
                if w.text.upper() in self.label_defs:
                    first = self.label_defs[w.text.upper()]
                    # as written: without the prefix of OB 100's or an inlined
                    # block's labels (OB100.M1; a source label has no `.`)
                    raise self.error(stmt.line, w.col, f"duplicate label "
                                     f"`{w.text.rsplit('.', 1)[-1]}` "
                                     f"(first defined at {first.line}:{first.col})")
                self.label_defs[w.text.upper()] = stmt
        if self.startup and STARTUP_LABEL in self.label_defs:
            stmt = self.label_defs[STARTUP_LABEL]
            raise self.error(stmt.line, stmt.labels[0].col, f"unsupported: the label "
                             f"`{STARTUP_LABEL}` (the listing's name of the OB 100 part)")
        assumed: dict[str, tuple[int, str]] = {}
        assumed_acc: dict[str, tuple] = {}
        self.assumed_cc: dict[str, bool] = {}
        # Kleene iteration: each label's states only move down their lattices, so the
        # passes settle; a bound in case they did not (never: an error, not a guess)
        for _ in range(6 + 4 * len(self.label_defs)):
            program, edges = self.translate_once(assumed, assumed_acc)
            wanted = self.check_edges(edges)
            wanted_acc = {}
            for name, states in self.acc_edges.items():
                acc = (TOP, TOP)
                for a in states:
                    acc = (_meet(acc[0], a[0]), _meet(acc[1], a[1]))
                wanted_acc[name] = acc
            wanted_cc = {name: meet_status(oks) for name, oks in self.cc_edges.items()
                         if oks}
            if wanted == assumed and wanted_acc == assumed_acc \
                    and wanted_cc == self.assumed_cc:
                self.check_overlaps()
                self.check_local_region()
                for ins in program.instrs:      # S7's time: the scan's latch (LATCH_MS)
                    ins.at_latch = ins.mnemonic in IL_TIMER_STARTS
                return program
            assumed, assumed_acc, self.assumed_cc = wanted, wanted_acc, wanted_cc
        raise self.error(1, 1, "internal error: the states at the labels did not "
                         "settle (please report this program)")

    def check_edges(self, edges: dict[str, list[tuple[int, Stmt, str]]]
                    ) -> dict[str, tuple[int, str]]:
        """One /FC per label: (/FC, how paths with /FC = 0 are made /FC = 1: "" for
        none, "SET" or "CLR"), or an unsupported error.

        Where both states meet and the target starts with U/UN/U(/UN(, a path with
        /FC = 0 sets the RLO to 1 before it arrives (1 AND x = x: the load S7 does
        there); before O/ON/X/XN/O(/... it clears it (0 OR x = 0 XOR x = x).  A
        conditional jump arrives with the RLO 1 (S7 and the IL agree), which suits the
        first kind only."""
        states = {}
        for name, incoming in edges.items():
            values = {ner for ner, _, _ in incoming}
            target = self.fc_reader(self.label_defs[name])
            if len(values) == 1:
                states[name] = (values.pop(), "")
                continue
            self.no_fc_through_jumps(name, target)
            if target.canon in FC_BLIND:
                states[name] = (0, "")
                continue
            combine = target.canon in COMBINE and target.operands
            if (combine or target.canon in OPEN) and target.canon.startswith("A"):
                states[name] = (1, "SET")
                continue
            jc = [s for ner, s, kind in incoming if ner == 0 and kind == "JC"]
            if (combine or target.canon in OPEN) and not jc:
                states[name] = (1, "CLR")
                continue
            sa = jc[0] if jc else next(s for ner, s, _ in incoming if ner == 0)
            sb = next(s for ner, s, _ in incoming if ner == 1)
            label = self.label_defs[name]
            raise self.error(label.line, label.labels[0].col,
                             f"unsupported: jump target `{label.labels[0].text}` is "
                             f"reached with /FC = 0 (from line {sa.line}) and "
                             f"/FC = 1 (from line {sb.line}), and "
                             f"`{target.mnemonic.text}` depends on it")
        return states

    def no_fc_through_jumps(self, name: str, reader: Stmt) -> None:
        """Paths with /FC = 0 and 1 meet at label `name`: a `LOOP` or a jump on the
        status bits between it and `reader` passes that /FC on to another label,
        which the /FC chosen here (and its SET/CLR) does not describe: rejected."""
        i = self.stmts.index(self.label_defs[name])
        while self.stmts[i] is not reader:
            stmt = self.stmts[i]
            if stmt.canon in ("LOOP",) + tuple(CC_JUMPS) and stmt.operands \
                    and stmt.operands[0].text.upper() != name:
                label = self.label_defs[name]
                raise self.error(label.line, label.labels[0].col,
                                 f"unsupported: jump target `{label.labels[0].text}` is "
                                 "reached with /FC = 0 and /FC = 1, which `"
                                 f"{stmt.mnemonic.text} {stmt.operands[0].text}` (line "
                                 f"{stmt.line}) passes on to its target")
            i += 1

    def fc_reader(self, stmt: Stmt) -> Stmt:
        """The statement that decides what a jump target needs of /FC: the target
        itself, or the first after the L/T/arithmetic that pass /FC along (up to
        another label)."""
        i = self.stmts.index(stmt)
        while self.stmts[i].canon in FC_PASS and i + 1 < len(self.stmts) \
                and not self.stmts[i + 1].labels:
            i += 1
        return self.stmts[i]

    def translate_once(self, assumed: dict[str, tuple[int, str]],
                       assumed_acc: dict[str, tuple]):
        self.out: list[Instr] = []
        self.labels: dict[str, int] = {}
        self.pending: list[str] = []
        self.assumed = assumed
        self.acc_edges: dict[str, list[tuple]] = {n: [] for n in self.label_defs}
        # CC 1 / CC 0 kept as S7's on each path into a label (docs/s7.md, Status bits)
        self.cc_edges: dict[str, list[bool]] = {n: [] for n in self.label_defs}
        self.word_uses: list[tuple[str, int, Stmt, Word]] = []
        self.last_load: Instr | None = None
        self.presets: dict[int, int] = {}
        self.timebases: dict[int, tuple[int, Stmt]] = {}  # S7's time base of a preset
        self.value_labels = 0                   # internal labels of TIME_VALUE code
        edges: dict[str, list[tuple[int, Stmt, str]]] = {n: [] for n in self.label_defs}
        st = _State()
        reachable = True            # the previous statement runs and falls through
        if ("BR",) in self.scratch_bits:    # S7 starts every OB with BR = 0
            self.stmt = self.stmts[0]
            for mnem, op in (("SET", None), ("R", self.scratch(("BR",))), ("CLR", None)):
                self.emit(mnem, op)
        if self.startup:            # the guard: OB 100 in the first scan only
            self.stmt = next(s for s in self.stmts if s.canon == "@STARTUP")
            self.emit("LDN", self.scratch(("started",)))
            self.emit("JC", Operand("label", label=STARTUP_LABEL, text=STARTUP_LABEL))
        for i, stmt in enumerate(self.stmts):
            self.stmt = stmt
            if stmt.canon in ("@STARTUP", "@STARTED"):
                self.end_block(st)
            if stmt.canon == "@STARTUP":    # OB 1 ends; OB 100 starts as a scan does
                self.pending.append(END_LABEL)
                self.emit("END", line=len(self.lines) + 1, col=1, source="")
                st, reachable = _State(), True
                self.pending.append(STARTUP_LABEL)
                self.emit("CLR")            # S7's RLO at a block start (the guard's is 1)
                continue
            name = stmt.labels[0].text.upper() if stmt.labels else ""
            ner, fix = assumed.get(name, (None, ""))
            if fix and reachable and st.ner == 0:
                self.emit(fix)              # this path arrives with /FC = 0
            elif st.need_set and (stmt.labels or not self.overwrites_rlo(stmt, st)):
                self.emit("SET")
            st.need_set = False
            if stmt.labels:
                if st.parens or st.orm != "none":
                    raise self.unsupported(stmt, "a label inside parentheses or an "
                                           "AND-before-OR term", stmt.labels[0].col)
                if reachable:
                    edges[name].append((st.ner, self.prev_stmt(i), "fall"))
                    self.acc_edges[name].append(st.acc)
                    self.cc_edges[name].append(st.cc_ok)
                st.ner = ner if ner is not None else (st.ner if reachable else 0)
                acc = assumed_acc.get(name)
                if acc is None:
                    acc = (TOP, TOP)
                    for a in self.acc_edges[name]:
                        acc = (_meet(acc[0], a[0]), _meet(acc[1], a[1]))
                st.acc = acc
                cc = self.assumed_cc.get(name)      # (not known yet: true, as TOP)
                st.cc_ok = cc if cc is not None else meet_status(self.cc_edges[name])
                for w in stmt.labels:
                    self.pending.append(w.text)
                reachable = True    # (a label nobody jumps to counts as reached)
            if not stmt.mnemonic.text:
                continue
            falls = self.statement(stmt, st, edges)
            reachable = reachable and falls
        if not self.startup:
            self.end_block(st)
            self.pending.append(END_LABEL)
            self.emit("END", line=len(self.lines) + 1, col=1, source="")
        self.prepend_timer_update()
        for ins in self.out:
            if ins.operand is not None and ins.operand.kind == "label" \
                    and ins.operand.label not in self.labels:
                raise self.error(ins.line, ins.col,
                                 f"unknown label `{ins.operand.text}`")
        program = Program(self.path, self.out, dict(self.labels), {})
        return program, {n: e for n, e in edges.items() if e}

    def end_block(self, st: _State) -> None:
        """The end of OB 1 or OB 100: every parenthesis closed, an open AND term
        closed."""
        if st.parens:
            opener = st.parens[-1][1]
            raise self.error(opener.line, opener.col, f"unbalanced parentheses: "
                             f"`{opener.mnemonic.text}` is never closed")
        self.close_term(st)
        st.need_set = False

    def prev_stmt(self, i: int) -> Stmt:
        return self.stmts[i - 1] if i > 0 else self.stmts[i]

    @staticmethod
    def overwrites_rlo(stmt: Stmt, st: _State) -> bool:
        """Does stmt ignore the RLO it finds (after SPB/SPBN, /FC = 0)?"""
        return stmt.canon in COMBINE or stmt.canon in OPEN or stmt.canon in (
            "SET", "CLR", "NOP", "BLD") + COMPARES + COMPARES_D or (stmt.canon == "O"
                                                      and not stmt.operands)

    def emit(self, mnemonic: str, operand: Operand | None = None, *, line=None,
             col=None, source=None) -> None:
        s = self.stmt
        ins = Instr(mnemonic, operand, s.line if line is None else line,
                    s.col if col is None else col, s.source if source is None else source)
        ins.labels = self.pending
        for name in self.pending:
            self.labels[name.upper()] = len(self.out)
        self.pending = []
        if len(self.out) >= self.config.prog_words:
            raise self.error(ins.line or s.line, ins.col or s.col,
                             f"program too large: more than {self.config.prog_words} "
                             "words (prog_words)")
        self.out.append(ins)

    def open_il(self, mnemonic: str, st: _State) -> None:
        st.il_depth += 1
        if st.il_depth > self.config.nest_depth:
            raise self.unsupported(self.stmt, f"parentheses (with AND-before-OR terms) "
                                   f"nested deeper than {self.config.nest_depth} levels "
                                   "in this build")
        self.emit(mnemonic)

    def close_term(self, st: _State) -> None:
        """End an AND term after `O`: S7's RLO (earlier terms OR this one) becomes
        the IL RLO."""
        if st.orm == "term":
            self.emit(")")
            st.il_depth -= 1
        st.orm = "none"

    def statement(self, stmt: Stmt, st: _State, edges) -> bool:
        """Translate one statement; False when it never falls through.  Afterwards
        the status bits count as changed where the translation emits word
        instructions S7 does not have (docs/s7.md, "Status bits")."""
        falls = self.translate_statement(stmt, st, edges)
        m = stmt.canon
        ops = stmt.operands
        area, rest = _split_area(ops[0].text) if ops else ("", "")
        tc = area.upper() in ("T", "Z", "C") and (rest[:1].isdigit() or not rest
                                                  and len(ops) > 1)   # not C#5
        if m.startswith("@") or m in tuple(IN_PLACE) + ("LOOP",):
            st.cc_ok = frozenset()      # (S7's calls and block ends clear OS; + n,
        elif m in ("LC", "JL", "FR") + TIMER_STARTS + ("CU", "CD") or \
                m in ("S", "R", "L") and tc:     # NEGI ... and LOOP may set it)
            st.cc_ok -= CC_OV           # compares and arithmetic that cannot overflow
        return falls

    def translate_statement(self, stmt: Stmt, st: _State, edges) -> bool:
        m = stmt.canon
        if m in ("@CALL", "@LEAVE", "@RET"):       # S7's CALL / block end: /FC, OR 0
            if st.parens:
                if m == "@LEAVE":
                    opener = st.parens[-1][1]
                    raise self.error(opener.line, opener.col, f"unbalanced parentheses: "
                                     f"`{opener.mnemonic.text}` is never closed")
                raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` inside parentheses")
            self.close_term(st)
            st.ner = 0
            if m == "@CALL":
                self.copy(stmt, st, stmt.extra)
            elif m == "@RET":
                edges[stmt.extra].append((0, stmt, "JU"))
                self.acc_edges[stmt.extra].append(st.acc)
                st.cc_ok = frozenset()      # a block end (its copies): not tracked
                self.cc_edges[stmt.extra].append(st.cc_ok)
                self.emit("JU", Operand("label", label=stmt.extra.upper(),
                                        text=stmt.mnemonic.text))
                return False
        elif m == "@END":
            self.copy(stmt, st, stmt.extra)
        elif m == "@STARTED":                   # OB 100's end: marked as run, END
            self.emit("SET")
            self.emit("=", self.scratch(("started",)))
            self.emit("END")
            return False
        elif m in COMBINE and stmt.operands:
            self.combine(stmt, st, m)
        elif m == "O":                          # O without operand: AND before OR
            self.no_operand(stmt)
            if st.ner == 1:
                self.close_term(st)
                st.orm = "pending"
        elif m in OPEN:
            self.no_operand(stmt)
            self.open_paren(stmt, st, m)
        elif m == ")":
            self.no_operand(stmt)
            self.close_paren(stmt, st)
        elif m in TIMER_STARTS:
            self.timer(stmt, st, m)
        elif m == "R" and stmt.operands and _split_area(
                stmt.operands[0].text)[0] == "T":
            op = self.timer_operand(stmt)
            self.close_term(st)
            self.emit("R", op)
            if op.index in self.timer_kinds:
                if self.timer_kinds[op.index][0] != "SE":
                    self.emit("S", self.scratch(("blocked", op.index)))
                else:                           # (the scan-start update: no edge)
                    self.emit("R", self.scratch(("pulse", op.index)))
                self.emit("R", self.scratch(("view", op.index)))
                if self.timer_kinds[op.index][0] in ("SS", "SE") and \
                        op.index in self.timer_reads:
                    self.emit("R", self.scratch(("run", op.index)))
                if ("held", op.index) in self.scratch_bits:
                    self.emit("R", self.scratch(("held", op.index)))
            if op.index in self.timer_reads:   # ACCU1's low word kept as LC Z's
                keep = st.acc[0] is not None
                old = self.scratch_word(stmt, "LC.ACCU1") if keep else None
                self.emit_code(([("T", old)] if keep else []) + self.time_value_reset(
                    op.index, stmt) + ([("L", old)] if keep else []))
                if keep:
                    acc1 = st.acc[0]
                    if isinstance(acc1, Known):     # the IL's ACCU1 back through 16 bits
                        il = acc1.il_value if acc1.il_value is not None else acc1.value
                        il = (il + 0x8000) % 0x10000 - 0x8000
                        acc1 = replace(acc1, il_value=None if il == acc1.value else il)
                    st.acc = (ANY if acc1 in (DINT, WIDE) else acc1,
                              ChangedBy(f"`{stmt.mnemonic.text} {op.text}` (line "
                                        f"{stmt.line})"))
            st.ner = 0
        elif m in ("CU", "CD") or m in ("S", "R") and stmt.operands and _split_area(
                stmt.operands[0].text)[0] == AREA_NAME[self.lang]["C"]:
            self.counter(stmt, st, m)
        elif m in ("=", "S", "R"):
            op = self.bit_operand(stmt, ("Q", "M"))
            self.close_term(st)
            self.emit(m, op)
            st.ner = 0
        elif m in ("FP", "FN"):
            op = self.bit_operand(stmt, ("Q", "M"))
            self.close_term(st)
            self.emit(m, op)
            st.ner = 1
        elif m in ("SET", "CLR"):
            self.no_operand(stmt)
            self.close_term(st)
            self.emit(m)
            st.ner = 0
        elif m == "NOT":
            self.no_operand(stmt)
            if st.orm != "none":
                raise self.unsupported(stmt, "NOT after `O` in an AND-before-OR "
                                       "string (S7 keeps the OR bit)")
            self.emit("NOT")
        elif m == "SAVE":                       # BR := RLO (nothing if BR is not read)
            self.no_operand(stmt)
            if ("BR",) in self.scratch_bits:
                if st.orm != "none":
                    raise self.unsupported(stmt, "`SAVE` after `O` in an AND-before-OR "
                                           "string (the RLO there is not S7's yet)")
                self.emit("=", self.scratch(("BR",)))
        elif m in ("NOP", "BLD"):               # NOP 0 / NOP 1 / BLD n: display hints
            top = 1 if m == "NOP" else 255
            if not stmt.operands:
                raise self.error(stmt.line, stmt.mnemonic.col, f"missing operand: "
                                 f"`{stmt.mnemonic.text}` needs a number 0..{top}")
            if len(stmt.operands) > 1:
                raise self.error(stmt.line, stmt.operands[1].col,
                                 f"extra operand `{stmt.operands[1].text}`")
            n = stmt.operands[0]
            if not (re.fullmatch(r"\d{1,3}", n.text) and int(n.text) <= top):
                raise self.error(stmt.line, n.col, f"malformed operand `{n.text}`: "
                                 f"`{stmt.mnemonic.text}` takes a number 0..{top}")
        elif m == "JL":
            return self.jump_list(stmt, st, edges)
        elif m in ("JBI", "JNBI"):
            return self.br_jump(stmt, st, m, edges)
        elif m == "FR":
            self.free(stmt, st)
        elif m in ("JU", "JC", "JCN", "BE", "BEU", "BEC", "JCB", "JNB"):
            if m == "JU" and isinstance(stmt.extra, str):   # an entry of a jump list
                self.pending.append(stmt.extra)
                self.emit("LD", self.local_bit(stmt, ("@", "RLO")))
            return self.jump(stmt, st, m, edges)
        elif m in ("L", "LC") and stmt.operands and _split_area(
                stmt.operands[0].text)[0] == "T" and not _split_area(
                stmt.operands[0].text)[1].startswith("#"):
            self.load_time_value(stmt, st, m)
        elif m == "LC":
            self.load_count_bcd(stmt, st)
        elif m == "LOOP":
            return self.loop(stmt, st, edges)
        elif m in CC_JUMPS:
            return self.cc_jump(stmt, st, m, edges)
        elif m in ("L", "T") + ARITHMETIC + COMPARES + ARITHMETIC_D + COMPARES_D:
            self.word_statement(stmt, st, m)
        elif m == "ITD":
            self.int_to_dint(stmt, st)
        elif m in LOGIC_W + LOGIC_D:
            self.word_logic(stmt, st, m)
        elif m in SHIFT_W + SHIFT_D:
            self.shift(stmt, st, m)
        elif m in IN_PLACE:
            self.in_place(stmt, st, m)
        elif m in COMBINE:
            raise self.error(stmt.line, stmt.mnemonic.col,
                             f"missing operand: `{stmt.mnemonic.text}` needs a bit")
        else:
            why = UNSUPPORTED_WHY.get(m)
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}`"
                                   + (f" ({why})" if why else ""))
        return True

    def prepend_timer_update(self) -> None:
        """S7 reads a timer's status from the time base; this CPU's status changes
        when the timer's instruction executes.  So OB 1 starts by executing each
        timer's instruction once more with the enable (and preset) of its last
        execution — no edge, no start: the status as at the scan's latch time — and
        copying that status into the timer's view bit, which every read of `T n`
        reads (spec §9: one consistent view per scan; also for a timer whose
        instruction a jump skips)."""
        block: list[Instr] = []
        inner: dict[str, int] = {}              # the time value updates' labels
        values: list[tuple] = []
        for n in sorted(self.timer_kinds):
            kind, stmt = self.timer_kinds[n]
            ms = self.presets.get(n)
            if ms is None:
                continue                        # never translated (pass 1 of a jump)
            where = (stmt.line, stmt.col, stmt.source)
            timer = Operand("index", area="T", index=n, text=f"T {n}")
            view = self.scratch(("view", n))
            if kind == "SE":                    # SV runs on its rising edges
                code = [("LD", self.scratch(("pulse", n)))]
            else:
                code = [("LD", self.scratch(("previous", n)))]
                if n in self.timer_resets:
                    code.append(("AN", self.scratch(("blocked", n))))
            code += [("L", Operand("const", area="TIME", value=ms, text=f"{ms}ms")),
                     (IL_TIMER[kind], timer)]
            # SI and SV run on the IL's on-delays: S7's pulse is on while that is not
            code += [("LD", view), ("AN", timer)] if kind in ("SP", "SE") else \
                [("LD", timer)]
            if ("held", n) in self.scratch_bits:
                code.append(("O", self.scratch(("held", n))))
            code.append(("=", view))
            if n in self.timer_reads:           # S7's time value at the latch time,
                values += [(mnem, op, where) for mnem, op in self.timer_running(
                    n, start=True) + self.time_value_update(n, stmt)]
            block += [Instr(mnem, op, *where) for mnem, op in code]
        for mnem, op, where in values:          # after every timer's execution
            if mnem == "@label":
                inner[op.upper()] = len(block)
                continue
            block.append(Instr(mnem, op, *where))
            block[-1].labels = [name for name, i in inner.items() if i == len(block) - 1]
        if not block:
            return
        last = block[-1]
        block.append(Instr("CLR", None, last.line, last.col, last.source))
        block[-1].labels = [name for name, i in inner.items() if i == len(block) - 1]
        if len(self.out) + len(block) > self.config.prog_words:
            raise self.error(1, 1, f"program too large: more than "
                             f"{self.config.prog_words} words (prog_words) with the "
                             "timers' scan-start update")
        self.out = block + self.out
        self.labels = {name: i + len(block) for name, i in self.labels.items()}
        self.labels.update(inner)

    # How each S7 timer instruction changes the status S7 shows, in the scan in
    # which it runs (awlsim's timers.py with cpu.now the latch time): E the enable,
    # P the last execution's, V the view.  With preset 0 the time has run out at
    # once.  IL code, leaving the result in V.
    VIEW_UPDATE = {
        ("SD", False): [("LD", "E"), ("A", "V")],             # SE: stops at E = 0
        ("SD", True): [("LD", "V"), ("ON", "P"), ("A", "E")],  # (at once, if started)
        ("SS", False): [],                                    # SS: only at run-out
        ("SS", True): [("LD", "E"), ("AN", "P"), ("O", "V")],  # a start runs out
        ("SP", False): [("LD", "V"), ("ON", "P"), ("A", "E")],  # SI: on at a rising
        ("SP", True): [("CLR", None)],                        # edge, off at E = 0
        ("SE", False): [("LD", "V"), ("O", "R")],             # SV: on at a rising
        ("SE", True): [("CLR", None)],                        # edge, whatever E
        ("SF", False): [("LD", "V"), ("O", "E"), ("O", "P")],  # SA: on at E = 1 and
        ("SF", True): [("LD", "E")],                          # at its falling edge
    }

    def counter(self, stmt: Stmt, st: _State, m: str) -> None:
        """ZV / ZR / S Z / R Z (English CU / CD / S C / R C) on the IL's: S7's
        counter holds 0..999 (the IL's 0..32767), so a count up is a pulse on S7's
        rising edge AND a count below 999; `S Z` loads the BCD value in ACCU1, known
        to the compiler, as its binary count; /FC and OR become 0, the RLO stays."""
        op = self.counter_operand(stmt)
        n = op.index
        if st.parens:
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` inside parentheses")
        if m == "S":
            known, count = self.known_constant(
                stmt, st, _bcd_decode, f"`{stmt.mnemonic.text} {op.text}` with a value",
                "a C# constant (or a W#16# BCD)")
            in_place = bool(self.out) and self.out[-1] is self.last_load
            self.close_term(st)
            if n in self.counter_frees:         # S7's edge, which FR clears
                self.emit_code(self.edge_pulse(n, "s") + self.clear_il_edge("S", op) +
                               [("LD", self.scratch(("s-pulse", n)))])
            self.with_acc1(st, known, count, in_place, "INT", ("S", op))
            if n in self.counter_frees:
                self.emit_code([("LD", self.scratch(("s-enable", n))),
                                ("=", self.scratch(("s-previous", n)))])
        elif m == "CU":
            self.close_term(st)
            enable = self.scratch(("cu-enable", n))
            previous = self.scratch(("cu-previous", n))
            pulse = self.scratch(("cu-pulse", n))
            self.emit("=", enable)
            self.emit("AN", previous)
            self.emit("=", pulse)
            if n in self.counter_frees:
                self.emit_code(self.clear_il_edge("CU", op))
            self.emit("L", op)
            self.emit("L", Operand("const", area="INT", value=999, text="999"))
            self.emit("<I")
            self.emit("A", pulse)
            self.emit("CU", op)
            self.emit("LD", enable)
            self.emit("=", previous)
            st.acc = (CLOBBERED, CLOBBERED)
        elif m == "CD" and n in self.counter_frees:
            self.close_term(st)
            self.emit_code(self.edge_pulse(n, "cd") + self.clear_il_edge("CD", op) + [
                ("LD", self.scratch(("cd-pulse", n))),
                (m, op), ("LD", self.scratch(("cd-enable", n))),
                ("=", self.scratch(("cd-previous", n)))])
        else:                                   # ZR (CD), R Z (R C)
            self.close_term(st)
            self.emit(m, op)
        st.ner = 0

    def edge_pulse(self, n: int, name: str) -> list[tuple[str, Operand | None]]:
        """With the RLO = S7's input: its enable bit := RLO, the RLO := the pulse of
        its rising edge against S7's edge memory (`<name>-previous`, which FR may
        clear), also kept in `<name>-pulse`.  The IL instruction after it then sees
        exactly S7's edges; the caller sets `<name>-previous` := enable after it."""
        enable, previous, pulse = (self.scratch((f"{name}-{k}", n))
                                   for k in ("enable", "previous", "pulse"))
        return [("=", enable), ("AN", previous), ("=", pulse)]

    @staticmethod
    def clear_il_edge(mnem: str, op: Operand) -> list[tuple[str, Operand | None]]:
        """The IL instruction once with RLO 0: its own edge memory 0, nothing else
        (after an FR two pulses of S7's edges may follow each other)."""
        return [("CLR", None), (mnem, op)]

    def free(self, stmt: Stmt, st: _State) -> None:
        """`FR T n` / `FR Z n` (English `FR C n`): on a rising RLO (against FR's own
        edge memory) S7 clears the edge memories of the timer's start / of the
        counter's ZV, ZR and S, so that the next of them with RLO 1 counts as an
        edge (awlsim's timers.py / counters.py run_FR); the RLO stays, OR and /FC
        become 0.  A counter's edge memories are the translation's bits: reset at
        once.  A timer's is also the enable of the scan-start update, so its
        `freed` bit is set and its next instruction takes it into account."""
        if st.parens:
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` inside parentheses")
        area = _split_area(stmt.operands[0].text)[0] if stmt.operands else ""
        timer = area == "T"
        op = self.timer_operand(stmt) if timer else self.counter_operand(stmt)
        n = op.index
        self.close_term(st)
        rlo = self.local_bit(stmt, ("@", "RLO"))
        code = [("=", rlo), ("AN", self.scratch(("fr-previous" if timer else
                                                 "cfr-previous", n)))]
        if timer:
            code.append(("S", self.scratch(("freed", n))))
        else:
            code += [("R", self.scratch((f"{k}-previous", n))) for k in ("cu", "cd", "s")
                     if (f"{k}-previous", n) in self.scratch_bits]
        code += [("LD", rlo), ("=", self.scratch(("fr-previous" if timer else
                                                  "cfr-previous", n)))]
        self.emit_code(code)
        st.ner = 0

    def known_acc1(self, stmt: Stmt, st: _State) -> Known | None:
        """ACCU1 for a timer preset or a counter value: what the compiler knows of
        it (None: a value it does not know)."""
        known = st.acc[0]
        if not (isinstance(known, Known) and known.il_value is not None):
            self.read_acc(stmt, st, 1)
        return known if isinstance(known, Known) else None

    def known_constant(self, stmt: Stmt, st: _State, decode, what: str, load: str):
        """ACCU1 known to the compiler and decoded (a counter's BCD value, a timer's
        S5TIME preset): (known, decoded), or `unsupported:` naming what to load."""
        known = self.known_acc1(stmt, st)
        value = decode(known.value) if known is not None else None
        if value is None:
            raise self.unsupported(stmt, f"{what} the compiler does not know: load {load} "
                                   "in this scan")
        return known, value

    def with_acc1(self, st: _State, known: Known, il_value: int, in_place: bool,
                  area: str, instr: tuple[str, Operand]) -> None:
        """Emit `instr` with the IL's ACCU1 = il_value (S7's holds known.value):
        the `L` right before it is changed (in_place; ACCU1 then differs from S7's
        until the next load), or il_value is loaded and S7's value loaded back
        (ACCU2 then differs)."""
        value = Operand("const", area=area, value=il_value,
                        text=f"{il_value}ms" if area == "TIME" else str(il_value))
        if known.value == il_value and known.il_value is None:
            self.emit(*instr)                   # the same number for both (C#5)
            return
        if known.il_value == il_value:          # the IL's ACCU1 holds it already
            in_place = True
        elif in_place:
            self.last_load.operand = value
        else:
            self.emit("L", value)
        self.emit(*instr)
        if in_place:
            st.acc = (Known(known.value, il_value=il_value), st.acc[1])
        else:
            self.emit("L", Operand("const", area="INT", value=known.value,
                                   text=f"W#16#{known.value & 0xFFFF:04X}"))
            st.acc = (st.acc[0], CLOBBERED)

    def timer(self, stmt: Stmt, st: _State, m: str) -> None:
        """SI / SE / SS / SA (English SP / SD / SS / SF) on the IL's SD / SS / SF:
        the enable is the RLO (S7's, so an AND term is closed first), the preset the
        S5TIME in ACCU1, known to the compiler; the view bit follows S7; /FC and OR
        become 0, the RLO stays."""
        op = self.timer_operand(stmt)
        n = op.index
        if st.parens:
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` inside parentheses")
        known, ms = self.known_constant(
            stmt, st, _s5t_decode, f"`{stmt.mnemonic.text}` with a preset",
            "an S5T# constant (or a W#16# S5TIME)")
        if self.presets.setdefault(n, ms) != ms:
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` with another preset "
                                   f"than the first start of `{op.text}` "
                                   "(one preset per timer: the scan-start update "
                                   "needs it)")
        if n in self.timer_reads:
            base = (known.value >> 12) & 3
            first = self.timebases.setdefault(n, (base, stmt))
            if first[0] != base:
                raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` with a preset in "
                                       "another time base than its start at line "
                                       f"{first[1].line} (`L`/`LC` of `{op.text}` "
                                       "read the time value in one time base)")
        in_place = bool(self.out) and self.out[-1] is self.last_load
        self.close_term(st)
        bits = {"E": self.scratch(("enable", n)), "P": self.scratch(("previous", n)),
                "V": self.scratch(("view", n))}
        self.emit("=", bits["E"])
        freed = self.scratch(("freed", n)) if n in self.timer_frees else None
        if freed:                               # after an FR S7's edge memory is 0
            self.emit_code([("LD", bits["P"]), ("AN", freed), ("=", bits["P"]),
                            ("LD", bits["E"])])
        if m == "SE":
            # SV (the extended pulse) on the IL's retentive on-delay: at S7's rising
            # edge R T n and a start, which runs out whatever the input does
            bits["R"] = self.scratch(("pulse", n))
            self.emit("AN", bits["P"])
            self.emit("=", bits["R"])
            self.emit("R", op)
        elif n in self.timer_resets:
            # S7 keeps the edge memory across `R T n`, this CPU clears it: after a
            # reset the IL timer's enable is held at 0 until S7's input falls
            blocked = self.scratch(("blocked", n))
            self.emit("A", blocked)
            self.emit("A", bits["P"])
            self.emit("=", blocked)
            self.emit("LD", bits["E"])
            self.emit("AN", blocked)
        if freed:
            # the IL timer's own edge memory is its last enable: it first runs with
            # the enable 0 where an FR freed it, so that an enable of 1 now is its
            # rising edge too (SV restarts by its pulse and `R T n` already)
            enable = [("LD", bits["E"])] + ([("AN", self.scratch(("blocked", n)))]
                                           if n in self.timer_resets else [])
            if m != "SE":
                self.emit_code([("AN", freed), ("L", Operand(
                    "const", area="TIME", value=ms, text=f"{ms}ms")), (IL_TIMER[m], op)]
                    + enable)
                known, in_place = Known(known.value, il_value=ms), True
                st.acc = (known, CLOBBERED)
            self.emit_code([("SET", None), ("R", freed)] + (
                enable if m != "SE" else [("LD", bits["R"])]))
        self.with_acc1(st, known, ms, in_place, "TIME", (IL_TIMER[m], op))
        if freed and m == "SD":
            # S7's on-delay restarted by an FR keeps its status (awlsim's run_SE
            # starts without clearing it), the IL's restart clears it: `held` keeps
            # S7's status of 1 while the input stays 1, for the scan-start update
            held = self.scratch(("held", n))
            self.emit_code([("LD", bits["V"]), ("O", held), ("A", bits["E"]),
                            ("=", held), ("LD", bits["E"])])
        code = self.VIEW_UPDATE[(m, ms == 0)]
        for mnem, name in code:
            self.emit(mnem, bits[name] if name else None)
        if code:
            self.emit("=", bits["V"])
        if n in self.timer_reads:
            self.emit_code(self.timer_running(n, start=False) + self.time_value_update(
                n, self.stmt, reload=st.acc[0], started=True))
            st.acc = (st.acc[0], CLOBBERED)
        self.emit("LD", bits["E"])
        self.emit("=", bits["P"])
        st.ner = 0

    # S7's time value of a timer that `L T n` / `LC T n` read (docs/s7.md, "Time
    # values"): two words the translation keeps, updated after each execution of the
    # IL timer while its elapsed time stands for S7's remaining time, left alone
    # (frozen, as S7 leaves it) while it does not.
    def timer_running(self, n: int, start: bool) -> list[tuple[str, Operand | None]]:
        """IL code leaving in the RLO, start=True: whether, after the scan-start
        update's execution of IL timer n, S7's remaining time is the preset minus
        its elapsed time — SD and SP (S7's SE, SI) while the IL enable is 1 (a
        run-out included: 0 left), SS and SV from a start until `R T n` (the `run`
        bit), SA while its input is 0 after having been 1 (the `armed` bit);
        start=False (at the timer's instruction): those bits kept, then whether this
        execution starts S7's timer (an edge of its input: rising, SA's falling), the
        only change of S7's time value within a scan."""
        kind = self.timer_kinds[n][0]
        enable, previous = self.scratch(("enable", n)), self.scratch(("previous", n))
        blocked = [("AN", self.scratch(("blocked", n)))] if n in self.timer_resets \
            and kind != "SE" else []
        if kind in ("SD", "SP"):
            return [("LD", previous)] + blocked if start else [
                ("LD", enable), ("AN", previous)]
        if kind == "SF":
            armed = self.scratch(("armed", n))
            return [("LDN", previous), ("A", armed)] if start else [
                ("LD", enable), ("O", armed), ("=", armed), ("LDN", enable),
                ("A", previous)]
        run = self.scratch(("run", n))
        if start:
            return [("LD", run)]
        on = [("LD", self.scratch(("pulse", n)))] if kind == "SE" else \
            [("LD", enable)] + blocked
        return on + [("O", run), ("=", run), ("LD", enable), ("AN", previous)]

    def time_value_word(self, stmt: Stmt, n: int, form: str) -> Operand:
        """The word holding timer n's time value as `L T n` (form "L": binary, in
        its time base) or `LC T n` ("LC": BCD with the time base) load it."""
        return self.scratch_word(stmt, f"T{n}.{form}")

    def time_value_dword(self, stmt: Stmt, n: int) -> Operand:
        """A double word of block-local words for timer n's remaining ms (MD n is
        MW n and MW n+2: two words allocated one after the other)."""
        low = self.scratch_word(stmt, f"T{n}.ms")
        high = self.scratch_word(stmt, f"T{n}.ms+2")
        assert high.index == low.index + 2, (low, high)
        return Operand("index", area="MD", index=low.index, text=f"MD{low.index}")

    def time_value_update(self, n: int, stmt: Stmt, reload=None, started=False
                          ) -> list[tuple[str, Operand | None]]:
        """With the RLO = timer_running: the words of time_value_word := S7's
        remaining time in the preset's time base, rounded (awlsim rounds the
        remaining seconds over the base), and as BCD with the time base in bits
        13..12; jumped over otherwise.  The IL timer runs on its scan's latch time as
        S7's does (at_latch): the remaining time is preset - elapsed, at least 0.
        `started`: the RLO says the timer has just started — its time value is the
        preset's (constants).  `reload`: what the compiler knows of ACCU1, loaded
        back afterwards (ACCU2 is then changed)."""
        label = self.value_label()
        ms, base = self.presets[n], self.timebases[n][0]
        tb = (10, 100, 1000, 10_000)[base]
        forms = self.timer_reads[n]

        def const(value: int) -> Operand:
            return Operand("const", area="INT" if -32768 <= value <= 32767 else "DINT",
                           value=value, text=str(value))

        def timer(k: int) -> Operand:
            return Operand("index", area="T", index=k, text=f"T {k}")
        binary = self.time_value_word(stmt, n, "L")
        code = [("JCN", Operand("label", label=label, text=label))]
        if started:
            units = ms // tb                    # S5TIME: ms = units * tb
            code += [("L", const(units)), ("T", binary)]
            if "LC" in forms:
                code += [("L", const(base << 12 | int(f"{units:03d}", 16))),
                         ("T", self.time_value_word(stmt, n, "LC"))]
        else:
            # r = max(0, preset - elapsed) ms; L T n: r over the base, rounded
            # (awlsim: round(); `L`'s in every base, `LC`'s in 10 ms, 100 ms)
            zero, store = f"{label}.0", f"{label}.1"
            code += [("L", const(ms)), ("L", timer(n)), ("-D", None),
                     ("L", const(0)), (">D", None),
                     ("JCN", Operand("label", label=zero, text=zero)),
                     ("+D", None), ("JU", Operand("label", label=store, text=store)),
                     ("@label", zero), ("L", const(0)), ("@label", store)]
            units = binary
            if "LC" in forms and base >= 2:
                # awlsim's S5TIME of the 1 s base truncates the seconds, of the 10 s
                # base rounds them and then truncates over 10 (timers.py
                # _seconds_to_s5t_tb1s / _tb10s): r kept in a double word for it
                r = self.time_value_dword(stmt, n)
                units = self.time_value_word(stmt, n, "units")
                code += [("T", r)]
            code += [("L", const(tb // 2)), ("+D", None), ("L", const(tb)), ("/D", None),
                     ("T", binary)]
            if units is not binary:
                code += [("L", r), ("L", const(1000)), ("/D", None)] if base == 2 else [
                    ("L", r), ("L", const(500)), ("+D", None), ("L", const(1000)),
                    ("/D", None), ("L", const(10)), ("/D", None)]
                code.append(("T", units))
            if "LC" in forms:                   # v + 6 (q + 16 h): load_count_bcd's
                tens = self.scratch_word(stmt, "LC.TENS")
                code += [("L", const(10)), ("/I", None), ("T", tens), ("L", const(10)),
                         ("/I", None), ("L", const(16)), ("*I", None), ("L", tens),
                         ("+I", None), ("L", const(6)), ("*I", None), ("L", units),
                         ("+I", None)] + ([("L", const(base << 12)), ("+I", None)]
                                          if base else []) + [
                         ("T", self.time_value_word(stmt, n, "LC"))]
        if isinstance(reload, Known):
            code.append(("L", Operand("const", area="TIME", value=reload.il_value,
                                      text=f"{reload.il_value}ms")
                         if reload.il_value is not None else const(reload.value)))
        return code + [("@label", label)]

    def value_label(self) -> str:
        """A fresh label of the time values' own code (no S7 label starts with @)."""
        self.value_labels += 1
        return f"@TV{self.value_labels - 1}"

    def time_value_reset(self, n: int, stmt: Stmt) -> list[tuple[str, Operand | None]]:
        """`R T n` with the RLO = 1: S7's time value 0, its time base kept."""
        label = self.value_label()
        code = [("JCN", Operand("label", label=label, text=label)),
                ("L", Operand("const", area="INT", value=0, text="0")),
                ("T", self.time_value_word(stmt, n, "L"))]
        if "LC" in self.timer_reads[n]:
            bcd = self.time_value_word(stmt, n, "LC")
            code += [("L", bcd), ("L", Operand("const", area="INT", value=0x3000,
                                               text="W#16#3000")),
                     ("AW", None), ("T", bcd)]
        return code + [("@label", label)]

    def emit_code(self, code: list[tuple[str, Operand | None]]) -> None:
        for mnem, op in code:
            if mnem == "@label":
                self.pending.append(op)
            else:
                self.emit(mnem, op)

    def load_time_value(self, stmt: Stmt, st: _State, form: str) -> None:
        """`L T n` / `LC T n`: S7 pushes ACCU1 into ACCU2 and loads the timer's
        time value (binary / BCD with the time base), status bits unchanged."""
        n = self.timer_operand(stmt).index
        self.emit("L", self.time_value_word(stmt, n, form))
        st.acc = (ANY, st.acc[0])

    # -- word instructions -----------------------------------------------------------

    def read_acc(self, stmt: Stmt, st: _State, which: int) -> None:
        """`stmt` reads ACCU<which>: it must have been loaded in this scan."""
        value = st.acc[which - 1]
        if value is None:
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` reads ACCU{which}, "
                                   "which this OB has not loaded here (what an OB finds "
                                   "in the accumulators at its start is no program's to "
                                   "rely on: awlsim clears them at each OB's start, this "
                                   "CPU at each scan's): load it first")
        if isinstance(value, ChangedBy):
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` reads ACCU{which}, "
                                   f"which the translation of {value.what} changed (S7 "
                                   "leaves it alone): load it first")
        if value == CLOBBERED or isinstance(value, Known) and value.il_value is not None:
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` reads ACCU{which}, "
                                   "which the translation of an earlier timer or "
                                   "counter instruction, block call, jump list, "
                                   "`LOOP` or `+ n` changed (S7 leaves it alone)")

    def read_dint(self, stmt: Stmt, st: _State, which: int) -> None:
        """`stmt` reads ACCU<which> as a DINT: the IL's 32 bits must be S7's (a DINT
        loaded or computed, ITD, or an INT constant >= 0).  S7's `L` of a word or of a
        negative INT constant zero-extends it where the IL sign-extends, and S7's INT
        arithmetic leaves ACCU1-H as it was (`+I`) or holds the product / remainder
        there (`*I`, `/I`), which the IL does not keep."""
        self.read_acc(stmt, st, which)
        value = st.acc[which - 1]
        if value in (DINT, TOP) or isinstance(value, Known) and value.il_value is None \
                and value.value >= 0:           # TOP: a later pass knows the label
            return
        raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` reads ACCU{which} as a "
                               "DINT, but its high word here need not be S7's (S7's `L` "
                               "of a word or of a negative INT constant zero-extends it, "
                               "its INT arithmetic leaves or sets the high word in ways "
                               "the IL does not keep): make it a DINT first (`ITD`, "
                               "`L L#n`, `L MD n`)")

    def word_statement(self, stmt: Stmt, st: _State, m: str) -> None:
        if m == "L":
            op, known = self.load_operand(stmt)
            self.emit("L", op)
            self.last_load = self.out[-1]
            dint = op.area in ("DINT", "MD")
            st.acc = (known if known is not None else DINT if dint else ANY, st.acc[0])
        elif m == "T":
            op = self.word_operand(stmt, ("QW", "MW", "MD"))
            if op.area == "MD":
                self.read_dint(stmt, st, 1)
            self.read_acc(stmt, st, 1)
            self.emit("T", op)
        elif m in ARITHMETIC + ARITHMETIC_D:
            self.no_operand(stmt)
            dint = m in ARITHMETIC_D
            for which in (1, 2):
                (self.read_dint if dint else self.read_acc)(stmt, st, which)
            self.emit(IL_DINT.get(m, m))
            st.acc = (DINT if dint else ANY, st.acc[1])
            st.cc_ok |= CC_OV
        else:                                   # a compare: RLO := result, OR := 0
            self.no_operand(stmt)
            for which in (1, 2):
                (self.read_dint if m in COMPARES_D else self.read_acc)(stmt, st, which)
            self.close_term(st)
            self.emit(m)
            st.ner = 1
            st.cc_ok |= CC_OV

    def word_logic(self, stmt: Stmt, st: _State, m: str) -> None:
        """`UW`/`OW`/`XOW` (English `AW`/`OW`/`XOW`): S7 combines ACCU1-L with ACCU2-L
        or with a constant and keeps ACCU1-H; `UD`/`OD`/`XOD` all 32 bits (awlsim's
        insn_uw.py ... insn_xod.py).  ACCU2 is left alone.  Here the IL's `AW` ...
        `XOD` combine with ACCU2; with a constant `L c` comes first, which changes
        ACCU2 (an instruction that reads it before the next load is rejected)."""
        dint = m in LOGIC_D
        read = self.read_dint if dint else self.read_acc
        ops = stmt.operands
        if ops:
            value, word = self.immediate(stmt)
            if not dint and not 0 <= value <= 0xFFFF:
                raise self.error(stmt.line, word.col, f"constant out of range: "
                                 f"`{word.text}` (`{stmt.mnemonic.text}` takes 16 bits)")
            read(stmt, st, 1)
            area = "INT" if -32768 <= value <= 32767 else "DINT"
            self.emit("L", Operand("const", area=area, value=value, text=word.text))
            self.emit(m)
            st.acc = (DINT if dint else ANY,
                      ChangedBy(f"`{stmt.mnemonic.text} {word.text}` (line {stmt.line})"))
            st.cc_ok |= CC_OV
            return
        read(stmt, st, 1)
        read(stmt, st, 2)
        self.emit(m)
        st.acc = (DINT if dint else ANY, st.acc[1])
        st.cc_ok |= CC_OV

    def immediate(self, stmt: Stmt) -> tuple[int, Word]:
        """The constant operand of a word logic or shift instruction as S7's immediate
        (an INT or a 16-bit pattern zero-extended, a DINT form as its 32 bits; `C#n`
        as its BCD pattern), and the word as written; `B#(…)` put together again.
        S5TIME, TIME, REAL, characters and addresses are not immediates (awlsim
        rejects them: an invalid operator type)."""
        ops = stmt.operands
        if len(ops) > 1 and ops[1].text == "(" and ops[0].text.upper() == "B#":
            ops = [Word("".join(w.text for w in ops), ops[0].col)]
        if len(ops) > 1:
            raise self.error(stmt.line, ops[1].col, f"extra operand `{ops[1].text}`")
        word = ops[0]
        up = word.text.upper()
        if not re.match(r"[+-]?\d|(W#|B#|DW#|L#|C#)?\d*#?|B#\(", up) or re.match(
                r"(S5T|S5TIME|T|TIME|D|TOD|P|DATE)#|'", up) or not (
                up[0].isdigit() or up[0] in "+-" or "#" in up):
            raise self.error(stmt.line, word.col, f"invalid operand `{word.text}`: "
                             f"`{stmt.mnemonic.text}` takes an integer constant")
        value = self.dint_constant(stmt, word)
        if value is None:
            value = self.constant(stmt, word).value & 0xFFFF
        return value, word

    def shift(self, stmt: Stmt, st: _State, m: str) -> None:
        """`SLW`/`SRW`/`SSI n` shift ACCU1-L (S7 keeps ACCU1-H), `SLD`/`SRD`/`SSD`/
        `RLD`/`RRD n` all of ACCU1 (awlsim's insn_slw.py ... insn_rrd.py); without n
        the count is ACCU2's low byte.  The IL's instructions of the same names do
        the same (a count of 0 leaves ACCU1 as it is, in both)."""
        dint = m in SHIFT_D
        ops = stmt.operands
        count = None
        if ops:
            count, word = self.immediate(stmt)
            if not 0 <= count <= 255:
                raise self.error(stmt.line, word.col, f"constant out of range: "
                                 f"`{word.text}` (a shift count is 0..255)")
        (self.read_dint if dint else self.read_acc)(stmt, st, 1)
        if count is None:
            self.read_acc(stmt, st, 2)
        self.emit(m, None if count is None else
                  Operand("const", area="INT", value=count, text=str(count)))
        before = st.acc[0]
        if dint:
            after = DINT
        elif count == 0:
            after = before                      # nothing changes, in S7 and here
        elif count is None and before in (DINT, WIDE):
            after = WIDE                        # a count of 0 leaves the IL's 32 bits
        else:
            after = ANY
        st.acc = (after, st.acc[1])
        if count:                               # a count of 0 changes no status bit
            st.cc_ok |= CC_OV                   # (from ACCU2: maybe 0, kept as it was)

    def int_to_dint(self, stmt: Stmt, st: _State) -> None:
        """`ITD`: S7 sign-extends ACCU1-L into ACCU1 and leaves ACCU2 alone (awlsim's
        insn_itd.py).  The IL's ACCU1 already holds INT(S7's ACCU1) sign-extended
        after every INT instruction: nothing to do.  After a DINT one it may hold
        more: `L 0`, `+I` (INT(x) + 0, sign-extended), which changes ACCU2."""
        self.no_operand(stmt)
        self.read_acc(stmt, st, 1)
        if st.acc[0] in (DINT, WIDE):
            self.emit("L", Operand("const", area="INT", value=0, text="0"))
            self.emit("+I")
            st.acc = (DINT, ChangedBy(f"`{stmt.mnemonic.text}` (line {stmt.line})"))
            st.cc_ok = frozenset()              # S7's ITD changes no status bit
        else:
            st.acc = (DINT, st.acc[1])

    def scratch_word(self, stmt: Stmt, name: str) -> Operand:
        """A word of the block-local region the translation keeps for itself
        (MW 128 .. MW 190, as the jump lists' index word)."""
        word = self.cell(stmt, Binding(decl=Decl(name, "TEMP", "INT", 0, 0),
                                       cell=("@", name)), stmt.col)[0]
        return Operand("index", area="MW", index=int(word.text[2:]), text=word.text)

    def load_count_bcd(self, stmt: Stmt, st: _State) -> None:
        """`LC Z n` (English `LC C n`): S7 pushes ACCU1 into ACCU2 and loads the
        count c (0..999) as 3 BCD digits, changing no status bit (awlsim's
        insn_lc.py, counters.py getValueBCD).  The IL has the binary count
        (`L C n`) and no BCD conversion; with q = c / 10 and h = q / 10 the BCD
        pattern 256 h + 16 (q MOD 10) + c MOD 10 is c + 6 (q + 16 h), made of the
        IL's L, T, /I, *I, +I, which leave the RLO alone.  ACCU1 is saved in a
        scratch word first and loaded back before the result, so that ACCU2 is
        S7's too (both left out when ACCU1 was not loaded here)."""
        op = self.counter_operand(stmt)
        keep = st.acc[0] is not None
        old, count, tens = (self.scratch_word(stmt, name)
                            for name in ("LC.ACCU1", "LC.COUNT", "LC.TENS"))

        def const(value: int) -> Operand:
            return Operand("const", area="INT", value=value, text=str(value))

        if keep:
            self.emit("T", old)
        for mnem, operand in (("L", op), ("T", count), ("L", const(10)), ("/I", None),
                              ("T", tens), ("L", const(10)), ("/I", None),
                              ("L", const(16)), ("*I", None), ("L", tens), ("+I", None),
                              ("L", const(6)), ("*I", None), ("L", count),
                              ("+I", None)):
            self.emit(mnem, operand)
        if keep:
            self.emit("T", count)
            self.emit("L", old)
            self.emit("L", count)
        # ACCU2 is S7's old ACCU1 through a 16-bit word: INT(.) of it, sign-extended
        old_acc1 = ANY if st.acc[0] in (DINT, WIDE) else st.acc[0]
        st.acc = (ANY, old_acc1)

    def in_place(self, stmt: Stmt, st: _State, m: str) -> None:
        """`+ n` (an INT constant), `NEGI`, `INVI`: S7 changes ACCU1-L and leaves
        ACCU2 alone (awlsim's insn_pl.py, insn_negi.py, insn_invi.py); here the IL
        steps of IN_PLACE (`L n`, `+I`; `L -1`, `*I`; `L -1`, `*I`, `L -1`, `+I`:
        -x-1 is the ones' complement), which give the same ACCU1-L but change
        ACCU2 (an instruction that reads it before the next load is rejected)."""
        steps = IN_PLACE[m]
        dint = m in ("NEGD", "INVD")
        if m != "+":
            self.no_operand(stmt)
        else:
            ops = stmt.operands
            if not ops:
                raise self.error(stmt.line, stmt.mnemonic.col,
                                 "missing operand: `+` needs an INT constant")
            if len(ops) > 1:
                raise self.error(stmt.line, ops[1].col, f"extra operand `{ops[1].text}`")
            if not re.match(r"[+-]?\d|[A-Z0-9#]*#|'", ops[0].text, re.I):
                raise self.error(stmt.line, ops[0].col, f"malformed operand "
                                 f"`{ops[0].text}`: `+` takes a constant")
            n = self.dint_constant(stmt, ops[0])
            if n is not None:                               # + L#n: S7 adds a DINT
                dint, steps = True, (n, "+D")
            elif not re.fullmatch(r"[+-]?\d+", ops[0].text):
                raise self.unsupported(stmt, f"`+ {ops[0].text}` (`+` adds INT and DINT "
                                       "constants; others are not supported)", ops[0].col)
            else:
                n = self.constant(stmt, ops[0]).value
                steps = tuple(n if s == "n" else s for s in steps)
        (self.read_dint if dint else self.read_acc)(stmt, st, 1)
        for s in steps:
            if isinstance(s, int):
                area = "DINT" if not -32768 <= s <= 32767 else "INT"
                self.emit("L", Operand("const", area=area, value=s, text=str(s)))
            else:
                self.emit(s)
        written = " ".join([stmt.mnemonic.text] + [w.text for w in stmt.operands])
        st.acc = (DINT if dint else ANY, ChangedBy(f"`{written}` (line {stmt.line})"))

    def load_operand(self, stmt: Stmt) -> tuple[Operand, Known | None]:
        """The operand of `L`: a constant (with what the compiler knows of it) or a
        word IW/QW/MW."""
        ops = stmt.operands
        if not ops:
            raise self.error(stmt.line, stmt.mnemonic.col,
                             f"missing operand: `{stmt.mnemonic.text}` needs a value")
        text = ops[0].text
        if text.upper().startswith("P#"):
            raise self.unsupported(stmt, "pointer constant `" + " ".join(
                w.text for w in ops) + "` (no address registers, no indirect "
                "addressing)", ops[0].col)
        if text.upper() == "B#" and len(ops) > 1 and ops[1].text == "(":
            # B#(1, 2): the tokens of the parenthesis put together again
            text = "".join(w.text for w in ops)
            ops = [Word(text, ops[0].col)]
        if text[0].isdigit() or text[0] in "+-" or "#" in text or text[0] == "'":
            if len(ops) > 1:
                raise self.error(stmt.line, ops[1].col, f"extra operand `{ops[1].text}`")
            value = self.dint_constant(stmt, ops[0])
            if value is not None:
                return Operand("const", area="DINT", value=value, text=text), None
            known = self.constant(stmt, ops[0])
            return Operand("const", area="INT", value=known.value, text=text), known
        return self.word_operand(stmt, ("IW", "QW", "MW", "MD", "C")), None

    def dint_constant(self, stmt: Stmt, word: Word) -> int | None:
        """An S7 32-bit constant as the DINT it loads (`L#n`, `DW#16#…`, `2#` of 17..32
        digits, `B#(b1, b2, b3, b4)`), or None for any other text."""
        up = word.text.upper()

        def bad(what: str) -> SourceError:
            return self.error(stmt.line, word.col, what)

        def signed(value: int) -> int:
            return value - (1 << 32) if value & 0x80000000 else value

        if up.startswith("L#"):
            m = re.fullmatch(r"L#([+-]?)(\d+)", up)
            if not m:
                raise bad(f"malformed constant `{word.text}`: L#<decimal>")
            value = -int(m.group(2)) if m.group(1) == "-" else int(m.group(2))
            if not -2 ** 31 <= value < 2 ** 31:
                raise bad(f"constant out of range: `{word.text}` (DINT is "
                          "-2147483648..2147483647)")
            return value
        if up.startswith("DW#16#"):
            if not re.fullmatch(r"DW#16#[0-9A-F]+(_[0-9A-F]+)*", up) \
                    or int(up[6:].replace("_", ""), 16) > 0xFFFFFFFF:
                raise bad(f"malformed constant `{word.text}`: DW#16#0..DW#16#FFFFFFFF")
            return signed(int(up[6:].replace("_", ""), 16))
        m = re.fullmatch(r"2#([01]+(?:_[01]+)*)", up)
        if m and 0xFFFF < int(m.group(1).replace("_", ""), 2) <= 0xFFFFFFFF:
            return signed(int(m.group(1).replace("_", ""), 2))
        m = re.fullmatch(r"B#\((\d{1,3}),(\d{1,3}),(\d{1,3}),(\d{1,3})\)", up)
        if m and all(int(b) <= 255 for b in m.groups()):
            value = 0
            for b in m.groups():
                value = value << 8 | int(b)
            return signed(value)
        return None

    def constant(self, stmt: Stmt, word: Word) -> Known:
        """An S7 constant as the 16-bit pattern S7 loads (INT, W#16#, B#16#, 16#, 2#,
        S5T#, C#); any other (DINT, REAL, TIME, pointers, strings) is unsupported."""
        text = word.text
        up = text.upper()

        def bad(what: str) -> SourceError:
            return self.error(stmt.line, word.col, what)

        def pattern(value: int) -> int:
            return value - 0x10000 if value & 0x8000 else value

        prefix, sep, digits = up.rpartition("#")
        bases = {"W#16": 16, "B#16": 16, "16": 16, "2": 2, "W#2": 2, "B#2": 2}
        if up.startswith("'"):
            raise bad(f"unsupported: character constant `{text}` (this slice loads "
                      "INT, W#16#, B#16#, 2#, S5T# and C# constants)")
        if not sep and re.fullmatch(r"[+-]?\d+(\.\d*)?(E[+-]?\d+)?", up) and (
                "." in up or "E" in up):
            raise bad(f"unsupported: REAL constant `{text}` (no floating point in the "
                      "byte processor)")
        if not sep:
            sign, body = (up[0], up[1:]) if up[0] in "+-" else ("", up)
            if not body.isdigit():
                raise bad(f"malformed constant `{text}`")
            value = -int(body) if sign == "-" else int(body)
            if not -32768 <= value <= 32767:
                raise bad(f"unsupported: constant `{text}` beyond INT (-32768..32767; "
                          f"awlsim, too, rejects it): write the DINT as `L#{value}`")
            return Known(value)
        if up.startswith("B#("):
            m = re.fullmatch(r"B#\((\d{1,3})((?:,\d{1,3})*)\)", up)
            parts = [m.group(1)] + m.group(2).split(",")[1:] if m else []
            if not parts or any(int(b) > 255 for b in parts) or len(parts) not in (2, 4):
                raise bad(f"malformed constant `{text}`: B#(b1, b2), bytes 0..255")
            if len(parts) == 4:
                raise bad(f"unsupported: 32-bit constant `{text}` where a 16-bit "
                          "value is needed (`L` loads it as a DINT)")
            return Known(pattern(int(parts[0]) << 8 | int(parts[1])))
        if prefix == "16":
            raise bad(f"malformed constant `{text}`: STL writes a hexadecimal constant "
                      "as W#16#… or B#16#…")
        if prefix in bases:
            base = bases[prefix]
            limit = 0xFF if prefix.startswith("B#") else 0xFFFF
            digit = "[01]" if base == 2 else "[0-9A-F]"
            if not re.fullmatch(rf"{digit}+(_{digit}+)*", digits):
                raise bad(f"malformed constant `{text}`: digits "
                          f"{'0, 1' if base == 2 else '0..9, A..F'} expected")
            value = int(digits.replace("_", ""), base)
            if prefix == "2" and limit < value <= 0xFFFFFFFF:
                raise bad(f"unsupported: 32-bit constant `{text}` where a 16-bit "
                          "value is needed (`L` loads it as a DINT)")
            if value > limit:
                raise bad(f"constant out of range: `{text}`")
            return Known(pattern(value))
        if prefix in ("S5T", "S5TIME"):
            ms = _s5t_ms(digits)
            if ms is None:
                raise bad(f"malformed constant `{text}`: S5T# with parts <n>H <n>M "
                          "<n>S <n>MS, largest first, at most S5T#2H46M30S")
            return _s5t_known(ms)
        if prefix == "C":
            if not digits.isdigit() or int(digits) > 999:
                raise bad(f"malformed constant `{text}`: C#0..C#999")
            n = int(digits)
            return Known(int(str(n), 16), count=n)
        raise bad(f"unsupported: constant `{text}` (this slice loads INT, W#16#, "
                  "B#16#, 2#, S5T# and C# constants)")

    def word_operand(self, stmt: Stmt, areas: tuple[str, ...]) -> Operand:
        """`EW 2` / `IW2` / `AW 4` / `MW 10` -> a word Operand (English area)."""
        first, canon, rest, written = self.address(stmt, "word")
        if canon not in areas:
            if canon == "IW" and stmt.canon == "T":
                raise self.unsupported(stmt, f"`{stmt.mnemonic.text} {written}` writes "
                                       "the input image (word inputs are stimuli "
                                       "here)", first.col)
            if canon in ("I", "Q", "M") and canon + "W" in areas or canon in WORD_AREAS:
                raise self.error(stmt.line, first.col,
                                 f"operand of the wrong kind: `{stmt.mnemonic.text}` "
                                 f"needs a word, not `{written}`")
            what = {"T": "the remaining time of a timer", "C": "a counter value"}.get(
                canon, "operand")
            raise self.unsupported(stmt, f"{what} `{written}` in "
                                   f"`{stmt.mnemonic.text}` (words IW, QW, MW and the "
                                   "double word MD here)",
                                   first.col)
        op = self.numbered(stmt, first, canon, rest, written)
        if canon in WORD_AREAS:
            self.word_uses.append((canon, op.index, stmt, Word(written, first.col)))
        elif canon == "MD":                     # bytes n..n+3: the words n and n+2
            for n in (op.index, op.index + 2):
                self.word_uses.append(("MW", n, stmt, Word(written, first.col)))
        return op

    def check_overlaps(self) -> None:
        """S7's IW/QW/MW n is bytes n and n+1 of the I/Q/M area; here words live in
        the byte processor, apart from the bits, so a program that uses a word and a
        bit (or two words) in the same bytes is rejected."""
        bits: dict[tuple[str, int], Instr] = {}
        for ins in self.out:
            op = ins.operand
            if op is not None and op.kind == "bit":
                bits.setdefault((op.area, op.byte), ins)
        words: dict[tuple[str, int], tuple[Stmt, Word]] = {}
        for area, n, stmt, word in self.word_uses:
            for other in (n - 1, n + 1):
                if (area, other) in words:
                    o_stmt, o_word = words[(area, other)]
                    raise self.unsupported(stmt, f"`{word.text}` and `{o_word.text}` "
                                           f"(line {o_stmt.line}) overlap (an S7 word n "
                                           "is bytes n and n+1; here each word stands "
                                           "alone)", word.col)
            words.setdefault((area, n), (stmt, word))
            bit_area = WORD_AREAS[area]
            for b in (n, n + 1):
                ins = bits.get((bit_area, b))
                if ins is not None:
                    raise self.unsupported(stmt, f"word `{word.text}` overlaps the bit "
                                           f"`{ins.operand.text}` (line {ins.line}): "
                                           f"S7's `{word.text}` covers bytes {n} and "
                                           f"{n + 1}, "
                                           "here words and bits are apart", word.col)

    def need_cc(self, stmt: Stmt, st: _State, bits=("CC",)) -> None:
        if "OV" in bits and "OV" not in st.cc_ok or "OS" in bits and "OS" not in st.cc_ok:
            which = "OV" if "OV" in bits and "OV" not in st.cc_ok else "OS"
            read = (f"`{stmt.mnemonic.text}"
                    f"{' ' + stmt.operands[0].text if stmt.operands else ''}` reads the "
                    f"status bit {which}, which this translation keeps as S7's ")
            raise self.unsupported(stmt, read + (
                "from the OB's start until a call or block end (S7 clears it there), "
                "the target of an `SPS` (which clears it where it jumps), or its own "
                "code for `+ n`, `NEGI`, `INVI`, `NEGD`, `INVD`, `ITD` or `LOOP`, which "
                "may set it; nothing makes it S7's again before the scan ends"
                if which == "OS" else
                "only right after an arithmetic, compare, word logic or shift "
                "instruction in straight-line code (not across a label, a call, `LOOP`, "
                "a jump list, a timer or counter, `LC`, `+ n` …)"))
        if "CC" in bits and "CC" not in st.cc_ok:
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}"
                                   f"{' ' + stmt.operands[0].text if stmt.operands else ''}"
                                   "` reads the status bits CC 1/CC 0, which this "
                                   "translation keeps as S7's only right after an "
                                   "arithmetic, compare, word logic or shift instruction "
                                   "in straight-line code (not across a label, a call, "
                                   "`LOOP`, a jump list, a timer or counter, `LC`, `+ n`, "
                                   "`NEGI`/`INVI`/`NEGD`/`INVD`, whose translations "
                                   "change them)")

    def combine(self, stmt: Stmt, st: _State, m: str) -> None:
        func, neg = COMBINE[m]
        cond = stmt.operands[0].text.upper() if len(stmt.operands) == 1 else ""
        if cond in CC_CONDITIONS:               # U ==0 ... U OS: a status condition
            self.need_cc(stmt, st, (status_bit(cond),))
            n = "N" if neg else ""
            if st.ner == 0:
                self.emit(f"LD{n} {cond}")
            elif func == "A" and st.orm == "pending":
                self.open_il("O(", st)
                st.orm = "term"
                self.emit(f"LD{n} {cond}")
            elif func == "A":
                self.emit(f"A{n} {cond}")
            else:
                self.close_term(st)
                self.emit(f"{func}{n} {cond}")
            st.ner = 1
            return
        if cond in ("BR", "BIE"):              # U BIE (A BR): the translation's bit
            op = self.scratch(("BR",))
        else:
            op = self.bit_operand(stmt, BIT_AREAS + STATUS_AREAS)
        if op.area == "T":                      # S7's status: the view bit
            view = self.scratch_bits.get(("view", op.index))
            if view is not None:
                op = Operand("bit", area="M", byte=view.byte, bit=view.bit,
                             text=op.text)
        if st.ner == 0:                         # first check: the string starts
            self.emit("LDN" if neg else "LD", op)
        elif func == "A":
            if st.orm == "pending":             # the AND term after `O` starts
                self.open_il("O(", st)
                st.orm = "term"
                self.emit("LDN" if neg else "LD", op)
            else:
                self.emit(m, op)
        else:                                   # O / X end an AND term
            self.close_term(st)
            self.emit(m, op)
        st.ner = 1

    def open_paren(self, stmt: Stmt, st: _State, m: str) -> None:
        func, neg = OPEN[m]
        if st.ner == 0:
            virtual = True                      # the parenthesis starts the string
        elif func == "A" and st.orm == "pending":
            self.open_il("O(", st)
            st.orm = "term"
            virtual = True                      # it starts the AND term
        else:
            if func != "A":
                self.close_term(st)
            self.open_il(m, st)
            virtual = False
        st.parens.append((m, stmt, virtual, st.orm))
        st.ner, st.orm = 0, "none"
        nxt = self.next_stmt(stmt)
        if nxt is None or not (nxt.canon in OPEN or (nxt.canon in COMBINE
                                                     and nxt.operands)) or nxt.labels:
            where = nxt if nxt is not None else stmt
            raise self.unsupported(where, f"`{where.mnemonic.text or 'a label'}` right "
                                   f"after `{stmt.mnemonic.text}` (a parenthesis starts "
                                   "with U/UN/O/ON/X/XN or another parenthesis here)")

    def next_stmt(self, stmt: Stmt) -> Stmt | None:
        i = self.stmts.index(stmt)
        return self.stmts[i + 1] if i + 1 < len(self.stmts) else None

    def close_paren(self, stmt: Stmt, st: _State) -> None:
        if not st.parens:
            raise self.error(stmt.line, stmt.mnemonic.col,
                             "unbalanced parentheses: `)` without an open `(`")
        self.close_term(st)
        m, _, virtual, outer_orm = st.parens.pop()
        if virtual:
            if OPEN[m][1]:
                self.emit("NOT")
        else:
            self.emit(")")
            st.il_depth -= 1
        st.ner, st.orm = 1, outer_orm

    def jump(self, stmt: Stmt, st: _State, m: str, edges) -> bool:
        if m in ("BE", "BEU", "BEC"):
            self.no_operand(stmt)
            label = END_LABEL
        else:
            label = self.label_operand(stmt)
            if label not in self.label_defs:
                raise self.error(stmt.line, stmt.operands[0].col,
                                 f"unknown label `{stmt.operands[0].shown or stmt.operands[0].text}`")
        if st.parens:
            raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` inside parentheses")
        target = Operand("label", label=label,
                         text=stmt.operands[0].text if stmt.operands else label)
        if m in ("JU", "BE", "BEU"):
            if st.orm != "none":
                raise self.unsupported(stmt, f"`{stmt.mnemonic.text}` after `O` in an "
                                       "AND-before-OR string")
            if label != END_LABEL:
                edges[label].append((st.ner, stmt, "JU"))
                self.acc_edges[label].append(st.acc)
                self.cc_edges[label].append(st.cc_ok)
                fix = self.assumed.get(label, (0, ""))[1]
                if fix and st.ner == 0:
                    self.emit(fix)          # this path arrives with /FC = 0
            self.emit("JU", target)
            return False
        self.close_term(st)
        if m in ("JCB", "JNB") and ("BR",) in self.scratch_bits:
            self.emit("=", self.scratch(("BR",)))       # BR := the RLO, then as JC/JCN
        if m in ("JCN", "JNB"):                 # S7 sets RLO = 1 on both paths
            self.emit("NOT")
        self.emit("JC", target)
        st.ner = 0
        st.need_set = True                      # not taken: S7's RLO is 1
        if label != END_LABEL:
            edges[label].append((0, stmt, "JC"))
            self.acc_edges[label].append(st.acc)
            self.cc_edges[label].append(st.cc_ok)
        return True


    # -- global data blocks (docs/s7.md, "Global data blocks") ------------------------

    def read_db_field(self, block: Block, n: int, col: int, text: str) -> None:
        """`name : TYPE [:= value];` in a DB's STRUCT (a global DB's field)."""
        m = _DECL.match(text)
        if not m:
            raise self.error(n, col, f"malformed declaration `{text}`: name : type; "
                             "expected")
        fields = self.db_fields.setdefault(block.number, [])
        name = m.group(1)
        if any(f.name.upper() == name.upper() for f in fields):
            raise self.error(n, col, f"duplicate declaration `{name}` in {block.name}")
        value = m.group(3)
        fields.append(DbField(name, m.group(2).strip().upper(), n, col, value,
                              col + text.index(value) if value else 0))

    def read_db_assignment(self, block: Block, n: int, col: int, text: str) -> None:
        """A global DB's `name := value;` after BEGIN: the field's initial value."""
        m = re.fullmatch(r"\s*([A-Za-z_]\w*)((?:\s*\[[^]]*\]|\s*\.\s*[A-Za-z_]\w*)*)"
                         r"\s*:=\s*([^;]+?)\s*;?\s*", text)
        if not m:
            raise self.error(n, col, f"malformed initial value `{text}`")
        fields = self.db_fields.get(block.number, [])
        field_ = next((f for f in fields if f.name.upper() == m.group(1).upper()), None)
        if field_ is None:
            raise self.error(n, col, f"unknown field `{m.group(1)}` in {block.name}"
                             + did_you_mean(m.group(1), [f.name for f in fields]))
        if m.group(2):                          # `s.x := …`, `arr[1] := …`: a member
            field_.members.append((n, col, m.group(1) + m.group(2)))   # (checked once
            return                              # the DB is laid out: data_block)
        field_.value, field_.value_line = m.group(3), n
        field_.value_col = col + text.index(m.group(3))

    def db_symbol(self, stmt: Stmt) -> bool:
        """`"Data".count` (a DB's symbol and a field) -> `DB1.count`, named as
        written; False when the operand is no such pair."""
        word, member = stmt.operands[0], stmt.operands[1:2]
        if not member or not member[0].text.startswith(".") or \
                member[0].col != word.col + len(word.text):
            return False
        sym = self.symbol_table.get(word.text.strip('"').upper())
        if sym is None:
            self.resolve_word(stmt, word)       # raises: undeclared symbol
        if re.fullmatch(r"\.DB[XBWD]", member[0].text, re.I):
            raise self.error(stmt.line, word.col, f"malformed operand `{word.text}"
                             f"{member[0].text}`: a DB's symbol takes a field's name "
                             f"(`{word.text}.name`; awlsim's parser takes no "
                             f"`{word.text}{member[0].text}` either)")
        m = re.fullmatch(r"DB\s*(\d+)", sym.address, re.I)
        if m is None:
            raise self.error(stmt.line, word.col, f"`{word.text}{member[0].text}`: the "
                             f"symbol `{word.text}` is `{sym.address}` "
                             f"({self.symbol_path}:{sym.line}), not a DB")
        stmt.operands[0:2] = [Word(f"DB{m.group(1)}{member[0].text}", word.col,
                                   word.text + member[0].text)]
        return True

    def data_block(self, stmt: Stmt, number: int, col: int) -> dict:
        """The layout of global DB `number`, its markers allocated on first use:
        {"base": marker byte of DB byte 0, "size": bytes, "fields": [DbField]}."""
        if number in self.db_used:
            return self.db_used[number]
        block = self.blocks.get(("DB", number))
        if block is None:
            raise self.error(stmt.line, col, f"DB {number} is not in the source")
        if block.instance_of is not None:
            raise self.unsupported(stmt, f"DB {number} is the instance DB of FB "
                                   f"{block.instance_of} (its data is the FB's `#name`s, "
                                   "not DB operands)", col)
        bit = 0                                 # S7's layout: bit offset in the DB
        fields = self.db_fields.get(number, [])
        for f in fields:
            size = DB_TYPE_BYTES.get(f.type)
            if size is None:
                raise self.error(f.line, f.col, f"unsupported: field `{f.name}` of type "
                                 f"{f.type} in DB {number} (fields of this slice: BOOL, "
                                 "BYTE, INT, WORD and other elementary types)")
            if size == 0:                       # BOOL: the next bit
                f.byte, f.bit = divmod(bit, 8)
                bit += 1
                continue
            byte = (bit + 7) // 8
            if size > 1 and byte % 2:
                byte += 1
            f.byte, f.bit = byte, None
            bit = (byte + size) * 8
        for f in fields:                        # elementary: no member to set
            for line, col_, path in f.members:
                raise self.error(line, col_, f"`{path}`: `{f.name}` is {f.type}, not a "
                                 "STRUCT or ARRAY")
        size = (bit + 7) // 8
        size += size % 2
        base = DB_BYTES[0] + sum(d["size"] for d in self.db_used.values())
        if base + size > DB_BYTES[1]:
            raise self.unsupported(stmt, f"DB {number} ({size} bytes) does not fit into "
                                   f"the markers kept for global DBs (M {DB_BYTES[0]} .. "
                                   f"M {DB_BYTES[1] - 1}, {base - DB_BYTES[0]} bytes used "
                                   "by other DBs)", col)
        self.db_used[number] = {"base": base, "size": size, "fields": fields,
                                "block": block}
        return self.db_used[number]

    def db_registers(self, stmts: list[Stmt], scope: dict) -> list:
        """S7's DB register before each statement of one block, known statically:
        ("db", n), or ("?", why) where it is not.  A block starts with none open
        (awlsim: DB 0 at an OB; an FB sees the caller's DI), an FC with its caller's;
        `OPN DB n` opens n; a CALL of an FC leaves it as it was (awlsim restores it),
        of an FB opens its instance DB; a read of a field `DBn.…` opens n (awlsim's
        and S7's CPU fetch it so), a write of one in another DB than the open one
        makes the register unknown (S7 opens n, awlsim does not); where paths meet
        they must agree.  The states at the labels are iterated to their fixed point
        (each changes at most twice: none, DB n, unknown)."""
        block = scope["block"]
        entry = getattr(self, "db_at_call", None) if block.kind == "FC" else None
        if entry is None:
            entry = ("?", f"no DB is open at the start of {block.name}")
        targets: dict[str, tuple] = {}
        while True:
            before, state, changed = [], entry, False
            for stmt in stmts:
                for w in stmt.labels:
                    got = targets.get(w.text.upper())
                    state = _db_meet(state, got) if got else state
                before.append(state)
                m = stmt.canon
                if m == "OPN" and len(stmt.operands) in (1, 2) and re.fullmatch(
                        r"DB\s*\d+", "".join(w.text for w in stmt.operands), re.I):
                    state = ("db", int("".join(w.text for w in stmt.operands)[2:]))
                elif m == "CALL" and isinstance(stmt.extra, CallInfo) and \
                        stmt.extra.kind.upper() == "FB":
                    state = ("?", f"after `{stmt.mnemonic.text} FB {stmt.extra.number}"
                                  f", DB {stmt.extra.db}` the open DB is its instance DB")
                elif m not in ("CALL", "UC", "CC") and stmt.operands and \
                        not self.is_jump(stmt) and (field_ := re.match(
                            r"DB(\d+)\.", stmt.operands[0].text, re.I)):
                    n = int(field_.group(1))
                    if m not in ("=", "S", "R", "T"):
                        state = ("db", n)       # awlsim's __fetchDB, S7: opens DB n
                    elif state not in (None, ("db", n)):   # (None: no path here
                        # yet in this pass, a later one has it)
                        ops = stmt.operands
                        written = ops[0].shown or " ".join([ops[0].text] + [
                            w.text for w in ops[1:2] if w.text[0].isdigit()])
                        state = ("?", f"S7 opens DB {n} at `{stmt.mnemonic.text} "
                                      f"{written}`, awlsim does not")
                elif self.is_jump(stmt) and stmt.operands:
                    key = stmt.operands[0].text.upper()
                    new = _db_meet(targets.get(key), state)
                    changed |= new != targets.get(key)
                    targets[key] = new
                if m in ("JU", "BEU", "BE"):
                    state = None                # no fall-through (joined at a label)
            if not changed:
                return [s or entry for s in before]

    def db_operands(self, stmt: Stmt, register) -> Stmt:
        """`OPN DB n` -> nothing (`NOP 0`: no status bit changes); a DB operand
        (`DB1.DBX 0.0`, `DB1.DBW 2`, `DB1.field`, `DBX 0.0` / `DBW 2` of the open DB)
        -> the marker of the field.  A CALL remembers the register for its FC."""
        if stmt.canon in ("CALL", "UC", "CC"):
            self.db_at_call = register
            return stmt
        ops = stmt.operands
        if stmt.canon == "OPN":
            return self.open_db(stmt)
        if not ops or self.is_jump(stmt):
            return stmt
        text = ops[0].text
        full = re.fullmatch(r"DB(\d+)\.(DB[XBWD])(.*)", text, re.I)
        open_ = re.fullmatch(r"(DB[XBWD])(.*)", text, re.I)
        named = None if full else re.fullmatch(r"DB(\d+)\.([A-Za-z_]\w*)", text, re.I)
        if not (full or open_ or named):
            return stmt
        match = full or open_
        used = 1
        if match:
            area, rest = match.group(match.lastindex - 1).upper(), match.group(
                match.lastindex)
            if not rest and len(ops) > 1:
                rest, used = ops[1].text, 2
        written = " ".join(w.text for w in ops[:used])
        if full or named:
            number = int((full or named).group(1))
        elif register[0] == "db":
            number = register[1]
        else:
            raise self.unsupported(stmt, f"DB register not known statically at "
                                   f"`{stmt.mnemonic.text} {written}` ({register[1]}; "
                                   "open it with `OPN DB n` in this block, or write "
                                   "`DBn.DBX`)" if self.lang == "en" else
                                   f"DB register not known statically at "
                                   f"`{stmt.mnemonic.text} {written}` ({register[1]}; "
                                   "open it with `AUF DB n` in this block, or write "
                                   "`DBn.DBX`)", ops[0].col)
        db = self.data_block(stmt, number, ops[0].col)
        if named:
            f = next((f for f in db["fields"] if f.name.upper() ==
                      named.group(2).upper()), None)
            if f is None:
                raise self.error(stmt.line, ops[0].col, f"unknown field "
                                 f"`{named.group(2)}` in DB {number}" + did_you_mean(
                                     named.group(2), [f.name for f in db["fields"]]))
            area = "DBX" if f.type == "BOOL" else "DBW" if DB_TYPE_BYTES[
                f.type] == 2 else "DBB" if DB_TYPE_BYTES[f.type] == 1 else "DBD"
            byte, bit = f.byte, f.bit
        else:
            where = f"`{written}`: {area} <byte>" + (".<bit>" if area == "DBX" else "")
            m = re.fullmatch(r"(\d+)\.(\d)" if area == "DBX" else r"(\d+)", rest)
            if m is None:
                raise self.error(stmt.line, ops[0].col, f"malformed address {where} "
                                 "expected")
            byte, bit = int(m.group(1)), int(m.group(2)) if area == "DBX" else None
            if bit is not None and bit > 7:
                raise self.error(stmt.line, ops[0].col, f"operand out of range: "
                                 f"`{written}` (bit 0..7)")
        width = {"DBX": 1, "DBB": 1, "DBW": 2, "DBD": 4}[area]
        if byte + width > db["size"]:
            raise self.error(stmt.line, ops[0].col, f"operand out of range: `{written}` "
                             f"(DB {number} has {db['size']} bytes, 0..{db['size'] - 1})"
                             if db["size"] else f"operand out of range: `{written}` (DB "
                             f"{number} has no fields, no bytes)")
        kind = {"DBX": "a BOOL", "DBW": "an INT/WORD"}.get(area)
        ok = [f for f in db["fields"] if f.byte == byte and (
            f.type == "BOOL" if area == "DBX" else f.type in ("INT", "WORD"))] \
            if kind else []
        if area == "DBX" and not ok and not any(
                f.byte <= byte < f.byte + max(DB_TYPE_BYTES[f.type], 1)
                for f in db["fields"]):
            ok = [None]                         # a byte no field covers (padding)
        if not ok:
            raise self.unsupported(stmt, f"`{written}`: " + (
                f"{area} (this slice reads a DB's BOOL fields as DBX and its INT/WORD "
                "fields as DBW)" if kind is None else f"not {kind} field of DB "
                f"{number} (here a DB's bits and words are kept apart, as markers' are: "
                f"DBX reads BOOL fields, DBW INT/WORD fields)"), ops[0].col)
        k = db["base"] + byte
        target = f"M{k}.{bit}" if area == "DBX" else f"MW{k}"
        shown = ops[0].shown or (f"DB{number}.{written}" if open_ else written)
        new_ops = [Word(target, ops[0].col, shown, True)] + ops[used:]
        return Stmt(stmt.line, stmt.col, stmt.source, stmt.mnemonic, new_ops,
                    stmt.labels, stmt.canon, stmt.extra)

    def open_db(self, stmt: Stmt) -> Stmt:
        """`OPN DB n` (`AUF DB n`) -> `NOP 0` (no status bit changes), the DB laid out;
        its operand checked as S7's (`DB n`, or a DB's symbol): other forms are
        errors, `OPN DI n` is unsupported (instance DBs are inlined)."""
        mn, ops = stmt.mnemonic.text, stmt.operands
        if not ops:
            raise self.error(stmt.line, stmt.mnemonic.col, f"missing operand: `{mn}` "
                             f"needs a DB (`{mn} DB n`)")
        m = re.fullmatch(r"D([BI])\s*(\d*)", ops[0].text, re.I)
        used = 1
        if m and not m.group(2) and len(ops) > 1 and ops[1].text.isdigit():
            used = 2
        if m and not m.group(2) and used == 1:
            raise self.error(stmt.line, ops[0].col, f"missing operand: `{mn} "
                             f"{ops[0].text}` needs the block's number (`{mn} "
                             f"{ops[0].text.upper()} n`)")
        if m is None:
            raise self.error(stmt.line, ops[0].col, f"operand of the wrong kind: `{mn}` "
                             f"opens a data block (`{mn} DB n`), not `"
                             f"{' '.join(w.text for w in ops)}`")
        if len(ops) > used:
            raise self.error(stmt.line, ops[used].col, f"extra operand "
                             f"`{ops[used].text}`")
        number = int(m.group(2) or ops[1].text)
        if m.group(1).upper() == "I":
            raise self.unsupported(stmt, f"`{mn} DI {number}` (the instance DB "
                                   "register: instance DBs are inlined)")
        self.data_block(stmt, number, ops[0].col)
        return Stmt(stmt.line, stmt.col, stmt.source, stmt.mnemonic,
                    [Word("0", ops[0].col)], stmt.labels, "NOP")

    def check_initial(self, f: DbField, line: int) -> None:
        """The initial value of a BOOL is TRUE or FALSE, of an INT a decimal INT
        constant (awlsim takes no other), of a WORD not TRUE/FALSE (its constant is
        checked as `L`'s)."""
        v = f.value.strip().upper()
        what = f"initial value `{f.value.strip()}` of the {f.type} `{f.name}`"
        if f.type == "BOOL" and v not in ("TRUE", "FALSE"):
            raise self.error(line, f.value_col, f"malformed {what} (TRUE or FALSE)")
        if f.type == "INT":
            if not re.fullmatch(r"[+-]?\d+", v):
                raise self.error(line, f.value_col, f"malformed {what} (a decimal INT "
                                 "constant, -32768..32767)")
            if not -32768 <= int(v) <= 32767:
                raise self.error(line, f.value_col, f"{what} out of range (INT is "
                                 "-32768..32767)")
        if f.type == "WORD" and v in ("TRUE", "FALSE"):
            raise self.error(line, f.value_col, f"malformed {what} (a WORD constant: "
                             "W#16#…, B#16#…, 2#…)")

    def init_data_blocks(self) -> None:
        """S7 loads a DB's initial values before the startup: statements at the start
        of the startup part (OB 100's, or one made for them) set the used DBs' fields
        whose initial value is not 0 (markers start at 0)."""
        init: list[Stmt] = []
        bits, words = [], []
        for number, db in self.db_used.items():
            for f in db["fields"]:
                if f.value is None or f.type not in ("BOOL", "INT", "WORD"):
                    continue
                value = _initial(f.value)
                line = getattr(f, "value_line", f.line)
                source = self.lines[line - 1].rstrip("\r")
                k = db["base"] + f.byte
                self.check_initial(f, line)
                if f.type == "BOOL":
                    if value:
                        bits.append(Stmt(line, f.value_col, source, Word("=", f.value_col),
                                         [Word(f"M{k}.{f.bit}", f.value_col,
                                               f"DB{number}.{f.name}", True)], [], "="))
                elif value != 0:
                    words += [Stmt(line, f.value_col, source, Word("L", f.value_col),
                                   [Word(f.value.strip(), f.value_col)], [], "L"),
                              Stmt(line, f.value_col, source, Word("T", f.value_col),
                                   [Word(f"MW{k}", f.value_col, f"DB{number}.{f.name}",
                                         True)], [], "T")]
        if bits:
            s = bits[0]
            init += [Stmt(s.line, s.col, s.source, Word("SET", s.col), [], [], "SET")]
            init += bits + [Stmt(s.line, s.col, s.source, Word("CLR", s.col), [], [],
                                 "CLR")]
        init += words
        if not init:
            return
        if self.startup:
            if words:                           # awlsim's accumulators at OB 100: 0
                s = words[0]
                init += [Stmt(s.line, s.col, s.source, Word("L", s.col),
                              [Word("0", s.col)], [], "L")] * 2
            at = next(i for i, s in enumerate(self.stmts) if s.canon == "@STARTUP")
            self.stmts[at + 1:at + 1] = init
            return
        self.startup = True
        block = next(iter(self.db_used.values()))["block"]

        def mark(line: int, canon: str, labels: list[Word]) -> Stmt:
            source = self.lines[line - 1].rstrip("\r")
            col = len(source) - len(source.lstrip()) + 1
            return Stmt(line, col, source, Word(source.split()[0], col), [], labels,
                        canon)
        self.stmts += [mark(block.line, "@STARTUP", [])] + init + [
            mark(block.end or block.line, "@STARTED", [Word(STARTUP_END, 1)])]

    def check_db_region(self) -> None:
        """The global DBs' markers stay below the translation's own (the timers'
        scratch bits, the started bit), and the program's own operands out of them."""
        if not self.db_used:
            return
        end = DB_BYTES[0] + sum(d["size"] for d in self.db_used.values())
        low = min((op.byte for op in self.scratch_bits.values()), default=None)
        if low is not None and low < end:       # at the first DB that reaches M low
            stmt = next(d for d in self.db_used.values() if d["base"] + d["size"] >
                        low)["block"]
            raise self.error(stmt.line, stmt.col, f"unsupported: the global DBs need M "
                             f"{DB_BYTES[0]} .. M {end - 1}, but the translation keeps M "
                             f"{low} and up for the timers and the startup")
        for stmt, ops, lo, hi in self.marker_uses():
            if lo < end and hi >= DB_BYTES[0]:
                shown = ops[0].shown or " ".join(w.text for w in ops[:2])
                raise self.unsupported(self.param_stmt(stmt, ops[0]),
                                       f"`{shown}` is in M {DB_BYTES[0]} .. M "
                                       f"{end - 1}, which this program's global DBs "
                                       "use", ops[0].col)


# Global data blocks (docs/s7.md, "Global data blocks"): the fields of the DBs a
# program uses live in markers from M 224 up, DB byte b of a DB at its base + b
# (bits M base+b.n, words MW base+b), below the translation's own bits (M 255.7 down).
DB_BYTES = (224, 254)
# bytes of a field type in S7's DB layout (0: BOOL, a bit); other types are unsupported
DB_TYPE_BYTES = {"BOOL": 0, "BYTE": 1, "CHAR": 1, "INT": 2, "WORD": 2, "S5TIME": 2,
                 "DATE": 2, "DINT": 4, "DWORD": 4, "REAL": 4, "TIME": 4,
                 "TIME_OF_DAY": 4, "TOD": 4}


@dataclass
class DbField:
    """A field of a global DB: `name : TYPE [:= value];` (its value may be set again
    after BEGIN) and, once laid out, its S7 address."""

    name: str
    type: str
    line: int
    col: int
    value: str | None = None
    value_col: int = 0
    byte: int = 0
    bit: int | None = None
    members: list = field(default_factory=list)  # `s.x := …` after BEGIN: (line, col,
                                                 # path)


def _db_meet(a, b):
    """Two DB register states where paths meet (None: no path yet)."""
    if a is None or a == b:
        return b
    if b is None:
        return a
    if a[0] == "?":
        return a
    if b[0] == "?":
        return b
    return ("?", f"DB {a[1]} on one path, DB {b[1]} on another")


_S5T_PART = re.compile(r"(\d+)(MS|D|H|M|S)_?")
_S5T_UNITS = {"D": 86_400_000, "H": 3_600_000, "M": 60_000, "S": 1000, "MS": 1}
def _s5t_ms(body: str) -> int | None:
    """`1H2M3S4MS` (or with `_`) -> ms; None if malformed or above 2H46M30S."""
    pos, total, last = 0, 0, -1
    order = list(_S5T_UNITS)
    while pos < len(body):
        m = _S5T_PART.match(body, pos)
        if not m or order.index(m.group(2)) <= last:
            return None
        last = order.index(m.group(2))
        total += int(m.group(1)) * _S5T_UNITS[m.group(2)]
        pos = m.end()
    if pos == 0 or total > 9_990_000:
        return None
    return total


def _bcd_decode(value: int) -> int | None:
    """The count of a BCD counter value 16#0000..16#0999, or None."""
    value &= 0xFFFF
    digits = [(value >> k) & 0xF for k in (12, 8, 4, 0)]
    if digits[0] or max(digits) > 9:
        return None
    return digits[1] * 100 + digits[2] * 10 + digits[3]


def _s5t_decode(value: int) -> int | None:
    """ms of an S5TIME pattern (time base in bits 13..12, three BCD digits), or
    None if it is not one."""
    value &= 0xFFFF
    digits = [(value >> k) & 0xF for k in (8, 4, 0)]
    if value & 0xC000 or max(digits) > 9:
        return None
    units = digits[0] * 100 + digits[1] * 10 + digits[2]
    return units * (10, 100, 1000, 10_000)[(value >> 12) & 3]


def _s5t_known(ms: int) -> Known:
    """The S5TIME pattern for `ms` as S7 (and awlsim) encode it: the finest time base
    that holds it (10 ms up to 9.99 s, 100 ms, 1 s, 10 s), three BCD digits."""
    seconds = ms / 1000.0
    if seconds <= 9.99:
        base, units = 0, int(round(seconds * 100.0))
    elif seconds <= 99.9:
        base, units = 1, int(round(seconds * 10.0))
    elif seconds <= 999.0:
        base, units = 2, int(seconds)
    else:
        base, units = 3, int(round(seconds)) // 10
    bcd = int(str(units % 1000), 16)
    value = (base << 12) | bcd
    return Known(value, s5t_ms=units * (10, 100, 1000, 10_000)[base])


def _split_area(text: str) -> tuple[str, str]:
    i = 0
    while i < len(text) and text[i].isascii() and text[i].isalpha():
        i += 1
    return text[:i].upper(), text[i:]


def _english_area_names(areas: tuple[str, ...], lang: str) -> list[str]:
    if lang == "en":
        return list(areas)
    back = {"I": "E", "Q": "A", "M": "M"}
    return [back[a] for a in areas]


# --------------------------------------------------------------------------------------
# Entry points
# --------------------------------------------------------------------------------------

def decode(data: bytes) -> str:
    """UTF-8, else Windows-1252 (STEP 7 Classic's export encoding); CR LF -> LF."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        text = data.decode("cp1252", errors="replace")
    return text.replace("\r\n", "\n")


def parse_stl(path: str, data: bytes | str, config: Config = DEFAULT,
              mnemonics: str | None = None, symbols: str | None = None) -> Program:
    """Check and translate one .awl source, with the STEP 7 symbol table at the path
    `symbols` if given.  Raises only SourceError."""
    text = data if isinstance(data, str) else decode(data)
    return StlFrontEnd(path, text, config, mnemonics, symbols).parse()
