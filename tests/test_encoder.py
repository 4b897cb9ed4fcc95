"""The binary encoding of docs/isa.md, checked against words written out by hand
(never computed from bitbyte.encoding.isa's tables), plus the image files of `assemble`.

Word: opcode (31..24) | reserved 0 (23..16) | area (15..12) | index (11..0),
or opcode | 0 | jump target (15..0).  Areas: I 0, PI 1, IR 2, IF 3, Q 4, PQ 5, M 6,
T 7, C 8.  Bit index = byte*8 + bit.
"""
from __future__ import annotations

import json

import pytest

from bitbyte.asm import assemble
from bitbyte.lang.config import Config
from bitbyte.encoding.encoder import constant_pool, encode, encode_words
from bitbyte.lang.errors import SourceError
from bitbyte.lang.parser import parse


def words_of(text: str, config: Config = Config()) -> list[int]:
    return encode_words(parse("t.il", text, config), config)


def single(text: str) -> int:
    """The word of a one-instruction program (its appended END is 0x01000000)."""
    words = words_of(text + "\n")
    assert words[-1] == 0x01000000
    return words[0]


# ---------------------------------------------------------------------------------------
# Every bit instruction
# ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("text, word", [
    ("NOP", 0x00000000),
    ("END", 0x01000000),
    ("NOT", 0x02000000),
    ("SET", 0x03000000),
    ("CLR", 0x04000000),
    ("REFRESH", 0x06000000),
    ("REFRESH I", 0x06000000),
    ("REFRESH Q", 0x07000000),
    # loads and combines: 0x08 | f<<1 | n with f = 00 load, 01 AND, 10 OR, 11 XOR
    ("LD I0.0", 0x08000000),
    ("LDN I0.0", 0x09000000),
    ("A I1.3", 0x0A00000B),             # the docs/isa.md example
    ("AN I1.3", 0x0B00000B),
    ("O I1.3", 0x0C00000B),
    ("ON I1.3", 0x0D00000B),
    ("X I1.3", 0x0E00000B),
    ("XN I1.3", 0x0F00000B),
    # every readable area
    ("LD PI0.1", 0x08001001),
    ("LD IR1.0", 0x08002008),
    ("LD IF15.7", 0x0800307F),
    ("LD Q0.1", 0x08004001),
    ("LD PQ2.2", 0x08005012),
    ("A QR1.3", 0x0A00D00B),
    ("ON QF15.7", 0x0D00E07F),
    ("LD M255.7", 0x080067FF),
    ("LD M 16.0", 0x08006080),
    ("LD T63", 0x0800703F),
    ("A C3", 0x0A008003),
    ("ON T 0", 0x0D007000),
    # writes
    ("= Q0.1", 0x18004001),             # the docs/isa.md example
    ("= PQ0.0", 0x18005000),
    ("= M1.2", 0x1800600A),
    ("S M1.0", 0x19006008),
    ("S Q15.7", 0x1900407F),
    ("R PQ0.0", 0x1A005000),
    ("R M0.7", 0x1A006007),
    ("FP M0.0", 0x1B006000),
    ("FP Q0.2", 0x1B004002),
    ("FN M2.1", 0x1C006011),
    ("FN Q0.1", 0x1C004001),
])
def test_bit_instruction_words(text, word):
    assert single(text) == word


def test_parentheses_words():
    text = ("LD I0.0\nA(\nLD I0.1\n)\nAN(\nLD I0.1\n)\nO(\nLD I0.1\n)\nON(\nLD I0.1\n)\n"
            "X(\nLD I0.1\n)\nXN(\nLD I0.1\n)\nA (\nLDN I0.1\n)\n")
    opens = [w for w in words_of(text) if 0x10000000 <= w < 0x18000000]
    assert opens == [0x12000000, 0x13000000, 0x14000000, 0x15000000, 0x16000000,
                     0x17000000, 0x12000000]
    assert words_of(text).count(0x05000000) == 7


def test_jumps_encode_the_label_address():
    text = "NOP\nNOP\nNOP\nNOP\nNOP\ntarget: NOP\nJU target\nJC target\nJCN target\n" \
           "JU first\nfirst:\n"
    words = words_of(text)
    # JC to address 5 is the docs/isa.md example 0x21000005
    assert words[6:10] == [0x20000005, 0x21000005, 0x22000005, 0x2000000A]
    assert words[10] == 0x01000000            # `first:` marks the appended END


