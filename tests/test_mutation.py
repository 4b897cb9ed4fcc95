"""A small fixed sample of `make mutate` (mutation/run_mutate.py): three mutants of
cond_ff built into one netlist and run through its cocotb bench must all be killed
while the unmutated netlist (mutsel 0) passes; and the miter check proves a mutation
that cannot change anything equivalent, and finds the difference a real one makes."""
from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "mutation"))
import mutlib  # noqa: E402
import run_mutate  # noqa: E402


def test_three_cond_ff_mutants_are_killed(tmp_path):
    campaign = next(c for c in run_mutate.CAMPAIGNS if c.name == "cond_ff")
    res = run_mutate.run_tests(campaign, seed=1, count=3, work=tmp_path)
    assert [m["home"] for m in res["mutations"]] == ["cond_ff"] * 3
    assert all(o == "pass" for o, _ in res["baseline"].values()), res["baseline"]
    assert sorted(int(k) for k in res["killed"]) == [1, 2, 3]


@pytest.fixture(scope="module")
def queue_netlist(tmp_path_factory):
    """cond_queue (Depth 4) with three mutations of the saturation test
    `underflows_o != 16'hFFFF`: 1 = bit 13 of the constant stuck at 1 (it is 1: no
    change), 2 = stuck at 0 (the counter stops at 16'hDFFF, 57 343 underflows after
    reset), 3 = the compare inverted (the counter never counts: one underflow shows)."""
    work = mutlib.prepare_dir(tmp_path_factory.mktemp("eq") / "elab")
    script = mutlib.elab_script("cond_queue", {"Depth": 4})
    cands = mutlib.candidates(work, script, ["cond_queue"], "all")
    src = (mutlib.RTL / "cond_queue.v").read_text().splitlines()
    line = next(i for i, t in enumerate(src, 1) if "underflows_o != 16'hFFFF" in t)
    picked = []
    for mode, port, bit in (("const1", "B", 13), ("const0", "B", 13), ("inv", "Y", 0)):
        (m,) = [c for c in cands if c.mode == mode and c.cell.startswith("$ne$")
                and c.port == port and c.portbit == bit
                and any(re.match(rf"cond_queue\.v:{line}\.", s) for s in c.srcs)]
        m.id = len(picked) + 1
        picked.append(m)
    return mutlib.write_netlist(work, script, "cond_queue", picked, "mutants")


def test_a_bit_stuck_at_its_own_constant_is_a_no_op(tmp_path):
    """mutlib.noop reads the netlist the sample was drawn from: of the three
    mutations of queue_netlist, only the first (bit 13 of 16'hFFFF stuck at 1) leaves
    every bit as it was; stuck at 0 and the inverted compare do not."""
    work = mutlib.prepare_dir(tmp_path / "elab")
    script = mutlib.elab_script("cond_queue", {"Depth": 4})
    cands = mutlib.candidates(work, script, ["cond_queue"], "all")
    mutlib.run_yosys(work, script + "write_json d.json\n", "d")
    design = json.loads((work / "d.json").read_text())["modules"]
    src = (mutlib.RTL / "cond_queue.v").read_text().splitlines()
    line = next(i for i, t in enumerate(src, 1) if "underflows_o != 16'hFFFF" in t)
    found = {}
    for mode, port, bit in (("const1", "B", 13), ("const0", "B", 13), ("inv", "Y", 0)):
        (m,) = [c for c in cands if c.mode == mode and c.cell.startswith("$ne$")
                and c.port == port and c.portbit == bit
                and any(re.match(rf"cond_queue\.v:{line}\.", s) for s in c.srcs)]
        found[mode] = mutlib.noop(m, design)
    assert found == {"const1": "B[13] is the constant 1 already", "const0": None, "inv": None}


@pytest.mark.parametrize("memories", [pytest.param(True, marks=pytest.mark.slow), False],
                         ids=["through_memories", "words"])
