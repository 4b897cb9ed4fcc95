"""The partition report, the side-by-side view (paper Fig. 13 style) and the listing of
both parts.
"""
from __future__ import annotations

from bitbyte.compiler.common import _text
from bitbyte.compiler.estimate import estimate
from bitbyte.lang.parts import PartInstr, Partition, TO_BIT, TO_BYTE


def report_text(part: Partition, costs="paper") -> str:
    """Instructions per side, transfers per direction, channels used, the estimated
    clocks per scan (and how they are estimated)."""
    est = estimate(part, costs)
    nbit, nbyte = len(part.bit) - 1, len(part.byte) - 1
    out = [f"; partition of {part.program.path}"
           + (" (hand-partitioned: BIT:/BYTE: sections taken verbatim)"
              if part.hand_partitioned else ""),
           f"bit part:  {nbit} instructions + END = {len(part.bit)} words",
           f"byte part: {nbyte} instructions + END_B = {len(part.byte)} words"]
    for direction, name, arrow in ((TO_BYTE, "FBY", "bit -> byte"),
                                   (TO_BIT, "FBI", "byte -> bit")):
        used = part.channels_used(direction)
        chans = ", ".join(f"{name} {k}" for k in used) or "none"
        out.append(f"transfers {arrow}: {part.transfer_count(direction)} "
                   f"(channels used: {chans})")
    out.append(f"channels per direction: {part.channels} (round-robin; with the queue "
               "exchange the order alone counts)")
    if not part.hand_partitioned:
        out.append(f"status sync (spec section 2: T n / C n reads wait for earlier updates): "
                   f"{'on' if part.status_sync else 'off (paper Fig. 2: not serial-equivalent)'}")
        mirrored = [part.program.instrs[i] for i in part.mirrored]
        out.append("jumps the byte side takes too: " + (", ".join(
            f"`{_text(j.mnemonic, j.operand)}` (line {j.line})" for j in mirrored)
            or "none"))
    if part.schedule is not None:
        moved, before, after = part.schedule
        out.append(f"bit-side schedule: {moved} rungs moved inside their blocks, ahead of "
                   f"rungs that wait for the byte side (timing model, straight line: "
                   f"{before} -> {after} clocks); the listing below is in program order, "
                   f"the bit part's addresses give the executed order")
    for t in part.transfers:
        arrow = "bit -> byte" if t.direction == TO_BYTE else "byte -> bit"
        name = "FBY" if t.direction == TO_BYTE else "FBI"
        out.append(f"  line {t.line:>4}: {arrow} {name} {t.channel}: {t.reason}")
    for w in part.warnings:
        out.append(f"warning: {w}")
    out += ["",
            f"estimated clocks per scan: {est.clocks} = max(byte part {est.byte_clocks} "
            f"+ bit tail {est.tail}, bit part {est.bit_clocks})",
            f"  byte part: {est.word_instrs} word instructions + {est.binary_instrs} "
            f"binary (READ/WRITE/jumps) at the {costs if isinstance(costs, str) else 'given'}"
            f" costs, END_B 0 = {est.byte_clocks} clocks",
            f"  bit part: {est.bit_clocks} instructions at 1 clock, END included"
            + (" (up to the first END: OB 100's part after it runs once)"
               if est.bit_clocks < len(part.bit) else ""),
            f"  bit tail: the instructions from the last FBI read through END "
            f"({est.tail}); they wait for the byte side's last WRITE",
            "  (straight-line path: jumps not taken, loops once; other waits are assumed "
            "hidden under the byte side's work; the hardware's cycles are the measure)"]
    if est.serial is not None:
        out.append(f"serial mode: {est.serial} clocks per scan "
                   f"({est.serial - 1} of instruction work + END)")
    return "\n".join(out) + "\n"


def _cell(ins: PartInstr | None) -> str:
    if ins is None:
        return ""
    op = ins.operand
    if op is None:
        return ins.mnemonic
    text = f"{op.area} {op.index}" if op.area in ("FBI", "FBY") else (op.text or op.address())
    return f"{ins.mnemonic:<6}{text}"


def side_by_side(part: Partition) -> str:
    """Two columns like the paper's Fig. 13: each instruction in its own row, in
    program order; a transfer is one row, `-->` bit to byte, `<--` byte to bit."""
    w = 26
    out = [f"{'line':>4}  {'bit processor':<{w}} {'':5} byte processor",
           f"{'----':>4}  {'-' * w} {'':5} {'-' * w}"]
    if part.hand_partitioned:
        out.insert(0, "; hand-partitioned: the columns are independent (row n = the "
                      "n-th instruction of each part)")
    for row in part.rows:
        if row.kind == "label":
            cell = row.label + ":"
            out.append(f"{'':4}  {cell:<{w}} {'':5} {cell}")
            continue
        ins = row.bit if row.bit is not None else row.byte
        line = "" if ins is None or ins.line <= 0 else str(ins.line)
        arrow = {TO_BYTE: "-->", TO_BIT: "<--"}.get(row.kind, "")
        text = f"{line:>4}  {_cell(row.bit):<{w}} {arrow:^5} {_cell(row.byte):<{w}}"
        notes = [i.note for i in (row.bit, row.byte)
                 if i is not None and i.synthesized and i.note]
        if notes and not part.hand_partitioned:
            text += f" ; {notes[0]}"
        out.append(text.rstrip())
    return "\n".join(out) + "\n"


def part_listing(part: Partition) -> str:
    """Both parts, address by address: `AAAA  WWWWWWWW  line: instruction ; note`."""
    out = []
    for name, instrs, words, labels in (
            ("bit part (bit processor program memory)", part.bit, part.bit_words,
             part.bit_labels),
            ("byte part (byte processor program memory)", part.byte, part.byte_words,
             part.byte_labels)):
        out += ["", f"{name}: {len(words)} words", "addr  word      line: instruction"]
        for address, (ins, word) in enumerate(zip(instrs, words)):
            out += [f"{'':16}{label}:" for label in ins.labels]
            text = _cell(ins)
            if ins.operand is not None and ins.operand.kind == "label":
                text += f"  -> {labels[ins.operand.label]:04X}"
            line = f"{address:04X}  {word:08X}  {ins.line:>4}: {text}"
            out.append(f"{line:<56} ; {ins.note}" if ins.note else line)
    return "\n".join(out) + "\n"
