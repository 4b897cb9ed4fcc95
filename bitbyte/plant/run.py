"""`bitbyte run PLANT.toml`: a multi-core plant on the simulated hardware (spec §7).

The linker (`plant.link`) gives every core its program and its precycle / postcycle
copy lists; this module encodes those lists as the copy-plan words that the core
sequencer (rtl/core_seq.v) streams, writes the plant harness's run file
(sim/plant_harness.cpp, sim/README.md "Plants") and runs it: one trace per core,
`T.<core>.csv`, header `scan,t_us,cycles,pre,post,sem_wait,copy_fail,overrun`, then the
core's Q and QW columns and its watched operands.

Copy-plan words (docs/multicore.md, "The copy engine"):
  descriptor  bit 31 = 1, bits 23..16 the writing core (ping-pong buffer select)
  item        bit 31 = 0, bit 30 bit (1) / word (0), bits 29..25 the bit in the
              shared word, bits 24..12 the shared word, bits 11..0 the local address
              (M bit number byte*8+bit, or the MW index)
"""
from __future__ import annotations

import fcntl
import os
import subprocess
import tempfile
from pathlib import Path

from bitbyte.plant.link import SharedMap, link, load_plant
from bitbyte.plant.plans import (MAX_CORES, SHARED_WORDS, PlantRunError, encode_plans,
                                 period_clocks)
from bitbyte.lang.errors import SourceError, UsageError
from bitbyte.plant.cocotb_runner import run_plant_cocotb
from bitbyte.run.prepare import prepare
from bitbyte.run.summary import hw_mode_text, parse_stats, plant_summary_text
from bitbyte.sim.gtkw import WaveLayoutError, write_plant_gtkw
from bitbyte.sim.verilator import progress_fd

ROOT = Path(__file__).resolve().parents[2]
PLANT_GTKW = ROOT / "sim" / "plant.gtkw"     # the waveform layout beside a plant's waves
def plant_harness_path(cores: int) -> Path:
    return ROOT / "sim" / "build" / f"plant{cores}" / "Vplc_system"


def ensure_plant_harness(cores: int = 2) -> Path:
    """Build sim/build/plant<cores>/Vplc_system (plc_system with Cores = cores) through
    the Makefile when missing or stale.  BITBYTE_PLANT_HARNESS_<cores> names another,
    built already (mutation/run_mutate.py's plant mutants)."""
    other = os.environ.get(f"BITBYTE_PLANT_HARNESS_{cores}")
    if other:
        return Path(other)
    binary = plant_harness_path(cores)
    binary.parent.mkdir(parents=True, exist_ok=True)
    with open(binary.parent / ".lock", "w") as lock:   # concurrent runs build once
        fcntl.flock(lock, fcntl.LOCK_EX)
        proc = subprocess.run(["make", "-s", "-C", str(ROOT), "plant-harness",
                               f"CORES={cores}"], capture_output=True, text=True)
    if proc.returncode != 0 or not binary.exists():
        raise PlantRunError("building the plant harness failed:\n" + proc.stdout + proc.stderr)
    return binary


def split_watch(watch: str, core_names: list[str]) -> dict[str, list[str]]:
    """`p1.MW20,p2.C0` -> {'P1': ['MW20'], 'P2': ['C0']} (core names case-insensitive)."""
    out: dict[str, list[str]] = {n.upper(): [] for n in core_names}
    for part in (w.strip() for w in watch.split(",")):
        if not part:
            continue
        core, dot, operand = part.partition(".")
        if not dot or core.upper() not in out or not operand.strip():
            raise UsageError(f"--watch: {part!r} is not CORE.OPERAND with a core of the "
                             f"plant ({', '.join(core_names)})")
        out[core.upper()].append(operand.strip())
    return out


