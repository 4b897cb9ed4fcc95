"""Free-running mode's exchange against its model (tests/exchange_model.py): random
programs that cross sides run on the Verilator harness with `--exchange-log`; with the
free-running queues every read gives the model's value and the loss counts are the
model's, with the marker area every read keeps the snapshot bound. `make soak` does the
same over its N programs (soak/test_soak.py, free_check). The checks are shown to fail
on a broken log: inverted reads, a loss more, positions not restarting at a scan."""
from __future__ import annotations

import contextlib
import dataclasses
import io
import random
from pathlib import Path

import pytest

from bitbyte import cli
from exchange_model import TO_BIT, TO_BYTE, check_marker, check_queues, losses_of, read_log
from randprog import long_timers, random_parallel_program, random_scan_stimulus

SEEDS = (2, 11, 17, 26)   # parallel-generator programs that cross both ways and lose some
SCANS = 40


def free_run(tmp: Path, seed: int, exchange: str):
    """(crossings, losses by direction or None) of one free-running run."""
    il, stim, log = tmp / f"p{seed}.il", tmp / f"s{seed}.csv", tmp / f"x{seed}{exchange}.csv"
    il.write_text(long_timers(random_parallel_program(seed), random.Random(seed)))
    stim.write_text(random_scan_stimulus(seed, SCANS))
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        rc = cli.main(["run", str(il), "--stimulus", str(stim), "--scans", str(SCANS),
                       "--mode", "free", "--exchange", exchange, "--exchange-log", str(log)])
    assert rc == 0, out.getvalue()
    crossings, snaps = read_log(log)
    return crossings, snaps, losses_of(out.getvalue())


def inverted_reads(crossings):
    return [c if c.write else dataclasses.replace(c, value=1 - c.value) for c in crossings]


@pytest.mark.parametrize("seed", SEEDS)
def test_free_running_queues_against_the_model(tmp_path, seed):
    crossings, _, losses = free_run(tmp_path, seed, "queue-free")
    kinds = {(c.direction, c.write) for c in crossings}
    assert kinds == {(TO_BYTE, True), (TO_BYTE, False), (TO_BIT, True), (TO_BIT, False)}
    assert check_queues(crossings, losses) is None, check_queues(crossings, losses)
    # broken logs: every read inverted; one loss more; positions counted over the run
    # (the slot pointers not returning to 0 at a scan start)
    assert check_queues(inverted_reads(crossings), losses) is not None
    for direction in (TO_BYTE, TO_BIT):
        for kind in (0, 1):                     # an overflow, an underflow more
            more = list(losses[direction])
            more[kind] += 1
            assert check_queues(crossings, dict(losses, **{direction: tuple(more)})) \
                is not None
    one_scan = [dataclasses.replace(c, scan=0) for c in crossings]
    assert check_queues(one_scan, losses) is not None


@pytest.mark.parametrize("seed", SEEDS)
def test_marker_area_keeps_the_snapshot_bound(tmp_path, seed):
    crossings, snaps, _ = free_run(tmp_path, seed, "marker")
    assert sum(not c.write for c in crossings) >= 20
    assert check_marker(crossings, snaps) is None, check_marker(crossings, snaps)
    # broken logs: every read inverted; a snapshot never taken (every read 0); each
    # scan reading what the scan before read (a snapshot a scan late)
    assert check_marker(inverted_reads(crossings), snaps) is not None
    never = [c if c.write else dataclasses.replace(c, value=0) for c in crossings]
    assert check_marker(never, snaps) is not None
    before = {}
    for c in crossings:
        if not c.write:
            before.setdefault((c.side, c.scan, c.cell), c.value)
    late = [c if c.write else dataclasses.replace(
        c, value=before.get((c.side, c.scan - 1, c.cell), c.value)) for c in crossings]
    assert check_marker(late, snaps) is not None


@pytest.mark.parametrize("extra", [[], ["--mode", "parallel", "--sim", "icarus"]])
def test_exchange_log_needs_crossings_on_verilator(tmp_path, capsys, extra):
    il = tmp_path / "p.il"
    il.write_text("LD I0.0\n= Q0.0\n")
    rc = cli.main(["run", str(il), "--scans", "1", "--exchange-log", str(tmp_path / "x.csv"),
                   *extra])
    assert rc != 0 and "--exchange-log: parallel and free-running mode on Verilator" \
        in capsys.readouterr().err
    assert not (tmp_path / "x.csv").exists()
