"""The byte processor's cost model (spec §5): which byte instructions there are, their
cost classes and the named cost tables, all read from bitbyte/lang/definition.toml, and
the resolution of a `--costs` setting into clocks per instruction kind.

Used alike by the reference interpreter, the partitioning compiler's timing model and
`bitbyte alloc`: the spec fixes these numbers, so they are data of the language, not
of any one of them.
"""
from __future__ import annotations

from typing import Mapping

from bitbyte.lang.definition import DEF
from bitbyte.lang.program import Instr, Program

# Every byte instruction kind -> its cost class (bitbyte/lang/definition.toml, the classes
# of the byte firmware).  A kind is the canonical mnemonic, except that `S C n`,
# `R C n`, `R T n` (parsed as "S"/"R" with a C/T operand) are the kinds "S C", "R C",
# "R T".  The definition's data that the spec fixes (which instructions are word
# instructions, the cost tables); never its encoding.
BYTE_KINDS: dict[str, str] = DEF.byte_kinds
WORD_CLASSES = DEF.word_classes
COST_CLASSES = DEF.priced_classes

# Named tables (spec §5): "paper" (the default), the S7-315-2DP weights of the seed
# paper, 1 µs per word instruction and 0.1 µs per binary one at 100 MHz; "c320": the
# paper's 80C320 byte processor (Table 1 average), 57 clocks per word instruction, 6
# per binary one.
COST_TABLES: dict[str, dict[str, int]] = DEF.cost_tables
PAPER_COSTS = COST_TABLES["paper"]


def byte_kind(ins: Instr) -> str | None:
    """The cost-table kind of a byte instruction ("L", "+I", "A >=I", "SD", "S C",
    "R T", "READ", ...), or None for a bit instruction."""
    m = ins.mnemonic
    if m in ("S", "R"):
        op = ins.operand
        if op is not None and op.kind == "index" and op.area in ("T", "C"):
            return f"{m} {op.area}"
        return None
    return m if m in BYTE_KINDS else None


def resolve_costs(costs: Mapping[str, int] | str | None = None) -> dict[str, int]:
    """kind -> clocks for every byte instruction kind.

    costs is the name of a table of COST_TABLES ("paper", "c320"), or a dict laid
    over the "paper" table whose keys are kinds of BYTE_KINDS ("*I", "S C",
    "A ==I", ...), cost classes ("load", "transfer", "arith", "muldiv", "compare",
    "timer", "counter", "binary") or "word" (all seven word classes).  The most
    specific entry given wins: kind, then class, then "word", then "paper".  Every
    cost is a whole number of clocks >= 1 (the byte processor answers DONE in the
    last clock of its cost, at the earliest in the dispatch clock).
    """
    if costs is None:
        costs = {}
    elif isinstance(costs, str):
        if costs not in COST_TABLES:
            raise ValueError(f"cost table: unknown table {costs!r} "
                             f"(known: {', '.join(COST_TABLES)})")
        costs = COST_TABLES[costs]
    for key, clocks in costs.items():
        if key not in BYTE_KINDS and key not in COST_CLASSES and key != "word":
            raise ValueError(f"cost table: unknown byte instruction or class {key!r}")
        if isinstance(clocks, bool) or not isinstance(clocks, int) or clocks < 1:
            raise ValueError(f"cost table: {key!r} must cost a whole number of "
                             f"clocks >= 1, not {clocks!r}")
    table = {}
    for kind, cls in BYTE_KINDS.items():
        for key in (kind, cls, "word" if cls in WORD_CLASSES else None):
            if key in costs:
                table[kind] = costs[key]
                break
        else:
            table[kind] = PAPER_COSTS[cls]
    return table


def serial_cost(program: Program, costs: Mapping[str, int] | str | None = None) -> int:
    """Clocks of instruction work of a straight-line program in serial mode: 1 per bit
    instruction, the table cost per byte instruction, up to the first END (END not
    included, so a scan has serial_cost + 1 cycles).  Jumps count as not taken
    (1 clock).  Spec §5's Fig. 5 program gives 59 with the default table."""
    table = resolve_costs(costs)
    total = 0
    for ins in program.instrs:
        if ins.mnemonic == "END":
            break
        kind = byte_kind(ins)
        total += 1 if kind is None else table[kind]
    return total
