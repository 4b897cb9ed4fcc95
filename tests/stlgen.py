"""Random S7 statement-list programs (OB 1, bit logic) for the awlsim comparison.

Each program is German or English throughout and exercises what the S7 front end
must get right: first-check strings (every network starts a fresh string with
U/UN/O/ON/X/XN, and `=`/`S`/`R`, SET/CLR, jumps end one), `O` without operand (AND
before OR, also as the very first statement of a string, where it does nothing),
nesting `U(`/`UN(`/`O(`/`ON(`/`X(`/`XN(` ... `)` up to three deep, X after `O`,
FP/FN in the middle of a string, NOT, forward jumps SPA/SPB/SPBN (JU/JC/JCN) to a
label on a later network, BEB (BEC); word networks: L of words (IW/QW/MW, German
EW/AW/MW) and constants (INT, W#16#, B#16#, S5T#, C#), +I -I *I /I, T, and the
compares ==I <>I >I <I >=I <=I (also after a logic string and after `O`, and with the
string going on after them), L/T in the middle of a string; counter networks: ZV ZR
(CU CD), S Z with C# and W#16# BCD values (near 999 too), R Z, `L Z n`, and `U Z n` in
strings.  With timers=True (time-keyed programs, no words, no counters, no jumps):
the S7 timers SI SV SE SS SA (SP SE SD SS SF) with S5T# and W#16# presets, R T, and their
status read in strings.  A few programs contain what the front end rejects
(NOT after `O` in a string, a jump target reached with different /FC): the test
expects `unsupported:` for those, never a silent difference.

With calls=True (tests/test_stl_calls.py, soak/test_stl_soak.py): FC 1, FC 2 and FB 1
with DB 1 and DB 2, whose bodies are random networks over their `#name`s, called from
OB 1 with CALL / UC / CC, and jump lists SPL (JL) with their SPA (JU) lists.

random_program(seed) -> (source text, language); random_inputs(seed, scans) -> the
input bytes 0 and 1 per scan.
"""
from __future__ import annotations

import random
import re

COMBINES = {"de": ["U", "UN", "O", "ON", "X", "XN"], "en": ["A", "AN", "O", "ON", "X", "XN"]}
OPENS = {"de": ["U(", "UN(", "O(", "ON(", "X(", "XN("],
         "en": ["A(", "AN(", "O(", "ON(", "X(", "XN("]}
AREA = {"de": {"I": "E", "Q": "A", "M": "M"}, "en": {"I": "I", "Q": "Q", "M": "M"}}
JUMPS = {"de": ["SPA", "SPB", "SPBN"], "en": ["JU", "JC", "JCN"]}
# Words: input words on input bytes 2..5, output words and data words apart from the
# bytes the bit operands use (S7's IW/QW/MW n is bytes n and n+1).
IN_WORDS = (2, 4)
WORDS = ("QW2", "QW4", "MW10", "MW12", "MW14")
WORD_AREA = {"de": {"IW": "EW", "QW": "AW", "MW": "MW"},
             "en": {"IW": "IW", "QW": "QW", "MW": "MW"}}
# Timers: German SI SV SE SS SA = English SP SE SD SS SF (S7's pulse, extended pulse,
# on-delay, retentive on-delay, off-delay).
TIMER_KINDS = {"de": ["SI", "SV", "SE", "SS", "SA"], "en": ["SP", "SE", "SD", "SS", "SF"]}
PRESETS_MS = (0, 50, 70, 100, 150, 200)   # 0, or five scans and more (below)
COUNTER = {"de": "Z", "en": "C"}
UP_DOWN = {"de": ("ZV", "ZR"), "en": ("CU", "CD")}
ARITH = ["+I", "-I", "*I", "/I"]
COMPARE = ["==I", "<>I", ">I", "<I", ">=I", "<=I"]
# DINT (docs/s7.md, DINT): S7's MOD is the DINT remainder; MD 10 / MD 12 are the
# watched words MW10+MW12 / MW12+MW14
ARITH_D = ["+D", "-D", "*D", "/D", "MOD"]
COMPARE_D = ["==D", "<>D", ">D", "<D", ">=D", "<=D"]
DOUBLES = (10, 12)
# word logic (German UW/UD are English AW/AD) and shifts; counts around the widths
LOGIC_W = {"de": ["UW", "OW", "XOW"], "en": ["AW", "OW", "XOW"]}
LOGIC_D = {"de": ["UD", "OD", "XOD"], "en": ["AD", "OD", "XOD"]}
SHIFT_W = ["SLW", "SRW", "SSI"]
SHIFT_D = ["SLD", "SRD", "SSD", "RLD", "RRD"]
SHIFT_COUNTS = (0, 1, 3, 15, 16, 17, 31, 32, 40, 255)
# S7's status bits CC 1 / CC 0 (docs/s7.md, Status bits)
CC_CONDITIONS = ("==0", "<>0", ">0", "<0", ">=0", "<=0", "UO")
CC_JUMPS = {"de": ["SPZ", "SPN", "SPP", "SPM", "SPPZ", "SPMZ", "SPU"],
            "en": ["JZ", "JN", "JP", "JM", "JPZ", "JMZ", "JUO"]}


