#!/usr/bin/env python3
"""Bit-engine throughput (issue 18): IL bit instructions per clock and ns per IL bit
instruction of the bit processor on the issue's benchmark programs, beside Siemens'
published figures. Today's engine is the scalar one (one instruction per clock); this
is the baseline a wide engine is measured against.

    python bench/bit_engine_bench.py [--quick]

The programs:
* the 64-bit ripple-carry adder of the issue (the Boolean-throughput idea of the public
  plc_benchmark collection, `add/`, written anew in IL): a = I0.0..I7.7, b =
  I8.0..I15.7, the sum on Q0.0..Q8.0, each bit the plain full adder
  `LD a / X b / A c / O( / LD a / A b / ) / = c1 / LD c / X a / X b / = s / LD c1 / = c`
  (14 instructions, no hand optimisation), the carry c in M0.0, c1 in M0.1;
* the interlock and star-delta examples (examples/*.il).

Each runs through `bitbyte run` (serial mode) on the Verilator harness; the clocks per
scan come from its trace, the instruction counts from the parser (spec §3), the clock
from docs/synthesis.md's `Fmax` lines. Writes the section of docs/performance.md
between its markers.
"""
from __future__ import annotations

import argparse
import random
import re
import statistics
import sys
from fractions import Fraction
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))

import benchlib as bl                     # noqa: E402

BEGIN = "<!-- bit-engine: bench/bit_engine_bench.py -->"
END = "<!-- /bit-engine -->"
BITS = 64
CARRY, CARRY1 = "M0.0", "M0.1"
# Published execution times per bit instruction (Siemens technical data sheets).
S7 = (("S7-1518", 1.0), ("S7-1516", 10.0), ("S7-315-2DP", 100.0))


def bit_name(area: str, n: int) -> str:
    return f"{area}{n // 8}.{n % 8}"


def adder_il(bits: int = BITS) -> str:
    """The ripple-carry adder: a = I bits 0..bits-1, b = I bits bits..2*bits-1, the sum
    on Q bits 0..bits (the last is the carry out)."""
    lines = [f"// {bits}-bit ripple-carry adder (issue 18): a = I0.0.., b = "
             f"{bit_name('I', bits)}.., sum Q0.0..{bit_name('Q', bits)}",
             "CLR", f"= {CARRY}"]
    for i in range(bits):
        a, b, s = bit_name("I", i), bit_name("I", bits + i), bit_name("Q", i)
        lines += [f"LD {a}", f"X {b}", f"A {CARRY}", "O(", f"LD {a}", f"A {b}", ")",
                  f"= {CARRY1}", f"LD {CARRY}", f"X {a}", f"X {b}", f"= {s}",
                  f"LD {CARRY1}", f"= {CARRY}"]
    lines += [f"LD {CARRY}", f"= {bit_name('Q', bits)}"]
    return "\n".join(lines) + "\n"


def adder_stimulus(operands: list[tuple[int, int]], bits: int = BITS) -> str:
    """One scan per operand pair: the I bits of a and b."""
    cols = [bit_name("I", n) for n in range(2 * bits)]
    rows = ["scan," + ",".join(cols)]
    for k, (a, b) in enumerate(operands):
        v = a | b << bits
        rows.append(f"{k}," + ",".join(str(v >> n & 1) for n in range(2 * bits)))
    return "\n".join(rows) + "\n"


def adder_watch(bits: int = BITS) -> str:
    return ",".join(bit_name("Q", n) for n in range(bits + 1))


def sums_from_trace(header: list[str], rows: list[list[int]], bits: int = BITS) -> list[int]:
    """The sum each scan left on Q0.0..Q<bits>, read from the trace's columns."""
    at = [header.index(bit_name("Q", n)) for n in range(bits + 1)]
    return [sum(row[c] << n for n, c in enumerate(at)) for row in rows]


def fmax_lines() -> dict[str, Fraction]:
    """`Fmax <part>: <n> MHz` lines of docs/synthesis.md (spec §6)."""
    path = bl.ROOT / "docs" / "synthesis.md"
    text = path.read_text() if path.exists() else ""
    return {m.group(1): Fraction(m.group(2))
            for m in re.finditer(r"^Fmax (\S+):\s*([0-9.]+)\s*MHz\s*$", text, re.M)}


