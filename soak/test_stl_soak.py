"""The S7 call soak (`make soak`, issue 19): BITBYTE_STL_SOAK_N (default 1000) random
statement-list programs with calls of generated FCs and an FB with two instance DBs
(tests/stlgen.py, calls=True), each compared with awlsim scan for scan on the
reference interpreter (tests/test_stl_calls.py's random_call_programs), in chunks of
CHUNK so that pytest-xdist spreads them.  0 mismatches; what is rejected is
`unsupported:` and stays rare.  `make test` runs a few of them
(test_random_programs_with_calls_against_awlsim)."""
from __future__ import annotations

import os

import pytest

import test_stl_calls as calls

N = int(os.environ.get("BITBYTE_STL_SOAK_N", "1000"))
CHUNK = 100


@pytest.mark.parametrize("chunk", range((N + CHUNK - 1) // CHUNK))
def test_stl_call_soak_chunk(chunk, tmp_path):
    count = min(CHUNK, N - chunk * CHUNK)
    compared, rejected, _ = calls.random_call_programs(tmp_path, count, chunk * CHUNK)
    assert compared + len(rejected) == count
    assert len(rejected) <= count * 0.25, rejected
