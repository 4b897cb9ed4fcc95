"""The first-check warning for `.il` sources (issue 19, item 5).

The IL dialect (spec §3) has no first-check bit: the RLO is 0 at the start of every
scan and `A`/`AN`/`O`/`ON`/`X`/`XN` always combine with it.  A program written as S7
statement list is written (`A Start / O Motor / A Stop / = Motor`) therefore ANDs
with 0 and never switches the motor on.  This pass finds every combining instruction
that can only meet the scan-start RLO: one that every path from the scan start
reaches without an instruction that sets the RLO before it — the program's first
logic instruction, or the first after a label reached only from there.  It is a
warning, not an error: the program is valid IL.  `= x` followed by `A y` stays silent
when an instruction before the `=` set the RLO (the paper's Fig. 14 does it).

Instructions that leave the scan-start RLO as it is: `NOP`, `REFRESH` (I or Q), `=`, `S`, `R`,
the jumps, `END` and the byte instructions that do not write the RLO (`L`, `T`,
arithmetic, timers, counters, `WRITE`).  Every other instruction sets it (loads,
combines, `NOT`, `SET`, `CLR`, parentheses, `FP`/`FN`, compares, `READ`).
Hand-partitioned programs (`BIT:`/`BYTE:` sections) are not checked.
"""
from __future__ import annotations

from bitbyte.lang.definition import DEF
from bitbyte.lang.errors import SourceError
from bitbyte.lang.program import COMBINES, JUMPS, Program

KEEPS_RLO = frozenset(("NOP", "REFRESH", "REFRESH Q", "=", "S", "R", "END", "L", "T")
                      + DEF.arithmetic + DEF.word_logic + DEF.shifts
                      + ("SD", "SS", "SP", "SF", "CU", "CD", "WRITE") + JUMPS)
WARNED = tuple(m for m, (func, _) in COMBINES.items() if func is not None)


def first_check_warnings(program: Program) -> list[SourceError]:
    """One warning (a SourceError to print, not to raise) per combining instruction
    that can only meet the scan-start RLO of 0."""
    instrs = program.instrs
    if not instrs or any(ins.section for ins in instrs):
        return []
    n = len(instrs)
    preds: list[list[int]] = [[] for _ in range(n)]
    for pc, ins in enumerate(instrs):
        if ins.mnemonic in JUMPS:
            preds[program.labels[ins.operand.label]].append(pc)
        if ins.mnemonic not in ("JU", "END") and pc + 1 < n:
            preds[pc + 1].append(pc)
    succs: list[list[int]] = [[] for _ in range(n)]
    for pc, pred in enumerate(preds):
        for p in pred:
            succs[p].append(pc)
    reached, todo = {0}, [0]
    while todo:
        for nxt in succs[todo.pop()]:
            if nxt not in reached:
                reached.add(nxt)
                todo.append(nxt)
    # fresh[pc]: every path from the scan start to pc keeps the scan-start RLO (the
    # greatest fixpoint: start from "all fresh", only ever clear)
    fresh = [pc in reached for pc in range(n)]
    changed = True
    while changed:
        changed = False
        for pc in range(1, n):
            if fresh[pc] and not all(fresh[p] and instrs[p].mnemonic in KEEPS_RLO
                                     for p in preds[pc] if p in reached):
                fresh[pc] = False
                changed = True
    warnings = []
    for pc, ins in enumerate(instrs):
        if fresh[pc] and ins.mnemonic in WARNED:
            load = "LDN" if ins.mnemonic.endswith("N") else "LD"
            warnings.append(SourceError(
                program.path, ins.line, ins.col,
                f"warning: `{ins.mnemonic}` combines with the scan-start RLO 0 (this "
                f"dialect has no first check): start the logic string with `{load}`, "
                "or write the program as S7 statement list (.awl) for S7's first check",
                ins.source))
    return warnings
