"""STIM.csv (spec §4): the input pins of a run, as a step function of scan or of time.

    scan,I0.0,Start,IW0          t_us,I 0.1,IW3
    0,1,0,100                    0,1,0
    3,0,,-5                      0.25,0,16#FFFF

The first column is `scan` or `t_us`; the others name input bits (`Ib.n`, `I b.n`,
`PIb.n` — all the same pin), input words (`IW n`) or symbols of those (any case,
optionally in double quotes).  A value holds until a later row changes it (an empty
cell changes nothing); inputs never named are 0.  Rows are in non-decreasing order of
the first column; blank lines and lines starting with `#` are skipped.

A `t_us` row at time T reaches the hardware in the first clock n with n/f >= T, i.e.
from clock ceil(T*f); T is read as an exact decimal so no float rounding can move a
change across a clock edge.  Pins are one int, bit i = input byte*8 + bit.
"""
from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field
from fractions import Fraction

from bitbyte.lang.config import Config
from bitbyte.lang.program import Operand
from bitbyte.lang.trace import mhz, operand_fits, resolve_operand

from bitbyte.lang.errors import SourceError, read_utf8
from bitbyte.lang.suggest import did_you_mean

KINDS = ("scan", "t_us")


@dataclass(frozen=True)
class Row:
    """The full input state from `key` on (a scan number or a t_us Fraction)."""

    key: int | Fraction
    pins: int
    words: tuple[tuple[int, int], ...]   # (IW n, signed value), sorted by n


@dataclass
class Stimulus:
    """The parsed stimulus: kind is 'scan', 't_us' or 'none' (no file: all inputs 0)."""

    kind: str = "none"
    rows: list[Row] = field(default_factory=list)
    clock_mhz: Fraction = Fraction(100)
    _clock_cache: dict = field(default_factory=dict, repr=False, compare=False)

    # --- scan-based ------------------------------------------------------------

    def pins_for_scan(self, scan: int) -> int:
        """Pins during scan `scan` (scan stimuli; 0 for an empty stimulus)."""
        self._require("scan")
        row = self._row_at(self.rows, [r.key for r in self.rows], scan)
        return row.pins if row else 0

    def words_for_scan(self, scan: int) -> dict[int, int]:
        self._require("scan")
        row = self._row_at(self.rows, [r.key for r in self.rows], scan)
        return dict(row.words) if row else {}

    # --- time-based ------------------------------------------------------------

    def pins_at_clock(self, clock: int, clock_mhz=None) -> int:
        """Pins in clock `clock` (t_us stimuli; 0 for an empty stimulus)."""
        self._require("t_us")
        clocks, rows = self._clocked(clock_mhz)
        row = self._row_at(rows, clocks, clock)
        return row.pins if row else 0

    def words_at_clock(self, clock: int, clock_mhz=None) -> dict[int, int]:
        self._require("t_us")
        clocks, rows = self._clocked(clock_mhz)
        row = self._row_at(rows, clocks, clock)
        return dict(row.words) if row else {}

    def edges_between(self, after: int, upto: int, clock_mhz=None) -> tuple[int, int]:
        """(rises, falls): pins that rose / fell at some clock c, after < c <= upto,
        comparing consecutive per-clock values (the value before clock 0 is 0).
        This is what a latch in clock `upto` shows in IR / IF when the previous latch
        was in clock `after` (-1 for the first latch)."""
        self._require("t_us")
        clocks, rows = self._clocked(clock_mhz)
        value = self.pins_at_clock(after, clock_mhz) if after >= 0 else 0
        rises = falls = 0
        i = bisect.bisect_right(clocks, after)
        while i < len(clocks) and clocks[i] <= upto:
            new = rows[i].pins
            rises |= new & ~value
            falls |= value & ~new
            value = new
            i += 1
        return rises, falls

    # --- for the C++ / cocotb harness --------------------------------------------

    def events_for_harness(self, clock_mhz=None) -> list[tuple[str, int, int]]:
        """[(kind, key, pins)] with kind 'scan' (key = scan number) or 'clock' (key =
        clock number at clock_mhz); keys strictly increasing, several rows on one key
        collapsed to the last.  Before the first event every pin is 0."""
        if self.kind == "scan":
            keys, rows = [r.key for r in self.rows], self.rows
            kind = "scan"
        elif self.kind == "t_us":
            keys, rows = self._clocked(clock_mhz)
            kind = "clock"
        else:
            return []
        return [(kind, k, r.pins) for k, r in zip(keys, rows)]

    def changes(self, clock_mhz=None) -> list[tuple[str, int | Fraction]]:
        """The moments the inputs change, as the hardware sees them: ('scan', s) for a
        scan row (from the PII latch of scan s), ('clock', t_us * f) for a t_us row (an
        exact Fraction of a clock, rows within one clock collapsed to the last); a row
        that leaves every pin and word as it was is no change.  Before the first row
        every input is 0.  (The run summary's response times, bitbyte/run/response.py.)"""
        if self.kind == "scan":
            moments, rows = [("scan", r.key) for r in self.rows], self.rows
        elif self.kind == "t_us":
            f = mhz(self.clock_mhz if clock_mhz is None else clock_mhz)
            rows = self._clocked(f)[1]
            moments = [("clock", r.key * f) for r in rows]
        else:
            return []
        out, before = [], (0, ())
        for moment, r in zip(moments, rows):
            state = (r.pins, tuple((n, v) for n, v in r.words if v))
            if state != before:
                out.append(moment)
            before = state
        return out

    # --- internals ------------------------------------------------------------

    def _require(self, kind: str) -> None:
        if self.kind not in (kind, "none"):
            raise ValueError(f"a {self.kind} stimulus has no {kind} lookup")

    @staticmethod
    def _row_at(rows: list[Row], keys: list, key) -> Row | None:
        i = bisect.bisect_right(keys, key)
        return rows[i - 1] if i else None

    def _clocked(self, clock_mhz) -> tuple[list[int], list[Row]]:
        """Rows keyed by clock number, same-clock rows collapsed to the last (cached)."""
        f = mhz(self.clock_mhz if clock_mhz is None else clock_mhz)
        if f not in self._clock_cache:
            clocks: list[int] = []
            rows: list[Row] = []
            for r in self.rows:
                c = math.ceil(r.key * f)
                if clocks and clocks[-1] == c:
                    rows[-1] = r
                else:
                    clocks.append(c)
                    rows.append(r)
            self._clock_cache[f] = (clocks, rows)
        return self._clock_cache[f]


