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
  its snapshot, taken from the writer's cells in the reader's snapshot clock (the bit
  side's END clock before the scan, the byte side's SCAN_DONE): every read of a cell
  in a reader's scan gives the same value, the writer's cell as it was then (a write
  in the snapshot clock itself allowed either way). So a condition written before the
  reader's scan starts is seen in that scan: "within the reader's next complete scan".
"""
from __future__ import annotations

import csv
import re
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


def read_log(path: Path) -> tuple[list[Crossing], dict[str, dict[int, int]]]:
    """The crossings in clock order, and each side's snapshot clocks by scan: the clock
    a scan's marker snapshot is taken in (the bit side's: its END clock, the one before
    the latch of the next scan; the byte side's: its SCAN_DONE write). Scan 0's is not
    in the log."""
    crossings: list[Crossing] = []
    snaps: dict[str, dict[int, int]] = {"bit": {}, "byte": {}}
    with open(path, newline="") as f:
        for n, row in enumerate(csv.DictReader(f), start=2):
            clock, side, scan = int(row["clock"]), row["side"], int(row["scan"])
            if side == "bit" and row["at"] == "latch":
                snaps["bit"][scan] = clock - 1
                continue
            at, value = int(row["at"]), int(row["value"])
            if side == "bit":
                op, cell = at >> 24, at & 0xFFF
                if op == EQ:                                   # = FBY k
                    crossings.append(Crossing(clock, side, scan, TO_BYTE, True, cell,
                                              int(row["rlo"])))
                elif (op & DEF.logic_mask) == isa.LOAD_BASE:    # LD/A/O/X[N] FBI k
                    crossings.append(Crossing(clock, side, scan, TO_BIT, False, cell, value))
                else:
                    raise ValueError(f"{path}:{n}: a bit instruction on a channel that "
                                     f"is neither `= FBY k` nor a read: {at:#010x}")
            elif at == SCAN_DONE:
                snaps["byte"][scan + 1] = clock
            elif FBY0 <= at < FBY0 + CHANNELS:                 # READ FBY k
                crossings.append(Crossing(clock, side, scan, TO_BYTE, False, at - FBY0, value))
            elif FBI0 <= at < FBI0 + CHANNELS:                 # WRITE FBI k
                crossings.append(Crossing(clock, side, scan, TO_BIT, True, at - FBI0, value))
            elif MCELL0 <= at < MCELL0 + MCELLS:               # a cell from 8 on
                write = row["rlo"] == "1"
                crossings.append(Crossing(clock, side, scan, TO_BIT if write else TO_BYTE,
                                          write, at - MCELL0, value))
    crossings.sort(key=lambda c: c.clock)
    return crossings, snaps


LOSSES = re.compile(r"queue losses +overflows to-byte (\d+) to-bit (\d+), underflows "
                    r"to-byte (\d+) to-bit (\d+)")


def losses_of(summary: str) -> dict[str, tuple[int, int]] | None:
    """The free-running queues' (overflows, underflows) per direction from a `bitbyte
    run` summary (its `queue losses` line), None without one."""
    found = LOSSES.search(summary)
    if not found:
        return None
    ovf_byte, ovf_bit, unf_byte, unf_bit = map(int, found.groups())
    return {TO_BYTE: (ovf_byte, unf_byte), TO_BIT: (ovf_bit, unf_bit)}


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


def check_marker(crossings: list[Crossing], snaps: dict[str, dict[int, int]],
                 latency: int = 1) -> str | None:
    """None if the marker area's reads keep the snapshot semantics (the module's
    docstring); else the first read that does not. A reader scan's snapshot is taken in
    its snapshot clock S (read_log): every read of a cell in that scan gives one value,
    the writer's cell as it was after clock S - latency or a write up to clock S
    (marker_region.v: a write reaches the snapshots from the next clock). Scan 0, whose
    snapshot clock the log does not show: a value the cell held before the scan's first
    crossing."""
    for direction, reader in ((TO_BYTE, "byte"), (TO_BIT, "bit")):
        mine = [c for c in crossings if c.direction == direction]
        history: dict[int, list[tuple[int, int]]] = {}       # cell -> (clock, value)
        for c in mine:
            if c.write:
                history.setdefault(c.cell, []).append((c.clock, c.value))
        first_crossing: dict[int, int] = {}
        for c in crossings:
            if c.side == reader:
                first_crossing.setdefault(c.scan, c.clock)
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
            if scan in snaps[reader]:
                hi = snaps[reader][scan]
                lo = hi - latency
            elif scan == 0:
                lo, hi = -1, first_crossing[scan]
            else:
                return f"{direction}: {reader} scan {scan} has no snapshot clock in the log"
            writes = history.get(cell, [])
            held = {next((v for t, v in reversed(writes) if t <= lo), 0)}
            held |= {v for t, v in writes if lo < t <= hi}
            if read.value not in held:
                return (f"{direction}: cell {cell} read {read.value} in clock "
                        f"{read.clock} ({reader} scan {scan}); the writer's cell held "
                        f"only {sorted(held)} from clock {lo} to {hi}")
    return None
