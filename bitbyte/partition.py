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
  the previous iteration).  A byte -> bit transfer row between U and R already orders
  them (the bit side cannot pass its `.. FBI k` before the byte side has executed
  every row before `WRITE FBI k`, U included), so the walk keeps the set of timers /
  counters updated since the last byte -> bit row on some path (`unsynced_updates`:
  joined over the jumps to a label; at a loop head every updated one), and a read
  needs ordering only when its timer / counter is in that set *and* an update may
  precede it; symmetrically `unsynced_reads` (bit reads since the last bit -> byte
  row) for updates after reads.
  - A bit read of T n / C n that needs ordering gets a synchronising round trip
    right before it: the RLO is made valid on the byte side (bit -> byte transfer if
    needed), then byte `WRITE FBI k` + bit `LD FBI k`, which both carries the RLO
    back and holds the read until the byte side has passed every earlier update.
    When the read is LD/LDN (it overwrites the RLO anyway) the plain `WRITE FBI k` +
    `LD FBI k` suffices, whatever F_B holds.  (hardware_wait: a read with a sole
    update in the same straight stretch waits in hardware instead, bit 16.)
  - A byte update of T n / C n that a bit read of it may precede, with no bit -> byte
    row in between, must not overtake the read: a bit -> byte transfer goes right
    before the update even when the byte side already holds the RLO (when only the
    byte side holds it, it first goes to the bit side): the byte side cannot pass
    `READ FBY k` before the bit side has executed everything before `= FBY k`, the
    read included.
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
* The bit side's schedule (`schedule`, on by default with the status sync; off in
  the paper's / free-running mode): the rows fix the byte part and the order of the
  transfers, but the bit part's rungs may run in another order inside a basic block
  (cut at labels, jumps, END).  A rung starts at an RLO load (LD LDN SET CLR) at
  parenthesis depth 0 and runs to the next one: nothing before it is read by it,
  its RLO is dead at its end.  Two rungs keep their order when one writes a bit the
  other reads or writes; when both hold `= FBY` writes or both FBI reads (the i-th
  write pairs with the i-th read); when the first holds `= FBY` and the second
  waits for the byte side (an FBI read, a bit-16 status read) -- only writes to the
  byte side move up past reads from it; when either reads T n / C n and the other
  holds a transfer (the status ordering above counts on those positions); and
  around barriers (jumps, END, REFRESH, NOP, PI / PQ, a block's first rung when it
  continues an RLO, a block's last rung: the code after a label may continue its RLO).  So every rung computes what it computes serially, and
  serial-equivalence is kept.  Among the orders allowed, a list schedule driven by
  a timing model of the straight-line path (bit: 1 clock per instruction, byte: the
  cost table; `_Timing`) takes the rungs a pending `= FBY` depends on when the byte
  side would otherwise wait for it, else the first rung in program order that
  runs without waiting, else the one that finishes first: a rung that needs a
  compare result steps back and independent bit work runs meanwhile.  Each block's
  new order is played against the byte part with one place per direction (a queue
  of depth 1: every handshake channel count and queue depth waits on a subset of
  that) and kept only when it cannot deadlock; the whole order only when the model
  gives fewer clocks than program order.  Transfers are complete inside a block on
  both sides and the sides take the same path through the blocks, so the per-block
  check covers every path.  report_text() says how many rungs moved.
* Exchange instructions (READ, WRITE, operands FBI/FBY) in a mixed program are an
  error: the compiler inserts them.  A hand-partitioned program (`BIT:` / `BYTE:`
  sections, see bitbyte/parser.py) is taken verbatim: its BYTE section's JU/JC/JCN
  become JU_B/JC_B/JCN_B, its END END_B, and each part gets a final END / END_B when
  missing.

API: partition(program, channels=4, *, config, status_sync, hardware_wait, schedule,
costs) -> Partition; report_text(partition);
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


# --------------------------------------------------------------------------------------
# Entry point
# --------------------------------------------------------------------------------------

def partition(program: Program, channels: int = 4, *, config: Config = DEFAULT,
              status_sync: bool = True, hardware_wait: bool = True,
              schedule: bool | None = None, costs="paper") -> Partition:
    """Split `program` into its bit and byte parts (module docstring) and encode them.

    channels: exchange channels per direction used round-robin (1..config.channels).
    status_sync=False: the paper's Fig. 2 timers (no waiting for T n / C n; not
    serial-equivalent).  hardware_wait: a status read that exactly one update
    precedes in the same straight-line stretch waits in hardware (instruction bit 16,
    docs/isa.md) instead of through a channel round trip.  schedule: reorder the bit
    part's rungs inside basic blocks to wait less (default: on with status_sync);
    costs: the byte cost table the schedule's timing model assumes (the order is valid
    for any).  Raises SourceError for what cannot be partitioned (an exchange
    instruction in a mixed program, a part too large) and ValueError for a bad channel
    count."""
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
        if status_sync if schedule is None else schedule:
            _schedule_bit_part(part, costs)
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
        # Timer / counter keys with a byte update not yet followed by a byte -> bit
        # transfer (on some path), and with a bit read not yet followed by a bit -> byte
        # transfer: see "Timer / counter status" in the module docstring.
        self.unsynced_updates: set[tuple[str, int]] = set()
        self.unsynced_reads: set[tuple[str, int]] = set()
        self.label_state: dict[str, tuple[set, set]] = {}     # from the jumps to it

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
        if kind == TO_BIT:          # the bit side passes it only after every byte row before
            self.unsynced_updates = set()
        elif kind == TO_BYTE:       # the byte side passes it only after every bit row before
            self.unsynced_reads = set()
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
                else:
                    self.unsynced_updates, self.unsynced_reads = set(), set()
                self.loc = {BIT}
                self.dead = False
                self.join_status(i, joined)
            for name in ins.labels:
                self.label_rows[name.upper()] = len(self.rows)
                self.rows.append(Row("label", i, label=name))
            self.instruction(ins)

    def join_status(self, i: int, joined: list[str]) -> None:
        """The unsynced timer / counter keys at a join point: those of the fall-through
        path (already in place) and of every forward jump to it; a loop head (a jump at
        or after it targets it) gets every key the program updates / reads, since the
        loop's back edge is not compiled yet."""
        instrs = self.program.instrs
        names = {name.upper() for name in joined}
        for name in names:
            ups, reads = self.label_state.get(name, (set(), set()))
            self.unsynced_updates |= ups
            self.unsynced_reads |= reads
        if any(ins.mnemonic in JUMPS and ins.operand.label.upper() in names
               for ins in instrs[i:]):
            self.unsynced_updates |= set(self.status_ops.updates)
            self.unsynced_reads |= set(self.status_ops.reads)

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
        status = m in COMBINES and op.area in ("T", "C") and op.kind == "index"
        if status and self.status_sync:
            update = self.status_ops.update_before(self.reach, self.cur) \
                if (op.area, op.index) in self.unsynced_updates else None
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
        if status:
            self.unsynced_reads.add((op.area, op.index))
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
            key = (ins.operand.area, ins.operand.index)
            read = self.status_ops.read_before(self.reach, self.cur) \
                if self.status_sync and key in self.unsynced_reads else None
            if read is not None:
                self.need_bit(f"RLO to the bit side, to order `{what}` after {read}")
                self.to_byte(f"RLO for `{what}`, and order: after {read} on the bit side")
            else:
                self.need_byte(f"RLO for `{what}`")
            self.row(BYTE, byte=self.copy(ins))
            self.unsynced_updates.add(key)
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
        ups, reads = self.label_state.setdefault(op.label.upper(), (set(), set()))
        ups |= self.unsynced_updates
        reads |= self.unsynced_reads
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
# The bit side's schedule (list scheduling of rungs inside a basic block)
# --------------------------------------------------------------------------------------

_SCHED_AREAS = ("I", "IR", "IF", "Q", "M", "T", "C", "FBI", "FBY")


@dataclass
class _Seg:
    """A rung of the bit part: from an RLO setter at parenthesis depth 0 (or a block's
    start) up to the next one.  Its RLO is its own: nothing before it is read by it,
    nothing it leaves in F_b is read after it (the next rung overwrites F_b first), so
    rungs may change places when their data and the exchange allow it."""

    lo: int                               # bit part indices [lo, hi)
    hi: int
    reads: set = field(default_factory=set)
    writes: set = field(default_factory=set)
    fby: list = field(default_factory=list)      # ordinals of its `= FBY k` (bit order)
    fbi: list = field(default_factory=list)      # ordinals of its `.. FBI k` reads
    updates: list = field(default_factory=list)  # byte indices its bit-16 reads wait for
    status: bool = False                  # reads T n / C n
    barrier: bool = False                 # stays where it is, everything else around it


def _segments(bit: list[PartInstr], lo: int, hi: int, fby_no: dict, fbi_no: dict,
              wait_on: dict) -> list[_Seg] | None:
    """The rungs of the block bit[lo:hi]; None when the block closes a parenthesis
    it did not open (then it is left alone). A block that starts inside parentheses
    is split as usual: its first rung (a barrier) holds everything up to the first
    RLO load at depth 0."""
    segs: list[_Seg] = []
    depth = 0
    for n in range(lo, hi):
        ins = bit[n]
        m, op = ins.mnemonic, ins.operand
        if not segs or (depth == 0 and m in BIT_RLO_SETTERS):
            segs.append(_Seg(n, n + 1, barrier=not (depth == 0 and m in BIT_RLO_SETTERS)))
        seg = segs[-1]
        seg.hi = n + 1
        if m in OPENS:
            depth += 1
        elif m == ")":
            depth -= 1
        if depth < 0:
            return None
        if m in JUMPS or m in ("END", "NOP", "REFRESH") or \
                (op is not None and op.kind not in ("bit", "index", "label")) or \
                (op is not None and op.kind != "label" and op.area not in _SCHED_AREAS):
            seg.barrier = True
            continue
        if op is None:
            continue
        if op.area == "FBY":
            seg.fby.append(fby_no[n])
        elif op.area == "FBI":
            seg.fbi.append(fbi_no[n])
        elif op.area in ("T", "C"):
            seg.status = True
            if n in wait_on:
                seg.updates.append(wait_on[n])
        else:
            key = (op.area, op.bit_number)
            if m in ("=", "S", "R"):
                seg.writes.add(key)
            elif m in ("FP", "FN"):
                seg.reads.add(key)
                seg.writes.add(key)
            else:
                seg.reads.add(key)
    if segs:
        # the block's last rung stays last: what it leaves (the RLO, an open
        # parenthesis) may be used after the block's end (a label's fall-through)
        segs[-1].barrier = True
    return segs


def _seg_preds(segs: list[_Seg]) -> list[set[int]]:
    """Which rungs each rung must stay behind (indices into segs).

    data: a rung that writes a bit another one reads or writes (either order);
    exchange: `= FBY` writes keep their order, FBI reads keep theirs (the queues pair
    the i-th write with the i-th read), and a rung that waits for the byte side (an
    FBI read, a bit-16 status read) stays behind every `= FBY` that came before it, so
    the byte side never waits for a write placed after a read that waits for it; only
    `= FBY` writes move up past FBI reads.  A T n / C n read keeps its place among the
    rungs that hold transfers (the syncs the compiler chose count on it); barriers
    (jumps, END, REFRESH, NOP, PI/PQ, a block's first rung when it continues the RLO
    and its last rung) keep theirs among all."""
    preds: list[set[int]] = [set() for _ in segs]
    for j, b in enumerate(segs):
        for i in range(j):
            a = segs[i]
            if a.barrier or b.barrier:
                dep = True
            elif a.writes & (b.reads | b.writes) or a.reads & b.writes:
                dep = True
            elif (a.fby and b.fby) or (a.fbi and b.fbi):
                dep = True
            elif a.fby and (b.fbi or b.updates):
                dep = True
            elif (b.status or b.updates) and (a.fby or a.fbi):
                dep = True
            elif (a.status or a.updates) and (b.fby or b.fbi):
                dep = True
            else:
                dep = False
            if dep:
                preds[j].add(i)
    return preds


class _Timing:
    """The compile-time timing model the schedule is chosen with: the straight-line
    path (jumps not taken), the bit side 1 clock per instruction, the byte side its
    cost table, a transfer seen by the reader the clock after the write, a status the
    clock after its update.  Only the choice of the order depends on it; whether an
    order is allowed does not."""

    def __init__(self, byte: list[PartInstr], costs):
        self.table = resolve_costs(costs)
        self.byte = byte
        self.fby_time: dict[int, int] = {}     # FBY ordinal -> clock the byte side sees it
        self.fbi_time: dict[int, int] = {}     # FBI ordinal -> clock the bit side sees it
        self.upd_time: dict[int, int] = {}     # byte index -> clock its status is seen
        self.pc = 0
        self.t = 0                             # byte side's clock
        self.reads = 0
        self.writes = 0

    def clone(self) -> "_Timing":
        other = _Timing.__new__(_Timing)
        other.__dict__.update(self.__dict__)
        other.fby_time, other.fbi_time = dict(self.fby_time), dict(self.fbi_time)
        other.upd_time = dict(self.upd_time)
        return other

    def advance(self) -> None:
        """Run the byte side until it needs a bit -> byte transfer not written yet."""
        while self.pc < len(self.byte):
            ins = self.byte[self.pc]
            m = ins.mnemonic
            if m == "END_B":
                break
            start = self.t
            if m == "READ":
                if self.reads not in self.fby_time:
                    return
                start = max(start, self.fby_time[self.reads])
                self.reads += 1
                cost = self.table["READ"]
            elif m == "WRITE":
                self.fbi_time[self.writes] = start + 1
                self.writes += 1
                cost = self.table["WRITE"]
            elif m in BYTE_JUMPS.values():
                cost = self.table["READ"]
            else:
                cost = self.table[byte_kind(ins)]
            self.t = start + cost
            if byte_kind(ins) in STATUS_UPDATES:
                self.upd_time[self.pc] = self.t
            self.pc += 1

    def run_seg(self, bit: list[PartInstr], seg: _Seg, t: int, fby_no: dict,
                fbi_no: dict, wait_on: dict, commit: bool) -> float:
        """The clock the bit side finishes seg at when it starts at t (inf: it would
        wait for something the byte side cannot produce yet)."""
        for n in range(seg.lo, seg.hi):
            op = bit[n].operand
            ready = t
            if n in fbi_no:
                ready = self.fbi_time.get(fbi_no[n], float("inf"))
            elif n in wait_on:
                ready = self.upd_time.get(wait_on[n], float("inf"))
            t = max(t, ready) + 1
            if t == float("inf"):
                return t
            if commit and op is not None and n in fby_no:
                self.fby_time[fby_no[n]] = t
                self.advance()
        return t


def _transfer_numbers(bit: list[PartInstr]) -> tuple[dict, dict]:
    fby_no, fbi_no = {}, {}
    for n, ins in enumerate(bit):
        op = ins.operand
        if op is not None and op.kind == "index" and op.area == "FBY":
            fby_no[n] = len(fby_no)
        elif op is not None and op.kind == "index" and op.area == "FBI":
            fbi_no[n] = len(fbi_no)
    return fby_no, fbi_no


def _update_waits(part: Partition) -> dict[int, int]:
    """bit index of each bit-16 status read -> byte index of the update it waits for
    (the last update of that timer / counter before it in the rows)."""
    bit_at = {id(ins): n for n, ins in enumerate(part.bit)}
    byte_at = {id(ins): n for n, ins in enumerate(part.byte)}
    last: dict[tuple[str, int], int] = {}
    out = {}
    for row in part.rows:
        y = row.byte
        if y is not None and byte_kind(y) in STATUS_UPDATES:
            last[(y.operand.area, y.operand.index)] = byte_at[id(y)]
        b = row.bit
        if b is not None and b.wait_update:
            out[bit_at[id(b)]] = last[(b.operand.area, b.operand.index)]
    return out


def _blocks(part: Partition) -> list[tuple[int, int]]:
    """Basic blocks of the bit part: cut at every label and after every jump / END."""
    starts = {0} | set(part.bit_labels.values())
    for n, ins in enumerate(part.bit):
        if ins.mnemonic in JUMPS or ins.mnemonic == "END":
            starts.add(n + 1)
    cuts = sorted(s for s in starts if 0 <= s <= len(part.bit)) + [len(part.bit)]
    return [(a, b) for a, b in zip(cuts, cuts[1:]) if a < b]


def _model_clocks(part: Partition, bit: list[PartInstr], costs) -> float:
    """The timing model's clocks per scan for a bit part order (straight line)."""
    fby_no, fbi_no = _transfer_numbers(bit)
    wait_on = _remap(_update_waits(part), part.bit, bit)
    tm = _Timing(part.byte, costs)
    tm.advance()
    t = 0
    for n in range(len(bit)):
        seg = _Seg(n, n + 1)
        if bit[n].mnemonic == "END":
            tm.advance()
            return max(t, tm.t) + 1
        t = tm.run_seg(bit, seg, t, fby_no, fbi_no, wait_on, True)
        if t == float("inf"):
            return t                  # cannot happen for an order _no_deadlock passed
    return max(t, tm.t) + 1


def _no_deadlock(bit: list[PartInstr], lo: int, hi: int, byte: list[PartInstr],
                 fby_no: dict, fbi_no: dict, wait_on: dict) -> bool:
    """True when the block bit[lo:hi] in its present order cannot deadlock against
    the byte side.  The exchange events
    of the block (its `= FBY` / FBI reads / bit-16 reads; on the byte side the READs,
    WRITEs and updates they pair with, in byte order) are played with one place per
    direction, the tightest exchange there is (a queue of depth 1): whatever the two
    sides' speeds, each event can run once everything it waits for has run.  With
    more places (deeper queues, handshake channels used round-robin) the waits are a
    subset, so no order that passes here can deadlock there."""
    bit_ev = []
    for n in range(lo, hi):
        if n in fby_no:
            bit_ev.append(("w", fby_no[n]))
        elif n in fbi_no:
            bit_ev.append(("r", fbi_no[n]))
        elif n in wait_on:
            bit_ev.append(("u", wait_on[n]))
    if not bit_ev:
        return True
    fbys = {k for e, k in bit_ev if e == "w"}
    fbis = {k for e, k in bit_ev if e == "r"}
    ups = {k for e, k in bit_ev if e == "u"}
    byte_ev = []
    reads = writes = 0
    for y, ins in enumerate(byte):
        if ins.mnemonic == "READ":
            if reads in fbys:
                byte_ev.append(("r", reads))
            reads += 1
        elif ins.mnemonic == "WRITE":
            if writes in fbis:
                byte_ev.append(("w", writes))
            writes += 1
        if y in ups:
            byte_ev.append(("u", y))
    written = {"fby": set(), "fbi": set()}
    consumed = {"fby": set(), "fbi": set()}
    updated: set[int] = set()
    lo_fby, lo_fbi = min(fbys, default=0), min(fbis, default=0)
    i = j = 0
    while i < len(bit_ev) or j < len(byte_ev):
        moved = False
        while i < len(bit_ev):
            e, k = bit_ev[i]
            if e == "w" and not (k == lo_fby or k - 1 in consumed["fby"]):
                break
            if e == "r" and k not in written["fbi"]:
                break
            if e == "u" and k not in updated:
                break
            if e == "w":
                written["fby"].add(k)
            elif e == "r":
                consumed["fbi"].add(k)
            i += 1
            moved = True
        while j < len(byte_ev):
            e, k = byte_ev[j]
            if e == "r" and k not in written["fby"]:
                break
            if e == "w" and not (k == lo_fbi or k - 1 in consumed["fbi"]):
                break
            if e == "r":
                consumed["fby"].add(k)
            elif e == "w":
                written["fbi"].add(k)
            else:
                updated.add(k)
            j += 1
            moved = True
        if not moved:
            return False
    return True


def _schedule_bit_part(part: Partition, costs="paper") -> None:
    """Reorder the rungs of the bit part inside each basic block so that the bit side
    waits less (paper §4.3: "the program should be written and compiled in such a way
    that the load of both processors is equally distributed").  The byte part and
    the transfers' order stay as they are; what moves is bit-side work:

    * a rung that reads a condition from the byte side (a compare result) goes where
      its condition is there, and the independent rungs after it run meanwhile
      (independent bit work hoisted past the wait);
    * the rungs a `= FBY` (a timer enable, a counter pulse, a jump condition the byte
      side needs) depends on go first when the byte side would otherwise wait for it.

    The order is a list schedule driven by _Timing; the dependencies (_seg_preds) keep
    every scan's result the serial one, _no_deadlock keeps every exchange deadlock-free;
    a block whose new order fails that keeps its old one, and the whole new order is
    kept only when the model says it is faster."""
    bit = part.bit
    fby_no, fbi_no = _transfer_numbers(bit)
    wait_on = _update_waits(part)
    if not fby_no and not fbi_no and not wait_on:
        return
    tm = _Timing(part.byte, costs)
    tm.advance()
    t = 0
    new: list[PartInstr] = []
    moved = 0
    for lo, hi in _blocks(part):
        segs = _segments(bit, lo, hi, fby_no, fbi_no, wait_on)
        order = list(range(len(segs))) if segs else None
        if segs and len(segs) > 2:
            order = _list_schedule(bit, segs, tm, t, fby_no, fbi_no, wait_on)
            block = [bit[n] for s in order for n in range(segs[s].lo, segs[s].hi)]
            trial = bit[:lo] + block + bit[hi:]
            if not _no_deadlock(trial, lo, hi, part.byte, *_transfer_numbers(trial),
                                _remap(wait_on, bit, trial)):
                order = list(range(len(segs)))
        if segs is None:
            new += bit[lo:hi]
            for n in range(lo, hi):
                t = tm.run_seg(bit, _Seg(n, n + 1), t, fby_no, fbi_no, wait_on, True)
            continue
        for s in order:
            t = tm.run_seg(bit, segs[s], t, fby_no, fbi_no, wait_on, True)
            new += bit[segs[s].lo:segs[s].hi]
        moved += sum(1 for k, s in enumerate(order) if s != k)
    if moved == 0:
        return
    assert sorted(map(id, new)) == sorted(map(id, bit))
    before, after = _model_clocks(part, bit, costs), _model_clocks(part, new, costs)
    if after >= before:
        return
    labels = [ins.labels for ins in bit]          # labels are positions: they stay
    for ins, names in zip(new, labels):
        ins.labels = names
    part.bit[:] = new
    part.schedule = (moved, before, after)


def _remap(wait_on: dict, old: list, new: list) -> dict:
    """wait_on (bit index -> update) for the instructions of `old` placed as in `new`."""
    where = {id(ins): n for n, ins in enumerate(new)}
    return {where[id(old[n])]: u for n, u in wait_on.items()}


def _list_schedule(bit, segs, tm: _Timing, t: int, fby_no, fbi_no, wait_on) -> list[int]:
    """The order of one block's rungs (see _schedule_bit_part).  Simulates the block
    on a copy of the timing model; at each step takes, among the rungs whose
    predecessors are placed: the ancestors of the next `= FBY` when the byte side
    would otherwise wait for it, else the first (in program order) that runs without
    waiting, else the one that finishes first."""
    preds = _seg_preds(segs)
    succs: list[set[int]] = [set() for _ in segs]
    for j, ps in enumerate(preds):
        for i in ps:
            succs[i].add(j)
    left = [len(ps) for ps in preds]
    ready = {j for j, c in enumerate(left) if c == 0}
    done: set[int] = set()
    sim = tm.clone()
    order = []
    fby_seg = {k: j for j, s in enumerate(segs) for k in s.fby}
    size = [s.hi - s.lo for s in segs]
    while ready:
        pick = None
        need = sim.reads                        # the byte side's next READ
        if need in fby_seg and fby_seg[need] not in done:
            anc, todo = set(), [fby_seg[need]]
            while todo:
                j = todo.pop()
                if j in anc or j in done:
                    continue
                anc.add(j)
                todo.extend(preds[j])
            work = sum(size[j] for j in anc)
            if sim.pc < len(sim.byte) and sim.byte[sim.pc].mnemonic == "READ" and \
                    t + work >= sim.t:
                pick = min(j for j in anc if j in ready)
        if pick is None:
            best = None
            for j in sorted(ready):
                end = sim.run_seg(bit, segs[j], t, fby_no, fbi_no, wait_on,
                                             False)
                if end <= t + size[j]:
                    pick = j
                    break
                if best is None or end < best[0]:
                    best = (end, j)
            if pick is None:
                pick = best[1]
        t = sim.run_seg(bit, segs[pick], t, fby_no, fbi_no, wait_on, True)
        order.append(pick)
        done.add(pick)
        ready.discard(pick)
        for j in succs[pick]:
            left[j] -= 1
            if left[j] == 0:
                ready.add(j)
    assert len(order) == len(segs)
    return order


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
    if part.schedule is not None:
        moved, before, after = part.schedule
        out.append(f"bit-side schedule: {moved} rungs moved inside their blocks, ahead of "
                   f"rungs that wait for the byte side (timing model, straight line: "
                   f"{before} -> {after} clocks); the listing below is in program order, "
                   f"the bit part's addresses give the executed order")
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
