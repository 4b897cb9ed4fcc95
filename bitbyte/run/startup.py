"""The startup scans on the hardware runners (Program.startup_scans; docs/s7.md "OB
100: the startup"): an S7 source's OB 100 runs in the first hardware scan, before
scan 0, and that scan is not a scan of the trace.

A RunJob states the run as the user sees it (scans, scan-keyed stimulus rows,
`--status`, `--force` keyed by trace scans) plus `startup_scans`; hardware_job() is
the job the hardware runs (the Verilator harness, cocotb), with that many scans more
in front, and traced() turns the hardware's records back into the trace's: this is
the one place that shifts scan numbers.  (The reference interpreter runs the startup
scans itself: bitbyte.ref.refsim.RefSim.run_scan.)

In the startup scans the inputs are scan 0's (spec §9's oracle awlsim reads its
inputs before OB 100, as before each cycle); a `t_us` stimulus needs no shift (time
counts from reset, the startup scans included), nor does `--until-us`'s clock, but
it stops no run in a startup scan (spec §4: the first scan ending at or after T is a
scan of the trace; the hardware job's until_min_scans: the startup scans and scan 0).
"""
from __future__ import annotations

import dataclasses

from bitbyte.lang.trace import ScanRecord
from bitbyte.run.force import BEFORE_RUN
from bitbyte.run.runjob import RunJob


def hardware_job(job: RunJob) -> RunJob:
    """The job as the hardware runs it: `startup_scans` more scans; scan-keyed
    stimulus rows, the --status scan and the --force tables of scan k moved to
    hardware scan k + n, scan 0's inputs also in the n scans before."""
    n = job.startup_scans
    if not n:
        return job
    stim = job.stim
    if job.stim_kind == "scan":
        stim = [(key + n, pins, words) for key, pins, words in job.stim]
        if job.stim and job.stim[0][0] == 0:
            stim.insert(0, job.stim[0])
    return dataclasses.replace(
        job, startup_scans=0, stim=stim,
        scans=None if job.scans is None else job.scans + n,
        until_min_scans=n + 1 if job.until_clock is not None else 0,
        status_scan=None if job.status_scan is None else job.status_scan + n,
        # the table written before RUN holds through the startup scans into scan 0
        force=[(key if key == BEFORE_RUN else key + n, *rest)
               for key, *rest in job.force])


def startup_cycles(job: RunJob, records: list) -> tuple[int, ...]:
    """The clocks of each startup scan the hardware completed (its records before
    traced() drops them): the run summary's `startup scan` line and watchdog margin
    (the watchdog times the startup scans as any scan)."""
    return tuple(r.cycles for r in records[:job.startup_scans])


def traced(job: RunJob, records: list) -> list:
    """The hardware's records without the startup scans, numbered from 0 (end clocks
    stay counted from reset: t_us includes the startup)."""
    n = job.startup_scans
    if not n:
        return records
    return [ScanRecord(r.scan - n, r.end_clock, r.cycles, r.values) for r in records[n:]]
