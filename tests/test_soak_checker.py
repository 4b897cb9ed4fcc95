"""The soak (soak/, `make soak`) can fail: its comparisons catch a broken reference in
serial and in parallel mode and save the case, its timer transformation does what it
says, and its report fails on a mismatch, a missing chunk or a missed coverage bin.
A few programs through the real comparisons here; the N-program run is `make soak`."""
from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

SOAK = Path(__file__).resolve().parents[1] / "soak"
sys.path.insert(0, str(SOAK))

import coverage_count  # noqa: E402
import soak_report as report  # noqa: E402
import test_soak as soak  # noqa: E402
from randprog import long_timers  # noqa: E402


def test_long_timers_by_hand():
    src = "  LD I0.0\n  L T#5ms\nx: SD T3\n  L T3\n  T MW0\n  R T3\n  SF T9\n  L T 9\n"
    assert long_timers(src).split("\n")[:-1] == [
        "  LD I0.0", "  L T#5ms", "x:", "  L T#9000s", "  SD T3", "  L T8", "  T MW0",
        "  R T3", "  L T#9000s", "  SF T9", "  L T8"]


def test_the_programs_agree_and_are_counted(tmp_path, monkeypatch):
    monkeypatch.setattr(soak, "OUT", tmp_path / "out")
    monkeypatch.setattr(soak, "SEED", 1)      # fixed: the counts below must not be luck
    cov = coverage_count.Coverage()
    for index in range(4):
        family = soak.FAMILIES[index]
        assert soak.serial_check(tmp_path, index, family, cov) is None
        assert soak.parallel_check(tmp_path, index, family, cov) == []
        assert soak.free_check(tmp_path, index, family, cov) == []
    modes = {(mo, ex) for (_, _, mo, ex) in cov.counts}
    assert modes == set(coverage_count.MODES)
    assert set(cov.counts) <= coverage_count.legal_bins()
    # the byte part counts in every mode that has one (the word loads run there)
    for mode in coverage_count.MODES[1:]:
        assert any(m == "L" and (mo, ex) == mode for m, _, mo, ex in cov.counts), mode


@pytest.mark.parametrize("broken", ["none", "one retirement lost per address"])
def test_the_hardware_counts_what_the_reference_executes(tmp_path, monkeypatch, broken):
    """The coverage is the hardware's (the harness's line counts through the listing
    back to the source), and it equals what the reference interpreter executed, bin by
    bin, parentheses' depths included: serially, and in parallel mode (where the
    partitioning compiler splits and mirrors instructions over the two parts) in runs
    the watchdog did not end (in one it did, the modes' different timing ends the scan
    at different points).  With one retirement per address lost from the harness's
    counts, they differ."""
    monkeypatch.setattr(soak, "OUT", tmp_path / "out")
    monkeypatch.setattr(soak, "SEED", 4)    # program 3's parallel run hits the watchdog
    if broken != "none":
        good = soak.read_line_counts

        def lose_one(path):
            return {part: {pc: n - 1 for pc, n in counts.items()}
                    for part, counts in good(path).items()}
        monkeypatch.setattr(soak, "read_line_counts", lose_one)
    compared, differ, faulted = [], [], []
    for index in range(8):
        for parallel in (False, True):
            hw, ref = coverage_count.Coverage(), coverage_count.Coverage()
            family = soak.FAMILIES[index % len(soak.FAMILIES)]
            case = soak.Case(tmp_path, index, family, hw, parallel, ref)
            assert case.on_harness(tmp_path) == []
            assert hw.counts, "nothing counted"
            if parallel and case.expected.endswith("fault=True\n"):
                faulted.append(index)
                continue
            compared.append((index, parallel))
            differ += [(index, parallel)] if hw.counts != ref.counts else []
    assert faulted, "no parallel run ended by the watchdog: the exception is untested"
    assert differ == ([] if broken == "none" else compared)


def test_a_jump_inside_parentheses_is_refused(tmp_path):
    """The coverage's parenthesis depth is static: a program that jumps out of (or
    into) parentheses is refused, file:line:col."""
    from bitbyte.lang.parser import parse_file
    il = tmp_path / "j.il"
    il.write_text("top: LD I0.0\n  A(\n  LD I0.1\n  JC top\n  )\n  = Q0.0\n")
    with pytest.raises(ValueError, match=r"j.il:4:3: a jump or a label inside parentheses"):
        coverage_count.source_keys(parse_file(str(il)))


def test_a_broken_reference_is_caught_and_saved(tmp_path, monkeypatch):
    """XOR computed as OR in the reference: the hardware's traces now differ, in
    serial and in parallel mode, and each case is saved with what repeats it."""
    import bitbyte.ref.refsim as refsim
    good = refsim.combine
    monkeypatch.setattr(refsim, "combine",
                        lambda func, rlo, x: good("O" if func == "X" else func, rlo, x))
    monkeypatch.setattr(soak, "OUT", tmp_path / "out")
    monkeypatch.setattr(soak, "SEED", 1)      # fixed programs: this one must not be luck
    cov = coverage_count.Coverage()
    serial, parallel = [], []
    for index in range(8):
        family = soak.FAMILIES[index % len(soak.FAMILIES)]
        problem = soak.serial_check(tmp_path, index, family, cov)
        serial += [problem] if problem else []
        parallel += soak.parallel_check(tmp_path, index, family, cov)
    assert serial and parallel, (serial, parallel)
    saved = sorted((tmp_path / "out" / "cases").iterdir())
    assert len(saved) == len(serial) + len(parallel)
    for case in saved:
        assert {p.name for p in case.iterdir()} == {
            "program.il", "stimulus.csv", "expected.txt", "got.txt", "repeat.sh"}
        assert (case / "expected.txt").read_text() != (case / "got.txt").read_text()


