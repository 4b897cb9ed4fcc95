"""STEP 7 symbol tables (spec §9, `--symbols FILE`): the ASCII exports of STEP 7
Classic's symbol editor, read into {symbol name: Symbol}.

Three formats, told apart by their content (the suffix is only a hint):

* `.asc` — fixed columns after `126,`: name (24 characters), address (12), data type
  (10), comment (80); the format awlsim reads too.
* `.sdf` (System Data Format) — one symbol a line, fields in double quotes separated by
  commas: `"Motor","A 4.0","BOOL","Motor on"`.
* `.seq` (assignment list) — fields separated by tabs, a tab first:
  `<TAB>A 4.0<TAB>Motor<TAB>Motor on`; no data type.  Lines starting with `;` are
  comments.

Symbol names are compared without regard to case, as STEP 7 does.  Addresses keep the
table's spelling (German `E 0.0` or English `I 0.0`); bitbyte.lang.stl reads them in the
language of the table and writes them into the source's.
"""
from __future__ import annotations

import csv
from dataclasses import dataclass

from bitbyte.lang.errors import SourceError


@dataclass(frozen=True)
class Symbol:
    name: str           # as written in the table
    address: str        # as written in the table, blanks folded: "E 0.0", "MW 10"
    type: str           # "BOOL", "WORD", "TIMER", ... ("" in a .seq table)
    line: int           # 1-based line of the table


ASC_FIELDS = (("name", 24), ("address", 12), ("type", 10))


def table_format(text: str) -> str:
    """"asc", "sdf" or "seq" from the first line that is not blank or a comment."""
    for line in text.splitlines():
        if not line.strip() or line.startswith(";"):
            continue
        if line.startswith("126,"):
            return "asc"
        if line.lstrip().startswith('"'):
            return "sdf"
        if "\t" in line:
            return "seq"
        break
    return ""


def _rows(path: str, text: str, fmt: str):
    """(line number, name, address, type) for every symbol line."""
    for n, line in enumerate(text.splitlines(), start=1):
        if not line.strip() or fmt == "seq" and line.startswith(";"):
            continue
        if fmt == "asc":
            if not line.startswith("126,"):
                raise SourceError(path, n, 1, "symbol table (.asc): a line starts with "
                                  "`126,`")
            pos, fields = 4, []
            for _, width in ASC_FIELDS:
                fields.append(line[pos:pos + width].strip())
                pos += width
            yield n, fields[0], fields[1], fields[2]
        elif fmt == "sdf":
            try:
                fields = next(csv.reader([line], skipinitialspace=True))
            except csv.Error as exc:
                raise SourceError(path, n, 1, f"symbol table (.sdf): {exc}") from None
            if len(fields) < 2:
                raise SourceError(path, n, 1, 'symbol table (.sdf): "name","address",'
                                  '"type","comment" expected')
            yield n, fields[0].strip(), fields[1].strip(), \
                fields[2].strip() if len(fields) > 2 else ""
        else:
            fields = line[1:].split("\t") if line.startswith("\t") else line.split("\t")
            if len(fields) < 2:
                raise SourceError(path, n, 1, "symbol table (.seq): <TAB>address<TAB>"
                                  "symbol<TAB>comment expected")
            yield n, fields[1].strip(), fields[0].strip(), ""


def parse_symbol_table(path: str, data: bytes | str) -> dict[str, Symbol]:
    """{upper-case name: Symbol}.  Raises only SourceError (at the table's line)."""
    if isinstance(data, bytes):
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            text = data.decode("cp1252", errors="replace")
    else:
        text = data
    text = text.replace("\r\n", "\n")
    fmt = table_format(text)
    if not text.strip():
        return {}                       # an empty export: no symbols
    if not fmt:
        raise SourceError(path, 1, 1, "not a STEP 7 symbol table: expected the .asc "
                          "(`126,` fixed columns), .sdf (\"name\",\"address\",...) or .seq "
                          "(tab-separated) export")
    table: dict[str, Symbol] = {}
    for n, name, address, kind in _rows(path, text, fmt):
        if not name:
            raise SourceError(path, n, 1, f"symbol table (.{fmt}): a symbol without "
                              "a name")
        if not address:
            raise SourceError(path, n, 1, f"symbol table (.{fmt}): symbol `{name}` "
                              "has no address")
        key = name.upper()
        if key in table:
            raise SourceError(path, n, 1, f"duplicate symbol `{name}` (first defined "
                              f"at line {table[key].line})")
        table[key] = Symbol(name, " ".join(address.split()), kind.upper(), n)
    return table


def read_symbol_table(path: str) -> dict[str, Symbol]:
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as exc:
        raise SourceError(path, 0, 0, f"cannot read: {exc.strerror or exc}") from None
    return parse_symbol_table(path, data)
