"""The reference interpreter against results worked out by hand from spec §3 and the
timing model of docs/isa.md.  Every expected value below is written down, never
computed by the code under test.

Programs are built with a tiny test-only assembler (`prog`) so these tests do not
depend on bitbyte.lang.parser.
"""
import re

import pytest

from bitbyte.lang.config import Config
from bitbyte.lang.definition import DEF
from bitbyte.lang.program import Instr, Operand, Program
from bitbyte.ref.refsim import RefSim, RefSimError, refsim_trace
from bitbyte.lang.stimulus import parse_stimulus
from bitbyte.lang.parser import parse
from bitbyte.lang.trace import trace_columns, trace_text
from test_cpu_directed import CASES as DIRECTED

# --- helpers --------------------------------------------------------------------------

_BIT = re.compile(r"^(PI|IR|IF|PQ|I|Q|M)\s*(\d+)\.(\d)$", re.I)
_IDX = re.compile(r"^(FBI|FBY|IW|QW|MW|T|C)\s*(\d+)$", re.I)
_JUMPS = ("JU", "JC", "JCN")


def _operand(mnemonic, text):
    if text is None:
        return None
    if mnemonic in _JUMPS:
        return Operand("label", label=text.upper(), text=text)
    m = _BIT.match(text)
    if m:
        return Operand("bit", m[1].upper(), byte=int(m[2]), bit=int(m[3]), text=text)
    m = _IDX.match(text)
    assert m, f"test helper cannot read operand {text!r}"
    return Operand("index", m[1].upper(), index=int(m[2]), text=text)


def prog(src, symbols=None):
    """One instruction per line, optional `label:` in front; END appended if missing."""
    instrs, labels = [], {}
    for n, line in enumerate(src.strip().splitlines(), start=1):
        line = line.split("//")[0].strip()
        m = re.match(r"^(\w+):\s*(.*)$", line)
        if m:
            labels[m[1].upper()] = len(instrs)
            line = m[2].strip()
        if not line:
            continue
        parts = line.split(None, 1)
        mn = parts[0].upper()
        arg = parts[1].strip() if len(parts) > 1 else None
        if mn == "REFRESH" and arg:                   # REFRESH I / REFRESH Q
            mn, arg = ("REFRESH Q" if arg.upper() == "Q" else "REFRESH"), None
        instrs.append(Instr(mn, _operand(mn, arg), n, 1, line))
    if not instrs or instrs[-1].mnemonic != "END":
        instrs.append(Instr("END", None, 0, 0))
    return Program("test.il", instrs, labels, symbols or {})


def stim(text, config=Config()):
    return parse_stimulus(text, "stim.csv", None, config)


def column(records, header):
    return [r.values[header] for r in records]


def run(src, stimulus=None, scans=4, watch=(), **kw):
    columns, records, fault = refsim_trace(prog(src), Config(), stimulus, watch,
                                           scans=scans, **kw)
    assert not fault
    return records


# Scan k of this stimulus has (I0.0, I0.1) = (0,0), (0,1), (1,0), (1,1).
TWO_INPUTS = "scan,I0.0,I0.1\n0,0,0\n1,0,1\n2,1,0\n3,1,1\n"


# --- loads and combines -------------------------------------------------------------


@pytest.mark.parametrize("mnemonic, expected", [
    # a = I0.0 (loaded first), b = I0.1; scans (a,b) = 00, 01, 10, 11
    ("LD", [0, 1, 0, 1]),     # b
    ("LDN", [1, 0, 1, 0]),    # not b
    ("A", [0, 0, 0, 1]),      # a and b
    ("AN", [0, 0, 1, 0]),     # a and not b
    ("O", [0, 1, 1, 1]),      # a or b
    ("ON", [1, 0, 1, 1]),     # a or not b
    ("X", [0, 1, 1, 0]),      # a xor b
    ("XN", [1, 0, 0, 1]),     # a xor not b
])
def test_load_and_combine(mnemonic, expected):
    recs = run(f"LD I0.0\n{mnemonic} I0.1\n= Q0.0", stim(TWO_INPUTS))
    assert column(recs, "Q0.0") == expected