def _chunk(build: Path, n: int, mismatches=(), coverage=None):
    build.mkdir(parents=True, exist_ok=True)
    if coverage is None:
        coverage = [list(b) + [1] for b in sorted(coverage_count.legal_bins())]
    (build / f"chunk{n:05d}.json").write_text(json.dumps({
        "seed": 1, "chunk": n, "programs": 25, "mismatches": list(mismatches),
        "seconds": 1.0, "coverage": coverage}))


def _wide_chunk(build: Path, n: int, mismatches=()):
    (build / f"wide_chunk{n:05d}.json").write_text(json.dumps({
        "seed": 1, "chunk": n, "programs": 25, "mismatches": list(mismatches),
        "seconds": 1.0, "units": 10, "lut_words": 12, "unit_il": 40, "fallbacks": 0,
        "pi_units": 2, "jump_programs": 5}))


@pytest.mark.parametrize("broken", ["none", "mismatch", "bin missed", "chunk missing",
                                    "plant bin missed", "plant bin not legal",
                                    "wide mismatch", "wide chunk missing"])
def test_report_fails_on_what_it_must(tmp_path, broken, capsys):
    build = tmp_path / "b"
    bins = [list(b) + [1] for b in sorted(coverage_count.legal_bins())]
    bins = bins[1:] if broken == "bin missed" else bins
    _chunk(build, 0, ["p: differs"] if broken == "mismatch" else (), bins)
    _chunk(build, 1, (), bins)
    _wide_chunk(build, 0, ["program 3: Q0.0 scan 1"] if broken == "wide mismatch" else ())
    if broken != "wide chunk missing":
        _wide_chunk(build, 1)
    plant = [list(b) + [3] for b in sorted(coverage_count.plant_legal_bins())]
    (build / "plant_a.json").write_text(json.dumps({"plant_coverage": plant[:5]}))
    (build / "plant_b.json").write_text(json.dumps(
        {"plant_coverage": plant[6:] if broken == "plant bin missed" else plant[5:]}))
    if broken == "plant bin not legal":
        (build / "plant_c.json").write_text(json.dumps(
            {"plant_coverage": [["none", "compact", "copy_fail", 1]]}))
    n = 75 if broken == "chunk missing" else 50
    out = tmp_path / "soak.md"
    rc = report.main(["--build", str(build), "--out", str(out), "--n", str(n),
                      "--seconds", "60"])
    assert rc == (0 if broken == "none" else 1)
    text = out.read_text()
    assert ("Legal bins: 16; **missed: 0**." in text) == (broken != "plant bin missed")
    assert ("Counted but not legal (a defect in the bins or the plant): "
            "none/compact/copy_fail" in text) == (broken == "plant bin not legal")
    assert ("hit: {0}; **missed: 0**.".format(len(coverage_count.legal_bins()))
            in text) == (broken != "bin missed")
    assert ("**Mismatches: 1.**" in text) == (broken in ("mismatch", "wide mismatch"))
    wide = 25 if broken == "wide chunk missing" else 50
    assert f"{wide} random programs (bit-only" in text
    assert (f"{wide // 25 * 10} units ({wide // 25 * 40} IL instructions in "
            f"{wide // 25 * 12} LUT words; {wide // 25 * 2} reading PI pins), 0 fallen "
            f"back to scalar, {wide // 25 * 5} programs with jumps") in text
    assert ("- program 3: Q0.0 scan 1" in text) == (broken == "wide mismatch")


def test_plant_contention_by_hand():
    """A reader scan's precycle against another core's postcycles, in clocks at
    100 MHz: t_us ends the postcycle, which follows the scan, which follows the
    precycle (soak/coverage_count.py)."""
    def row(end_clock, pre, cycles, post, fail="0"):
        return {"t_us": f"{end_clock / 100}", "pre": str(pre), "cycles": str(cycles),
                "post": str(post), "copy_fail": fail}
    writer = [row(100, 5, 10, 20)]                  # postcycle: clocks 80..99
    reader = [row(60, 10, 5, 5),                    # precycle 40..49: apart
              row(120, 30, 5, 5),                   # precycle 80..109: overlap
              row(200, 5, 5, 5, "1"),               # the first copy_fail
              row(300, 5, 5, 5, "1"),               # sticky: no new event
              row(105, 5, 5, 5)]                    # precycle 90..94: inside it
    assert coverage_count.plant_contention(reader, [writer]) == [
        "apart", "overlap", "copy_fail", "apart", "overlap"]
    # a precycle that ends where the postcycle begins does not share a clock with it
    assert coverage_count.plant_contention([row(90, 10, 5, 5)], [writer]) == ["apart"]
    assert coverage_count.plant_contention([row(91, 10, 5, 5)], [writer]) == ["overlap"]
