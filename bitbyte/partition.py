"""Parallel mode's partitioning compiler (spec §2, §3 "Exchange instructions"; paper
§4.2-4.3, Fig. 10-15): one mixed program -> a bit part for the bit processor and a
byte part for the byte processor, with the transfer and synchronisation instructions
inserted, so that every scan's outputs, markers, words, timers and counters equal
serial mode's whatever the relative speed of the two processors.

The model
---------
In parallel mode each processor runs its own part from its own memory.  They meet only
in the exchange channels (`= FBY k` -> `READ FBY k`: a condition to the byte side;
`WRITE FBI k` -> `LD/A/O.. FBI k`: to the bit side; a read of an empty channel and a
write of a full one stall) and at END / END_B (the PIO/PII update waits for both).
Serial mode has one RLO; parallel mode has two condition flip-flops, F_b (bit side) and
F_B (byte side).  The compiler walks the program in order and keeps `loc`, the set of
sides whose flip-flop holds the serial RLO at this point: {bit, byte} at scan start
(both are 0 then: the bit RLO is reset, the firmware's bb_run_scan clears F_B).

The walk produces *rows*: one per instruction of either side, in program order; a
transfer is one row holding both halves (the write on one side, the read on the
other), a label one row valid on both sides.  The bit part is the rows' bit column,
the byte part the byte column.  Both sides execute the projections of the same path
(see "Jumps"), so each side meets the transfers in the same order; with a one-place
handshake channel per index (or one queue per direction) the i-th write of a channel
pairs with its i-th read, and since every transfer's two halves sit in one row, no
side can wait for something the other side only does later: no deadlock
(tests/test_partition.py checks both claims on random programs with random
interleavings).

Rules (source instruction -> rows):

* Bit instructions that read the RLO -- A AN O ON X XN, NOT, = S R, FP FN, JC JCN, the
  opening parentheses (they push it) and `)` (combines with it) -- need it on the bit
  side: if bit is not in loc, a transfer byte -> bit (byte `WRITE FBI k`, bit
  `LD FBI k`) goes before.  LD LDN SET CLR and the combining ones leave loc = {bit};
  = S R and the openers leave loc as it is (with bit added by the transfer).
* Byte instructions that read the RLO -- SD SS SP SF, R T n, CU CD, S C n, R C n --
  need it on the byte side: else a transfer bit -> byte (bit `= FBY k`, byte
  `READ FBY k`) goes before; they do not change it.  A plain compare sets it on the
  byte side (loc = {byte}).  `A cmp` / `O cmp`: with byte in loc they run as written
  (loc = {byte}); otherwise as in the paper's Fig. 13: the byte side runs the plain
  compare and `WRITE FBI k`, the bit side `A FBI k` / `O FBI k` (loc = {bit}) -- this
  spends no transfer of the RLO itself.  L, T and the arithmetic leave loc alone.
* Parentheses: the stack lives on the bit side; byte instructions inside are fine
  (an `A cmp` inside combines on the bit side as above; a `)` after a compare first
  fetches the RLO back).
* Jumps (bit JU/JC/JCN): the byte side must take the same path when the code the jump
  skips (forward: the rows between the jump and its label; backward: the rows of the
  loop body, label to jump) holds any byte-side row -- transfers the compiler put
  there included.  Then the jump is *mirrored*: JU gets a byte `JU_B`; JC/JCN get
  `JC_B`/`JCN_B` on F_B, after a bit -> byte transfer of the condition when byte is not
  in loc (when F_B already holds the RLO, e.g. right after a compare whose result was
  fetched for the jump, no transfer is needed: an improvement over "always transfer").
  Whether a jump needs mirroring depends on transfers inserted further on, so the walk
  is repeated with the set of mirrored jumps growing until nothing new is found (it
  only grows: a mirror adds byte rows, never removes the need for another).  A jump
  whose skipped code has no byte row is not mirrored: the byte side's sequence is the
  same whether it is taken or not.
* Join points: before a label that a jump targets (on the fall-through path, unless
  that path is dead after JU or END) and before every jump, the RLO is brought to the
  bit side; after such a label loc = {bit} (the paths may leave F_B differently).
  Labels are positions in both parts (`bit_labels`, `byte_labels`).
* Timer / counter status (spec §2: a bit-side read of `T n` / `C n` waits for every
  earlier instruction on that timer or counter).  "Earlier" is taken from the control
  flow graph: an update U may precede a read R in a scan when R is reachable from U
  (forward jumps may make this conservative, loops are covered -- plain program order
  would miss the read at the top of a loop that follows the update at its bottom in
  the previous iteration).
  - A bit read of T n / C n that an update of it may precede gets a synchronising
    round trip right before it: the RLO is made valid on the byte side (bit -> byte
    transfer if needed), then byte `WRITE FBI k` + bit `LD FBI k`, which both carries
    the RLO back and holds the read until the byte side has passed every earlier
    update.  When the read is LD/LDN (it overwrites the RLO anyway) the plain
    `WRITE FBI k` + `LD FBI k` suffices, whatever F_B holds.
  - A byte update of T n / C n that a bit read of it may precede must not overtake the
    read: a bit -> byte transfer goes right before the update even when the byte side
    already holds the RLO (when only the byte side holds it, it first goes to the bit
    side): the byte side cannot pass `READ FBY k` before the bit side has executed
    everything before `= FBY k`, the read included.
  `status_sync=False` drops both (the paper's Fig. 2 timers: the bit side never
  waits); that gives the paper's Fig. 13 exactly but is not serial-equivalent.
* REFRESH: one that would be the bit part's first instruction although it is not the
  program's first gets a NOP before it: the first bit instruction executes in the PII
  latch clock, where REFRESH is one with the latch, whereas serially it comes later
  and re-latches (clearing IR/IF).
* END anywhere: bit END and byte END_B in one row; the parts end with END / END_B.
* Channels: transfers are numbered round-robin per direction over `channels`
  (FBY 0, 1, 2, ... ; FBI 0, 1, ...), so a writer can run up to `channels` conditions
  ahead.  The queue exchange (one queue per direction) runs the same code: there the
  index is irrelevant, the order is what counts.
* Exchange instructions (READ, WRITE, operands FBI/FBY) in a mixed program are an
  error: the compiler inserts them.  A hand-partitioned program (`BIT:` / `BYTE:`
  sections, see bitbyte/parser.py) is taken verbatim: its BYTE section's JU/JC/JCN
  become JU_B/JC_B/JCN_B, its END END_B, and each part gets a final END / END_B when
  missing.

API: partition(program, channels=4) -> Partition; report_text(partition);
side_by_side(partition); part_listing(partition); estimate(partition);
assemble_parallel(path, outdir, config) writes the `bitbyte asm --mode parallel` files.
"""
from __future__ import annotations

