"""S7's `L T n` / `LC T n` (the time value of a timer: binary in its time base, and
BCD with the time base) against awlsim (docs/s7.md, "Time values"), spec §9.

A time value changes with the time base, not at transitions: tracecmp's
time_value_difference says what is compared.  The check is shown to fail on a
broken translation."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from asmcheck import assert_refused
from awlsim_oracle import timer_scans
import tracecmp
from tracecmp import transition_difference, transitions

from bitbyte.lang import stl

# timer n: (kind, preset, time base in ms); German kinds (SI SV SE SS SA)
TIMERS = {1: ("SI", "S5T#12S", 100), 2: ("SV", "S5T#15S", 100),
          3: ("SE", "S5T#11S", 100), 4: ("SS", "S5T#20S", 100),
          5: ("SA", "S5T#1S400MS", 10)}
KIND_EN = {"SI": "SP", "SV": "SE", "SE": "SD", "SS": "SS", "SA": "SF"}


# the 1 s and 10 s time bases, whose S5TIME awlsim converts otherwise (truncated)
COARSE = {6: ("SV", "S5T#150S", 1000), 7: ("SS", "S5T#20M", 10_000)}   # 150 x 1 s, 120 x 10 s


def program(lang: str, timers=TIMERS) -> str:
    """Each kind started from input 0.0, reset (but SA) from input 0.1; every time
    value loaded in both forms into MW 10 + 4 (n - 1) and the word after it."""
    de = lang == "de"
    a, i, q = ("U", "E", "A") if de else ("A", "I", "Q")
    lines = ["ORGANIZATION_BLOCK OB 1", "BEGIN", "NETWORK", "TITLE = time values",
             f"      {a}     {i} 0.0"]
    for n, (kind, preset, _) in timers.items():
        lines += [f"      L     {preset}", f"      {kind if de else KIND_EN[kind]}    T {n}"]
    lines.append(f"      {a}     {i} 0.1")
    lines += [f"      R     T {n}" for n, (kind, _, _) in timers.items() if kind != "SA"]
    for n in timers:
        lines += [f"      L     T {n}", f"      T     MW {10 + 4 * (n - 1)}",
                  f"      LC    T {n}", f"      T     MW {12 + 4 * (n - 1)}"]
    for n in timers:
        lines += [f"      {a}     T {n}", f"      =     {q} 0.{n}"]
    return "\n".join(lines + ["END_ORGANIZATION_BLOCK", ""])


WORDS = tuple(f"MW{10 + 2 * k}" for k in range(2 * len(TIMERS)))


def stimulus(seed: int, scans: int) -> list[dict[int, int]]:
    """Input 0.0 toggling every few hundred scans (starts, stops mid-run, run-outs),
    input 0.1 a rare one-scan reset."""
    rng, level, rows = random.Random(seed), 0, []
    for _ in range(scans):
        if rng.random() < 0.006:
            level ^= 1
        rows.append({0: level | (2 if rng.random() < 0.003 else 0)})
    return rows


def time_values(timers=TIMERS) -> dict[str, tuple[int, int, bool]]:
    """The program's time value words: column -> (timer, time base ms, BCD)."""
    return {f"MW{10 + 4 * (n - 1) + 2 * bcd}": (n, tb, bool(bcd))
            for n, (_, _, tb) in timers.items() for bcd in (0, 1)}


def time_value_difference(expected, got, timers=TIMERS):
    return tracecmp.time_value_difference(expected, got, time_values(timers))


def run(tmp: Path, lang: str, seed: int, scans: int, timers=TIMERS, clock="0.02",
        **kw):
    path = tmp / f"tv_{lang}.awl"
    path.write_text(program(lang, timers))
    expected, got, _ = timer_scans(path, stimulus(seed, scans), tmp, mnemonics=lang,
                                   timers=tuple(timers), words=tuple(time_values(timers)),
                                   clock_mhz=clock, **kw)
    return expected, got


def check(expected, got, timers=TIMERS) -> None:
    assert time_value_difference(expected, got, timers) is None, \
        time_value_difference(expected, got, timers)
    words = time_values(timers)
    rest = [[{c: v for c, v in row.items() if c not in words} for row in rows]
            for rows in (expected, got)]
    assert transition_difference(*rest) is None, transition_difference(*rest)


@pytest.mark.parametrize("lang,seed", [("de", 0), ("en", 1),
                                       pytest.param("de", 2, marks=pytest.mark.slow)])