def test_not_set_clr():
    recs = run("LD I0.0\nNOT\n= Q0.0\nSET\n= Q0.1\nCLR\n= Q0.2",
               stim("scan,I0.0\n0,0\n1,1\n"), scans=2)
    assert column(recs, "Q0.0") == [1, 0]
    assert column(recs, "Q0.1") == [1, 1]
    assert column(recs, "Q0.2") == [0, 0]


def test_combines_strictly_in_sequence():
    # a=1, b=0, c=0: (a or b) and c = 0; AND-before-OR would give 1
    recs = run("LD I0.0\nO I0.1\nA I0.2\n= Q0.0", stim("scan,I0.0\n0,1\n"), scans=1)
    assert column(recs, "Q0.0") == [0]


def test_rlo_is_0_at_every_scan_start():
    recs = run("= Q0.0\nSET\n= Q0.1", scans=3)
    assert column(recs, "Q0.0") == [0, 0, 0]
    assert column(recs, "Q0.1") == [1, 1, 1]


def test_assign_set_reset_and_markers():
    src = "LD I0.0\nS Q0.0\nLD I0.1\nR Q0.0\nLD I0.0\n= M0.0\nLD M0.0\n= Q0.1"
    # (I0.0, I0.1) per scan: 00, 10, 00, 01, 11, 00
    s = stim("scan,I0.0,I0.1\n0,0,0\n1,1,0\n2,0,0\n3,0,1\n4,1,1\n5,0,0\n")
    recs = run(src, s, scans=6, watch=["M0.0"])
    assert column(recs, "Q0.0") == [0, 1, 1, 0, 0, 0]   # S holds, R wins when last
    assert column(recs, "Q0.1") == [0, 1, 0, 0, 1, 0]
    assert column(recs, "M0.0") == [0, 1, 0, 0, 1, 0]


def test_set_reset_do_nothing_when_rlo_is_0():
    recs = run("SET\n= Q0.0\n= Q0.1\nCLR\nR Q0.0\nS Q0.2", scans=1)
    assert column(recs, "Q0.0") == [1]
    assert column(recs, "Q0.1") == [1]
    assert column(recs, "Q0.2") == [0]


# --- edges ----------------------------------------------------------------------------

FP_FN_STIM = "scan,I0.0\n0,1\n3,0\n"   # I0.0 = 1 in scans 0-2, 0 from scan 3


def test_fp_fn_worked_example_of_spec():
    src = "LD I0.0\nFP M0.0\n= Q0.0\nLD I0.0\nFN M0.1\n= Q0.1"
    recs = run(src, stim(FP_FN_STIM), scans=5, watch=["M0.0", "M0.1"])
    assert column(recs, "Q0.0") == [1, 0, 0, 0, 0]
    assert column(recs, "Q0.1") == [0, 0, 0, 1, 0]
    assert column(recs, "M0.0") == [1, 1, 1, 0, 0]   # m := old RLO
    assert column(recs, "M0.1") == [1, 1, 1, 0, 0]


def test_fp_fn_with_q_memory():
    src = "LD I0.0\nFP Q1.0\n= Q0.0\nLD I0.0\nFN Q1.1\n= Q0.1"
    recs = run(src, stim(FP_FN_STIM), scans=5)
    assert column(recs, "Q0.0") == [1, 0, 0, 0, 0]
    assert column(recs, "Q0.1") == [0, 0, 0, 1, 0]
    assert column(recs, "Q1.0") == [1, 1, 1, 0, 0]
    assert column(recs, "Q1.1") == [1, 1, 1, 0, 0]


# --- parentheses ----------------------------------------------------------------------

