"""Build and run one cocotb test module against one RTL top on one simulator.

Every tb/test_<module>.py calls `run_cocotb` from a pytest function parametrized over
SIMULATORS, so that `pytest` runs each module's cocotb tests on Icarus and Verilator.
Build directories are per (top, simulator, parameters) and reused between runs.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path

from cocotb_tools.runner import get_runner

ROOT = Path(__file__).resolve().parents[1]
RTL = ROOT / "rtl"
SIMULATORS = ("icarus", "verilator")


def rtl_sources() -> list[Path]:
    return sorted(RTL.glob("*.v"))


def run_cocotb(sim: str, toplevel: str, test_module: str,
               parameters: dict | None = None, extra_env: dict | None = None,
               testcase: str | None = None) -> None:
    """Build `toplevel` from rtl/ and run the cocotb tests of `test_module` on `sim`.

    Raises (via cocotb's runner) when any cocotb test fails."""
    parameters = parameters or {}
    tag = hashlib.sha1(repr(sorted(parameters.items())).encode()).hexdigest()[:8]
    build_dir = ROOT / "tb" / "build" / f"{toplevel}-{sim}-{tag}"
    runner = get_runner(sim)
    build_args = []
    if sim == "verilator":
        build_args = ["-Wno-fatal", "-j", "2"]
    runner.build(
        sources=rtl_sources(),
        includes=[RTL],
        hdl_toplevel=toplevel,
        parameters=parameters,
        build_dir=build_dir,
        build_args=build_args,
        timescale=("1ns", "1ps"),
        waves=False,
    )
    env = dict(extra_env or {})
    env.setdefault("PYTHONPATH", os.pathsep.join([str(ROOT / "tb"), str(ROOT)]))
    runner.test(
        hdl_toplevel=toplevel,
        test_module=test_module,
        build_dir=build_dir,
        test_dir=build_dir,
        extra_env=env,
        testcase=testcase,
    )
