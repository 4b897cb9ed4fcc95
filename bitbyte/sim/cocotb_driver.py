"""cocotb driver of rtl/bitbyte_cpu.v: runs the RunJobs named by $BITBYTE_JOBS and
writes the RunResults to $BITBYTE_RESULTS.

The protocol is the one of docs/isa.md's timing model and of the C++ harness: load
the program in reset, wait for `ready_o`, raise `run_i` for one clock, then clock 0 is
the PII latch of scan 0. Inputs for clock n are driven at the falling edge inside
clock n; a scan's results are read at the falling edge after the edge that ended it.

The byte processor is the real firmware (firmware_byte/, loaded with ctypes). It runs
in a bridged thread (cocotb.task.bridge); each HAL call it makes is a resume-wrapped
coroutine that drives the bus and awaits clock edges, so the C code blocks exactly
as long as its bus accesses and its `hal_spend` take in simulated clocks. The HAL
reaches this job's callbacks through the state's HAL context (a bb_hal_callbacks
table, firmware_byte/hal_callbacks.h), not through globals of the library.

The design is observed through its ports only: the trace columns I, IR, IF, T, C read
the observation ports dbg_*; a marker M n is looked up through dbg_m_addr_i / dbg_m_o
(a new address settles in one simulator step, at the falling edge where a row is
read, half a clock before the next edge).
"""
from __future__ import annotations

import ctypes
import inspect
import json
import os
from pathlib import Path

import cocotb
from cocotb.clock import Clock
from cocotb.task import bridge, resume
from cocotb.triggers import Event, FallingEdge, First, ReadOnly, RisingEdge, Timer
from cocotb.utils import get_sim_steps, get_sim_time

from bitbyte.lang.definition import DEF
from bitbyte.run.runjob import RunJob

BUS = DEF.bus                          # byte-bus register addresses

FIRMWARE_LIB = Path(__file__).resolve().parents[2] / "firmware_byte" / "build" / \
    "libbyteproc_cb.so"

PERIOD_NS = 10      # simulator time only; reported time uses the job's clock_hz
MARKER_BITS = DEF.sizes["marker_bytes"] * 8  # the marker RAM clears one bit per clock after reset


def _word(vector, index: int) -> int:
    return _signed16((int(vector.value) >> (16 * index)) & 0xFFFF)


def _signed16(v: int) -> int:
    return v - 0x10000 if v & 0x8000 else v


class _MarkerLook:
    """M n through the look-up port: dbg_m_o shows M[dbg_m_addr_i]."""

    def __init__(self, dut):
        self.dut = dut
        self.addr = 0                        # what dbg_m_addr_i holds (run_job sets 0)

    async def __call__(self, n: int) -> int:
        if n != self.addr:
            self.dut.dbg_m_addr_i.value = self.addr = n
            await Timer(1, unit="step")      # combinational: settled one step later
        return int(self.dut.dbg_m_o.value) & 1


def _reader(dut, kind: str, index: int, mw=None, look=None):
    """A function returning the current value of one traced column (for M n: a
    coroutine function; MW n: `mw(n)`, the firmware's word)."""
    if kind == "mw":
        return lambda: mw(index)
    if kind == "qw":
        return lambda: _word(dut.out_words_o, index)
    if kind == "iw":
        return lambda: _word(dut.in_words_i, index)
    if kind == "q":
        return lambda: (int(dut.out_pins_o.value) >> index) & 1
    if kind == "pi":
        return lambda: (int(dut.in_pins_i.value) >> index) & 1
    ports = {"i": dut.dbg_pii_o, "ir": dut.dbg_rise_o, "if": dut.dbg_fall_o,
             "qr": dut.dbg_q_rise_o, "qf": dut.dbg_q_fall_o,
             "t": dut.dbg_timer_status_o, "c": dut.dbg_counter_status_o}
    if kind in ports:
        sig = ports[kind]
        return lambda: (int(sig.value) >> index) & 1
    if kind == "m":
        return lambda: look(index)
    return lambda: 0


class HalCallbacks(ctypes.Structure):
    """firmware_byte/hal_callbacks.h: bb_hal_callbacks, one per firmware state (its HAL
    context)."""
    _fields_ = [("bus_read", ctypes.CFUNCTYPE(ctypes.c_uint32, ctypes.c_uint16)),
                ("bus_write", ctypes.CFUNCTYPE(None, ctypes.c_uint16, ctypes.c_uint32)),
                ("spend", ctypes.CFUNCTYPE(None, ctypes.c_uint32)),
                ("wait_dispatch", ctypes.CFUNCTYPE(None)),
                ("now", ctypes.CFUNCTYPE(ctypes.c_uint64))]


