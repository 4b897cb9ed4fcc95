#!/usr/bin/env python3
"""`make bench`: scan time, response time and simulator speed (issue 8).

    python bench/run_bench.py [--modes serial,parallel,free] [--edges 1000] [--quick]

Runs everything through `bitbyte run` (the Verilator C++ harness unless said
otherwise), keeps its raw material in build/bench/ (traces, stimuli, results.json) and
regenerates docs/performance.md and docs/perf_*.png from scratch (bench/report.py).

Modes are a parameter: each one asked for is first tried on the paper's Fig. 5
program; a mode that `bitbyte run --mode M` does not run yet is listed in the report
as not available and skipped, so the same command measures parallel and free-running
mode once they land.
"""
from __future__ import annotations

import argparse
import json
import os
import random
import statistics
import sys
import time
from fractions import Fraction
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))

import benchlib as bl                     # noqa: E402
import gen_programs                       # noqa: E402
import mcu_baseline                       # noqa: E402
import tc_path_bench                      # noqa: E402
import bit_engine_bench                   # noqa: E402

ROOT = bl.ROOT
EX = ROOT / "examples"
PROG = HERE / "programs"
SEED = gen_programs.DEFAULT_SEED
C320_MHZ = Fraction(10)     # the c320 table's unit: 1 clock = 0.1 us (costs.c)
# sensitivity of the baseline to its bit cost (c320 clocks of 0.1 µs); the counted
# figures (bench/mcu_baseline.py: native code, interpreter at 33 and 25 MHz) are added
MCU_BIT_COSTS = (6, 12, 29, 57)


# ---------------------------------------------------------------------- stimuli
def random_input_stimulus(path: Path, duration_us: Fraction, changes: int,
                          rng: random.Random) -> None:
    """A plant's inputs: `changes` random single-bit changes of I0.0..I11.7 spread
    uniformly over the run, and a new analog value on IW0..IW7 at every 8th change."""
    bits = [f"I{b}.{n}" for b in range(gen_programs.IN_BYTES) for n in range(8)]
    words = [f"IW{n}" for n in range(8)]
    cols = bits + words
    state = {c: 0 for c in cols}
    times = sorted(Fraction(rng.randrange(1, int(duration_us * 1000)), 1000)
                   for _ in range(changes))
    lines = ["t_us," + ",".join(cols), "0," + ",".join("0" for _ in cols)]
    for i, t in enumerate(times):
        row = {}
        b = rng.choice(bits)
        state[b] ^= 1
        row[b] = state[b]
        if i % 8 == 0:
            w = rng.choice(words)
            row[w] = rng.randrange(-200, 2000)
        lines.append(bl.fmt_us(t) + "," + ",".join(str(row.get(c, "")) for c in cols))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n")


# ---------------------------------------------------------------------- scan time
def scan_cases(f: Fraction, quick: bool) -> list[dict]:
    """(name, program, stimulus, stop) per benchmark program."""
    rng = random.Random(SEED)
    cases = [
        dict(name="Fig. 5", key="fig5", prog=EX / "fig5.il", stim=EX / "fig5.stim.csv",
             scans=200 if quick else 1000),
        dict(name="Fig. 14", key="fig14", prog=EX / "fig14.il", stim=EX / "fig14.stim.csv",
             until_us="40000"),
        dict(name="star-delta", key="star_delta", prog=EX / "star_delta.il",
             stim=EX / "star_delta.stim.csv", until_us="260000"),
    ]
    t1 = dict(name="Table-1 size", key="table1", prog=PROG / "table1.il", scans=500 if quick
              else 3000)
    st = bl.static_counts(t1["prog"])
    dur = Fraction(st.serial_clocks(10) * t1["scans"]) / f
    t1["stim"] = bl.BUILD / "table1.stim.csv"
    random_input_stimulus(t1["stim"], dur, t1["scans"], rng)
    cases.append(t1)
    for pct in (0, 10, 20, 30, 40, 50):
        c = dict(name=f"mix {pct} %", key=f"mix_{pct:02d}", prog=PROG / f"mix_{pct:02d}.il",
                 scans=300, share=pct)
        st = bl.static_counts(c["prog"])
        dur = Fraction(st.serial_clocks(10) * c["scans"]) / f
        c["stim"] = bl.BUILD / f"mix_{pct:02d}.stim.csv"
        random_input_stimulus(c["stim"], dur, c["scans"], rng)
        cases.append(c)
    return cases


