"""The block status (`bitbyte run --status K`, issue 17 item 2): per program line of
scan K the RLO after it, the operand bit it read, the accumulators after word
instructions, "not executed" — read from the simulated system (the bit processor's
retirement port, the firmware's accumulators) on both simulators, and compared here
with the reference interpreter's own values, recorded instruction by instruction."""
from __future__ import annotations

from pathlib import Path

import pytest

from bitbyte.lang.program import COMBINES
from bitbyte.ref.refsim import RefSim
from bitbyte.run.prepare import prepare
from test_cli import bitbyte

ROOT = Path(__file__).resolve().parents[1]
EX = ROOT / "examples"


def parse_status(stdout: str, table: int = 0) -> dict[int, dict]:
    """A block status table (parallel mode: 0 the bit part, 1 the byte part): row
    index (program order) -> its fields."""
    lines = stdout.splitlines()
    heads = [i for i, l in enumerate(lines) if l.startswith(" line  instruction")]
    rows = {}
    for i, line in enumerate(lines[heads[table] + 1:]):
        if not line[:5].strip().isdigit():
            break
        rest = line[42:]
        if rest.startswith("(the byte part's end)"):
            rows[i] = {"line": int(line[:5]), "executed": None}
            continue
        if rest.startswith("not executed"):
            rows[i] = {"line": int(line[:5]), "executed": False}
            continue
        count = int(rest.split("(")[1].split()[0]) if "times)" in rest else 1
        field = lambda a, b: rest[a:b].strip() or None   # noqa: E731
        rows[i] = {"line": int(line[:5]), "executed": True, "rlo": int(rest[0:3]),
                   "sta": field(4, 7), "accu1": field(8, 15), "accu2": field(16, 23),
                   "count": count}
    return rows


class _Recorder(RefSim):
    """The reference interpreter, noting in scan `status_scan` per address the RLO
    after each instruction, the operand bit it read and the accumulators after it."""

    def __init__(self, *args, status_scan: int, **kwargs):
        super().__init__(*args, **kwargs)
        self.status_scan, self.seen, self.last_read = status_scan, {}, None

    def _read(self, op, clock):
        self.last_read = super()._read(op, clock)
        return self.last_read

    def _step(self, ins, pc, clock):
        self.last_read = None
        result = super()._step(ins, pc, clock)
        if self.scan == self.status_scan:
            count = self.seen.get(pc, {}).get("count", 0) + 1
            self.seen[pc] = {"rlo": self.rlo, "sta": self.last_read, "count": count,
                             "accu": (self.accu1, self.accu2)}
        return result


def reference(program: Path, stimulus: Path | None, clock_mhz: str, scan: int) -> dict:
    prep = prepare(str(program), stimulus=str(stimulus) if stimulus else None,
                   clock_mhz=clock_mhz, scans=scan + 1)
    ref = _Recorder(prep.program, prep.config, prep.stimulus, prep.job.watchdog,
                    status_scan=scan)
    ref.run(scans=scan + 1)
    return ref.seen


def mismatches(got: dict[int, dict], want: dict[int, dict], program) -> list[str]:
    """Where the block status differs from the reference (END: executed, RLO 0)."""
    out = []
    for pc, ins in enumerate(program.instrs):
        row = got[pc]
        if ins.mnemonic == "END":
            if not (row["executed"] and row["rlo"] == 0):
                out.append(f"END: {row}")
            continue
        ref = want.get(pc)
        if ref is None:
            if row["executed"]:
                out.append(f"line {ins.line}: executed, the reference skipped it")
            continue
        if not row["executed"]:
            out.append(f"line {ins.line}: not executed, the reference ran it")
            continue
        if row["rlo"] != ref["rlo"] or row["count"] != ref["count"]:
            out.append(f"line {ins.line}: RLO {row['rlo']} x{row['count']}, "
                       f"reference {ref['rlo']} x{ref['count']}")
        if ins.mnemonic in COMBINES and ins.operand.kind in ("bit", "index") \
                and row["sta"] != str(ref["sta"]):
            out.append(f"line {ins.line}: STA {row['sta']}, reference {ref['sta']}")
        if row["accu1"] is not None and (int(row["accu1"]), int(row["accu2"])) != ref["accu"]:
            out.append(f"line {ins.line}: ACCU {row['accu1']}/{row['accu2']}, "
                       f"reference {ref['accu']}")
    return out