def test_a_mutation_no_output_reads_is_dead(memories, tmp_path):
    """mutlib.dead on shared_mem's read select `bank_rdata[(rbank * Cores + r) * 32 +: 32]`
    and clearing counter (3 cores, 16 words): bit 31 of the inner product, which the
    product with 32 shifts out of the 32-bit index, is dead; bit 31 of the outer one
    sends the read out of range (an undefined word, not a value the optimiser may
    pick), bit 1 of the clearing counter's next value clears the words in another
    order: neither is dead."""
    work = mutlib.prepare_dir(tmp_path / "elab")
    script = mutlib.elab_script("shared_mem", {"Cores": 3, "SharedWords": 16})
    cands = mutlib.candidates(work, script, ["shared_mem"], "all")
    src = (mutlib.RTL / "shared_mem.v").read_text().splitlines()
    sel = next(i for i, t in enumerate(src, 1) if "bank_rdata[({{(32-IdW)" in t)
    clr = next(i for i, t in enumerate(src, 1) if "clear_q <= clear_q + 1'b1" in t)

    def span(m):   # columns of the expression: the outer product is the longer
        a, b = re.search(r":\d+\.(\d+)-\d+\.(\d+)", m.srcs[0]).groups()
        return int(b) - int(a)

    def pick(kind, line, port, bit, longest=False):
        ms = [c for c in cands if c.cell.startswith(kind) and c.port == port
              and c.portbit == bit and c.mode == "inv"
              and any(re.match(rf"shared_mem\.v:{line}\.", s) for s in c.srcs)]
        return (max if longest else min)(ms, key=span)
    picked = (pick("$mul$", sel, "Y", 31), pick("$mul$", sel, "Y", 31, longest=True),
              pick("$add$", clr, "A", 1))
    assert [mutlib.dead(tmp_path / f"d{k}", script, m, 300, memories=memories)
            for k, m in enumerate(picked)] == [True, False, False]


NEVER_LOADED = """\
module never_loaded (input wire clk, input wire [3:0] a, input wire [3:0] d,
                     output wire y, output wire z);
  reg [3:0] q;                 // no reset, never loaded: a value, not a don't-care
  wire load = 1'b0;
  always @(posedge clk) if (load) q <= d;
  assign y = q[0] ^ a[0];
  assign z = q[1] & a[1];
endmodule
"""


def test_a_register_never_loaded_is_not_a_dont_care(tmp_path):
    """Found by review: with opt_dff removing the register's D path, q became 'x and
    opt_expr folded `x ^ a` and `x & a` to 0, so inverting a[0] or a[1] looked dead
    while y and z do change with it (a miter and both simulators show it)."""
    src = tmp_path / "src"
    src.mkdir()
    (src / "never_loaded.v").write_text(NEVER_LOADED)
    script = "read_verilog -sv never_loaded.v\n" + mutlib.light_elab("never_loaded")
    work = mutlib.prepare_dir(tmp_path / "elab", src)
    cands = mutlib.candidates(work, script, ["never_loaded"], "all")
    xor_a = next(c for c in cands if c.cell.startswith("$xor$") and c.port == "B"
                 and c.mode == "inv")
    and_a = next(c for c in cands if c.cell.startswith("$and$") and c.port == "B"
                 and c.mode == "inv")
    assert [mutlib.dead(tmp_path / f"d{k}", script, m, 300, rtl=src)
            for k, m in enumerate((xor_a, and_a))] == [False, False]


def test_no_op_mutant_is_proved_equivalent(queue_netlist, tmp_path):
    assert mutlib.equivalence(tmp_path, queue_netlist, "cond_queue", 1, 8, 300) == "equivalent"


def test_deep_difference_is_not_called_equivalent(queue_netlist, tmp_path):
    # beyond the k-induction's depth from reset: no proof either way, never "equivalent"
    assert mutlib.equivalence(tmp_path, queue_netlist, "cond_queue", 2, 8, 300) == "unknown"


def test_difference_is_found(queue_netlist, tmp_path):
    assert mutlib.equivalence(tmp_path, queue_netlist, "cond_queue", 3, 8, 300) == "different"


