"""A CLI that explains itself (issue 17, item 5): help text on every option and
command, examples that run, `--version`, errors that suggest the fix, the cycle-time
statistics of the run summary."""
from __future__ import annotations

import argparse
import re
import shlex
import tomllib
from pathlib import Path

import pytest

from bitbyte import cli
from bitbyte.lang.suggest import did_you_mean
from bitbyte.run.summary import histogram, watchdog_margin
from test_cli import bitbyte as run_bitbyte

ROOT = Path(__file__).resolve().parents[1]


def bitbyte(*args):
    """`bitbyte` in a subprocess from the repository root (the examples' paths)."""
    return run_bitbyte(*args, cwd=ROOT)


# --- the argparse tree --------------------------------------------------------------

def _subparsers(parser: argparse.ArgumentParser):
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            helps = {a.dest: a.help for a in action._choices_actions}
            for name, sub in action.choices.items():
                yield name, sub, helps.get(name)


def undocumented(parser: argparse.ArgumentParser, path: str | None = None) -> list[str]:
    """Every option, positional and command of the tree without help text, and every
    command without a description or examples."""
    path = path or parser.prog
    missing = []
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            continue
        if not (action.help or "").strip() or action.help == argparse.SUPPRESS:
            missing.append(f"{path} {'/'.join(action.option_strings) or action.dest}")
    for name, sub, helptext in _subparsers(parser):
        where = f"{path} {name}"
        if not (helptext or "").strip():
            missing.append(f"{where} (command help)")
        if not (sub.description or "").strip():
            missing.append(f"{where} (description)")
        if "example" not in (sub.epilog or ""):
            missing.append(f"{where} (examples)")
        missing += undocumented(sub, where)
    return missing


def test_every_option_and_command_has_help():
    assert undocumented(cli._parser()) == []


def test_the_walk_finds_what_has_no_help():
    """The checker fails on a tree with an option, a command and examples missing."""
    p = argparse.ArgumentParser(prog="x")
    p.add_argument("--documented", help="yes")
    p.add_argument("--bare")
    sub = p.add_subparsers(dest="cmd")
    s = sub.add_parser("quiet", description="d")
    s.add_argument("file", help="f")
    s.add_argument("-n", type=int)
    assert undocumented(p) == ["x --bare", "x quiet (command help)", "x quiet (examples)",
                               "x quiet -n"]


def test_version_is_the_package_version():
    version = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    proc = bitbyte("--version")
    assert proc.returncode == 0
    assert proc.stdout.strip() == f"bitbyte {version}"


# --- the examples in the help text run ----------------------------------------------

OUTPUTS = {"-o", "--outdir", "--trace", "--json", "--emit", "--waves", "--save-tasks"}


def help_examples() -> list[tuple[str, list[str]]]:
    """(command, argv) of every `bitbyte ...` line in the commands' examples; a line
    ending in a backslash continues on the next."""
    found = []
    for name, sub, _ in _subparsers(cli._parser()):
        lines = iter((sub.epilog or "").splitlines())
        for line in lines:
            if not line.startswith("  bitbyte "):
                continue
            while line.endswith("\\"):
                line = line[:-1] + next(lines).strip()
            found.append((name, shlex.split(line)[1:]))
    return found


def test_help_has_examples_for_every_command():
    assert {name for name, _ in help_examples()} == {"asm", "run", "link", "alloc"}


@pytest.mark.parametrize("argv", [argv for _, argv in help_examples()],
                         ids=lambda argv: " ".join(argv)[:60])
def test_help_example_runs(tmp_path, argv):
    """Each example as printed, its output files moved into tmp_path."""
    argv = list(argv)
    for i, word in enumerate(argv[:-1]):
        if word in OUTPUTS:
            argv[i + 1] = str(tmp_path / Path(argv[i + 1]).name)
    for word in argv:
        if word.startswith("examples/"):
            assert (ROOT / word).exists(), word
    proc = bitbyte(*argv)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    if "--waves" in argv:
        waves = Path(argv[argv.index("--waves") + 1])
        assert waves.exists()


# --- errors that suggest the fix ----------------------------------------------------

def test_did_you_mean():
    assert did_you_mean("strat", ["Start", "Stop", "Motor"]) == "; did you mean `Start`?"
    assert did_you_mean("LDD", ["LD", "LDN", "ST"]) == "; did you mean `LD` or `LDN`?"
    assert did_you_mean("Conveyor", ["Start", "Stop"]) == ""


