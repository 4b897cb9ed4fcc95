"""The wide bit engine's soak (`make soak`, issue 18): N random programs compiled for
the wide engine (bitbyte/wide: units of straight-line bit code as LUT words, each
unit checked exhaustively when compiled) and relinked into the wide image
(bitbyte/wide/link.py), the image run word by word (bitbyte/wide/iss.py) and on the
wide RTL (`make harness-wide`, tests/test_wide_rtl.py): the compiler, the linker, the
model and the RTL at scale.

Per program (serial mode, as spec §4 `--bit-engine` says):

* scan-keyed stimulus (inputs and IW words): the image's trace against the scalar
  reference interpreter in every column but `t_us` and `cycles`, and against the wide
  model (bitbyte/wide/model.py, which runs the compiled units from the source program)
  in every column, `cycles` included;
* pins changing in every clock (`t_us`) for as long as the scan-keyed run took: the
  image against the wide model in every column, `cycles` included (the unit's pin
  sample clock, docs/wide-rtl-plan.md §2.3);
* the wide RTL (the Verilator harness of `BitEngine=1`) under both stimuli against the
  image interpreter: every column, `cycles` included.

Program i has the seed BITBYTE_SEED * 100000 + i and comes from tests/randprog.py by
i % 3: bit-only (jumps, REFRESH, parentheses, edges, PI/PQ), mixed with its timers
stripped (words, compares, counters: the model's timers run, but spec §4 promises
trace equality only without them), and bit-only with `label: NOP` lines put in.
These are the wide soak's own families, not the main soak's programs. Chunks of CHUNK
programs, each compiled in one Yosys run; a mismatch or any error of a program is saved
under build/soak/wide-cases/wide<i>/ (program, stimuli, the image as linked in its
chunk, the differences, repeat.sh) and the chunk goes on before it fails; a chunk that
ran no LUT word, or fell back to scalar for more than one unit in twenty, fails too.
Each chunk writes its counts to build/soak/wide_chunk*.json; soak/soak_report.py adds
them up.
"""
from __future__ import annotations

import json
import os
import random
import time
import traceback
from pathlib import Path

import pytest

from bitbyte.lang.parser import parse
from bitbyte.lang.program import JUMPS
from bitbyte.lang.stimulus import parse_stimulus
from bitbyte.ref.refsim import refsim_trace
from bitbyte.wide import iss, link, model
from randprog import (FULL_WATCH, random_mixed_program, random_program, random_scan_stimulus,
                      strip_timers)
from test_wide_image import dense_stimulus, differences
from test_wide_model import with_label_nops
from test_wide_rtl import _image_rows, _prepared, _run_image

ROOT = Path(__file__).resolve().parents[1]
OUT = Path(os.environ.get("BITBYTE_SOAK_OUT", ROOT / "build" / "soak"))
CASES = OUT / "wide-cases"
N = int(os.environ.get("BITBYTE_SOAK_N", "100"))
SEED = int(os.environ["BITBYTE_SEED"])
CHUNK = 200
SCANS = 8


def program_text(index: int) -> str:
    seed = SEED * 100000 + index
    kind = index % 3
    if kind == 1:
        return strip_timers(random_mixed_program(seed))
    text = random_program(seed)
    return with_label_nops(text, random.Random(seed)) if kind == 2 else text


def scalar_differences(program, image, stimulus) -> tuple[list[str], int]:
    """The image against the scalar interpreter: every trace column (the records'
    values; t_us and cycles are not among them). Also the scalar run's last clock."""
    cols, want, want_fault = refsim_trace(program, stimulus=stimulus, watch=FULL_WATCH,
                                          scans=SCANS)
    _, got, got_fault, _ = iss.image_trace(image, stimulus=stimulus, watch=FULL_WATCH,
                                           scans=SCANS)
    out = [] if (want_fault, len(want)) == (got_fault, len(got)) else \
        [f"fault/scans: image {got_fault}/{len(got)}, scalar {want_fault}/{len(want)}"]
    for w, g in zip(want, got):
        out += [f"{c.header} scan {w.scan}: image {g.values[c.header]}, scalar "
                f"{w.values[c.header]}" for c in cols
                if w.values[c.header] != g.values[c.header]]
    return out, max((r.end_clock for r in want), default=0)


def rtl_differences(text: str, image, stimulus_text: str, tmp: Path) -> list[str]:
    """The image on the wide RTL against the image interpreter: every column and
    `cycles` of every scan (tests/test_wide_rtl.py's runs of both)."""
    prep = _prepared(tmp, "p", text, stimulus_text, FULL_WATCH, SCANS)
    (got, got_fault), (want, sim) = _run_image(prep, image), _image_rows(prep, image, SCANS)
    out = [] if (sim.watchdog_fault, len(want)) == (got_fault, len(got)) else \
        [f"fault/scans: RTL {got_fault}/{len(got)}, image {sim.watchdog_fault}/{len(want)}"]
    for (scan, w_cycles, w), (_, g_cycles, g) in zip(want, got):
        if w_cycles != g_cycles:
            out.append(f"cycles scan {scan}: RTL {g_cycles}, image {w_cycles}")
        out += [f"{c.header} scan {scan}: RTL {gv}, image {wv}"
                for c, wv, gv in zip(prep.columns, w, g) if wv != gv]
    return out


