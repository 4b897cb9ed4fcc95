"""The reference interpreter: the oracle every hardware test compares against.

It reads the parsed program (bitbyte.lang.program), never the binary encoding, and shares
no code with the encoder, the RTL or the byte firmware, so that a bug in one of them
cannot hide in the other.  It is meant to be read next to spec §3 (what each
instruction does) and the "Timing model" / "Serial mode timing" of docs/isa.md (in
which clock it does it).  It runs the SERIAL mode (spec §2): one instruction stream,
one shared RLO, the bit processor waiting for each byte instruction.

  * scan k latches the PII (and IR/IF) in its first clock L, in which its first
    instruction already executes (seeing the values being latched);
  * each executed bit instruction takes one clock, a taken jump DEF.jump_taken_clocks
    (bitbyte/lang/definition.toml [timing]);
  * a byte instruction takes exactly its cost-table cost (default "paper": 10 per word
    instruction, 1 per READ/WRITE), from its first clock c to c + cost - 1, and the
    next instruction executes in clock c + cost;
  * END takes the last clock E, where PIO -> output register; cycles = E - L + 1
    = sum of instruction clocks + 1 (END);
  * scan k+1 latches in clock E + 1 (= the record's end_clock), t_us = end_clock / f.

Byte instructions act in their first clock c: `L IW n` reads the input word in clock
c (IW has no image); timers take now = floor(t / 1 ms) with t = c / f µs.  The status
a timer or counter instruction writes is in the status buffer at once, so the next
instruction's `T n` / `C n` sees it.

State is plain Python ints used as bit vectors (bit i = byte*8 + bit), words in dicts.
Pins are a step function looked up per instruction, never simulated clock by clock.

The exchange channels (READ, WRITE, FBI, FBY) exist only in parallel mode; here they
raise RefSimError.  They sit behind the hooks read_fbi / write_fby / exchange_instruction
that a parallel-mode interpreter overrides.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Iterable, Mapping

from bitbyte.lang.config import DEFAULT, Config
from bitbyte.lang.costs import byte_kind, resolve_costs
from bitbyte.lang.definition import DEF
from bitbyte.lang.program import COMBINES, JUMPS, OPENS, TIMER_STARTS, Instr, Operand, Program
from bitbyte.lang.stimulus import Stimulus, no_stimulus
from bitbyte.lang.trace import Column, ScanRecord, mhz, trace_columns

# --- byte instructions ------------------------------------------------------------------

ARITHMETIC = DEF.arithmetic                 # +I ... MOD, +D ... MODD
COMPARES = DEF.all_compares                 # ==I ... <=I, ==D ... <=D
TIMERS = TIMER_STARTS
COUNTER_MAX = DEF.firmware["counter_max"]

class RefSimError(Exception):
    """A program the serial-mode interpreter cannot run (an exchange channel, a read
    of a write-only operand, a parenthesis stack overflow through jumps ...)."""


def to_int16(v: int) -> int:
    """INT(v): the low 16 bits of v, signed."""
    v &= 0xFFFF
    return v - 0x10000 if v & 0x8000 else v


def to_int32(v: int) -> int:
    """v wrapped to 32 bits, signed (an accumulator)."""
    v &= 0xFFFFFFFF
    return v - 0x100000000 if v & 0x80000000 else v


def _div_trunc(a: int, b: int) -> int:
    """a / b truncated toward zero (b != 0)."""
    q = abs(a) // abs(b)
    return q if (a < 0) == (b < 0) else -q


def arithmetic(m: str, a: int, b: int) -> tuple[int, bool]:
    """(result of a op b, division by zero?).  INT forms (+I ... MOD): a = INT(ACCU2),
    b = INT(ACCU1), the result wrapped to 16 bits; DINT forms (+D ... MODD): the
    accumulators, wrapped to 32 bits as S7's are (accu_operands gives both)."""
    wrap = to_int32 if m in DEF.dint_mnemonics else to_int16
    op = m[:-1] if m[0] in "+-*/" else "MOD"            # "+I" / "+D" -> "+"
    if op == "+":
        r = a + b
    elif op == "-":
        r = a - b
    elif op == "*":
        r = a * b
    elif b == 0:                          # /, MOD by zero: 0 and the sticky flag
        return 0, True
    elif op == "/":
        r = _div_trunc(a, b)
    else:                                 # MOD, MODD: sign of the dividend
        r = a - b * _div_trunc(a, b)
    return wrap(r), False


