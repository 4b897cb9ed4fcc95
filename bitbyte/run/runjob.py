"""One simulation job, the same for every hardware runner.

`bitbyte run` turns (image, stimulus, trace columns, stop condition) into a RunJob;
the Verilator C++ harness reads it as a small text file (`to_harness_text`), the
cocotb driver as JSON. Both return the same per-scan values, so the trace writer and
the summary do not care which simulator produced them.
"""
from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field

from bitbyte.lang.program import Operand

# Hardware column kinds understood by both runners.
_BIT_KINDS = {"Q": "q", "PQ": "q", "QR": "qr", "QF": "qf", "I": "i", "PI": "pi", "IR": "ir",
              "IF": "if", "M": "m"}
_INDEX_KINDS = {"T": "t", "C": "c", "MW": "mw", "QW": "qw", "IW": "iw"}
WORD_KINDS = ("mw", "qw", "iw")          # traced as signed decimal


def hw_column(operand: Operand) -> tuple[str, int]:
    """(kind, index) of a traced operand in the hardware: a bit of the CPU, a status
    bit (t, c), a word (mw: byte processor memory, qw/iw: word I/O); 'zero' for what
    has no value in serial mode (the exchange channels)."""
    if operand.kind == "bit" and operand.area in _BIT_KINDS:
        return _BIT_KINDS[operand.area], operand.bit_number
    if operand.kind == "index" and operand.area in _INDEX_KINDS:
        return _INDEX_KINDS[operand.area], operand.index
    return "zero", 0


@dataclass
class RunJob:
    prog: list[int]                      # program image words
    clock_hz: int = 100_000_000
    watchdog: int = 100_000
    scans: int | None = None             # stop after this many scans, or
    until_clock: int | None = None       # after the first scan ending at or after it
    until_min_scans: int = 0             # ... but not before this many scans (startup)
    stim_kind: str = "none"              # none | scan | clock
    # (key, pins, words): words = the 16 input words IW0..15, or None (no IW columns)
    stim: list[tuple[int, int, list[int] | None]] = field(default_factory=list)
    cols: list[tuple[str, str, int]] = field(default_factory=list)  # (header, kind, index)
    costs: str = "paper"                 # byte processor cost table
    pool: list[int] = field(default_factory=list)   # constant pool words
    mode: str = "serial"                 # serial | parallel | free
    exchange: str = "handshake"          # handshake | queue | queue-free | marker
    # marker exchange: writers publish their cells at their scan end (the write buffer,
    # --marker-write-buffer), so a snapshot holds whole scans of the other side
    marker_write_buffer: bool = False
    byte_prog: list[int] = field(default_factory=list)   # parallel: the byte part
    status_scan: int | None = None       # the block status of this scan (--status)
    xlog: str | None = None              # --exchange-log: every crossing, one line each
    line_counts: bool = False            # --line-counts: retirements per address, whole run
    # --force: (scan, in mask, in values, out mask, out values), the force table a host
    # writes during that scan (-1: before RUN); bitbyte.run.force
    force: list[tuple[int, int, int, int, int]] = field(default_factory=list)
    # scans the hardware runs before scan 0 that are no scans of the trace (an S7
    # source's OB 100); bitbyte.run.startup.hardware_job adds them
    startup_scans: int = 0
    # the wide bit engine's image (issue 18): its extension words, one per address of
    # prog (0 for a scalar word); None: a scalar image, run on the scalar build
    prog_ext: list[int] | None = None

    def to_json(self) -> dict:
        return asdict(self)

    @classmethod
    def from_json(cls, data: dict) -> "RunJob":
        return cls(**data)

    def to_harness_text(self, prog_path: str, trace_path: str, waves: str | None,
                        byte_prog_path: str | None = None,
                        prog_ext_path: str | None = None) -> str:
        lines = [f"prog {prog_path}", f"clock_hz {self.clock_hz}",
                 f"watchdog {self.watchdog}", f"mode {self.mode}",
                 f"exchange {self.exchange}"]
        if byte_prog_path:
            lines.append(f"byte_prog {byte_prog_path}")
        if prog_ext_path:
            lines.append(f"prog_ext {prog_ext_path}")
        if self.marker_write_buffer:
            lines.append("marker_write_buffer 1")
        if self.scans is not None:
            lines.append(f"scans {self.scans}")
        if self.until_clock is not None:
            lines.append(f"until_clock {self.until_clock}")
            if self.until_min_scans:
                lines.append(f"until_min_scans {self.until_min_scans}")
        if self.status_scan is not None:
            lines.append(f"status {self.status_scan}")
        if self.xlog is not None:
            lines.append(f"xlog {self.xlog}")
        if self.line_counts:
            lines.append("line_counts 1")
        for key, *vectors in self.force:
            lines.append(f"force {'pre' if key < 0 else key} "
                         + " ".join(f"{v:x}" for v in vectors))
        lines.append(f"stim_kind {self.stim_kind}")
        for key, pins, words in self.stim:
            tail = "" if words is None else " " + " ".join(str(w) for w in words)
            lines.append(f"stim {key} {pins:x}{tail}")
        lines.append(f"costs {self.costs}")
        if self.pool:
            lines.append("pool " + " ".join(f"{w:08x}" for w in self.pool))
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
    stalls: tuple[int, int] = (0, 0)     # (bit side, byte side) clocks spent waiting
    byte_scans: int | None = None        # free-running: the byte side's own scans
    queue_losses: tuple[int, int] | None = None   # queue-free: QUEUE_OVERFLOWS, _UNDERFLOWS
    byte_flags: int = 0                  # bb_flags()
    block_status: dict | None = None     # --status: address -> (count, rlo, operand, accu1, accu2)
    byte_status: dict | None = None      # ... of the byte part (parallel mode)

    def to_json(self) -> str:
        return json.dumps(asdict(self))
