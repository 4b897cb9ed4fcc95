"""The single-processor baseline's cost of one bit instruction (issue 8, goal 2).

The baseline is the paper's byte processor, an 80C320 (Dallas DS80C320, an 8051 with
4 clocks per machine cycle), running the whole IL program alone.  Its word cost comes
from the paper's Table 1 (the firmware's `c320` table: 57 clocks of 0.1 µs).  The paper
gives no bit-instruction time for it, so the bit cost is counted here, instruction by
instruction, for the two ways an 8051 can run IL bit instructions:

* INTERPRETER -- the way the paper's byte processor runs every instruction (paper §2:
  "for the byte processor every single instruction is equivalent to a procedure
  execution that consists of several native instructions"): fetch the IL instruction,
  dispatch through a jump table, fetch the operand, do the bit operation on the process
  image, go on.  This is the like-for-like baseline: the 57-clock word cost is a
  procedure cost of the same kind.
* NATIVE -- the IL compiled to 8051 instructions (no fetch, no dispatch): a lower bound
  for any 8051, listed for honesty (its word instructions would then also cost less
  than 57, so it is not like-for-like).

Cycle counts: oscillator clocks per opcode of the DS80C320, from the instruction table
of Dallas Semiconductor's *High-Speed Microcontroller User's Guide* as tabulated in
github.com/cyrozap/8051-timing-db, `cycles_DS80C320_published.csv` (opcode -> clocks;
the opcodes are listed next to each line below).  Clock: 33 MHz, the DS80C320's maximum
(datasheet DS80C320/DS80C323 rev. 101006: "4 Clocks/Machine Cycle", "DC to 33MHz",
"Single-Cycle Instruction in 121ns").  The paper does not give its 80C320's clock; the
fastest part is the choice in the MCU's favour (a slower clock only makes b dearer:
at 25 MHz, the first DS80C320 grade, b is 33/25 times larger).

Choices in the MCU's favour throughout: the process image in internal RAM (@R0, one
clock cycle), the bit mask precomputed by the IL compiler (no mask table lookup), the
RLO in the carry flag, the dual data pointer of the DS80C320 for the jump table (no
save/restore of the program pointer), the dispatch inlined at the end of each handler
(no jump back to a loop head), MOVX without stretch cycles.
"""
from __future__ import annotations

from fractions import Fraction

# DS80C320 oscillator clocks per opcode (cycles_DS80C320_published.csv)
CLOCKS = {
    "MOVX A,@DPTR": (0xE0, 8), "INC DPTR": (0xA3, 12), "RL A": (0x23, 4),
    "INC direct": (0x05, 8), "JMP @A+DPTR": (0x73, 12), "AJMP": (0x01, 12),
    "MOV R0,A": (0xF8, 4), "ANL A,@R0": (0x56, 4), "ORL A,@R0": (0x46, 4),
    "MOV @R0,A": (0xF6, 4), "ADD A,#data": (0x24, 8), "CPL C": (0xB3, 4),
    "CLR C": (0xC3, 4), "SETB C": (0xD3, 4), "CPL A": (0xF4, 4), "JZ": (0x60, 12),
    "JNZ": (0x70, 12), "JC": (0x40, 12), "JNC": (0x50, 12),
    "MOV A,direct": (0xE5, 8), "MOV direct,A": (0xF5, 8), "MOV C,bit": (0xA2, 8),
    "MOV bit,C": (0x92, 8), "ANL C,bit": (0x82, 8), "ANL C,/bit": (0xB0, 8),
    "ORL C,bit": (0x72, 8), "ORL C,/bit": (0xA0, 8), "ORL A,#data": (0x44, 8),
}
MCU_MHZ = Fraction(33)
UNIT_US = Fraction(1, 10)         # the c320 table's clock: 0.1 µs (10 MHz)