def measure_scan(cases, modes, f) -> dict:
    out = {}
    for c in cases:
        st = bl.static_counts(c["prog"])
        entry = dict(name=c["name"], program=str(c["prog"].relative_to(ROOT)),
                     stimulus=str(Path(c["stim"]).relative_to(ROOT)),
                     n_bit=st.n_bit, n_word=st.n_word, n_jump=st.n_jump,
                     share=c.get("share"),
                     static_paper=st.serial_clocks(bl.cost_table("paper")["word"]),
                     static_c320=st.serial_clocks(bl.cost_table("c320")["word"]),
                     runs={})
        runs = [(m, "paper", f) for m in modes] + [("serial", "c320", C320_MHZ)]
        for mode, costs, clk in runs:
            tag = f"{mode}/{costs}"
            mtag = mode.replace(":", "_")
            trace = bl.BUILD / "traces" / f"{c['key']}.{mtag}.{costs}.csv"
            r = bl.run_bitbyte(c["prog"], mode=mode, clock_mhz=clk, stimulus=c["stim"],
                               scans=c.get("scans"), until_us=c.get("until_us"),
                               costs=costs, trace=trace)
            if not r.ok or not r.rows:
                entry["runs"][tag] = dict(error=(r.stderr.strip() or f"exit {r.rc}")[-300:])
                bl.progress(f"  {c['name']:<14} {tag:<15} FAILED: {r.stderr.strip()[-120:]}")
                continue
            cyc = r.cycles
            lo, med, hi = min(cyc), statistics.median(cyc), max(cyc)
            stalls = r.stalls()
            entry["runs"][tag] = dict(mode=mode, costs=costs, clock_mhz=float(clk),
                                      scans=len(cyc), min=lo, median=med, max=hi,
                                      mean=sum(cyc) / len(cyc), wall_s=r.wall_s,
                                      trace=str(trace.relative_to(ROOT)),
                                      stalls_per_scan=[x / len(cyc) for x in stalls]
                                      if stalls else None, free=r.free_running())
            bl.progress(f"  {c['name']:<14} {tag:<15} {len(cyc):>6} scans  cycles "
                        f"min {lo} median {med:g} max {hi}")
        if any(bl.split_mode(m)[0] == "parallel" for m in modes):
            entry["partition"] = bl.partition_report(c["prog"], bl.BUILD / "asm" / c["key"])
        out[c["key"]] = entry
    return out


# ---------------------------------------------------------------------- response
def measure_response(modes, f, n_edges: int, out_key: str = "response",
                     program: str = "response.il") -> dict:
    prog = PROG / program
    st = bl.static_counts(prog)
    word_cost = bl.cost_table("paper")["word"]
    i_read = st.find("LD", "P" + gen_programs.RESPONSE_PIN)
    i_write = st.find("=", gen_programs.RESPONSE_PQ)
    read_off, write_off = st.offset(i_read, word_cost), st.offset(i_write, word_cost)
    result = dict(program=str(prog.relative_to(ROOT)), n_edges=n_edges,
                  read_offset=read_off, write_offset=write_off, modes={})
    for mode in modes:
        # the scan length first (no stimulus), then edges spread over 1-scan-wide gaps
        mtag = mode.replace(":", "_")
        pre = bl.run_bitbyte(prog, mode=mode, clock_mhz=f, scans=20,
                             trace=bl.BUILD / "traces" / f"response_pre.{mtag}.csv")
        if not pre.ok or not pre.rows:
            result["modes"][mode] = dict(error=pre.stderr.strip()[-300:])
            continue
        scan = max(pre.cycles)
        rng = random.Random(SEED + 7)
        edges = bl.random_edges(n_edges, scan, f, rng)
        # the rest of the plant moves too: one random input change per scan on
        # average, so the conditional jumps after the rungs vary the scan length
        span = edges[-1] + Fraction(4 * scan) / f
        bits = [f"I{b}.{n}" for b in range(gen_programs.IN_BYTES) for n in range(8)]
        state = dict.fromkeys(bits, 0)
        background = []
        for _ in range(int(span * f / scan)):
            t = Fraction(rng.randrange(1, int(span * 1000)), 1000)
            b = rng.choice(bits)
            background.append((t, b, None))
        background.sort()
        for i, (t, b, _) in enumerate(background):
            state[b] ^= 1
            background[i] = (t, b, state[b])
        stim = bl.BUILD / f"response.{mtag}.stim.csv"
        bl.write_edge_stimulus(stim, gen_programs.RESPONSE_PIN, edges, background)
        until = bl.fmt_us(edges[-1] + Fraction(4 * scan) / f)
        bl.progress(f"  response {mode}: {n_edges} edges over {until} us "
                    f"(~{int(Fraction(until) * f / scan)} scans)")
        trace = bl.BUILD / "traces" / f"response.{mtag}.csv"
        r = bl.run_bitbyte(prog, mode=mode, clock_mhz=f, stimulus=stim, until_us=until,
                           trace=trace)
        if not r.ok:
            result["modes"][mode] = dict(error=r.stderr.strip()[-300:])
            continue
        q_img = gen_programs.RESPONSE_Q
        q_dir = gen_programs.RESPONSE_PQ[1:]           # PQ15.6 is traced as Q15.6
        img = bl.responses(r, edges, f, q_img, "image")
        exact = mode == "serial"
        drc = bl.responses(r, edges, f, q_dir, "direct",
                           write_offset=write_off if exact else None,
                           read_offset=read_off if exact else None)
        m = {}
        for resp in (img, drc):
            clocks = [float(x) for x in resp.clocks]
            lo, med, hi = bl.quantiles(clocks)
            p99 = bl.quantiles(clocks, (0.99,))[0]
            m[resp.kind] = dict(clocks=clocks, phase=resp.phase, min=lo, median=med,
                                max=hi, p99=p99, bound=resp.bound, exact=resp.exact,
                                note=resp.note, scan_min=resp.scan_min,
                                scan_max=resp.scan_max,
                                within_bound=hi < resp.bound,
                                local_ok=resp.local_ok)
            bl.progress(f"    {resp.kind:<6}: clocks min {lo:.1f} median {med:.1f} "
                        f"max {hi:.1f}  bound {resp.bound}  "
                        f"({'ok' if hi < resp.bound else 'EXCEEDED'})")
        m["scans"] = len(r.rows)
        m["free"] = r.free_running()
        m["trace"] = str(trace.relative_to(ROOT))
        m["stimulus"] = str(stim.relative_to(ROOT))
        result["modes"][mode] = m
    return result


