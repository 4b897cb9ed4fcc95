"""The simulation hosts reach the design only through its ports and Verilator's public
API, and the firmware keeps no state outside its bb_state, so that one process runs
several byte processors on one copy of it.

- No Verilator internals in the hosts (sim/*.cpp, sim/*.h, sim/*.vlt, bitbyte/**/*.py):
  no `rootp->` member access, no `__DOT__` signal names, no `___024root` header or
  function, no `public_flat*` configuration. What a trace needs beyond the functional
  ports comes from the observation ports `dbg_*` of rtl/bitbyte_cpu.v / plc_core.v /
  plc_system.v.
- No hierarchical handles in the cocotb hosts (`dut.u_...`, `dut.g_core[...]`,
  `dut.next`): they read ports too.
- The build sizes the hosts load and check against (BB_HW_*, generated into
  firmware_byte/bb_isa.h from bitbyte/lang/definition.toml) are the RTL's parameter
  defaults.
- The firmware objects define no writable data (.data / .bss / common): the HAL
  context in bb_state is the only link to a host.
"""
from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

HOSTS = sorted([*ROOT.glob("sim/*.cpp"), *ROOT.glob("sim/*.h"), *ROOT.glob("sim/*.vlt"),
                *ROOT.glob("bitbyte/**/*.py")])                 # sub-packages too
INTERNALS = re.compile(r"rootp->|__DOT__|___024root|public_flat")
# cocotb: a handle below the toplevel, or the toplevel's internal `next` net
HIERARCHY = re.compile(r"\bdut\s*\.\s*(?:u_\w+|g_\w+\s*\[|next\b|_id\s*\()"
                       r"|getattr\(\s*dut\s*,\s*[\"'](?:u_|g_|next\b)")


def _hits(pattern: re.Pattern, paths) -> list[str]:
    return [f"{p.relative_to(ROOT)}:{n}: {line.strip()}"
            for p in paths for n, line in enumerate(p.read_text().splitlines(), 1)
            if pattern.search(line)]


def test_hosts_use_no_verilator_internals():
    assert any(p.suffix == ".cpp" for p in HOSTS) and any(p.suffix == ".py" for p in HOSTS)
    assert any(p.name == "cocotb_plant.py" for p in HOSTS)      # found in its sub-package
    assert _hits(INTERNALS, HOSTS) == []


def test_cocotb_hosts_use_ports_only():
    cocotb_hosts = [p for p in HOSTS if p.name.startswith("cocotb_")]
    assert len(cocotb_hosts) >= 2
    assert _hits(HIERARCHY, cocotb_hosts) == []


# Each pattern is shown to catch what it is for, and to pass the port-based lines.
PATTERN_CASES = {
    "internals": (INTERNALS,
                  ('#include "Vbitbyte_cpu___024root.h"  // internal signals',
                   "  bool next() const { return top->rootp->bitbyte_cpu__DOT__next; }",
                   "auto& m = rp->bitbyte_cpu__DOT__u_bit_proc__DOT__u_marker_ram__DOT__mem;",
                   "void Vplc_system___024root___eval(Vplc_system___024root* vlSelf);",
                   'public_flat_rd -module "input_unit" -var "pii_o"',
                   "public_flat_rw"),
                  ("  bool next() const { return top->byte_next_o; }",
                   "srcs.push_back(wide_bit(top.dbg_pii_o, c.index, c));",
                   "top.eval();")),
    "hierarchy": (HIERARCHY,
                  ("        if int(dut.next.value) or self.stopped.is_set():",
                   "        await First(RisingEdge(dut.next), self.stopped.wait())",
                   "        sig = getattr(dut.u_input_unit, images[kind])",
                   "        cell = dut.u_bit_proc.u_marker_ram.mem[index]",
                   "        inner = dut.g_core[c].u_core",
                   '        sub = getattr(dut, "u_bit_proc")',
                   '        sig = dut._id("u_tc_status", extended=False)'),
                  ("        if int(dut.byte_next_o.value):",
                   "        sig = dut.dbg_timer_status_o",
                   "        self.dut.dbg_m_addr_i.value = n")),
}


