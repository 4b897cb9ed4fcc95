"""Bit processor pipeline: one instruction per clock, marker forwarding, jumps, END,
the parenthesis stack. The scan controller is played by the test; instruction words
are written by hand from docs/isa.md (not produced by the assembler)."""
from __future__ import annotations

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from simrun import SIMULATORS, run_cocotb

MARKER_BITS = 64
# Opcodes (docs/isa.md) and area codes, spelled out independently of bitbyte/encoding/isa.py
END, NOT, SET, CLR, CLOSE, NOP = 0x01, 0x02, 0x03, 0x04, 0x05, 0x00
LD, LDN, A, AN, O, ON, X, XN = range(0x08, 0x10)
A_OPEN, AN_OPEN, O_OPEN, ON_OPEN, X_OPEN, XN_OPEN = range(0x12, 0x18)
ASSIGN, S, R, FP, FN = 0x18, 0x19, 0x1A, 0x1B, 0x1C
JU, JC, JCN = 0x20, 0x21, 0x22
AREA = {"I": 0, "PI": 1, "IR": 2, "IF": 3, "Q": 4, "PQ": 5, "M": 6, "T": 7, "C": 8,
        "FB": 9}
CMP_GE = 0x94            # byte instruction `>=I` (docs/isa.md)


def w(op, area=None, index=0):
    return (op << 24) | ((AREA[area] << 12 | index) if area else index)


class Bench:
    """Plays the scan controller and the I/O units around bit_proc."""

    def __init__(self, dut):
        self.dut = dut
        self.pio = 0
        self.writes = []        # (clock, index, value, direct)

    async def start(self, prog, pii=0):
        d = self.dut
        cocotb.start_soon(Clock(d.clk_i, 10, unit="ns").start())
        for sig in (d.rst_ni, d.start_i, d.latch_i, d.exec_i, d.prog_we_i, d.pins_i, d.rise_i,
                    d.fall_i, d.rise_pend_i, d.fall_pend_i, d.pio_i, d.timer_status_i, d.counter_status_i,
                    d.timer_updated_i, d.counter_updated_i, d.end_hold_i,
                    d.fbi_rd_data_i, d.fbi_rd_ready_i, d.byte_done_i, d.byte_rlo_i,
                    d.byte_rlo_we_i, d.copy_en_i, d.copy_we_i, d.copy_addr_i, d.copy_wdata_i,
                    d.tc_we_i, d.tc_is_counter_i, d.tc_idx_i, d.tc_val_i,
                    d.marker_i, d.cell_rdata_i):
            sig.value = 0
        d.fby_wr_ready_i.value = 0b1111
        # the input unit's image; in the latch clock the first instruction sees the
        # pins being latched, so the pins carry the same value
        d.pii_i.value = pii
        d.pins_i.value = pii
        for addr, word in enumerate(prog):
            await FallingEdge(d.clk_i)
            d.prog_we_i.value, d.prog_waddr_i.value, d.prog_wdata_i.value = 1, addr, word
        await FallingEdge(d.clk_i)
        d.prog_we_i.value = 0
        d.rst_ni.value = 1
        await Timer(MARKER_BITS * 10, unit="ns")
        while not int(d.mem_ready_o.value):
            await FallingEdge(d.clk_i)
        await FallingEdge(d.clk_i)

    async def begin(self):
        """An idle clock announcing the scan (start_i: address 0 moves to execute),
        then the latch clock, in which the first instruction executes."""
        d = self.dut
        d.start_i.value, d.latch_i.value, d.exec_i.value = 1, 0, 0
        await RisingEdge(d.clk_i)
        await FallingEdge(d.clk_i)
        d.start_i.value, d.latch_i.value, d.exec_i.value = 0, 1, 1

    async def scan(self, limit=1000):
        """One scan: from the latch clock until END. Returns (cycles, pcs, rlos):
        cycles counted like the scan controller (latch clock through END), pcs/rlos =
        executed address and RLO after it, per clock (None = bubble)."""
        d = self.dut
        await self.begin()
        cycles, pcs, rlos = 0, [], []
        for clock in range(limit):
            await Timer(1, unit="ns")      # let the new controls settle before sampling
            valid = int(d.exec_valid_o.value)
            pc = int(d.exec_pc_o.value) if valid else None
            ended = int(d.end_o.value)
            if int(d.out_wr_en_o.value):
                idx, val = int(d.out_wr_idx_o.value), int(d.out_wr_val_o.value)
                self.writes.append((cycles, idx, val, int(d.out_wr_direct_o.value)))
                self.pio = (self.pio & ~(1 << idx)) | (val << idx)
            await RisingEdge(d.clk_i)
            await FallingEdge(d.clk_i)
            d.latch_i.value = 0
            d.pio_i.value = self.pio
            cycles += 1
            pcs.append(pc)
            rlos.append(int(d.rlo_o.value))
            if ended:
                d.exec_i.value = 0
                return cycles, pcs, rlos
        raise AssertionError("no END")


