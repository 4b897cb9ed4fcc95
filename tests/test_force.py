"""Forcing (`bitbyte run --force`, issue 17 item 4): the force table in front of the
I/O units (rtl/force_table.v), written over the byte bus by the simulation hosts.
A directed program with a hand-worked trace on both simulators."""
from __future__ import annotations

import csv
import re
from pathlib import Path

import pytest

from bitbyte.lang.config import Config
from bitbyte.lang.errors import UsageError
from bitbyte.lang.program import Operand
from bitbyte.run.force import BEFORE_RUN, check_overlaps, force_tables, parse_force
from test_cli import bitbyte

PROGRAM = """\
VAR
  In    AT I0.0;
  Out   AT Q0.0;
  Copy  AT Q0.1;
END_VAR
      LD    In
      =     Copy
      LD    IR0.0
      =     Q0.2
      SET
      =     Out
"""
STIMULUS = "scan,In\n0,0\n3,1\n"
FORCES = ["In=1@1-2", "I0.0=0@4", "Out=0@2-3"]

# Worked by hand from the pins (In: 0 in scans 0..2, 1 from scan 3) and the forces:
# In reads 1 in scans 1-2 (forced while the pin is 0), 0 in scan 4 (forced while the
# pin is 1); IR0.0 follows what the CPU reads (rises in scans 1 and 5); Out is 1 by
# the program but the pin shows 0 in scans 2-3.
#            scan: Out(Q0.0) Copy(Q0.1) Q0.2 I0.0
EXPECTED = [(0, 1, 0, 0, 0),
            (1, 1, 1, 1, 1),
            (2, 0, 1, 0, 1),
            (3, 0, 1, 0, 1),
            (4, 1, 0, 0, 0),
            (5, 1, 1, 1, 1)]


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
def test_forced_input_and_output_hand_worked(tmp_path, sim):
    src, stim, trace = tmp_path / "f.il", tmp_path / "s.csv", tmp_path / "t.csv"
    src.write_text(PROGRAM)
    stim.write_text(STIMULUS)
    args = ["run", src, "--stimulus", stim, "--scans", 6, "--watch", "I0.0",
            "--trace", trace, "--sim", sim]
    for f in FORCES:
        args += ["--force", f]
    proc = bitbyte(*args)
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.DictReader(trace.open()))
    got = [(int(r["scan"]), int(r["Q0.0"]), int(r["Q0.1"]), int(r["Q0.2"]), int(r["I0.0"]))
           for r in rows]
    assert got == EXPECTED


def test_without_force_the_program_rules(tmp_path):
    """The same run unforced: Out always 1, Copy and I0.0 the pin (the check above is
    not satisfied by a table that does nothing)."""
    src, stim, trace = tmp_path / "f.il", tmp_path / "s.csv", tmp_path / "t.csv"
    src.write_text(PROGRAM)
    stim.write_text(STIMULUS)
    proc = bitbyte("run", src, "--stimulus", stim, "--scans", 6, "--watch", "I0.0",
                   "--trace", trace)
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.DictReader(trace.open()))
    assert [(int(r["Q0.0"]), int(r["Q0.1"]), int(r["I0.0"])) for r in rows] == \
        [(1, 0, 0), (1, 0, 0), (1, 0, 0), (1, 1, 1), (1, 1, 1), (1, 1, 1)]


def test_forced_input_in_the_block_status(tmp_path):
    src = tmp_path / "f.il"
    src.write_text(PROGRAM)
    proc = bitbyte("run", src, "--scans", 3, "--force", "In=1@1-2", "--status", 1)
    assert proc.returncode == 0, proc.stderr
    line = next(l for l in proc.stdout.splitlines() if "LD In" in l)
    assert line.split()[-2:] == ["1", "1"]           # RLO 1, STA 1: the forced value


SYMS = {"START": Operand("bit", "I", byte=0, bit=0, text="Start"),
        "MOTOR": Operand("bit", "Q", byte=0, bit=0, text="Motor")}


def test_force_tables_by_hand():
    forces = [parse_force(t, SYMS, Config()) for t in ("Start=1@2-3", "Q0.1=1@0-1")]
    # key j: inputs forced in scan j+1, outputs forced in row j; before RUN the
    # outputs forced from scan 0
    assert force_tables(forces) == [
        (BEFORE_RUN, 0, 0, 0b10, 0b10),
        (1, 0b1, 0b1, 0b10, 0b10),      # Start from scan 2 (written in scan 1)
        (2, 0b1, 0b1, 0, 0),            # Q0.1 released after row 1
        (3, 0, 0, 0, 0)]                # Start released after scan 3


@pytest.mark.parametrize("text,message", [
    ("Start", "expected OPERAND=0|1"),
    ("Start=2", "expected OPERAND=0|1"),
    ("Strat=1", "did you mean `START`?"),
    ("M0.0=1", "only input (I, PI) and output (Q, PQ) bits"),
    ("I0.0=1@5-3", "ends before it starts"),
])
def test_force_errors(text, message):
    with pytest.raises(UsageError, match=message.replace("(", r"\(").replace(")", r"\)")
                       .replace("|", r"\|").replace("?", r"\?")):
        parse_force(text, SYMS, Config())


def test_force_overlap_and_build_size():
    with pytest.raises(UsageError, match="same pin in scan 3"):
        check_overlaps([parse_force(t, SYMS, Config()) for t in ("Start=1@1-3", "I0.0=0@3")])
    small = Config.of_profile("hx8k")
    assert small.force_bits == 16
    parse_force("I1.7=1", SYMS, small)
    with pytest.raises(UsageError, match="forces bits 0.0..1.7"):
        parse_force("I2.0=1", SYMS, small)


def test_force_usage_through_the_cli(tmp_path):
    src = tmp_path / "f.il"
    src.write_text(PROGRAM)
    proc = bitbyte("run", src, "--scans", 2, "--force", "Copy=1", "--force", "Q0.1=0@1")
    assert proc.returncode == 2 and "same pin in scan 1" in proc.stderr


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
def test_a_table_that_does_not_fit_its_scan_is_an_error(tmp_path, sim):
    """A 3-clock scan cannot carry four register writes: the run stops and says so
    (the table would otherwise take effect a scan late, silently)."""
    src = tmp_path / "tiny.il"
    src.write_text("  LD I0.0\n  = Q0.0\n")
    proc = bitbyte("run", src, "--scans", 4, "--force", "I0.0=1@2", "--force", "Q0.0=1@1",
                   "--sim", sim)
    assert proc.returncode == 4, proc.stdout + proc.stderr
    # (which scan runs short first depends on the host's clock of its first write)
    assert re.search(r"the force table of scan [12] did not fit into that scan", proc.stderr)


def test_plant_runs_refuse_force_and_status():
    plant = Path(__file__).resolve().parents[1] / "examples" / "plant_6_1" / "plant_sim.toml"
    for opt in (["--force", "I0.0=1"], ["--status", "1"]):
        proc = bitbyte("run", plant, "--until-us", 2000, *opt)
        assert proc.returncode == 2 and "does not apply to a plant" in proc.stderr
