"""The wide engine's image (issue 18 slice S3, docs/wide-rtl-plan.md §1 option D):
`bitbyte asm --bit-engine wide` relinks a program into LUT words and scalar words, and
bitbyte/wide/iss.py runs that image word by word. Its traces must equal the wide model's
(bitbyte/wide/model.py, which runs the compiled units from the source program) in every
column, `cycles` included, and so the scalar engine's but for `cycles` (the model's own
test). Shown able to fail: a table bit flipped, a jump retargeted, a scalar word changed,
a unit's first mark dropped."""
from __future__ import annotations

import json
import os
import random
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
import randprog                                        # noqa: E402
from bitbyte.encoding import isa                       # noqa: E402
from bitbyte.lang.definition import DEF                # noqa: E402
from bitbyte.lang.parser import parse                  # noqa: E402
from bitbyte.lang.stimulus import parse_stimulus       # noqa: E402
from bitbyte.wide import iss, link, model              # noqa: E402
from bitbyte.wide import lutmap as L                   # noqa: E402
from test_wide_model import (_adder, _adder_stimulus, _operands,  # noqa: E402
                             with_label_nops)

PROGRAMS = int(os.environ.get("BITBYTE_WIDE_MODEL_PROGRAMS", "40"))
SCANS = 8
BASE_SEED = int(os.environ.get("BITBYTE_SEED", "1"))


def differences(program, compiled, image, stimulus, watch, scans=SCANS) -> list:
    """Every column (cycles included) where the image's run and the model's differ."""
    cols, want, want_fault, _ = model.wide_trace(program, compiled, stimulus=stimulus,
                                                 watch=watch, scans=scans)
    _, got, got_fault, _ = iss.image_trace(image, stimulus=stimulus, watch=watch, scans=scans)
    out = [] if (want_fault, len(want)) == (got_fault, len(got)) else \
        [f"fault/scans: image {got_fault}/{len(got)}, model {want_fault}/{len(want)}"]
    for w, g in zip(want, got):
        if w.cycles != g.cycles:
            out.append(f"cycles scan {w.scan}: image {g.cycles}, model {w.cycles}")
        out += [f"{c.header} scan {w.scan}" for c in cols
                if w.values[c.header] != g.values[c.header]]
    return out


def _random_set(base: int = BASE_SEED):
    texts = [randprog.random_program(base * 1000 + k) if k % 2 == 0 else
             randprog.strip_timers(randprog.random_mixed_program(base * 1000 + k))
             for k in range(PROGRAMS)]
    texts += [with_label_nops(t, random.Random(base * 1000 + k))
              for k, t in enumerate(texts)]
    progs = [parse(f"img{k}.il", t) for k, t in enumerate(texts)]
    return progs, model.compile_programs(progs)


@pytest.fixture(scope="module")
def random_set():
    return _random_set()


def test_the_adder_image_sums_as_the_model():
    p, c = _adder()
    img = link.link(p, c)
    ops = _operands(BASE_SEED, 6)
    st = parse_stimulus(_adder_stimulus(ops))
    watch = [f"Q{i // 8}.{i % 8}" for i in range(65)]
    assert differences(p, c, img, st, watch, len(ops)) == []
    lut_words = sum(len(prog) for prog in c.programs)
    # 898 instructions in units, the two first scalar, END
    assert len(img.base) == lut_words + 3 and len(img.units) == sum(
        1 for prog in c.programs if prog)
    _, recs, _, sim = iss.image_trace(img, stimulus=st, watch=watch, scans=len(ops))
    for (a, b), r in zip(ops, recs):        # and the sums themselves, from the trace
        assert sum(r.values[f"Q{i // 8}.{i % 8}"] << i for i in range(65)) == a + b
    assert sim.lut_clocks == lut_words * len(ops)


def test_random_images_run_as_the_model(random_set):
    """The regression's generators (jumps, backward ones too, REFRESH, parentheses,
    edges, PI/PQ, words, compares, counters; with `label: NOP` lines): every column
    and `cycles` of every scan equal, 0 mismatching programs."""
    progs, comp = random_set
    bad, jumps = [], 0
    for k, (p, c) in enumerate(zip(progs, comp)):
        img = link.link(p, c)
        st = parse_stimulus(randprog.scan_stimulus(BASE_SEED * 1000 + k % PROGRAMS, SCANS))
        d = differences(p, c, img, st, randprog.FULL_WATCH)
        if d:
            bad.append((k, d[:3]))
        jumps += sum(1 for s in img.src if isinstance(s, int)
                     and p.instrs[s].mnemonic in isa.JUMP_OPS)
    assert bad == [], bad
    assert jumps > 50             # relinked jumps ran