NEST7 = """
SET
A(
LD I0.0
O(
LD I0.1
A(
LDN I0.2
X(
LD I0.3
AN(
LD I0.4
ON(
LD I0.5
XN(
LD I0.6
)
)
)
)
)
)
)
= Q0.0
"""


def nest7_by_hand(i):
    """The expression of NEST7, innermost first."""
    l6 = i[5] ^ (1 - i[6])          # XN(: I5 xor not I6
    l5 = i[4] | (1 - l6)            # ON(
    l4 = i[3] & (1 - l5)            # AN(
    l3 = (1 - i[2]) ^ l4            # X(  after LDN I0.2
    l2 = i[1] & l3                  # A(
    l1 = i[0] | l2                  # O(
    return 1 & l1                   # A( after SET


def test_nested_parentheses_7_deep():
    lines = ["scan,I0.0,I0.1,I0.2,I0.3,I0.4,I0.5,I0.6"]
    inputs = [[(k >> b) & 1 for b in range(7)] for k in range(128)]
    lines += [f"{k}," + ",".join(map(str, v)) for k, v in enumerate(inputs)]
    recs = run(NEST7, stim("\n".join(lines)), scans=128)
    assert column(recs, "Q0.0") == [nest7_by_hand(v) for v in inputs]
    # two spot checks worked fully by hand
    assert recs[0].values["Q0.0"] == 0          # all inputs 0
    assert recs[0b0000001].values["Q0.0"] == 1  # I0.0 = 1 alone
    # SET + 7 opens + 7 loads + 7 `)` + `=` = 23 instructions, SET in the latch
    # clock, + END
    assert all(r.cycles == 23 + 1 for r in recs)


def test_parenthesis_versus_sequence():
    # a=0, b=0, c=1: a and (b or c) = 0, while a and b or c = 1
    recs = run("LD I0.0\nA(\nLD I0.1\nO I0.2\n)\n= Q0.0",
               stim("scan,I0.2\n0,1\n"), scans=1)
    assert column(recs, "Q0.0") == [0]


def test_paren_stack_is_empty_at_every_scan_start():
    # jumps out of an open parenthesis every scan: 20 scans > nest_depth 8 pushes
    recs = run("A(\nLD I0.0\nJU out\n)\nout: = Q0.0", stim("scan,I0.0\n0,1\n"), scans=20)
    assert column(recs, "Q0.0") == [1] * 20


def test_paren_stack_overflow_within_a_scan_is_an_error():
    sim = RefSim(prog("l: A(\nLD I0.0\nJU l"), Config())
    with pytest.raises(RefSimError, match="overflow"):
        sim.run(scans=1)


# --- jumps and cycles -----------------------------------------------------------------

J = DEF.jump_taken_clocks      # a taken jump's clocks (definition.toml [timing]: 3)


@pytest.mark.parametrize("src, stimulus, q00, q01, cycles, end_clocks", [
    # forward JC taken and not taken -- taken: LD + JC(J) + LD + = + END = 4 + J (LD in
    # the latch clock 0); not taken: 6 instructions + END = 7
    ("LD I0.0\nJC skip\nSET\n= Q0.0\nskip: LD I0.1\n= Q0.1",
     "scan,I0.0,I0.1\n0,1,1\n1,0,0\n", [0, 1], [1, 0], [4 + J, 7], [4 + J, 4 + J + 7]),
    # JCN and JU -- scan 0: LD, JCN(J), JU(J), NOP = 2 + 2J + END; scan 1: LD, JCN, SET,
    # =, JU(J), NOP = 5 + J + END
    ("LD I0.0\nJCN skip\nSET\n= Q0.0\nskip: JU over\nSET\n= Q0.1\nover: NOP",
     "scan,I0.0\n0,0\n1,1\n", [0, 1], [0, 0], [3 + 2 * J, 6 + J],
     [3 + 2 * J, 3 + 2 * J + 6 + J]),
], ids=["forward_jc_taken_and_not_taken", "jcn_and_ju"])
def test_conditional_jumps(src, stimulus, q00, q01, cycles, end_clocks):
    recs = run(src, stim(stimulus), scans=2)
    assert column(recs, "Q0.0") == q00
    assert column(recs, "Q0.1") == q01
    assert [r.cycles for r in recs] == cycles
    assert [r.end_clock for r in recs] == end_clocks


