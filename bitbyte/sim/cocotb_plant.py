"""cocotb driver of a multi-core plant (rtl/plc_system.v): the cocotb twin of the
Verilator plant harness sim/plant_harness.cpp, clock for clock.

Reads the plant described by the JSON file $BITBYTE_PLANT (written by
`bitbyte.plant.cocotb_runner.run_plant_cocotb`), writes one trace per core and the
results (status, summary) to the JSON file named in it.

The protocol is the harness's: reset, every core's program and copy plan loaded in
reset, configuration, `ready_o`, TICK_DIV written on every core's bus, `run_i`, then
clock 0 of the plant's time base. Per clock n:

  1. for every core: the clock-keyed inputs of clock n; the core's firmware runs if it
     is not asleep (it wants the bus, its `hal_spend` is over, or it waits for a
     dispatch and `byte_next_o[c]` is 1) until it asks for the clock again; its bus
     request is put on its slice of the bus ports;
  2. the clock-low half (clk_i = 0, inputs settled): each bus access's ready and read
     data;
  3. the rising edge; then per core: `cycle_done_o` writes a trace row with t_us =
     (n + 1) / clock_mhz, then applies the scan-keyed inputs of the next scan.

The clock is driven by this module (two Timers per clock, the edge in the middle),
not by a free-running cocotb Clock, so that the inputs of a clock are always written
after the previous edge has settled and the ready / read data are sampled after the
inputs. Where every core's firmware is idle (no bus access, asleep or waiting for a
dispatch that has not come) a cocotb Clock runs instead until the first clock where
a core is due or an output the loop reacts to changes (`Plant.fast_forward`): the
same waveform and the same traces, without Python in every clock.

Firmware and concurrency. Every core runs the real firmware (firmware_byte/), all of
them from one loaded libbyteproc_cb.so: the firmware keeps no globals, and each
core's state has its own HAL context, a bb_hal_callbacks table of that core's
callbacks (firmware_byte/hal_callbacks.h). The results file says how many times the
library was loaded and which copies of it the process maps (one). The firmware's
loop runs in an OS thread of its own, and exactly one of {the cocotb scheduler,
core 0's firmware, core 1's firmware, ...} runs at any time: the clock coroutine hands the CPU to a core's thread
(a pair of locks) and blocks until that thread asks for the next clock (a HAL call),
as the harness's ucontext coroutines do. The firmware threads never touch a
simulator handle or cocotb; they only post their bus request in Python fields, which
the clock coroutine puts on the ports. cocotb's `bridge` / `resume` work too (several
bridged threads, each HAL call a `resume`-wrapped coroutine, give the same traces),
but a resumed bridge thread runs at the same time as the scheduler and the other
resumed threads, each HAL call is a new cocotb task, and a bridge thread (not a
daemon) must be driven to its end before the simulator can exit; the plain hand-off
keeps the order fixed and the firmware out of the scheduler. When the run is over,
the threads stay blocked in their last HAL call (daemon threads) until the
simulator process ends.

The plant is observed through its ports only. The trace columns I, IR, IF, T, C read
core c's slice of the observation ports dbg_*; M n and MW n are looked up through
dbg_m_addr_i / dbg_m_o and dbg_mw_addr_i / dbg_mw_o: a row writes the addresses that
change and waits one simulator step for each, in the clock-high half after the edge
that ended the scan; the next clock-low half is shortened by as many steps, so the
clock period stays exact.
"""
from __future__ import annotations

import ctypes
import inspect
import json
import os
import threading
from fractions import Fraction

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import First, Timer
from cocotb.utils import get_sim_steps, get_sim_time

from bitbyte.lang.definition import DEF
from bitbyte.sim.cocotb_driver import hal_callbacks, load_firmware
from bitbyte.run.prepare import PLANT_MODES
from bitbyte.run.runjob import RunJob
from bitbyte.lang.trace import format_decimal

