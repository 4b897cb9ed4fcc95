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
import dataclasses
import importlib.metadata
import json
import sys
import textwrap
import tomllib
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
from bitbyte.run.prepare import MODES, TC_PATHS, check_tc_path, parse_clock_mhz, prepare
from bitbyte.run.force import check_overlaps, force_tables, parse_force
from bitbyte.run.response import response_times
from bitbyte.run.line_counts import line_count_rows, line_counts_csv
from bitbyte.run.status import block_status_text, parallel_block_status_text
from bitbyte.run.summary import fault_scan_name, summary_text
from bitbyte.sim.cocotb_runner import run_cocotb
from bitbyte.sim.gtkw import WaveLayoutError, write_gtkw
from bitbyte.sim.verilator import harness_period_ps, run_harness

EXIT_SOURCE, EXIT_USAGE, EXIT_WATCHDOG, EXIT_SIM = 1, 2, 3, 4
EXIT_NO_FIT = 5


def version() -> str:
    """The package version, written once in pyproject.toml (installed metadata, or the
    file itself when run from a source tree that is not installed)."""
    try:
        return importlib.metadata.version("bitbyte")
    except importlib.metadata.PackageNotFoundError:
        pyproject = Path(__file__).resolve().parents[1] / "pyproject.toml"
        return tomllib.loads(pyproject.read_text())["project"]["version"]


_FORMAT = argparse.RawDescriptionHelpFormatter   # the examples keep their lines


def _para(text: str) -> str:
    """A description paragraph, wrapped as argparse would (the raw formatter does not)."""
    return textwrap.fill(text, 79)

_ASM_EXAMPLES = """\
examples:
  bitbyte asm examples/star_delta.il -o build/star_delta
      the image (.hex), the listing (.lst) and the program model (.json)
  bitbyte asm examples/fig5.il --mode parallel -o build/fig5
      the bit part and the byte part (the partitioning compiler's report beside them)
"""

_RUN_EXAMPLES = """\
examples:
  bitbyte run examples/star_delta.il --stimulus examples/star_delta.stim.csv \\
      --clock-mhz 1 --until-us 260000 --watch Run,SpeedOK --trace star.csv
      serial mode on Verilator: one trace row per scan, the summary on stdout
  bitbyte run examples/fig5.il --mode parallel --scans 20 --sim icarus
      the paper's Fig. 5 program split over the bit and byte processors, on Icarus
  bitbyte run examples/fig5.il --stimulus examples/fig5.stim.csv --scans 4 --status 3
      the block status of scan 3: RLO, operand and accumulators per line
  bitbyte run examples/tutorial/motor.il --scans 6 --force Stop=1 --force Start=1@1-2 \\
      --force Ready=1@4 --watch Start,Running
      Stop released, Start pressed in scans 1 and 2: the motor starts; the Ready lamp
      lit in scan 4 whatever the program says
  bitbyte run examples/star_delta.il --scans 50 --waves sim/waves/star.fst
      also writes star.gtkw: open it with `gtkwave sim/waves/star.fst sim/waves/star.gtkw`
  bitbyte run examples/plant_6_1/plant_sim.toml --until-us 300000
      a multi-core plant (spec section 7): every core's trace and summary

exit status: 0 done, 1 bad program or stimulus (file:line:col: message), 2 usage,
3 scan watchdog (completed scans still traced), 4 simulator failure
"""