def test_image_layout(random_set):
    """Jump targets are a unit's first word or a scalar word, the instruction's new
    address; a unit's words are consecutive, first and last marked; every source
    instruction has its address (a unit's instructions its first word's; a unit of no
    word, the next word's)."""
    progs, comp = random_set
    empty = 0
    for p, c in zip(progs, comp):
        img = link.link(p, c)
        starts = {u["addr"] for u in img.units}
        for a, s in enumerate(img.src):
            if isinstance(s, int):
                assert img.addr[s] == a and img.ext[a] == 0
                ins = p.instrs[s]
                if ins.mnemonic in isa.JUMP_OPS:
                    t = link.jump_target(img.base[a])
                    assert t == img.addr[p.labels[ins.operand.label]]
                    assert t in starts or isinstance(img.src[t], int)
            else:
                assert img.is_lut(a)
        for u in img.units:
            assert all(img.src[a] == tuple(u["src"]) for a in range(u["addr"], u["addr"] + u["words"]))
            assert img.addr[u["src"][0]] == u["addr"]
        for unit, prog in zip(c.split.units, c.programs):
            if prog == []:
                empty += 1
                assert img.addr[unit.start] == img.addr[unit.stop]
        assert img.addr == sorted(img.addr)
    assert empty > 0              # units of no word were relinked past


def dense_stimulus(seed: int, clocks: int) -> str:
    """A `t_us` stimulus whose pins change in every clock (100 MHz): the clock a unit
    samples its PI pins in decides what it reads."""
    rng = random.Random(seed)
    cols = [f"I{b}.{n}" for b in range(randprog.IN_BYTES) for n in range(8)]
    return "t_us," + ",".join(cols) + "\n" + "".join(
        f"{c / 100:.2f}," + ",".join(str(rng.randrange(2)) for _ in cols) + "\n"
        for c in range(clocks))


def test_random_images_under_pins_changing_every_clock(random_set):
    """The pin rule of docs/wide-rtl-plan.md §2.3 (a unit's PI pins once, in its first
    word's operand clock; behind a dispatched byte or timer/counter instruction, in
    that instruction's first clock), which scan-keyed stimuli cannot tell from others."""
    progs, comp = random_set
    bad, pi = [], 0
    for k, (p, c) in list(enumerate(zip(progs, comp)))[::2]:   # half: make test's time
        pi += any(x.startswith("PI") for u, g in zip(c.split.units, c.programs) if g
                  for x in u.inputs)
        d = differences(p, c, link.link(p, c), parse_stimulus(dense_stimulus(k, 1200)),
                        randprog.FULL_WATCH)
        if d:
            bad.append((k, d[:3]))
    assert bad == [] and pi >= 10, (bad, pi)


@pytest.mark.parametrize("before", ["NOP", "L 5", "CU C1"])
def test_pins_behind_a_byte_instruction(before):
    """A unit reading PI right behind a byte (or counter) instruction of several clocks,
    and the same with a scalar word between: the pins change at each of the first clocks."""
    for mid in ("", "la: LD I0.1\n"):
        text = f"NOP\nNOP\n{before}\n{mid}lb: LD PI0.0\n= Q0.0\nLD PI0.1\n= Q0.1\nEND\n"
        p = parse("pi.il", text)
        c = model.compile_program(p)
        img = link.link(p, c)
        assert img.units, text
        for rise in ("0.01", "0.02", "0.03", "0.04", "0.05", "0.1", "0.11", "0.12"):
            st = parse_stimulus(f"t_us,I0.0,I0.1\n0,0,0\n{rise},1,1\n")
            assert differences(p, c, img, st, ["Q0.0", "Q0.1"], scans=2) == [], (text, rise)


def test_a_non_live_rlo_write_is_refused(random_set):
    """No word of a unit whose RLO the next instruction does not read writes the RLO
    (§2.4): the RLO is no trace column, so the linker refuses such a program."""
    progs, comp = random_set
    for p, c in zip(progs, comp):
        hit = [i for i, (u, g) in enumerate(zip(c.split.units, c.programs))
               if g and not u.rlo_live]
        if hit:
            link.link(p, c)                  # as compiled: accepted
            c.programs[hit[0]] = c.programs[hit[0]] + [L.MInstr((), [("RLO", 1)])]
            with pytest.raises(link.LinkError, match="not live"):
                link.link(p, c)
            c.programs[hit[0]] = c.programs[hit[0]][:-1]
            return
    raise AssertionError("no unit with a dead RLO")


# Fixed seeds, not the run's: that a broken image is seen must not depend on whether
# this run's programs happen to have a JU whose target's neighbour differs.
FIXED_BASE = 1


@pytest.fixture(scope="module")
def fixed_set():
    return _random_set(FIXED_BASE)