import json
import os
from dataclasses import asdict, dataclass, field

from . import encoder
from .config import DEFAULT, Config
from .errors import SourceError
from .program import Instr, Operand, Program
from .refsim import COMBINES, COMPARES, OPENS, byte_kind, resolve_costs, serial_cost

BIT, BYTE = "bit", "byte"
TO_BYTE, TO_BIT = "to_byte", "to_bit"
JUMPS = ("JU", "JC", "JCN")
BYTE_JUMPS = {"JU": "JU_B", "JC": "JC_B", "JCN": "JCN_B"}
BYTE_PROG_WORDS = 4096            # firmware_byte BB_PROG_WORDS

# Bit instructions and the RLO
BIT_RLO_SETTERS = ("LD", "LDN", "SET", "CLR")                     # loc := {bit}
BIT_RLO_MODIFIERS = ("A", "AN", "O", "ON", "X", "XN", "NOT", "FP", "FN", ")")
BIT_RLO_KEEPERS = ("=", "S", "R") + tuple(OPENS) + ("JC", "JCN")   # read, keep
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


# --------------------------------------------------------------------------------------
# Entry point
# --------------------------------------------------------------------------------------

def partition(program: Program, channels: int = 4, *, config: Config = DEFAULT,
              status_sync: bool = True, hardware_wait: bool = True) -> Partition:
    """Split `program` into its bit and byte parts (module docstring) and encode them.

    channels: exchange channels per direction used round-robin (1..config.channels).
    status_sync=False: the paper's Fig. 2 timers (no waiting for T n / C n; not
    serial-equivalent).  hardware_wait: a status read that exactly one update
    precedes in the same straight-line stretch waits in hardware (instruction bit 16,
    docs/isa.md) instead of through a channel round trip.  Raises SourceError for what cannot be partitioned (an
    exchange instruction in a mixed program, a part too large) and ValueError for a
    bad channel count."""
    if not 1 <= channels <= config.channels:
        raise ValueError(f"channels must be 1..{config.channels} (the build's exchange "
                         f"channels per direction), not {channels}")
    if any(ins.section for ins in program.instrs):
        part = _hand_partitioned(program, channels)
    else:
        mirrored: set[int] = set()
        while True:
            builder = _Builder(program, channels, status_sync, mirrored, hardware_wait)
            builder.build()
            more = builder.unmirrored_jumps_over_byte_rows()
            if not more:
                break
            mirrored |= more
        part = builder.result()
    _encode(part, config)
    return part


# --------------------------------------------------------------------------------------
# The walk over a mixed program
# --------------------------------------------------------------------------------------

def _text(mnemonic: str, op: Operand | None) -> str:
    """`SD Timer`, `= FBY 0`, `A >=I`: an instruction as the listings show it."""
    if op is None:
        return mnemonic
    if op.area in ("FBI", "FBY"):
        return f"{mnemonic} {op.area} {op.index}"
    return f"{mnemonic} {op.text or op.address()}"


