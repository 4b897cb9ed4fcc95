"""A model of the exchange in free-running mode, checked against a run's crossings
(`bitbyte run --exchange-log`, docs/exchange.md "Free-running queues" and "The marker
area in block RAM"), for make soak and tests/test_exchange_model.py.

The log has one line per crossing (sim/harness.cpp): the bit side's retirements with an
FBI / FBY operand (clock, the bit side's scan, the instruction word, the operand bit it
read, the RLO after it) and the byte side's channel and cell accesses and SCAN_DONE
(clock, the byte side's scan, the bus address, bit 0 of the data, 1 for a write).

* **Free-running queues** (`queue-free`): per direction, slot i holds the writer's i-th
  condition of its scan and gives the reader its i-th read of its scan (positions mod
  the queue's depth, counted from each side's own scan start); a slot is fresh from its
  write to its read. A read returns the slot's value (fresh or not: a stale one is an
  underflow), a write into a fresh slot overwrites it (an overflow) unless the reader
  takes that slot in the same clock. Checked: every read's value, and the run's loss
  counts against the model's. Positions come from the scan numbers of the log, not
  from the RTL's pointers, and the clocks order the two sides.
* **Marker area** (`marker`, without the write buffer): the reader reads each cell of
  its snapshot, taken at its own scan start from the writer's cells. Checked as the
  documented bound, not clock for clock: every read of a cell in a reader's scan gives
  the same value, and that value is one the writer's cell held at some clock from a few
  clocks before that scan's first crossing to the first read (a write a scan earlier
  than that is visible: "within the reader's next complete scan").
"""
from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path

from bitbyte.encoding import isa
from bitbyte.lang.definition import DEF

REG = {r.name: r.addr for r in DEF.registers}
FBY0, FBI0, MCELL0 = REG["FBY"], REG["FBI"], REG["MCELL"]
CHANNELS, MCELLS = 8, 128                  # bus windows (docs/byte-bus.md)
SCAN_DONE = REG["SCAN_DONE"]
EQ = isa.OPCODES["="]
QUEUE_DEPTH = DEF.sizes["queue_depth"]
TO_BYTE, TO_BIT = "to-byte", "to-bit"


@dataclass(frozen=True)
class Crossing:
    clock: int
    side: str          # "bit" or "byte": who made the access
    scan: int          # that side's scan
    direction: str     # TO_BYTE (FBY: bit writes, byte reads) or TO_BIT (FBI)
    write: bool
    cell: int          # the channel / cell number
    value: int         # written, or read


def read_log(path: Path) -> tuple[list[Crossing], dict[str, list[int]]]:
    """The crossings in clock order, and each side's scan-start clocks as far as the log
    shows them (the byte side's: the clock after each SCAN_DONE)."""
    crossings: list[Crossing] = []
    starts: dict[str, list[int]] = {"bit": [], "byte": [0]}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            clock, side, scan = int(row["clock"]), row["side"], int(row["scan"])
            at, value = int(row["at"]), int(row["value"])
            if side == "bit":
                op, cell = at >> 24, at & 0xFFF
                if op == EQ:                                   # = FBY k
                    crossings.append(Crossing(clock, side, scan, TO_BYTE, True, cell,
                                              int(row["rlo"])))
                elif (op & DEF.logic_mask) == isa.LOAD_BASE:    # LD/A/O/X[N] FBI k
                    crossings.append(Crossing(clock, side, scan, TO_BIT, False, cell, value))
            elif at == SCAN_DONE:
                starts["byte"].append(clock + 1)
            elif FBY0 <= at < FBY0 + CHANNELS:                 # READ FBY k
                crossings.append(Crossing(clock, side, scan, TO_BYTE, False, at - FBY0, value))
            elif FBI0 <= at < FBI0 + CHANNELS:                 # WRITE FBI k
                crossings.append(Crossing(clock, side, scan, TO_BIT, True, at - FBI0, value))
            elif MCELL0 <= at < MCELL0 + MCELLS:               # a cell from 8 on
                write = row["rlo"] == "1"
                crossings.append(Crossing(clock, side, scan, TO_BIT if write else TO_BYTE,
                                          write, at - MCELL0, value))
    crossings.sort(key=lambda c: c.clock)
    return crossings, starts


