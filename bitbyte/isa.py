"""The binary encoding of bit instructions (docs/isa.md), encoder side only.

The reference interpreter never reads this module: it interprets the parsed program,
so that a wrong opcode here shows up as a mismatch between RTL and reference instead
of hiding in both.  `rtl/bit_isa.vh` holds the same numbers for the hardware.

Word layout (bits):  31..24 opcode | 23..16 reserved (0) | 15..12 area | 11..0 index,
or 15..0 the jump target, or all operand bits 0.
"""
from __future__ import annotations

OPCODE_SHIFT = 24
AREA_SHIFT = 12
INDEX_BITS = 12            # operand index field: byte*8+bit, or n
WAIT_UPDATE_BIT = 16       # T/C read in a bit part: wait for this scan's update
TARGET_BITS = 16           # jump target field: an instruction address

# Logic function field f of loads/combines and opening parentheses.
LOGIC_F = {"LD": 0b00, "A": 0b01, "O": 0b10, "X": 0b11}
LOAD_BASE = 0x08           # LD LDN A AN O ON X XN = 0x08 | f<<1 | n
OPEN_BASE = 0x10           # A( AN( O( ON( X( XN(  = 0x10 | f<<1 | n


def _logic_opcodes() -> dict[str, int]:
    """The eight loads/combines and six opening parentheses from their f and n
    fields, as docs/isa.md defines them (one decoder path in the RTL)."""
    table = {}
    for name, f in LOGIC_F.items():
        for n, suffix in ((0, ""), (1, "N")):
            table[name + suffix] = LOAD_BASE | f << 1 | n
            if name != "LD":
                table[name + suffix + "("] = OPEN_BASE | f << 1 | n
    return table


OPCODES: dict[str, int] = {
    "NOP": 0x00, "END": 0x01, "NOT": 0x02, "SET": 0x03, "CLR": 0x04, ")": 0x05,
    "REFRESH": 0x06,
    **_logic_opcodes(),
    "=": 0x18, "S": 0x19, "R": 0x1A, "FP": 0x1B, "FN": 0x1C,
    "JU": 0x20, "JC": 0x21, "JCN": 0x22,
}

# Operand area codes (bits 15..12).  FBI and FBY share code 9: the direction follows
# from the opcode (a read is F_Bb k, a write F_bB k).
AREA_CODES: dict[str, int] = {
    "I": 0, "PI": 1, "IR": 2, "IF": 3, "Q": 4, "PQ": 5, "M": 6,
    "T": 7, "C": 8, "FBI": 9, "FBY": 9,
}
BYTE_DOT_BIT_AREAS = ("I", "PI", "IR", "IF", "Q", "PQ", "M")   # index = byte*8+bit

# What the bit processor itself can do with an operand, by opcode group.  Anything
# else in a parsed program (word instructions, S/R on timers and counters, the
# exchange channels) belongs to the byte processor.
READ_OPS = ("LD", "LDN", "A", "AN", "O", "ON", "X", "XN")
WRITE_OPS = ("=", "S", "R")
EDGE_OPS = ("FP", "FN")
JUMP_OPS = ("JU", "JC", "JCN")
BIT_READ_AREAS = ("I", "PI", "IR", "IF", "Q", "PQ", "M", "T", "C")
BIT_WRITE_AREAS = ("Q", "PQ", "M")
EDGE_AREAS = ("Q", "M")
EXCHANGE_AREAS = ("FBI", "FBY")


def allowed_areas(mnemonic: str) -> tuple[str, ...]:
    """The operand areas the bit processor executes `mnemonic` on (stage 1)."""
    if mnemonic in READ_OPS:
        return BIT_READ_AREAS
    if mnemonic in WRITE_OPS:
        return BIT_WRITE_AREAS
    if mnemonic in EDGE_OPS:
        return EDGE_AREAS
    return ()


def operand_word(opcode: int, area: str, index: int) -> int:
    return opcode << OPCODE_SHIFT | AREA_CODES[area] << AREA_SHIFT | index


def jump_word(opcode: int, target: int) -> int:
    return opcode << OPCODE_SHIFT | target


def plain_word(opcode: int) -> int:
    return opcode << OPCODE_SHIFT


# --------------------------------------------------------------------------------------
# Byte instructions (docs/isa.md "Byte instructions"): opcodes 0x80..0xFF.
# --------------------------------------------------------------------------------------

COMPARES = ("==I", "<>I", ">I", "<I", ">=I", "<=I")       # compare code c = index
BYTE_OPCODES: dict[str, int] = {
    "L#": 0x80, "L#POOL": 0x81, "L": 0x82, "T": 0x83,
    "+I": 0x88, "-I": 0x89, "*I": 0x8A, "/I": 0x8B, "MOD": 0x8C,
    **{cmp: 0x90 + c for c, cmp in enumerate(COMPARES)},
    **{f"A {cmp}": 0x98 + c for c, cmp in enumerate(COMPARES)},
    **{f"O {cmp}": 0xA0 + c for c, cmp in enumerate(COMPARES)},
    "SD": 0xB0, "SS": 0xB1, "SP": 0xB2, "SF": 0xB3, "R T": 0xB4,
    "CU": 0xB8, "CD": 0xB9, "S C": 0xBA, "R C": 0xBB,
    "READ": 0xC0, "WRITE": 0xC1,
}
WORD_AREA_CODES = {"T": 7, "C": 8, "FBI": 9, "FBY": 9, "IW": 10, "QW": 11, "MW": 12}
IMM_BITS = 24                                            # L constant immediate field
EXCHANGE_OPS = ("READ", "WRITE")


def byte_key(mnemonic: str, area: str) -> str:
    """The BYTE_OPCODES key of a byte instruction: `S`/`R` on a counter or timer are
    `S C` / `R C` / `R T`."""
    if mnemonic in ("S", "R") and area in ("T", "C"):
        return f"{mnemonic} {area}"
    return mnemonic


def is_byte_instruction(mnemonic: str, area: str | None) -> bool:
    return byte_key(mnemonic, area or "") in BYTE_OPCODES


def fits_immediate(value: int) -> bool:
    return -(1 << (IMM_BITS - 1)) <= value < (1 << (IMM_BITS - 1))


def immediate_word(value: int) -> int:
    return BYTE_OPCODES["L#"] << OPCODE_SHIFT | (value & ((1 << IMM_BITS) - 1))


def pool_word(index: int) -> int:
    return BYTE_OPCODES["L#POOL"] << OPCODE_SHIFT | index


def word_operand_word(opcode: int, area: str, index: int) -> int:
    return opcode << OPCODE_SHIFT | WORD_AREA_CODES[area] << AREA_SHIFT | index


# Parallel mode: the byte program's own control instructions (docs/isa.md, byte program
# only; firmware_byte/byteproc.h BB_OP_JU_B ... BB_OP_END_B).  Jumps carry the target
# byte-program address in bits 15..0, as JU/JC/JCN do in the bit program.
BYTE_PROGRAM_OPCODES: dict[str, int] = {
    "JU_B": 0xC8, "JC_B": 0xC9, "JCN_B": 0xCA, "END_B": 0xCF,
}
