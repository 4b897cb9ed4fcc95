"""Generated plants for the multi-core tests and benchmarks (docs/multicore.md).

* `tearing_pair`: a writer that stamps its scan count into every word of a group of
  shared words each scan, and a reader that only copies the group in (its trace shows
  what its precycle copied): the tearing stress test.
* `table4_pair`: seed 000's Table 4 load: each core reads the other core's N words,
  increments them and writes N words of its own.
* `write_plant`: the plant file and the programs in a folder.
"""
from __future__ import annotations

from pathlib import Path


def write_plant(folder: Path, cores: list[tuple[str, str, int]], *, clock_mhz=100,
                layout: str = "compact", protection: str = "semaphore") -> Path:
    """cores: (name, IL text, period_us). Returns the plant file's path."""
    folder.mkdir(parents=True, exist_ok=True)
    lines = [f"clock_mhz = {clock_mhz}", f'layout = "{layout}"',
             f'protection = "{protection}"']
    for name, text, period in cores:
        (folder / f"{name}.il").write_text(text)
        lines += ["", "[[core]]", f'name = "{name}"', f'program = "{name}.il"',
                  f"period_us = {period}"]
    path = folder / "plant.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


def _globals(decls: list[str]) -> str:
    return "VAR_GLOBAL\n" + "".join(f"  {d};\n" for d in decls) + "END_VAR\n"


def tearing_pair(group: int = 8, reader_nops: int = 0) -> tuple[str, str]:
    """(writer IL, reader IL) over the shared words G0..G<group-1> (MW0.. on both
    sides). The writer counts its scans in MW200 and transfers the count into every
    word of the group; the reader executes `reader_nops` NOPs (to vary its phase).
    The reader declares the group in the opposite order: with the random layout its
    copies run in that order, against the writer's, as two projects written by
    different people would (compact copies both in shared-address order)."""
    writer = (_globals([f"G{i} AT MW{i} : WRITE" for i in range(group)])
              + "      L MW200\n      L 1\n      +I\n      T MW200\n"
              + "".join(f"      T G{i}\n" for i in range(group)) + "      END\n")
    reader = (_globals([f"G{i} AT MW{i} : READ" for i in reversed(range(group))])
              + "      NOP\n" * reader_nops + "      END\n")
    return writer, reader


def table4_pair(words: int, back: int | None = None) -> tuple[str, str]:
    """(core A IL, core B IL): A writes A0..A<words-1> (MW0..), B reads them into
    MW0.., increments each and writes B0..B<back-1> (MW<words>..), which A reads into
    MW<words>.. and increments into its own words: every word read, incremented and
    written back, as in seed 000's Table 4. back defaults to words."""
    back = words if back is None else back
    a_decls = ([f"A{i} AT MW{i} : WRITE" for i in range(words)]
               + [f"B{i} AT MW{words + i} : READ" for i in range(back)])
    b_decls = ([f"A{i} AT MW{i} : READ" for i in range(words)]
               + [f"B{i} AT MW{words + i} : WRITE" for i in range(back)])
    a_body = "".join(f"      L B{i % back if back else 0}\n      L 1\n      +I\n      T A{i}\n"
                     if back else f"      L A{i}\n      L 1\n      +I\n      T A{i}\n"
                     for i in range(words))
    b_body = "".join(f"      L A{i % words}\n      L 1\n      +I\n      T B{i}\n"
                     for i in range(back))
    return (_globals(a_decls) + a_body + "      END\n",
            _globals(b_decls) + b_body + "      END\n")
