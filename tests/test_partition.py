"""The partitioning compiler of parallel mode (bitbyte/compiler/) and its
co-simulation (bitbyte/ref/parsim.py).

The directed tests spell out, by hand, the two parts each small program must give
(instruction lists in the form `mnemonic address`, the parts' END / END_B included);
the random tests run partitioned programs under random interleavings of the two
processors against the serial reference and require the same scan results, and no
deadlock."""
from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from bitbyte.lang.config import Config
from bitbyte.encoding.encoder import encode
from bitbyte.lang.errors import SourceError
from bitbyte.lang.parser import parse, parse_file
from bitbyte.ref.parsim import (POLICIES, ChannelError, Deadlock, ParSim,
                                serial_states, state_snapshot)
from bitbyte.compiler.estimate import estimate
from bitbyte.compiler.partition import partition
from bitbyte.compiler.report import part_listing, report_text, side_by_side
from bitbyte.lang.parts import TO_BIT, TO_BYTE
from bitbyte.lang.stimulus import load_stimulus, parse_stimulus
from randprog import (matches_serial, plant_stimulus, random_mixed_program,
                      random_mixed_stimulus, random_parallel_program, strip_timers)

ROOT = Path(__file__).resolve().parents[1]
FIG5 = ROOT / "examples" / "fig5.il"
FIG5_STIM = ROOT / "examples" / "fig5.stim.csv"


def split(text: str, channels: int = 4, **kw):
    return partition(parse("t.il", text), channels, **kw)


def show(instrs) -> list[str]:
    return [f"{i.mnemonic} {i.operand.address()}" if i.operand is not None else i.mnemonic
            for i in instrs]


def parts(text: str, channels: int = 4, **kw) -> tuple[list[str], list[str]]:
    p = split(text, channels, **kw)
    return show(p.bit), show(p.byte)


# --------------------------------------------------------------------------------------
# Spec §5: the paper's Fig. 5 program and its Fig. 13 partition
# --------------------------------------------------------------------------------------

FIG5_BIT = ["LD I0.0", "O M0.0", "A I0.1", "A I0.2", "= M0.0", "= FBY0",
            "LD FBI0",                              # sync: LD Timer waits for SD Timer
            "LD T1", "= Q0.0", "LD Q0.0", "A FBI1", "= Q0.1", "END"]
FIG5_BYTE = ["L MW1", "READ FBY0", "SD T1",
             "WRITE FBI0",                          # sync: after SD Timer
             "L IW0", "L MW0", ">=I", "WRITE FBI1", "END_B"]
# The paper's Fig. 13 exactly (its Fig. 2 timers: the bit side never waits).
FIG13_BIT = ["LD I0.0", "O M0.0", "A I0.1", "A I0.2", "= M0.0", "= FBY0", "LD T1",
             "= Q0.0", "LD Q0.0", "A FBI0", "= Q0.1", "END"]
FIG13_BYTE = ["L MW1", "READ FBY0", "SD T1", "L IW0", "L MW0", ">=I", "WRITE FBI0",
              "END_B"]


def test_fig5_default_is_fig13_with_a_hardware_wait():
    """By default `LD Timer` waits in hardware for `SD Timer` (instruction bit 16: the
    status buffer's updated bit), so no transfer is needed: the paper's Fig. 13 split,
    52 byte clocks, estimate 55, and serial-equivalent."""
    p = partition(parse_file(str(FIG5)))
    assert show(p.bit) == FIG13_BIT and show(p.byte) == FIG13_BYTE
    assert [i.wait_update for i in p.bit] == [i == 6 for i in range(12)]
    assert p.bit_words[6] == 0x08017001            # LD T1 with bit 16
    e = estimate(p)
    assert (e.byte_clocks, e.clocks) == (52, 55)


def test_fig5_partition_with_the_status_sync():
    p = partition(parse_file(str(FIG5)), hardware_wait=False)
    assert show(p.bit) == FIG5_BIT
    assert show(p.byte) == FIG5_BYTE
    assert [(t.direction, t.channel, t.line) for t in p.transfers] == [
        (TO_BYTE, 0, 24),        # = FBY 0 / READ FBY 0: the RLO for `SD Timer` (line 24)
        (TO_BIT, 0, 25),         # WRITE FBI 0 / LD FBI 0: sync before `LD Timer`
        (TO_BIT, 1, 30)]         # >=I / WRITE FBI 1 / A FBI 1: `A >=I` (line 30)
    assert p.mirrored == []


def test_fig5_paper_partition_is_fig13():
    p = partition(parse_file(str(FIG5)), status_sync=False)
    assert show(p.bit) == FIG13_BIT
    assert show(p.byte) == FIG13_BYTE


def test_fig5_synthesized_instructions_point_at_their_cause():
    p = partition(parse_file(str(FIG5)), hardware_wait=False)
    fby = p.bit[5]
    assert (fby.mnemonic, fby.line, fby.col, fby.synthesized) == ("=", 24, 7, True)
    assert "SD Timer" in fby.note
    sync = p.bit[6]
    assert (sync.line, sync.synthesized) == (25, True) and sync.note.startswith("sync")
    cmp = p.byte[6]                 # the compare of `A >=I`, rewritten
    assert (cmp.mnemonic, cmp.line, cmp.synthesized) == (">=I", 30, True)
    src = p.bit[0]
    assert (src.line, src.synthesized, src.note) == (18, False, "")


def test_fig5_words():
    p = partition(parse_file(str(FIG5)), hardware_wait=False)
    assert p.bit_words == [0x08000000, 0x0C006000, 0x0A000001, 0x0A000002, 0x18006000,
                           0x18009000,             # = FBY 0: opcode `=`, area 9
                           0x08009000,             # LD FBI 0
                           0x08007001, 0x18004000, 0x08004000,
                           0x0A009001,             # A FBI 1
                           0x18004001, 0x01000000]
    assert p.byte_words == [0x8200C001,            # L MW1
                            0xC0009000,            # READ FBY 0
                            0xB0007001,            # SD T1
                            0xC1009000,            # WRITE FBI 0
                            0x8200A000, 0x8200C000,
                            0x94000000,            # >=I
                            0xC1009001,            # WRITE FBI 1
                            0xCF000000]            # END_B
    assert p.pool == []