def test_backward_loop():
    src = """
          CLR
          = M0.0
    loop: LD M0.0
          NOT
          = M0.0
          JC loop      // taken once (M0.0 became 1), then falls through
          SET
          = Q0.0
    """
    recs = run(src, scans=2, watch=["M0.0"])
    assert column(recs, "Q0.0") == [1, 1]
    assert column(recs, "M0.0") == [0, 0]
    # CLR, =, (LD NOT = JC:J), (LD NOT = JC:1), SET, = -> 11 + J (CLR in the latch
    # clock), + END
    assert [r.cycles for r in recs] == [12 + J, 12 + J]


@pytest.mark.parametrize("n", [0, 1, 5, 100])
def test_straight_line_takes_n_plus_1(n):
    # n NOPs from the latch clock on, END in clock n of the scan
    recs = run("NOP\n" * n, scans=3)
    assert [r.cycles for r in recs] == [n + 1] * 3
    assert [r.end_clock for r in recs] == [(n + 1), 2 * (n + 1), 3 * (n + 1)]


def test_t_us_of_61_cycle_scans():
    # 60 NOPs + END = 61 cycles; end clocks 61, 122, 183 at 100 MHz
    columns, recs, fault = refsim_trace(prog("NOP\n" * 60), Config(), scans=3)
    assert trace_text(columns, recs, 100) == (
        "scan,t_us,cycles\n0,0.61,61\n1,1.22,61\n2,1.83,61\n")


def test_until_us_stops_after_first_scan_ending_at_or_after_t():
    p = prog("NOP\n" * 60)                       # 61 cycles: 0.61 us per scan
    for until, count in [(0, 1), (1.22, 2), ("1.22", 2), (1.23, 3), (0.61, 1)]:
        _, recs, _ = refsim_trace(p, Config(), until_us=until)
        assert len(recs) == count, until


def test_label_on_final_end_and_end_mid_program():
    src = "SET\nJC done\n= Q0.0\ndone: END\nSET\n= Q0.1"
    recs = run(src, scans=1)
    assert column(recs, "Q0.0") == [0]
    assert column(recs, "Q0.1") == [0]
    assert recs[0].cycles == 1 + J + 1      # SET (latch clock), JC taken, END


# --- inputs, edges and REFRESH ----------------------------------------------------------

EDGE_PROG = "LD IR0.0\n= Q0.0\nLD IF0.0\n= Q0.1\nLD I0.0\n= Q0.2"   # 7 clocks a scan


def test_ir_in_scan_0_for_input_high_from_t0():
    for s in (stim("t_us,I0.0\n0,1\n"), stim("scan,I0.0\n0,1\n")):
        recs = run(EDGE_PROG, s, scans=3)
        assert column(recs, "Q0.0") == [1, 0, 0]
        assert column(recs, "Q0.1") == [0, 0, 0]
        assert column(recs, "Q0.2") == [1, 1, 1]


def test_if_with_scan_stimulus():
    recs = run(EDGE_PROG, stim("scan,I0.0\n1,1\n2,0\n"), scans=4)
    assert column(recs, "Q0.0") == [0, 1, 0, 0]
    assert column(recs, "Q0.1") == [0, 0, 1, 0]


def test_pulse_shorter_than_a_scan_is_seen_by_ir_and_if():
    # latches at clocks 0, 7, 14 (100 MHz); the pin is 1 in clocks 3 and 4 only
    recs = run(EDGE_PROG, stim("t_us,I0.0\n0.03,1\n0.05,0\n"), scans=3)
    assert column(recs, "Q0.0") == [0, 1, 0]
    assert column(recs, "Q0.1") == [0, 1, 0]
    assert column(recs, "Q0.2") == [0, 0, 0]


