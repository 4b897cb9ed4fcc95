"""Program -> 32-bit program-memory words (docs/isa.md) and a listing.

Serial mode (the default) encodes bit and byte instructions into the one program:
the bit processor dispatches the byte ones.  The exchange instructions (READ, WRITE,
bit instructions on FBI/FBY) belong to parallel mode and are rejected here, as are
hand-partitioned programs (BIT:/BYTE: sections) and byte instructions with
`mode="parallel"`: in parallel mode bitbyte/compiler/ splits the program first
and encodes its two parts with encode_bit_part / encode_byte_part (below); an image
that silently dropped instructions would run a different program than the one written.
Constants of `L` that do not fit the 24-bit immediate go to a constant pool
(`constant_pool`), which the byte processor loads next to the image.
"""
from __future__ import annotations

from dataclasses import asdict
from typing import NamedTuple

from bitbyte.encoding import isa
from bitbyte.lang.config import DEFAULT, Config
from bitbyte.lang.definition import DEF
from bitbyte.lang.errors import SourceError
from bitbyte.lang.program import TIMER_STARTS, Instr, Program

BYTE_PROCESSOR = "needs the byte processor"
PARALLEL = "is for the byte processor: in parallel mode the program is partitioned " \
           "first (bitbyte asm --mode parallel, bitbyte.compiler)"
SERIAL_EXCHANGE = "needs the byte processor in parallel mode: serial mode has one RLO " \
                  "and no exchange channels"
MODES = ("serial", "parallel")


class Encoded(NamedTuple):
    words: list[int]
    listing: str


POOL_WORDS = DEF.firmware["pool_words"]


def encode(program: Program, config: Config = DEFAULT, mode: str = "serial") -> Encoded:
    """The words of `program` (address 0 first) and its listing text."""
    words = encode_words(program, config, mode)
    return Encoded(words, listing(program, words, config))


def encode_words(program: Program, config: Config = DEFAULT,
                 mode: str = "serial") -> list[int]:
    """One 32-bit word per instruction; SourceError at the first that cannot be."""
    pool = constant_pool(program)
    for instr in program.instrs:
        if instr.section:
            raise _error(program, instr, "a hand-partitioned program (BIT:/BYTE: "
                                         "sections) runs in parallel mode only: "
                                         "bitbyte asm --mode parallel")
    return [encode_instr(program, instr, mode, pool) for instr in program.instrs]


def constant_pool(program: Program) -> list[int]:
    """32-bit constants of `L` too wide for the immediate, in first-use order; more
    than the byte processor's pool holds is an error at the first one past it."""
    pool: list[int] = []
    for instr in program.instrs:
        op = instr.operand
        if instr.mnemonic == "L" and op is not None and op.kind == "const" \
                and not isa.fits_immediate(op.value) and op.value not in pool:
            if len(pool) == POOL_WORDS:
                raise _error(program, instr, f"program too large: more than "
                             f"{POOL_WORDS} different constants outside -8388608.."
                             "8388607 (the byte processor's constant pool)")
            pool.append(op.value)
    return [v & 0xFFFFFFFF for v in pool]


def encode_instr(program: Program, instr: Instr, mode: str = "serial",
                 pool: list[int] | None = None) -> int:
    m, op = instr.mnemonic, instr.operand
    area = op.area if op is not None else None
    if isa.is_byte_instruction(m, area) or area in isa.EXCHANGE_AREAS:
        return _encode_byte_side(program, instr, mode, pool or [])
    opcode = isa.OPCODES.get(m)
    if opcode is None:
        raise _error(program, instr, f"`{m}` {BYTE_PROCESSOR}")
    if m in isa.JUMP_OPS:
        return isa.jump_word(opcode, _jump_target(program, instr))
    if op is None:
        return isa.plain_word(opcode)
    if op.area not in isa.allowed_areas(m):
        raise _error(program, instr, _not_bit_message(m, op.area, op.address()))
    index = op.bit_number if op.area in isa.BYTE_DOT_BIT_AREAS else op.index
    if index >= 1 << isa.INDEX_BITS:
        raise _error(program, instr, f"operand `{op.address()}` does not fit the "
                                     f"{isa.INDEX_BITS}-bit index field")
    return isa.operand_word(opcode, op.area, index)