def test_fig5_report_numbers():
    """Ours: byte part 5 x 10 + 3 x 1 = 53, tail `A FBI 1`, `= Out`, END = 3 -> 56.
    The paper's (no sync): 52 + 3 = 55.  Serial: 9 + 50 + END = 60."""
    ours = estimate(partition(parse_file(str(FIG5)), hardware_wait=False))
    assert (ours.byte_clocks, ours.tail, ours.bit_clocks, ours.clocks, ours.serial) == \
        (53, 3, 13, 56, 60)
    paper = estimate(partition(parse_file(str(FIG5)), status_sync=False))
    assert (paper.byte_clocks, paper.tail, paper.bit_clocks, paper.clocks, paper.serial) \
        == (52, 3, 12, 55, 60)
    text = report_text(partition(parse_file(str(FIG5)), hardware_wait=False))
    assert "bit part:  12 instructions + END = 13 words" in text
    assert "byte part: 8 instructions + END_B = 9 words" in text
    assert "transfers bit -> byte: 1 (channels used: FBY 0)" in text
    assert "transfers byte -> bit: 2 (channels used: FBI 0, FBI 1)" in text
    assert "estimated clocks per scan: 56 = max(byte part 53 + bit tail 3, bit part 13)" \
        in text
    assert "serial mode: 60 clocks per scan" in text
    assert "estimated clocks per scan: 55 = max(byte part 52 + bit tail 3, bit part 12)" \
        in report_text(partition(parse_file(str(FIG5)), status_sync=False))


def test_side_by_side_shape():
    text = side_by_side(split("  LD I0.0\n  L 5\n  SD T1\n  LD I0.1\n  L MW0\n"
                              "  L MW1\n  A >I\n  = Q0.0\n"))
    assert text.splitlines() == [
        "line  bit processor                    byte processor",
        "----  --------------------------       --------------------------",
        "   1  LD    I0.0",
        "   2                                   L     5",
        "   3  =     FBY 0                 -->  READ  FBY 0                ; RLO for `SD T1`",
        "   3                                   SD    T1",
        "   4  LD    I0.1",
        "   5                                   L     MW0",
        "   6                                   L     MW1",
        "   7                                   >I                         ; compare of "
        "`A >I`: the RLO is on the bit side, A there",
        "   7  A     FBI 0                 <--  WRITE FBI 0                ; `A >I`: "
        "compare result to the bit side",
        "   8  =     Q0.0",
        "   9  END                              END_B                      ; end of the scan",
    ]
    # with the RLO on both sides (after the transfer for SD) `A >I` stays whole
    assert parts("  LD I0.0\n  L 5\n  SD T1\n  L MW0\n  L MW1\n  A >I\n  = Q0.0\n") == (
        ["LD I0.0", "= FBY0", "LD FBI0", "= Q0.0", "END"],
        ["L 5", "READ FBY0", "SD T1", "L MW0", "L MW1", "A >I", "WRITE FBI0", "END_B"])


def test_side_by_side_fig5_rows_in_program_order():
    rows = side_by_side(partition(parse_file(str(FIG5)), hardware_wait=False)).splitlines()[2:]
    assert len(rows) == 18                     # 14 source + 3 transfer rows + END
    arrows = [r for r in rows if "-->" in r or "<--" in r]
    assert [("-->" in r, r[6:26].strip(), r[39:60].strip()) for r in arrows] == [
        (True, "=     FBY 0", "READ  FBY 0"),
        (False, "LD    FBI 0", "WRITE FBI 0"),
        (False, "A     FBI 1", "WRITE FBI 1")]


# --------------------------------------------------------------------------------------
# The RLO between the sides
# --------------------------------------------------------------------------------------

def test_compare_feeding_a_bit_combine():
    assert parts("  L MW0\n  L MW1\n  >I\n  A I0.0\n  = Q0.0\n") == (
        ["LD FBI0", "A I0.0", "= Q0.0", "END"],
        ["L MW0", "L MW1", ">I", "WRITE FBI0", "END_B"])


def test_or_compare_with_the_rlo_on_the_bit_side():
    assert parts("  LD I0.0\n  L MW0\n  L MW1\n  O ==I\n  = Q0.0\n") == (
        ["LD I0.0", "O FBI0", "= Q0.0", "END"],
        ["L MW0", "L MW1", "==I", "WRITE FBI0", "END_B"])


def test_and_compare_with_the_rlo_on_the_byte_side():
    assert parts("  L MW0\n  L MW1\n  >I\n  L MW2\n  L MW3\n  A <I\n  = Q0.0\n") == (
        ["LD FBI0", "= Q0.0", "END"],
        ["L MW0", "L MW1", ">I", "L MW2", "L MW3", "A <I", "WRITE FBI0", "END_B"])


def test_compare_with_the_rlo_on_both_sides_runs_as_written():
    # after `= Q0.0` the compare result is on both sides: `O <I` stays a byte instruction
    assert parts("  L MW0\n  L MW1\n  >I\n  = Q0.0\n  L MW2\n  L MW3\n  O <I\n"
                 "  = Q0.1\n") == (
        ["LD FBI0", "= Q0.0", "LD FBI1", "= Q0.1", "END"],
        ["L MW0", "L MW1", ">I", "WRITE FBI0", "L MW2", "L MW3", "O <I", "WRITE FBI1",
         "END_B"])


def test_timer_enable_from_a_bit_condition():
    assert parts("  LD I0.0\n  A I0.1\n  L T#5s\n  SD T2\n") == (
        ["LD I0.0", "A I0.1", "= FBY0", "END"],
        ["L 5000", "READ FBY0", "SD T2", "END_B"])


def test_counter():
    text = ("  LD I0.0\n  CU C1\n  LD I0.1\n  CD C1\n  L C1\n  T MW0\n  LD C1\n"
            "  = Q0.0\n")
    assert parts(text) == (
        ["LD I0.0", "= FBY0", "LD I0.1", "= FBY1",
         "LD FBI0",                          # sync: LD C1 after CU/CD (plain: LD loads)
         "LD C1", "= Q0.0", "END"],
        ["READ FBY0", "CU C1", "READ FBY1", "CD C1", "L C1", "T MW0", "WRITE FBI0",
         "END_B"])


def test_counter_set_and_reset():
    assert parts("  LD I0.2\n  L 7\n  S C1\n  LD I0.3\n  R C1\n") == (
        ["LD I0.2", "= FBY0", "LD I0.3", "= FBY1", "END"],
        ["L 7", "READ FBY0", "S C1", "READ FBY1", "R C1", "END_B"])


def test_parentheses_around_a_compare():
    assert parts("  LD I0.0\n  A(\n  LD I0.1\n  L MW0\n  L MW1\n  O >I\n  )\n"
                 "  = Q0.0\n") == (
        ["LD I0.0", "A(", "LD I0.1", "O FBI0", ")", "= Q0.0", "END"],
        ["L MW0", "L MW1", ">I", "WRITE FBI0", "END_B"])


def test_closing_parenthesis_after_a_plain_compare():
    assert parts("  LD I0.0\n  O(\n  LD I0.1\n  L MW0\n  L MW1\n  ==I\n  )\n"
                 "  = Q0.0\n") == (
        ["LD I0.0", "O(", "LD I0.1", "LD FBI0", ")", "= Q0.0", "END"],
        ["L MW0", "L MW1", "==I", "WRITE FBI0", "END_B"])


