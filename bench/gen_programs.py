#!/usr/bin/env python3
"""Deterministic generator of the benchmark programs (issue 8).

    python bench/gen_programs.py [--seed 2008] [--out bench/programs]

writes
  table1.il             a program the size of the paper's Table 1 rows for the
                        S7-313 / S7-315-2DP (1000 bit + 115 word instructions), in the mix
                        of a real plant program: seal-in interlocks, parallel branches in
                        parentheses, FP/FN edges, set/reset latches, step sequences,
                        timers, counters, compares, arithmetic, word outputs and a few
                        conditional jumps over blocks;
  mix_00.il .. mix_50.il  the same kinds of rungs at a fixed total of 200 instructions,
                        0 %, 10 %, ... 50 % of them word instructions (straight line:
                        no jumps, so every scan executes every instruction);
  response.il           a Table-1-sized program with the response rungs in its middle:
                        `LD PI15.7` / `= PQ15.6` (direct access) and `LD I15.7` /
                        `= Q15.7` (process image); the part before them has no jumps,
                        so the clock at which `= PQ15.6` executes is known statically.

"Bit instruction" = one the bit processor executes (LD, A, O, X and negations, the
parentheses, =, S, R, FP, FN, NOT, jumps); "word instruction" = one the byte processor
executes (L, T, arithmetic, compares incl. `A >=I`, SD/SP/SF/SS, R T, CU/CD, S C, R C).
The appended END is not counted (as in the paper's Table 1).

The same seed gives the same files byte for byte (random.Random(seed), no time,
no hash ordering), so `make bench` regenerates them without a diff.
"""
from __future__ import annotations

import argparse
import random
from pathlib import Path

HERE = Path(__file__).resolve().parent
DEFAULT_SEED = 2008            # the year of the paper

# Address ranges the generated rungs use (inside the default build's sizes). Input and
# output byte 15 are kept free for the response rungs.
IN_BYTES = 12
OUT_BYTES = 12
RESPONSE_PIN = "I15.7"        # the input whose edges the response benchmark times
RESPONSE_Q = "Q15.7"          # process image:  LD I15.7  / = Q15.7
RESPONSE_PQ = "PQ15.6"        # direct access:  LD PI15.7 / = PQ15.6


