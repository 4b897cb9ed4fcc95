"""Multi-core plants (spec §7, seed 000): the plant file and the linker.

`load_plant(path)` reads the plant TOML into a `Plant`; `link(plant)` parses every
core's program, checks the shared variables (seed 000 §3.3) and lays them out in the
shared memory (§3.4), giving a `SharedMap` with each core's precycle / postcycle copy
plan (§3.5).  `format_map` is what `bitbyte link` prints.  Every problem is a
`SourceError` (`file:line:col: message`, the line, a caret), never a traceback.

The rules (docs/multicore.md):

* A shared variable is declared in `VAR_GLOBAL` by every core that uses it, with
  `WRITE` in exactly one core (the writer) and `READ` in the others; every
  declaration agrees on its kind (bit: local copy in M; word: local copy in MW).
  Declarations are taken in plant order (cores as listed, each program top to
  bottom).  Errors: a second `WRITE` at that declaration; no `WRITE` at the first
  reader's declaration; a kind that differs from the first declaration's at the one
  that differs; a name twice in one program is the parser's (duplicate symbol).
  When several declarations conflict, the first in plant order is reported.
* The shared memory is an array of 32-bit words (`SHn`); a bit lives at `SHn.b`
  (b = 0..31), a word (INT) takes a whole shared word (`SHn`).
* `compact`: one sector per writer core (`SH_<core>`), in plant order, from word 0
  on, each a contiguous word range: the writer's bits first, packed 32 per word in
  declaration order, then its words, one each.  A writer's postcycle is one burst over its whole
  sector; a reader's precycle is one burst per sector it reads from, over the words
  from the first to the last it needs there (its whole sector when it reads all).
  Local copies stay where the program declares them: a burst is a contiguous
  shared range with a gather / scatter list on the local side.
* `random`: every variable has a shared word of its own (a bit at bit 0), at
  crc32(NAME) mod R with R the smallest power of two >= max(16, 4 * variables),
  names taken in alphabetical order, probing upwards past words that are taken or
  next to a taken one: spread (no two variables in neighbouring words),
  deterministic, collision-free.  Every copy is a single one (one variable): a
  postcycle in the core's declaration order, a precycle writer by writer (plant order),
  each in the core's declaration order.  There are no sectors.
"""
from __future__ import annotations

import math
import os
import re
import zlib
from dataclasses import dataclass, field
from fractions import Fraction

from bitbyte.lang.config import Config
from bitbyte.lang.definition import DEF
from bitbyte.lang.errors import SourceError, read_utf8
from bitbyte.lang.program import GlobalVar, Program
from bitbyte.run.prepare import MODE_EXCHANGES, PLANT_MODES, check_mode

try:
    import tomllib
except ModuleNotFoundError:                  # Python 3.10: the same parser as tomli
    try:
        import tomli as tomllib
    except ModuleNotFoundError:
        tomllib = None

PLANT_KEYS = ("clock_mhz", "layout", "protection", "core")
CORE_KEYS = ("name", "program", "period_us", "stimulus", "mode", "exchange")
LAYOUTS = ("compact", "random")
PROTECTIONS = DEF.protections
PLANT_EXCHANGES = tuple(dict.fromkeys(      # what a plant core's `exchange` may say: a
    e for m in PLANT_MODES for e in MODE_EXCHANGES[m]))   # serial core ignores it
DEFAULT_CLOCK_MHZ = 100
MAX_CLOCK_MHZ = 10_000        # sanity bounds (docs/multicore.md)
MAX_PERIOD_US = 2 ** 31 - 1
BITS_PER_WORD = 32            # bits packed into one shared word
RANDOM_MIN_WORDS = 16         # smallest region of the random layout

_CORE_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_-]*\Z")


