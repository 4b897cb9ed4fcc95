"""`bitbyte` command line (spec §4, §7, §8): `asm`, `run`, `link` and `alloc`.

Every user error ends as `file:line:col: message` (or a one-line message for command
line mistakes) and a non-zero exit status, never a traceback:
  1  the program or the stimulus is malformed
  2  command-line usage error
  3  scan watchdog (the run stopped; completed scans are still traced)
  4  simulator failure (build or run)
  5  alloc: the tasks do not fit on the cores (the reason on stderr)
"""
from __future__ import annotations

import argparse
import fcntl
import math
import subprocess
import sys
import tempfile
from fractions import Fraction
from pathlib import Path

from .errors import UsageError  # noqa: F401  (raised by the modules cli calls)
from .config import Config
from .errors import SourceError, format_error

EXIT_SOURCE, EXIT_USAGE, EXIT_WATCHDOG, EXIT_SIM = 1, 2, 3, 4
EXIT_NO_FIT = 5
ROOT = Path(__file__).resolve().parents[1]
HARNESS = ROOT / "sim" / "build" / "Vbitbyte_cpu"
DEFAULT_SCANS = 10



def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="bitbyte", description="bit-byte PLC CPU toolchain")
    sub = p.add_subparsers(dest="command", required=True)

    a = sub.add_parser("asm", help="assemble PROG.il: image (.hex), listing (.lst), .json")
    a.add_argument("program")
    a.add_argument("--mode", choices=["serial", "parallel"], default="serial")
    a.add_argument("-o", "--outdir", default=None)

    r = sub.add_parser("run", help="assemble and simulate PROG.il, write a trace")
    r.add_argument("program")
    r.add_argument("--mode", choices=["serial", "parallel", "free"], default="serial")
    r.add_argument("--exchange", choices=["handshake", "queue", "queue-free", "marker"])
    r.add_argument("--stimulus")
    stop = r.add_mutually_exclusive_group()
    stop.add_argument("--scans", type=int)
    stop.add_argument("--until-us", type=str)
    r.add_argument("--watchdog", type=int, default=100_000)
    r.add_argument("--trace")
    r.add_argument("--watch", default="")
    r.add_argument("--waves")
    r.add_argument("--sim", choices=["verilator", "icarus"], default="verilator")
    r.add_argument("--clock-mhz", type=str, default="100")
    r.add_argument("--channels", type=int, default=None,
                   help="parallel/free mode: exchange channels per direction the "
                        "partitioning compiler uses (1..4, default 4; Fig. 14/15 tasks)")
    r.add_argument("--costs", default="paper",
                   help="byte processor cost table: paper (default) or c320")

    k = sub.add_parser("link", help="check a multi-core plant (PLANT.toml) and print its "
                                    "shared-memory map and copy plan")
    k.add_argument("plant")

    al = sub.add_parser("alloc", help="allocate periodic tasks (TASKS.csv) to cores "
                                      "(spec section 8, seed 002)")
    al.add_argument("tasks", nargs="?")
    al.add_argument("--generate", choices=["becker2015"],
                    help="instead of TASKS.csv: seed 002's synthetic workload (Table I)")
    al.add_argument("--networks", type=int, help="--generate: number of networks")
    al.add_argument("--seed", type=int, default=0, help="--generate: random seed")
    al.add_argument("--save-tasks", metavar="TASKS.csv",
                    help="--generate: also write the generated tasks as a task file")
    al.add_argument("--cores", type=int, help="cores available (--generate: 16)")
    al.add_argument("--mem", type=int, default=4096, help="bytes per core (4096)")
    al.add_argument("--alpha", default="0.001145", help="read time, ms per byte")
    al.add_argument("--beta", default="0.001145", help="write time, ms per byte")
    al.add_argument("--algorithm", choices=["ffd", "best"], default="best")
    al.add_argument("--clock-mhz", type=str, default="100",
                    help="clock for WCETs from programs and for --emit (100)")
    al.add_argument("--mode", choices=["serial", "parallel"], default="serial",
                    help="WCET of a program: serial or parallel scan (serial)")
    al.add_argument("--json", metavar="OUT.json")
    al.add_argument("--emit", metavar="PLANT.toml")
    return p