class Gen:
    """Emits rungs; counts bit and word instructions exactly."""

    def __init__(self, rng: random.Random, tag: str = ""):
        self.rng = rng
        self.lines: list[str] = []
        self.bits = 0
        self.words = 0
        self.jumps = 0
        self.tag = tag
        self._m = 0          # next free marker byte for coils / edge memories
        self._t = 0
        self._c = 0
        self._mw = 0
        self._label = 0
        self._q = 0

    # ---- operands ----------------------------------------------------------------
    def _next(self, counter: str, wrap: int) -> int:
        """The next of `wrap` numbers handed out in turn (counter: the attribute)."""
        n = getattr(self, counter)
        setattr(self, counter, n + 1)
        return n % wrap

    def inp(self) -> str:
        return f"I{self.rng.randrange(IN_BYTES)}.{self.rng.randrange(8)}"

    def marker(self) -> str:
        """A marker some earlier rung may have written (read side)."""
        hi = max(1, min(self._m, 199))
        return f"M{self.rng.randrange(hi)}.{self.rng.randrange(8)}"

    def new_marker(self) -> str:
        return f"M{self._next('_m', 200)}.{self.rng.randrange(8)}"

    def edge_mem(self) -> str:
        return f"M{200 + self.rng.randrange(56)}.{self.rng.randrange(8)}"

    def out(self) -> str:
        q = self._next("_q", OUT_BYTES * 8)
        return f"Q{q // 8}.{q % 8}"

    def contact(self) -> str:
        """A contact: an input (55 %), a marker (~42 %) or, rarely, the status of a
        timer or counter defined earlier -- about 0.3 % per defined timer / counter,
        at most 3 %, so that each status is read once or twice outside its own rung,
        as in a plant program (not dozens of times)."""
        r = self.rng.random()
        p_t = min(0.03, 0.003 * min(self._t, 48))
        p_c = min(0.03, 0.003 * min(self._c, 48))
        if r < p_t:
            return f"T{self.rng.randrange(min(self._t, 48))}"
        if r < p_t + p_c:
            return f"C{self.rng.randrange(min(self._c, 48))}"
        if r < 0.55:
            return self.inp()
        return self.marker()

    def timer(self) -> str:
        return f"T{self._next('_t', 48)}"

    def counter(self) -> str:
        return f"C{self._next('_c', 48)}"

    def mw(self) -> str:
        return f"MW{self._next('_mw', 100)}"

    def old_mw(self) -> str:
        return f"MW{self.rng.randrange(max(1, min(self._mw, 100)))}"

    def iw(self) -> str:
        return f"IW{self.rng.randrange(8)}"

    def label(self) -> str:
        self._label += 1
        return f"{self.tag.lower()}skip{self._label}"

    # ---- emit --------------------------------------------------------------------
    def b(self, mnemonic: str, operand: str = "") -> None:
        self.lines.append(f"      {mnemonic:<6}{operand}".rstrip())
        self.bits += 1

    def w(self, mnemonic: str, operand: str = "") -> None:
        self.lines.append(f"      {mnemonic:<6}{operand}".rstrip())
        self.words += 1

    def comment(self, text: str) -> None:
        self.lines.append(f"// {text}")

    def contacts(self, n: int) -> None:
        for _ in range(n):
            self.b(self.rng.choice(["A", "A", "A", "AN", "O", "ON"]), self.contact())

    # ---- bit rungs (n = exact number of bit instructions, n >= 1) ---------------
    def bit_rung(self, n: int) -> None:
        """A bit-only rung of exactly n instructions, of a kind that fits n."""
        if n == 1:
            self.b("=", self.new_marker())
            return
        if n == 2:
            self.b("LD", self.contact())
            self.b("=", self.new_marker())
            return
        kinds = ["interlock", "plain"]
        if n >= 4:
            kinds += ["edge", "setreset"]
        if n >= 5:
            kinds += ["step"]
        if n >= 7:
            kinds += ["branches", "branches"]
        kind = self.rng.choice(kinds)
        if kind == "plain":
            self.comment("logic")
            self.b("LD", self.contact())
            self.contacts(n - 2)
            self.b("=", self.out() if self.rng.random() < 0.5 else self.new_marker())
        elif kind == "interlock":
            self.comment("seal-in interlock")
            coil = self.new_marker()
            self.b("LD", self.inp())
            self.b("O", coil)
            for _ in range(n - 3):
                self.b(self.rng.choice(["A", "A", "AN"]), self.contact())
            self.b("=", coil)
        elif kind == "edge":
            self.comment("edge pulse")
            self.b("LD", self.inp())
            self.contacts(n - 4)
            self.b(self.rng.choice(["FP", "FN"]), self.edge_mem())
            self.b(self.rng.choice(["=", "S"]), self.new_marker())
            self.b("R" if self.rng.random() < 0.5 else "=", self.out())
        elif kind == "setreset":
            self.comment("set / reset latch")
            q = self.out()
            k = n - 4
            k1 = k // 2
            self.b("LD", self.contact())
            self.contacts(k1)
            self.b("S", q)
            self.b("LD", self.contact())
            self.contacts(k - k1)
            self.b("R", q)
        elif kind == "step":
            self.comment("step sequence: step n + transition -> step n+1")
            s_from, s_to = self.new_marker(), self.new_marker()
            self.b("LD", s_from)
            self.contacts(n - 4)
            self.b("S", s_to)
            self.b("R", s_from)
            self.b("=", self.out())
        else:
            self.comment("parallel branches")
            # LD a; A b; O( LD c; A d ); [more]; = coil   -- opener, LD and ) = 3 each
            self.b("LD", self.contact())
            left = n - 2
            while left >= 3 + 1 + 1:         # a branch needs O( LD ) and leaves >= 1
                inner = self.rng.randrange(0, min(3, left - 4) + 1)
                self.b(self.rng.choice(["O(", "A(", "AN(", "O("]), "")
                self.b("LD", self.contact())
                self.contacts(inner)
                self.b(")")
                left -= 3 + inner
                if self.rng.random() < 0.4:
                    break
            self.contacts(left - 1)
            self.b("=", self.out() if self.rng.random() < 0.5 else self.new_marker())

    # ---- word rungs: (lines, bits, words) fixed per kind ------------------------
    WORD_KINDS = {            # kind: (bits, words)
        "timer": (4, 2),      # LD; A; L T#; SD T; LD T; = q        -> 4 b, 2 w
        "timer_reset": (5, 3),
        "counter": (5, 2),    # LD; FP; CU C; LD; R C (R C is a word instr) -> see body
        "cmp": (2, 3),        # L IW; L MW; >I; A c; = q
        "cmp_and": (3, 3),    # LD; A; L IW; L k; A >=I; = q
        "cnt_cmp": (1, 3),    # L C; L k; >=I; = q
        "arith": (0, 4),      # L; L; +I; T
        "scale": (0, 6),      # L IW; L k; *I; L k; /I; T MW
        "wordout": (0, 2),    # L MW; T QW
        "reset_t": (1, 1),    # LD; R T
    }

    def word_rung(self, kind: str) -> None:
        r = self.rng
        if kind == "timer":
            self.comment("timer")
            t = self.timer()
            self.b("LD", self.contact())
            self.b(r.choice(["A", "AN"]), self.contact())
            self.w("L", f"T#{r.choice([2, 5, 10, 20, 50, 100, 250, 500])}ms")
            self.w(r.choice(["SD", "SD", "SD", "SP", "SF"]), t)
            self.b("LD", t)
            self.b("=", self.out() if r.random() < 0.5 else self.new_marker())
            # bits: LD, A, LD, =  -> 4 ; words: L, SD -> 2
        elif kind == "timer_reset":
            self.comment("retentive timer with reset")
            t = self.timer()
            self.b("LD", self.contact())
            self.w("L", f"T#{r.choice([10, 30, 100, 300])}ms")
            self.w("SS", t)
            self.b("LD", self.inp())
            self.w("R", t)
            self.b("LD", t)
            self.b("A", self.contact())
            self.b("=", self.new_marker())
        elif kind == "counter":
            self.comment("counter with reset")
            c = self.counter()
            self.b("LD", self.inp())
            self.b(r.choice(["FP", "FN"]), self.edge_mem())    # a software edge
            self.w(r.choice(["CU", "CU", "CD"]), c)
            self.b("LD", self.inp())
            self.w("R", c)
            self.b("LD", c)
            self.b("=", self.new_marker())
        elif kind == "cmp":
            self.comment("compare")
            self.w("L", self.iw())
            self.w("L", self.old_mw() if r.random() < 0.5 else str(r.randrange(-500, 2000)))
            self.w(r.choice([">I", "<I", ">=I", "<=I", "==I", "<>I"]))
            self.b(r.choice(["A", "O"]), self.contact())
            self.b("=", self.new_marker())
        elif kind == "cmp_and":
            self.comment("enabled compare")
            self.b("LD", self.contact())
            self.b("A", self.contact())
            self.w("L", self.iw())
            self.w("L", str(r.randrange(0, 1000)))
            self.w(r.choice(["A >=I", "A <I", "A >I"]))
            self.b("=", self.out())
        elif kind == "cnt_cmp":
            self.comment("counter value compare")
            self.w("L", f"C{r.randrange(max(1, self._c))}")
            self.w("L", str(r.randrange(1, 20)))
            self.w(">=I")
            self.b("=", self.new_marker())
        elif kind == "arith":
            self.comment("arithmetic")
            self.w("L", self.old_mw() if r.random() < 0.6 else self.iw())
            self.w("L", self.old_mw() if r.random() < 0.5 else str(r.randrange(1, 100)))
            self.w(r.choice(["+I", "+I", "-I", "*I"]))
            self.w("T", self.mw())
        elif kind == "scale":
            self.comment("analog scaling: MW = IW * k1 / k2")
            self.w("L", self.iw())
            self.w("L", str(r.randrange(2, 40)))
            self.w("*I")
            self.w("L", str(r.randrange(3, 100)))
            self.w("/I")
            self.w("T", self.mw())
        elif kind == "wordout":
            self.comment("word output")
            self.w("L", self.old_mw())
            self.w("T", f"QW{r.randrange(8)}")
        elif kind == "reset_t":
            self.comment("timer reset")
            self.b("LD", self.inp())
            self.w("R", f"T{r.randrange(max(1, self._t))}")
        else:
            raise ValueError(kind)

    def jump_block(self, bits_left: int, words_left: int) -> tuple[int, int]:
        """`LD a; AN b; JCN skip` + a block (arithmetic, or a bit rung) + `skip:`.
        Returns the instructions it used (bits, words)."""
        lab = self.label()
        self.comment("conditional block")
        self.b("LD", self.contact())
        self.b(self.rng.choice(["A", "AN"]), self.contact())
        self.b(self.rng.choice(["JCN", "JC"]), lab)
        used_b, used_w = 3, 0
        if words_left >= 4 and self.rng.random() < 0.6:
            self.word_rung("arith")
            used_w += 4
        else:
            n = min(bits_left - 3, self.rng.randrange(4, 9))
            if n >= 1:
                self.bit_rung(n)
                used_b += n
        self.lines.append(f"{lab}:")
        return used_b, used_w


