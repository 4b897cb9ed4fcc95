"""The independent oracle for `.awl` sources (spec §9): awlsim (PyPI `awlsim`, pinned in
requirements.txt, GPL-2.0, used as a test tool from the registry and never copied into
the tree) runs an S7 program scan by scan, and `bitbyte run` runs the same file; the
helpers here put both into one shape so that tests compare them scan for scan.

awlsim is driven as its own `awlsim-test` drives it: `Project.fromProjectOrRawAwlFile`,
`AwlParser` per source, `AwlSim.load`, `build`, `startup` (OB 100 runs there, at
time 0), then one `runCycle()` per scan.  Before each cycle the scan's input bytes
are written into the process image (`cpu.storeInputByte`), and scan 0's before
`startup` too (awlsim's own `AwlSim.startup` reads the hardware inputs before OB
100, as `runCycle` does before OB 1); simulated time replaces
`cpu.updateTimestamp`, so that `cpu.now` is each scan's latch time (seconds since
reset), never the wall clock.  After each cycle the output image and the marker bytes
are read back.

A scan of either simulator becomes {"Q0.0": 0/1, ..., "M1.7": 0/1}: the bits of the
output bytes and marker bytes asked for.
"""
from __future__ import annotations

from pathlib import Path

from tracecmp import transitions

BITS = range(8)


def signed16(value: int) -> int:
    return value - 0x10000 if value & 0x8000 else value


def word_of(image, n: int) -> int:
    """S7's word n of a byte image: bytes n (high) and n+1 (low), signed."""
    return signed16((image.get(n, 0) << 8) | image.get(n + 1, 0))


def scan_inputs_csv(inputs: list[dict[int, int]], in_bytes: int,
                    in_words: tuple[int, ...] = ()) -> str:
    """A `scan`-keyed STIM.csv (spec §4) for per-scan input bytes {byte: value}; the
    input words IW n of `in_words` are made of bytes n and n+1 as in S7."""
    names = [f"I{b}.{n}" for b in range(in_bytes) for n in BITS]
    names += [f"IW{n}" for n in in_words]
    rows = ["scan," + ",".join(names)]
    for k, image in enumerate(inputs):
        cells = [str((image.get(b, 0) >> n) & 1) for b in range(in_bytes) for n in BITS]
        cells += [str(word_of(image, n)) for n in in_words]
        rows.append(f"{k}," + ",".join(cells))
    return "\n".join(rows) + "\n"


def byte_numbers(count) -> tuple[int, ...]:
    """Bytes 0..count-1 for an int, or the byte numbers given (out_bytes=(4, 5))."""
    return tuple(range(count)) if isinstance(count, int) else tuple(count)


def columns_of(out_bytes, marker_bytes, words: tuple[str, ...] = ()) -> list[str]:
    return ([f"Q{b}.{n}" for b in byte_numbers(out_bytes) for n in BITS]
            + [f"M{b}.{n}" for b in byte_numbers(marker_bytes) for n in BITS]
            + list(words))


def awlsim_scans(path: str | Path, inputs: list[dict[int, int]], *, mnemonics: str,
                 out_bytes=2, marker_bytes=2, words: tuple[str, ...] = (),
                 scan_times_s: list[float] | None = None, timers: tuple[int, ...] = (),
                 symbols: str | Path | None = None) -> list[dict[str, int]]:
    """Run `path` in awlsim for len(inputs) scans; mnemonics "de" or "en"; `words`
    ("QW2", "MW10") are read as S7 words (bytes n and n+1) of the output image and
    the marker area; out_bytes / marker_bytes: a count (bytes 0..n-1) or the byte
    numbers; `timers` adds "@T n", the status of timer n after the cycle, and
    "@T n<", as at the scan's latch (not compared: stimuli for timer programs are
    made with them); `symbols`: a STEP 7 .asc symbol table, loaded as awlsim loads
    one (SymTabParser, loadSymbolTable)."""
    from awlsim.common.cpuconfig import S7CPUConfig
    from awlsim.common.project import Project
    from awlsim.core.main import AwlSim
    from awlsim.awlcompiler.tokenizer import AwlParser

    project = Project.fromProjectOrRawAwlFile(str(path))
    sim = AwlSim()
    sim.reset()
    cpu = sim.getCPU()
    cpu.getConf().setConfiguredMnemonics(
        {"de": S7CPUConfig.MNEMONICS_DE, "en": S7CPUConfig.MNEMONICS_EN}[mnemonics])
    if symbols is not None:
        from awlsim.core.symbolparser import SymTabParser
        sim.loadSymbolTable(SymTabParser.parseText(
            Path(symbols).read_text(encoding="cp1252"), mnemonics={
                "de": S7CPUConfig.MNEMONICS_DE, "en": S7CPUConfig.MNEMONICS_EN}[mnemonics]))
    for src in project.getAwlSources():
        parser = AwlParser()
        parser.parseSource(src)
        sim.load(parser.getParseTree())
    sim.build()
    clock = {"now": 0.0}

    def update_timestamp(*_args):
        cpu.now = clock["now"]

    cpu.updateTimestamp = update_timestamp
    for b, value in (inputs[0] if inputs else {}).items():
        cpu.storeInputByte(b, value)            # OB 100 sees scan 0's inputs
    sim.startup()
    scans = []
    for k, image in enumerate(inputs):
        clock["now"] = scan_times_s[k] if scan_times_s else 0.0
        for b in range(max(image, default=-1) + 1):
            cpu.storeInputByte(b, image.get(b, 0))
        cpu.now = clock["now"]
        at_latch = {n: cpu.getTimer(n).get() for n in timers}
        left = {n: cpu.getTimer(n).remaining for n in timers}   # (get(): at the latch)
        sim.runCycle()
        markers = cpu.flags.getDataBytes()
        row = {}
        for b in byte_numbers(out_bytes):
            value = cpu.fetchOutputByte(b)
            row.update({f"Q{b}.{n}": (value >> n) & 1 for n in BITS})
        for b in byte_numbers(marker_bytes):
            row.update({f"M{b}.{n}": (markers[b] >> n) & 1 for n in BITS})
        for name in words:
            n = int(name[2:])
            if name.startswith("QW"):
                image = {b: cpu.fetchOutputByte(b) for b in (n, n + 1)}
            else:
                image = {b: markers[b] for b in (n, n + 1)}
            row[name] = word_of(image, n)
        for n in timers:
            row[f"@T{n}"] = cpu.getTimer(n).get()
            row[f"@T{n}<"] = at_latch[n]            # as the scan's first read sees it
            row[f"@R{n}"] = cpu.getTimer(n).remaining   # s left (after get(): now)
            row[f"@R{n}<"] = left[n]                    # ... as at the scan's latch
        scans.append(row)
    return scans


