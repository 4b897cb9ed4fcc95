"""Forcing (`bitbyte run --force OPERAND=VALUE[@FROM-TO]`, issue 17 item 4), as S7
engineers use it: a forced input is what the CPU reads at that pin whatever is wired to
it, a forced output is what the pin shows whatever the program writes.

The hardware is the force table in front of the I/O units (rtl/force_table.v, the
FORCE_* registers of the byte bus): a host writes a pending table, which takes effect
at the next PIO update (END) — an output from that scan's PIO update on, an input
latched by the next scan — and at once before RUN. So the host writes, during scan j,
the table that holds the inputs forced in scan j+1 and the outputs forced in scan j's
trace row (values after its PIO update); before RUN, the inputs of scan 0 and the
outputs forced from scan 0. force_tables() turns the user's windows into those tables,
one per scan where the table changes (the simulation hosts write what changed, in
clocks the byte processor leaves the bus idle)."""
from __future__ import annotations

import re
from dataclasses import dataclass

from bitbyte.lang.config import Config
from bitbyte.lang.errors import UsageError
from bitbyte.lang.program import Operand
from bitbyte.lang.suggest import did_you_mean
from bitbyte.lang.trace import resolve_operand

BEFORE_RUN = -1                         # the key of the table written before RUN
_SPEC = re.compile(r"^\s*(?P<op>[^=@]+?)\s*=\s*(?P<value>[01])\s*"
                   r"(?:@\s*(?P<first>\d+)\s*(?:-\s*(?P<last>\d+)?)?)?\s*$")


@dataclass(frozen=True)
class Force:
    """One --force: the pin (output or input side, its bit number), its value and the
    scans it holds for (last None: to the end of the run)."""
    text: str
    output: bool
    pin: int
    value: int
    first: int = 0
    last: int | None = None

    def holds(self, scan: int) -> bool:
        return self.first <= scan and (self.last is None or scan <= self.last)


def parse_force(text: str, symbols: dict[str, Operand], config: Config,
                names: dict[str, str] | None = None) -> Force:
    """`Start=1`, `I0.0=1@5-8`, `Q0.1=0@3-`, `Motor=1@2`: an input (I/PI, the pin) or
    an output (Q/PQ) bit, its value, from scan FROM (default 0) to TO (default: the
    end; `@K` alone is scan K only)."""
    m = _SPEC.match(text)
    if m is None:
        raise UsageError(f"--force {text!r}: expected OPERAND=0|1[@FROM-TO], e.g. "
                         "I0.0=1@5-8")
    op = resolve_operand(m["op"], symbols)
    if op is None:
        raise UsageError(f"--force {text!r}: unknown operand '{m['op']}'"
                         + did_you_mean(m["op"], [(names or {}).get(k, k) for k in symbols]))
    if op.kind != "bit" or op.area not in ("I", "PI", "Q", "PQ"):
        raise UsageError(f"--force {text!r}: only input (I, PI) and output (Q, PQ) bits "
                         "can be forced")
    if op.bit_number >= config.force_bits:
        raise UsageError(f"--force {text!r}: this build forces bits 0.0.."
                         f"{(config.force_bits - 1) // 8}.{(config.force_bits - 1) % 8} of "
                         "each side (ForceBits)")
    first = int(m["first"]) if m["first"] is not None else 0
    if m["first"] is not None and m["last"] is None and "-" not in text.split("@", 1)[1]:
        last: int | None = first                # `@K`: scan K only
    else:
        last = int(m["last"]) if m["last"] is not None else None
    if last is not None and last < first:
        raise UsageError(f"--force {text!r}: the window ends before it starts")
    return Force(text.strip(), op.area in ("Q", "PQ"), op.bit_number, int(m["value"]),
                 first, last)


def check_overlaps(forces: list[Force]) -> None:
    """One pin, one value at a time."""
    for i, a in enumerate(forces):
        for b in forces[i + 1:]:
            if (a.output, a.pin) == (b.output, b.pin):
                lo, hi = max(a.first, b.first), min(x for x in (a.last, b.last, 1 << 62)
                                                    if x is not None)
                if lo <= hi:
                    raise UsageError(f"--force {a.text!r} and {b.text!r} force the same "
                                     f"pin in scan {lo}")


def force_tables(forces: list[Force]) -> list[tuple[int, int, int, int, int]]:
    """(key, in mask, in values, out mask, out values) for the scans where the pending
    table changes (key BEFORE_RUN: before RUN), ascending."""
    def table(j: int) -> tuple[int, int, int, int]:
        in_mask = in_val = out_mask = out_val = 0
        for f in forces:
            bit = 1 << f.pin
            if not f.output and f.holds(j + 1):
                in_mask |= bit
                in_val |= bit * f.value
            if f.output and (f.holds(j) or (j == BEFORE_RUN and f.first == 0)):
                out_mask |= bit
                out_val |= bit * f.value
        return in_mask, in_val, out_mask, out_val

    keys = {BEFORE_RUN}
    for f in forces:
        keys |= {f.first - 1, f.first}
        if f.last is not None:
            keys |= {f.last, f.last + 1}
    out, last = [], (0, 0, 0, 0)
    for j in sorted(k for k in keys if k >= BEFORE_RUN):
        t = table(j)
        if t != last:
            out.append((j, *t))
            last = t
    return out
