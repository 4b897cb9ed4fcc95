"""S7 statement list (`.awl`, spec §9, issue 19): every behaviour checked against
awlsim, the independent S7 simulator (tests/awlsim_oracle.py), scan for scan — the
hand-written programs and random ones (tests/stlgen.py) on the reference
interpreter, a sample on the Verilator harness in serial and parallel mode.  The
expected values come from awlsim, never from the front end's own output; a few
tests also state the S7 result in words (the seal-in switches the motor on).

BITBYTE_STL_PROGRAMS=<n> sets the number of random programs (default 200; the soak
is n = 5000, see docs/s7.md); the seed is BITBYTE_SEED (pytest header).
"""
from __future__ import annotations

import os
import re
import textwrap
from pathlib import Path

import pytest

from awlsim_oracle import (awlsim_scans, bitbyte_scans, equal_or_rejected, latch_times,
                           timer_equal_or_rejected, timer_scans)
from bitbyte import cli
from bitbyte.lang import stl
from bitbyte.lang.errors import SourceError
from bitbyte.lang.parser import parse_file
from stlgen import (IN_WORDS, WORDS, random_inputs, random_program, slow_inputs,
                    symbol_table, time_value_columns, with_symbols)
from tracecmp import first_difference, transition_difference, transitions

PROGRAMS = int(os.environ.get("BITBYTE_STL_PROGRAMS", "200"))
BASE_SEED = int(os.environ.get("BITBYTE_SEED", "0"))


def ob1(body: str) -> str:
    return ("ORGANIZATION_BLOCK OB 1\nTITLE = test\nVERSION : 0.1\n\nBEGIN\nNETWORK\n"
            "TITLE =\n" + textwrap.dedent(body).strip("\n") + "\nEND_ORGANIZATION_BLOCK\n")


def write(tmp: Path, name: str, body: str) -> Path:
    path = tmp / name
    path.write_text(ob1(body))
    return path


def every_input(scans: int = 16) -> list[dict[int, int]]:
    """I0.0..I0.3 count through all 16 combinations, one per scan (twice, so
    that state kept across scans is seen from every previous combination)."""
    return [{0: k % 16} for k in range(scans)] + [{0: (k * 7) % 16} for k in range(scans)]


def same_as_awlsim(path: Path, lang: str, inputs, tmp: Path, words=(), in_words=(),
                   **kw):
    expected = awlsim_scans(path, inputs, mnemonics=lang, words=words)
    got = bitbyte_scans(path, inputs, tmp, words=words, in_words=in_words, **kw)
    assert first_difference(expected, got) is None, (path.read_text(),
                                                     first_difference(expected, got))
    return expected


# --------------------------------------------------------------------------------------
# Hand-written programs
# --------------------------------------------------------------------------------------

SEAL_IN = {
    "de": """
        U     E 0.0   // Start
        O     A 0.0   // Motor
        U     E 0.1   // Stop (normally closed)
        =     A 0.0   // Motor
        """,
    "en": """
        A     I 0.0
        O     Q 0.0
        A     I 0.1
        =     Q 0.0
        """,
}


@pytest.mark.parametrize("lang", ["de", "en"])
def test_seal_in_switches_the_motor_on(tmp_path, lang):
    """The classic seal-in: the first U/A of the string loads (S7's first check), so
    Start switches the motor on, it holds after Start is released, Stop drops it."""
    path = write(tmp_path, f"seal_{lang}.awl", SEAL_IN[lang])
    inputs = [{0: 0b10}, {0: 0b11}, {0: 0b10}, {0: 0b10}, {0: 0b00}, {0: 0b10}]
    rows = same_as_awlsim(path, lang, inputs, tmp_path)
    assert [r["Q0.0"] for r in rows] == [0, 1, 1, 1, 0, 0]


FIRST_CHECK = {
    # each string starts with another combine; after =, S, R, SET, CLR a new one
    "starts": """
        O     E 0.0
        U     E 0.1
        =     A 0.0
        X     E 0.2
        XN    E 0.3
        =     A 0.1
        UN    E 0.0
        S     M 0.0
        ON    E 0.1
        R     M 0.0
        U     M 0.0
        =     A 0.2
        SET
        U     E 0.2
        =     A 0.3
        CLR
        O     E 0.3
        =     A 0.4
        """,
    # `O` at the start of a string does nothing; FP / FN keep the string going
    "o_first_and_edges": """
        O
        U     E 0.0
        FP    M 1.0
        U     E 0.1
        =     A 0.0
        U     E 0.2
        FN    M 1.1
        O     E 0.3
        =     A 0.1
        UN    E 0.0
        NOT
        =     A 0.2
        """,
    # AND before OR: the terms around `O`, O/X with an operand after `O`
    "and_before_or": """
        U     E 0.0
        U     E 0.1
        O
        U     E 0.2
        U     E 0.3
        O
        UN    E 0.0
        UN    E 0.2
        =     A 0.0
        U     E 0.0
        O
        O     E 0.1
        U     E 0.2
        =     A 0.1
        U     E 0.0
        U     E 0.1
        O
        X     E 0.2
        =     A 0.2
        U     E 0.1
        O
        O
        UN    E 0.3
        =     A 0.3
        U     E 0.3
        O
        =     A 0.4
        """,
    # nesting: U( / O( / X( at the start of a string, inside an AND term, three deep
    "nesting": """
        U(
        O     E 0.0
        O     E 0.1
        )
        U(
        UN    E 0.2
        O     E 0.3
        )
        =     A 0.0
        UN(
        U     E 0.0
        X(
        U     E 0.1
        O(
        U     E 0.2
        U     E 0.3
        )
        )
        )
        =     A 0.1
        U     E 0.0
        O
        U     E 0.1
        U(
        O     E 0.2
        O
        U     E 0.3
        U     E 0.0
        )
        ON(
        U     E 0.1
        U     E 0.3
        )
        =     A 0.2
        X(
        U     E 0.0
        )
        XN(
        U     E 0.1
        )
        O
        UN(
        O     E 0.2
        )
        =     A 0.3
        """,
    # jumps: SPB / SPBN set the RLO to 1 on both paths, SPA keeps the string going
    "jumps": """
        U     E 0.0
        SPB   M1
        =     A 0.0
        U     E 0.1
        SPBN  M2
        =     A 0.1
M1:     U     E 0.2
        =     A 0.2
M2:     U     E 0.3
        SPA   M3
        =     A 0.3
M3:     U     E 0.1
        =     A 0.4
        U     E 0.3
        BEB
        SET
        =     A 0.5
        """,
    # jump targets reached with /FC = 0 and /FC = 1: the /FC = 0 paths get SET before
    # U/U( and CLR before O/X (S7 loads there, 1 AND x = 0 OR x = x)
    "jump_fc_merge": """
        U     E 0.0
        SPB   M5
        U     E 0.1
        SPA   M1
M5:     =     M 0.2
        U     E 0.3
        SPB   M1
        =     A 0.0
        SPA   M1
M1:     U     E 0.2
        =     A 0.1
        U     E 0.3
        SPB   M6
        U     E 0.0
        SPA   M2
M6:     =     A 0.2
M2:     O     E 0.0
        X     E 0.1
        =     A 0.3
        U     E 0.2
        SPBN  M7
        U     E 0.1
        SPA   M3
M7:     =     M 0.0
M3:     X(
        U     E 0.1
        O     E 0.3
        )
        =     A 0.4
        U     E 0.1
        SPB   M8
        U     E 0.2
        SPA   M4
M8:     =     M 0.1
M4:     UN(
        U     E 0.0
        )
        =     A 0.5
        """,
}


@pytest.mark.parametrize("name", sorted(FIRST_CHECK))
def test_first_check_nesting_jumps_against_awlsim(tmp_path, name):
    same_as_awlsim(write(tmp_path, f"{name}.awl", FIRST_CHECK[name]), "de",
                   every_input(), tmp_path)


