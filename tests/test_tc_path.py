"""`--tc-path status` (issue 16 item 1, paper Fig. 2's bit -> byte half): in free-running
mode a timer's enable / a counter's input goes through the timer/counter status buffer
(`= T n` / `= C n` on the bit side, the byte word's from-status flag) instead of an
exchange channel; docs/exchange.md. The default (`channel`) is today's partition."""
from __future__ import annotations

import pytest

from bitbyte import cli
from bitbyte.compiler.partition import partition
from bitbyte.encoding import isa
from bitbyte.lang.parser import parse, parse_file

# Timer 1 delays I0.0 by 2 ms into Q0.0; counter 1 counts the rising edges of I0.1 and
# the byte side copies its value into MW0.
PROGRAM = """\
      LD    I0.0
      L     2
      SD    T1
      LD    T1
      =     Q0.0
      LD    I0.1
      CU    C1
      L     C1
      T     MW0
"""
# I0.0 rises at 100 us; I0.1 rises at 300, 500 and 700 us (3 edges)
STIM = "t_us,I0.0,I0.1\n100,1,0\n300,1,1\n400,1,0\n500,1,1\n600,1,0\n700,1,1\n"
EDGES = (300, 500, 700)


def free(text: str, tc_path: str):
    return partition(parse("t.il", text), 4, status_sync=False, hardware_wait=False,
                     tc_path=tc_path)


def show(instrs):
    return [f"{i.mnemonic} {i.operand.text}".strip() if i.operand else i.mnemonic
            for i in instrs]


def test_fig5_free_status_words():
    """Fig. 5 in free mode: `SD Timer` takes its enable through T_ENABLE bit 1 instead
    of FBY 0. Words worked by hand from docs/isa.md: `= T 1` is ASSIGN (0x18), area T
    (7), index 1; SD T1 is 0xB0, word area T (7), index 1, plus bit 17."""
    program = parse_file("examples/fig5.il")
    chan = partition(program, 4, status_sync=False, hardware_wait=False)
    stat = partition(program, 4, status_sync=False, hardware_wait=False, tc_path="status")
    assert [t.direction for t in chan.transfers] == ["to_byte", "to_bit"]
    assert [t.direction for t in stat.transfers] == ["to_bit"]
    assert "= T1" in show(stat.bit) and "= FBY0" not in show(stat.bit)
    assert "READ FBY0" not in show(stat.byte)
    assert 0x18007001 in stat.bit_words
    assert 0xB0027001 in stat.byte_words and 0xB0007001 in chan.byte_words
    assert isa.FROM_STATUS_BIT == 17
    # the default is the channel path
    named = partition(program, 4, status_sync=False, hardware_wait=False, tc_path="channel")
    assert (chan.bit_words, chan.byte_words) == (named.bit_words, named.byte_words)


def test_fig5_parallel_status_words():
    """Parallel mode: the same path, and the SD word also carries the status-wait bit
    (18): the byte side reads T_ENABLE bit 1 only once T_WRITTEN bit 1 says the bit side
    wrote it in this scan. Hand-worked: 0xB0007001 | 1 << 17 | 1 << 18 = 0xB0067001."""
    program = parse_file("examples/fig5.il")
    chan = partition(program, 4)
    stat = partition(program, 4, tc_path="status")
    assert [t.direction for t in chan.transfers] == ["to_byte", "to_bit"]
    assert [t.direction for t in stat.transfers] == ["to_bit"]
    assert 0x18007001 in stat.bit_words and 0xB0067001 in stat.byte_words
    assert isa.STATUS_WAIT_BIT == 18
    # free-running mode never waits: bit 17 only
    assert 0xB0027001 in free(program_text("examples/fig5.il"), "status").byte_words


def program_text(path: str) -> str:
    with open(path) as f:
        return f.read()


