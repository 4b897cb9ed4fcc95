"""The reference interpreter's byte instructions in serial mode, against values worked
out by hand from spec §3 (semantics), §5 (costs) and docs/isa.md "Serial mode timing".
Every expected value is written down, never computed by the code under test; the
derivation is in the comment next to it.

Timing reminders used throughout (default "paper" table): the first instruction of a
scan runs in its latch clock; a scan is 1 per bit instruction + 10 per word instruction
(L, T, arithmetic, compares, timers, counters) + 1 (END); a byte instruction starting
in clock c occupies c .. c+9 and the next instruction runs in c+10; a timer's
now = floor(c / (1000 * f_MHz)).
"""
from pathlib import Path

import pytest

from bitbyte.lang.config import Config
from bitbyte.lang.definition import DEF
from bitbyte.lang.parser import parse
from bitbyte.lang.costs import resolve_costs, serial_cost
from bitbyte.ref.refsim import RefSim, RefSimError, refsim_trace
from bitbyte.lang.stimulus import parse_stimulus
from bitbyte.lang.trace import trace_text


def program(src, config=Config()):
    return parse("t.il", src.strip() + "\n", config)


def stim(text, config=Config(), symbols=None):
    return parse_stimulus(text, "stim.csv", symbols, config)


def scan_stim(names, *columns):
    """A scan stimulus: one row per scan, columns[i][k] = value of names[i] in scan k."""
    rows = [f"scan,{','.join(names)}"]
    for k, values in enumerate(zip(*columns)):
        rows.append(f"{k}," + ",".join(str(v) for v in values))
    return stim("\n".join(rows) + "\n")


def run(src, stimulus=None, scans=1, watch=(), config=Config(), **kw):
    columns, records, fault = refsim_trace(program(src, config), config, stimulus,
                                           watch, scans=scans, **kw)
    assert not fault
    return records


def col(records, header):
    return [r.values[header] for r in records]


# --- spec §3 "Worked examples" ----------------------------------------------------------


def test_worked_example_subtract_and_compare():
    # 7 word instructions (70) + `= Q0.0` (1) + END = 72 cycles, t_us 0.72
    src = "L 10\nL 3\n-I\nT MW0\nL 5\nL 3\n>I\n= Q0.0"
    columns, recs, _ = refsim_trace(program(src), Config(), watch=["MW0"], scans=2)
    assert trace_text(columns, recs, 100) == (
        "scan,t_us,cycles,Q0.0,MW0\n"
        "0,0.72,72,1,7\n"
        "1,1.44,72,1,7\n")


def test_worked_example_int_wrap_division_modulo():
    src = ("L 16#FFFF\nT MW1\nL 32767\nL 1\n+I\nT MW2\n"
           "L -7\nL 2\n/I\nT MW3\nL -7\nL 2\nMOD\nT MW4")
    recs = run(src, watch=["MW1", "MW2", "MW3", "MW4"])
    assert col(recs, "MW1") == [-1]
    assert col(recs, "MW2") == [-32768]
    assert col(recs, "MW3") == [-3]
    assert col(recs, "MW4") == [-1]
    assert recs[0].cycles == 141              # 14 word instructions + END


def test_worked_example_on_delay_at_100_mhz():
    # LD, L T#2ms, SD T1, LD T1, = Q0.0: 1 + 10 + 10 + 1 + 1 + 1 (END) = 24 cycles, so
    # scan k latches in clock 24k (LD runs there) and SD starts in clock 24k + 11 (LD,
    # 10 of L).  100 MHz: 100 000 clocks per ms.  Scan 0: SD in clock 11, now = 0, the
    # timer starts.  Q0.0 = 1 in the first scan with 24k + 11 >= 200 000, i.e.
    # k >= 199 989 / 24 = 8332.875: scan 8333 (SD in clock 199 992 + 11 = 200 003,
    # now = 2); scan 8332: SD in clock 199 968 + 11 = 199 979, now = 1.
    src = "LD I0.0\nL T#2ms\nSD T1\nLD T1\n= Q0.0"
    sim = RefSim(program(src), Config(), stim("scan,I0.0\n0,1\n"))
    recs = sim.run(scans=8335)
    assert {r.cycles for r in recs} == {24}
    q = col(recs, "Q0.0")
    assert q[:8333] == [0] * 8333
    assert q[8333:] == [1, 1]
    assert recs[8333].end_clock == 24 * 8334 == 200016    # t_us 2000.16
    assert sim.timers[1].start == 0


