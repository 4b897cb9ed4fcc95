#!/usr/bin/env python3
"""Bit-engine throughput (issue 18): IL bit instructions per clock and ns per IL bit
instruction of the bit processor's two engines on the issue's benchmark programs,
beside Siemens' published figures: the scalar engine (one instruction per clock) and
the wide one (`--bit-engine wide`: straight-line stretches compiled into LUT words,
several IL instructions a clock; docs/wide-engine.md).

    python bench/bit_engine_bench.py [--quick]

The programs:
* the 64-bit ripple-carry adder of the issue (the Boolean-throughput idea of the public
  plc_benchmark collection, `add/`, written anew in IL): a = I0.0..I7.7, b =
  I8.0..I15.7, the sum on Q0.0..Q8.0, each bit the plain full adder
  `LD a / X b / A c / O( / LD a / A b / ) / = c1 / LD c / X a / X b / = s / LD c1 / = c`
  (14 instructions, no hand optimisation), the carry c in M0.0, c1 in M0.1;
* random straight-line bit programs of the wide engine's measurement
  (bench/wide_map_bench.py: parentheses, edges, S/R, assignments mid-rung, PI/PQ);
* the interlock and star-delta examples (examples/*.il), and the Table-1 program
  (bench/programs/table1.il: byte instructions and jumps, clocks only).

Each runs through `bitbyte run` (serial mode) on the Verilator harness of each engine;
the clocks per scan come from its trace, the instruction counts from the parser (spec
§3), the clock from docs/synthesis.md's `Fmax` lines (`ECP5-25 (wide)` for the wide
engine). Writes the section of docs/performance.md between its markers.
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
    """`Fmax <part>: <n> MHz` lines of docs/synthesis.md (spec §6; `ECP5-25 (wide)` when a
    full `make synth` has placed the wide build), else of docs/synthesis-wide.md (`make
    synth-wide`)."""
    out: dict[str, Fraction] = {}
    for name in ("synthesis-wide.md", "synthesis.md"):      # the full report wins
        path = bl.ROOT / "docs" / name
        text = path.read_text() if path.exists() else ""
        out.update({m.group(1): Fraction(m.group(2)) for m in re.finditer(
            r"^Fmax ([^:\n]+):\s*([0-9.]+)\s*MHz\s*$", text, re.M) if float(m.group(2)) > 0})
    return out


ENGINES = ("scalar", "wide")
RANDOM = 10            # random straight-line programs


def cases(work: Path, operands) -> list[tuple[str, list[tuple[Path, Path]], str, bool]]:
    """(title, [(program, stimulus)], watch, straight-line?)"""
    sys.path.insert(0, str(bl.ROOT / "tests"))
    from randprog import scan_stimulus
    from wide_map_bench import random_programs
    adder = work / "adder64.il"
    adder.write_text(adder_il())
    stim = work / "adder64.csv"
    stim.write_text(adder_stimulus(operands))
    rand = []
    for k, text in enumerate(random_programs(RANDOM, True)):
        il, st = work / f"rand{k}.il", work / f"rand{k}.csv"
        il.write_text(text)
        st.write_text(scan_stimulus(1818 + k, len(operands), in_bytes=16))
        rand.append((il, st))
    ex = bl.ROOT / "examples"
    t1 = HERE / "programs" / "table1.il"
    t1_stim = work / "table1.csv"
    t1_stim.write_text(scan_stimulus(1818, len(operands), in_bytes=16))
    return [("64-bit ripple-carry adder", [(adder, stim)], adder_watch(), True),
            (f"{RANDOM} random straight-line bit programs", rand, "", True),
            ("examples/interlock.il", [(ex / "interlock.il", ex / "interlock.stim.csv")], "",
             True),
            ("examples/star_delta.il", [(ex / "star_delta.il", ex / "star_delta.stim.csv")],
             "", True),
            ("Table-1 program (serial: byte instructions, jumps)", [(t1, t1_stim)], "", False)]


def measure(quick: bool = False) -> dict:
    from bitbyte.lang.parser import parse_file
    work = bl.BUILD / "bit_engine"
    work.mkdir(parents=True, exist_ok=True)
    rng = random.Random(18)
    scans = 4 if quick else 16
    operands = [(rng.getrandbits(BITS), rng.getrandbits(BITS)) for _ in range(scans)]
    runs = []
    for title, programs, watch, straight in cases(work, operands):
        r = {"title": title, "programs": len(programs), "straight": straight,
             "instructions": 0, "clocks": {e: 0.0 for e in ENGINES}}
        for il, st in programs:
            r["instructions"] += len([i for i in parse_file(str(il)).instrs
                                      if i.mnemonic != "END"])
            for engine in ENGINES:
                trace = work / f"{il.stem}.{engine}.trace.csv"
                run = bl.run_bitbyte(il, clock_mhz=bl.DEFAULT_CLOCK_MHZ, stimulus=st,
                                     scans=scans, trace=trace, watch=watch,
                                     extra=["--bit-engine", engine])
                if run.rc != 0:
                    raise SystemExit(f"bit_engine_bench: bitbyte run {il} --bit-engine "
                                     f"{engine} failed:\n{run.stderr}")
                header, rows = run.header, run.rows
                r["clocks"][engine] += statistics.median(row[header.index("cycles")] for row in rows)
                if watch:       # the adder: its sums on both engines
                    want = [a + b for a, b in operands[:len(rows)]]
                    r.setdefault("sums_ok", True)
                    r["sums_ok"] &= sums_from_trace(header, rows) == want
        runs.append(r)
    return {"runs": runs, "fmax": {k: str(v) for k, v in fmax_lines().items()},
            "rev": bl.source_rev()}


def markdown(res: dict) -> list[str]:
    fmax = {k: Fraction(v) for k, v in res["fmax"].items()}
    clock = {"scalar": fmax.get("ECP5-25"), "wide": fmax.get("ECP5-25 (wide)")}
    hx = fmax.get("HX8K")
    mhz = lambda f: f"{float(f):g} MHz" if f else "no Fmax line"   # noqa: E731
    L = [BEGIN, "", "### Bit-engine throughput (issue 18): the scalar and the wide engine", "",
         f"Measured by `bench/bit_engine_bench.py` at commit `{res['rev']}` on the Verilator "
         "harness of each engine (`bitbyte run --bit-engine scalar|wide`, serial mode; "
         "the wide build runs the program compiled into LUT words, docs/wide-engine.md). "
         "*IL* are the programs' IL instructions without `END`, all executed once a scan "
         "in the straight-line programs; *clocks* the median scan from the trace (`END` "
         "included; summed over a row's programs); *IL / clock* their ratio, the issue's "
         "figure (≥ 4 for the adder, ≥ 2.5 for random straight-line programs); *ns / IL* "
         "at each engine's ECP5-25 clock (`Fmax` lines of docs/synthesis.md, `make synth`: "
         f"scalar {mhz(clock['scalar'])}, the scalar engine on the HX8K {mhz(hx)}; "
         f"docs/synthesis-wide.md, `make synth-wide`: wide {mhz(clock['wide'])}). The star-delta program's timers and the Table-1 program's "
         "byte instructions are dispatched to the byte processor at their cost in both "
         "engines. The adder's sums are checked against a + b for every scan on both "
         "engines (tests/test_bit_engine_bench.py, tests/test_wide_rtl.py).", "",
         "| program | IL | clocks / scan scalar | clocks / scan wide | speed-up | "
         "IL / clock scalar | IL / clock wide | ns / IL scalar | ns / IL wide |",
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in res["runs"]:
        c = r["clocks"]
        cells = [f"{c['scalar']:g}", f"{c['wide']:g}", f"{c['scalar'] / c['wide']:.2f}"]
        if r["straight"]:
            ipc = {e: r["instructions"] / c[e] for e in ENGINES}
            cells += [f"{ipc['scalar']:.2f}", f"{ipc['wide']:.2f}"]
            cells += [f"{1000 / float(clock[e]) / ipc[e]:.2f}" if clock[e] else "–"
                      for e in ENGINES]
        else:
            cells += ["–"] * 4
        L.append(f"| {r['title']} | {r['instructions']} | " + " | ".join(cells) + " |")
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
