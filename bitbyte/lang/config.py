"""Sizes of one configured build; the assembler rejects any address the build cannot
hold.  The defaults are bitbyte/lang/definition.toml's [sizes] (spec §3), where the comment
of each names the RTL parameter of `rtl/bitbyte_cpu.v` it corresponds to (timers and
counters are both `StatusBits`)."""
from __future__ import annotations

from dataclasses import dataclass, fields

from bitbyte.lang.definition import DEF

_S = DEF.sizes


@dataclass(frozen=True)
class Config:
    prog_words: int = _S["prog_words"]  # ProgWords: instructions in program memory
    in_bytes: int = _S["in_bytes"]  # InBytes: I/PI/IR/IF b = 0..in_bytes-1
    out_bytes: int = _S["out_bytes"]  # OutBytes: Q/PQ b = 0..out_bytes-1
    marker_bytes: int = _S["marker_bytes"]  # MarkerBytes: M b = 0..marker_bytes-1
    timers: int = _S["timers"]  # Timers: T 0..timers-1
    counters: int = _S["counters"]  # Counters: C 0..counters-1
    channels: int = _S["channels"]  # Channels: FBI/FBY k = 0..channels-1
    marker_cells: int = _S["marker_cells"]  # MarkerCells: FBI/FBY k with the marker exchange
    nest_depth: int = _S["nest_depth"]  # NestDepth: parenthesis nesting levels
    in_words: int = _S["in_words"]  # IW n
    out_words: int = _S["out_words"]  # QW n
    data_words: int = _S["data_words"]  # MW n
    force_bits: int = _S["force_bits"]  # ForceBits: I/Q bits 0..force_bits-1 can be forced
    clock_mhz: float = 100.0  # bit-processor clock

    def area_size(self, area: str) -> int:
        """Bytes (byte.bit areas) or elements (numbered areas) this build holds."""
        return {
            "I": self.in_bytes, "PI": self.in_bytes, "IR": self.in_bytes,
            "IF": self.in_bytes, "Q": self.out_bytes, "PQ": self.out_bytes,
            "QR": self.out_bytes, "QF": self.out_bytes,
            "M": self.marker_bytes, "T": self.timers, "C": self.counters,
            "FBI": self.channels, "FBY": self.channels, "IW": self.in_words,
            "QW": self.out_words, "MW": self.data_words,
            "MD": max(self.data_words - 2, 0),      # MD n is MW n and MW n+2
        }[area]

    @classmethod
    def of_profile(cls, name: str | None, **kw) -> "Config":
        """The defaults, or with the sizes of a build profile (definition.toml
        [profiles]: `bitbyte asm|run --profile NAME`)."""
        if name is None:
            return cls(**kw)
        names = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in DEF.profile_sizes(name).items() if k in names}, **kw)


DEFAULT = Config()