def test_worked_example_counter():
    # LD, CU, L C1, T MW0: 1 + 30 + 1 (END) = 32 cycles; one count, in scan 0
    recs = run("LD I0.0\nCU C1\nL C1\nT MW0", stim("scan,I0.0\n0,1\n"), scans=4,
               watch=["MW0", "C1"])
    assert col(recs, "MW0") == [1, 1, 1, 1]
    assert col(recs, "C1") == [1, 1, 1, 1]
    assert {r.cycles for r in recs} == {32}


def test_worked_example_trace_header():
    # LD + 3 bit writes + L (10) + T (10) + END = 25 cycles
    src = """VAR
  Start AT I0.0;
END_VAR
LD Start
= Q1.0
S Q0.3
= PQ0.1
L 12
T QW2
"""
    p = parse("t.il", src)
    columns, recs, _ = refsim_trace(p, Config(), stim("scan,I0.0\n0,1\n"),
                                    ["MW0", "Start"], scans=1)
    assert trace_text(columns, recs, 100) == (
        "scan,t_us,cycles,Q0.1,Q0.3,Q1.0,QW2,MW0,Start\n"
        "0,0.25,25,1,1,1,12,0,1\n")


# --- spec §5: the Fig. 5 program ------------------------------------------------------

# the paper's Fig. 5 with the addresses of spec §5 (one copy of it, in examples/)
FIG5 = (Path(__file__).resolve().parents[1] / "examples" / "fig5.il").read_text()


def test_fig5_serial_cost_is_59():
    # 9 bit instructions + 5 word instructions (L, SD, L, L, A >=I) * 10 = 59
    assert serial_cost(parse("fig5.il", FIG5)) == 59


def test_fig5_runs_in_60_cycles_with_its_logic():
    # Time = MW1 = 0 (never written): preset 0, so SD's status follows its enable Flag
    # at once.  Out = Start_Up AND (IW0 >= MW0 = 0).
    #   scan 0: Start 0            -> Flag 0, Q0.0 0, Q0.1 0
    #   scan 1: Start 1, IW0 5     -> Flag 1 (rising: start, d 0 >= 0), Q0.0 1, Q0.1 1
    #   scan 2: Start 0, IW0 -3    -> Flag holds 1, Q0.0 1, Q0.1 0 (-3 < 0)
    #   scan 3: Stop 0             -> Flag 0, SD enable 0: status 0, Q0.0 0, Q0.1 0
    p = parse("fig5.il", FIG5)
    s = stim("scan,Start,Stop,BLK,SP_cur\n0,0,1,1,5\n1,1\n2,0,,,-3\n3,,0\n",
             symbols=p.symbols)
    columns, recs, _ = refsim_trace(p, Config(), s, ["T1", "M0.0"], scans=4)
    assert [r.cycles for r in recs] == [60, 60, 60, 60]    # 9 + 50 + 1 (END)
    assert [r.end_clock for r in recs] == [60, 120, 180, 240]
    assert col(recs, "Q0.0") == [0, 1, 1, 0]
    assert col(recs, "Q0.1") == [0, 1, 0, 0]
    assert col(recs, "T1") == [0, 1, 1, 0]
    assert col(recs, "M0.0") == [0, 1, 1, 0]


def test_fig13_byte_part_cost_is_52():
    # L Time, READ, SD, L, L, >=I, WRITE: 5 * 10 + 2 * 1
    src = "L MW1\nREAD FBY0\nSD T1\nL IW0\nL MW0\n>=I\nWRITE FBI0"
    assert serial_cost(program(src)) == 52


# --- arithmetic --------------------------------------------------------------------------


