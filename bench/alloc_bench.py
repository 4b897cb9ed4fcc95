#!/usr/bin/env python3
"""`make bench-alloc`: task allocation (issue 10, seed 002) -> docs/allocation.md.

    python bench/alloc_bench.py [--seeds 20] [--instances 1000] [--quick]

Everything goes through bitbyte.alloc (the code behind `bitbyte alloc`); the optimum
of the small instances is cross-checked with HiGHS.  Writes docs/allocation.md and
docs/alloc_*.png from scratch; deterministic apart from the run times.
"""
from __future__ import annotations

import argparse
import math
import random
import statistics
import sys
import time
from collections import Counter
from dataclasses import replace
from fractions import Fraction
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

from bitbyte import alloc as al            # noqa: E402

DOCS = ROOT / "docs"
PERIODS = al.BECKER_PERIODS_MS
PAPER = {10: 6, 20: 4, 100: 3, 200: 3}     # seed 002 §V-B
SCALES = ["1", "0.5", "0.4", "0.35", "1/3", "0.3", "0.25", "0.2", "0.1"]
UNLIMITED = 1000                           # cores, to see what a group needs


# ------------------------------------------------------------------ experiments

def per_sct(a: al.Allocation) -> dict[int, int]:
    got = {int(g.period): g.cores for g in a.groups}
    return {p: got.get(p, 0) for p in PERIODS}


def seed_case(seeds: int) -> dict:
    """Table I as printed, 800 networks: cores per SCT (ffd, best, bounds) and the
    outcome on the seed's 16 cores."""
    rows = []
    for s in range(1, seeds + 1):
        tasks = al.generate_becker2015(800, s)
        inst = al._Instance(tasks, al.Platform(UNLIMITED))
        row = {"seed": s, "n": {p: len(inst.groups.get(Fraction(p), [])) for p in PERIODS},
               "sum_u": {p: float(sum(inst.load[i] for i in inst.groups[Fraction(p)])
                                  / inst.cap(Fraction(p))) for p in PERIODS},
               "sum_mem": {p: sum(inst.mem[i] for i in inst.groups[Fraction(p)])
                           for p in PERIODS},
               "bound": {p: inst.group_bound(Fraction(p)) for p in PERIODS}}
        for alg in al.ALGORITHMS:
            t0 = time.perf_counter()
            a = al.allocate(tasks, al.Platform(UNLIMITED), alg)
            row[f"{alg}_s"] = time.perf_counter() - t0
            row[alg] = per_sct(a)
            row[f"{alg}_optimal"] = {int(g.period): g.optimal for g in a.groups}
            row[f"{alg}_lb"] = a.lower_bound
            b16 = al.allocate(tasks, al.Platform(al.BECKER_CORES), alg)
            row[f"{alg}_16"] = (b16.ok, len(b16.unassigned), per_sct(b16))
        rows.append(row)
    return {"rows": rows}


def seed_mean_load() -> dict:
    """What Table I says a network costs, on average (ms)."""
    exec_ms = (al.BECKER_EXEC_US[0] + al.BECKER_EXEC_US[1]) / 2 / 1000
    io = (al.BECKER_IO_BYTES[0] + al.BECKER_IO_BYTES[1]) / 2
    load = exec_ms + 2 * io * float(al.ALPHA_MS)
    # spread of one network's load (uniform draws) and of a group's sum: the group
    # size is binomial(800, 1/4) too, Var(sum) = E[N] Var(X) + Var(N) E[X]^2
    var_exec = ((al.BECKER_EXEC_US[1] - al.BECKER_EXEC_US[0] + 1) ** 2 - 1) / 12 / 1e6
    var_io = ((al.BECKER_IO_BYTES[1] - al.BECKER_IO_BYTES[0] + 1) ** 2 - 1) / 12 \
        * 2 * float(al.ALPHA_MS) ** 2
    var_x = var_exec + var_io
    sd_sum = math.sqrt(200 * var_x + 800 * 0.25 * 0.75 * load ** 2)
    return {"exec": exec_ms, "io_bytes": io, "io_ms": 2 * io * float(al.ALPHA_MS),
            "load": load, "mem": 2 * io, "sd_sum": sd_sum}


def scale_sweep(seeds: int) -> list[dict]:
    """Execution times scaled by s (everything else as in Table I): which per-SCT
    core counts ffd gives, how often the paper's 6/4/3/3 comes out."""
    base = {s: al.generate_becker2015(800, s) for s in range(1, seeds + 1)}
    out = []
    for text in SCALES:
        scale = Fraction(text)
        counts = Counter()
        fits = 0
        for tasks in base.values():
            scaled = [replace(t, wcet_ms=t.wcet_ms * scale) for t in tasks]
            a = al.allocate(scaled, al.Platform(UNLIMITED), "ffd")
            c = per_sct(a)
            counts[tuple(c[p] for p in PERIODS)] += 1
            fits += a.cores_used <= al.BECKER_CORES
        out.append({"scale": text, "counts": counts, "paper": counts[tuple(PAPER.values())],
                    "fits16": fits, "seeds": len(base)})
    return out


def seed_as_printed(tasks: list[al.Task], cores: int, mem: int = al.DEFAULT_MEM):
    """Algorithms 1 and 2 exactly as printed (utilization and memory checks of Eq. 2,
    AssignSCT returning the empty set on failure).  Returns ("success" | "error",
    networks never assigned)."""
    p = al.Platform(cores, mem)
    inst = al._Instance(tasks, p)
    free = list(range(cores))
    left = sorted(range(len(tasks)), key=lambda i: tasks[i].period_ms)
    lost = []
    while left:
        if not free:
            return "error", lost + left
        low = min(tasks[i].period_ms for i in left)
        group = [i for i in left if tasks[i].period_ms == low]
        left = [i for i in left if tasks[i].period_ms != low]
        cap = inst.cap(low)
        queue = sorted(group, key=lambda i: (-inst.wcet[i], i))
        load = {c: 0 for c in free}
        used = {c: 0 for c in free}
        i = i_max = 0
        result = None
        while queue:
            t = queue[0]
            while cap - load[free[i]] < inst.load[t] or used[free[i]] + inst.mem[t] > mem:
                i += 1
                if i >= len(free):
                    result = []               # line 10: return the empty set
                    lost += queue             # ... and these networks are forgotten
                    break
                i_max = max(i_max, i)
            if result is not None:
                break
            load[free[i]] += inst.load[t]
            used[free[i]] += inst.mem[t]
            queue.pop(0)
            i = 0
        free = result if result is not None else free[i_max + 1:]
    return "success", lost