def bitbyte_scans(path: str | Path, inputs: list[dict[int, int]], tmp: Path, *,
                  sim: str = "ref", mode: str = "serial", in_bytes: int = 2,
                  out_bytes=2, marker_bytes=2, words: tuple[str, ...] = (),
                  in_words: tuple[int, ...] = (), clock_mhz: str = "100",
                  mnemonics: str | None = None, symbols: str | Path | None = None,
                  exchange: str | None = None,
                  watchdog: int = 100_000) -> list[dict[str, int]]:
    """`bitbyte run` on `path` (sim "ref": the reference interpreter; "verilator":
    the C++ harness; exchange: parallel mode's, its default when None; watchdog:
    `--watchdog`, in clocks), one row per scan with the same keys as
    awlsim_scans."""
    from bitbyte.lang.config import Config
    from bitbyte.lang.stimulus import load_stimulus
    from bitbyte.ref.refsim import refsim_trace
    from bitbyte.run.prepare import prepare_run

    stim = tmp / (Path(path).stem + ".stim.csv")
    stim.write_text(scan_inputs_csv(inputs, in_bytes, in_words))
    watch = columns_of(out_bytes, marker_bytes, words)
    program, columns, job, f = prepare_run(
        str(path), stimulus=str(stim), watch=",".join(watch), scans=len(inputs),
        mode=mode, exchange=exchange, mnemonics=mnemonics, clock_mhz=clock_mhz,
        symbols=None if symbols is None else str(symbols), watchdog=watchdog)
    if sim == "ref":
        assert mode == "serial", "the reference interpreter runs serial mode"
        stimulus = load_stimulus(str(stim), program.symbols)
        _, records, fault = refsim_trace(program, Config(clock_mhz=float(f)), stimulus,
                                         watch, scans=len(inputs), watchdog=watchdog)
    else:
        from bitbyte.sim.verilator import run_harness
        records, fault, _ = run_harness(job, columns)
    assert not fault, f"{path}: watchdog"
    # LATCH: the scan's latch time in s (awlsim's cpu.now); scan 0 latches at 0, or
    # after the startup scan (OB 100), which awlsim runs at 0
    rows, latch = [], records[0].end_clock - records[0].cycles if records else 0
    for rec in records:
        rows.append({name: rec.values[name] for name in watch} | {LATCH: latch / f / 1e6})
        latch = rec.end_clock
    return rows


LATCH = "@latch_s"


# Where bitbyte runs a program: (sim, mode, exchange) of bitbyte_scans.  SERIAL_REF
# is the reference interpreter; EVERY_RUN adds the Verilator harness in serial mode
# and in parallel mode (the partitioning compiler's bit and byte parts running
# concurrently) with each of its exchanges, the handshake flip-flops and the queues.
SERIAL_REF = (("ref", "serial", None),)
EVERY_RUN = SERIAL_REF + (("verilator", "serial", None),
                          ("verilator", "parallel", "handshake"),
                          ("verilator", "parallel", "queue"))


def run_name(sim: str, mode: str, exchange: str | None) -> str:
    return f"{sim} {mode}" + (f" ({exchange})" if exchange else "")