@pytest.mark.parametrize("src, expected", [
    ("L 300\nL 300\n*I", 24464),             # 90000 - 65536
    ("L -300\nL 300\n*I", -24464),           # -90000 + 131072 = 41072 -> -24464
    ("L 256\nL 256\n*I", 0),                 # 65536 wraps to 0
    ("L -32768\nL -1\n/I", -32768),          # 32768 wraps
    ("L -32768\nL -1\nMOD", 0),
    ("L 7\nL -2\n/I", -3),                   # toward zero
    ("L -7\nL -2\n/I", 3),
    ("L 7\nL -2\nMOD", 1),                   # sign of the dividend
    ("L -7\nL -2\nMOD", -1),
    ("L 32767\nL -1\n-I", -32768),
    ("L -32768\nL 1\n-I", 32767),
    ("L T#1m10s\nL 1\n+I", 4465),            # INT(70000) = 4464
    ("L 3\nL 4\nL 5\n-I", -1),               # L pushes ACCU1 into ACCU2: 4 - 5
    ("L 10\nL 3\n-I\n-I", 3),                # ACCU2 stays 10: 10 - 3 = 7, 10 - 7 = 3
    ("L 16#8000\nL 16#FFFF\n+I", 32767),     # -32768 + -1 wraps
])
def test_arithmetic(src, expected):
    sim = RefSim(program(src + "\nT MW0"), Config())
    sim.run(scans=1)
    assert sim.mw[0] == expected
    assert sim.arith_error is False


# DINT (docs/isa.md): S7's results, worked by hand (awlsim's insn_pl_d ... insn_mod)
@pytest.mark.parametrize("src, hi, lo", [
    ("L L#100000\nL L#-70000\n+D", 0, 30000),            # 0x00007530
    ("L L#2147483647\nL 1\n+D", -32768, 0),               # wraps to 0x80000000
    ("L 3\nL L#100000\n-D", -2, 31075),                  # -99997 = 0xFFFE7963
    ("L 1000\nL -3000\n*D", -46, 14656),                  # -3000000 = 0xFFD23940
    ("L L#65536\nL L#65536\n*D", 0, 0),                   # 2^32 wraps to 0
    ("L L#-2147483648\nL -1\n/D", -32768, 0),             # 2^31 wraps
    ("L L#-100001\nL 7\n/D", -1, -14285),                # toward zero
    ("L L#-100001\nL 7\nMODD", -1, -6),                  # sign of the dividend
    ("L L#100001\nL -7\nMODD", 0, 6),
    ("L 300\nL 300\n*I", 0, 24464),                      # the INT forms unchanged
])
def test_dint_arithmetic_through_a_double_word(src, hi, lo):
    sim = RefSim(program(src + "\nT MD0\nL MD0\nT MD4"), Config())
    sim.run(scans=1)
    assert (sim.mw[0], sim.mw[2]) == (hi, lo)
    assert (sim.mw[4], sim.mw[6]) == (hi, lo)          # L MD reads what T MD wrote
    assert sim.mw.get(1, 0) == 0 and sim.arith_error is False


@pytest.mark.parametrize("src, rlo", [
    ("L L#65536\nL 0\n==I", 1),            # INT(65536) = 0
    ("L L#65536\nL 0\n==D", 0),
    ("L L#65536\nL 0\n>D", 1),
    ("L L#-70000\nL L#-69999\n<D", 1),
    ("L L#65536\nL 1\n<I", 1),             # INT: 0 < 1
    ("L L#65536\nL 1\n<D", 0),
    ("SET\nL 1\nL 2\nA >=D", 0),
    ("CLR\nL 1\nL 2\nO <=D", 1),
])
def test_dint_compares(src, rlo):
    sim = RefSim(program(src + "\n= Q0.0"), Config())
    sim.run(scans=1)
    assert sim.pio & 1 == rlo


def test_division_by_zero_dint():
    sim = RefSim(program("L 1\nT MW0\nL L#65536\nL L#0\nMODD\nT MW0"), Config())
    sim.run(scans=1)
    assert sim.mw[0] == 0 and sim.arith_error is True
    sim = RefSim(program("L 5\nL L#65536\n/D\nT MW0"), Config())   # 65536 is not 0
    sim.run(scans=1)
    assert sim.mw[0] == 0 and sim.arith_error is False