def test_load_transfer_arithmetic_leave_the_rlo_where_it_is():
    # the RLO of LD I0.0 stays valid on the bit side across the word instructions
    assert parts("  LD I0.0\n  L 1\n  L 2\n  +I\n  T MW0\n  = Q0.0\n") == (
        ["LD I0.0", "= Q0.0", "END"], ["L 1", "L 2", "+I", "T MW0", "END_B"])


def test_scan_start_rlo_is_on_both_sides():
    # RLO 0 and F_B 0 at scan start: an update first needs no transfer
    assert parts("  CU C1\n  = Q0.0\n") == (["= Q0.0", "END"], ["CU C1", "END_B"])


# --------------------------------------------------------------------------------------
# Jumps
# --------------------------------------------------------------------------------------

def test_forward_jc_skipping_byte_code():
    p = split("  LD I0.0\n  JC skip\n  L 1\n  T MW0\nskip: LD I0.1\n  = Q0.0\n")
    assert (show(p.bit), show(p.byte)) == (
        ["LD I0.0", "= FBY0", "JC SKIP", "LD I0.1", "= Q0.0", "END"],
        ["READ FBY0", "JC_B SKIP", "L 1", "T MW0", "END_B"])
    assert (p.bit_labels, p.byte_labels) == ({"SKIP": 3}, {"SKIP": 4})
    assert p.mirrored == [1]
    assert p.byte_words[1] == 0xC9000004           # JC_B to byte address 4 (END_B)
    assert p.bit_words[2] == 0x21000003            # JC to bit address 3


def test_forward_jcn_gives_jcn_b():
    assert parts("  LD I0.0\n  JCN skip\n  L 1\n  T MW0\nskip: NOP\n")[1] == \
        ["READ FBY0", "JCN_B SKIP", "L 1", "T MW0", "END_B"]


def test_forward_jump_skipping_only_bit_code():
    p = split("  L 1\n  T MW0\n  LD I0.0\n  JCN skip\n  LD I0.1\n  = Q0.0\n"
              "skip: L 2\n  T MW1\n")
    assert (show(p.bit), show(p.byte)) == (
        ["LD I0.0", "JCN SKIP", "LD I0.1", "= Q0.0", "END"],
        ["L 1", "T MW0", "L 2", "T MW1", "END_B"])
    assert p.transfers == [] and p.mirrored == []


def test_backward_loop_with_byte_code():
    text = ("loop: L MW0\n  L 1\n  +I\n  T MW0\n  LD M0.0\n  NOT\n  = M0.0\n"
            "  JC loop\n")
    p = split(text)
    assert (show(p.bit), show(p.byte)) == (
        ["LD M0.0", "NOT", "= M0.0", "= FBY0", "JC LOOP", "END"],
        ["L MW0", "L 1", "+I", "T MW0", "READ FBY0", "JC_B LOOP", "END_B"])
    assert (p.bit_labels, p.byte_labels) == ({"LOOP": 0}, {"LOOP": 0})
    # the loop runs twice per scan, on both sides: MW0 = 2, 4, 6
    for policy in POLICIES:
        sim = ParSim(p, rng=1, policy=policy)
        assert [sim.run_scan() and sim.mw[0] for _ in range(3)] == [2, 4, 6]


def test_byte_loop_on_a_compare_jumps_on_f_b():
    # the condition is the compare: F_B holds it, JC_B needs no transfer; the bit
    # side fetches it (WRITE FBI / LD FBI) for its own JC
    p = split("loop: L MW7\n  L 1\n  +I\n  T MW7\n  L MW7\n  L 3\n  <I\n  JC loop\n")
    assert (show(p.bit), show(p.byte)) == (
        ["LD FBI0", "JC LOOP", "END"],
        ["L MW7", "L 1", "+I", "T MW7", "L MW7", "L 3", "<I", "WRITE FBI0", "JC_B LOOP",
         "END_B"])
    sim = ParSim(p, rng=2)
    assert [sim.run_scan() and sim.mw[7] for _ in range(3)] == [3, 4, 5]


def test_jump_after_a_compare_needs_no_condition_transfer():
    assert parts("  L MW0\n  L MW1\n  >I\n  JC skip\n  L 1\n  T MW2\nskip: = Q0.0\n") == (
        ["LD FBI0", "JC SKIP", "= Q0.0", "END"],
        ["L MW0", "L MW1", ">I", "WRITE FBI0", "JC_B SKIP", "L 1", "T MW2", "END_B"])


JOIN = ("  LD I0.0\n  JC la\n  LD I0.1\n  JU lb\nla: L MW0\n  L MW1\n  >I\n"
        "lb: CU C1\n  L C1\n  T MW2\n")


def test_join_point_assumes_the_rlo_on_the_bit_side_only():
    """At lb the fall-through has the compare on both sides, but the JU path left F_B
    holding the JC condition: CU must get the RLO from the bit side.  JU lb skips byte
    code (mirrored), and that JU_B makes JC la skip byte code too (mirrored on the
    second pass)."""
    p = split(JOIN)
    assert (show(p.bit), show(p.byte)) == (
        ["LD I0.0", "= FBY0", "JC LA", "LD I0.1", "JU LB", "LD FBI0", "= FBY1", "END"],
        ["READ FBY0", "JC_B LA", "JU_B LB", "L MW0", "L MW1", ">I", "WRITE FBI0",
         "READ FBY1", "CU C1", "L C1", "T MW2", "END_B"])
    assert (p.bit_labels, p.byte_labels) == ({"LA": 5, "LB": 6}, {"LA": 3, "LB": 7})
    assert p.mirrored == [1, 3]
    stim = "scan,I0.0,I0.1,IW0\n0,0,1,0\n1,0,0,0\n2,0,1,0\n3,1,1,0\n4,0,1,0\n"
    assert_same_as_serial(p, stim, scans=6)


def test_end_in_the_middle_ends_both_sides():
    p = split("  LD I0.0\n  JCN more\n  L 1\n  T MW0\n  END\nmore: L 2\n  T MW0\n")
    assert (show(p.bit), show(p.byte)) == (
        ["LD I0.0", "= FBY0", "JCN MORE", "END", "END"],
        ["READ FBY0", "JCN_B MORE", "L 1", "T MW0", "END_B", "L 2", "T MW0", "END_B"])
    assert_same_as_serial(p, "scan,I0.0\n0,1\n1,0\n2,1\n", scans=3)


def test_refresh_first_in_the_bit_part_needs_no_nop():
    # in the latch clock REFRESH is a second latch (IR/IF := 0), as serially after the
    # byte work in front of it with scan-keyed pins: no NOP is put before it
    p = split("  L 1\n  T MW0\n  REFRESH\n  LD IR0.0\n  = Q0.0\n")
    assert show(p.bit) == ["REFRESH", "LD IR0.0", "= Q0.0", "END"]
    assert_same_as_serial(p, "scan,I0.0\n0,0\n1,1\n2,1\n3,0\n4,1\n", scans=5)
    assert show(split("  REFRESH\n  L 1\n  T MW0\n  LD IR0.0\n  = Q0.0\n").bit)[0] == \
        "REFRESH"