# --------------------------------------------------------------------------------------
# The plant file
# --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class CoreSpec:
    """One `[[core]]` of the plant file.

    program / stimulus: paths resolved against the plant file's folder (as the
    user would type them from the current directory); program_text: as written.
    line/col: the `[[core]]` header (1:1 for an inline table).  mode: serial or
    parallel; exchange: the one it runs with (as `run --mode --exchange` resolves
    them: bitbyte.run.prepare.check_mode; handshake for a serial core).
    """

    name: str
    program: str
    period_us: int
    stimulus: str | None = None
    line: int = 0
    col: int = 0
    program_text: str = ""
    mode: str = "serial"
    exchange: str = "handshake"


@dataclass
class Plant:
    """A checked plant file.  clock_mhz is exact (a whole number of kHz)."""

    path: str
    clock_mhz: Fraction
    layout: str
    protection: str
    cores: list[CoreSpec]
    # `file:line:col: warning: ...` for the caller to print (stderr): an `exchange` on
    # a serial core, which ignores it
    warnings: list[SourceError] = field(default_factory=list)

    def config(self) -> Config:
        """The build every core's program is checked against."""
        return Config(clock_mhz=float(self.clock_mhz))


class _TomlText:
    """Where keys and table headers are in the plant text, for error positions.

    tomllib gives values, not positions, so the text is scanned line by line: a
    table header `[x]` / `[[x]]` opens a context (("x",) / ("x", i) for the i-th
    array table, i from 0), a line `key = value` records the key's and the value's
    column in the current context.  Multi-line strings are skipped.  A key not found
    (inline tables, arrays spanning lines) falls back to its table's header, then to
    1:1.
    """

    _HEADER = re.compile(r"\s*(\[\[?)([^\]\n]*)\]")
    _KEY = re.compile(r"""(\s*)([A-Za-z0-9_-]+|"[^"\n]*"|'[^'\n]*')"""
                      r"""((?:\s*\.\s*(?:[A-Za-z0-9_-]+|"[^"\n]*"|'[^'\n]*'))*)\s*=\s*""")

    def __init__(self, path: str, text: str):
        self.path = path
        self.lines = [ln[:-1] if ln.endswith("\r") else ln for ln in text.split("\n")]
        self._keys: dict[tuple, tuple[int, int, int]] | None = None
        self._headers: dict[tuple, tuple[int, int]] = {}

    @property
    def keys(self) -> dict[tuple, tuple[int, int, int]]:
        """(context..., key) -> (line, key column, value column)."""
        if self._keys is None:
            self._scan()
        return self._keys

    @property
    def headers(self) -> dict[tuple, tuple[int, int]]:
        """context -> (line, column) of its header."""
        if self._keys is None:
            self._scan()
        return self._headers

    def _scan(self) -> None:
        self._keys = {}
        counts: dict[str, int] = {}
        ctx: tuple = ()
        in_string = ""
        for number, line in enumerate(self.lines, start=1):
            if in_string:
                if line.count(in_string) % 2 == 1:
                    in_string = ""
                continue
            header = self._HEADER.match(line)
            key = None if header else self._KEY.match(line)
            if header:
                name = ".".join(part.strip().strip("\"'")
                                for part in header.group(2).split("."))
                if header.group(1) == "[[":
                    ctx = (name, counts.get(name, 0))
                    counts[name] = ctx[1] + 1
                else:
                    ctx = (name,)
                self._headers.setdefault(ctx, (number, len(line) - len(line.lstrip()) + 1))
            elif key:
                name = key.group(2).strip("\"'")
                self._keys.setdefault(ctx + (name,), (number, len(key.group(1)) + 1,
                                                     key.end() + 1))
            for delim in ('"""', "'''"):
                if line.count(delim) % 2 == 1:
                    in_string = delim
                    break

    def error(self, line: int, col: int, message: str) -> SourceError:
        text = self.lines[line - 1] if 1 <= line <= len(self.lines) else ""
        return SourceError(self.path, line, col, message, text)

    def at_key(self, ctx: tuple, key: str, message: str, value: bool = False) -> SourceError:
        """An error at `key` of table ctx (at its value when value=True)."""
        found = self.keys.get(ctx + (key,))
        if found:
            return self.error(found[0], found[2] if value else found[1], message)
        return self.at_table(ctx, message)

    def at_table(self, ctx: tuple, message: str) -> SourceError:
        """An error at the header of table ctx (or where the table is named)."""
        if ctx in self.headers:
            return self.error(*self.headers[ctx], message)
        if ctx and ctx[:1] != ctx and (ctx[0],) in self.keys:     # core = [{...}]
            line, col, _ = self.keys[(ctx[0],)]
            return self.error(line, col, message)
        return self.error(1, 1, message)

    def at_name(self, name: str, message: str) -> SourceError:
        """An error where top-level `name` is defined: `name = ...` or `[name]`."""
        if ((name,)) in self.keys:
            line, col, _ = self.keys[(name,)]
            return self.error(line, col, message)
        for ctx in self.headers:
            if ctx[0] == name:
                return self.error(*self.headers[ctx], message)
        return self.error(1, 1, message)


