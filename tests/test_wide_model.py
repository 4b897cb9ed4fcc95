"""The wide bit engine's reference model (bitbyte/wide/model.py, issue 18): whole
programs run with their compiled units as LUT programs give the scalar reference
interpreter's trace (every column but t_us and cycles; scan-keyed stimuli, no timers,
spec §4 `--bit-engine`), and the 64-bit adder's sums are the integer sums."""
from __future__ import annotations

import os
import random
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
import randprog                                        # noqa: E402
from bit_engine_bench import adder_il                  # noqa: E402
from bitbyte.lang.parser import parse                  # noqa: E402
from bitbyte.lang.stimulus import parse_stimulus       # noqa: E402
from bitbyte.wide import lutmap as L                   # noqa: E402
from bitbyte.wide import model                         # noqa: E402

PROGRAMS = int(os.environ.get("BITBYTE_WIDE_MODEL_PROGRAMS", "40"))
SCANS = 8
BASE_SEED = int(os.environ.get("BITBYTE_SEED", "1"))


def _adder():
    p = parse("adder.il", adder_il())
    return p, model.compile_program(p)


def _operands(seed: int, scans: int) -> list[tuple[int, int]]:
    rng = random.Random(seed)
    ops = [(0, 0), (2**64 - 1, 1), (2**64 - 1, 2**64 - 1), (0x5555555555555555, 0xAAAAAAAAAAAAAAAB)]
    return (ops + [(rng.getrandbits(64), rng.getrandbits(64)) for _ in range(scans)])[:scans]


def _adder_stimulus(ops) -> str:
    cols = [f"I{b}.{n}" for b in range(16) for n in range(8)]
    rows = ["scan," + ",".join(cols)]
    for s, (a, b) in enumerate(ops):
        bits = a | b << 64
        rows.append(f"{s}," + ",".join(str(bits >> i & 1) for i in range(128)))
    return "\n".join(rows) + "\n"


def test_the_adder_sums_operands_as_integers():
    """Q0.0..Q8.0 of each scan, read from the trace, is a + b of that scan's pins; the
    adder's 900 IL run as 2 scalar instructions (positions 0 and 1, R1) and about 83
    LUT instructions (10.5 per clock)."""
    p, c = _adder()
    ops = _operands(BASE_SEED, 12)
    st = parse_stimulus(_adder_stimulus(ops))
    watch = [f"Q{i // 8}.{i % 8}" for i in range(65)]
    diffs, sim = model.compare(p, st, watch=watch, scans=len(ops), compiled=c)
    assert diffs == []
    _, recs, fault, _ = model.wide_trace(p, c, stimulus=st, watch=watch, scans=len(ops))
    assert not fault and c.fallbacks == 0
    for (a, b), r in zip(ops, recs):
        got = sum(r.values[f"Q{i // 8}.{i % 8}"] << i for i in range(65))
        assert got == a + b, (hex(a), hex(b), hex(got))
    assert sim.unit_il == 898 * len(ops) and sim.lut_clocks * 10 < sim.unit_il
    # the bit part's count: every IL instruction of the adder is a bit instruction, in
    # a unit but the first two, END is none (the bench's "bit IL per clock")
    lut = sum(len(prog) for prog in c.programs)
    assert (sim.bit_il, sim.bit_clocks) == (900 * len(ops), (lut + 2) * len(ops))


def with_label_nops(text: str, rng: random.Random) -> str:
    """`label: NOP` (the jump-target idiom the generators do not write) before about
    one line in eight: a unit of NOPs between two others must hand the RLO on."""
    out, k = [], 0
    lines = text.split("\n")
    for i, line in enumerate(lines):
        s, prev = line.strip(), lines[i - 1].strip() if i else ""
        if s and not s.startswith(("VAR", "END_VAR")) and ":" not in s and \
                " AT " not in s and not prev.endswith("(") and rng.random() < 0.12:
            out.append(f"NP{k}: NOP")
            k += 1
        out.append(line)
    return "\n".join(out)


