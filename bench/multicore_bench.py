"""`make bench-multicore`: seed 000's Table 4 in clocks, and the protections compared.

Runs generated plants (bench/plantgen.py) on the Verilator plant harness and rewrites
the part of docs/multicore.md between the markers `<!-- bench:begin -->` and
`<!-- bench:end -->`, plus docs/multicore_copy.png.

Table 4 load: core a writes N words and reads core b's N words; b reads a's, adds 1,
writes its own (every word read, incremented and written back). The MW area holds
256 words per core, so the symmetric load stops at N = 120 (2 x 120 local copies); the
200-word row is asymmetric (a writes 200 words that b reads; nothing flows back).
Copy times are taken from scans that did not wait for the lock (sem_wait = 0).
"""
from __future__ import annotations

import re
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

import plantgen  # noqa: E402
from bitbyte.plant.run import run_plant  # noqa: E402

DOC = ROOT / "docs" / "multicore.md"
PLOT = ROOT / "docs" / "multicore_copy.png"
SEED_RATIO = "9.0–9.6"      # seed 000 Table 4: random / compact copy time


def _median_nowait(rows, key):
    vals = [int(r[key]) for r in rows if r["sem_wait"] == "0"]
    return _num(statistics.median(vals)) if vals else None


def _num(x):
    """A median as an int when it is whole (medians of an even count may be .5)."""
    return int(x) if x == int(x) else x


def run_case(tmp: Path, words: int, back: int, layout: str, protection="semaphore",
             until_us="3000", quiet_other=True):
    """Medians per core. quiet_other: measure each core in a run of its own where the
    other core scans once (at t = 0) and then idles (a period longer than the run), so
    that the copies measured never meet the other core's (copy times without waits);
    otherwise both run back to back (period 0) and meet."""
    a, b = plantgen.table4_pair(words, back)
    out = {}
    for core in ("a", "b"):
        periods = {"a": 0, "b": 0}
        if quiet_other:
            # idle from the end of scan 0 until just after the run (no long tail)
            periods["b" if core == "a" else "a"] = int(until_us) + 1
        plant = plantgen.write_plant(
            tmp / f"{layout}{words}_{back}_{protection}_{core}{int(quiet_other)}",
            [("a", a, periods["a"]), ("b", b, periods["b"])], layout=layout,
            protection=protection)
        status, summary, rows = run_plant(str(plant), until_us=until_us)
        if status != 0:
            raise SystemExit(summary)
        r = rows[core][1:] if quiet_other else rows[core]   # scan 0 meets the other's
        out[core] = {k: _median_nowait(r, k) if quiet_other
                     else _num(statistics.median(int(x[k]) for x in r))
                     for k in ("pre", "cycles", "post")}
        out[core]["scans"] = len(rows[core])
        out[core]["sem_wait"] = sum(int(x["sem_wait"]) for x in rows[core])
        out[core]["copy_fail"] = rows[core][-1]["copy_fail"] if rows[core] else "0"
    return out


def fit(xs, ys):
    """Least-squares line y = a + b x."""
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return my - b * mx, b


