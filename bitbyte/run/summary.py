"""The run summary `bitbyte run` prints, for every simulator: the Verilator harness
reports its figures as `stat NAME VALUE` lines (sim/README.md), the cocotb driver in
its results; both become a RunStats, and this one printer writes the text."""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from bitbyte.lang.definition import DEF
from bitbyte.lang.trace import ScanRecord, format_decimal, format_t_us
from bitbyte.run.response import Responses


@dataclass(frozen=True)
class RunStats:
    """What a run reports besides its trace rows."""
    clocks: int                                  # clocks simulated since clock 0
    stalls: tuple[int, int] = (0, 0)             # (bit side, byte side) clocks waiting
    byte_scans: int | None = None                # free-running: the byte side's scans
    queue_losses: tuple[int, int] | None = None  # queue-free: QUEUE_OVERFLOWS, _UNDERFLOWS
    byte_flags: int = 0                          # BYTE_FLAGS (bb_flags())
    # the Verilator harness: T_ENABLE and C_PULSE (64 bits each) after the last scan
    tc_inputs: tuple[int, int] | None = None
    wall_s: float | None = None                  # the simulator's own run time
    wave_t0_ps: int | None = None                # with waves: the waveform time of clock 0
    block_status: dict | None = None             # --status: address -> Retired
    byte_status: dict | None = None              # ... of the byte part (parallel mode)
    # --line-counts: address -> how often it retired in the whole run (the bit
    # processor's program; the byte part's in parallel and free-running mode)
    line_counts: dict | None = None
    byte_line_counts: dict | None = None
    # the startup scans (an S7 source's OB 100, bitbyte.run.startup): how many the
    # program has, and the clocks of each the run completed (a watchdog fault in one
    # leaves fewer); they are no scans of the trace, but the watchdog times them
    startup_scans: int = 0
    startup_cycles: tuple[int, ...] = ()

    def fault_in_startup(self) -> bool:
        """Whether a watchdog fault of this run stopped a startup scan."""
        return len(self.startup_cycles) < self.startup_scans


@dataclass(frozen=True)
class Retired:
    """The block status of one program address in the chosen scan (bitbyte run
    --status): how often it retired, and at its last retirement the RLO after it, the
    operand bit it read, the byte processor's ACCU1 / ACCU2 after it. The wide engine's
    lines inside a unit (LUT words) have no RLO or operand of their own ("–"), and a
    unit of no word no count (None)."""
    count: int | None
    rlo: int | str
    operand: int | str
    accu1: int
    accu2: int


def parse_block_status(stdout: str, key: str = "status") -> dict[int, Retired]:
    """A harness's `status PC COUNT RLO OPERAND ACCU1 ACCU2` lines (sim/README.md), or
    its byte part's `bstatus PC COUNT RLO ACCU1 ACCU2` (operand 0)."""
    out = {}
    for line in stdout.splitlines():
        words = line.split()
        if words and words[0] == key and len(words) in (6, 7):
            pc, count, rlo, *rest = (int(w) for w in words[1:])
            operand = rest[0] if len(rest) == 3 else 0
            out[pc] = Retired(count, rlo, operand, rest[-2], rest[-1])
    return out


def parse_line_counts(stdout: str, key: str = "count") -> dict[int, int]:
    """A harness's `count PC N` lines, or the byte part's `bcount PC N` (sim/README.md)."""
    out = {}
    for line in stdout.splitlines():
        words = line.split()
        if len(words) == 3 and words[0] == key:
            out[int(words[1])] = int(words[2])
    return out


def parse_stats(stdout: str) -> dict[str, float]:
    """A harness's `stat NAME VALUE` lines (sim/README.md)."""
    stats = {}
    for line in stdout.splitlines():
        words = line.split()
        if len(words) == 3 and words[0] == "stat":
            stats[words[1]] = float(words[2]) if "." in words[2] else int(words[2])
    return stats


STARTUP_SCAN = "the startup scan (OB 100)"


def fault_scan_name(fault_scan: int, stats: RunStats) -> str:
    """The scan a watchdog fault stopped, in words: `scan N`, or the startup scan."""
    return STARTUP_SCAN if stats.fault_in_startup() else f"scan {fault_scan}"


def _label(name: str) -> str:
    return f"{name:<17}"


