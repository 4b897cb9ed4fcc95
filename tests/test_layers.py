"""The toolchain package is layered: every import (module level or inside a function)
points down the table below or stays inside its own sub-package, and the module graph
has no cycle.  tests/test_layers.py reads the sources with `ast`; nothing is imported.

    rank  package            may import
    0     bitbyte.lang       (the definition, program model, parser, errors, config,
                              cost model, stimulus and trace formats, partitioned-program
                              model)
    1     bitbyte.encoding   lang
    1     bitbyte.ref        lang only: the reference interpreters never see the
                              encoder, the compiler or a simulator
    2     bitbyte.compiler   lang, encoding
    2     bitbyte.wide       lang, encoding, ref (the wide engine's LUT compiler checks
                              each unit against the reference interpreter's step; its
                              linker encodes the scalar words)
    3     bitbyte.asm, bitbyte.alloc, bitbyte.run
    4     bitbyte.sim        (simulator drivers)
    5     bitbyte.plant      (plants: link, copy plans, run)
    6     bitbyte.cli        (argument parsing)
"""
import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PKG = ROOT / "bitbyte"
RANK = {"lang": 0, "encoding": 1, "ref": 1, "compiler": 2, "wide": 2, "asm": 3, "alloc": 3,
        "run": 3, "sim": 4, "plant": 5, "cli": 6}
ONLY = {"ref": {"lang"}, "encoding": {"lang"}}


def module_name(path: Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports_of(path: Path, modules: set[str]) -> set[str]:
    """Every bitbyte module `path` imports, at any depth of the file."""
    me = module_name(path)
    pkg = me if path.name == "__init__.py" else me.rpartition(".")[0]
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Call) and _dynamic_import(node):
            arg = node.args[0] if node.args else None
            names = [arg.value] if isinstance(arg, ast.Constant) and \
                isinstance(arg.value, str) else ["<dynamic>"]
            if names == ["<dynamic>"]:
                out.add("<dynamic>")           # a computed module name: never allowed
                continue
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                up = pkg.split(".")[: len(pkg.split(".")) - (node.level - 1)]
                base = ".".join(up + ([base] if base else []))
            names = [base] + [f"{base}.{a.name}" for a in node.names]
        else:
            continue
        out |= {n for n in names if n in modules and n != me}
    out.discard(me)
    return out


def _dynamic_import(call: ast.Call) -> bool:
    """importlib.import_module(...), import_module(...) or __import__(...)."""
    f = call.func
    name = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else ""
    return name in ("import_module", "__import__")


def graph() -> dict[str, set[str]]:
    files = sorted(PKG.rglob("*.py"))
    modules = {module_name(f) for f in files}
    return {module_name(f): imports_of(f, modules) for f in files}


def group(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def violations(g: dict[str, set[str]]) -> list[str]:
    bad = []
    for mod, deps in g.items():
        gm = group(mod)
        if gm not in RANK:
            if mod != "bitbyte":
                bad.append(f"{mod}: not in the layer table")
            continue
        for dep in deps:
            if dep == "<dynamic>":
                bad.append(f"{mod} imports a computed module name")
                continue
            gd = group(dep)
            if gd == gm or gd == "":
                continue
            if gd not in RANK or RANK[gd] >= RANK[gm] or gd not in ONLY.get(gm, {gd}):
                bad.append(f"{mod} imports {dep}")
    return sorted(bad)


def cycles(g: dict[str, set[str]]) -> list[list[str]]:
    found, state = [], {}

    def visit(m, stack):
        state[m] = 1
        for d in sorted(g.get(m, ())):
            if state.get(d) == 1:
                found.append(stack[stack.index(d):] + [d])
            elif d not in state:
                visit(d, stack + [d])
        state[m] = 2

    for m in sorted(g):
        if m not in state:
            visit(m, [m])
    return found


def test_imports_point_down_the_layers():
    assert violations(graph()) == []


def test_no_import_cycle():
    assert cycles(graph()) == []


def test_every_package_module_is_seen():
    g = graph()
    assert {"bitbyte.lang.parser", "bitbyte.compiler.partition", "bitbyte.cli",
            "bitbyte.ref.refsim", "bitbyte.plant.run"} <= set(g)
    assert "bitbyte.lang.parser" in g["bitbyte.compiler.walk"] or \
        any(d.startswith("bitbyte.lang") for d in g["bitbyte.compiler.walk"])


def test_the_checks_can_fail():
    """A function-level import that points up, and a cycle, are both caught."""
    g = {k: set(v) for k, v in graph().items()}
    g["bitbyte.ref.refsim"].add("bitbyte.encoding.encoder")       # ref sees the encoder
    g["bitbyte.lang.program"].add("bitbyte.cli")                   # lang imports up
    assert "bitbyte.ref.refsim imports bitbyte.encoding.encoder" in violations(g)
    assert "bitbyte.lang.program imports bitbyte.cli" in violations(g)
    g2 = {k: set(v) for k, v in graph().items()}
    g2["bitbyte.lang.errors"].add("bitbyte.lang.parser")           # parser imports errors
    assert cycles(g2)


def test_function_level_and_dynamic_imports_are_read(tmp_path):
    src = tmp_path / "bitbyte" / "lang" / "x.py"
    src.parent.mkdir(parents=True)
    src.write_text("import importlib\n\ndef f():\n    from bitbyte.cli import main\n"
                   "    importlib.import_module('bitbyte.asm')\n"
                   "    return __import__(name)\n")
    global ROOT
    old = ROOT
    try:
        ROOT = tmp_path
        assert imports_of(src, {"bitbyte.cli", "bitbyte.asm", "bitbyte.lang.x"}) == \
            {"bitbyte.cli", "bitbyte.asm", "<dynamic>"}
    finally:
        ROOT = old
