"""Run a RunJob on the Verilator C++ harness (sim/harness.cpp), building it through the
Makefile when it is missing or stale.  The harness writes the trace and reports its
figures as `stat NAME VALUE` lines; the summary text is bitbyte/run/summary.py's.
"""
from __future__ import annotations

import fcntl
from fractions import Fraction
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from bitbyte.lang.errors import SimError
from bitbyte.lang.trace import read_trace_rows, write_trace
from bitbyte.run.startup import hardware_job, startup_cycles, traced
from bitbyte.run.summary import RunStats, parse_block_status, parse_line_counts, parse_stats
from bitbyte.wide.link import hex_ext

ROOT = Path(__file__).resolve().parents[2]
HARNESS = ROOT / "sim" / "build" / "Vbitbyte_cpu"
# the wide bit engine's build (BitEngine=1, `make harness-wide`): runs a wide image
HARNESS_WIDE = ROOT / "sim" / "build" / "wide" / "Vbitbyte_cpu"
HARNESS_WATCHDOG = 3      # the harness's exit status when the scan watchdog stopped a run
GTKW = ROOT / "sim" / "bitbyte.gtkw"   # the waveform layout beside its waves


def harness_period_ps(clock_hz: int) -> int:
    """The harness's clock period in its waveform's ps (sim/harness.cpp: rounded)."""
    return max(2, (10 ** 12 + clock_hz // 2) // clock_hz)


def ensure_harness(wide: bool = False) -> Path:
    """Build sim/build/Vbitbyte_cpu (wide: the wide bit engine's build,
    sim/build/wide/) through the Makefile when it is missing or stale;
    BITBYTE_HARNESS (BITBYTE_HARNESS_WIDE) names another, built already
    (mutation/run_mutate.py's mutants)."""
    given = os.environ.get("BITBYTE_HARNESS_WIDE" if wide else "BITBYTE_HARNESS")
    if given:
        return Path(given)
    harness = HARNESS_WIDE if wide else HARNESS
    if harness in _BUILT and harness.exists():   # asked make once in this process
        return harness
    harness.parent.mkdir(parents=True, exist_ok=True)
    with open(HARNESS.parent / ".lock", "w") as lock:   # concurrent runs build once
        fcntl.flock(lock, fcntl.LOCK_EX)
        proc = subprocess.run(["make", "-s", "-C", str(ROOT),
                               "harness-wide" if wide else "harness"],
                              capture_output=True, text=True)
    if proc.returncode != 0 or not harness.exists():
        raise SimError("building the Verilator harness failed:\n" + proc.stdout + proc.stderr)
    _BUILT.add(harness)
    return harness


# The harnesses make has brought up to date in this process: a run does not ask it again
# (about 0.15 s a call, most of a short run's time; the RTL does not change under a
# running process)
_BUILT: set[Path] = set()


def progress_fd() -> tuple[int, int] | None:
    """Where the harness shows its progress line, and after how many seconds: this
    process's stderr when it is a terminal (after 2 s), or when BITBYTE_PROGRESS=S
    asks for it (after S seconds); None: no progress line (logs, tests)."""
    after = os.environ.get("BITBYTE_PROGRESS")
    if after is None and not sys.stderr.isatty():
        return None
    return os.dup(sys.stderr.fileno()), int(after) if after and after.isdigit() else 2


def run_harness(job, columns, trace: str | None = None, waves: str | None = None):
    """Run `job`; returns (records, watchdog fault?, RunStats).  trace: where the
    harness writes the trace CSV (else a temporary file; with startup scans it is
    written here, without them); waves: FST/VCD."""
    harness = ensure_harness(wide=job.prog_ext is not None)
    user_job, job = job, hardware_job(job)
    with tempfile.TemporaryDirectory(prefix="bitbyte-") as tmp:
        hex_path = Path(tmp) / "prog.hex"
        hex_path.write_text("".join(f"{w:08x}\n" for w in job.prog))
        trace_path = Path(trace).resolve() if trace and not user_job.startup_scans \
            else Path(tmp) / "trace.csv"
        waves = str(Path(waves).resolve()) if waves else None
        if waves:
            Path(waves).parent.mkdir(parents=True, exist_ok=True)
        run_file = Path(tmp) / "run.txt"
        byte_path = None
        if job.mode in ("parallel", "free"):
            byte_path = Path(tmp) / "byte.hex"
            byte_path.write_text("".join(f"{w:08x}\n" for w in job.byte_prog))
        ext_path = None
        if job.prog_ext is not None:     # the wide image's extension words
            ext_path = Path(tmp) / "prog.ext.hex"
            ext_path.write_text(hex_ext(job.prog_ext))
        text = job.to_harness_text(str(hex_path), str(trace_path), waves,
                                   str(byte_path) if byte_path else None,
                                   str(ext_path) if ext_path else None)
        progress = progress_fd()
        if progress is not None:
            text += f"progress {progress[0]} {progress[1]}\n"
        run_file.write_text(text)
        plusargs = os.environ.get("BITBYTE_HARNESS_ARGS", "").split()   # +name=value
        try:
            proc = subprocess.run([str(harness), str(run_file), *plusargs],
                                  capture_output=True, text=True,
                                  pass_fds=(progress[0],) if progress else ())
        finally:
            if progress is not None:
                os.close(progress[0])
        if proc.returncode not in (0, HARNESS_WATCHDOG):
            raise SimError(f"Verilator harness failed ({proc.returncode}):\n{proc.stderr}")
        records = read_trace_rows(trace_path, columns)
    st = parse_stats(proc.stdout)
    if st.get("scans") != len(records):
        raise SimError(f"Verilator harness: {st.get('scans')} scans reported, "
                       f"{len(records)} in its trace")
    # the CPU's own scan counter and longest scan (registers for a host: synth_top's
    # SPI read-back), against the scans the trace holds
    longest = max((r.cycles for r in records), default=0)
    if (st.get("scan_count"), st.get("scan_cycles_max")) != (len(records), longest):
        raise SimError(f"Verilator harness: the CPU counted {st.get('scan_count')} scans, "
                       f"the longest {st.get('scan_cycles_max')} clocks; its trace has "
                       f"{len(records)}, the longest {longest}")
    startup = startup_cycles(user_job, records)
    records = traced(user_job, records)
    if trace and user_job.startup_scans:
        write_trace(trace, columns, records, Fraction(job.clock_hz, 1_000_000))
    stats = RunStats(clocks=st["clocks"], stalls=(st["stalls_bit"], st["stalls_byte"]),
                     byte_scans=st.get("byte_scans"),
                     queue_losses=(st["queue_overflows"], st["queue_underflows"])
                     if "queue_overflows" in st else None,
                     byte_flags=st["byte_flags"], wall_s=st["wall_s"],
                     tc_inputs=(st["t_enable"], st["c_pulse"]) if "t_enable" in st else None,
                     wave_t0_ps=st.get("wave_t0_ps"),
                     startup_scans=user_job.startup_scans, startup_cycles=startup,
                     block_status=parse_block_status(proc.stdout)
                     if job.status_scan is not None else None,
                     byte_status=parse_block_status(proc.stdout, "bstatus")
                     if job.status_scan is not None and job.mode == "parallel" else None,
                     line_counts=parse_line_counts(proc.stdout) if job.line_counts else None,
                     byte_line_counts=parse_line_counts(proc.stdout, "bcount")
                     if job.line_counts and job.mode != "serial" else None)
    return records, proc.returncode == HARNESS_WATCHDOG, stats
