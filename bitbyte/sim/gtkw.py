"""The waveform layout of a run (spec §4, issue 17): `bitbyte run ... --waves W.fst`
also writes W.gtkw, a GTKWave save file in the program's own names.

What a PLC engineer sees when GTKWave opens it:
* Scan: the scan count, the scan controller's state by name, latch and scan end;
* Program: the instruction in the bit processor's execute stage as `line: source`
  (a translate filter on its program counter), the RLO, and in serial mode whether a
  byte instruction is with the byte processor;
* Inputs, Outputs, Markers, Timers / counters, Words: every declared symbol, and every
  address the program uses without a symbol, as its own named signal — GTKWave aliases
  onto bits of the image vectors (`+{name} (k)vector`), words combined from 16 bits
  (`#{name} ...`), markers from the marker RAM's words (traced: sim/trace.vlt);
* a first view from the latch of scan 0 over a few whole scans (with an S7 OB 100:
  after the startup scan, which the scan row shows as `startup`, and hardware scan
  n + 1 as the trace's scan n: a translate filter, W.scan.txt).

GTKWave silently drops a signal its file does not have, so every name is checked
against the wave file's own signal list (read_signal_names) before it is written;
WaveLayoutError names the first that is missing. The translate filter files sit
beside W.gtkw (W.state.txt, W.instr.txt)."""
from __future__ import annotations

import math
import re
import subprocess
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path

from bitbyte.lang.program import Instr, Operand, Program, display_text

ROOT = Path(__file__).resolve().parents[2]
CPU = "TOP.bitbyte_cpu"
SCAN_CTRL_V = ROOT / "rtl" / "scan_ctrl.v"

# GTKWave trace flags (the `@` lines): right-justified binary, hex, decimal; +0x2000
# runs the value through the current translate filter; group open / close.
BIN, DEC, SIGNED_DEC = "@28", "@24", "@424"
DEC_FILTERED = "@2024"
GROUP_OPEN, GROUP_CLOSE = "@800200", "@1000200"

WAVE_AREA_PX = 880          # the wave pane of a [size] 1400 x 900 window
SCANS_IN_FIRST_VIEW = 4
# GTKWave's zoom z shows 2**-z / ZOOM_PS_PER_PX_SCALE ps per pixel (measured under
# Xvfb: at z = -30, 1 ms is 191 px; at z = -20, 1 us is 195 px).
ZOOM_PS_PER_PX_SCALE = 204.8


class WaveLayoutError(Exception):
    """A signal the layout needs is not in the wave file."""


# --- the wave file's own signal list -----------------------------------------------

def read_signal_names(wave_file: str | Path) -> set[str]:
    """Every signal of an FST or VCD file as GTKWave names it: scope path, name, and
    the bit range of a vector (`TOP.bitbyte_cpu.pii[127:0]`); an array word traced
    as its own signal keeps its index (`...u_marker_ram.mem.mem[5]`)."""
    path = Path(wave_file)
    if path.suffix == ".vcd":
        with path.open(errors="replace") as f:      # the header only, streamed
            return _vcd_header_names(f)
    proc = subprocess.Popen(["fst2vcd", "-f", str(path)], stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL, text=True)
    lines = []
    assert proc.stdout is not None
    for line in proc.stdout:                 # the header only: stop at its end
        lines.append(line)
        if "$enddefinitions" in line:
            break
    proc.kill()
    proc.wait()
    return _vcd_header_names(lines)


def _vcd_header_names(lines) -> set[str]:
    names, scope = set(), []
    for line in lines:
        words = line.split()
        if not words:
            continue
        if words[0] == "$scope":
            scope.append(words[2])
        elif words[0] == "$upscope":
            scope.pop()
        elif words[0] == "$var":
            width, name = int(words[2]), words[4]
            rng = words[5] if len(words) > 6 and words[5].startswith("[") else ""
            full = ".".join(scope + [name])
            names.add(full + rng if width > 1 else full)
        elif words[0] == "$enddefinitions":
            break
    return names


# --- translate filters --------------------------------------------------------------

def scan_states(scan_ctrl_v: Path = SCAN_CTRL_V) -> dict[int, str]:
    """The scan controller's state codes and names, read from its localparams
    (`localparam [1:0] StRun = 2'd2;` -> 2: run): one place for the encoding."""
    states = {}
    for m in re.finditer(r"localparam\s*\[[^\]]*\]\s*St(\w+)\s*=\s*\d+'d(\d+)\s*;",
                         scan_ctrl_v.read_text()):
        states[int(m.group(2))] = m.group(1).lower()
    return states


def instruction_text(instr: Instr | str) -> str:
    """`line: source text` of an instruction (bitbyte.lang.program.display_text); a
    text as it is (a wide image's LUT word: bitbyte/wide/link.py wave_listing)."""
    return instr if isinstance(instr, str) else f"{instr.line}: {display_text(instr)}"