# TOML value types as the messages name them (bool before int: a bool is an int)
_TYPE_NAMES = ((bool, "a boolean"), (int, "an integer"), (float, "a float"),
               (str, "a string"), (list, "an array"), (dict, "a table"))


def _type_name(value) -> str:
    return next((name for t, name in _TYPE_NAMES if isinstance(value, t)), "a date/time")


def _read_text(path: str) -> str:
    """The plant file as text (UTF-8); unreadable or undecodable: SourceError."""
    return read_utf8(path, "a plant file is UTF-8 text (TOML)")


_TOML_POS = re.compile(r"\s*\(at line (\d+), column (\d+)\)\s*$")
_TOML_END = re.compile(r"\s*\(at end of document\)\s*$")


def _toml_error(text: _TomlText, exc: Exception) -> SourceError:
    """tomllib's message `Invalid value (at line 3, column 9)` as file:3:9."""
    message = str(exc) or type(exc).__name__
    pos = _TOML_POS.search(message)
    if pos:
        line, col = int(pos.group(1)), int(pos.group(2))
        message = message[: pos.start()]
    elif _TOML_END.search(message):
        message = message[: _TOML_END.search(message).start()] + " at the end of the file"
        line = len(text.lines)
        while line > 1 and text.lines[line - 1] == "":
            line -= 1
        col = len(text.lines[line - 1]) + 1 if text.lines else 1
    else:                                  # e.g. int()'s digit limit: no position
        line, col = 1, 1
        long_number = re.search(r"[0-9_]{4000,}", "\n".join(text.lines))
        if long_number:
            before = "\n".join(text.lines)[: long_number.start()]
            line = before.count("\n") + 1
            col = long_number.start() - (before.rfind("\n") + 1) + 1
    if "integer string conversion" in message:
        message = "integer too long"
    message = message[:1].lower() + message[1:]
    return text.error(line, col, f"TOML syntax error: {message}")