def test_time_values_against_awlsim(tmp_path, lang, seed):
    """The five kinds, started, stopped, run out and reset: every time value word
    as awlsim's (reference interpreter, serial)."""
    expected, got = run(tmp_path, lang, seed, 900)
    check(expected, got)
    for column in WORDS:                        # the words do change, in both forms
        assert len(transitions(expected, column)) >= 10, column
    exact = sum(a[c] == b[c] for a, b in zip(expected, got) for c in WORDS)
    assert exact >= 0.95 * len(got) * len(WORDS)     # mostly the very same word


def test_time_values_in_the_1s_and_10s_bases(tmp_path):
    """awlsim's S5TIME truncates there (LC T n), its binary value rounds (L T n)."""
    expected, got = run(tmp_path, "de", 4, 1500, timers=COARSE, clock="0.02")
    check(expected, got, COARSE)
    for column in time_values(COARSE):
        assert len(transitions(expected, column)) >= 5, column


@pytest.mark.parametrize("mode", ["serial", "parallel"])
def test_time_values_on_verilator(tmp_path, mode):
    expected, got = run(tmp_path, "de", 3, 600, sim="verilator", mode=mode)
    check(expected, got)


def test_the_check_fails_on_broken_translations(tmp_path, monkeypatch):
    """Never frozen (a stopped SI/SE timer's value from its stopped IL timer: the
    preset), IL timers on their instructions' time instead of the scan's latch time,
    and one unit added to every value: each is caught (within 300 scans)."""
    expected, got = run(tmp_path, "de", 0, 300)
    shifted = [dict(row) for row in got]
    for row in shifted:
        row["MW22"] += 1                        # T 4's binary value, one unit more
    assert time_value_difference(expected, shifted) is not None

    real = stl.StlFrontEnd.timer_running

    def never_frozen(self, n, start):
        code = real(self, n, start)
        return [("SET", None)] if start else code
    monkeypatch.setattr(stl.StlFrontEnd, "timer_running", never_frozen)
    expected, got = run(tmp_path, "de", 0, 300)
    assert time_value_difference(expected, got) is not None
    monkeypatch.setattr(stl.StlFrontEnd, "timer_running", real)

    monkeypatch.setattr(stl, "IL_TIMER_STARTS", ())     # no timer at_latch
    expected, got = run(tmp_path, "de", 0, 300)
    assert time_value_difference(expected, got) is not None


@pytest.mark.parametrize("text,where,message", [
    ("      U E 0.0\n      L S5T#2S\n      SE T 1\n      L W#16#2002\n      SE T 1\n"
     "      L T 1\n      T MW 10\n", "7:7:", "another time base"),
])
def test_refusals(tmp_path, capsys, text, where, message):
    body = "ORGANIZATION_BLOCK OB 1\nBEGIN\n" + text + "END_ORGANIZATION_BLOCK\n"
    err = assert_refused(tmp_path, capsys, body, where)
    assert "unsupported:" in err and message in err, err


@pytest.mark.parametrize("kind", ["SS", "SV"])
def test_reset_keeps_a_preset_beyond_int_in_accu1(tmp_path, kind):
    """Regression (helper review): `R T 1` of a timer whose time value is read saves
    and restores ACCU1 through 16 bits; a preset of 40 000 ms the IL held there was
    then taken as still in ACCU1 by the next start (SS/SV T 2 ran out at once)."""
    path = tmp_path / f"r_{kind}.awl"
    path.write_text("ORGANIZATION_BLOCK OB 1\nBEGIN\n"
                    "      U     E 0.0\n      L     S5T#40S\n      SE    T 1\n"
                    "      U     E 0.2\n      R     T 1\n"
                    f"      U     E 0.1\n      {kind}    T 2\n"
                    "      U     T 2\n      =     A 0.2\n"
                    "      L     T 1\n      T     MW 10\nEND_ORGANIZATION_BLOCK\n")
    stimulus = [{0: 0}] * 3 + [{0: 3}] * 6
    expected, got, _ = timer_scans(path, stimulus, tmp_path, mnemonics="de",
                                   timers=(1, 2), quiet=False, clock_mhz="0.2")
    assert transitions(got, "Q0.2") == transitions(expected, "Q0.2")
    assert transitions(expected, "Q0.2") == ([(3, 1)] if kind == "SV" else [])