CASES = [  # program, stimulus, clock MHz, scans run, the scan shown
    ("fig5.il", "fig5.stim.csv", "100", 5, 3),
    ("fig5.il", "fig5.stim.csv", "100", 5, 0),
    ("star_delta.il", "star_delta.stim.csv", "1", 60, 10),   # Start latched, timer runs
    ("star_delta.il", "star_delta.stim.csv", "1", 60, 55),
]


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
@pytest.mark.parametrize("name,stim,mhz,scans,k", CASES)
def test_block_status_equals_the_reference(sim, name, stim, mhz, scans, k):
    proc = bitbyte("run", EX / name, "--stimulus", EX / stim, "--clock-mhz", mhz,
                   "--scans", scans, "--status", k, "--sim", sim)
    assert proc.returncode == 0, proc.stderr
    got = parse_status(proc.stdout)
    program = prepare(str(EX / name)).program
    assert len(got) == len(program.instrs)
    assert mismatches(got, reference(EX / name, EX / stim, mhz, k), program) == []


LOOP = """\
        CLR
        = M0.0          // first pass
again:  LD I0.0
        = Q0.0
        LD M0.0
        JC done         // the second pass leaves
        SET
        = M0.0
        JU again
        L 7             // never: jumped over
done:   L 5
        L 6
        END
"""


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
def test_a_loop_shows_its_last_pass_and_count(tmp_path, sim):
    """Hand-worked: lines 3..6 run twice (the last pass with M0.0 = 1), 7..9 once,
    line 10 never; ACCU1/ACCU2 after `L 5` / `L 6` are 5/0 and 6/5."""
    src = tmp_path / "loop.il"
    src.write_text(LOOP)
    stim = tmp_path / "s.csv"
    stim.write_text("scan,I0.0\n0,1\n")
    proc = bitbyte("run", src, "--stimulus", stim, "--scans", 2, "--status", 1, "--sim", sim)
    assert proc.returncode == 0, proc.stderr
    rows = parse_status(proc.stdout)
    by_line = {r["line"]: r for r in rows.values()}
    assert {l: by_line[l]["count"] for l in (3, 4, 5, 6)} == {3: 2, 4: 2, 5: 2, 6: 2}
    assert [by_line[l]["rlo"] for l in (3, 4, 5, 6)] == [1, 1, 1, 1]
    assert by_line[5]["sta"] == "1"                   # M0.0 in the last pass
    assert {l: by_line[l]["count"] for l in (1, 2, 7, 8, 9)} == dict.fromkeys((1, 2, 7, 8, 9), 1)
    assert not by_line[10]["executed"]
    assert (by_line[11]["accu1"], by_line[11]["accu2"]) == ("5", "0")
    assert (by_line[12]["accu1"], by_line[12]["accu2"]) == ("6", "5")
    program = prepare(str(src)).program
    assert mismatches(rows, reference(src, stim, "100", 1), program) == []


def test_the_comparison_sees_a_wrong_value():
    """mismatches() fails on a flipped RLO, a wrong operand, a wrong count, a skipped
    line and wrong accumulators: the check above can fail."""
    program = prepare(str(EX / "fig5.il")).program
    want = reference(EX / "fig5.il", EX / "fig5.stim.csv", "100", 3)
    proc = bitbyte("run", EX / "fig5.il", "--stimulus", EX / "fig5.stim.csv",
                   "--scans", 4, "--status", 3)
    got = parse_status(proc.stdout)
    assert mismatches(got, want, program) == []
    first = 0                                             # LD Start
    accu = next(pc for pc, r in got.items() if r.get("accu1") is not None)
    for pc, change in [(first, {"rlo": 1 - got[first]["rlo"]}),
                       (first, {"sta": "1" if got[first]["sta"] == "0" else "0"}),
                       (first, {"count": 2}), (first, {"executed": False}),
                       (accu, {"accu1": str(int(got[accu]["accu1"]) + 1)})]:
        broken = {**got, pc: {**got[pc], **change}}
        assert mismatches(broken, want, program), change


