"""Hand-partitioned programs (BIT: / BYTE: sections): taken verbatim, channel counts
checked.
"""
from __future__ import annotations

from bitbyte.compiler.common import _error
from bitbyte.lang.parts import (BYTE_JUMPS, TO_BIT, TO_BYTE, PartInstr, Partition, Row,
                                Transfer)
from bitbyte.lang.program import COMBINES, Program


def _hand_partitioned(program: Program, channels: int) -> Partition:
    parts: dict[str, list[PartInstr]] = {"BIT": [], "BYTE": []}
    labels: dict[str, dict[str, int]] = {"BIT": {}, "BYTE": {}}
    transfers: list[Transfer] = []
    for i, ins in enumerate(program.instrs):
        side = ins.section
        if side not in parts:              # the parser puts every instruction in one
            raise _error(program, ins, "instruction outside the BIT:/BYTE: sections")
        for name in ins.labels:
            labels[side][name.upper()] = len(parts[side])
        m, op = ins.mnemonic, ins.operand
        p = PartInstr(m, op, ins.line, ins.col, ins.source, list(ins.labels), side,
                      ins.at_latch, origin=i)
        if side == "BYTE" and m in BYTE_JUMPS:
            p.mnemonic, p.note = BYTE_JUMPS[m], "byte jump on F_B"
        elif side == "BYTE" and m == "END":
            p.mnemonic, p.note = "END_B", "end of the byte part"
        parts[side].append(p)
        if op is not None and op.area in ("FBI", "FBY"):
            if op.index >= channels:
                raise _error(program, ins, f"operand out of range: `{op.address()}` "
                                           f"(channels 0..{channels - 1} in this build)")
            if m == "=" and side == "BIT":
                transfers.append(Transfer(TO_BYTE, op.index, ins.line, ins.col, "written"))
            elif m == "WRITE":
                transfers.append(Transfer(TO_BIT, op.index, ins.line, ins.col, "written"))
    for side, end in (("BIT", "END"), ("BYTE", "END_B")):
        if not parts[side] or parts[side][-1].mnemonic != end:
            last = program.instrs[-1]
            parts[side].append(PartInstr(end, None, last.line, last.col, "", [], side,
                                         note="appended", synthesized=True))
    bit, byte = parts["BIT"], parts["BYTE"]
    rows = [Row("pair", None, bit[n] if n < len(bit) else None,
                byte[n] if n < len(byte) else None)
            for n in range(max(len(bit), len(byte)))]
    return Partition(program, channels, bit, byte, labels["BIT"], labels["BYTE"], rows,
                     transfers, [], hand_partitioned=True,
                     warnings=_channel_count_warnings(bit, byte))


def _channel_count_warnings(bit: list[PartInstr], byte: list[PartInstr]) -> list[str]:
    """Static counts per channel (writes on one side vs reads on the other)."""
    def count(instrs, pred):
        out: dict[int, int] = {}
        for ins in instrs:
            if ins.operand is not None and pred(ins):
                out[ins.operand.index] = out.get(ins.operand.index, 0) + 1
        return out
    fby_w = count(bit, lambda i: i.mnemonic == "=" and i.operand.area == "FBY")
    fby_r = count(byte, lambda i: i.mnemonic == "READ")
    fbi_w = count(byte, lambda i: i.mnemonic == "WRITE")
    fbi_r = count(bit, lambda i: i.mnemonic in COMBINES and i.operand.area == "FBI")
    warnings = []
    for name, w, r, ws, rs in (("FBY", fby_w, fby_r, "bit", "byte"),
                               ("FBI", fbi_w, fbi_r, "byte", "bit")):
        for k in sorted(set(w) | set(r)):
            if w.get(k, 0) != r.get(k, 0):
                warnings.append(f"channel {name} {k}: {w.get(k, 0)} write(s) on the {ws} "
                                f"side, {r.get(k, 0)} read(s) on the {rs} side (static "
                                "count: fine only if the paths make them pair up)")
    return warnings