_ALLOC_EXAMPLES = """\
examples:
  bitbyte alloc examples/alloc/tasks.csv --cores 4 --json alloc.json
      pack the periodic tasks of tasks.csv onto at most 4 cores, the table on stdout
  bitbyte alloc --generate becker2015 --networks 200 --seed 1
      seed 002's synthetic workload on its 16 cores
  bitbyte alloc examples/alloc/tasks.csv --cores 4 --emit plant.toml
      also write a plant file (spec section 7) when every task is placed

exit status: 0 placed, 1 a task fits no core (its line named; --json still written),
2 usage, 5 the tasks do not fit the cores (the reason on stderr)
"""


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="bitbyte", formatter_class=_FORMAT,
        description=_para("Toolchain of the bit-byte PLC CPU: assemble instruction-list "
                          "(IL) or S7 statement-list programs, simulate them on the RTL "
                          "(Verilator or Icarus), check multi-core plants and allocate "
                          "tasks to cores."),
        epilog=_para("`bitbyte COMMAND --help` explains a command and shows examples; "
                     "docs/toolchain.md describes them all."))
    p.add_argument("--version", action="version", version=f"%(prog)s {version()}",
                   help="print the toolchain's version and exit")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND",
                           title="commands")

    a = sub.add_parser("asm", formatter_class=_FORMAT, epilog=_ASM_EXAMPLES,
                       help="assemble a program: image (.hex), listing (.lst), .json",
                       description=_para("Assemble PROG.il (or PROG.awl) into the program "
                                   "memory image, a listing and the program model; in "
                                   "parallel mode also the bit and byte parts."))
    a.add_argument("program", metavar="PROG.il",
                   help="the source: IL (spec section 3) or S7 STL (.awl, section 9)")
    a.add_argument("--mode", choices=["serial", "parallel"], default="serial",
                   help="serial: one image, byte instructions dispatched from the bit "
                        "processor; parallel: partition into a bit part and a byte part "
                        "(the paper's Fig. 12/13) (default serial)")
    a.add_argument("--tc-path", choices=TC_PATHS, default="channel",
                   help="how a timer's enable / a counter's input reaches the byte side "
                        "in the parallel-mode partition (see run --tc-path); serial mode "
                        "refuses status (default channel)")
    a.add_argument("--bit-engine", choices=["scalar", "wide"], default="scalar",
                   help="scalar: one bit instruction per clock; wide: each straight-line "
                        "stretch compiled into LUT words (several bit instructions per "
                        "clock), written as the wide image: .hex (base words), .ext.hex "
                        "(extension words), .lst, .json; serial mode (default scalar)")
    a.add_argument("-o", "--outdir", default=None, metavar="OUTDIR",
                   help="where the files go (default: beside the source)")
    _source_options(a)

    r = sub.add_parser("run", formatter_class=_FORMAT, epilog=_RUN_EXAMPLES,
                       help="assemble and simulate a program (or a plant), write a trace",
                       description=_para("Assemble PROG.il and run it on the simulated CPU: "
                                   "the bit processor's RTL and the byte processor's "
                                   "firmware model. Prints a summary (scans, scan time, "
                                   "stalls, exchange and response-time figures); --trace "
                                   "writes one row per scan (spec section 4). PROG may "
                                   "also be a plant file PLANT.toml (section 7)."))
    r.add_argument("program", metavar="PROG.il",
                   help="the source (IL or .awl), or a plant file PLANT.toml")
    r.add_argument("--mode", choices=MODES, default="serial",
                   help="serial: the byte processor waits for its dispatched "
                        "instructions; parallel: both processors run their part of each "
                        "scan at once; free: each side scans at its own pace "
                        "(spec section 2; default serial)")
    r.add_argument("--exchange", choices=DEF.exchanges,
                   help="how conditions cross between the processors in parallel/free "
                        "mode: handshake (one-slot channels, the writer waits), queue "
                        "(FIFOs), queue-free (FIFOs, losses counted instead of waits), "
                        "marker (Fig. 17's marker area). Default: handshake in parallel "
                        "mode, marker in free mode; serial mode ignores it")
    r.add_argument("--marker-write-buffer", action="store_true",
                   help="marker exchange: each side publishes its cells at its own scan "
                        "end, so the other side's snapshot (taken at its scan start) "
                        "holds whole scans of the writer, never half of one; without it "
                        "the snapshot takes the cells as they are (Fig. 17 as drawn: "
                        "the conditions of one writer scan may be split between two "
                        "reader scans)")
    r.add_argument("--tc-path", choices=TC_PATHS, default="channel",
                   help="parallel and free mode: how a timer's enable / a counter's input reaches the "
                        "byte side: channel (a condition through the exchange, = FBY k / "
                        "READ FBY k) or status (the bit side writes it into the "
                        "timer/counter status buffer, = T n / = C n, and the byte side "
                        "reads it there like an input: the paper's Fig. 2; "
                        "docs/exchange.md; in parallel mode the byte side first waits "
                        "until the bit side has written it in this scan). Serial mode "
                        "refuses status (default channel)")
    r.add_argument("--stimulus", metavar="STIM.csv",
                   help="input pins over time: first column scan or t_us, then one "
                        "column per input (I0.0, IW3 or a symbol); unnamed inputs are 0")
    stop = r.add_mutually_exclusive_group()
    stop.add_argument("--scans", type=int, metavar="N",
                      help="stop after N complete scans")
    stop.add_argument("--until-us", type=str, metavar="T",
                      help="stop after the first scan that ends at or after T "
                           "microseconds of simulated time")
    r.add_argument("--watchdog", type=int, default=100_000, metavar="N",
                   help="a scan longer than N clocks is a fault: outputs go to 0, the "
                        "run stops with exit status 3 (default 100000)")
    r.add_argument("--trace", metavar="TRACE.csv",
                   help="write the trace: scan, t_us, cycles, every written Q bit and "
                        "QW, then the --watch operands; one row per scan")
    r.add_argument("--watch", default="", metavar="OP,...",
                   help="extra trace columns: addresses (MW0, M0.0, T1, C2, IW0) or "
                        "declared symbols, comma-separated, named as typed")
    r.add_argument("--waves", metavar="FILE.fst",
                   help="write a waveform (FST, or VCD by the suffix) of the whole "
                        "run, with a GTKWave layout beside it (Verilator only)")
    r.add_argument("--sim", choices=["verilator", "icarus"], default="verilator",
                   help="simulator: the Verilator C++ harness (fast) or cocotb on "
                        "Icarus; both give identical traces (default verilator)")
    r.add_argument("--clock-mhz", type=str, default="100", metavar="F",
                   help="the bit processor's clock in MHz, an exact decimal; sets "
                        "t_us and the timers' time base (default 100)")
    r.add_argument("--channels", type=int, default=None, metavar="K",
                   help="parallel/free mode: exchange channels per direction the "
                        "partitioning compiler uses (1..4, default 4; Fig. 14/15 tasks)")
    r.add_argument("--status", type=int, default=None, metavar="SCAN",
                   help="print the block status of scan SCAN (from 0) after the summary: "
                        "per program line the RLO after it, the operand bit it read, "
                        "ACCU1/ACCU2 after word instructions, or 'not executed' "
                        "(serial and parallel mode)")
    r.add_argument("--line-counts", default=None, metavar="FILE",
                   help="Verilator: write how often each program line executed in the "
                        "whole run to FILE (CSV: part, address, source line, instruction, "
                        "count; 0 for a line never reached, empty for the byte part's "
                        "END_B), counted on the simulated hardware; in parallel and "
                        "free-running mode the bit and the byte part")
    r.add_argument("--exchange-log", default=None, metavar="FILE",
                   help="parallel and free-running mode, Verilator: write every condition "
                        "that crosses to FILE (CSV: the bit side's FBI/FBY retirements, "
                        "the byte side's channel and cell accesses and SCAN_DONE, each "
                        "with its clock and its side's scan; docs/exchange.md)")
    r.add_argument("--force", action="append", default=[], metavar="OP=V[@FROM-TO]",
                   help="force an input or output bit (I, PI, Q, PQ or its symbol) to 0 "
                        "or 1 in scans FROM..TO (default: all; @K: scan K only; @K-: "
                        "from K on), as the force table in the I/O units does it: a "
                        "forced input is what the CPU reads, a forced output what the pin "
                        "shows. Repeatable")
    r.add_argument("--costs", default="paper", metavar="TABLE",
                   help="byte processor cost table, in bit-processor clocks per "
                        "instruction: paper (S7-315-2DP weights, default) or c320")
    r.add_argument("--bit-engine", choices=["scalar", "wide"], default="scalar",
                   help="the bit processor's engine (spec section 4): scalar (default); "
                        "wide: the program compiled into LUT words (as `asm --bit-engine "
                        "wide`), run on the wide build (serial mode, --sim verilator; "
                        "--waves names a LUT word by its unit's lines)")
    _source_options(r)

    k = sub.add_parser("link", formatter_class=_FORMAT,
                       help="check a multi-core plant (PLANT.toml) and print its "
                            "shared-memory map and copy plan",
                       description=_para("Read a plant file (spec section 7), check "
                                         "its projects and shared variables, and print "
                                         "where each shared variable lives and what each "
                                         "core copies."),
                       epilog="example:\n  bitbyte link examples/plant_6_1/plant_sim.toml\n")
    k.add_argument("plant", metavar="PLANT.toml", help="the plant file")

    al = sub.add_parser("alloc", formatter_class=_FORMAT, epilog=_ALLOC_EXAMPLES,
                        help="allocate periodic tasks (TASKS.csv) to cores "
                             "(spec section 8, seed 002)",
                        description=_para("Allocate periodic tasks to cores so that each "
                                    "core's utilisation, memory and communication fit "
                                    "(spec section 8, after seed 002)."))
    al.add_argument("tasks", nargs="?", metavar="TASKS.csv",
                    help="one task per row: name, period, WCET or program, memory, "
                         "communication (spec section 8)")
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
    al.add_argument("--algorithm", choices=["ffd", "best"], default="best",
                    help="ffd: first-fit decreasing; best: the best of several "
                         "orderings and fits (default best)")
    al.add_argument("--clock-mhz", type=str, default="100",
                    help="clock for WCETs from programs and for --emit (100)")
    al.add_argument("--mode", choices=["serial", "parallel"], default="serial",
                    help="WCET of a program: serial or parallel scan (serial)")
    al.add_argument("--json", metavar="OUT.json",
                    help="write the allocation as JSON (also when it does not fit)")
    al.add_argument("--emit", metavar="PLANT.toml",
                    help="write a plant file for the allocation (only when every task "
                         "is placed)")
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
    check_tc_path(args.mode, args.tc_path)
    result = assemble(args.program, outdir=args.outdir, config=Config.of_profile(args.profile),
                      mode=args.mode, lang=args.lang, mnemonics=args.mnemonics,
                      symbols=args.symbols, tc_path=args.tc_path,
                      bit_engine=args.bit_engine, profile=args.profile)
    _warnings(args, result["program"])
    for kind in ("hex", "ext_hex", "bit_hex", "byte_hex", "pool", "lst", "report", "json"):
        if kind in result:
            print(f"wrote {result[kind]}")
    return 0


