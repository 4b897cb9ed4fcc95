"""Write synth_top.v (into synth/build/), the FPGA wrapper, from the core's own port list.

The core (rtl/bitbyte_cpu.v) has far more ports than an FPGA package has pins, and
its port list grows as modules land. The wrapper is therefore generated: every
core port gets a role by its name and width, and the roles are served by the small
blocks in synth/synth_*.v.

| core port | FPGA side |
|---|---|
| `clk_i` | the clock pin |
| `rst_ni` | the reset pin through `synth_reset_sync` |
| `prog_we_i`, `prog_waddr_i`, `prog_wdata_i` | SPI command 0x01 (program load) |
| the byte-side bus `bus_*` | SPI commands 0x04/0x05 via `synth_bus_bridge` |
| `in_pins_i` | a 74HC165 chain (`synth_sin`) |
| `out_pins_o` | a 74HC595 chain (`synth_sout`) |
| any other 1-bit input / output | a pin (two-flop synchroniser / output flip-flop) |
| any other vector input | host registers, SPI command 0x02 (`synth_host_regs`) |
| any other vector output | read back over SPI, command 0x03 (`synth_readback`) |
| a plant's per-core program ports and buses (`plc_system`: a strobe per core) | host registers / read-back, as any other vector |
| observation ports `dbg_*` (simulation hosts only) | inputs tied to 0, outputs open |

The wrapper has the core's parameters (same names, same defaults) and passes them
down, so Yosys' `chparam` on `synth_top` sweeps the core.
"""

import re
from dataclasses import dataclass, field
from pathlib import Path

# Single-bit ports beyond these counts go to host registers / read-back instead of
# pins, so that even the 48-pin UP5K package keeps enough I/O.
MAX_IN_PINS = 8
MAX_OUT_PINS = 8

BUS_PORTS = ("bus_addr_i", "bus_wdata_i", "bus_we_i", "bus_re_i", "bus_rdata_o", "bus_ready_o")
PROG_PORTS = ("prog_we_i", "prog_waddr_i", "prog_wdata_i")
EXT_PORT = "prog_ext_wdata_i"   # the wide engine's extension word (issue 18): 0 here


@dataclass
class Port:
    direction: str          # input / output
    name: str
    msb: str | None = None  # range text as written in the core, None for one bit
    lsb: str | None = None

    @property
    def vector(self) -> bool:
        return self.msb is not None

    @property
    def decl(self) -> str:
        return f"[{self.msb}:{self.lsb}]" if self.vector else ""

    @property
    def width(self) -> str:
        """Width as a Verilog constant expression of the core's parameters."""
        if not self.vector:
            return "1"
        msb, lsb = self.msb.replace(" ", ""), self.lsb.replace(" ", "")
        if msb.isdigit() and lsb.isdigit():
            return str(int(msb) - int(lsb) + 1)
        if lsb == "0" and msb.endswith("-1"):
            return f"({msb[:-2]})"
        return f"(({self.msb}) - ({self.lsb}) + 1)"


@dataclass
class Module:
    name: str
    params: list[tuple[str, str]] = field(default_factory=list)  # (name, default text)
    ports: list[Port] = field(default_factory=list)


def _strip_comments(text: str) -> str:
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def _balanced(text: str, start: int) -> tuple[str, int]:
    """The text inside the parenthesis opening at text[start]; index after it."""
    assert text[start] == "("
    depth = 0
    for i in range(start, len(text)):
        if text[i] == "(":
            depth += 1
        elif text[i] == ")":
            depth -= 1
            if depth == 0:
                return text[start + 1:i], i + 1
    raise ValueError("unbalanced parentheses")


def _split_top(text: str) -> list[str]:
    """Split at commas outside (), [] and {}."""
    parts, depth, cur = [], 0, []
    for ch in text:
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append("".join(cur))
            cur = []
        else:
            cur.append(ch)
    parts.append("".join(cur))
    return [p.strip() for p in parts if p.strip()]