def save(index: int, chunk: int, text: str, problems: list[str], image,
         stimuli: dict[str, str]) -> None:
    """The case: program, stimuli, the image as linked in its chunk (Yosys maps a
    chunk's units in one run, so the program compiled alone may map differently), what
    differed, and how to repeat the chunk."""
    case = CASES / f"wide{index}"
    case.mkdir(parents=True, exist_ok=True)
    (case / "program.il").write_text(text)
    for name, st in stimuli.items():
        (case / f"{name}.csv").write_text(st)
    if image is not None:
        (case / "image.hex").write_text("".join(f"{w:08X}\n" for w in image.base))
        (case / "image.ext.hex").write_text(link.hex_ext(image.ext))
        (case / "image.json").write_text(json.dumps(link.summary(image), indent=1))
    (case / "problems.txt").write_text("\n".join(problems[:40]) + "\n")
    (case / "repeat.sh").write_text(
        f"BITBYTE_SEED={SEED} BITBYTE_SOAK_N={N} pytest -p no:cacheprovider "
        f"'soak/test_wide_soak.py::test_wide_soak_chunk[{chunk}]'\n")


@pytest.mark.parametrize("chunk", range((N + CHUNK - 1) // CHUNK))
def test_wide_soak_chunk(chunk, tmp_path):
    t0 = time.monotonic()
    indexes = range(chunk * CHUNK, min(N, (chunk + 1) * CHUNK))
    texts = {i: program_text(i) for i in indexes}
    progs = {i: parse(f"wide{i}.il", t) for i, t in texts.items()}
    compiled = dict(zip(indexes, model.compile_programs([progs[i] for i in indexes])))
    mismatches, counts = [], {"units": 0, "lut_words": 0, "unit_il": 0, "fallbacks": 0,
                              "pi_units": 0, "jump_programs": 0, "rtl_runs": 0}
    for i in indexes:
        p, c = progs[i], compiled[i]
        problems: list[str] = []
        image, stimuli = None, {}
        try:
            image = link.link(p, c)
            stimuli["scan"] = random_scan_stimulus(SEED * 100000 + i, SCANS)
            scan = parse_stimulus(stimuli["scan"])
            diffs, last = scalar_differences(p, image, scan)
            problems += diffs
            problems += [f"model: {d}" for d in differences(p, c, image, scan, FULL_WATCH)]
            # pins changing in every clock of the run (its scans as long as the
            # scan-keyed run's, and a margin)
            stimuli["dense"] = dense_stimulus(SEED * 100000 + i, last + 200)
            problems += [f"t_us model: {d}" for d in differences(
                p, c, image, parse_stimulus(stimuli["dense"]), FULL_WATCH)]
            for kind in ("scan", "dense"):     # the RTL, both stimuli
                problems += [f"{kind} RTL: {d}" for d in
                             rtl_differences(texts[i], image, stimuli[kind], tmp_path)]
                counts["rtl_runs"] += 1
        except Exception as exc:       # any error is this program's case, not the chunk's
            problems.append(f"{type(exc).__name__}: {exc}\n{traceback.format_exc()}")
        if problems:
            mismatches.append(f"program {i} (wide-cases/wide{i}/): {problems[0].splitlines()[0]}")
            save(i, chunk, texts[i], problems, image, stimuli)
        live = [(u, g) for u, g in zip(c.split.units, c.programs) if g]   # in the image
        counts["units"] += len(live)
        counts["lut_words"] += sum(len(g) for _, g in live)
        counts["unit_il"] += sum(u.size for u, _ in live)
        counts["fallbacks"] += c.fallbacks
        counts["pi_units"] += sum(any(x.startswith("PI") for x in u.inputs) for u, _ in live)
        counts["jump_programs"] += any(ins.mnemonic in JUMPS for ins in p.instrs)
    # a compiler that falls back everywhere would pass the comparisons: the chunk must
    # have run LUT code, and fallen back rarely (none in the runs so far)
    if counts["lut_words"] == 0 or counts["fallbacks"] * 20 > counts["units"]:
        mismatches.append(f"chunk {chunk}: {counts['units']} units in {counts['lut_words']} "
                          f"LUT words, {counts['fallbacks']} fallen back to scalar")
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"wide_chunk{chunk:05d}.json").write_text(json.dumps({
        "seed": SEED, "chunk": chunk, "programs": len(indexes), "mismatches": mismatches,
        "seconds": round(time.monotonic() - t0, 1), **counts}))
    assert not mismatches, "\n".join(mismatches)
