"""The binary encoding of bit instructions (docs/isa.md), encoder side only.

The reference interpreter never reads this module: it interprets the parsed program,
so that a wrong opcode here shows up as a mismatch between RTL and reference instead
of hiding in both.  The numbers come from bitbyte/lang/definition.toml, as do those of the
generated `rtl/bit_isa.vh` and `firmware_byte/bb_isa.h`.

Word layout (bits):  31..24 opcode | 23..16 reserved (0, except bit 16 wait-for-update
of a bit-side T/C read, bits 17/18 from-status / status-wait of a byte T/C instruction,
bit 19 at-latch of a timer: docs/isa.md) | 15..12 area | 11..0 index, or 15..0 the jump target, or all operand
bits 0.
"""
from __future__ import annotations

from bitbyte.lang.definition import DEF

OPCODE_SHIFT = DEF.fields["opcode"].lo
AREA_SHIFT = DEF.fields["area"].lo
INDEX_BITS = DEF.fields["index"].width     # operand index field: byte*8+bit, or n
WAIT_UPDATE_BIT = DEF.wait_update_bit      # T/C read in a bit part: wait for this scan's update
FROM_STATUS_BIT = DEF.from_status_bit      # byte T/C word: input from T_ENABLE / C_PULSE bit n
STATUS_WAIT_BIT = DEF.status_wait_bit      # ... after the bit side wrote it this scan
AT_LATCH_BIT = DEF.at_latch_bit            # byte SD/SS/SP/SF: the time is the scan's latch time
TARGET_BITS = DEF.fields["target"].width   # jump target field: an instruction address

# Logic function field f of loads/combines and opening parentheses.
LOGIC_F = {name: f for f, (name, _) in enumerate(DEF.logic_functions)}
LOAD_BASE = DEF.load_base  # LD LDN A AN O ON X XN = LOAD_BASE | f<<1 | n
OPEN_BASE = DEF.open_base  # A( AN( O( ON( X( XN(  = OPEN_BASE | f<<1 | n

OPCODES: dict[str, int] = DEF.bit_opcodes

# Operand area codes (bits 15..12).  FBI and FBY share code 9: the direction follows
# from the opcode (a read is F_Bb k, a write F_bB k).
AREA_CODES: dict[str, int] = DEF.area_codes
BYTE_DOT_BIT_AREAS = DEF.bit_form_areas   # index = byte*8+bit

# What the bit processor itself can do with an operand, by opcode group.  Anything
# else in a parsed program (word instructions, S/R on timers and counters, the
# exchange channels) belongs to the byte processor.
READ_OPS = ("LD", "LDN", "A", "AN", "O", "ON", "X", "XN")
WRITE_OPS = ("=", "S", "R")
EDGE_OPS = ("FP", "FN")
JUMP_OPS = ("JU", "JC", "JCN")
BIT_READ_AREAS = ("I", "PI", "IR", "IF", "Q", "QR", "QF", "PQ", "M", "T", "C")
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

BYTE_OPCODES: dict[str, int] = DEF.byte_opcodes
WORD_AREA_CODES = DEF.word_area_codes
IMM_BITS = DEF.fields["imm"].width        # L constant immediate field
EXCHANGE_OPS = ("READ", "WRITE")
SHIFTS = DEF.shifts                       # SLW ... RRD: a count in the index field
COUNT_FROM_ACCU2 = 1 << DEF.count_from_accu2_bit


def byte_key(mnemonic: str, area: str) -> str:
    """The BYTE_OPCODES key of a byte instruction: `S`/`R` on a counter or timer are
    `S C` / `R C` / `R T`."""
    if mnemonic in ("S", "R") and area in ("T", "C"):
        return f"{mnemonic} {area}"
    return mnemonic


def is_byte_instruction(mnemonic: str, area: str | None) -> bool:
    return byte_key(mnemonic, area or "") in BYTE_OPCODES or mnemonic in DEF.status_reads


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
BYTE_PROGRAM_OPCODES: dict[str, int] = DEF.byte_program_opcodes