# A difference in the first clocks after power-up only: a register without reset
# counts the clocks, and the mutant drops the one clock in which the output flop
# took the count's pulse. Yosys's equiv_induct proves the induction step alone (pairs
# equal for 5 clocks stay equal), which holds here: the check must not call it
# equivalent for that (the base case from reset is checked; found by review).
EARLY_DIFFERENCE = """\
module early (input clk_i, input rst_ni, input d_i, output reg q_o);
  wire [1:0] mutsel = `MUTSEL;
  reg [2:0] count;                       // no reset: from its zero initial value
  always @(posedge clk_i) if (count != 3'd7) count <= count + 3'd1;
  wire pulse = (mutsel == 2'd1) ? 1'b0 : count == 3'd1;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) q_o <= 1'b0; else q_o <= d_i ^ pulse;
endmodule
"""


def test_an_early_difference_is_not_called_equivalent(tmp_path):
    netlist = tmp_path / "early.v"
    netlist.write_text(EARLY_DIFFERENCE)
    assert mutlib.equivalence(tmp_path / "eq", netlist, "early", 1, 8, 300) == "different"


def test_yosys_equivalence_step(queue_netlist, tmp_path):
    """The step by itself: it proves the no-op mutation, not the visible one."""
    def step(mut):
        work = mutlib.prepare_dir(tmp_path / str(mut))   # Yosys sees this folder only
        (work / "q.v").write_text(queue_netlist.read_text())
        both = "".join(
            f"read_verilog -sv -DMUTSEL={k} q.v\nhierarchy -top cond_queue\n"
            "proc\nflatten\nmemory -nomap\nmemory_map\nopt_clean\nsetundef -zero -init\n"
            f"rename cond_queue {copy}\ndesign -stash {copy}\n"
            for k, copy in ((0, "gold"), (mut, "gate")))
        both += "design -copy-from gold -as gold gold\ndesign -copy-from gate -as gate gate\n"
        return mutlib.yosys_equiv(work, both, f"s{mut}", [mutlib.MUTSEL], 300)
    assert step(1) and not step(3)


# settled_equivalence on a small copy of shared_mem's clearing (four words of four bits,
# solved in seconds; make mutate applies it to shared_mem itself, whose mutants 1-4
# below are the campaign's): 1 = bit 1 of the clearing counter's next value inverted
# (the words cleared in the order 0, 3, 2, 1), 2 = the clearing's data bit 0 stuck at 1
# (every word reads 1 once ready), 3 = bit 1 of the counter's hold value inverted (once
# done, that bit toggles every clock: the counter's low bits differ for ever, and
# nothing reads them then), 4 = bit 0 of the clearing address stuck at 0 (words 1 and 3
# are never cleared: after reset from power-up they are 0 anyway, after a later reset
# they keep what was written). Reset in the first clock, four clearing clocks, the
# registered read: ready and settled at clock 6.
CLEARING_RAM = """\
// A RAM of four words cleared after reset, as shared_mem's banks are (a small copy
// that the checker's tests solve in seconds); `MUTSEL picks a mutant.
module clearing_ram (input clk_i, input rst_ni, input we_i, input [1:0] waddr_i,
                     input [3:0] wdata_i, input [1:0] raddr_i, output [3:0] rdata_o,
                     output ready_o);
  wire [2:0] mutsel = `MUTSEL;
  reg  [3:0] mem [0:3];
  reg  [3:0] rdata_q;
  reg  [2:0] clear_q;                    // 4 when done
  wire       clearing = !clear_q[2];
  // 1: bit 1 of the counter's next value inverted (the words cleared 0, 3, 2, 1)
  wire [2:0] next = (clear_q ^ ((mutsel == 3'd1) ? 3'b010 : 3'b000)) + 3'd1;
  // 3: bit 1 of its hold value inverted (once done it toggles; nothing reads it then)
  wire [2:0] hold = clear_q ^ ((mutsel == 3'd3) ? 3'b010 : 3'b000);
  // 4: the clearing address's bit 0 stuck at 0 (words 1 and 3 never cleared)
  wire [1:0] caddr = clear_q[1:0] & ((mutsel == 3'd4) ? 2'b10 : 2'b11);
  // 2: the clearing's data bit 0 stuck at 1
  wire [3:0] cdata = (mutsel == 3'd2) ? 4'd1 : 4'd0;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) clear_q <= 3'd0;
    else         clear_q <= clearing ? next : hold;
  always @(posedge clk_i) begin
    if (clearing || we_i) mem[clearing ? caddr : waddr_i] <= clearing ? cdata : wdata_i;
    rdata_q <= mem[raddr_i];
  end
  assign rdata_o = rdata_q;
  assign ready_o = !clearing;
endmodule
"""