# --------------------------------------------------------------------------------------
# Timer / counter status: reads wait for earlier updates, updates for earlier reads
# --------------------------------------------------------------------------------------

def test_status_read_after_update_waits_in_hardware():
    """The update precedes the read in one straight stretch: instruction bit 16."""
    p = split("  LD I0.0\n  L 10\n  SD T1\n  LD I0.1\n  A T1\n  = Q0.0\n")
    assert (show(p.bit), show(p.byte)) == (
        ["LD I0.0", "= FBY0", "LD I0.1", "A T1", "= Q0.0", "END"],
        ["L 10", "READ FBY0", "SD T1", "END_B"])
    assert [i.wait_update for i in p.bit] == [False, False, False, True, False, False]
    # not in one stretch (a jump target in between): the channel round trip instead
    q = split("  LD I0.0\n  L 10\n  SD T1\n  LD I0.2\n  JC here\nhere: LD I0.1\n"
              "  A T1\n  = Q0.0\n")
    assert not any(i.wait_update for i in q.bit) and "LD FBI0" in show(q.bit)


def test_status_read_after_update_gets_a_sync():
    assert parts("  LD I0.0\n  L 10\n  SD T1\n  LD I0.1\n  A T1\n  = Q0.0\n",
                 hardware_wait=False) == (
        ["LD I0.0", "= FBY0", "LD I0.1",
         "= FBY1", "LD FBI0",               # the RLO makes the round trip: the sync
         "A T1", "= Q0.0", "END"],
        ["L 10", "READ FBY0", "SD T1", "READ FBY1", "WRITE FBI0", "END_B"])


def test_status_read_without_update_needs_no_sync():
    assert parts("  LD I0.1\n  A T1\n  = Q0.0\n  L MW0\n  T MW1\n") == (
        ["LD I0.1", "A T1", "= Q0.0", "END"], ["L MW0", "T MW1", "END_B"])


def test_update_after_read_forces_a_transfer():
    # the RLO (the compare) is on both sides after `= Q0.1`: CU could run at once, but
    # must not overtake `LD C2` -> = FBY 0 / READ FBY 0 anyway
    assert parts("  LD C2\n  = Q0.0\n  L 3\n  L 4\n  <I\n  = Q0.1\n  CU C2\n") == (
        ["LD C2", "= Q0.0", "LD FBI0", "= Q0.1", "= FBY0", "END"],
        ["L 3", "L 4", "<I", "WRITE FBI0", "READ FBY0", "CU C2", "END_B"])
    # without the read: no transfer before CU
    assert parts("  LD I0.0\n  = Q0.0\n  L 3\n  L 4\n  <I\n  = Q0.1\n  CU C2\n")[1] == \
        ["L 3", "L 4", "<I", "WRITE FBI0", "CU C2", "END_B"]


def test_update_after_read_with_the_rlo_only_on_the_byte_side():
    # round trip: to the bit side first, then back (the value must be the RLO)
    assert parts("  LD C2\n  = Q0.0\n  L 3\n  L 4\n  <I\n  CU C2\n") == (
        ["LD C2", "= Q0.0", "LD FBI0", "= FBY0", "END"],
        ["L 3", "L 4", "<I", "WRITE FBI0", "READ FBY0", "CU C2", "END_B"])


def test_status_in_a_loop_follows_the_control_flow_not_the_program_order():
    """LD T3 at the top of the loop comes after SD T3 of the previous iteration: it
    gets a sync although no update precedes it in program order; SD T3 gets the
    forced transfer (LD T3 precedes it)."""
    p = split("top: LD T3\n  = Q0.0\n  LD I0.0\n  L 5\n  SD T3\n  LD M1.0\n  NOT\n"
              "  = M1.0\n  JC top\n")
    assert (show(p.bit), show(p.byte)) == (
        ["LD FBI0", "LD T3", "= Q0.0", "LD I0.0", "= FBY0", "LD M1.0", "NOT", "= M1.0",
         "= FBY1", "JC TOP", "END"],
        ["WRITE FBI0", "L 5", "READ FBY0", "SD T3", "READ FBY1", "JC_B TOP", "END_B"])


def test_status_read_after_a_transfer_needs_no_sync():
    """A byte -> bit transfer after the update already holds the bit side until the
    byte side has passed the update: the read far below needs no sync of its own."""
    p = split("  LD I0.0\n  L 10\n  SD T1\n  L IW0\n  L 5\n  >I\n  = Q0.0\n"
              "  LD I0.2\n  JC here\n  LD I0.3\n  = Q0.2\nhere: LD I0.1\n  A T1\n"
              "  = Q0.1\n", schedule=False)
    assert show(p.bit) == ["LD I0.0", "= FBY0", "LD FBI0", "= Q0.0", "LD I0.2",
                           "JC HERE", "LD I0.3", "= Q0.2", "LD I0.1", "A T1", "= Q0.1",
                           "END"]
    assert not any(i.wait_update for i in p.bit)
    # a path that skips the transfer (JC over it) leaves the update unsynced: a sync
    q = split("  LD I0.0\n  L 10\n  SD T1\n  LD I0.2\n  JC here\n  L IW0\n  L 5\n"
              "  >I\n  = Q0.0\nhere: LD I0.1\n  A T1\n  = Q0.1\n", schedule=False)
    assert show(q.bit)[-6:] == ["LD I0.1", "= FBY2", "LD FBI1", "A T1", "= Q0.1", "END"]
    assert sum(t.reason.startswith("sync") for t in q.transfers) == 1


def test_update_after_a_transfer_to_the_byte_side_needs_no_extra_one():
    """`CU C2` after `LD C2`: a bit -> byte transfer between them (here the enable of
    SD T1) already orders the update after the read."""
    p = split("  LD C2\n  = Q0.0\n  L 10\n  SD T1\n  L 3\n  L 4\n  >I\n  CU C2\n",
              schedule=False)
    assert show(p.byte) == ["L 10", "READ FBY0", "SD T1", "L 3", "L 4", ">I", "CU C2",
                            "END_B"]


# --------------------------------------------------------------------------------------
# The bit side's schedule: rungs move inside a block when it saves waiting
# --------------------------------------------------------------------------------------

SCHED = ("  L IW0\n  L 5\n  >I\n  A I0.0\n  = Q0.0\n"       # waits for the compare
         "  LD I0.1\n  A I0.2\n  = Q0.1\n"                   # independent
         "  LD I0.3\n  AN I0.4\n  = Q0.2\n"                  # independent
         "  LD Q0.1\n  = Q0.3\n")


