"""Response time: from an input change to the PIO update that shows it (spec §4's
"response-time figures where inputs changed"; the definition is docs/toolchain.md's).

A scan's outputs reach the pins in its END clock, so an output change shows at the
scan's end, end_clock (= the next scan's latch clock; t_us = end_clock / f).  The
response to an input change at clock c (exact: a t_us row may fall between two clock
edges) is end_clock - c of the first scan that ends after c and shows it.  `make
bench` (bench/benchlib.py) measures its image-output responses with the same
`responding_scan`; the run summary's figures come from `response_times`.
"""
from __future__ import annotations

import bisect
from fractions import Fraction
from typing import Callable

from bitbyte.lang.trace import Column, ScanRecord

OUTPUT_AREAS = ("Q", "PQ", "QW")      # what reaches the pins at END (PQ: also at once)


def responding_scan(change: Fraction, ends: list[int], shows: Callable[[int], bool],
                    until: Fraction | None = None) -> int | None:
    """The first scan k that ends after the input change at clock `change` (and, with
    `until`, no later than that clock: the next change) and for which shows(k) holds;
    None when there is none.  ends: the scans' end_clocks, ascending.  A scan ending
    at `change` itself updated its outputs in the clock before: it cannot show it."""
    k = bisect.bisect_right(ends, change)
    while k < len(ends) and (until is None or ends[k] <= until):
        if shows(k):
            return k
        k += 1
    return None


def change_clocks(changes: list[tuple[str, int | Fraction]],
                  records: list[ScanRecord]) -> list[Fraction]:
    """The stimulus's input changes (Stimulus.changes) as clocks: a scan row at its
    scan's latch (the previous scan's end_clock, 0 for scan 0), a t_us row at its
    exact moment.  Only changes a completed scan latched at or after: the run stopped
    before the others could show."""
    if not records:
        return []
    latches = [0] + [r.end_clock for r in records[:-1]]
    out = []
    for kind, key in changes:
        if kind == "scan":
            if key < len(records):
                out.append(Fraction(latches[key]))
        elif key <= latches[-1]:
            out.append(Fraction(key))
    return out


def response_times(changes: list[tuple[str, int | Fraction]], records: list[ScanRecord],
                   columns: list[Column]) -> tuple[list[Fraction], int]:
    """(responses in clocks, input changes counted).  An input change's response ends
    at the first scan, before the next change, whose outputs (the trace's Q, PQ, QW
    columns) differ from the scan before it (scan 0: from the reset value 0); a change
    after which no output changes before the next one has no response."""
    outs = [c.header for c in columns if c.operand.area in OUTPUT_AREAS]
    values = [tuple(r.values[h] for h in outs) for r in records]
    reset = tuple(0 for _ in outs)
    ends = [r.end_clock for r in records]

    def shows(k: int) -> bool:
        return values[k] != (values[k - 1] if k else reset)

    clocks = change_clocks(changes, records)
    got = []
    for i, c in enumerate(clocks):
        until = clocks[i + 1] if i + 1 < len(clocks) else None
        hit = responding_scan(c, ends, shows, until)
        if hit is not None:
            got.append(ends[hit] - c)
    return got, len(clocks)