def test_change_exactly_at_a_latch_clock_and_just_after():
    # 7-clock scans: scan 1 latches (and runs LD IR0.0) in clock 7, scan 2 in clock 14
    at_latch = run(EDGE_PROG, stim("t_us,I0.0\n0.07,1\n"), scans=3)      # clock 7
    assert column(at_latch, "Q0.2") == [0, 1, 1]
    assert column(at_latch, "Q0.0") == [0, 1, 0]
    after = run(EDGE_PROG, stim("t_us,I0.0\n0.0701,1\n"), scans=3)      # clock 8
    assert column(after, "Q0.2") == [0, 0, 1]
    assert column(after, "Q0.0") == [0, 0, 1]


def test_changes_within_one_clock_collapse_to_the_last():
    # 0.031 and 0.039 us both land in clock 4: the pin never rises
    recs = run(EDGE_PROG, stim("t_us,I0.0\n0.031,1\n0.039,0\n"), scans=3)
    assert column(recs, "Q0.0") == [0, 0, 0]
    assert column(recs, "Q0.1") == [0, 0, 0]


def test_pi_reads_the_pin_in_the_clock_of_the_instruction():
    # LD@0 (latch clock) =@1 LD@2 =@3 END@4; pin rises at clock 2
    recs = run("LD PI0.0\n= Q0.0\nLD PI0.0\n= Q0.1", stim("t_us,I0.0\n0.02,1\n"),
               scans=2, watch=["I0.0", "PI0.0"])
    assert column(recs, "Q0.0") == [0, 1]
    assert column(recs, "Q0.1") == [1, 1]
    assert column(recs, "I0.0") == [0, 1]    # PII latched at clock 0, then at 5
    assert column(recs, "PI0.0") == [1, 1]


def refresh_prog():
    # latch+LD@0 =@1 NOP@2 NOP@3 REFRESH@4 LD@5 =@6 LD@7 =@8 END@9 -> 10 cycles
    return "LD I0.0\n= Q0.0\nNOP\nNOP\nREFRESH\nLD I0.0\n= Q0.1\nLD IR0.0\n= Q0.2"


def test_refresh_relatches_pii_and_edges():
    # the pin rises in clock 3, between the latch (0) and the REFRESH (4)
    recs = run(refresh_prog(), stim("t_us,I0.0\n0.03,1\n"), scans=2)
    assert column(recs, "Q0.0") == [0, 1]
    assert column(recs, "Q0.1") == [1, 1]
    assert column(recs, "Q0.2") == [1, 0]    # the rise was taken by the REFRESH
    assert [r.cycles for r in recs] == [10, 10]


def test_refresh_sees_a_change_in_its_own_clock_only():
    # REFRESH in clock 4: a rise at 0.04 us (clock 4) is seen, at 0.041 us (clock 5) not
    in_clock = run(refresh_prog(), stim("t_us,I0.0\n0.04,1\n"), scans=1)
    assert column(in_clock, "Q0.1") == [1]
    later = run(refresh_prog(), stim("t_us,I0.0\n0.041,1\n"), scans=2)
    assert column(later, "Q0.1") == [0, 1]
    assert column(later, "Q0.0") == [0, 1]   # scan 1's latch took the rise ...
    assert column(later, "Q0.2") == [0, 0]   # ... so its REFRESH sees no new edge


