#!/usr/bin/env python3
"""The wide bit engine's instruction format, measured (issue 18, direction (a)): how
many IL bit instructions one LUT instruction replaces on the issue's benchmarks, per LUT
size K and instruction format (bitbyte/wide/lutmap.py), after the stretch rule of
bitbyte/wide/stretch.py.  No RTL: a static count, one LUT instruction per clock.

    python bench/wide_map_bench.py [--quick] [--no-doc]

The programs: the 64-bit ripple-carry adder of bench/bit_engine_bench.py; 50 random
straight-line bit programs from tests/randprog.py's generator (its rungs and edges, no
jumps, no REFRESH; as generated, with direct PI/PQ operands, and without them); the
Table-1 program's bit part (bench/programs/table1.il); examples/interlock.il and
examples/star_delta.il.  Every compiled unit is checked exhaustively against the scalar
semantics and the format's limits (its network itself against the reference
interpreter: every input combination up to 10 inputs, structured and random ones above,
each in a random machine state); a
unit that fails stays scalar and is counted.  Writes the table of docs/wide-engine.md
between its markers.  Not part of `make test` (about a minute: `make bench-wide`).
"""
from __future__ import annotations

import argparse
import random
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path[:0] = [str(HERE), str(ROOT), str(ROOT / "tests"), str(ROOT / "synth")]

import randprog                                   # noqa: E402
from bit_engine_bench import adder_il, fmax_lines  # noqa: E402
from benchlib import progress as bl_progress      # noqa: E402
from benchlib import source_rev, splice_section    # noqa: E402
from bitbyte.compiler.partition import partition  # noqa: E402
from bitbyte.lang.parser import parse             # noqa: E402
from bitbyte.wide import lutmap as L              # noqa: E402
from bitbyte.wide.stretch import split_program    # noqa: E402

BEGIN = "<!-- wide-map: bench/wide_map_bench.py -->"
END = "<!-- /wide-map -->"
KS = (3, 4, 5, 6)
VARIANTS = ("single", "dual", "dual_s", "rlo")
FLOWS = tuple(L.FLOWS)
SEED = 1818
BYTE_SIDE = ("byte", "timer/counter", "end")   # not bit instructions of the count


class StraightGen(randprog.Gen):
    """randprog's generator, its straight-line blocks only: a rung (chain, then one or
    two of `=`/`S`/`R`) or an edge (chain, FP/FN, `=`).  direct=False: no PI/PQ."""

    def __init__(self, rng, direct: bool = True):
        super().__init__(rng)
        self.direct = direct

    def operand(self, areas=randprog.READ_AREAS):
        if not self.direct:
            areas = [a for a in areas if not a.startswith("P")]
        return super().operand(areas)

    def block(self, index, nblocks):
        rng = self.rng
        self.chain(0, full=rng.random() < 0.04)
        if rng.random() < 0.8:
            for _ in range(rng.randrange(1, 3)):
                op = rng.choice(["=", "=", "S", "R"])
                self.lines.append(f"  {op} {self.operand(randprog.WRITE_AREAS)}")
        else:
            mem = randprog._bit(rng, rng.choice(["M", "M", "Q"]))
            self.lines.append(f"  {rng.choice(['FP', 'FN'])} {mem}")
            self.lines.append(f"  = {self.operand(randprog.WRITE_AREAS)}")


def random_programs(n: int, direct: bool) -> list[str]:
    return [StraightGen(random.Random(SEED + k), direct).program() for k in range(n)]