HALF_NS = 5          # half a clock in simulator time; reported time uses clock_hz
BUS_ADDR = DEF.bus   # byte-bus register addresses
IN_BITS = DEF.sizes["in_bytes"] * 8      # plc_system InBytes * 8
OUT_BITS = DEF.sizes["out_bytes"] * 8    # plc_system OutBytes * 8
WORD_BITS = DEF.sizes["in_words"] * 16   # plc_system InWords / OutWords * 16
BB_PROG_WORDS = DEF.firmware["byte_prog_words"]
FF_MIN = 3           # idle stretches shorter than this are clocked one by one
FF_CAP = 1 << 24     # clocks one fast-forward may cover without a known end

# what a core's firmware asks for (plant_harness.cpp Core::Want)
START, BUS, SLEEP, WAIT = range(4)


def _s16(v: int) -> int:
    v &= 0xFFFF
    return v - 0x10000 if v & 0x8000 else v


def _field(vector: int, lsb: int, width: int) -> int:
    return (vector >> lsb) & ((1 << width) - 1)


def _set_field(vector: int, lsb: int, width: int, value: int) -> int:
    mask = ((1 << width) - 1) << lsb
    return (vector & ~mask) | ((value << lsb) & mask)


def _slice(value, lsb: int, width: int) -> int:
    """Bits [lsb +: width] of a LogicArray value; X / Z elsewhere in it do not matter
    (Icarus is 4-state: another core's read data may be X where Verilator has 0)."""
    try:
        return (int(value) >> lsb) & ((1 << width) - 1)
    except ValueError:
        bits = str(value)                                # most significant bit first
        return int(bits[len(bits) - lsb - width:len(bits) - lsb], 2)


LIB_LOADS = 0        # ctypes loads of the firmware library in this process (one)


def _load_lib(path: str):
    global LIB_LOADS
    LIB_LOADS += 1
    return load_firmware(path)


def _mapped_copies(name: str = "libbyteproc") -> list[str]:
    """The files named *name* this process maps (/proc/self/maps): the copies of the
    firmware library that are loaded."""
    try:
        with open("/proc/self/maps") as f:
            return sorted({line.split()[-1] for line in f
                           if len(line.split()) >= 6 and name in line.split()[-1]})
    except OSError:
        return []


class CoreFirmware:
    """One core's byte processor: its state on the shared library, its HAL context,
    its thread, and the bus request it has posted for the clock being prepared."""

    def __init__(self, plant: "Plant", idx: int, job: RunJob, lib):
        self.plant, self.idx, self.job = plant, idx, job
        self.want = START
        self.wake = 0
        self.addr = 0
        self.wdata = 0
        self.re = self.we = False
        self.ready = False
        self.rdata = 0
        self.error: BaseException | None = None
        self.lib = lib
        self.state = lib.bb_new()
        costs = lib.bb_cost_table(job.costs.encode())
        if not costs:
            raise RuntimeError(f"unknown cost table {job.costs!r}")
        lib.bb_init(self.state, costs)
        lib.bb_set_mw_bus(self.state, 1)        # a plant core keeps MW in the FPGA
        if job.pool:
            words = (ctypes.c_uint32 * len(job.pool))(*job.pool)
            lib.bb_load_pool(self.state, words, len(job.pool))
        if job.mode not in PLANT_MODES:
            raise RuntimeError(f"a plant core runs in {' or '.join(PLANT_MODES)} mode")
        self.parallel = job.mode == "parallel"
        if self.parallel:
            words = (ctypes.c_uint32 * max(1, len(job.byte_prog)))(*job.byte_prog)
            if (len(job.byte_prog) > BB_PROG_WORDS
                    or lib.bb_load_program(self.state, words, len(job.byte_prog)) != 0):
                raise RuntimeError("byte part too large")
        # this core's HAL context: its own callback table (kept alive with the core)
        self._hal = hal_callbacks(self._read, self._write, self._spend, self._wait,
                                  self._now)
        lib.bb_set_hal_ctx(self.state, ctypes.byref(self._hal))
        # hand-off: exactly one of the clock coroutine and this thread runs
        self._to_fw = threading.Lock()
        self._to_main = threading.Lock()
        self._to_fw.acquire()
        self._to_main.acquire()
        self.thread = threading.Thread(target=self._main, name=f"firmware-core{idx}",
                                       daemon=True)
        self.thread.start()

    # ---- the clock coroutine's side
    def run(self) -> None:
        """Let the firmware run until it asks for the next clock."""
        self._to_fw.release()
        self._to_main.acquire()
        if self.error is not None:
            raise RuntimeError(f"core {self.idx}: firmware thread failed") from self.error

    # When the run is over, the thread is left where it is: blocked in a HAL call,
    # holding no lock, until the simulator process ends (it is a daemon thread).
    # Letting it run on with dummy bus answers could loop in the firmware.

    # ---- the firmware thread's side
    def _main(self) -> None:
        self._to_fw.acquire()                   # clock 0
        lib, state = self.lib, self.state
        try:
            lib.bb_run(state, DEF.modes["parallel" if self.parallel else "serial"])
        except BaseException as e:  # noqa: BLE001 - handed to the clock coroutine
            self.error = e
        self._to_main.release()

    def _yield_clock(self) -> None:
        self._to_main.release()
        self._to_fw.acquire()

    # HAL (plant_harness.cpp): a bus access takes the clock it is asked in and repeats
    # while the port answers "not ready"; hal_spend(n) sleeps n clocks; the dispatch
    # wait returns in the first clock where byte_next_o[c] was 1 after the edge (at
    # once when it was 1 after the last edge).
    def _read(self, addr: int) -> int:
        while True:
            self.want, self.addr, self.re, self.we = BUS, addr, True, False
            self._yield_clock()
            if self.ready:
                return self.rdata

    def _write(self, addr: int, data: int) -> None:
        while True:
            self.want, self.addr, self.wdata = BUS, addr, data
            self.we, self.re = True, False
            self._yield_clock()
            if self.ready:
                return

    def _spend(self, clocks: int) -> None:
        if clocks:
            self.want, self.wake = SLEEP, self.plant.n + clocks
            self._yield_clock()

    def _wait(self) -> None:
        if (self.plant.next_bits >> self.idx) & 1:
            return          # NEXT already up after the last edge: this is the clock
        self.want = WAIT
        self._yield_clock()

    def _now(self) -> int:
        return self.plant.n