def accu_operands(c: str, accu2: int, accu1: int) -> tuple[int, int]:
    """What a compare or an arithmetic instruction `c` reads of the accumulators: all
    32 bits for the DINT ones (+D, ==D, A ==D, MODD ...), INT(.) otherwise."""
    if c in DEF.dint_mnemonics:
        return accu2, accu1
    return to_int16(accu2), to_int16(accu1)


def word_logic(m: str, accu2: int, accu1: int) -> int:
    """AW OW XOW (on INT(.), sign-extended) and AD OD XOD (32 bits): ACCU1 op ACCU2."""
    a, b = accu1 & 0xFFFFFFFF, accu2 & 0xFFFFFFFF
    r = {"A": a & b, "O": a | b, "X": a ^ b}[m[0]]
    return to_int32(r) if m in DEF.dint_mnemonics else to_int16(r)


def shift(m: str, accu1: int, count: int) -> int:
    """SLW SRW SSI on the low 16 bits (sign-extended result), SLD SRD SSD RLD RRD on
    32: S7's (awlsim's) results; a count of 0 leaves ACCU1, a count past the width
    acts as the width."""
    if count == 0:
        return accu1
    if m in ("SLW", "SRW", "SSI"):
        c, w = min(count, 16), accu1 & 0xFFFF
        if m == "SLW":
            return to_int16(w << c)
        return to_int16(w >> c if m == "SRW" else to_int16(w) >> c)
    c, d = min(count, 32), accu1 & 0xFFFFFFFF
    if m == "SLD":
        return to_int32(d << c)
    if m == "SRD":
        return to_int32(d >> c)
    if m == "SSD":
        return to_int32(to_int32(d) >> c)
    if m == "RLD":
        return to_int32(d << c | d >> (32 - c))
    return to_int32(d >> c | d << (32 - c))                # RRD


# S7's status bits CC 1 / CC 0 (docs/isa.md, "Status bits"), as (A1, A0): awlsim's
# rules, written here independently of the firmware.
def cc_of(v: int) -> tuple[int, int]:
    """CC of a value: 0 -> 00, negative -> 01, positive -> 10."""
    return (0, 0) if v == 0 else (0, 1) if v < 0 else (1, 0)


def arith_cc(m: str, a: int, b: int, result: int) -> tuple[int, int]:
    """After +I ... MODD with operands a (ACCU2), b (ACCU1) as the instruction reads
    them: + and - by the wrapped result, * / MOD by the exact value, 11 after / by 0."""
    op = m[:-1] if m[0] in "+-*/" else "MOD"
    if op == "*":
        return cc_of(a * b)
    if op in ("/", "MOD"):
        if b == 0:
            return (1, 1)
        q = _div_trunc(a, b)
        return cc_of(q if op == "/" else a - b * q)
    return cc_of(result)


def arith_ov(m: str, a: int, b: int) -> bool:
    """S7's OV after +I ... MODD (awlsim): the exact sum, difference, product or
    quotient outside INT (DINT for the D forms), or a division by 0; MOD only by 0."""
    op = m[:-1] if m[0] in "+-*/" else "MOD"
    if op in ("/", "MOD") and b == 0:
        return True
    if op == "MOD":
        return False
    v = a + b if op == "+" else a - b if op == "-" else a * b if op == "*" \
        else _div_trunc(a, b)
    bits = 32 if m.endswith("D") else 16
    return not -(1 << (bits - 1)) <= v < 1 << (bits - 1)


STATUS_CONDITIONS = {
    "==0": lambda a1, a0: not a1 and not a0, "<>0": lambda a1, a0: a1 or a0,
    ">0": lambda a1, a0: a1 and not a0, "<0": lambda a1, a0: a0 and not a1,
    ">=0": lambda a1, a0: not a0, "<=0": lambda a1, a0: not a1,
    "UO": lambda a1, a0: a1 and a0}