# The interpreter.  Program: per IL instruction an opcode byte, the image byte's
# internal-RAM address, the bit mask; RLO in C; DPTR0 = IL program pointer, DPTR1 =
# jump table.  Every handler ends with a copy of NEXT (inlined dispatch).
NEXT = [                          # fetch and dispatch the next IL instruction
    ("MOVX A,@DPTR", "opcode"),
    ("INC DPTR", ""),
    ("RL A", "x2: AJMP table entries are 2 bytes"),
    ("INC direct", "INC DPS: select DPTR1 (jump table)"),
    ("JMP @A+DPTR", ""),
    ("AJMP", "table entry -> handler"),
    ("INC direct", "INC DPS: back to DPTR0 (program)"),
]
OPERAND = [                       # image byte address into R0, bit mask into A
    ("MOVX A,@DPTR", "image byte address"),
    ("INC DPTR", ""),
    ("MOV R0,A", ""),
    ("MOVX A,@DPTR", "bit mask (precomputed)"),
    ("INC DPTR", ""),
]
# handler bodies after OPERAND: the two paths (operand bit / RLO 0 or 1), averaged
HANDLERS = {
    "LD": ([("ANL A,@R0", ""), ("ADD A,#data", "#0FFh: C := (bit != 0)")],) * 2,
    "LDN": ([("ANL A,@R0", ""), ("ADD A,#data", "#0FFh"), ("CPL C", "")],) * 2,
    "A": ([("ANL A,@R0", ""), ("JNZ", "bit 1: RLO stays")],
          [("ANL A,@R0", ""), ("JNZ", "not taken"), ("CLR C", "bit 0: RLO := 0")]),
    "O": ([("ANL A,@R0", ""), ("JZ", "bit 0: RLO stays")],
          [("ANL A,@R0", ""), ("JZ", "not taken"), ("SETB C", "bit 1: RLO := 1")]),
    "=": ([("JC", "RLO 1 -> set path"), ("ORL A,@R0", ""), ("MOV @R0,A", "")],
          [("JC", "not taken"), ("CPL A", ""), ("ANL A,@R0", ""), ("MOV @R0,A", "")]),
    "S": ([("JNC", "RLO 0: nothing to do")],
          [("JNC", "not taken"), ("ORL A,@R0", ""), ("MOV @R0,A", "")]),
    "R": ([("JNC", "RLO 0: nothing to do")],
          [("JNC", "not taken"), ("CPL A", ""), ("ANL A,@R0", ""), ("MOV @R0,A", "")]),
}
# AN / ON / X / XN are A / O with the other jump (same clocks); the rest (parentheses:
# push / pop the RLO; FP / FN: read, combine and write the edge memory; jumps: load a
# new program pointer) are dearer: counting them at the mean of these handlers is
# again in the MCU's favour.
ALIAS = {"AN": "A", "ON": "O", "X": "A", "XN": "A"}

# Native code: IL compiled to 8051 instructions, image bytes in internal RAM.
NATIVE = {
    "LD": [("MOV A,direct", "image byte"), ("MOV C,bit", "C := ACC.n")],
    "A": [("MOV A,direct", ""), ("ANL C,bit", "ANL C,ACC.n")],
    "O": [("MOV A,direct", ""), ("ORL C,bit", "ORL C,ACC.n")],
    "=": [("MOV A,direct", ""), ("MOV bit,C", "MOV ACC.n,C"), ("MOV direct,A", "")],
}
# S / R: `JNC skip` then read-modify-write the image byte; the RLO-0 path is the jump
# alone: native_clocks() takes the mean of the two paths.
NATIVE["S"] = NATIVE["R"] = [("JNC", "RLO 0: skip (the other path ends here)"),
                             ("MOV A,direct", ""),
                             ("ORL A,#data", "ORL / ANL with the mask"),
                             ("MOV direct,A", "")]
NATIVE_SHORT = {"S": 1, "R": 1}    # kind -> length of its short path


def clocks(seq) -> int:
    return sum(CLOCKS[ins][1] for ins, _ in seq)


