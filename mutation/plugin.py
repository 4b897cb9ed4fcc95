"""pytest plugin: run the selected tests once per mutant (mutation/run_mutate.py).

Loaded with `-p plugin` (mutation/ on PYTHONPATH) and configured by the JSON file
named in BITBYTE_MUTATION. Every selected test item runs first on the original
(mutsel 0; that run is the one pytest reports) and then once per mutant not yet
killed, inside the same session, so module fixtures (the random programs and their
reference traces) are made once. A mutant is killed by an item that fails on it
while passing on the original; its record says which item and how (fail/timeout).

Two ways a test reaches the mutated design:
- cocotb benches (tb/): simrun.run_cocotb is replaced by one that elaborates the
  bench's top with the bench's own parameters, builds the mutant netlist once per
  (top, parameters, simulator) and runs the bench with +mutsel=<id>. The first
  elaboration samples the mutations; a later one with other parameters gets them
  mapped by key (mutlib.map_mutations), the unmapped ones skipped there.
- the Verilator harness (campaign "harness"): the netlist of bitbyte_cpu is built into
  its own harness binary at the start (the wide campaign: with BitEngine=1, the wide
  harness, BITBYTE_HARNESS_WIDE); BITBYTE_HARNESS names it and
  BITBYTE_HARNESS_ARGS passes +mutsel=<id> (bitbyte/sim/verilator.py).
- the plant harness (campaign "plant"): the netlist of plc_system with two cores is
  built into its own plant harness; BITBYTE_PLANT_HARNESS_2 names it and the same
  BITBYTE_HARNESS_ARGS passes +mutsel=<id> (bitbyte/plant/run.py).
"""
from __future__ import annotations

import hashlib
import json
import os
import signal
import subprocess
import threading
import time
from pathlib import Path

import pytest
from _pytest.runner import runtestprotocol

import mutlib

CONFIG = os.environ.get("BITBYTE_MUTATION")


class Campaign:
    def __init__(self, cfg: dict):
        self.cfg = cfg
        self.work = Path(cfg["work"])
        self.mutations: list[mutlib.Mutation] = []
        self.home = None            # (sigs, full candidate list) of the sampling elaboration
        self.netlists: dict = {}     # (top, params) -> (netlist, mapped ids)
        self.items: dict = {}        # nodeid -> {id: outcome}
        self.killed: dict = {}       # id -> (nodeid, outcome)
        self.baseline: dict = {}     # nodeid -> (outcome, seconds)
        self.elabs: list = []
        self.current = 0             # the mutsel of the run under way
        self.timed_out = False

    # -- elaboration ---------------------------------------------------------------
    def netlist(self, top: str, params: dict) -> tuple[Path, set]:
        key = (top, tuple(sorted(params.items())))
        if key in self.netlists:
            return self.netlists[key]
        tag = hashlib.sha1(repr(key).encode()).hexdigest()[:8]
        work = mutlib.prepare_dir(self.work / f"{top}-{tag}")
        script = mutlib.elab_script(top, params)
        modules = self.cfg["modules"]
        sigs = mutlib.cell_signatures(work, script, "sigs")
        cands = mutlib.candidates(work, script, modules, "all")
        if self.home is None:
            self.mutations = mutlib.list_mutations(work, script, modules, self.cfg["count"],
                                                   self.cfg["seed"], "sample")
            for i, m in enumerate(self.mutations, 1):
                m.id = i
            self.keep_kills()
            self.home = (sigs, cands)
            mapped = {m.id: m for m in self.mutations}
        else:
            mapped = mutlib.map_mutations(self.mutations, self.home[0], cands, sigs,
                                          self.home[1])
        path = mutlib.write_netlist(work, script, top, list(mapped.values()), "mutants")
        self.netlists[key] = (path, set(mapped))
        self.elabs.append({"top": top, "params": params, "dir": str(work),
                           "mapped": sorted(mapped), "candidates": len(cands)})
        return self.netlists[key]

    def keep_kills(self) -> None:
        """The test kills of an earlier run of this sample (cfg "keep": its results.json):
        only the mutants it left alive run again. Sound when tests were only added since
        (run_mutate.py --keep-kills); the sample must be the same mutations."""
        if not self.cfg.get("keep"):
            return
        prev = json.loads(Path(self.cfg["keep"]).read_text())
        if prev["mutations"] != [m.to_json() for m in self.mutations]:
            raise mutlib.MutationError(f"{self.cfg['keep']}: another sample (seed, count or "
                                       "the RTL changed): its kills do not apply")
        for k, (nodeid, outcome) in prev["killed"].items():
            self.killed[int(k)] = (nodeid, f"{outcome} (kept)")

    # -- results ---------------------------------------------------------------------
    def record(self, nodeid: str, mut: int, outcome: str) -> None:
        self.items.setdefault(nodeid, {})[mut] = outcome
        if mut and outcome in ("fail", "timeout") and mut not in self.killed:
            self.killed[mut] = (nodeid, outcome)

    def save(self) -> None:
        out = {"config": self.cfg, "mutations": [m.to_json() for m in self.mutations],
               "elaborations": self.elabs, "baseline": self.baseline,
               "killed": {str(k): v for k, v in self.killed.items()},
               "items": {n: {str(k): v for k, v in r.items()} for n, r in self.items.items()}}
        Path(self.cfg["results"]).write_text(json.dumps(out, indent=1))


