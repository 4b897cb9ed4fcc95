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
