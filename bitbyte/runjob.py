"""One simulation job, the same for every hardware runner.

`bitbyte run` turns (image, stimulus, trace columns, stop condition) into a RunJob;
the Verilator C++ harness reads it as a small text file (`to_harness_text`), the
cocotb driver as JSON. Both return the same per-scan values, so the trace writer and
the summary do not care which simulator produced them.
"""
from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field

from .program import Operand

# Hardware column kinds understood by both runners.
_BIT_KINDS = {"Q": "q", "PQ": "q", "I": "i", "PI": "pi", "IR": "ir", "IF": "if", "M": "m"}


def hw_column(operand: Operand) -> tuple[str, int]:
    """(kind, index) of a traced operand in the hardware; 'zero' for what the
    bit-only CPU does not hold yet (timer/counter status, words)."""
    if operand.kind == "bit" and operand.area in _BIT_KINDS:
        return _BIT_KINDS[operand.area], operand.bit_number
    if operand.kind == "index" and operand.area in ("T", "C"):
        return operand.area.lower(), operand.index
    return "zero", 0


@dataclass
class RunJob:
    prog: list[int]                      # program image words
    clock_hz: int = 100_000_000
    watchdog: int = 100_000
    scans: int | None = None             # stop after this many scans, or
    until_clock: int | None = None       # after the first scan ending at or after it
    stim_kind: str = "none"              # none | scan | clock
    stim: list[tuple[int, int]] = field(default_factory=list)   # (key, pins)
    cols: list[tuple[str, str, int]] = field(default_factory=list)  # (header, kind, index)

    def to_json(self) -> dict:
        return asdict(self)

    @classmethod
    def from_json(cls, data: dict) -> "RunJob":
        return cls(**data)

    def to_harness_text(self, prog_path: str, trace_path: str, waves: str | None) -> str:
        lines = [f"prog {prog_path}", f"clock_hz {self.clock_hz}",
                 f"watchdog {self.watchdog}"]
        if self.scans is not None:
            lines.append(f"scans {self.scans}")
        if self.until_clock is not None:
            lines.append(f"until_clock {self.until_clock}")
        lines.append(f"stim_kind {self.stim_kind}")
        lines += [f"stim {key} {pins:x}" for key, pins in self.stim]
        lines += [f"col {header} {kind} {index}" for header, kind, index in self.cols]
        lines.append(f"trace {trace_path}")
        if waves:
            lines.append(f"waves {waves}")
        return "\n".join(lines) + "\n"


@dataclass
class RunResult:
    """Per completed scan: (scan, end_clock, cycles, [column values]); and the fault."""
    rows: list[tuple[int, int, int, list[int]]]
    fault: bool = False
    clocks: int = 0

    def to_json(self) -> str:
        return json.dumps(asdict(self))