def errata_demo() -> dict:
    """Give the seed's algorithm one core less than the last group needs."""
    tasks = al.generate_becker2015(800, 1)
    need = al.allocate(tasks, al.Platform(UNLIMITED), "ffd").cores_used
    cores = need - 1
    verdict, lost = seed_as_printed(tasks, cores)
    fixed = al.allocate(tasks, al.Platform(cores), "ffd")
    verdict_ok, _ = seed_as_printed(tasks, need)
    return {"need": need, "cores": cores, "printed": verdict, "lost": len(lost),
            "lost_periods": sorted({int(tasks[i].period_ms) for i in lost}),
            "fixed_ok": fixed.ok, "fixed_unassigned": len(fixed.unassigned),
            "printed_at_need": verdict_ok}


def hard_tasks(rng: random.Random, n: int) -> list[al.Task]:
    """One 10 ms period, load and memory each 10 .. 60 % of a core."""
    return [al.Task(f"t{i}", Fraction(10), Fraction(rng.randint(100, 600), 100), 0, 0,
                    rng.randint(400, 2400)) for i in range(n)]


def _mean_cores(row: dict, instances) -> None:
    """Append to row[key] the mean over `instances` of each algorithm's cores, the
    lower bound and the sum of the per-period bounds."""
    acc = {key: [] for key in row}
    for tasks in instances:
        for alg in al.ALGORITHMS:
            a = al.allocate(tasks, al.Platform(UNLIMITED), alg)
            acc[alg].append(a.cores_used)
        acc["lower_bound"].append(a.lower_bound)
        acc["bound"].append(sum(g.bound for g in a.groups))
    for key, v in acc.items():
        row[key].append(statistics.mean(v))


def cores_vs_networks(seeds: int) -> dict:
    ks = list(range(50, 801, 50))
    out = {"k": ks, "becker": {}, "hard_n": [10, 20, 40, 80, 120, 160, 200], "hard": {}}
    for key in ("ffd", "best", "lower_bound", "bound"):
        out["becker"][key] = []
        out["hard"][key] = []
    for k in ks:
        _mean_cores(out["becker"], [al.generate_becker2015(k, s) for s in range(1, seeds + 1)])
    rng = random.Random(2015)
    for n in out["hard_n"]:
        _mean_cores(out["hard"], [hard_tasks(rng, n) for _ in range(seeds)])
    return out


def highs_min_cores(items, cap, mcap, ub) -> int:
    """MILP: x_ib task i on core b < ub, y_b core b used, min sum y (HiGHS)."""
    import highspy
    h = highspy.Highs()
    h.setOptionValue("output_flag", False)
    h.setOptionValue("threads", 1)
    n = len(items)
    kind = highspy.HighsVarType.kInteger
    x = [[h.addVariable(0, 1, type=kind) for _ in range(ub)] for _ in range(n)]
    y = [h.addVariable(0, 1, obj=1, type=kind) for _ in range(ub)]
    for i in range(n):
        h.addConstr(sum(x[i][b] for b in range(ub)) == 1)
    for b in range(ub):
        h.addConstr(sum(items[i][0] * x[i][b] for i in range(n)) - cap * y[b] <= 0)
        h.addConstr(sum(items[i][1] * x[i][b] for i in range(n)) - mcap * y[b] <= 0)
        if b:
            h.addConstr(y[b - 1] - y[b] >= 0)
    h.minimize()
    assert h.getModelStatus() == highspy.HighsModelStatus.kOptimal
    return round(h.getInfo().objective_function_value)


def gap_study(instances: int) -> dict:
    """Small instances: ffd and best against the proved optimum (exact search with a
    large budget), each group's optimum checked with HiGHS."""
    try:
        import highspy  # noqa: F401
        have_highs = True
    except ImportError:
        have_highs = False
    families = {}
    for family in ("becker", "hard"):
        rng = random.Random({"becker": 1, "hard": 2}[family])
        gaps = {"ffd": Counter(), "heuristics": Counter(), "best": Counter()}
        checked = agree = unproved = 0
        sizes = []
        for _ in range(instances):
            if family == "becker":
                tasks = al.generate_becker2015(rng.randint(8, 60), rng.randrange(10 ** 6))
                # shrink the memory so that both dimensions matter in small instances
                p = al.Platform(UNLIMITED, rng.choice([256, 512, 1024, 4096]))
            else:
                tasks = hard_tasks(rng, rng.randint(4, 16))
                p = al.Platform(UNLIMITED)
            sizes.append(len(tasks))
            inst = al._Instance(tasks, p)
            opt = heur = 0
            for per, idx in inst.groups.items():
                heur += len(al.best_group(inst, per, exact=False)[0])
                bins, proved = al.best_group(inst, per, budget=2_000_000)
                unproved += not proved
                opt += len(bins)
                if have_highs and len(idx) <= 20:
                    items = [(inst.load[i], inst.mem[i]) for i in idx]
                    checked += 1
                    agree += highs_min_cores(items, inst.cap(per), p.mem, len(bins)) == \
                        len(bins)
            for alg in al.ALGORITHMS:
                gaps[alg][al.allocate(tasks, p, alg).cores_used - opt] += 1
            gaps["heuristics"][heur - opt] += 1
        families[family] = {"gaps": gaps, "checked": checked, "agree": agree,
                            "unproved": unproved, "sizes": (min(sizes), max(sizes)),
                            "instances": instances}
    return {"families": families, "highs": have_highs}