def no_stimulus(config: Config | None = None) -> Stimulus:
    """All inputs 0 for the whole run."""
    return Stimulus("none", [], mhz((config or Config()).clock_mhz))


# --- reading the file -------------------------------------------------------------


@dataclass
class _Cell:
    text: str
    col: int   # 1-based column of the cell's first non-blank character


def _cells(line: str) -> list[_Cell]:
    """Split a CSV line on commas, remembering where each (stripped) cell starts."""
    cells, start = [], 0
    for part in line.split(","):
        lead = len(part) - len(part.lstrip())
        cells.append(_Cell(part.strip(), start + lead + 1))
        start += len(part) + 1
    return cells


class _Reader:
    """Reads one file; `fail` raises a SourceError at a cell."""

    def __init__(self, path: str, symbols: dict[str, Operand] | None, config: Config,
                 names: dict[str, str] | None = None):
        self.path, self.symbols, self.config = path, symbols or {}, config
        self.names = names or {}          # the symbols as declared (for hints)
        self.line_no, self.line = 0, ""

    def fail(self, cell: _Cell | None, message: str):
        col = cell.col if cell else 1
        raise SourceError(self.path, self.line_no, col, message, self.line)

    def header(self, cells: list[_Cell]) -> tuple[str, list[Operand]]:
        kind = cells[0].text.lower()
        if kind not in KINDS:
            self.fail(cells[0], "first column must be 'scan' or 't_us'")
        ops, seen = [], {}
        for cell in cells[1:]:
            op = self.input_operand(cell)
            key = (op.area, op.bit_number if op.kind == "bit" else op.index)
            if key in seen:
                self.fail(cell, f"input '{cell.text}' named twice (column {seen[key]})")
            seen[key] = cell.col
            ops.append(op)
        return kind, ops

    def input_operand(self, cell: _Cell) -> Operand:
        if not cell.text:
            self.fail(cell, "empty column name")
        op = resolve_operand(cell.text, self.symbols)
        if op is None:
            self.fail(cell, f"unknown operand '{cell.text}'"
                      + did_you_mean(cell.text, [self.names.get(k, k) for k in self.symbols]))
        if op.kind == "bit" and op.area in ("I", "PI"):
            op = Operand("bit", "I", byte=op.byte, bit=op.bit, text=cell.text)
        elif not (op.kind == "index" and op.area == "IW"):
            self.fail(cell, f"'{cell.text}' is not an input (I b.n or IW n)")
        if not operand_fits(op, self.config):
            self.fail(cell, f"operand out of range: '{cell.text}'")
        return op

    def key(self, kind: str, cell: _Cell) -> int | Fraction:
        text = cell.text
        try:
            if kind == "scan":
                if not text.isdigit():
                    raise ValueError
                return int(text)
            value = Fraction(text)
            if value < 0 or not _plain_decimal(text):
                raise ValueError
            return value
        except (ValueError, ZeroDivisionError):
            what = "scan number" if kind == "scan" else "time in µs"
            self.fail(cell, f"'{text}' is not a {what} (a non-negative number)")

    def bit_value(self, cell: _Cell) -> int:
        if cell.text not in ("0", "1"):
            self.fail(cell, f"a bit is 0 or 1, not '{cell.text}'")
        return int(cell.text)

    def word_value(self, cell: _Cell) -> int:
        text = cell.text
        try:
            if text.upper().startswith("16#"):
                v = int(text[3:].replace("_", ""), 16)
                if not 0 <= v <= 0xFFFF or text[3:].startswith(("-", "+")):
                    raise ValueError
                return v - 0x10000 if v & 0x8000 else v
            v = int(text)
            if not -32768 <= v <= 32767:
                raise ValueError
            return v
        except ValueError:
            self.fail(cell, f"a word is -32768..32767 or 16#0..16#FFFF, not '{text}'")