def check_queues(crossings: list[Crossing], losses: dict[str, tuple[int, int]],
                 depth: int = QUEUE_DEPTH) -> str | None:
    """None if every read gives the model's value and the run's (overflows,
    underflows) per direction are the model's; else what differs first."""
    for direction in (TO_BYTE, TO_BIT):
        data, fresh = [0] * depth, [False] * depth
        pos: dict[tuple[bool, int], int] = {}      # (write?, scan) -> next position
        overflows = underflows = 0
        mine = [c for c in crossings if c.direction == direction]
        by_clock: dict[int, list[Crossing]] = {}
        for c in mine:
            by_clock.setdefault(c.clock, []).append(c)
        for clock in sorted(by_clock):
            here = by_clock[clock]
            reads = [c for c in here if not c.write]
            writes = [c for c in here if c.write]
            if len(reads) > 1 or len(writes) > 1:
                return f"{direction}: two reads or two writes in clock {clock}"
            rslot = wslot = None
            if reads:
                r = reads[0]
                rslot = pos.get((False, r.scan), 0) % depth
                pos[(False, r.scan)] = pos.get((False, r.scan), 0) + 1
                if not fresh[rslot]:
                    underflows += 1
                if r.value != data[rslot]:
                    return (f"{direction}: the read in clock {clock} ({r.side} scan "
                            f"{r.scan}, slot {rslot}) gave {r.value}, the model "
                            f"{data[rslot]}")
            if writes:
                w = writes[0]
                wslot = pos.get((True, w.scan), 0) % depth
                pos[(True, w.scan)] = pos.get((True, w.scan), 0) + 1
                if fresh[wslot] and rslot != wslot:
                    overflows += 1
            if rslot is not None:
                fresh[rslot] = False
            if wslot is not None:
                data[wslot], fresh[wslot] = writes[0].value, True
        if (overflows, underflows) != losses[direction]:
            return (f"{direction}: the run counted (overflows, underflows) "
                    f"{losses[direction]}, the model {(overflows, underflows)}")
    return None


def check_marker(crossings: list[Crossing], latency: int = 4) -> str | None:
    """None if the marker area's reads keep the documented bound (the module's
    docstring); else the first read that does not. `latency`: clocks a write may take
    to reach the snapshots (the region merges a cell into its word in two)."""
    for direction, reader in ((TO_BYTE, "byte"), (TO_BIT, "bit")):
        mine = [c for c in crossings if c.direction == direction]
        history: dict[int, list[tuple[int, int]]] = {}       # cell -> (clock, value)
        for c in mine:
            if c.write:
                history.setdefault(c.cell, []).append((c.clock, c.value))
        span: dict[int, tuple[int, int]] = {}                # reader scan -> first, last
        for c in crossings:
            if c.side == reader:
                first, last = span.get(c.scan, (c.clock, c.clock))
                span[c.scan] = (min(first, c.clock), max(last, c.clock))
        got: dict[tuple[int, int], Crossing] = {}           # (scan, cell) -> first read
        for c in mine:
            if c.write:
                continue
            first = got.setdefault((c.scan, c.cell), c)
            if c.value != first.value:
                return (f"{direction}: cell {c.cell} read {first.value} in clock "
                        f"{first.clock} and {c.value} in clock {c.clock}, both in "
                        f"{reader} scan {c.scan}: not one snapshot")
        for (scan, cell), read in got.items():
            # the snapshot was taken between the reader's last crossing of the scan
            # before and its first of this one
            lo = span[scan - 1][1] - latency if scan - 1 in span else -1
            hi = span[scan][0]
            writes = history.get(cell, [])
            held = {next((v for t, v in reversed(writes) if t <= lo), 0)}
            held |= {v for t, v in writes if lo < t <= hi}
            if read.value not in held:
                return (f"{direction}: cell {cell} read {read.value} in clock "
                        f"{read.clock} ({reader} scan {scan}); the writer's cell held "
                        f"only {sorted(held)} from clock {lo} to {hi}")
    return None
