"""STIM.csv reading and TRACE.csv writing (spec §4), against hand-written expectations."""
from fractions import Fraction

import pytest

from bitbyte.lang.config import Config
from bitbyte.lang.errors import SourceError
from bitbyte.lang.program import Instr, Operand, Program
from bitbyte.lang.stimulus import load_stimulus, no_stimulus, parse_stimulus
from bitbyte.lang.trace import (Column, ScanRecord, format_t_us, format_value, header_line,
                           parse_address, trace_columns, write_trace)

SYMBOLS = {
    "START": Operand("bit", "I", byte=0, bit=0, text="Start"),
    "STOP": Operand("bit", "I", byte=1, bit=2, text="Stop"),
    "SPEED": Operand("index", "IW", index=3, text="Speed"),
    "LAMP": Operand("bit", "Q", byte=0, bit=0, text="Lamp"),
}


def parse(text, config=Config()):
    return parse_stimulus(text, "stim.csv", SYMBOLS, config)


# --- stimulus: scan rows ------------------------------------------------------------


def test_scan_rows_hold_until_changed():
    s = parse("scan,I0.0,I 0.1,IW 2\n1,1,0,7\n3,,1,\n3,0,,-1\n6,1,1,16#FFFE\n")
    assert s.kind == "scan"
    # bit i = byte*8 + bit: I0.0 -> 1, I0.1 -> 2
    assert [s.pins_for_scan(k) for k in range(8)] == [0, 1, 1, 2, 2, 2, 3, 3]
    assert s.words_for_scan(0) == {}
    assert s.words_for_scan(2) == {2: 7}
    assert s.words_for_scan(5) == {2: -1}
    assert s.words_for_scan(9) == {2: -2}
    assert s.events_for_harness() == [("scan", 1, 1), ("scan", 3, 2), ("scan", 6, 3)]


def test_symbols_any_case_and_quoted():
    s = parse('SCAN,start,"STOP",Speed,pi1.3\n0,1,1,-300,1\n')
    # I0.0 -> bit 0; I1.2 -> bit 10; PI1.3 names the pin I1.3 -> bit 11
    assert s.pins_for_scan(0) == (1 << 0) | (1 << 10) | (1 << 11)
    assert s.words_for_scan(0) == {3: -300}


def test_no_stimulus_is_all_zero():
    s = no_stimulus(Config())
    assert s.kind == "none"
    assert s.pins_for_scan(5) == 0 and s.pins_at_clock(5) == 0
    assert s.events_for_harness() == []


def test_blank_lines_comments_and_crlf(tmp_path):
    p = tmp_path / "s.csv"
    p.write_bytes(b"# my stimulus\r\nscan,I0.0\r\n\r\n0,1\r\n# later\r\n2,0\r\n")
    s = load_stimulus(str(p), SYMBOLS, Config())
    assert [s.pins_for_scan(k) for k in range(3)] == [1, 1, 0]


# --- stimulus: time rows ------------------------------------------------------------


def test_t_us_rows_apply_from_ceil_of_t_times_f():
    # 100 MHz: 0.07 us is exactly clock 7 (as a float 0.07*100 = 7.000000000000001)
    s = parse("t_us,I0.0\n0.07,1\n0.071,0\n0.09,1\n")
    assert s.kind == "t_us"
    assert [s.pins_at_clock(c) for c in range(6, 10)] == [0, 1, 0, 1]
    assert s.events_for_harness() == [("clock", 7, 1), ("clock", 8, 0), ("clock", 9, 1)]


def test_t_us_rows_on_one_clock_collapse_to_the_last():
    s = parse("t_us,I0.0,I0.1\n0.031,1,1\n0.039,0,\n0.5,,0\n")
    assert s.events_for_harness() == [("clock", 4, 2), ("clock", 50, 0)]
    assert s.edges_between(0, 10) == (2, 0)    # I0.0 never rose at a clock edge


def test_t_us_at_another_clock():
    s = parse("t_us,I0.0\n1,1\n1.5,0\n", Config(clock_mhz=3))
    assert s.events_for_harness() == [("clock", 3, 1), ("clock", 5, 0)]  # 3, ceil(4.5)
    assert s.events_for_harness(clock_mhz=2) == [("clock", 2, 1), ("clock", 3, 0)]
    assert s.pins_at_clock(4) == 1 and s.pins_at_clock(4, 2) == 0


def test_edges_between_latches():
    s = parse("t_us,I0.0,I0.1\n0,1,0\n0.03,0,1\n0.05,1,\n")
    assert s.edges_between(-1, 0) == (1, 0)       # first latch: pins counted 0 before
    assert s.edges_between(0, 4) == (2, 1)        # I0.0 fell, I0.1 rose at clock 3
    assert s.edges_between(0, 5) == (3, 1)        # ... and I0.0 rose again at 5
    assert s.edges_between(5, 9) == (0, 0)
    assert s.words_at_clock(0) == {}


