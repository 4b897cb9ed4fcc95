"""The one definition of the CPU's interfaces (bitbyte/lang/definition.toml), read once.

Everything here is data: the instruction word's fields, opcodes and areas, the byte
instructions with their cost classes, the cost tables, the byte-bus register map, the
firmware flags and the default sizes. `bitbyte/lang/generate.py` writes the RTL, firmware and
documentation tables from the same data, so a number changed in the TOML file changes
everywhere at once (tests/test_generated.py fails until the files are regenerated).

This module imports nothing from the rest of the package: it is the bottom layer.
"""
from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path

PATH = Path(__file__).with_name("definition.toml")


@dataclass(frozen=True)
class Field:
    hi: int
    lo: int

    @property
    def width(self) -> int:
        return self.hi - self.lo + 1

    @property
    def mask(self) -> int:
        return (1 << self.width) - 1


@dataclass(frozen=True)
class Register:
    name: str
    addr: int
    access: str
    doc: str
    count: int = 1               # a window: register n at addr + n
    plant_only: bool = False
    reset: int | None = None
    fields: tuple[tuple[str, int], ...] = ()


@dataclass(frozen=True)
class ByteOpcode:
    mnemonic: str                # the encoder's key ("L#", "S C", "A >=I", ...)
    kind: str                    # the cost-table kind of the reference interpreter
    value: int
    cls: str                     # cost class
    c: str | None = None         # firmware macro
    rtl: str | None = None       # RTL macro, where the RTL needs it
    byte_program: bool = False
    operand: str = "—"
    doc: str | None = None
    dint: bool = False           # reads the accumulators' full 32 bits (+D ... MODD)
    group: str | None = None     # "logic" (AW ... XOD) or "shift" (SLW ... RRD)


@dataclass(frozen=True)
class LutFormat:
    """The wide engine's LUT word ([lut], [[lut_area]]): a base word (the fields at
    their bit positions in 32 bits) and an extension word (ext_bits)."""
    k: int
    scratch_bits: int
    ext_bits: int
    tag: Field
    tag_value: int
    first: int
    last: int
    dst_area: Field
    scr_index: Field
    scr_en: int
    dst_index: Field
    table_a: Field
    table_b: Field
    operand_base: int
    operand_bits: int
    operand_area: Field
    operand_index: Field
    areas: tuple[tuple[str, int, str, str], ...]   # (name, code, rtl macro, doc)

    def operand(self, j: int) -> Field:
        """Operand j's bits in the extension word."""
        lo = self.operand_base + self.operand_bits * j
        return Field(lo + self.operand_bits - 1, lo)

    def area_code(self, name: str) -> int:
        return next(code for n, code, _, _ in self.areas if n == name)