def _channel_operand(area: str, k: int) -> Operand:
    return Operand("index", area=area, index=k, text=f"{area}{k}")


class _Builder:
    def __init__(self, program: Program, channels: int, status_sync: bool,
                 mirrored: set[int], hardware_wait: bool = True):
        self.program = program
        self.channels = channels
        self.status_sync = status_sync
        self.hardware_wait = hardware_wait
        self.mirrored = set(mirrored)
        self.rows: list[Row] = []
        self.transfers: list[Transfer] = []
        self.loc = {BIT, BYTE}
        self.count = {TO_BYTE: 0, TO_BIT: 0}
        self.jump_rows: dict[int, int] = {}
        self.label_rows: dict[str, int] = {}
        self.bit_emitted = 0
        self.dead = False                    # fall-through after JU / END
        self.cur = 0                          # source index being compiled
        self.reach = _Reach(program)
        self.status_ops = _status_ops(program)

    # -- rows -------------------------------------------------------------------------

    def copy(self, ins: Instr) -> PartInstr:
        return PartInstr(ins.mnemonic, ins.operand, ins.line, ins.col, ins.source, [],
                         ins.section, origin=self.cur)

    def synth(self, mnemonic: str, op: Operand | None, note: str) -> PartInstr:
        cause = self.program.instrs[self.cur]
        return PartInstr(mnemonic, op, cause.line, cause.col, cause.source, [], "",
                         note=note, origin=self.cur, synthesized=True)

    def row(self, kind: str, bit: PartInstr | None = None, byte: PartInstr | None = None,
            channel: int | None = None) -> int:
        self.rows.append(Row(kind, self.cur, bit, byte, channel=channel))
        if bit is not None:
            self.bit_emitted += 1
        return len(self.rows) - 1

    def channel(self, direction: str) -> int:
        k = self.count[direction] % self.channels
        self.count[direction] += 1
        return k

    def to_byte(self, reason: str) -> None:
        """bit `= FBY k`, byte `READ FBY k`: F_B := the RLO (it must be on the bit side)."""
        assert BIT in self.loc, "bit -> byte transfer without the RLO on the bit side"
        k = self.channel(TO_BYTE)
        op = _channel_operand("FBY", k)
        self.row(TO_BYTE, self.synth("=", op, reason), self.synth("READ", op, reason), k)
        self.transfers.append(self._transfer(TO_BYTE, k, reason))
        self.loc = {BIT, BYTE}

    def to_bit(self, reason: str, bit_mnemonic: str = "LD", plain: bool = False) -> None:
        """byte `WRITE FBI k`, bit `<bit_mnemonic> FBI k`.  LD carries the RLO when F_B
        holds it; plain: F_B may hold anything (a pure synchronisation before an
        instruction that overwrites the RLO)."""
        assert plain or bit_mnemonic != "LD" or BYTE in self.loc
        k = self.channel(TO_BIT)
        op = _channel_operand("FBI", k)
        self.row(TO_BIT, self.synth(bit_mnemonic, op, reason),
                 self.synth("WRITE", op, reason), k)
        self.transfers.append(self._transfer(TO_BIT, k, reason))
        if bit_mnemonic != "LD":
            self.loc = {BIT}
        elif BYTE in self.loc:
            self.loc = {BIT, BYTE}
        else:
            self.loc = set()        # plain sync: the next instruction loads the RLO

    def _transfer(self, direction: str, k: int, reason: str) -> Transfer:
        cause = self.program.instrs[self.cur]
        return Transfer(direction, k, cause.line, cause.col, reason)

    def need_bit(self, reason: str) -> None:
        if BIT not in self.loc:
            self.to_bit(reason)

    def need_byte(self, reason: str) -> None:
        if BYTE not in self.loc:
            self.to_byte(reason)

    # -- the walk -----------------------------------------------------------------------

    def build(self) -> None:
        instrs = self.program.instrs
        targets = {ins.operand.label for ins in instrs if ins.mnemonic in JUMPS}
        for i, ins in enumerate(instrs):
            self.cur = i
            if ins.mnemonic == "REFRESH" and self.bit_emitted == 0 and i > 0:
                self.row(BIT, bit=self.synth("NOP", None, "REFRESH must not execute in "
                                                          "the PII latch clock: serially "
                                                          "it comes after byte work"))
            joined = [name for name in ins.labels if name.upper() in targets]
            if joined:
                if not self.dead:
                    self.need_bit(f"RLO to the bit side at the join point `{joined[0]}`")
                self.loc = {BIT}
                self.dead = False
            for name in ins.labels:
                self.label_rows[name.upper()] = len(self.rows)
                self.rows.append(Row("label", i, label=name))
            self.instruction(ins)

    def instruction(self, ins: Instr) -> None:
        m, op = ins.mnemonic, ins.operand
        if m in ("READ", "WRITE") or (op is not None and op.area in ("FBI", "FBY")):
            raise _error(self.program, ins, f"`{_text(m, op)}`: exchange instructions are "
                                            "inserted by the partitioning compiler; write "
                                            "them only in BIT:/BYTE: sections of a "
                                            "hand-partitioned program")
        if m == "END":
            self.row("both", self.copy(ins), self.synth("END_B", None, "end of the scan"))
            self.dead = True
            return
        kind = byte_kind(ins)
        if kind is not None:
            self.byte_instruction(ins, kind)
        elif m in JUMPS:
            self.jump(ins)
        else:
            self.bit_instruction(ins)

    def bit_instruction(self, ins: Instr) -> None:
        m, op = ins.mnemonic, ins.operand
        what = _text(m, op)
        wait_update = False
        if m in COMBINES and op.area in ("T", "C") and self.status_sync:
            update = self.status_ops.update_before(self.reach, self.cur)
            if update is not None and self.hardware_wait and \
                    self.status_ops.sole_dominating_update(self.reach, self.cur) is not None:
                wait_update = True                  # no transfer: the read waits in hardware
            elif update is not None:
                reason = f"sync: `{what}` waits for {update} on the byte side"
                if m in ("LD", "LDN"):
                    self.to_bit(reason, plain=True)
                else:
                    self.need_byte(f"RLO to the byte side for the sync of `{what}`")
                    self.to_bit(reason)
        if m in BIT_RLO_MODIFIERS or m in BIT_RLO_KEEPERS:
            self.need_bit(f"RLO for `{what}`")
        bit = self.copy(ins)
        if wait_update:
            bit.wait_update = True
            bit.synthesized = True
            bit.note = f"waits (bit 16) until {update} has run this scan"
        self.row(BIT, bit=bit)
        if m in BIT_RLO_SETTERS or m in BIT_RLO_MODIFIERS:
            self.loc = {BIT}

    def byte_instruction(self, ins: Instr, kind: str) -> None:
        what = _text(ins.mnemonic, ins.operand)
        if kind in COMPARES:
            self.row(BYTE, byte=self.copy(ins))
            self.loc = {BYTE}
        elif kind[:2] in ("A ", "O "):                          # A ==I ... O <=I
            if BYTE in self.loc:
                self.row(BYTE, byte=self.copy(ins))
                self.loc = {BYTE}
            else:
                logic, cmp = kind[0], kind[2:]
                self.row(BYTE, byte=self.synth(cmp, None, f"compare of `{what}`: the "
                                               f"RLO is on the bit side, {logic} there"))
                self.to_bit(f"`{what}`: compare result to the bit side", logic)
        elif kind in STATUS_UPDATES:
            read = self.status_ops.read_before(self.reach, self.cur) \
                if self.status_sync else None
            if read is not None:
                self.need_bit(f"RLO to the bit side, to order `{what}` after {read}")
                self.to_byte(f"RLO for `{what}`, and order: after {read} on the bit side")
            else:
                self.need_byte(f"RLO for `{what}`")
            self.row(BYTE, byte=self.copy(ins))
        else:                                                     # L, T, arithmetic
            self.row(BYTE, byte=self.copy(ins))

    def jump(self, ins: Instr) -> None:
        m, op = ins.mnemonic, ins.operand
        what = _text(m, op)
        self.need_bit(f"RLO to the bit side before `{what}` (join point `{op.text}`)")
        if self.cur in self.mirrored:
            note = f"the byte side takes `{what}` too: it skips byte code"
            if m != "JU":
                self.need_byte(f"condition of `{what}` for the byte side")
            self.jump_rows[self.cur] = self.row(
                "both", self.copy(ins), self.synth(BYTE_JUMPS[m], op, note))
        else:
            self.jump_rows[self.cur] = self.row(BIT, bit=self.copy(ins))
        if m == "JU":
            self.dead = True

    # -- jumps over byte rows -------------------------------------------------------------

    def unmirrored_jumps_over_byte_rows(self) -> set[int]:
        """The jumps not mirrored yet whose skipped rows (forward: after the jump up to
        the label; backward: the label up to the jump) hold a byte-side row."""
        before = [0]                          # byte rows before row n
        for row in self.rows:
            before.append(before[-1] + (row.byte is not None))
        more = set()
        for i, jr in self.jump_rows.items():
            if i in self.mirrored:
                continue
            lr = self.label_rows[self.program.instrs[i].operand.label]
            first, end = (jr + 1, lr) if lr > jr else (lr, jr)
            if before[max(end, first)] - before[first] > 0:
                more.add(i)
        return more

    # -- the two parts ---------------------------------------------------------------------

    def result(self) -> Partition:
        bit, byte, bit_labels, byte_labels = _split(self.rows)
        return Partition(self.program, self.channels, bit, byte, bit_labels, byte_labels,
                         self.rows, self.transfers, sorted(self.mirrored),
                         status_sync=self.status_sync)


