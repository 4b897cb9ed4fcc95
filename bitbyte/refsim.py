"""The reference interpreter: the oracle every hardware test compares against.

It reads the parsed program (bitbyte.program), never the binary encoding, and shares
no code with the encoder or the RTL, so that a bug in one of them cannot hide in the
other.  It is meant to be read next to spec §3 (what each instruction does) and the
"Timing model" of docs/isa.md (in which clock it does it):

  * scan k latches the PII (and IR/IF) in its first clock L;
  * each executed instruction takes one clock, a taken jump two;
  * END takes the last clock E, where PIO -> output register; cycles = E - L + 1;
  * scan k+1 latches in clock E + 1 (= the record's end_clock), t_us = end_clock / f.

State is plain Python ints used as bit vectors (bit i = byte*8 + bit).  Pins are a
step function looked up per instruction, never simulated clock by clock.

What this stage has no byte processor for is behind small hooks (timer_status,
counter_status, read_fbi, write_fby, byte_instruction) that a later stage overrides.
"""
from __future__ import annotations

from typing import Iterable

from .config import DEFAULT, Config
from .program import Instr, Operand, Program
from .stimulus import Stimulus, no_stimulus
from .trace import Column, ScanRecord, mhz, trace_columns

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


class RefSimError(Exception):
    """A program the bit-only interpreter cannot run (a byte instruction, a read of a
    write-only operand, a parenthesis stack overflow through jumps ...)."""


def combine(func: str | None, rlo: int, x: int) -> int:
    """RLO := RLO func x; func None loads x."""
    if func is None:
        return x
    if func == "A":
        return rlo & x
    if func == "O":
        return rlo | x
    return rlo ^ x


def _bit(vector: int, n: int) -> int:
    return (vector >> n) & 1


def _with_bit(vector: int, n: int, value: int) -> int:
    return vector | (1 << n) if value else vector & ~(1 << n)