def load_plant(path: str) -> Plant:
    """Read and check the plant file (spec §7).  Raises only SourceError."""
    if tomllib is None:
        raise SourceError(path, 0, 0, "reading a plant file needs Python 3.11 (tomllib) "
                                      "or the tomli package")
    raw = _read_text(path)
    text = _TomlText(path, raw)
    try:
        data = tomllib.loads(raw)
    except RecursionError:
        raise text.error(1, 1, "TOML syntax error: nested too deeply") from None
    except (ValueError, TypeError, IndexError, KeyError) as exc:   # TOMLDecodeError too
        raise _toml_error(text, exc) from None

    for key in data:
        if key not in PLANT_KEYS:
            raise text.at_name(key, f"unknown key `{key}` in the plant file (known: "
                                    f"{', '.join(PLANT_KEYS)})")
    clock = _clock(text, data.get("clock_mhz", DEFAULT_CLOCK_MHZ))
    layout = _choice(text, (), data, "layout", LAYOUTS)
    protection = _choice(text, (), data, "protection", PROTECTIONS)
    tables = data.get("core")
    if tables is None:
        raise text.error(1, 1, "no [[core]] in the plant file: a plant needs at least "
                               "one core (`[[core]]` with name, program, period_us)")
    if not isinstance(tables, list) or not all(isinstance(t, dict) for t in tables):
        raise text.at_name("core", "`core` must be an array of tables: write each core "
                                   "as a `[[core]]` table")
    if not tables:
        raise text.at_name("core", "no core in the plant file: a plant needs at least "
                                   "one `[[core]]`")
    base = os.path.dirname(path)
    cores: list[CoreSpec] = []
    warnings: list[SourceError] = []
    first_line: dict[str, tuple[str, int]] = {}
    for i, table in enumerate(tables):
        core = _core(text, ("core", i), table, base)
        if "exchange" in table and core.mode == "serial":
            warnings.append(text.at_key(
                ("core", i), "exchange",
                f"warning: `exchange` is ignored: core `{core.name}` runs in serial mode "
                "(add `mode = \"parallel\"` to use the exchange)"))
        key = core.name.lower()
        if key in first_line:
            first, line = first_line[key]
            raise text.at_key(("core", i), "name",
                              f"duplicate core name `{core.name}` (core `{first}` is "
                              f"declared at line {line}): core names are unique "
                              "(case-insensitive)", value=True)
        first_line[key] = (core.name, text.keys.get(("core", i, "name"), (core.line,))[0])
        cores.append(core)
    return Plant(path, clock, layout, protection, cores, warnings)


def _clock(text: _TomlText, value) -> Fraction:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise text.at_key((), "clock_mhz", f"`clock_mhz` must be a number (MHz), not "
                                           f"{_type_name(value)}", value=True)
    if (isinstance(value, float) and not math.isfinite(value)) or value <= 0 \
            or value > MAX_CLOCK_MHZ:
        shown = value if isinstance(value, float) or value < 10 ** 12 else "too large"
        raise text.at_key((), "clock_mhz", "`clock_mhz` must be a positive number of "
                                           f"MHz up to {MAX_CLOCK_MHZ}, not {shown}",
                          value=True)
    f = Fraction(str(value)) if isinstance(value, float) else Fraction(value)
    if (f * 1000).denominator != 1:
        raise text.at_key((), "clock_mhz", "`clock_mhz` must be a whole number of kHz "
                                           "(the timers' 1 ms time base counts whole "
                                           "clocks)", value=True)
    return f


def _choice(text: _TomlText, ctx: tuple, data: dict, key: str, allowed: tuple[str, ...],
            other: tuple[tuple[str, ...], str] = ((), "")) -> str:
    """The value of `key` in table ctx: one of `allowed`, the first when absent.
    other: (values the single CPU takes there but a plant does not, why not)."""
    value = data.get(key, allowed[0])
    if not isinstance(value, str):
        raise text.at_key(ctx, key, f"`{key}` must be a string ({' | '.join(allowed)}), "
                                    f"not {_type_name(value)}", value=True)
    if value not in allowed:
        why = f" ({other[1]})" if value in other[0] else ""
        raise text.at_key(ctx, key, f"bad value `{value}` for `{key}`: "
                                    f"{' | '.join(allowed)}{why}", value=True)
    return value