def _split(rows: list[Row]):
    """The parts from the rows: labels become the address of the next instruction of
    each part."""
    bit: list[PartInstr] = []
    byte: list[PartInstr] = []
    bit_labels: dict[str, int] = {}
    byte_labels: dict[str, int] = {}
    pending: list[str] = []
    pending_b: list[str] = []
    for row in rows:
        if row.kind == "label":
            bit_labels[row.label.upper()] = len(bit)
            byte_labels[row.label.upper()] = len(byte)
            pending.append(row.label)
            pending_b.append(row.label)
            continue
        if row.bit is not None:
            row.bit.labels, pending = pending, []
            bit.append(row.bit)
        if row.byte is not None:
            row.byte.labels, pending_b = pending_b, []
            byte.append(row.byte)
    return bit, byte, bit_labels, byte_labels


class _Reach:
    """Which source instructions may execute after which in one scan (control flow
    graph: fall-through, jump targets; END ends the scan)."""

    def __init__(self, program: Program):
        self.program = program
        self.cache: dict[int, set[int]] = {}

    def successors(self, i: int) -> list[int]:
        instrs = self.program.instrs
        ins = instrs[i]
        if ins.mnemonic == "END":
            return []
        nxt = [i + 1] if i + 1 < len(instrs) else []
        if ins.mnemonic in JUMPS:
            target = self.program.labels[ins.operand.label]
            return [target] if ins.mnemonic == "JU" else nxt + [target]
        return nxt

    def after(self, i: int) -> set[int]:
        """Instructions reachable from i in one or more steps."""
        if i not in self.cache:
            seen: set[int] = set()
            todo = list(self.successors(i))
            while todo:
                j = todo.pop()
                if j not in seen:
                    seen.add(j)
                    todo.extend(self.successors(j))
            self.cache[i] = seen
        return self.cache[i]