@cocotb.test()
async def one_instruction_per_clock(dut):
    """Straight-line code: N instructions + END take N + 1 clocks, no bubble (the
    first executes in the latch clock)."""
    pattern = [w(LD, "I", 0), w(A, "I", 1), w(O, "I", 2), w(X, "I", 3),
               w(AN, "I", 4), w(ON, "I", 5), w(XN, "I", 6), w(LDN, "I", 7)]
    for n in (1, 8, 100):
        bench = Bench(dut)
        prog = [pattern[i % 8] for i in range(n)] + [w(END)]
        await bench.start(prog, pii=0b10100110)
        cycles, pcs, _ = await bench.scan()
        assert cycles == n + 1, f"N={n}: {cycles} clocks"
        assert pcs == list(range(n + 1)), "a bubble or a skipped instruction"
        dut._log.info("N=%d: %d clocks per scan, CPI %.2f", n, cycles, (cycles - 1) / n)
        cycles2, pcs2, _ = await bench.scan()      # the next scan: same, no refill
        assert (cycles2, pcs2) == (cycles, pcs)


@cocotb.test()
async def logic_ops_in_sequence(dut):
    """RLO after each combine, against hand-computed values (no AND-before-OR)."""
    bench = Bench(dut)
    # I0.0=0 I0.1=1 I0.2=1 I0.3=0
    prog = [w(LD, "I", 1), w(O, "I", 0), w(A, "I", 3), w(ON, "I", 3), w(X, "I", 2),
            w(XN, "I", 3), w(AN, "I", 1), w(LDN, "I", 0), w(NOT), w(SET), w(CLR), w(END)]
    await bench.start(prog, pii=0b0110)
    _, _, rlos = await bench.scan()
    assert rlos[:11] == [1, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0]


@cocotb.test()
async def marker_write_then_read(dut):
    """A marker written by one instruction is read by the very next (forwarding)."""
    bench = Bench(dut)
    prog = [w(SET), w(ASSIGN, "M", 5), w(LD, "M", 5), w(ASSIGN, "Q", 0),
            w(CLR), w(ASSIGN, "M", 5), w(LDN, "M", 5), w(ASSIGN, "Q", 1),
            w(LD, "M", 5), w(ASSIGN, "Q", 2), w(SET), w(S, "M", 9), w(NOP),
            w(LD, "M", 9), w(ASSIGN, "Q", 3), w(END)]
    await bench.start(prog)
    await bench.scan()
    assert bench.pio & 0b1111 == 0b1011


@cocotb.test()
async def markers_survive_scans(dut):
    """M keeps its value across scans; FP fires once per rising edge of the RLO."""
    bench = Bench(dut)
    prog = [w(SET), w(FP, "M", 3), w(ASSIGN, "Q", 0), w(END)]
    await bench.start(prog)
    await bench.scan()
    assert bench.pio & 1 == 1
    await bench.scan()
    assert bench.pio & 1 == 0