def benchmarks(quick: bool) -> list[tuple[str, list[tuple[str, str]], bool]]:
    """(title, [(name, source)], PI/PQ absorbed into units?)"""
    n = 10 if quick else 50
    ex = ROOT / "examples"
    rand = [(f"rand{k}.il", t) for k, t in enumerate(random_programs(n, True))]
    interlock = [("interlock.il", (ex / "interlock.il").read_text())]
    t1 = (HERE / "programs" / "table1.il").read_text()
    t1p = parse("table1.il", t1)
    return [
        ("64-bit ripple-carry adder", [("adder64.il", adder_il())], False),
        (f"{n} random straight-line (randprog)", rand, False),
        ("the same, PI/PQ absorbed", rand, True),
        (f"{n} random, no PI/PQ",
         [(f"randnd{k}.il", t) for k, t in enumerate(random_programs(n, False))], False),
        ("Table-1 program, mixed (serial: its bit instructions)", [("table1.il", t1)],
         False),
        ("Table-1 parallel bit part (channels)",
         [("table1.bit", partition(t1p).bit_program())], False),
        ("Table-1 parallel bit part (--tc-path status)",
         [("table1.bit", partition(t1p, tc_path="status").bit_program())], False),
        ("examples/interlock.il", interlock, False),
        ("the same, PI/PQ absorbed", interlock, True),
        ("examples/star_delta.il", [("star_delta.il", (ex / "star_delta.il").read_text())],
         False),
    ]


def measure(quick: bool = False) -> list[dict]:
    rows = []
    every = []                                    # all units of all benchmarks
    for title, sources, absorb in benchmarks(quick):
        units, bit_il, scalar_il, stretches, ref_bad = [], 0, 0, 0, 0
        for name, text in sources:
            p = parse(name, text) if isinstance(text, str) else text
            s = split_program(p, absorb_direct=absorb)
            stretches += len(s.stretches)
            cut = sum(len(v) for k, v in s.scalar.items() if k not in BYTE_SIDE)
            bit_il += cut + sum(u.size for u in s.units)
            scalar_il += cut
            ref_bad += sum(not L.check_against_refsim(u, p) for u in s.units)
            units += s.units
        writes = sum(len(u.outputs) for u in units)
        rows.append({"title": title, "programs": len(sources), "bit_il": bit_il,
                     "writes": writes, "unit_il": sum(u.size for u in units),
                     "scalar_il": scalar_il, "stretches": stretches, "units": len(units),
                     "max_inputs": max((len(u.inputs) for u in units), default=0),
                     "ref_bad": ref_bad, "first": len(every), "res": {}})
        every += units
    bl_progress(f"{len(every)} units split and checked against the reference interpreter")
    mapped = {(k, f): L.map_units(every, k, f) for k in range(2, max(KS) + 2)
              for f in FLOWS}
    bl_progress("mapped: LUT sizes 2..7, flows " + ", ".join(FLOWS))
    for r, nxt in zip(rows, rows[1:] + [None]):
        span = range(r["first"], nxt["first"] if nxt else len(every))
        for K in KS:
            for v in VARIANTS:
                sizes = range(2, K + 2) if v == "rlo" else range(2, K + 1)
                lut, fb_units, fb_il, unit_il = 0, 0, 0, 0
                for i in span:
                    u = every[i]
                    cands = sorted((L.PROGRAMS[v](mapped[(k, f)][i], K)
                                    for k in sizes for f in FLOWS), key=len)
                    best = next((c for c in cands if L.check(u, c, K=K, variant=v)), None)
                    if best is None:
                        fb_units += 1
                        fb_il += u.size
                    else:
                        lut += len(best)
                        unit_il += u.size
                r["res"][(K, v)] = {"lut": lut, "fallback_units": fb_units,
                                    "fallback_il": fb_il, "unit_il": unit_il,
                                    "clocks": lut + fb_il + r["scalar_il"]}
        bl_progress(r["title"])
    return rows


