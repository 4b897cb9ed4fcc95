"""How often each program line executed over a whole run (`bitbyte run --line-counts
FILE`): the coverage of a user's own program, and what `make soak` counts its
functional coverage from (soak/coverage_count.py).

The counts are the simulated system's, never the reference interpreter's: the
Verilator harness counts every clock in which the bit processor's retirement port
(rtl/bit_proc.v `ret_*_o`) names an address, and in parallel and free-running mode
every instruction the byte processor firmware records as completed (`bb_ret_seq`).
Startup scans (an S7 source's OB 100) are part of the run and are counted. The byte
part's END_B completes no instruction the firmware records (it ends the byte side's
scan): its row's count is empty, as `--status` shows it as "the byte part's end"."""
from __future__ import annotations

import csv
import io

from bitbyte.lang.program import Instr, display_text

HEADER = ("part", "address", "line", "instruction", "count")


def line_count_rows(listing: list[Instr], counts: dict[int, int],
                    byte_listing: list[Instr] | None = None,
                    byte_counts: dict[int, int] | None = None) -> list[tuple]:
    """One row per program word, in address order: (part, address, source line,
    instruction, count); part is `program` in serial mode, else `bit` and `byte`.
    A line the run never reached has count 0."""
    rows = []
    parts = [("program" if byte_listing is None else "bit", listing, counts)]
    if byte_listing is not None:
        parts.append(("byte", byte_listing, byte_counts or {}))
    for part, words, got in parts:
        unknown = set(got) - set(range(len(words)))
        if unknown:
            raise ValueError(f"{part} part: retirements at addresses {sorted(unknown)} "
                             f"outside its {len(words)} words")
        rows += [(part, pc, ins.line, display_text(ins),
                  "" if part == "byte" and ins.mnemonic == "END_B" else got.get(pc, 0))
                 for pc, ins in enumerate(words)]
    return rows


def line_counts_csv(rows: list[tuple]) -> str:
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(HEADER)
    w.writerows(rows)
    return out.getvalue()