def test_schedule_hoists_independent_rungs_past_a_wait():
    p = split(SCHED)
    assert show(p.bit) == ["LD I0.1", "A I0.2", "= Q0.1", "LD I0.3", "AN I0.4", "= Q0.2",
                           "LD FBI0", "A I0.0", "= Q0.0", "LD Q0.1", "= Q0.3", "END"]
    assert show(p.byte) == ["L IW0", "L 5", ">I", "WRITE FBI0", "END_B"]
    moved, before, after = p.schedule
    assert (before, after) == (43, 37) and moved > 0
    assert "rungs moved" in report_text(p)
    # off: program order
    assert show(split(SCHED, schedule=False).bit)[:3] == ["LD FBI0", "A I0.0", "= Q0.0"]
    # the paper's mode (no status sync, used by free-running mode) is not scheduled
    assert split(SCHED, status_sync=False).schedule is None


def test_schedule_keeps_data_dependencies():
    """A rung that reads what the waiting rung writes (Q0.0) stays behind it, and a rung
    writing what it reads (I-image: read only; M5.0 here) does not overtake it."""
    p = split("  L IW0\n  L 5\n  >I\n  A M5.0\n  = Q0.0\n"
              "  LD Q0.0\n  = Q0.1\n  LD I0.1\n  = M5.0\n  LD I0.2\n  = Q0.2\n"
              "  LD I0.3\n  = Q0.3\n  LD I0.4\n  = Q0.4\n")
    b = show(p.bit)
    assert b.index("LD FBI0") < b.index("LD Q0.0") and b.index("LD FBI0") < b.index("= M5.0")
    assert b.index("LD I0.3") < b.index("LD FBI0")        # this one did move up


def test_schedule_moves_a_timer_enable_up_before_a_wait():
    """The byte side needs the enable of SD T2 (= FBY) right after its compare; the
    enable's rung does not depend on the compare's, so it goes first."""
    p = split("  L IW0\n  L 5\n  >I\n  A I0.0\n  = Q0.0\n"
              + "".join(f"  LD I1.{n}\n  = M1.{n}\n" for n in range(8))
              + "  LD I0.5\n  L 7\n  SD T2\n  LD I0.6\n  = Q0.6\n")
    b = show(p.bit)
    assert b.index("= FBY0") < b.index("LD FBI0")
    q = split("  L IW0\n  L 5\n  >I\n  A I0.0\n  = Q0.0\n"
              + "".join(f"  LD I1.{n}\n  = M1.{n}\n" for n in range(8))
              + "  LD I0.5\n  L 7\n  SD T2\n  LD I0.6\n  = Q0.6\n", schedule=False)
    assert estimate(p).clocks <= estimate(q).clocks
    assert p.schedule[2] < p.schedule[1]


def test_schedule_keeps_the_rung_a_label_continues_last():
    """`here: = Q0.2` continues the RLO of the rung before the label: that rung stays
    the block's last although the compare's rung would like to step behind it."""
    p = split("  L IW0\n  L 5\n  >I\n  A I0.0\n  = Q0.0\n  LD I0.1\n  = Q0.1\n"
              "  LD I0.2\n  A I0.3\nhere: = Q0.2\n")
    b = show(p.bit)
    assert b[b.index("= Q0.2") - 2:b.index("= Q0.2") + 1] == ["LD I0.2", "A I0.3", "= Q0.2"]
    stim = "scan,I0.0,I0.1,I0.2,I0.3,IW0\n0,1,0,1,1,9\n1,1,1,0,1,9\n2,0,1,1,1,0\n"
    assert_same_as_serial(p, stim, 3, runs=len(POLICIES))


def test_no_deadlock_check_rejects_a_read_before_the_write_it_needs():
    """The check the schedule relies on: the bit side reading FBI 0 before writing the
    FBY 0 that the byte side needs before it can write FBI 0 is a deadlock."""
    from bitbyte.compiler.schedule import _no_deadlock, _transfer_numbers
    p = split("  LD I0.0\n  L 10\n  SD T1\n  L IW0\n  L 5\n  >I\n  = Q0.0\n",
              schedule=False)
    assert show(p.bit) == ["LD I0.0", "= FBY0", "LD FBI0", "= Q0.0", "END"]
    ok = p.bit
    bad = [ok[2], ok[3], ok[0], ok[1], ok[4]]
    assert _no_deadlock(ok, 0, 5, p.byte, *_transfer_numbers(ok), {})
    assert not _no_deadlock(bad, 0, 5, p.byte, *_transfer_numbers(bad), {})


def test_paper_mode_is_not_serial_equivalent():
    """Without the status sync (Fig. 13 as printed) a bit side that runs ahead reads
    T1 before SD T1 of the same scan: Start_Up comes a scan late."""
    program = parse_file(str(FIG5))
    stim = load_stimulus(str(FIG5_STIM), program.symbols)
    expected = serial_states(program, stim, 10, timers=True)

    def scans(part):
        sim = ParSim(part, stimulus=stim, policy="bit-first", ms_per_scan=1)
        return [(sim.run_scan().values, state_snapshot(sim)) for _ in range(10)]
    assert scans(partition(program)) == expected
    paper = scans(partition(program, status_sync=False))
    # Flag (= the timer's enable; preset MW1 = 0) is 1 in scans 2..7
    assert [v["Q0.0"] for v, _ in expected] == [0, 0, 1, 1, 1, 1, 1, 1, 0, 0]
    assert [v["Q0.0"] for v, _ in paper] == [0, 0, 0, 1, 1, 1, 1, 1, 1, 0]


# --------------------------------------------------------------------------------------
# Channels
# --------------------------------------------------------------------------------------

COUNTERS4 = "".join(f"  LD I0.{n}\n  CU C{n}\n" for n in range(4)) + \
    "".join(f"  L MW{n}\n  L 0\n  A >I\n  = Q0.{n}\n" for n in range(3))


@pytest.mark.parametrize("channels,fby,fbi", [
    (4, [0, 1, 2, 3], [0, 1, 2]),
    (2, [0, 1, 0, 1], [0, 1, 0]),
    (1, [0, 0, 0, 0], [0, 0, 0]),
])
def test_channels_round_robin_per_direction(channels, fby, fbi):
    p = split(COUNTERS4, channels)
    assert [t.channel for t in p.transfers if t.direction == TO_BYTE] == fby
    assert [t.channel for t in p.transfers if t.direction == TO_BIT] == fbi
    reads = [i.operand.index for i in p.byte if i.mnemonic == "READ"]
    writes = [i.operand.index for i in p.bit if i.mnemonic == "="
              and i.operand.area == "FBY"]
    assert reads == writes == fby
    assert p.channels_used(TO_BYTE) == sorted(set(fby))
    stim = "scan,I0.0,I0.1,I0.2,I0.3\n0,1,0,1,0\n1,0,1,1,1\n2,1,1,0,1\n"
    for exchange in ("handshake", "queue"):
        assert_same_as_serial(p, stim, scans=3, exchange=exchange)


