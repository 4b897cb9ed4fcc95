"""Run a multi-core plant through cocotb (Icarus or Verilator): the counterpart of
`bitbyte.plant.run.run_plant`'s Verilator C++ harness, with the same traces.

`run_plant_cocotb` builds rtl/ with the toplevel plc_system (Cores = the plant's
core count) once per simulator and core count under build/cocotb-plant<cores>-<sim>/
and runs the cocotb test module `bitbyte.sim.cocotb_plant`, which drives the plant clock
for clock exactly as sim/plant_harness.cpp does.
"""
from __future__ import annotations

import csv
import fcntl
import json
from pathlib import Path

from bitbyte.plant.plans import PlantRunError, period_clocks
from bitbyte.run.summary import hw_mode_text, plant_summary_text
from bitbyte.sim.cocotb_runner import ROOT, build_and_test, build_firmware

FIRMWARE_LIB = ROOT / "firmware_byte" / "build" / "libbyteproc_cb.so"
SIMS = ("icarus", "verilator")


def run_plant_cocotb(shared_map, jobs, plans, until_clock: int, sim: str,
                     trace_base: str | None, tmpdir, *, fast: bool = True
                     ) -> tuple[int, str, dict]:
    """Run the linked plant on cocotb + `sim` until every core has finished a scan
    ending at or after `until_clock`.

    shared_map, jobs, plans, until_clock: as `bitbyte.plant.run.prepare_plant` returns them.
    trace_base: the traces go to `<trace_base>.<core>.csv` (else into tmpdir).
    fast: let the simulator clock stretches where every core's firmware is idle on
    its own (bitbyte.sim.cocotb_plant.Plant.fast_forward); False clocks every clock from
    Python (slower, the same traces).
    Returns (status, summary text, {core name: trace rows as csv.DictReader gives}),
    status 0, or 3 when a core's scan watchdog fired (as the plant harness)."""
    if sim not in SIMS:
        raise PlantRunError(f"unknown simulator {sim!r} (cocotb runs {', '.join(SIMS)})")
    plant = shared_map.plant
    tmp = Path(tmpdir)
    build_firmware()            # one library for all cores: a HAL context per core
    traces = [(f"{trace_base}.{core.name}.csv" if trace_base
               else str(tmp / f"trace.{core.name}.csv")) for core in plant.cores]
    results = tmp / "plant_results.json"
    cfg = {
        "clock_hz": jobs[0].clock_hz,
        "watchdog": jobs[0].watchdog,
        "until_clock": until_clock,
        "fast": fast,
        "protect": plant.protection,
        "lib": str(FIRMWARE_LIB),
        "results": str(results),
        "cores": [{"name": core.name, "job": job.to_json(), "plan": plan.words,
                   "period": period_clocks(core.period_us, plant.clock_mhz),
                   "pre_len": plan.pre_len, "post_base": plan.post_base,
                   "post_len": plan.post_len, "trace": trace}
                  for core, job, plan, trace in zip(plant.cores, jobs, plans, traces)],
    }
    cfg_path = tmp / "plant_cocotb.json"
    cfg_path.write_text(json.dumps(cfg))
    cores = len(plant.cores)
    build_dir = ROOT / "build" / f"cocotb-plant{cores}-{sim}"
    build_dir.mkdir(parents=True, exist_ok=True)
    # One build directory per simulator and core count (plc_system's Cores), shared
    # by concurrent runs: serialise.
    with open(build_dir / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            build_and_test(sim, "plc_system", "bitbyte.sim.cocotb_plant", build_dir,
                           parameters={"Cores": cores},
                           extra_env={"BITBYTE_PLANT": str(cfg_path)}, quiet=True)
        except (SystemExit, RuntimeError, OSError) as e:
            raise PlantRunError(f"cocotb on {sim} failed: {e}\n{_log_tail(build_dir)}") \
                from None
        if not results.exists():
            raise PlantRunError(f"cocotb on {sim} wrote no results\n{_log_tail(build_dir)}")
    res = json.loads(results.read_text())
    rows = {}
    for core, path in zip(plant.cores, traces):
        with open(path, newline="") as f:
            rows[core.name] = list(csv.DictReader(f))
    summary = plant_summary_text(plant.protection, jobs[0].clock_hz, res["clocks"],
                                 [(c.name, hw_mode_text(*res["modes"][c.name]), rows[c.name],
                                   res["skips"][c.name])
                                  for c in plant.cores])
    summary += res["stderr"] if res["status"] == 3 else ""
    return res["status"], summary, rows


def _log_tail(build_dir: Path, lines: int = 40) -> str:
    log = build_dir / "sim.log"
    if not log.exists():
        log = build_dir / "build.log"
    if not log.exists():
        return ""
    return "\n".join(log.read_text(errors="replace").splitlines()[-lines:])