@pytest.mark.parametrize("src", [
    "L 5\nL 0\n/I",
    "L -7\nL 0\nMOD",
    "L 9\nL T#1m5s536ms\nMOD",               # 65536: INT(ACCU1) = 0
])
def test_division_by_zero_gives_0_and_sets_the_flag(src):
    sim = RefSim(program("L 1\nT MW0\n" + src + "\nT MW0"), Config())
    assert sim.arith_error is False
    sim.run(scans=1)
    assert sim.mw[0] == 0 and sim.arith_error is True


def test_arithmetic_error_is_sticky():
    src = "L 12\nL IW0\n/I\nT MW0"
    sim = RefSim(program(src), Config(), stim("scan,IW0\n0,0\n1,4\n"))
    recs = sim.run(scans=2)
    assert [r.values for r in recs] == [{}, {}]
    assert sim.mw[0] == 3 and sim.arith_error is True      # scan 1: 12 / 4
    clean = RefSim(program(src), Config(), stim("scan,IW0\n0,4\n"))
    clean.run(scans=2)
    assert clean.arith_error is False


def test_accumulators_are_0_at_every_scan_start():
    # without the reset, scan 1 would store 9 in MW0 and 7 + 9 = 16 in MW1
    recs = run("T MW0\n+I\nT MW1\nL 7\nL 9", scans=3, watch=["MW0", "MW1"])
    assert col(recs, "MW0") == [0, 0, 0]
    assert col(recs, "MW1") == [0, 0, 0]


# --- compares and the RLO ---------------------------------------------------------------


@pytest.mark.parametrize("a, b, op, expected", [
    ("5", "3", ">I", 1), ("3", "5", ">I", 0), ("3", "3", ">=I", 1), ("2", "3", ">=I", 0),
    ("3", "3", "<I", 0), ("3", "5", "<I", 1), ("-1", "1", "<=I", 1), ("2", "1", "<=I", 0),
    ("4", "4", "==I", 1), ("4", "5", "==I", 0), ("4", "5", "<>I", 1), ("4", "4", "<>I", 0),
    ("T#1m10s", "4464", "==I", 1),           # compares INT(ACCU2) = 4464
    ("16#FFFF", "0", "<I", 1),               # -1 < 0
])
def test_compare_sets_the_rlo(a, b, op, expected):
    recs = run(f"SET\nL {a}\nL {b}\n{op}\n= Q0.0\nCLR\nL {a}\nL {b}\n{op}\n= Q0.1")
    assert col(recs, "Q0.0") == [expected]
    assert col(recs, "Q0.1") == [expected]


@pytest.mark.parametrize("first, a, b, op, expected", [
    ("CLR", 1, 1, "O ==I", 1), ("SET", 1, 2, "O ==I", 1), ("CLR", 1, 2, "O ==I", 0),
    ("SET", 2, 1, "A >I", 1), ("CLR", 2, 1, "A >I", 0), ("SET", 1, 2, "A >I", 0),
    ("SET", 1, 2, "A <>I", 1), ("SET", 3, 3, "A <=I", 1), ("CLR", 4, 3, "O <=I", 0),
    ("CLR", 4, 3, "O >=I", 1), ("SET", 4, 3, "A <I", 0), ("CLR", 3, 4, "O <I", 1),
])
def test_compare_and_combine(first, a, b, op, expected):
    recs = run(f"{first}\nL {a}\nL {b}\n{op}\n= Q0.0")
    assert col(recs, "Q0.0") == [expected]


def test_load_transfer_timers_counters_leave_the_rlo_alone():
    src = ("SET\nL 1\nT MW0\nL T#5s\nSD T2\nCU C3\nS C4\nR C5\n*I\n= Q0.0\n"
           "CLR\nL 1\nT MW0\nL T#5s\nSS T2\nCD C3\nS C4\nR C5\nR T2\n+I\n= Q0.1")
    recs = run(src)
    assert col(recs, "Q0.0") == [1]
    assert col(recs, "Q0.1") == [0]


# --- words: IW timing, QW, trace values ------------------------------------------------