def filter_text(rows: dict[int, str]) -> str:
    """A GTKWave translate filter: the value as the decimal trace shows it, then the
    text to show instead."""
    return "".join(f"{value} {text}\n" for value, text in sorted(rows.items()))


# --- the layout ---------------------------------------------------------------------

@dataclass
class Layout:
    """A .gtkw being written: its lines, the signals it names, the filter files."""
    signals: set[str]
    lines: list[str] = field(default_factory=list)
    named: list[str] = field(default_factory=list)      # every signal the layout names
    filters: dict[str, str] = field(default_factory=dict)  # file name -> contents

    def need(self, signal: str) -> str:
        if signal not in self.signals:
            raise WaveLayoutError(f"the wave file has no signal {signal}")
        self.named.append(signal)
        return signal

    def group(self, title: str, rows: list[str]) -> None:
        if rows:
            self.lines += [GROUP_OPEN, f"-{title}", *rows, GROUP_CLOSE, f"-{title}"]

    def trace(self, fmt: str, signal: str, alias: str | None = None) -> list[str]:
        name = self.need(signal)
        return [fmt, f"+{{{alias}}} {name}" if alias else name]

    def vector(self, vector: str) -> tuple[str, int]:
        """The wave file's `vector[msb:0]` and its width (the build's size)."""
        for name in self.signals:
            m = re.fullmatch(re.escape(vector) + r"\[(\d+):0\]", name)
            if m:
                self.named.append(name)
                return name, int(m.group(1)) + 1
        raise WaveLayoutError(f"the wave file has no signal {vector}[..:0]")

    def bit(self, vector: str, index: int, alias: str) -> list[str]:
        """Bit `index` of a vector (GTKWave counts exploded bits from the most
        significant one)."""
        name, width = self.vector(vector)
        if index >= width:
            raise WaveLayoutError(f"{alias}: bit {index} is beyond {name}")
        return [BIN, f"+{{{alias}}} ({width - 1 - index}){name}"]

    def word(self, vector: str, index: int, alias: str) -> list[str]:
        """16-bit word `index` of a vector of words, shown as signed decimal."""
        name, width = self.vector(vector)
        if 16 * index + 15 >= width:
            raise WaveLayoutError(f"{alias}: word {index} is beyond {name}")
        bits = " ".join(f"({width - 1 - (16 * index + b)}){name}" for b in range(15, -1, -1))
        return [SIGNED_DEC, f"#{{{alias}}} {bits}"]

    def filtered(self, signal: str, alias: str, filter_name: str, rows: dict[int, str],
                 filter_dir: Path) -> list[str]:
        name = self.need(signal)
        self.filters[filter_name] = filter_text(rows)
        return [DEC_FILTERED, f"^1 {filter_dir / filter_name}", f"+{{{alias}}} {name}"]


def _operands(program: Program) -> list[tuple[str, Operand]]:
    """(name, operand): every declared symbol (as declared), then every address the
    program uses without a symbol, each operand once."""
    out: list[tuple[str, Operand]] = []
    seen: set[tuple] = set()

    def key(op: Operand) -> tuple:
        return (op.kind, op.area, op.bit_number if op.kind == "bit" else op.index)

    for upper, op in program.symbols.items():
        if op.kind in ("bit", "index") and key(op) not in seen:
            seen.add(key(op))
            out.append((program.symbol_names.get(upper, upper), op))
    for instr in program.instrs:
        op = instr.operand
        if op is not None and op.kind in ("bit", "index") and key(op) not in seen:
            seen.add(key(op))
            out.append((op.address(), op))
    return out


# The image vector each bit area is shown from: the PII and its edge flags, the pins
# as the CPU reads them (PI: read directly; after the force table), the output pins
# (what the PIO update drives, after the force table) and the output unit's edge flags
# of the last PIO update (QR / QF: the unit's own pins, before the force table).
BIT_VECTORS = {"I": "pii", "PI": "in_pins", "IR": "rise", "IF": "fall",
               "Q": "out_pins_o", "PQ": "out_pins_o", "QR": "q_rise", "QF": "q_fall"}
OUTPUT_AREAS = ("Q", "PQ", "QR", "QF")


def scan_names(startup_scans: int, hardware_scans: int) -> dict[int, str]:
    """The scan count's translate filter where a program has startup scans (OB 100,
    bitbyte.run.startup): hardware scans 0 .. startup_scans - 1 are `startup`, hardware
    scan n the trace's scan n - startup_scans."""
    return {n: "startup" if n < startup_scans else str(n - startup_scans)
            for n in range(hardware_scans + 1)}


