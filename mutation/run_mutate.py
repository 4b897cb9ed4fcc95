"""make mutate: mutation testing of rtl/ with Yosys's `mutate` (issue 15, Build item 2).

For each campaign below (a test top and the RTL modules it is the home of), a seeded
sample of mutations per module is built into one netlist behind mutsel
(mutation/mutlib.py) and the campaign's tests run once per mutant in one pytest
session (mutation/plugin.py). A mutant no test kills then meets every proof in
formal/ that reads its module (the mutation applied in the proof's own elaboration),
and one no proof kills either is checked for equivalence with the original (a Yosys
miter from reset, k-induction in SymbiYosys). What is left is a gap: a test to add.
Writes build/mutation/<campaign>/summary.json and docs/mutation.md.

    python mutation/run_mutate.py [--seed S] [--count N] [--only a,b] [--jobs J]
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(1, str(Path(__file__).resolve().parents[1] / "bench"))
import mutlib  # noqa: E402
from benchlib import source_rev  # noqa: E402  (the commit a report's figures belong to)

ROOT = mutlib.ROOT
BUILD = ROOT / "build" / "mutation"
DOC = ROOT / "docs" / "mutation.md"


@dataclass
class Campaign:
    name: str
    tests: list            # pytest arguments (files or node ids)
    modules: list          # the RTL modules sampled here (each module has one home)
    keyword: str = ""      # pytest -k (the benches: Icarus only, the faster build)
    harness: bool = False  # the tests run the Verilator harness (bitbyte_cpu)
    plant: bool = False    # the tests run two-core plants on the plant harness (plc_system)
    wide: bool = False     # with harness: the wide build (BitEngine=1, make harness-wide)
    env: dict = field(default_factory=dict)
    equivalence: bool = True   # the miter is small enough (not the whole CPU)
    # else: the modules whose survivors are checked alone (their own module in the
    # campaign's netlist, its mutsel port tied to the mutant)
    equiv_modules: tuple = ()
    # the contract after reset (mutlib.Settle): survivors the checks leave open are
    # checked once more, as equivalent once the module has settled
    settle: mutlib.Settle | None = None
    # the module's interface contract (mutlib.Contract): survivors still open are
    # checked as equivalent where its users can look
    contract: mutlib.Contract | None = None
    # its proofs and checks need longer than --timeout (at least this, seconds): the
    # settled checks through a slow clearing; so that `make mutate` in one sitting
    # reproduces what the campaign showed once
    min_check_timeout: float = 0.0


def bench(module: str, *more: str) -> Campaign:
    return Campaign(module, [f"tb/test_{module}.py"], [module, *more], keyword="icarus")


# The random programs per family in the CPU campaign: a mutant that survives the
# directed tests meets this many programs (the regression's 200 each take longer
# per mutant than the whole directed set; the seed is the campaign's).
CPU_PROGRAMS = 60

CAMPAIGNS = [
    bench("cond_ff"), bench("hsem"),
    # a read's cell is on rd_data_o in the clock after the read, only then (the block
    # RAM's output register, read by nothing else). Its users keep that: the bit side
    # takes cell_rdata_i only in its first execute clock, the one after the operand
    # stage's read, and keeps its own copy (bit_proc.v e_first_q / cell_hold_q; its
    # proof assumes the same, f_inv_cell_rd); the byte side in the clock after its
    # request (byte_port.v mc_pend_q), answering not-ready in the request clock
    Campaign("marker_region", ["tb/test_marker_region.py"], ["marker_region"],
             keyword="icarus",
             contract=mutlib.Contract(valid={"rd_data_o": "rd_req_i"}, free=("ram_r_q",))),
    # its saturation test runs on Verilator only (131 000 clocks)
    Campaign("cond_queue", ["tb/test_cond_queue.py"], ["cond_queue"], keyword="icarus or saturation"),
    bench("dispatch"), bench("input_unit"), bench("output_unit"), bench("scan_ctrl"),
    bench("tc_status"),
    # the bench's 16 words a buffer, two buffers: cleared in 32 clocks after reset;
    # the clearing counter's low bits are read only while clearing
    # (two of its survivors settle only with 1200 s a check: stop 38, 108 min)
    Campaign("shared_mem", ["tb/test_shared_mem.py"], ["shared_mem"], keyword="icarus",
             settle=mutlib.Settle("ready_o", 36, ("rdata_o",), free=("clear_q",)),
             min_check_timeout=1200.0),
    bench("force_table"),
    bench("byte_port", "time_base", "bus_stats"),
    bench("core_seq", "copy_engine"),
    # its own bench against a model of the four settings (the CPU tests reach only the
    # setting each program runs in, and through the whole CPU)
    # (the marker area's two regions: cleared in 32 clocks after reset)
    # (the regions clear alike: their clearing counters are equal in every clock)
    Campaign("cond_exchange", ["tb/test_cond_exchange.py"], ["cond_exchange"],
             keyword="icarus", settle=mutlib.Settle("marker_ready_o", 36),
             contract=mutlib.Contract(same=(("g_marker.u_region_fby.clear_q",
                                             "g_marker.u_region_fbi.clear_q"),))),
    Campaign("cpu", ["tests/test_cpu_directed.py::test_every_pin_harness",
                     "tests/test_cpu_directed.py::test_directed_harness",
                     "tests/test_cpu_directed.py::test_every_status_index_harness",
                     "tests/test_cpu_directed.py::test_every_counter_through_the_status_buffer_harness",
                     "tests/test_cpu_directed.py::test_every_timer_and_counter_input_bit_harness",
                     "tests/test_cpu_directed.py::test_accumulators_reset_after_65536_skipped_scans",
                     "tests/test_cpu_directed.py::test_a_scan_longer_than_2_to_the_20_clocks",
                     "tests/test_cpu_directed.py::test_every_output_edge_harness",
                     "tests/test_cpu_directed.py::test_every_input_word_bit_harness",
                     "tests/test_cpu_directed.py::test_every_output_word_bit_harness",
                     "tests/test_cpu_directed.py::test_every_timer_status_column_harness",
                     "tests/test_cpu_directed.py::test_every_pending_edge_after_refresh_harness",
                     "tests/test_cpu_directed.py::test_every_pending_edge_within_the_scan_harness",
                     "tests/test_cpu_directed.py::test_bit_side_stall_count_past_bit_15_harness",
                     "tests/test_random_programs.py::test_verilator_harness",
                     "tests/test_random_programs.py::test_mixed_verilator_harness",
                     "tests/test_random_parallel.py::test_parallel_on_harness",
                     # free-running mode against the exchange model (both exchanges)
                     "tests/test_exchange_model.py",
                     # 100 marker cells each way (the MCELL window's cells from 64 on)
                     "tests/test_free_running.py::test_marker_area_carries_100_crossings_each_way[verilator]",
                     # the marker copy port (plants' copy engine), which the harness ties off
                     "tb/test_bitbyte_cpu.py"],
             ["bit_proc", "bitbyte_cpu", "sync_ram"], harness=True,
             env={"BITBYTE_RANDOM_PROGRAMS": str(CPU_PROGRAMS),
                  "BITBYTE_MIXED_PROGRAMS": str(CPU_PROGRAMS)},
             equivalence=False, equiv_modules=("sync_ram",)),
    # the wide bit engine's LUT execution (issue 18): the CPU with BitEngine=1 on a wide
    # harness built once from the mutant netlist; random images and directed programs
    # against the image interpreter, the adder's sums (the waves test needs a traced
    # harness: left out). bit_proc's own cells are the cpu campaign's.
    Campaign("wide", ["tests/test_wide_rtl.py"], ["lut_unit"], keyword="not waves",
             harness=True, wide=True, equivalence=False, equiv_modules=("lut_unit",)),
    # the multi-core plant's own modules (a core: CPU, MW RAM, precycle / postcycle
    # sequencer; the system: cores, shared memory, semaphore, period timers) through
    # two-core plants on a plant harness built once from the mutant netlist of
    # plc_system; its CPUs are the cpu campaign's, sampled there
    Campaign("plant", ["tests/test_plant_every_bit.py",
                       "tests/test_plant_run.py::test_seed_6_1_example",
                       "tests/test_plant_parallel.py", "tests/test_plant_spec.py",
                       "tests/test_plant_tearing.py"],
             ["plc_core", "plc_system"], plant=True, equivalence=False),
]


def proofs_of(module: str) -> list[mutlib.Sby]:
    """The formal/*.sby files that read `module`."""
    return [s for s in (mutlib.Sby.load(p) for p in sorted(mutlib.FORMAL.glob("*.sby")))
            if module in s.modules()]


def run_tests(c: Campaign, seed: int, count: int, work: Path, keep: Path | None = None) -> dict:
    """The campaign's tests against every mutant (one pytest session): plugin results.
    `keep`: an earlier run's results.json whose test kills stand (its survivors run)."""
    cfg = {"work": str(work), "modules": c.modules, "count": count, "seed": seed,
           "tests": c.tests,
           "harness": c.harness, "plant": c.plant, "wide": c.wide,
           "results": str(work / "results.json"),
           "keep": str(keep) if keep else None}
    (work / "config.json").write_text(json.dumps(cfg))
    env = dict(os.environ, BITBYTE_MUTATION=str(work / "config.json"), BITBYTE_SEED=str(seed),
               PYTHONPATH=os.pathsep.join([str(ROOT / "mutation"), os.environ.get("PYTHONPATH", "")]),
               **c.env)
    cmd = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "plugin",
           "-p", "no:xdist", *c.tests] + (["-k", c.keyword] if c.keyword else [])
    proc = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True)
    (work / "pytest.log").write_text(proc.stdout + proc.stderr)
    results = work / "results.json"
    if not results.exists():
        raise mutlib.MutationError(f"{work / 'pytest.log'}: the tests did not run:\n"
                                   + "\n".join(proc.stdout.splitlines()[-15:]))
    return json.loads(results.read_text())


def run_proofs(muts, survivors, work: Path, timeout: float) -> dict:
    """Each surviving mutant against the prove tasks of every proof reading its module:
    {id: {proof: outcome}}; the proof's elaboration gets the mutation mapped by key."""
    out: dict = {}
    home_sigs = None
    by_module: dict = {}
    for m in muts:
        if m.id in survivors:
            by_module.setdefault(m.home, []).append(m)
    for module, ms in sorted(by_module.items()):
        for sby in proofs_of(module):
            for task in sby.prove_tasks():
                pw = mutlib.prepare_dir(work / f"proof-{sby.path.stem}-{task}")
                elab, _ = sby.elab(task)
                cands = mutlib.candidates(pw, elab, [module], "all")
                sigs = mutlib.cell_signatures(pw, elab, "sigs")
                if home_sigs is None:
                    home_sigs = load_home_sigs(work)
                mapped = mutlib.map_mutations(ms, home_sigs, cands, sigs, home_candidates(work))
                for m in ms:
                    name = f"{sby.path.stem}:{task}"
                    if m.id not in mapped:
                        out.setdefault(m.id, {})[name] = "n/a"
                        continue
                    res = mutlib.run_sby(pw, sby.with_mutation(task, mapped[m.id]),
                                         f"m{m.id}", timeout)
                    out.setdefault(m.id, {})[name] = res
    return out


def home_dir(work: Path) -> Path:
    results = json.loads((work / "results.json").read_text())
    return Path(results["elaborations"][0]["dir"])


def load_home_sigs(work: Path) -> dict:
    """The sampling elaboration's cell signatures (the plugin wrote them there)."""
    return mutlib.signatures_from_json(home_dir(work) / "sigs.json")


def home_candidates(work: Path) -> list:
    home = home_dir(work)
    return [mutlib.Mutation.parse(line) for f in sorted(home.glob("all.*.list"))
            for line in f.read_text().splitlines() if line.strip()]


def summarize(c: Campaign, seed: int, count: int, work: Path, eq_depth: int,
              timeout: float, reuse: bool = False, keep: Path | None = None,
              eq_jobs: int = 1) -> dict:
    t0 = time.time()
    if reuse:   # the tests' results of an interrupted run (their time is not known)
        res = json.loads((work / "results.json").read_text())
    else:
        res = run_tests(c, seed, count, work, keep)
    t_tests = time.time() - t0
    muts = [mutlib.Mutation.from_json(d) for d in res["mutations"]]
    base_bad = {n: o for n, o in res["baseline"].items() if o[0] != "pass"}
    killed = {int(k): v for k, v in res["killed"].items()}
    survivors = {m.id for m in muts if m.id not in killed}
    t1 = time.time()
    proofs = run_proofs(muts, survivors, work, timeout)
    t_proofs = time.time() - t1
    proof_killed = {i for i, r in proofs.items()
                    if any(o in ("fail", "unknown") for o in r.values())}
    t2 = time.time()
    equiv = {}
    # the no-op and dead checks apply to every campaign (the plant's too); the
    # equivalence proper to those whose miter is small enough (below)
    home = res["elaborations"][0]
    by_id = {m.id: m for m in muts}
    design = json.loads((Path(home["dir"]) / "sigs.json").read_text())["modules"]

    def check(i: int) -> str | None:
        """The verdict on survivor i (None: no check applies), its files in
        equiv/m<i>/ (the checks of different mutants run side by side)."""
        # a mutation that changes no bit of the netlist needs no proof (and the
        # whole CPU, too large for the checks below, has such mutants too)
        why = mutlib.noop(by_id[i], design)
        if why:
            return "no-op: " + why
        here = work / "equiv" / f"m{i}"
        # the whole design with its memories as memories (in the CPU: sync_ram's
        # held word, its read enable tied to 1), then through the memories (the
        # whole CPU is too large for that: its modules alone)
        script = mutlib.elab_script(home["top"], home.get("params"))
        drawn = Path(home["dir"])   # the RTL the sample was drawn from
        alone = None if c.equivalence else by_id[i].module
        if mutlib.dead(here, script, by_id[i], timeout, memories=False,
                       rtl=drawn) or (alone != home["top"] and mutlib.dead(
                           here, script, by_id[i], timeout, alone, rtl=drawn)):
            return "no-op: Yosys's clean-up removes it (no output reads it)"
        if not c.equivalence and by_id[i].home not in c.equiv_modules:
            return None
        top = home["top"] if c.equivalence else by_id[i].module
        netlist = Path(home["dir"]) / "mutants.v"
        try:
            verdict = mutlib.equivalence(here, netlist, top, i, eq_depth, timeout)
            if verdict != "equivalent" and c.settle:
                # a longer proof (a BMC through the clearing): four times the time
                if mutlib.settled_equivalence(here, netlist, top, i, c.settle,
                                              4 * timeout) == "equivalent":
                    return f"settled: equivalent once {c.settle.signal} is up"
            if verdict != "equivalent" and c.contract:
                if mutlib.contract_equivalence(here, netlist, top, i, c.contract,
                                               timeout) == "equivalent":
                    return "contract: equivalent where its users look"
            return verdict
        except mutlib.MutationError as e:
            (work / f"equiv-{i}.err").write_text(str(e))
            return "error"

    todo = sorted(survivors - proof_killed)
    with ThreadPoolExecutor(max_workers=eq_jobs) as pool:
        for i, verdict in zip(todo, pool.map(check, todo)):
            if verdict is not None:
                equiv[i] = verdict
    t_eq = time.time() - t2
    cands = {}
    for f in sorted(home_dir(work).glob("all.*.list")):
        cands[f.name.split(".")[1]] = sum(1 for line in f.read_text().splitlines() if line.strip())
    head = source_rev()     # -dirty for code, not for docs/ (which a campaign writes)
    summary = {
        "campaign": c.name, "commit": head, "tests": c.tests, "keyword": c.keyword, "modules": c.modules,
        "seed": seed, "count": count, "env": c.env, "candidates": cands,
        "elaborations": res["elaborations"], "baseline": res["baseline"],
        "baseline_failed": base_bad,
        "mutants": [dict(m.to_json(), where=m.where(),
                         tests=killed.get(m.id), proofs=proofs.get(m.id, {}),
                         equivalence=equiv.get(m.id)) for m in muts],
        "seconds": {"tests": round(t_tests, 1), "proofs": round(t_proofs, 1),
                    "equivalence": round(t_eq, 1)},
        "tests_reused": reuse, "check_timeout": timeout, "eq_depth": eq_depth,
        "kills_kept": sum(1 for v in killed.values() if v[1].endswith("(kept)")),
    }
    (work / "summary.json").write_text(json.dumps(summary, indent=1))
    return summary


def verdict(m: dict) -> str:
    if m["tests"]:
        return "killed (tests)"
    if any(o in ("fail", "unknown") for o in m["proofs"].values()):
        return "killed (proof)"
    if m["equivalence"] == "equivalent" or (m["equivalence"] or "").startswith(
            ("no-op", "settled", "contract")):
        return "equivalent"
    return "survived"


def module_rows(summaries) -> list:
    rows = []
    for s in summaries:
        for mod in s["modules"]:
            ms = [m for m in s["mutants"] if m["home"] == mod]
            v = [verdict(m) for m in ms]
            kt, kp = v.count("killed (tests)"), v.count("killed (proof)")
            eq, sv = v.count("equivalent"), v.count("survived")
            live = len(ms) - eq
            rate = f"{100.0 * (kt + kp) / live:.1f} %" if live else "-"
            rows.append((mod, s["campaign"], s["candidates"].get(mod, 0), len(ms), kt, kp, eq,
                         sv, rate))
    return rows


def write_doc(summaries, total_s: float, path: Path = DOC) -> None:
    lines = [
        "# Mutation testing",
        "",
        "Generated by `make mutate` (mutation/run_mutate.py); do not edit by hand. "
        "What it does and why: [verification.md](verification.md#mutation-testing).",
        "",
        "Each mutant is one bit of one cell of the elaborated module (Yosys `mutate`: an "
        "input or output bit inverted, stuck at 0 or 1, or XORed with another bit), drawn "
        "by `mutate -list N -seed S` evenly over the module's cells. All of a "
        "campaign's mutants are built into one netlist behind `mutsel` (0 = the "
        "original), built once per simulator; each mutant is a run with `+mutsel=<id>`. "
        "A mutant is **killed (tests)** when a test of its campaign fails on it while "
        "passing on the original, **killed (proof)** when a prove task of a "
        "formal/*.sby reading its module no longer passes with the mutation applied "
        "in the proof's elaboration, **equivalent** when a Yosys miter of the original "
        "and the mutant is proved (k-induction, SymbiYosys) to give the same outputs "
        "from reset, when the mutation is a no-op (a bit stuck at the constant it "
        "already is in the netlist, or one Yosys's clean-up removes: no output reads it), "
        "or when it changes only how the module gets ready after reset and is proved the "
        "same once ready (mutlib.settled_equivalence), or when it is proved the same "
        "where the module's users look (mutlib.contract_equivalence: an output read only "
        "in the clock after its request, registers proved equal in the original). "
        "**Survived** is a gap: a test to add.",
        "",
        f"Run time {total_s / 60:.1f} min (the campaigns' tests, proofs and "
        "equivalence checks, one after another, on a 2-core machine).",
        "",
        "| module | campaign | candidates | sampled | killed (tests) | killed (proof) "
        "| equivalent | survived | kill rate |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for row in module_rows(summaries):
        lines.append("| " + " | ".join(str(x) for x in row) + " |")
    missing = [c for c in CAMPAIGNS if c.name not in {s["campaign"] for s in summaries}]
    lines += ["", "Kill rate: killed / (sampled - equivalent). Candidates: every mutation "
              "`mutate` can make in the module's elaboration."]
    if missing:
        lines += ["", "Not in these results (campaign not run yet): " + "; ".join(
            f"{c.name} ({', '.join(c.modules)})" for c in missing) + "."]
    homeless = sorted({p.stem for p in mutlib.RTL.glob("*.v")}
                      - {m for c in CAMPAIGNS for m in c.modules})
    if homeless:
        lines += ["", "Modules in no campaign yet: " + ", ".join(homeless) + "."]
    lines += ["", "## Campaigns", ""]
    for s in summaries:
        tests = ", ".join(f"`{t}`" for t in s["tests"])
        kw = f" (`-k {s['keyword']}`)" if s["keyword"] else ""
        env = "".join(f", {k}={v}" for k, v in s["env"].items())
        sec = s["seconds"]
        at = f" (at {s['commit']})" if s.get("commit") else ""
        lines.append(f"- **{s['campaign']}**{at}: seed {s['seed']}, "
                     f"{s['count']} per module{env}; "
                     f"tests {tests}{kw}; "
                     + ("tests' results kept from an interrupted run (time not recorded), "
                        if s.get("tests_reused") else f"{sec['tests']} s tests, ")
                     + (f"{s['kills_kept']} test kills kept from an earlier run of the same "
                        "sample (--keep-kills; the tests re-run on its survivors only), "
                        if s.get("kills_kept") else "")
                     + f"{sec['proofs']} s proofs, {sec['equivalence']} s equivalence"
                     + (f" (each proof and check stopped after {s['check_timeout']:.0f} s, "
                        f"k-induction depth {s['eq_depth']})" if "check_timeout" in s else "")
                     + ".")
        for e in s["elaborations"]:
            p = ", ".join(f"{k}={v}" for k, v in e["params"].items()) or "defaults"
            hb = f"; harness build {e['harness_build_s']} s" if "harness_build_s" in e else ""
            lines.append(f"  - elaboration `{e['top']}` ({p}): {len(e['mapped'])} mutants "
                         f"mapped{hb}")
        if not next((c.equivalence for c in CAMPAIGNS if c.name == s["campaign"]), True):
            lines.append("  - no equivalence check: the miter of the whole CPU (4096-word "
                         "program memory, 2048 markers) is beyond this flow; its survivors "
                         "are open")
        if s["baseline_failed"]:
            lines.append(f"  - tests failing on the unmutated netlist (left out): "
                         f"{', '.join(s['baseline_failed'])}")
    lines += ["", "## Mutants not killed", "",
              "| campaign | id | module | where (source, cell.port[bit], mode) | proofs | verdict |",
              "|---|---:|---|---|---|---|"]
    for s in summaries:
        for m in s["mutants"]:
            v = verdict(m)
            if v.startswith("killed"):
                continue
            pr = ", ".join(f"{k} {o}" for k, o in m["proofs"].items()) or "none reads it"
            if v == "survived":
                v += f" (miter: {m['equivalence'] or 'not run'})"
            elif m["equivalence"].startswith(("no-op", "settled", "contract")):
                v += f" ({m['equivalence']})"
            lines.append(f"| {s['campaign']} | {m['id']} | {m['home']} | `{m['where']}` | "
                         f"{pr} | {v} |")
    path.write_text("\n".join(lines) + "\n")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--count", type=int, default=30, help="mutants per module (all when fewer)")
    ap.add_argument("--only", help="campaigns, comma-separated (default: all)")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--eq-depth", type=int, default=8)
    ap.add_argument("--timeout", type=float, default=120.0, help="per proof, seconds")
    ap.add_argument("--eq-jobs", type=int, default=1,
                    help="a campaign's equivalence checks run side by side (one mutant each)")
    ap.add_argument("--doc", default=str(DOC))
    ap.add_argument("--reuse-tests", action="store_true",
                    help="keep a campaign's test results (build/mutation/<c>/results.json) "
                         "and redo only its proofs and equivalence checks")
    ap.add_argument("--keep-kills", metavar="RESULTS",
                    help="an earlier run's results.json (one campaign, the same seed and "
                         "count): its test kills stand and the tests run on its survivors "
                         "only; sound when tests were only added since")
    ap.add_argument("--doc-only", action="store_true",
                    help="rewrite the doc from the campaigns' last summaries, run nothing")
    args = ap.parse_args(argv)
    names = args.only.split(",") if args.only else [c.name for c in CAMPAIGNS]
    if args.doc_only:
        names = []
    unknown = set(names) - {c.name for c in CAMPAIGNS}
    if unknown:
        print(f"run_mutate.py: unknown campaign(s): {', '.join(sorted(unknown))}", file=sys.stderr)
        return 2
    def one(c):
        work = BUILD / c.name
        keep = None
        if args.keep_kills:   # copied first: it may be this campaign's own, about to go
            keep = BUILD / f"{c.name}.kept.json"
            keep.parent.mkdir(parents=True, exist_ok=True)
            keep.write_bytes(Path(args.keep_kills).read_bytes())
        reuse = args.reuse_tests and (work / "results.json").exists()
        if work.exists() and not reuse:
            subprocess.run(["rm", "-rf", str(work)], check=True)
        work.mkdir(parents=True, exist_ok=True)
        t = time.time()
        s = summarize(c, args.seed, args.count, work, args.eq_depth,
                      max(args.timeout, c.min_check_timeout), reuse, keep, args.eq_jobs)
        print(f"{c.name}: {len(s['mutants'])} mutants, {time.time() - t:.0f} s", flush=True)
        return s
    try:
        with ThreadPoolExecutor(max_workers=args.jobs) as pool:
            list(pool.map(one, [c for c in CAMPAIGNS if c.name in names]))
    except mutlib.MutationError as e:
        print(f"run_mutate.py: {e}", file=sys.stderr)
        return 1
    summaries = [json.loads((BUILD / c.name / "summary.json").read_text())
                 for c in CAMPAIGNS if (BUILD / c.name / "summary.json").exists()]
    total = sum(sum(s["seconds"].values()) for s in summaries)
    write_doc(summaries, total, Path(args.doc))
    rows = module_rows(summaries)
    for row in rows:
        print("  {:14s} {:10s} sampled {:3d}  tests {:3d}  proof {:3d}  equiv {:3d}  "
              "survived {:3d}  {}".format(row[0], row[1], *row[3:]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
