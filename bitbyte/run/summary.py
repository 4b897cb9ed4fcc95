"""The run summary printed by `bitbyte run` (same layout as the C++ harness prints)."""
from __future__ import annotations

from fractions import Fraction

from bitbyte.lang.trace import ScanRecord, format_decimal, format_t_us


def summary_text(records: list[ScanRecord], clock_mhz: Fraction,
                 trace_path: str | None = None, stalls: tuple[int, int] = (0, 0)) -> str:
    lines = [f"{'scans':<17}{len(records)}"]
    if records:
        cycles = [r.cycles for r in records]
        lo, hi = min(cycles), max(cycles)
        mean = Fraction(sum(cycles), len(cycles))
        lines.append(f"{'cycles/scan':<17}min {lo}  mean {format_decimal(mean, 3)}  max {hi}")
        us = [format_t_us(c, clock_mhz) for c in (lo, hi)]
        mean_us = format_decimal(mean / clock_mhz)
        lines.append(f"{'scan time [us]':<17}min {us[0]}  mean {mean_us}  max {us[1]}"
                     f"  (clock {format_decimal(clock_mhz)} MHz)")
    lines.append(f"{'stalls':<17}bit side {stalls[0]}, byte side {stalls[1]}")
    end = records[-1].end_clock if records else 0
    lines.append(f"{'simulated':<17}{format_t_us(end, clock_mhz)} us, {end} clocks")
    if trace_path:
        lines.append(f"{'trace':<17}{trace_path}")
    return "\n".join(lines) + "\n"