def to_english(body: str) -> str:
    swaps = {"U": "A", "UN": "AN", "U(": "A(", "UN(": "AN(", "SPA": "JU", "SPB": "JC",
             "SPBN": "JCN", "BEB": "BEC", "BEA": "BEU"}
    areas = {"E": "I", "A": "Q"}
    out = []
    for line in body.splitlines():
        label, _, rest = line.rpartition(":") if ":" in line else ("", "", line)
        words = rest.split()
        if words:
            words[0] = swaps.get(words[0], words[0])
            if len(words) > 1 and words[1] in areas:
                words[1] = areas[words[1]]
        out.append((label + ": " if label else "\t") + " ".join(words))
    return "\n".join(out)


@pytest.mark.parametrize("name", sorted(FIRST_CHECK))
def test_english_mnemonics_against_awlsim(tmp_path, name):
    same_as_awlsim(write(tmp_path, f"{name}_en.awl", to_english(FIRST_CHECK[name])),
                   "en", every_input(), tmp_path)


def test_step7_export_layout(tmp_path):
    """A STEP 7 Classic export: header attributes, the OB 1 TEMP declarations,
    statements ended by `;`, network titles and comments; CR LF line ends."""
    text = textwrap.dedent("""\
        ORGANIZATION_BLOCK OB 1
        TITLE = "Main Program Sweep (Cycle)"
        VERSION : 0.1

        VAR_TEMP
          OB1_EV_CLASS : BYTE ;\t//Bits 0-3 = 1 (Coming event)
          OB1_SCAN_1 : BYTE ;\t//1 (Cold restart scan 1 of OB 1)
        END_VAR
        BEGIN
        NETWORK
        TITLE = Motor
        // seal-in
              U     E      0.0; 
              O     A      0.0; 
              U     E      0.1; 
              =     A      0.0; 
        NETWORK
        TITLE =
        M001: U(    ; 
              ON    E      0.2; 
              )     ; 
              =     M      0.0; 
        END_ORGANIZATION_BLOCK
        """).replace("\n", "\r\n")
    path = tmp_path / "export.awl"
    path.write_bytes(text.encode())
    same_as_awlsim(path, "de", every_input(), tmp_path)


# --------------------------------------------------------------------------------------
# Word instructions: L / T, INT arithmetic and compares
# --------------------------------------------------------------------------------------

WORD_PROGRAM = {
    # loads of every constant form and of IW/QW/MW, the S7 accumulator push on L,
    # arithmetic with wrap-around and /I by 0, T to QW and MW
    "arithmetic": """
        L     EW 2
        L     7
        +I
        T     MW 10
        L     MW 10
        L     W#16#FFF0
        *I
        T     AW 2
        L     AW 2
        L     EW 4
        -I
        L     3
        /I
        T     MW 12
        L     EW 4
        L     MW 14
        /I
        T     MW 14
        L     32767
        L     B#16#01
        +I
        L     3
        *I
        T     AW 4
        L     S5T#2S
        T     MW 16
        L     C#25
        T     MW 18
        L     2#1010
        L     MW 18
        """,
    # compares set the RLO (and /FC := 1, OR := 0) whatever came before; the string
    # goes on after them; L / T inside a string and an AND-before-OR term
    "compares": """
        L     EW 2
        L     100
        >I
        =     A 0.0
        U     E 0.0
        L     EW 2
        L     EW 4
        ==I
        U     E 0.1
        =     A 0.1
        U     E 0.2
        O
        U     E 0.3
        L     EW 4
        L     0
        <>I
        O     E 0.0
        =     A 0.2
        U     E 0.1
        O
        U     E 0.2
        L     EW 2
        T     MW 10
        U     E 0.3
        =     A 0.3
        L     MW 10
        L     EW 4
        <I
        =     A 0.4
        L     EW 4
        L     -5
        >=I
        S     A 0.5
        L     EW 2
        L     EW 4
        <=I
        R     A 0.5
        """,
    # `+ n` adds to ACCU1-L (S7 leaves ACCU2 alone, here it is changed: only ACCU1
    # is read after it), wrapping at the ends of INT; a jump target after it
    "add_constant": """
        L     EW 2
        +     1
        T     MW 10
        L     EW 4
        +     -100
        +     32767
        T     MW 12
        L     EW 2
        L     EW 4
        +     5
        T     MW 14
        U     E 0.0
        SPB   M1
        +     -32768
M1:     +     0
        T     MW 16
        L     MW 16
        L     EW 2
        >I
        =     A 0.0
        """,
    # NEGI and INVI change ACCU1-L in place (ACCU2 changed here: only ACCU1 is read
    # after them), at the ends of INT too
    "negate_invert": """
        L     EW 2
        NEGI
        T     MW 10
        L     EW 4
        INVI
        T     MW 12
        L     EW 2
        INVI
        NEGI
        T     MW 14
        L     MW 14
        L     EW 4
        >I
        =     A 0.0
        """,
    # the accumulators across jumps: the meet of the paths into a label
    "jumps": """
        L     EW 2
        L     EW 4
        U     E 0.0
        SPB   M1
        L     1
        L     2
M1:     +I
        T     MW 10
        U     E 0.1
        SPBN  M2
        L     EW 2
        L     10
        >I
M2:     =     A 0.0
        """,
}


def word_inputs(scans: int = 24) -> list[dict[int, int]]:
    """I0.0..I0.3 through all combinations; IW 2 and IW 4 (bytes 2..5) through
    values around 0, 100 and the ends of the INT range."""
    values = (0, 1, 100, 101, 0xFFFF, 0x8000, 0x7FFF, 99, 5, 0xFFFB, 0x1234, 2)
    rows = []
    for k in range(scans):
        a, b = values[k % len(values)], values[(k * 5 + 3) % len(values)]
        rows.append({0: k % 16, 2: a >> 8, 3: a & 0xFF, 4: b >> 8, 5: b & 0xFF})
    return rows


@pytest.mark.parametrize("lang", ["de", "en"])
@pytest.mark.parametrize("name", sorted(WORD_PROGRAM))
def test_word_instructions_against_awlsim(tmp_path, name, lang):
    body = WORD_PROGRAM[name]
    if lang == "en":
        body = to_english(body.replace("EW", "IW").replace("AW", "QW"))
    words = ("QW2", "QW4", "MW10", "MW12", "MW14", "MW16", "MW18")
    rows = same_as_awlsim(write(tmp_path, f"{name}_{lang}.awl", body), lang,
                          word_inputs(), tmp_path, words=words, in_words=(2, 4))
    if name == "arithmetic":                    # S7's values, stated in words too
        assert rows[0]["MW16"] == 0x0200 and rows[0]["MW18"] == 0x25
        assert rows[0]["QW4"] == -32768         # (32767 + 1) * 3, wrapped


def test_words_on_verilator_serial_and_parallel(tmp_path):
    words = ("QW2", "QW4", "MW10", "MW12", "MW14", "MW16", "MW18")
    for name in ("arithmetic", "compares"):
        path = write(tmp_path, f"{name}.awl", WORD_PROGRAM[name])
        for mode in ("serial", "parallel"):
            same_as_awlsim(path, "de", word_inputs(12), tmp_path, words=words,
                           in_words=(2, 4), sim="verilator", mode=mode)


# --------------------------------------------------------------------------------------
# Timers: S5TIME presets, SI SE SS SA (SP SD SS SF), R T, the status from the time base
# --------------------------------------------------------------------------------------

