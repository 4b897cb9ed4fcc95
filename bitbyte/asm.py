"""`bitbyte asm`: one source file -> program image, listing and a JSON summary.

Writes, beside the source or into outdir, `<stem>.hex` (one 8-digit hex word per
line, address 0 first: the `$readmemh` format), `<stem>.lst` (the listing) and
`<stem>.json` ({"source", "words", "config", "symbols", "labels", "startup_scans"}).  With
mode="parallel" the program is partitioned first (bitbyte.compiler) and the files are
those of assemble_parallel (`<stem>.bit.hex`, `<stem>.byte.hex`, ...).
Nothing is written when the program has an error: the SourceError propagates to the caller
(the CLI prints it with `format_error` and exits non-zero).
"""
from __future__ import annotations

import json
import os
from dataclasses import asdict

from bitbyte.lang.config import DEFAULT, Config
from bitbyte.encoding.encoder import constant_pool, encode, encode_words
from bitbyte.lang.errors import UsageError
from bitbyte.lang.parser import parse_file
from bitbyte.compiler.estimate import estimate
from bitbyte.compiler.partition import partition
from bitbyte.compiler.report import part_listing, report_text, side_by_side
from bitbyte.lang.program import Program


def assemble(path: str, outdir: str | None = None, config: Config = DEFAULT,
             mode: str = "serial", lang: str | None = None,
             mnemonics: str | None = None, symbols: str | None = None,
             tc_path: str = "channel", bit_engine: str = "scalar",
             profile: str | None = None) -> dict:
    """Parse, encode and write the three files (and `<stem>.pool.hex` when the
    program has constants too wide for the 24-bit immediate).

    Returns {"hex": path, "lst": path, "json": path, "words": n, "program": the
    parsed Program}.  Raises only
    SourceError for a bad program (OSError if outdir cannot be written).
    """
    if bit_engine == "wide":
        return assemble_wide(path, outdir, config, mode, profile, lang=lang,
                             mnemonics=mnemonics, symbols=symbols)
    if mode == "parallel":            # two images and the partition report
        return assemble_parallel(path, outdir, config, lang=lang, mnemonics=mnemonics,
                                 symbols=symbols, tc_path=tc_path)
    program = parse_file(path, config, lang=lang, mnemonics=mnemonics, symbols=symbols)
    words, listing_text = encode(program, config, mode)
    pool = constant_pool(program)
    out = _output_dir(path, outdir)
    paths = {ext: out(ext) for ext in ("hex", "lst", "json")}
    _write(paths["hex"], hex_image(words))
    _write(paths["lst"], _with_startup_line(listing_text, program))
    _write(paths["json"], json.dumps(summary(program, words, config), indent=2) + "\n")
    if pool:
        paths["pool"] = out("pool.hex")
        _write(paths["pool"], hex_image(pool))
    return {**paths, "words": len(words), "program": program}


def assemble_wide(path: str, outdir: str | None, config: Config, mode: str,
                  profile: str | None, **parse_kw) -> dict:
    """`bitbyte asm --bit-engine wide` (issue 18, docs/wide-engine.md): the program
    split into units, each compiled into LUT words (Yosys's ABC), relinked into the
    wide image (bitbyte/wide/link.py): `<stem>.hex` (base words), `<stem>.ext.hex`
    (extension words), `<stem>.lst`, `<stem>.json` (with the map from wide addresses
    to source instructions). Serial mode only so far; the wide engine is an ECP5
    build (docs/wide-rtl-plan.md §5): a profile for a smaller part is refused."""
    from bitbyte.wide import link as wide_link
    from bitbyte.wide.model import compile_program
    if mode != "serial":
        raise UsageError("--bit-engine wide: serial mode only so far (the parallel "
                         "mode's bit part is not yet compiled for it: docs/wide-engine.md)")
    if profile is not None:
        raise UsageError(f"--bit-engine wide with --profile {profile}: the wide engine "
                         "is built for the ECP5-25 at the default sizes only "
                         "(docs/wide-rtl-plan.md §5)")
    program = parse_file(path, config, **parse_kw)
    encode_words(program, config, mode)     # the scalar checks (SourceError at the line)
    image = wide_link.link(program, compile_program(program), config)
    pool = constant_pool(program)
    out = _output_dir(path, outdir)
    paths = {ext: out(ext) for ext in ("hex", "ext.hex", "lst", "json")}
    _write(paths["hex"], hex_image(image.base))
    _write(paths["ext.hex"], wide_link.hex_ext(image.ext))
    _write(paths["lst"], _with_startup_line(wide_link.listing(image, config), program))
    _write(paths["json"], json.dumps({**summary(program, image.base, config),
                                      **wide_link.summary(image)}, indent=2) + "\n")
    if pool:
        paths["pool"] = out("pool.hex")
        _write(paths["pool"], hex_image(pool))
    return {"hex": paths["hex"], "ext_hex": paths["ext.hex"], "lst": paths["lst"],
            "json": paths["json"], **({"pool": paths["pool"]} if pool else {}),
            "words": len(image.base), "program": program, "image": image}