class _StatusOps:
    """Per timer / counter: the byte updates and the bit reads of its status."""

    def __init__(self, program: Program):
        self.program = program
        self.updates: dict[tuple[str, int], list[int]] = {}
        self.reads: dict[tuple[str, int], list[int]] = {}

    def key(self, i: int) -> tuple[str, int]:
        op = self.program.instrs[i].operand
        return op.area, op.index

    def update_before(self, reach: _Reach, i: int) -> str | None:
        """An update of the status read at i that may execute before it, or None."""
        for q in self.updates.get(self.key(i), []):
            if i in reach.after(q):
                return _where(self.program.instrs[q])
        return None

    def sole_dominating_update(self, reach: _Reach, i: int) -> int | None:
        """The one update of the status read at i that precedes it, when the hardware
        wait (instruction bit 16: wait until the status was written this scan) orders
        them exactly: it is the only update that may run before i, it runs exactly
        once per scan before i (same straight-line stretch: no jump, END or jump
        target between them), and neither is inside a loop."""
        ups = [q for q in self.updates.get(self.key(i), []) if i in reach.after(q)]
        if len(ups) != 1:
            return None
        q = ups[0]
        if q >= i or q in reach.after(q) or i in reach.after(i):
            return None
        instrs = self.program.instrs
        targets = {self.program.labels[ins.operand.label] for ins in instrs
                   if ins.mnemonic in JUMPS}
        if any(instrs[j].mnemonic in JUMPS or instrs[j].mnemonic == "END"
               for j in range(q, i)) or any(j in targets for j in range(q + 1, i + 1)):
            return None
        return q

    def read_before(self, reach: _Reach, i: int) -> str | None:
        """A bit read of the status updated at i that may execute before it."""
        for p in self.reads.get(self.key(i), []):
            if i in reach.after(p):
                return _where(self.program.instrs[p])
        return None


def _where(ins: Instr) -> str:
    return f"`{_text(ins.mnemonic, ins.operand)}` (line {ins.line})"


def _status_ops(program: Program) -> _StatusOps:
    ops = _StatusOps(program)
    for i, ins in enumerate(program.instrs):
        op = ins.operand
        if op is None or op.area not in ("T", "C") or op.kind != "index":
            continue
        if byte_kind(ins) in STATUS_UPDATES:
            ops.updates.setdefault((op.area, op.index), []).append(i)
        elif ins.mnemonic in COMBINES:
            ops.reads.setdefault((op.area, op.index), []).append(i)
    return ops


# --------------------------------------------------------------------------------------
# Hand-partitioned programs (BIT: / BYTE: sections)
# --------------------------------------------------------------------------------------

