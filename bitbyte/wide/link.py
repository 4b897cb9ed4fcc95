"""The wide engine's image (issue 18, docs/wide-rtl-plan.md §1 option D): a program
relinked so that each compiled unit of m IL instructions becomes its n LUT words at n
consecutive addresses, every other instruction its scalar word at an address of its
own, and every jump target moved to the new address of its instruction.

An address holds a 32-bit base word (the program RAM, as today) and a 144-bit
extension word (the LUT RAM, read with the same PC); a scalar word's extension word is
0. Labels cut units (bitbyte/wide/stretch.py), so a jump lands on a unit's first word
or on a scalar word, never inside a unit; a unit of no word (NOPs only, or nothing
live) takes no address, and what jumps to it lands on the word after it.

`link` builds the image from a compiled program (bitbyte/wide/model.py
compile_program); `asm_files` writes it as `bitbyte asm --bit-engine wide` does:
`<stem>.hex` (base words, the `$readmemh` format of the scalar image), `<stem>.ext.hex`
(extension words, 36 hex digits a line), `<stem>.lst` and `<stem>.json` (the map from
wide addresses to source instructions and lines, which hosts use for anything keyed
by the PC). bitbyte/wide/iss.py runs the image.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

from bitbyte.encoding import isa
from bitbyte.encoding.encoder import constant_pool, encode_instr
from bitbyte.lang.config import DEFAULT, Config
from bitbyte.lang.definition import DEF
from bitbyte.lang.errors import SourceError
from bitbyte.lang.program import Program, display_text
from bitbyte.wide.encode import ZERO, decode, encode_unit
from bitbyte.wide.stretch import RLO

LUT = DEF.lut
EXT_DIGITS = (LUT.ext_bits + 3) // 4      # hex digits of an extension word
TARGET = DEF.fields["target"]   # a jump word's target field


@dataclass
class WideImage:
    """base[a], ext[a]: the words at wide address a. src[a]: the source instruction
    index of a scalar word, or (start, stop) of the unit a LUT word belongs to.
    addr[p]: the wide address of source instruction p (a unit's instructions: its
    first word's; after the last instruction: len(base)). units: one entry per unit
    in the image (n >= 1 words)."""

    program: Program
    base: list[int]
    ext: list[int]
    src: list[int | tuple[int, int]]
    addr: list[int]
    units: list[dict]

    def is_lut(self, a: int) -> bool:
        return self.base[a] >> LUT.tag.lo & LUT.tag.mask == LUT.tag_value


class LinkError(RuntimeError):
    """A compiled program the image must not hold (a defect of the compiler)."""


def jump_target(word: int) -> int:
    """The target field of a jump word (a wide address in the wide image)."""
    return word >> TARGET.lo & TARGET.mask


def link(program: Program, compiled, config: Config = DEFAULT) -> WideImage:
    """The wide image of `program` with its compiled units (model.Compiled);
    SourceError (program too large) when it does not fit the program memory."""
    instrs = program.instrs
    runs = {u.start: (u, p) for u, p in zip(compiled.split.units, compiled.programs)
            if p is not None}
    # pass 1: the wide address of every source instruction
    addr, p, a = [], 0, 0
    while p < len(instrs):
        hit = runs.get(p)
        if hit is None:
            addr.append(a)
            a, p = a + 1, p + 1
            continue
        unit, prog = hit
        addr += [a] * unit.size
        a, p = a + len(prog), unit.stop
    addr.append(a)
    if a > config.prog_words:
        last = instrs[-1]
        raise SourceError(program.path, last.line, last.col,
                          f"program too large: the wide image has {a} words, program "
                          f"memory holds {config.prog_words} (prog_words)")
    # pass 2: the words
    pool = constant_pool(program)
    base, ext, src, units = [], [], [], []
    p = 0
    while p < len(instrs):
        hit = runs.get(p)
        if hit is None:
            ins = instrs[p]
            word = encode_instr(program, ins, "serial", pool)
            if ins.mnemonic in isa.JUMP_OPS:      # the target, relinked
                target = addr[program.labels[ins.operand.label]]
                word = word & ~(TARGET.mask << TARGET.lo) | target << TARGET.lo
            base.append(word)
            ext.append(0)
            src.append(p)
            p += 1
            continue
        unit, prog = hit
        if not unit.rlo_live and any(d == RLO for ins in prog for d, _ in ins.outs):
            # the RTL's rule (docs/wide-rtl-plan.md §2.4): the RLO is written only where
            # the instruction after the unit reads it; a compiler that writes it anyway
            # is refused here, since no trace column shows the RLO
            raise LinkError(f"{program.path}: the unit of source instructions "
                            f"{unit.start}..{unit.stop - 1} writes the RLO, which is not live")
        words = encode_unit(prog)
        if words:
            lines = [ins.line for ins in instrs[unit.start:unit.stop]]
            units.append({"addr": addr[p], "words": len(words),
                          "src": [unit.start, unit.stop],
                          "lines": [min(lines), max(lines)]})
        for b, e in words:
            base.append(b)
            ext.append(e)
            src.append((unit.start, unit.stop))
        p = unit.stop
    return WideImage(program, base, ext, src, addr, units)


def hex_ext(words: list[int]) -> str:
    """Extension words as `$readmemh` text, EXT_DIGITS hex digits a line."""
    return "".join(f"{w:0{EXT_DIGITS}X}\n" for w in words)


def listing(image: WideImage, config: Config = DEFAULT) -> str:
    """One line per wide address: address, base word, and the source line it stands
    for; a LUT word: its place in its unit, the unit's lines, and what it computes,
    `dest := TABLE(operands)` per port (the truth table over the operands it reads,
    operand j bit j of the row; the extension word itself is in the .ext.hex file)."""
    prog = image.program
    n_units = len(image.units)
    out = [f"; bitbyte listing of {prog.path} (wide bit engine)",
           f"; program memory: {len(image.base)} of {config.prog_words} words "
           f"({len(prog.instrs)} instructions; {n_units} unit{'s' * (n_units != 1)} in "
           f"{sum(u['words'] for u in image.units)} LUT words)",
           "; config: " + " ".join(f"{k}={v}" for k, v in asdict(config).items())]
    labels = wide_labels(image)
    if labels:
        out += ["", "labels:"] + [f"  {name:<16} {a:04X}" for name, a in labels.items()]
    out += ["", "addr  word      line: source"]
    at: dict[int, list[str]] = {}
    for name, a in labels.items():
        at.setdefault(a, []).append(name)
    for a, (word, s) in enumerate(zip(image.base, image.src)):
        if a in at and a > 0:
            out.append("")
        out += [f"{'':16}{name}:" for name in at.get(a, [])]
        if isinstance(s, int):
            ins = prog.instrs[s]
            text = ins.source.strip().expandtabs(4) if ins.source else "(appended END)"
            line = f"{a:04X}  {word:08X}  {ins.line:>4}: {text}"
            if ins.mnemonic in isa.JUMP_OPS:
                line = f"{line:<60} ; -> {jump_target(word):04X}"
            out.append(line)
            continue
        unit, k = unit_of(image, a)
        lo, hi = unit["lines"]
        ins, _, _ = decode(word, image.ext[a])
        used = [x for x in ins.inputs if x != ZERO]
        what = "; ".join(f"{d} := {t & (1 << (1 << len(used))) - 1:0{max(1, (1 << len(used)) // 4)}X}"
                         f"({', '.join(used)})" for d, t in ins.outs)
        line = f"{a:04X}  {word:08X}  {lo:>4}: LUT word {k}/{unit['words']} of lines {lo}-{hi}"
        out.append(f"{line:<60} ; {what}")
    return "\n".join(out) + "\n"


def wide_labels(image: WideImage) -> dict[str, int]:
    """Each label at its wide address (where its jumps go)."""
    return {name: image.addr[p] for name, p in image.program.labels.items()}


def summary(image: WideImage) -> dict:
    """The JSON side file's wide part: the engine, the labels at their wide addresses,
    the units, and the wide address of every source instruction (hosts map PCs back
    to lines with it)."""
    return {"bit_engine": "wide", "words": len(image.base), "labels": wide_labels(image),
            "units": image.units, "addr": image.addr[:-1]}


def source_counts(image: WideImage, counts: dict[int, int]) -> dict[int, int | str]:
    """How often each source instruction ran, from the retirements the wide build
    counted per wide address (`--line-counts`): a scalar word's count is its
    instruction's; a unit is entered only at its first word and runs to its last, so
    that word's count is every instruction's of the unit. A unit of no word has no
    address and no count: its instructions get "" (unknown). In serial mode a source
    instruction's index is its address in the scalar image, so the rows are the scalar
    run's."""
    out: dict[int, int | str] = {}
    first = {u["addr"]: u for u in image.units}
    for a, src in enumerate(image.src):
        if isinstance(src, int):
            out[src] = counts.get(a, 0)
        elif a in first:
            for p in range(*first[a]["src"]):
                out[p] = counts.get(a, 0)
    for p in range(len(image.program.instrs)):
        out.setdefault(p, "")
    return out



def unit_of(image: WideImage, a: int) -> tuple[dict, int]:
    """The unit the LUT word at wide address `a` belongs to, and its place in it (1..n)."""
    unit = next(u for u in image.units if u["addr"] <= a < u["addr"] + u["words"])
    return unit, a - unit["addr"] + 1


def wave_listing(image: WideImage) -> list:
    """What the waveform's `executing` row shows at each wide address (`--waves`): a
    scalar word's source instruction (gtkw shows `line: source`); a LUT word as the
    lines its unit runs, its place in the unit and the unit's first instruction that is
    not a NOP, `12-25: LUT word 2/3 (LD I0.0 ..)` (a unit of one line: `12: ...`): a
    unit has no single source instruction, it runs all of them in its words."""
    out: list = []
    for a, src in enumerate(image.src):
        if isinstance(src, int):
            out.append(image.program.instrs[src])
            continue
        unit, k = unit_of(image, a)
        lo, hi = unit["lines"]
        instrs = image.program.instrs[slice(*unit["src"])]
        head = next((i for i in instrs if i.mnemonic != "NOP"), instrs[0])
        lines = f"{lo}" if lo == hi else f"{lo}-{hi}"
        out.append(f"{lines}: LUT word {k}/{unit['words']} ({display_text(head)} ..)")
    return out