def _encode_byte_side(program: Program, instr: Instr, mode: str, pool: list[int]) -> int:
    """A byte instruction (or an exchange operand) in serial mode."""
    m, op = instr.mnemonic, instr.operand
    what = f"`{m} {op.address()}`" if op is not None else f"`{m}`"
    if mode != "serial":
        raise _error(program, instr, f"{what} {PARALLEL}")
    if m in isa.EXCHANGE_OPS or (op is not None and op.area in isa.EXCHANGE_AREAS):
        raise _error(program, instr, f"{what} {SERIAL_EXCHANGE}")
    if m in DEF.status_reads:       # LD ==0 ... XN UO: base + f, the condition
        opcode, index = DEF.status_reads[m]
        return isa.plain_word(opcode) | index
    if m in isa.SHIFTS:             # the count in the index, or ACCU2's low byte
        return isa.plain_word(isa.BYTE_OPCODES[m]) | (
            op.value if op is not None else isa.COUNT_FROM_ACCU2)
    if op is None:
        return isa.plain_word(isa.BYTE_OPCODES[m])
    if op.kind == "const":
        if isa.fits_immediate(op.value):
            return isa.immediate_word(op.value)
        return isa.pool_word(pool.index(op.value & 0xFFFFFFFF))
    opcode = isa.BYTE_OPCODES[isa.byte_key(m, op.area)]
    word = isa.word_operand_word(opcode, op.area, op.index)
    if instr.at_latch and m in TIMER_STARTS:
        word |= 1 << isa.AT_LATCH_BIT        # the time is the scan's latch time (S7)
    return word


# --------------------------------------------------------------------------------------
# Parallel mode: the two parts of a partitioned program (bitbyte/compiler/)
# --------------------------------------------------------------------------------------

def encode_bit_part(program: Program) -> list[int]:
    """Words of the bit part of a partitioned program: the bit instructions as in
    serial mode, plus the exchange operands (`= FBY k`, `LD/A/O... FBI k`: area 9).
    program.labels are bit-part addresses."""
    words = []
    for instr in program.instrs:
        op = instr.operand
        if op is not None and op.area in isa.EXCHANGE_AREAS:
            m = instr.mnemonic
            if not (m == "=" and op.area == "FBY") and \
                    not (m in isa.READ_OPS and op.area == "FBI"):
                raise _error(program, instr, f"`{m} {op.address()}` cannot be encoded: "
                                             "the bit side writes a channel with `= FBY k` "
                                             "and reads one with LD/A/O/X... FBI k")
            words.append(isa.operand_word(isa.OPCODES[m], op.area, op.index))
        elif instr.mnemonic == "=" and op is not None and op.area in ("T", "C") \
                and op.kind == "index":
            # --tc-path status: the enable of timer n / the input of counter n into the
            # status buffer (Fig. 2); the compiler writes it, the parser never accepts it
            words.append(isa.operand_word(isa.OPCODES["="], op.area, op.index))
        elif isa.is_byte_instruction(instr.mnemonic, op.area if op else None) or \
                instr.mnemonic in isa.BYTE_PROGRAM_OPCODES:
            raise _error(program, instr, f"`{instr.mnemonic}` is a byte instruction: "
                                         "not in the bit part")
        else:
            word = encode_instr(program, instr)
            if getattr(instr, "wait_update", False):
                word |= 1 << isa.WAIT_UPDATE_BIT     # wait for this scan's T/C update
            words.append(word)
    return words


def encode_byte_part(program: Program, pool: list[int] | None = None) -> list[int]:
    """Words of the byte part of a partitioned program: word instructions as in serial
    mode, `READ FBY k` / `WRITE FBI k`, and the byte program's JU_B / JC_B / JCN_B
    (targets: program.labels, byte-part addresses) and END_B.  pool: the byte part's
    constant pool (default constant_pool(program))."""
    pool = constant_pool(program) if pool is None else pool
    words = []
    for instr in program.instrs:
        m, op = instr.mnemonic, instr.operand
        if m in isa.BYTE_PROGRAM_OPCODES:
            opcode = isa.BYTE_PROGRAM_OPCODES[m]
            words.append(isa.plain_word(opcode) if m == "END_B" else
                         isa.jump_word(opcode, _jump_target(program, instr)))
        elif m in isa.EXCHANGE_OPS:
            words.append(isa.word_operand_word(isa.BYTE_OPCODES[m], op.area, op.index))
        elif isa.is_byte_instruction(m, op.area if op else None):
            word = _encode_byte_side(program, instr, "serial", pool)
            if getattr(instr, "from_status", False):
                word |= 1 << isa.FROM_STATUS_BIT   # input from T_ENABLE / C_PULSE bit n
            if getattr(instr, "status_wait", False):
                word |= 1 << isa.STATUS_WAIT_BIT   # ... written by the bit side this scan
            words.append(word)
        else:
            raise _error(program, instr, f"`{m}` is a bit instruction: not in the byte part")
    return words