CAMPAIGN = Campaign(json.loads(Path(CONFIG).read_text())) if CONFIG else None


def mutant_run_cocotb(sim, toplevel, test_module, parameters=None, extra_env=None,
                      testcase=None):
    """simrun.run_cocotb on the mutant netlist, mutant CAMPAIGN.current."""
    from bitbyte.sim.cocotb_runner import build_and_test
    path, mapped = CAMPAIGN.netlist(toplevel, dict(parameters or {}))
    mut = CAMPAIGN.current
    if mut and mut not in mapped:
        pytest.skip(f"mutant {mut} has no counterpart in {toplevel} {parameters}")
    build_dir = path.parent / f"build-{sim}"
    build_and_test(sim, toplevel, test_module, build_dir, {}, extra_env, testcase,
                   quiet=True, sources=[path], plusargs=[f"+{mutlib.PLUSARG}={mut}"])


def build_harness(cfg: dict) -> None:
    """The mutant netlist of bitbyte_cpu in its own Verilator harness (sim/Makefile);
    cfg "wide": elaborated with BitEngine=1 into the wide harness (harness_wide.cpp;
    the netlist has the parameter set already), named by BITBYTE_HARNESS_WIDE."""
    wide = bool(cfg.get("wide"))
    params = dict(cfg.get("params", {}), **({"BitEngine": 1} if wide else {}))
    path, _ = CAMPAIGN.netlist("bitbyte_cpu", params)
    out = path.parent / "harness"
    t0 = time.time()
    proc = subprocess.run(["make", "-s", "-C", str(mutlib.ROOT / "sim"), "harness",
                           f"OUT={out}", f"RTL_SOURCES={path}", "TRACE=none"]
                          + (["BIT_ENGINE=wide", "ENGINE_FLAGS="] if wide else []),
                          capture_output=True, text=True)
    if proc.returncode != 0:
        raise mutlib.MutationError(f"{path}: harness build failed:\n{proc.stderr[-3000:]}")
    CAMPAIGN.elabs[-1]["harness_build_s"] = round(time.time() - t0, 1)
    os.environ["BITBYTE_HARNESS_WIDE" if wide else "BITBYTE_HARNESS"] = str(out / "Vbitbyte_cpu")