# ---------------------------------------------------------------------- sim speed
def measure_simspeed(f, quick: bool) -> dict:
    prog = PROG / "table1.il"
    out = {}
    # Verilator C++ harness: its own figure (M clocks/s over the scan loop) and wall
    n = 4000 if quick else 20000
    best = None
    for _ in range(2):
        r = bl.run_bitbyte(prog, clock_mhz=f, scans=n, trace=bl.BUILD / "traces" /
                           "speed.harness.csv")
        if r.ok and (best is None or (r.mclocks_per_s() or 0) > (best.mclocks_per_s() or 0)):
            best = r
    clocks = best.rows[-1][1]
    out["harness"] = dict(label="Verilator C++ harness (sim/build/Vbitbyte_cpu)",
                          scans=n, clocks=clocks, mclocks_s=best.mclocks_per_s(),
                          wall_s=best.wall_s,
                          note="summary's `M clocks/s` (scan loop); wall = whole "
                               "`bitbyte run` incl. Python start-up and trace reading")
    bl.progress(f"  harness: {best.mclocks_per_s()} M clocks/s ({clocks} clocks, "
                f"{best.wall_s:.2f} s wall)")

    from bitbyte.run.prepare import prepare_run
    from bitbyte.sim.cocotb_runner import run_jobs

    for sim, n_small, n_large in (("verilator", 2, 12 if quick else 150),
                                  ("icarus", 2, 6 if quick else 50)):
        def job(scans):
            return prepare_run(str(prog), scans=scans,
                               clock_mhz=bl.clock_mhz_text(f))[2]
        t0 = time.perf_counter()
        run_jobs([job(1)], sim)                 # build (or the up-to-date check)
        first = time.perf_counter() - t0
        times = {}
        clocks = {}
        for scans in (n_small, n_large):
            best_t = None
            for _ in range(2):                  # best of 2: the machine is shared
                j = job(scans)
                t0 = time.perf_counter()
                (res,) = run_jobs([j], sim)
                dt = time.perf_counter() - t0
                best_t = dt if best_t is None else min(best_t, dt)
            times[scans], clocks[scans] = best_t, res.clocks
        dclk = clocks[n_large] - clocks[n_small]
        dt = times[n_large] - times[n_small]
        speed = dclk / dt if dt > 0 else float("nan")
        out[f"cocotb_{sim}"] = dict(
            label=f"cocotb on {'Verilator' if sim == 'verilator' else 'Icarus'}",
            scans=n_large, clocks=clocks[n_large], wall_s=times[n_large],
            mclocks_s=speed / 1e6, overhead_s=times[n_small] - clocks[n_small] /
            speed if speed == speed else float("nan"), first_call_s=first,
            note=f"run_jobs([job], '{sim}'); speed = extra clocks / extra time between "
                 f"{n_small} and {n_large} scans (best of 2 each), so the simulator "
                 f"start-up and the build check are not in it")
        bl.progress(f"  cocotb {sim}: {speed / 1e3:.1f} k clocks/s "
                    f"({clocks[n_large]} clocks in {times[n_large]:.2f} s, "
                    f"first call {first:.1f} s)")
    mt = os.environ.get("BENCH_MAKE_TEST_SECONDS")
    src = "environment variable BENCH_MAKE_TEST_SECONDS"
    if not mt and (ROOT / "build" / "make_test_seconds").exists():
        mt = (ROOT / "build" / "make_test_seconds").read_text().split()[0]
        src = "build/make_test_seconds"
    out["make_test"] = dict(seconds=float(mt) if mt else None,
                            source=src if mt else None)
    return out