@pytest.mark.parametrize("name", sorted(PATTERN_CASES))
def test_pattern_catches_what_it_is_for(name):
    pattern, caught, passed = PATTERN_CASES[name]
    for line in caught:
        assert pattern.search(line), line
    for line in passed:
        assert not pattern.search(line), line


# ---------------------------------------------------------------- the build sizes

def _defines(path: Path) -> dict[str, int]:
    return {m.group(1): int(m.group(2), 0)
            for m in re.finditer(r"^#define\s+(\w+)\s+(0x[0-9A-Fa-f]+|\d+)u?\b",
                                 path.read_text(), re.M)}


def _params(module: str) -> dict[str, int]:
    text = (ROOT / "rtl" / f"{module}.v").read_text()
    return {m.group(1): int(m.group(2))
            for m in re.finditer(r"parameter\s+integer\s+(\w+)\s*=\s*(\d+)", text)}


def _port_msb(module: str, port: str) -> str:
    text = (ROOT / "rtl" / f"{module}.v").read_text()
    m = re.search(r"\[([^\]:]+):0\]\s*" + port + r"\b", text)
    assert m, (module, port)
    return m.group(1).replace(" ", "")


def test_generated_build_sizes_are_the_rtl_defaults():
    isa = _defines(ROOT / "firmware_byte" / "bb_isa.h")
    bus = _defines(ROOT / "firmware_byte" / "bus_map.h")
    cpu, core, system = _params("bitbyte_cpu"), _params("plc_core"), _params("plc_system")
    for define, param in (("BB_HW_PROG_WORDS", "ProgWords"), ("BB_HW_IN_BYTES", "InBytes"),
                          ("BB_HW_OUT_BYTES", "OutBytes"),
                          ("BB_HW_MARKER_BYTES", "MarkerBytes"),
                          ("BB_HW_STATUS_BITS", "StatusBits"), ("BB_HW_IN_WORDS", "InWords"),
                          ("BB_HW_OUT_WORDS", "OutWords")):
        assert isa[define] == cpu[param], define
        for top in (core, system):              # the plant passes its own defaults down
            if param in top:
                assert top[param] == cpu[param], (define, param)
    assert isa["BB_HW_MW_WORDS"] == core["MwWords"]
    assert isa["BB_HW_PLAN_WORDS"] == core["PlanWords"] == system["PlanWords"]
    assert bus["BB_BUS_ADDR_BITS"] == int(_port_msb("bitbyte_cpu", "bus_addr_i")) + 1
    assert bus["BB_BUS_PLANT_ADDR_BITS"] == int(_port_msb("plc_core", "bus_addr_i")) + 1
    # plc_system sizes its per-core look-up addresses from its own parameters
    assert _port_msb("plc_system", "dbg_m_addr_i") == "Cores*$clog2(MarkerBytes*8)-1"
    assert _port_msb("plc_system", "dbg_mw_addr_i") == "Cores*$clog2(MwWords)-1"
    assert system["MarkerBytes"] == cpu["MarkerBytes"] and system["MwWords"] == core["MwWords"]


# ---------------------------------------------------------------- no firmware globals

WRITABLE = re.compile(r"^\S+\s+[lg]\s+O\s+(\.data(?!\.rel\.ro)\S*|\.bss\S*|\*COM\*)\s", re.M)


@pytest.mark.skipif(shutil.which("objdump") is None, reason="needs binutils' objdump")
def test_firmware_has_no_writable_globals():
    subprocess.run(["make", "-s", "-C", str(ROOT / "firmware_byte"), "lib"], check=True,
                   capture_output=True)
    objs = sorted((ROOT / "firmware_byte" / "build" / "obj").glob("*.o"))
    assert any(o.name == "hal_callbacks.o" for o in objs) and len(objs) >= 8
    table = subprocess.run(["objdump", "-t", *map(str, objs)], check=True,
                           capture_output=True, text=True).stdout
    assert WRITABLE.findall(table) == []
    # the check sees a writable variable (a callback pointer as hal_callbacks.c had)
    sample = "0000000000000000 l     O .bss\t0000000000000008 cb_read\n"
    assert WRITABLE.findall(sample) == [".bss"]
    sample = "0000000000000060 l     O .data.rel.ro.local\t0000000000000060 bb_cost_tables\n"
    assert WRITABLE.findall(sample) == []