def prepare_plant(plant_path: str, *, until_us: str, watch: str = "",
                  watchdog: int = 100_000, costs: str = "paper"):
    """Link the plant and prepare one RunJob per core (bitbyte.run.prepare does the
    program, stimulus and trace columns, as for a single CPU, in the core's mode:
    a parallel core's program partitioned as `run --mode parallel` does).

    Returns (shared_map, jobs, preps, plans, until_clock): preps the cores'
    bitbyte.run.prepare.Prepared (program, trace columns, listing), in plant order."""
    plant = load_plant(plant_path)
    shared_map = link(plant)
    if not 2 <= len(plant.cores) <= MAX_CORES:
        raise SourceError(plant_path, 0, 0, f"this release simulates plants of 2 to "
                          f"{MAX_CORES} cores, not {len(plant.cores)}")
    if shared_map.size_words > SHARED_WORDS:
        raise SourceError(plant_path, 0, 0, f"{shared_map.size_words} shared words exceed "
                          f"the shared memory ({SHARED_WORDS} words)")
    plans = encode_plans(shared_map)
    watches = split_watch(watch, [c.name for c in plant.cores])
    preps = []
    clock_text = str(plant.clock_mhz)
    for core in plant.cores:
        try:
            preps.append(prepare(core.program, stimulus=core.stimulus,
                                 watch=",".join(watches[core.name.upper()]),
                                 until_us=until_us, watchdog=watchdog,
                                 clock_mhz=clock_text, costs=costs,
                                 mode=core.mode, exchange=core.exchange))
        except UsageError as e:                     # name the core a watch belongs to
            text = str(e)
            if text.startswith("--watch: "):
                raise UsageError(f"--watch: core {core.name}: {text[9:]}") from None
            raise
    jobs = [p.job for p in preps]
    until_clock = jobs[0].until_clock
    if until_clock >= 2 ** 62:
        raise UsageError("--until-us: too far (at most 2^62 clocks)")
    return shared_map, jobs, preps, plans, until_clock


def run_file_text(shared_map: SharedMap, jobs, plans, until_clock: int, tmp: Path,
                  trace_base: str | None, waves: str | None) -> str:
    plant = shared_map.plant
    lines = [f"clock_hz {jobs[0].clock_hz}", f"watchdog {jobs[0].watchdog}",
             f"until_clock {until_clock}", f"protect {plant.protection}",
             f"gtkw {PLANT_GTKW}"]
    if waves:
        lines.append(f"waves {waves}")
    for i, (core, job, plan) in enumerate(zip(plant.cores, jobs, plans)):
        prog = tmp / f"{core.name}.hex"
        prog.write_text("".join(f"{w:08x}\n" for w in job.prog))
        plan_path = tmp / f"{core.name}.plan.hex"
        plan_path.write_text("".join(f"{w:08x}\n" for w in plan.words))
        trace = (f"{trace_base}.{core.name}.csv" if trace_base
                 else str(tmp / f"trace.{core.name}.csv"))
        byte_prog = None
        if job.mode == "parallel":                      # the byte part of the program
            byte_prog = tmp / f"{core.name}.byte.hex"
            byte_prog.write_text("".join(f"{w:08x}\n" for w in job.byte_prog))
        job.until_clock, job.scans = None, None
        text = job.to_harness_text(str(prog), trace, None,
                                   str(byte_prog) if byte_prog else None)
        lines += [f"core {i}", f"name {core.name}", f"plan {plan_path}",
                  f"period {period_clocks(core.period_us, plant.clock_mhz)}",
                  f"pre_len {plan.pre_len}", f"post_base {plan.post_base}",
                  f"post_len {plan.post_len}"]
        # the per-core keys of a single CPU's run file, minus the plant-wide ones
        lines += [l for l in text.splitlines()
                  if l.split(" ", 1)[0] not in ("clock_hz", "watchdog", "until_clock",
                                                "scans")]
    return "\n".join(lines) + "\n"


def trace_base_of(trace: str) -> str:
    """`T.csv` -> `T` (the traces are `T.<core>.csv`)."""
    return trace[:-4] if trace.lower().endswith(".csv") else trace


def _plant_layout(plant, waves: str, preps) -> str:
    """W.gtkw beside the plant's waves: every core's project in its own names, the
    semaphore's owner by core name (bitbyte.sim.gtkw); the first view two periods of
    the slowest core.  preps: the cores' Prepared (program, bit processor listing)."""
    gtkw = str(Path(waves).with_suffix(".gtkw"))
    cores = [(c.name, p.program, p.listing, c.mode == "serial")
             for c, p in zip(plant.cores, preps)]
    view = 2 * max(c.period_us for c in plant.cores) * plant.clock_mhz
    try:
        write_plant_gtkw(gtkw, waves, cores, clock_mhz=plant.clock_mhz,
                         view_clocks=int(view))
    except WaveLayoutError as e:
        raise PlantRunError(f"waveform layout {gtkw}: {e}") from None
    return gtkw