@cocotb.test()
async def jumps_cost(dut):
    """Taken jump: 3 clocks (decode and operand squashed); not taken: 1."""
    bench = Bench(dut)
    prog = [w(CLR),               # 0
            w(JC, None, 5),       # 1 not taken
            w(JU, None, 5),       # 2 taken
            w(SET), w(SET),       # 3, 4 skipped
            w(JCN, None, 7),      # 5 taken (RLO 0)
            w(SET),               # 6 skipped
            w(END)]               # 7
    await bench.start(prog)
    cycles, pcs, _ = await bench.scan()
    assert [p for p in pcs if p is not None] == [0, 1, 2, 5, 7]
    assert cycles == 1 + 1 + 3 + 3 + 1


@cocotb.test()
async def backward_jump_loop(dut):
    """A loop over an M counter bit: l: LD M0.0; NOT; = M0.0; JC l; END."""
    bench = Bench(dut)
    prog = [w(LD, "M", 0), w(NOT), w(ASSIGN, "M", 0), w(JC, None, 0), w(END)]
    await bench.start(prog)
    cycles, pcs, _ = await bench.scan()
    # first pass: M0.0 0 -> 1, RLO 1, jump; second: 1 -> 0, fall through
    assert [p for p in pcs if p is not None] == [0, 1, 2, 3, 0, 1, 2, 3, 4]
    assert cycles == 3 + 3 + 4 + 1


@cocotb.test()
async def parentheses_eight_deep(dut):
    """A( A( ... 8 levels: each level pushes, `)` combines with the saved RLO."""
    bench = Bench(dut)
    # RLO = I0.0 AND (I0.1 OR (I0.0 XOR (...))) built by hand for I0.0=1, I0.1=0
    prog = [w(LD, "I", 0)]
    opens = [A_OPEN, O_OPEN, X_OPEN, AN_OPEN, ON_OPEN, XN_OPEN, A_OPEN, O_OPEN]
    for op in opens:
        prog += [w(op), w(LD, "I", 1)]
    prog += [w(CLOSE)] * 8 + [w(ASSIGN, "Q", 0), w(END)]
    await bench.start(prog, pii=0b01)
    _, _, rlos = await bench.scan()
    # innermost result 0 (I0.1); fold outward with saved RLOs (all 0 inside, 1 outside)
    expect = 0
    saved = [1] + [0] * 7
    for op, acc in reversed(list(zip(opens, saved))):
        f, n = (op >> 1) & 3, op & 1
        x = expect ^ n
        expect = {1: acc & x, 2: acc | x, 3: acc ^ x}[f]
    assert rlos[-3] == expect
    assert bench.pio & 1 == expect


@cocotb.test()
async def waits_on_channels(dut):
    """`= FBY 1` waits while F_bB 1 is full; `A FBI 2` waits while F_Bb 2 is empty;
    nothing takes effect before the clock the channel is ready."""
    bench = Bench(dut)
    prog = [w(SET), w(ASSIGN, "FB", 1), w(A, "FB", 2), w(ASSIGN, "Q", 0), w(END)]
    await bench.start(prog)
    d = dut
    d.fby_wr_ready_i.value = 0
    d.fbi_rd_ready_i.value = 0
    await bench.begin()
    trace = []
    for clock in range(12):
        if clock == 3:
            d.fby_wr_ready_i.value = 0b0010
        if clock == 6:
            d.fbi_rd_ready_i.value, d.fbi_rd_data_i.value = 0b0100, 0b0100
        await Timer(1, unit="ns")
        trace.append((int(d.exec_pc_o.value), int(d.stall_o.value),
                      int(d.fby_wr_req_o.value), int(d.fbi_rd_req_o.value),
                      int(d.out_wr_en_o.value)))
        ended = int(d.end_o.value)
        await RisingEdge(d.clk_i)
        await FallingEdge(d.clk_i)
        d.latch_i.value = 0
        if ended:
            break
    # pc 1 (= FBY 1) offers to channel 1 for clocks 1..3, taken at 3
    assert [t[:3] for t in trace[1:4]] == [(1, 1, 2), (1, 1, 2), (1, 0, 2)]
    # pc 2 (A FBI 2) asks channel 2 for clocks 4..6, served at 6; then = Q0.0 writes 1
    assert [t[:2] + (t[3],) for t in trace[4:7]] == [(2, 1, 4), (2, 1, 4), (2, 0, 4)]
    assert trace[7][0] == 3 and trace[7][4] == 1


