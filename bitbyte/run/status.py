"""The block status of one scan (`bitbyte run --status K`, issue 17 item 2), as
STEP 7's "monitor" view shows an STL block: per program line, the RLO after it, the
status of the operand it read (STA), the accumulators after a word instruction, and
"not executed" for what the scan skipped. A line that ran several times in the scan
(a loop) shows its last execution and how often it ran.

The values are the simulated system's: the bit processor's retirement port (RLO,
operand bit; rtl/bit_proc.v `ret_*_o`) and the byte processor firmware's accumulators
(bb_accu1 / bb_accu2) at the clock the instruction completed, recorded by the Verilator
harness and by the cocotb driver alike (bitbyte.run.summary.Retired) — never by the
reference interpreter, which the tests compare them with."""
from __future__ import annotations

from bitbyte.encoding.isa import READ_OPS, is_byte_instruction
from bitbyte.lang.program import Instr, display_text
from bitbyte.run.summary import Retired
from bitbyte.wide.link import WideImage

SOURCE_WIDTH = 34


def _reads_bit(instr: Instr) -> bool:
    """An instruction whose operand is a bit it reads (its STA is meaningful)."""
    op = instr.operand
    return instr.mnemonic in READ_OPS and op is not None and (
        op.kind == "bit" or op.area in ("T", "C"))


def _is_word(instr: Instr) -> bool:
    op = instr.operand
    return is_byte_instruction(instr.mnemonic, op.area if op is not None else None)


def block_status_text(listing: list[Instr], status: dict[int, Retired], scan: int,
                      where: str, ended_by_watchdog: bool = False) -> str:
    """listing: the bit processor's program memory by address (serial mode: the whole
    program); status: address -> its retirement in scan `scan`; where: the simulator;
    ended_by_watchdog: the scan did not end, the watchdog stopped it (its lines show
    what ran up to then)."""
    head = (f"block status of scan {scan} ({where}"
            + ("; ended by the scan watchdog: the lines up to then" if ended_by_watchdog
               else "")
            + "): RLO after each line, STA the operand bit it read, ACCU1/ACCU2 after "
            "word instructions")
    lines = [head] + _rows(listing, status, "RLO")
    return "\n".join(lines) + "\n"


def parallel_block_status_text(listing: list[Instr], status: dict[int, Retired],
                               byte_listing: list[Instr], byte_status: dict[int, Retired],
                               scan: int, where: str, ended_by_watchdog: bool = False) -> str:
    """Parallel mode: the bit part's lines with F_b (the bit processor's RLO), then the
    byte part's with F_B (the byte processor's) and the accumulators, from the
    firmware's record of each completed byte-part instruction."""
    head = (f"block status of scan {scan} ({where}, parallel mode"
            + ("; ended by the scan watchdog: the lines up to then" if ended_by_watchdog
               else "") + ")")
    lines = [head, "bit part: F_b after each line, STA the operand bit it read"]
    lines += _rows(listing, status, "F_b")
    lines += ["byte part: F_B and ACCU1/ACCU2 after each line"]
    lines += _rows(byte_listing, byte_status, "F_B", byte_part=True)
    return "\n".join(lines) + "\n"


def _rows(listing: list[Instr], status: dict[int, Retired], rlo_name: str,
          byte_part: bool = False) -> list[str]:
    lines = [f"{'line':>5}  {'instruction':<{SOURCE_WIDTH}} {rlo_name:>3} {'STA':>3} "
             f"{'ACCU1':>7} {'ACCU2':>7}"]
    for pc, instr in enumerate(listing):
        text = display_text(instr)
        if len(text) > SOURCE_WIDTH:
            text = text[:SOURCE_WIDTH - 1] + "~"
        row = f"{instr.line:>5}  {text:<{SOURCE_WIDTH}}"
        r = status.get(pc)
        if byte_part and instr.mnemonic == "END_B":
            lines.append(f"{row} (the byte part's end)")
            continue
        if r is None:
            lines.append(f"{row} not executed")
            continue
        if r.count is None:       # the wide engine compiled it into no word
            lines.append(f"{row} (no word in the wide image)")
            continue
        sta = str(r.operand) if not byte_part and _reads_bit(instr) else ""
        accus = (f"{r.accu1:>7} {r.accu2:>7}" if byte_part or _is_word(instr)
                 else f"{'':>7} {'':>7}")
        times = f"  ({r.count} times)" if r.count > 1 else ""
        lines.append(f"{row} {r.rlo:>3} {sta:>3} {accus}{times}".rstrip())
    return lines


def source_status(image: WideImage, status: dict) -> dict:
    """The block status (`--status`) by source instruction, from the retirements the wide
    build reported per wide address (bitbyte.run.summary.Retired): a scalar word's is its
    instruction's; a unit's lines take its first word's count and accumulators (no bit
    instruction changes them), their RLO and operand are not observable ("–"); a unit
    of no word has no count (None)."""
    out = {}
    first = {u["addr"]: u for u in image.units}
    for a, src in enumerate(image.src):
        r = status.get(a)
        if isinstance(src, int):
            if r is not None:
                out[src] = r
        elif a in first and r is not None:
            for p in range(*first[a]["src"]):
                out[p] = Retired(r.count, "–", "–", r.accu1, r.accu2)
    covered = {src for src in image.src if isinstance(src, int)}
    covered |= {p for u in image.units for p in range(*u["src"])}
    for p in range(len(image.program.instrs)):
        if p not in covered:
            out[p] = Retired(None, "–", "–", 0, 0)
    return out