@pytest.mark.parametrize("fault", ["table_bit", "jump_target", "scalar_word", "first_mark"])
def test_a_broken_image_is_seen(fixed_set, fault):
    progs, comp = fixed_set
    seen = 0
    for k, (p, c) in enumerate(zip(progs, comp)):
        img = link.link(p, c)
        st = parse_stimulus(randprog.scan_stimulus(FIXED_BASE * 1000 + k % PROGRAMS, SCANS))
        if fault == "table_bit":
            if not img.units:
                continue
            a = img.units[0]["addr"]
            img.ext[a] ^= (1 << (1 << DEF.lut.k)) - 1      # table A inverted
        elif fault == "jump_target":
            at = [a for a, s in enumerate(img.src) if isinstance(s, int)
                  and p.instrs[s].mnemonic == "JU"]
            if not at:
                continue
            img.base[at[0]] ^= 1 << DEF.fields["target"].lo   # one address off
        elif fault == "scalar_word":
            img.base[0] ^= 1 << DEF.fields["index"].lo
        else:
            if not img.units:
                continue
            img.base[img.units[0]["addr"]] &= ~(1 << DEF.lut.first)
        try:
            d = differences(p, c, img, st, randprog.FULL_WATCH)
        except iss.ImageError:
            d = ["ImageError"]
        seen += bool(d)
        if seen >= 5:
            break
    assert seen >= 5, (fault, seen)


def _asm(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    src = tmp_path / "interlock.il"
    src.write_text((ROOT / "examples" / "interlock.il").read_text())
    return subprocess.run([sys.executable, "-m", "bitbyte.cli", "asm", str(src), *args],
                          capture_output=True, text=True, cwd=tmp_path)


def test_asm_bit_engine_wide_writes_the_image(tmp_path):
    r = _asm(tmp_path, "--bit-engine", "wide")
    assert r.returncode == 0, r.stderr
    base = (tmp_path / "interlock.hex").read_text().split()
    ext = (tmp_path / "interlock.ext.hex").read_text().split()
    meta = json.loads((tmp_path / "interlock.json").read_text())
    p = parse(str(tmp_path / "interlock.il"), (tmp_path / "interlock.il").read_text())
    img = link.link(p, model.compile_program(p))
    assert base == [f"{w:08X}" for w in img.base] and len(ext) == len(base)
    assert all(len(e) == link.EXT_DIGITS for e in ext)
    assert [int(e, 16) for e in ext] == img.ext
    assert meta["bit_engine"] == "wide" and meta["words"] == len(base) and meta["units"]
    assert len(meta["addr"]) == len(p.instrs)
    # the labels where their jumps go, in the .hex
    jumps = {int(w, 16) >> DEF.fields["target"].lo & DEF.fields["target"].mask
             for w in base if int(w, 16) >> DEF.fields["opcode"].lo in (isa.OPCODES[j] for j in isa.JUMP_OPS)}
    assert jumps and jumps <= set(meta["labels"].values())
    assert meta["labels"] == {n: img.addr[a] for n, a in p.labels.items()}
    for u in meta["units"]:       # a unit's lines: those of its source instructions
        lines = [ins.line for ins in p.instrs[u["src"][0]:u["src"][1]]]
        assert u["lines"] == [min(lines), max(lines)]
    lst = (tmp_path / "interlock.lst").read_text()
    assert "LUT word 1/" in lst and ":=" in lst


def test_run_takes_bit_engine(tmp_path):
    """spec §4: `run --bit-engine scalar|wide`: the same trace but `cycles` and `t_us`
    (the wide build: tests/test_wide_rtl.py); what the wide run does not do yet is
    refused with exit 2."""
    src = tmp_path / "p.il"
    src.write_text("LD I0.0\nA I0.1\nO I0.2\n= Q0.0\nX Q0.0\n= Q0.1\nEND\n")
    stim = tmp_path / "s.csv"
    stim.write_text("scan,I0.0,I0.1,I0.2\n0,1,1,0\n1,0,1,0\n2,0,0,1\n")
    run = [sys.executable, "-m", "bitbyte.cli", "run", str(src), "--scans", "3",
           "--stimulus", str(stim)]
    traces = {}
    for engine in ("scalar", "wide"):
        trace = tmp_path / f"{engine}.csv"
        r = subprocess.run(run + ["--bit-engine", engine, "--trace", str(trace)],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        rows = [line.split(",") for line in trace.read_text().splitlines()]
        traces[engine] = [[v for h, v in zip(rows[0], row) if h not in ("t_us", "cycles")]
                          for row in rows]
    assert traces["wide"] == traces["scalar"] and len(traces["wide"]) == 4
    for opt in (["--mode", "parallel"], ["--sim", "icarus"]):
        r = subprocess.run(run + ["--bit-engine", "wide", *opt], capture_output=True, text=True)
        assert r.returncode == 2 and "not supported yet" in r.stderr and "Traceback" not in r.stderr


@pytest.mark.parametrize("args,message", [
    (("--mode", "parallel"), "serial mode only"),
    (("--profile", "hx8k"), "ECP5-25"),
])
def test_asm_bit_engine_wide_refuses(tmp_path, args, message):
    r = _asm(tmp_path, "--bit-engine", "wide", *args)
    assert r.returncode == 2 and message in r.stderr and "Traceback" not in r.stderr
    assert not (tmp_path / "interlock.ext.hex").exists()