def emitted_plant(tmp: Path) -> dict:
    """Table I with execution times / 3 fits the seed's 16 cores: emit it (10 MHz) and
    run every core's program alone in the reference interpreter; then emit two of its
    cores (the fullest 10 ms and the fullest 200 ms one, 1 MHz) as a plant and run it
    on the multi-core system (`bitbyte run PLANT.toml`, the Verilator plant harness)."""
    import csv
    import subprocess
    from bitbyte.lang.parser import parse_file
    from bitbyte.ref.refsim import RefSim
    tasks = [replace(t, wcet_ms=t.wcet_ms / 3) for t in al.generate_becker2015(800, 1)]
    a = al.allocate(tasks, al.Platform(al.BECKER_CORES))
    assert a.ok
    mhz = 10
    plant = tmp / "all" / "plant.toml"
    al.emit_plant(a, str(plant), Fraction(mhz))
    rows = []
    for c in a.cores:
        prog = parse_file(str(plant.parent / f"plant_core{c.index}.il"))
        (scan,) = RefSim(prog, watchdog=10 ** 9).run(scans=1)
        budget = int(c.sct_ms * mhz * 1000)          # clocks per SCT
        rows.append({"core": c.index, "sct": int(c.sct_ms), "u": float(c.u),
                     "clocks": scan.cycles, "words": len(prog.instrs),
                     "measured": scan.cycles / budget, "within": scan.cycles <= budget})
    # two cores on the plant harness
    pick = [max((c for c in a.cores if c.sct_ms == p), key=lambda c: c.u) for p in (10, 200)]
    two = replace(a, cores=[al.Core(k, c.sct_ms, c.tasks, c.p) for k, c in enumerate(pick)])
    plant2 = tmp / "two" / "plant.toml"
    al.emit_plant(two, str(plant2), Fraction(1))
    until = 1_000_000
    exe = ROOT / ".venv" / "bin" / "bitbyte"
    proc = subprocess.run([str(exe) if exe.exists() else "bitbyte", "run", str(plant2),
                           "--until-us", str(until), "--trace", str(tmp / "T.csv")],
                          capture_output=True, text=True)
    run = {"ok": proc.returncode == 0, "error": (proc.stderr.strip().splitlines() or [""])[0],
           "until": until, "cores": []}
    if run["ok"]:
        for k, c in enumerate(two.cores):
            with open(tmp / f"T.core{k}.csv") as f:
                scans = [{key: int(v) for key, v in r.items() if key in (
                    "scan", "cycles", "pre", "post", "overrun")} for r in csv.DictReader(f)]
            period = int(c.sct_ms * 1000)             # 1 MHz: clocks = µs
            busy = [r["pre"] + r["cycles"] + r["post"] for r in scans]
            run["cores"].append({
                "name": f"core{k}", "from": pick[k].index, "sct": int(c.sct_ms),
                "u": float(c.u), "scans": len(scans), "busy_max": max(busy),
                "period": period, "measured": statistics.mean(busy) / period,
                "pre": max(r["pre"] for r in scans), "post": max(r["post"] for r in scans),
                "overruns": sum(r["overrun"] for r in scans)})
    return {"rows": rows, "alloc": a, "mhz": mhz, "run": run}


# ------------------------------------------------------------------ plots

def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({"font.size": 9, "axes.grid": True, "grid.alpha": 0.3,
                         "savefig.dpi": 120, "savefig.bbox": "tight"})
    return plt


COLORS = {10: "tab:blue", 20: "tab:orange", 100: "tab:green", 200: "tab:red"}


def plot_fig4(a: al.Allocation, path: Path, title: str) -> None:
    """Per core: U stacked read / execute / write, and memory use (seed Fig. 4);
    right: the averages per SCT."""
    plt = _plt()
    fig, (ax, ay) = plt.subplots(1, 2, figsize=(12, 4),
                                 gridspec_kw={"width_ratios": [3, 1.2]})
    xs = range(len(a.cores))
    r = [float(c.u_read) for c in a.cores]
    e = [float(c.u_exec) for c in a.cores]
    w = [float(c.u_write) for c in a.cores]
    m = [c.mem_bytes / a.platform.mem for c in a.cores]
    cols = [COLORS[int(c.sct_ms)] for c in a.cores]
    ax.bar([x - 0.2 for x in xs], e, 0.4, color=cols, label="execute")
    ax.bar([x - 0.2 for x in xs], r, 0.4, bottom=e, color="black", label="read")
    ax.bar([x - 0.2 for x in xs], w, 0.4, bottom=[i + j for i, j in zip(e, r)],
           color="grey", label="write")
    ax.bar([x + 0.2 for x in xs], m, 0.4, color=cols, alpha=0.35, hatch="//",
           edgecolor="k", label="memory / --mem")
    ax.set_xticks(list(xs))
    ax.set_xticklabels([f"{c.index}\n{_ms(c.sct_ms)}" for c in a.cores], fontsize=7)
    ax.set_ylim(0, 1.05)
    ax.set_ylabel("fraction of the core")
    ax.set_xlabel("core and its SCT [ms]; left bar: U (colour: execute, black: read, "
                  "grey: write), right bar: memory")
    fig.suptitle(title)
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), fontsize=7, ncols=4,
              frameon=False)
    pers = sorted({int(c.sct_ms) for c in a.cores})
    for k, per in enumerate(pers):
        cs = [c for c in a.cores if int(c.sct_ms) == per]
        ay.bar(k - 0.2, statistics.mean(float(c.u) for c in cs), 0.4, color=COLORS[per])
        ay.bar(k + 0.2, statistics.mean(c.mem_bytes / a.platform.mem for c in cs), 0.4,
               color=COLORS[per], alpha=0.35, hatch="//", edgecolor="k")
    ay.set_xticks(range(len(pers)))
    ay.set_xticklabels([f"{p} ms\n{sum(int(c.sct_ms) == p for c in a.cores)} cores"
                        for p in pers], fontsize=7)
    ay.set_ylim(0, 1.05)
    ay.set_title("average per SCT: U (left), memory (right)", fontsize=8)
    fig.savefig(path)
    plt.close(fig)