def _cpu_groups(lay: Layout, cpu: str, program: Program, listing: list[Instr | str], *,
                serial: bool, stem: str, filter_dir: Path, title: str = "",
                mw_ram: str | None = None, hardware_scans: int = 0) -> None:
    """One CPU's groups (its scope `cpu`): Scan, Program, then its operands by kind;
    titles prefixed with `title` (a plant's core name). mw_ram: the scope of the word
    RAM holding MW n (a plant core's), else MW is the byte processor's memory;
    hardware_scans: how many scans the run's waves hold (the scan row's names with a
    startup scan)."""
    bp = f"{cpu}.u_bit_proc"
    pre = f"{title}: " if title else ""
    scan_signal = f"{cpu}.scan_count_o[31:0]"
    lay.group(f"{pre}Scan", [
        *(lay.filtered(scan_signal, f"{pre}scan", f"{stem}.scan.txt",
                       scan_names(program.startup_scans, hardware_scans), filter_dir)
          if program.startup_scans else lay.trace(DEC, scan_signal, f"{pre}scan")),
        *lay.filtered(f"{cpu}.u_scan_ctrl.state_q[1:0]", f"{pre}scan state",
                      f"{stem}.state.txt", scan_states(), filter_dir),
        *lay.trace(BIN, f"{cpu}.latch", f"{pre}latch (PII)"),
        *lay.trace(BIN, f"{cpu}.scan_done_o", f"{pre}scan done (PIO)"),
        *lay.trace(BIN, f"{cpu}.fault_o", f"{pre}watchdog fault"),
    ])
    # the instruction executing: in execute, or in the wait slot while it waits there
    # for the byte side (bit_proc's exec_pc_o / exec_valid_o)
    program_rows = [
        *lay.filtered(f"{cpu}.exec_pc[11:0]", f"{pre}executing", f"{stem}.instr.txt",
                      {pc: instruction_text(i) for pc, i in enumerate(listing)}, filter_dir),
        *lay.trace(BIN, f"{cpu}.exec_valid", f"{pre}executing valid"),
        *lay.trace(BIN, f"{cpu}.rlo", f"{pre}RLO"),
    ]
    if serial:      # a byte instruction dispatched to the byte processor, until DONE
        program_rows += lay.trace(BIN, f"{cpu}.byte_req", f"{pre}byte busy")
    lay.group(f"{pre}Program", program_rows)

    kinds: dict[str, list[str]] = {k: [] for k in
                                   ("Inputs", "Outputs", "Markers", "Timers / counters",
                                    "Words", "Not in the waves")}
    for name, op in _operands(program):
        alias = name if name == op.address() else f"{name} {op.address()}"
        alias = f"{pre}{alias}"
        if op.kind == "bit" and op.area in BIT_VECTORS:
            group = "Outputs" if op.area in OUTPUT_AREAS else "Inputs"
            kinds[group] += lay.bit(f"{cpu}.{BIT_VECTORS[op.area]}", op.bit_number, alias)
        elif op.kind == "bit" and op.area == "M":
            kinds["Markers"] += lay.trace(
                BIN, f"{bp}.u_marker_ram.mem.mem[{op.bit_number}]", alias)
        elif op.kind == "index" and op.area in ("T", "C"):
            vec = f"{cpu}.{'timer' if op.area == 'T' else 'counter'}_status"
            kinds["Timers / counters"] += lay.bit(vec, op.index, alias)
        elif op.kind == "index" and op.area in ("IW", "QW"):
            vec = f"{cpu}.{'in_words_i' if op.area == 'IW' else 'out_words_o'}"
            kinds["Words"] += lay.word(vec, op.index, alias)
        elif op.kind == "index" and op.area == "MW" and mw_ram is not None:
            kinds["Words"] += lay.trace(SIGNED_DEC, f"{mw_ram}.mem.mem[{op.index}][15:0]", alias)
        else:                                   # MW: the byte processor's memory
            kinds["Not in the waves"].append(f"-{alias}: byte processor memory (--watch)")
    for kind, rows in kinds.items():
        lay.group(f"{pre}{kind}", rows)


def _write(lay: Layout, gtkw_path: Path, wave_file, what: str, filter_dir: Path,
           clock_mhz: Fraction, t0_ps: int | None, view_clocks: int | None) -> None:
    """The header (the first view: from t0_ps over view_clocks), the groups, the
    filter files."""
    header = [f"[*] {what}: waveform layout written by bitbyte run",
              f"[*] open with: gtkwave {wave_file} {gtkw_path}",
              f"[dumpfile] \"{Path(wave_file).resolve()}\"",
              "[size] 1400 900", "[signals_width] 320", "[sst_width] 200",
              "[sst_expanded] 0"]
    if t0_ps is not None:
        header.append(f"[timestart] {t0_ps}")
        ps = (view_clocks or 400) * Fraction(1_000_000, 1) / clock_mhz
        zoom = -math.log2(float(ps) / WAVE_AREA_PX * ZOOM_PS_PER_PX_SCALE)
        header.append(f"*{zoom:.6f} {t0_ps} -1")
    gtkw_path.write_text("\n".join(header + lay.lines) + "\n")
    for fname, text in lay.filters.items():
        (filter_dir / fname).write_text(text)


