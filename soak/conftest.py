"""The soak's pytest setup: the generators of tests/randprog.py and one seed per run,
shared with the xdist workers (BITBYTE_SEED=<n> repeats a run)."""
import os
import sys
import time
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "tests"))


def pytest_configure(config):
    os.environ.setdefault("BITBYTE_SEED", str(int(time.time()) % 1_000_000))


def pytest_report_header(config):
    return (f"soak: BITBYTE_SEED={os.environ.get('BITBYTE_SEED')}, "
            f"N={os.environ.get('BITBYTE_SOAK_N', '100')} programs")


class _Progress:
    """Every tenth of the soak's items (on the controller, after xdist's reports): how
    many are done and the time left at this pace, on stderr; pytest -q's dots say the
    rest."""

    def __init__(self):
        self.total = self.done = 0
        self.t0 = time.monotonic()
        self.next = 0.1

    def collected(self, n: int) -> None:
        self.total, self.t0 = n, time.monotonic()

    def finished(self) -> None:
        self.done += 1
        if self.total and self.done / self.total >= self.next:
            self.next += 0.1
            run = time.monotonic() - self.t0
            left = run * (self.total - self.done) / self.done
            sys.stderr.write(f"\nsoak: {self.done}/{self.total} items, {run / 60:.1f} min so "
                             f"far, about {left / 60:.1f} min left\n")


_PROGRESS = _Progress()
_STL = {}     # kind -> [compared, rejected, mismatches], from soak/test_stl_soak.py's chunks


def pytest_collection_finish(session):
    if not os.environ.get("PYTEST_XDIST_WORKER"):
        _PROGRESS.collected(len(session.items))


def pytest_runtest_logreport(report):
    if report.when == "teardown" and not os.environ.get("PYTEST_XDIST_WORKER"):
        _PROGRESS.finished()
    if report.when == "call":
        for _, (kind, *counts) in (p for p in report.user_properties
                                   if p[0] == "stl_soak"):
            _STL[kind] = [a + b for a, b in zip(_STL.get(kind, [0, 0, 0]), counts)]


def pytest_xdist_node_collection_finished(node, ids):
    """With xdist the controller learns the count from the workers (each collects all)."""
    _PROGRESS.collected(len(ids))


def pytest_terminal_summary(terminalreporter):
    """The S7 soak's counts: each compared program equals awlsim's on the reference
    interpreter (serial) and on the Verilator harness in serial and parallel mode
    (both exchanges)."""
    for kind, (compared, rejected, mismatches) in sorted(_STL.items()):
        terminalreporter.write_line(
            f"stl soak {kind}: {compared} programs compared with awlsim (ref serial, "
            f"verilator serial, verilator parallel handshake and queue), {rejected} "
            f"rejected as "
            f"unsupported, {mismatches} mismatching (BITBYTE_SEED="
            f"{os.environ.get('BITBYTE_SEED')})")