class Core:
    """One core of the plant: configuration, firmware, stimulus, trace."""

    def __init__(self, idx: int, cfg: dict):
        self.idx = idx
        self.name = cfg["name"]
        self.job = RunJob.from_json(cfg["job"])
        self.cfg = cfg
        self.stim = self.job.stim
        self.next_stim = 0
        self.fw: CoreFirmware | None = None
        self.trace = None
        self.readers = []
        self.scans = 0                              # rows traced
        self.skips = 0                              # skips_o at the last traced scan
        self.finished = False


class Plant:
    def __init__(self, dut, cfg: dict):
        self.dut, self.cfg = dut, cfg
        self.n = 0                                  # the clock being prepared
        self.clock_hz = int(cfg["clock_hz"])
        self.cores = [Core(i, c) for i, c in enumerate(cfg["cores"])]
        ncores = len(dut.fault_o)
        if ncores != len(self.cores):
            raise RuntimeError(f"plc_system is built for {ncores} cores, the plant has "
                               f"{len(self.cores)}")
        self.ncores = ncores
        self.aw = len(dut.post_base_i) // ncores     # $clog2(PlanWords)
        self.status_bits = len(dut.dbg_timer_status_o) // ncores   # StatusBits
        # the look-up ports: per core the address each holds, its width, the steps the
        # look-ups took in this clock's high half
        self.look = {"m": (dut.dbg_m_addr_i, len(dut.dbg_m_addr_i) // ncores, [0] * ncores),
                     "mw": (dut.dbg_mw_addr_i, len(dut.dbg_mw_addr_i) // ncores,
                            [0] * ncores)}
        self.look_steps = 0
        self.in_pins = 0
        self.in_words = 0
        self.next_bits = 0                          # byte_next_o after the last edge
        self.bus = (0, 0, 0, 0)                     # bus_addr/wdata/we/re as driven
        self._timer = Timer(HALF_NS, unit="ns")
        self.fast = bool(cfg.get("fast", True))
        self.half = get_sim_steps(HALF_NS, "ns")       # in simulator steps

    # ---------------------------------------------------------------- clocks
    async def tick(self) -> None:
        """One clock from the settled state after an edge: clk low, clk high."""
        self.dut.clk_i.value = 0
        await self._timer
        self.dut.clk_i.value = 1
        await self._timer

    # ---------------------------------------------------------------- stimulus
    def apply_stim(self, core: Core, key: int) -> None:
        """The last stimulus row with KEY <= key, if one is due (apply_stim)."""
        st = None
        stim = core.stim
        while core.next_stim < len(stim) and stim[core.next_stim][0] <= key:
            st = stim[core.next_stim]
            core.next_stim += 1
        if st is None:
            return
        _, pins, words = st
        c = core.idx
        self.in_pins = _set_field(self.in_pins, IN_BITS * c, IN_BITS, pins)
        self.dut.in_pins_i.value = self.in_pins
        if words is not None:
            for i, w in enumerate(words[:DEF.sizes["in_words"]]):
                self.in_words = _set_field(self.in_words, WORD_BITS * c + 16 * i, 16,
                                           w & 0xFFFF)
            self.dut.in_words_i.value = self.in_words

    # ---------------------------------------------------------------- trace columns
    def column_reader(self, core: Core, kind: str, n: int):
        dut, c = self.dut, core.idx
        if kind == "q":
            sig = dut.out_pins_o
            return lambda: str((int(sig.value) >> (OUT_BITS * c + n)) & 1)
        if kind == "pi":
            return lambda: str((self.in_pins >> (IN_BITS * c + n)) & 1)
        if kind == "qw":
            sig = dut.out_words_o
            return lambda: str(_s16(int(sig.value) >> (WORD_BITS * c + 16 * n)))
        if kind == "iw":
            return lambda: str(_s16(self.in_words >> (WORD_BITS * c + 16 * n)))
        if kind == "zero":
            return lambda: "0"
        if kind == "mw":
            sig = dut.dbg_mw_o
            return lambda: self.look_up("mw", c, n, lambda: str(_s16(_slice(sig.value,
                                                                            16 * c, 16))))
        if kind == "m":
            sig = dut.dbg_m_o
            return lambda: self.look_up("m", c, n, lambda: str(_slice(sig.value, c, 1)))
        vectors = {"i": (dut.dbg_pii_o, IN_BITS), "ir": (dut.dbg_rise_o, IN_BITS),
                   "if": (dut.dbg_fall_o, IN_BITS), "qr": (dut.dbg_q_rise_o, OUT_BITS),
                   "qf": (dut.dbg_q_fall_o, OUT_BITS), "t": (dut.dbg_timer_status_o,
                                                          self.status_bits),
                   "c": (dut.dbg_counter_status_o, self.status_bits)}
        if kind in vectors:
            sig, bits = vectors[kind]
            return lambda: str(_slice(sig.value, bits * c + n, 1))
        raise RuntimeError(f"unknown column kind {kind!r}")

    async def look_up(self, kind: str, c: int, n: int, read) -> str:
        """M n / MW n of core c: set its look-up address if it changes (one simulator
        step to settle, counted in look_steps), then read."""
        port, width, addrs = self.look[kind]
        if addrs[c] != n:
            addrs[c] = n
            port.value = sum(a << (width * i) for i, a in enumerate(addrs))
            await Timer(1, unit="step")
            self.look_steps += 1
        return read()

    # ---------------------------------------------------------------- the run
    async def reset_and_load(self) -> None:
        dut, cfg = self.dut, self.cfg
        for sig in (dut.prog_we_i, dut.prog_waddr_i, dut.prog_wdata_i, dut.plan_we_i,
                    dut.plan_waddr_i, dut.plan_wdata_i, dut.parallel_i, dut.exchange_i,
                    dut.period_i, dut.pre_len_i, dut.post_base_i, dut.post_len_i,
                    dut.protect_i, dut.watchdog_limit_i, dut.in_pins_i, dut.in_words_i,
                    dut.bus_addr_i, dut.bus_wdata_i, dut.bus_we_i, dut.bus_re_i,
                    dut.dbg_m_addr_i, dut.dbg_mw_addr_i):
            sig.value = 0
        dut.rst_ni.value = 0
        dut.run_i.value = 0
        dut.clk_i.value = 1
        await self._timer
        await self.tick()
        aw = self.aw
        plan_words = 1 << aw
        period = pre_len = post_base = post_len = parallel = exchange = 0
        for core in self.cores:
            c, job, cc = core.idx, core.job, core.cfg
            for a, word in enumerate(job.prog):
                dut.prog_we_i.value = 1 << c
                dut.prog_waddr_i.value = a
                dut.prog_wdata_i.value = word
                await self.tick()
            dut.prog_we_i.value = 0
            for a, word in enumerate(cc["plan"]):
                dut.plan_we_i.value = 1 << c
                dut.plan_waddr_i.value = a
                dut.plan_wdata_i.value = word
                await self.tick()
            dut.plan_we_i.value = 0
            if cc["pre_len"] > plan_words or cc["post_base"] + cc["post_len"] > plan_words:
                raise RuntimeError(f"core {c}: plan too long")
            period = _set_field(period, 64 * c, 64, cc["period"])
            pre_len = _set_field(pre_len, (aw + 1) * c, aw + 1, cc["pre_len"])
            post_base = _set_field(post_base, aw * c, aw, cc["post_base"])
            post_len = _set_field(post_len, (aw + 1) * c, aw + 1, cc["post_len"])
            parallel = _set_field(parallel, c, 1, int(job.mode == "parallel"))
            exchange = _set_field(exchange, 2 * c, 2, DEF.exchanges.index(job.exchange))
        dut.period_i.value = period
        dut.pre_len_i.value = pre_len
        dut.post_base_i.value = post_base
        dut.post_len_i.value = post_len
        dut.parallel_i.value = parallel
        dut.exchange_i.value = exchange
        dut.protect_i.value = DEF.protections.index(cfg["protect"])
        dut.watchdog_limit_i.value = int(cfg["watchdog"])
        await self.tick()
        dut.rst_ni.value = 1
        i = 0
        while not int(dut.ready_o.value):
            if i > 1_000_000:
                raise RuntimeError("ready_o never rose after reset")
            await self.tick()
            i += 1
        addr = wdata = we = 0
        for c in range(self.ncores):                 # TICK_DIV on every core
            addr = _set_field(addr, 9 * c, 9, BUS_ADDR["TICK_DIV"])
            wdata = _set_field(wdata, 32 * c, 32, self.clock_hz // 1000)
            we = _set_field(we, c, 1, 1)
        dut.bus_addr_i.value = addr
        dut.bus_wdata_i.value = wdata
        dut.bus_we_i.value = we
        await self.tick()
        dut.bus_we_i.value = 0
        dut.run_i.value = 1
        await self.tick()                            # the next clock is clock 0
        self.bus = (addr, wdata, 0, 0)               # what the bus ports hold now

    def open_traces(self, lib) -> None:
        """Every core's firmware on `lib` (the one loaded library), its readers, its
        trace file."""
        for core in self.cores:
            core.fw = CoreFirmware(self, core.idx, core.job, lib)
            core.readers = [self.column_reader(core, kind, index)
                            for _, kind, index in core.job.cols]
            path = core.cfg.get("trace")
            if path:
                core.trace = open(path, "w", newline="")
                core.trace.write(",".join(
                    ["scan", "t_us", "cycles", "pre", "post", "sem_wait", "copy_fail",
                     "overrun"] + [h for h, _, _ in core.job.cols]) + "\n")

    async def clocks(self) -> bool:
        """Clock 0 on until every core has finished a scan ending at or after
        until_clock (or a core's watchdog fires). Returns the fault flag."""
        dut = self.dut
        cores = self.cores
        until = int(self.cfg["until_clock"])
        clk = dut.clk_i
        timer = self._timer
        bus_addr_h, bus_wdata_h = dut.bus_addr_i, dut.bus_wdata_i
        bus_we_h, bus_re_h = dut.bus_we_i, dut.bus_re_i
        ready_h, rdata_h, next_h = dut.bus_ready_o, dut.bus_rdata_o, dut.byte_next_o
        fault_h, sdone_h, cdone_h = dut.fault_o, dut.scan_done_o, dut.cycle_done_o
        count_h = dut.scan_count_o
        clock_stim = [c for c in cores if c.job.stim_kind == "clock"]
        scan_stim = {c.idx for c in cores if c.job.stim_kind == "scan"}
        for c in cores:
            if c.idx in scan_stim:
                self.apply_stim(c, 0)
        bus_addr, bus_wdata, bus_we, bus_re = self.bus
        next_bits = self.next_bits = int(next_h.value)
        fault_bits = sdone = cdone = 0
        fault = False
        n = 0
        while True:
            self.n = n
            # ---- inputs of clock n: stimulus, firmware, bus requests
            for k in clock_stim:
                if k.next_stim < len(k.stim) and k.stim[k.next_stim][0] <= n:
                    self.apply_stim(k, n)
            any_bus = False
            addr, wdata, we, re = bus_addr, bus_wdata, 0, 0
            for k in cores:
                fw = k.fw
                want = fw.want
                fw.re = fw.we = False
                if (want <= BUS or (want == SLEEP and n >= fw.wake)
                        or (want == WAIT and (next_bits >> k.idx) & 1)):
                    fw.run()
                    want = fw.want
                c = k.idx
                addr = _set_field(addr, 9 * c, 9, fw.addr)
                wdata = _set_field(wdata, 32 * c, 32, fw.wdata)
                if want == BUS:
                    any_bus = True
                    if fw.we:
                        we |= 1 << c
                    if fw.re:
                        re |= 1 << c
            if addr != bus_addr:
                bus_addr_h.value = bus_addr = addr
            if wdata != bus_wdata:
                bus_wdata_h.value = bus_wdata = wdata
            if we != bus_we:
                bus_we_h.value = bus_we = we
            if re != bus_re:
                bus_re_h.value = bus_re = re
            # ---- idle: no bus access, no core due before clock `due`: let a cocotb
            # Clock run until then or until an output the loop reacts to changes
            idle = self.fast and not any_bus and not (fault_bits or sdone or cdone)
            if idle:
                due = n + FF_CAP
                waiting = 0
                for k in cores:
                    fw = k.fw
                    if fw.want == SLEEP:
                        due = min(due, fw.wake)
                    elif fw.want == WAIT:
                        waiting |= 1 << k.idx
                if next_bits & waiting:     # a waiting core due at clock n + 1
                    idle = False
                for k in clock_stim:
                    if k.next_stim < len(k.stim):
                        due = min(due, k.stim[k.next_stim][0])
                idle = idle and due - n >= FF_MIN
            if idle:
                n = await self.fast_forward(n, due - n)
            else:
                # ---- the clock-low half: ready and read data (shorter by the steps
                # the last row's look-ups added to the high half before it)
                clk.value = 0
                if self.look_steps:
                    await Timer(max(1, self.half - self.look_steps), unit="step")
                    self.look_steps = 0
                else:
                    await timer
                if any_bus:
                    ready, rdata = ready_h.value, rdata_h.value
                    for k in cores:
                        fw = k.fw
                        if fw.want == BUS:
                            fw.ready = bool(_slice(ready, k.idx, 1))
                            fw.rdata = _slice(rdata, 32 * k.idx, 32)
                # ---- the rising edge
                clk.value = 1
                await timer
            next_bits = self.next_bits = int(next_h.value)
            fault_bits = int(fault_h.value)
            sdone = int(sdone_h.value)
            cdone = int(cdone_h.value)
            all_done = True
            if fault_bits:
                fault = True
            if cdone:
                for k in cores:
                    c = k.idx
                    if (cdone >> c) & 1:
                        if not k.finished:
                            await self.row(k, n)
                            if n + 1 >= until:
                                k.finished = True
                        # the next scan's scan-keyed inputs: after this row, so that
                        # its PI / IW columns are this scan's, and before its latch
                        if c in scan_stim:
                            self.apply_stim(k, _field(int(count_h.value), 32 * c, 32))
            for k in cores:
                all_done = all_done and k.finished
            if fault or all_done:
                n += 1
                break
            n += 1
        self.n = n
        return fault

    async def fast_forward(self, n: int, clocks: int) -> int:
        """Clocks n, n+1, ... while every core is idle, at most `clocks` of them.

        Called at the settled point after edge n - 1 (clk_i high) with clock n's inputs
        written; no core wants the bus, none is due before clock n + clocks, every
        waiting core's byte_next_o bit and all scan_done_o / cycle_done_o / fault_o
        bits are 0. A cocotb Clock (the simulator's own, cheap) then makes the same
        waveform as `clocks()` (clk_i low at once, the edge half a clock later) until
        one of those outputs changes, which can only happen at an edge, or until the
        edge of clock n + clocks - 1 is past. Returns the clock q whose edge was the
        last one, at the settled point after it: the loop goes on as after clock q."""
        dut = self.dut
        half = self.half
        start = get_sim_time("step")
        period = 2 * half
        clock = Clock(dut.clk_i, period, unit="step")
        clock.start(start_high=False)
        wake = [dut.scan_done_o.value_change, dut.cycle_done_o.value_change,
                dut.fault_o.value_change]
        if any(k.fw.want == WAIT for k in self.cores):
            wake.append(dut.byte_next_o.value_change)
        # half a clock after the last allowed edge (never on a toggle of the Clock)
        wake.append(Timer(period * clocks - half // 2, unit="step"))
        await First(*wake)
        clock.stop()                     # clk_i stays high: the next toggle is later
        now = get_sim_time("step")
        if now < start + half:
            raise RuntimeError(f"clock {n}: an output changed without a clock edge")
        q = n + (now - start - half) // period
        await Timer(start + period * (q - n + 1) - now, unit="step")
        return q

    async def row(self, k: Core, n: int) -> None:
        dut, c = self.dut, k.idx
        cycles = _field(int(dut.scan_cycles_o.value), 32 * c, 32)
        pre = _field(int(dut.pre_clocks_o.value), 32 * c, 32)
        post = _field(int(dut.post_clocks_o.value), 32 * c, 32)
        wait = _field(int(dut.sem_wait_o.value), 32 * c, 32)
        over = _field(int(dut.overrun_o.value), c, 1)
        k.skips = _field(int(dut.skips_o.value), 32 * c, 32)
        fail = _field(int(dut.copy_fail_o.value), c, 1)
        if k.trace:
            t_us = format_decimal(Fraction((n + 1) * 1_000_000, self.clock_hz))
            values = []
            for r in k.readers:
                v = r()
                values.append(await v if inspect.isawaitable(v) else v)
            k.trace.write(",".join([str(k.scans), t_us, str(cycles), str(pre), str(post),
                                    str(wait), str(fail), str(over)] + values) + "\n")
        k.scans += 1

    def watchdog_text(self, fault: bool) -> str:
        """stderr as the plant harness writes it when a core's scan watchdog fired."""
        if not fault:
            return ""
        fault_bits = int(self.dut.fault_o.value)
        return "".join(f"scan watchdog: core {k.name} scan {k.scans} exceeded "
                       f"{self.cfg['watchdog']} clocks\n"
                       for k in self.cores if (fault_bits >> k.idx) & 1)


@cocotb.test()
async def run_plant(dut):
    """Run the plant of $BITBYTE_PLANT and write its traces and results."""
    with open(os.environ["BITBYTE_PLANT"]) as f:
        cfg = json.load(f)
    plant = Plant(dut, cfg)
    await plant.reset_and_load()
    plant.open_traces(_load_lib(cfg["lib"]))           # once, for every core
    try:
        fault = await plant.clocks()
    finally:
        for k in plant.cores:
            if k.trace:
                k.trace.close()
    with open(cfg["results"], "w") as f:
        json.dump({"status": 3 if fault else 0, "clocks": plant.n,
                   "skips": {k.name: k.skips for k in plant.cores},
                   # each core's mode and exchange as driven on parallel_i / exchange_i
                   # (read back from the DUT): the summary's mode labels
                   "modes": {k.name: [_field(int(dut.parallel_i.value), k.idx, 1),
                                      _field(int(dut.exchange_i.value), 2 * k.idx, 2)]
                             for k in plant.cores},
                   "stderr": plant.watchdog_text(fault),
                   "firmware_loads": LIB_LOADS, "firmware_mapped": _mapped_copies()}, f)