class RefSim:
    """Runs a Program scan by scan.  run() may be called repeatedly; it continues.

    After a watchdog fault (a scan needing more than `watchdog` clocks) the outputs are
    0, watchdog_fault is True, fault_scan / fault_clock say where (fault_clock = the
    scan's latch clock + watchdog, the first clock the scan was not allowed), and
    nothing more runs.  output_events lists (clock, output register) at every change
    of the output pins: a PQ write in the clock of its instruction, Q at END.
    """

    def __init__(self, program: Program, config: Config = DEFAULT,
                 stimulus: Stimulus | None = None, watchdog: int = 100000,
                 columns: list[Column] | None = None):
        self.program = program
        self.config = config
        self.stimulus = stimulus if stimulus is not None else no_stimulus(config)
        self.f = mhz(config.clock_mhz)
        self.watchdog = watchdog
        self.columns = columns if columns is not None else trace_columns(program)
        # process images, markers, output pins
        self.pii = self.ir = self.if_ = 0
        self.pio = self.outputs = 0
        self.markers = 0
        self.latched_pins = 0        # pins at the previous latch (0 before the first)
        self.last_latch = -1         # clock of the previous latch, -1 = none yet
        # bit processor
        self.rlo = 0
        self.stack: list[tuple[int, str, int]] = []
        # words (byte processor's, all 0 in this stage but for IW from the stimulus)
        self.mw: dict[int, int] = {}
        self.qw: dict[int, int] = {}
        self.fby: dict[int, int] = {}
        # progress
        self.scan = 0                # number of the scan that runs next / is running
        self.clock = 0               # latch clock of the next scan
        self.watchdog_fault = False
        self.fault_scan: int | None = None
        self.fault_clock: int | None = None
        self.output_events: list[tuple[int, int]] = []

    # --- hooks for the byte processor (next stage) ----------------------------------

    def timer_status(self, n: int) -> int:
        """Status bit `T n` (status buffer); no byte processor yet, so 0."""
        return 0

    def counter_status(self, n: int) -> int:
        """Status bit `C n`; no byte processor yet, so 0."""
        return 0

    def read_fbi(self, k: int) -> int:
        """A bit-side read of exchange channel FBI k; nothing writes it yet, so 0."""
        return 0

    def write_fby(self, k: int, value: int) -> None:
        """`= FBY k`: kept for inspection; nothing reads it yet."""
        self.fby[k] = value

    def byte_instruction(self, ins: Instr, clock: int) -> int:
        """Execute a byte instruction and return its clocks; none exist yet."""
        raise RefSimError(f"{self.program.path}:{ins.line}:{ins.col}: byte instruction "
                          f"'{ins.mnemonic}' needs the byte processor")

    # --- running ---------------------------------------------------------------------

    def run(self, scans: int | None = None, until_us=None) -> list[ScanRecord]:
        """Run `scans` more scans, or until the first scan that ends at or after
        `until_us` (µs since reset, exact decimal), whichever comes first; stops early
        at a watchdog fault.  Returns the records of the scans completed by this call."""
        if scans is None and until_us is None:
            raise ValueError("run() needs scans or until_us")
        limit = None if until_us is None else mhz(until_us) * self.f  # in clocks
        records: list[ScanRecord] = []
        while not self.watchdog_fault and (scans is None or len(records) < scans):
            rec = self.run_scan()
            if rec is None:
                break
            records.append(rec)
            if limit is not None and rec.end_clock >= limit:
                break
        return records

    def run_scan(self) -> ScanRecord | None:
        """One scan: latch, instructions up to END, PIO -> outputs.  None on a fault."""
        if self.watchdog_fault:
            return None
        start = self.clock
        self._latch(start)
        self.rlo, self.stack = 0, []
        pc, clock = 0, start + 1
        while True:
            if clock - start + 1 > self.watchdog:      # even END here would be too late
                self._fault(start)
                return None
            ins = self._instr(pc)
            if ins.mnemonic == "END":
                break
            pc, clocks = self._step(ins, pc, clock)
            clock += clocks
        self._set_outputs(self.pio, clock)             # END, in clock `clock`
        rec = ScanRecord(self.scan, clock + 1, clock - start + 1, self._values(clock))
        self.scan += 1
        self.clock = clock + 1
        return rec

    def _instr(self, pc: int) -> Instr:
        """The instruction at pc; running off the end acts as END (parser adds one)."""
        if pc < len(self.program.instrs):
            return self.program.instrs[pc]
        return Instr("END", None, 0, 0)

    def _fault(self, start: int) -> None:
        self.watchdog_fault = True
        self.fault_scan = self.scan
        self.fault_clock = start + self.watchdog
        self._set_outputs(0, self.fault_clock)

    # --- one instruction ------------------------------------------------------------

    def _step(self, ins: Instr, pc: int, clock: int) -> tuple[int, int]:
        """Execute ins (at program index pc, in clock `clock`); (next pc, clocks)."""
        m, op = ins.mnemonic, ins.operand
        if m in COMBINES:
            func, neg = COMBINES[m]
            self.rlo = combine(func, self.rlo, self._read(op, clock) ^ neg)
        elif m in OPENS:
            if len(self.stack) >= self.config.nest_depth:
                raise RefSimError(f"{self.program.path}:{ins.line}:{ins.col}: "
                                  f"parenthesis stack overflow")
            func, neg = OPENS[m]
            self.stack.append((self.rlo, func, neg))
        elif m == ")":
            if not self.stack:
                raise RefSimError(f"{self.program.path}:{ins.line}:{ins.col}: "
                                  f"')' with nothing open")
            saved, func, neg = self.stack.pop()
            self.rlo = combine(func, saved, self.rlo ^ neg)
        elif m in JUMPS:
            return self._jump(m, op, pc)
        elif not self._simple(m, op, clock):
            return pc + 1, self.byte_instruction(ins, clock)
        return pc + 1, 1

    def _simple(self, m: str, op: Operand | None, clock: int) -> bool:
        """The one-clock bit instructions without parentheses; False if m is not one."""
        if m == "NOT":
            self.rlo ^= 1
        elif m == "SET":
            self.rlo = 1
        elif m == "CLR":
            self.rlo = 0
        elif m in ("S", "R") and op.area in ("T", "C"):
            return False                       # S C n, R C n, R T n: byte procedures
        elif m == "=":
            self._write(op, self.rlo, clock)
        elif m == "S":
            if self.rlo:
                self._write(op, 1, clock)
        elif m == "R":
            if self.rlo:
                self._write(op, 0, clock)
        elif m == "FP":
            old, mem = self.rlo, self._read(op, clock)
            self.rlo = old & (mem ^ 1)
            self._write(op, old, clock)
        elif m == "FN":
            old, mem = self.rlo, self._read(op, clock)
            self.rlo = (old ^ 1) & mem
            self._write(op, old, clock)
        elif m == "NOP":
            pass
        elif m == "REFRESH":
            self._latch(clock)
        else:
            return False
        return True

    def _jump(self, m: str, op: Operand, pc: int) -> tuple[int, int]:
        """JU / JC / JCN: a taken jump costs 2 clocks (one squashed fetch)."""
        taken = m == "JU" or (m == "JC" and self.rlo == 1) or (m == "JCN" and self.rlo == 0)
        if not taken:
            return pc + 1, 1
        return self.program.labels[op.label.upper()], 2

    # --- operands -----------------------------------------------------------------------

    def _read(self, op: Operand, clock: int) -> int:
        """A bit read by an instruction executing in `clock`."""
        area = op.area
        if area == "I":
            return _bit(self.pii, op.bit_number)
        if area == "PI":
            return _bit(self.pins(clock), op.bit_number)
        if area == "IR":
            return _bit(self.ir, op.bit_number)
        if area == "IF":
            return _bit(self.if_, op.bit_number)
        if area in ("Q", "PQ"):                 # a PQ read sees the PIO
            return _bit(self.pio, op.bit_number)
        if area == "M":
            return _bit(self.markers, op.bit_number)
        if area == "T":
            return self.timer_status(op.index) & 1
        if area == "C":
            return self.counter_status(op.index) & 1
        if area == "FBI":
            return self.read_fbi(op.index) & 1
        raise RefSimError(f"cannot read {op.address()} as a bit")

    def _write(self, op: Operand, value: int, clock: int) -> None:
        """A bit write by an instruction executing in `clock`."""
        area = op.area
        if area in ("Q", "PQ"):
            self.pio = _with_bit(self.pio, op.bit_number, value)
            if area == "PQ":                     # direct: the pin changes at once too
                self._set_outputs(_with_bit(self.outputs, op.bit_number, value), clock)
        elif area == "M":
            self.markers = _with_bit(self.markers, op.bit_number, value)
        elif area == "FBY":
            self.write_fby(op.index, value)
        else:
            raise RefSimError(f"cannot write {op.address()}")

    def _set_outputs(self, value: int, clock: int) -> None:
        if value != self.outputs:
            self.outputs = value
            self.output_events.append((clock, value))

    # --- inputs ----------------------------------------------------------------------

    def pins(self, clock: int) -> int:
        """The input pins in `clock` (during the current scan for scan stimuli)."""
        kind = self.stimulus.kind
        if kind == "scan":
            return self.stimulus.pins_for_scan(self.scan)
        if kind == "t_us":
            return self.stimulus.pins_at_clock(clock, self.f)
        return 0

    def input_words(self, clock: int) -> dict[int, int]:
        """IW values in `clock` (no image: seen at once)."""
        kind = self.stimulus.kind
        if kind == "scan":
            return self.stimulus.words_for_scan(self.scan)
        if kind == "t_us":
            return self.stimulus.words_at_clock(clock, self.f)
        return {}

    def _latch(self, clock: int) -> None:
        """PII := pins; IR/IF := rises/falls since the previous latch (scan start or
        REFRESH).  Scan-stimulus pins change only at a scan's latch, so comparing with
        the previous latched value is exact there; time stimuli may change several
        times between latches, so their steps are walked."""
        pins = self.pins(clock)
        if self.stimulus.kind == "t_us":
            self.ir, self.if_ = self.stimulus.edges_between(self.last_latch, clock, self.f)
        else:
            self.ir, self.if_ = pins & ~self.latched_pins, self.latched_pins & ~pins
        self.pii = self.latched_pins = pins
        self.last_latch = clock

    # --- trace values ---------------------------------------------------------------------

    def peek(self, op: Operand, clock: int) -> int:
        """An operand's value as the trace shows it, looking at clock `clock`."""
        if op.kind == "bit" or op.area in ("T", "C", "FBI"):
            return self._read(op, clock)
        if op.area == "FBY":
            return self.fby.get(op.index, 0)
        if op.area == "IW":
            return self.input_words(clock).get(op.index, 0)
        if op.area == "QW":
            return self.qw.get(op.index, 0)
        if op.area == "MW":
            return self.mw.get(op.index, 0)
        raise RefSimError(f"cannot trace {op.address()}")

    def _values(self, end_clock: int) -> dict[str, int]:
        """Every column after END; Q columns show the output register (= PIO now)."""
        values = {}
        for col in self.columns:
            op = col.operand
            if op.kind == "bit" and op.area in ("Q", "PQ"):
                values[col.header] = _bit(self.outputs, op.bit_number)
            else:
                values[col.header] = self.peek(op, end_clock)
        return values


def refsim_trace(program: Program, config: Config = DEFAULT,
                 stimulus: Stimulus | None = None, watch: Iterable[str] = (),
                 scans: int | None = None, until_us=None, watchdog: int = 100000,
                 ) -> tuple[list[Column], list[ScanRecord], bool]:
    """(columns, records, watchdog fault?) of one run: the reference TRACE.csv."""
    columns = trace_columns(program, list(watch), program.symbols, config)
    sim = RefSim(program, config, stimulus, watchdog, columns)
    records = sim.run(scans, until_us)
    return columns, records, sim.watchdog_fault
