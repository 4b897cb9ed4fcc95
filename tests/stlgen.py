"""Random S7 statement-list programs (OB 1, bit logic) for the awlsim comparison.

Each program is German or English throughout and exercises what the S7 front end
must get right: first-check strings (every network starts a fresh string with
U/UN/O/ON/X/XN, and `=`/`S`/`R`, SET/CLR, jumps end one), `O` without operand (AND
before OR, also as the very first statement of a string, where it does nothing),
nesting `U(`/`UN(`/`O(`/`ON(`/`X(`/`XN(` ... `)` up to three deep, X after `O`,
FP/FN in the middle of a string, NOT, forward jumps SPA/SPB/SPBN (JU/JC/JCN) to a
label on a later network, BEB (BEC).  A few programs contain what the front end rejects
(NOT after `O` in a string, a jump target reached with different /FC): the test
expects `unsupported:` for those, never a silent difference.

random_program(seed) -> (source text, language); random_inputs(seed, scans) -> the
input bytes 0 and 1 per scan.
"""
from __future__ import annotations

import random

COMBINES = {"de": ["U", "UN", "O", "ON", "X", "XN"], "en": ["A", "AN", "O", "ON", "X", "XN"]}
OPENS = {"de": ["U(", "UN(", "O(", "ON(", "X(", "XN("],
         "en": ["A(", "AN(", "O(", "ON(", "X(", "XN("]}
AREA = {"de": {"I": "E", "Q": "A", "M": "M"}, "en": {"I": "I", "Q": "Q", "M": "M"}}
JUMPS = {"de": ["SPA", "SPB", "SPBN"], "en": ["JU", "JC", "JCN"]}


class Gen:
    def __init__(self, seed: int):
        self.r = random.Random(seed)
        self.lang = self.r.choice(("de", "en"))
        self.lines: list[str] = []
        self.label = ""                 # put before the next statement

    def addr(self, areas: str = "IQM") -> str:
        r = self.r
        area = r.choice(areas)
        spaced = r.random() < 0.7
        name = AREA[self.lang][area]
        return f"{name}{' ' if spaced else ''}{r.randrange(2)}.{r.randrange(8)}"

    def emit(self, text: str) -> None:
        self.lines.append(self.label + "\t" + text)
        self.label = ""

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
            self.emit(r.choice(("FP", "FN")) + " " + self.addr("M").replace("0.", "1.", 1))
        elif not opening and x < 0.35:
            self.emit("NOT")
        else:
            self.emit(f"{r.choice(COMBINES[self.lang])}\t{self.addr()}")

    def network(self, n: int, labels: dict[int, str]) -> None:
        r = self.r
        self.lines.append(f"NETWORK\nTITLE = network {n}")
        if n in labels:
            self.label = f"{labels[n]}:"
        if r.random() < 0.08:
            self.emit(r.choice(("SET", "CLR")))
        else:
            self.string(0)
        for _ in range(r.randrange(1, 3)):
            op = r.choice(("=", "=", "S", "R"))
            self.emit(f"{op}\t{self.addr('QM')}")

    def program(self) -> str:
        r = self.r
        networks = r.randrange(2, 7)
        labels: dict[int, str] = {}
        jumps: dict[int, tuple[str, str]] = {}
        for n in range(networks - 1):
            if r.random() < 0.25:
                target = r.randrange(n + 1, networks)
                name = labels.setdefault(target, f"M{target:03d}")
                jumps[n] = (r.choice(JUMPS[self.lang]), name)
        self.lines = ["ORGANIZATION_BLOCK OB 1", "TITLE = random", "VERSION : 0.1", "",
                      "BEGIN"]
        for n in range(networks):
            self.network(n, labels)
            if n in jumps:
                mnem, name = jumps[n]
                if r.random() < 0.3:
                    self.string(0)                  # a condition of its own
                self.emit(f"{mnem}\t{name}")
            elif r.random() < 0.05:
                self.string(0)
                self.emit("BEB" if self.lang == "de" else "BEC")
        self.lines.append("END_ORGANIZATION_BLOCK")
        return "\n".join(self.lines) + "\n"


def random_program(seed: int) -> tuple[str, str]:
    g = Gen(seed)
    return g.program(), g.lang


def random_inputs(seed: int, scans: int) -> list[dict[int, int]]:
    """Input bytes 0 and 1: random at scan 0, then a few bits flip per scan."""
    r = random.Random(seed * 7919 + 1)
    image = [r.randrange(256), r.randrange(256)]
    rows = []
    for _ in range(scans):
        rows.append({0: image[0], 1: image[1]})
        for _ in range(r.randrange(0, 4)):
            image[r.randrange(2)] ^= 1 << r.randrange(8)
    return rows