def _plant_warnings(plant) -> None:
    """A plant file's warnings (bitbyte.plant.link.Plant.warnings): on stderr."""
    for warning in plant.warnings:
        print(format_error(warning), file=sys.stderr)


def cmd_link(args) -> int:
    plant = load_plant(args.plant)
    _plant_warnings(plant)
    print(format_map(link(plant)), end="")
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


def _check_wide_run(args) -> None:
    """`run --bit-engine wide` (issue 18): the wide build on Verilator, serial mode; the
    line counts and the block status go through the image's map to the source
    (bitbyte/wide/link.py source_counts, bitbyte/run/status.py source_status), the
    waveform's `executing` row through its listing (wave_listing: a LUT word as its
    unit's lines)."""
    for opt, given in (("a plant file", args.program.lower().endswith(".toml")),
                       (f"--mode {args.mode}", args.mode != "serial"),
                       (f"--sim {args.sim}", args.sim != "verilator")):
        if given:
            raise UsageError(f"--bit-engine wide: {opt} is not supported yet (serial mode "
                             "on Verilator; docs/wide-rtl-plan.md, slice S7)")


def cmd_run(args) -> int:
    if args.bit_engine == "wide":
        _check_wide_run(args)
    if args.program.lower().endswith(".toml"):
        return cmd_run_plant(args)

    prep = prepare(
        args.program, stimulus=args.stimulus, watch=args.watch, scans=args.scans,
        until_us=args.until_us, watchdog=args.watchdog, clock_mhz=args.clock_mhz,
        costs=args.costs, mode=args.mode, exchange=args.exchange,
        channels=args.channels, lang=args.lang, mnemonics=args.mnemonics,
        profile=args.profile, symbols=args.symbols,
        marker_write_buffer=args.marker_write_buffer, tc_path=args.tc_path)
    program, columns, job, f = prep.program, prep.columns, prep.job, prep.f
    _warnings(args, program)
    image = None
    if args.bit_engine == "wide":     # the wide image, on the wide build
        from bitbyte.wide import link as wide_link
        from bitbyte.wide.model import compile_program
        image = wide_link.link(program, compile_program(program), prep.config)
        job.prog, job.prog_ext = image.base, image.ext
    if args.status is not None:
        if args.mode == "free":
            raise UsageError("--status: serial and parallel mode (in free-running mode the "
                             "two sides' scans are not the same scans)")
        if args.status < 0 or (args.scans is not None and args.status >= args.scans):
            raise UsageError(f"--status {args.status}: not a scan of this run "
                             f"(scans 0..{(args.scans or 1) - 1})")
        job.status_scan = args.status
    if args.exchange_log is not None:
        if args.mode == "serial" or args.sim != "verilator":
            raise UsageError("--exchange-log: parallel and free-running mode on Verilator "
                             "(serial mode has no crossings)")
        job.xlog = str(Path(args.exchange_log).resolve())
    if args.line_counts is not None:
        if args.sim != "verilator":
            raise UsageError("--line-counts: the Verilator harness counts them "
                             "(use --sim verilator)")
        try:     # checked before the run, as --trace is: not lost after it
            Path(args.line_counts).write_text("")
        except OSError as e:
            raise UsageError(f"--line-counts: cannot write {args.line_counts}: "
                             f"{e.strerror}") from None
        job.line_counts = True
    if args.force:
        forces = [parse_force(text, program.symbols, prep.config, program.symbol_names)
                  for text in args.force]
        check_overlaps(forces)
        job.force = force_tables(forces)

    if args.sim == "verilator":
        records, fault, stats = run_harness(job, columns, args.trace, args.waves)
    else:
        if args.waves:
            raise UsageError("--waves is written by the Verilator harness; use --sim verilator")
        records, fault, stats = run_cocotb(job, columns, args.sim, f, args.trace)
    waves = (args.waves, _wave_layout(args, prep, records, stats, image)) if args.waves \
        else None
    if args.line_counts is not None:
        if image is not None:          # wide addresses -> the source's (scalar) ones
            from bitbyte.wide.link import source_counts
            stats = dataclasses.replace(stats, line_counts=source_counts(
                image, stats.line_counts or {}))
        _write_line_counts(args.line_counts, prep, stats)
    print(summary_text(records, f, stats, args.trace, waves,
                       None if args.force else response_times(prep, records),
                       watchdog=args.watchdog,
                       fault_scan=len(records) if fault else None), end="")
    if args.status is not None:
        faulted = fault and len(records) == args.status    # the scan the watchdog ended
        if len(records) <= args.status and not faulted:
            raise UsageError(f"--status {args.status}: the run ended after "
                             f"{len(records)} scans")
        if args.mode == "parallel":
            print(parallel_block_status_text(prep.listing, stats.block_status or {},
                                             prep.byte_listing, stats.byte_status or {},
                                             args.status, args.sim, faulted), end="")
        else:
            status = stats.block_status or {}
            if image is not None:      # wide addresses -> the source's
                from bitbyte.run.status import source_status
                status = source_status(image, status)
            print(block_status_text(prep.listing, status, args.status,
                                    args.sim, ended_by_watchdog=faulted), end="")
    if fault:
        print(f"scan watchdog: {fault_scan_name(len(records), stats)} exceeded "
              f"{args.watchdog} clocks; "
              "outputs forced to 0", file=sys.stderr)
        return EXIT_WATCHDOG
    return 0