def test_refresh_in_the_latch_clock_is_a_second_latch():
    # REFRESH@L (the latch clock itself) LD IR0.0@L+1 =@L+2 LD I0.0@L+3 =@L+4 END@L+5:
    # 6 cycles, latches 0, 6, 12.  The pin rises in clock 6 (0.06 us) / in scan 1: scan
    # 1's latch takes the rise, its REFRESH in that same clock is a second latch that
    # finds no edge since the first (spec §4), so IR0.0 is 0 in every scan.
    src = "REFRESH\nLD IR0.0\n= Q0.0\nLD I0.0\n= Q0.1"
    for s in (stim("t_us,I0.0\n0.06,1\n"), stim("scan,I0.0\n1,1\n")):
        recs = run(src, s, scans=3)
        assert column(recs, "Q0.0") == [0, 0, 0]
        assert column(recs, "Q0.1") == [0, 1, 1]
        assert [r.cycles for r in recs] == [6, 6, 6]


@pytest.mark.parametrize("front", ["", "NOP\n"])
def test_a_nop_in_front_of_refresh_changes_nothing(front):
    # issue 15, defect 1: with I0.0 rising at scan 0, `REFRESH / LD IR0.0 / = Q0.0` gave
    # 1 (the REFRESH merged with the scan start's latch), with a NOP in front 0
    recs = run(front + "REFRESH\nLD IR0.0\n= Q0.0", stim("scan,I0.0\n0,1\n"), scans=2)
    assert column(recs, "Q0.0") == [0, 0]


def test_refresh_with_scan_stimulus_sees_no_new_edge():
    recs = run(refresh_prog(), stim("scan,I0.0\n1,1\n"), scans=3)
    assert column(recs, "Q0.1") == [0, 1, 1]
    assert column(recs, "Q0.2") == [0, 0, 0]   # scan 1's rise was taken by its latch


def test_scan_stimulus_values_hold():
    recs = run("LD I0.0\n= Q0.0", stim("scan,I0.0\n2,1\n"), scans=4)
    assert column(recs, "Q0.0") == [0, 0, 1, 1]


# --- outputs ----------------------------------------------------------------------------


def test_pq_changes_the_pin_at_once_q_at_end():
    # SET@0 =PQ0.0@1 =Q0.1@2 NOP@3 NOP@4 END@5; scan 1 (latch 6) changes nothing
    sim = RefSim(prog("SET\n= PQ0.0\n= Q0.1\nNOP\nNOP"), Config())
    recs = sim.run(scans=2)
    assert sim.output_events == [(1, 0b01), (5, 0b11)]
    assert column(recs, "Q0.0") == [1, 1]
    assert column(recs, "Q0.1") == [1, 1]


def test_pq_read_sees_the_pio():
    # SET@0 =Q0.0@1 LD PQ0.0@2 =PQ0.1@3 LD Q0.1@4 =Q0.2@5 END@6
    sim = RefSim(prog("SET\n= Q0.0\nLD PQ0.0\n= PQ0.1\nLD Q0.1\n= Q0.2"), Config())
    recs = sim.run(scans=1)
    assert sim.output_events == [(3, 0b010), (6, 0b111)]
    assert column(recs, "Q0.2") == [1]


def test_refresh_q_moves_the_pins_mid_scan():
    # SET@0 =Q0.0@1 REFRESH Q@2 (the pin rises) CLR@3 =Q0.0@4 END@5 (it falls)
    sim = RefSim(prog("SET\n= Q0.0\nREFRESH Q\nCLR\n= Q0.0"), Config())
    (rec,) = sim.run(scans=1)
    assert sim.output_events == [(2, 0b1), (5, 0b0)]
    assert rec.cycles == 6 and (sim.qr, sim.qf) == (0, 1)


def test_refresh_i_is_refresh():
    assert [i.mnemonic for i in parse("t.il", "REFRESH I\nREFRESH\nREFRESH Q").instrs[:3]] == \
        ["REFRESH", "REFRESH", "REFRESH Q"]


