"""`bitbyte run --line-counts FILE` (docs/toolchain.md): how often each program line
executed over the run, counted on the simulated hardware. Checked against a
hand-worked count (a jump that skips a line in two of four scans; a loop), and the
parallel mode's two parts against the same program's serial counts; bad uses get a
message and exit status 2."""
from __future__ import annotations

import csv
from pathlib import Path

import pytest

from bitbyte import cli

ROOT = Path(__file__).resolve().parents[1]

SKIP = """      LD I0.0
      JC skip
      = Q0.0
skip: LD I0.1
      = Q0.1
      END
"""
SKIP_STIM = "scan,I0.0\n0,0\n1,1\n3,0\n"
# a loop: MW0 counts 3 times round per scan (L/T/compare/JC), then END
LOOP = """      L 0
      T MW0
top:  L MW0
      L 1
      +I
      T MW0
      L MW0
      L 3
      <I
      JC top
      END
"""


def lines_of(path: Path) -> list[tuple[str, int, int, str, str]]:
    with open(path, newline="") as f:
        return [(r["part"], int(r["address"]), int(r["line"]), r["instruction"], r["count"])
                for r in csv.DictReader(f)]


def run(tmp_path, program: str, *args: str, stim: str | None = None, scans: int = 4) -> Path:
    il = tmp_path / "p.il"
    il.write_text(program)
    argv = ["run", str(il), "--scans", str(scans), "--line-counts", str(tmp_path / "l.csv"),
            *args]
    if stim is not None:
        (tmp_path / "s.csv").write_text(stim)
        argv += ["--stimulus", str(tmp_path / "s.csv")]
    assert cli.main(argv) == 0
    return tmp_path / "l.csv"


def test_a_skipped_line_is_counted_by_hand(tmp_path):
    # I0.0 is 1 in scans 1 and 2: the jump skips `= Q0.0` there
    got = lines_of(run(tmp_path, SKIP, stim=SKIP_STIM))
    assert got == [("program", 0, 1, "LD I0.0", "4"), ("program", 1, 2, "JC skip", "4"),
                   ("program", 2, 3, "= Q0.0", "2"), ("program", 3, 4, "skip: LD I0.1", "4"),
                   ("program", 4, 5, "= Q0.1", "4"), ("program", 5, 6, "END", "4")]


def test_a_loop_body_is_counted_per_round(tmp_path):
    counts = [int(c) for *_, c in lines_of(run(tmp_path, LOOP))]
    assert counts == [4, 4] + [12] * 8 + [4]       # 3 rounds a scan, 4 scans


@pytest.mark.parametrize("mode", ["parallel", "free"])
def test_the_two_parts_count_what_serial_mode_ran(tmp_path, mode):
    """Fig. 5 in parallel mode: every source line's words count as often as the line
    did serially (the partitioning compiler's transfers serve those lines); END_B's
    count is empty. Free-running mode: the bit part the same (20 bit scans), the byte
    part's straight-line words each as often as its own scans got to them: all within
    one of each other, at least 2 (its scans are longer than the bit side's, not 10
    times longer)."""
    fig5 = (ROOT / "examples" / "fig5.il").read_text()
    stim = (ROOT / "examples" / "fig5.stim.csv").read_text()
    serial = {line: int(n) for _, _, line, _, n in
              lines_of(run(tmp_path, fig5, stim=stim, scans=20))}
    args = ["--mode", mode] + (["--exchange", "queue-free"] if mode == "free" else [])
    got = lines_of(run(tmp_path, fig5, *args, stim=stim, scans=20))
    assert {p for p, *_ in got} == {"bit", "byte"}
    byte = []
    for part, _, line, text, n in got:
        if text == "END_B":
            assert part == "byte" and n == ""
        elif part == "bit" or mode == "parallel":
            assert int(n) == serial[line] == 20, (part, line, text)
        else:
            byte.append(int(n))
    if mode == "free":
        assert min(byte) >= 2 and max(byte) - min(byte) <= 1, byte


@pytest.mark.parametrize("args, message", [
    (["--sim", "icarus"], "--line-counts: the Verilator harness counts them"),
    (["--line-counts", "/nonexistent/dir/l.csv"], "--line-counts: cannot write"),
])
def test_bad_uses_say_why(tmp_path, capsys, args, message):
    il = tmp_path / "p.il"
    il.write_text(SKIP)
    argv = ["run", str(il), "--scans", "2", "--line-counts", str(tmp_path / "l.csv"), *args]
    assert cli.main(argv) == 2
    assert message in capsys.readouterr().err


def test_a_plant_refuses_it(tmp_path, capsys):
    plant = ROOT / "examples" / "plant_6_1" / "plant_sim.toml"
    assert cli.main(["run", str(plant), "--until-us", "10", "--line-counts",
                     str(tmp_path / "l.csv")]) == 2
    assert "--line-counts does not apply to a plant" in capsys.readouterr().err