def hal_callbacks(read, write, spend, wait, now) -> HalCallbacks:
    """A callback table of Python functions (they must outlive the C calls: keep the
    table)."""
    types = dict((name, t) for name, t in HalCallbacks._fields_)
    return HalCallbacks(types["bus_read"](read), types["bus_write"](write),
                        types["spend"](spend), types["wait_dispatch"](wait),
                        types["now"](now))


def load_firmware(path):
    """firmware_byte's shared library through ctypes, with the signatures (byteproc.h)
    of what the cocotb hosts call: one load serves every byte processor of a process."""
    vp, uint = ctypes.c_void_p, ctypes.c_uint
    signatures = {                                  # name: (argument types, result type)
        "bb_new": ([], vp), "bb_free": ([vp], None),
        "bb_cost_table": ([ctypes.c_char_p], vp), "bb_init": ([vp, vp], None),
        "bb_set_hal_ctx": ([vp, vp], None), "bb_set_mw_bus": ([vp, ctypes.c_int], None),
        "bb_load_pool": ([vp, vp, uint], None), "bb_load_program": ([vp, vp, uint], ctypes.c_int),
        "bb_run_step": ([vp, ctypes.c_int], ctypes.c_int), "bb_run": ([vp, ctypes.c_int], None),
        "bb_mw": ([vp, uint], ctypes.c_int16), "bb_flags": ([vp], ctypes.c_uint32),
        "bb_byte_scans": ([vp], ctypes.c_uint64),
        "bb_accu1": ([vp], ctypes.c_int32), "bb_accu2": ([vp], ctypes.c_int32),
        "bb_ret_seq": ([vp], ctypes.c_uint64), "bb_ret_pc": ([vp], ctypes.c_uint32),
        "bb_ret_rlo": ([vp], ctypes.c_int), "bb_ret_accu1": ([vp], ctypes.c_int32),
        "bb_ret_accu2": ([vp], ctypes.c_int32)}
    lib = ctypes.CDLL(str(path))
    for name, (args, result) in signatures.items():
        fn = getattr(lib, name)
        fn.argtypes, fn.restype = args, result
    return lib


