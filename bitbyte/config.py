"""Sizes of one configured build.  The RTL parameters of `rtl/bitbyte_cpu.v` carry the
same names; the assembler rejects any address the build cannot hold."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Config:
    prog_words: int = 4096    # ProgWords: instructions in program memory
    in_bytes: int = 16        # InBytes: I/PI/IR/IF b = 0..in_bytes-1
    out_bytes: int = 16       # OutBytes: Q/PQ b = 0..out_bytes-1
    marker_bytes: int = 256   # MarkerBytes: M b = 0..marker_bytes-1
    timers: int = 64          # Timers: T 0..timers-1
    counters: int = 64        # Counters: C 0..counters-1
    channels: int = 4         # Channels: FBI/FBY k = 0..channels-1
    nest_depth: int = 8       # NestDepth: parenthesis nesting levels
    in_words: int = 16        # IW n
    out_words: int = 16       # QW n
    data_words: int = 256     # MW n
    clock_mhz: float = 100.0  # bit-processor clock

    def area_size(self, area: str) -> int:
        """Bytes (byte.bit areas) or elements (numbered areas) this build holds."""
        return {
            "I": self.in_bytes, "PI": self.in_bytes, "IR": self.in_bytes,
            "IF": self.in_bytes, "Q": self.out_bytes, "PQ": self.out_bytes,
            "M": self.marker_bytes, "T": self.timers, "C": self.counters,
            "FBI": self.channels, "FBY": self.channels, "IW": self.in_words,
            "QW": self.out_words, "MW": self.data_words,
        }[area]


DEFAULT = Config()