# The bit side reaches `= T1` 21 instructions after the FBI read that gives it the
# compare result, the byte side its SD after one `L 0`: without the wait the byte side
# reads T_ENABLE before this scan's write and the timer follows IW0 a scan late.
RACE = ("L IW0\nL 0\n>I\nA I0.0\n" + "AN M1.0\n" * 20 + "L 0\nSD T1\nLD T1\n= Q0.0\n")
RACE_STIM = "scan,IW0,I0.0\n0,1,1\n1,0,1\n2,1,1\n3,1,1\n4,0,1\n5,1,1\n"


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
def test_parallel_status_waits_for_this_scans_write(tmp_path, sim):
    """Worked by hand: SD with preset 0 is on exactly while its enable is, so Q0.0 =
    (IW0 > 0) AND I0.0 in the same scan: 1 0 1 1 0 1, serial and parallel alike. Shown
    to fail (a scan late: 0 1 0 1 1 0) with the firmware's wait removed."""
    il = tmp_path / "race.il"
    il.write_text(RACE)
    st = tmp_path / "race.csv"
    st.write_text(RACE_STIM)
    got = {}
    for mode, path in (("serial", "channel"), ("parallel", "channel"), ("parallel", "status")):
        trace = tmp_path / f"{mode}-{path}.csv"
        assert cli.main(["run", str(il), "--mode", mode, "--tc-path", path, "--sim", sim,
                         "--stimulus", str(st), "--scans", "6", "--trace", str(trace),
                         "--watch", "T1"]) == 0
        got[mode, path] = [tuple(line.split(",")[3:]) for line in
                           trace.read_text().splitlines()[1:]]
    want = [(q, q) for q in "101101"]
    assert got["serial", "channel"] == got["parallel", "channel"] == want
    assert got["parallel", "status"] == want


def test_two_instructions_on_one_timer_keep_the_channel():
    """One enable bit per timer: SD T1 and R T1 with their own RLOs would overwrite
    each other's, so both keep a channel; the counter next to them goes through the
    buffer."""
    p = free("LD I0.0\nL 5\nSD T1\nLD I0.1\nR T1\nLD I0.2\nCD C2\n", "status")
    assert show(p.bit).count("= FBY0") + show(p.bit).count("= FBY1") == 2
    assert "= C2" in show(p.bit) and "= T1" not in show(p.bit)
    assert [i.from_status for i in p.byte if i.mnemonic == "CD"] == [True]
    assert not any(i.from_status for i in p.byte if i.mnemonic in ("SD", "R T", "R"))


def test_one_instruction_in_a_loop_keeps_the_channel():
    """A counter counted in a loop gets one input per iteration: the channel carries
    each in order, one enable bit would keep the last only. The same instruction
    outside the loop, behind a forward jump, takes the buffer."""
    loop = free("SET\n= M0.0\ntop: LD I0.1\nCU C1\nLD M0.0\nR M0.0\nJC top\n", "status")
    assert "= C1" not in show(loop.bit) and any(t.direction == "to_byte"
                                                 for t in loop.transfers)
    fwd = free("LD I0.0\nJC skip\nLD I0.1\nCU C1\nskip: NOP\n", "status")
    assert "= C1" in show(fwd.bit)


def test_rlo_already_on_the_byte_side_needs_no_path():
    """A compare's result is on the byte side: the counter takes F_B, nothing crosses."""
    p = free("L MW0\nL 3\n>I\nCU C1\n", "status")
    assert not p.transfers and all(not i.from_status for i in p.byte)
    assert show(p.bit) == ["END"]


def test_serial_mode_refuses_status(tmp_path, capsys):
    il = tmp_path / "p.il"
    il.write_text(PROGRAM)
    assert cli.main(["run", str(il), "--tc-path", "status", "--scans", "2"]) == 2
    assert "--tc-path status: parallel and free-running mode" in capsys.readouterr().err


