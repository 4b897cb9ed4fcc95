"""A plant's copy plans as the plan RAM of each core sequencer holds them (rtl/core_seq.v,
docs/multicore.md), the sequencer's period unit, and what the plant hardware holds.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

from bitbyte.lang.definition import DEF
from bitbyte.lang.errors import SourceError
from bitbyte.lang.program import Operand
from bitbyte.lang.trace import parse_address
from bitbyte.plant.link import Copy, SharedMap

MAX_CORES = DEF.plant["max_cores"]        # plants this release builds a harness for
PLAN_WORDS = DEF.plant["plan_words"]      # rtl/plc_system.v PlanWords
SHARED_WORDS = DEF.plant["shared_words"]  # rtl/plc_system.v SharedWords (per ping-pong buffer)


class PlantRunError(Exception):
    """A plant the hardware cannot hold (too many cores, plan or shared words)."""


def descriptor(writer: int) -> int:
    return (1 << 31) | ((writer & 0xFF) << 16)


def item_word(kind: str, word: int, bit: int | None, local: Operand) -> int:
    is_bit = kind == "bit"
    loc = local.bit_number if is_bit else local.index
    return ((int(is_bit) << 30) | (((bit or 0) & 31) << 25) | ((word & 0x1FFF) << 12)
            | (loc & 0xFFF))


@dataclass
class CorePlanWords:
    """One core's plan RAM image and the sequencer's three lengths."""
    words: list[int] = field(default_factory=list)
    pre_len: int = 0
    post_base: int = 0
    post_len: int = 0


def encode_plans(shared_map: SharedMap) -> list[CorePlanWords]:
    """Every core's copy plan as plan-RAM words, precycle first."""
    index = {c.name.upper(): i for i, c in enumerate(shared_map.cores)}

    def writer_of(copy: Copy) -> int:
        return index[shared_map.var(copy.items[0].name).writer.upper()]

    def encode(copies: list[Copy]) -> list[int]:
        out: list[int] = []
        for copy in copies:
            out.append(descriptor(writer_of(copy)))
            for it in copy.items:
                local = parse_address(it.local)
                out.append(item_word(it.kind, it.word, it.bit, local))
        return out

    plans = []
    for plan in shared_map.cores:
        pre, post = encode(plan.precycle), encode(plan.postcycle)
        if len(pre) + len(post) > PLAN_WORDS:
            raise SourceError(shared_map.plant.path, 0, 0,
                              f"core {plan.name}: copy plan of {len(pre) + len(post)} "
                              f"entries exceeds the plan RAM ({PLAN_WORDS} entries)")
        plans.append(CorePlanWords(pre + post, len(pre), len(pre), len(post)))
    return plans


def period_clocks(period_us: int, clock_mhz: Fraction) -> int:
    """The period in thousandths of a clock, as the core sequencer takes it: exact,
    since the clock is a whole number of kHz (scan k starts in the first clock at or
    after k * period_us)."""
    milli = Fraction(period_us) * clock_mhz * 1000
    assert milli.denominator == 1, "clock_mhz is a whole number of kHz"
    return int(milli)