def equal_or_rejected(seed: int, path: Path, lang: str, inputs, tmp: Path, *,
                      words: tuple[str, ...], in_words: tuple[int, ...],
                      runs=SERIAL_REF) -> bool:
    """A random program: True when its scans equal awlsim's in every run of `runs`
    (asserted; the message names the run that differs), False when the front end
    rejects it — only ever as `unsupported:` (asserted)."""
    from bitbyte.lang.errors import SourceError
    from tracecmp import first_difference

    expected = None
    for sim, mode, exchange in runs:
        try:
            got = bitbyte_scans(path, inputs, tmp, words=words, in_words=in_words,
                                sim=sim, mode=mode, exchange=exchange)
        except SourceError as e:
            assert expected is None, (seed, sim, mode, str(e))   # the first run rejects
            assert e.message.startswith("unsupported:"), (seed, str(e))
            return False
        if expected is None:
            expected = awlsim_scans(path, inputs, mnemonics=lang, words=words)
        diff = first_difference(expected, got)
        assert diff is None, (f"seed {seed} ({path}) differs from awlsim on "
                              f"{run_name(sim, mode, exchange)}: {diff}")
    return True


def timer_equal_or_rejected(seed: int, path: Path, lang: str, inputs, tmp: Path, *,
                            timers: tuple[int, ...], runs=SERIAL_REF,
                            values: dict[str, tuple[int, int, bool]] | None = None
                            ) -> bool:
    """equal_or_rejected for a timer program (timer_scans): every transition within
    one scan of awlsim's (awlsim at each run's own latch times); `values`: the time
    value words (`L T n`, `LC T n`), compared by tracecmp.time_value_difference."""
    from bitbyte.lang.errors import SourceError
    from tracecmp import time_value_difference, transition_difference

    values = values or {}
    for n, (sim, mode, exchange) in enumerate(runs):
        try:
            expected, got, _ = timer_scans(path, inputs, tmp, mnemonics=lang,
                                           timers=timers, sim=sim, mode=mode,
                                           exchange=exchange, words=tuple(values))
        except SourceError as e:
            assert n == 0, (seed, sim, mode, str(e))
            assert e.message.startswith("unsupported:"), (seed, str(e))
            return False
        diff = time_value_difference(expected, got, values)
        assert diff is None, (f"seed {seed} ({path}) time value differs from awlsim "
                              f"on {run_name(sim, mode, exchange)}: {diff}")
        expected, got = ([{c: v for c, v in row.items() if c not in values}
                          for row in rows] for rows in (expected, got))
        # (bitbyte's timers run on the latch time in whole ms, awlsim's on the
        # latch time in s: a transition may come a scan early or late)
        diff = transition_difference(expected, got, slack=1)
        assert diff is None, (f"seed {seed} ({path}) differs from awlsim on "
                              f"{run_name(sim, mode, exchange)}: {diff}")
    return True


def latch_times(rows: list[dict[str, int]]) -> list[float]:
    """The scans' latch times (s) of a bitbyte_scans result, for awlsim's cpu.now."""
    return [float(row[LATCH]) for row in rows]


def timer_busy(rows: list[dict[str, int]]) -> set[int]:
    """The scans within one scan of a transition of a timer's status ("@T n")."""
    busy = set()
    for column in rows[0]:
        if column.startswith("@T"):
            for k, _ in transitions(rows, column):
                busy |= {k - 1, k, k + 1}
    return busy


def quiet_inputs(inputs: list[dict[int, int]], busy: set[int]) -> list[dict[int, int]]:
    """`inputs` with every change that falls in a `busy` scan put off until after
    it.  Spec §9 lets a timer's transition come a scan late; an input that changes
    in that scan too would make a one-scan pulse in one simulator and none in the
    other, which no "within one scan" comparison can match."""
    out, current = [], inputs[0]
    for k, image in enumerate(inputs):
        if k not in busy:
            current = image
        out.append(current)
    return out


def timer_scans(path, inputs, tmp, *, mnemonics: str, timers: tuple[int, ...],
                clock_mhz: str = "0.02", words: tuple[str, ...] = (),
                in_words: tuple[int, ...] = (), quiet: bool = True, out_bytes=2,
                marker_bytes=2, awlsim_path=None, **kw):
    """(awlsim's rows, bitbyte's rows, the inputs used) for a timer program: awlsim
    runs at bitbyte's latch times, the inputs kept quiet around awlsim's timer
    transitions (quiet_inputs; the busy scans only grow, so this settles), unless
    `quiet` is False (hand-written stimuli that keep clear of them by design);
    `awlsim_path`: the file awlsim runs, when it is not `path` itself."""
    busy: set[int] = set()
    for _ in range(12):
        stimulus = quiet_inputs(inputs, busy)
        got = bitbyte_scans(path, stimulus, tmp, clock_mhz=clock_mhz, words=words,
                            in_words=in_words, out_bytes=out_bytes,
                            marker_bytes=marker_bytes, **kw)
        expected = awlsim_scans(awlsim_path or path, stimulus, mnemonics=mnemonics,
                                words=words, scan_times_s=latch_times(got), timers=timers,
                                out_bytes=out_bytes, marker_bytes=marker_bytes)
        grown = busy | timer_busy(expected) if quiet else busy
        if grown == busy:
            break
        busy = grown
    return expected, got, stimulus
