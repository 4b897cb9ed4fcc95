"""`bitbyte` command line (spec §4, §7, §8): `asm`, `run`, `link` and `alloc`.

Every user error ends as `file:line:col: message` (or a one-line message for command
line mistakes) and a non-zero exit status, never a traceback:
  1  the program or the stimulus is malformed
  2  command-line usage error
  3  scan watchdog (the run stopped; completed scans are still traced)
  4  simulator failure (build or run)
  5  alloc: the tasks do not fit on the cores (the reason on stderr); a task that
     fits no core at all is a bad input (1), the allocation of the others still written
"""
from __future__ import annotations

import argparse
import json
import sys
from fractions import Fraction
from pathlib import Path

from bitbyte import alloc as al
from bitbyte.asm import assemble
from bitbyte.lang.config import Config
from bitbyte.lang.definition import DEF
from bitbyte.lang.errors import SimError, SourceError, UsageError, format_error
from bitbyte.lang.firstcheck import first_check_warnings
from bitbyte.lang.parser import source_language
from bitbyte.plant.link import format_map, link, load_plant
from bitbyte.plant.run import PlantRunError, run_plant
from bitbyte.run.prepare import parse_clock_mhz, prepare
from bitbyte.run.response import response_times
from bitbyte.run.summary import summary_text
from bitbyte.sim.cocotb_runner import run_cocotb
from bitbyte.sim.verilator import GTKW, run_harness

EXIT_SOURCE, EXIT_USAGE, EXIT_WATCHDOG, EXIT_SIM = 1, 2, 3, 4
EXIT_NO_FIT = 5


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="bitbyte", description="bit-byte PLC CPU toolchain")
    sub = p.add_subparsers(dest="command", required=True)

    a = sub.add_parser("asm", help="assemble PROG.il: image (.hex), listing (.lst), .json")
    a.add_argument("program")
    a.add_argument("--mode", choices=["serial", "parallel"], default="serial")
    a.add_argument("-o", "--outdir", default=None)
    _source_options(a)

    r = sub.add_parser("run", help="assemble and simulate PROG.il, write a trace")
    r.add_argument("program")
    r.add_argument("--mode", choices=["serial", "parallel", "free"], default="serial")
    r.add_argument("--exchange", choices=DEF.exchanges)
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
    _source_options(r)

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


def _source_options(p: argparse.ArgumentParser) -> None:
    """--lang and --mnemonics (spec §9): how the source file is read."""
    p.add_argument("--lang", choices=["il", "stl"], default=None,
                   help="source language: il (spec section 3) or stl (S7 statement "
                        "list, section 9); default from the suffix (.awl: stl)")
    p.add_argument("--mnemonics", choices=["de", "en"], default=None,
                   help="stl: German or English mnemonics (default: detected from "
                        "the source)")
    p.add_argument("--profile", choices=sorted(DEF.profiles), default=None,
                   help="check the program against a build profile's sizes ("
                        + "; ".join(f"{k}: {v['doc']}" for k, v in sorted(DEF.profiles.items()))
                        + "); default: the full ranges of the default build")
    p.add_argument("--symbols", metavar="FILE", default=None,
                   help="stl: a STEP 7 symbol table export (.asc, .seq or .sdf) for "
                        "the quoted symbols of the source")


def _warnings(args, program) -> None:
    """The first-check warning for IL sources (issue 19): on stderr, the run goes on."""
    if source_language(args.program, args.lang) == "il":
        for warning in first_check_warnings(program):
            print(format_error(warning), file=sys.stderr)


def cmd_asm(args) -> int:
    result = assemble(args.program, outdir=args.outdir, config=Config.of_profile(args.profile),
                      mode=args.mode, lang=args.lang, mnemonics=args.mnemonics,
                      symbols=args.symbols)
    _warnings(args, result["program"])
    for kind in ("hex", "bit_hex", "byte_hex", "pool", "lst", "report", "json"):
        if kind in result:
            print(f"wrote {result[kind]}")
    return 0


def cmd_link(args) -> int:
    print(format_map(link(load_plant(args.plant))), end="")
    return 0


def cmd_alloc(args) -> int:
    """Spec §8: read or generate the tasks, allocate, print the table; --json is
    written even when the tasks do not fit (exit 5) or a task fits no core (exit 1,
    its error at its line), --emit only when every task is placed."""
    f = parse_clock_mhz(args.clock_mhz)
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
    try:
        result = al.allocate(tasks, platform, args.algorithm)
        print(al.format_table(result), end="")
        if args.json:
            Path(args.json).write_text(json.dumps(al.to_json(result), indent=1) + "\n")
        for _, error in result.misfits:          # spec §8: each an error at its line
            print(format_error(error), file=sys.stderr)
        if not result.ok:
            why = result.reason()
            if why or args.emit:
                print(f"bitbyte: alloc: {why or 'a task fits no core'}"
                      + ("; no plant written" if args.emit else ""), file=sys.stderr)
            return EXIT_SOURCE if result.misfits else EXIT_NO_FIT
        if args.emit:
            for path in al.emit_plant(result, args.emit, f):
                print(f"wrote {path}")
    except al.UsageProblem as e:
        raise UsageError(str(e)) from None
    return 0


def cmd_run(args) -> int:
    if args.program.lower().endswith(".toml"):
        return cmd_run_plant(args)

    prep = prepare(
        args.program, stimulus=args.stimulus, watch=args.watch, scans=args.scans,
        until_us=args.until_us, watchdog=args.watchdog, clock_mhz=args.clock_mhz,
        costs=args.costs, mode=args.mode, exchange=args.exchange,
        channels=args.channels, lang=args.lang, mnemonics=args.mnemonics,
        profile=args.profile, symbols=args.symbols)
    program, columns, job, f = prep.program, prep.columns, prep.job, prep.f
    _warnings(args, program)

    if args.sim == "verilator":
        records, fault, stats = run_harness(job, columns, args.trace, args.waves)
    else:
        if args.waves:
            raise UsageError("--waves is written by the Verilator harness; use --sim verilator")
        records, fault, stats = run_cocotb(job, columns, args.sim, f, args.trace)
    waves = (args.waves, str(GTKW)) if args.waves else None
    print(summary_text(records, f, stats, args.trace, waves,
                       response_times(prep, records)), end="")
    if fault:
        print(f"scan watchdog: scan {len(records)} exceeded {args.watchdog} clocks; "
              "outputs forced to 0", file=sys.stderr)
        return EXIT_WATCHDOG
    return 0


def cmd_run_plant(args) -> int:
    """`run PLANT.toml` (spec §7): every core on the multi-core system."""
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
