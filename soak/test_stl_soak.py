"""The S7 soak (`make soak`, issue 19): random statement-list programs of
tests/stlgen.py, each compared with awlsim scan for scan in every run of
awlsim_oracle.EVERY_RUN — the reference interpreter in serial mode, the Verilator
harness in serial mode and in parallel mode (the partitioning compiler's bit and byte
parts running concurrently) with the handshake flip-flops and with the queues.  Three
kinds:

* calls: programs with calls of generated FCs and an FB with two instance DBs and
  jump lists (calls=True; tests/test_stl_calls.py's random_call_programs);
* plain: bit logic, words and counters (tests/test_stl.py's random_cases);
* timers: the S7 timers, every transition within one scan of awlsim's
  (awlsim_oracle.timer_equal_or_rejected).

BITBYTE_STL_SOAK_N (default 1000) is the number of programs COMPARED per kind: a
chunk takes the programs of its own span of SPAN indices in order, skips the ones the
front end rejects (`unsupported:` only, asserted; at most a quarter), and stops when
CHUNK are compared; chunks are separate tests so that pytest-xdist spreads them.
A mismatch does not stop the chunk: the program is saved under
build/soak/stl-cases/ with the difference, and the chunk fails at its end.  The
counts go to the terminal summary (soak/conftest.py).  `make test` runs a few of them
(test_random_programs_with_calls_against_awlsim; on the harness,
test_random_call_programs_on_verilator_parallel)."""
from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

import test_stl
import test_stl_calls as calls
from awlsim_oracle import EVERY_RUN, equal_or_rejected, timer_equal_or_rejected
from stlgen import IN_WORDS, WORDS, random_program, slow_inputs, time_value_columns

N = int(os.environ.get("BITBYTE_STL_SOAK_N", "1000"))
CHUNK = 100
SPAN = 2 * CHUNK
CASES = Path(__file__).resolve().parents[1] / "build" / "soak" / "stl-cases"


def call_program(tmp: Path, index: int) -> tuple[int, bool]:
    seed = calls.BASE_SEED * 10_000 + index
    compared, _, _ = calls.random_call_programs(tmp, 1, index, runs=EVERY_RUN)
    return seed, compared == 1


def plain_program(tmp: Path, index: int) -> tuple[int, bool]:
    seed, path, lang, inputs = next(test_stl.random_cases(tmp, 1, index))
    return seed, equal_or_rejected(seed, path, lang, inputs, tmp, words=WORDS,
                                   in_words=IN_WORDS, runs=EVERY_RUN)


def timer_program(tmp: Path, index: int) -> tuple[int, bool]:
    seed = test_stl.BASE_SEED * 10_000 + 20_000 + index     # test_stl's timer seeds
    text, lang = random_program(seed, words=False, timers=True)
    path = tmp / f"tm{seed}.awl"
    path.write_text(text)
    return seed, timer_equal_or_rejected(seed, path, lang, slow_inputs(seed, 40), tmp,
                                         timers=(1, 2, 3, 4, 5), runs=EVERY_RUN,
                                         values=time_value_columns(text))


KINDS = {"calls": call_program, "plain": plain_program, "timers": timer_program}


def save_mismatch(kind: str, index: int, tmp: Path, message: str) -> None:
    CASES.mkdir(parents=True, exist_ok=True)
    for path in tmp.glob("*.awl"):
        shutil.copy(path, CASES / f"{kind}-{index}-{path.name}")
    (CASES / f"{kind}-{index}.txt").write_text(
        f"BITBYTE_SEED={os.environ.get('BITBYTE_SEED')} kind {kind} index {index}\n"
        f"{message}\n")


@pytest.mark.parametrize("chunk", range((N + CHUNK - 1) // CHUNK))
@pytest.mark.parametrize("kind", sorted(KINDS))
def test_stl_soak_chunk(kind, chunk, tmp_path, record_property):
    want = min(CHUNK, N - chunk * CHUNK)
    compared, rejected, mismatches = 0, [], []
    for index in range(chunk * SPAN, (chunk + 1) * SPAN):
        if compared + len(mismatches) == want:
            break
        tmp = tmp_path / str(index)
        tmp.mkdir()
        try:
            seed, equal = KINDS[kind](tmp, index)
        except AssertionError as e:
            if "differs from awlsim" not in str(e):
                raise
            mismatches.append(str(e))
            save_mismatch(kind, index, tmp, str(e))
            continue
        if equal:
            compared += 1
        else:
            rejected.append(seed)
        shutil.rmtree(tmp)
    record_property("stl_soak", [kind, compared, len(rejected), len(mismatches)])
    assert not mismatches, mismatches
    assert compared == want, f"{kind} chunk {chunk}: {compared} compared, " \
                             f"{len(rejected)} rejected in {SPAN} programs"
    assert len(rejected) <= max(3, (compared + len(rejected)) * 0.25), rejected
