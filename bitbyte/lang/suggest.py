"""Errors that suggest the fix (issue 17): the declared names nearest a mistyped one.

One helper for every place a name is looked up (symbols, labels, mnemonics, stimulus
columns, --watch operands), so that they all answer the same way:
`undeclared symbol `Strat`; did you mean `Start`?`."""
from __future__ import annotations

import difflib
from collections.abc import Iterable


def nearest(name: str, candidates: Iterable[str], n: int = 3) -> list[str]:
    """Up to n candidates close to name (case-insensitive, difflib's ratio >= 0.6),
    best first, spelled as declared."""
    by_key: dict[str, str] = {}
    for c in candidates:
        by_key.setdefault(c.upper(), c)
    keys = difflib.get_close_matches(name.strip().strip('"').upper(), list(by_key), n=n,
                                     cutoff=0.6)
    return [by_key[k] for k in keys]


def did_you_mean(name: str, candidates: Iterable[str]) -> str:
    """"; did you mean `A`?" / "; did you mean `A` or `B`?" — or "" when nothing is
    close (the message then stands alone)."""
    near = nearest(name, candidates)
    if not near:
        return ""
    quoted = [f"`{c}`" for c in near]
    alts = quoted[0] if len(quoted) == 1 else ", ".join(quoted[:-1]) + " or " + quoted[-1]
    return f"; did you mean {alts}?"