def measure(quick: bool = False) -> dict:
    from bitbyte.lang.parser import parse_file
    work = bl.BUILD / "bit_engine"
    work.mkdir(parents=True, exist_ok=True)
    rng = random.Random(18)
    scans = 4 if quick else 16
    adder = work / "adder64.il"
    adder.write_text(adder_il())
    stim = work / "adder64.csv"
    operands = [(rng.getrandbits(BITS), rng.getrandbits(BITS)) for _ in range(scans)]
    stim.write_text(adder_stimulus(operands))
    cases = [("64-bit ripple-carry adder", adder, stim, adder_watch())]
    for name in ("interlock", "star_delta"):
        il = bl.ROOT / "examples" / f"{name}.il"
        cases.append((f"examples/{name}.il", il, il.with_suffix(".stim.csv"), ""))
    runs = []
    for title, il, st, watch in cases:
        trace = work / f"{il.stem}.trace.csv"
        run = bl.run_bitbyte(il, clock_mhz=bl.DEFAULT_CLOCK_MHZ, stimulus=st,
                             scans=scans, trace=trace, watch=watch)
        if run.rc != 0:
            raise SystemExit(f"bit_engine_bench: bitbyte run {il} failed:\n{run.stderr}")
        header, rows = run.header, run.rows
        cycles = [r[header.index("cycles")] for r in rows]
        instrs = [i for i in parse_file(str(il)).instrs if i.mnemonic != "END"]
        r = {"title": title, "instructions": len(instrs),
             "clocks": statistics.median(cycles), "scans": len(rows)}
        if il == adder:
            want = [a + b for a, b in operands[:len(rows)]]
            r["sums_ok"] = sums_from_trace(header, rows) == want
        runs.append(r)
    return {"runs": runs, "fmax": {k: str(v) for k, v in fmax_lines().items()}}


def markdown(res: dict) -> list[str]:
    fmax = {k: Fraction(v) for k, v in res["fmax"].items()}
    parts = [p for p in ("HX8K", "ECP5-25") if p in fmax]
    L = [BEGIN, "", "### Bit-engine throughput (issue 18): the scalar engine's baseline", "",
         "IL bit instructions per clock and ns per IL bit instruction at the `make synth` "
         "clock (`Fmax` lines of docs/synthesis.md), serial mode, programs without jumps "
         "(bench/bit_engine_bench.py). *Instructions* are the program's IL instructions "
         "without `END`; *clocks* the median scan from the trace (`END` included; the "
         "star-delta program's timers are byte instructions, dispatched in serial mode, "
         "which is why it runs slower than one per clock). The 64-bit adder's sums are checked against a + b for every scan "
         "(tests/test_bit_engine_bench.py). The scalar engine executes one instruction "
         "per clock, so its figure is the clock period; a wide engine (issue 18: ≥ 4 "
         "per clock, ≤ 1.25 ns on ECP5-25) is measured against it here.", "",
         "| program | instructions | clocks / scan | instr. / clock | "
         + " | ".join(f"ns / instr. at {p} {float(fmax[p]):g} MHz" for p in parts) + " |",
         "|---|---:|---:|---:|" + "---:|" * len(parts)]
    for r in res["runs"]:
        ipc = r["instructions"] / r["clocks"]
        ns = [f"{1000 / float(fmax[p]) / ipc:.1f}" for p in parts]
        L.append(f"| {r['title']} | {r['instructions']} | {r['clocks']:g} | {ipc:.2f} | "
                 + " | ".join(ns) + " |")
    L += ["", "Published, per bit instruction: " + ", ".join(
        f"{name} {ns:g} ns" for name, ns in S7) + " (Siemens technical data).", "", END]
    return L


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="4 scans instead of 16")
    args = ap.parse_args(argv)
    res = measure(args.quick)
    if not all(r.get("sums_ok", True) for r in res["runs"]):
        print("bit_engine_bench: the adder's sums differ from a + b", file=sys.stderr)
        return 1
    doc = bl.ROOT / "docs" / "performance.md"
    doc.write_text(bl.splice_section(doc.read_text(), markdown(res)))
    bl.progress("docs/performance.md: the bit-engine section rewritten")
    return 0


if __name__ == "__main__":
    sys.exit(main())