def test_backward_jump_to_zero_and_forward_over_an_end():
    words = words_of("top: LD I0.0\nJC out\nEND\nout: = Q0.0\nJU top\n")
    assert words == [0x08000000, 0x21000003, 0x01000000, 0x18004000, 0x20000000,
                     0x01000000]


def test_symbols_encode_as_their_addresses():
    text = ("VAR\n Start AT I0.0; Out AT Q0.1; Edge AT M7.7; Tm AT T5; Cn AT C6;\n"
            "END_VAR\nLD \"Start\"\nA Tm\nO cn\nFP Edge\n= OUT\n")
    assert words_of(text) == [0x08000000, 0x0A007005, 0x0C008006, 0x1B00603F,
                              0x18004001, 0x01000000]


def test_end_is_appended_only_when_missing():
    assert words_of("LD I0.0\n= Q0.0\nEND\n") == [0x08000000, 0x18004000, 0x01000000]
    assert words_of("LD I0.0\n= Q0.0") == [0x08000000, 0x18004000, 0x01000000]
    assert words_of("END\nNOP\n") == [0x01000000, 0x00000000, 0x01000000]
    assert words_of("") == [0x01000000]


# ---------------------------------------------------------------------------------------
# The spec's worked examples
# ---------------------------------------------------------------------------------------

def test_worked_example_edges_is_bit_only():
    text = "LD I0.0\nFP M0.0\n= Q0.0\nLD I0.0\nFN M0.1\n= Q0.1\n"
    assert words_of(text) == [0x08000000, 0x1B006000, 0x18004000, 0x08000000,
                              0x1C006001, 0x18004001, 0x01000000]


# Byte instructions in serial mode (docs/isa.md "Byte instructions"), words by hand.
BYTE_WORDS = [
    ("L 10", 0x8000000A), ("L -1", 0x80FFFFFF), ("L 16#FFFF", 0x80FFFFFF),
    ("L 16#7FFF", 0x80007FFF), ("L T#2ms", 0x80000002), ("L T#1h", 0x8036EE80),
    ("L MW1", 0x8200C001), ("L IW3", 0x8200A003), ("L QW15", 0x8200B00F),
    ("L T 4", 0x82007004), ("L C63", 0x8200803F), ("T MW255", 0x8300C0FF),
    ("T QW2", 0x8300B002), ("+I", 0x88000000), ("-I", 0x89000000), ("*I", 0x8A000000),
    ("/I", 0x8B000000), ("MOD", 0x8C000000), ("==I", 0x90000000), ("<>I", 0x91000000),
    (">I", 0x92000000), ("<I", 0x93000000), (">=I", 0x94000000), ("<=I", 0x95000000),
    ("A ==I", 0x98000000), ("A >=I", 0x9C000000), ("O ==I", 0xA0000000),
    ("O <=I", 0xA5000000), ("SD T1", 0xB0007001), ("SS T2", 0xB1007002),
    ("SP T3", 0xB2007003), ("SF T63", 0xB300703F), ("R T 5", 0xB4007005),
    ("CU C1", 0xB8008001), ("CD C2", 0xB9008002), ("S C 3", 0xBA008003),
    ("R C4", 0xBB008004),
]


@pytest.mark.parametrize("text, word", BYTE_WORDS)
def test_byte_instruction_words(text, word):
    assert words_of("LD I0.0\n" + text + "\n")[1] == word


def test_wide_constants_go_to_the_pool():
    # 2h19m48s607ms = 8388607 ms = 2^23 - 1, the largest immediate
    program = parse("p.il", "L T#500h\nL T#2h19m48s607ms\nL T#2h19m48s608ms\n"
                            "L T#500h\nL -32768\n")
    assert constant_pool(program) == [1_800_000_000, 8_388_608]
    assert encode_words(program)[:5] == [0x81000000, 0x807FFFFF, 0x81000001,
                                         0x81000000, 0x80FF8000]


def test_fig5_program_encodes_in_serial_mode():
    text = """VAR
  Start AT I0.0; Stop AT I0.1; BLK AT I0.2;
  Flag AT M0.0; Timer AT T1;
  Start_Up AT Q0.0; Out AT Q0.1;
  SP_cur AT IW0; SP_nom AT MW0; Time AT MW1;
END_VAR
LD Start
O Flag
A Stop
A BLK
= Flag
L Time
SD Timer
LD Timer
= Start_Up
LD Start_Up
L SP_cur
L SP_nom
A >=I
= Out
"""
    program = parse("fig5.il", text)
    assert len(program.instrs) == 15
    assert program.instrs[12].mnemonic == "A >=I"
    assert encode_words(program) == [
        0x08000000, 0x0C006000, 0x0A000001, 0x0A000002, 0x18006000,  # LD..= Flag
        0x8200C001, 0xB0007001,                                      # L Time, SD Timer
        0x08007001, 0x18004000, 0x08004000,                          # LD Timer..LD Start_Up
        0x8200A000, 0x8200C000, 0x9C000000, 0x18004001, 0x01000000]


