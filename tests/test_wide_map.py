"""The wide bit engine's compiler front half (issue 18, direction (a)): stretches of pure
bit instructions and their units (bitbyte/wide/stretch.py), the units' networks against
the reference interpreter, their LUT programs (bitbyte/wide/lutmap.py, Yosys `abc -lut
K`) checked exhaustively, and that check catching a broken mapping."""
from __future__ import annotations

import random
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
sys.path.insert(0, str(ROOT / "tests"))

from bitbyte.lang.parser import parse                 # noqa: E402
from bitbyte.wide import lutmap as L                   # noqa: E402
from bitbyte.wide.stretch import RLO, split_program   # noqa: E402

CUTS = """LD I0.0
A M0.0
= Q0.0
LD PI0.1
= M0.1
L MW0
T MW1
lab: LD I0.2
O M0.3
JC lab
A(
LD I0.3
A PI0.4
A M0.2
)
= Q0.1
REFRESH
LD I0.5
S M0.7
END
"""

# one bit of the adder (bench/bit_engine_bench.py): a = I0.0, b = I1.0,
# carry in and out M0.0, c1 = M0.1, sum Q0.0
FULL_ADDER = """LD I0.0
X I1.0
A M0.0
O(
LD I0.0
A I1.0
)
= M0.1
LD M0.0
X I0.0
X I1.0
= Q0.0
LD M0.1
= M0.0
"""


def test_cuts_fall_at_labels_jumps_direct_byte_refresh_end():
    s = split_program(parse("cuts.il", CUTS))
    assert [(u.start, u.stop) for u in s.units] == [
        (0, 3), (4, 5), (7, 9), (11, 12), (13, 14), (15, 16), (17, 19)]
    assert s.scalar == {"direct": [3, 12], "byte": [5, 6], "jump": [9],
                        "paren": [10, 14], "refresh": [16], "end": [19]}
    u = {x.start: x for x in s.units}
    assert u[0].inputs == ["I0.0", "M0.0"] and list(u[0].outputs) == ["Q0.0"]
    assert not u[0].rlo_live                        # LD PI0.1 sets the RLO unread
    assert u[4].inputs == [RLO] and u[4].rlo_live   # = M0.1 after the cut; L keeps the RLO
    assert u[7].inputs == ["I0.2", "M0.3"] and u[7].rlo_live   # JC reads it
    # inside the group a cut interrupted: a unit with the RLO in and out, A( and ) scalar
    assert u[13].inputs == [RLO, "M0.2"] and list(u[13].outputs) == [RLO]
    # S: the old value is an input (not taken, the bit keeps it); END: the RLO is dead
    assert u[17].inputs == ["I0.5", "M0.7"] and list(u[17].outputs) == ["M0.7"]


def test_units_stay_within_the_input_limit_and_wide_groups_split():
    body = ["LD I0.0"] + [f"A I{b}.{n}" for b in range(1, 4) for n in range(8)] + ["= Q0.0"]
    group = ["LD I0.0", "A("] + body[:-1] + [")", "= Q0.1"]
    s = split_program(parse("w.il", "\n".join(body + group) + "\n"), max_inputs=8)
    assert all(len(u.inputs) <= 8 for u in s.units)
    assert s.scalar.get("paren") == [len(body) + 1, len(body) + len(group) - 2]
    assert sum(u.size for u in s.units) + 2 == len(body) + len(group)   # but A( and )


def test_networks_match_the_reference_interpreter_on_random_programs():
    import wide_map_bench as W
    interlock = (ROOT / "examples" / "interlock.il").read_text()
    for text in W.random_programs(6, True) + [FULL_ADDER, CUTS, interlock]:
        p = parse("r.il", text)
        for absorb in (False, True):            # PI read, PQ written inside a unit
            for u in split_program(p, absorb_direct=absorb).units:
                assert L.check_against_refsim(u, p, samples=16), (text, u.start, absorb)


def test_direct_accesses_absorbed_on_request():
    s = split_program(parse("cuts.il", CUTS), absorb_direct=True)
    assert "direct" not in s.scalar and "paren" not in s.scalar
    u = {x.start: x for x in s.units}
    assert u[0].stop == 5 and u[0].inputs[-1] == "PI0.1"      # LD PI0.1, = M0.1
    assert u[10].stop == 16 and "PI0.4" in u[10].inputs      # A( ... A PI0.4 ... ) = Q0.1