def _hand_partitioned(program: Program, channels: int) -> Partition:
    parts: dict[str, list[PartInstr]] = {"BIT": [], "BYTE": []}
    labels: dict[str, dict[str, int]] = {"BIT": {}, "BYTE": {}}
    transfers: list[Transfer] = []
    for i, ins in enumerate(program.instrs):
        side = ins.section
        if side not in parts:              # the parser puts every instruction in one
            raise _error(program, ins, "instruction outside the BIT:/BYTE: sections")
        for name in ins.labels:
            labels[side][name.upper()] = len(parts[side])
        m, op = ins.mnemonic, ins.operand
        p = PartInstr(m, op, ins.line, ins.col, ins.source, list(ins.labels), side,
                      origin=i)
        if side == "BYTE" and m in BYTE_JUMPS:
            p.mnemonic, p.note = BYTE_JUMPS[m], "byte jump on F_B"
        elif side == "BYTE" and m == "END":
            p.mnemonic, p.note = "END_B", "end of the byte part"
        parts[side].append(p)
        if op is not None and op.area in ("FBI", "FBY"):
            if op.index >= channels:
                raise _error(program, ins, f"operand out of range: `{op.address()}` "
                                           f"(channels 0..{channels - 1} in this build)")
            if m == "=" and side == "BIT":
                transfers.append(Transfer(TO_BYTE, op.index, ins.line, ins.col, "written"))
            elif m == "WRITE":
                transfers.append(Transfer(TO_BIT, op.index, ins.line, ins.col, "written"))
    for side, end in (("BIT", "END"), ("BYTE", "END_B")):
        if not parts[side] or parts[side][-1].mnemonic != end:
            last = program.instrs[-1]
            parts[side].append(PartInstr(end, None, last.line, last.col, "", [], side,
                                         note="appended", synthesized=True))
    bit, byte = parts["BIT"], parts["BYTE"]
    rows = [Row("pair", None, bit[n] if n < len(bit) else None,
                byte[n] if n < len(byte) else None)
            for n in range(max(len(bit), len(byte)))]
    return Partition(program, channels, bit, byte, labels["BIT"], labels["BYTE"], rows,
                     transfers, [], hand_partitioned=True,
                     warnings=_channel_count_warnings(bit, byte))


def _channel_count_warnings(bit: list[PartInstr], byte: list[PartInstr]) -> list[str]:
    """Static counts per channel (writes on one side vs reads on the other)."""
    def count(instrs, pred):
        out: dict[int, int] = {}
        for ins in instrs:
            if ins.operand is not None and pred(ins):
                out[ins.operand.index] = out.get(ins.operand.index, 0) + 1
        return out
    fby_w = count(bit, lambda i: i.mnemonic == "=" and i.operand.area == "FBY")
    fby_r = count(byte, lambda i: i.mnemonic == "READ")
    fbi_w = count(byte, lambda i: i.mnemonic == "WRITE")
    fbi_r = count(bit, lambda i: i.mnemonic in COMBINES and i.operand.area == "FBI")
    warnings = []
    for name, w, r, ws, rs in (("FBY", fby_w, fby_r, "bit", "byte"),
                               ("FBI", fbi_w, fbi_r, "byte", "bit")):
        for k in sorted(set(w) | set(r)):
            if w.get(k, 0) != r.get(k, 0):
                warnings.append(f"channel {name} {k}: {w.get(k, 0)} write(s) on the {ws} "
                                f"side, {r.get(k, 0)} read(s) on the {rs} side (static "
                                "count: fine only if the paths make them pair up)")
    return warnings


# --------------------------------------------------------------------------------------
# Encoding
# --------------------------------------------------------------------------------------

def _encode(part: Partition, config: Config) -> None:
    for name, instrs, limit in (("bit", part.bit, config.prog_words),
                                ("byte", part.byte, BYTE_PROG_WORDS)):
        if len(instrs) > limit:
            culprit = instrs[limit]
            raise SourceError(part.program.path, culprit.line, culprit.col,
                              f"program too large: the {name} part has {len(instrs)} "
                              f"words, its program memory holds {limit}", culprit.source)
    part.bit_words = encoder.encode_bit_part(part.bit_program())
    byte_program = part.byte_program()
    part.pool = encoder.constant_pool(byte_program)
    part.byte_words = encoder.encode_byte_part(byte_program, part.pool)


def _error(program: Program, ins: Instr, message: str) -> SourceError:
    return SourceError(program.path, ins.line, ins.col, message, ins.source)


# --------------------------------------------------------------------------------------
# Estimate, report, listings
# --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Estimate:
    """Clocks per scan along the straight-line path (jumps not taken, loops once).

    bit_clocks: bit-part instructions, END included (1 clock each).  byte_clocks: the
    byte part's cost-table sum (word instructions, READ/WRITE/JU_B/JC_B/JCN_B binary,
    END_B 0).  tail: bit instructions from the last FBI read through END: they cannot
    start before the byte side's last WRITE.  clocks = max(byte_clocks + tail,
    bit_clocks).  serial: the same program in serial mode (None if hand-partitioned)."""

    bit_clocks: int
    byte_clocks: int
    tail: int
    clocks: int
    serial: int | None
    word_instrs: int
    binary_instrs: int