def test_t_us_words():
    s = parse("t_us,Speed\n0.01,5\n0.02,-32768\n")
    assert [s.words_at_clock(c).get(3, 0) for c in range(4)] == [0, 5, -32768, -32768]


# --- stimulus: errors ---------------------------------------------------------------


@pytest.mark.parametrize("text, line, col, words", [
    ("time,I0.0\n0,1\n", 1, 1, "first column"),
    ("scan, I0.0,Foo\n", 1, 12, "unknown operand 'Foo'"),
    ("scan,Lamp\n", 1, 6, "not an input"),
    ("scan,IR0.0\n", 1, 6, "not an input"),
    ("scan,I16.0\n", 1, 6, "out of range"),
    ("scan,I0.8\n", 1, 6, "out of range"),
    ("scan,IW16\n", 1, 6, "out of range"),
    ("scan,I0.0,Start\n", 1, 11, "named twice"),
    ("scan,I0.0\n0,1\nx,0\n", 3, 1, "not a scan number"),
    ("scan,I0.0\n-1,1\n", 2, 1, "not a scan number"),
    ("t_us,I0.0\n0.5,1\n1/3,1\n", 3, 1, "not a time"),
    ("t_us,I0.0\n-0.5,1\n", 2, 1, "not a time"),
    ("scan,I0.0\n0,1\n2,0\n1,1\n", 4, 1, "non-decreasing"),
    ("t_us,I0.0\n0.5,1\n0.25,1\n", 3, 1, "non-decreasing"),
    ("scan,I0.0\n0,2\n", 2, 3, "0 or 1"),
    ("scan,I0.0, Speed\n0,1,  abc\n", 2, 7, "a word"),
    ("scan,IW0\n0,32768\n", 2, 3, "a word"),
    ("scan,IW0\n0,16#10000\n", 2, 3, "a word"),
    ("scan,I0.0\n0,1,1\n", 2, 5, "more values"),
    ("\n\n", 1, 1, "empty stimulus"),
])
def test_stimulus_errors(text, line, col, words):
    with pytest.raises(SourceError) as info:
        parse(text)
    e = info.value
    assert (e.line, e.col) == (line, col)
    assert words in str(e)
    assert str(e).startswith(f"stim.csv:{line}:{col}: ")


def test_stimulus_error_from_file_names_the_file(tmp_path):
    p = tmp_path / "bad.csv"
    p.write_text("scan,I0.0\n0,7\n")
    with pytest.raises(SourceError, match=r"bad\.csv:2:3: "):
        load_stimulus(str(p), None, Config())


def test_lookup_of_the_wrong_kind_is_refused():
    with pytest.raises(ValueError):
        parse("scan,I0.0\n0,1\n").pins_at_clock(0)


# --- addresses ----------------------------------------------------------------------


@pytest.mark.parametrize("text, address", [
    ("I0.0", "I0.0"), ("I 0.0", "I0.0"), ("pi1.2", "PI1.2"), ("IR 3.7", "IR3.7"),
    ("PQ0.1", "PQ0.1"), ("m255.7", "M255.7"), ("MW0", "MW0"), ("T 2", "T2"),
    ("c1", "C1"), ("FBI1", "FBI1"), ("IW 15", "IW15"),
])
def test_parse_address(text, address):
    assert parse_address(text).address() == address


@pytest.mark.parametrize("text", ["Q0", "MW0.1", "Start", "I0.", "X1.0", ""])
def test_parse_address_rejects(text):
    assert parse_address(text) is None


# --- trace columns --------------------------------------------------------------------


def _instr(mnemonic, operand):
    return Instr(mnemonic, operand, 1, 1)


def _bit(area, byte, bit):
    return Operand("bit", area, byte=byte, bit=bit, text=f"{area}{byte}.{bit}")


def _word(area, n):
    return Operand("index", area, index=n, text=f"{area}{n}")


def test_trace_header_example_of_spec():
    prog = Program("p.il", [
        _instr("=", _bit("Q", 1, 0)),
        _instr("S", _bit("Q", 0, 3)),
        _instr("=", _bit("PQ", 0, 1)),
        _instr("L", Operand("const", "INT", value=1)),
        _instr("T", _word("QW", 2)),
        _instr("END", None),
    ], symbols={"START": SYMBOLS["START"]})
    cols = trace_columns(prog, ["MW0", "Start"])
    assert header_line(cols) == "scan,t_us,cycles,Q0.1,Q0.3,Q1.0,QW2,MW0,Start"


