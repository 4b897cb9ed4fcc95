"""The parsed program: what the parser produces and what both the encoder and the
reference interpreter read.  Nothing here knows the binary encoding.

An operand is kept in canonical form (symbols already resolved), so that the encoder
and the reference interpreter see the same addresses but compute with them
independently.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from bitbyte.lang.definition import DEF

# Bit areas addressed as byte.bit (I PI IR IF Q PQ M QR QF: definition.toml, form "bit")
BIT_AREAS = DEF.bit_form_areas
# Bit areas addressed by a number (status bits and exchange channels)
INDEXED_BIT_AREAS = ("T", "C", "FBI", "FBY")
# Word areas (byte processor)
WORD_AREAS = ("IW", "QW", "MW")

# Loads and combines: mnemonic -> (logic function, operand negated).  None = load.
COMBINES = {
    "LD": (None, 0), "LDN": (None, 1), "A": ("A", 0), "AN": ("A", 1),
    "O": ("O", 0), "ON": ("O", 1), "X": ("X", 0), "XN": ("X", 1),
}
# Opening parentheses: mnemonic -> (function applied at `)`, sub-result negated).
OPENS = {
    "A(": ("A", 0), "AN(": ("A", 1), "O(": ("O", 0), "ON(": ("O", 1),
    "X(": ("X", 0), "XN(": ("X", 1),
}
JUMPS = ("JU", "JC", "JCN")
# The timer instructions that read the time base (R T n does not): the ones an
# Instr.at_latch concerns.
TIMER_STARTS = ("SD", "SS", "SP", "SF")


@dataclass(frozen=True)
class Operand:
    """One resolved operand.

    kind is one of:
      "bit"    area in BIT_AREAS, byte and bit set
      "index"  area in INDEXED_BIT_AREAS (T, C, FBI, FBY) or WORD_AREAS, index set
      "const"  value set (an INT, a 16#.. pattern, an L#.. DINT or a T# duration in
               ms); area is "INT", "DINT" or "TIME"
      "label"  label set (upper-case label name); a jump target
    text is the operand as written in the source (symbol name or address).
    """

    kind: str
    area: str = ""
    byte: int = 0
    bit: int = 0
    index: int = 0
    value: int = 0
    label: str = ""
    text: str = ""

    @property
    def bit_number(self) -> int:
        """byte*8 + bit for byte.bit areas."""
        return self.byte * 8 + self.bit

    def address(self) -> str:
        """Canonical address text: I0.0, T3, MW2, FBI1, 16 ..."""
        if self.kind == "bit":
            return f"{self.area}{self.byte}.{self.bit}"
        if self.kind == "index":
            return f"{self.area}{self.index}"
        if self.kind == "const":
            return f"L#{self.value}" if self.area == "DINT" else str(self.value)
        return self.label


@dataclass
class Instr:
    """One instruction of the source, in program order.

    mnemonic is canonical upper case: "LD", "LDN", "A", "AN", "O", "ON", "X", "XN",
    "A(", "AN(", "O(", "ON(", "X(", "XN(", ")", "NOT", "SET", "CLR", "=", "S", "R",
    "FP", "FN", "JU", "JC", "JCN", "NOP", "REFRESH", "REFRESH Q", "END", and the byte mnemonics
    ("L", "T", "+I", ... "SD", "CU", "READ", "WRITE", ...).
    line/col are 1-based and point at the mnemonic; source is the whole source line.
    section is "" in an ordinary (mixed) program, "BIT" or "BYTE" for an instruction
    of a hand-partitioned program's `BIT:` / `BYTE:` section (parallel mode only).
    at_latch: a timer instruction (SD SS SP SF) whose time is its scan's latch time,
    not its own (the word's at-latch bit, LATCH_MS): S7's timers, which the `.awl`
    front end emits (docs/s7.md "Timers"); the IL has no syntax for it.
    """

    mnemonic: str
    operand: Operand | None
    line: int
    col: int
    source: str = ""
    labels: list[str] = field(default_factory=list)
    section: str = ""
    at_latch: bool = False


@dataclass(frozen=True)
class GlobalVar:
    """One `VAR_GLOBAL` declaration (spec §7): `Name AT M10.0 : WRITE;`.

    name: the plant-wide name, upper case (it is also a symbol of the program).
    kind: "bit" (local copy in M) or "word" (local copy in MW).
    access: "WRITE" (this core publishes it) or "READ" (another core does).
    operand: the local copy.  line/col: 1-based, at the name; source: the whole
    source line.  text: the name as written.
    """

    name: str
    kind: str
    access: str
    operand: Operand
    line: int
    col: int
    source: str = ""
    text: str = ""


@dataclass
class Program:
    """A checked program.

    instrs: in program order; a final END is appended by the parser when missing.
    labels: upper-case label -> index into instrs of the instruction it marks.
    symbols: upper-case symbol -> Operand it stands for (VAR_GLOBAL names included).
    globals: the VAR_GLOBAL declarations in source order (empty for a single-core
    program); the linker (bitbyte.plant.link) reads them, the encoder does not.
    startup_scans: how many hardware scans run before scan 0 and are not scans of the
    trace (an S7 source's OB 100: 1, docs/s7.md "OB 100: the startup"); every runner
    honours it (bitbyte.run.startup, the reference interpreter).
    """

    path: str
    instrs: list[Instr]
    labels: dict[str, int] = field(default_factory=dict)
    symbols: dict[str, Operand] = field(default_factory=dict)
    globals: list[GlobalVar] = field(default_factory=list)
    symbol_names: dict[str, str] = field(default_factory=dict)  # upper-case -> as declared
    startup_scans: int = 0


def display_text(instr: Instr) -> str:
    """An instruction as a listing shows it: its source line without the comment, and
    for a transfer the partitioning compiler made (`= FBY 0` for the enable of
    `SD Timer`, `READ FBY 0` on the byte side) the transfer, then the line it serves."""
    text = " ".join(instr.source.split("//")[0].split()) or instr.mnemonic
    op = instr.operand
    if op is not None and op.area in ("FBI", "FBY"):
        return f"{instr.mnemonic} {op.area} {op.index}  ({text})"
    return text
