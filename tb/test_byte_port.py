"""Byte-side port: register map (docs/byte-bus.md), time base, word I/O, channel
routing with ready/stall, DONE and TC_BIT strobes; and every register bit, every
address and every strobe against a model of the register map (BusModel), its
addresses and fields read from bitbyte/lang/definition.toml."""
from __future__ import annotations

import random

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from bitbyte.lang.definition import DEF

from simrun import SIMULATORS, run_cocotb

CHANNELS = 4
CELLS = 128            # marker area cells (the MCELL window full)
STATUS_BITS = 64       # byte_port's defaults (the register map's LO/HI pairs full)
WORDS = 16             # InWords = OutWords


async def reset(dut):
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    for sig in (dut.rst_ni, dut.bus_addr_i, dut.bus_wdata_i, dut.bus_we_i, dut.bus_re_i,
                dut.latch_i, dut.time_start_i, dut.exec_i, dut.fault_i, dut.next_i, dut.dispatch_instr_i,
                dut.dispatch_ctx_i, dut.timer_status_i, dut.counter_status_i,
                dut.timer_enable_i, dut.counter_pulse_i, dut.timer_written_i,
                dut.counter_written_i, dut.fby_rd_data_i, dut.marker_i, dut.cell_rdata_i,
                dut.fby_rd_ready_i, dut.fby_full_i, dut.fbi_wr_ready_i, dut.fbi_full_i,
                dut.in_words_i, dut.bit_stall_i, dut.queue_overflows_i,
                dut.queue_underflows_i):
        sig.value = 0
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.rst_ni.value = 1


async def access(dut, addr, data=None):
    """One bus clock: a read (data None) or a write. Returns (rdata, ready)."""
    dut.bus_addr_i.value = addr
    dut.bus_we_i.value = int(data is not None)
    dut.bus_re_i.value = int(data is None)
    dut.bus_wdata_i.value = data or 0
    await Timer(1, unit="ns")
    result = int(dut.bus_rdata_o.value), int(dut.bus_ready_o.value)
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.bus_we_i.value = dut.bus_re_i.value = 0
    return result


async def read(dut, addr):
    return (await access(dut, addr))[0]


@cocotb.test()
async def id_and_status(dut):
    await reset(dut)
    assert await read(dut, 0x00) == 0xB17B7E01
    dut.next_i.value, dut.exec_i.value = 1, 1
    dut.dispatch_instr_i.value = 0xB0007005
    dut.dispatch_ctx_i.value = 0x00030001
    assert await read(dut, 0x01) == 0b011
    assert await read(dut, 0x02) == 0xB0007005
    assert await read(dut, 0x03) == 0x00030001
    assert await read(dut, 0x77) == 0            # unmapped


@cocotb.test()
async def time_base_from_clock_zero(dut):
    """TIME_MS = floor(clock / TICK_DIV), clock 0 = the first latch."""
    await reset(dut)
    await access(dut, 0x09, 3)                   # 3 clocks per ms
    for _ in range(5):                           # before scan 0: time stands still
        assert await read(dut, 0x0A) == 0
    dut.latch_i.value = 1                        # clock 0
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.latch_i.value = 0
    for clock in range(1, 12):
        dut.bus_addr_i.value, dut.bus_re_i.value = 0x08, 1
        await Timer(1, unit="ns")
        ms = int(dut.bus_rdata_o.value)
        dut.bus_addr_i.value = 0x0A
        await Timer(1, unit="ns")
        assert (int(dut.bus_rdata_o.value), ms) == (clock, clock // 3)
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)


