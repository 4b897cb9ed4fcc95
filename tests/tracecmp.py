"""Two traces compared scan by scan: the oracle comparisons of the tests, one helper
for all (awlsim against bitbyte, spec §9, tests/awlsim_oracle.py; a parallel-mode
plant against the serial plant, spec §7, tests/test_plant_parallel.py).

A trace is a list of rows, one per scan, each {column: value}.  Columns whose name
starts with `@` are a run's own bookkeeping (awlsim_oracle's latch time), and
`ignore` names more that are not compared (a plant's `t_us`, `cycles`, ...).
"""
from __future__ import annotations


def numeric(rows: list[dict[str, str]]) -> list[dict[str, int]]:
    """Rows as csv.DictReader gives them (bitbyte.plant.run's) with integer values."""
    return [{c: int(v) for c, v in row.items()} for row in rows]


def transitions(rows: list[dict[str, int]], column: str) -> list[tuple[int, int]]:
    """(scan, new value) of every change of `column`, from the reset value 0."""
    out, last = [], 0
    for k, row in enumerate(rows):
        if row[column] != last:
            out.append((k, row[column]))
            last = row[column]
    return out


def transition_difference(expected, got, slack: int = 1):
    """None if every column makes the same transitions in both, each within `slack`
    scans (spec §9: timer programs), else (column, expected's, got's).  A
    transition in the last `slack` scans may be missing from the other trace (it
    would come after its end)."""
    end = len(expected) - slack
    for column in expected[0]:
        if column[0] == "@":
            continue
        a, b = transitions(expected, column), transitions(got, column)
        longer = a[len(b):] + b[len(a):]
        if any(k < end for k, _ in longer) or any(
                va != vb or abs(ka - kb) > slack for (ka, va), (kb, vb) in zip(a, b)):
            return column, a, b
    return None


def first_difference(expected: list[dict[str, int]], got: list[dict[str, int]],
                     ignore=()):
    """(scan, {column: (expected, got)}) of the first scan that differs in a compared
    column, or None.  Different numbers of scans, or of compared columns, differ at
    the first scan one trace lacks (as "scans" / "columns")."""
    if len(expected) != len(got):
        return (min(len(expected), len(got)), {"scans": (len(expected), len(got))})
    for k, (a, b) in enumerate(zip(expected, got)):
        columns = [c for c in a if c[0] != "@" and c not in ignore]
        if k == 0 and set(columns) != {c for c in b if c[0] != "@" and c not in ignore}:
            return 0, {"columns": (list(a), list(b))}
        diff = {c: (a[c], b[c]) for c in columns if a[c] != b[c]}
        if diff:
            return k, diff
    return None


def bcd_units(word: int) -> tuple[int, int] | None:
    """(time base code, units) of an S5TIME pattern, None if it is not one."""
    digits = [(word >> k) & 0xF for k in (8, 4, 0)]
    if word & 0xC000 or max(digits) > 9:
        return None
    return (word >> 12) & 3, digits[0] * 100 + digits[1] * 10 + digits[2]


def time_value_difference(expected, got, values: dict[str, tuple[int, int, bool]]):
    """None if every time value word of `got` is acceptable, else (scan, column,
    awlsim's word, ours).  `values`: column -> (timer n, its time base in ms, BCD:
    `LC T n` rather than `L T n`); `expected` has awlsim's remaining seconds of
    timer n after each scan as "@R n" and at its latch as "@R n<" (a read before
    the timer's instruction in the scan sees that).  A time value changes with the time base,
    not at transitions (spec §9's "the same transitions, each within one scan"
    does not fit it): a word is acceptable if it equals awlsim's at that scan or a
    neighbouring one, or if it lies between what awlsim's own conversions
    (timers.py: getTimevalBin, _seconds_to_s5t_tb*) give for awlsim's remaining
    time there minus and plus 1 ms (S7's timers run on the scan's latch time, in
    whole ms here — LATCH_MS — and in s in awlsim)."""
    from awlsim.core import timers as awl

    s5t = {10: awl._seconds_to_s5t_tb10ms, 100: awl._seconds_to_s5t_tb100ms,
           1000: awl._seconds_to_s5t_tb1s, 10_000: awl._seconds_to_s5t_tb10s}

    def convert(seconds: float, tb: int, bcd: bool) -> int:
        seconds = max(0.0, seconds)
        return s5t[tb](seconds) if bcd else int(round(seconds / (tb / 1000)))

    def units(word: int, bcd: bool) -> tuple[int, int]:
        if not bcd:
            return 0, word
        found = bcd_units(word)
        return found if found is not None else (-1, -1)

    for column, (n, tb, bcd) in values.items():
        for k, row in enumerate(got):
            near = [j for j in (k - 1, k, k + 1) if 0 <= j < len(expected)]
            if row[column] in {expected[j][column] for j in near}:
                continue
            base, ours = units(row[column], bcd)
            left = [expected[j][key] for j in near for key in (f"@R{n}", f"@R{n}<")]
            if not any(base == units(convert(r - 0.001, tb, bcd), bcd)[0] and
                       units(convert(r - 0.001, tb, bcd), bcd)[1] <= ours <=
                       units(convert(r + 0.001, tb, bcd), bcd)[1] for r in left):
                return k, column, expected[k][column], row[column]
    return None


def assert_equal_and_varied(expected, got, columns) -> None:
    """`got` equals `expected` scan for scan, and each of `columns` takes both values
    in `expected` (so that the comparison can see a wrong translation of it)."""
    assert first_difference(expected, got) is None, first_difference(expected, got)
    for column in columns:
        assert {row[column] for row in expected} == {0, 1}, column
