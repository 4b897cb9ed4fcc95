#!/usr/bin/env python3
"""The Table-1 program with `--tc-path channel` and `--tc-path status` side by side
(issue 16 item 1, docs/exchange.md): transfers per scan from the partition, clocks per
scan from the run, in parallel and free-running mode.

    python bench/tc_path_bench.py [--quick]

run_bench.py (make bench) calls measure() and report.py renders the section; run
alone, this measures just that and rewrites the section of docs/performance.md between
its markers (the rest of the file stays as make bench wrote it).
"""
from __future__ import annotations

import argparse
import json
import statistics
import sys
from fractions import Fraction
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))

import benchlib as bl                     # noqa: E402

PATHS = ("channel", "status")
MODES = ("parallel", "free:queue-free", "free:marker")
BEGIN = "<!-- tc-path: bench/tc_path_bench.py -->"
END = "<!-- /tc-path -->"


def _partition_counts(prog: Path, mode: str, tc_path: str) -> dict:
    """Transfers per direction and status-buffer writes per straight-line scan, as the
    partitioning compiler makes them (bitbyte.run.prepare's settings for the mode)."""
    from bitbyte.compiler.partition import partition
    from bitbyte.lang.parser import parse_file
    free = mode == "free"
    part = partition(parse_file(str(prog)), 4, status_sync=not free,
                     hardware_wait=not free, tc_path=tc_path)
    return dict(to_byte=sum(t.direction == "to_byte" for t in part.transfers),
                to_bit=sum(t.direction == "to_bit" for t in part.transfers),
                status=sum(1 for i in part.byte if i.from_status),
                bit=len(part.bit), byte=len(part.byte))


def measure(case: dict, f: Fraction) -> dict:
    """case: run_bench.scan_cases' Table-1 entry (program, stimulus, scans)."""
    out = dict(program=str(case["prog"].relative_to(bl.ROOT)), scans=case["scans"],
               clock_mhz=float(f), rev=bl.source_rev(), runs=[])
    for spec in MODES:
        mode, _ = bl.split_mode(spec)
        for tp in PATHS:
            trace = bl.BUILD / "traces" / f"table1.{spec.replace(':', '_')}.tc_{tp}.csv"
            r = bl.run_bitbyte(case["prog"], mode=spec, clock_mhz=f, stimulus=case["stim"],
                               scans=case["scans"], trace=trace, extra=["--tc-path", tp])
            if not r.ok or not r.rows:
                raise RuntimeError(f"{spec} --tc-path {tp}: {r.stderr.strip()[-300:]}")
            cyc = r.cycles
            stalls = r.stalls()
            run = dict(mode=spec, tc_path=tp, median=statistics.median(cyc),
                       mean=sum(cyc) / len(cyc), max=max(cyc), scans=len(cyc),
                       stalls_per_scan=[x / len(cyc) for x in stalls] if stalls else None,
                       free=r.free_running(), **_partition_counts(case["prog"], mode, tp))
            out["runs"].append(run)
            bl.progress(f"  tc-path {spec:<16} {tp:<8} median {run['median']:g} clocks, "
                        f"transfers {run['to_byte']} / {run['to_bit']}, "
                        f"status {run['status']}")
    return out


def markdown(res: dict) -> list[str]:
    """The section's lines (with its markers)."""
    L = [BEGIN, "", "### Timer / counter inputs: `--tc-path channel` vs `status` "
         "(issue 16 item 1)", "",
         f"The Table-1 program (`{res['program']}`, {res['scans']} scans, the stimulus of "
         f"§1, {res['clock_mhz']:g} MHz; measured at `{res.get('rev', '?')}`). "
         "*Transfers* are per straight-line scan as the "
         "compiler makes them (bit → byte / byte → bit); *status* counts the byte "
         "instructions whose enable / count input the bit side leaves in the status buffer "
         "(`= T n` / `= C n`) instead of a channel; in parallel mode the byte side waits for "
         "this scan's write there (the status-wait bit, docs/exchange.md), so both of its "
         "rows keep the serial result. In free-running mode the median is "
         "the bit side's scan, then the byte side's scans (simulated clocks / its scans) and, "
         "with the free-running queues, their losses (overflows / underflows, to-byte and "
         "to-bit); the marker area loses nothing (each crossing has a cell of its own, "
         "read from the reader's snapshot).", "",
         "| mode | --tc-path | transfers bit→byte / byte→bit | via status buffer | "
         "bit part / byte part [instr.] | median / max [clocks] | stalls per scan bit / byte "
         "| free-running: byte side, losses |",
         "|---|---|---|---|---|---|---|---|"]
    for r in res["runs"]:
        st = r["stalls_per_scan"]
        stalls = f"{st[0]:.1f} / {st[1]:.1f}" if st else "—"
        fr = r["free"]
        if fr:
            lo = fr["losses"]
            free = (f"{fr['byte_scans']} scans, mean {fr['byte_scan']:.0f} clocks; losses "
                    f"{lo[0]} / {lo[1]}, {lo[2]} / {lo[3]}" if lo else
                    f"{fr['byte_scans']} scans, mean {fr['byte_scan']:.0f} clocks")
        else:
            free = "—"
        L.append(f"| {r['mode']} | {r['tc_path']} | {r['to_byte']} / {r['to_bit']} | "
                 f"{r['status']} | {r['bit']} / {r['byte']} | {r['median']:g} / {r['max']} | "
                 f"{stalls} | {free} |")
    L += ["", END]
    return L


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="500 scans instead of 3000")
    args = ap.parse_args(argv)
    import gen_programs
    import run_bench
    gen_programs.main(["--seed", str(run_bench.SEED)])
    f, _ = bl.synth_clock()
    case = next(c for c in run_bench.scan_cases(f, args.quick) if c["key"] == "table1")
    res = measure(case, f)
    bl.BUILD.mkdir(parents=True, exist_ok=True)
    (bl.BUILD / "tc_path.json").write_text(json.dumps(res, indent=1))
    doc = bl.ROOT / "docs" / "performance.md"
    doc.write_text(bl.splice_section(doc.read_text(), markdown(res)))
    bl.progress("docs/performance.md: the --tc-path section rewritten")
    return 0


if __name__ == "__main__":
    sys.exit(main())
