"""Status syncs: which timer/counter updates reach a read of `T n` / `C n` in the same scan
(paths through jumps included), so that the bit side waits for the byte side's update
where serial mode would have seen it.
"""
from __future__ import annotations

from bitbyte.compiler.common import _text
from bitbyte.lang.costs import byte_kind
from bitbyte.lang.parts import STATUS_UPDATES
from bitbyte.lang.program import COMBINES, Instr, JUMPS, Program


class _Reach:
    """Which source instructions may execute after which in one scan (control flow
    graph: fall-through, jump targets; END ends the scan)."""

    def __init__(self, program: Program):
        self.program = program
        self.cache: dict[int, set[int]] = {}

    def successors(self, i: int) -> list[int]:
        instrs = self.program.instrs
        ins = instrs[i]
        if ins.mnemonic == "END":
            return []
        nxt = [i + 1] if i + 1 < len(instrs) else []
        if ins.mnemonic in JUMPS:
            target = self.program.labels[ins.operand.label]
            return [target] if ins.mnemonic == "JU" else nxt + [target]
        return nxt

    def after(self, i: int) -> set[int]:
        """Instructions reachable from i in one or more steps."""
        if i not in self.cache:
            seen: set[int] = set()
            todo = list(self.successors(i))
            while todo:
                j = todo.pop()
                if j not in seen:
                    seen.add(j)
                    todo.extend(self.successors(j))
            self.cache[i] = seen
        return self.cache[i]


class _StatusOps:
    """Per timer / counter: the byte updates and the bit reads of its status."""

    def __init__(self, program: Program):
        self.program = program
        self.updates: dict[tuple[str, int], list[int]] = {}
        self.reads: dict[tuple[str, int], list[int]] = {}

    def key(self, i: int) -> tuple[str, int]:
        op = self.program.instrs[i].operand
        return op.area, op.index

    def update_before(self, reach: _Reach, i: int) -> str | None:
        """An update of the status read at i that may execute before it, or None."""
        for q in self.updates.get(self.key(i), []):
            if i in reach.after(q):
                return _where(self.program.instrs[q])
        return None

    def sole_dominating_update(self, reach: _Reach, i: int) -> int | None:
        """The one update of the status read at i that precedes it, when the hardware
        wait (instruction bit 16: wait until the status was written this scan) orders
        them exactly: it is the only update that may run before i, it runs exactly
        once per scan before i (same straight-line stretch: no jump, END or jump
        target between them), and neither is inside a loop."""
        ups = [q for q in self.updates.get(self.key(i), []) if i in reach.after(q)]
        if len(ups) != 1:
            return None
        q = ups[0]
        if q >= i or q in reach.after(q) or i in reach.after(i):
            return None
        instrs = self.program.instrs
        targets = {self.program.labels[ins.operand.label] for ins in instrs
                   if ins.mnemonic in JUMPS}
        if any(instrs[j].mnemonic in JUMPS or instrs[j].mnemonic == "END"
               for j in range(q, i)) or any(j in targets for j in range(q + 1, i + 1)):
            return None
        return q

    def read_before(self, reach: _Reach, i: int) -> str | None:
        """A bit read of the status updated at i that may execute before it."""
        for p in self.reads.get(self.key(i), []):
            if i in reach.after(p):
                return _where(self.program.instrs[p])
        return None


def _where(ins: Instr) -> str:
    return f"`{_text(ins.mnemonic, ins.operand)}` (line {ins.line})"


def _status_ops(program: Program) -> _StatusOps:
    ops = _StatusOps(program)
    for i, ins in enumerate(program.instrs):
        op = ins.operand
        if op is None or op.area not in ("T", "C") or op.kind != "index":
            continue
        if byte_kind(ins) in STATUS_UPDATES:
            ops.updates.setdefault((op.area, op.index), []).append(i)
        elif ins.mnemonic in COMBINES:
            ops.reads.setdefault((op.area, op.index), []).append(i)
    return ops