@pytest.mark.parametrize("nops", [False, True], ids=["as_generated", "label_nops"])
def test_random_programs_trace_as_the_scalar_engine(nops):
    """Random programs of the regression's generators (bit-only: jumps, REFRESH,
    parentheses, edges, PI/PQ; mixed serial-mode programs with their timers stripped:
    words, compares, counters), scan-keyed stimuli: 0 mismatching programs. Also with
    `label: NOP` lines put in (a review found the RLO dropped before one)."""
    texts = [randprog.random_program(BASE_SEED * 1000 + k) if k % 2 == 0 else
             randprog.strip_timers(randprog.random_mixed_program(BASE_SEED * 1000 + k))
             for k in range(PROGRAMS)]
    if nops:
        texts = [with_label_nops(t, random.Random(BASE_SEED * 1000 + k))
                 for k, t in enumerate(texts)]
    progs = [parse(f"wide{BASE_SEED * 1000 + k}.il", t) for k, t in enumerate(texts)]
    compiled = model.compile_programs(progs)
    # direct PI reads are units' inputs (model.ABSORB_DIRECT): some ran here
    assert sum(any(x.startswith("PI") for x in u.inputs)
               for c in compiled for u in c.split.units) >= 10
    bad, unit_il = [], 0
    for k, (p, c) in enumerate(zip(progs, compiled)):
        seed = BASE_SEED * 1000 + k
        st = parse_stimulus(randprog.scan_stimulus(seed, SCANS))
        diffs, sim = model.compare(p, st, watch=randprog.FULL_WATCH, scans=SCANS, compiled=c)
        unit_il += sim.unit_il
        if diffs:
            bad.append((seed, diffs[:3]))
    assert bad == [], bad
    assert unit_il > 1000        # units ran: the comparison is not of two scalar runs


def test_a_unit_before_a_label_nop_hands_on_its_rlo():
    """LD/A is a unit, `skip: NOP` a unit of its own, CU a cut: the first unit's RLO
    reaches CU (and `= Q0.0`) through the NOP (the review's reproducer: the RLO was
    dropped, Q0.0 and C1 differed in scan 1)."""
    p = parse("nop.il", "NOP\nNOP\nLD I0.0\nA I0.1\nskip: NOP\nCU C1\nA C1\n= Q0.0\n")
    c = model.compile_program(p)     # (positions 0 and 1 stay scalar: R1)
    assert [(u.start, u.stop) for u in c.split.units][:2] == [(2, 4), (4, 5)]
    assert c.split.units[0].rlo_live
    st = parse_stimulus(randprog.scan_stimulus(BASE_SEED, SCANS, fixed={"I0.0": 1, "I0.1": 1}))
    assert model.compare(p, st, watch=["Q0.0", "C1"], scans=SCANS, compiled=c)[0] == []


# the RLO live across a cut: the unit LD/A/O hands its RLO to JC and to `= Q0.0`
JUMP_PROGRAM = """\
      LD  I0.0
      A   I0.1
      O   I0.2
      JC  L1
      LD  I0.3
      =   Q0.1
L1:   =   Q0.0
"""


@pytest.mark.parametrize("fault", ["table_bit", "rlo_dropped", "output_dropped"])
def test_a_broken_wide_program_is_seen(fault):
    """The comparison fails on a wrong LUT program: one truth-table bit flipped in
    every unit of the adder; a live RLO not handed on (a unit before JC); a written
    bit (the adder's carry out) not written."""
    if fault == "rlo_dropped":
        p = parse("jump.il", JUMP_PROGRAM)
        c = model.compile_program(p)
        assert any(u.rlo_live for u in c.split.units) and c.fallbacks == 0
        st = parse_stimulus(randprog.scan_stimulus(1, SCANS))    # fixed seeds: a
        watch, scans = ["Q0.0", "Q0.1"], SCANS                   # check must not be luck
    else:
        p, c = _adder()
        ops = _operands(2, 6)
        st = parse_stimulus(_adder_stimulus(ops))
        watch, scans = [f"Q{i // 8}.{i % 8}" for i in range(65)], len(ops)
    assert model.compare(p, st, watch=watch, scans=scans, compiled=c)[0] == []
    if fault == "table_bit":
        rng = random.Random(7)
        for prog in c.programs:
            ins = prog[rng.randrange(len(prog))]
            d, t = ins.outs[0]
            ins.outs[0] = (d, t ^ (1 << rng.randrange(1 << len(ins.inputs))))
        diffs, _ = model.compare(p, st, watch=watch, scans=scans, compiled=c)
    else:
        orig = model.WideRefSim._set

        def broken(self, x, v):
            if (fault == "rlo_dropped" and x == model.RLO) or \
                    (fault == "output_dropped" and x == "Q8.0"):
                return
            orig(self, x, v)
        model.WideRefSim._set = broken
        try:
            diffs, _ = model.compare(p, st, watch=watch, scans=scans, compiled=c)
        finally:
            model.WideRefSim._set = orig
    assert diffs, fault