@pytest.fixture
def clearing_netlist(tmp_path):
    netlist = tmp_path / "clearing_ram.v"
    netlist.write_text(CLEARING_RAM)
    return netlist


def test_another_clearing_order_is_equivalent_once_settled(clearing_netlist, tmp_path):
    settle = mutlib.Settle("ready_o", 6, ("rdata_o",))
    assert mutlib.settled_equivalence(tmp_path / "a", clearing_netlist, "clearing_ram", 1,
                                      settle, 300) == "equivalent"
    assert mutlib.settled_equivalence(tmp_path / "b", clearing_netlist, "clearing_ram", 2,
                                      settle, 300) == "different"
    # a clearing that misses words: equal after the power-up reset (every word starts
    # at 0 there), different after a later one; the check starts anywhere
    assert mutlib.settled_equivalence(tmp_path / "m", clearing_netlist, "clearing_ram", 4,
                                      settle, 300) == "different"
    # a contract the original does not keep (ready after 3 clocks) proves nothing
    early = mutlib.Settle("ready_o", 3, ("rdata_o",))
    assert mutlib.settled_equivalence(tmp_path / "c", clearing_netlist, "clearing_ram", 1,
                                      early, 300) == "different"


def test_a_free_register_must_be_unread_once_settled(clearing_netlist, tmp_path):
    """Settle.free: the counter's low bits differ for ever after mutant 3, so the
    copies are equal once settled only with them left free; leaving free a register the
    outputs read (word 2 of the memory) proves nothing, and a name that is no register
    is refused. (A register loaded from the inputs every clock, as rdata_q, may be left
    free: it is equal again one clock later, which is what the induction step sees.)"""
    strict = mutlib.Settle("ready_o", 6, ("rdata_o",))
    assert mutlib.settled_equivalence(tmp_path / "a", clearing_netlist, "clearing_ram", 3,
                                      strict, 300) == "fail (state)"
    free = mutlib.Settle("ready_o", 6, ("rdata_o",), free=("clear_q",))
    assert mutlib.settled_equivalence(tmp_path / "b", clearing_netlist, "clearing_ram", 3,
                                      free, 300) == "equivalent"
    # freeing a read memory word: the induction step fails (SBY's UNKNOWN)
    read = mutlib.Settle("ready_o", 6, ("rdata_o",), free=("clear_q", "mem[2]"))
    assert mutlib.settled_equivalence(tmp_path / "d", clearing_netlist, "clearing_ram", 1,
                                      read, 300) == "unknown (step)"
    with pytest.raises(mutlib.MutationError, match="no_such_q"):
        mutlib.settled_equivalence(tmp_path / "e", clearing_netlist, "clearing_ram", 1,
                                   mutlib.Settle("ready_o", 6, free=("no_such_q",)), 300)
    with pytest.raises(mutlib.MutationError, match="clearing.*no registers"):
        mutlib.settled_equivalence(tmp_path / "f", clearing_netlist, "clearing_ram", 1,
                                   mutlib.Settle("ready_o", 6, free=("clearing",)), 300)


# Equivalence by contract (mutlib.Contract): a read register a RAM's users read only in
# the clock after their read, and two clearing counters that always step together.
READ_PORT = """\
module rport (input clk_i, input rst_ni, input we_i, input [1:0] wa_i, input [3:0] wd_i,
              input re_i, input [1:0] ra_i, output [3:0] rd_o, output reads_o);
  wire [1:0] mutsel = `MUTSEL;
  reg [3:0] mem [0:3];
  reg [3:0] q;                           // the RAM's output register: no reset
  reg [3:0] reads;                       // reads so far (an output reads it)
  always @(posedge clk_i) begin
    if (we_i) mem[wa_i] <= wd_i;
    // 1: the held word's bit 0 toggles while no read comes (nobody may look then);
    // 2: a read's bit 0 inverted
    if (re_i) q <= {mem[ra_i][3:1], mem[ra_i][0] ^ (mutsel == 2'd2)};
    else      q <= {q[3:1], q[0] ^ (mutsel == 2'd1)};
  end
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) reads <= 4'd0; else if (re_i) reads <= reads + 4'd1;
  assign rd_o = q;
  assign reads_o = reads[3];            // (not all of it: a paired port pins it)
endmodule
"""

