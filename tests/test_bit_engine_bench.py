"""The 64-bit ripple-carry adder of issue 18 (bench/bit_engine_bench.py) on the hardware:
its sums, read from the trace's Q columns, equal the integer a + b of the operands the
stimulus drove — an independent check of the benchmark program and of the engine
running it; a broken adder (one XOR negated) is caught. The scan length is one clock
per instruction, END included (spec §5: straight-line bit code at CPI 1)."""
from __future__ import annotations

import random
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))

import bit_engine_bench as beb                      # noqa: E402
from bitbyte import cli                              # noqa: E402
from bitbyte.lang.parser import parse                 # noqa: E402

SCANS = 6


def run_adder(tmp_path: Path, text: str, operands, sim: str = "verilator"):
    il = tmp_path / "adder.il"
    il.write_text(text)
    st = tmp_path / "adder.csv"
    st.write_text(beb.adder_stimulus(operands))
    trace = tmp_path / "adder.trace.csv"
    assert cli.main(["run", str(il), "--stimulus", str(st), "--scans", str(len(operands)),
                     "--sim", sim, "--trace", str(trace), "--watch", beb.adder_watch()]) == 0
    lines = trace.read_text().splitlines()
    header = lines[0].split(",")
    rows = [[int(v) if "." not in v else 0 for v in line.split(",")] for line in lines[1:]]
    return header, rows


def operands(seed: int):
    rng = random.Random(seed)
    pairs = [(2**64 - 1, 1), (0, 0), (2**63, 2**63)]       # carry through all, none, out
    return pairs + [(rng.getrandbits(64), rng.getrandbits(64))
                    for _ in range(SCANS - len(pairs))]


def test_adder_program_shape():
    """14 instructions per bit as the issue writes them, plus CLR / = c before and
    LD c / = Q8.0 after: 900 IL instructions."""
    program = parse("adder.il", beb.adder_il())
    body = [i for i in program.instrs if i.mnemonic != "END"]
    assert len(body) == 64 * 14 + 4


def test_adder_sums_on_the_harness(tmp_path):
    ops = operands(18)
    header, rows = run_adder(tmp_path, beb.adder_il(), ops)
    assert beb.sums_from_trace(header, rows) == [a + b for a, b in ops]
    # one clock per instruction, END included (spec §5)
    assert {r[header.index("cycles")] for r in rows} == {64 * 14 + 4 + 1}


def test_a_broken_adder_is_caught(tmp_path):
    """The same check on an adder whose bit-40 sum uses XN instead of X: some sum
    differs (the check can fail)."""
    text = beb.adder_il()
    lines = text.splitlines()
    k = lines.index("X I13.0", lines.index("LD M0.0", 3 + 40 * 14))   # bit 40's sum
    lines[k] = "XN I13.0"
    ops = operands(18)
    header, rows = run_adder(tmp_path, "\n".join(lines) + "\n", ops)
    assert beb.sums_from_trace(header, rows) != [a + b for a, b in ops]
