"""docs/tutorial.md cannot go stale (issue 17 item 6): every command of its `console`
blocks runs here, from a scratch directory holding the repository's examples/, and
prints exactly what the page shows (the simulator's speed in `simulated` aside)."""
from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TUTORIAL = ROOT / "docs" / "tutorial.md"
SPEED = re.compile(r", [0-9.]+ M clocks/s wall$")


def console_steps(text: str) -> list[tuple[str, list[str]]]:
    """(command, expected output lines) of every `$ ` line of the console blocks."""
    steps = []
    for block in re.findall(r"```console\n(.*?)```", text, re.S):
        for line in block.splitlines():
            if line.startswith("$ "):
                steps.append((line[2:], []))
            else:
                steps[-1][1].append(line)
    return steps


def normalise(lines: list[str]) -> list[str]:
    return [SPEED.sub("", line.rstrip()) for line in lines]


def test_the_tutorial_has_steps():
    commands = [c for c, _ in console_steps(TUTORIAL.read_text())]
    assert len(commands) >= 6
    assert any("--status" in c for c in commands) and any("--waves" in c for c in commands)


def run_page(page: Path, tmp_path: Path) -> None:
    """All steps in order, in one directory: later steps read earlier steps' files."""
    tmp_path.mkdir(exist_ok=True)
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    for command, expected in console_steps(page.read_text()):
        argv = command
        if command.startswith("bitbyte "):
            argv = f"{sys.executable} -m bitbyte.cli {command[len('bitbyte '):]}"
        proc = subprocess.run(["bash", "-c", argv], cwd=tmp_path, env=env,
                              capture_output=True, text=True, timeout=300)
        assert proc.returncode == 0, (command, proc.stderr)
        assert "Traceback" not in proc.stderr
        assert normalise(proc.stdout.splitlines()) == normalise(expected), command


def test_tutorial_commands_print_what_the_page_shows(tmp_path):
    run_page(TUTORIAL, tmp_path)
    assert (tmp_path / "build" / "tutorial" / "motor.gtkw").exists()


def test_a_stale_page_fails(tmp_path):
    """The comparison sees an output that is not what the page shows."""
    page = TUTORIAL.read_text().replace("0,5600,28,0,0,0,0", "0,5600,28,1,0,0,0", 1)
    assert page != TUTORIAL.read_text()
    stale = tmp_path / "tutorial.md"
    stale.write_text(page)
    with pytest.raises(AssertionError, match="cat build/tutorial/motor.csv"):
        run_page(stale, tmp_path / "run")
