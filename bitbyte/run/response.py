"""Response time: from an input change to the PIO update that shows it (spec §4's
"response-time figures where inputs changed"; the definition is docs/toolchain.md's).

A scan's outputs reach the pins in its END clock (a `= PQ` write or a `REFRESH Q`
moves them earlier; measured here at the scan end all the same, an upper bound), so an
output change shows at the scan's end, end_clock (= the next scan's latch clock; t_us = end_clock / f).  The
response to an input change at clock c (exact: a t_us row may fall between two clock
edges) is end_clock - c of the first scan that ends after c and shows it
(`responding_scan`).  What "shows it" means is causal for the run summary
(`response_times`): the scan's outputs differ from those of the reference interpreter
run with that change withheld, so a change is never credited with an output another
change caused, however the responses overlap.  `make bench` (bench/benchlib.py) finds
its responses with the same `responding_scan`, "shows" being its rung's output taking
the edge's level (its edges are more than two scans apart, one rung per output).
"""
from __future__ import annotations

import bisect
import copy
from dataclasses import dataclass
from fractions import Fraction
from typing import Callable

from bitbyte.lang.stimulus import Row, Stimulus
from bitbyte.lang.trace import ScanRecord
from bitbyte.ref.parsim import state_snapshot
from bitbyte.ref.refsim import RefSim, RefSimError

# The reference replays the run in Python, much slower than the harness: it stops
# measuring after this many clocks simulated (the run's and the counterfactuals'
# together: a few seconds) or this many changes, and the summary says so.
REPLAY_CLOCKS = 2_000_000
MAX_CHANGES = 1000


def responding_scan(change: Fraction, ends: list[int],
                    shows: Callable[[int], bool | None]) -> int | None:
    """The first scan k that ends after the input change at clock `change` and for
    which shows(k) holds; None when there is none, or when shows(k) returns None (it
    cannot hold from k on).  ends: the scans' end_clocks, ascending.  A scan ending at
    `change` itself updated its outputs in the clock before: it cannot show it."""
    k = bisect.bisect_right(ends, change)
    while k < len(ends):
        hit = shows(k)
        if hit is None:
            return None
        if hit:
            return k
        k += 1
    return None


def change_clocks(changes: list[tuple[str, int | Fraction]],
                  records: list[ScanRecord]) -> list[Fraction]:
    """The stimulus's input changes (Stimulus.changes) as clocks: a scan row at its
    scan's latch (the previous scan's end_clock, 0 for scan 0), a t_us row at its
    exact moment.  Only changes a completed scan latched at or after: the run stopped
    before the others could show."""
    if not records:
        return []
    latches = [0] + [r.end_clock for r in records[:-1]]
    out = []
    for kind, key in changes:
        if kind == "scan":
            if key < len(records):
                out.append(Fraction(latches[key]))
        elif key <= latches[-1]:
            out.append(Fraction(key))
    return out


@dataclass(frozen=True)
class Responses:
    """What the summary prints: the responses found (clocks) and the input changes
    counted; measured: how many of them, the first ones, were measured (None: all),
    with `stopped` saying why no more; not_measured: why none could be."""
    clocks: list[Fraction]
    changes: int
    measured: int | None = None
    stopped: str = ""
    not_measured: str | None = None


class _Meter:
    """Clocks the reference has replayed, the run's and the counterfactuals' together."""
    clocks = 0


class _OnHardwareLatches(RefSim):
    """The reference interpreter with each scan latching in the clock the hardware's
    scan did (the same clocks in serial mode; in parallel mode the latches then see
    the pins the hardware latched, which the serial timing would not)."""

    def __init__(self, *args, latches: list[int], meter: _Meter, **kwargs):
        super().__init__(*args, **kwargs)
        self.latches, self.meter = latches, meter

    def _start_scan(self) -> int:
        if not self.in_startup:             # a startup scan (OB 100) starts at 0
            self.clock = self.latches[self.scan]
        return super()._start_scan()

    def run_scan(self) -> ScanRecord | None:
        rec = super().run_scan()
        self.meter.clocks += rec.cycles if rec else self.watchdog
        self.output_events.clear()               # not needed here: keep forks cheap
        return rec


def _fork(sim: RefSim, stimulus: Stimulus) -> RefSim:
    """A copy of sim that runs on by itself on `stimulus`: its lists and dicts copied,
    and the timer / counter records in them (the program, the settings and the meter
    are shared)."""
    twin = copy.copy(sim)
    for name, value in vars(sim).items():
        if isinstance(value, list):
            setattr(twin, name, [copy.copy(x) for x in value])
        elif isinstance(value, dict):
            setattr(twin, name, dict(value))
    twin.stimulus = stimulus
    return twin


def _outputs(sim: RefSim) -> tuple:
    """The output pins and words after END (the trace's Q, PQ, QW columns)."""
    return sim.outputs, tuple(sorted((n, v) for n, v in sim.qw.items() if v))


def _state(sim: RefSim) -> tuple:
    """All a scan leaves for the next: equal states on equal inputs, equal futures."""
    return state_snapshot(sim) + (sim.latched_pins, sim.last_latch)