def shifted_out(m: str, before: int, count: int, after: int) -> int:
    """CC 1 after a shift by count >= 1: the bit moved out last (awlsim); after a
    rotation the bit that came round (RLD: bit 0, RRD: bit 31 of the result)."""
    if m in ("SLW", "SRW", "SSI"):
        c, w = min(count, 16), before & 0xFFFF
        return (w >> (16 - c)) & 1 if m == "SLW" else (w >> (c - 1)) & 1
    c, d = min(count, 32), before & 0xFFFFFFFF
    if m == "SLD":
        return (d >> (32 - c)) & 1
    if m in ("SRD", "SSD"):
        return (d >> (c - 1)) & 1
    return after & 1 if m == "RLD" else (after >> 31) & 1


def compare(c: str, a: int, b: int) -> int:
    """a c b as 0/1, c one of COMPARES (I or D: the caller passes the operands)."""
    return int({"==": a == b, "<>": a != b, ">": a > b, "<": a < b,
                ">=": a >= b, "<=": a <= b}[c[:-1]])     # "==I" / "==D" -> "=="


@dataclass
class TimerState:
    """One timer (spec §3 Timers).  start is None while the timer is stopped."""

    status: int = 0
    elapsed: int = 0
    start: int | None = None
    edge: int = 0