def _output_dir(path: str, outdir: str | None):
    """`ext -> <outdir>/<stem>.<ext>` for the source at path (outdir made; default: beside
    the source)."""
    stem = os.path.splitext(os.path.basename(path))[0]
    outdir = outdir if outdir is not None else (os.path.dirname(path) or ".")
    os.makedirs(outdir, exist_ok=True)
    return lambda ext: os.path.join(outdir, f"{stem}.{ext}")


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
        "startup_scans": program.startup_scans,
    }


def startup_line(program: Program) -> str:
    """The listing's line on the startup scans (an S7 OB 100), or nothing."""
    if not program.startup_scans:
        return ""
    return (f"; startup scans: {program.startup_scans} (OB 100, from OB100: to OB100.END: "
            "below: the hardware's first scan, before scan 0; no scan of the trace)\n")


def _with_startup_line(text: str, program: Program) -> str:
    """`text` with startup_line after its header comment lines."""
    lines = text.splitlines(keepends=True)
    n = next((i for i, line in enumerate(lines) if not line.startswith(";")), len(lines))
    return "".join(lines[:n]) + startup_line(program) + "".join(lines[n:])


def _write(path: str, text: str) -> None:
    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write(text)


def assemble_parallel(path: str, outdir: str | None = None, config: Config = DEFAULT,
                      channels: int | None = None, lang: str | None = None,
                      mnemonics: str | None = None, symbols: str | None = None,
                      tc_path: str = "channel") -> dict:
    """Parse, partition, encode, write (stem = the source's name without .il):

      <stem>.bit.hex        bit part image ($readmemh, one 8-digit word per line)
      <stem>.byte.hex       byte part image (the firmware's bb_load_program words)
      <stem>.pool.hex       the byte part's constant pool, only when it has one
      <stem>.lst            report, side-by-side view, both parts address by address
      <stem>.partition.txt  report and side-by-side view
      <stem>.json           {"source", "mode", "channels", "config", "symbols",
                             "bit_words", "byte_words", "bit_labels", "byte_labels",
                             "transfers", "mirrored_jumps", "estimate",
                             "startup_scans"}

    Returns {"bit_hex", "byte_hex", ["pool"], "lst", "report", "json": paths,
    "words": bit words, "byte_words": byte words, "program": the parsed Program}.  Nothing is written on an error."""
    program = parse_file(path, config, lang=lang, mnemonics=mnemonics, symbols=symbols)
    part = partition(program, channels or config.channels, config=config, tc_path=tc_path)
    report = report_text(part)
    view = side_by_side(part)
    out = _output_dir(path, outdir)
    paths = {key: out(ext) for key, ext in (
        ("bit_hex", "bit.hex"), ("byte_hex", "byte.hex"), ("lst", "lst"),
        ("report", "partition.txt"), ("json", "json"))}
    _write(paths["bit_hex"], hex_image(part.bit_words))
    _write(paths["byte_hex"], hex_image(part.byte_words))
    if part.pool:
        paths["pool"] = out("pool.hex")
        _write(paths["pool"], hex_image(part.pool))
    _write(paths["report"], report + "\n" + view)
    _write(paths["lst"], _with_startup_line(report + "\n" + view + part_listing(part),
                                            program))
    est = estimate(part)
    summary = {
        "source": program.path, "mode": "parallel", "channels": part.channels,
        "hand_partitioned": part.hand_partitioned, "config": asdict(config),
        "symbols": {name: op.address() for name, op in program.symbols.items()},
        "bit_words": len(part.bit_words), "byte_words": len(part.byte_words),
        "bit_labels": part.bit_labels, "byte_labels": part.byte_labels,
        "transfers": [asdict(t) for t in part.transfers],
        "mirrored_jumps": [program.instrs[i].line for i in part.mirrored],
        "estimate": asdict(est),
        "startup_scans": program.startup_scans,
    }
    _write(paths["json"], json.dumps(summary, indent=2) + "\n")
    return {**paths, "words": len(part.bit_words), "byte_words": len(part.byte_words),
            "program": program}