def _core(text: _TomlText, ctx: tuple, table: dict, base: str) -> CoreSpec:
    """One [[core]] table, checked."""
    number = ctx[1] + 1
    for key in table:
        if key not in CORE_KEYS:
            raise text.at_key(ctx, key, f"unknown key `{key}` in [[core]] #{number} "
                                        f"(known: {', '.join(CORE_KEYS)})")
    for key in ("name", "program", "period_us"):
        if key not in table:
            who = f"`{table['name']}`" if isinstance(table.get("name"), str) \
                else f"#{number}"
            raise text.at_table(ctx, f"missing `{key}` in [[core]] {who} (a core needs "
                                     "name, program and period_us)")

    def string(key: str) -> str:
        value = table[key]
        if not isinstance(value, str):
            raise text.at_key(ctx, key, f"`{key}` must be a string, not "
                                        f"{_type_name(value)}", value=True)
        if value == "":
            raise text.at_key(ctx, key, f"`{key}` must not be empty", value=True)
        return value

    name = string("name")
    if not _CORE_NAME.match(name):
        raise text.at_key(ctx, "name", f"bad core name `{name}`: letters, digits, `_` "
                                       "and `-`, starting with a letter or `_` (it names "
                                       "trace files and `--watch CORE.ADDR`)", value=True)
    period = table["period_us"]
    if isinstance(period, bool) or not isinstance(period, int):
        raise text.at_key(ctx, "period_us", f"`period_us` must be a whole number of "
                                            f"µs, not {_type_name(period)}", value=True)
    if not 0 <= period <= MAX_PERIOD_US:
        shown = str(period) if abs(period) < 10 ** 12 else "too large"
        raise text.at_key(ctx, "period_us", f"`period_us` out of range: {shown} (0.."
                                            f"{MAX_PERIOD_US} µs)", value=True)
    program_text = string("program")
    program = _existing(text, ctx, "program", program_text, base, "program")
    stimulus = None
    if "stimulus" in table:
        stimulus = _existing(text, ctx, "stimulus", string("stimulus"), base, "stimulus")
    mode = _choice(text, ctx, table, "mode", PLANT_MODES,
                   (tuple(MODE_EXCHANGES), "free-running plant cores are not built"))
    exchange = _choice(text, ctx, table, "exchange", PLANT_EXCHANGES,
                       (DEF.exchanges, "a free-running exchange: a plant core runs in "
                                       "serial or parallel mode"))
    header = text.headers.get(ctx, (1, 1))
    return CoreSpec(name, program, period, stimulus, header[0], header[1], program_text,
                    mode, check_mode(mode, exchange if "exchange" in table else None))


def _existing(text: _TomlText, ctx: tuple, key: str, written: str, base: str,
              what: str) -> str:
    """`written` resolved against the plant's folder; it must be a file."""
    resolved = os.path.join(base, written)
    try:
        ok = os.path.isfile(resolved)
    except (OSError, ValueError):          # NUL in the name, name too long, ...
        ok = False
    if not ok:
        raise text.at_key(ctx, key, f"{what} file `{written}` not found (looked for "
                                    f"{resolved})", value=True)
    return resolved


# --------------------------------------------------------------------------------------
# The shared-memory map
# --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Sector:
    """compact layout: the words [start, start + length) written by core `writer`.
    name is `SH_<writer>` (seed 000 calls the sector written by project i SH_i)."""

    name: str
    writer: str
    start: int
    length: int


@dataclass
class SharedVar:
    """One shared variable of the plant.

    word: its shared word; bit: 0..31 for a bit, None for a word.  sector: the
    compact layout's sector name, None with random.  decls: core -> declaration.
    """

    name: str
    kind: str
    writer: str
    readers: list[str]
    word: int
    bit: int | None
    sector: str | None
    decls: dict[str, GlobalVar] = field(default_factory=dict)

    def address(self) -> str:
        """`SH3.5` (bit 5 of shared word 3) or `SH3` (a word)."""
        return f"SH{self.word}" if self.bit is None else f"SH{self.word}.{self.bit}"


@dataclass(frozen=True)
class CopyItem:
    """One variable carried by a copy: shared word.bit <-> local operand address."""

    name: str
    kind: str
    word: int
    bit: int | None
    local: str

    def shared(self) -> str:
        return f"SH{self.word}" if self.bit is None else f"SH{self.word}.{self.bit}"


