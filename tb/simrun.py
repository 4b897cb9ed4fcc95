"""Build and run one cocotb test module against one RTL top on one simulator.

Every tb/test_<module>.py calls `run_cocotb` from a pytest function parametrized over
SIMULATORS, so that `pytest` runs each module's cocotb tests on Icarus and Verilator
(Verilator in the slow tier: make test-slow, make soak; the CPU's cocotb tests in
tests/ take Verilator in make test).
Build directories are per (top, simulator, parameters) and reused between runs.
"""
from __future__ import annotations

import hashlib
from pathlib import Path

import pytest

from bitbyte.sim.cocotb_runner import build_and_test

ROOT = Path(__file__).resolve().parents[1]
SIMULATORS = ("icarus", pytest.param("verilator", marks=pytest.mark.slow))


def run_cocotb(sim: str, toplevel: str, test_module: str,
               parameters: dict | None = None, extra_env: dict | None = None,
               testcase: str | None = None) -> None:
    """Build `toplevel` from rtl/ and run the cocotb tests of `test_module` on `sim`;
    raises when any cocotb test fails."""
    parameters = parameters or {}
    tag = hashlib.sha1(repr(sorted(parameters.items())).encode()).hexdigest()[:8]
    build_dir = ROOT / "tb" / "build" / f"{toplevel}-{sim}-{tag}"
    build_and_test(sim, toplevel, test_module, build_dir, parameters, extra_env, testcase)