def main() -> int:
    t0 = time.time()
    cases = [(n, n) for n in (25, 50, 100, 120)] + [(200, 0)]
    results = {}
    with tempfile.TemporaryDirectory(prefix="bench-mc-") as tmpdir:
        tmp = Path(tmpdir)
        for layout in ("compact", "random"):
            for words, back in cases:
                print(f"  table 4: {layout:7s} {words:3d}/{back:3d} words", flush=True)
                results[(layout, words, back)] = run_case(tmp, words, back, layout)
        prot = {}
        for protection in ("semaphore", "pingpong", "none"):
            print(f"  protection: {protection}", flush=True)
            prot[protection] = run_case(tmp, 100, 100, "compact", protection,
                                        quiet_other=False)

    L = ["<!-- bench:begin -->",
         f"*Written by `make bench-multicore` (`bench/multicore_bench.py`, "
         f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}); do not edit by hand.*", "",
         "### Table 4 in clocks", "",
         "Seed 000's load: core a writes N words and reads core b's N; b reads a's, adds 1 "
         "and writes its own N (semaphore). Each core is measured back to back (period 0) "
         "while the other idles after its first scan, so the copies measured never wait; "
         "medians of those scans. `pre` / `post` in clocks (the start clock, the lock clock, "
         "the copy; `pre` also the RUN clock), `cycles` the scan itself (spec §7). Row 200: "
         "a writes 200 words that b reads (256 MW words per core do not hold 2 × 200 local "
         "copies).", "",
         "| N | layout | a pre | a cycles | a post | b pre | b cycles | b post |",
         "|---|---|---|---|---|---|---|---|"]
    for words, back in cases:
        for layout in ("compact", "random"):
            r = results[(layout, words, back)]
            label = f"{words}" if back == words else f"{words} → (0 back)"
            L.append(f"| {label} | {layout} | {r['a']['pre']} | {r['a']['cycles']} | "
                     f"{r['a']['post']} | {r['b']['pre']} | {r['b']['cycles']} | "
                     f"{r['b']['post']} |")
    # per-word cost: a's postcycle (N words) against N; b's precycle likewise
    lines = {}
    for layout in ("compact", "random"):
        xs = [w for w, _ in cases]
        post = [results[(layout, w, b)]["a"]["post"] for w, b in cases]
        pre = [results[(layout, w, b)]["b"]["pre"] for w, b in cases]
        lines[layout] = {"post": fit(xs, post), "pre": fit(xs, pre), "xs": xs,
                         "post_y": post, "pre_y": pre}
    cyc_same = all(results[("compact", w, b)][c]["cycles"] == results[("random", w, b)][c]["cycles"]
                   for w, b in cases for c in ("a", "b"))
    ratio_post = lines["random"]["post"][1] / lines["compact"]["post"][1]
    ratio_pre = lines["random"]["pre"][1] / lines["compact"]["pre"][1]
    r200c, r200r = results[("compact", 200, 0)], results[("random", 200, 0)]
    L += ["", "Copy time against size (least-squares line over N = 25 … 200):", "",
          "| copy | layout | clocks = fixed + per word × N | per 32-bit word |",
          "|---|---|---|---|"]
    for layout in ("compact", "random"):
        for kind, label in (("post", "postcycle (a, N words out)"),
                            ("pre", "precycle (b, N words in)")):
            a0, b1 = lines[layout][kind]
            L.append(f"| {label} | {layout} | {a0:.1f} + {b1:.3f} × N | **{b1:.3f}** |")
    L += ["",
          f"* **Cycle column unchanged by the layout: {'yes' if cyc_same else 'NO'}** "
          "(the copies are outside the scan).",
          f"* **Copy time linear in size**: the table above; compact moves one 32-bit word "
          f"per clock (goal ≤ 1 clock per word: "
          f"{'met' if lines['compact']['post'][1] <= 1.0001 and lines['compact']['pre'][1] <= 1.0001 else 'NOT met'}"
          f"), plus a fixed {lines['compact']['post'][0]:.0f} clocks (lock, descriptor, "
          "pipeline fill and drain).",
          f"* **random / compact**: {ratio_post:.2f} (postcycle), {ratio_pre:.2f} (precycle) "
          f"per word; at 200 words {r200r['a']['post'] / r200c['a']['post']:.2f} / "
          f"{r200r['b']['pre'] / r200c['b']['pre']:.2f} (seed 000: {SEED_RATIO}). In the "
          "hardware a single copy costs its descriptor clock plus the item clock, 2 clocks "
          "per variable against 1 in a burst; the seed's software copy paid a function call, "
          "address arithmetic and the HSEM per variable, hence its larger ratio.", "",
          "![copy time against size](multicore_copy.png)", "",
          "### Protections compared (N = 100, compact, both cores back to back)", "",
          "Both cores run back to back (period 0) and their copies meet in every scan; "
          "medians over all scans, waits included.", "",
          "| protection | a pre | a post | b pre | b post | sem_wait a / b [clocks, whole run] | "
          "scans a / b |", "|---|---|---|---|---|---|---|"]
    for p, r in prot.items():
        L.append(f"| {p} | {r['a']['pre']} | {r['a']['post']} | {r['b']['pre']} | "
                 f"{r['b']['post']} | {r['a']['sem_wait']} / {r['b']['sem_wait']} | "
                 f"{r['a']['scans']} / {r['b']['scans']} |")
    L += ["", "Ping-pong needs no lock and never waits; it costs a second buffer per "
          "writer (twice the shared memory) and is tear-free as long as a writer cannot "
          "finish two postcycles while one reader's precycle is still copying (see "
          "*Protection*). `none` is as fast and tears (tests/test_plant_tearing.py).",
          f"", f"Run time of this benchmark: {time.time() - t0:.0f} s.", "<!-- bench:end -->"]

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4))
    for layout, style in (("compact", "o-"), ("random", "s--")):
        ax.plot(lines[layout]["xs"], lines[layout]["post_y"], style, label=f"postcycle, {layout}")
        ax.plot(lines[layout]["xs"], lines[layout]["pre_y"], style, alpha=0.5,
                label=f"precycle, {layout}")
    ax.set_xlabel("shared words copied (N)")
    ax.set_ylabel("copy time [clocks] (µs at 100 MHz × 100)")
    ax.set_title("Copy time of one precycle / postcycle (seed 000 Table 4 load)")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(PLOT, dpi=110)

    text = DOC.read_text()
    block = "\n".join(L)
    if "<!-- bench:begin -->" in text:
        text = re.sub(r"<!-- bench:begin -->.*<!-- bench:end -->", lambda m: block, text,
                      flags=re.S)
    else:
        text = text.rstrip("\n") + "\n\n## Measured (make bench-multicore)\n\n" + block + "\n"
    DOC.write_text(text)
    print(f"wrote {DOC.relative_to(ROOT)} and {PLOT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