def plot_cores(cv: dict, path: Path) -> None:
    plt = _plt()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.6))
    styles = {"ffd": ("tab:red", "o-"), "best": ("tab:blue", "s-"),
              "bound": ("k", "--"), "lower_bound": ("grey", ":")}
    names = {"ffd": "ffd (seed Alg. 1/2)", "best": "best",
             "bound": "bound with memory", "lower_bound": "Σ ⌈Σ U⌉ (spec)"}
    for ax, key, xs, title in ((a1, "becker", cv["k"], "Table I workload (4 SCTs)"),
                               (a2, "hard", cv["hard_n"],
                                "one SCT, load and memory 10–60 % each")):
        for alg, ys in cv[key].items():
            color, st = styles[alg]
            ax.plot(xs, ys, st, color=color, label=names[alg], ms=3)
        ax.set_xlabel("networks (tasks)")
        ax.set_ylabel("cores used (mean)")
        ax.set_title(title)
        ax.legend(fontsize=7)
    a1.axhline(al.BECKER_CORES, color="tab:green", lw=0.8)
    a1.text(60, al.BECKER_CORES + 0.5, "16 cores (the seed's platform)", fontsize=7,
            color="tab:green")
    fig.savefig(path)
    plt.close(fig)


def plot_gap(gs: dict, path: Path) -> None:
    plt = _plt()
    fams = gs["families"]
    fig, axes = plt.subplots(1, len(fams), figsize=(9, 3.2))
    for ax, (fam, d) in zip(axes, fams.items()):
        top = max(max(c) for c in d["gaps"].values())
        xs = list(range(top + 1))
        for k, (alg, color) in enumerate((("ffd", "tab:red"), ("heuristics", "tab:orange"),
                                          ("best", "tab:blue"))):
            ax.bar([x + (k - 1) * 0.27 for x in xs], [d["gaps"][alg][x] for x in xs], 0.27,
                   color=color, label={"heuristics": "best without the exact step"}
                   .get(alg, alg))
        ax.set_xticks(xs)
        ax.set_xlabel("cores above the optimum")
        ax.set_ylabel("instances")
        ax.set_title({"becker": "Table I tasks, 8–60, --mem 256–4096",
                      "hard": "one SCT, 4–16 tasks, 10–60 %"}[fam], fontsize=9)
        ax.legend(fontsize=7)
    fig.savefig(path)
    plt.close(fig)


# ------------------------------------------------------------------ the report

def _ms(x) -> str:
    return al._f(Fraction(x))


def _counts(c: dict) -> str:
    return " / ".join(str(c[p]) for p in PERIODS)