@cocotb.test()
async def dispatch_holds_until_done(dut):
    """A byte instruction waits in execute until DONE; DONE may carry a new RLO."""
    bench = Bench(dut)
    prog = [w(SET), CMP_GE << 24, w(ASSIGN, "Q", 0), w(END)]
    await bench.start(prog)
    d = dut
    await bench.begin()
    reqs = []
    for clock in range(10):
        done = clock == 5
        d.byte_done_i.value, d.byte_rlo_i.value, d.byte_rlo_we_i.value = int(done), 0, 1
        await Timer(1, unit="ns")
        reqs.append(int(d.byte_req_o.value))
        if int(d.byte_req_o.value):
            assert int(d.byte_instr_o.value) == CMP_GE << 24
        if int(d.out_wr_en_o.value):
            assert int(d.out_wr_val_o.value) == 0    # the RLO came from DONE
            wrote = clock
        await RisingEdge(d.clk_i)
        await FallingEdge(d.clk_i)
        d.latch_i.value = 0
        d.byte_done_i.value = 0
    assert reqs[:7] == [0, 1, 1, 1, 1, 1, 0]         # dispatched clocks 1..5
    assert wrote == 6


CMP_EQ = 0x90            # byte instruction `==I` (a compare: DONE carries the RLO)
SD_T = 0xB0              # byte instruction `SD T n` (no RLO with DONE)


async def run_with_byte_side(bench, cost, tc_writes=(), fbi=None, limit=200):
    """One scan with a byte side that answers every dispatched instruction `cost(pc)`
    clocks after it was offered (DONE in its last clock; a compare's DONE carries
    RLO = 1), writes the T/C status bits of `tc_writes` ((clock, is_counter, index,
    value)) and makes FBI channels ready from a clock on (`fbi`: {clock: (ready,
    data)}). Returns per clock (pc or None, stall, byte_req, fbi_rd_req)."""
    d = bench.dut
    writes = {c: (isc, idx, val) for c, isc, idx, val in tc_writes}
    fbi = fbi or {}
    await bench.begin()
    trace, offered, tstat, cstat = [], 0, 0, 0
    tupd = cupd = 0       # tc_status.v's updated bits: set by a write, 0 at the scan start
    d.timer_updated_i.value = d.counter_updated_i.value = 0
    for clock in range(limit):
        if clock in fbi:
            d.fbi_rd_ready_i.value, d.fbi_rd_data_i.value = fbi[clock]
        await Timer(1, unit="ns")
        req = int(d.byte_req_o.value)
        done = 0
        if req:
            offered += 1
            if offered == cost(int(d.exec_pc_o.value)):
                done, offered = 1, 0
        instr = int(d.byte_instr_o.value) >> 24
        d.byte_done_i.value = done
        d.byte_rlo_i.value = 1
        d.byte_rlo_we_i.value = int(done and 0x90 <= instr <= 0xA7)
        w8 = writes.get(clock)
        d.tc_we_i.value = int(w8 is not None)
        if w8:
            d.tc_is_counter_i.value, d.tc_idx_i.value, d.tc_val_i.value = w8
        await Timer(1, unit="ns")
        valid = int(d.exec_valid_o.value)
        trace.append((int(d.exec_pc_o.value) if valid else None, int(d.stall_o.value),
                      req, int(d.fbi_rd_req_o.value)))
        if int(d.out_wr_en_o.value):
            idx, val = int(d.out_wr_idx_o.value), int(d.out_wr_val_o.value)
            bench.pio = (bench.pio & ~(1 << idx)) | (val << idx)
        ended = int(d.end_o.value)
        await RisingEdge(d.clk_i)
        if w8:            # the status buffer (tc_status.v) takes the write at the edge
            isc, idx, val = w8
            if isc:
                cstat = (cstat & ~(1 << idx)) | (val << idx)
                cupd |= 1 << idx
            else:
                tstat = (tstat & ~(1 << idx)) | (val << idx)
                tupd |= 1 << idx
        await FallingEdge(d.clk_i)
        d.latch_i.value = 0
        d.tc_we_i.value = 0
        d.byte_done_i.value = 0
        d.pio_i.value = bench.pio
        d.timer_status_i.value, d.counter_status_i.value = tstat, cstat
        d.timer_updated_i.value, d.counter_updated_i.value = tupd, cupd
        if ended:
            d.exec_i.value = 0
            return trace
    raise AssertionError("no END")


