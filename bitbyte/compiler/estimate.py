"""The timing estimate of a partition: clocks per scan of each side and the waits, from the
cost table.
"""
from __future__ import annotations

from dataclasses import dataclass

from bitbyte.lang.costs import byte_kind, resolve_costs, serial_cost
from bitbyte.lang.parts import BYTE_JUMPS, Partition


@dataclass(frozen=True)
class Estimate:
    """Clocks per scan along the straight-line path (jumps not taken, loops once; a
    taken bit jump would cost DEF.jump_taken_clocks, bitbyte/lang/definition.toml).

    bit_clocks: bit-part instructions, END included (1 clock each).  byte_clocks: the
    byte part's cost-table sum (word instructions, READ/WRITE/JU_B/JC_B/JCN_B binary,
    END_B 0).  tail: bit instructions from the last FBI read through END: they cannot
    start before the byte side's last WRITE.  clocks = max(byte_clocks + tail,
    bit_clocks).  serial: the same program in serial mode (None if hand-partitioned).

    A scan runs each part up to its first END / END_B: what stands after them (an S7
    source's OB 100, run once in the startup scan, docs/s7.md) is no part of the
    estimate, as serial_cost stops at the first END."""

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
    bit = _scan_part(part.bit, "END")
    for ins in _scan_part(part.byte, "END_B"):
        if ins.mnemonic == "END_B":
            continue
        kind = "READ" if ins.mnemonic in BYTE_JUMPS.values() else byte_kind(ins)
        byte_clocks += table[kind]
        if kind in ("READ", "WRITE"):
            binaries += 1
        else:
            words += 1
    last_read = max((n for n, ins in enumerate(bit)
                     if ins.operand is not None and ins.operand.area == "FBI"), default=None)
    tail = 1 if last_read is None else len(bit) - last_read
    bit_clocks = len(bit)
    serial = None if part.hand_partitioned else serial_cost(part.program, costs) + 1
    return Estimate(bit_clocks, byte_clocks, tail, max(byte_clocks + tail, bit_clocks),
                    serial, words, binaries)


def _scan_part(instrs: list, end: str) -> list:
    """The instructions a scan runs (jumps not taken): up to the first `end`, it
    included."""
    for n, ins in enumerate(instrs):
        if ins.mnemonic == end:
            return instrs[:n + 1]
    return instrs
