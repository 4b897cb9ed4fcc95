"""The wide engine's LUT words (issue 18): a compiled unit's LUT program (lutmap.MInstr,
dual_s) as the base and extension words of `bitbyte/lang/definition.toml` [lut]
(docs/isa.md "The wide engine's LUT word"), and back.

encode_unit numbers the unit's scratch bits S0.. in the order the program first names
them and writes each instruction as (base, ext): operands j < k in the extension word
(unused ones ZERO), the truth tables widened to 2^K bits (an operand past the
instruction's k is a don't-care), port A the instruction's bit-memory or RLO result (a
scratch result when it has none), port B its scratch result. decode gives the
instruction back with the scratch bits named `S<n>`, K operands (unused ones `ZERO`,
which reads 0) and the widened tables: what the model runs (bitbyte/wide/model.py), so
every model run goes through the words the RTL will read.
"""
from __future__ import annotations

import re

from bitbyte.lang.definition import DEF, Field
from bitbyte.wide.lutmap import MInstr
from bitbyte.wide.stretch import RLO

LUT = DEF.lut
ZERO = "ZERO"
# the bit areas a LUT word reads or writes (PQ reads are Q, stretch.loc)
BIT_AREAS = ("I", "PI", "IR", "IF", "Q", "QR", "QF", "M", "T", "C")
_CODES = {a: DEF.area_codes[a] for a in BIT_AREAS} | {
    name: code for name, code, _, _ in LUT.areas}
_NAMES = {code: name for name, code in _CODES.items()}
_LOC = re.compile(r"^([A-Z]+)(\d+)(?:\.(\d))?$")


class EncodeError(ValueError):
    """A LUT program that the word format cannot hold."""


def _put(word: int, f: Field, value: int, what: str) -> int:
    if not 0 <= value <= f.mask:
        raise EncodeError(f"{what} {value} does not fit {f.width} bits")
    return word | value << f.lo


def _get(word: int, f: Field) -> int:
    return word >> f.lo & f.mask


def _location(x: str, scratch: dict[str, int]) -> tuple[int, int]:
    """(area code, index) of an operand or destination name."""
    if x.startswith("S:") or x in scratch:
        return _CODES["S"], scratch[x]
    if x in (RLO, ZERO):
        return _CODES[x], 0
    m = _LOC.match(x)
    if not m or m.group(1) not in BIT_AREAS:
        raise EncodeError(f"no LUT-word location: {x}")
    area, n, bit = m.group(1), int(m.group(2)), m.group(3)
    return _CODES[area], n * 8 + int(bit) if bit is not None else n


def _name(code: int, index: int) -> str:
    area = _NAMES.get(code)
    if area is None:
        raise EncodeError(f"area code {code} is no LUT-word area")
    if area == "S":
        return f"S{index}"
    if area in (RLO, ZERO):
        return area
    if area in ("T", "C"):
        return f"{area}{index}"
    return f"{area}{index // 8}.{index % 8}"


def widen(table: int, k: int) -> int:
    """A k-input truth table as a K-input one: inputs k.. are don't-cares."""
    size = 1 << k
    return sum((table >> (i % size) & 1) << i for i in range(1 << LUT.k))


def scratch_map(prog: list[MInstr]) -> dict[str, int]:
    """S0.. for the program's scratch names, in the order it first names them."""
    out: dict[str, int] = {}
    for p in prog:
        for x in list(p.inputs) + [d for d, _ in p.outs]:
            if x.startswith("S:") and x not in out:
                out[x] = len(out)
    if len(out) > LUT.scratch_bits:
        raise EncodeError(f"{len(out)} scratch bits, the file has {LUT.scratch_bits}")
    return out


def encode(p: MInstr, scratch: dict[str, int], first: bool, last: bool) -> tuple[int, int]:
    """One LUT instruction as (base word, extension word)."""
    k = len(p.inputs)
    if k > LUT.k:
        raise EncodeError(f"{k} operands, a LUT word has {LUT.k}")
    mem = [(d, t) for d, t in p.outs if not d.startswith("S:")]
    scr = [(d, t) for d, t in p.outs if d.startswith("S:")]
    if len(mem) > 1 or not 1 <= len(p.outs) <= 2:
        raise EncodeError(f"outputs {[d for d, _ in p.outs]}: one to the bit memory or "
                          "the RLO at most, two in all")
    port_a = mem[0] if mem else scr.pop(0)
    base = _put(0, LUT.tag, LUT.tag_value, "tag")
    base |= int(first) << LUT.first | int(last) << LUT.last
    area, index = _location(port_a[0], scratch)
    base = _put(base, LUT.dst_area, area, "destination area")
    base = _put(base, LUT.dst_index, index, f"destination {port_a[0]}")
    ext = _put(0, LUT.table_a, widen(port_a[1], k), "table")
    if scr:
        base |= 1 << LUT.scr_en
        base = _put(base, LUT.scr_index, scratch[scr[0][0]], "scratch index")
        ext = _put(ext, LUT.table_b, widen(scr[0][1], k), "table")
    for j in range(LUT.k):
        area, index = _location(p.inputs[j] if j < k else ZERO, scratch)
        f = LUT.operand(j)
        op = _put(_put(0, LUT.operand_area, area, "operand area"), LUT.operand_index, index,
                  f"operand {p.inputs[j] if j < k else ZERO}")
        ext = _put(ext, f, op, "operand")
    return base, ext


def decode(base: int, ext: int) -> tuple[MInstr, bool, bool]:
    """(the instruction, first, last) of a LUT word's base and extension word."""
    if _get(base, LUT.tag) != LUT.tag_value:
        raise EncodeError(f"0x{base:08X} is no LUT word")
    inputs = tuple(_name(_get(_get(ext, LUT.operand(j)), LUT.operand_area),
                         _get(_get(ext, LUT.operand(j)), LUT.operand_index))
                   for j in range(LUT.k))
    outs = []
    if _get(base, LUT.dst_area) not in (_CODES[a] for a in ("Q", "M", "S", RLO, ZERO)) or \
            any(_get(_get(ext, LUT.operand(j)), LUT.operand_area) == _CODES["S"] and
                _get(_get(ext, LUT.operand(j)), LUT.operand_index) >= LUT.scratch_bits
                for j in range(LUT.k)) or _get(base, LUT.scr_index) >= LUT.scratch_bits:
        raise EncodeError(f"0x{base:08X}: a destination no LUT word writes, or a scratch "
                          "bit past the file")
    dst = _name(_get(base, LUT.dst_area), _get(base, LUT.dst_index))
    if dst != ZERO:
        outs.append((dst, _get(ext, LUT.table_a)))
    if base >> LUT.scr_en & 1:
        outs.append((f"S{_get(base, LUT.scr_index)}", _get(ext, LUT.table_b)))
    return MInstr(inputs, outs), bool(base >> LUT.first & 1), bool(base >> LUT.last & 1)


def encode_unit(prog: list[MInstr]) -> list[tuple[int, int]]:
    """A unit's LUT program as its words, first and last marked."""
    scratch = scratch_map(prog)
    return [encode(p, scratch, i == 0, i == len(prog) - 1) for i, p in enumerate(prog)]


def decode_unit(words: list[tuple[int, int]]) -> list[MInstr]:
    out = []
    for i, (base, ext) in enumerate(words):
        p, first, last = decode(base, ext)
        if (first, last) != (i == 0, i == len(words) - 1):
            raise EncodeError(f"word {i} of {len(words)}: first/last marks {first}/{last}")
        out.append(p)
    return out