class Gen:
    def __init__(self, seed: int, words: bool = True, timers: bool = False,
                 calls: bool = False):
        self.r = random.Random(seed)
        self.seed = seed
        self.calls = calls
        self.jump_lists = calls         # (programs without calls stay as they were)
        self.local_bits: list[str] = []     # `#name`s a body in a block may read ...
        self.local_out: list[str] = []      # ... and write
        self.local_words: list[str] = []
        self.local_word_out: list[str] = []
        self.lang = self.r.choice(("de", "en"))
        self.words = words
        self.counters = words           # (programs keyed by scan)
        self.timer_kind: dict[int, str] = {}
        if timers:
            for n in self.r.sample(range(1, 6), self.r.randrange(1, 4)):
                self.timer_kind[n] = self.r.choice(TIMER_KINDS[self.lang])
        self.preset = {n: self.r.choice(PRESETS_MS) for n in self.timer_kind}
        self.network_timer = min(self.timer_kind, default=0)
        self.timer_nets: set[int] = set()
        self.edge_memories = 0
        # Timer programs read inputs and timers only: with no feedback through Q and
        # M, no output oscillates from scan to scan, whose phase a timer's edge
        # (allowed to come a scan late, spec §9) would turn round.
        self.read_areas = "I" if timers else "IQM"
        self.reads_timers = True
        self.lines: list[str] = []
        self.label = ""                 # put before the next statement
        self.edge_memory = ""           # a block's own edge memory (FB: `#edge`)
        self.prefix_labels = ""

    def addr(self, areas: str = "IQM") -> str:
        r = self.r
        pool = self.local_out if areas in ("QM", "M") else self.local_bits
        if pool and r.random() < 0.5:
            return r.choice(pool)
        area = r.choice(areas)
        spaced = r.random() < 0.7
        name = AREA[self.lang][area]
        # timer programs write M byte 0 only: M byte 1 holds the edge memories
        byte = 0 if self.timer_kind and area == "M" and areas != "M" else r.randrange(2)
        return f"{name}{' ' if spaced else ''}{byte}.{r.randrange(8)}"

    def emit(self, text: str) -> None:
        self.lines.append(self.label + "\t" + text)
        self.label = ""

    def word(self, areas: str = "IQM") -> str:
        r = self.r
        pool = self.local_word_out if areas == "QM" else self.local_words
        if pool and r.random() < 0.5:
            return r.choice(pool)
        area = r.choice(areas) + "W"
        n = r.choice(IN_WORDS) if area == "IW" else int(r.choice(
            [w for w in WORDS if w.startswith(area)])[2:])
        return f"{WORD_AREA[self.lang][area]}{' ' if r.random() < 0.7 else ''}{n}"

    def value(self) -> str:
        """A load operand: a word or a constant of one of the S7 forms."""
        r = self.r
        x = r.random()
        if x < 0.55:
            return self.word()
        if x < 0.75:
            return str(r.choice((0, 1, 2, 3, 7, -1, -5, 100, 1000, 32767, -32768,
                                 r.randrange(-300, 300))))
        if x < 0.85:
            return f"W#16#{r.randrange(0x10000):04X}"
        if x < 0.9:
            return f"B#16#{r.randrange(256):02X}"
        if x < 0.95:
            return f"S5T#{r.choice(('10MS', '2S', '1M30S', '250MS', '2H'))}"
        return f"C#{r.randrange(1000)}"

    def loads(self) -> None:
        """L, L, then arithmetic: a value in ACCU1 and ACCU2."""
        r = self.r
        self.emit(f"L\t{self.value()}")
        self.emit(f"L\t{self.value()}")
        for _ in range(r.randrange(0, 3)):
            x = r.random()
            if x < 0.7 or self.local_words:
                self.emit(r.choice(ARITH))
            elif x < 0.85:                      # word logic, with ACCU2 or a constant
                self.emit(r.choice(LOGIC_W[self.lang])
                          + (f"\tW#16#{r.randrange(0x10000):04X}" if r.random() < 0.4 else ""))
            else:                               # a shift by a count or by ACCU2
                self.emit(r.choice(SHIFT_W) + (f"\t{r.choice(SHIFT_COUNTS)}"
                                               if r.random() < 0.7 else ""))
            if r.random() < 0.5:
                self.emit(f"L\t{self.value()}")

    def dint_value(self) -> None:
        """A DINT into ACCU1: a word or an INT made one by ITD, a DINT constant of
        one of the S7 forms, or a double word."""
        r = self.r
        x = r.random()
        if x < 0.4:
            self.emit(f"L\t{self.value()}")
            self.emit("ITD")
        elif x < 0.55:
            n = r.choice((0, 1, -1, 65536, 100000, -100000, 2**31 - 1, -2**31,
                          r.randrange(-2**31, 2**31)))
            self.emit(f"L\tL#{n}")
        elif x < 0.6:
            self.emit(f"L\tDW#16#{r.randrange(2**32):08X}")
        else:
            self.emit(f"L\tMD {r.choice(DOUBLES)}")

    def dint_network(self) -> None:
        """DINT arithmetic into a double word, or a DINT compare into bits."""
        r = self.r
        self.dint_value()
        self.dint_value()
        if r.random() < 0.5:
            x = r.random()
            if x < 0.6:
                self.emit(r.choice(ARITH_D))
            elif x < 0.8:
                self.emit(r.choice(LOGIC_D[self.lang])
                          + (f"\tDW#16#{r.randrange(2**32):08X}" if r.random() < 0.4 else ""))
            else:
                self.emit(r.choice(SHIFT_D) + (f"\t{r.choice(SHIFT_COUNTS)}"
                                               if r.random() < 0.7 else ""))
            for _ in range(r.randrange(0, 3)):   # ITD after a DINT: not a no-op
                self.emit(r.choice(("NEGD", "INVD", "ITD",
                                    f"+\tL#{r.randrange(-70000, 70000)}")))
            self.emit(f"T\tMD {r.choice(DOUBLES)}")
            return
        self.emit(r.choice(COMPARE_D))
        for _ in range(r.randrange(1, 3)):
            self.emit(f"{r.choice(('=', '=', 'S', 'R'))}\t{self.addr('QM')}")

    def word_network(self) -> None:
        r = self.r
        x = r.random()
        if 0.03 <= x < 0.25 and not self.local_words:
            self.dint_network()
            return
        if x < 0.03:
            self.emit(f"L\t{self.value()}")        # ACCU2 not loaded in this scan:
            self.emit(r.choice(ARITH + COMPARE))  # rejected
        elif x < 0.5:
            if r.random() < 0.4:                # a result whose status bits are read
                self.emit(f"L\t{self.value()}")
                self.emit(f"L\t{self.value()}")
                self.emit(r.choice(ARITH + COMPARE))
            else:
                self.loads()
            last = self.lines[-1].split("\t")[1].split()[0]
            self.emit(f"T\t{self.word('QM')}")
            if r.random() < 0.3:
                self.emit(f"T\t{self.word('QM')}")
            if last in ARITH + COMPARE + LOGIC_W[self.lang] + SHIFT_W and r.random() < 0.7:
                # the status bits of that result (T leaves them): a combine or a jump
                if r.random() < 0.7:
                    cond = self.overflow_bit(r.choice(CC_CONDITIONS))
                    self.emit(f"{r.choice(COMBINES[self.lang])}\t{cond}")
                    self.emit(f"=\t{self.addr('QM')}")
                else:
                    self.cc_labels = getattr(self, "cc_labels", 0) + 1
                    label = f"K{self.cc_labels}"
                    jump = self.overflow_bit(r.choice(CC_JUMPS[self.lang]))
                    self.emit(f"{jump}\t{label}")
                    self.emit(f"=\t{self.addr('QM')}")
                    self.label = f"{label}:"
                    self.emit(f"=\t{self.addr('QM')}")
            return
        else:
            if r.random() < 0.3:
                self.string(0)                  # a compare overwrites the RLO
                if r.random() < 0.3:
                    self.emit("O")
            self.loads()
            self.emit(r.choice(COMPARE))
            if r.random() < 0.3:
                self.item(0, opening=False)     # the string goes on (/FC = 1)
        for _ in range(r.randrange(1, 3)):
            self.emit(f"{r.choice(('=', '=', 'S', 'R'))}\t{self.addr('QM')}")

    def string(self, depth: int, first: bool = True) -> None:
        """A logic string: a first combine or parenthesis, then more items."""
        r = self.r
        if first and r.random() < 0.05:
            self.emit("O")                          # O at /FC = 0: no effect
        self.item(depth, opening=True)
        for _ in range(r.randrange(0, 6)):
            self.item(depth, opening=False)

    def item(self, depth: int, opening: bool) -> None:
        r = self.r
        x = r.random()
        if depth < 3 and x < 0.18:
            self.emit(r.choice(OPENS[self.lang]))
            self.string(depth + 1, first=False)
            self.emit(")")
        elif not opening and x < 0.30:
            self.emit("O")                          # AND before OR
        elif not opening and x < 0.33:
            memory = self.addr("M").replace("0.", "1.", 1)
            if memory.startswith("#"):
                memory = self.edge_memory or memory
            if self.timer_kind:         # one edge memory each (M 2.0 .. M 3.7): no
                k = self.edge_memories  # feedback through a shared one
                if k == 16:
                    return self.item(depth, opening)
                self.edge_memories += 1
                memory = f"M {2 + k // 8}.{k % 8}"
            self.emit(r.choice(("FP", "FN")) + " " + memory)
        elif not opening and x < 0.35:
            self.emit("NOT")
        elif self.counters and r.random() < 0.08:
            self.emit(f"{r.choice(COMBINES[self.lang])}\t{COUNTER[self.lang]} "
                      f"{r.randrange(1, 4)}")
        elif self.timer_kind and self.reads_timers and r.random() < 0.3:
            n = self.network_timer      # one timer per network: two, each a scan
            self.emit(f"{r.choice(COMBINES[self.lang])}\tT {n}")
        else:
            self.emit(f"{r.choice(COMBINES[self.lang])}\t{self.addr(self.read_areas)}")

    def timer_network(self) -> None:
        """An enable from inputs only (a timer started by another timer's status
        may come two scans late), the preset, the start; now and then `R T n`."""
        r = self.r
        n = self.free_timers.pop()
        kind = self.timer_kind[n]
        self.network_timer = n          # (a jump condition after it may read it)
        self.reads_timers = False
        self.string(0)
        ms = self.preset[n]
        if r.random() < 0.15:
            self.emit(f"L\tW#16#{int(str(ms // 10), 16):04X}")   # 10 ms time base
        else:
            self.emit(f"L\tS5T#{ms}MS")
        self.emit(f"{kind}\tT {n}")
        if kind not in ("SA", "SF") and len(self.lines) % 3 == 0:
            # FR from an input, by position (the random stream stays as it was)
            self.emit(f"{COMBINES[self.lang][0]}\t{AREA[self.lang]['I']} 1."
                      f"{len(self.lines) % 8}")
            self.emit(f"FR\tT {n}")
        if r.random() < 0.3:
            self.emit(f"=\t{self.addr('QM')}")             # the RLO is the enable
        if kind not in ("SA", "SF") and r.random() < 0.3:
            self.string(0)
            self.emit(f"R\tT {n}")
        self.reads_timers = True

    def counter_network(self) -> None:
        """ZV / ZR / S Z / R Z (CU / CD / S C / R C) on Z 1..3, each after a string
        of its own; presets C# near 999 (S7's counters stop there) or W#16# BCD."""
        r = self.r
        area = COUNTER[self.lang]
        for _ in range(r.randrange(1, 4)):
            n = r.randrange(1, 4)
            self.string(0)
            x = r.random()
            if x < 0.4:
                self.emit(f"{UP_DOWN[self.lang][0]}\t{area} {n}")
            elif x < 0.65:
                self.emit(f"{UP_DOWN[self.lang][1]}\t{area} {n}")
            elif x < 0.9:
                value = r.choice((0, 1, 5, 25, 997, 998, 999, r.randrange(1000)))
                self.emit(f"L\tC#{value}" if r.random() < 0.8
                          else f"L\tW#16#{int(str(value), 16):04X}")
                self.emit(f"S\t{area} {n}")
            else:
                self.emit(f"R\t{area} {n}")
        if self.words and r.random() < 0.5:
            self.emit(f"L\t{area} {r.randrange(1, 4)}")
            self.emit(f"T\tMW {r.choice((10, 12, 14))}")

    def network(self, n: int, labels: dict[int, str]) -> None:
        r = self.r
        self.lines.append(f"NETWORK\nTITLE = network {n}")
        if n in labels:
            self.label = f"{labels[n]}:"
        if n in self.timer_nets:
            self.timer_network()
            return
        if self.words and not self.timer_kind and not self.jump_lists and \
                len(self.lines) % 4 == 1:
            # OS at a network's start (after labels, jumps ...; not in programs with
            # calls, which clear it in S7: jump_lists is their flag, `calls` is off
            # inside the blocks' bodies), chosen by position: the random stream
            # stays as it was
            combine = COMBINES[self.lang][len(self.lines) // 4 % len(COMBINES[self.lang])]
            self.emit(f"{combine}\tOS")
            self.emit(f"=\t{AREA[self.lang]['M']}1.6")
        elif self.words and not self.timer_kind and len(self.lines) % 4 == 3:
            combine = COMBINES[self.lang][len(self.lines) // 4 % len(COMBINES[self.lang])]
            self.emit(f"{combine}\t{'BIE' if self.lang == 'de' else 'BR'}")
            self.emit(f"=\t{AREA[self.lang]['M']}1.5")
        if self.timer_kind:             # off, could make an edge two scans off
            self.network_timer = r.choice(sorted(self.timer_kind))
        if self.words and r.random() < 0.35:
            self.word_network()
            return
        if self.counters and r.random() < 0.2:
            self.counter_network()
            return
        if r.random() < 0.08:
            self.emit(r.choice(("SET", "CLR")))
        else:
            self.string(0)
            if self.words and r.random() < 0.1:
                self.emit(f"L\t{self.value()}")    # L / T inside a string
                self.emit(f"T\t{self.word('QM')}")
                self.item(0, opening=False)
        for _ in range(r.randrange(1, 3)):
            op = r.choice(("=", "=", "S", "R"))
            self.emit(f"{op}\t{self.addr('QM')}")
        if self.words and len(self.lines) % 5 == 0:
            self.emit("SAVE")           # BR := RLO (by position: the stream stays)

    def body(self, networks: int) -> None:
        r = self.r
        labels: dict[int, str] = {}
        jumps: dict[int, tuple[str, str]] = {}
        for n in range(networks - 1):
            # (timer programs too: their jumps make scans of different lengths, which
            # S7's timers do not see, as they run on the latch time; docs/s7.md)
            if r.random() < 0.25:
                target = r.randrange(n + 1, networks)
                name = labels.setdefault(target, f"M{target:03d}")
                jumps[n] = (r.choice(JUMPS[self.lang]), name)
                if self.words and self.jump_lists and r.random() < 0.3:
                    # a jump list: SPL (JL) with 1..3 SPA (JU) to later networks
                    entries = [labels.setdefault(t, f"M{t:03d}") for t in (
                        r.randrange(n + 1, networks) for _ in range(r.randrange(1, 4)))]
                    jumps[n] = ("JL", entries, name)
        for n in range(networks):
            if self.calls and r.random() < 0.4:
                self.lines.append(f"NETWORK\nTITLE = network {n}")
                if n in labels:
                    self.label = f"{labels[n]}:"
                self.call_network()
            else:
                self.network(n, labels)
            if n in jumps and jumps[n][0] == "JL":
                _, entries, default = jumps[n]
                self.emit(f"L\t{r.choice(('0', '1', '2', '3', '-255', '257'))}"
                          if r.random() < 0.5 else f"L\t{self.word()}")
                spa = JUMPS[self.lang][0]
                self.emit(f"{'SPL' if self.lang == 'de' else 'JL'}\tL{n:03d}")
                for entry in entries:
                    self.emit(f"{spa}\t{entry}")
                self.label = f"L{n:03d}:"
                self.emit(f"{spa}\t{default}")
            elif n in jumps:
                mnem, name = jumps[n]
                if r.random() < 0.3:
                    self.string(0)                  # a condition of its own
                self.emit(f"{mnem}\t{name}")
            elif r.random() < 0.05 and not self.timer_kind:
                self.string(0)
                self.emit("BEB" if self.lang == "de" else "BEC")

    def program(self) -> str:
        r = self.r
        networks = r.randrange(2, 7)
        if self.timer_kind:
            networks += 1
            # one start per timer: a timer started twice in a scan with other
            # enables restarts at each, and its phase drifts by that scan each time
            self.timer_nets = set(r.sample(range(networks), r.randrange(
                1, min(len(self.timer_kind), networks) + 1)))
            self.free_timers = sorted(self.timer_kind)
            r.shuffle(self.free_timers)
        blocks = self.blocks() if self.calls else []
        self.lines = ["ORGANIZATION_BLOCK OB 1", "TITLE = random", "VERSION : 0.1", "",
                      "BEGIN"]
        self.body(networks)
        if self.timer_kind:
            self.time_values()
        self.lines.append("END_ORGANIZATION_BLOCK")
        return "\n".join(blocks + self.lines) + "\n"

    def overflow_bit(self, choice: str) -> str:
        """Every third status read (or jump on the status bits) reads OV or OS
        instead (SPO / SPS, English JO / JOS), chosen by the program's length, not by
        the random stream, so that the programs stay as they were otherwise."""
        k = len(self.lines)
        if k % 3:
            return choice
        bit = ("OV", "OS")[k // 3 % 2]
        if choice in CC_CONDITIONS:
            return bit
        return {("de", "OV"): "SPO", ("de", "OS"): "SPS", ("en", "OV"): "JO",
                ("en", "OS"): "JOS"}[self.lang, bit]

    def time_values(self) -> None:
        """Timer programs: now and then `L T n` / `LC T n` of some timers into MW 20
        up, in a network before the first (the values at the latch) and after the
        last (after the scan's starts).  From a random stream of its own, so that the
        rest of a program stays what it was without them."""
        r = random.Random(self.seed * 31 + 7)
        if r.random() < 0.4:
            return
        word = iter(range(20, 60, 2))
        where = [self.lines.index("BEGIN") + 1, len(self.lines)]
        for at in reversed(where):
            if r.random() < 0.4:
                continue
            lines = ["NETWORK", "TITLE = time values"]
            for n in r.sample(sorted(self.timer_kind), r.randrange(
                    1, len(self.timer_kind) + 1)):
                for form in r.sample(("L", "LC"), r.randrange(1, 3)):
                    lines += [f"\t{form}\tT {n}", f"\tT\tMW {next(word)}"]
            self.lines[at:at] = lines

    # -- calls (calls=True) ---------------------------------------------------------

    def blocks(self) -> list[str]:
        """FC 1 (bit and word parameters, a TEMP), FC 2 (none: for UC/CC), FB 1
        (instance data: a static bit and word, an edge memory) with DB 1 and DB 2;
        their bodies made like OB 1's networks, reading and writing `#name`s."""
        r = self.r
        out = []
        specs = [
            ("FUNCTION FC 1 : VOID", "END_FUNCTION",
             [("VAR_INPUT", ["a : BOOL", "b : BOOL", "n : INT"]),
              ("VAR_OUTPUT", ["q : BOOL", "w : INT"]), ("VAR_TEMP", ["t : BOOL"])],
             ["#a", "#b", "#q", "#t"], ["#q", "#t"], ["#n", "#w"], ["#w"],
             [f"{COMBINES[self.lang][0]}\t#a", "=\t#t"]),
            ("FUNCTION FC 2 : VOID", "END_FUNCTION", [], [], [], [], [], []),
            ("FUNCTION_BLOCK FB 1", "END_FUNCTION_BLOCK",
             [("VAR_INPUT", ["en : BOOL", "k : INT"]),
              ("VAR_OUTPUT", ["out : BOOL", "cnt : INT"]),
              ("VAR", ["s : BOOL", "c : INT", "edge : BOOL"])],
             ["#en", "#s", "#out"], ["#s", "#out"], ["#k", "#c", "#cnt"],
             ["#c", "#cnt"],
             # the instance's state, visible in its outputs: `s` toggles at each
             # rising edge of `en`, `c` adds `k` at every call
             [f"{COMBINES[self.lang][0]}\t#en", "FP\t#edge", "X\t#s", "=\t#s",
              f"{COMBINES[self.lang][0]}\t#s", "=\t#out"]
             + (["L\t#c", "L\t#k", "+I", "T\t#c", "L\t#c", "T\t#cnt"]
                if self.words else [])),
        ]
        for head, end, sections, bits, outs, words, word_outs, prefix in specs:
            self.local_bits, self.local_out = bits, outs
            self.local_words = words if self.words else []
            self.local_word_out = word_outs if self.words else []
            self.edge_memory = "#edge" if "FB" in head else ""
            self.lines = [head]
            for name, decls in sections:
                self.lines += [name] + [f"  {d} ;" for d in decls] + ["END_VAR"]
            self.lines += ["BEGIN", "NETWORK", "TITLE = prefix"]
            for line in prefix:
                self.emit(line)
            saved = self.calls
            self.calls = False
            self.body(r.randrange(1, 4))
            self.calls = saved
            self.lines.append(end)
            out += self.lines + [""]
        self.local_bits, self.local_out, self.local_words, self.local_word_out = \
            [], [], [], []
        self.edge_memory = ""
        for db in (1, 2):
            out += [f"DATA_BLOCK DB {db}", "  FB 1", "BEGIN", "END_DATA_BLOCK", ""]
        return out

    def actual_word(self, out: bool) -> str:
        r = self.r
        if not out and r.random() < 0.4:
            return str(r.choice((0, 1, 5, -3, 100, 32767)))
        return self.word("QM" if out else "IQM")

    def call_network(self) -> None:
        """A CALL of FC 1, FB 1 with DB 1 or DB 2 (some parameters left out), or
        UC/CC FC 2; now and then a string before it (the RLO the callee starts with)
        and an assignment after it (the RLO it returns)."""
        r = self.r
        if r.random() < 0.3:
            self.string(0)
        x = r.random()
        if x < 0.4:
            word = self.words
            params = [f"a := {self.addr()}", f"b := {self.addr()}",
                      f"n := {self.actual_word(False) if word else 0}",
                      f"q := {self.addr('QM')}",
                      f"w := {self.actual_word(True) if word else 'MW 10'}"]
            self.emit(f"CALL\tFC 1 ({', '.join(params)})")
        elif x < 0.8:
            dbs = [r.choice((1, 2))] if r.random() < 0.4 else r.sample((1, 2), 2)
            for db in dbs:              # often both instances, in either order
                params = [f"en := {self.addr()}"]
                if r.random() < 0.7:
                    params.append(f"k := {self.actual_word(False)}")
                if r.random() < 0.9:
                    params.append(f"out := {self.addr('QM')}")
                if r.random() < 0.7:
                    params.append(f"cnt := {self.actual_word(True)}")
                r.shuffle(params)
                self.emit(f"CALL\tFB 1, DB {db} ({', '.join(params)})")
        else:
            self.emit(f"{r.choice(('UC', 'CC'))}\tFC 2")
        if r.random() < 0.4:
            self.emit(f"=\t{self.addr('QM')}")


def time_value_columns(text: str) -> dict[str, tuple[int, int, bool]]:
    """The time value words of a generated timer program (Gen.time_values): column
    -> (timer, time base ms: every preset here is in the 10 ms base, BCD)."""
    found = re.findall(r"^\t(LC?)\tT (\d+)\n\tT\tMW (\d+)$", text, re.M)
    return {f"MW{w}": (int(n), 10, form == "LC") for form, n, w in found}


def random_program(seed: int, words: bool = True, timers: bool = False,
                   calls: bool = False) -> tuple[str, str]:
    g = Gen(seed, words, timers, calls)
    return g.program(), g.lang


def slow_inputs(seed: int, scans: int) -> list[dict[int, int]]:
    """Input bytes 0 and 1 for timer programs: one bit flips now and then, so that
    timers run out between the changes as well as being cut short by them."""
    r = random.Random(seed * 7919 + 2)
    image = [r.randrange(256), r.randrange(256)]
    rows = []
    for _ in range(scans):
        rows.append({0: image[0], 1: image[1]})
        if r.random() < 0.2:
            image[r.randrange(2)] ^= 1 << r.randrange(8)
    return rows


def random_inputs(seed: int, scans: int) -> list[dict[int, int]]:
    """Input bytes 0 and 1 (bits): random at scan 0, then a few bits flip per scan;
    bytes 2..5 (the input words IW 2, IW 4): small or random values, new ones now
    and then."""
    r = random.Random(seed * 7919 + 1)
    image = [r.randrange(256), r.randrange(256)]

    def word() -> int:
        return r.choice((0, 1, 2, 5, 100, r.randrange(65536), 0xFFFF, 0x8000))

    words = [word() for _ in IN_WORDS]
    rows = []
    for _ in range(scans):
        row = {0: image[0], 1: image[1]}
        for n, w in zip(IN_WORDS, words):
            row[n], row[n + 1] = w >> 8, w & 0xFF
        rows.append(row)
        for _ in range(r.randrange(0, 4)):
            image[r.randrange(2)] ^= 1 << r.randrange(8)
        if r.random() < 0.3:
            words[r.randrange(len(words))] = word()
    return rows


_ADDRESS = re.compile(r"^(\S*\t(?:[A-Z]+\(?|=|[+*/<>=-]+I?)\t)([A-Z]+) ?(\d+(?:\.\d)?)$")


def with_symbols(text: str, lang: str, seed: int) -> tuple[str, list[tuple[str, str, str]]]:
    """The program with about half of its operands written as quoted symbols of a
    symbol table, and that table as (name, address, type) rows in the program's
    language (names with blanks and mixed case, as STEP 7 allows them)."""
    r = random.Random(seed * 31 + 5)
    names: dict[str, str] = {}
    out = []
    for line in text.split("\n"):
        m = _ADDRESS.match(line)
        jump = m and m.group(1).split()[-1] in JUMPS[lang] + CC_JUMPS[lang] + [
            "SPO", "SPS", "JO", "JOS"]                       # (a label, not an address)
        if m and not jump and r.random() < 0.5:
            address = f"{m.group(2)} {m.group(3)}"
            if address not in names:
                names[address] = r.choice(("Valve", "pump", "Level high", "Motor_1",
                                           "Lamp", "speed SP")) + f" {len(names)}"
            line = f'{m.group(1)}"{names[address]}"'
        out.append(line)
    kinds = {"E": "BOOL", "A": "BOOL", "I": "BOOL", "Q": "BOOL", "M": "BOOL",
             "EW": "INT", "AW": "INT", "IW": "INT", "QW": "INT", "MW": "INT",
             "T": "TIMER", "Z": "COUNTER", "C": "COUNTER"}
    rows = [(name, address, kinds.get(address.split()[0], "BOOL"))
            for address, name in names.items()]
    return "\n".join(out), rows


def symbol_table(rows: list[tuple[str, str, str]], fmt: str) -> str:
    """A STEP 7 export of (name, address, type) rows: "asc", "sdf" or "seq"."""
    if fmt == "asc":
        return "".join("126," + n.ljust(24) + a.ljust(12) + t.ljust(10) + " " * 80
                       + "\r\n" for n, a, t in rows)
    if fmt == "sdf":
        return "".join(f'"{n}","{a}","{t}",""\r\n' for n, a, t in rows)
    return "".join(f"\t{a}\t{n}\t\r\n" for n, a, t in rows)
