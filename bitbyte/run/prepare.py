"""Everything `bitbyte run` does before a simulator starts: check the run settings,
parse the program, encode it (or partition it for parallel and free-running mode), load
the stimulus and name the trace columns; the result is a RunJob (bitbyte.run.runjob)
that every simulator driver runs alike.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from fractions import Fraction

from bitbyte.compiler.partition import partition
from bitbyte.encoding.encoder import constant_pool, encode_words
from bitbyte.lang import trace as tr
from bitbyte.lang.config import Config
from bitbyte.lang.costs import COST_TABLES
from bitbyte.lang.errors import SourceError, UsageError
from bitbyte.lang.parser import parse_file
from bitbyte.lang.program import Program
from bitbyte.lang.stimulus import Stimulus, load_stimulus, no_stimulus
from bitbyte.run.runjob import RunJob, hw_column

DEFAULT_SCANS = 10


def parse_clock_mhz(text: str) -> Fraction:
    try:
        f = Fraction(text)
    except (ValueError, ZeroDivisionError):
        raise UsageError(f"--clock-mhz: not a number: {text!r}") from None
    if f <= 0 or (f * 1000).denominator != 1:
        raise UsageError("--clock-mhz must be positive and a whole number of kHz "
                         "(the timers' 1 ms time base counts whole clocks)")
    return f


# The exchange circuits each mode runs with, its default first (spec §2, §4): the one
# place that says which `--exchange` goes with which `--mode` (the single CPU's `run`,
# a plant core's `mode` / `exchange`, the benches).  Serial mode uses no exchange
# circuit and ignores the setting; a plant core runs in serial or parallel mode only.
# The C++ harnesses (sim/harness.cpp, sim/plant_harness.cpp) accept any mode/exchange
# pair they are given: this table is the only check.
MODE_EXCHANGES: dict[str, tuple[str, ...]] = {
    "serial": ("handshake",),
    "parallel": ("handshake", "queue"),        # strict: the writer or reader waits
    "free": ("marker", "queue-free"),          # free-running: nobody waits
}
MODES = tuple(MODE_EXCHANGES)
# --tc-path: how a timer's enable / a counter's input reaches the byte side (docs/exchange.md)
TC_PATHS = ("channel", "status")
PLANT_MODES = ("serial", "parallel")   # the plant harnesses run no free-running core


def check_mode(mode: str, exchange: str | None) -> str:
    """The exchange setting for a run: the mode's default (MODE_EXCHANGES) when none
    is given; serial mode ignores --exchange (spec §4)."""
    allowed = MODE_EXCHANGES[mode]
    if mode == "serial" or exchange is None:
        return allowed[0]
    if exchange not in allowed:
        use = " or ".join(allowed)
        why = (f"free-running processors never wait; use {use}" if mode == "free" else
               f"{mode} mode runs with {use} (free-running exchanges need --mode free)")
        raise UsageError(f"--exchange {exchange}: {why}")
    return exchange


def check_tc_path(mode: str, tc_path: str) -> None:
    """--tc-path for `asm` and `run`: status needs a partitioned mode (docs/exchange.md)."""
    if tc_path not in TC_PATHS:
        raise UsageError(f"--tc-path: {tc_path!r} is not one of {', '.join(TC_PATHS)}")
    if tc_path == "status" and mode == "serial":
        raise UsageError("--tc-path status: parallel and free-running mode (in serial "
                         "mode the dispatch itself writes the enable / pulse bits)")


@dataclass(frozen=True)
class Prepared:
    """What `prepare` returns: prepare_run's four, the stimulus's input changes
    (Stimulus.changes) and what the summary's response times replay the run with
    (bitbyte.run.response): the stimulus and the configuration."""
    program: Program
    columns: list
    job: RunJob
    f: Fraction
    changes: list
    stimulus: Stimulus
    config: Config
    listing: list = field(default_factory=list)   # the bit processor's program, word by word
    byte_listing: list = field(default_factory=list)   # parallel: the byte part's


def prepare_run(program_path: str, **settings):
    """prepare(...) as the tuple (program, columns, job, f) the tests unpack."""
    p = prepare(program_path, **settings)
    return p.program, p.columns, p.job, p.f


def prepare(program_path: str, *, stimulus: str | None = None, watch: str = "",
                scans: int | None = None, until_us: str | None = None,
                watchdog: int = 100_000, clock_mhz: str = "100", costs: str = "paper",
                mode: str = "serial", exchange: str | None = None,
                channels: int | None = None, lang: str | None = None,
                mnemonics: str | None = None, profile: str | None = None,
                symbols: str | None = None, marker_write_buffer: bool = False,
                tc_path: str = "channel"):
    """Everything `run` does before the simulator: parse, encode, stimulus, columns.

    f is the clock in MHz as a Fraction.  The differential tests call this too (as
    prepare_run), so they exercise the same path."""

    f = parse_clock_mhz(clock_mhz)
    config = Config.of_profile(profile, clock_mhz=float(f))
    if scans is not None and scans < 1:
        raise UsageError("--scans must be at least 1")
    if not 2 <= watchdog < 2 ** 32:
        raise UsageError("--watchdog must be 2 .. 2^32-1 clocks")
    until_clock = None
    if until_us is not None:
        try:
            t = Fraction(until_us)
        except (ValueError, ZeroDivisionError):
            raise UsageError(f"--until-us: not a number: {until_us!r}") from None
        if t < 0:
            raise UsageError("--until-us must not be negative")
        until_clock = math.ceil(t * f)
    if scans is None and until_clock is None:
        scans = DEFAULT_SCANS

    if costs not in COST_TABLES:
        raise UsageError(f"--costs: unknown table {costs!r} (known: {', '.join(COST_TABLES)})")
    exchange = check_mode(mode, exchange)
    check_tc_path(mode, tc_path)
    if marker_write_buffer and exchange != "marker":
        raise UsageError("--marker-write-buffer: the marker exchange's option "
                         "(--mode free, --exchange marker)")
    # the marker exchange's FBI / FBY k are the marker area's cells, not the channels
    cells = mode == "free" and exchange == "marker"
    if cells:
        config = replace(config, channels=config.marker_cells)
    program = parse_file(program_path, config, lang=lang, mnemonics=mnemonics,
                         symbols=symbols)
    byte_words: list[int] = []
    if mode == "free" and program.startup_scans:
        raise UsageError("--mode free: this program has an OB 100, which runs in a "
                         "startup scan before scan 0; free-running sides have scans of "
                         "their own, so the byte side would not run its part of it "
                         "(docs/s7.md, OB 100: the startup); use serial or parallel mode")
    if mode in ("parallel", "free"):
        # free-running: nobody waits, so no ordering of status reads (paper Fig. 2)
        free = mode == "free"
        if channels is not None and not 1 <= channels <= config.channels:
            raise UsageError(f"--channels must be 1..{config.channels}"
                             + (" (the marker area's cells)" if cells else ""))
        part = partition(program, channels or config.channels, config=config,
                         status_sync=not free,
                         hardware_wait=not free, costs=costs, tc_path=tc_path)
        words, byte_words, pool = part.bit_words, part.byte_words, part.pool
        if cells:
            _one_cell_per_condition(program, part, channels or config.channels)
    else:
        words, pool = encode_words(program, config), constant_pool(program)
    stim = (load_stimulus(stimulus, program.symbols, config, program.symbol_names) if stimulus
            else no_stimulus(config))
    watch_list = [w for w in watch.split(",") if w.strip()] if watch else []
    try:
        columns = tr.trace_columns(program, watch_list, program.symbols, config)
    except ValueError as e:
        raise UsageError(f"--watch: {e}") from None
    events = stim.events_for_harness(f)
    has_words = any(row.words for row in stim.rows)

    def input_words(kind: str, key: int):
        if not has_words:
            return None
        got = stim.words_for_scan(key) if kind == "scan" else stim.words_at_clock(key, f)
        return [got.get(n, 0) for n in range(config.in_words)]

    job = RunJob(prog=words, clock_hz=int(f * 1_000_000), watchdog=watchdog,
                 scans=scans, until_clock=until_clock,
                 stim_kind=events[0][0] if events else "none",
                 stim=[(key, pins, input_words(kind, key)) for kind, key, pins in events],
                 cols=[(c.header, *hw_column(c.operand)) for c in columns],
                 costs=costs, pool=pool, mode=mode, exchange=exchange,
                 marker_write_buffer=marker_write_buffer, byte_prog=byte_words,
                 startup_scans=program.startup_scans)
    return Prepared(program, columns, job, f, stim.changes(f), stim, config,
                    list(part.bit) if mode in ("parallel", "free") else list(program.instrs),
                    list(part.byte) if mode in ("parallel", "free") else [])


def _one_cell_per_condition(program, part, cells: int) -> None:
    """The marker area holds one condition per cell and a reader snapshots it once a
    scan: two conditions of one scan in one cell would mix. Free-running mode with
    the marker exchange therefore needs a cell per transfer and direction."""
    seen: dict[str, int] = {}
    for t in part.transfers:
        seen[t.direction] = seen.get(t.direction, 0) + 1
        if seen[t.direction] > cells:
            line = next((i.source for i in program.instrs if i.line == t.line), "")
            raise SourceError(program.path, t.line, t.col,
                              f"more than {cells} conditions cross "
                              f"{'bit -> byte' if t.direction == 'to_byte' else 'byte -> bit'} in one "
                              f"scan: the marker area has {cells} cells per direction "
                              "(use --exchange queue-free, or fewer crossings)", line)