def test_trace_columns_order_and_dedup():
    prog = Program("p.il", [
        _instr("R", _bit("Q", 0, 3)), _instr("S", _bit("Q", 0, 3)),
        _instr("FN", _bit("PQ", 2, 0)), _instr("FP", _bit("Q", 0, 7)),
        _instr("=", _bit("Q", 1, 0)), _instr("=", _bit("PQ", 1, 0)),
        _instr("=", _bit("M", 0, 0)), _instr("LD", _bit("Q", 5, 5)),
        _instr("T", _word("QW", 5)), _instr("T", _word("QW", 2)),
        _instr("T", _word("QW", 5)), _instr("T", _word("MW", 3)),
        _instr("END", None),
    ])
    cols = trace_columns(prog, [" m0.0", "I 0.0", "c1", '"Start"'], SYMBOLS)
    assert [c.header for c in cols] == [
        "Q0.3", "Q0.7", "Q1.0", "Q2.0", "QW2", "QW5", "m0.0", "I 0.0", "c1", '"Start"']
    assert cols[6].operand.address() == "M0.0"
    assert cols[9].operand.address() == "I0.0"


def test_bad_watch_is_refused():
    prog = Program("p.il", [_instr("END", None)])
    with pytest.raises(ValueError, match="Nope"):
        trace_columns(prog, ["Nope"], SYMBOLS)
    with pytest.raises(ValueError, match="out of range"):
        trace_columns(prog, ["MW256"], SYMBOLS, Config())
    assert [c.header for c in trace_columns(prog, ["MW255"], SYMBOLS, Config())] == ["MW255"]


# --- values ---------------------------------------------------------------------------

BIT_COL = Column("Q0.0", _bit("Q", 0, 0))
WORD_COL = Column("MW0", _word("MW", 0))


@pytest.mark.parametrize("col, value, text", [
    (BIT_COL, 0, "0"), (BIT_COL, 1, "1"), (BIT_COL, True, "1"),
    (WORD_COL, 0, "0"), (WORD_COL, -1, "-1"), (WORD_COL, 0xFFFF, "-1"),
    (WORD_COL, 0x8000, "-32768"), (WORD_COL, 32767, "32767"), (WORD_COL, -32768, "-32768"),
])
def test_format_value(col, value, text):
    assert format_value(col, value) == text


@pytest.mark.parametrize("end_clock, f, text", [
    (62, 100, "0.62"), (124, 100, "1.24"), (1250, 100, "12.5"), (100, 100, "1"),
    (0, 100, "0"), (7, 100.0, "0.07"), (1, 100, "0.01"), (5, 12.5, "0.4"),
    (1, 3, "0.333333"), (2, 3, "0.666667"), (3, 3, "1"), (1, 16, "0.0625"),
    (123456789, 100, "1234567.89"), (1, Fraction(1, 3), "3"),
])
def test_format_t_us(end_clock, f, text):
    assert format_t_us(end_clock, f) == text


def test_write_trace(tmp_path):
    cols = [BIT_COL, WORD_COL]
    rows = [ScanRecord(0, 62, 62, {"Q0.0": 1, "MW0": -7}),
            ScanRecord(1, 124, 62, {"Q0.0": 0, "MW0": 0xFFFF})]
    path = tmp_path / "TRACE.csv"
    write_trace(str(path), cols, rows, 100)
    assert path.read_bytes() == (
        b"scan,t_us,cycles,Q0.0,MW0\n0,0.62,62,1,-7\n1,1.24,62,0,-1\n")


def test_edges_between_agree_with_a_clock_by_clock_walk():
    """Randomised: rises/falls from the step function equal those found by comparing
    the pins of every pair of consecutive clocks."""
    import math
    import random
    rng = random.Random(7)
    for _ in range(50):
        times = sorted(Fraction(rng.randrange(0, 400), 100) for _ in range(rng.randrange(1, 12)))
        rows = [(t, rng.randrange(4)) for t in times]
        text = "t_us,I0.0,I0.1\n" + "".join(
            f"{float(t):.2f},{v & 1},{v >> 1}\n" for t, v in rows)
        s = parse(text)
        per_clock = []
        for c in range(420):
            applied = [v for t, v in rows if math.ceil(t * 100) <= c]
            per_clock.append(applied[-1] if applied else 0)
        latches = sorted(rng.sample(range(420), 6))
        prev = -1
        for latch in latches:
            rises = falls = 0
            before = per_clock[prev] if prev >= 0 else 0
            for c in range(prev + 1, latch + 1):
                rises |= per_clock[c] & ~before
                falls |= before & ~per_clock[c]
                before = per_clock[c]
            assert s.edges_between(prev, latch) == (rises, falls)
            assert s.pins_at_clock(latch) == per_clock[latch]
            prev = latch