def parse_module(path: Path, name: str) -> Module:
    """Parameters and ANSI ports of module `name` in `path`."""
    text = _strip_comments(path.read_text())
    m = re.search(r"\bmodule\s+" + re.escape(name) + r"\b", text)
    if not m:
        raise ValueError(f"module {name} not found in {path}")
    pos = m.end()
    mod = Module(name)
    rest = text[pos:].lstrip()
    pos = len(text) - len(rest)
    if rest.startswith("#"):
        p = text.index("(", pos)
        body, pos = _balanced(text, p)
        for item in _split_top(body):
            pm = re.match(r"(?:parameter|localparam)?\s*(?:integer|int|signed|unsigned)?\s*"
                          r"(?:\[[^\]]*\])?\s*(\w+)\s*=\s*(.+)$", item, re.S)
            if not pm:
                raise ValueError(f"cannot read parameter '{item}'")
            mod.params.append((pm.group(1), " ".join(pm.group(2).split())))
    p = text.index("(", pos)
    body, _ = _balanced(text, p)
    direction = None
    rng = None
    for item in _split_top(body):
        pm = re.match(r"(?:(input|output|inout)\s+)?(?:(?:wire|reg|logic)\s+)?(?:signed\s+)?"
                      r"(\[([^:\]]+):([^\]]+)\])?\s*(\w+)$", " ".join(item.split()))
        if not pm:
            raise ValueError(f"cannot read port '{item}' (ANSI ports expected)")
        if pm.group(1):
            direction = pm.group(1)
            rng = (pm.group(3).strip(), pm.group(4).strip()) if pm.group(2) else None
        elif pm.group(2):
            rng = (pm.group(3).strip(), pm.group(4).strip())
        if direction not in ("input", "output"):
            raise ValueError(f"port {pm.group(5)}: only input and output are supported")
        mod.ports.append(Port(direction, pm.group(5), *(rng or (None, None))))
    return mod


def _pin_name(port: Port) -> str:
    return re.sub(r"_(i|o|ni|no)$", "", port.name) + ("_n" if port.name.endswith(("_ni", "_no")) else "")