def markdown(rows: list[dict]) -> list[str]:
    fmax = fmax_lines().get("ECP5-25")
    L_ = [BEGIN, "", f"Measured by `bench/wide_map_bench.py` at commit `{source_rev()}` "
          f"(Yosys `{L.YOSYS}`, flows {', '.join(f'`{f}`' for f in FLOWS)}, the best "
          "checked program over LUT sizes k ≤ K). *Bit IL*: the IL bit instructions "
          "(jumps, direct and cut instructions included; byte, timer and counter "
          "instructions but a bit part's `= T n`/`= C n`, and END not); *scalar*: those outside every unit (cuts, "
          "parentheses a cut interrupts), one clock each; *units*: compiled units, "
          "their largest input count; *fallback*: units that failed the exhaustive "
          "check (they would run scalar); *written bits*: the units' outputs (bits whose "
          "final value differs from the old one, and the live final RLO), each one write "
          "at least, so *IL per written bit* bounds the IL per LUT instruction of "
          "*single* and *dual_s* (one write to the bit memory, the RLO an ordinary "
          "bit; a *dual_s* scratch write is no written bit), not of *dual* (two "
          "writes) nor of *rlo* (it writes the RLO beside one bit); *bit IL* also "
          "counts a parallel bit part's channel instructions (FBI/FBY), status "
          "waits and `= T n`/`= C n`, scalar; *network ≠ refsim*: units whose network disagreed with the "
          "reference interpreter (every input combination up to 10 inputs, all 0, "
          "all 1, one-hot, one-cold and 32 random ones above; every other image bit, "
          "status, pin and the RLO random; the whole state compared).", "",
          "| benchmark | programs | bit IL | scalar | stretches | units (max inputs) "
          "| written bits | IL per written bit | network ≠ refsim |",
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        L_.append(f"| {r['title']} | {r['programs']} | {r['bit_il']} | {r['scalar_il']} | "
                  f"{r['stretches']} | {r['units']} ({r['max_inputs']}) | {r['writes']} | "
                  f"{r['unit_il'] / max(r['writes'], 1):.2f} | {r['ref_bad']} |")
    for v in VARIANTS:
        L_ += ["", f"**{v}**: LUT instructions, then *IL per LUT instruction* (units "
               "only) / *IL per clock* (the whole bit part, scalar instructions at one "
               "clock), fallback units if any.", "",
               "| benchmark | " + " | ".join(f"K = {K}" for K in KS) + " |",
               "|---|" + "---:|" * len(KS)]
        for r in rows:
            cells = []
            for K in KS:
                x = r["res"][(K, v)]
                ipl = x["unit_il"] / x["lut"] if x["lut"] else 0
                ipc = r["bit_il"] / x["clocks"] if x["clocks"] else 0
                fb = f", {x['fallback_units']} fb" if x["fallback_units"] else ""
                cells.append(f"{x['lut']}: {ipl:.2f} / **{ipc:.2f}**{fb}")
            L_.append(f"| {r['title']} | " + " | ".join(cells) + " |")
    adder = rows[0]
    need = "; ".join(f"{v} " + ", ".join(
        f"{800 * adder['res'][(K, v)]['clocks'] / adder['bit_il']:.0f}" for K in KS)
        for v in VARIANTS)
    L_ += ["", f"The clock the issue's 1.25 ns per IL bit instruction needs on the "
           f"{adder['title']} (800 MHz / IL per clock), K = {', '.join(map(str, KS))}, "
           f"in MHz: {need}."]
    if fmax:
        L_ += ["", f"At today's ECP5-25 Fmax ({float(fmax):g} MHz, docs/synthesis.md) "
               f"1.25 ns per IL bit instruction needs {1000 / float(fmax) / 1.25:.1f} IL "
               "per clock; a wide engine's own Fmax decides."]
    L_ += ["", END]
    return L_


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="10 random programs, not 50")
    ap.add_argument("--no-doc", action="store_true", help="print, do not write the doc")
    args = ap.parse_args(argv)
    rows = measure(args.quick)
    lines = markdown(rows)
    print("\n".join(lines))
    if not args.no_doc:
        doc = ROOT / "docs" / "wide-engine.md"
        doc.write_text(splice_section(doc.read_text() if doc.exists() else "", lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