def test_full_adder_maps_to_two_3_luts():
    u, = split_program(parse("fa.il", FULL_ADDER)).units
    assert u.inputs == ["I0.0", "I1.0", "M0.0"]
    assert set(u.outputs) == {"M0.1", "Q0.0", "M0.0"}      # the RLO: END, dead
    m, = L.map_units([u], 3)
    assert len(m.nodes) == 2 and all(len(f) == 3 for f, _ in m.nodes.values())
    single, dual = L.program_single(m), L.program_dual(m, 3)
    assert len(single) == 3                     # sum, carry, carry copied to M0.1
    assert len(dual) == 2 and L.check(u, single) and L.check(u, dual)
    # sum -> Q0.0, carry -> M0.0 (no scratch): dual_s cannot pair them
    assert len(L.PROGRAMS["dual_s"](m, 3)) == 3
    m_if, = L.map_units([u], 3, "if")           # the bench's second ABC flow
    assert len(m_if.nodes) == 2 and L.check(u, L.program_single(m_if))


@pytest.fixture(scope="module")
def mapped():
    texts = [(ROOT / "examples" / "interlock.il").read_text(),
             (ROOT / "examples" / "star_delta.il").read_text(), FULL_ADDER * 3,
             "S Q0.4\nJC done\ndone: NOP\n"]            # the RLO passes through a unit
    units = [u for t in texts for u in split_program(parse("p.il", t)).units]
    return units, L.map_units(units, 4), L.map_units(units, 5)


@pytest.mark.parametrize("variant", ["single", "dual", "dual_s", "rlo"])
def test_every_variant_passes_the_exhaustive_check(mapped, variant):
    units, m4, m5 = mapped
    for u, a, b in zip(units, m4, m5):
        prog = L.PROGRAMS[variant](b if variant == "rlo" else a, 4)
        assert L.check(u, prog), (variant, u.start)
        assert all(len([x for x in p.inputs if not (variant == "rlo" and x == RLO)]) <= 4
                   for p in prog)


def test_the_check_fails_on_a_flipped_truth_table_bit(mapped):
    units, m4, _ = mapped
    rng = random.Random(7)
    caught = 0
    for u, m in zip(units, m4):
        prog = L.program_single(m)
        luts = [i for i, p in enumerate(prog) if p.inputs]
        if not luts:
            continue
        i = rng.choice(luts)
        p = prog[i]
        bit = rng.randrange(1 << len(p.inputs))
        broken = list(prog)
        broken[i] = L.MInstr(p.inputs, [(p.outs[0][0], p.outs[0][1] ^ (1 << bit))])
        assert not L.check(u, broken), (u.start, i, bit)
        caught += 1
    assert caught >= 5


def test_the_check_catches_a_write_before_its_old_value_is_read():
    # Q0.0 := I0.0 after M0.0 := old Q0.0: writing Q0.0 first breaks it
    u, = split_program(parse("war.il", "LD Q0.0\n= M0.0\nLD I0.0\n= Q0.0\n")).units
    m, = L.map_units([u], 4)
    prog = L.program_single(m)
    assert L.check(u, prog)
    assert not L.check(u, prog[::-1])
    swap, = split_program(parse("swap.il", "LD M0.0\n= M0.2\nLD M0.1\n= M0.0\n"
                                "LD M0.2\n= M0.1\n")).units
    m, = L.map_units([swap], 4)
    assert L.check(swap, L.program_single(m))          # a cycle: through a scratch bit


LONE_NOPS = """LD PI0.0
JCN skip
SET
= M0.0
skip: NOP
= PQ0.1
LD PI0.0
NOP
JC there
SET
= Q0.2
there: NOP
END
"""


def test_a_unit_of_only_nops_keeps_the_rlo():
    # a lone NOP between a label and a reader of the RLO: it must not set the RLO to 0
    p = parse("nops.il", LONE_NOPS)
    s = split_program(p)
    u = {x.start: x for x in s.units}
    for a in (4, 7):
        assert u[a].instrs[0].mnemonic == "NOP" and u[a].rlo_live
        assert RLO not in u[a].outputs or (
            u[a].inputs == [RLO] and u[a].outputs[RLO] == u[a].net.var(RLO))
        assert L.check_against_refsim(u[a], p)
        m, = L.map_units([u[a]], 4)
        prog = L.program_single(m)
        assert L.check(u[a], prog)
        # the program leaves the RLO as it came in
        pats, mask = L.patterns([RLO])
        assert L.execute(prog, pats, mask)[RLO] == pats[RLO]


def test_a_waiting_timer_read_cuts():
    # parallel mode: the bit part's `LD T1` waits for the byte part's SD T1 (bit 16)
    from bitbyte.compiler.partition import partition
    p = parse("wait.il", "L MW0\nL 5\n>I\nSD T1\nLD I0.0\n= Q0.2\nLD T1\n= Q0.1\n")
    bp = partition(p).bit_program()
    waits = [i for i, x in enumerate(bp.instrs) if getattr(x, "wait_update", False)]
    assert waits and bp.instrs[waits[0]].operand.address() == "T1"
    s = split_program(bp)
    assert s.scalar.get("wait") == waits
    for u in s.units:
        assert not any(getattr(x, "wait_update", False) for x in u.instrs)
        assert "T1" not in u.inputs