def _plain_decimal(text: str) -> bool:
    """Digits with at most one '.', as a time is written (no 1/3, no 1e3, no sign)."""
    body = text.replace(".", "", 1)
    return body.isdigit()


def load_stimulus(path: str, symbols: dict[str, Operand] | None = None,
                  config: Config | None = None,
                  names: dict[str, str] | None = None) -> Stimulus:
    """Read STIM.csv; every malformed line raises SourceError(path, line, col, ...).
    names: the symbols as declared (Program.symbol_names), for the hints."""
    config = config or Config()
    text = read_utf8(path, "a stimulus is UTF-8 text")   # as open(newline=""): line ends kept
    return parse_stimulus(text, path, symbols, config, names)


def parse_stimulus(text: str, path: str = "<stimulus>",
                   symbols: dict[str, Operand] | None = None,
                   config: Config | None = None,
                   names: dict[str, str] | None = None) -> Stimulus:
    """The parser behind load_stimulus, on a string."""
    config = config or Config()
    rd = _Reader(path, symbols, config, names)
    kind, ops = None, []
    pins, words = 0, {}
    rows: list[Row] = []
    for line_no, raw in enumerate(text.split("\n"), start=1):
        line = raw[:-1] if raw.endswith("\r") else raw
        rd.line_no, rd.line = line_no, line
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        cells = _cells(line)
        if kind is None:
            kind, ops = rd.header(cells)
            continue
        if len(cells) > len(ops) + 1:
            rd.fail(cells[len(ops) + 1], f"more values than columns ({len(ops) + 1})")
        key = rd.key(kind, cells[0])
        if rows and key < rows[-1].key:
            rd.fail(cells[0], f"rows must be in non-decreasing {kind} order")
        for op, cell in zip(ops, cells[1:]):
            if not cell.text:
                continue   # empty cell: the value holds
            if op.kind == "bit":
                mask = 1 << op.bit_number
                pins = pins | mask if rd.bit_value(cell) else pins & ~mask
            else:
                words[op.index] = rd.word_value(cell)
        row = Row(key, pins, tuple(sorted(words.items())))
        if rows and rows[-1].key == key:
            rows[-1] = row             # several rows for one key: the last one counts
        else:
            rows.append(row)
    if kind is None:
        rd.line_no, rd.line = 1, ""
        rd.fail(None, "empty stimulus: expected a header 'scan,...' or 't_us,...'")
    return Stimulus(kind, rows, mhz(config.clock_mhz))