def _withheld(stim: Stimulus, f: Fraction, changes: list, k: int, m: int | None
              ) -> Stimulus:
    """`stim` with change k withheld up to change m (None: the end): the pins and words
    change k changed keep the values they had before it, in every row that reaches the
    hardware from change k on and before change m, until a row changes them again (a
    row holds the whole input state, so a later row would bring change k back).  Scan
    rows reach it at their scan, t_us rows in the clock ceil(t_us * f); of the rows
    reaching it together, the last counts (Stimulus.changes)."""
    scale = 1 if stim.kind == "scan" else f
    lo, hi = _reach(changes[k][1]), (_reach(changes[m][1]) if m is not None else None)
    last: dict[int, Row] = {}
    for r in stim.rows:
        last[_reach(r.key * scale)] = r
    before = Row(0, 0, ())
    for at, r in last.items():
        if at < lo:
            before = r
    new = last[lo]
    held_pins = before.pins ^ new.pins               # the pins change k changed
    old_w, new_w = dict(before.words), dict(new.words)
    held_words = {n for n in old_w.keys() | new_w.keys() if old_w.get(n, 0) != new_w.get(n, 0)}
    rows = []
    for at, r in last.items():
        if lo <= at and (hi is None or at < hi) and (held_pins or held_words):
            held_pins &= ~(r.pins ^ new.pins)        # changed again: the row's value
            words = dict(r.words)
            held_words = {n for n in held_words if words.get(n, 0) == new_w.get(n, 0)}
            words.update((n, old_w.get(n, 0)) for n in held_words)
            r = Row(r.key, (r.pins & ~held_pins) | (before.pins & held_pins),
                    tuple(sorted(words.items())))
        rows.append(r)
    return Stimulus(stim.kind, rows, stim.clock_mhz)


def _reach(moment) -> int:
    """The clock (t_us rows) or scan a change at `moment` reaches the hardware in."""
    return -(-moment // 1)                           # ceil, exact for Fractions


class _Stop(Exception):
    """The measuring stops here (the message says why)."""


def response_times(prep, records: list[ScanRecord], replay_clocks: int = REPLAY_CLOCKS,
                   max_changes: int = MAX_CHANGES) -> Responses:
    """The run summary's response figures (prep: bitbyte.run.prepare's Prepared; records:
    the hardware's).  Each input change's response is responding_scan's, scan k showing
    it when the reference's outputs after scan k differ from those of the reference run
    with that change withheld, both on the hardware's latch clocks; its time is the
    hardware's end_clock of scan k minus the change.

    The counterfactual starts from the reference's state at the start of the first scan
    ending after the change (a direct read in it may see the change; an image cannot)
    and runs until it differs, until its state equals the reference's after a scan that
    latched at or after the next change (the same state on the same inputs: it never
    differs), or to the run's end.  Free-running mode: the byte side's scans are not the
    reference's, so nothing is measured."""
    clocks = change_clocks(prep.changes, records)
    if not clocks or prep.job.mode == "free":
        return Responses([], len(clocks), 0 if clocks else None, "",
                         "not measured in free-running mode" if clocks else None)
    ends = [r.end_clock for r in records]
    # scan 0 latches at 0, or after the startup scans (OB 100), which no record shows
    latches = [records[0].end_clock - records[0].cycles
               if prep.program.startup_scans else 0] + ends[:-1]
    starts = [bisect.bisect_right(ends, c) for c in clocks]    # a counterfactual's start
    # change k is withheld up to the first change after the first latch at or after it
    # (changes before that latch are taken in with it: withheld, it stays out of them)
    every = [Fraction(latches[key]) if kind == "scan" else Fraction(key)
             for kind, key in prep.changes if kind != "scan" or key < len(latches)]
    ends_at: list[int | None] = []            # None: withheld to the end
    for c in clocks:
        m = bisect.bisect_right(every, latches[bisect.bisect_left(latches, c)])
        ends_at.append(m if m < len(prep.changes) else None)
    wanted = set(starts[:max_changes])
    meter = _Meter()
    ref = _OnHardwareLatches(prep.program, prep.config, prep.stimulus, prep.job.watchdog,
                             None, prep.job.costs, latches=latches, meter=meter)
    outs: list[tuple] = []            # the reference's outputs and state after each scan
    states: list[tuple] = []
    snapshots: dict[int, RefSim] = {}

    def reference_upto(j: int) -> None:
        while len(outs) <= j:
            if len(outs) in wanted:
                snapshots[len(outs)] = _fork(ref, prep.stimulus)
            if ref.run_scan() is None:
                raise _Stop(f"the reference's scan {len(outs)} passed the watchdog")
            outs.append(_outputs(ref))
            states.append(_state(ref))

    got: list[Fraction] = []
    measured, stopped = 0, ""
    try:
        for k, c in enumerate(clocks[:max_changes]):
            m = ends_at[k]
            nxt = every[m] if m is not None and m < len(every) else None   # real inputs
            reference_upto(starts[k])
            base = snapshots[starts[k]]
            if k + 1 >= len(clocks) or starts[k + 1] != starts[k]:
                del snapshots[starts[k]]                     # no other change starts there
            cf = _fork(base, _withheld(prep.stimulus, prep.f, prep.changes, k, m))

            def shows(j: int, cf=cf, nxt=nxt) -> bool | None:
                if meter.clocks > replay_clocks:
                    raise _Stop(f"the reference replays at most {replay_clocks} clocks")
                reference_upto(j)
                if cf.run_scan() is None:      # without the change: a watchdog fault
                    return True
                if _outputs(cf) != outs[j]:
                    return True
                if nxt is not None and latches[j] >= nxt and _state(cf) == states[j]:
                    return None
                return False

            hit = responding_scan(c, ends, shows)
            measured += 1
            if hit is not None:
                got.append(ends[hit] - c)
    except _Stop as e:
        stopped = str(e)
    except RefSimError as e:
        stopped = f"the reference interpreter stopped: {e}"
    if measured == len(clocks):
        return Responses(got, len(clocks))
    if not measured:
        return Responses([], len(clocks), 0, "", f"not measured: {stopped}")
    return Responses(got, len(clocks), measured,
                     stopped or f"at most {max_changes} changes are measured")
