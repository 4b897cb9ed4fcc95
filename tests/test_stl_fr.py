"""S7's `FR` (enable) on timers and counters in `.awl` sources (spec §9; docs/s7.md,
"FR"): a rising RLO at `FR T n` / `FR Z n` clears the edge memory of the timer's start
/ the counter's ZV, ZR and S, so that the next of them with RLO 1 restarts or counts
(awlsim's timers.py / counters.py `run_FR`).  Checked against awlsim on the reference
interpreter and the Verilator harness in serial and parallel mode, with the FR shown
to matter (awlsim without it differs) and wrong translations caught."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from awlsim_oracle import awlsim_scans, bitbyte_scans, timer_scans
from bitbyte.lang import stl
from test_stl_dint import error_of
from tracecmp import first_difference, time_value_difference, transition_difference
from tracecmp import transitions

# SI, SV, SE (with its time value) and SS restarted by FR (E 0.1) while E 0.0 stays 1
TIMERS_DE = """ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE = FR on timers
      U     E 0.1
      FR    T 1
      FR    T 2
      FR    T 3
      FR    T 4
      U     E 0.0
      L     S5T#40MS
      SI    T 1
      L     S5T#30MS
      SV    T 2
      L     S5T#50MS
      SE    T 3
      L     S5T#60MS
      SS    T 4
      U     E 0.2
      R     T 3
      R     T 4
      U     T 1
      =     A 0.1
      U     T 2
      =     A 0.2
      U     T 3
      =     A 0.3
      U     T 4
      =     A 0.4
      L     T 3
      T     MW 10
END_ORGANIZATION_BLOCK
"""
COUNTERS_DE = """ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
TITLE = FR on counters
      U     E 0.1
      FR    Z 1
      U     E 0.0
      ZV    Z 1
      U     E 0.3
      ZR    Z 1
      U     E 0.2
      L     C#5
      S     Z 1
      U     E 0.4
      R     Z 1
      U     E 0.1
      FR    Z 2
      U     E 0.0
      ZV    Z 2
      L     Z 1
      T     MW 10
      L     Z 2
      T     MW 12
      U     Z 1
      =     A 0.0
