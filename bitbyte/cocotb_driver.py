"""cocotb driver of rtl/bitbyte_cpu.v: runs the RunJobs named by $BITBYTE_JOBS and
writes the RunResults to $BITBYTE_RESULTS.

The protocol is the one of docs/isa.md's timing model and of the C++ harness: load
the program in reset, wait for `ready_o`, raise `run_i` for one clock, then clock 0 is
the PII latch of scan 0. Inputs for clock n are driven at the falling edge inside
clock n; a scan's results are read at the falling edge after the edge that ended it.
"""
from __future__ import annotations

import json
import os

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, Timer

from bitbyte.runjob import RunJob

PERIOD_NS = 10      # simulator time only; reported time uses the job's clock_hz
MARKER_BITS = 2048  # the marker RAM clears one bit per clock after reset


def _reader(dut, kind: str, index: int):
    """A function returning the current value of one traced column."""
    if kind == "q":
        return lambda: (int(dut.out_pins_o.value) >> index) & 1
    if kind == "pi":
        return lambda: (int(dut.in_pins_i.value) >> index) & 1
    images = {"i": "pii_o", "ir": "rise_o", "if": "fall_o"}
    if kind in images:
        sig = getattr(dut.u_input_unit, images[kind])
        return lambda: (int(sig.value) >> index) & 1
    if kind == "m":
        cell = dut.u_bit_proc.u_marker_ram.mem[index]
        return lambda: int(cell.value) & 1
    if kind == "t":
        sig = dut.u_tc_status.timer_status_o
        return lambda: (int(sig.value) >> index) & 1
    if kind == "c":
        sig = dut.u_tc_status.counter_status_o
        return lambda: (int(sig.value) >> index) & 1
    return lambda: 0


async def run_job(dut, job: RunJob) -> dict:
    dut.rst_ni.value = 0
    dut.run_i.value = 0
    dut.in_pins_i.value = 0
    dut.watchdog_limit_i.value = job.watchdog
    for addr, word in enumerate(job.prog):
        await FallingEdge(dut.clk_i)
        dut.prog_we_i.value = 1
        dut.prog_waddr_i.value = addr
        dut.prog_wdata_i.value = word
    await FallingEdge(dut.clk_i)
    dut.prog_we_i.value = 0
    dut.rst_ni.value = 1
    await Timer(MARKER_BITS * PERIOD_NS, unit="ns")
    while not int(dut.ready_o.value):
        await FallingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.run_i.value = 1                    # this clock is still IDLE
    await FallingEdge(dut.clk_i)           # now inside clock 0, the latch of scan 0

    readers = [_reader(dut, kind, index) for _, kind, index in job.cols]
    stim = list(job.stim)
    next_stim = 0
    rows, fault = [], False
    clock, scan = 0, 0
    pins = 0
    while True:
        if int(dut.fault_o.value):
            fault = True
            break
        if int(dut.scan_done_o.value):
            rows.append((scan, clock, int(dut.scan_cycles_o.value), [r() for r in readers]))
            scan += 1
            if job.scans is not None and scan >= job.scans:
                break
            if job.until_clock is not None and clock >= job.until_clock:
                break
        # Inputs for this clock: scan rows switch at the latch of their scan (the
        # clock right after scan_done / clock 0), time rows at their clock.
        key = scan if job.stim_kind == "scan" else clock
        latch_clock = clock == 0 or int(dut.scan_done_o.value)
        if job.stim_kind == "clock" or (job.stim_kind == "scan" and latch_clock):
            while next_stim < len(stim) and stim[next_stim][0] <= key:
                pins = stim[next_stim][1]
                next_stim += 1
            dut.in_pins_i.value = pins
        await FallingEdge(dut.clk_i)
        clock += 1
    return {"rows": rows, "fault": fault, "clocks": clock}


@cocotb.test()
async def run_jobs(dut):
    """Execute every job of $BITBYTE_JOBS in order."""
    jobs = [RunJob.from_json(d) for d in json.load(open(os.environ["BITBYTE_JOBS"]))]
    cocotb.start_soon(Clock(dut.clk_i, PERIOD_NS, unit="ns").start())
    for sig in (dut.prog_we_i, dut.prog_waddr_i, dut.prog_wdata_i, dut.in_words_i,
                dut.bus_addr_i, dut.bus_wdata_i, dut.bus_we_i, dut.bus_re_i):
        sig.value = 0
    results = [await run_job(dut, job) for job in jobs]
    with open(os.environ["BITBYTE_RESULTS"], "w") as f:
        json.dump(results, f)