@cocotb.test()
async def blocked_behind_a_byte_instruction_reads_what_was_written(dut):
    """The instruction behind a byte instruction that waits (it enters execute behind
    the wait slot, blocked) executes in the clock after DONE and sees M and Q written
    just before the byte instruction, and T / C status bits the byte side writes
    during the wait, also in the DONE clock; a compare's RLO comes with DONE."""
    bench = Bench(dut)
    prog = [w(SET), w(ASSIGN, "M", 5), w(ASSIGN, "Q", 4),    # 0..2
            SD_T << 24 | 7 << 12 | 3,                       # 3  byte, 4 clocks
            w(LD, "M", 5), w(A, "Q", 4), w(ASSIGN, "Q", 0), # 4..6  M5 = Q4 = 1
            w(CLR), w(ASSIGN, "M", 5),                      # 7, 8  M5 := 0
            SD_T << 24 | 7 << 12 | 3,                       # 9  byte, 4 clocks
            w(LDN, "M", 5), w(ASSIGN, "Q", 1),              # 10, 11  Q1 = 1
            SD_T << 24 | 7 << 12 | 3,                       # 12 byte, 5 clocks; T3 := 1
            w(LD, "T", 3), w(ASSIGN, "Q", 2),               # 13, 14  Q2 = T3 = 1
            SD_T << 24 | 7 << 12 | 2,                       # 15 byte, 5 clocks; C2 := 1
            w(LD, "C", 2), w(ASSIGN, "Q", 3),               #    (in the DONE clock)
            w(CLR), CMP_EQ << 24,                           # 18, 19 compare: RLO 1
            w(ASSIGN, "Q", 5), w(END)]                      # 20, 21
    await bench.start(prog)
    byte_pcs = {3: 4, 9: 4, 12: 5, 15: 5, 19: 3}
    cost = lambda pc: byte_pcs[pc]
    # every instruction in turn, a byte instruction for its cost; the status writes
    # land in the waits of pcs 12 (T3) and 15 (C2, in its DONE clock)
    pcs = []
    for pc in range(len(prog)):
        pcs += [pc] * byte_pcs.get(pc, 1)
    t12, t15 = pcs.index(12), pcs.index(15)
    trace = await run_with_byte_side(
        bench, cost, tc_writes=[(t12 + 2, 0, 3, 1), (t15 + 4, 1, 2, 1)])
    assert [t[0] for t in trace] == pcs, "a byte instruction must take exactly its cost"
    assert [t[2] for t in trace] == [int(pc in byte_pcs) for pc in pcs], "NEXT"
    assert all(t[1] == 0 for t in trace), "a dispatched instruction's clocks are no stall"
    assert bench.pio & 0b111111 == 0b111111, f"PIO {bench.pio:#06b}"


AFTER_UPDATE = 1 << 16   # operand bit 16 of a T / C read: wait for this scan's update


@cocotb.test()
async def status_read_after_the_update(dut):
    """A `T` / `C` read marked "after the update" (bit 16): written earlier in the scan
    (the updated bit is set), it reads the new status at once; not yet written, it
    waits until the byte side writes it and reads that; unmarked, it reads the status
    as it is. (The bench plays tc_status.v: a write sets the status and its updated
    bit at the edge; the bits are 0 from the scan start.)"""
    prog = [w(NOP), w(NOP), w(NOP),                              # 0..2  T3 := 1 in clock 1
            w(LD, "T", 3) | AFTER_UPDATE, w(ASSIGN, "Q", 0),     # 3, 4  updated: no wait
            w(LDN, "C", 2), w(ASSIGN, "Q", 1),                   # 5, 6  C2 as it is: 0
            w(LD, "C", 2) | AFTER_UPDATE, w(ASSIGN, "Q", 2),     # 7, 8  waits for C2
            w(END)]
    bench = Bench(dut)
    await bench.start(prog)
    trace = await run_with_byte_side(bench, lambda pc: 1,
                                     tc_writes=[(1, 0, 3, 1), (12, 1, 2, 1)])
    pcs = [t[0] for t in trace]
    stalls = [t[1] for t in trace]
    assert pcs[:8] == list(range(8)) and not any(stalls[:7]), (pcs, stalls)
    last7 = max(i for i, pc in enumerate(pcs) if pc == 7)
    assert last7 >= 12 and all(stalls[7:12]), (pcs, stalls)      # waited for the write
    assert pcs[last7 + 1:] == [8, 9], pcs
    assert bench.pio & 0b111 == 0b111, f"PIO {bench.pio:#05b}: a read did not see the update"