def estimate(part: Partition, costs="paper") -> Estimate:
    table = resolve_costs(costs)
    byte_clocks = words = binaries = 0
    for ins in part.byte:
        if ins.mnemonic == "END_B":
            continue
        kind = "READ" if ins.mnemonic in BYTE_JUMPS.values() else byte_kind(ins)
        byte_clocks += table[kind]
        if kind in ("READ", "WRITE"):
            binaries += 1
        else:
            words += 1
    last_read = max((n for n, ins in enumerate(part.bit)
                     if ins.operand is not None and ins.operand.area == "FBI"), default=None)
    tail = 1 if last_read is None else len(part.bit) - last_read
    bit_clocks = len(part.bit)
    serial = None if part.hand_partitioned else serial_cost(part.program, costs) + 1
    return Estimate(bit_clocks, byte_clocks, tail, max(byte_clocks + tail, bit_clocks),
                    serial, words, binaries)


def report_text(part: Partition, costs="paper") -> str:
    """Instructions per side, transfers per direction, channels used, the estimated
    clocks per scan (and how they are estimated)."""
    est = estimate(part, costs)
    nbit, nbyte = len(part.bit) - 1, len(part.byte) - 1
    out = [f"; partition of {part.program.path}"
           + (" (hand-partitioned: BIT:/BYTE: sections taken verbatim)"
              if part.hand_partitioned else ""),
           f"bit part:  {nbit} instructions + END = {len(part.bit)} words",
           f"byte part: {nbyte} instructions + END_B = {len(part.byte)} words"]
    for direction, name, arrow in ((TO_BYTE, "FBY", "bit -> byte"),
                                   (TO_BIT, "FBI", "byte -> bit")):
        used = part.channels_used(direction)
        chans = ", ".join(f"{name} {k}" for k in used) or "none"
        out.append(f"transfers {arrow}: {part.transfer_count(direction)} "
                   f"(channels used: {chans})")
    out.append(f"channels per direction: {part.channels} (round-robin; with the queue "
               "exchange the order alone counts)")
    if not part.hand_partitioned:
        out.append(f"status sync (spec section 2: T n / C n reads wait for earlier updates): "
                   f"{'on' if part.status_sync else 'off (paper Fig. 2: not serial-equivalent)'}")
        mirrored = [part.program.instrs[i] for i in part.mirrored]
        out.append("jumps the byte side takes too: " + (", ".join(
            f"`{_text(j.mnemonic, j.operand)}` (line {j.line})" for j in mirrored)
            or "none"))
    for t in part.transfers:
        arrow = "bit -> byte" if t.direction == TO_BYTE else "byte -> bit"
        name = "FBY" if t.direction == TO_BYTE else "FBI"
        out.append(f"  line {t.line:>4}: {arrow} {name} {t.channel}: {t.reason}")
    for w in part.warnings:
        out.append(f"warning: {w}")
    out += ["",
            f"estimated clocks per scan: {est.clocks} = max(byte part {est.byte_clocks} "
            f"+ bit tail {est.tail}, bit part {est.bit_clocks})",
            f"  byte part: {est.word_instrs} word instructions + {est.binary_instrs} "
            f"binary (READ/WRITE/jumps) at the {costs if isinstance(costs, str) else 'given'}"
            f" costs, END_B 0 = {est.byte_clocks} clocks",
            f"  bit part: {len(part.bit)} instructions at 1 clock, END included",
            f"  bit tail: the instructions from the last FBI read through END "
            f"({est.tail}); they wait for the byte side's last WRITE",
            "  (straight-line path: jumps not taken, loops once; other waits are assumed "
            "hidden under the byte side's work; the hardware's cycles are the measure)"]
    if est.serial is not None:
        out.append(f"serial mode: {est.serial} clocks per scan "
                   f"({est.serial - 1} of instruction work + END)")
    return "\n".join(out) + "\n"


def _cell(ins: PartInstr | None) -> str:
    if ins is None:
        return ""
    op = ins.operand
    if op is None:
        return ins.mnemonic
    text = f"{op.area} {op.index}" if op.area in ("FBI", "FBY") else (op.text or op.address())
    return f"{ins.mnemonic:<6}{text}"