@pytest.mark.parametrize("change_us, expected", [
    # L IW0 (10) + T MW0 (10) + END = 21 cycles: L IW0 runs in the latch clock, clocks
    # 0..9 of scan 0 and 21..30 of scan 1.  0.21 us = clock 21 (scan 1's first L
    # clock: seen), 0.22 us = clock 22 (its second clock: too late, scan 1 keeps 5)
    ("0.21", [5, -6]),
    ("0.22", [5, 5]),
])
def test_iw_is_read_in_the_first_clock_of_l(change_us, expected):
    recs = run("L IW0\nT MW0", stim(f"t_us,IW0\n0,5\n{change_us},-6\n"), scans=2,
               watch=["MW0", "IW0"])
    assert col(recs, "MW0") == expected
    assert col(recs, "IW0") == [5, -6]                # seen at END (clocks 20 and 41)
    assert [r.cycles for r in recs] == [21, 21]


def test_qw_column_sign_extension_and_read_back():
    # IW3 = 16#8000 = -32768 -> QW1; L QW1 < 0.  5 word instructions + `=` + END:
    # 52 cycles
    src = "L IW3\nT QW1\nL QW1\nL 0\n<I\n= Q0.0"
    columns, recs, _ = refsim_trace(program(src), Config(), stim("scan,IW3\n0,16#8000\n"),
                                    ["MW0", "QW1"], scans=1)
    assert trace_text(columns, recs, 100) == (
        "scan,t_us,cycles,Q0.0,QW1,MW0,QW1\n"
        "0,0.52,52,1,-32768,0,-32768\n")


def test_watched_exchange_channel_shows_0_in_serial_mode():
    assert col(run("NOP", watch=["FBI0", "FBY1"]), "FBI0") == [0]


@pytest.mark.parametrize("src", ["READ FBY0", "SET\nWRITE FBI2", "LD FBI1\n= Q0.0",
                                 "SET\n= FBY0"])
def test_exchange_is_parallel_mode_only(src):
    with pytest.raises(RefSimError, match=r"^t\.il:\d+:\d+: .*serial mode has no "
                                          r"exchange channels"):
        run(src)


# --- timers -------------------------------------------------------------------------------
#
# One template for the four kinds.  Clocks of scan k (latch in clock 60k):
#   LD I0.0 +0, L T#3ms +1..10, Sx T1 +11..20, LD T1 +21, = Q0.0 +22, L T1 +23..32,
#   T MW0 +33..42, LD I0.1 +43, R T1 +44..53, 5 NOP +54..58, END +59: 60 cycles.
# At 0.06 MHz a ms is 60 clocks, so Sx runs at now = floor((60k + 11) / 60) = k.
# Q0.0 = status right after Sx, MW0 = elapsed right after Sx, watched T1 = status at
# the end of the scan (after R T1, which I0.1 enables).

F06 = Config(clock_mhz=0.06)


def timer_prog(kind, preset="T#3ms"):
    return (f"LD I0.0\nL {preset}\n{kind} T1\nLD T1\n= Q0.0\nL T1\nT MW0\n"
            "LD I0.1\nR T1\nNOP\nNOP\nNOP\nNOP\nNOP")


def run_timer(kind, enable, reset, preset="T#3ms"):
    s = parse_stimulus("scan,I0.0,I0.1\n" + "".join(
        f"{k},{e},{r}\n" for k, (e, r) in enumerate(zip(enable, reset))), "s", None, F06)
    recs = run(timer_prog(kind, preset), s, scans=len(enable), watch=["MW0", "T1"],
               config=F06)
    assert {r.cycles for r in recs} == {60}
    assert [r.end_clock for r in recs] == [60 * (k + 1) for k in range(len(enable))]
    return col(recs, "Q0.0"), col(recs, "MW0"), col(recs, "T1")


def test_sd_on_delay():
    # 0-2: start at 0, d 0..2.  3: enable drops just at d = preset -> stopped, 0.
    # 4: rising, start 4; 7: d 3 -> 1; 8: 1, then R T1.  9: enable 0.  10: start,
    # 12: enable 0 before the preset.  14: start; 15: R T1; 16: rising again
    # (R cleared the edge memory), start 16; 19: d 3 -> 1.
    enable = [1, 1, 1, 0, 1, 1, 1, 1, 1, 0, 1, 1, 0, 0, 1, 1, 1, 1, 1, 1]
    reset = [0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0]
    q, elapsed, t1 = run_timer("SD", enable, reset)
    assert q == [0, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1]
    assert elapsed == [0, 1, 2, 0, 0, 1, 2, 3, 3, 0, 0, 1, 0, 0, 0, 1, 0, 1, 2, 3]
    assert t1 == [0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1]