@pytest.mark.parametrize("text,message", [
    ("VAR Start AT I0.0; Stop AT I0.1; END_VAR\n  LD Strat\n  = Q0.0\n",
     ":2:6: undeclared symbol `Strat`; did you mean `Start`?"),
    ("  LDD I0.0\n  = Q0.0\n", ":1:3: unknown mnemonic `LDD`; did you mean `LD`, `SLD` or `RLD`?"),  # shifts
    ("  LD I0.0\n  JC Loop\nLoops: = Q0.0\n",
     ":2:6: unknown label `Loop`; did you mean `Loops`?"),
])
def test_source_errors_suggest_the_declared_name(tmp_path, text, message):
    src = tmp_path / "p.il"
    src.write_text(text)
    proc = bitbyte("asm", src, "-o", tmp_path)
    assert proc.returncode == 1
    assert proc.stderr.splitlines()[0] == f"{src}{message}"


def test_watch_and_stimulus_suggest_the_declared_name(tmp_path):
    src = tmp_path / "p.il"
    src.write_text("VAR Start AT I0.0; Motor AT Q0.0; END_VAR\n  LD Start\n  = Motor\n")
    proc = bitbyte("run", src, "--scans", "2", "--watch", "Motr")
    assert proc.returncode == 2
    assert "did you mean `Motor`?" in proc.stderr
    stim = tmp_path / "s.csv"
    stim.write_text("scan,Strat\n0,1\n")
    proc = bitbyte("run", src, "--scans", "2", "--stimulus", stim)
    assert proc.returncode == 1
    assert "unknown operand 'Strat'; did you mean `Start`?" in proc.stderr


# --- cycle-time statistics ----------------------------------------------------------

def test_histogram_one_bin_per_length():
    assert histogram([59, 59, 61, 59]) == "[clk] 59: 3 | 61: 1"


def test_histogram_equal_bins_over_many_lengths():
    # 100..119: 20 lengths -> 8 bins of width 3 from 100; 118 and 119 share 118-119
    cycles = list(range(100, 120)) + [100, 100]
    assert histogram(cycles) == ("[clk] 100-102: 5 | 103-105: 3 | 106-108: 3 | "
                                 "109-111: 3 | 112-114: 3 | 115-117: 3 | 118-119: 2")


def test_watchdog_margin():
    assert watchdog_margin(116, 100_000) == \
        "limit 100000 clocks, longest scan 116: margin 99884 clocks (99.9 %)"


def test_summary_shows_the_scan_statistics(tmp_path):
    """Fig. 5 serially (spec §5: 59 clocks of instruction work): one length."""
    proc = bitbyte("run", "examples/fig5.il", "--scans", "5", "--watchdog", "1000")
    assert proc.returncode == 0, proc.stderr
    lines = {l[:17].strip(): l[17:] for l in proc.stdout.splitlines()}
    cycles = int(lines["cycles/scan"].split()[1])
    assert lines["scan histogram"] == f"[clk] {cycles}: 5"
    assert lines["watchdog"].startswith(f"limit 1000 clocks, longest scan {cycles}: "
                                        f"margin {1000 - cycles} clocks")


def test_stl_unknown_mnemonic_suggests(tmp_path):
    src = tmp_path / "p.awl"
    src.write_text("ORGANIZATION_BLOCK OB 1\nBEGIN\n      UNN E 0.0;\n      = A 0.0;\n"
                   "END_ORGANIZATION_BLOCK\n")
    proc = bitbyte("asm", src, "-o", tmp_path)
    assert proc.returncode == 1
    assert proc.stderr.splitlines()[0] == \
        f"{src}:3:7: unknown mnemonic `UNN`; did you mean `UN` or `UN(`?"


# --- progress on long runs ------------------------------------------------------------

def test_progress_line_on_request(tmp_path):
    """BITBYTE_PROGRESS=S (a terminal gets it after 2 s): the harness rewrites one line
    with the scan, the share done and the time left; without it, stderr stays quiet."""
    import os
    run = ["run", "examples/star_delta.il", "--clock-mhz", "1", "--until-us", "400000"]
    os.environ["BITBYTE_PROGRESS"] = "0"
    try:
        proc = bitbyte(*run)
    finally:
        del os.environ["BITBYTE_PROGRESS"]
    assert proc.returncode == 0, proc.stderr
    # (text mode reads the carriage return that rewrites the line as a newline)
    assert re.search(r"^bitbyte run: scan \d+, [\d.]+ s simulated: \d+ %, \d+ s so far, "
                     r"about \d+ s left", proc.stderr, re.M), proc.stderr
    assert proc.stderr.endswith("\n")
    assert bitbyte(*run).stderr == ""


def test_plant_progress_line_on_request():
    import os
    os.environ["BITBYTE_PROGRESS"] = "0"
    try:
        proc = bitbyte("run", "examples/plant_6_1/plant_sim.toml", "--until-us", "100000")
    finally:
        del os.environ["BITBYTE_PROGRESS"]
    assert proc.returncode == 0, proc.stderr
    assert re.search(r"^bitbyte run \(plant\): [\d.]+ s simulated: \d+ %", proc.stderr, re.M)
