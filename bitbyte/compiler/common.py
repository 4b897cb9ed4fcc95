"""Helpers every stage of the partitioning compiler shares: how an instruction is shown, a
channel operand, an error at an instruction.
"""
from __future__ import annotations

from bitbyte.lang.errors import SourceError
from bitbyte.lang.program import Instr, Operand, Program


def _text(mnemonic: str, op: Operand | None) -> str:
    """`SD Timer`, `= FBY 0`, `A >=I`: an instruction as the listings show it."""
    if op is None:
        return mnemonic
    if op.area in ("FBI", "FBY"):
        return f"{mnemonic} {op.area} {op.index}"
    return f"{mnemonic} {op.text or op.address()}"


def _channel_operand(area: str, k: int) -> Operand:
    return Operand("index", area=area, index=k, text=f"{area}{k}")


def _error(program: Program, ins: Instr, message: str) -> SourceError:
    return SourceError(program.path, ins.line, ins.col, message, ins.source)