@dataclass(frozen=True)
class Copy:
    """One copy operation of a precycle or postcycle: the shared words
    [start, start + length) and the variables it moves.  sector is set for a burst
    (compact layout), None for a single copy (random layout: one variable)."""

    sector: str | None
    start: int
    length: int
    items: tuple[CopyItem, ...]

    @property
    def is_burst(self) -> bool:
        return self.sector is not None


@dataclass
class CorePlan:
    """One core's side of the link: its program and its two copy lists.
    precycle: shared -> local, before the PII latch (the READ variables);
    postcycle: local -> shared, after the PIO update (the WRITE variables)."""

    name: str
    program: Program
    precycle: list[Copy]
    postcycle: list[Copy]


@dataclass
class SharedMap:
    """The linked plant: variables in shared-address order, sectors (compact),
    one CorePlan per core in plant order, and the shared words in use."""

    plant: Plant
    layout: str
    variables: list[SharedVar]
    sectors: list[Sector]
    cores: list[CorePlan]
    size_words: int

    def var(self, name: str) -> SharedVar:
        key = name.upper()
        for v in self.variables:
            if v.name == key:
                return v
        raise KeyError(name)

    def core(self, name: str) -> CorePlan:
        for c in self.cores:
            if c.name == name:
                return c
        raise KeyError(name)


def link(plant: Plant) -> SharedMap:
    """Parse every core's program, check the shared variables, lay them out.
    Raises only SourceError (in a program, or in the plant file)."""
    from bitbyte.lang.parser import parse_file

    config = plant.config()
    programs = [(core, parse_file(core.program, config)) for core in plant.cores]
    for core, program in programs:
        if program.startup_scans:       # an S7 OB 100 (docs/s7.md): single CPU only
            first = program.instrs[program.labels["OB100"]]
            raise SourceError(core.program, first.line, first.col,
                              f"unsupported: OB 100 in a plant's core ({core.name}): the "
                              "plant runs every core's scans from t = 0 (OB 100 runs "
                              "with `bitbyte run` of one program)", first.source)
    order: list[str] = []                                   # names, first seen first
    decls: dict[str, list[tuple[int, str, Program, GlobalVar]]] = {}
    for index, (core, program) in enumerate(programs):
        for g in program.globals:
            if g.name not in decls:
                decls[g.name] = []
                order.append(g.name)
            decls[g.name].append((index, core.name, program, g))
    _check_rules(decls)

    variables = []
    for name in order:
        entries = decls[name]
        writer = next(core for _, core, _, g in entries if g.access == "WRITE")
        variables.append(SharedVar(
            name, entries[0][3].kind, writer,
            [core for _, core, _, g in entries if g.access == "READ"], 0, None, None,
            {core: g for _, core, _, g in entries}))
    if plant.layout == "compact":
        sectors, size = _layout_compact(plant, variables)
    else:
        sectors, size = [], _layout_random(variables)
    variables.sort(key=lambda v: (v.word, -1 if v.bit is None else v.bit))
    order = {core.name: k for k, (core, _) in enumerate(programs)}
    plans = [CorePlan(core.name, program, *_copies(plant.layout, core.name, program,
                                                   variables, sectors, order))
             for core, program in programs]
    return SharedMap(plant, plant.layout, variables, sectors, plans, size)


def _where(program: Program, g: GlobalVar) -> str:
    return f"{program.path}:{g.line}:{g.col}"


