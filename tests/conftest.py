import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))


def pytest_configure(config):
    # One seed per run for the random tests, shared with the xdist workers (they
    # inherit the controller's environment). Reproduce a run with BITBYTE_SEED=<n>.
    os.environ.setdefault("BITBYTE_SEED", str(int(time.time()) % 1_000_000))


def pytest_report_header(config):
    return f"random test seed: BITBYTE_SEED={os.environ.get('BITBYTE_SEED')}"