TIMER_PROGRAM = {
    # every kind, read before its instruction (the scan-start view) and after it,
    # the RLO after a timer instruction (the enable), a W#16# preset
    "kinds": """
        U     T 1
        =     A 0.4
        U     E 0.0
        L     S5T#50MS
        SE    T 1
        =     A 1.0
        U     T 1
        =     A 0.0
        U     E 0.1
        L     S5T#70MS
        SI    T 2
        U     T 2
        =     A 0.1
        U     E 0.2
        L     W#16#0006
        SA    T 3
        U     T 3
        =     A 0.2
        U     E 0.3
        L     S5T#40MS
        SS    T 4
        U     E 0.4
        R     T 4
        U     T 4
        =     A 0.3
        UN    T 2
        U     T 3
        =     A 0.5
        U     E 0.5
        O     E 0.1
        L     S5T#60MS
        SV    T 5
        U     T 5
        =     A 0.6
        U     E 0.6
        R     T 5
        """,
    # R T while the input is still 1 (S7 keeps the edge memory: no restart), on
    # SE, SI and SS; preset 0 (and reset)
    "resets": """
        U     E 0.0
        L     S5T#60MS
        SE    T 1
        U     T 1
        =     A 0.0
        U     E 0.5
        R     T 1
        U     E 0.1
        L     S5T#60MS
        SI    T 2
        U     E 0.5
        R     T 2
        U     T 2
        =     A 0.1
        U     E 0.2
        L     S5T#0MS
        SE    T 3
        U     T 3
        =     A 0.2
        U     E 0.6
        R     T 3
        U     E 0.3
        L     S5T#0MS
        SI    T 4
        U     T 4
        =     A 0.3
        U     E 0.4
        L     S5T#0MS
        SA    T 5
        U     T 5
        =     A 0.4
        """,
    # a timer whose instruction a jump skips: S7's status still runs out; one
    # preset loaded for two timers (the IL's ACCU1 holds its ms after the first)
    "skipped": """
        U     E 0.0
        L     S5T#80MS
        SE    T 1
        U     E 0.6
        SPB   M1
        U     E 0.1
        L     S5T#120MS
        SS    T 2
        U     E 0.2
        L     S5T#90MS
        SA    T 3
M1:     U     T 1
        =     A 0.0
        U     T 2
        =     A 0.1
        U     T 3
        =     A 0.2
        L     S5T#30MS
        L     S5T#30MS
        U     E 0.3
        SE    T 4
        SI    T 5
        U     T 4
        =     A 0.3
        U     T 5
        =     A 0.4
        """,
}