def generate(core: Module, core_file: str) -> tuple[str, dict]:
    """The wrapper's Verilog text and a summary of the roles given to the ports."""
    ports = {p.name: p for p in core.ports}
    used: set[str] = set()
    roles: dict[str, list[str]] = {}

    def take(role, names):
        for n in names:
            used.add(n)
            roles.setdefault(role, []).append(n)

    clk = next((p for p in core.ports if p.direction == "input" and not p.vector
                and re.match(r"clk", p.name)), None)
    if clk is None:
        raise ValueError("the core has no clock input clk*")
    rst = next((p for p in core.ports if p.direction == "input" and not p.vector
                and re.match(r"rst\w*n", p.name)), None)
    take("clock pin", [clk.name])
    if rst:
        take("reset pin (synchronised release)", [rst.name])
    # one program port and one byte-side bus (bitbyte_cpu); a plant (plc_system) has a
    # strobe per core, and its per-core ports become host registers / read-back
    has_prog = (all(n in ports for n in PROG_PORTS) and ports["prog_waddr_i"].vector
                and not ports["prog_we_i"].vector)
    if has_prog:
        take("SPI 0x01 program load", PROG_PORTS)
    has_ext = EXT_PORT in ports
    if has_ext:   # loaded beside the base word (a scalar build leaves it unused)
        take("SPI 0x06 LUT extension word (32-bit pieces at addr 0, 1, ...)", [EXT_PORT])
    has_bus = all(n in ports for n in BUS_PORTS) and not ports["bus_we_i"].vector
    if has_bus:
        take("SPI 0x04/0x05 byte-side bus", BUS_PORTS)
    sin = ports.get("in_pins_i") if ports.get("in_pins_i", Port("", "")).vector else None
    sout = ports.get("out_pins_o") if ports.get("out_pins_o", Port("", "")).vector else None
    if sin:
        take("74HC165 input chain", [sin.name])
    if sout:
        take("74HC595 output chain", [sout.name])
    dbg = [p for p in core.ports if p.name.startswith("dbg_") and p.name not in used]
    take("observation (sim only): 0 / open", [p.name for p in dbg])
    rest = [p for p in core.ports if p.name not in used]
    in_pins = [p for p in rest if p.direction == "input" and not p.vector][:MAX_IN_PINS]
    out_pins = [p for p in rest if p.direction == "output" and not p.vector][:MAX_OUT_PINS]
    take("pin (input synchroniser)", [p.name for p in in_pins])
    take("pin (output flip-flop)", [p.name for p in out_pins])
    host = [p for p in core.ports if p.name not in used and p.direction == "input"]
    readback = [p for p in core.ports if p.name not in used and p.direction == "output"]
    take("SPI 0x02 host registers", [p.name for p in host])
    take("SPI 0x03 read-back", [p.name for p in readback])

    L = []
    w = L.append
    w("`default_nettype none")
    w('`include "bit_isa.vh"')
    w(f"// GENERATED by synth/gen_wrapper.py from the port list of {core_file}: do not edit.")
    w("// `make synth` rewrites it whenever the core's ports change.")
    w("//")
    w("// FPGA wrapper used for the synthesis reports (docs/synthesis.md). The core has far")
    w("// more ports than a package has pins, so they stay inside, behind small, realistic")
    w("// I/O blocks (synth/synth_*.v), and nothing of the core is optimised away:")
    for role, names in roles.items():
        w(f"//   {role:34s} {', '.join(names)}")
    w("// SPI frame: header {cmd[7:0], addr[23:0]}, then 32-bit words at addr, addr+1, ...")
    w(f"module synth_top #(")
    for i, (n, v) in enumerate(core.params):
        w(f"  parameter integer {n} = {v}{',' if i < len(core.params) - 1 else ''}")
    w(") (")
    pins = ["  input  wire clk"]
    if rst:
        pins.append("  input  wire rst_n")
    pins += ["  input  wire spi_sck", "  input  wire spi_cs_n", "  input  wire spi_mosi",
             "  output wire spi_miso"]
    if sin:
        pins += ["  output wire din_load_n", "  output wire din_sclk", "  input  wire din_sdata"]
    if sout:
        pins += ["  output wire dout_sclk", "  output wire dout_rclk", "  output wire dout_sdata"]
    pins += [f"  input  wire {_pin_name(p)}" for p in in_pins]
    pins += [f"  output reg  {_pin_name(p)}" for p in out_pins]
    w(",\n".join(pins))
    w(");")
    host_bits = " + ".join(p.width for p in host) or "0"
    read_bits = " + ".join(p.width for p in readback) or "0"
    w(f"  localparam integer HostBits  = {host_bits};")
    w("  localparam integer HostWords = (HostBits + 31) / 32 > 0 ? (HostBits + 31) / 32 : 1;")
    w(f"  localparam integer ReadBits  = {read_bits};")
    w("  localparam integer ReadWords = (ReadBits + 31) / 32 > 0 ? (ReadBits + 31) / 32 : 1;")
    if has_prog:
        w(f"  localparam integer ProgAddrW = {ports['prog_waddr_i'].width};")
    if has_bus:
        w(f"  localparam integer BusAddrW  = {ports['bus_addr_i'].width};")
    w("")
    w("  wire rst_s_n;")
    if rst:
        w("  synth_reset_sync u_reset (.clk_i(clk), .rst_ni(rst_n), .rst_no(rst_s_n));")
    else:
        w("  synth_reset_sync u_reset (.clk_i(clk), .rst_ni(1'b1), .rst_no(rst_s_n));")
    w("")
    w("  // the core's side of every port")
    for p in core.ports:
        if p is clk or p is rst:
            continue
        w(f"  wire {p.decl + ' ' if p.vector else ''}c_{p.name};")
    w("")
    w("  // ---------------------------------------------------------------- SPI")
    w("  wire        spi_wr, spi_rd, rd_valid;")
    w("  wire [7:0]  spi_cmd;")
    w("  wire [23:0] spi_addr;")
    w("  wire [31:0] spi_data, rd_data;")
    w("  synth_spi u_spi (")
    w("    .clk_i(clk), .rst_ni(rst_s_n),")
    w("    .sck_i(spi_sck), .cs_ni(spi_cs_n), .mosi_i(spi_mosi), .miso_o(spi_miso),")
    w("    .wr_o(spi_wr), .rd_o(spi_rd), .cmd_o(spi_cmd), .addr_o(spi_addr), .data_o(spi_data),")
    w("    .rd_valid_i(rd_valid), .rd_data_i(rd_data));")
    w("")
    if has_prog:
        w("  // 0x01: program words")
        w("  assign c_prog_we_i    = spi_wr && spi_cmd == 8'h01;")
        w("  assign c_prog_waddr_i = spi_addr[ProgAddrW-1:0];")
        w("  assign c_prog_wdata_i = spi_data;")
        w("")
    if has_ext:
        w("  // 0x06: the wide engine's extension word, 32 bits at a time (piece addr), written")
        w("  // with the next 0x01 base word; the scalar build does not read it (Yosys removes it)")
        w(f"  localparam integer ExtW = {ports[EXT_PORT].width};")
        w("  localparam integer ExtPieces = (ExtW + 31) / 32;")
        w("  reg [ExtPieces*32-1:0] ext_q;")
        w("  genvar ext_i;")
        w("  generate for (ext_i = 0; ext_i < ExtPieces; ext_i = ext_i + 1) begin : g_ext")
        w("    always @(posedge clk or negedge rst_s_n)")
        w("      if (!rst_s_n) ext_q[ext_i*32 +: 32] <= 32'd0;")
        w("      else if (spi_wr && spi_cmd == 8'h06 && {8'd0, spi_addr} == ext_i) ext_q[ext_i*32 +: 32] <= spi_data;")
        w("  end endgenerate")
        w(f"  assign c_{EXT_PORT} = ext_q[ExtW-1:0];")
        w("  generate if (ExtPieces * 32 > ExtW) begin : g_ext_spare")
        w("    // verilator lint_off UNUSEDSIGNAL")
        w("    wire unused_ext = ^ext_q[ExtPieces*32-1:ExtW];")
        w("    // verilator lint_on UNUSEDSIGNAL")
        w("  end endgenerate")
        w("")
    w("  // 0x02: host registers")
    w("  wire [HostWords*32-1:0] host_q;")
    w("  synth_host_regs #(.Words(HostWords)) u_host (")
    w("    .clk_i(clk), .rst_ni(rst_s_n), .we_i(spi_wr && spi_cmd == 8'h02),")
    w("    .addr_i(spi_addr), .data_i(spi_data), .q_o(host_q));")
    if host:
        w(f"  assign {{{', '.join('c_' + p.name for p in host)}}} = host_q[HostBits-1:0];")
    w("  generate if (HostWords * 32 > HostBits) begin : g_host_spare")
    w("    // verilator lint_off UNUSEDSIGNAL")
    w("    wire unused_host = ^host_q[HostWords*32-1:HostBits];")
    w("    // verilator lint_on UNUSEDSIGNAL")
    w("  end endgenerate")
    w("")
    w("  // 0x03: read-back")
    w("  wire [ReadWords*32-1:0] rb_words;")
    w("  wire [31:0]             rb_word;")
    if readback:
        w(f"  assign rb_words[ReadBits-1:0] = {{{', '.join('c_' + p.name for p in readback)}}};")
    w("  generate if (ReadWords * 32 > ReadBits) begin : g_rb_pad")
    w("    assign rb_words[ReadWords*32-1:ReadBits] = {(ReadWords*32-ReadBits){1'b0}};")
    w("  end endgenerate")
    w("  synth_readback #(.Words(ReadWords)) u_readback (")
    w("    .words_i(rb_words), .addr_i(spi_addr), .data_o(rb_word));")
    w("  reg        rb_valid_q;")
    w("  reg [31:0] rb_data_q;")
    w("  always @(posedge clk or negedge rst_s_n) begin")
    w("    if (!rst_s_n) begin")
    w("      rb_valid_q <= 1'b0;")
    w("      rb_data_q  <= 32'd0;")
    w("    end else begin")
    w("      rb_valid_q <= spi_rd && spi_cmd == 8'h03;")
    w("      rb_data_q  <= rb_word;")
    w("    end")
    w("  end")
    w("")
    if has_bus:
        w("  // 0x04 / 0x05: the byte-side bus (the byte processor, an external microcontroller)")
        w("  wire        bus_valid;")
        w("  wire [31:0] bus_data;")
        w("  synth_bus_bridge #(.AddrW(BusAddrW)) u_bus (")
        w("    .clk_i(clk), .rst_ni(rst_s_n),")
        w("    .wr_i(spi_wr && spi_cmd == 8'h04), .rd_i(spi_rd && spi_cmd == 8'h05),")
        w("    .addr_i(spi_addr), .data_i(spi_data),")
        w("    .bus_addr_o(c_bus_addr_i), .bus_wdata_o(c_bus_wdata_i),")
        w("    .bus_we_o(c_bus_we_i), .bus_re_o(c_bus_re_i),")
        w("    .bus_rdata_i(c_bus_rdata_o), .bus_ready_i(c_bus_ready_o),")
        w("    .rd_valid_o(bus_valid), .rd_data_o(bus_data));")
        w("  assign rd_valid = rb_valid_q || bus_valid;")
        w("  assign rd_data  = bus_valid ? bus_data : rb_data_q;")
    else:
        w("  assign rd_valid = rb_valid_q;")
        w("  assign rd_data  = rb_data_q;")
    w("")
    if sin:
        w("  // process inputs: 74HC165 chain")
        w(f"  synth_sin #(.Bits({sin.width})) u_din (")
        w("    .clk_i(clk), .rst_ni(rst_s_n),")
        w("    .load_no(din_load_n), .sclk_o(din_sclk), .sdata_i(din_sdata),")
        w(f"    .par_o(c_{sin.name}));")
        w("")
    if sout:
        w("  // process outputs: 74HC595 chain")
        w(f"  synth_sout #(.Bits({sout.width})) u_dout (")
        w("    .clk_i(clk), .rst_ni(rst_s_n),")
        w(f"    .par_i(c_{sout.name}),")
        w("    .sclk_o(dout_sclk), .rclk_o(dout_rclk), .sdata_o(dout_sdata));")
        w("")
    if in_pins:
        w("  // single-bit inputs: pins through two-flop synchronisers")
        w(f"  synth_sync #(.Width({len(in_pins)})) u_pin_sync (")
        w(f"    .clk_i(clk), .d_i({{{', '.join(_pin_name(p) for p in in_pins)}}}),")
        w(f"    .q_o({{{', '.join('c_' + p.name for p in in_pins)}}}));")
        w("")
    if out_pins:
        w("  // single-bit outputs: pins from output flip-flops")
        w("  always @(posedge clk or negedge rst_s_n) begin")
        w("    if (!rst_s_n) begin")
        for p in out_pins:
            w(f"      {_pin_name(p)} <= 1'b0;")
        w("    end else begin")
        for p in out_pins:
            w(f"      {_pin_name(p)} <= c_{p.name};")
        w("    end")
        w("  end")
        w("")
    dbg_in = [p for p in dbg if p.direction == "input"]
    dbg_out = [p for p in dbg if p.direction == "output"]
    if dbg:
        w("  // observation ports of the simulation hosts: nothing to observe them here")
        for p in dbg_in:
            w(f"  assign c_{p.name} = {{{p.width}{{1'b0}}}};")
        if dbg_out:
            w("  // verilator lint_off UNUSEDSIGNAL")
            w(f"  wire unused_dbg = ^{{{', '.join('c_' + p.name for p in dbg_out)}}};")
            w("  // verilator lint_on UNUSEDSIGNAL")
        w("")
    w("  // ---------------------------------------------------------------- the core")
    w(f"  {core.name} #(")
    w(",\n".join(f"    .{n}({n})" for n, _ in core.params))
    w(f"  ) u_core (")
    conns = [f"    .{clk.name}(clk)"]
    if rst:
        conns.append(f"    .{rst.name}(rst_s_n)")
    conns += [f"    .{p.name}(c_{p.name})" for p in core.ports if p is not clk and p is not rst]
    w(",\n".join(conns))
    w("  );")
    w("endmodule")
    w("`default_nettype wire")
    summary = {"roles": roles, "in_pins": [p.name for p in in_pins],
               "out_pins": [p.name for p in out_pins], "host": [p.name for p in host],
               "readback": [p.name for p in readback]}
    return "\n".join(L) + "\n", summary


def write_wrapper(core_path: Path, top: str, out: Path, core_file: str) -> dict:
    core = parse_module(core_path, top)
    text, summary = generate(core, core_file)
    if not out.exists() or out.read_text() != text:
        out.write_text(text)
    summary["params"] = core.params
    return summary


if __name__ == "__main__":
    root = Path(__file__).resolve().parent.parent
    s = write_wrapper(root / "rtl" / "bitbyte_cpu.v", "bitbyte_cpu",
                      root / "synth" / "build" / "synth_top.v", "rtl/bitbyte_cpu.v")
    for role, names in s["roles"].items():
        print(f"{role:34s} {', '.join(names)}")