def summary_text(records: list[ScanRecord], clock_mhz: Fraction, stats: RunStats,
                 trace_path: str | None = None, waves: tuple[str, str] | None = None,
                 response: Responses | None = None, watchdog: int | None = None,
                 fault_scan: int | None = None) -> str:
    """waves: (the wave file, the GTKWave layout); response: bitbyte.run.response's
    figures, printed when an input changed; watchdog: the limit in clocks (its margin
    against the longest scan is printed); fault_scan: the scan the watchdog stopped."""
    mhz = format_decimal(clock_mhz)
    lines = [_label("scans") + str(len(records))]
    if records:
        cycles = [r.cycles for r in records]
        lo, hi = min(cycles), max(cycles)
        mean = Fraction(sum(cycles), len(cycles))
        lines.append(_label("cycles/scan") + f"min {lo}  mean {format_decimal(mean, 3)}  max {hi}")
        us = [format_t_us(c, clock_mhz) for c in (lo, hi)]
        lines.append(_label("scan time [us]") + f"min {us[0]}  mean "
                     f"{format_decimal(mean / clock_mhz)}  max {us[1]}  (clock {mhz} MHz)")
        lines.append(_label("scan histogram") + histogram(cycles))
    if stats.startup_cycles:
        lines.append(_label("startup scan") + f"(OB 100) {max(stats.startup_cycles)} clocks "
                     "(before scan 0, not a scan of the trace)")
    if watchdog is not None and fault_scan is not None:
        lines.append(_label("watchdog") + f"limit {watchdog} clocks: exceeded in "
                     f"{fault_scan_name(fault_scan, stats)} (the run stopped there)")
    elif watchdog is not None and records:
        longest = max(r.cycles for r in records)
        startup = max(stats.startup_cycles, default=0)
        lines.append(_label("watchdog") + watchdog_margin(
            max(longest, startup), watchdog,
            ("the startup scan, OB 100" if startup > longest else "an OB 1 scan")
            if stats.startup_cycles else None))
    else:
        lines += [_label("cycles/scan") + "-", _label("scan time [us]") + f"-  (clock {mhz} MHz)"]
    lines.append(_label("stalls") + f"bit side {stats.stalls[0]}, byte side {stats.stalls[1]}")
    if response is not None and response.changes:
        lines += _response_lines(response, clock_mhz)
    if stats.byte_scans is not None:
        lines.append(_label("byte side") + f"{stats.byte_scans} scans (free-running)")
    if stats.queue_losses is not None:
        f = dict(DEF.register("QUEUE_OVERFLOWS").fields)   # UNDERFLOWS: the same layout
        mask, shift = f["QUEUE_TO_BYTE_MASK"], f["QUEUE_TO_BIT_SHIFT"]
        ovf, unf = stats.queue_losses
        lines.append(_label("queue losses") + f"overflows to-byte {ovf & mask} to-bit "
                     f"{ovf >> shift}, underflows to-byte {unf & mask} to-bit {unf >> shift}")
    flags = [f"{f['name']} ({f['doc']})" for f in DEF.byte_flag_rows
             if stats.byte_flags >> f["bit"] & 1]
    if flags:
        lines.append(_label("byte flags") + ", ".join(flags))
    simulated = f"{format_t_us(stats.clocks, clock_mhz)} us, {stats.clocks} clocks"
    if stats.wall_s is not None:
        rate = stats.clocks / stats.wall_s / 1e6 if stats.wall_s > 0 else 0.0
        simulated += f", {rate:.{1 if rate >= 1 else 3}f} M clocks/s wall"
    lines.append(_label("simulated") + simulated)
    if trace_path:
        lines.append(_label("trace") + str(trace_path))
    if waves:
        lines.append(_label("waves") + f"{waves[0]}   (gtkwave {waves[0]} {waves[1]})")
    return "\n".join(lines) + "\n"


HISTOGRAM_BINS = 8


