"""The wide bit engine's soak (`make soak`, issue 18): N random programs compiled for
the wide engine (bitbyte/wide: units of straight-line bit code as LUT words, each
unit checked exhaustively when compiled) and relinked into the wide image
(bitbyte/wide/link.py), the image run word by word (bitbyte/wide/iss.py). No RTL yet:
this is the compiler, the linker and the model at scale, before the wide RTL is
checked against them.

Per program (serial mode, as spec §4 `--bit-engine` says):

* scan-keyed stimulus: the image's trace against the scalar reference interpreter in
  every column but `t_us` and `cycles`, and against the wide model
  (bitbyte/wide/model.py, which runs the compiled units from the source program) in
  every column, `cycles` included;
* pins changing in every clock (`t_us`): the image against the wide model in every
  column, `cycles` included (the unit's pin sample clock, docs/wide-rtl-plan.md §2.3).

Program i has the seed BITBYTE_SEED * 100000 + i and comes from tests/randprog.py by
i % 3: bit-only (jumps, REFRESH, parentheses, edges, PI/PQ), mixed with its timers
stripped (words, compares, counters: the model's timers run, but spec §4 promises
trace equality only without them), and bit-only with `label: NOP` lines put in.
Chunks of CHUNK programs, each compiled in one Yosys run; a mismatch is saved under
build/soak/wide-cases/ and the chunk goes on before it fails. Each chunk writes its
counts to build/soak/wide_chunk*.json; soak/soak_report.py adds them up.
"""
from __future__ import annotations

import json
import os
import random
import time
from pathlib import Path

import pytest

from bitbyte.lang.parser import parse
from bitbyte.lang.stimulus import parse_stimulus
from bitbyte.ref.refsim import refsim_trace
from bitbyte.wide import iss, link, model
from randprog import FULL_WATCH, random_mixed_program, random_program, scan_stimulus, strip_timers
from test_wide_image import dense_stimulus, differences
from test_wide_model import with_label_nops

ROOT = Path(__file__).resolve().parents[1]
OUT = Path(os.environ.get("BITBYTE_SOAK_OUT", ROOT / "build" / "soak"))
CASES = OUT / "wide-cases"
N = int(os.environ.get("BITBYTE_SOAK_N", "100"))
SEED = int(os.environ["BITBYTE_SEED"])
CHUNK = 200
SCANS = 8
DENSE_CLOCKS = 1200


def program_text(index: int) -> str:
    seed = SEED * 100000 + index
    kind = index % 3
    if kind == 1:
        return strip_timers(random_mixed_program(seed))
    text = random_program(seed)
    return with_label_nops(text, random.Random(seed)) if kind == 2 else text


def scalar_differences(program, image, stimulus) -> list[str]:
    """The image against the scalar interpreter: every column but t_us and cycles."""
    cols, want, want_fault = refsim_trace(program, stimulus=stimulus, watch=FULL_WATCH,
                                          scans=SCANS)
    _, got, got_fault, _ = iss.image_trace(image, stimulus=stimulus, watch=FULL_WATCH,
                                           scans=SCANS)
    out = [] if (want_fault, len(want)) == (got_fault, len(got)) else \
        [f"fault/scans: image {got_fault}/{len(got)}, scalar {want_fault}/{len(want)}"]
    for w, g in zip(want, got):
        out += [f"{c.header} scan {w.scan}: image {g.values[c.header]}, scalar "
                f"{w.values[c.header]}" for c in cols
                if c.header != "t_us" and w.values[c.header] != g.values[c.header]]
    return out


def save(index: int, text: str, problems: list[str]) -> None:
    CASES.mkdir(parents=True, exist_ok=True)
    (CASES / f"wide{index}.il").write_text(text)
    (CASES / f"wide{index}.txt").write_text(
        f"BITBYTE_SEED={SEED} program {index}\n" + "\n".join(problems[:20]) + "\n")


@pytest.mark.parametrize("chunk", range((N + CHUNK - 1) // CHUNK))
def test_wide_soak_chunk(chunk):
    t0 = time.monotonic()
    indexes = range(chunk * CHUNK, min(N, (chunk + 1) * CHUNK))
    texts = {i: program_text(i) for i in indexes}
    progs = {i: parse(f"wide{i}.il", t) for i, t in texts.items()}
    compiled = dict(zip(indexes, model.compile_programs([progs[i] for i in indexes])))
    mismatches, counts = [], {"units": 0, "lut_words": 0, "unit_il": 0, "fallbacks": 0,
                              "pi_units": 0, "jump_programs": 0}
    for i in indexes:
        p, c = progs[i], compiled[i]
        problems: list[str] = []
        try:
            image = link.link(p, c)
            scan = parse_stimulus(scan_stimulus(SEED * 100000 + i, SCANS))
            problems += scalar_differences(p, image, scan)
            problems += [f"model: {d}" for d in differences(p, c, image, scan, FULL_WATCH)]
            dense = parse_stimulus(dense_stimulus(SEED * 100000 + i, DENSE_CLOCKS))
            problems += [f"t_us model: {d}" for d in differences(p, c, image, dense, FULL_WATCH)]
        except (iss.ImageError, link.LinkError) as exc:
            problems.append(f"{type(exc).__name__}: {exc}")
        if problems:
            mismatches.append(f"program {i} (wide-cases/wide{i}.il): {problems[0]}")
            save(i, texts[i], problems)
        live = [(u, g) for u, g in zip(c.split.units, c.programs) if g is not None]
        counts["units"] += len(live)
        counts["lut_words"] += sum(len(g) for _, g in live)
        counts["unit_il"] += sum(u.size for u, _ in live)
        counts["fallbacks"] += c.fallbacks
        counts["pi_units"] += sum(any(x.startswith("PI") for x in u.inputs) for u, _ in live)
        counts["jump_programs"] += any(ins.mnemonic in ("JU", "JC", "JCN") for ins in p.instrs)
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"wide_chunk{chunk:05d}.json").write_text(json.dumps({
        "seed": SEED, "chunk": chunk, "programs": len(indexes), "mismatches": mismatches,
        "seconds": round(time.monotonic() - t0, 1), **counts}))
    assert not mismatches, "\n".join(mismatches)
