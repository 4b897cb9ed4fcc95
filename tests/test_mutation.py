"""A small fixed sample of `make mutate` (mutation/run_mutate.py): three mutants of
cond_ff built into one netlist and run through its cocotb bench must all be killed
while the unmutated netlist (mutsel 0) passes; and the miter check proves a mutation
that cannot change anything equivalent, and finds the difference a real one makes."""
from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "mutation"))
import mutlib  # noqa: E402
import run_mutate  # noqa: E402


def test_three_cond_ff_mutants_are_killed(tmp_path):
    campaign = next(c for c in run_mutate.CAMPAIGNS if c.name == "cond_ff")
    res = run_mutate.run_tests(campaign, seed=1, count=3, work=tmp_path)
    assert [m["home"] for m in res["mutations"]] == ["cond_ff"] * 3
    assert all(o == "pass" for o, _ in res["baseline"].values()), res["baseline"]
    assert sorted(int(k) for k in res["killed"]) == [1, 2, 3]


@pytest.fixture(scope="module")
def queue_netlist(tmp_path_factory):
    """cond_queue (Depth 4) with three mutations of the saturation test
    `underflows_o != 16'hFFFF`: 1 = bit 13 of the constant stuck at 1 (it is 1: no
    change), 2 = stuck at 0 (the counter stops at 16'hDFFF, 57 343 underflows after
    reset), 3 = the compare inverted (the counter never counts: one underflow shows)."""
    work = mutlib.prepare_dir(tmp_path_factory.mktemp("eq") / "elab")
    script = mutlib.elab_script("cond_queue", {"Depth": 4})
    cands = mutlib.candidates(work, script, ["cond_queue"], "all")
    src = (mutlib.RTL / "cond_queue.v").read_text().splitlines()
    line = next(i for i, t in enumerate(src, 1) if "underflows_o != 16'hFFFF" in t)
    picked = []
    for mode, port, bit in (("const1", "B", 13), ("const0", "B", 13), ("inv", "Y", 0)):
        (m,) = [c for c in cands if c.mode == mode and c.cell.startswith("$ne$")
                and c.port == port and c.portbit == bit
                and any(re.match(rf"cond_queue\.v:{line}\.", s) for s in c.srcs)]
        m.id = len(picked) + 1
        picked.append(m)
    return mutlib.write_netlist(work, script, "cond_queue", picked, "mutants")


def test_no_op_mutant_is_proved_equivalent(queue_netlist, tmp_path):
    assert mutlib.equivalence(tmp_path, queue_netlist, "cond_queue", 1, 8, 300) == "equivalent"


def test_deep_difference_is_not_called_equivalent(queue_netlist, tmp_path):
    # beyond the k-induction's depth from reset: no proof either way, never "equivalent"
    assert mutlib.equivalence(tmp_path, queue_netlist, "cond_queue", 2, 8, 300) == "unknown"


def test_difference_is_found(queue_netlist, tmp_path):
    assert mutlib.equivalence(tmp_path, queue_netlist, "cond_queue", 3, 8, 300) == "different"