def test_pq_writes_cut_even_when_direct_accesses_are_absorbed():
    # the pin pulses 1 then 0 at the two PQ writes' clocks; a unit would write only
    # its final value (no pin change at all), and QR/QF would differ
    text = "LD PI0.0\n= PQ0.0\nCLR\n= PQ0.0\nLD PQ0.0\n= M0.0\n"
    p = parse("pq.il", text)
    s = split_program(p, absorb_direct=True)
    assert s.scalar.get("direct") == [1, 3]
    for u in s.units:
        assert not any(x.operand is not None and x.operand.area == "PQ"
                       and x.mnemonic == "=" for x in u.instrs)
        assert L.check_against_refsim(u, p)


AND8 = "LD I0.0\n" + "".join(f"A I0.{b}\n" for b in range(1, 8)) + "= Q0.0\n"


def test_refsim_comparison_is_exhaustive_up_to_10_inputs_and_structured_above():
    u, = split_program(parse("and8.il", AND8)).units
    p = parse("and8.il", AND8)
    assert L.check_against_refsim(u, p)
    u.outputs["Q0.0"] = u.net.C0                 # wrong only in the all-ones state
    assert not L.check_against_refsim(u, p)
    st = L.refsim_states(12, samples=4)
    full = (1 << 12) - 1
    assert 0 in st and full in st and all(1 << j in st and full ^ (1 << j) in st
                                          for j in range(12))
    assert sorted(L.refsim_states(10)) == list(range(1024))
    assert sorted(L.refsim_states(2)) == [0] * 8 + [1] * 8 + [2] * 8 + [3] * 8


def test_refsim_comparison_randomises_the_state_outside_the_inputs():
    p = parse("m.il", "LD M0.0\n= Q0.0\n")
    u, = split_program(p).units
    assert L.check_against_refsim(u, p)
    net = u.net
    u.outputs["Q0.0"] = net.AND(net.var("M0.0"), net.NOT(net.var(RLO)))   # reads the RLO
    assert not L.check_against_refsim(u, p)
    u.outputs = {}                               # claims Q0.0 unchanged: refsim changes it
    assert not L.check_against_refsim(u, p)


def test_the_check_rejects_reads_of_non_inputs_and_format_violations():
    p = parse("m.il", "LD M0.0\n= Q0.0\n")
    u, = split_program(p).units
    assert u.inputs == ["M0.0"]
    good = [L.MInstr(("M0.0",), [("Q0.0", 0b10)])]
    assert L.check(u, good)
    # Q0.0 := M0.0 ∧ ¬M0.1: M0.1 is no input (0 in the enumeration, anything on the chip)
    assert not L.check(u, [L.MInstr(("M0.0", "M0.1"), [("Q0.0", 0b0010)])])
    # a scratch bit read before it is written
    assert not L.check(u, [L.MInstr(("M0.0", "S:x"), [("Q0.0", 0b0010)])])
    # format limits: K operands, dual_s one memory write, single one destination
    and8, = split_program(parse("and8.il", AND8)).units
    wide = [L.MInstr(tuple(f"I0.{b}" for b in range(5)), [("S:a", 1 << 31)]),
            L.MInstr(("S:a", "I0.5", "I0.6", "I0.7"), [("Q0.0", 1 << 15)])]
    assert L.check(and8, wide) and L.check(and8, wide, K=5, variant="single")
    assert not L.check(and8, wide, K=4, variant="single")
    two = [L.MInstr(("M0.0",), [("Q0.0", 0b10), ("M0.1", 0b10)])]
    u2, = split_program(parse("two.il", "LD M0.0\n= Q0.0\n= M0.1\n")).units
    assert L.check(u2, two, K=4, variant="dual")
    assert not L.check(u2, two, K=4, variant="dual_s")
    assert not L.check(u2, two, K=4, variant="single")
    many = [L.MInstr(("M0.0",), [(f"S:{k}", 0b10)]) for k in range(L.SCRATCH_BITS + 1)]
    assert not L.format_ok(many, 4, "single")


def test_a_bit_parts_status_write_is_a_counted_bit_instruction():
    # --tc-path status: the bit part's `= T1` is a one-clock bit instruction (scalar),
    # counted in the bench's bit IL (not on the byte side)
    import wide_map_bench as W
    from bitbyte.compiler.partition import partition
    p = parse("st.il", "LD I0.1\nL 5\nSD T1\nLD I0.0\n= Q0.2\nLD T1\n= Q0.1\n")
    bp = partition(p, tc_path="status").bit_program()
    s = split_program(bp)
    writes = [i for i, x in enumerate(bp.instrs) if x.mnemonic == "="
              and x.operand.area == "T"]
    assert writes and s.scalar.get("status") == writes
    assert "status" not in W.BYTE_SIDE and "wait" not in W.BYTE_SIDE
    titles = [t for t, _, _ in W.benchmarks(True)]
    assert any("parallel bit part (channels)" in t for t in titles)
    assert any("--tc-path status" in t for t in titles)