def test_channel_count_is_checked():
    program = parse("t.il", "  LD I0.0\n")
    for bad in (0, 5):
        with pytest.raises(ValueError):
            partition(program, bad)


# --------------------------------------------------------------------------------------
# What cannot be partitioned
# --------------------------------------------------------------------------------------

@pytest.mark.parametrize("text,line,col", [
    ("  LD I0.0\n  = FBY 0\n", 2, 3),
    ("  L 1\n  READ FBY0\n", 2, 3),
    ("  LD FBI1\n", 1, 3),
])
def test_exchange_instructions_in_a_mixed_program(text, line, col):
    with pytest.raises(SourceError) as info:
        split(text)
    assert (info.value.line, info.value.col) == (line, col)
    assert "inserted by the partitioning compiler" in info.value.message


# --------------------------------------------------------------------------------------
# Hand-partitioned programs: BIT: / BYTE: sections
# --------------------------------------------------------------------------------------

HAND = """VAR
  Start AT I0.0; Stop AT I0.1; BLK AT I0.2; Flag AT M0.0; Timer AT T1
  Start_Up AT Q0.0; Out AT Q0.1; SP_cur AT IW0; SP_nom AT MW0; Time AT MW1
END_VAR
BIT:
  LD Start
  O Flag
  A Stop
  A BLK
  = Flag
  = FBY 0
  LD FBI 0        ; wait for SD Timer
  LD Timer
  = Start_Up
  LD Start_Up
  A FBI 1
  = Out
BYTE:
  L Time
  READ FBY 0
  SD Timer
  WRITE FBI 0
  L SP_cur
  L SP_nom
  >=I
  WRITE FBI 1
  JCN skip
  L 1
  T MW5
skip: END
"""


def test_hand_partitioned_program_is_taken_verbatim():
    program = parse("hand.il", HAND)
    assert {i.section for i in program.instrs} == {"BIT", "BYTE"}
    p = partition(program)
    assert p.hand_partitioned
    assert show(p.bit) == FIG5_BIT
    assert show(p.byte) == FIG5_BYTE[:-1] + ["JCN_B SKIP", "L 1", "T MW5", "END_B"]
    assert p.byte_labels == {"SKIP": 11} and p.bit_labels == {}
    assert p.byte_words[8] == 0xCA00000B            # JCN_B 11
    assert p.warnings == []
    # and it behaves as the serial Fig. 5 (plus MW5 = 1 while Out is 0)
    stim = load_stimulus(str(FIG5_STIM), program.symbols)
    serial = serial_states(parse_file(str(FIG5)), stim, 10, timers=True)
    for policy in POLICIES:
        sim = ParSim(p, stimulus=stim, policy=policy, rng=3, ms_per_scan=1)
        for rec, (values, _) in zip(sim.run(10), serial):
            assert {k: rec.values[k] for k in values} == values


def test_hand_partitioned_labels_at_a_section_end():
    p = partition(parse("t.il", "BIT:\n  LD I0.0\n  JC e\n  NOP\ne:\nBYTE: L 1\n"
                                "  T MW0\n"))
    assert (show(p.bit), show(p.byte)) == (["LD I0.0", "JC E", "NOP", "END"],
                                           ["L 1", "T MW0", "END_B"])
    assert p.bit_labels == {"E": 3}


def test_hand_partitioned_channel_count_warning():
    p = partition(parse("t.il", "BIT:\n  LD I0.0\n  = FBY 1\nBYTE:\n  L 1\n"))
    assert p.warnings and "FBY 1: 1 write(s) on the bit side, 0 read(s)" in p.warnings[0]
    assert "warning: channel FBY 1" in report_text(p)


@pytest.mark.parametrize("text,line,col,what", [
    ("BIT:\n  L MW0\n", 2, 3, "byte instruction"),
    ("BIT:\n  LD I0.0\n  CU C1\n", 3, 3, "byte instruction"),
    ("BYTE:\n  LD I0.0\n", 2, 3, "bit instruction"),
    ("BYTE:\n  L 1\n  NOP\n", 3, 3, "bit instruction"),
    ("BIT:\n  LD I0.0\n  S FBY 0\n", 3, 3, "only `= FBY k`"),
    ("BIT:\n  JU lab\nBYTE:\nlab: L 1\n", 2, 6, "BYTE: section"),
    ("  LD I0.0\nBYTE:\n  L 1\n", 2, 1, "outside any section"),
    ("BIT:\n  A(\n  LD I0.0\nBYTE:\n  L 1\n", 2, 3, "unbalanced parentheses"),
    ("lab: BIT:\n  LD I0.0\n", 1, 6, "start of its line"),
])
def test_section_errors(text, line, col, what):
    with pytest.raises(SourceError) as info:
        parse("t.il", text)
    assert (info.value.line, info.value.col) == (line, col), info.value.message
    assert what in info.value.message


def test_serial_mode_rejects_a_hand_partitioned_program():
    with pytest.raises(SourceError) as info:
        encode(parse("t.il", "BIT:\n  LD I0.0\n  = Q0.0\n"))
    assert (info.value.line, info.value.col) == (2, 3)
    assert "parallel mode only" in info.value.message


def test_cosim_detects_deadlock_and_leftover_conditions():
    """The co-simulator must be able to fail: a read nobody writes deadlocks, a write
    nobody reads is left over at END."""
    stuck = partition(parse("t.il", "BIT:\n  LD FBI 0\n  = Q0.0\nBYTE:\n  L 1\n"))
    with pytest.raises(Deadlock):
        ParSim(stuck).run_scan()
    left = partition(parse("t.il", "BIT:\n  LD I0.0\n  = FBY 2\nBYTE:\n  L 1\n"))
    with pytest.raises(ChannelError):
        ParSim(left).run_scan()


# --------------------------------------------------------------------------------------
# bitbyte asm --mode parallel
# --------------------------------------------------------------------------------------

