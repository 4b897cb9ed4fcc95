"""The walk over a mixed program: the rows of both parts with the transfers where the RLO
crosses, jumps mirrored where the byte side needs them (module docstring of
bitbyte.compiler.partition).
"""
from __future__ import annotations

from bitbyte.compiler.common import _channel_operand, _error, _text
from bitbyte.compiler.status import _Reach, _status_ops
from bitbyte.lang.costs import byte_kind
from bitbyte.lang.definition import DEF
from bitbyte.lang.parser import COMPARES
from bitbyte.lang.parts import (BIT, BYTE, BYTE_JUMPS, PartInstr, Partition, Row,
                                STATUS_UPDATES, TO_BIT, TO_BYTE, Transfer)
from bitbyte.lang.program import COMBINES, Instr, JUMPS, OPENS, Operand, Program


# Bit instructions and the RLO
BIT_RLO_SETTERS = ("LD", "LDN", "SET", "CLR")                     # loc := {bit}
BIT_RLO_MODIFIERS = ("A", "AN", "O", "ON", "X", "XN", "NOT", "FP", "FN", ")")
BIT_RLO_KEEPERS = ("=", "S", "R") + tuple(OPENS) + ("JC", "JCN")   # read, keep


class _Builder:
    def __init__(self, program: Program, channels: int, status_sync: bool,
                 mirrored: set[int], hardware_wait: bool = True, tc_status: bool = False):
        self.program = program
        # --tc-path status (parallel and free-running mode): a timer / counter
        # instruction that needs the RLO from the bit side gets it through the status
        # buffer (`= T n` there, the byte word's from-status flag) instead of a channel,
        # when it is the only instruction on its timer / counter (one enable / pulse bit
        # each)
        self.tc_status = tc_status
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
                         ins.section, ins.at_latch, origin=self.cur)

    def synth(self, mnemonic: str, op: Operand | None, note: str) -> PartInstr:
        cause = self.program.instrs[self.cur]
        return PartInstr(mnemonic, op, cause.line, cause.col, cause.source, [], "",
                         note=note, origin=self.cur, synthesized=True)

    def row(self, kind: str, bit: PartInstr | None = None, byte: PartInstr | None = None,
            channel: int | None = None) -> int:
        self.rows.append(Row(kind, self.cur, bit, byte, channel=channel))
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
        if kind in DEF.status_reads and not kind.startswith("LD"):
            # A/AN/O/ON/X/XN ==0 ...: as a combined compare; off the byte side, the
            # (negated) condition is read there and combined on the bit side
            func, cond = kind.split()
            if BYTE in self.loc:
                self.row(BYTE, byte=self.copy(ins))
                self.loc = {BYTE}
            else:
                plain = f"LD{'N' if func.endswith('N') else ''} {cond}"
                self.row(BYTE, byte=self.synth(plain, None, f"status bits of `{what}`: "
                                               f"the RLO is on the bit side, {func[0]} "
                                               "there"))
                self.to_bit(f"`{what}`: status bit to the bit side", func[0])
            return
        if kind in COMPARES or kind in DEF.status_reads:      # LD ==0: as a compare
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
            elif self.tc_status and BYTE not in self.loc and BIT in self.loc and \
                    len(self.status_ops.updates.get(key, [])) == 1 and \
                    self.cur not in self.reach.after(self.cur):
                # one enable bit: one instruction on the timer / counter, once a scan
                # (in a loop its per-iteration inputs would collapse to the last one)
                self.through_status(ins, key)
                self.unsynced_updates.add(key)
                return
            else:
                self.need_byte(f"RLO for `{what}`")
            self.row(BYTE, byte=self.copy(ins))
            self.unsynced_updates.add(key)
        else:                                                     # L, T, arithmetic
            self.row(BYTE, byte=self.copy(ins))

    def through_status(self, ins: Instr, key: tuple[str, int]) -> None:
        """bit `= T n` / `= C n`, byte the instruction flagged "from status": the RLO
        reaches the byte side through the status buffer's enable / pulse bit (Fig. 2),
        seen there like an input (docs/exchange.md). F_B keeps what it held."""
        area, n = key
        what = _text(ins.mnemonic, ins.operand)
        op = Operand("index", area=area, index=n, text=f"{area}{n}")
        self.row(BIT, bit=self.synth("=", op, f"enable / input of `{what}` into the "
                                              "status buffer (--tc-path status)"))
        byte = self.copy(ins)
        byte.from_status = True
        # parallel mode: the serial result needs this scan's bit, so the byte side
        # waits until the bit side has written it (free-running mode never waits)
        byte.status_wait = self.status_sync
        byte.synthesized = True
        reg = "T_ENABLE" if area == "T" else "C_PULSE"
        byte.note = f"input from the status buffer's {reg} bit {n}" + (
            ", once written in this scan" if self.status_sync else "")
        self.row(BYTE, byte=byte)

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