def histogram(cycles: list[int]) -> str:
    """Scans per scan length in clocks: one bin per value when there are at most
    HISTOGRAM_BINS distinct lengths, else HISTOGRAM_BINS bins of equal integer width
    from the shortest scan (`lo-hi count`, empty bins left out)."""
    values = sorted(set(cycles))
    if len(values) <= HISTOGRAM_BINS:
        bins = [(v, v, cycles.count(v)) for v in values]
    else:
        lo, hi = values[0], values[-1]
        width = -(-(hi - lo + 1) // HISTOGRAM_BINS)
        counts = [0] * HISTOGRAM_BINS
        for c in cycles:
            counts[(c - lo) // width] += 1
        bins = [(lo + i * width, min(hi, lo + (i + 1) * width - 1), n)
                for i, n in enumerate(counts) if n]
    return "[clk] " + " | ".join((f"{a}" if a == b else f"{a}-{b}") + f": {n}"
                                 for a, b, n in bins)


def watchdog_margin(longest: int, limit: int, which: str | None = None) -> str:
    """How far the longest scan stayed below the scan watchdog (spec §4); which: the
    scan that was longest, where a program has a startup scan (timed as any scan)."""
    margin = limit - longest
    which = f" ({which})" if which else ""
    return (f"limit {limit} clocks, longest scan {longest}{which}: margin {margin} clocks "
            f"({format_decimal(Fraction(100 * margin, limit), 1)} %)")


def _response_lines(response: Responses, clock_mhz: Fraction) -> list[str]:
    """min / median (the mean of the middle two for an even count) / max, in clocks
    (a t_us change may fall between clock edges: a fraction) and in µs; where only
    the first changes were measured, how many and why; none: why."""
    clocks, changes = response.clocks, response.changes
    if response.not_measured:
        return [_label("response [clk]") + f"{response.not_measured} ({changes} input "
                f"change{'s' if changes != 1 else ''})"]
    of = (f"the first {response.measured} of {changes}" if response.measured is not None
          else str(changes))
    count = (f"({len(clocks)} of {of} input changes changed an output"
             + (f"; {response.stopped})" if response.measured is not None else ")"))
    if not clocks:
        return [_label("response [clk]") + "-  " + count, _label("response [us]") + "-"]
    s = sorted(clocks)
    mid = len(s) // 2
    median = s[mid] if len(s) % 2 else (s[mid - 1] + s[mid]) / 2
    figures = (s[0], median, s[-1])

    def three(xs) -> str:
        return "  ".join(f"{name} {format_decimal(x)}"
                         for name, x in zip(("min", "median", "max"), xs))
    return [_label("response [clk]") + three(figures) + "  " + count,
            _label("response [us]") + three(x / clock_mhz for x in figures)]


def hw_mode_text(parallel: int, exchange: int) -> str:
    """A plant core's mode label from what the harness drove on plc_system's
    parallel_i / exchange_i (read back at the end of the run): `serial`, or
    `parallel/handshake` with the exchange (DEF.exchanges' code)."""
    if not parallel:
        return "serial"
    name = DEF.exchanges[exchange] if exchange < len(DEF.exchanges) else f"#{exchange}"
    return f"parallel/{name}"


def plant_summary_text(protection: str, clock_hz: int, clocks: int,
                       cores: list[tuple[str, str, list[dict[str, str]], int]],
                       waves: tuple[str, str] | None = None) -> str:
    """A plant run (spec §7): cores = (name, its mode as the harness drove it (hw_mode_text), its trace
    rows as csv.DictReader gives them, skips_o at its last traced scan); the other
    figures are the rows' (pre, post, sem_wait, overrun, copy_fail: the trace header
    of bitbyte.plant.run)."""
    def us(clocks_num: int, n: int = 1) -> str:
        return format_decimal(Fraction(clocks_num * 1_000_000, n * clock_hz))

    out = [_label("plant") + f"{len(cores)} cores, protection {protection}, clock "
           f"{format_decimal(Fraction(clock_hz, 1_000_000))} MHz"]
    for name, mode, rows, skips in cores:
        line = f"core {name:<11} {mode}, scans {len(rows)}"
        if rows:
            cyc = [int(r["cycles"]) for r in rows]
            lo, hi, total = min(cyc), max(cyc), sum(cyc)
            line += (f", cycles min {lo} mean {format_decimal(Fraction(total, len(cyc)), 3)}"
                     f" max {hi}, scan time [us] min {us(lo)} mean {us(total, len(cyc))} max "
                     f"{us(hi)}, pre max {max(int(r['pre']) for r in rows)}, post max "
                     f"{max(int(r['post']) for r in rows)}, sem_wait "
                     f"{sum(int(r['sem_wait']) for r in rows)}")
        # over the traced scans (the run goes on until every core has finished)
        line += (f", overruns {sum(int(r['overrun']) for r in rows)}, skipped precycles "
                 f"{skips}, copy_fail {rows[-1]['copy_fail'] if rows else 0}")
        out.append(line)
    out.append(_label("simulated") + f"{us(clocks)} us, {clocks} clocks")
    if waves:
        out.append(_label("waves") + f"{waves[0]}   (gtkwave {waves[0]} {waves[1]})")
    return "\n".join(out) + "\n"
