"""The wide bit engine's RTL on the Verilator harness (issue 18, docs/wide-rtl-plan.md).

Slice S4, the scaffolding: `bitbyte_cpu #(.BitEngine(1))` holds the extension RAM
beside the program RAM and loads a wide image's extension words (`prog_ext` in the
harness's run file, `make harness-wide`); its LUT words pass the pipeline as NOPs, one
clock each, until slice S6 executes them. Checked here against independent models:

* the wide build runs a scalar image (every extension word 0) exactly as the scalar
  build does: every column, `cycles` and the end clock (`t_us`) of every scan, timers included (the
  scalar engine inside the wide build is untouched);
* a wide image with LUT words (units of the regression's random programs, the 64-bit
  adder) runs as the image interpreter (bitbyte/wide/iss.py) runs it when a LUT word
  is a one-clock NOP: every column and `cycles` (so a LUT word costs one clock, never
  looks like END, a jump or a wait, and every relinked jump lands where the image
  says);
* the scalar build refuses an extension file (a wide image on the scalar build would
  run its units as NOPs without a word).
"""
from __future__ import annotations

import dataclasses
import os
import random

import pytest

import randprog
from bitbyte.lang.errors import SimError
from bitbyte.run.prepare import prepare
from bitbyte.sim.verilator import run_harness
from bitbyte.wide import iss, link, model
from test_wide_model import adder_il, with_label_nops

PROGRAMS = int(os.environ.get("BITBYTE_WIDE_RTL_PROGRAMS", "24"))
SCANS = 6
BASE_SEED = int(os.environ.get("BITBYTE_SEED", "1"))


class NopLutImageSim(iss.ImageSim):
    """The image interpreter with every LUT word a one-clock NOP (slice S4's RTL)."""

    def _step(self, ins, pc, clock):
        if ins is iss._LUT_INSTR:
            self._byte_start = None
            return pc + 1, 1
        return super()._step(ins, pc, clock)


def _prepared(tmp_path, name, text, stim, watch):
    il = tmp_path / f"{name}.il"
    il.write_text(text)
    st = tmp_path / f"{name}.csv"
    st.write_text(stim)
    return prepare(str(il), stimulus=str(st), watch=",".join(watch), scans=SCANS)


def _rows(records, columns):
    return [(r.scan, r.cycles, [r.values[c.header] for c in columns]) for r in records]


def _cases(kinds):
    out = []
    for k in range(PROGRAMS):
        seed = BASE_SEED * 1000 + k
        kind = kinds[k % len(kinds)]
        if kind == "bit":
            text = randprog.random_program(seed)
        elif kind == "mixed":
            text = randprog.random_mixed_program(seed)
        else:                       # timers stripped, `label: NOP` lines put in
            text = with_label_nops(randprog.strip_timers(randprog.random_mixed_program(seed)),
                                   random.Random(seed))
        out.append((f"p{k}", text, randprog.scan_stimulus(seed, SCANS)))
    return out


def test_the_wide_build_runs_a_scalar_image_as_the_scalar_build(tmp_path):
    bad = []
    for name, text, stim in _cases(["bit", "mixed"]):
        prep = _prepared(tmp_path, name, text, stim, randprog.FULL_WATCH)
        want, want_fault, _ = run_harness(prep.job, prep.columns)
        job = dataclasses.replace(prep.job, prog_ext=[0] * len(prep.job.prog))
        got, got_fault, _ = run_harness(job, prep.columns)
        if (want_fault, [(r.end_clock, *row) for r, row in zip(want, _rows(want, prep.columns))]) != \
                (got_fault, [(r.end_clock, *row) for r, row in zip(got, _rows(got, prep.columns))]):
            bad.append(name)
    assert bad == []


def _nop_rows(prep, image, scans):
    sim = NopLutImageSim(image, prep.config, prep.stimulus, prep.job.watchdog, prep.columns)
    return _rows(sim.run(scans), prep.columns), sim


def test_lut_words_pass_the_pipeline_as_one_clock_nops(tmp_path):
    """Random programs' wide images, relinked jumps and units after byte instructions
    included: the RTL's trace is the NOP interpreter's, `cycles` included."""
    bad, lut_words, faults = [], 0, 0
    cases = _cases(["bit", "nops"])
    progs = [_prepared(tmp_path, name, text, stim, randprog.FULL_WATCH)
             for name, text, stim in cases]
    for prep, (name, _, _), comp in zip(progs, cases,
                                          model.compile_programs([p.program for p in progs])):
        image = link.link(prep.program, comp)
        job = dataclasses.replace(prep.job, prog=image.base, prog_ext=image.ext)
        got, fault, _ = run_harness(job, prep.columns)
        want, sim = _nop_rows(prep, image, SCANS)
        if (fault, _rows(got, prep.columns)) != (sim.watchdog_fault, want):
            bad.append((name, fault, [r[1] for r in _rows(got, prep.columns)], [r[1] for r in want]))
        faults += fault
        lut_words += sum(image.is_lut(a) for a in range(len(image.base)))
    assert bad == []
    print(f"{len(cases)} programs, {lut_words} LUT words, {faults} watchdog faults")
    assert lut_words > 100       # the images held LUT words
    # (a loop whose exit a unit computes never ends with NOP units: both sides fault)
    assert faults <= len(cases) // 3


def test_the_adder_image_runs_its_lut_words_in_one_clock_each(tmp_path):
    prep = _prepared(tmp_path, "adder", adder_il(), "scan,I0.0\n0,1\n", ["Q0.0"])
    image = link.link(prep.program, model.compile_program(prep.program))
    job = dataclasses.replace(prep.job, prog=image.base, prog_ext=image.ext)
    got, fault, _ = run_harness(job, prep.columns)
    want, _ = _nop_rows(prep, image, SCANS)
    assert not fault and _rows(got, prep.columns) == want
    # one clock a word, as the scalar adder's 901 words take 901 (docs/wide-engine.md):
    # the two scalar words of R1, the LUT words, END
    assert {r.cycles for r in got} == {len(image.base)} and len(image.base) < 100


def test_the_scalar_build_refuses_an_extension_file(tmp_path):
    prep = _prepared(tmp_path, "s", "LD I0.0\n= Q0.0\n", "scan,I0.0\n0,1\n", [])
    job = dataclasses.replace(prep.job, prog_ext=[0] * len(prep.job.prog))
    os.environ["BITBYTE_HARNESS_WIDE"] = str(__import__("bitbyte.sim.verilator",
                                                        fromlist=["x"]).ensure_harness())
    try:
        with pytest.raises(SimError, match="scalar build"):
            run_harness(job, prep.columns)
    finally:
        del os.environ["BITBYTE_HARNESS_WIDE"]