class Definition:
    """The parsed definition.  `raw` is the TOML document as read."""

    def __init__(self, raw: dict):
        self.raw = raw
        w = raw["word"]
        self.word_bits: int = w["bits"]
        self.fields = {k: Field(*w[k]) for k in ("opcode", "area", "index", "target", "imm")}
        self.wait_update_bit: int = w["wait_update"]
        self.from_status_bit: int = w["from_status"]
        self.status_wait_bit: int = w["status_wait"]
        self.at_latch_bit: int = w["at_latch"]
        self.byte_bit: int = w["byte_bit"]
        self.count_from_accu2_bit: int = w["count_from_accu2"]

        lu = raw["lut"]
        self.lut = LutFormat(
            k=lu["k"], scratch_bits=lu["scratch_bits"], ext_bits=lu["ext_bits"],
            tag=Field(*lu["tag"]), tag_value=lu["tag_value"], first=lu["first"],
            last=lu["last"], dst_area=Field(*lu["dst_area"]),
            scr_index=Field(*lu["scr_index"]), scr_en=lu["scr_en"],
            dst_index=Field(*lu["dst_index"]), table_a=Field(*lu["table_a"]),
            table_b=Field(*lu["table_b"]), operand_base=lu["operand_base"],
            operand_bits=lu["operand_bits"], operand_area=Field(*lu["operand_area"]),
            operand_index=Field(*lu["operand_index"]),
            areas=tuple((a["name"], a["code"], a["rtl"], a["doc"]) for a in raw["lut_area"]))

        tm = raw["timing"]
        self.bit_clocks: int = tm["bit_clocks"]
        self.jump_taken_clocks: int = tm["jump_taken_clocks"]

        lg = raw["logic"]
        self.load_base: int = lg["load_base"]
        self.open_base: int = lg["open_base"]
        self.logic_mask: int = lg["mask"]
        self.logic_functions: tuple[tuple[str, str], ...] = tuple(
            (m, r) for m, r in lg["functions"])

        self.bit_opcode_rows: tuple[dict, ...] = tuple(raw["bit_opcode"])
        self.bit_opcodes: dict[str, int] = dict(self._logic_opcodes())
        for row in self.bit_opcode_rows:
            self.bit_opcodes[row["mnemonic"]] = row["value"]

        self.area_rows: tuple[dict, ...] = tuple(raw["area"])
        # Areas of bit operands (I .. C, FBI/FBY); the word areas only in byte instructions.
        self.area_codes: dict[str, int] = {
            a["name"]: a["code"] for a in self.area_rows if not a.get("word")}
        self.bit_form_areas: tuple[str, ...] = tuple(
            a["name"] for a in self.area_rows if a["form"] == "bit")
        # Areas a byte instruction names by number (T, C, FB, IW, QW, MW).
        self.word_area_codes: dict[str, int] = {
            a["name"]: a["code"] for a in self.area_rows if a["form"] == "n"}

        cmp = raw["compare"]
        self.compares: tuple[str, ...] = tuple(cmp["codes"])
        self.compare_c: tuple[str, ...] = tuple(cmp["c"])
        self.compare_bases = {"": cmp["plain_base"], "A ": cmp["and_base"],
                              "O ": cmp["or_base"]}
        # DINT compares: the same codes c over 32 bits, bases of their own
        self.dint_compares: tuple[str, ...] = tuple(cmp["dint_codes"])
        self.dint_compare_bases = {"": cmp["dint_plain_base"], "A ": cmp["dint_and_base"],
                                   "O ": cmp["dint_or_base"]}
        self.byte_opcode_rows: tuple[ByteOpcode, ...] = tuple(
            ByteOpcode(mnemonic=r["mnemonic"], kind=r.get("kind", r["mnemonic"]),
                       value=r["value"], cls=r["class"], c=r.get("c"), rtl=r.get("rtl"),
                       byte_program=r.get("byte_program", False),
                       operand=r.get("operand", "—"), doc=r.get("doc"),
                       dint=r.get("dint", False), group=r.get("group"))
            for r in raw["byte_opcode"])
        self.byte_opcodes: dict[str, int] = {}
        self.byte_kinds: dict[str, str] = {}
        compares_top = cmp["or_base"] + 7
        for op in self.byte_opcode_rows:
            if op.byte_program:
                continue
            if op.value > compares_top and not self.byte_opcodes.keys() & set(self.compares):
                self._add_compares(cmp["class"])    # in opcode order
            self.byte_opcodes[op.mnemonic] = op.value
            self.byte_kinds.setdefault(op.kind, op.cls)
        self._add_compares(cmp["class"], self.dint_compares, self.dint_compare_bases)
        # every compare mnemonic (INT, then DINT) and the arithmetic (+I ... MODD)
        self.all_compares: tuple[str, ...] = self.compares + self.dint_compares
        self.arithmetic: tuple[str, ...] = tuple(
            op.mnemonic for op in self.byte_opcode_rows
            if op.cls in ("arith", "muldiv") and op.group is None)
        self.word_logic: tuple[str, ...] = tuple(
            op.mnemonic for op in self.byte_opcode_rows if op.group == "logic")
        self.shifts: tuple[str, ...] = tuple(
            op.mnemonic for op in self.byte_opcode_rows if op.group == "shift")
        # the instructions that read ACCU1/ACCU2 as DINT (the rest of them read INT(.))
        self.dint_mnemonics: frozenset[str] = frozenset(
            [op.mnemonic for op in self.byte_opcode_rows if op.dint]
            + [p + c for p in self.dint_compare_bases for c in self.dint_compares])
        # status-bit reads: mnemonic ("LD ==0", "AN UO", ...) -> (opcode, index)
        sr = raw["status_read"]
        self.status_base: int = sr["base"]
        self.status_conditions: tuple[str, ...] = tuple(sr["conditions"])
        self.status_c: tuple[str, ...] = tuple(sr["c"])
        self.status_negate_bit: int = sr["negate_bit"]
        self.status_reads: dict[str, tuple[int, int]] = {}
        for f, (name, _) in enumerate(self.logic_functions):
            for n, suffix in ((0, ""), (1, "N")):
                for c, cond in enumerate(self.status_conditions):
                    self.status_reads[f"{name}{suffix} {cond}"] = (
                        self.status_base + f, c | n << self.status_negate_bit)
        self.status_class: str = sr["class"]
        for m in self.status_reads:
            self.byte_kinds[m] = self.status_class
        self.byte_program_opcodes: dict[str, int] = {
            op.mnemonic: op.value for op in self.byte_opcode_rows if op.byte_program}

        self.cost_class_rows: tuple[dict, ...] = tuple(raw["cost_class"])
        self.cost_classes: tuple[str, ...] = tuple(c["name"] for c in self.cost_class_rows)
        self.word_classes: tuple[str, ...] = tuple(
            c["name"] for c in self.cost_class_rows if c.get("word"))
        self.fixed_costs: dict[str, int] = {
            c["name"]: c["fixed"] for c in self.cost_class_rows if "fixed" in c}
        # The classes a table prices (the reference interpreter's view).
        self.priced_classes: tuple[str, ...] = tuple(
            c for c in self.cost_classes if c not in self.fixed_costs)
        self.cost_tables: dict[str, dict[str, int]] = {
            name: {c: (t["word"] if c in self.word_classes else t[c])
                   for c in self.priced_classes}
            for name, t in raw["cost_table"].items()}

        bus = raw["bus"]
        self.bus_id_value: int = bus["id_value"]
        self.bus_addr_bits: int = bus["addr_bits"]
        self.plant_bus_addr_bits: int = bus["plant_addr_bits"]
        self.registers: tuple[Register, ...] = tuple(
            Register(name=r["name"], addr=r["addr"], access=r["access"], doc=r["doc"],
                     count=r.get("count", 1), plant_only=r.get("plant_only", False),
                     reset=r.get("reset"),
                     fields=tuple((n, v) for n, v in r.get("fields", ())))
            for r in raw["register"])
        self.bus: dict[str, int] = {r.name: r.addr for r in self.registers}

        self.byte_flags: dict[str, int] = {f["name"]: 1 << f["bit"] for f in raw["byte_flag"]}
        self.byte_flag_rows: tuple[dict, ...] = tuple(raw["byte_flag"])
        self.sizes: dict[str, int] = dict(raw["sizes"])
        self.plant: dict[str, int] = dict(raw["plant"])
        # build profiles: name -> the [sizes] it changes (and a "doc" line)
        self.profiles: dict[str, dict] = {k: dict(v) for k, v in raw.get("profiles", {}).items()}
        # top module -> RTL parameter -> its default (from [sizes] / [plant])
        self.rtl_keys: dict[str, dict[str, str]] = {top: dict(params)
                                                    for top, params in raw["rtl"].items()}
        self.rtl_defaults: dict[str, dict[str, int]] = {
            top: {param: {**self.sizes, **self.plant}[key] for param, key in params.items()}
            for top, params in self.rtl_keys.items()}
        self.firmware: dict = dict(raw["firmware"])
        # run-time settings: names in code order (code = index), their RTL/C names
        self.settings: dict[str, tuple[tuple[str, str, str], ...]] = {
            k: tuple(tuple(row) for row in rows) for k, rows in raw["settings"].items()}
        self.exchanges: tuple[str, ...] = tuple(r[0] for r in self.settings["exchange"])
        self.protections: tuple[str, ...] = tuple(r[0] for r in self.settings["protection"])
        # bb_run's modes: name -> the enum value of firmware_byte/bb_isa.h
        self.modes: dict[str, int] = {m.lower(): i for i, (m, _) in
                                      enumerate(self.firmware["modes"])}
        self._check()

    def _logic_opcodes(self):
        """The eight loads/combines and six opening parentheses from f and n."""
        for f, (name, _) in enumerate(self.logic_functions):
            for n, suffix in ((0, ""), (1, "N")):
                yield name + suffix, self.load_base | f << 1 | n
                if name != "LD":
                    yield name + suffix + "(", self.open_base | f << 1 | n

    def _add_compares(self, cls: str, codes=None, bases=None) -> None:
        for prefix, base in (bases or self.compare_bases).items():
            for c, cmp in enumerate(codes or self.compares):
                self.byte_opcodes[prefix + cmp] = base + c
                self.byte_kinds[prefix + cmp] = cls

    def register(self, name: str) -> Register:
        for r in self.registers:
            if r.name == name:
                return r
        raise KeyError(name)

    def profile_sizes(self, name: str) -> dict[str, int]:
        """[sizes] as the build profile `name` has them."""
        return {**self.sizes, **{k: v for k, v in self.profiles[name].items() if k != "doc"}}

    def profile_params(self, name: str, top: str) -> dict[str, int]:
        """The RTL parameters of `top` that the profile changes (name -> value)."""
        sizes = self.profile_sizes(name)
        return {param: sizes[key] for param, key in self.rtl_keys[top].items()
                if key in sizes and sizes[key] != self.rtl_defaults[top][param]}

    def _check(self) -> None:
        """The definition is consistent, or DefinitionError says where not: no opcode
        or address used twice, byte opcodes have bit 7 set and bit opcodes do not,
        every class is priced or fixed, every register fits the bus address width, a
        window of n registers starts at a multiple of n (n a power of two: the RTL
        decodes it by its high address bits), and the windows hold the sizes the
        firmware is built for."""
        def need(ok: bool, message: str) -> None:
            if not ok:
                raise DefinitionError(f"{PATH.name}: {message}")

        lut = self.lut                                # the LUT word's fields fit
        base = [("tag", lut.tag), ("first", Field(lut.first, lut.first)),
                ("last", Field(lut.last, lut.last)), ("dst_area", lut.dst_area),
                ("scr_index", lut.scr_index), ("scr_en", Field(lut.scr_en, lut.scr_en)),
                ("dst_index", lut.dst_index)]
        used = 0
        for name, f in base:
            need(0 <= f.lo <= f.hi < self.word_bits and not used >> f.lo & f.mask,
                 f"[lut] {name}: outside the word or overlapping another field")
            used |= f.mask << f.lo
        # bit 23 is the program RAM's END mark (bit_proc.v prog_word) and the area field
        # must read as no FB access: no base field there
        reserved = 1 << 23 | self.fields["area"].mask << self.fields["area"].lo
        need(not used & reserved & ~(lut.tag.mask << lut.tag.lo),
             "[lut] a base field on bit 23 (the END mark) or the area field")
        top = lut.tag.lo - self.fields["opcode"].lo     # the tag: the opcode's top bits
        need(lut.tag.hi == self.fields["opcode"].hi and top >= 0 and
             0 <= lut.tag_value <= lut.tag.mask and
             all(v >> top != lut.tag_value for v in
                 list(self.bit_opcodes.values()) + list(self.byte_opcodes.values()) +
                 list(self.byte_program_opcodes.values()) + [self.load_base, self.open_base]),
             "[lut] tag: must be the opcode's top bits, with a value no opcode has")
        need(lut.table_a.width == lut.table_b.width == 1 << lut.k,
             "[lut] table_a/table_b: 2^k bits each")
        ext, ext_used = [("table_a", lut.table_a), ("table_b", lut.table_b)] + [
            (f"operand {j}", lut.operand(j)) for j in range(lut.k)], 0
        for name, f in ext:
            need(0 <= f.lo <= f.hi < lut.ext_bits and not ext_used >> f.lo & f.mask,
                 f"[lut] {name}: outside the extension word or overlapping another field")
            ext_used |= f.mask << f.lo
        need(lut.operand_area.hi < lut.operand_bits and lut.operand_area.lo ==
             lut.operand_index.hi + 1 and lut.operand_index.lo == 0,
             "[lut] operand_area/operand_index: the operand's two fields, index low")
        bits = max(8 * self.sizes["marker_bytes"], 8 * self.sizes["in_bytes"],
                   8 * self.sizes["out_bytes"], self.sizes["timers"], self.sizes["counters"])
        need(1 << lut.dst_index.width >= bits and 1 << lut.operand_index.width >= bits,
             f"[lut] dst_index/operand_index: {bits} bits of an area need "
             f"{(bits - 1).bit_length()} index bits")
        need(all(c <= lut.dst_area.mask and c <= lut.operand_area.mask
                 for c in list(self.area_codes.values()) + [c for _, c, _, _ in lut.areas]),
             "[lut] dst_area/operand_area: an area code does not fit")
        need(1 << lut.scr_index.width >= lut.scratch_bits, "[lut] scr_index: too narrow")
        codes = [c for _, c, _, _ in lut.areas]
        need(len(set(codes)) == len(codes) and
             not set(codes) & set(self.area_codes.values()) and
             all(c < 1 << lut.operand_area.width for c in codes),
             "[[lut_area]]: codes must be distinct, no bit area's, and fit the area field")
        for name, prof in self.profiles.items():      # a profile shrinks [sizes]
            for key, value in prof.items():
                need(key == "doc" or (key in self.sizes and isinstance(value, int)
                                      and 0 < value <= self.sizes[key]),
                     f"[profiles.{name}] {key}: not a [sizes] key, or not 1..its default")
        for key, rows in self.settings.items():       # 2-bit inputs, distinct names
            need(len(rows) <= 4, f"settings.{key}: {len(rows)} codes do not fit 2 bits")
            for col in (0, 1):
                need(len({r[col] for r in rows}) == len(rows),
                     f"settings.{key}: a name is given twice")
        values = list(self.bit_opcodes.values()) + list(self.byte_opcodes.values()) \
            + list(self.byte_program_opcodes.values())
        values += [self.status_base + f for f in range(len(self.logic_functions))]
        need(len(values) == len(set(values)), "an opcode is defined twice")
        need(len(self.status_conditions) <= 1 << self.status_negate_bit,
             "[status_read] more conditions than index bits below negate_bit")
        need(len(self.dint_compares) == len(self.compares),
             "[compare] dint_codes must pair with codes (one compare code c each)")
        need(all(v < 0x80 for v in self.bit_opcodes.values()),
             "a bit opcode has bit 7 set")
        need(all(0x80 <= v <= 0xFF for v in values if v not in self.bit_opcodes.values()),
             "a byte opcode is outside 0x80..0xFF")
        for r in self.registers:
            bits = self.plant_bus_addr_bits if r.plant_only else self.bus_addr_bits
            need(r.addr + r.count <= 1 << bits,
                 f"register {r.name} does not fit {bits} address bits")
            need(r.count & (r.count - 1) == 0 and r.addr % r.count == 0,
                 f"window {r.name}: {r.count} registers must start at a multiple of "
                 f"{r.count}")
        spans = sorted((r.addr, r.addr + r.count - 1, r.name) for r in self.registers)
        for (_, hi, a), (lo, _, b) in zip(spans, spans[1:]):
            need(hi < lo, f"bus registers {a} and {b} overlap")
        for op in self.byte_opcode_rows:
            need(op.cls in self.cost_classes, f"{op.mnemonic}: unknown class {op.cls}")
        for name, t in self.cost_tables.items():
            need(set(t) == set(self.priced_classes), f"cost table {name}: classes")
        for reg, size in (("IW", "in_words"), ("QW", "out_words"), ("MW", "data_words")):
            need(self.register(reg).count == self.sizes[size],
                 f"window {reg} holds {self.register(reg).count}, [sizes] {size} is "
                 f"{self.sizes[size]}")
        need(self.register("FBY").count == self.register("FBI").count >= self.sizes["channels"],
             "the FBY and FBI windows must be alike and hold [sizes] channels")
        need(self.register("MCELL").count >= self.sizes["marker_cells"] >=
             self.register("FBY").count,
             "the MCELL window must hold [sizes] marker_cells, and they the FBY window's")
        # the marker area's regions (rtl/marker_region.v) pack 16 cells a RAM word and
        # need two words at least; the byte port's window holds 128 (bitbyte_cpu checks
        # the same at elaboration)
        for where, sizes in [("[sizes]", self.sizes)] + [
                (f"[profiles.{n}]", self.profile_sizes(n)) for n in self.profiles]:
            cells = sizes["marker_cells"]
            need(32 <= cells <= self.register("MCELL").count and cells & (cells - 1) == 0,
                 f"{where} marker_cells must be a power of two in 32.."
                 f"{self.register('MCELL').count}, not {cells}")


class DefinitionError(ValueError):
    """bitbyte/lang/definition.toml contradicts itself."""


def load(path: Path = PATH) -> Definition:
    with open(path, "rb") as f:
        return Definition(tomllib.load(f))


DEF = load()