def test_ss_retentive_on_delay():
    # 0: start 0.  1: enable 0, runs on (d 1).  2: rising while running -> restart 2.
    # 5: d 3 with enable 0 -> 1.  6: rising -> restart 6, status stays 1, elapsed 0.
    # 7: R T1.  8: rising (edge cleared) -> start 8; 11: d 3 -> 1; 13: R T1.
    # 14: stopped, enable 0 -> 0.
    enable = [1, 0, 1, 1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 0, 0]
    reset = [0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0]
    q, elapsed, t1 = run_timer("SS", enable, reset)
    assert q == [0, 0, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1, 0]
    assert elapsed == [0, 1, 0, 1, 2, 3, 0, 1, 0, 1, 2, 3, 3, 3, 0]
    assert t1 == [0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0]


def test_sp_pulse_without_retrigger():
    # 0: start 0, 1.  1: enable 0 but d < 3: runs on.  2: rising with d 2 < 3: no
    # retrigger.  3: d 3 -> 0, still running (enable 1).  5: enable 0, d 5 -> stop.
    # 6: start 6.  7, 8: enable 0, d < 3.  9: rising with d 3 >= 3 -> restart 9.
    # 11: R T1.  12: rising -> start 12; 15: d 3 -> 0; 16: enable 0 -> stop.
    enable = [1, 0, 1, 1, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 1, 1, 0, 0]
    reset = [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0]
    q, elapsed, t1 = run_timer("SP", enable, reset)
    assert q == [1, 1, 1, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 0]
    assert elapsed == [0, 1, 2, 3, 3, 0, 0, 1, 2, 0, 1, 2, 0, 1, 2, 3, 0, 0]
    assert t1 == [1, 1, 1, 0, 0, 0, 1, 1, 1, 1, 1, 0, 1, 1, 1, 0, 0, 0]


def test_sf_off_delay():
    # 0: enable 0, no falling edge (edge memory 0 after reset) -> 0.  1: enable 1 -> 1.
    # 3: falling -> start 3.  5: enable 1 -> stop, 1.  6: falling -> start 6; 9: d 3
    # -> 0, elapsed stays 3 while running.  11: enable 1.  12: falling, then R T1.
    # 13: enable 0 but no falling edge (R cleared it) -> stays 0.  14: 1.  15: falling.
    enable = [0, 1, 1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0]
    reset = [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0]
    q, elapsed, t1 = run_timer("SF", enable, reset)
    assert q == [0, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 1, 1, 0, 1, 1]
    assert elapsed == [0, 0, 0, 0, 1, 0, 0, 1, 2, 3, 3, 0, 0, 0, 0, 0]
    assert t1 == [0, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 1, 0, 0, 1, 1]


@pytest.mark.parametrize("preset", ["0", "-5"])          # negative counts as 0
@pytest.mark.parametrize("kind, expected", [
    ("SD", [1, 1, 0, 0]),        # d 0 >= 0 at the start
    ("SS", [1, 1, 1, 1]),        # done at once, until R T n
    ("SP", [0, 0, 0, 0]),        # a pulse of length 0
    ("SF", [1, 1, 0, 0]),        # falling start in scan 2 ends at once
])
def test_preset_0(kind, expected, preset):
    q, elapsed, t1 = run_timer(kind, [1, 1, 0, 0], [0, 0, 0, 0], preset)
    assert q == expected
    assert t1 == expected
    assert elapsed == [0, 0, 0, 0]


def test_preset_is_the_full_32_bit_accu():
    # T#1m5s539ms = 65539 ms; INT of it would be 3 (status 1 in scan 3)
    q, elapsed, t1 = run_timer("SD", [1] * 6, [0] * 6, "T#1m5s539ms")
    assert q == [0] * 6
    assert elapsed == [0, 1, 2, 3, 4, 5]


