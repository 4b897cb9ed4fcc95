"""The waveform layout a PLC engineer opens (spec §4, issue 17 item 1): `bitbyte run
... --waves W.fst` writes W.gtkw in the program's own names. Checked the way a user
sees it: GTKWave itself opens W.fst with W.gtkw under a virtual display and lists the
signals it displays (its Tcl API), so a name GTKWave would silently drop fails here."""
from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from test_cli import bitbyte

ROOT = Path(__file__).resolve().parents[1]
STAR = ROOT / "examples" / "star_delta.il"
STAR_STIM = ROOT / "examples" / "star_delta.stim.csv"
CPU = "TOP.bitbyte_cpu"

# Hand-written: where GTKWave shows each kind of operand (the RTL's image vectors,
# bit n of byte b = bit 8b+n; the marker RAM word by word; T n / C n: status bit n).
EXPECTED_SIGNAL = {
    "I": lambda b, n: [f"{CPU}.pii[{8 * b + n}]"],
    "Q": lambda b, n: [f"{CPU}.out_pins_o[{8 * b + n}]"],
    "M": lambda b, n: [f"{CPU}.u_bit_proc.u_marker_ram.mem.mem[{8 * b + n}][0]"],
    "T": lambda n: [f"{CPU}.timer_status[{n}]"],
    "C": lambda n: [f"{CPU}.counter_status[{n}]"],
    "IW": lambda n: [f"{CPU}.in_words_i[{16 * n + k}]" for k in range(15, -1, -1)],
}


def declared(source: Path) -> list[tuple[str, str, tuple[int, ...]]]:
    """(symbol, area, numbers) of the VAR blocks (VAR_GLOBAL's `: READ` / `: WRITE`
    too), read with a regex of its own."""
    out = []
    for name, area, nums in re.findall(r"^\s*(\w+)\s+AT\s+([A-Z]+)\s*([\d.]+)\s*(?::\s*\w+\s*)?;",
                                       source.read_text(), re.M):
        out.append((name, area, tuple(int(x) for x in nums.split("."))))
    return out


GTKW_TCL = """\
set f [open "{out}" w]
foreach s [gtkwave::getDisplayedSignals] {{ puts $f $s }}
close $f
gtkwave::/File/Quit
"""


def gtkwave_displays(tmp_path: Path, waves: Path, gtkw: Path) -> list[str]:
    """The signals GTKWave displays after loading the layout."""
    out = tmp_path / "displayed.txt"
    script = tmp_path / "list.tcl"
    script.write_text(GTKW_TCL.format(out=out))
    proc = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1500x1000x24", "gtkwave",
                           "-S", str(script), str(waves), str(gtkw)],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    return out.read_text().split()


def screenshot(tmp_path: Path, waves: Path, gtkw: Path, png: Path) -> None:
    """What a user sees: GTKWave on a virtual display, the screen as a PNG."""
    cmd = (f"gtkwave '{waves}' '{gtkw}' >/dev/null 2>&1 & pid=$!; sleep 6; "
           f"import -window root '{png}'; kill $pid")
    subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1500x1000x24", "sh", "-c", cmd],
                   check=True, timeout=120, capture_output=True)


