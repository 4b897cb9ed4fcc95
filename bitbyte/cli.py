"""`bitbyte` command line (spec §4)."""
from __future__ import annotations

import sys


def main(argv: list[str] | None = None) -> int:
    print("bitbyte: toolchain under construction", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