def side_by_side(part: Partition) -> str:
    """Two columns like the paper's Fig. 13: each instruction in its own row, in
    program order; a transfer is one row, `-->` bit to byte, `<--` byte to bit."""
    w = 26
    out = [f"{'line':>4}  {'bit processor':<{w}} {'':5} byte processor",
           f"{'----':>4}  {'-' * w} {'':5} {'-' * w}"]
    if part.hand_partitioned:
        out.insert(0, "; hand-partitioned: the columns are independent (row n = the "
                      "n-th instruction of each part)")
    for row in part.rows:
        if row.kind == "label":
            cell = row.label + ":"
            out.append(f"{'':4}  {cell:<{w}} {'':5} {cell}")
            continue
        ins = row.bit if row.bit is not None else row.byte
        line = "" if ins is None or ins.line <= 0 else str(ins.line)
        arrow = {TO_BYTE: "-->", TO_BIT: "<--"}.get(row.kind, "")
        text = f"{line:>4}  {_cell(row.bit):<{w}} {arrow:^5} {_cell(row.byte):<{w}}"
        notes = [i.note for i in (row.bit, row.byte)
                 if i is not None and i.synthesized and i.note]
        if notes and not part.hand_partitioned:
            text += f" ; {notes[0]}"
        out.append(text.rstrip())
    return "\n".join(out) + "\n"


def part_listing(part: Partition) -> str:
    """Both parts, address by address: `AAAA  WWWWWWWW  line: instruction ; note`."""
    out = []
    for name, instrs, words, labels in (
            ("bit part (bit processor program memory)", part.bit, part.bit_words,
             part.bit_labels),
            ("byte part (byte processor program memory)", part.byte, part.byte_words,
             part.byte_labels)):
        out += ["", f"{name}: {len(words)} words", "addr  word      line: instruction"]
        for address, (ins, word) in enumerate(zip(instrs, words)):
            out += [f"{'':16}{label}:" for label in ins.labels]
            text = _cell(ins)
            if ins.operand is not None and ins.operand.kind == "label":
                text += f"  -> {labels[ins.operand.label]:04X}"
            line = f"{address:04X}  {word:08X}  {ins.line:>4}: {text}"
            out.append(f"{line:<56} ; {ins.note}" if ins.note else line)
    return "\n".join(out) + "\n"


# --------------------------------------------------------------------------------------
# bitbyte asm --mode parallel
# --------------------------------------------------------------------------------------

def assemble_parallel(path: str, outdir: str | None = None, config: Config = DEFAULT,
                      channels: int | None = None) -> dict:
    """Parse, partition, encode, write (stem = the source's name without .il):

      <stem>.bit.hex        bit part image ($readmemh, one 8-digit word per line)
      <stem>.byte.hex       byte part image (the firmware's bb_load_program words)
      <stem>.pool.hex       the byte part's constant pool, only when it has one
      <stem>.lst            report, side-by-side view, both parts address by address
      <stem>.partition.txt  report and side-by-side view
      <stem>.json           {"source", "mode", "channels", "config", "symbols",
                             "bit_words", "byte_words", "bit_labels", "byte_labels",
                             "transfers", "mirrored_jumps", "estimate"}

    Returns {"bit_hex", "byte_hex", ["pool"], "lst", "report", "json": paths,
    "words": bit words, "byte_words": byte words}.  Nothing is written on an error."""
    from .asm import _write, hex_image
    from .parser import parse_file

    program = parse_file(path, config)
    part = partition(program, channels or config.channels, config=config)
    report = report_text(part)
    view = side_by_side(part)
    stem = os.path.splitext(os.path.basename(path))[0]
    outdir = outdir if outdir is not None else (os.path.dirname(path) or ".")
    os.makedirs(outdir, exist_ok=True)
    paths = {key: os.path.join(outdir, f"{stem}.{ext}") for key, ext in (
        ("bit_hex", "bit.hex"), ("byte_hex", "byte.hex"), ("lst", "lst"),
        ("report", "partition.txt"), ("json", "json"))}
    _write(paths["bit_hex"], hex_image(part.bit_words))
    _write(paths["byte_hex"], hex_image(part.byte_words))
    if part.pool:
        paths["pool"] = os.path.join(outdir, f"{stem}.pool.hex")
        _write(paths["pool"], hex_image(part.pool))
    _write(paths["report"], report + "\n" + view)
    _write(paths["lst"], report + "\n" + view + part_listing(part))
    est = estimate(part)
    summary = {
        "source": program.path, "mode": "parallel", "channels": part.channels,
        "hand_partitioned": part.hand_partitioned, "config": asdict(config),
        "symbols": {name: op.address() for name, op in program.symbols.items()},
        "bit_words": len(part.bit_words), "byte_words": len(part.byte_words),
        "bit_labels": part.bit_labels, "byte_labels": part.byte_labels,
        "transfers": [asdict(t) for t in part.transfers],
        "mirrored_jumps": [program.instrs[i].line for i in part.mirrored],
        "estimate": asdict(est),
    }
    _write(paths["json"], json.dumps(summary, indent=2) + "\n")
    return {**paths, "words": len(part.bit_words), "byte_words": len(part.byte_words)}