@pytest.fixture(scope="module")
def star_waves(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("waves")
    waves = tmp / "star.fst"
    proc = bitbyte("run", STAR, "--stimulus", STAR_STIM, "--clock-mhz", "1",
                   "--until-us", "40000", "--waves", waves)
    assert proc.returncode == 0, proc.stderr
    return tmp, waves, tmp / "star.gtkw", proc.stdout


def test_layout_is_written_and_named_in_the_summary(star_waves):
    tmp, waves, gtkw, stdout = star_waves
    assert gtkw.exists()
    assert f"gtkwave {waves} {gtkw}" in stdout
    text = gtkw.read_text()
    for name, area, nums in declared(STAR):
        address = f"{area}{'.'.join(map(str, nums))}"
        if area == "MW":      # the byte processor's memory: a comment row, not a signal
            assert f"\n-{name} {address}: byte processor memory" in text, name
        else:
            assert re.search(r"[+#]\{" + re.escape(f"{name} {address}") + r"\}", text), name


def test_instructions_and_states_by_name(star_waves):
    tmp, waves, gtkw, _ = star_waves
    src = STAR.read_text().splitlines()
    instr = (tmp / "star.instr.txt").read_text().splitlines()
    # the first instruction of the program: its line and text, at address 0
    first = next(i for i, line in enumerate(src, 1)
                 if line.strip() and not line.strip().startswith("//")
                 and re.match(r"\s+[A-Z]", line) and "AT" not in line
                 and not line.strip().startswith(("VAR", "END_VAR")))
    assert instr[0] == f"0 {first}: {' '.join(src[first - 1].split('//')[0].split())}"
    states = dict(line.split(" ", 1) for line in (tmp / "star.state.txt").read_text().splitlines())
    # scan_ctrl.v's own encoding, read here independently
    rtl = (ROOT / "rtl" / "scan_ctrl.v").read_text()
    assert states == {v: k.lower() for k, v in
                      re.findall(r"localparam \[1:0\] St(\w+)\s*=\s*2'd(\d);", rtl)}


def test_gtkwave_shows_every_named_signal(star_waves, tmp_path):
    _, waves, gtkw, _ = star_waves
    shown = gtkwave_displays(tmp_path, waves, gtkw)
    for name, area, nums in declared(STAR):
        for signal in EXPECTED_SIGNAL.get(area, lambda n: [])(*nums):
            assert signal in shown, (name, signal)
    # nothing the layout asks for was dropped: one displayed signal per trace line
    # (+{alias} name, a bare name) and per bit of a combined word (#{alias} bits)
    text = gtkw.read_text().splitlines()
    asked = sum(1 for line in text if line.startswith(("+{", f"{CPU}")))
    asked += sum(len(line.split("} ", 1)[1].split()) for line in text if line.startswith("#{"))
    assert len(shown) == asked


def test_the_check_sees_a_dropped_signal(star_waves, tmp_path):
    """A layout naming a signal the wave file lacks is caught: GTKWave displays one
    signal fewer than the layout asks for (the count above)."""
    _, waves, gtkw, _ = star_waves
    broken = tmp_path / "broken.gtkw"
    broken.write_text(gtkw.read_text().replace("scan_count_o[31:0]", "scan_count_q[31:0]"))
    shown = gtkwave_displays(tmp_path, waves, broken)
    assert f"{CPU}.scan_count_o[31:0]" not in shown
    assert f"{CPU}.scan_done_o" in shown


def test_screenshot(star_waves, tmp_path):
    _, waves, gtkw, _ = star_waves
    png = tmp_path / "shot.png"
    screenshot(tmp_path, waves, gtkw, png)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000


def test_parallel_mode_layout_lists_the_bit_part(tmp_path):
    waves = tmp_path / "fig5.fst"
    proc = bitbyte("run", ROOT / "examples" / "fig5.il", "--mode", "parallel",
                   "--scans", "3", "--waves", waves)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "fig5.gtkw").read_text()
    assert "{executing}" in text and "{byte busy}" not in text   # no serial dispatch
    instr = (tmp_path / "fig5.instr.txt").read_text()
    assert "FBY" in instr           # the bit part's channel write (`= FBY k`)


def test_plant_layout_names_every_core(tmp_path):
    """A plant (spec §7): both projects' symbols per core, the semaphore and its owner,
    each core's sequencer state by name; GTKWave displays every signal it names."""
    waves = tmp_path / "plant.fst"
    proc = bitbyte("run", ROOT / "examples" / "plant_6_1" / "plant_sim.toml",
                   "--until-us", "60000", "--waves", waves)
    assert proc.returncode == 0, proc.stderr
    gtkw = tmp_path / "plant.gtkw"
    assert f"gtkwave {waves} {gtkw}" in proc.stdout
    text = gtkw.read_text()
    for core, source in (("p1", "p1.il"), ("p2", "p2.il")):
        for name, area, nums in declared(ROOT / "examples" / "plant_6_1" / source):
            address = f"{area}{'.'.join(map(str, nums))}"
            assert f"{{{core}: {name} {address}}}" in text, (core, name)
    assert "{lock owner}" in text and "{p2: sequencer}" in text
    seq = (tmp_path / "plant.seq.txt").read_text()
    assert "1 pre lock" in seq and "4 scan" in seq
    shown = gtkwave_displays(tmp_path, waves, gtkw)
    asked = [line for line in text.splitlines() if line.startswith(("+{", "#{", CPU))]
    assert len(shown) == len(asked)
    assert "TOP.plc_system.g_core[1].u_core.u_mw_ram.mem.mem[0][15:0]" in shown   # p2's CNT
