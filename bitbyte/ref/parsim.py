"""A functional co-simulator of parallel mode: the two parts of a Partition run as two
sequential processes whose steps are interleaved in an order chosen at random (or by a
policy), talking only through the exchange channels, and meeting at END / END_B.  It
is the semantic check of the partitioning compiler without hardware: for programs
whose result does not depend on time, every scan must leave the same outputs, markers,
words, timers and counters as the serial reference (bitbyte.ref.refsim.RefSim), under
every interleaving, and must never deadlock.

It reuses RefSim for everything an instruction does (it subclasses it: the bit side's
instructions go through RefSim._step, the byte side's through RefSim.byte_instruction,
with the RLO swapped in and out: F_b for the bit side, F_B for the byte side); it adds
the channels, the byte program's JU_B / JC_B / JCN_B / END_B and the scheduler.

Not a timing model: `cycles` in its records count interleaved steps, and the clock an
instruction sees is its own side's count of clocks (bit: 1 per instruction; byte:
the cost table).  Time-dependent
inputs (t_us stimuli, PI) and timers therefore differ from serial mode, as they do on
the hardware; `ms_per_scan` makes timers see now = scan * ms_per_scan in both this
and ScanTimeRefSim, so that programs with timers can be compared too.

Exchange models: "handshake" (channel k of each direction holds one condition; a
write to a full one and a read of an empty one wait) and "queue" (one FIFO of
`queue_depth` places per direction; the index is ignored).
"""
from __future__ import annotations

import random
from collections import deque

from bitbyte.lang.config import DEFAULT, Config
from bitbyte.lang.parts import BYTE_JUMPS, STATUS_UPDATES, Partition
from bitbyte.lang.program import Instr
from bitbyte.lang.costs import byte_kind
from bitbyte.lang.program import COMBINES
from bitbyte.ref.refsim import RefSim, RefSimError
from bitbyte.lang.stimulus import Stimulus
from bitbyte.lang.trace import Column, ScanRecord

TO_BYTE, TO_BIT = "to_byte", "to_bit"
POLICIES = ("random", "bursty", "bit-first", "byte-first")


class Deadlock(RefSimError):
    """Neither side can make a step and the scan is not over."""


class ChannelError(RefSimError):
    """A channel still holds conditions at the end of a scan (the parts disagree)."""


class ScanTimeRefSim(RefSim):
    """RefSim whose timers see now = scan * ms_per_scan (for comparing with ParSim)."""

    def __init__(self, *args, ms_per_scan: int = 1, **kwargs):
        super().__init__(*args, **kwargs)
        self.ms_per_scan = ms_per_scan

    def now_ms(self, clock: int) -> int:
        return self.scan * self.ms_per_scan