@cocotb.test()
async def blocked_behind_a_channel_read(dut):
    """`A FBI 1` on an empty channel waits in the slot; the next instruction (an FBI
    read of another channel, then a byte instruction) waits behind it: stalls are the
    clocks the channel is empty, the byte instruction is offered only from the clock
    after the read, and reads the data as it is then."""
    bench = Bench(dut)
    prog = [w(SET), w(A, "FB", 1), w(A, "FB", 2), CMP_EQ << 24 | 0, w(ASSIGN, "Q", 0),
            w(LD, "FB", 2), w(ASSIGN, "Q", 1), w(END)]
    await bench.start(prog)
    dut.fbi_rd_ready_i.value = 0b0100   # channel 2 ready, 1 empty until clock 5
    dut.fbi_rd_data_i.value = 0b0100
    trace = await run_with_byte_side(bench, lambda pc: 3,
                                     fbi={5: (0b0110, 0b0110)})
    assert [t[0] for t in trace] == [0, 1, 1, 1, 1, 1, 2, 3, 3, 3, 4, 5, 6, 7]
    assert [t[1] for t in trace] == [0, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0]
    assert [t[2] for t in trace] == [0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 0, 0, 0, 0]
    assert [t[3] for t in trace][:7] == [0, 2, 2, 2, 2, 2, 4]
    assert bench.pio & 0b11 == 0b11


@cocotb.test()
async def stopped_while_waiting(dut):
    """exec_i falling (the scan watchdog's FAULT) while an instruction waits for the
    byte side ends the wait at once, as for an instruction held in execute: no NEXT,
    no channel request, no stall, nothing executing in the next clock."""
    for prog, wait_clocks in (([w(SET), CMP_GE << 24, w(ASSIGN, "Q", 0), w(END)], 3),
                              ([w(SET), w(A, "FB", 1), w(ASSIGN, "Q", 0), w(END)], 3),
                              ([w(SET), w(ASSIGN, "FB", 1), w(ASSIGN, "Q", 0), w(END)], 3)):
        bench = Bench(dut)
        await bench.start(prog)
        d = dut
        d.fbi_rd_ready_i.value, d.fby_wr_ready_i.value = 0, 0
        await bench.begin()
        for clock in range(1 + wait_clocks):   # SET, then the wait (no answer)
            await RisingEdge(d.clk_i)
            await FallingEdge(d.clk_i)
            d.latch_i.value = 0
        d.exec_i.value = 0                      # FAULT: nothing executes any more
        for clock in range(3):
            await Timer(1, unit="ns")
            seen = (int(d.byte_req_o.value), int(d.fbi_rd_req_o.value),
                    int(d.fby_wr_req_o.value), int(d.stall_o.value), int(d.exec_valid_o.value))
            assert seen == (0, 0, 0, 0, 0), f"{prog[1]:#010x}: clock {clock} after FAULT: {seen}"
            await RisingEdge(d.clk_i)
            await FallingEdge(d.clk_i)
        d.fbi_rd_ready_i.value, d.fby_wr_ready_i.value = 0, 0b1111


@pytest.mark.parametrize("sim", SIMULATORS)
def test_bit_proc(sim):
    run_cocotb(sim, "bit_proc", "test_bit_proc",
               parameters={"ProgWords": 256, "InBits": 16, "OutBits": 16,
                           "MarkerBits": MARKER_BITS})