def _check_rules(decls: dict[str, list[tuple[int, str, Program, GlobalVar]]]) -> None:
    """Seed 000 §3.3 over all declarations; the first conflict in plant order."""
    problems: list[tuple[tuple[int, int, int], SourceError]] = []

    def problem(index: int, program: Program, g: GlobalVar, message: str) -> None:
        err = SourceError(program.path, g.line, g.col, message, g.source)
        problems.append(((index, g.line, g.col), err))

    for name, entries in decls.items():
        _, first_core, first_prog, first = entries[0]
        writer = None
        for index, core, program, g in entries:
            if g.kind != first.kind:
                problem(index, program, g,
                        f"kinds differ: shared variable `{g.text}` is a {g.kind} here "
                        f"({g.operand.address()}) but a {first.kind} in core "
                        f"`{first_core}` ({_where(first_prog, first)}: "
                        f"{first.operand.address()}); every core must agree on its kind")
            elif g.access == "WRITE":
                if writer is not None:
                    wcore, wprog, wg = writer
                    problem(index, program, g,
                            f"two writers: core `{core}` declares shared variable "
                            f"`{g.text}` WRITE, but core `{wcore}` already writes it "
                            f"({_where(wprog, wg)}); exactly one core writes a shared "
                            "variable")
                else:
                    writer = (core, program, g)
        if writer is None and all(g.access == "READ" for *_, g in entries):
            index, core, program, g = entries[0]
            readers = ", ".join(f"`{c}`" for _, c, _, _ in entries)
            cores = "core" if len(entries) == 1 else "cores"
            problem(index, program, g,
                    f"no writer: shared variable `{g.text}` is read by {cores} "
                    f"{readers} but no core declares it WRITE; exactly one core "
                    "writes a shared variable")
    if problems:
        raise min(problems, key=lambda p: p[0])[1]