class Firmware:
    """The byte processor: firmware_byte's C code with a HAL onto this simulation."""

    _lib = None

    def __init__(self, dut, job: RunJob, clock0_ns: float):
        lib = Firmware._load()
        self.dut, self.clock0_ns = dut, clock0_ns
        self.stopped = Event()
        self.state = lib.bb_new()
        lib.bb_init(self.state, lib.bb_cost_table(job.costs.encode()))
        if job.pool:
            words = (ctypes.c_uint32 * len(job.pool))(*job.pool)
            lib.bb_load_pool(self.state, words, len(job.pool))
        self.parallel = job.mode == "parallel"
        self.free = job.mode == "free"
        if self.parallel or self.free:
            words = (ctypes.c_uint32 * len(job.byte_prog))(*job.byte_prog)
            lib.bb_load_program(self.state, words, len(job.byte_prog))
        # The HAL: each callback runs in the firmware's thread and blocks on a coroutine;
        # the table is this state's HAL context.
        # --force: the host's writes of the force table go over the byte bus in clocks
        # the byte processor leaves it idle (_spend, _wait), as sim/harness.cpp does
        self.forces = {key: vectors for key, *vectors in job.force}
        self.force_written = [0, 0, 0, 0]
        self.host_writes: list[tuple[int, int]] = []
        self.host_queued = Event()             # wakes an idle byte processor for them
        self._hal = hal_callbacks(resume(self._read), resume(self._write),
                                  resume(self._spend), resume(self._wait), self._now)
        lib.bb_set_hal_ctx(self.state, ctypes.byref(self._hal))

    @classmethod
    def _load(cls):
        if cls._lib is None:
            cls._lib = load_firmware(FIRMWARE_LIB)
        return cls._lib

    def mw(self, n: int) -> int:
        return int(self._lib.bb_mw(self.state, n))

    def accus(self) -> tuple[int, int]:
        return int(self._lib.bb_accu1(self.state)), int(self._lib.bb_accu2(self.state))

    def retired(self) -> tuple[int, int, int, int, int]:
        """The byte part's last completed instruction: (count so far, its address,
        F_B, ACCU1, ACCU2 after it) — bb_ret_* (parallel mode)."""
        lib, s = self._lib, self.state
        return (int(lib.bb_ret_seq(s)), int(lib.bb_ret_pc(s)), int(lib.bb_ret_rlo(s)),
                int(lib.bb_ret_accu1(s)), int(lib.bb_ret_accu2(s)))

    def stats(self) -> dict:
        """The firmware's part of the run summary (bitbyte.run.summary.RunStats)."""
        return {"byte_flags": int(self._lib.bb_flags(self.state)),
                "byte_scans": int(self._lib.bb_byte_scans(self.state)) if self.free else None}

    def close(self):
        self._lib.bb_set_hal_ctx(self.state, None)
        self._lib.bb_free(self.state)

    # HAL (docs/byte-bus.md). Each runs at a falling edge: "this clock" is the clock
    # whose falling edge it is; an access takes the clock and returns at the next one.
    async def _access(self, addr: int, data: int | None) -> int:
        dut = self.dut
        while not self.stopped.is_set():
            dut.bus_addr_i.value = addr
            dut.bus_re_i.value = int(data is None)
            dut.bus_we_i.value = int(data is not None)
            dut.bus_wdata_i.value = data or 0
            await Timer(1, unit="ns")                    # combinational read data
            rdata, ready = int(dut.bus_rdata_o.value), int(dut.bus_ready_o.value)
            await FallingEdge(dut.clk_i)
            dut.bus_re_i.value = dut.bus_we_i.value = 0
            if ready:
                return rdata
        return 0

    async def _read(self, addr: int) -> int:
        return await self._access(addr, None)

    async def _write(self, addr: int, data: int) -> None:
        await self._access(addr, data)

    def queue_force(self, key: int) -> None:
        """The force table for scan `key` (bitbyte.run.force), its changed registers."""
        if key not in self.forces:
            return
        base = BUS["FORCE_IN_MASK"]
        for g, vector in enumerate(self.forces[key]):
            for n in range(4):
                word = vector >> (32 * n) & 0xFFFFFFFF
                if word != self.force_written[g] >> (32 * n) & 0xFFFFFFFF:
                    self.host_writes.append((base + 4 * g + n, word))
            self.force_written[g] = vector
        if self.host_writes:
            self.host_queued.set()

    async def _host_clock(self) -> None:
        """An idle clock of the byte processor carrying the next host write."""
        dut = self.dut
        dut.bus_addr_i.value, dut.bus_wdata_i.value = self.host_writes.pop(0)
        dut.bus_we_i.value = 1
        await FallingEdge(dut.clk_i)
        dut.bus_we_i.value = 0

    async def _spend(self, clocks: int) -> None:
        # from one falling edge to the falling edge `clocks` clocks later, in one wait
        # unless host writes come (queued at a falling edge: their clocks start there)
        end = get_sim_time("ns") + clocks * PERIOD_NS
        while not self.stopped.is_set() and get_sim_time("ns") < end:
            if self.host_writes:
                await self._host_clock()
                continue
            self.host_queued.clear()
            await First(Timer(end - get_sim_time("ns"), unit="ns"), self.host_queued.wait())

    async def _wait(self) -> None:
        # NEXT is combinational: an event-driven simulator may show it rising for a
        # moment at a clock edge (registers updated one by one), so it is looked at
        # again in the clock itself
        dut = self.dut
        while not (int(dut.byte_next_o.value) or self.stopped.is_set()):
            if self.host_writes:
                await self._host_clock()
                continue
            self.host_queued.clear()
            next_rose = RisingEdge(dut.byte_next_o)
            fired = await First(next_rose, self.stopped.wait(), self.host_queued.wait())
            if fired is next_rose and not self.stopped.is_set():
                await FallingEdge(dut.clk_i)           # into the dispatch clock

    def _now(self) -> int:
        return int((get_sim_time("ns") - self.clock0_ns) // PERIOD_NS)

    def run_until_stopped(self) -> None:
        """The firmware's main loop (in the bridged thread): serial mode executes
        dispatched instructions; parallel mode runs its byte part from each scan's
        latch clock (NEXT) and reports SCAN_DONE."""
        lib = self._lib
        mode = DEF.modes["parallel" if self.parallel else "free" if self.free else "serial"]
        while not self.stopped.is_set():       # the firmware's main loop, turn by turn
            lib.bb_run_step(self.state, mode)


class RunError(Exception):
    """A run the user asked for cannot be done as asked (bitbyte.run.force's table)."""


async def run_job(dut, job: RunJob) -> dict:
    dut.rst_ni.value = 0
    dut.run_i.value = 0
    dut.in_pins_i.value = 0
    dut.in_words_i.value = 0               # nothing of the previous job carries over
    dut.mcopy_en_i.value = 0               # a single CPU: no copy engine
    dut.time_start_i.value = 0             # ... and its time base starts at its latch
    dut.mcopy_we_i.value = 0
    dut.mcopy_addr_i.value = 0
    dut.mcopy_wdata_i.value = 0
    dut.dbg_m_addr_i.value = 0             # the marker look-up port (_MarkerLook)
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
    dut.bus_addr_i.value, dut.bus_wdata_i.value = BUS["TICK_DIV"], job.clock_hz // 1000
    dut.bus_we_i.value = 1
    await FallingEdge(dut.clk_i)
    dut.bus_we_i.value = 0
    firmware = Firmware(dut, job, 0.0)
    firmware.queue_force(-1)                # --force: the table before RUN, at once
    for addr, word in firmware.host_writes:
        dut.bus_addr_i.value, dut.bus_wdata_i.value, dut.bus_we_i.value = addr, word, 1
        await FallingEdge(dut.clk_i)
        dut.bus_we_i.value = 0
    firmware.host_writes.clear()
    firmware.queue_force(0)                 # ... then scan 0's, during scan 0
    dut.parallel_i.value = int(job.mode == "parallel")
    dut.free_i.value = int(job.mode == "free")
    dut.marker_write_buffer_i.value = int(job.marker_write_buffer)
    dut.exchange_i.value = DEF.exchanges.index(job.exchange)
    dut.run_i.value = 1                    # this clock is still IDLE
    await FallingEdge(dut.clk_i)           # now inside clock 0, the latch of scan 0

    firmware.clock0_ns = get_sim_time("ns")
    fw_thread = cocotb.start_soon(bridge(firmware.run_until_stopped)())
    status: dict[int, list[int]] = {}
    byte_status: dict[int, list[int]] = {}
    monitor = (cocotb.start_soon(_block_status(dut, job.status_scan, firmware, status,
                                               byte_status if job.mode == "parallel" else None))
               if job.status_scan is not None else None)
    try:
        result = await _scans(dut, job, firmware)
        result["block_status"] = status if monitor is not None else None
        result["byte_status"] = (byte_status if monitor is not None and job.mode == "parallel"
                                 else None)
        if monitor is not None:
            monitor.cancel()
    finally:
        firmware.stopped.set()
        await fw_thread
        firmware.close()
        dut.bus_re_i.value = dut.bus_we_i.value = 0
    return result


async def _block_status(dut, status_scan: int, firmware: Firmware,
                        out: dict[int, list[int]],
                        byte_out: dict[int, list[int]] | None) -> None:
    """bitbyte run --status, as the C++ harness keeps it: after every clock edge of
    scan `status_scan`, the instruction that retired in that clock (the bit
    processor's retirement port), its RLO after, its operand bit, and the firmware's
    accumulators (the firmware thread waits inside the HAL call spanning the clock)."""
    scan, byte_seq = 0, 0
    while scan <= status_scan:
        await RisingEdge(dut.clk_i)
        await ReadOnly()
        if scan == status_scan and int(dut.dbg_ret_valid_o.value):
            pc = int(dut.dbg_ret_pc_o.value)
            count = out[pc][0] + 1 if pc in out else 1
            out[pc] = [count, int(dut.dbg_rlo_o.value), int(dut.dbg_ret_opnd_o.value),
                       *firmware.accus()]
        if byte_out is not None:                # parallel mode: the byte part's record
            seq, pc, rlo, accu1, accu2 = firmware.retired()
            if scan == status_scan and seq != byte_seq:
                count = byte_out[pc][0] + 1 if pc in byte_out else 1
                byte_out[pc] = [count, rlo, 0, accu1, accu2]
            byte_seq = seq
        if int(dut.scan_done_o.value):
            scan += 1


async def _scans(dut, job: RunJob, firmware: Firmware) -> dict:
    """From clock 0 on: inputs, finished scans, the stop condition. The coroutine
    wakes only at the clocks where something happens (a scan ends, the watchdog
    fires, a time-keyed input changes), always at that clock's falling edge.

    What the firmware holds (MW columns, its flags and scan count) is taken at the
    edge itself, while the firmware thread waits inside the HAL call that spans that
    clock, as the C++ harness takes it: at the falling edge the thread may already
    have run on into the next clock's work."""
    look = _MarkerLook(dut)
    mw_cols = sorted({index for _, kind, index in job.cols if kind == "mw"})
    held = {"mw": {}, "stats": firmware.stats()}

    def take_firmware() -> None:
        held["mw"] = {n: firmware.mw(n) for n in mw_cols}
        held["stats"] = firmware.stats()

    readers = [_reader(dut, kind, index, lambda n: held["mw"][n], look)
               for _, kind, index in job.cols]
    stim = list(job.stim)
    next_stim = 0
    rows, fault = [], False
    scan = 0
    pins = 0
    step0 = get_sim_steps(firmware.clock0_ns, "ns", round_mode="round")   # clock 0
    period = get_sim_steps(PERIOD_NS, "ns")

    def clock_now() -> int:
        return (get_sim_time("step") - step0) // period

    async def values() -> list[int]:
        out = []
        for r in readers:
            v = r()
            out.append(await v if inspect.isawaitable(v) else v)
        return out

    def apply_due(key: int) -> None:
        nonlocal next_stim, pins
        while next_stim < len(stim) and stim[next_stim][0] <= key:
            _, pins, words = stim[next_stim]
            next_stim += 1
            if words is not None:
                dut.in_words_i.value = sum((w & 0xFFFF) << (16 * i) for i, w in enumerate(words))
        dut.in_pins_i.value = pins

    apply_due(0)                               # clock 0: the latch of scan 0
    while True:
        # sleep until a scan ends, the watchdog fires or the next time-keyed input
        wake = [RisingEdge(dut.scan_done_o), RisingEdge(dut.fault_o)]
        if job.stim_kind == "clock" and next_stim < len(stim):
            at = step0 + stim[next_stim][0] * period - get_sim_time("step")
            wake.append(Timer(at, unit="step"))   # at > 0: due inputs are applied
        fired = await First(*wake)
        if isinstance(fired, RisingEdge):
            take_firmware()
            await FallingEdge(dut.clk_i)       # into the clock after the edge
        clock = clock_now()
        if int(dut.fault_o.value):
            fault = True
            break
        if isinstance(fired, RisingEdge) and int(dut.scan_done_o.value):
            if firmware.host_writes:           # the table would take effect a scan late
                raise RunError(f"--force: the force table of scan {scan} did not fit into "
                               f"that scan ({len(firmware.host_writes)} of its register "
                               "writes left; it takes effect at the scan's END, so all must "
                               "be written in clocks where the byte processor leaves the "
                               "bus idle): a short scan, or one whose byte side keeps the "
                               "bus busy; spread the changes over more scans")
            rows.append((scan, clock, int(dut.scan_cycles_o.value), await values()))
            scan += 1
            firmware.queue_force(scan)
            if job.scans is not None and scan >= job.scans:
                break
            if job.until_clock is not None and clock >= job.until_clock \
                    and scan >= job.until_min_scans:
                break
            if job.stim_kind == "scan":
                apply_due(scan)                # this clock latches scan `scan`
        if job.stim_kind == "clock":
            apply_due(clock)
    queue_free = job.exchange == "queue-free"
    return {"rows": rows, "fault": fault, "clocks": clock_now(), **held["stats"],
            "stalls": [int(dut.stalls_bit_o.value), int(dut.stalls_byte_o.value)],
            "queue_losses": [int(dut.dbg_queue_overflows_o.value),
                             int(dut.dbg_queue_underflows_o.value)] if queue_free else None}


@cocotb.test()
async def run_jobs(dut):
    """Execute every job of $BITBYTE_JOBS in order."""
    jobs = [RunJob.from_json(d) for d in json.load(open(os.environ["BITBYTE_JOBS"]))]
    cocotb.start_soon(Clock(dut.clk_i, PERIOD_NS, unit="ns").start())
    for sig in (dut.prog_we_i, dut.prog_waddr_i, dut.prog_wdata_i, dut.in_words_i,
                dut.bus_addr_i, dut.bus_wdata_i, dut.bus_we_i, dut.bus_re_i):
        sig.value = 0
    try:
        results = [await run_job(dut, job) for job in jobs]
    except RunError as e:                       # a user's error: its words, not a trace
        results = {"error": str(e)}
    with open(os.environ["BITBYTE_RESULTS"], "w") as f:
        json.dump(results, f)
