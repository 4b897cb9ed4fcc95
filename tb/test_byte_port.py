"""Byte-side port: register map (docs/byte-bus.md), time base, word I/O, channel
routing with ready/stall, DONE and TC_BIT strobes."""
from __future__ import annotations

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from bitbyte.lang.definition import DEF

from simrun import SIMULATORS, run_cocotb

CHANNELS = 4


async def reset(dut):
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    for sig in (dut.rst_ni, dut.bus_addr_i, dut.bus_wdata_i, dut.bus_we_i, dut.bus_re_i,
                dut.latch_i, dut.time_start_i, dut.exec_i, dut.fault_i, dut.next_i, dut.dispatch_instr_i,
                dut.dispatch_ctx_i, dut.timer_status_i, dut.counter_status_i,
                dut.timer_enable_i, dut.counter_pulse_i, dut.timer_written_i,
                dut.counter_written_i, dut.fby_rd_data_i,
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


@pytest.mark.parametrize("sim", SIMULATORS)
def test_byte_port(sim):
    run_cocotb(sim, "byte_port", "test_byte_port", parameters={"Channels": CHANNELS})
