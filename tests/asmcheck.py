"""`bitbyte asm` on a source that must be refused: the one check the S7 error tests
share (tests/test_stl_db.py, test_stl_ob100.py, test_stl_loop_lc.py)."""
from __future__ import annotations

from pathlib import Path

from bitbyte import cli


def assert_refused(tmp: Path, capsys, text: str, where: str) -> str:
    """Assemble `text` as bad.awl: exit status EXIT_SOURCE, stderr starting with
    `bad.awl:<where>` (line:col: message…), no traceback; returns stderr."""
    path = tmp / "bad.awl"
    path.write_text(text)
    code = cli.main(["asm", str(path), "-o", str(tmp)])
    err = capsys.readouterr().err
    assert code == cli.EXIT_SOURCE, err
    assert err.startswith(f"{path}:{where}"), err
    assert "Traceback" not in err
    return err
