"""The S7 examples of examples/s7/ (docs/s7.md, "Examples"): each runs with its
stimulus as the README's one-liner does, and its trace equals awlsim's scan for
scan (the mixing tank, a timer program: the same transitions, each within one
scan); the behaviour docs/s7.md writes down is checked on awlsim's rows.
"""
from __future__ import annotations

import csv
from pathlib import Path

import pytest

from awlsim_oracle import awlsim_scans, bitbyte_scans, timer_scans
from bitbyte import cli
from tracecmp import first_difference, transition_difference, transitions

EXAMPLES = Path(__file__).resolve().parents[1] / "examples" / "s7"
# name: (mnemonics, scans, watched words, input words, clock MHz or None)
CASES = {
    "mixing_tank": ("de", 150, ("MW10",), (2,), "0.05"),
    "traffic_light": ("en", 90, ("MW10",), (), None),
    "conveyor": ("de", 100, ("MW10", "MW12"), (), None),
}


def stimulus_inputs(path: Path, scans: int) -> list[dict[int, int]]:
    """A scan-keyed STIM.csv (rows only where something changes) as the input bytes
    of every scan: I b.n bits, IW n words (bytes n and n+1, as in S7)."""
    rows = list(csv.DictReader(path.open()))
    image: dict[int, int] = {}
    out, i = [], 0
    for k in range(scans):
        while i < len(rows) and int(rows[i]["scan"]) <= k:
            for name, value in rows[i].items():
                if name.startswith("IW"):
                    n, v = int(name[2:]), int(value) & 0xFFFF
                    image[n], image[n + 1] = v >> 8, v & 0xFF
                elif name.startswith("I"):
                    b, bit = (int(x) for x in name[1:].split("."))
                    image[b] = image.get(b, 0) & ~(1 << bit) | (int(value) << bit)
            i += 1
        out.append(dict(image))
    return out


def rows_of(name: str, tmp: Path, **kw):
    lang, scans, words, in_words, clock = CASES[name]
    path = EXAMPLES / f"{name}.awl"
    inputs = stimulus_inputs(EXAMPLES / f"{name}.stim.csv", scans)
    if clock:
        expected, got, _ = timer_scans(path, inputs, tmp, mnemonics=lang, timers=(1,),
                                       clock_mhz=clock, words=words, in_words=in_words,
                                       quiet=False, **kw)
        return expected, got, transition_difference(expected, got)
    expected = awlsim_scans(path, inputs, mnemonics=lang, words=words)
    got = bitbyte_scans(path, inputs, tmp, words=words, in_words=in_words, **kw)
    return expected, got, first_difference(expected, got)


@pytest.mark.parametrize("name", sorted(CASES))
def test_example_against_awlsim(tmp_path, name):
    expected, _, diff = rows_of(name, tmp_path)
    assert diff is None, (name, diff)


@pytest.mark.parametrize("name", sorted(CASES))
def test_example_one_liner(tmp_path, name, capsys):
    lang, scans, _, _, clock = CASES[name]
    argv = ["run", str(EXAMPLES / f"{name}.awl"), "--stimulus",
            str(EXAMPLES / f"{name}.stim.csv"), "--scans", str(scans)]
    if clock:
        argv += ["--clock-mhz", clock]
    assert cli.main(argv) == 0, capsys.readouterr().err


def rises(rows, column):
    return [k for k, v in transitions(rows, column) if v == 1]


def test_mixing_tank_behaviour(tmp_path):
    """Start at scan 2 opens the fill valve; full (EW 2 >= 800, scan 15) mixes for
    200 ms (about 47 scans of 4.3 ms); then drains until below 51, counts the batch,
    and starts the next one; Stop (scan 136) closes everything."""
    expected, _, _ = rows_of("mixing_tank", tmp_path)
    assert rises(expected, "Q0.0")[:2] == [2, 67]
    assert rises(expected, "Q0.1")[:1] == [15]
    mix = rises(expected, "Q0.2")[0] - 15
    assert 44 <= mix <= 50, mix
    assert expected[-1]["MW10"] == 2
    assert not any(expected[137][f"Q0.{n}"] for n in range(4))


def test_traffic_light_behaviour(tmp_path):
    """Red, red+amber, green (held), amber, red+walk on the clock's rising edges;
    green is held until the pedestrian button; night mode flashes amber alone."""
    expected, _, _ = rows_of("traffic_light", tmp_path)
    phases = [expected[k]["MW10"] for k in (0, 2, 6, 10, 14, 18, 22, 26, 46)]
    assert phases == [0, 1, 2, 3, 4, 0, 1, 2, 2]
    assert expected[14]["Q0.3"] == 1 and expected[14]["Q0.0"] == 1
    assert expected[9]["Q0.4"] == 1 and expected[18]["Q0.4"] == 0
    night = expected[70:84]
    assert {r["Q0.1"] for r in night} == {0, 1}
    assert not any(r["Q0.0"] or r["Q0.2"] for r in night)


def test_conveyor_behaviour(tmp_path):
    """Both belts start at scan 2 and count their parts apart (two instance DBs);
    belt 2's barrier blocked from scan 40 is a jam after three clock edges: the
    lamp, belt 2 stops, belt 1 runs on; acknowledge and start restart it; stop
    stops both."""
    expected, _, _ = rows_of("conveyor", tmp_path)
    assert expected[2]["Q0.0"] == expected[2]["Q0.1"] == 1
    assert rises(expected, "Q0.2") == [54]
    assert expected[56]["Q0.1"] == 0 and expected[56]["Q0.0"] == 1
    assert expected[66]["Q0.1"] == 1
    assert expected[81]["Q0.0"] == expected[81]["Q0.1"] == 0
    assert expected[-1]["MW10"] == 14 and expected[-1]["MW12"] == 9


def test_examples_on_verilator_serial_and_parallel(tmp_path):
    for mode in ("serial", "parallel"):
        _, _, diff = rows_of("conveyor", tmp_path, sim="verilator", mode=mode)
        assert diff is None, (mode, diff)
