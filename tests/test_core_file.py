"""bitbyte.core (FuseSoC) names exactly the RTL that is in rtl/: a module added or
removed without updating it fails here."""
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def test_core_file_lists_every_rtl_file():
    text = (ROOT / "bitbyte.core").read_text()
    assert text.startswith("CAPI=2:\n")
    listed = set(re.findall(r"^\s+- (rtl/\S+)", text, re.M))
    present = {f"rtl/{p.name}" for p in (ROOT / "rtl").iterdir()
               if p.suffix in (".v", ".vh")}
    assert listed == present
    for top in ("bitbyte_cpu", "plc_system"):
        assert re.search(rf"^    toplevel : {top}$", text, re.M)