def _write_line_counts(path: str, prep, stats) -> None:
    rows = line_count_rows(prep.listing, stats.line_counts or {},
                           prep.byte_listing if prep.job.mode != "serial" else None,
                           stats.byte_line_counts)
    try:
        Path(path).write_text(line_counts_csv(rows))
    except OSError as e:
        raise UsageError(f"--line-counts: cannot write {path}: {e.strerror}") from None


def _wave_layout(args, prep, records, stats, image=None) -> str:
    """W.gtkw beside the waves W.fst: the layout in the program's names (spec §4);
    image: the wide build's (its words, not the program's instructions, execute)."""
    gtkw = str(Path(args.waves).with_suffix(".gtkw"))
    t0_ps = stats.wave_t0_ps     # clock 0; with OB 100 scan 0 latches after the startup
    if t0_ps is not None and stats.startup_cycles:
        t0_ps += sum(stats.startup_cycles) * harness_period_ps(prep.job.clock_hz)
    try:
        if image is not None:
            from bitbyte.wide.link import wave_listing
        write_gtkw(gtkw, args.waves, prep.program,
                   prep.listing if image is None else wave_listing(image),
                   serial=args.mode == "serial", clock_mhz=prep.f,
                   t0_ps=t0_ps, scan_clocks=records[0].cycles if records else None,
                   hardware_scans=len(stats.startup_cycles) + len(records))
    except WaveLayoutError as e:
        raise SimError(f"waveform layout {gtkw}: {e}") from None
    return gtkw


def cmd_run_plant(args) -> int:
    """`run PLANT.toml` (spec §7): every core on the multi-core system."""
    if args.until_us is None:
        raise UsageError("running a plant needs --until-us T")
    for opt, given in (("--mode", args.mode != "serial"), ("--exchange", args.exchange),
                       ("--stimulus", args.stimulus), ("--channels", args.channels),
                       ("--marker-write-buffer", args.marker_write_buffer),
                       ("--tc-path", args.tc_path != "channel"),
                       ("--clock-mhz", args.clock_mhz != "100"),
                       ("--status", args.status is not None), ("--force", args.force),
                       ("--exchange-log", args.exchange_log is not None),
                       ("--line-counts", args.line_counts is not None)):
        if given:
            raise UsageError(f"{opt} does not apply to a plant (the plant file sets it)")
    try:
        status, summary, _ = run_plant(args.program, until_us=args.until_us,
                                       trace=args.trace, watch=args.watch,
                                       waves=args.waves, watchdog=args.watchdog,
                                       costs=args.costs, sim=args.sim)
    except PlantRunError as e:
        raise SimError(str(e)) from None
    _plant_warnings(load_plant(args.program))      # read and checked by the run
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
