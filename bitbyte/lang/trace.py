"""TRACE.csv (spec §4): which columns a run traces, how values print, and the per-scan
record every runner (reference interpreter, Verilator, cocotb) produces.

Keeping the column choice and the formatting here, in one place, is what lets two
runners be compared by comparing their trace files byte for byte.

A trace line is `scan,t_us,cycles` followed by one value per `Column`:
  * `Qb.n` for every Q or PQ bit the program writes (`=`, `S`, `R`, `FP`, `FN`; a PQ
    target is listed as Q), by byte then bit;
  * `QWn` for every QW the program writes with `T`, by n;
  * the `--watch` operands, each headed exactly as typed.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Iterable

from bitbyte.lang.config import Config
from bitbyte.lang.program import BIT_AREAS, INDEXED_BIT_AREAS, WORD_AREAS, Operand, Program
from bitbyte.lang.suggest import did_you_mean

FIXED_HEADER = ("scan", "t_us", "cycles")

# Mnemonics whose operand is a written bit (the trace shows the Q/PQ ones).
BIT_WRITERS = ("=", "S", "R", "FP", "FN")

# Longest names first so that "PI" is not read as "P" + "I", "IW" not as "I" + "W" ...
_AREAS = sorted(BIT_AREAS + INDEXED_BIT_AREAS + WORD_AREAS, key=len, reverse=True)
_ADDRESS_RE = re.compile(
    r"^(?P<area>" + "|".join(_AREAS) + r")\s*(?P<num>\d+)(?:\.(?P<bit>\d+))?$",
    re.IGNORECASE,
)


@dataclass(frozen=True)
class Column:
    """One traced value: the header text and the operand it shows."""

    header: str
    operand: Operand

    @property
    def is_word(self) -> bool:
        return self.operand.area in WORD_AREAS


@dataclass
class ScanRecord:
    """What one completed scan leaves in the trace, before formatting.

    end_clock is the clock right after the scan's END (= the next scan's latch clock),
    so t_us = end_clock / clock_mhz; cycles counts the scan's clocks from its PII latch
    through END.  values maps each Column.header to an int (bits 0/1, words signed or
    a raw 16-bit pattern: format_value normalises both).
    """

    scan: int
    end_clock: int
    cycles: int
    values: dict[str, int] = field(default_factory=dict)


# --- operands -------------------------------------------------------------------


def parse_address(text: str) -> Operand | None:
    """Parse an address such as `I0.0`, `I 0.0`, `MW3`, `T 2`, `FBI1` (any case).

    Returns None when the text is not shaped like an address (it may be a symbol).
    The operand's text is the input, stripped.  Ranges are not checked here.
    """
    m = _ADDRESS_RE.match(text.strip())
    if not m:
        return None
    area, num, bit = m.group("area").upper(), int(m.group("num")), m.group("bit")
    if area in BIT_AREAS:
        if bit is None:
            return None
        return Operand("bit", area, byte=num, bit=int(bit), text=text.strip())
    if bit is not None:
        return None
    return Operand("index", area, index=num, text=text.strip())


def resolve_operand(text: str, symbols: dict[str, Operand] | None) -> Operand | None:
    """An address or a declared symbol (case-insensitive, optionally in double quotes);
    None if it is neither."""
    name = text.strip()
    if len(name) >= 2 and name[0] == name[-1] == '"':
        name = name[1:-1].strip()
    op = parse_address(name)
    if op is not None:
        return op
    return (symbols or {}).get(name.upper())


def operand_fits(op: Operand, config: Config) -> bool:
    """Whether the configured build holds this operand (spec §3 ranges)."""
    if op.kind == "bit":
        return 0 <= op.byte < config.area_size(op.area) and 0 <= op.bit <= 7
    if op.kind == "index":
        return 0 <= op.index < config.area_size(op.area)
    return False


# --- columns ----------------------------------------------------------------------


def written_q_bits(program: Program) -> list[tuple[int, int]]:
    """(byte, bit) of every Q or PQ bit the program writes, sorted, no duplicates."""
    bits = {
        (ins.operand.byte, ins.operand.bit)
        for ins in program.instrs
        if ins.mnemonic in BIT_WRITERS
        and ins.operand is not None
        and ins.operand.kind == "bit"
        and ins.operand.area in ("Q", "PQ")
    }
    return sorted(bits)


def written_qwords(program: Program) -> list[int]:
    """n of every QW n the program writes with `T`, sorted, no duplicates."""
    return sorted({
        ins.operand.index
        for ins in program.instrs
        if ins.mnemonic == "T" and ins.operand is not None and ins.operand.area == "QW"
    })


def trace_columns(program: Program, watch: Iterable[str] = (),
                  symbols: dict[str, Operand] | None = None,
                  config: Config | None = None) -> list[Column]:
    """The value columns of a trace, in order (the fixed `scan,t_us,cycles` come first
    in the file but are not Columns).  symbols defaults to the program's.

    Raises ValueError naming a watch entry that is neither an address nor a symbol, or
    (with a config) an address the build cannot hold.
    """
    if symbols is None:
        symbols = program.symbols
    cols = [Column(f"Q{b}.{n}", Operand("bit", "Q", byte=b, bit=n, text=f"Q{b}.{n}"))
            for b, n in written_q_bits(program)]
    cols += [Column(f"QW{n}", Operand("index", "QW", index=n, text=f"QW{n}"))
             for n in written_qwords(program)]
    cols += [_watch_column(w, symbols, config, program.symbol_names) for w in watch]
    return cols


def _watch_column(text: str, symbols: dict[str, Operand], config: Config | None,
                  names: dict[str, str] | None = None) -> Column:
    header = text.strip()
    op = resolve_operand(header, symbols)
    if op is None or op.kind not in ("bit", "index"):
        raise ValueError(f"'{header}' is neither an address nor a bit/word symbol"
                         + (did_you_mean(header, [(names or {}).get(k, k) for k in symbols])
                            if op is None else ""))
    if config is not None and not operand_fits(op, config):
        raise ValueError(f"'{header}': operand out of range")
    return Column(header, op)


def header_line(columns: list[Column]) -> str:
    return ",".join(FIXED_HEADER + tuple(c.header for c in columns))


# --- values -------------------------------------------------------------------------


def format_value(column: Column, value: int) -> str:
    """Bits print 0/1; words print signed decimal, a 16-bit pattern read as signed
    (so a runner may hand over either -1 or 0xFFFF)."""
    if not column.is_word:
        return "1" if value else "0"
    v = int(value) & 0xFFFF
    return str(v - 0x10000 if v & 0x8000 else v)


def mhz(clock_mhz) -> Fraction:
    """The clock frequency as an exact Fraction (100.0 -> 100, '12.5' -> 25/2)."""
    if isinstance(clock_mhz, Fraction):
        return clock_mhz
    return Fraction(str(clock_mhz))


def format_decimal(x: Fraction, places: int = 6) -> str:
    """x as a decimal: exact when it terminates within `places` decimals, otherwise
    rounded half-up to `places`; trailing zeros and a trailing point dropped
    (0.62, 12.5, 3, 0.333333). The C++ harness (sim/harness.cpp fmt_ratio) prints
    with the same rule, so traces from both compare as text.

    Exact arithmetic, so a trace never shows float noise like 0.6200000000000001.
    """
    scale = 10 ** places
    scaled = abs(x) * scale
    rounded = int(scaled + Fraction(1, 2))          # half-up on the magnitude
    sign = "-" if x < 0 and rounded else ""
    whole, frac = divmod(rounded, scale)
    text = str(whole)
    if frac:
        text += "." + str(frac).rjust(places, "0").rstrip("0")
    return sign + text


def format_t_us(end_clock: int, clock_mhz) -> str:
    return format_decimal(Fraction(end_clock) / mhz(clock_mhz))


def trace_line(columns: list[Column], rec: ScanRecord, clock_mhz) -> str:
    fixed = [str(rec.scan), format_t_us(rec.end_clock, clock_mhz), str(rec.cycles)]
    return ",".join(fixed + [format_value(c, rec.values[c.header]) for c in columns])


def trace_text(columns: list[Column], rows: Iterable[ScanRecord], clock_mhz) -> str:
    """The whole TRACE.csv as one string (header + one line per scan, '\\n' ends)."""
    lines = [header_line(columns)] + [trace_line(columns, r, clock_mhz) for r in rows]
    return "\n".join(lines) + "\n"


def write_trace(path: str, columns: list[Column], rows: Iterable[ScanRecord],
                clock_mhz) -> None:
    """Write TRACE.csv; clock_mhz is needed to turn end clocks into t_us."""
    with open(path, "w", newline="") as f:
        f.write(trace_text(columns, rows, clock_mhz))


def read_trace_rows(path, columns: list[Column]) -> list[ScanRecord]:
    """Read a trace CSV written by a hardware runner back into ScanRecords (the
    end clock is recovered from t_us and cycles: end = latch + cycles, and scans
    are back to back from clock 0)."""
    records: list[ScanRecord] = []
    with open(path) as f:
        header = f.readline().strip().split(",")
        expected = ["scan", "t_us", "cycles"] + [c.header for c in columns]
        if header != expected:
            raise ValueError(f"{path}: header {header} is not {expected}")
        end = 0
        for line in f:
            cells = line.strip().split(",")
            cycles = int(cells[2])
            end += cycles
            values = {c.header: int(v) for c, v in zip(columns, cells[3:])}
            records.append(ScanRecord(int(cells[0]), end, cycles, values))
    return records