def run_plant(plant_path: str, *, until_us: str, trace: str | None = None,
              watch: str = "", waves: str | None = None, watchdog: int = 100_000,
              costs: str = "paper", sim: str = "verilator"
              ) -> tuple[int, str, dict[str, list[dict[str, str]]]]:
    """Run a plant on the Verilator plant harness (sim "verilator"), or through
    cocotb on Icarus ("icarus") or on Verilator ("cocotb-verilator"): the same traces.

    Returns (harness exit status, summary text, {core: rows as dicts of strings})."""
    import csv
    if sim not in ("verilator", "icarus", "cocotb-verilator"):
        raise PlantRunError(f"unknown simulator {sim!r}")
    if sim != "verilator" and waves:
        raise UsageError("--waves is written by the Verilator plant harness; "
                         "use --sim verilator")
    shared_map, jobs, preps, plans, until_clock = prepare_plant(
        plant_path, until_us=until_us, watch=watch, watchdog=watchdog, costs=costs)
    if trace:          # every trace file writable before the run (OSError: exit 1)
        for core in shared_map.plant.cores:
            open(f"{trace_base_of(trace)}.{core.name}.csv", "w").close()
    vcd = None
    if waves:
        if not waves.lower().endswith((".fst", ".vcd")):
            raise UsageError("--waves: the file must end in .fst or .vcd")
        waves = str(Path(waves).resolve())
        if waves.lower().endswith(".vcd"):      # the harness writes FST: convert after
            vcd, waves = waves, waves + ".tmp.fst"
    if sim != "verilator":
        base = str(Path(trace_base_of(trace)).resolve()) if trace else None
        with tempfile.TemporaryDirectory(prefix="bitbyte-plant-") as tmpdir:
            return run_plant_cocotb(shared_map, jobs, plans, until_clock,
                                    sim.removeprefix("cocotb-"), base, tmpdir)
    harness = ensure_plant_harness(len(shared_map.cores))
    with tempfile.TemporaryDirectory(prefix="bitbyte-plant-") as tmpdir:
        tmp = Path(tmpdir)
        base = str(Path(trace_base_of(trace)).resolve()) if trace else None
        if waves:
            waves = str(Path(waves).resolve())
            Path(waves).parent.mkdir(parents=True, exist_ok=True)
        run = tmp / "plant.run"
        text = run_file_text(shared_map, jobs, plans, until_clock, tmp, base, waves)
        progress = progress_fd()
        if progress is not None:
            text = f"progress {progress[0]} {progress[1]}\n" + text   # a plant key: before the cores
        run.write_text(text)
        try:
            plusargs = os.environ.get("BITBYTE_HARNESS_ARGS", "").split()   # +name=value
            proc = subprocess.run([str(harness), str(run), *plusargs], capture_output=True,
                                  text=True,
                                  pass_fds=(progress[0],) if progress else ())
        finally:
            if progress is not None:
                os.close(progress[0])
        if proc.returncode not in (0, 3):
            raise PlantRunError(f"plant harness failed ({proc.returncode}):\n{proc.stderr}")
        rows = {}
        for core in shared_map.plant.cores:
            path = (f"{base}.{core.name}.csv" if base else str(tmp / f"trace.{core.name}.csv"))
            with open(path, newline="") as f:
                rows[core.name] = list(csv.DictReader(f))
    if vcd:
        conv = subprocess.run(["fst2vcd", "-f", waves, "-o", vcd], capture_output=True,
                              text=True)
        if conv.returncode != 0:
            raise PlantRunError(f"fst2vcd failed (is gtkwave installed?): {conv.stderr}")
        Path(waves).unlink()
        waves = vcd
    st = parse_stats(proc.stdout)
    # the plant's own time base (plc_system time_o, clocks since the plant runs) against
    # the clocks the harness simulated, as the single CPU's counters are checked
    if st.get("time_o") != st["clocks"]:
        raise PlantRunError(f"plant harness: the plant's time base time_o says "
                            f"{st.get('time_o')} clocks, the harness ran {st['clocks']}")
    plant = shared_map.plant
    summary = plant_summary_text(
        plant.protection, jobs[0].clock_hz, st["clocks"],
        [(c.name, hw_mode_text(st[f"parallel.{c.name}"], st[f"exchange.{c.name}"]),
          rows[c.name], st[f"skips.{c.name}"]) for c in plant.cores],
        (waves, _plant_layout(plant, waves, preps)) if waves else None)
    if proc.returncode == 3:
        summary += proc.stderr
    return proc.returncode, summary, rows

