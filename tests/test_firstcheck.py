"""The first-check warning for `.il` sources (issue 19, item 5): a combining
instruction that can only meet the scan-start RLO of 0 gets a warning on stderr
(exit status 0, the program still assembles and runs); valid uses stay silent."""
from __future__ import annotations

from pathlib import Path

import pytest

from bitbyte import cli
from bitbyte.lang.firstcheck import first_check_warnings
from bitbyte.lang.parser import parse

EXAMPLES = sorted((Path(__file__).parent.parent / "examples").glob("*.il"))


def warned(text: str) -> list[tuple[int, int]]:
    return [(w.line, w.col) for w in first_check_warnings(parse("p.il", text))]


def test_fires_on_a_start_as_the_first_instruction(tmp_path, capsys):
    path = tmp_path / "seal.il"
    path.write_text("VAR\n  Start AT I0.0;\n  Stop AT I0.1;\n  Motor AT Q0.0;\nEND_VAR\n"
                    "      A   Start\n      O   Motor\n      A   Stop\n      =   Motor\n")
    code = cli.main(["asm", str(path), "-o", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 0
    assert err.startswith(f"{path}:6:7: warning: `A` combines with the scan-start RLO 0")
    assert "`LD`" in err and ".awl" in err
    assert err.count("warning") == 1          # only the first: O, A after it are fine


def test_silent_on_the_papers_fig14_and_every_example(capsys):
    assert any(p.name == "fig14.il" for p in EXAMPLES)
    for path in EXAMPLES:
        assert first_check_warnings(parse(str(path), path.read_bytes())) == [], path


@pytest.mark.parametrize("text,expected", [
    ("LD I0.0\n= Q0.0\nA I0.1\n= Q0.1\n", []),            # = x then A y: valid IL
    ("AN I0.0\n= Q0.0\n", [(1, 1)]),
    ("O I0.0\n= Q0.0\n", [(1, 1)]),
    ("XN I0.0\n= Q0.0\n", [(1, 1)]),
    ("L 5\nT MW0\nNOP\nA I0.0\n= Q0.0\n", [(4, 1)]),       # nothing set the RLO yet
    ("= Q0.1\nA I0.0\n= Q0.0\n", [(2, 1)]),                # = keeps the scan-start 0
    ("JU lab\nLD I0.1\nlab: A I0.0\n= Q0.0\n", [(3, 6)]),     # label reached only from start
    ("LD I0.1\nJC lab\nlab: A I0.0\n= Q0.0\n", []),           # reached after a load
    ("JU lab\nmm: A I0.0\n= Q0.0\nlab: LD I0.1\nJC mm\n", []),  # reached from a load only
    ("SET\nA I0.0\n= Q0.0\n", []),
    ("LD I0.0\nJC lab\nA I0.2\nlab: O I0.1\n= Q0.0\n", []),
])
def test_where_it_fires(text, expected):
    assert warned(text) == expected


def test_run_goes_on_after_the_warning(tmp_path, capsys):
    path = tmp_path / "w.il"
    path.write_text("A I0.0\n= Q0.0\n")
    trace = tmp_path / "t.csv"
    code = cli.main(["run", str(path), "--scans", "2", "--trace", str(trace)])
    assert code == 0 and "warning" in capsys.readouterr().err
    assert trace.read_text().splitlines()[0] == "scan,t_us,cycles,Q0.0"


def test_awl_sources_get_no_il_warning(tmp_path, capsys):
    path = tmp_path / "seal.awl"
    path.write_text("ORGANIZATION_BLOCK OB 1\nBEGIN\nU E 0.0\nO A 0.0\nU E 0.1\n"
                    "= A 0.0\nEND_ORGANIZATION_BLOCK\n")
    assert cli.main(["asm", str(path), "-o", str(tmp_path)]) == 0
    assert "warning" not in capsys.readouterr().err