def bitbyte(*args):
    proc = subprocess.run([sys.executable, "-m", "bitbyte.cli", *map(str, args)],
                          capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert "Traceback" not in proc.stderr, proc.stderr
    return proc


def test_asm_parallel_writes_both_images_listing_report_json(tmp_path):
    proc = bitbyte("asm", FIG5, "--mode", "parallel", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.splitlines() == [f"wrote {tmp_path / name}" for name in (
        "fig5.bit.hex", "fig5.byte.hex", "fig5.lst", "fig5.partition.txt", "fig5.json")]
    p = partition(parse_file(str(FIG5)))      # the default: hardware wait, Fig. 13
    assert (tmp_path / "fig5.bit.hex").read_text() == "".join(
        f"{w:08X}\n" for w in p.bit_words)
    assert (tmp_path / "fig5.byte.hex").read_text() == "".join(
        f"{w:08X}\n" for w in p.byte_words)
    report = (tmp_path / "fig5.partition.txt").read_text()
    assert "estimated clocks per scan: 55" in report and "READ  FBY 0" in report
    listing = (tmp_path / "fig5.lst").read_text()
    assert "0005  18009000    24: =     FBY 0" in listing
    assert "0006  C1009000    30: WRITE FBI 0" in listing
    import json
    summary = json.loads((tmp_path / "fig5.json").read_text())
    assert (summary["mode"], summary["bit_words"], summary["byte_words"]) == \
        ("parallel", 12, 8)
    assert summary["estimate"]["clocks"] == 55
    assert [t["direction"] for t in summary["transfers"]] == [TO_BYTE, TO_BIT]
    assert not (tmp_path / "fig5.pool.hex").exists()


def test_asm_parallel_constant_pool(tmp_path):
    src = tmp_path / "big.il"
    src.write_text("  LD I0.0\n  L T#3h\n  SD T1\n")
    proc = bitbyte("asm", src, "--mode", "parallel")
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "big.pool.hex").read_text() == "00A4CB80\n"   # 10 800 000 ms
    assert (tmp_path / "big.byte.hex").read_text().split()[0] == "81000000"


def test_asm_parallel_error_writes_nothing(tmp_path):
    src = tmp_path / "bad.il"
    src.write_text("  LD I0.0\n  = FBY 0\n")
    proc = bitbyte("asm", src, "--mode", "parallel", "-o", tmp_path / "out")
    assert proc.returncode == 1
    assert proc.stderr.startswith(f"{src}:2:3: ")
    assert not (tmp_path / "out").exists()


def test_part_listing_shows_labels_and_targets():
    text = part_listing(split("  LD I0.0\n  JC skip\n  L 1\n  T MW0\nskip: LD I0.1\n"))
    assert "0001  C9000004     2: JC_B  skip  -> 0004" in text
    assert "                skip:" in text


# --------------------------------------------------------------------------------------
# Semantics without hardware: random programs, random interleavings, vs serial
# --------------------------------------------------------------------------------------

SCANS = 8


def assert_same_as_serial(part, stim_text, scans, timers=False, runs=4,
                          exchange="handshake", seed=0, queue_depth=4):
    """Every scan of `runs` random interleavings equals serial mode; a scan serial
    mode does not finish (watchdog) must not finish in parallel either."""
    stim = parse_stimulus(stim_text) if isinstance(stim_text, str) else stim_text
    expected = serial_states(part.program, stim, scans, timers)
    for run in range(runs):
        sim = ParSim(part, Config(), stim, exchange=exchange, rng=seed * 101 + run,
                     max_steps=30_000, ms_per_scan=1 if timers else None,
                     queue_depth=queue_depth)
        matches_serial(sim, expected, scans, lambda scan: f"scan {scan}, run {run}",
                       side_by_side(part))


def scan_stimulus(seed: int) -> str:
    """random_mixed_stimulus, keyed by scan (a t_us one would make PI and IW reads
    depend on when they happen, which differs between the modes by design)."""
    k = 0
    while True:
        text = random_mixed_stimulus(seed * 7919 + k, SCANS, 3000)
        if text.startswith("scan"):
            return text
        k += 1


@pytest.mark.parametrize("name", ["fig5", "interlock"])
def test_examples_with_scan_stimuli_match_serial(name):
    """The examples whose stimuli are keyed by scan (fig14 and star_delta use t_us
    rows: their IW / pin timing differs between the modes by design)."""
    program = parse_file(str(ROOT / "examples" / f"{name}.il"))
    stim = load_stimulus(str(ROOT / "examples" / f"{name}.stim.csv"), program.symbols)
    assert_same_as_serial(partition(program), stim, 20, timers=True, runs=len(POLICIES))


def _check_random(seed: int, source: str, timers: bool) -> None:
    import random
    rng = random.Random(seed)
    part = partition(parse(f"rand{seed}.il", source), rng.choice([1, 2, 4]))
    assert_same_as_serial(part, scan_stimulus(seed), SCANS, timers=timers, runs=3,
                          exchange=rng.choice(["handshake", "queue"]), seed=seed,
                          queue_depth=rng.choice([1, 2, 4]))


BATCH = 30


@pytest.mark.parametrize("batch", range(10))
def test_random_mixed_programs_without_timers_match_serial(batch):
    """300 random_mixed_program()s, timers stripped, against RefSim itself."""
    for seed in range(batch * BATCH, (batch + 1) * BATCH):
        _check_random(seed, strip_timers(random_mixed_program(seed)), timers=False)


@pytest.mark.parametrize("batch", range(10))
def test_random_parallel_programs_with_timers_match_serial(batch):
    """300 programs shaped for the compiler's special cases (tests/randprog.py
    random_parallel_program), timers kept: both sides see now = scan number (ms)."""
    for seed in range(batch * BATCH, (batch + 1) * BATCH):
        _check_random(seed, random_parallel_program(seed), timers=True)


def test_random_programs_run_seed():
    """A further 40 programs from this run's seed (BITBYTE_SEED, see conftest)."""
    base = int(os.environ.get("BITBYTE_SEED", "0")) * 1000 + 10_000
    for seed in range(base, base + 20):
        _check_random(seed, strip_timers(random_mixed_program(seed)), timers=False)
        _check_random(seed, random_parallel_program(seed), timers=True)


# --------------------------------------------------------------------------------------
# Table-1-style programs (bench/gen_programs.py rungs: interlocks, edges, latches, step
# sequences, timers, counters, compares, arithmetic, jumps over blocks): the schedule
# moves many rungs in these, so they are its random test
# --------------------------------------------------------------------------------------

def crowd_addresses(text: str) -> str:
    """Fold the generator's markers onto M0..M3 (edge memories onto M4..M5) and its
    outputs onto Q0..Q1: rungs then share many bits, so a schedule that broke a data
    dependency would show in the results."""
    def marker(m):
        b, n = int(m.group(1)), m.group(2)
        return f"M{4 + b % 2 if b >= 200 else b % 2}.{n}"
    text = re.sub(r"\bM(\d+)\.(\d)", marker, text)
    return re.sub(r"\bQ(\d+)\.(\d)", lambda m: f"Q{int(m.group(1)) % 2}.{m.group(2)}",
                  text)


def _plant_program(seed: int) -> str:
    sys.path.insert(0, str(ROOT / "bench"))
    import gen_programs
    import random
    rng = random.Random(seed)
    n_words = rng.randrange(5, 40)
    g = gen_programs.generate(rng.randrange(40, 160), n_words, seed,
                              jumps=rng.randrange(0, 4))
    text = "\n".join(g.lines) + "\n"
    if seed % 2:
        # and, before some rungs, a label and a coil that continues the RLO of the rung
        # before the label (a block boundary the schedule must not reorder across)
        lines, k = [], 0
        for line in text.splitlines():
            if line.startswith("//") and rng.random() < 0.1:
                k += 1
                lines += [f"cut{k}:", "      =     M3.7"]
            lines.append(line)
        return crowd_addresses("\n".join(lines) + "\n")
    return text


def _plant_stimulus(seed: int, scans: int) -> str:
    import random
    return plant_stimulus(random.Random(seed ^ 0x7AB1E), scans, min_flips=0, word_p=0.5)


@pytest.mark.parametrize("batch", range(4))
def test_scheduled_plant_programs_match_serial(batch):
    """40 generated plant programs: with timers (now = scan number on both sides) and
    without, every interleaving policy, handshake (1, 2, 4 channels) and queues of
    depth 1, 2, 4: every scan equals serial mode and nothing deadlocks."""
    import random
    scheduled = 0
    for seed in range(batch * 10, batch * 10 + 10):
        rng = random.Random(seed)
        source = _plant_program(seed)
        for text, timers in ((source, True), (strip_timers(source), False)):
            part = partition(parse(f"plant{seed}.il", text), rng.choice([1, 2, 4]))
            scheduled += part.schedule is not None
            assert_same_as_serial(part, _plant_stimulus(seed, 6), 6, timers=timers,
                                  runs=len(POLICIES), exchange=rng.choice(["handshake",
                                                                           "queue"]),
                                  seed=seed, queue_depth=rng.choice([1, 2, 4]))
    assert scheduled >= 10, f"only {scheduled} of 20 programs were rescheduled"


def _rungs(instrs) -> list[list[int]]:
    """Indices of instrs split into rungs: a new one at every LD/LDN/SET/CLR outside
    parentheses and after every jump / END / label (an independent re-statement of the
    compiler's rule, for the checker below)."""
    out, depth = [], 0
    for n, ins in enumerate(instrs):
        m = ins.mnemonic
        starts = (depth == 0 and m in ("LD", "LDN", "SET", "CLR")) or bool(ins.labels) \
            or not out or instrs[n - 1].mnemonic in ("JU", "JC", "JCN", "END")
        if starts:
            out.append([])
        out[-1].append(n)
        depth += (m.endswith("(")) - (m == ")")
    return out


def _check_schedule(original, scheduled, labels):
    """The scheduled bit part is the original one with whole rungs swapped, and only
    where nothing can tell: no two swapped instructions touch the same bit (one of them
    writing it), `= FBY` writes keep their order and so do FBI reads, an FBI read /
    bit-16 wait never moves ahead of a `= FBY` write, T / C reads keep their place
    among transfers, nothing moves across a label, jump, END, REFRESH, NOP or PI / PQ."""
    assert sorted(map(id, original)) == sorted(map(id, scheduled))
    pos = {id(ins): n for n, ins in enumerate(scheduled)}
    # labels: per position of the unscheduled part (the label attributes of the
    # instruction objects follow the positions, so they are taken from that part)
    for rung in _rungs(original):
        where = [pos[id(original[n])] for n in rung]
        assert where == list(range(where[0], where[0] + len(where))), "rung split"
    block, b = [], 0
    for n, ins in enumerate(original):
        if labels[n] or (n and original[n - 1].mnemonic in ("JU", "JC", "JCN", "END")):
            b += 1
        block.append(b)
    for n, ins in enumerate(original):
        assert block[pos[id(ins)]] == block[n], "moved out of its block"
    for n in range(1, len(original)):
        if block[n] != block[n - 1] and original[n].mnemonic not in ("LD", "LDN", "SET",
                                                                     "CLR"):
            # the code after the block boundary continues the RLO (or the open
            # parentheses) of the block's last instruction: that must stay last
            assert pos[id(original[n - 1])] == n - 1, "a continued rung moved"
    assert [list(ins.labels) for ins in scheduled] == labels, "labels must stay put"

    def info(ins):
        m, op = ins.mnemonic, ins.operand
        area = op.area if op is not None and op.kind in ("bit", "index") else None
        barrier = m in ("JU", "JC", "JCN", "END", "REFRESH", "NOP") or area in ("PI", "PQ")
        key = (area, op.bit_number) if op is not None and op.kind == "bit" else None
        writes = m in ("=", "S", "R", "FP", "FN") and area not in ("FBY",)
        return dict(barrier=barrier, key=key, writes=writes,
                    fby=area == "FBY", fbi=area == "FBI",
                    wait=bool(getattr(ins, "wait_update", False)),
                    status=area in ("T", "C"))
    inf = [info(i) for i in original]
    for i in range(len(original)):
        for j in range(i + 1, len(original)):
            if pos[id(original[i])] < pos[id(original[j])]:
                continue                                       # not swapped
            a, b = inf[i], inf[j]
            assert not (a["barrier"] or b["barrier"])
            if a["key"] is not None and a["key"] == b["key"]:
                assert not (a["writes"] or b["writes"]), "data dependency broken"
            assert not (a["fby"] and b["fby"]) and not (a["fbi"] and b["fbi"])
            assert not (a["fby"] and (b["fbi"] or b["wait"])), "read moved before write"
            if a["status"] or b["status"]:
                assert not (a["fby"] or a["fbi"] or b["fby"] or b["fbi"])


@pytest.mark.parametrize("batch", range(4))
def test_schedule_swaps_only_independent_rungs(batch):
    """An independent check of the schedule's rule on 100 programs per batch (plant
    programs, crowded and not, and the compiler-shaped random ones)."""
    import random
    swapped = 0
    for seed in range(batch * 100, batch * 100 + 100):
        rng = random.Random(seed)
        text = _plant_program(seed) if seed % 3 else random_parallel_program(seed)
        program = parse(f"s{seed}.il", text)
        ch = rng.choice([1, 2, 4])
        before = partition(program, ch, schedule=False)
        after = partition(program, ch)
        assert show(after.byte) == show(before.byte)
        assert [(t.direction, t.channel) for t in after.transfers] == \
            [(t.direction, t.channel) for t in before.transfers]
        assert show(before.bit) == show([r.bit for r in after.rows if r.bit is not None])
        # program order: the rows (the two partitions are separate objects)
        _check_schedule([r.bit for r in after.rows if r.bit is not None], after.bit,
                        [list(ins.labels) for ins in before.bit])
        swapped += after.schedule is not None
    assert swapped >= 30


def test_table1_program_schedule():
    """The Table-1-sized benchmark program: the schedule moves rungs and the estimate
    drops; with it serial-equivalent under random interleavings (timers kept)."""
    program = parse_file(str(ROOT / "bench" / "programs" / "table1.il"))
    part = partition(program)
    moved, before, after = part.schedule
    assert moved > 50 and after < before
    assert_same_as_serial(part, _plant_stimulus(1, 4), 4, timers=True, runs=len(POLICIES))
    assert_same_as_serial(part, _plant_stimulus(2, 4), 4, timers=True, runs=2,
                          exchange="queue", queue_depth=1)