@pytest.mark.parametrize("nops, expected", [
    # SET, L T#3ms, SD T1, LD T1, = Q0.0, NOPs at 0.01 MHz (10 clocks per ms):
    # 24 + nops cycles (SET in the latch clock); SD starts in clock 11 of each scan.
    # Scan 0: SD in clock 11, now 1, start 1.
    (5, [0, 1, 1]),    # 29-cycle scans: scan 1's SD in clock 40, now 4, d 3;
                       #     scan 2 in clock 69, now 6
    (4, [0, 0, 1]),    # 28: clock 39, now 3, d 2 (its last clock, 48, would be 4 ms);
                       #     scan 2 in clock 67, now 6
])
def test_now_is_taken_in_the_first_clock_of_the_timer_instruction(nops, expected):
    cfg = Config(clock_mhz=0.01)
    recs = run("SET\nL T#3ms\nSD T1\nLD T1\n= Q0.0" + "\nNOP" * nops, scans=3, config=cfg)
    assert col(recs, "Q0.0") == expected
    assert {r.cycles for r in recs} == {24 + nops}


def test_status_and_elapsed_change_only_when_the_timer_executes():
    # At 0.01 MHz.  I0.1 = 1 jumps over SD (scans 1-3).
    #   SD scan: LD, JC (not taken), LD, L 10, SD 10, LD, =, L 10, T 10, END = 46,
    #            LD in the latch clock, SD in clock latch + 13
    #   skip:    LD, JC (taken, J = 3), LD, =, L 10, T 10, END = 24 + J = 27
    # scan 0: latch 0, SD in clock 13: now 1, start.  Scans 1-3 (latches 46, 73, 100)
    # pass 2 ms but show status 0 and elapsed 0.  Scan 4: latch 127, SD in clock 140:
    # now 14, d 13 -> 1, elapsed min(13, 2) = 2.
    src = "LD I0.1\nJC skip\nLD I0.0\nL T#2ms\nSD T1\nskip: LD T1\n= Q0.0\nL T1\nT MW0"
    cfg = Config(clock_mhz=0.01)
    s = stim("scan,I0.0,I0.1\n0,1,0\n1,1,1\n4,1,0\n")
    recs = run(src, s, scans=5, watch=["MW0", "T1"], config=cfg)
    skip = 24 + DEF.jump_taken_clocks
    assert [r.cycles for r in recs] == [46, skip, skip, skip, 46]
    assert col(recs, "Q0.0") == [0, 0, 0, 0, 1]
    assert col(recs, "T1") == [0, 0, 0, 0, 1]
    assert col(recs, "MW0") == [0, 0, 0, 0, 2]


def test_last_timer_and_counter():
    recs = run("SET\nL 0\nSD T63\nCU C63\nLD T63\nA C63\n= Q0.0", watch=["T63", "C63"])
    assert col(recs, "Q0.0") == [1]
    assert col(recs, "T63") == [1] and col(recs, "C63") == [1]


# --- counters -------------------------------------------------------------------------


def test_counter_edges_saturation_set_and_reset():
    # a = I0.0 (CU), b = I0.1 (CD), s = I0.2 (S C1 with 32766), r = I0.3 (R C1)
    #  0: CU edge -> 1          1: CD edge -> 0          2: b held -> 0
    #  3: -> 0                  4: CD edge at 0 -> 0      5: CU edge -> 1
    #  6: S edge -> 32766       7: CU -> 32767           8: 32767
    #  9: CU at 32767 -> 32767 10: R -> 0 (s held)       11: s held, no S edge -> 0
    # 12: 0                    13: S edge -> 32766       14: CU -> 32767, then R -> 0
    # 15: a held, no CU edge -> 0                        16: CD edge at 0 -> 0
    a = [1, 1, 0, 0, 0, 1, 0, 1, 0, 1, 0, 0, 0, 0, 1, 1, 0]
    b = [0, 1, 1, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1]
    s = [0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 0, 1, 0, 0, 0]
    r = [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0]
    src = ("LD I0.0\nCU C1\nLD I0.1\nCD C1\nLD I0.2\nL 32766\nS C1\nLD I0.3\nR C1\n"
           "L C1\nT MW0\nLD C1\n= Q0.0")
    recs = run(src, scan_stim(["I0.0", "I0.1", "I0.2", "I0.3"], a, b, s, r),
               scans=17, watch=["MW0", "C1"])
    assert col(recs, "MW0") == [1, 0, 0, 0, 0, 1, 32766, 32767, 32767, 32767, 0, 0, 0,
                                32766, 0, 0, 0]
    assert col(recs, "C1") == [1, 0, 0, 0, 0, 1, 1, 1, 1, 1, 0, 0, 0, 1, 0, 0, 0]
    assert col(recs, "Q0.0") == col(recs, "C1")
    # 5 LD + `=` (6) + CU CD L S R L T (70) + END
    assert {r.cycles for r in recs} == {77}