def _clock_mhz(text: str) -> Fraction:
    try:
        f = Fraction(text)
    except (ValueError, ZeroDivisionError):
        raise UsageError(f"--clock-mhz: not a number: {text!r}") from None
    if f <= 0 or (f * 1000).denominator != 1:
        raise UsageError("--clock-mhz must be positive and a whole number of kHz "
                         "(the timers' 1 ms time base counts whole clocks)")
    return f


def _check_mode(mode: str, exchange: str | None) -> str:
    """The exchange setting for a run: parallel mode defaults to handshake; serial
    mode ignores --exchange (spec §4); free-running mode takes marker or queue-free."""
    if mode == "serial":
        return "handshake"
    if mode == "free":
        exchange = exchange or "marker"
        if exchange not in ("marker", "queue-free"):
            raise UsageError(f"--exchange {exchange}: free-running processors never wait; "
                             "use marker or queue-free")
        return exchange
    exchange = exchange or "handshake"
    if exchange not in ("handshake", "queue"):
        raise UsageError(f"--exchange {exchange}: parallel mode runs with handshake or "
                         "queue (free-running exchanges need --mode free)")
    return exchange


def cmd_asm(args) -> int:
    from .asm import assemble
    result = assemble(args.program, outdir=args.outdir, config=Config(), mode=args.mode)
    for kind in ("hex", "bit_hex", "byte_hex", "pool", "lst", "report", "json"):
        if kind in result:
            print(f"wrote {result[kind]}")
    return 0