END_ORGANIZATION_BLOCK
"""
ENGLISH = {"U": "A", "E": "I", "A": "Q", "Z": "C", "ZV": "CU", "ZR": "CD", "SI": "SP",
           "SV": "SE", "SE": "SD"}


def source(text: str, lang: str, fr: bool = True) -> str:
    lines = [line for line in text.splitlines() if fr or "FR " not in line]
    if lang == "en":
        lines = [" ".join(ENGLISH.get(w, w) for w in line.split(" ")) for line in lines]
    return "\n".join(lines) + "\n"


def timer_stimulus(scans: int = 260) -> list[dict[int, int]]:
    """E 0.0 on for long stretches, FR pulses (E 0.1) while timers run and after
    they ran out, a reset (E 0.2) with E 0.0 still on and an FR after it."""
    rows = []
    for k in range(scans):
        on = 10 <= k < 100 or 140 <= k < 200 or 220 <= k < 240
        fr = k in (20, 50, 76, 150, 160, 185, 230)
        rows.append({0: int(on) | 2 * fr | 4 * (k == 170)})
    return rows


def counter_stimulus(seed: int, scans: int = 120) -> list[dict[int, int]]:
    rng, image, rows = random.Random(seed), 0, []
    for _ in range(scans):
        if rng.random() < 0.6:
            image ^= 1 << rng.choice((0, 0, 1, 1, 2, 3, 3, 4))
        if rng.random() < 0.7:
            image &= ~16
        rows.append({0: image})
    return rows


def timers(tmp: Path, lang: str, fr: bool = True, **kw):
    path = tmp / f"fr_t_{lang}_{fr}.awl"
    path.write_text(source(TIMERS_DE, lang, fr))
    expected, got, _ = timer_scans(path, timer_stimulus(), tmp, mnemonics=lang,
                                   timers=(1, 2, 3, 4), words=("MW10",), quiet=False,
                                   clock_mhz="0.2", **kw)
    return expected, got


def timer_difference(expected, got):
    values = {"MW10": (3, 10, False)}
    rest = [[{c: v for c, v in row.items() if c != "MW10"} for row in rows]
            for rows in (expected, got)]
    return time_value_difference(expected, got, values) or transition_difference(*rest)


@pytest.mark.parametrize("lang", ["de", "en"])
def test_fr_on_timers_against_awlsim(tmp_path, lang):
    expected, got = timers(tmp_path, lang)
    assert timer_difference(expected, got) is None, timer_difference(expected, got)
    without, _ = timers(tmp_path, lang, fr=False)
    for column in ("Q0.1", "Q0.2", "MW10"):         # the FRs restart T 1, T 2, T 3
        assert transitions(expected, column) != transitions(without, column), column
    assert transitions(expected, "Q0.3") == [(39, 1), (100, 0)]    # status kept


@pytest.mark.parametrize("mode", ["serial", "parallel"])
def test_fr_on_timers_on_verilator(tmp_path, mode):
    expected, got = timers(tmp_path, "de", sim="verilator", mode=mode)
    assert timer_difference(expected, got) is None, timer_difference(expected, got)


def counters(tmp: Path, lang: str, seed: int, fr: bool = True, **kw):
    path = tmp / f"fr_c_{lang}_{fr}.awl"
    path.write_text(source(COUNTERS_DE, lang, fr))
    rows = counter_stimulus(seed)
    expected = awlsim_scans(path, rows, mnemonics=lang, words=("MW10", "MW12"))
    got = bitbyte_scans(path, rows, tmp, words=("MW10", "MW12"), **kw)
    return expected, got


@pytest.mark.parametrize("lang,seed", [("de", 1), ("en", 2), ("de", 5)])
def test_fr_on_counters_against_awlsim(tmp_path, lang, seed):
    expected, got = counters(tmp_path, lang, seed)
    assert first_difference(expected, got) is None, first_difference(expected, got)
    without, _ = counters(tmp_path, lang, seed, fr=False)
    assert first_difference(expected, without) is not None


@pytest.mark.parametrize("mode", ["serial", "parallel"])
def test_fr_on_counters_on_verilator(tmp_path, mode):
    expected, got = counters(tmp_path, "de", 5, sim="verilator", mode=mode)
    assert first_difference(expected, got) is None, first_difference(expected, got)


def test_wrong_translations_are_caught(tmp_path, monkeypatch):
    """The IL counter's edge memory not cleared; an FR that frees nothing; the
    on-delay's status not held across its restart."""
    monkeypatch.setattr(stl.StlFrontEnd, "clear_il_edge", staticmethod(lambda m, op: []))
    assert first_difference(*counters(tmp_path, "de", 5)) is not None
    monkeypatch.undo()

    real_emit_code = stl.StlFrontEnd.emit_code

    def without(purpose):
        def emit_code(self, code):
            bits = {v for k, v in self.scratch_bits.items() if k[0] == purpose}
            real_emit_code(self, [(m, op) for m, op in code if op not in bits
                                  or m != ("S" if purpose == "freed" else "O")])
        return emit_code
    monkeypatch.setattr(stl.StlFrontEnd, "emit_code", without("freed"))
    assert timer_difference(*timers(tmp_path, "de")) is not None
    monkeypatch.setattr(stl.StlFrontEnd, "emit_code", real_emit_code)

    real_prepend = stl.StlFrontEnd.prepend_timer_update

    def no_hold(self):
        self.scratch_bits = {k: v for k, v in self.scratch_bits.items()
                             if k[0] != "held"}
        real_prepend(self)
    monkeypatch.setattr(stl.StlFrontEnd, "prepend_timer_update", no_hold)
    assert timer_difference(*timers(tmp_path, "de")) is not None


@pytest.mark.parametrize("body, line, needle", [
    ("U E 0.0\nL S5T#1S\nSA T 1\nU E 0.1\nFR T 1", 12, "`FR T 1` on an off-delay"),
    ("U E 0.0\nU(\nU E 0.1\nFR Z 1\n)\n= A 0.0", 11, "`FR` inside parentheses"),
])
def test_rejections(tmp_path, body, line, needle):
    err = error_of(tmp_path, body)
    assert err.line == line and needle in err.message, (err.line, err.message)