def report(R: dict, args) -> str:
    ml = R["mean_load"]
    sc = R["seed_case"]["rows"]
    first = sc[0]
    out = []
    w = out.append
    w("# Allocating tasks to cores (`bitbyte alloc`)\n")
    w("Spec §8, issue 10, seed 002 (Becker et al., *A Many-Core based Execution "
      "Framework for IEC 61131-3*). Code: `bitbyte/alloc.py`; command: `bitbyte alloc`; "
      "tests: `tests/test_alloc.py`; this page and `docs/alloc_*.png` are written by "
      "`make bench-alloc` (`bench/alloc_bench.py`, also part of `make bench`).\n")
    w("```\nbitbyte alloc TASKS.csv --cores N [--mem BYTES] [--alpha MS_PER_BYTE] "
      "[--beta MS_PER_BYTE]\n              [--algorithm ffd|best] [--clock-mhz F] "
      "[--mode serial|parallel]\n              [--json OUT.json] [--emit PLANT.toml]\n"
      "bitbyte alloc --generate becker2015 --networks K --seed S [--save-tasks T.csv] "
      "[same options]\n```\n")
    w("""## Model

A task is one of the seed's serialized FBD networks: a period (its scan cycle time,
SCT), a WCET, the bytes it reads before and writes after executing, and the local
memory those take. A core runs the tasks of **one** period only: per scan one read
phase, all the executes, one write phase. Its utilization is seed 002 Eq. 2,

    U = (α · Σ read_bytes + Σ wcet_ms + β · Σ write_bytes) / SCT  ≤ 1,

and Σ mem_bytes ≤ `--mem`. The seed prints its condition (1) the wrong way round
(`SCT ≤ T_R + T_E + T_W`); the condition used is T_R + T_E + T_W ≤ SCT. Defaults as in
the seed's §V: α = β = 0.001145 ms per byte (1.145 µs), `--mem 4096` (the 4 kB of a
core's 16 kB kept for I/O data).

All arithmetic is exact: times are read as decimals into fractions, and one instance
is scaled to integers (the least common denominator of its loads and periods), so a
core at U = 1 exactly fits and no rounding decides anything.

Because cores never mix periods, the periods are independent two-dimensional
bin-packing problems (load against the SCT, memory against `--mem`) that only share
the number of cores.

## Task files

```
# comment lines and blank lines are skipped
name,period_ms,wcet_ms,read_bytes,write_bytes,mem_bytes,program
valve,10,0.35,12,4,,
mixer,20,,8,8,64,mixer.il
```

The first five columns are required, in this order; `mem_bytes` (default read_bytes +
write_bytes) and `program` may follow. Times are plain non-negative decimals, byte
counts whole numbers, the period positive; names unique. A `program` is relative to
the task file; when `wcet_ms` is empty the WCET is its scan time at `--clock-mhz`
(default 100):

* `--mode serial` (default): the serial straight line of docs/isa.md, Σ bit + Σ
  word costs + 1 (END) clocks with the default (paper) cost table, jumps not taken
  (`bitbyte.lang.costs.serial_cost` + 1: the Fig. 5 program takes 60 clocks);
* `--mode parallel`: the partitioning compiler's estimate, max(byte part + bit tail,
  bit part) (`bitbyte.compiler.estimate`, the figure `bitbyte asm --mode parallel`
  reports).

Every bad input is `file:line:col: message` with the line and a caret, exit 1, never a
traceback: a bad header (at the wrong column), a bad or negative number, an empty or
zero period, too many or too few values, a duplicate or empty name, a missing program
file (at its cell), an error in the program (at the program's own line), and a task
that fits no empty core: U > 1 on its own (at `wcet_ms`, or at `program` when the
WCET came from it) or more memory than `--mem` (at `mem_bytes`, or at `read_bytes`
when the memory is the default). Command-line mistakes are exit 2.

## Output

A table, one row per core: its number (from 0), SCT, tasks, U and its read /
execute / write parts, memory; the task names under the row; then per period the
cores used against ⌈Σ U⌉ and against the stronger bound below, and whether the count
is proved optimal. `--json` writes exactly spec §8's object (`cores_used`,
`lower_bound`, `unassigned`, `cores` with `core`, `sct_ms`, `tasks`, `u`, `u_read`,
`u_exec`, `u_write`, `mem_bytes`); task names are listed in file order. Exit 0 when
every task is placed within `--cores`; otherwise exit **5** with the reason on stderr
(how many tasks of which periods are unassigned, and how many cores at least are
needed), the JSON still written, no plant emitted.

## Algorithms

**ffd** is the seed's Algorithms 1 and 2, with its errata fixed: periods in ascending
order (Alg. 2); per period the tasks by WCET, largest first (`sortDescending(A, C)`,
ties in file order), each onto the first core of that period where both the
utilization and the memory fit, a new core when none does (Alg. 1). The seed's
Alg. 1 returns the empty set both when it fails (line 10) and when every core is used
(line 20); Alg. 2 then stops only if more periods are left, so a failure in the last
period is reported as success and its remaining networks are silently dropped. Here
a task that needs a new core when none is left is *unassigned*, the smaller tasks
after it still try the open cores, and the result is a failure (exit 5). The sort
key is the WCET, as in the seed, not the load: a task with a small WCET and much I/O
comes late.

**best** never uses more cores than ffd, and per period:

1. ten greedy packings: first fit and best fit (least normalized slack left), each
   with the tasks in five decreasing orders (WCET, load, memory, and the sum and the
   maximum of load / SCT and memory / `--mem`); the best is kept;
2. a large-neighbourhood search: one of the six emptiest cores plus s − 1 others
   (s = 2 … 5, in order of fill) are repacked onto s − 1 cores by the exact search
   below (2 000 nodes each); every success saves a core; until a whole round saves
   nothing, the bound is reached or the node budget (60 000) is used;
3. for a period with at most 30 tasks, an exact search (depth-first branch and bound)
   for k = bound, bound + 1, … cores below the best found: tasks in decreasing
   max-normalized size, each onto an open core where it fits (tightest first; cores
   with equal load and memory tried once) or onto one new core (empty cores are
   interchangeable), pruned when the tasks left exceed the room on the cores that can
   still take the smallest of them. The first k that packs is the optimum once every
   smaller k was proved infeasible; the table says `optimal` then.

Bound per period: max(⌈Σ U⌉, ⌈Σ mem / --mem⌉, the tasks with more than half a core's
time, the tasks with more than half its memory). The JSON's `lower_bound` is spec §8's
Σ ⌈Σ U⌉ (time only). When the cores run out, the periods take cores in ascending
order as in Alg. 2, a period that gets too few keeps its cores with the most tasks and
first-fits the rest onto them; of that and ffd's result the one with fewer unassigned
tasks (then fewer cores) is reported.

Why hand-written rather than a solver: the instances are small per period, a
node-count budget keeps the result deterministic (a solver's time limit would not),
and no extra run-time dependency. The exact search is checked against a brute-force
enumeration (300 instances in the tests) and against the HiGHS MILP solver (`highspy`,
pinned in requirements.txt, used only by the tests and this benchmark): see the
tables below.

Everything is deterministic: no clocks, no set iteration order; the generated
workload uses Python's `random.Random(seed)`, whose integer draws are stable across
Python versions.

## The seed's workload (`--generate becker2015`)

Table I and §V: per network, uniformly and independently, an execution time of
0.122 … 1.223 ms (on a 1 µs grid), 1 … 50 input bytes, 1 … 50 output bytes, an SCT of
10, 20, 100 or 200 ms; memory = input + output bytes; 16 cores (the default `--cores`
with `--generate`), 4096 bytes, α = β = 1.145 µs/byte. Names `n001` … ; `--save-tasks`
writes the generated tasks as a task file.
""")
    w("## Results\n")
    w(f"Generated by `bench/alloc_bench.py --seeds {args.seeds} --instances "
      f"{args.instances}`.\n")
    w("### The seed's case: Table I as printed, 800 networks\n")
    w(f"A network costs on average {ml['exec']:.4f} ms of execution plus "
      f"2 × {ml['io_bytes']:.1f} bytes × 1.145 µs = {ml['io_ms']:.4f} ms of I/O, "
      f"**{ml['load']:.4f} ms**, and takes {ml['mem']:.0f} bytes. Cores per SCT "
      f"(10 / 20 / 100 / 200 ms) with as many cores as needed:\n")
    w("| seed | networks per SCT | Σ U per SCT | Σ mem per SCT [B] | bound | ffd | best | "
      "on 16 cores (ffd) |")
    w("|---|---|---|---|---|---|---|---|")
    for r in sc:
        ok, un, c16 = r["ffd_16"]
        sum_u = " / ".join(f"{r['sum_u'][p]:.2f}" for p in PERIODS)
        w(f"| {r['seed']} | {_counts(r['n'])} | {sum_u} | "
          f"{_counts(r['sum_mem'])} | {_counts(r['bound'])} | {_counts(r['ffd'])} "
          f"(= {sum(r['ffd'].values())}) | {_counts(r['best'])} "
          f"(= {sum(r['best'].values())}) | "
          f"{'fits' if ok else f'fails: {un} unassigned'} |")
    tot = [sum(r["best"].values()) for r in sc]
    ten = [r["best"][10] for r in sc]
    twenty = [r["best"][20] for r in sc]
    opt = sum(all(r["best_optimal"].values()) for r in sc)
    same = sum(r["ffd"] == r["best"] for r in sc)
    hundred = sum(r["best"][100] == 3 and r["best"][200] == 3 for r in sc)
    w("")
    w(f"* **100 ms and 200 ms: 3 cores each, as in the paper**, in {hundred} of "
      f"{len(sc)} seeds. Both groups are bound by memory, not time: about 200 networks × "
      f"51 bytes ≈ 10 kB need ⌈10 200 / 4096⌉ = 3 cores, while their Σ U is only "
      f"≈ 1.5 and ≈ 0.7.")
    w(f"* **10 ms and 20 ms: {min(ten)}–{max(ten)} and {min(twenty)}–{max(twenty)} "
      f"cores**, not the paper's 6 and 4; {min(tot)}–{max(tot)} cores in all, so the "
      f"configuration **does not fit the seed's 16 cores** (ffd and best both exit 5; "
      f"on 16 cores the 10 ms group takes {min(ten)}–{max(ten)} of them and the 20 ms "
      f"group runs out).")
    w(f"* ffd already reaches the bound here in most groups (its result equals best's "
      f"in {same} of {len(sc)} seeds; best is proved optimal in every group in {opt} of "
      f"{len(sc)} seeds): with 200 small networks per period first fit wastes little.")
    w("")
    w("![Fig. 4 like: per core](alloc_fig4.png)\n")
    w(f"Seed 1 with enough cores (best). As in the seed's Fig. 4 the 10 ms cores are "
      f"nearly fully utilized with most of their memory unused, the 200 ms cores the "
      f"reverse; read and write are a small part of U.\n")
    w("### The 10 / 20 ms discrepancy\n")
    w(f"""With Table I as printed, 6 cores at 10 ms are impossible: 6 cores hold at most
6 × 10 = 60 ms of load per 10 ms, but ≈ 200 networks at {ml['load']:.3f} ms each bring
≈ {200 * ml['load']:.0f} ms (Σ U = {min(r['sum_u'][10] for r in sc):.1f} …
{max(r['sum_u'][10] for r in sc):.1f} over the seeds above). The sum's standard
deviation, from the spread of the draws and of the group size (binomial, 800 × 1/4), is
≈ {ml['sd_sum']:.0f} ms: 60 ms lies {(200 * ml['load'] - 60) / ml['sd_sum']:.1f}
standard deviations below the mean, no draw comes near it. Likewise 4 cores at 20 ms hold 80 ms,
against ≈ {200 * ml['load']:.0f} ms. The 3 + 3 cores at 100 / 200 ms pin the group
size: they are memory-bound, and fewer networks (say 80 per group, which 6 cores at
10 ms could take) would need one or two cores there. So the execution times must
differ from Table I. The paper's counts imply a mean load of at most 60 / 200 ≈ 0.30
ms per 10 ms network (and, since 4 > 3 cores at 20 ms, Σ U(20 ms) > 3, i.e. just over
0.30 ms there): about **a third** of Table I's {ml['load']:.2f} ms.

Sweep: every execution time multiplied by s, everything else as printed (ffd, 800
networks, {args.seeds} seeds; cores per SCT 10 / 20 / 100 / 200 ms):
""")
    w("| s | mean load [ms] | most frequent results (seeds) | 6 / 4 / 3 / 3 | fits 16 cores |")
    w("|---|---|---|---|---|")
    for row in R["sweep"]:
        s = float(Fraction(row["scale"]))
        common = ", ".join(f"{'/'.join(map(str, k))} ({v})"
                           for k, v in row["counts"].most_common(3))
        w(f"| {row['scale']} | {s * ml['exec'] + ml['io_ms']:.3f} | {common} | "
          f"{row['paper']} of {row['seeds']} | {row['fits16']} of {row['seeds']} |")
    best_row = max(R["sweep"], key=lambda r: r["paper"])
    hits = [r["scale"] for r in R["sweep"] if r["paper"]]
    others = ", ".join(f"{'/'.join(map(str, k))} ({v})"
                       for k, v in best_row["counts"].most_common()
                       if k != tuple(PAPER.values()))
    w("")
    w(f"""The paper's 6 / 4 / 3 / 3 comes out only for s in {{{', '.join(hits)}}}, most
often at s = {best_row['scale']} ({best_row['paper']} of {best_row['seeds']} seeds; the
others: {others}). At s ≈ 1/3 the execution times are about 0.04 … 0.41 ms (≈ 3 … 33
function blocks of 12.24 µs instead of 10 … 100) and a network costs ≈ 0.28 ms in
all. Even there the result is not stable: 6 / 4 needs Σ U(10 ms) ≤ 6 and Σ U(20 ms) > 3
at once, two sums of the same distribution over SCTs a factor 2 apart, so it sits on a
knife edge (a pure time bound would give 6 : 3). We therefore take it that
the paper's simulation used execution times about three times shorter than Table I
states (or an equivalent slip in the per-block time); the seed does not give enough to
say which. What does reproduce as printed: the 100 / 200 ms groups (3 cores each, by
memory) and the Fig. 4 pattern.

![Fig. 4 like, execution times / 3, 16 cores](alloc_fig4_third.png)
""")
    third = per_sct(R["plant"]["alloc"])
    w(f"""With execution times / 3 the seed's 16 cores suffice (seed 1, best:
{_counts(third)} = {sum(third.values())} cores): the same pattern, 10 ms cores near
U = 1 with memory to spare, 200 ms cores with memory nearly full at low U.
""")
    e = R["errata"]
    w("### The seed's algorithm as printed against the fixed one\n")
    w(f"Seed 1, 800 networks, Table I as printed: ffd needs {e['need']} cores. Given "
      f"{e['cores']} (one too few for the last, 200 ms group), Algorithms 1 and 2 as "
      f"printed (simulated in `bench/alloc_bench.py`) answer **{e['printed']}** and "
      f"silently drop {e['lost']} networks (SCT "
      f"{', '.join(map(str, e['lost_periods']))} ms); with "
      f"{e['need']} cores they answer {e['printed_at_need']}. The fixed ffd reports the "
      f"failure: {'ok' if e['fixed_ok'] else 'exit 5'}, {e['fixed_unassigned']} "
      f"unassigned (listed in the JSON).\n")
    w("### Cores used against the number of networks\n")
    w("![cores against networks](alloc_cores.png)\n")
    cv = R["cores"]
    w(f"Means over {args.seeds} seeds (enough cores). Left, Table I: ffd and best lie on "
      f"the bound (≤ {max(b - l for b, l in zip(cv['becker']['ffd'], cv['becker']['bound'])):.2f} "
      f"cores above it); the spec's Σ ⌈Σ U⌉ is lower because the slow groups are bound by "
      f"memory. The 16 cores are used up at about "
      f"{next((k for k, y in zip(cv['k'], cv['becker']['best']) if y > 16), '>800')} "
      f"networks. Right, two-dimensional tasks (one SCT, load and memory each 10–60 % of "
      f"a core): ffd, sorting by WCET alone, packs memory badly; best saves "
      f"{cv['hard']['ffd'][-1] - cv['hard']['best'][-1]:.1f} cores of "
      f"{cv['hard']['ffd'][-1]:.1f} at {cv['hard_n'][-1]} tasks.\n")
    w("| networks | " + " | ".join(str(k) for k in cv["k"]) + " |")
    w("|---|" + "---|" * len(cv["k"]))
    for key in ("ffd", "best", "bound", "lower_bound"):
        w(f"| {key} | " + " | ".join(f"{y:.1f}" for y in cv["becker"][key]) + " |")
    w("")
    w("| tasks (2-D) | " + " | ".join(str(k) for k in cv["hard_n"]) + " |")
    w("|---|" + "---|" * len(cv["hard_n"]))
    for key in ("ffd", "best", "bound", "lower_bound"):
        w(f"| {key} | " + " | ".join(f"{y:.1f}" for y in cv["hard"][key]) + " |")
    w("")
    gs = R["gap"]
    w("### Heuristic against the optimum (small instances)\n")
    w("Cores used minus the optimum, summed over the periods of an instance. The optimum "
      "is best's exact search with a budget of 2 000 000 nodes per period (proved in every "
      "group when *unproved groups* is 0). HiGHS solved the same problem as a MILP for "
      "every group of at most 20 tasks, with as many cores as the exact search used: "
      "*agrees* means it found no packing with fewer. *heuristics* is best without its "
      "exact step (the ten greedy packings and the neighbourhood search), what best does "
      "on a period of more than 30 tasks.\n")
    w("| family | instances | tasks | algorithm | gap 0 | gap 1 | gap 2 | gap ≥ 3 | mean gap | "
      "unproved groups | HiGHS agrees |")
    w("|---|---|---|---|---|---|---|---|---|---|---|")
    names = {"becker": "Table I tasks (4 SCTs), `--mem` 256 / 512 / 1024 / 4096",
             "hard": "one SCT, load and memory 10–60 % each"}
    for fam, d in gs["families"].items():
        for alg in ("ffd", "heuristics", "best"):
            g = d["gaps"][alg]
            n = sum(g.values())
            w(f"| {names[fam]} | {d['instances']} | {d['sizes'][0]}–{d['sizes'][1]} | "
              f"{alg} | {g[0]} | {g[1]} | {g[2]} | "
              f"{sum(v for k, v in g.items() if k >= 3)} | "
              f"{sum(k * v for k, v in g.items()) / n:.3f} | {d['unproved']} | "
              + (f"{d['agree']} of {d['checked']} groups" if gs["highs"] else
                 "not installed") + " |")
    w("")
    w("![gap distribution](alloc_gap.png)\n")
    w("### The emitted plant\n")
    w(f"""`--emit PLANT.toml` writes a plant file (docs/multicore.md) with one `[[core]]`
per used core, `name = "coreI"`, `period_us` = its SCT, `clock_mhz` = `--clock-mhz`,
layout compact, protection semaphore, and beside it `<stem>_coreI.il`, one program per
core. The tasks of the seed's model have no IL, and a core's tasks would not combine
into one program anyway, so each program stands for its core's whole predicted load:
every scan takes exactly min(floor(load · f), SCT · f − {al.PLANT_HEADROOM}) clocks (load =
the core's read + execute + write time in ms, f in kHz; the {al.PLANT_HEADROOM} clocks leave
room for the plant's empty precycle and postcycle, 3 + 2 clocks on the plant harness).

The program uses **bit instructions only** (one clock each in every mode and with
every byte-processor cost table): a counted loop of 1000 clocks an iteration whose
counter is a {al.COUNTER_BITS}-bit binary number in marker bits, preset to 2^{al.COUNTER_BITS} − n
and incremented by a ripple-carry chain of bit instructions; the carry out of the top
bit ends the loop after exactly n iterations. NOPs make up the rest:

```
      SET                 // preset the counter to 2^20 - n
      =     M0.0          // ... the bits that are 1
      CLR
      =     M0.1          // ... the bits that are 0
loop0:
      NOP                 // {al.LOOP_NOPS} NOPs
      LD    M0.0          // carries from the old bits: c1 = m0,
      =     M8.1          //   c(i+1) = c(i) AND m(i)    (M8.1 ...)
      LD    M8.1
      A     M0.1
      =     M8.2
      ...
      LDN   M0.0          // new bits: m0 = NOT m0, m(i) = m(i) XOR c(i)
      =     M0.0
      LD    M0.1
      X     M8.1
      =     M0.1
      ...
      LD    M10.4         // carry out of bit 19: the counter overflowed
      JCN   loop0         // {al.LOOP_ITER} clocks an iteration, the last one {al.LOOP_ITER - al.JUMP_EXTRA}
      NOP                 // the rest, < {al.LOOP_ITER + al.LOOP_FIXED} clocks
      END
```

A first version counted in MW0 with word instructions (62 clocks an iteration): on the
plant harness each word instruction took 11 clocks instead of the cost table's 10, so
its scans ran 8 % long; with bit instructions only the load does not depend on the
byte processor at all. One loop holds up to 2^20 iterations (≈ 10⁹ clocks); the
program has at most ≈ 2 000 instructions.

The plant declares no shared variables: the seed's read and write phases are α and β
per byte on its NoC, which the bit-byte plant's copies do not model, so they are part
of the program's load and the precycle and postcycle are empty. `bitbyte link`
accepts the plant. A lower `--clock-mhz` makes it cheaper to simulate (1 MHz: 10 000
clocks per 10 ms).
""")
    pl = R["plant"]
    w(f"Every core's program alone in the reference interpreter (`bitbyte.ref.refsim`): Table "
      f"I with execution times / 3, seed 1, 16 cores, {pl['mhz']} MHz.\n")
    w("| core | SCT [ms] | predicted U | clocks per scan | instructions | measured U | "
      "within SCT |")
    w("|---|---|---|---|---|---|---|")
    for r in pl["rows"]:
        w(f"| {r['core']} | {r['sct']} | {r['u']:.6f} | {r['clocks']} | {r['words']} | "
          f"{r['measured']:.6f} | {'yes' if r['within'] else 'NO'} |")
    worst = max(abs(r["measured"] - r["u"]) / r["u"] for r in pl["rows"])
    w(f"\nLargest relative difference measured / predicted: {worst:.1e} (the issue asks "
      f"for ≤ 5 %; the rest is the floor to whole clocks and the headroom).\n")
    run = pl["run"]
    w("**On the multi-core system.** Two of these cores (the fullest 10 ms and the "
      "fullest 200 ms one) "
      f"were emitted as a plant at 1 MHz and run with `bitbyte run PLANT.toml --until-us "
      f"{run['until']}` (busy = precycle + cycles + postcycle of a scan, from the "
      "trace):\n")
    if run["ok"]:
        w("| plant core (from core) | SCT [µs] | scans | predicted U | measured U (mean busy / "
          "SCT) | difference | max busy [clocks] | pre / post max | overruns |")
        w("|---|---|---|---|---|---|---|---|---|")
        for c in run["cores"]:
            w(f"| {c['name']} ({c['from']}) | {c['period']} | {c['scans']} | {c['u']:.5f} | "
              f"{c['measured']:.5f} | {100 * (c['measured'] - c['u']) / c['u']:+.2f} % | "
              f"{c['busy_max']} of {c['period']} | {c['pre']} / {c['post']} | "
              f"{c['overruns']} |")
        w("\nEvery scan's precycle + cycle + postcycle fits its SCT, and the measured "
          "utilization is within 5 % of the prediction (tests/test_alloc.py checks the "
          "same on a two-core plant with a core at U = 0.9995).\n")
    else:
        w(f"Not run: `{run['error']}`.\n")
    w("### Run time\n")
    fs = [r["ffd_s"] for r in sc]
    bs = [r["best_s"] for r in sc]
    w(f"800 networks (Table I): ffd {statistics.median(fs) * 1000:.0f} ms, best "
      f"{statistics.median(bs) * 1000:.0f} ms median (max {max(bs) * 1000:.0f} ms) in "
      f"Python on this machine; `best` spends at most 60 000 search nodes per period in "
      f"the neighbourhood search and as many in the exact search.\n")
    w("## Reproduce\n")
    w("```\nmake bench-alloc                    # this page and docs/alloc_*.png\n"
      "bitbyte alloc --generate becker2015 --networks 800 --seed 1 --cores 64\n"
      "pytest -n 2 tests/test_alloc.py\n```\n")
    return "\n".join(out)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--instances", type=int, default=1000)
    ap.add_argument("--quick", action="store_true", help="3 seeds, 100 instances")
    ap.add_argument("--out", default=str(DOCS))
    args = ap.parse_args()
    if args.quick:
        args.seeds, args.instances = 3, 100
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    import tempfile
    R = {"mean_load": seed_mean_load()}
    steps = [("seed_case", lambda: seed_case(args.seeds)),
             ("sweep", lambda: scale_sweep(args.seeds)),
             ("errata", errata_demo),
             ("cores", lambda: cores_vs_networks(args.seeds)),
             ("gap", lambda: gap_study(args.instances))]
    for name, fn in steps:
        t0 = time.perf_counter()
        R[name] = fn()
        print(f"{name}: {time.perf_counter() - t0:.1f} s", flush=True)
    with tempfile.TemporaryDirectory(prefix="alloc-plant-") as tmp:
        R["plant"] = emitted_plant(Path(tmp))
    tasks = al.generate_becker2015(800, 1)
    plot_fig4(al.allocate(tasks, al.Platform(UNLIMITED)), out / "alloc_fig4.png",
              "Table I as printed, 800 networks, seed 1 (best)")
    plot_fig4(R["plant"]["alloc"], out / "alloc_fig4_third.png",
              "execution times / 3, 800 networks, seed 1, 16 cores (best)")
    plot_cores(R["cores"], out / "alloc_cores.png")
    plot_gap(R["gap"], out / "alloc_gap.png")
    (out / "allocation.md").write_text(report(R, args))
    print(f"wrote {out / 'allocation.md'} and {out}/alloc_*.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