def test_status_usage_errors():
    proc = bitbyte("run", EX / "fig5.il", "--scans", 3, "--status", 3)
    assert proc.returncode == 2 and "--status 3: not a scan of this run" in proc.stderr
    proc = bitbyte("run", EX / "fig5.il", "--mode", "free", "--scans", 3, "--status", 1)
    assert proc.returncode == 2 and "serial and parallel mode" in proc.stderr


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
def test_the_scan_the_watchdog_stopped(tmp_path, sim):
    """--status on the scan the watchdog ends: what ran up to then (the loop, the lines
    after it not reached), the summary and exit status of a fault."""
    src, stim = tmp_path / "loop.il", tmp_path / "s.csv"
    src.write_text("again:  LD    I0.1\n        JC    again\n        LD    I0.0\n"
                   "        =     Q0.0\n")
    stim.write_text("scan,I0.1\n0,0\n2,1\n")
    proc = bitbyte("run", src, "--stimulus", stim, "--scans", 5, "--status", 2,
                   "--watchdog", 200, "--sim", sim)
    assert proc.returncode == 3, proc.stderr
    assert "scan watchdog: scan 2 exceeded 200 clocks" in proc.stderr
    assert "watchdog         limit 200 clocks: exceeded in scan 2" in proc.stdout
    assert "ended by the scan watchdog" in proc.stdout
    rows = {r["line"]: r for r in parse_status(proc.stdout).values()}
    assert rows[1]["executed"] and rows[1]["count"] >= 40 and rows[1]["rlo"] == 1
    assert not rows[3]["executed"] and not rows[4]["executed"]


PARALLEL_CASES = [("fig5.il", "fig5.stim.csv", "100", 5, 3),
                  ("star_delta.il", "star_delta.stim.csv", "1", 60, 12)]


@pytest.mark.parametrize("sim", ["verilator", "icarus"])
@pytest.mark.parametrize("name,stim,mhz,scans,k", PARALLEL_CASES)
def test_parallel_block_status_against_the_serial_reference(sim, name, stim, mhz, scans, k):
    """Parallel mode: the bit part's F_b after each of its lines equals the serial
    RLO after the same line (the partition keeps each rung's logic), the byte part's
    accumulators after each word instruction the serial ACCUs after it (program order
    is kept); the compiler's transfers have no serial twin and are not compared."""
    proc = bitbyte("run", EX / name, "--stimulus", EX / stim, "--clock-mhz", mhz,
                   "--scans", scans, "--status", k, "--sim", sim, "--mode", "parallel")
    assert proc.returncode == 0, proc.stderr
    bit, byte = parse_status(proc.stdout, 0), parse_status(proc.stdout, 1)
    prep = prepare(str(EX / name), stimulus=str(EX / stim), clock_mhz=mhz, scans=scans,
                   mode="parallel")
    serial = prepare(str(EX / name)).program
    ref = reference(EX / name, EX / stim, mhz, k)
    twin = {(ins.line, ins.mnemonic): ref.get(pc) for pc, ins in enumerate(serial.instrs)}
    compared = 0
    for rows, listing, what in ((bit, prep.listing, "rlo"), (byte, prep.byte_listing, "accu")):
        assert len(rows) == len(listing)
        for pc, ins in enumerate(listing):
            want = twin.get((ins.line, ins.mnemonic), "none")
            op = ins.operand
            if want == "none" or (op is not None and op.area in ("FBI", "FBY")) or \
                    ins.mnemonic in ("END", "END_B"):     # the reference does not step END
                continue
            row = rows[pc]
            assert row["executed"] == (want is not None), (what, ins.line, ins.mnemonic)
            if want is None:
                continue
            if what == "rlo":
                assert row["rlo"] == want["rlo"], (ins.line, ins.mnemonic, row, want)
            else:
                assert (int(row["accu1"]), int(row["accu2"])) == want["accu"], (ins.line, row)
            compared += 1
    assert compared >= 10
