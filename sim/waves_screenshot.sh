#!/bin/sh
# The waveform screenshots in docs/ (docs/toolchain.md, "Waveforms"; docs/tutorial.md):
# star-delta at 1 MHz and the tutorial's motor, opened in GTKWave with the layout `bitbyte run --waves` writes, on a virtual
# display. Needs xvfb, gtkwave and imagemagick (make deps). Run from the repository
# root:  sh sim/waves_screenshot.sh
set -eu
out=${1:-docs}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bitbyte run examples/star_delta.il --stimulus examples/star_delta.stim.csv \
  --clock-mhz 1 --until-us 2000 --waves "$tmp/star_delta.fst" >/dev/null
shot() {  # layout, png
  xvfb-run -a -s "-screen 0 1400x900x24" sh -c \
    "gtkwave '$tmp/star_delta.fst' '$1' >/dev/null 2>&1 & pid=\$!; sleep 6; import -window root '$2'; kill \$pid"
}
# the first view, as the layout opens: scan 0 and the next few whole scans
shot "$tmp/star_delta.gtkw" "$out/waves_star_delta.png"
# zoomed to 30 clocks of scan 9, where the Start press (at 1000 us) is latched
t0=$(sed -n 's/^\[timestart\] //p' "$tmp/star_delta.gtkw")
t=$((t0 + 9 * 116 * 1000000))
sed -e "s/^\[timestart\] .*/[timestart] $t/" -e "s/^\*[-0-9.]* [0-9]* /*-22.5 $t /" \
  "$tmp/star_delta.gtkw" > "$tmp/zoom.gtkw"
shot "$tmp/zoom.gtkw" "$out/waves_star_delta_zoom.png"
# the tutorial's motor (docs/tutorial.md), its whole run
bitbyte run examples/tutorial/motor.il --stimulus examples/tutorial/motor.stim.csv \
  --clock-mhz 0.005 --until-us 80000 --waves "$tmp/motor.fst" >/dev/null
t0=$(sed -n 's/^\[timestart\] //p' "$tmp/motor.gtkw")
sed -e "s/^\*[-0-9.]* [0-9]* /*-33.3 $t0 /" "$tmp/motor.gtkw" > "$tmp/motor_all.gtkw"
xvfb-run -a -s "-screen 0 1400x900x24" sh -c \
  "gtkwave '$tmp/motor.fst' '$tmp/motor_all.gtkw' >/dev/null 2>&1 & pid=\$!; sleep 6; import -window root '$out/tutorial_waves.png'; kill \$pid"
echo "wrote $out/waves_star_delta.png $out/waves_star_delta_zoom.png $out/tutorial_waves.png"