class ParSim(RefSim):
    """Runs a Partition scan by scan (run(), run_scan() as RefSim).

    rng: random.Random (or a seed) driving the interleaving; policy: one of POLICIES
    or "mixed" (a policy drawn per scan).  max_steps: interleaved steps a scan may take
    before it counts as a watchdog fault (outputs 0, nothing more runs), like RefSim's
    watchdog.  ms_per_scan: see the module docstring (None: timers use the side's
    clock).  Counters of what happened: stalls[TO_BYTE/TO_BIT] (steps a side was
    blocked on a channel while the other moved), max_fill (the fullest a channel or
    queue ever got)."""

    def __init__(self, part: Partition, config: Config = DEFAULT,
                 stimulus: Stimulus | None = None, columns: list[Column] | None = None,
                 *, exchange: str = "handshake", queue_depth: int = 4,
                 rng: random.Random | int | None = None, policy: str = "mixed",
                 max_steps: int = 100_000, ms_per_scan: int | None = None, costs=None):
        super().__init__(part.program, config, stimulus, max_steps, columns, costs)
        if exchange not in ("handshake", "queue"):
            raise ValueError(f"exchange must be handshake or queue, not {exchange!r}")
        if policy not in POLICIES + ("mixed",):
            raise ValueError(f"unknown policy {policy!r}")
        self.part = part
        self.bit_program = part.bit_program()
        self.byte_program = part.byte_program()
        self.exchange = exchange
        self.capacity = 1 if exchange == "handshake" else queue_depth
        self.rng = rng if isinstance(rng, random.Random) else random.Random(rng)
        self.policy = policy
        self.max_steps = max_steps
        self.ms_per_scan = ms_per_scan
        self.queues: dict[tuple[str, int], deque] = {}
        self.stalls = {TO_BYTE: 0, TO_BIT: 0, "status": 0}
        self.max_fill = 0
        # --tc-path status (docs/exchange.md): the status buffer's enable / pulse bits
        # (kept over scans, as tc_status.v keeps them) and the ones the bit side wrote
        # in this scan (its `written` bits, cleared at the scan's start)
        self.tc_enable: dict[tuple[str, int], int] = {}
        self.tc_written: set[tuple[str, int]] = set()

    # --- channels --------------------------------------------------------------------

    def _queue(self, direction: str, k: int) -> deque:
        key = (direction, k if self.exchange == "handshake" else 0)
        return self.queues.setdefault(key, deque())

    def _push(self, direction: str, k: int, value: int) -> None:
        q = self._queue(direction, k)
        assert len(q) < self.capacity, "write to a full channel (scheduler bug)"
        q.append(value & 1)
        self.max_fill = max(self.max_fill, len(q))

    def _pop(self, direction: str, k: int) -> int:
        q = self._queue(direction, k)
        assert q, "read of an empty channel (scheduler bug)"
        return q.popleft()

    def read_fbi(self, k: int) -> int:
        return self._pop(TO_BIT, k)

    def write_fby(self, k: int, value: int) -> None:
        self._push(TO_BYTE, k, value)

    def _write(self, op, value: int, clock: int) -> None:
        if op.area in ("T", "C"):           # the bit part's `= T n` / `= C n`
            self.tc_enable[(op.area, op.index)] = value & 1
            self.tc_written.add((op.area, op.index))
        else:
            super()._write(op, value, clock)

    def byte_instruction(self, ins: Instr, clock: int) -> int:
        if not getattr(ins, "from_status", False):
            return super().byte_instruction(ins, clock)
        # its input is the status buffer's bit, not F_B, which it leaves as it was
        f_b = self.rlo
        self.rlo = self.tc_enable.get((ins.operand.area, ins.operand.index), 0)
        cost = super().byte_instruction(ins, clock)
        self.rlo = f_b
        return cost

    def exchange_instruction(self, ins: Instr, clock: int) -> None:
        k = ins.operand.index
        if ins.mnemonic == "READ":
            self.rlo = self._pop(TO_BYTE, k)
        else:
            self._push(TO_BIT, k, self.rlo)

    def _bit_blocked(self, ins: Instr) -> str | None:
        """The channel direction the bit instruction waits on, or None."""
        op = ins.operand
        if op is None:
            return None
        if getattr(ins, "wait_update", False) and (op.area, op.index) not in self.updated:
            return "status"                  # instruction bit 16: until the update ran
        if op.area == "FBI" and ins.mnemonic in COMBINES:
            return TO_BIT if not self._queue(TO_BIT, op.index) else None
        if op.area == "FBY":
            full = len(self._queue(TO_BYTE, op.index)) >= self.capacity
            return TO_BYTE if full else None
        return None

    def _byte_blocked(self, ins: Instr) -> str | None:
        if getattr(ins, "status_wait", False) and \
                (ins.operand.area, ins.operand.index) not in self.tc_written:
            return "status"                  # TC_WAIT: until this scan's `= T n` ran
        if ins.mnemonic == "READ":
            return TO_BYTE if not self._queue(TO_BYTE, ins.operand.index) else None
        if ins.mnemonic == "WRITE":
            full = len(self._queue(TO_BIT, ins.operand.index)) >= self.capacity
            return TO_BIT if full else None
        return None

    def now_ms(self, clock: int) -> int:
        if self.ms_per_scan is not None:
            return self.scan * self.ms_per_scan
        return super().now_ms(clock)

    # --- scheduler ---------------------------------------------------------------------

    def _chooser(self):
        policy = self.policy
        if policy == "mixed":
            policy = self.rng.choice(POLICIES)
        rng = self.rng
        state = {"side": "bit", "left": 0}

        def choose(ready: list[str]) -> str:
            if len(ready) == 1:
                return ready[0]
            if policy == "bit-first":
                return "bit"
            if policy == "byte-first":
                return "byte"
            if policy == "random":
                return rng.choice(ready)
            if state["left"] <= 0:                  # bursty: runs of 1..30 steps
                state["side"] = rng.choice(ready)
                state["left"] = rng.randrange(1, 31)
            state["left"] -= 1
            return state["side"]
        return choose

    # --- one scan ------------------------------------------------------------------------

    def run_scan(self) -> ScanRecord | None:
        if self.watchdog_fault:
            return None
        start = self._start_scan()
        bit_instrs, byte_instrs = self.bit_program.instrs, self.byte_program.instrs
        byte_labels = self.byte_program.labels
        bit_pc = byte_pc = 0
        bit_rlo, bit_stack, f_b = 0, [], 0
        bit_clock = byte_clock = start
        bit_done = byte_done = False
        self.updated: set[tuple[str, int]] = set()     # T/C written by the byte side
        self.tc_written = set()                        # enables written by the bit side
        choose = self._chooser()
        steps = 0
        self.program = self.bit_program          # RefSim._jump reads the labels here
        while not (bit_done and byte_done):
            bit_ins = None if bit_done else _at(bit_instrs, bit_pc, "END")
            byte_ins = None if byte_done else _at(byte_instrs, byte_pc, "END_B")
            bit_wait = bit_ins is not None and self._bit_blocked(bit_ins)
            byte_wait = byte_ins is not None and self._byte_blocked(byte_ins)
            ready = [side for side, ins, wait in (("bit", bit_ins, bit_wait),
                                                  ("byte", byte_ins, byte_wait))
                     if ins is not None and not wait]
            if not ready:
                raise Deadlock(self._deadlock_text(bit_ins, byte_ins))
            steps += 1
            if steps > self.max_steps:
                self._fault(start)
                return None
            if bit_wait:
                self.stalls[bit_wait] += 1
            if byte_wait:
                self.stalls[byte_wait] += 1
            if choose(ready) == "bit":
                if bit_ins.mnemonic == "END":
                    bit_done = True
                    continue
                self.rlo, self.stack = bit_rlo, bit_stack
                self.current = bit_ins
                if byte_kind(bit_ins) is not None:
                    raise RefSimError(f"byte instruction in the bit part: {bit_ins}")
                bit_pc, clocks = self._step(bit_ins, bit_pc, bit_clock)
                bit_rlo, bit_stack = self.rlo, self.stack
                bit_clock += clocks
            else:
                m = byte_ins.mnemonic
                if m == "END_B":
                    byte_done = True
                    continue
                if m in _BYTE_JUMP_SET:
                    taken = m == "JU_B" or (m == "JC_B") == (f_b == 1)
                    byte_pc = byte_labels[byte_ins.operand.label] if taken else byte_pc + 1
                    byte_clock += self.costs["READ"]
                    continue
                self.rlo = f_b
                self.current = byte_ins
                byte_clock += self.byte_instruction(byte_ins, byte_clock)
                if byte_kind(byte_ins) in STATUS_UPDATES:
                    self.updated.add((byte_ins.operand.area, byte_ins.operand.index))
                f_b = self.rlo
                byte_pc += 1
        leftover = {key: list(q) for key, q in self.queues.items() if q}
        if leftover:
            raise ChannelError(f"scan {self.scan}: channels not empty at END: {leftover}")
        self.rlo = bit_rlo
        return self._end_scan(max(bit_clock, byte_clock), steps)

    def _deadlock_text(self, bit_ins, byte_ins) -> str:
        def show(ins):
            if ins is None:
                return "done"
            op = ins.operand
            return f"{ins.mnemonic} {op.address() if op else ''} (line {ins.line})"
        return (f"scan {self.scan}: deadlock: bit side at {show(bit_ins)}, byte side at "
                f"{show(byte_ins)}; channels {dict(self.queues)}")

    def _fault(self, start: int) -> None:
        self.watchdog_fault = True
        self.fault_scan = self.scan
        self.fault_clock = start + self.max_steps
        self._set_outputs(0, self.fault_clock)