@pytest.mark.parametrize("name", [c[0] for c in DIRECTED])
def test_directed_cases_by_hand(name):
    """The hand-worked CPU cases (tests/test_cpu_directed.py) hold here too."""
    _, text, stim_text, scans, expect = next(c for c in DIRECTED if c[0] == name)
    s = stim(stim_text) if stim_text else None
    columns, records, fault = refsim_trace(parse("t.il", text), Config(), s, (), scans=scans)
    assert not fault
    q = [c.header for c in columns if c.header.startswith("Q")]
    assert ["".join(str(r.values[h]) for h in q) for r in records] == expect


# --- hooks and watched words ------------------------------------------------------------


def test_timer_and_counter_status_are_0_without_byte_processor():
    recs = run("LD T1\n= Q0.0\nLDN C2\n= Q0.1", scans=1, watch=["T1", "C2"])
    assert column(recs, "Q0.0") == [0]
    assert column(recs, "Q0.1") == [1]
    assert column(recs, "T1") == [0]
    assert column(recs, "C2") == [0]


def test_watched_words():
    recs = run("NOP", stim("scan,IW0\n0,-5\n1,16#7FFF\n"), scans=2, watch=["IW0", "MW0", "QW1"])
    assert column(recs, "IW0") == [-5, 32767]
    assert column(recs, "MW0") == [0, 0]
    assert column(recs, "QW1") == [0, 0]


def test_byte_instruction_runs_in_serial_mode():
    # L 3 (10 clocks, from the latch clock), NOP (1), T MW0 (10), END: 10 + 1 + 10 + 1
    # = 22 cycles
    p = prog("NOP\nT MW0")
    p.instrs.insert(0, Instr("L", Operand("const", "INT", value=3), 1, 1, "L 3"))
    sim = RefSim(p, Config())
    (rec,) = sim.run(scans=1)
    assert rec.cycles == 22 and sim.mw == {0: 3}


@pytest.mark.parametrize("src", ["LD FBI0\n= Q0.0", "SET\n= FBY1"])
def test_exchange_channels_are_not_in_serial_mode(src):
    with pytest.raises(RefSimError, match=r"test.il:\d+:1: .*serial mode has no exchange"):
        RefSim(prog(src), Config()).run(scans=1)


# --- watchdog ---------------------------------------------------------------------------


def test_watchdog_on_endless_loop():
    columns, recs, fault = refsim_trace(prog("l: JU l"), Config(), watchdog=100, scans=5)
    assert fault
    assert recs == []


def test_watchdog_after_good_scans_drops_the_outputs():
    # SET = LD JC(not taken) + END -> 5 cycles while I0.0 = 0 (latches 0, 5, 10);
    # from scan 2 an endless loop
    src = "SET\n= Q0.0\nLD I0.0\nl: JC l"
    sim = RefSim(prog(src), Config(), stim("scan,I0.0\n0,0\n2,1\n"), watchdog=1000)
    recs = sim.run(scans=10)
    assert [r.scan for r in recs] == [0, 1]
    assert column(recs, "Q0.0") == [1, 1]
    assert sim.watchdog_fault and sim.fault_scan == 2
    assert sim.fault_clock == 10 + 1000
    assert sim.outputs == 0
    assert sim.output_events[-1] == (1010, 0)
    assert sim.run(scans=1) == []


def test_watchdog_limit_is_inclusive():
    p = prog("NOP\nNOP")                            # 3 cycles a scan
    assert refsim_trace(p, Config(), scans=3, watchdog=3)[2] is False
    _, recs, fault = refsim_trace(p, Config(), scans=3, watchdog=2)
    assert fault and recs == []


def test_run_needs_a_limit():
    with pytest.raises(ValueError):
        RefSim(prog("NOP"), Config()).run()


def test_default_columns_are_the_written_outputs():
    p = prog("SET\n= Q0.1\nS PQ0.0")
    assert [c.header for c in RefSim(p, Config()).columns] == ["Q0.0", "Q0.1"]
    assert [c.header for c in trace_columns(p)] == ["Q0.0", "Q0.1"]
