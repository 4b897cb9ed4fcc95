"""A partitioned program (parallel and free-running mode, spec §2): the bit part and the
byte part with their transfers, as the partitioning compiler (bitbyte.compiler) makes
it, the assembler writes it and the parallel reference interpreter (bitbyte.ref.parsim)
runs it.  Data only: no compiler logic here.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from bitbyte.lang.definition import DEF
from bitbyte.lang.program import Instr, Program

BIT, BYTE = "bit", "byte"
TO_BYTE, TO_BIT = "to_byte", "to_bit"
BYTE_JUMPS = {"JU": "JU_B", "JC": "JC_B", "JCN": "JCN_B"}
BYTE_PROG_WORDS = DEF.firmware["byte_prog_words"]   # firmware_byte BB_PROG_WORDS

# Byte instructions that read the RLO (they never change it)
TIMER_UPDATES = ("SD", "SS", "SP", "SF", "R T")
COUNTER_UPDATES = ("CU", "CD", "S C", "R C")
STATUS_UPDATES = TIMER_UPDATES + COUNTER_UPDATES



@dataclass
class PartInstr(Instr):
    """An instruction of one part.  origin: index into program.instrs of the source
    instruction it is (or that caused it); synthesized: inserted or rewritten by the
    compiler, with note saying why (the listing shows it)."""

    note: str = ""
    origin: int | None = None
    synthesized: bool = False
    wait_update: bool = False   # T/C read: wait for this scan's update (bit 16)
    # byte T/C instruction: its enable / count input is the status buffer's bit n, which
    # the bit part's `= T n` / `= C n` writes (--tc-path status, docs/exchange.md)
    from_status: bool = False
    # ... and in parallel mode waits first until the bit side has written it in this
    # scan (the word's status-wait bit, T_WRITTEN / C_WRITTEN)
    status_wait: bool = False


@dataclass
class Row:
    """One row of the side-by-side view, in program order.

    kind: "bit" / "byte" (one side only), "both" (END + END_B, a mirrored jump),
    "to_byte" / "to_bit" (a transfer: both halves), "label" (a position in both
    parts), "pair" (hand-partitioned: the n-th instruction of each part)."""

    kind: str
    origin: int | None
    bit: PartInstr | None = None
    byte: PartInstr | None = None
    label: str = ""
    channel: int | None = None


@dataclass(frozen=True)
class Transfer:
    direction: str          # TO_BYTE (= FBY k / READ FBY k) or TO_BIT (WRITE FBI k / .. FBI k)
    channel: int
    line: int
    col: int
    reason: str


@dataclass
class Partition:
    """The result of partition().

    bit / byte: the two parts (bit ends with END, byte with END_B); bit_labels /
    byte_labels: upper-case label -> address in that part; rows: program order, for
    side_by_side(); transfers: every inserted transfer, in program order; mirrored:
    source indices of the jumps the byte side takes too; bit_words / byte_words: the
    encoded parts (docs/isa.md); pool: the byte part's constant pool; warnings: for
    hand-partitioned programs, static channel counts that do not match."""

    program: Program
    channels: int
    bit: list[PartInstr]
    byte: list[PartInstr]
    bit_labels: dict[str, int]
    byte_labels: dict[str, int]
    rows: list[Row]
    transfers: list[Transfer]
    mirrored: list[int]
    bit_words: list[int] = field(default_factory=list)
    byte_words: list[int] = field(default_factory=list)
    pool: list[int] = field(default_factory=list)
    hand_partitioned: bool = False
    status_sync: bool = True
    warnings: list[str] = field(default_factory=list)
    schedule: tuple[int, int, int] | None = None   # rungs moved, model clocks before, after

    def bit_program(self) -> Program:
        return Program(self.program.path, list(self.bit), dict(self.bit_labels),
                       dict(self.program.symbols))

    def byte_program(self) -> Program:
        return Program(self.program.path, list(self.byte), dict(self.byte_labels),
                       dict(self.program.symbols))

    def transfer_count(self, direction: str) -> int:
        return sum(1 for t in self.transfers if t.direction == direction)

    def channels_used(self, direction: str) -> list[int]:
        return sorted({t.channel for t in self.transfers if t.direction == direction})