# ---------------------------------------------------------------------- main
def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="make bench")
    ap.add_argument("--modes", default=os.environ.get("BENCH_MODES", "serial,parallel,free:queue-free"))
    ap.add_argument("--edges", type=int, default=int(os.environ.get("BENCH_EDGES", 1000)))
    ap.add_argument("--quick", action="store_true", help="fewer scans (a smoke run)")
    ap.add_argument("--no-cocotb", action="store_true", help="skip the cocotb speed runs")
    args = ap.parse_args(argv)
    t_start = time.perf_counter()
    rev = bl.source_rev()      # taken first: the figures are of the tree as it starts
    bl.BUILD.mkdir(parents=True, exist_ok=True)
    try:
        import matplotlib  # noqa: F401  (the plots; pinned in requirements.txt)
    except ImportError:
        print("bench: matplotlib is missing from this Python; `make venv` installs the "
              "pinned one (requirements.txt)", file=sys.stderr)
        return 1

    gen_programs.main(["--seed", str(SEED)])
    f, f_src = bl.synth_clock()
    bl.progress(f"clock {bl.mhz_text(f)} MHz ({f_src})")

    asked = [m.strip() for m in args.modes.split(",") if m.strip()]
    modes, mode_status = [], {}
    for m in asked:
        ok, msg = bl.probe_mode(m, f)
        mode_status[m] = dict(available=ok, message=msg)
        bl.progress(f"mode {m}: {'available' if ok else 'not available: ' + msg}")
        if ok:
            modes.append(m)
    if "serial" not in modes:
        print("bench: serial mode does not run; nothing to measure", file=sys.stderr)
        return 1

    steps = 5 if args.no_cocotb else 6     # the phases below, for the progress lines
    bl.progress(f"[1/{steps}] scan time (harness) ...")
    cases = scan_cases(f, args.quick)
    scan = measure_scan(cases, modes, f)
    bl.progress("  --tc-path channel vs status, Table-1 program ...")
    tc_path = tc_path_bench.measure(next(c for c in cases if c["key"] == "table1"), f)
    bl.progress("  bit-engine throughput (issue 18) ...")
    bit_engine = bit_engine_bench.measure(args.quick)
    bl.progress(f"[2/{steps}] response time: {args.edges} edges per mode ...")
    resp = measure_response(modes, f, args.edges)
    bl.progress(f"[3/{steps}] response time, fast bit logic next to slow word logic ...")
    resp_fast = measure_response(modes, f, args.edges, "response_fast", "response_fast.il")
    if args.no_cocotb:
        speed = {}
    else:
        bl.progress(f"[4/{steps}] simulator speed (harness, cocotb on Verilator and Icarus) ...")
        speed = measure_simspeed(f, args.quick)

    bl.progress(f"[{steps - 1}/{steps}] single-MCU baseline ...")
    mcu = mcu_baseline.bit_cost(PROG / "table1.il")
    bl.progress(f"single-MCU baseline: {mcu['b']} clocks of 0.1 µs per bit instruction "
                f"(8051 interpreter on a {mcu['mcu_mhz']:g} MHz DS80C320; native code "
                f"{mcu['b_native']})")
    load = os.getloadavg() if hasattr(os, "getloadavg") else None
    results = dict(rev=rev, clock_mhz=float(f), clock_source=f_src, c320_mhz=float(C320_MHZ),
                   modes=mode_status, scan=scan, response=resp,
                   response_fast=resp_fast, simspeed=speed, tc_path=tc_path,
                   bit_engine=bit_engine,
                   seed=SEED, quick=args.quick, load_avg=load, cpus=os.cpu_count(),
                   bench_wall_s=time.perf_counter() - t_start,
                   costs=dict(paper=bl.cost_table("paper"), c320=bl.cost_table("c320")),
                   mcu=mcu, mcu_listing=mcu_baseline.listing(),
                   mcu_bit_costs=sorted(set(MCU_BIT_COSTS) | {
                       mcu["b"], mcu["b_native"], mcu["b_25mhz"]}))
    (bl.BUILD / "results.json").write_text(json.dumps(results, indent=1))
    bl.progress(f"[{steps}/{steps}] report ...")
    import report
    report.write_report(results)
    bl.progress(f"done in {time.perf_counter() - t_start:.0f} s: docs/performance.md")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
