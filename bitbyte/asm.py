"""`bitbyte asm`: one source file -> program image, listing and a JSON summary.

Writes, beside the source or into outdir, `<stem>.hex` (one 8-digit hex word per
line, address 0 first: the `$readmemh` format), `<stem>.lst` (the listing) and
`<stem>.json` ({"source", "words", "config", "symbols", "labels"}).  With
mode="parallel" the program is partitioned first and the files are those of
bitbyte.partition.assemble_parallel (`<stem>.bit.hex`, `<stem>.byte.hex`, ...).
Nothing is written when the program has an error: the SourceError propagates to the caller
(the CLI prints it with `format_error` and exits non-zero).
"""
from __future__ import annotations

import json
import os
from dataclasses import asdict

from .config import DEFAULT, Config
from .encoder import constant_pool, encode
from .parser import parse_file
from .program import Program


def assemble(path: str, outdir: str | None = None, config: Config = DEFAULT,
             mode: str = "serial") -> dict:
    """Parse, encode and write the three files (and `<stem>.pool.hex` when the
    program has constants too wide for the 24-bit immediate).

    Returns {"hex": path, "lst": path, "json": path, "words": n}.  Raises only
    SourceError for a bad program (OSError if outdir cannot be written).
    """
    if mode == "parallel":            # two images, partition report: bitbyte.partition
        from .partition import assemble_parallel
        return assemble_parallel(path, outdir, config)
    program = parse_file(path, config)
    words, listing_text = encode(program, config, mode)
    pool = constant_pool(program)
    stem = os.path.splitext(os.path.basename(path))[0]
    outdir = outdir if outdir is not None else (os.path.dirname(path) or ".")
    os.makedirs(outdir, exist_ok=True)
    paths = {ext: os.path.join(outdir, f"{stem}.{ext}") for ext in ("hex", "lst", "json")}
    _write(paths["hex"], hex_image(words))
    _write(paths["lst"], listing_text)
    _write(paths["json"], json.dumps(summary(program, words, config), indent=2) + "\n")
    if pool:
        paths["pool"] = os.path.join(outdir, f"{stem}.pool.hex")
        _write(paths["pool"], hex_image(pool))
    return {**paths, "words": len(words)}


def hex_image(words: list[int]) -> str:
    """`$readmemh` text: one word per line, 8 hex digits, address 0 first."""
    return "".join(f"{w:08X}\n" for w in words)


def summary(program: Program, words: list[int], config: Config) -> dict:
    """The JSON side file: sizes, symbols (name -> address), labels (name -> addr)."""
    return {
        "source": program.path,
        "words": len(words),
        "config": asdict(config),
        "symbols": {name: op.address() for name, op in program.symbols.items()},
        "labels": dict(program.labels),
    }


def _write(path: str, text: str) -> None:
    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write(text)