def timer_inputs(scans: int = 90) -> list[dict[int, int]]:
    """E 0.0 .. E 0.6 on and off for runs of 3 to 30 scans (about 5 ms each): the
    timers run out and are cut short; E 0.5 (the resets) pulses now and then,
    E 0.6 (the jump over the timers) holds for long."""
    runs = [18, 5, 4, 25, 9, 3, 30, 12, 6, 21]
    rows = []
    for k in range(scans):
        image = 0
        for bit in range(7):
            t, i, value = k + 7 * bit, bit, 0
            while t >= runs[i % len(runs)]:
                t -= runs[i % len(runs)]
                i, value = i + 1, value ^ 1
            if bit == 5:
                value &= (k % 23 < 2)
            if bit == 6:
                value = (k // 40) % 2
            image |= value << bit
        rows.append({0: image})
    return rows


def same_transitions(path: Path, lang: str, tmp: Path, inputs=None, **kw):
    expected, got, _ = timer_scans(path, inputs or timer_inputs(), tmp, mnemonics=lang,
                                   timers=(1, 2, 3, 4, 5), quiet=False,
                                   clock_mhz="0.05", **kw)
    diff = transition_difference(expected, got)
    assert diff is None, (path.read_text(), diff)
    return expected, got


@pytest.mark.parametrize("lang", ["de", "en"])
@pytest.mark.parametrize("name", sorted(TIMER_PROGRAM))
def test_timers_against_awlsim(tmp_path, name, lang):
    """Each transition within one scan of awlsim's (spec §9), awlsim at bitbyte's
    latch times; the timers do run out and are cut short within the 60 scans."""
    body = TIMER_PROGRAM[name]
    if lang == "en":
        body = to_english(body)
        for de, en in (("SE ", "SD "), ("SI ", "SP "), ("SA ", "SF "), ("SV ", "SE ")):
            body = body.replace(de, en)
    expected, _ = same_transitions(write(tmp_path, f"{name}_{lang}.awl", body), lang,
                                   tmp_path)
    for n in (1, 2, 3):                 # (SS T 2 of "skipped" runs out only once)
        assert len(transitions(expected, f"@T{n}")) > (n != 2), (name, n)


def test_timer_status_from_the_time_base(tmp_path):
    """An on-delay read before its instruction turns on in the scan whose latch time
    reaches the preset, not a scan after its next execution (one view per scan)."""
    path = write(tmp_path, "ton.awl", """
        U     T 1
        =     A 0.0
        U     E 0.0
        L     S5T#50MS
        SE    T 1
        U     T 1
        =     A 0.1
        """)
    expected, got = same_transitions(path, "de", tmp_path, inputs=[{0: 1}] * 120)
    latch = latch_times(got)
    on = [k for k, row in enumerate(got) if row["Q0.0"]]
    assert on and latch[on[0] - 1] < 0.050 <= latch[on[0]] + 0.001
    assert [r["Q0.0"] for r in got] == [r["Q0.1"] for r in got]


def test_timers_on_verilator_serial_and_parallel(tmp_path):
    for name in ("kinds", "skipped"):
        path = write(tmp_path, f"{name}.awl", TIMER_PROGRAM[name])
        for mode in ("serial", "parallel"):
            same_transitions(path, "de", tmp_path, sim="verilator", mode=mode)
    checked = 0
    for seed in range(60_000, 60_008):      # random timer programs too
        text, lang = random_program(seed, words=False, timers=True)
        path = tmp_path / f"tm{seed}.awl"
        path.write_text(text)
        try:
            parse_file(str(path))
        except SourceError:
            continue
        for mode in ("serial", "parallel"):
            expected, got, _ = timer_scans(path, slow_inputs(seed, 40), tmp_path,
                                           mnemonics=lang, timers=(1, 2, 3, 4, 5),
                                           sim="verilator", mode=mode)
            assert transition_difference(expected, got) is None, (seed, mode)
        checked += 1
    assert checked >= 5


# --------------------------------------------------------------------------------------
# Counters: ZV ZR (CU CD), S Z with BCD values, R Z, the status, L Z
# --------------------------------------------------------------------------------------

COUNTER_PROGRAM = """
        U     E 0.0
        ZV    Z 1
        U     E 0.1
        ZR    Z 1
        U     E 0.2
        L     C#997
        S     Z 1
        U     E 0.3
        R     Z 1
        L     Z 1
        T     MW 10
        U     Z 1
        =     A 0.0
        U     E 0.4
        L     C#5
        S     Z 2
        T     MW 12
        U     E 0.0
        ZR    Z 2
        U     E 0.4
        ZV    Z 2
        L     Z 2
        T     MW 14
        UN    Z 2
        =     A 0.1
        U     E 0.5
        L     W#16#0123
        S     Z 3
        L     Z 3
        T     MW 16
        """


def counter_inputs() -> list[dict[int, int]]:
    """S Z 1 to 997 early, then E 0.0 pulses past 999 (S7 stops there), E 0.1 and
    E 0.3 count down and reset; E 0.4 sets and counts Z 2, E 0.5 sets Z 3."""
    rows = []
    for k in range(48):
        image = (k % 2) * (k < 20)              # E 0.0: ten rising edges
        image |= (k == 2) << 2                  # E 0.2: S Z 1 to 997
        image |= (22 <= k < 30 and k % 2) << 1  # E 0.1: four down
        image |= (k == 34) << 3                 # E 0.3: R Z 1
        image |= (k % 7 == 3) << 4              # E 0.4
        image |= (k > 40) << 5                  # E 0.5
        rows.append({0: image})
    return rows


@pytest.mark.parametrize("lang", ["de", "en"])
def test_counters_against_awlsim(tmp_path, lang):
    body = COUNTER_PROGRAM
    if lang == "en":
        body = to_english(body.replace("ZV", "CU").replace("ZR", "CD")
                          .replace("Z ", "C "))
    words = ("MW10", "MW12", "MW14", "MW16")
    rows = same_as_awlsim(write(tmp_path, f"counters_{lang}.awl", body), lang,
                          counter_inputs(), tmp_path, words=words)
    assert max(r["MW10"] for r in rows) == 999      # S7's counters stop at 999
    assert rows[-1]["MW16"] == 123 and rows[-1]["MW10"] == 0


def test_counters_on_verilator_serial_and_parallel(tmp_path):
    path = write(tmp_path, "counters.awl", COUNTER_PROGRAM)
    for mode in ("serial", "parallel"):
        same_as_awlsim(path, "de", counter_inputs(), tmp_path, words=("MW10", "MW14"),
                       sim="verilator", mode=mode)


# --------------------------------------------------------------------------------------
# Symbols: --symbols FILE (STEP 7's .asc, .sdf, .seq exports), "quoted" in the source
# --------------------------------------------------------------------------------------

SYMBOLS = [("Start", "E 0.0", "BOOL"), ("Stop", "E 0.1", "BOOL"),
           ("Motor", "A 0.0", "BOOL"), ("Run time", "T 1", "TIMER"),
           ("Parts", "Z 2", "COUNTER"), ("Speed", "EW 2", "INT"),
           ("Setpoint", "MW 10", "INT"), ("lamp", "A 0.1", "BOOL"),
           ("Main", "OB 1", "OB 1")]

SYMBOL_PROGRAM = """
        U     "Start"
        O     "Motor"
        U     "Stop"
        =     "Motor"
        U     "START"
        ZV    "Parts"
        L     "Speed"
        L     "Parts"
        +I
        T     "Setpoint"
        L     "Speed"
        L     100
        >I
        =     "Lamp"
        """


def english_symbols():
    swap = {"E": "I", "A": "Q", "EW": "IW", "Z": "C"}
    return [(n, " ".join([swap.get(a.split()[0], a.split()[0])] + a.split()[1:]), t)
            for n, a, t in SYMBOLS]


@pytest.mark.parametrize("fmt", ["asc", "sdf", "seq"])
@pytest.mark.parametrize("lang", ["de", "en"])
def test_symbol_tables_against_awlsim(tmp_path, lang, fmt):
    """The same program with each export format, German and English: awlsim (which
    reads .asc) and bitbyte give the same scans; names are matched without case."""
    rows = SYMBOLS if lang == "de" else english_symbols()
    body = SYMBOL_PROGRAM if lang == "de" else to_english(SYMBOL_PROGRAM.replace("ZV",
                                                                                "CU"))
    path = write(tmp_path, f"sym_{lang}.awl", body)
    asc = tmp_path / f"sym_{lang}.asc"
    asc.write_bytes(symbol_table(rows, "asc").encode())
    table = tmp_path / f"sym_{lang}.{fmt}"
    table.write_bytes(symbol_table(rows, fmt).encode())
    inputs = [{0: k % 4, 2: 0, 3: (k * 37) % 256} for k in range(24)]
    words = ("MW10",)
    expected = awlsim_scans(path, inputs, mnemonics=lang, words=words, symbols=asc)
    got = bitbyte_scans(path, inputs, tmp_path, words=words, in_words=(2,),
                        symbols=table)
    assert first_difference(expected, got) is None
    assert [r["Q0.0"] for r in got][:8] == [0, 0, 0, 1, 0, 0, 0, 1]   # the seal-in


def test_symbols_in_the_other_language(tmp_path):
    """A German table for an English source: the addresses are read in the table's
    language (E 0.0 is I0.0)."""
    path = write(tmp_path, "sym_en.awl", to_english(SYMBOL_PROGRAM.replace("ZV", "CU")))
    de, en = tmp_path / "de.sdf", tmp_path / "en.sdf"
    de.write_text(symbol_table(SYMBOLS, "sdf"))
    en.write_text(symbol_table(english_symbols(), "sdf"))
    inputs = [{0: k % 4, 3: k} for k in range(10)]
    assert bitbyte_scans(path, inputs, tmp_path, symbols=de, in_words=(2,)) == \
        bitbyte_scans(path, inputs, tmp_path, symbols=en, in_words=(2,))


def test_symbols_cli_watch_and_stimulus(tmp_path, capsys):
    path = write(tmp_path, "sym.awl", SYMBOL_PROGRAM)
    table = tmp_path / "sym.seq"
    table.write_text(symbol_table(SYMBOLS, "seq"))
    stim = tmp_path / "sym.stim.csv"
    stim.write_text("scan,Start,Stop,Speed\n0,1,1,150\n1,0,1,150\n3,0,0,7\n")
    trace = tmp_path / "trace.csv"
    code, _, err = run_cli(["run", str(path), "--symbols", str(table), "--stimulus",
                            str(stim), "--scans", "5", "--watch", "Setpoint,Parts",
                            "--trace", str(trace)], capsys)
    assert code == 0, err
    rows = [line.split(",") for line in trace.read_text().splitlines()]
    assert rows[0] == ["scan", "t_us", "cycles", "Q0.0", "Q0.1", "Setpoint", "Parts"]
    assert [r[3] for r in rows[1:]] == ["1", "1", "1", "0", "0"]
    assert rows[1][5:] == ["151", "1"]


def test_symbols_on_verilator_serial_and_parallel(tmp_path):
    path = write(tmp_path, "sym.awl", SYMBOL_PROGRAM)
    asc = tmp_path / "sym.asc"
    asc.write_text(symbol_table(SYMBOLS, "asc"))
    inputs = [{0: k % 4, 2: 0, 3: (k * 37) % 256} for k in range(12)]
    expected = awlsim_scans(path, inputs, mnemonics="de", words=("MW10",), symbols=asc)
    for mode in ("serial", "parallel"):
        got = bitbyte_scans(path, inputs, tmp_path, words=("MW10",), in_words=(2,),
                            symbols=asc, sim="verilator", mode=mode)
        assert first_difference(expected, got) is None, mode


@pytest.mark.parametrize("body,table,line,col,message", [
    ('U     "Nope"', "asc", 8, 7, 'undeclared symbol `"Nope"` (not in the symbol table'),
    ('U     "Start"', None, 8, 7, 'undeclared symbol `"Start"` (no symbol table'),
    ('U     "Main"', "asc", 8, 7, 'unsupported: symbol `"Main"` is `OB 1`'),
    ('U     "Setpoint"', "sdf", 8, 7, 'unsupported: byte/word operand `"Setpoint" = '
     'MW 10`'),
    ('L     "Start"', "seq", 8, 7, 'operand of the wrong kind: `L` needs a word, not '
     '`"Start" = E 0.0`'),
])
def test_symbol_errors(tmp_path, capsys, body, table, line, col, message):
    path = write(tmp_path, "bad.awl", body)
    argv = ["asm", str(path), "-o", str(tmp_path)]
    if table:
        (tmp_path / f"s.{table}").write_text(symbol_table(SYMBOLS, table))
        argv += ["--symbols", str(tmp_path / f"s.{table}")]
    code, _, err = run_cli(argv, capsys)
    assert code == 1 and err.startswith(f"{path}:{line}:{col}: {message}"), err
    assert "Traceback" not in err


@pytest.mark.parametrize("text,message", [
    ('"A","E 0.0","BOOL",""\n"a","E 0.1","BOOL",""\n', "2:1: duplicate symbol `a`"),
    ('"A","","BOOL",""\n', "1:1: symbol table (.sdf): symbol `A` has no address"),
    ("just text\n", "1:1: not a STEP 7 symbol table"),
    ('"A","E 0.0","BOOL",""\n"B","I 0.1","BOOL",""\n', "2:1: mixed mnemonics"),
])
def test_symbol_table_errors(tmp_path, capsys, text, message):
    path = write(tmp_path, "p.awl", 'U     "A"\n=     A 0.0')
    table = tmp_path / "t.sdf"
    table.write_text(text)
    code, _, err = run_cli(["asm", str(path), "--symbols", str(table), "-o",
                            str(tmp_path)], capsys)
    assert code == 1 and err.startswith(f"{table}:{message}"), err


def test_symbols_need_an_s7_source(tmp_path, capsys):
    il = tmp_path / "p.il"
    il.write_text("LD I0.0\n= Q0.0\n")
    table = tmp_path / "t.sdf"
    table.write_text('"A","E 0.0","BOOL",""\n')
    code, _, err = run_cli(["asm", str(il), "--symbols", str(table)], capsys)
    assert code == 1 and "goes with an S7 source" in err


# --------------------------------------------------------------------------------------
# The command line and its errors
# --------------------------------------------------------------------------------------

def run_cli(argv, capsys):
    code = cli.main(argv)
    out = capsys.readouterr()
    return code, out.out, out.err


def test_cli_asm_and_run(tmp_path, capsys):
    path = write(tmp_path, "seal.awl", SEAL_IN["de"])
    (tmp_path / "seal.stim.csv").write_text("scan,I0.0,I0.1\n0,1,1\n1,0,1\n3,0,0\n")
    code, out, err = run_cli(["asm", str(path), "-o", str(tmp_path / "out")], capsys)
    assert code == 0 and "seal.hex" in out, err
    trace = tmp_path / "trace.csv"
    code, out, err = run_cli(["run", str(path), "--stimulus",
                              str(tmp_path / "seal.stim.csv"), "--scans", "5",
                              "--trace", str(trace)], capsys)
    assert code == 0, err
    rows = [line.split(",") for line in trace.read_text().splitlines()]
    assert rows[0] == ["scan", "t_us", "cycles", "Q0.0"]
    assert [r[3] for r in rows[1:]] == ["1", "1", "1", "0", "0"]


def test_lang_option_for_another_suffix(tmp_path, capsys):
    path = tmp_path / "seal.stl"
    path.write_text(ob1(SEAL_IN["en"]))
    code, _, err = run_cli(["asm", str(path), "--lang", "stl", "-o", str(tmp_path)],
                           capsys)
    assert code == 0, err
    code, _, err = run_cli(["asm", str(path), "--lang", "stl", "--mnemonics", "de",
                            "-o", str(tmp_path)], capsys)
    assert code == 1 and "`A` is English" in err


ERRORS = [
    # (body, line within the file, column, message start); the body starts at line 8
    ("U     E 0.0\nL     MW 0\nSE    T 1", 10, 1, "unsupported: `SE` with a preset the "
     "compiler does not know"),
    ("U     E 0.0\nL     W#16#00AA\nSE    T 1", 10, 1, "unsupported: `SE` with a preset"),
    ("U     E 0.0\nL     S5T#1S\nSE    T 1\nL     S5T#2S\nSE    T 1", 12, 1,
     "unsupported: `SE` with another preset than the first start of `T 1`"),
    ("U     E 0.0\nL     S5T#1S\nSE    T 1\nSS    T 1", 11, 1,
     "unsupported: `SS` on a timer started as `SE` at line 10"),
    ("U     E 0.0\nL     S5T#1S\nSA    T 1\nR     T 1", 11, 1,
     "unsupported: `R T 1` on an off-delay timer"),
    ("U     E 0.0\nL     S5T#1S\nSE    T 1\nL     MW 0\n+I", 12, 1,
     "unsupported: `+I` reads ACCU2, which the translation of an earlier timer"),
    ("U     E 0.0\nL     S5T#1S\nSE    T 1\nT     MW 0", 11, 1,
     "unsupported: `T` reads ACCU1, which the translation of an earlier timer"),
    ("U     E 0.0\nL     S5T#1S\nSE    T 1\nU     M 255.7\n=     A 0.0", 11, 7,
     "unsupported: `M 255.7` uses M255.7, which the translation"),
    ("U     E 0.0\nL     S5T#1S\nSE    T 64", 10, 7, "operand out of range: `T 64`"),
    ("U     E 0.0\nL     S5T#3H", 9, 7, "malformed constant `S5T#3H`"),
    ("U     E 0.0\nL     S5T#1S\nSA    T 1\nFR    T 1", 11, 1,
     "unsupported: `FR T 1` on an off-delay timer"),
    ("U     E 0.0\nL     MW 0\nS     Z 1", 10, 1, "unsupported: `S Z 1` with a value"),
    ("U     E 0.0\nL     W#16#00AB\nS     Z 1", 10, 1, "unsupported: `S Z 1` with a"),
    ("U     E 0.0\nZV    Z 1\nT     MW 0", 10, 1, "unsupported: `T` reads ACCU1, which "
     "the translation of an earlier timer or counter"),
    ("U     E 0.0\nZV    Z 64", 9, 7, "operand out of range: `Z 64`"),
    ("U     E 0.0\nZV    M 0.0", 9, 7, "operand of the wrong kind: `ZV` needs a counter"),
    ("LC    T 64", 8, 7, "operand out of range: `T 64`"),
    ("U(\nU     E 0.0\nFR    Z 1", 10, 1, "unsupported: `FR` inside parentheses"),
    ("U(\nU     E 0.0\nL     S5T#1S\nSE    T 1\n)", 11, 1,
     "unsupported: `SE` inside parentheses"),
    ("L     MW 0\n+I", 9, 1,
     "unsupported: `+I` reads ACCU2, which this OB has not loaded here"),
    ("T     MW 2", 8, 1, "unsupported: `T` reads ACCU1"),
    ("U     E 0.0\nSPB   M1\nL     1\nL     2\nM1:   +I\nT     MW 0", 12, 7,
     "unsupported: `+I` reads ACCU1"),
    ("L     MW 10\nT     MW 11", 9, 7, "unsupported: `MW 11` and `MW 10` (line 8) "
     "overlap"),
    ("U     M 10.1\n=     A 0.0\nL     1\nT     MW 9", 11, 7,
     "unsupported: word `MW 9` overlaps the bit `M 10.1` (line 8)"),
    ("L     EW 0\nT     MW 2\nU     E 1.7\n=     A 0.0", 8, 7,
     "unsupported: word `EW 0` overlaps the bit `E 1.7`"),
    ("L     40000", 8, 7, "unsupported: constant `40000` beyond INT"),
    ("L     L#5x", 8, 7, "malformed constant `L#5x`"),
    ("L     1.5", 8, 7, "unsupported: REAL constant `1.5`"),
    ("L     W#16#10000", 8, 7, "constant out of range: `W#16#10000`"),
    ("L     C#1000", 8, 7, "malformed constant `C#1000`"),
    ("L     MB 0", 8, 7, "unsupported: operand `MB 0` in `L`"),
    ("L     1\nT     EW 0", 9, 7, "unsupported: `T EW 0` writes the input image"),
    # DINT (tests/test_stl_dint.py): an accumulator whose high word S7 holds otherwise
    ("L     MW 2\nL     2\nMOD\nT     MW 0", 10, 1, "unsupported: `MOD` reads ACCU2 "
     "as a DINT"),
    ("L     1\nL     -2\n+D\nT     MW 0", 10, 1, "unsupported: `+D` reads ACCU1 as a "
     "DINT"),
    ("L     1\nL     2\nTAK", 10, 1, "unsupported: `TAK`"),
    ("L     1\nL     2\n+     1\n+I", 11, 1, "unsupported: `+I` reads ACCU2, which "
     "the translation of `+ 1` (line 10) changed (S7 leaves it alone)"),
    # review finding: after NEGI / INVI the message named only `+ n`
    ("L     1\nL     2\nNEGI\n+I", 11, 1, "unsupported: `+I` reads ACCU2, which "
     "the translation of `NEGI` (line 10) changed"),
    ("L     1\nL     2\nINVI\n<I\n=     A 0.0", 11, 1, "unsupported: `<I` reads ACCU2, "
     "which the translation of `INVI` (line 10) changed"),
    ("L     -1\n+     L#1", 9, 1, "unsupported: `+` reads ACCU1 as a DINT"),
    ("L     1\n+     40000", 9, 7, "unsupported: constant `40000` beyond INT"),
    ("+     1", 8, 1, "unsupported: `+` reads ACCU1, which this OB has not loaded"),
    ("L     MW 256", 8, 7, "operand out of range: `MW 256`"),
    ("U     E 0.0\nU     I 0.1\n=     A 0.0", 9, 7, "mixed mnemonics: `I` is English"),
    ("U     E 0.0\nA     I 0.1", 9, 1, "mixed mnemonics: `A` is English"),
    ("UX    E 0.0", 8, 1, "unknown mnemonic `UX`"),
    ("U(\nU     E 0.0\n=     A 0.0", 8, 1, "unbalanced parentheses"),
    (")\n=     A 0.0", 8, 1, "unbalanced parentheses"),
    ("SPA   M9", 8, 7, "unknown label `M9`"),
    ("U     E 16.0\n=     A 0.0", 8, 7, "operand out of range"),
    ("U     E 0.8", 8, 7, "operand out of range"),
    ("U     E 0.0\n=     E 0.1", 9, 7, "unsupported: `= E 0.1` writes the input image "
     "(inputs come from the stimulus)"),
    # review findings: valid S7 rejected as a wrong kind or as undeclared; invalid
    # constants and operands accepted (Python's int() reads signs and `_`)
    ("U     E 0.0\nS     E 0.1", 9, 7, "unsupported: `S E 0.1` writes the input image"),
    ("U     E 0.0\nR     E 0.1", 9, 7, "unsupported: `R E 0.1` writes the input image"),
    ("U     E 0.0\nFP    E 0.1", 9, 7, "unsupported: `FP E 0.1` writes the input image"),
    ("L     2#" + "1" * 33 + "\nT     MW 0", 8, 7, "constant out of range"),
    ("L     B#(1,2,3)\nT     MW 0", 8, 7, "malformed constant `B#(1,2,3)`"),
    ("L     B#(1,256)\nT     MW 0", 8, 7, "malformed constant `B#(1,256)`"),
    ("U     #s.a\n=     A 0.0", 8, 7, "unsupported: STRUCT/ARRAY member `#s.a`"),
    ("L     W#16#-1\nT     MW 0", 8, 7, "malformed constant `W#16#-1`"),
    ("L     B#16#-1\nT     MW 0", 8, 7, "malformed constant `B#16#-1`"),
    ("L     2#-1\nT     MW 0", 8, 7, "malformed constant `2#-1`"),
    ("L     2#12\nT     MW 0", 8, 7, "malformed constant `2#12`"),
    ("L     W#16#1_\nT     MW 0", 8, 7, "malformed constant `W#16#1_`"),
    ("L     16#-8000\nT     MW 0", 8, 7, "malformed constant `16#-8000`"),
    ("L     16#FFFF\nT     MW 0", 8, 7, "malformed constant `16#FFFF`"),
    ("NOP   2", 8, 7, "malformed operand `2`: `NOP` takes a number 0..1"),
    ("BLD   300", 8, 7, "malformed operand `300`: `BLD` takes a number 0..255"),
    ("NOP", 8, 1, "missing operand: `NOP` needs a number 0..1"),
    ("L     1\n+     (", 9, 7, "malformed operand `(`: `+` takes a constant"),
    ("L     1\n+     )", 9, 7, "malformed operand `)`: `+` takes a constant"),
    ("CALL  FC", 8, 7, "malformed call `CALL FC`"),
    ("CALL  FB 1,", 8, 7, "malformed call `CALL FB 1,`"),
    ("U     E 0.0\n=", 9, 1, "missing operand"),
    ("U     E 0.0 E 0.1", 8, 13, "extra operand"),
    ("U     E 0.0\nO\nNOT\n=     A 0.0", 10, 1, "unsupported: NOT after `O`"),
    ("U     E 0.0\nSPB   M1\nU     E 0.1\nSPA   M1\nM1:   O     E 0.3\n=     A 0.1",
     12, 1, "unsupported: jump target `M1` is reached with /FC = 0 (from line 9) and "
     "/FC = 1 (from line 11)"),
    ("U     E 0.0\nSPA   M1\nM2:   =     A 0.0\nM1:   NOT\nSPA   M2", 11, 1,
     "unsupported: jump target `M1` is reached with /FC = 0"),
    ("U(\n=     A 0.0\n)", 9, 1, "unsupported: `=` right after `U(`"),
]


@pytest.mark.parametrize("body,line,col,message", ERRORS)
def test_errors_point_at_the_statement(tmp_path, capsys, body, line, col, message):
    path = write(tmp_path, "bad.awl", body)
    code, out, err = run_cli(["asm", str(path), "-o", str(tmp_path)], capsys)
    assert code == 1, (out, err)
    assert err.startswith(f"{path}:{line}:{col}: {message}"), err
    assert "Traceback" not in err


@pytest.mark.parametrize("text,message", [
    ("TYPE UDT 1\nSTRUCT\nEND_STRUCT\nEND_TYPE\n", "1:1: unsupported: TYPE"),
    ("ORGANIZATION_BLOCK OB 35\nBEGIN\nEND_ORGANIZATION_BLOCK\n",
     "1:1: unsupported: `ORGANIZATION_BLOCK OB 35`"),
    ("ORGANIZATION_BLOCK OB 1\nBEGIN\nU E 0.0\n", "2:1: missing END_ORGANIZATION_BLOCK"),
    ("", "no ORGANIZATION_BLOCK OB 1"),
    ('FUNCTION_BLOCK "Motor"\nBEGIN\nEND_FUNCTION_BLOCK\n',
     '1:16: unsupported: block named by a symbol `"Motor"`'),
])
def test_block_errors(tmp_path, capsys, text, message):
    path = tmp_path / "blocks.awl"
    path.write_text(text)
    code, _, err = run_cli(["run", str(path)], capsys)
    assert code == 1 and message in err.splitlines()[0], err


# --------------------------------------------------------------------------------------
# Random programs against awlsim
# --------------------------------------------------------------------------------------

def random_cases(tmp: Path, count: int, offset: int = 0, base: int | None = None):
    """base: the run's seed (BITBYTE_SEED) unless given."""
    base = BASE_SEED if base is None else base
    for index in range(offset, offset + count):
        seed = base * 10_000 + index
        text, lang = random_program(seed)
        path = tmp / f"stl{seed}.awl"
        path.write_text(text)
        yield seed, path, lang, random_inputs(seed, 12)


def test_random_programs_against_awlsim(tmp_path):
    """0 mismatches; what is rejected is rejected as `unsupported:` and stays rare;
    every construct the generator makes appears in an accepted program."""
    compared, rejected, seen = 0, [], set()
    for seed, path, lang, inputs in random_cases(tmp_path, PROGRAMS):
        if not equal_or_rejected(seed, path, lang, inputs, tmp_path, words=WORDS,
                                 in_words=IN_WORDS):
            rejected.append(seed)
            continue
        compared += 1
        seen |= {line.split()[0].split(":")[-1] for line in path.read_text().splitlines()
                 if line.strip() and line.startswith("\t")}
    # (about 13 % rejected: 27 of 200 expected, 5 a standard deviation)
    assert len(rejected) <= PROGRAMS * 0.25, rejected
    need = {"O", "ON", "X", "XN", "O(", "ON(", "X(", "XN(", ")", "=", "S", "R", "FP",
            "FN", "NOT", "SET", "CLR"}
    need |= {"U", "UN", "U(", "UN(", "SPA", "SPB", "SPBN", "BEB",
             "A", "AN", "A(", "AN(", "JU", "JC", "JCN", "BEC"}
    need |= {"L", "T", "+I", "-I", "*I", "/I", "==I", "<>I", ">I", "<I", ">=I", "<=I"}
    need |= {"ZV", "ZR", "CU", "CD"}
    dint = {"+D", "-D", "*D", "/D", "MOD", "NEGD", "INVD", "+", "==D", "<>D", ">D", "<D",
            ">=D", "<=D", "OW", "XOW", "OD", "XOD", "SLW", "SRW", "SSI", "SLD", "SRD",
            "SSD", "RLD", "RRD", "UW", "AW", "UD", "AD", "SPZ", "SPN", "SPP", "SPM",
            "SPPZ", "SPMZ", "SPU", "JZ", "JN", "JP", "JM", "JPZ", "JMZ", "JUO"}
    need.add("ITD")
    if PROGRAMS >= 200:         # each DINT one in the soak's 1 000s, some in 200
        assert need <= seen, need - seen
        assert len(dint & seen) >= (len(dint) if PROGRAMS >= 1000 else 8), dint - seen
    print(f"{compared} random STL programs equal awlsim's, {len(rejected)} rejected "
          "as unsupported")


TIMER_PROGRAMS = int(os.environ.get("BITBYTE_STL_TIMER_PROGRAMS", "100"))


def test_random_timer_programs_against_awlsim(tmp_path):
    """Random programs with timers (tests/stlgen.py, timers=True): every transition
    within one scan of awlsim's, awlsim at bitbyte's latch times (0.02 MHz: scans of
    a few ms), the inputs kept quiet around awlsim's timer transitions."""
    compared, rejected, seen = 0, 0, set()
    for index in range(TIMER_PROGRAMS):
        seed = BASE_SEED * 10_000 + 20_000 + index
        text, lang = random_program(seed, words=False, timers=True)
        path = tmp_path / f"tm{seed}.awl"
        path.write_text(text)
        if not timer_equal_or_rejected(seed, path, lang, slow_inputs(seed, 40), tmp_path,
                                       timers=(1, 2, 3, 4, 5),
                                       values=time_value_columns(text)):
            rejected += 1
            continue
        compared += 1
        seen |= {line.split()[0] for line in text.splitlines() if line.startswith("\t")}
        seen |= {"R T" for line in text.splitlines() if line.startswith("\tR\tT")}
        seen |= {f"{line.split()[0]} T" for line in text.splitlines()
                 if re.match(r"\tLC?\tT ", line)}
    assert rejected <= TIMER_PROGRAMS * 0.2
    if TIMER_PROGRAMS >= 100:
        need = {"SI", "SV", "SE", "SS", "SA", "SP", "SD", "SF", "R T", "L T", "LC T"}
        assert need <= seen, need - seen
    print(f"{compared} random STL timer programs make awlsim's transitions, each "
          f"within one scan; {rejected} rejected as unsupported")


SYMBOL_PROGRAMS = int(os.environ.get("BITBYTE_STL_SYMBOL_PROGRAMS", "100"))


def test_random_programs_with_symbols_against_awlsim(tmp_path):
    """Random programs with half of their operands as quoted symbols of a STEP 7
    symbol table (stlgen.with_symbols): awlsim reads the .asc export, bitbyte each of
    .asc, .sdf and .seq; equal scan for scan."""
    # about one program in six uses a construct bitbyte refuses (`unsupported:`); the
    # share varies with the seed (22 of 100 at BITBYTE_SEED=629080), so programs past
    # SYMBOL_PROGRAMS are drawn until 80 % of it are compared (at most twice as many)
    wanted = int(SYMBOL_PROGRAMS * 0.8)
    compared = 0
    index = -1
    while index + 1 < SYMBOL_PROGRAMS or (compared < wanted and index + 1 < 2 * SYMBOL_PROGRAMS):
        index += 1
        seed = BASE_SEED * 10_000 + 30_000 + index
        text, lang = random_program(seed)
        text, rows = with_symbols(text, lang, seed)
        path = tmp_path / f"sym{seed}.awl"
        path.write_text(text)
        tables = {}
        for fmt in ("asc", "sdf", "seq"):
            tables[fmt] = tmp_path / f"sym{seed}.{fmt}"
            tables[fmt].write_bytes(symbol_table(rows, fmt).encode("cp1252"))
        inputs = random_inputs(seed, 12)
        try:
            got = bitbyte_scans(path, inputs, tmp_path, words=WORDS, in_words=IN_WORDS,
                                symbols=tables["asc"])
        except SourceError as e:
            assert e.message.startswith("unsupported:"), (seed, str(e))
            continue
        expected = awlsim_scans(path, inputs, mnemonics=lang, words=WORDS,
                                symbols=tables["asc"])
        assert first_difference(expected, got) is None, (seed, path)
        if index % 10 == 0:
            for fmt in ("sdf", "seq"):
                assert got == bitbyte_scans(path, inputs, tmp_path, words=WORDS,
                                            in_words=IN_WORDS, symbols=tables[fmt])
        compared += 1
    assert compared >= wanted, (compared, index + 1)
    print(f"{compared} random STL programs with symbol tables equal awlsim's")


def test_random_programs_on_verilator_serial_and_parallel(tmp_path):
    """A sample on the C++ harness: serial and parallel mode equal awlsim too."""
    checked = 0
    # programs until 8 are accepted (about 13 % are rejected as unsupported)
    for seed, path, lang, inputs in random_cases(tmp_path, 40, offset=50_000):
        if checked == 8:
            break
        try:
            parse_file(str(path))
        except SourceError:
            continue
        expected = awlsim_scans(path, inputs, mnemonics=lang, words=WORDS)
        for mode in ("serial", "parallel"):
            got = bitbyte_scans(path, inputs, tmp_path, sim="verilator", mode=mode,
                                words=WORDS, in_words=IN_WORDS)
            assert first_difference(expected, got) is None, (seed, mode)
        checked += 1
    assert checked == 8


def test_seal_in_on_verilator(tmp_path):
    path = write(tmp_path, "seal.awl", SEAL_IN["de"])
    inputs = [{0: 0b10}, {0: 0b11}, {0: 0b10}, {0: 0b00}, {0: 0b10}]
    for mode in ("serial", "parallel"):
        same_as_awlsim(path, "de", inputs, tmp_path, sim="verilator", mode=mode)


# --------------------------------------------------------------------------------------
# The comparison can fail: deliberately wrong translations are caught
# --------------------------------------------------------------------------------------

def mismatches(tmp: Path, count: int = 60) -> int:
    """Random programs disagreeing with awlsim. The seeds are fixed (not the run's
    BITBYTE_SEED): a check that a broken translation is caught must not depend on
    whether this run's programs happen to use the broken construct."""
    found = 0
    for seed, path, lang, inputs in random_cases(tmp, count, offset=90_000, base=0):
        try:
            got = bitbyte_scans(path, inputs, tmp, words=WORDS, in_words=IN_WORDS)
        except SourceError:
            continue
        found += first_difference(awlsim_scans(path, inputs, mnemonics=lang,
                                               words=WORDS), got) is not None
    return found


def test_oracle_catches_a_missing_first_check(tmp_path, monkeypatch):
    """Translate U/UN as A/AN even at /FC = 0 (what an IL programmer gets by
    writing `A Start` first): the seal-in never starts, awlsim disagrees."""
    real = stl.StlFrontEnd.combine

    def no_first_check(self, stmt, st, m):
        if st.ner == 0 and m in ("A", "AN"):
            self.emit(m, self.bit_operand(stmt))
            st.ner = 1
            return
        real(self, stmt, st, m)

    monkeypatch.setattr(stl.StlFrontEnd, "combine", no_first_check)
    path = write(tmp_path, "seal.awl", SEAL_IN["de"])
    inputs = [{0: 0b10}, {0: 0b11}, {0: 0b10}]
    assert first_difference(awlsim_scans(path, inputs, mnemonics="de"),
                            bitbyte_scans(path, inputs, tmp_path)) is not None
    assert mismatches(tmp_path) > 0


def test_oracle_catches_or_strictly_in_sequence(tmp_path, monkeypatch):
    """Ignore `O` without operand (IL's strictly-in-sequence OR): caught."""
    real = stl.StlFrontEnd.statement

    def no_and_before_or(self, stmt, st, edges):
        if stmt.canon == "O" and not stmt.operands:
            return True
        return real(self, stmt, st, edges)

    path = write(tmp_path, "or_seq.awl", """
        U     E 0.0
        U     E 0.1
        O
        U     E 0.2
        =     A 0.0
        """)
    inputs = every_input()
    same_as_awlsim(path, "de", inputs, tmp_path)
    monkeypatch.setattr(stl.StlFrontEnd, "statement", no_and_before_or)
    assert first_difference(awlsim_scans(path, inputs, mnemonics="de"),
                            bitbyte_scans(path, inputs, tmp_path)) is not None
    assert mismatches(tmp_path) > 0


def test_oracle_catches_rlo_kept_after_a_conditional_jump(tmp_path, monkeypatch):
    """Leave the RLO as it is after SPB / SPBN (S7 sets it to 1): caught."""
    path = write(tmp_path, "jump.awl", """
        U     E 0.0
        SPB   M1
        =     A 0.0
M1:     U     E 0.1
        =     A 0.1
        """)
    inputs = every_input()
    same_as_awlsim(path, "de", inputs, tmp_path)
    real = stl.StlFrontEnd.jump

    def keep_rlo(self, stmt, st, m, edges):
        result = real(self, stmt, st, m, edges)
        st.need_set = False
        return result

    monkeypatch.setattr(stl.StlFrontEnd, "jump", keep_rlo)
    assert first_difference(awlsim_scans(path, inputs, mnemonics="de"),
                            bitbyte_scans(path, inputs, tmp_path)) is not None


def test_oracle_catches_timers_without_the_scan_start_update(tmp_path, monkeypatch):
    """Without the scan-start update a timer read before its instruction changes a
    scan late, and one that a jump skips does not run out: caught."""
    monkeypatch.setattr(stl.StlFrontEnd, "prepend_timer_update", lambda self: None)
    path = write(tmp_path, "skipped.awl", TIMER_PROGRAM["skipped"])
    expected, got, _ = timer_scans(path, timer_inputs(), tmp_path, mnemonics="de",
                                   timers=(1, 2, 3, 4, 5), quiet=False,
                                   clock_mhz="0.05")
    assert transition_difference(expected, got) is not None


def test_oracle_catches_a_pulse_on_the_ils_pulse_timer(tmp_path, monkeypatch):
    """S7's SI on the IL's SP (IEC TP: it does not stop when the input falls) with
    the IL's status: caught."""
    real = stl.StlFrontEnd.timer

    def tp(self, stmt, st, m):
        if m == "SP":
            self.emit("L", stl.Operand("const", area="TIME", value=70, text="70ms"))
            self.emit("SP", self.timer_operand(stmt))
            self.scratch_bits.pop(("view", self.timer_operand(stmt).index), None)
            st.ner = 0
            return
        real(self, stmt, st, m)

    monkeypatch.setattr(stl.StlFrontEnd, "timer", tp)
    monkeypatch.setattr(stl.StlFrontEnd, "prepend_timer_update", lambda self: None)
    path = write(tmp_path, "si.awl", """
        U     E 0.1
        L     S5T#70MS
        SI    T 2
        U     T 2
        =     A 0.1
        """)
    expected, got, _ = timer_scans(path, timer_inputs(), tmp_path, mnemonics="de",
                                   timers=(2,), quiet=False, clock_mhz="0.05")
    assert transition_difference(expected, got) is not None


def test_oracle_catches_counters_past_999(tmp_path, monkeypatch):
    """ZV as the IL's CU alone (it counts on to 32767): caught."""
    real = stl.StlFrontEnd.counter

    def plain(self, stmt, st, m):
        if m == "CU":
            self.emit("CU", self.counter_operand(stmt))
            st.ner = 0
            return
        real(self, stmt, st, m)

    monkeypatch.setattr(stl.StlFrontEnd, "counter", plain)
    path = write(tmp_path, "counters.awl", COUNTER_PROGRAM)
    assert first_difference(awlsim_scans(path, counter_inputs(), mnemonics="de",
                                         words=("MW10",)),
                            bitbyte_scans(path, counter_inputs(), tmp_path,
                                          words=("MW10",))) is not None


@pytest.mark.parametrize("name,wrong", [
    ("add_constant", {"+": ("n",)}),                  # `+ n` as `L n` alone
    ("negate_invert", {"NEGI": (-1, "*I"), "INVI": (-1, "*I")}),   # INVI as NEGI
])
def test_oracle_catches_wrong_in_place_steps(tmp_path, monkeypatch, name, wrong):
    monkeypatch.setattr(stl, "IN_PLACE", {**stl.IN_PLACE, **wrong})
    with pytest.raises(AssertionError):
        test_word_instructions_against_awlsim(tmp_path, name, "de")


@pytest.mark.parametrize("lang", ["de", "en"])
def test_two_byte_constant_against_awlsim(tmp_path, lang):
    """Review finding: `L B#(1,2)` was an `extra operand`; it is the 16-bit pattern
    byte1 * 256 + byte2 (awlsim: 258)."""
    path = write(tmp_path, "bb.awl", "L     B#(1,2)\nT     MW 10\nL     B#( 255 , 255 )\n"
                 "T     MW 12\nL     2#1111_0000_1111_0000\nT     MW 14")
    words = ("MW10", "MW12", "MW14")
    expected = awlsim_scans(path, [{}], mnemonics=lang, words=words)
    got = bitbyte_scans(path, [{}], tmp_path, words=words, mnemonics=lang)
    assert first_difference(expected, got) is None
    assert [expected[0][w] for w in words] == [258, -1, -3856]


def test_se_alone_does_not_decide_the_language(tmp_path, capsys):
    """Review finding: a source whose only language-specific word is `SE` compiled
    as German (the on-delay) silently; English reads it as the extended pulse.  It
    is an error at the `SE` now, unless --mnemonics decides."""
    path = write(tmp_path, "se.awl", "O     M 0.0\nL     S5T#1S\nSE    T 1\nO     T 1\n"
                 "=     M 0.1")
    code, _, err = run_cli(["asm", str(path), "-o", str(tmp_path)], capsys)
    assert code == 1 and err.startswith(
        f"{path}:10:1: ambiguous: `SE` is the German on-delay and the English extended "
        "pulse; no other word decides the language: give --mnemonics de|en"), err
    for lang in ("de", "en"):
        code, _, err = run_cli(["asm", str(path), "--mnemonics", lang, "-o",
                                str(tmp_path)], capsys)
        assert code == 0, err
    # another word decides: no error (German `E`), and no `SE`: today's default
    for body in ("U     E 0.0\nL     S5T#1S\nSE    T 1", "O     M 0.0\n=     M 0.1"):
        path = write(tmp_path, "ok.awl", body)
        code, _, err = run_cli(["asm", str(path), "-o", str(tmp_path)], capsys)
        assert code == 0, err
