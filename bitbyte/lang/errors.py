"""Errors that point into a source file.

Every problem the toolchain finds in a user's program is a `SourceError`: the CLI
prints it and exits non-zero, never with a traceback.  The text looks like a C
compiler's so that editors and people read it the same way:

    prog.il:3:4: unknown mnemonic `LDX`
    LDX I0.0
    ^

Columns count characters from 1; a tab counts as one column, and the caret line
repeats the tabs of the source line so that the caret lands under the right character
in any terminal.
"""
from __future__ import annotations


class SourceError(Exception):
    """A problem at path:line:col.

    line and col are 1-based.  line 0 means "the file as a whole" (for instance a
    file that cannot be read); such an error prints without a position.
    source_line is the text of the offending line (without its newline), shown
    under the message with a caret.
    """

    def __init__(self, path: str, line: int, col: int, message: str,
                 source_line: str = ""):
        super().__init__(message)
        self.path = path
        self.line = line
        self.col = col
        self.message = message
        self.source_line = source_line

    def __str__(self) -> str:
        return format_error(self)


def caret_line(source_line: str, col: int) -> str:
    """Blanks up to column col (tabs kept as tabs), then `^`."""
    prefix = source_line[: max(col - 1, 0)]
    pad = "".join("\t" if ch == "\t" else " " for ch in prefix)
    pad += " " * (col - 1 - len(prefix)) if col - 1 > len(prefix) else ""
    return pad + "^"


def format_error(err: SourceError) -> str:
    """`path:line:col: message`, then the source line and a caret under col.

    No trailing newline.  Without a position (line 0) only `path: message`.
    """
    if err.line <= 0:
        return f"{err.path}: {err.message}"
    head = f"{err.path}:{err.line}:{err.col}: {err.message}"
    return "\n".join((head, err.source_line, caret_line(err.source_line, err.col)))


class UsageError(Exception):
    """A command-line mistake: printed as `bitbyte: message`, exit 2.  Defined here,
    not in cli.py, so that modules cli.py calls raise the very class it catches
    (also when cli.py runs as `python -m bitbyte.cli`, i.e. as __main__)."""


class SimError(Exception):
    """The simulator could not be built or run: `bitbyte: message`, exit 4."""


def read_utf8(path: str, what: str) -> str:
    """A source file's text; unreadable, or a byte that is not UTF-8: SourceError at
    the file (or at the bad byte's line and column). what ends the message: "invalid
    UTF-8 byte 0xFF: <what>", e.g. "a stimulus is UTF-8 text"."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as exc:
        raise SourceError(path, 0, 0, f"cannot read: {exc.strerror or exc}") from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        before = data[: exc.start]
        line = before.count(b"\n") + 1
        line_start = before.rfind(b"\n") + 1
        col = len(before[line_start:].decode("utf-8", errors="replace")) + 1
        end = data.find(b"\n", exc.start)
        shown = data[line_start: len(data) if end < 0 else end]
        raise SourceError(path, line, col,
                          f"invalid UTF-8 byte 0x{data[exc.start]:02X}: {what}",
                          shown.decode("utf-8", errors="replace").rstrip("\r")) from None
