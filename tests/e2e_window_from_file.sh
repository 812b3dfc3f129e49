#!/usr/bin/env bash
# End-to-end in the real window (Xvfb, xdotool): a world made by `new flat from=FILE`
# holds nothing of the user's until it is edited (the file on disk has it all, as an
# image opened in GIMP or a heightmap read into a new Gaea graph), so Ctrl+Q quits
# without asking and leaves no recovery journal; once edited, Ctrl+Q asks, and Discard
# quits and drops the journal. A small heightmap's world opens seen whole.
# Usage: e2e_window_from_file.sh OROGEN TESTS_DIR
set -u
orogen=$1
. "$2/support/window_session.sh"
begin_window_test from-file
require_tools Xvfb xdotool
dem="$2/data/dem/N22W160.hgt"
journals() { find "$work/state" -name '*.recover' 2>/dev/null | wc -l; }
# Waits up to 10 s for the editor to exit; prints its status, or "running" (and ends it).
exit_status() {
    for _ in $(seq 100); do alive || break; sleep 0.1; done
    if alive; then echo running; kill $app; wait $app 2>/dev/null; else wait $app; echo $?; fi
}

start_xvfb 1200x800
# session NAME: the editor on a world made from the DEM (stdin fifo per session).
session() {
    rm -f "$work/stdin"
    open_editor "$orogen"
    xdotool windowsize --sync "$wid" 900 700
    xdotool windowfocus --sync "$wid" 2>/dev/null
    line=$(ask "new flat from=$dem" '^imported')
    check "$1: new flat from=FILE in the window ($line)" $?
}
. "$2/support/gui_helpers.sh"

# 1. Unedited: no '*' in the title, Ctrl+Q quits at once, no journal is left.
session unedited
# The title follows a frame after the import's reply (under load, more than 0.5 s).
wait_title '^Orogen - unsaved world - '; ok=$?; check "the title does not mark it modified ($(title))" $ok
key ctrl+q
status=$(exit_status)
[ "$status" = 0 ]; check "Ctrl+Q quits without asking (status $status)" $?
[ "$(journals)" = 0 ]; ok=$?; check "no recovery journal is left to offer at the next start ($(journals))" $ok
exec 3>&-

# 2. Edited: '*', Ctrl+Q asks; Discard quits and drops the journal.
session edited
echo "dab 50000 50000" >&3
wait_title "unsaved world \* - "; ok=$?; check "a dab marks it modified ($(title))" $ok
key ctrl+q
widget "Unsaved changes/Discard" >/dev/null; check "Ctrl+Q asks once it is edited" $?
alive; check "and the window stays while it asks" $?
click "Unsaved changes/Discard"
status=$(exit_status)
[ "$status" = 0 ]; check "Discard quits (status $status)" $?
[ "$(journals)" = 0 ]; ok=$?; check "Discard drops the journal ($(journals))" $ok
exec 3>&-

# 2b. On this world's 89 m samples the brush is sized for them: the radius that follows
# the view is not capped at 500 m (under six samples: a stroke was a faint streak), and
# the Radius slider takes 3000 m (it stopped at 500).
session coarse
vp=""
for _ in $(seq 40); do vp=$(widget Viewport) && break; sleep 0.25; done
read -r VX VY VW VH <<<"$vp"
xdotool mousemove --window "$wid" $((VX + VW / 2)) $((VY + VH / 2))
r=$(ask_until tool '^radius=' '^radius=\([1-5][0-9][0-9][0-9]\)\(\.[0-9]*\)\?$')
check "the brush's auto radius on 89 m samples is 1-6 km, not 500 m ($r)" $?
read -r x y w h <<<"$(widget "Dock/Radius")"
xdotool mousemove --window "$wid" $((x + 10)) $((y + h / 2)) keydown ctrl click 1 keyup ctrl
sleep 0.5
xdotool type --delay 30 "3000"
key Return
r=$(ask_until tool '^radius=' '^radius=3000$')
[ "$r" = "radius=3000" ]; check "the Radius slider takes 3000 m on this world ($r)" $?
kill $app 2>/dev/null
wait $app 2>/dev/null
exec 3>&-

# 3. A small, oblong heightmap (600 x 200 m) opens seen whole: the view's centre is the
# world's middle (the first view used to look for land 300 m along both
# axes, outside this world, and stayed a few metres above its middle looking away).
"$orogen" -c "new flat; export $work/strip.exr region=1000,1000,1600,1200" >/dev/null 2>&1
rm -f "$work/stdin"
open_editor "$orogen"
xdotool windowsize --sync "$wid" 900 700
line=$(ask "new flat from=$work/strip.exr" '^imported')
check "new flat from a 600 x 200 m heightmap ($line)" $?
# The camera looks at the world's middle (300, ground, 100) from less than a kilometre.
ground=$(ask "sample 300 100" '^-\?[0-9]')
cam=$(ask camera '^camera ')
echo "$cam" | awk -v g="$ground" '{ x = $2; y = $3; z = $4; yaw = $5 * atan2(0, -1) / 180
    pitch = $6 * atan2(0, -1) / 180
    fx = cos(pitch) * sin(yaw); fy = sin(pitch); fz = -cos(pitch) * cos(yaw)
    dx = 300 - x; dy = g - y; dz = 100 - z; d = sqrt(dx * dx + dy * dy + dz * dz)
    exit !(d > 0 && d < 1000 && (fx * dx + fy * dy + fz * dz) / d > cos(3 * atan2(0, -1) / 180)) }'
ok=$?; check "the view's centre is the world's middle, seen from less than 1 km ($cam; ground $ground)" $ok
grep -q "camera:" "$work/err"; [ $? = 1 ]; ok=$?; check "no camera error ($(grep camera: "$work/err"))" $ok

end_window_test