def build_plant_harness(cfg: dict) -> None:
    """The mutant netlist of plc_system (Cores = 2) in its own plant harness: the
    plant runs (`bitbyte run PLANT.toml`, bitbyte.plant.run) of two-core plants take
    it through BITBYTE_PLANT_HARNESS_2."""
    params = dict(cfg.get("params", {}))
    cores = int(params.setdefault("Cores", 2))
    path, _ = CAMPAIGN.netlist("plc_system", params)
    out = path.parent / "harness"
    (out / f"plant{cores}").mkdir(parents=True, exist_ok=True)   # Verilator's -Mdir
    t0 = time.time()
    proc = subprocess.run(["make", "-s", "-C", str(mutlib.ROOT / "sim"), "plant",
                           f"OUT={out}", f"RTL_SOURCES={path}", f"CORES={cores}",
                           "PLANT_GFLAGS=", "TRACE=none"],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        raise mutlib.MutationError(f"{path}: plant harness build failed:\n{proc.stderr[-3000:]}")
    CAMPAIGN.elabs[-1]["harness_build_s"] = round(time.time() - t0, 1)
    os.environ[f"BITBYTE_PLANT_HARNESS_{cores}"] = str(out / f"plant{cores}" / "Vplc_system")


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(session, config, items):
    """The campaign's tests run in the order its list gives (the cheap test that kills
    most first), not in the regression's slow-first order (tests/conftest.py)."""
    if CAMPAIGN is None:
        return
    order = CAMPAIGN.cfg.get("tests", [])

    def rank(item):
        for k, spec in enumerate(order):
            if item.nodeid == spec or item.nodeid.startswith(spec + "::") or \
                    item.nodeid.startswith(spec + "["):
                return k
        return len(order)
    items.sort(key=rank)


def pytest_configure(config):
    if CAMPAIGN is None:
        return
    # The benches import run_cocotb from tb/simrun.py when they are collected, after
    # this: they get the mutant runner.
    import sys
    sys.path.insert(0, str(mutlib.ROOT / "tb"))
    import simrun
    simrun.run_cocotb = mutant_run_cocotb
    if CAMPAIGN.cfg.get("harness"):
        build_harness(CAMPAIGN.cfg)
    if CAMPAIGN.cfg.get("plant"):
        build_plant_harness(CAMPAIGN.cfg)


def set_mutant(mut: int) -> None:
    CAMPAIGN.current = mut
    os.environ["BITBYTE_HARNESS_ARGS"] = f"+{mutlib.PLUSARG}={mut}"


def kill_children() -> None:
    """End the simulators this process started (its direct children, by pid)."""
    me = os.getpid()
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == me:
            try:
                os.kill(int(stat.parent.name), signal.SIGKILL)
            except OSError:
                pass


def run_once(item, nextitem, mut: int, log: bool, timeout: float | None):
    """One run of `item` on mutant `mut`: ('pass'|'fail'|'skip'|'timeout', seconds)."""
    set_mutant(mut)
    CAMPAIGN.timed_out = False
    timer = None
    if timeout:
        def expire():
            CAMPAIGN.timed_out = True
            kill_children()
        timer = threading.Timer(timeout, expire)
        timer.start()
    t0 = time.time()
    if getattr(item, "funcargs", None) is None:
        item._initrequest()   # a run ends with the item's fixtures released (as reruns do)
    try:
        reports = runtestprotocol(item, nextitem=nextitem, log=log)
    finally:
        if timer:
            timer.cancel()
    took = time.time() - t0
    if CAMPAIGN.timed_out:
        return "timeout", took
    failed = [r for r in reports if r.failed]
    if failed:
        CAMPAIGN.last_failure = failed[0].longreprtext[-2000:]
        return "fail", took
    if any(r.skipped for r in reports):
        return "skip", took
    return "pass", took


def pytest_runtest_protocol(item, nextitem):
    if CAMPAIGN is None:
        return None
    item.ihook.pytest_runtest_logstart(nodeid=item.nodeid, location=item.location)
    # Between runs only the item's own (function) fixtures are torn down: the next
    # "item" is its parent, whose fixtures (module scope) stay.
    again = item.parent
    outcome, took = run_once(item, again, 0, True, None)
    CAMPAIGN.baseline[item.nodeid] = (outcome, round(took, 2))
    CAMPAIGN.record(item.nodeid, 0, outcome)
    todo = [] if outcome != "pass" else \
        [m.id for m in CAMPAIGN.mutations if m.id not in CAMPAIGN.killed]
    timeout = max(CAMPAIGN.cfg.get("min_timeout", 30.0), CAMPAIGN.cfg.get("timeout_factor", 5) * took)
    for i, mut in enumerate(todo):
        last = i == len(todo) - 1
        result, _ = run_once(item, nextitem if last else again, mut, False, timeout)
        CAMPAIGN.record(item.nodeid, mut, result)
        if result == "fail" and os.environ.get("BITBYTE_MUTATION_DEBUG"):
            print(f"\n--- mutant {mut}:\n{CAMPAIGN.last_failure}")
    item.ihook.pytest_runtest_logfinish(nodeid=item.nodeid, location=item.location)
    set_mutant(0)
    CAMPAIGN.save()
    return True


def pytest_sessionfinish(session):
    if CAMPAIGN is not None:
        CAMPAIGN.save()