@cocotb.test()
async def time_base_large_divider(dut):
    """TIME_MS with TICK_DIV = 3000 (the sub-millisecond count passes 2048, as it does
    at the default 100 000, and its last step comes from above it): CLOCK and TIME_MS
    read every clock for 3 ms and a bit (make mutate: a mutant flipping bit 4 of that
    count while its bit 11 is set survived the small dividers of the other tests; at
    4100 it would too: the flips then only reorder the counts before the last)."""
    await reset(dut)
    div = 3000
    await access(dut, REG["TICK_DIV"].addr, div)
    dut.latch_i.value = 1                        # clock 0
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.latch_i.value = 0
    dut.bus_re_i.value = 1
    for clock in range(1, 3 * div + 50):
        dut.bus_addr_i.value = REG["CLOCK"].addr
        await Timer(1, unit="ns")
        got_clock = int(dut.bus_rdata_o.value)
        dut.bus_addr_i.value = REG["TIME_MS"].addr
        await Timer(1, unit="ns")
        assert (got_clock, int(dut.bus_rdata_o.value)) == (clock, clock // div), clock
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
    dut.bus_re_i.value = 0


@cocotb.test()
async def word_io(dut):
    await reset(dut)
    dut.in_words_i.value = (0xFFFE << 16 * 3) | (0x1234 << 16 * 0)
    assert await read(dut, 0x40) == 0x1234
    assert await read(dut, 0x43) == 0xFFFFFFFE   # sign-extended -2
    await access(dut, 0x55, 0x1234_8001)         # QW5 keeps the low 16 bits
    assert (int(dut.out_words_o.value) >> 80) & 0xFFFF == 0x8001
    assert await read(dut, 0x55) == 0xFFFF8001


@cocotb.test()
async def channels_and_stalls(dut):
    await reset(dut)
    # FBY 2 (bit -> byte) empty: the read is not ready and counts a byte stall
    dut.fby_rd_ready_i.value = 0
    dut.bus_addr_i.value, dut.bus_re_i.value = 0x22, 1
    await Timer(1, unit="ns")
    assert int(dut.fby_rd_req_o.value) == 0b0100 and int(dut.bus_ready_o.value) == 0
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.fby_rd_ready_i.value, dut.fby_rd_data_i.value = 0b0100, 0b0100
    await Timer(1, unit="ns")
    assert int(dut.bus_ready_o.value) == 1 and int(dut.bus_rdata_o.value) == 1
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.bus_re_i.value = 0
    assert await read(dut, 0x61) == 1            # one byte-side stall clock
    # FBI 1 (byte -> bit): the write request carries bit 0 of the data
    dut.fbi_wr_ready_i.value = 0b1111
    dut.bus_addr_i.value, dut.bus_we_i.value, dut.bus_wdata_i.value = 0x29, 1, 1
    await Timer(1, unit="ns")
    assert int(dut.fbi_wr_req_o.value) == 0b0010 and int(dut.fbi_wr_data_o.value) == 1
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.bus_we_i.value = 0
    # a channel the build does not have: no request, ready, reads 0
    rdata, ready = await access(dut, 0x20 + CHANNELS)
    assert (rdata, ready) == (0, 1)
    dut.fby_full_i.value, dut.fbi_full_i.value = 0b1001, 0b0110
    assert await read(dut, 0x30) == 0x0609
    dut.bit_stall_i.value = 1
    for _ in range(3):
        await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.bit_stall_i.value = 0
    assert await read(dut, 0x60) == 3


@cocotb.test()
async def done_and_tc_bit_strobes(dut):
    await reset(dut)
    dut.bus_addr_i.value, dut.bus_we_i.value, dut.bus_wdata_i.value = 0x04, 1, 0b11
    await Timer(1, unit="ns")
    assert int(dut.done_we_o.value) == 1 and int(dut.done_data_o.value) == 0b11
    dut.bus_addr_i.value, dut.bus_wdata_i.value = 0x10, (1 << 8) | (1 << 6) | 37
    await Timer(1, unit="ns")
    assert int(dut.done_we_o.value) == 0
    assert (int(dut.tc_we_o.value), int(dut.tc_is_counter_o.value),
            int(dut.tc_idx_o.value), int(dut.tc_val_o.value)) == (1, 1, 37, 1)
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.bus_we_i.value = 0
    dut.timer_status_i.value = (1 << 63) | 5
    assert await read(dut, 0x11) == 5 and await read(dut, 0x12) == 1 << 31
    await access(dut, 0x62, 1)
    assert await read(dut, 0x62) == 1


@cocotb.test()
async def dispatch_snapshot(dut):
    """DISPATCH_MS / DISPATCH_IW hold the values of the dispatch's first clock, for a
    second dispatch right after DONE too."""
    await reset(dut)
    await access(dut, 0x09, 2)                   # 2 clocks per ms
    dut.latch_i.value = 1
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.latch_i.value = 0                        # now in clock 1: ms = 0
    for word_value, first_ms in ((0x1111, 0), (0xF000, 3)):   # clocks 1 and 6
        dut.in_words_i.value = word_value << (16 * 3)
        dut.next_i.value, dut.dispatch_instr_i.value = 1, 0x8200A003   # L IW3
        dut.bus_addr_i.value, dut.bus_re_i.value = 0x05, 1
        await Timer(1, unit="ns")
        assert int(dut.bus_rdata_o.value) == first_ms
        # the first clock's live values join after the read multiplexer (byte_port.v):
        # DISPATCH_IW and STATUS.NEXT in the same clock too
        expect = word_value | (0xFFFF0000 if word_value & 0x8000 else 0)
        dut.bus_addr_i.value = 0x06
        await Timer(1, unit="ns")
        assert int(dut.bus_rdata_o.value) == expect
        dut.bus_addr_i.value = 0x01
        await Timer(1, unit="ns")
        assert int(dut.bus_rdata_o.value) & 1 == 1
        dut.bus_addr_i.value = 0x05
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
        dut.in_words_i.value = 0x2222 << (16 * 3)   # changes after the first clock
        for _ in range(3):
            await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
        dut.bus_addr_i.value = 0x06
        await Timer(1, unit="ns")
        assert int(dut.bus_rdata_o.value) == expect
        dut.bus_addr_i.value = 0x05
        await Timer(1, unit="ns")
        assert int(dut.bus_rdata_o.value) == first_ms
        dut.bus_re_i.value = 0
        await access(dut, 0x04, 0)               # DONE: the next dispatch starts fresh
        dut.next_i.value = 0 if word_value == 0xF000 else 1


@cocotb.test()
async def latch_snapshot(dut):
    """LATCH_MS: TIME_MS in the latch clock (read live in that clock, when the byte
    side of parallel mode may already ask), then held until the next latch."""
    latch_ms, time_ms = REG["LATCH_MS"].addr, REG["TIME_MS"].addr
    await reset(dut)
    await access(dut, REG["TICK_DIV"].addr, 2)   # 2 clocks per ms
    dut.bus_re_i.value = 1
    clock = 0                                    # the first latch starts the time base

    async def tick():
        nonlocal clock
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
        clock += 1

    async def reads(addr) -> int:
        dut.bus_addr_i.value = addr
        await Timer(1, unit="ns")
        return int(dut.bus_rdata_o.value)

    for latch_clock in (0, 9, 16):
        while clock < latch_clock:
            await tick()
        dut.latch_i.value = 1
        now = await reads(time_ms)
        assert now == latch_clock // 2
        assert await reads(latch_ms) == now, ("live in the latch clock", latch_clock)
        await tick()
        dut.latch_i.value = 0
        for _ in range(3):                       # held while TIME_MS goes on
            assert await reads(latch_ms) == now, ("held", clock)
            await tick()
        assert await reads(time_ms) > now
    dut.bus_re_i.value = 0


@cocotb.test()
async def status_vectors(dut):
    """The six 64-bit vectors of the timer/counter status buffer, each on its LO/HI
    register pair (addresses from bitbyte/lang/definition.toml): distinct random
    patterns, so a register that shows another vector's bits or the other half fails."""
    import random
    rng = random.Random(16)
    await reset(dut)
    vectors = {"T_STATUS": dut.timer_status_i, "C_STATUS": dut.counter_status_i,
               "T_ENABLE": dut.timer_enable_i, "C_PULSE": dut.counter_pulse_i,
               "T_WRITTEN": dut.timer_written_i, "C_WRITTEN": dut.counter_written_i}
    for _ in range(3):
        values = {name: rng.getrandbits(64) for name in vectors}
        for name, sig in vectors.items():
            sig.value = values[name]
        for name, v in values.items():
            assert await read(dut, DEF.bus[name + "_LO"]) == v & 0xFFFFFFFF, name
            assert await read(dut, DEF.bus[name + "_HI"]) == v >> 32, name


@cocotb.test()
async def tc_wait_stalls_until_written(dut):
    """TC_WAIT (parallel mode's status wait): a write selects timer / counter n (bit 6
    counter, as TC_BIT); a read is not ready while its written bit is 0 (another
    index's or the other kind's bit does not count), then gives its enable / pulse."""
    await reset(dut)
    wait = DEF.bus["TC_WAIT"]
    counter = dict(DEF.register("TC_BIT").fields)["TC_COUNTER"]
    for kind, n in (("counter", 41), ("timer", 7)):
        written = dut.counter_written_i if kind == "counter" else dut.timer_written_i
        other = dut.timer_written_i if kind == "counter" else dut.counter_written_i
        value = dut.counter_pulse_i if kind == "counter" else dut.timer_enable_i
        value.value = 1 << n
        written.value = (1 << (n + 1)) | (1 << (n - 1))
        other.value = 1 << n
        await access(dut, wait, (counter if kind == "counter" else 0) | n)
        for _ in range(3):
            assert await access(dut, wait) == (1, 0), kind        # not ready
        written.value = 1 << n
        assert await access(dut, wait) == (1, 1), kind
        value.value = 0
        assert await access(dut, wait) == (0, 1), kind
        written.value = other.value = 0


# ------------------------------------------------------------------ the register map's model
M32 = 0xFFFFFFFF
REG = {r.name: r for r in DEF.registers if not r.plant_only}   # byte_port decodes 8 bits
F = dict(f for r in DEF.registers for f in r.fields)            # field masks and shifts


def sext16(v: int) -> int:
    return (v | 0xFFFF0000) if v & 0x8000 else v


def register_at(addr: int):
    """(register, index in its window) of a bus address, or (None, 0)."""
    for r in REG.values():
        if r.addr <= addr < r.addr + r.count:
            return r, addr - r.addr
    return None, 0


def word(vec: int, n: int) -> int:
    return (vec >> (16 * n)) & 0xFFFF


class BusModel:
    """byte_port as docs/byte-bus.md describes it, clock by clock: the read data and
    strobes of a clock from its inputs (`outputs`), the registers after its edge
    (`clock`). TIME_MS steps when TICK_DIV clocks (as TICK_DIV is at that clock) have
    passed since its last step, counted from clock 0 (the first latch / time start)."""

    def __init__(self):
        self.out_words = [0] * WORDS
        self.byte_flags = 0
        self.tick_div = REG["TICK_DIV"].reset
        self.scan_done = 0
        self.started = False
        self.clock_count = self.ms = self.since_step = 0
        self.stalls_bit = self.stalls_byte = 0
        self.pending = False
        self.disp_ms = self.disp_iw = 0
        self.latch_ms = 0               # TIME_MS at the last latch
        self.tc_wait_sel = 0
        self.mc_pend = False            # a marker cell's read was refused last clock

    def tc_wait_bit(self, i: dict, timer: str, counter: str) -> int:
        vec = i[counter] if self.tc_wait_sel & F["TC_COUNTER"] else i[timer]
        return vec >> (self.tc_wait_sel & F["TC_INDEX_MASK"]) & 1

    def read_value(self, name: str, n: int, i: dict) -> int:
        """What register `name` (window index n) reads with the inputs `i`."""
        first = i["next"] and not self.pending          # a dispatch's first clock: live
        named = word(i["in_words"], i["instr"] & 0xF)
        lo, hi = (lambda v: v & M32), (lambda v: v >> 32)
        values = {
            "ID": lambda: DEF.bus_id_value,
            # bit 0 NEXT, bit 1 running, bit 2 fault, bit 3 SCAN_DONE
            "STATUS": lambda: i["next"] | i["exec"] << 1 | i["fault"] << 2 | self.scan_done << 3,
            "DISPATCH_INSTR": lambda: i["instr"],
            "DISPATCH_CTX": lambda: i["ctx"],
            "DISPATCH_MS": lambda: self.ms if first else self.disp_ms,
            "DISPATCH_IW": lambda: sext16(named if first else self.disp_iw),
            "TIME_MS": lambda: self.ms,
            "TICK_DIV": lambda: self.tick_div,
            "CLOCK": lambda: self.clock_count,
            "LATCH_MS": lambda: self.ms if i["latch"] else self.latch_ms,
            "T_STATUS_LO": lambda: lo(i["t_stat"]), "T_STATUS_HI": lambda: hi(i["t_stat"]),
            "C_STATUS_LO": lambda: lo(i["c_stat"]), "C_STATUS_HI": lambda: hi(i["c_stat"]),
            "T_ENABLE_LO": lambda: lo(i["t_en"]), "T_ENABLE_HI": lambda: hi(i["t_en"]),
            "C_PULSE_LO": lambda: lo(i["c_pulse"]), "C_PULSE_HI": lambda: hi(i["c_pulse"]),
            "T_WRITTEN_LO": lambda: lo(i["t_wr"]), "T_WRITTEN_HI": lambda: hi(i["t_wr"]),
            "C_WRITTEN_LO": lambda: lo(i["c_wr"]), "C_WRITTEN_HI": lambda: hi(i["c_wr"]),
            # the enable / pulse bit of the timer / counter the last TC_WAIT write chose
            "TC_WAIT": lambda: self.tc_wait_bit(i, "t_en", "c_pulse"),
            # pops channel n: its condition in bit 0 (a channel the build lacks: 0); with
            # the marker exchange cell n (the cell port's answer, a clock after its read)
            "FBY": lambda: int(bool(i["re"] and (self.cell_data(i, n) if i["marker"] else
                                                 n < CHANNELS and i["fby_data"] >> n & 1))),
            "MCELL": lambda: int(bool(i["re"] and i["marker"] and self.cell_data(i, n))),
            # bits 7..0 FBY n full, bits 15..8 FBI n full
            "CHAN_STATUS": lambda: i["fby_full"] | i["fbi_full"] << 8,
            "IW": lambda: sext16(word(i["in_words"], n)),
            "QW": lambda: sext16(self.out_words[n]),
            "STALLS_BIT": lambda: self.stalls_bit,
            "STALLS_BYTE": lambda: self.stalls_byte,
            "BYTE_FLAGS": lambda: self.byte_flags,
            "QUEUE_OVERFLOWS": lambda: i["qov"],
            "QUEUE_UNDERFLOWS": lambda: i["qun"],
        }
        readable = {r.name for r in REG.values() if "R" in r.access}
        assert readable == set(values), "BusModel: the register map changed"
        return values[name]() if name in values else 0     # write-only registers read 0

    @staticmethod
    def cell_data(i: dict, k: int) -> int:
        return int(k < CELLS and i["cell_rdata"])   # a cell the build lacks reads 0

    @staticmethod
    def cell_access(i: dict, name: str | None):
        """(cell read, cell write, k) of the marker exchange: cell k at FBY k / FBI k
        and in the MCELL window."""
        k = i["addr"] - REG["MCELL"].addr if name == "MCELL" else i["addr"] & 7
        m = i["marker"]
        return (bool(i["re"] and m and name in ("FBY", "MCELL")),
                bool(i["we"] and m and name in ("FBI", "MCELL")), k)

    def outputs(self, i: dict) -> dict:
        reg, n = register_at(i["addr"])
        name = reg.name if reg else None
        chan = i["addr"] & 7
        fby_rd = i["re"] and name == "FBY" and not i["marker"]
        fbi_wr = i["we"] and name == "FBI" and not i["marker"]
        have = chan < CHANNELS
        cell_rd, cell_wr, k = self.cell_access(i, name)
        ready = not (fby_rd and have and not i["fby_ready"] >> chan & 1) and \
            not (fbi_wr and have and not i["fbi_ready"] >> chan & 1) and \
            not (i["re"] and name == "TC_WAIT" and not self.tc_wait_bit(i, "t_wr", "c_wr")) \
            and not (cell_rd and not self.mc_pend)     # a cell's read: two clocks
        w = i["wdata"]
        return {
            "bus_rdata_o": self.read_value(name, n, i) if name else 0,
            "bus_ready_o": int(ready),
            "fby_rd_req_o": (1 << chan) if fby_rd and have else 0,
            "fbi_wr_req_o": (1 << chan) if fbi_wr and have else 0,
            "cell_re_o": int(cell_rd and not self.mc_pend),
            "cell_ridx_o": k % CELLS,
            "cell_we_o": int(cell_wr and k < CELLS),
            "cell_widx_o": k % CELLS,
            "cell_wdata_o": w & 1,
            "fbi_wr_data_o": w & 1,
            "done_we_o": int(bool(i["we"] and name == "DONE")),
            "done_data_o": (w & (F["DONE_RLO"] | F["DONE_RLO_WE"])),
            "tc_we_o": int(bool(i["we"] and name == "TC_BIT")),
            "tc_is_counter_o": int(bool(w & F["TC_COUNTER"])),
            "tc_idx_o": w & F["TC_INDEX_MASK"] & (STATUS_BITS - 1),
            "tc_val_o": int(bool(w & F["TC_VALUE"])),
            "byte_scan_end_o": int(bool(i["we"] and name == "SCAN_DONE")),
        }

    def clock(self, i: dict, out: dict) -> None:
        reg, n = register_at(i["addr"])
        name = reg.name if reg else None
        if i["next"] and not self.pending:                 # the snapshot of a dispatch
            self.disp_ms = self.ms
            self.disp_iw = word(i["in_words"], i["instr"] & 0xF)
        self.pending = bool(i["next"] and not out["done_we_o"])
        if i["latch"]:
            self.latch_ms = self.ms
        if self.started or i["latch"] or i["time_start"]:
            self.started = True
            self.clock_count = (self.clock_count + 1) & M32
            self.since_step += 1
            if self.since_step >= self.tick_div:
                self.ms, self.since_step = (self.ms + 1) & M32, 0
        self.stalls_bit = (self.stalls_bit + i["bit_stall"]) & M32
        cell_rd, _, _ = self.cell_access(i, name)
        if (i["re"] or i["we"]) and not out["bus_ready_o"] and not cell_rd:
            self.stalls_byte = (self.stalls_byte + 1) & M32   # (a cell's RAM read is none)
        self.mc_pend = cell_rd and not self.mc_pend
        if i["we"] and name == "SCAN_DONE":
            self.scan_done = 1
        elif i["latch"]:
            self.scan_done = 0
        if i["we"] and name == "TICK_DIV":
            self.tick_div = i["wdata"]
        if i["we"] and name == "BYTE_FLAGS":
            self.byte_flags = i["wdata"]
        if i["we"] and name == "TC_WAIT":
            self.tc_wait_sel = i["wdata"] & (F["TC_COUNTER"] | F["TC_INDEX_MASK"])
        if i["we"] and name == "QW":
            self.out_words[n] = i["wdata"] & 0xFFFF

    def registers(self) -> dict:
        return {"out_words_o": sum(v << (16 * k) for k, v in enumerate(self.out_words)),
                "byte_scan_done_o": self.scan_done,
                "stalls_bit_o": self.stalls_bit, "stalls_byte_o": self.stalls_byte}


INPUTS = {"addr": "bus_addr_i", "wdata": "bus_wdata_i", "we": "bus_we_i", "re": "bus_re_i",
          "latch": "latch_i", "time_start": "time_start_i", "exec": "exec_i",
          "fault": "fault_i", "next": "next_i", "instr": "dispatch_instr_i",
          "ctx": "dispatch_ctx_i", "t_stat": "timer_status_i", "c_stat": "counter_status_i",
          "t_en": "timer_enable_i", "c_pulse": "counter_pulse_i",
          "t_wr": "timer_written_i", "c_wr": "counter_written_i",
          "fby_data": "fby_rd_data_i", "fby_ready": "fby_rd_ready_i",
          "fby_full": "fby_full_i", "fbi_ready": "fbi_wr_ready_i", "fbi_full": "fbi_full_i",
          "in_words": "in_words_i", "bit_stall": "bit_stall_i",
          "qov": "queue_overflows_i", "qun": "queue_underflows_i",
          "marker": "marker_i", "cell_rdata": "cell_rdata_i"}


def random_inputs(rng: random.Random, addr: int, kind: str, tick_div_small: bool) -> dict:
    """One clock's inputs: an access of `kind` ('r', 'w', '-') to `addr`, every other
    input random (each bit of every vector at 0 or 1)."""
    ch = (1 << CHANNELS) - 1
    wdata = rng.getrandbits(32)
    if tick_div_small and addr == REG["TICK_DIV"].addr:
        wdata = rng.randrange(0, 5)               # short milliseconds, 0 counting like 1
    return {"addr": addr, "wdata": wdata, "we": int(kind == "w"), "re": int(kind == "r"),
            "latch": int(rng.random() < 0.03), "time_start": int(rng.random() < 0.01),
            "exec": rng.getrandbits(1), "fault": rng.getrandbits(1),
            "next": int(rng.random() < 0.6), "instr": rng.getrandbits(32),
            "ctx": rng.getrandbits(32), "t_stat": rng.getrandbits(STATUS_BITS),
            "c_stat": rng.getrandbits(STATUS_BITS), "t_en": rng.getrandbits(STATUS_BITS),
            "c_pulse": rng.getrandbits(STATUS_BITS), "t_wr": rng.getrandbits(STATUS_BITS),
            "c_wr": rng.getrandbits(STATUS_BITS), "fby_data": rng.getrandbits(CHANNELS),
            "fby_ready": rng.getrandbits(CHANNELS) | (ch if rng.random() < 0.5 else 0),
            "fby_full": rng.getrandbits(CHANNELS),
            "fbi_ready": rng.getrandbits(CHANNELS) | (ch if rng.random() < 0.5 else 0),
            "fbi_full": rng.getrandbits(CHANNELS), "in_words": rng.getrandbits(16 * WORDS),
            "bit_stall": rng.getrandbits(1), "qov": rng.getrandbits(32),
            "qun": rng.getrandbits(32), "marker": int(rng.random() < 0.4),
            "cell_rdata": rng.getrandbits(1)}


async def against_model(dut, model: BusModel, accesses, rng: random.Random,
                        tick_div_small: bool = True) -> None:
    """Run `accesses` ((addr, kind) per clock) with random other inputs; compare every
    output with the model in every clock (the combinational ones before the edge, the
    registers after it)."""
    for clk, (addr, kind) in enumerate(accesses):
        i = random_inputs(rng, addr, kind, tick_div_small)
        for key, sig in INPUTS.items():
            getattr(dut, sig).value = i[key]
        await Timer(1, unit="ns")
        want = model.outputs(i)
        got = {k: int(getattr(dut, k).value) for k in want}
        assert got == want, (clk, hex(addr), kind, {k: (hex(got[k]), hex(want[k]))
                                                    for k in want if got[k] != want[k]})
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
        model.clock(i, want)
        want_r = model.registers()
        got_r = {k: int(getattr(dut, k).value) for k in want_r}
        assert got_r == want_r, (clk, hex(addr), kind, {k: (hex(got_r[k]), hex(want_r[k]))
                                                        for k in want_r if got_r[k] != want_r[k]})
    for sig in ("bus_we_i", "bus_re_i"):
        getattr(dut, sig).value = 0


def mapped_addresses() -> list[int]:
    return [r.addr + n for r in REG.values() for n in range(r.count)]


@cocotb.test()
async def every_address_against_model(dut):
    """Every one of the 256 addresses read, then written, then read again (the written
    registers read back), in clocks whose other inputs are all random: each register's
    every bit, the write-only and unmapped addresses reading 0, the strobes only at
    their address."""
    rng = random.Random(15)
    await reset(dut)
    model = BusModel()
    sweep = [(a, "r") for a in range(256)] + [(a, "w") for a in range(256)] + \
        [(a, "r") for a in range(256)]
    await against_model(dut, model, sweep, rng)


@cocotb.test()
async def random_traffic_against_model(dut):
    """Random reads, writes and idle clocks (mostly at mapped addresses) with random
    inputs (600 clocks), the time base running from a random latch, TICK_DIV rewritten with small
    values: reads, strobes, readiness, the stall counts, SCAN_DONE, the output words and
    the dispatch snapshot against the model in every clock."""
    rng = random.Random(1515)
    await reset(dut)
    model = BusModel()
    mapped = mapped_addresses()
    seq = []
    for _ in range(600):
        addr = rng.choice(mapped) if rng.random() < 0.8 else rng.randrange(256)
        seq.append((addr, rng.choice("rrw-")))
    await against_model(dut, model, seq, rng)


@cocotb.test()
async def every_output_word_bit(dut):
    """Each QW n written with patterns that give every bit both values and each bit a
    code of its own (its position in binary, and inverted): out_words_o carries exactly
    the written word in its 16 bits (the others untouched), and QW n reads it back."""
    await reset(dut)
    qw = REG["QW"]
    words = [0] * WORDS
    for mask in (0x5555, 0x3333, 0x0F0F, 0x00FF):
        for pattern in (mask, 0xFFFF ^ mask):
            for n in range(WORDS):
                value = pattern ^ (n * 0x1111 & 0xFFFF) if n % 2 else pattern
                await access(dut, qw.addr + n, value | 0xABCD0000)
                words[n] = value
                assert int(dut.out_words_o.value) == sum(v << 16 * k for k, v in enumerate(words))
            for n in range(WORDS):
                assert await read(dut, qw.addr + n) == sext16(words[n])



@cocotb.test()
async def tick_div_every_bit(dut):
    """TICK_DIV written with patterns that give every bit both values, alone and with
    all the others (one bit set, one bit clear) and each bit a code of its own (its
    position in binary, and inverted): it reads back exactly, and keeps the value over
    the clocks after the write. The random traffic writes small divisors only (short
    milliseconds), so a bit that goes wrong only when another is set (mutation 9 of
    the 2026-12-03 campaign: bit 9 flipped while bit 6 is set) needs these."""
    await reset(dut)
    tick = REG["TICK_DIV"]
    assert await read(dut, tick.addr) == tick.reset
    patterns = [1 << k for k in range(32)] + [M32 ^ (1 << k) for k in range(32)]
    for mask in (0x55555555, 0x33333333, 0x0F0F0F0F, 0x00FF00FF, 0x0000FFFF):
        patterns += [mask, M32 ^ mask]
    for value in patterns:
        await access(dut, tick.addr, value)
        for _ in range(2):
            assert await read(dut, tick.addr) == value, hex(value)


@cocotb.test()
async def dispatch_iw_every_word(dut):
    """DISPATCH_IW for each of the 16 input words an instruction can name (bits 3..0
    of the instruction word, as BusModel), every bit of the named word at both values
    (a random input vector, then its complement): the dispatch's first clock reads the
    named word live, the clocks after it the snapshot while the input words change.
    The random traffic rarely reads a snapshot of a given word (mutation 16 of the
    2026-12-03 campaign: word 5's bit 0 inverted on its way to the snapshot)."""
    rng = random.Random(16)
    await reset(dut)
    iw = REG["DISPATCH_IW"].addr
    full = (1 << 16 * WORDS) - 1
    for n in range(WORDS):
        vec = rng.getrandbits(16 * WORDS)
        for words in (vec, full ^ vec):
            dut.next_i.value = 0                  # no dispatch pending: the next is fresh
            await RisingEdge(dut.clk_i)
            await FallingEdge(dut.clk_i)
            dut.in_words_i.value = words
            dut.dispatch_instr_i.value = rng.getrandbits(28) << 4 | n
            dut.next_i.value = 1
            want = sext16(word(words, n))
            assert await read(dut, iw) == want, (n, "live")
            dut.in_words_i.value = full ^ words   # changes after the first clock
            for _ in range(2):
                assert await read(dut, iw) == want, (n, "snapshot")
    dut.next_i.value = 0

@pytest.mark.parametrize("sim", SIMULATORS)
def test_byte_port(sim):
    run_cocotb(sim, "byte_port", "test_byte_port", parameters={"Channels": CHANNELS})