TWIN_COUNTERS = """\
module twins (input clk_i, input rst_ni, output ready_o);
  wire [1:0] mutsel = `MUTSEL;
  reg [3:0] a_q, b_q;                    // two clearings of 8 clocks (bit 3: done)
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      a_q <= 4'd0;
      b_q <= 4'd0;
    end else begin
      if (!a_q[3]) a_q <= a_q + 4'd1;
      // 2: b counts in twos (done first)
      if (!b_q[3]) b_q <= b_q + ((mutsel == 2'd2) ? 4'd2 : 4'd1);
    end
  // 1: ready from b alone (a_q always equals b_q)
  assign ready_o = (mutsel == 2'd1) ? b_q[3] : (a_q[3] && b_q[3]);
endmodule
"""


def test_a_read_register_is_compared_where_the_contract_reads_it(tmp_path):
    """Contract.valid / free: mutant 1 changes the read register only where no user
    reads it (equivalent under the contract, not without it); mutant 2 changes what a
    read returns (different from reset); reading the output at other times (after a
    write) or leaving free a register an output reads proves nothing."""
    netlist = tmp_path / "rport.v"
    netlist.write_text(READ_PORT)
    ok = mutlib.Contract(valid={"rd_o": "re_i"}, free=("q",))
    assert mutlib.contract_equivalence(tmp_path / "a", netlist, "rport", 1, ok,
                                       300) == "equivalent"
    assert mutlib.contract_equivalence(tmp_path / "b", netlist, "rport", 2, ok,
                                       300) == "fail (outputs)"
    assert mutlib.contract_equivalence(tmp_path / "c", netlist, "rport", 1,
                                       mutlib.Contract(), 300) == "fail (outputs)"
    wrong = mutlib.Contract(valid={"rd_o": "we_i"}, free=("q",))
    assert mutlib.contract_equivalence(tmp_path / "d", netlist, "rport", 1, wrong,
                                       300) == "fail (outputs)"
    read = mutlib.Contract(valid={"rd_o": "re_i"}, free=("q", "reads"))
    assert mutlib.contract_equivalence(tmp_path / "e", netlist, "rport", 1, read,
                                       300) == "unknown (outputs)"
    with pytest.raises(mutlib.MutationError, match="wd_i is no output or rd_o no input"):
        mutlib.contract_equivalence(tmp_path / "f", netlist, "rport", 1,
                                    mutlib.Contract(valid={"wd_i": "rd_o"}), 300)


def test_registers_that_step_together_are_proved_then_assumed(tmp_path):
    """Contract.same: mutant 1 (ready from one of two twin counters) is equivalent once
    the twins are proved equal in the original, and not without that; a twin claim
    the design does not keep (mutant 2 is not the original: the claim is about the
    original, so a false claim is shown on a module whose counters differ) fails."""
    netlist = tmp_path / "twins.v"
    netlist.write_text(TWIN_COUNTERS)
    same = mutlib.Contract(same=(("a_q", "b_q"),))
    assert mutlib.contract_equivalence(tmp_path / "a", netlist, "twins", 1, same,
                                       300) == "equivalent"
    assert mutlib.contract_equivalence(tmp_path / "b", netlist, "twins", 1,
                                       mutlib.Contract(), 300) == "unknown (outputs)"
    # (b_q differs from the third clock: past the base case's two, the induction fails)
    assert mutlib.contract_equivalence(tmp_path / "c", netlist, "twins", 2, same,
                                       300) == "unknown (outputs)"
    # the claim checked on the original: with the counters unequal there, it fails
    skewed = tmp_path / "skewed.v"
    skewed.write_text(TWIN_COUNTERS.replace("`MUTSEL;", "(`MUTSEL == 0) ? 2'd2 : `MUTSEL;"))
    # (they part in the third clock: past the base case, the induction fails)
    assert mutlib.contract_equivalence(tmp_path / "d", skewed, "twins", 1, same,
                                       300) == "unknown (same)"