def generate(n_bits: int, n_words: int, seed: int, jumps: int = 0,
             tag: str = "") -> Gen:
    """Rungs with exactly n_bits bit and n_words word instructions, `jumps` conditional
    blocks spread over the program."""
    rng = random.Random(seed)
    g = Gen(rng, tag)
    kinds = list(Gen.WORD_KINDS)
    weights = {"timer": 6, "timer_reset": 1, "counter": 2, "cmp": 3, "cmp_and": 2,
               "cnt_cmp": 1, "arith": 2, "scale": 1, "wordout": 1, "reset_t": 1}
    total = n_bits + n_words
    jump_at = sorted(rng.sample(range(1, 20), jumps)) if jumps else []
    jump_at = [total * j // 20 for j in jump_at]
    while g.bits < n_bits or g.words < n_words:
        bl, wl = n_bits - g.bits, n_words - g.words
        done = g.bits + g.words
        if jump_at and done >= jump_at[0] and bl >= 12:
            jump_at.pop(0)
            g.jump_block(bl, wl)
            continue
        # keep word progress proportional to bit progress
        want_word = wl > 0 and (bl == 0 or wl / max(n_words, 1) >= bl / max(n_bits, 1))
        if want_word:
            fits = [k for k in kinds if Gen.WORD_KINDS[k][1] <= wl
                    and Gen.WORD_KINDS[k][0] <= bl]
            if not fits:                      # no bits left for a mixed rung
                fits = [k for k in kinds if Gen.WORD_KINDS[k] == (0, 2) and wl >= 2
                        or Gen.WORD_KINDS[k] == (0, 4) and wl >= 4]
            if not fits:
                # wl == 1 (or 3) with no bits left: a lone transfer / load keeps the
                # count exact (only at the very end of a pure-word tail)
                g.comment("word output")
                g.w("T", f"QW{rng.randrange(8)}")
                continue
            kind = rng.choices(fits, [weights[k] for k in fits])[0]
            g.word_rung(kind)
        else:
            n = min(bl, rng.choice([3, 4, 5, 6, 6, 7, 8, 9, 10, 12]))
            if 0 < bl - n < 2:
                n = bl
            g.bit_rung(n)
    assert (g.bits, g.words) == (n_bits, n_words), (g.bits, g.words)
    return g


HEADER = """// {title}
// GENERATED by bench/gen_programs.py --seed {seed}: do not edit (make bench rewrites it).
// {nb} bit instructions, {nw} word instructions (word share {share:.1f} %), {nj} jumps.
"""


def write(path: Path, title: str, seed: int, g_parts: list[Gen], middle: list[str] = (),
          extra_bits: int = 0) -> None:
    nb = sum(g.bits for g in g_parts) + extra_bits
    nw = sum(g.words for g in g_parts)
    nj = sum(sum(1 for ln in g.lines if ln.strip().startswith(("JC ", "JCN ", "JU ")))
             for g in g_parts)
    text = HEADER.format(title=title, seed=seed, nb=nb, nw=nw,
                         share=100.0 * nw / (nb + nw), nj=nj)
    body: list[str] = []
    for i, g in enumerate(g_parts):
        body += g.lines
        if i == 0 and middle:
            body += list(middle)
    path.write_text(text + "\n".join(body) + "\n")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED)
    ap.add_argument("--out", default=str(HERE / "programs"))
    ap.add_argument("--mix-total", type=int, default=200)
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    seed = args.seed

    g = generate(1000, 115, seed, jumps=5)
    write(out / "table1.il", "Table-1-sized program: 1000 bit + 115 word instructions "
          "(paper Table 1, S7-313 / S7-315-2DP rows)", seed, [g])

    for pct in (0, 10, 20, 30, 40, 50):
        nw = args.mix_total * pct // 100
        g = generate(args.mix_total - nw, nw, seed + pct + 1, jumps=0)
        write(out / f"mix_{pct:02d}.il", f"word-share sweep: {pct} % word instructions of "
              f"{args.mix_total}", seed, [g])

    # response.il: straight-line first half, the response rungs, second half with jumps
    g1 = generate(500, 57, seed + 100, jumps=0, tag="A")
    g2 = generate(496, 58, seed + 200, jumps=3, tag="B")
    middle = [
        "// ---- response rungs: direct access (PI -> PQ) and process image (I -> Q)",
        f"      LD    P{RESPONSE_PIN}",
        f"      =     {RESPONSE_PQ}",
        f"      LD    {RESPONSE_PIN}",
        f"      =     {RESPONSE_Q}",
        "// ----",
    ]
    write(out / "response.il", "response-time program: Table-1-sized, the output rungs "
          "in the middle", seed, [g1, g2], middle, extra_bits=4)
    # response_fast.il: fast bit-only logic next to slow word logic (issue 8: the case
    # free-running mode is for): the response rungs, 40 bit and 60 word instructions
    g3 = generate(40, 60, seed + 300, jumps=0, tag="F")
    write(out / "response_fast.il", "response-time program: fast bit-only logic next to "
          "slow word logic (40 bit, 60 word instructions)", seed, [g3], middle, extra_bits=4)
    print(f"wrote {out}/table1.il, mix_00..50.il, response.il, response_fast.il "
          f"(seed {seed})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