_BYTE_JUMP_SET = frozenset(BYTE_JUMPS.values())


def _at(instrs: list[Instr], pc: int, end: str) -> Instr:
    """The instruction at pc; running off the end acts as END / END_B."""
    return instrs[pc] if pc < len(instrs) else Instr(end, None, 0, 0)


def state_snapshot(sim: RefSim) -> tuple:
    """Everything a scan leaves that serial and parallel mode must agree on."""
    return (
        sim.outputs, sim.pio, sim.qr, sim.qf, sim.markers,
        tuple(sorted((k, v) for k, v in sim.mw.items() if v)),
        tuple(sorted((k, v) for k, v in sim.qw.items() if v)),
        tuple((t.status, t.elapsed, t.start, t.edge) for t in sim.timers),
        tuple((c.value, c.cu_edge, c.cd_edge, c.s_edge) for c in sim.counters),
        sim.arith_error,
    )


def serial_states(program, stimulus: Stimulus, scans: int, timers: bool,
                  watchdog: int = 100_000) -> list[tuple]:
    """The serial reference of a parallel run, scan by scan: (trace values,
    state_snapshot) of each completed scan; timers=True runs ScanTimeRefSim (timers on
    scan time, as ParSim sees them)."""
    ref = ScanTimeRefSim(program, Config(), stimulus, watchdog, ms_per_scan=1) if timers \
        else RefSim(program, Config(), stimulus, watchdog)
    out = []
    for _ in range(scans):
        rec = ref.run_scan()
        if rec is None:
            break
        out.append((rec.values, state_snapshot(ref)))
    return out