# ---------------------------------------------------------------------------------------
# What serial mode cannot do
# ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("text", [
    "READ FBY0", "WRITE FBI0", "LD FBI0", "AN FBI3", "= FBY0", "S FBY1", "R FBY1",
])
def test_exchange_instructions_need_parallel_mode(text):
    program = parse("t.il", "LD I0.0\n  " + text + "\n")
    with pytest.raises(SourceError) as info:
        encode(program)
    assert (info.value.line, info.value.col) == (2, 3)
    assert "parallel mode" in info.value.message


@pytest.mark.parametrize("text", ["L MW0", "SD T1", "A >=I", "CU C1"])
def test_parallel_mode_waits_for_the_partitioner(text):
    program = parse("t.il", "LD I0.0\n  " + text + "\n")
    with pytest.raises(SourceError) as info:
        encode(program, mode="parallel")
    assert (info.value.line, info.value.col) == (2, 3)
    assert "--mode parallel" in info.value.message


# ---------------------------------------------------------------------------------------
# Listing and image files
# ---------------------------------------------------------------------------------------

PROGRAM = """VAR
  Start AT I0.0;   // push button
END_VAR
loop:
  LD "Start"
  A I1.3
done: = Q0.1
  JC loop
"""


def test_listing_lines():
    program = parse("p.il", PROGRAM)
    words, text = encode(program)
    lines = text.splitlines()
    assert lines[0] == "; bitbyte listing of p.il"
    assert "5 of 4096 words" in lines[1]
    body = [line for line in lines if line[4:6] == "  " and
            all(c in "0123456789ABCDEF" for c in line[:4])]
    assert body[0].startswith("0000  08000000     5: LD \"Start\"")
    assert body[0].endswith("; I0.0")
    assert body[1] == "0001  0A00000B     6: A I1.3"
    assert body[2] == "0002  18004001     7: done: = Q0.1"
    assert body[3].startswith("0003  21000000     8: JC loop") and "-> 0000" in body[3]
    assert body[4] == "0004  01000000     9: (appended END)"
    assert "                loop:" in lines          # a label on its own line shows
    assert "                done:" not in lines      # ... one on the line does not twice


def test_assemble_writes_hex_listing_and_json(tmp_path):
    src = tmp_path / "prog.il"
    src.write_text(PROGRAM)
    out = tmp_path / "out"
    result = assemble(str(src), str(out))
    assert result["hex"] == str(out / "prog.hex") and result["words"] == 5
    assert (out / "prog.hex").read_text() == \
        "08000000\n0A00000B\n18004001\n21000000\n01000000\n"
    assert (out / "prog.lst").read_text().startswith("; bitbyte listing of")
    summary = json.loads((out / "prog.json").read_text())
    assert summary["source"] == str(src)
    assert summary["words"] == 5
    assert summary["symbols"] == {"START": "I0.0"}
    assert summary["labels"] == {"LOOP": 0, "DONE": 2}
    assert summary["config"]["prog_words"] == 4096


def test_assemble_defaults_to_the_source_directory(tmp_path):
    src = tmp_path / "beside.il"
    src.write_text("LD I0.0\n= Q0.0\n")
    result = assemble(str(src))
    assert result["hex"] == str(tmp_path / "beside.hex")
    assert (tmp_path / "beside.json").exists() and (tmp_path / "beside.lst").exists()


def test_assemble_writes_nothing_for_a_bad_program(tmp_path):
    src = tmp_path / "bad.il"
    src.write_text("LD I0.0\nREAD FBY 0\n")
    with pytest.raises(SourceError) as info:
        assemble(str(src), str(tmp_path))
    assert "parallel mode" in info.value.message
    assert not (tmp_path / "bad.hex").exists()


def test_assemble_uses_the_configuration(tmp_path):
    src = tmp_path / "big.il"
    src.write_text("NOP\nNOP\nNOP\n")
    with pytest.raises(SourceError) as info:
        assemble(str(src), config=Config(prog_words=3))
    assert "program too large" in info.value.message
