"""An interpreter of the wide engine's image (bitbyte/wide/link.py), clock by clock:
what the wide RTL will be checked against, and a check of the linker and the encoder
against the wide model (bitbyte/wide/model.py), which runs the compiled units from the
source program instead.

It runs wide addresses, not source instructions. A LUT word is executed from its
base and extension words alone (encode.decode): its operands read in order, word by
word, each word seeing the writes of the words before it (the RTL's forwarding), a
scratch bit read only after a word of the same unit wrote it (the scratch file is not
cleared between units: a read before a write would read another unit's bit), one
clock a word. PI pins are read once per unit, in its first word's operand clock (the
clock before it; behind a dispatched byte instruction, that instruction's first
clock): docs/wide-rtl-plan.md §2.3. A scalar word runs as the scalar interpreter runs
its source instruction, after the word is checked to be that instruction's encoding;
a jump goes to the wide address in its word's target field.
"""
from __future__ import annotations

from bitbyte.encoding import isa
from bitbyte.encoding.encoder import constant_pool, encode_instr
from bitbyte.lang.config import DEFAULT
from bitbyte.lang.program import Instr
from bitbyte.lang.trace import trace_columns
from bitbyte.ref.refsim import RefSim
from bitbyte.wide.encode import ZERO, decode
from bitbyte.wide.model import read_location, write_location
from bitbyte.wide.link import TARGET, WideImage, jump_target
from bitbyte.wide.stretch import RLO, cut_reason

_LUT_INSTR = Instr("(LUT word)", None, 0, 0)


class ImageError(RuntimeError):
    """The image is not what the interpreter can run (a defect of the linker)."""


class ImageSim(RefSim):
    """RefSim over the wide image's addresses. lut_clocks: the LUT words executed."""

    def __init__(self, image: WideImage, *args, **kwargs):
        super().__init__(image.program, *args, **kwargs)
        self.image = image
        self.pool = constant_pool(image.program)
        self.scratch: dict[int, int] = {}
        self.lut_clocks = 0
        self._byte_start: int | None = None

    def _instr(self, pc: int) -> Instr:
        if pc >= len(self.image.base):      # the image ends with END: never run past it
            raise ImageError(f"address {pc:04X}: past the image's last word")
        src = self.image.src[pc]
        if not isinstance(src, int):
            return _LUT_INSTR
        ins = self.program.instrs[src]
        word = encode_instr(self.program, ins, "serial", self.pool)
        mask = ~(TARGET.mask << TARGET.lo) if ins.mnemonic in isa.JUMP_OPS else ~0
        if (word ^ self.image.base[pc]) & mask or self.image.ext[pc]:
            raise ImageError(f"address {pc:04X}: word {self.image.base[pc]:08X} is not "
                             f"the encoding of `{ins.mnemonic}` (line {ins.line})")
        return ins

    # --- the machine state a LUT word reads and writes ---------------------------------

    def _read_loc(self, x: str, pin_clock: int) -> int:
        if x == ZERO:
            return 0
        if x.startswith("S") and x[1:].isdigit():
            n = int(x[1:])
            if n not in self.scratch:
                raise ImageError(f"scratch bit {x} read before a word of its unit wrote it")
            return self.scratch[n]
        return read_location(self, x, pin_clock)

    def _write_loc(self, x: str, v: int) -> None:
        if x.startswith("S") and x[1:].isdigit():
            self.scratch[int(x[1:])] = v
        elif x == RLO or x.rstrip("0123456789.") in ("Q", "M"):
            write_location(self, x, v)
        else:
            raise ImageError(f"a LUT word writes {x}")

    # --- one step ---------------------------------------------------------------------

    def _step(self, ins, pc, clock):
        if ins is not _LUT_INSTR:
            nxt, clocks = super()._step(ins, pc, clock)
            reason = cut_reason(ins)
            self._byte_start = clock if reason in ("byte", "timer/counter") else None
            return nxt, clocks
        pin_clock = self._byte_start if self._byte_start is not None else clock - 1
        self._byte_start = None
        self.scratch = {}
        a, first = pc, True
        while True:
            if a >= len(self.image.base) or not self.image.is_lut(a):
                raise ImageError(f"address {pc:04X}: a unit without its last word")
            p, is_first, is_last = decode(self.image.base[a], self.image.ext[a])
            if is_first != first:
                raise ImageError(f"address {a:04X}: first mark {is_first}")
            vals = [self._read_loc(x, pin_clock) for x in p.inputs]
            index = sum(v << j for j, v in enumerate(vals))
            for dst, table in p.outs:                  # both ports from the same operands
                self._write_loc(dst, table >> index & 1)
            a, first = a + 1, False
            if is_last:
                break
        self.lut_clocks += a - pc
        return a, a - pc


    def _jump(self, m, op, pc):
        """A taken jump goes to its word's target (the source label's address is not
        used); its cost is the scalar interpreter's."""
        nxt, clocks = super()._jump(m, op, pc)
        return (jump_target(self.image.base[pc]) if self.jump_taken(m) else nxt), clocks


def image_trace(image: WideImage, config=None, stimulus=None, watch=(),
                scans: int | None = None, watchdog: int = 100000):
    """(columns, records, fault?, sim) of a serial-mode run of the image."""
    config = config or DEFAULT
    program = image.program
    columns = trace_columns(program, list(watch), program.symbols, config)
    sim = ImageSim(image, config, stimulus, watchdog, columns)
    records = sim.run(scans)
    return columns, records, sim.watchdog_fault, sim