@pytest.mark.parametrize("value, expected", [
    ("100", 100), ("32767", 32767), ("-5", 0), ("16#8000", 0),
    ("T#1m10s", 4464),           # 70000: INT = 4464
    ("T#40s", 0),                # 40000: INT = -25536
    ("T#1m5s535ms", 0),          # 65535: INT = -1
])
def test_set_counter_loads_clamped_int_of_accu1(value, expected):
    sim = RefSim(program(f"SET\nL {value}\nS C2\nL C2\nT MW0"), Config())
    sim.run(scans=1)
    assert sim.mw[0] == expected
    assert sim.counter_status(2) == int(expected > 0)


def test_two_cu_on_one_counter_share_its_edge_memory():
    recs = run("SET\nCU C1\nCU C1\nL C1\nT MW0", scans=2, watch=["MW0"])
    assert col(recs, "MW0") == [1, 1]


# --- the cost table -----------------------------------------------------------------------


def test_default_cost_table():
    table = resolve_costs()
    assert table["L"] == table["A >=I"] == table["S C"] == table["R T"] == 10
    assert table["READ"] == table["WRITE"] == 1


def test_cost_by_class():
    # worked example 1 with 3 clocks per word instruction: 7 * 3 + 1 (`=`) + 1 (END)
    recs = run("L 10\nL 3\n-I\nT MW0\nL 5\nL 3\n>I\n= Q0.0", costs={"word": 3})
    assert recs[0].cycles == 23


def test_cost_by_mnemonic_wins_over_class():
    # L 2 + L 2 + *I 40 + T 10 (paper) + END = 55
    recs = run("L 3\nL 4\n*I\nT MW0", costs={"*I": 40, "L": 2}, watch=["MW0"])
    assert recs[0].cycles == 55 and col(recs, "MW0") == [12]
    assert serial_cost(parse("fig5.il", FIG5), {"word": 20}) == 9 + 5 * 20


def test_cost_by_firmware_class():
    # muldiv 25 covers *I, /I, MOD; "word" 4 the other word classes, "binary" stays 1
    table = resolve_costs({"muldiv": 25, "word": 4, "compare": 7})
    assert table["*I"] == table["/I"] == table["MOD"] == 25
    assert table["+I"] == table["L"] == table["SD"] == table["S C"] == 4
    assert table[">=I"] == table["O <>I"] == 7
    assert table["READ"] == 1
    # L 4 + L 4 + /I 25 + T 4 + END = 38
    assert run("L 9\nL 2\n/I\nT MW0", costs={"muldiv": 25, "word": 4})[0].cycles == 38


def test_named_cost_tables():
    fig5 = parse("fig5.il", FIG5)
    assert serial_cost(fig5, "paper") == 59
    assert serial_cost(fig5, "c320") == 9 + 5 * 57
    assert resolve_costs("c320")["WRITE"] == 6


@pytest.mark.parametrize("costs", [{"ADD": 3}, {"word": 0}, {"L": 2.5}, {"binary": True},
                                   "fast"])
def test_bad_cost_table(costs):
    with pytest.raises(ValueError, match="cost table"):
        RefSim(program("NOP"), Config(), costs=costs)


def test_watchdog_counts_byte_clocks():
    # L 1, L 2: 10 + 10 + 1 (END) = 21 cycles
    p = program("L 1\nL 2")
    assert refsim_trace(p, Config(), scans=2, watchdog=21)[2] is False
    _, recs, fault = refsim_trace(p, Config(), scans=2, watchdog=20)
    assert fault and recs == []