def _run(tmp_path, sim, tc_path):
    il = tmp_path / "p.il"
    il.write_text(PROGRAM)
    st = tmp_path / "s.csv"
    st.write_text(STIM)
    trace = tmp_path / f"{sim}-{tc_path}.csv"
    assert cli.main(["run", str(il), "--mode", "free", "--exchange", "queue-free",
                     "--tc-path", tc_path, "--sim", sim, "--stimulus", str(st),
                     "--clock-mhz", "1", "--until-us", "3000", "--trace", str(trace),
                     "--watch", "MW0"]) == 0
    rows = [line.split(",") for line in trace.read_text().splitlines()[1:]]
    return [(float(r[1]), int(r[3]), int(r[4])) for r in rows], trace.read_text()


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
def test_timer_and_counter_through_the_status_buffer(tmp_path, sim, capsys):
    """Worked by hand (1 MHz: 1 clock = 1 us, 1 ms = 1000 clocks). The bit scan is 7
    clocks, a byte scan at most 60 (L 2, SD, L C1, T MW0, CU, END_B). Spec §2: the
    byte side sees the bit side's `= T 1` / `= C 1` at the latest in its following
    scan, so a change reaches the trace within (bit scan + 2 byte scans + bit scan)
    = 134 us of the input. Timer: I0.0 rises at 100 us (ms 0), SD starts in ms 0, the
    status is 1 from ms 2 (2000 us): Q0.0 rises in [2000, 2134]. Counter: MW0 steps to
    k within 134 us after the k-th rising edge of I0.1 (300, 500, 700), never before,
    and ends at 3 (no edge lost, none counted twice)."""
    rows, text = _run(tmp_path, sim, "status")
    out = capsys.readouterr().out
    assert "queue losses     overflows to-byte 0 to-bit 0" in out   # nothing crossed
    q_rise = next(t for t, q, _ in rows if q)
    assert 2000 <= q_rise <= 2134, q_rise
    assert all(q for t, q, _ in rows if t >= q_rise)
    for k, edge in enumerate(EDGES, 1):
        assert all(mw < k for t, _, mw in rows if t < edge), (k, edge)
        seen = next(t for t, _, mw in rows if mw >= k)
        assert seen <= edge + 134, (k, edge, seen)
    assert rows[-1][2] == 3
    if sim == "icarus":     # both simulators give the same trace
        (tmp_path / "v").mkdir()
        assert text == _run(tmp_path / "v", "verilator", "status")[1]


def test_channel_path_is_unchanged_on_the_hardware(tmp_path):
    """The default path still carries the enable through FBY (its queue overflows in
    free mode: the bit side writes every 7-clock scan, the byte side reads once per
    byte scan) and gives the same timer and count."""
    rows, _ = _run(tmp_path, "verilator", "channel")
    q_rise = next(t for t, q, _ in rows if q)
    assert 2000 <= q_rise <= 2134, q_rise
    assert rows[-1][2] == 3


def test_random_programs_take_the_status_path(tmp_path):
    """The random generators' programs (tests/test_random_parallel.py, timers and
    counters included) do give the status path something to take, in free-running
    mode (no wait) and in parallel mode (with the status-wait bit); their serial
    traces with it are checked there on the harness."""
    import random
    from randprog import long_timers, random_mixed_program, random_parallel_program
    from bitbyte.run.prepare import prepare_run
    took = {"parallel": 0, "free": 0}
    for index in range(16):
        seed = 7_000_000 + index
        maker = random_parallel_program if index % 2 else random_mixed_program
        il = tmp_path / f"p{seed}.il"
        il.write_text(long_timers(maker(seed), random.Random(seed)))
        for mode, extra in (("parallel", {}), ("free", {"exchange": "queue-free"})):
            job = prepare_run(str(il), mode=mode, scans=2, tc_path="status", **extra)[2]
            writes = any(w >> 24 == 0x18 and (w >> 12) & 0xF in (7, 8) for w in job.prog)
            waits = any(w >> 24 >= 0x80 and (w >> isa.FROM_STATUS_BIT) & 1 and
                        ((w >> isa.STATUS_WAIT_BIT) & 1) == (mode == "parallel")
                        for w in job.byte_prog if (w >> 12) & 0xF in (7, 8))
            took[mode] += writes and waits
    assert took["parallel"] > 4 and took["free"] > 4, took


def test_asm_tc_path(tmp_path, capsys):
    """asm: serial mode refuses status as run does; parallel mode writes the status
    path's images: `= T1` (0x18007001) and `= C1` (0x18008001) in the bit part, SD T1
    and CU C1 with the from-status and status-wait bits (0xB0067001, 0xB8068001) in
    the byte part, none of them with `channel`."""
    il = tmp_path / "p.il"
    il.write_text(PROGRAM)
    assert cli.main(["asm", str(il), "--tc-path", "status"]) == 2
    assert "--tc-path status: parallel and free-running mode" in capsys.readouterr().err
    images = {}
    for tp in ("channel", "status"):
        out = tmp_path / tp
        assert cli.main(["asm", str(il), "--mode", "parallel", "--tc-path", tp,
                         "-o", str(out)]) == 0
        images[tp] = [(out / f"p.{k}.hex").read_text().lower().split() for k in ("bit", "byte")]
    for word, part in (("18007001", 0), ("18008001", 0), ("b0067001", 1), ("b8068001", 1)):
        assert word in images["status"][part] and word not in images["channel"][part]