def _layout_compact(plant: Plant, variables: list[SharedVar]) -> tuple[list[Sector], int]:
    """One sector per writer core in plant order: its bits (32 per word), then its
    words; variables in the writer's declaration order."""
    sectors, start = [], 0
    for core in plant.cores:
        own = sorted((v for v in variables if v.writer == core.name),
                     key=lambda v: (v.decls[core.name].line, v.decls[core.name].col))
        if not own:
            continue
        name = f"SH_{core.name}"
        word = start
        bits = [v for v in own if v.kind == "bit"]
        for i, v in enumerate(bits):
            v.word, v.bit, v.sector = start + i // BITS_PER_WORD, i % BITS_PER_WORD, name
        word = start + -(-len(bits) // BITS_PER_WORD)
        for v in (v for v in own if v.kind == "word"):
            v.word, v.bit, v.sector = word, None, name
            word += 1
        sectors.append(Sector(name, core.name, start, word - start))
        start = word
    return sectors, start


def random_region(count: int) -> int:
    """Words the random layout spreads `count` variables over."""
    size = RANDOM_MIN_WORDS
    while size < 4 * count:
        size *= 2
    return size


def _layout_random(variables: list[SharedVar]) -> int:
    """Each variable in a word of its own at crc32(name) mod R, probing upwards
    (wrapping) past any word that is taken or next to a taken one, so that no two
    variables are neighbours: every one needs a copy of its own.  With R >= 4n a
    free word always exists (each variable blocks at most three)."""
    size = random_region(len(variables))
    taken: set[int] = set()
    for v in sorted(variables, key=lambda v: v.name):
        word = zlib.crc32(v.name.encode("ascii")) % size
        while taken & {word - 1, word, word + 1}:
            word = (word + 1) % size
        taken.add(word)
        v.word, v.bit, v.sector = word, (0 if v.kind == "bit" else None), None
    return size


def _copies(layout: str, core: str, program: Program, variables: list[SharedVar],
            sectors: list[Sector], order: dict[str, int]) -> tuple[list[Copy], list[Copy]]:
    """(precycle, postcycle) of one core. order: the plant order of the cores."""
    by_name = {v.name: v for v in variables}

    def item(g: GlobalVar) -> CopyItem:
        v = by_name[g.name]
        return CopyItem(v.name, v.kind, v.word, v.bit, g.operand.address())

    reads = [item(g) for g in program.globals if g.access == "READ"]
    writes = [item(g) for g in program.globals if g.access == "WRITE"]
    if layout == "random":
        # A precycle takes its writers one after the other (plant order; each writer's
        # variables in this core's declaration order): then it copies one writer's
        # variables in one stretch, shorter than that writer's scan plus postcycle, so
        # ping-pong cannot tear (docs/multicore.md, Protection).
        reads.sort(key=lambda i: order[by_name[i.name].writer])
        return ([Copy(None, i.word, 1, (i,)) for i in reads],
                [Copy(None, i.word, 1, (i,)) for i in writes])

    def bursts(items: list[CopyItem], whole: bool) -> list[Copy]:
        out = []
        for sector in sectors:
            mine = sorted((i for i in items if by_name[i.name].sector == sector.name),
                          key=lambda i: (i.word, -1 if i.bit is None else i.bit))
            if not mine:
                continue
            if whole:
                start, length = sector.start, sector.length
            else:
                start, length = mine[0].word, mine[-1].word - mine[0].word + 1
            out.append(Copy(sector.name, start, length, tuple(mine)))
        return out

    return bursts(reads, whole=False), bursts(writes, whole=True)


# --------------------------------------------------------------------------------------
# What `bitbyte link` prints
# --------------------------------------------------------------------------------------

def _table(header: list[str], rows: list[list[str]]) -> list[str]:
    widths = [max(len(r[i]) for r in [header] + rows) for i in range(len(header))]
    return ["  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip()
            for r in [header] + rows]


def _mhz(f: Fraction) -> str:
    return str(f.numerator) if f.denominator == 1 else f"{float(f):g}"


def _copy_text(copy: Copy, direction: str) -> str:
    if direction == "pre":
        moves = ", ".join(f"{i.shared()} -> {i.local} ({i.name})" for i in copy.items)
    else:
        moves = ", ".join(f"{i.local} -> {i.shared()} ({i.name})" for i in copy.items)
    if copy.is_burst:
        span = f"SH{copy.start}" if copy.length == 1 else \
            f"SH{copy.start}..SH{copy.start + copy.length - 1}"
        words = f"{copy.length} word{'s' if copy.length != 1 else ''}"
        return f"burst {copy.sector} [{span}, {words}]: {moves}"
    return f"copy {moves}"


def format_map(shared: SharedMap) -> str:
    """The text of `bitbyte link`: plant, cores, the map, sectors, copy plans."""
    plant = shared.plant
    out = [f"plant {plant.path}: {len(plant.cores)} core{'s' if len(plant.cores) != 1 else ''}"
           f", layout {plant.layout}, protection {plant.protection}, clock "
           f"{_mhz(plant.clock_mhz)} MHz", ""]
    out += _table(["core", "program", "period_us", "stimulus", "mode", "exchange"],
                  [[c.name, c.program, str(c.period_us), c.stimulus or "-", c.mode,
                    "-" if c.mode == "serial" else c.exchange] for c in plant.cores])
    out += ["", f"shared memory: {len(shared.variables)} variable"
                f"{'s' if len(shared.variables) != 1 else ''} in {shared.size_words} "
                f"word{'s' if shared.size_words != 1 else ''} (32 bits each)"]
    if shared.variables:
        out += _table(["name", "kind", "writer", "readers", "address", "sector"],
                      [[v.name, v.kind, v.writer, ",".join(v.readers) or "-",
                        v.address(), v.sector or "-"] for v in shared.variables])
    if shared.sectors:
        out += ["", "sectors"]
        out += _table(["sector", "writer", "start", "words"],
                      [[s.name, s.writer, f"SH{s.start}", str(s.length)]
                       for s in shared.sectors])
    out += ["", "copy plan"]
    for plan in shared.cores:
        out.append(f"{plan.name}:")
        for label, copies, direction in (("precycle", plan.precycle, "pre"),
                                         ("postcycle", plan.postcycle, "post")):
            if not copies:
                out.append(f"  {label}: nothing")
                continue
            out.append(f"  {label}:")
            out += [f"    {_copy_text(c, direction)}" for c in copies]
    return "\n".join(out) + "\n"