def interpreter_clocks(kind: str) -> Fraction:
    """MCU oscillator clocks of one IL instruction of this kind (mean of its paths)."""
    paths = HANDLERS[ALIAS.get(kind, kind)]
    return Fraction(sum(clocks(NEXT + OPERAND + p) for p in paths), len(paths))


def native_clocks(kind: str) -> Fraction:
    k = ALIAS.get(kind, kind) if kind != "LDN" else "LD"
    seq = NATIVE[k]
    if k in NATIVE_SHORT:
        return Fraction(clocks(seq) + clocks(seq[:NATIVE_SHORT[k]]), 2)
    return Fraction(clocks(seq))


def to_units(mcu_clocks) -> Fraction:
    """MCU oscillator clocks -> clocks of the c320 table (0.1 µs)."""
    return Fraction(mcu_clocks) / MCU_MHZ / UNIT_US


def mix_of(path) -> dict[str, int]:
    """Bit-instruction kinds of a program (LD, A, O, =, ...) -> count."""
    from bitbyte.lang.parser import parse_file
    from bitbyte.lang.costs import byte_kind
    prog = parse_file(str(path))
    out: dict[str, int] = {}
    for ins in prog.instrs:
        if byte_kind(ins) is None and ins.mnemonic != "END":
            out[ins.mnemonic] = out.get(ins.mnemonic, 0) + 1
    return out


def bit_cost(path) -> dict:
    """The baseline's cost per bit instruction for the program at `path`: the mean over
    its bit instructions of the interpreter's clocks (kinds without a handler of their
    own count as the mean of the handlers), in c320 clocks (0.1 µs), rounded to the
    nearest clock; the native-code figure the same way."""
    mix = mix_of(path)
    known = [k for k in HANDLERS]
    mean_i = sum(interpreter_clocks(k) for k in known) / len(known)
    mean_n = sum(native_clocks(k) for k in NATIVE) / len(NATIVE)
    n = sum(mix.values())
    tot_i = tot_n = Fraction(0)
    for kind, c in mix.items():
        k = ALIAS.get(kind, kind)
        tot_i += c * (interpreter_clocks(k) if k in HANDLERS else mean_i)
        tot_n += c * (native_clocks(k) if k in NATIVE or k == "LDN" else mean_n)
    interp, native = tot_i / n, tot_n / n
    return {
        "b": round(to_units(interp)), "b_native": round(to_units(native)),
        "mcu_clocks": float(interp), "mcu_clocks_native": float(native),
        "us": float(interp / MCU_MHZ), "us_native": float(native / MCU_MHZ),
        "mcu_mhz": float(MCU_MHZ),
        "per_kind": {k: float(interpreter_clocks(k)) for k in HANDLERS},
        "per_kind_native": {k: float(native_clocks(k)) for k in NATIVE},
        "next": clocks(NEXT), "operand": clocks(OPERAND),
        "b_25mhz": round(to_units(interp) * MCU_MHZ / 25),
    }


def listing() -> str:
    """The interpreter's code with clocks, for docs/performance.md."""
    rows = ["| part | 8051 instruction (opcode) | DS80C320 clocks | note |",
            "|---|---|---|---|"]

    def add(part, seq):
        for ins, note in seq:
            op, c = CLOCKS[ins]
            rows.append(f"| {part} | `{ins}` ({op:02X}h) | {c} | {note} |")
            part = ""
    add(f"dispatch ({clocks(NEXT)})", NEXT)
    add(f"operand ({clocks(OPERAND)})", OPERAND)
    for kind, paths in HANDLERS.items():
        for i, p in enumerate(paths):
            if i and p == paths[0]:
                continue
            add(f"`{kind}` path {i + 1} ({clocks(p)})", p)
    return "\n".join(rows)


if __name__ == "__main__":
    import sys
    from pathlib import Path
    here = Path(__file__).resolve().parent
    sys.path.insert(0, str(here.parent))
    r = bit_cost(here / "programs" / "table1.il")
    print(listing())
    print(r)