def test_no_unit_at_the_scan_start_or_after_a_refresh():
    """The RTL's contract (docs/wide-rtl-plan.md R1/R2): positions 0 and 1 and the
    instruction after REFRESH / REFRESH Q stay scalar, on every program of the random
    test and on a hand-written one."""
    p = parse("r.il", "LD I0.0\nA I0.1\n= Q0.0\nREFRESH\nLD I0.2\nA I0.3\n= Q0.1\n"
                      "REFRESH Q\nLD I0.4\n= Q0.2\nLD I0.5\n= Q0.3\n")
    c = model.compile_program(p)
    assert [(u.start, u.stop) for u in c.split.units] == [(2, 3), (5, 7), (9, 12)]
    texts = [randprog.random_program(BASE_SEED * 1000 + k) for k in range(PROGRAMS)]
    progs = [parse(f"r{k}.il", t) for k, t in enumerate(texts)]
    starts = 0
    for p, c in zip(progs, model.compile_programs(progs)):
        for u in c.split.units:
            assert u.start >= 2 and \
                p.instrs[u.start - 1].mnemonic not in ("REFRESH", "REFRESH Q"), u.start
        starts += any(p.instrs[u.start - 2].mnemonic == "REFRESH" for u in c.split.units)
    assert starts, "no unit two after a REFRESH: the rule is untested"


def _pins_trace(text: str, rise_us: str) -> tuple[model.Compiled, dict[str, int]]:
    """The wide model's Q0.0..Q0.3 after one scan of `text` with I0.0 and I0.1 rising
    at `rise_us` (a t_us stimulus, 100 MHz: 0.01 us a clock)."""
    p = parse("pi.il", text)
    c = model.compile_program(p)
    st = parse_stimulus(f"t_us,I0.0,I0.1\n0,0,0\n{rise_us},1,1\n")
    watch = ["Q0.0", "Q0.1"]
    _, recs, _, _ = model.wide_trace(p, c, stimulus=st, scans=1, watch=watch)
    return c, {q: recs[0].values[q] for q in watch if q in recs[0].values}


def test_a_unit_samples_its_pins_once_in_its_first_operand_clock():
    """Under a t_us stimulus (which spec §4 leaves to each engine) a unit reads its
    PI pins once, in its first word's operand clock (the clock before it executes),
    for all its words: every word that reads a pin sees the value the unit's network
    was checked with. The unit at clock 2 (two words) samples clock 1: the pins rising
    at clock 2 are not seen (the scalar engine sees them: 1 and 1); rising at clock 1,
    both outputs see them. A pin read twice in one unit (`= Q0.0`, `= Q0.1`, and an
    edge through FP: the review's reproducers) gives one value."""
    c, got = _pins_trace("NOP\nNOP\nLD PI0.0\n= Q0.0\nLD PI0.1\n= Q0.1\nEND\n", "0.02")
    (unit, prog), = [(u, g) for u, g in zip(c.split.units, c.programs)]
    assert (unit.start, len(prog)) == (2, 2)
    assert got == {"Q0.0": 0, "Q0.1": 0}
    assert _pins_trace("NOP\nNOP\nLD PI0.0\n= Q0.0\nLD PI0.1\n= Q0.1\nEND\n",
                       "0.01")[1] == {"Q0.0": 1, "Q0.1": 1}
    c, got = _pins_trace("NOP\nNOP\nLD PI0.0\n= Q0.0\n= Q0.1\nEND\n", "0.02")
    assert sum(x == "PI0.0" for p in c.programs[0] for x in p.inputs) >= 2
    assert got["Q0.0"] == got["Q0.1"] == 0
    c, got = _pins_trace("NOP\nNOP\nLD PI0.0\nFP M0.0\nS Q0.0\nEND\n", "0.02")
    assert got["Q0.0"] == 0      # the edge is not lost: scan 1 would see it (below)
    p = parse("fp.il", "NOP\nNOP\nLD PI0.0\nFP M0.0\nS Q0.0\nEND\n")
    st = parse_stimulus("t_us,I0.0,I0.1\n0,0,0\n0.02,1,1\n")
    _, recs, _, _ = model.wide_trace(p, model.compile_program(p), stimulus=st, scans=2,
                                     watch=["Q0.0"])
    assert [r.values["Q0.0"] for r in recs] == [0, 1]


@pytest.mark.parametrize("byte", ["L 5", "CU C1"])
def test_behind_a_byte_instruction_the_pins_of_its_first_clock(byte):
    """Behind a dispatched byte instruction (clock 2, k >= 2 clocks; a counter's too)
    the unit samples the pins of clock 2: the pins rising at clock 3 are not seen,
    though the first word's own operand clock 2 + k - 1 would see them; also when a
    unit of no LUT word (a label on `LD I0.1`, dead) stands between."""
    for mid in ("", "la: LD I0.1\n"):
        text = f"NOP\nNOP\n{byte}\n{mid}lb: LD PI0.0\n= Q0.0\nLD PI0.1\n= Q0.1\nEND\n"
        c, got = _pins_trace(text, "0.03")
        assert [len(g) for g in c.programs if g is not None][-1] == 2, c.programs
        if mid:
            assert [len(g) for g in c.programs if g is not None][0] == 0
        assert got == {"Q0.0": 0, "Q0.1": 0}, (byte, mid, got)