def _jump_target(program: Program, instr: Instr) -> int:
    target = program.labels.get(instr.operand.label)
    if target is None:
        raise _error(program, instr, f"unknown label `{instr.operand.text}`")
    if target >= 1 << isa.TARGET_BITS:
        raise _error(program, instr, f"jump target {target} does not fit the "
                                     f"{isa.TARGET_BITS}-bit address field")
    return target


def _not_bit_message(mnemonic: str, area: str, address: str) -> str:
    """Why a parsed (so well-formed) instruction is not for the bit processor."""
    what = f"`{mnemonic} {address}`"
    if area in isa.EXCHANGE_AREAS:
        return f"{what} needs the byte processor (exchange channels: serial/parallel " \
               "mode, next release)"
    if area in ("T", "C"):
        return f"{what} {BYTE_PROCESSOR}"
    return f"{what} cannot be encoded: the bit processor has no such operand"


def _error(program: Program, instr: Instr, message: str) -> SourceError:
    return SourceError(program.path, instr.line, instr.col, message, instr.source)


# --------------------------------------------------------------------------------------
# Listing
# --------------------------------------------------------------------------------------

def listing(program: Program, words: list[int], config: Config = DEFAULT) -> str:
    """Human-readable image: header, symbols, labels, then one line per word:

        AAAA  WWWWWWWW  <line>: <source text>        ; <resolved operand>

    AAAA is the hex address, WWWWWWWW the word.  Each labelled instruction is
    preceded by a blank line and `<label>:` lines, so that jump targets stand out;
    an END is followed by a blank line (one scan's code per group).
    """
    out = _header(program, words, config)
    out += ["", "addr  word      line: source"]
    for address, (instr, word) in enumerate(zip(program.instrs, words)):
        if instr.labels and address > 0:
            out.append("")
        out += [f"{'':16}{label}:" for label in _labels_on_own_line(instr)]
        out.append(_instr_line(program, address, instr, word))
        if instr.mnemonic == "END" and address + 1 < len(words):
            out.append("")
    return "\n".join(out) + "\n"


def _header(program: Program, words: list[int], config: Config) -> list[str]:
    sizes = " ".join(f"{k}={v}" for k, v in asdict(config).items())
    lines = [f"; bitbyte listing of {program.path}",
             f"; program memory: {len(words)} of {config.prog_words} words",
             f"; config: {sizes}"]
    if program.symbols:
        lines += ["", "symbols:"]
        lines += [f"  {program.symbol_names.get(name, name):<16} {op.address()}"
                  for name, op in program.symbols.items()]
    if program.labels:
        lines += ["", "labels:"]
        lines += [f"  {name:<16} {addr:04X}" for name, addr in program.labels.items()]
    return lines


def _labels_on_own_line(instr: Instr) -> list[str]:
    """The labels of instr not already visible in its source line (they stood on
    lines of their own before it)."""
    before = instr.source[: max(instr.col - 1, 0)].replace(" ", "").replace("\t", "")
    written_here = {name.upper() for name in before.split(":") if name}
    return [label for label in instr.labels if label.upper() not in written_here]


def _instr_line(program: Program, address: int, instr: Instr, word: int) -> str:
    text = instr.source.strip().expandtabs(4) if instr.source else "(appended END)"
    line = f"{address:04X}  {word:08X}  {instr.line:>4}: {text}"
    note = _resolved(program, instr)
    return f"{line:<60} ; {note}" if note else line


def _resolved(program: Program, instr: Instr) -> str:
    """What the encoder used where the source text does not show it directly."""
    op = instr.operand
    if op is None:
        return ""
    if op.kind == "label":
        return f"-> {program.labels[op.label]:04X}"
    if op.text.upper().replace(" ", "") != op.address():
        return op.address()
    return ""
