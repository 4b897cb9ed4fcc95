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


# The modules that take longest (pytest --durations on 2 cores, 2026-12-03, after the
# Verilator builds went through ccache) run
# first, so that pytest-xdist does not hand one of them out last while the other
# worker idles; each module's own order is kept (module fixtures are set up once).
SLOW_FIRST = (
    "tests/test_formal.py",
    "tests/test_plant_cocotb.py",
    "tests/test_random_programs.py",
    "tests/test_alloc.py",
    "tests/test_cpu_directed.py",
    "tests/test_examples.py",
    "tests/test_link.py",
    "tb/test_core_seq.py",
    "tests/test_plant_tearing.py",
    "tests/test_plant_run.py",
    "tests/test_random_parallel.py",
    "tests/test_partition_adversarial.py",
)


def pytest_collection_modifyitems(session, config, items):
    def rank(item):
        module = item.nodeid.split("::")[0]
        return SLOW_FIRST.index(module) if module in SLOW_FIRST else len(SLOW_FIRST)
    items.sort(key=rank)