@dataclass
class CounterState:
    """One counter: value 0..32767 and one edge memory per counting instruction."""

    value: int = 0
    cu_edge: int = 0
    cd_edge: int = 0
    s_edge: int = 0


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

    costs is the byte processor's cost table (see resolve_costs): a table name
    ("paper", the default, or "c320") or a dict of kind / class -> clocks laid over
    "paper" (10 per word instruction, 1 per READ / WRITE).  Byte-side state open to inspection:
    accu1, accu2, mw, qw (signed 16-bit values by index), timers, counters (lists of
    TimerState / CounterState) and arith_error (sticky: a /I or MOD by 0 happened).
    """

    def __init__(self, program: Program, config: Config = DEFAULT,
                 stimulus: Stimulus | None = None, watchdog: int = 100000,
                 columns: list[Column] | None = None,
                 costs: Mapping[str, int] | str | None = None):
        self.program = program
        self.config = config
        self.stimulus = stimulus if stimulus is not None else no_stimulus(config)
        self.f = mhz(config.clock_mhz)
        self.watchdog = watchdog
        self.columns = columns if columns is not None else trace_columns(program)
        # process images, markers, output pins
        self.pii = self.ir = self.if_ = 0
        self.pio = self.outputs = 0
        self.qr = self.qf = 0        # outputs that rose / fell at the last PIO update
        self.markers = 0
        self.latched_pins = 0        # pins at the previous latch (0 before the first)
        self.last_latch = -1         # clock of the previous latch, -1 = none yet
        self.latch_clock = 0         # the clock of this scan's latch (LATCH_MS)
        # bit processor
        self.rlo = 0
        self.stack: list[tuple[int, str, int]] = []
        # byte processor: accumulators, words (signed 16-bit), timers, counters
        self.costs = resolve_costs(costs)
        self.accu1 = self.accu2 = 0
        self.cc = (0, 0)                # S7's CC 1, CC 0 (status-bit reads)
        self.ov = self.os = 0           # S7's OV and OS (OS sticky for the scan)
        self.mw: dict[int, int] = {}
        self.qw: dict[int, int] = {}
        self.timers = [TimerState() for _ in range(config.timers)]
        self.counters = [CounterState() for _ in range(config.counters)]
        self.arith_error = False
        self.current: Instr | None = None    # the instruction executing (for messages)
        # progress
        self.scan = 0                # number of the scan that runs next / is running
        # the startup scans (Program.startup_scans: an S7 source's OB 100) run first,
        # with scan 0's inputs, and are no scans of the trace (run_scan runs them)
        self.startup_left = program.startup_scans
        self.in_startup = False
        self.startup_cycles: list[int] = []   # the clocks of each completed startup scan
        self.clock = 0               # latch clock of the next scan
        self.watchdog_fault = False
        self.fault_scan: int | None = None
        self.fault_clock: int | None = None
        self.output_events: list[tuple[int, int]] = []

    # --- status buffer and exchange channels ------------------------------------------

    def timer_status(self, n: int) -> int:
        """Status bit `T n` (status buffer): what the last SD/SS/SP/SF/R T left."""
        return self.timers[n].status

    def counter_status(self, n: int) -> int:
        """Status bit `C n` = (count > 0)."""
        return int(self.counters[n].value > 0)

    def read_fbi(self, k: int) -> int:
        """A bit-side read of exchange channel FBI k: parallel mode only."""
        raise RefSimError(f"{self._where(self.current)}: FBI{k}: serial mode has no "
                          f"exchange channels")

    def write_fby(self, k: int, value: int) -> None:
        """`= FBY k`: parallel mode only."""
        raise RefSimError(f"{self._where(self.current)}: FBY{k}: serial mode has no "
                          f"exchange channels")

    def exchange_instruction(self, ins: Instr, clock: int) -> None:
        """READ FBY k / WRITE FBI k: parallel mode only."""
        raise RefSimError(f"{self._where(ins)}: {ins.mnemonic} {ins.operand.address()}: "
                          f"serial mode has no exchange channels")

    def _where(self, ins: Instr | None) -> str:
        if ins is None:
            return self.program.path
        return f"{self.program.path}:{ins.line}:{ins.col}"

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
        """One scan: latch, instructions up to END, PIO -> outputs.  None on a fault.
        Before scan 0 the startup scans, if any, which leave no record."""
        while self.startup_left and not self.watchdog_fault:
            self.startup_left -= 1
            self.in_startup = True
            try:
                rec = self._one_scan()
            finally:
                self.in_startup = False
            if rec is not None:
                self.startup_cycles.append(rec.cycles)
        return self._one_scan()

    def _one_scan(self) -> ScanRecord | None:
        if self.watchdog_fault:
            return None
        start = self._start_scan()
        self.rlo, self.stack = 0, []
        pc, clock = 0, start                           # the first one in the latch clock
        while True:
            if clock - start + 1 > self.watchdog:      # even END here would be too late
                self._fault(start)
                return None
            ins = self._instr(pc)
            if ins.mnemonic == "END":
                break
            pc, clocks = self._step(ins, pc, clock)
            clock += clocks
        return self._end_scan(clock, clock - start + 1)

    def _start_scan(self) -> int:
        """The scan's first clock: the inputs latched in it, ACCU1 / ACCU2 cleared."""
        start = self.clock
        self._latch(start)
        self.latch_clock = start                 # the time of S7's timers (at_latch)
        self.accu1 = self.accu2 = 0
        self.cc = (0, 0)
        self.ov = self.os = 0
        return start

    def _end_scan(self, end: int, cycles: int) -> ScanRecord:
        """END in clock `end`: PIO -> outputs, the scan's record; the next scan starts
        in the clock after."""
        self._update_outputs(end)
        rec = ScanRecord(self.scan, end + 1, cycles, self._values(end))
        self.scan += 0 if self.in_startup else 1
        self.clock = end + 1
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
        self.current = ins
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
            # also in the scan's latch clock (a scan's first instruction): a second
            # latch there finds no edge since the first, IR/IF become 0 (spec §4)
            self._latch(clock)
        elif m == "REFRESH Q":
            self._update_outputs(clock)
        else:
            return False
        return True

    def jump_taken(self, m: str) -> bool:
        """Whether JU / JC / JCN jumps at the current RLO."""
        return m == "JU" or (m == "JC" and self.rlo == 1) or (m == "JCN" and self.rlo == 0)

    def _jump(self, m: str, op: Operand, pc: int) -> tuple[int, int]:
        """JU / JC / JCN: a taken jump costs DEF.jump_taken_clocks (the instructions
        fetched behind it are squashed), one not taken DEF.bit_clocks."""
        if not self.jump_taken(m):
            return pc + 1, DEF.bit_clocks
        return self.program.labels[op.label.upper()], DEF.jump_taken_clocks

    # --- byte instructions (serial mode: the bit processor waits for each) ----------

    def byte_instruction(self, ins: Instr, clock: int) -> int:
        """Execute a byte instruction whose first clock is `clock`; return its cost."""
        kind = byte_kind(ins)
        if kind is None:
            raise RefSimError(f"{self._where(ins)}: unknown instruction '{ins.mnemonic}'")
        op = ins.operand
        if kind == "L":
            self.accu2, self.accu1 = self.accu1, to_int32(self._load(op, clock))
        elif kind == "T" and op.area == "MD":
            self._store(replace(op, area="MW"), to_int16(self.accu1 >> 16))
            self._store(replace(op, area="MW", index=op.index + 2), to_int16(self.accu1))
        elif kind == "T":
            self._store(op, to_int16(self.accu1))
        elif kind in ARITHMETIC:
            a, b = accu_operands(kind, self.accu2, self.accu1)
            result, by_zero = arithmetic(kind, a, b)
            self.accu1 = result
            self.arith_error |= by_zero
            self.cc = arith_cc(kind, a, b, result)
            self.ov = int(arith_ov(kind, a, b))
            self.os |= self.ov
        elif kind in DEF.status_reads:                  # LD ==0 ... XN UO
            func, cond = kind.split()
            bit = int(bool(self.ov if cond == "OV" else self.os if cond == "OS" else
                           STATUS_CONDITIONS[cond](*self.cc))) ^ func.endswith("N")
            self.rlo = bit if func.startswith("LD") else combine(func[0], self.rlo, bit)
        elif kind in DEF.word_logic:
            self.accu1 = word_logic(kind, self.accu2, self.accu1)
            wide = kind in DEF.dint_mnemonics
            self.cc = (int((self.accu1 & (0xFFFFFFFF if wide else 0xFFFF)) != 0), 0)
            self.ov = 0
        elif kind in DEF.shifts:
            count = self.accu2 & 0xFF if op is None else op.value
            before = self.accu1
            self.accu1 = shift(kind, self.accu1, count)
            if count:
                self.cc = (shifted_out(kind, before, count, self.accu1), 0)
                self.ov = 0
        elif kind in COMPARES:
            a2, a1 = accu_operands(kind, self.accu2, self.accu1)
            self.rlo = compare(kind, a2, a1)
            self.cc = (0, 0) if a1 == a2 else (0, 1) if a1 > a2 else (1, 0)
            self.ov = 0
        elif kind[:2] in ("A ", "O "):                  # "A ==I" ... "O <=D"
            a2, a1 = accu_operands(kind, self.accu2, self.accu1)
            self.cc = (0, 0) if a1 == a2 else (0, 1) if a1 > a2 else (1, 0)
            self.ov = 0
            bit = compare(kind[2:], a2, a1)
            self.rlo = combine(kind[0], self.rlo, bit)
        elif kind in TIMERS:
            # S7's timers (at_latch) take the scan's latch time: LATCH_MS
            self._timer(kind, self.timers[op.index],
                        self.latch_clock if ins.at_latch else clock)
        elif kind == "R T":
            if self.rlo:
                self.timers[op.index] = TimerState()    # stopped, status/elapsed/edge 0
        elif kind in ("CU", "CD", "S C", "R C"):
            self._counter(kind, self.counters[op.index])
        else:                                           # READ, WRITE
            self.exchange_instruction(ins, clock)
        return self.costs[kind]

    def now_ms(self, clock: int) -> int:
        """floor(t / 1 ms) for t = clock / f µs."""
        return clock // (self.f * 1000)

    def _timer(self, kind: str, tm: TimerState, clock: int) -> None:
        """SD / SS / SP / SF per the table of spec §3 (Timers)."""
        enable, now = self.rlo, self.now_ms(clock)
        preset = max(self.accu1, 0)
        rising = enable == 1 and tm.edge == 0
        falling = enable == 0 and tm.edge == 1

        def d() -> int:
            return now - tm.start

        if kind == "SD":                         # on-delay (TON)
            if rising:
                tm.start = now
            elif not enable:
                tm.start = None
            tm.status = int(enable == 1 and tm.start is not None and d() >= preset)
        elif kind == "SS":                       # retentive on-delay
            if rising:                           # starts, or restarts while running
                tm.start = now
            if tm.start is not None and d() >= preset:
                tm.status = 1                    # until R T n
        elif kind == "SP":                       # pulse (TP), no retrigger
            running = tm.start is not None
            if rising and not (running and d() < preset):
                tm.start = now
            elif running and not enable and d() >= preset:
                tm.start = None
            tm.status = int(tm.start is not None and d() < preset)
        else:                                    # SF: off-delay (TOF)
            if enable:
                tm.start = None
                tm.status = 1
            elif falling:
                tm.start = now
            if tm.start is not None and d() >= preset:
                tm.status = 0
        tm.elapsed = 0 if tm.start is None else min(d(), preset)
        tm.edge = enable

    def _counter(self, kind: str, ct: CounterState) -> None:
        """CU / CD / S C n count or load on a 0->1 of the RLO against their own edge
        memory; R C n clears while the RLO is 1 and leaves the edge memories alone."""
        rlo = self.rlo
        if kind == "CU":
            if rlo and not ct.cu_edge:
                ct.value = min(ct.value + 1, COUNTER_MAX)
            ct.cu_edge = rlo
        elif kind == "CD":
            if rlo and not ct.cd_edge:
                ct.value = max(ct.value - 1, 0)
            ct.cd_edge = rlo
        elif kind == "S C":
            if rlo and not ct.s_edge:
                ct.value = min(max(to_int16(self.accu1), 0), COUNTER_MAX)
            ct.s_edge = rlo
        elif rlo:                                # R C
            ct.value = 0

    def _load(self, op: Operand, clock: int) -> int:
        """The value `L op` loads (32-bit): constants as written (16#.. patterns and
        INTs sign-extended, T#.. in ms), words sign-extended, T n elapsed, C n count."""
        if op.kind == "const":
            return to_int16(op.value) if op.area == "INT" else op.value
        area = op.area
        if area == "IW":
            return to_int16(self.input_words(clock).get(op.index, 0))
        if area == "QW":
            return self.qw.get(op.index, 0)
        if area == "MW":
            return self.mw.get(op.index, 0)
        if area == "MD":                                # MW n high, MW n+2 low
            hi, lo = self.mw.get(op.index, 0), self.mw.get(op.index + 2, 0)
            return to_int32((hi & 0xFFFF) << 16 | (lo & 0xFFFF))
        if area == "T":
            return self.timers[op.index].elapsed
        if area == "C":
            return self.counters[op.index].value
        raise RefSimError(f"cannot load {op.address()}")

    def _store(self, op: Operand, value: int) -> None:
        """`T op`: a signed 16-bit value into MW n or QW n."""
        if op.area == "MW":
            self.mw[op.index] = value
        elif op.area == "QW":
            self.qw[op.index] = value
        else:
            raise RefSimError(f"cannot transfer to {op.address()}")

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
        if area == "QR":
            return _bit(self.qr, op.bit_number)
        if area == "QF":
            return _bit(self.qf, op.bit_number)
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

    def _update_outputs(self, clock: int) -> None:
        """A PIO update (END, REFRESH Q): the pins take the PIO; QR/QF flag the pins
        that change with it (a PQ write changed its pin already: no flag)."""
        self.qr, self.qf = self.pio & ~self.outputs, self.outputs & ~self.pio
        self._set_outputs(self.pio, clock)

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
        """An operand's value as the trace shows it, looking at clock `clock`: bits
        0/1 (`T n` / `C n` their status bit), words signed.  A watched exchange
        channel shows 0 (serial mode has none)."""
        if op.area in ("FBI", "FBY"):
            return 0
        if op.kind == "bit" or op.area in ("T", "C"):
            return self._read(op, clock)
        if op.area == "IW":
            return to_int16(self.input_words(clock).get(op.index, 0))
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
                 costs: Mapping[str, int] | str | None = None,
                 ) -> tuple[list[Column], list[ScanRecord], bool]:
    """(columns, records, watchdog fault?) of one run: the reference TRACE.csv of a
    serial-mode run with the cost table `costs` (default: the paper's)."""
    columns = trace_columns(program, list(watch), program.symbols, config)
    sim = RefSim(program, config, stimulus, watchdog, columns, costs)
    records = sim.run(scans, until_us)
    return columns, records, sim.watchdog_fault