def write_gtkw(gtkw_path: str | Path, wave_file: str | Path, program: Program,
               listing: list[Instr | str], *, serial: bool, clock_mhz: Fraction,
               t0_ps: int | None, scan_clocks: int | None,
               hardware_scans: int = 0) -> list[str]:
    """Write the layout (and its filter files) for a run; returns the signals it names.

    listing: the bit processor's program memory, word by word (serial mode: the whole
    program; parallel mode: the bit part; the wide build: its image, a LUT word as a
    text); t0_ps: the waveform time of scan 0's latch
    (clock 0, or after the startup scan of an OB 100); scan_clocks: a typical scan's
    length (the first view shows a few); hardware_scans: the scans the waves hold,
    the startup scans included (the scan row's names)."""
    gtkw_path = Path(gtkw_path)
    stem = gtkw_path.name.removesuffix(".gtkw")
    filter_dir = gtkw_path.resolve().parent
    lay = Layout(read_signal_names(wave_file))
    _cpu_groups(lay, CPU, program, listing, serial=serial, stem=stem, filter_dir=filter_dir,
                hardware_scans=hardware_scans)
    _write(lay, gtkw_path, wave_file, Path(program.path).name, filter_dir, clock_mhz, t0_ps,
           (scan_clocks or 100) * SCANS_IN_FIRST_VIEW)
    return lay.named


PLANT = "TOP.plc_system"


def core_seq_states(core_seq_v: Path = ROOT / "rtl" / "core_seq.v") -> dict[int, str]:
    """A plant core's sequencer states (seed 000 Fig. 8), from its localparams
    (`localparam [2:0] StPreLock = 3'd1;` -> 1: pre lock)."""
    states = {}
    for m in re.finditer(r"localparam\s*\[[^\]]*\]\s*St(\w+)\s*=\s*\d+'d(\d+)\s*;",
                         core_seq_v.read_text()):
        states[int(m.group(2))] = re.sub(r"(?<!^)([A-Z])", r" \1", m.group(1)).lower()
    return states


def write_plant_gtkw(gtkw_path: str | Path, wave_file: str | Path,
                     cores: list[tuple[str, Program, list[Instr], bool]], *,
                     clock_mhz: Fraction, view_clocks: int) -> list[str]:
    """A plant's layout (spec §7): the plant (time, the semaphore and its owner by core
    name, each core's sequencer state by name), then per core its CPU's groups with the
    project's symbols (shared variables among them; MW from the core's word RAM).
    cores: (name, program, its bit processor's listing, serial mode?) as write_gtkw."""
    gtkw_path = Path(gtkw_path)
    stem = gtkw_path.name.removesuffix(".gtkw")
    filter_dir = gtkw_path.resolve().parent
    lay = Layout(read_signal_names(wave_file))
    names = {i: core[0] for i, core in enumerate(cores)}
    rows = [*lay.trace(DEC, f"{PLANT}.time_o[63:0]", "plant clock"),
            *lay.trace(BIN, f"{PLANT}.locked_o", "semaphore locked")]
    owner = f"{PLANT}.lock_owner_o"        # a vector from three cores on
    owner = lay.need(owner) if owner in lay.signals else lay.vector(owner)[0]
    rows += [DEC_FILTERED, f"^1 {filter_dir / (stem + '.owner.txt')}",
             f"+{{lock owner}} {owner}"]
    lay.filters[f"{stem}.owner.txt"] = filter_text(names)
    for i, name in names.items():
        rows += lay.filtered(f"{PLANT}.g_core[{i}].u_core.u_seq.state_q[2:0]",
                             f"{name}: sequencer", f"{stem}.seq.txt", core_seq_states(),
                             filter_dir)
    lay.group("Plant", rows)
    for i, (name, program, listing, serial) in enumerate(cores):
        core = f"{PLANT}.g_core[{i}].u_core"
        _cpu_groups(lay, f"{core}.u_cpu", program, listing, serial=serial,
                    stem=f"{stem}.{name}", filter_dir=filter_dir, title=name,
                    mw_ram=f"{core}.u_mw_ram")
    _write(lay, gtkw_path, wave_file, "plant " + ", ".join(names.values()), filter_dir,
           clock_mhz, 0, view_clocks)
    return lay.named