def prepare_run(program_path: str, *, stimulus: str | None = None, watch: str = "",
                scans: int | None = None, until_us: str | None = None,
                watchdog: int = 100_000, clock_mhz: str = "100", costs: str = "paper",
                mode: str = "serial", exchange: str | None = None,
                channels: int | None = None):
    """Everything `run` does before the simulator: parse, encode, stimulus, columns.

    Returns (program, columns, job, f) with f the clock in MHz as a Fraction.
    The differential tests call this too, so they exercise the same path."""
    from . import trace as tr
    from .encoder import constant_pool, encode_words
    from .parser import parse_file
    from .refsim import COST_TABLES
    from .runjob import RunJob, hw_column
    from .stimulus import load_stimulus, no_stimulus

    f = _clock_mhz(clock_mhz)
    config = Config(clock_mhz=float(f))
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
    exchange = _check_mode(mode, exchange)
    program = parse_file(program_path, config)
    byte_words: list[int] = []
    if mode in ("parallel", "free"):
        from .partition import partition
        # free-running: nobody waits, so no ordering of status reads (paper Fig. 2)
        free = mode == "free"
        if channels is not None and not 1 <= channels <= config.channels:
            raise UsageError(f"--channels must be 1..{config.channels}")
        part = partition(program, channels or config.channels, config=config,
                         status_sync=not free,
                         hardware_wait=not free, costs=costs)
        words, byte_words, pool = part.bit_words, part.byte_words, part.pool
        if free and exchange == "marker":
            _one_cell_per_condition(program, part, channels or config.channels)
    else:
        words, pool = encode_words(program, config), constant_pool(program)
    stim = (load_stimulus(stimulus, program.symbols, config) if stimulus
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
        return [got.get(n, 0) for n in range(16)]

    job = RunJob(prog=words, clock_hz=int(f * 1_000_000), watchdog=watchdog,
                 scans=scans, until_clock=until_clock,
                 stim_kind=events[0][0] if events else "none",
                 stim=[(key, pins, input_words(kind, key)) for kind, key, pins in events],
                 cols=[(c.header, *hw_column(c.operand)) for c in columns],
                 costs=costs, pool=pool, mode=mode, exchange=exchange,
                 byte_prog=byte_words)
    return program, columns, job, f


def cmd_link(args) -> int:
    from .plant import format_map, link, load_plant
    print(format_map(link(load_plant(args.plant))), end="")
    return 0


def cmd_alloc(args) -> int:
    """Spec §8: read or generate the tasks, allocate, print the table; --json is
    written even when the tasks do not fit (exit 5), --emit only when they do."""
    import json
    from . import alloc as al

    f = _clock_mhz(args.clock_mhz)
    rates = {}
    for opt in ("alpha", "beta"):
        try:
            rates[opt] = Fraction(getattr(args, opt))
        except (ValueError, ZeroDivisionError):
            raise UsageError(f"--{opt}: not a number: {getattr(args, opt)!r}") from None
        if rates[opt] < 0:
            raise UsageError(f"--{opt} must not be negative")
    if args.mem < 1:
        raise UsageError("--mem must be at least 1 byte")
    if args.cores is not None and args.cores < 1:
        raise UsageError("--cores must be at least 1")
    if args.generate:
        if args.tasks:
            raise UsageError("give TASKS.csv or --generate, not both")
        if args.networks is None or args.networks < 1:
            raise UsageError("--generate needs --networks K (K >= 1)")
        tasks = al.generate_becker2015(args.networks, args.seed)
        cores = al.BECKER_CORES if args.cores is None else args.cores
        if args.save_tasks:
            Path(args.save_tasks).write_text(al.tasks_csv(tasks))
    else:
        if not args.tasks:
            raise UsageError("alloc needs TASKS.csv or --generate becker2015")
        if args.cores is None:
            raise UsageError("alloc TASKS.csv needs --cores N")
        if args.networks is not None or args.save_tasks:
            raise UsageError("--networks and --save-tasks go with --generate")
        tasks = al.load_tasks(args.tasks, f, args.mode)
        cores = args.cores
    platform = al.Platform(cores, args.mem, rates["alpha"], rates["beta"])
    al.check_fits(tasks, platform)
    try:
        result = al.allocate(tasks, platform, args.algorithm)
        print(al.format_table(result), end="")
        if args.json:
            Path(args.json).write_text(json.dumps(al.to_json(result), indent=1) + "\n")
        if not result.ok:
            print(f"bitbyte: alloc: {result.reason()}"
                  + ("; no plant written" if args.emit else ""), file=sys.stderr)
            return EXIT_NO_FIT
        if args.emit:
            for path in al.emit_plant(result, args.emit, f):
                print(f"wrote {path}")
    except al.UsageProblem as e:
        raise UsageError(str(e)) from None
    return 0


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


def cmd_run(args) -> int:
    from . import trace as tr

    if args.program.lower().endswith(".toml"):
        return cmd_run_plant(args)

    _, columns, job, f = prepare_run(
        args.program, stimulus=args.stimulus, watch=args.watch, scans=args.scans,
        until_us=args.until_us, watchdog=args.watchdog, clock_mhz=args.clock_mhz,
        costs=args.costs, mode=args.mode, exchange=args.exchange,
        channels=args.channels)

    if args.sim == "verilator":
        records, fault, summary = _run_harness(job, columns, args)
    else:
        records, fault, summary = _run_cocotb(job, columns, args, f)
    if args.trace and args.sim != "verilator":
        tr.write_trace(args.trace, columns, records, f)
    print(summary, end="")
    if fault:
        print(f"scan watchdog: scan {len(records)} exceeded {args.watchdog} clocks; "
              "outputs forced to 0", file=sys.stderr)
        return EXIT_WATCHDOG
    return 0


def cmd_run_plant(args) -> int:
    """`run PLANT.toml` (spec §7): every core on the multi-core system."""
    from .plantrun import PlantRunError, run_plant
    if args.until_us is None:
        raise UsageError("running a plant needs --until-us T")
    for opt, given in (("--mode", args.mode != "serial"), ("--exchange", args.exchange),
                       ("--stimulus", args.stimulus), ("--channels", args.channels),
                       ("--clock-mhz", args.clock_mhz != "100")):
        if given:
            raise UsageError(f"{opt} does not apply to a plant (the plant file sets it)")
    try:
        status, summary, _ = run_plant(args.program, until_us=args.until_us,
                                       trace=args.trace, watch=args.watch,
                                       waves=args.waves, watchdog=args.watchdog,
                                       costs=args.costs, sim=args.sim)
    except PlantRunError as e:
        raise SimError(str(e)) from None
    lines = summary.splitlines(keepends=True)      # the watchdog's words go to stderr
    print("".join(l for l in lines if not l.startswith("scan watchdog")), end="")
    print("".join(l for l in lines if l.startswith("scan watchdog")), end="",
          file=sys.stderr)
    return EXIT_WATCHDOG if status == 3 else 0


def _records_from_rows(columns, rows):
    from .trace import ScanRecord
    return [ScanRecord(scan=s, end_clock=e, cycles=c,
                       values={col.header: v for col, v in zip(columns, vals)})
            for s, e, c, vals in rows]


def _run_cocotb(job, columns, args, f):
    from .sim_cocotb import run_jobs
    from .summary import summary_text
    if args.waves:
        raise UsageError("--waves is written by the Verilator harness; use --sim verilator")
    try:
        (result,) = run_jobs([job], args.sim)
    except (SystemExit, RuntimeError, OSError) as e:
        raise SimError(f"cocotb on {args.sim} failed: {e}") from None
    records = _records_from_rows(columns, result.rows)
    return records, result.fault, summary_text(records, f, args.trace, result.stalls)


class SimError(Exception):
    """The simulator could not be built or run: exit 4."""


def ensure_harness() -> Path:
    """Build sim/build/Vbitbyte_cpu through the Makefile when it is missing or stale."""
    HARNESS.parent.mkdir(parents=True, exist_ok=True)
    with open(HARNESS.parent / ".lock", "w") as lock:   # concurrent runs build once
        fcntl.flock(lock, fcntl.LOCK_EX)
        proc = subprocess.run(["make", "-s", "-C", str(ROOT), "harness"],
                              capture_output=True, text=True)
    if proc.returncode != 0 or not HARNESS.exists():
        raise SimError("building the Verilator harness failed:\n" + proc.stdout + proc.stderr)
    return HARNESS


def _run_harness(job, columns, args):
    from .trace import read_trace_rows
    harness = ensure_harness()
    with tempfile.TemporaryDirectory(prefix="bitbyte-") as tmp:
        hex_path = Path(tmp) / "prog.hex"
        hex_path.write_text("".join(f"{w:08x}\n" for w in job.prog))
        trace_path = Path(args.trace).resolve() if args.trace else Path(tmp) / "trace.csv"
        waves = str(Path(args.waves).resolve()) if args.waves else None
        if waves:
            Path(waves).parent.mkdir(parents=True, exist_ok=True)
        run_file = Path(tmp) / "run.txt"
        byte_path = None
        if job.mode in ("parallel", "free"):
            byte_path = Path(tmp) / "byte.hex"
            byte_path.write_text("".join(f"{w:08x}\n" for w in job.byte_prog))
        text = job.to_harness_text(str(hex_path), str(trace_path), waves,
                                   str(byte_path) if byte_path else None)
        run_file.write_text(text + f"gtkw {ROOT / 'sim' / 'bitbyte.gtkw'}\n")
        proc = subprocess.run([str(harness), str(run_file)], capture_output=True, text=True)
        if not args.trace:        # the temporary trace is gone after the run: do not show it
            proc.stdout = "".join(l for l in proc.stdout.splitlines(keepends=True)
                                  if not l.startswith("trace "))
        if proc.returncode not in (0, EXIT_WATCHDOG):
            raise SimError(f"Verilator harness failed ({proc.returncode}):\n{proc.stderr}")
        records = read_trace_rows(trace_path, columns)
    return records, proc.returncode == EXIT_WATCHDOG, proc.stdout


def main(argv: list[str] | None = None) -> int:
    try:
        args = _parser().parse_args(argv)
        return {"asm": cmd_asm, "run": cmd_run, "link": cmd_link,
                "alloc": cmd_alloc}[args.command](args)
    except SourceError as e:
        print(format_error(e), file=sys.stderr)
        return EXIT_SOURCE
    except UsageError as e:
        print(f"bitbyte: {e}", file=sys.stderr)
        return EXIT_USAGE
    except SimError as e:
        print(f"bitbyte: {e}", file=sys.stderr)
        return EXIT_SIM
    except OSError as e:
        print(f"bitbyte: {e.filename or ''}: {e.strerror or e}", file=sys.stderr)
        return EXIT_SOURCE
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    sys.exit(main())
