"""The wide engine's LUT words (bitbyte/wide/encode.py, definition.toml [lut]): a
hand-worked word at the bit positions docs/isa.md gives; every unit of random
programs, the adder and the Table-1 program through encode and decode runs as
before, state for state; what does not fit the format is refused. The model runs
the decoded words (tests/test_wide_model.py), so its traces check them too."""
from __future__ import annotations

import random
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "bench"))

import randprog                                        # noqa: E402
from bit_engine_bench import adder_il                  # noqa: E402
from bitbyte.lang.parser import parse                  # noqa: E402
from bitbyte.wide import lutmap as L                   # noqa: E402
from bitbyte.wide import model                         # noqa: E402
from bitbyte.wide.encode import (EncodeError, decode, decode_unit, encode,  # noqa: E402
                                 encode_unit, widen)


def test_a_word_by_hand():
    """Q1.2 := I0.1 XOR RLO into port A, S:x := I0.1 AND RLO into port B, first word.
    Base: tag 01 (bits 31:30), first (29), Q = area 4 (27:24), scratch index 0 (20:16),
    scr_en (11), index 1*8+2 = 10 (10:0). Extension: table A 0b0110 widened to 32
    bits, table B 0b1000 widened (bits 63:32), operand 0 = I (0) index 1 at bit 64,
    operand 1 = RLO (11) at bit 79, operands 2..4 = ZERO (12)."""
    p = L.MInstr(("I0.1", "RLO"), [("Q1.2", 0b0110), ("S:x", 0b1000)])
    base, ext = encode(p, {"S:x": 0}, first=True, last=False)
    assert base == (1 << 30) | (1 << 29) | (4 << 24) | (0 << 16) | (1 << 11) | 10
    table_a = int("0110" * 8, 2)
    table_b = int("1000" * 8, 2)
    ops = [(0, 1), (11, 0), (12, 0), (12, 0), (12, 0)]
    want = table_a | table_b << 32
    for j, (area, index) in enumerate(ops):
        want |= (area << 11 | index) << (64 + 15 * j)
    assert ext == want
    back, first, last = decode(base, ext)
    assert (first, last) == (True, False)
    assert back.inputs == ("I0.1", "RLO", "ZERO", "ZERO", "ZERO")
    assert back.outs == [("Q1.2", table_a), ("S0", table_b)]


def _programs():
    texts = [randprog.random_program(20261207 + k) for k in range(12)]
    texts += [randprog.strip_timers(randprog.random_mixed_program(20261207 + k))
              for k in range(4)]
    texts += [adder_il(), (ROOT / "bench" / "programs" / "table1.il").read_text()]
    return [parse(f"e{k}.il", t) for k, t in enumerate(texts)]


def test_every_unit_runs_the_same_through_its_words():
    """Every unit's LUT program and its decoded words give the same state from every
    input combination (up to 10 inputs; 64 random states above), scratch renamed."""
    rng = random.Random(7)
    units = 0
    for c in model.compile_programs(_programs()):
        for u, prog in zip(c.split.units, c.programs):
            if prog is None:
                continue
            units += 1
            words = decode_unit(encode_unit(prog))
            n = len(u.inputs)
            if n <= 10:
                state, mask = L.patterns(list(u.inputs))
            else:
                mask = (1 << 64) - 1
                state = {x: rng.getrandbits(64) for x in u.inputs}
            want = L.execute(prog, state, mask)
            got = L.execute(words, state, mask)
            for x in u.outputs:
                assert got[x] == want[x], (u.start, x)
    assert units > 250


def test_a_flipped_table_bit_or_operand_changes_what_runs():
    """The decoding reads what the encoding wrote: flipping a table bit or an operand's
    index bit in one word changes the unit's result from some input state."""
    p = parse("a.il", adder_il())
    c = model.compile_program(p)
    u, prog = next((u, g) for u, g in zip(c.split.units, c.programs) if g and len(g) > 3)
    state, mask = L.patterns(list(u.inputs))
    want = L.execute(prog, state, mask)
    words = encode_unit(prog)
    for flip_ext in (1 << 3, 1 << (64 + 1)):          # table A bit 3; operand 0's index
        bad = [(b, e ^ flip_ext) if i == 1 else (b, e) for i, (b, e) in enumerate(words)]
        got = L.execute(decode_unit(bad), state, mask)
        assert any(got.get(x) != want[x] for x in u.outputs), hex(flip_ext)


@pytest.mark.parametrize("prog, message", [
    ([L.MInstr(("I0.0",) * 6, [("Q0.0", 1)])], "6 operands"),
    ([L.MInstr(("I0.0",), [("Q0.0", 1), ("M0.0", 1)])], "one to the bit memory"),
    ([L.MInstr(("M300.0",), [("Q0.0", 1)])], "does not fit 11 bits"),
    ([L.MInstr(("FBI1",), [("Q0.0", 1)])], "no LUT-word location"),
    ([L.MInstr(("I0.0",), [(f"S:{i}", 1)]) for i in range(33)], "33 scratch bits"),
])
def test_what_does_not_fit_is_refused(prog, message):
    with pytest.raises(EncodeError, match=message):
        encode_unit(prog)


def test_a_word_that_is_no_lut_word_is_refused():
    with pytest.raises(EncodeError, match="no LUT word"):
        decode(0x0A00000B, 0)                        # A I1.3
    with pytest.raises(EncodeError, match="a destination no LUT word writes"):
        decode(1 << 30 | 7 << 24, 0)                 # a LUT word writing T
    words = encode_unit([L.MInstr(("I0.0",), [("Q0.0", 2)]), L.MInstr(("I0.0",), [("Q0.1", 2)])])
    with pytest.raises(EncodeError, match="first/last"):
        decode_unit(words[::-1])


def test_scratch_bits_past_eight_keep_their_numbers():
    """32 scratch names in a unit of 40 words: S0..S31 in first-named order, the high
    index bits too; the decoded program computes the same."""
    prog = [L.MInstr(("I0.0", "I0.1"), [(f"S:n{i}", 0b0110 ^ i % 2)]) for i in range(32)]
    prog += [L.MInstr((f"S:n{i}", f"S:n{i + 16}"), [("M0.0" if i == 7 else f"S:n{i}", 0b1000)])
             for i in range(8)]
    words = encode_unit(prog)
    # a word with one scratch result writes it through port A: area S (10), its index
    assert [(b >> 24 & 15, b & 0x7FF) for b, _ in words[:32]] == [(10, i) for i in range(32)]
    state, mask = L.patterns(["I0.0", "I0.1"])
    assert L.execute(decode_unit(words), state, mask)["M0.0"] == \
        L.execute(prog, state, mask)["M0.0"]


def test_widen():
    assert widen(0b10, 1) == int("10" * 16, 2)
    assert widen(0xFFFF_0000, 5) == 0xFFFF_0000
