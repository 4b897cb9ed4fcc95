#!/usr/bin/env python3
"""The wide bit engine run, not counted (issue 18): clocks per scan of the scalar
reference interpreter and of the wide engine's reference model (bitbyte/wide/model.py:
every compiled unit as its LUT program, dual_s K = 5, one LUT instruction per clock),
serial mode, on the issue's benchmarks; and whether their traces agree (every column
but t_us and cycles, scan-keyed stimuli; programs with timers are not compared, their
transitions depend on time). No RTL: the clocks are the models'.
    python bench/wide_model_bench.py [--no-doc]
Writes the table of docs/wide-engine.md between its markers (`make bench-wide`).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path[:0] = [str(HERE), str(ROOT), str(ROOT / "tests")]
from benchlib import source_rev, splice_section    # noqa: E402
from bit_engine_bench import adder_il              # noqa: E402
from randprog import scan_stimulus                 # noqa: E402
from wide_map_bench import random_programs        # noqa: E402
from bitbyte.lang.parser import parse              # noqa: E402
from bitbyte.lang.stimulus import parse_stimulus   # noqa: E402
from bitbyte.ref.refsim import refsim_trace        # noqa: E402
from bitbyte.wide import model                     # noqa: E402

BEGIN = "<!-- wide-model: bench/wide_model_bench.py -->"
END = "<!-- /wide-model -->"
SCANS = 8
SEED = 1818


def benchmarks() -> list[tuple[str, list[tuple[str, str]], bool]]:
    """(title, [(name, source)], compare the traces?)"""
    ex = ROOT / "examples"
    return [
        ("64-bit ripple-carry adder", [("adder64.il", adder_il())], True),
        ("50 random straight-line (randprog)",
         [(f"rand{k}.il", t) for k, t in enumerate(random_programs(50, True))], True),
        ("50 random, no PI/PQ",
         [(f"randnd{k}.il", t) for k, t in enumerate(random_programs(50, False))], True),
        ("Table-1 program, mixed (serial)",
         [("table1.il", (HERE / "programs" / "table1.il").read_text())], False),
        ("examples/interlock.il", [("interlock.il", (ex / "interlock.il").read_text())], True),
        ("examples/star_delta.il", [("star_delta.il", (ex / "star_delta.il").read_text())],
         False),
    ]


def measure() -> list[dict]:
    rows = []
    for title, sources, comparable in benchmarks():
        progs = [parse(n, t) for n, t in sources]
        compiled = model.compile_programs(progs)
        scalar = wide = unit_il = lut = bit_il = bit_clocks = 0
        mismatching = 0
        for k, (p, c) in enumerate(zip(progs, compiled)):
            st = parse_stimulus(scan_stimulus(SEED + k, SCANS, in_bytes=16))
            _, ref, _ = refsim_trace(p, stimulus=st, scans=SCANS)
            _, rec, _, sim = model.wide_trace(p, c, stimulus=st, scans=SCANS)
            scalar += sum(r.cycles for r in ref)
            wide += sum(r.cycles for r in rec)
            unit_il += sim.unit_il
            lut += sim.lut_clocks
            bit_il += sim.bit_il
            bit_clocks += sim.bit_clocks
            if comparable:
                mismatching += bool(model.compare(p, st, scans=SCANS, compiled=c)[0])
        n = len(progs) * SCANS
        rows.append({"title": title, "programs": len(progs), "scalar": scalar / n,
                     "wide": wide / n, "unit_il": unit_il, "lut": lut,
                     "bit_per_clock": bit_il / bit_clocks if bit_clocks else 0.0,
                     "fallbacks": sum(c.fallbacks for c in compiled),
                     "units": sum(len(c.split.units) for c in compiled),
                     "mismatching": mismatching if comparable else None})
    return rows


def markdown(rows: list[dict]) -> list[str]:
    out = [BEGIN, "", f"Measured by `bench/wide_model_bench.py` at commit `{source_rev()}`: "
           f"{SCANS} scans of each program, serial mode, a row of random pins for every "
           "scan; the scalar reference interpreter against the wide engine's reference "
           "model (dual_s, K = 5, one LUT instruction per clock; cuts and fallback units "
           "one clock per scalar instruction, byte instructions at their cost). *Unit IL "
           "per LUT instruction*: the scalar instructions the executed units stood for, "
           "per LUT instruction executed (dynamic). *Bit IL per clock*: the bit part's IL "
           "instructions executed (in units and scalar; byte, timer and counter "
           "instructions and END not) per clock they took, the figure of the issue's "
           "≥ 2.5 and ≥ 4 (a taken jump's extra clocks included). *Traces*: programs whose trace "
           "(every column but t_us and cycles) differs from the scalar one; not compared "
           "for programs with timers.", "",
           "| benchmark | programs | units (fallback) | clocks/scan scalar | clocks/scan wide | "
           "speed-up | unit IL per LUT instruction | bit IL per clock | traces differing |",
           "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        per = r["unit_il"] / r["lut"] if r["lut"] else 0.0
        out.append(f"| {r['title']} | {r['programs']} | {r['units']} ({r['fallbacks']}) | "
                   f"{r['scalar']:.1f} | {r['wide']:.1f} | {r['scalar'] / r['wide']:.2f} | "
                   f"{per:.2f} | {r['bit_per_clock']:.2f} | "
                   f"{'not compared' if r['mismatching'] is None else r['mismatching']} |")
    return out + ["", END]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-doc", action="store_true", help="print, do not write the doc")
    args = ap.parse_args(argv)
    lines = markdown(measure())
    print("\n".join(lines))
    if not args.no_doc:
        doc = ROOT / "docs" / "wide-engine.md"
        doc.write_text(splice_section(doc.read_text(), lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
