#!/bin/bash
# End-to-end: a newcomer's whole first session in the real window (issue 26's scenario),
# with a fresh home, by mouse and keyboard: sculpt with each tool from the palette, a
# stamp, undo through History, the console with Tab, Save as, a click made while work
# runs, quit with unsaved changes and reopen from File's recent list, a failing and a
# working import through the dialog, export, carve, then at 1024 x 640 and UI scale 1.5
# (chosen in the View menu) a new planet, a brush radius drag on it and a bad slider
# value. Each step waits for its outcome through commands (hash, info, history, nparams,
# ui_messages, ui_widgets), never for a fixed time, and keeps a screenshot in
# build/test-artifacts/scenario_*.png.
set -u
orogen=$(realpath "$1")
. "$2/support/window_session.sh"
begin_window_test scenario
require_tools Xvfb xdotool import
start_xvfb 1600x1000
. "$2/support/gui_helpers.sh"
shot() { import -window "$wid" "$art/scenario_$1.png" 2>/dev/null; }
start() { # the editor from the home folder, its viewport's rectangle in VX VY VW VH
    open_editor sh -c 'cd "$HOME" && exec "$0"' "$orogen"
    read -r VX VY VW VH <<<"$(widget Viewport)"
}
steps() { ask history '^steps=' | sed -E 's/^steps=([0-9]+).*/\1/'; }
# Waits for the N-th undo step and prints its line of `history` ("* N NAME tiles=...").
step_line() { # N
    ask_until history '^steps=' "^steps=$1 " >/dev/null || return 1
    ask history "^\* $1 "
}
# The coarse heights of a box around the point the viewport's centre shows.
box() { ask "hash $((cx - 150)) $((cz - 150)) $((cx + 150)) $((cz + 150))" '^[0-9a-f]\{16\}$'; }
# A left drag across the viewport's centre (x offsets from it in pixels); each part
# waits for the window to act (the stroke's first dab done before the moves come, so
# every point is picked on the terrain as it is).
drag() { # DX0 DX1
    local y=$((VY + VH / 2)) x0=$((VX + VW / 2 + $1)) x1=$((VX + VW / 2 + $2))
    xdotool mousemove --window "$wid" $x0 $y mousedown 1
    settle
    xdotool mousemove --window "$wid" $(((x0 + x1) / 2)) $y mousemove --window "$wid" $x1 $y
    settle
    xdotool mouseup 1
}
wait_message() { # PATTERN: up to ~6 s for ui_messages to list it
    for _ in $(seq 20); do messages | grep -q -- "$1" && return 0; sleep 0.3; done
    return 1
}

t0=$SECONDS
section() { echo "[$((SECONDS - t0)) s] $1" >&2; }

section "1"
# 1. The first view, at the window's default size.
start
read -r _ cx _ cz <<<"$(ask "pick $((VW / 2)) $((VH / 2)) $VW $VH" '^pick ')"
cx=${cx%.*} cz=${cz%.*}
shot 01_first_view

section "2"
# 2. Sculpt with each tool of the palette: a drag across the centre makes one undo step
# named after the tool, and every height tool changes the heights there.
for t in Raise:raise Lower:raise Smooth:smooth Flatten:flatten "Set height:set" Ramp:ramp \
    Noise:noise Terrace:terrace Thermal:thermal Hydraulic:hydraulic Paint:paint; do
    label=${t%%:*} name=${t#*:}
    h0=${h1:-$(box)}
    n=$(steps)
    click "Tools/$label"
    dock=${label,,}
    widget "Dock/Tool: ${dock/set height/set}" >/dev/null # the dock shows the tool picked
    drag -60 60
    line=$(step_line $((n + 1)))
    case "$line" in *" $name stroke tiles="[1-9]*) rc=0 ;; *) rc=1 ;; esac
    check "Tools/$label and a drag make one undo step, '$name stroke' ($line)" $rc
    h1=$(box)
    [ "$name" = paint ] || [ "$h1" != "$h0" ]; check "and ${label,,} changes the heights under the drag" $?
done
n=$(steps)
shot 02_sculpted

section "3"
# 3. A stamp: Tools/Stamp, a crater in the browser, a click in the viewport.
click "Tools/Stamp"
click "Dock/Stamps/crater"
widget "Dock/Tool: stamp crater" 8 >/dev/null
check "the stamp browser's crater picks it" $?
xdotool mousemove --window "$wid" $((VX + VW / 2)) $((VY + VH / 2)) click 1
n=$((n + 1))
line=$(step_line $n)
case "$line" in *" stamp crater tiles="[1-9]*) rc=0 ;; *) rc=1 ;; esac
check "the stamp browser's crater and a click make step $n ($line)" $rc
stamped=$(box)
shot 03_stamp

section "4"
# 4. Undo through History (Edit > History brings it into view): a click on the step
# before the stamp goes back to it.
click "Tools/Raise"
click "Menu/Edit" && click "Menu/Edit/History"
line=$(widget_name "Dock/Steps/$((n - 1)) ")
click "$line"
ask_until history '^steps=' "undoable=$((n - 1)) " >/dev/null
check "a click on History's '${line#Dock/Steps/}' undoes the stamp" $?
[ "$(box)" != "$stamped" ]; check "and the crater is gone" $?
shot 04_history_undo
click "$(widget_name "Dock/Steps/$n ")"
ask_until history '^steps=' "undoable=$n " >/dev/null && [ "$(box)" = "$stamped" ]
check "a click on the stamp's step redoes it, the heights exactly as stamped" $?

section "5"
# 5. The console: ~ opens it, Tab completes a command, Return runs it.
key grave
widget "Console/Input" >/dev/null; check "~ opens the console" $?
before=$(wc -l <"$work/out")
xdotool type --delay 30 "hist"
key Tab
key Return
for _ in $(seq 50); do tail -n +$((before + 1)) "$work/out" | grep -q '^steps=' && break; sleep 0.1; done
tail -n +$((before + 1)) "$work/out" | grep -q "^steps="
check "'hist', Tab, Return runs history in the console" $?
shot 05_console
key grave
widget_gone "Console/Input"; check "~ closes it" $?

section "6"
# 6. Save as through its dialog.
click "Menu/File" && click "Menu/File/Save as..."
fill "Save as/Path" "$work/first.world"
click "Save as/Save"
ask_until info '^path=' "first.world" >/dev/null && [ -s "$work/first.world" ]
check "Save as writes first.world and the world is named after it" $?
wait_title "first.world" >/dev/null; ok=$?; check "the title names it ($(title))" $ok
shot 06_saved

section "7"
# 7. A click made while work runs is kept: during a long hydraulic stroke, a click on
# Tools/Smooth waits; Esc cancels the stroke at once, and then the click picks smooth
# (issue 26: input is never dropped). A stroke of ~10 dabs of a million droplets: one
# dab (~1.5 s) could end, at load 5-8, before the Esc got there.
s0=$(steps)
echo "tool hydraulic droplets=1000000 radius=200; stroke $cx $cz $((cx + 150)) $cz $cx $cz $((cx + 150)) $cz" >&3
wait_title "working"; ok=$?; check "a long stroke runs in the background ($(title))" $ok
read -r x y w h <<<"$(widget "Tools/Smooth")"
xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)) click 1
line=$(ask ui_input_waiting '^ui_input_waiting ')
[ "${line#ui_input_waiting }" -gt 0 ] 2>/dev/null; check "the click waits for the work ($line)" $?
shot 07_click_waits
key Escape
line=$(ask_until tool '^tool=' '^tool=smooth$')
check "Esc cancels the stroke and then the click picks smooth ($line)" $?
[ "$(steps)" = "$s0" ]; check "the cancelled stroke left no step" $?
echo "tool hydraulic droplets=2000 radius=73" >&3

section "8"
# 8. Quit with unsaved changes: File > Quit asks; Save saves and quits. Reopened, File's
# recent list opens the world as it was, camera included.
click "Tools/Raise"
drag -40 40
n=$((n + 1))
step_line $n >/dev/null
edited=$(box)
cam=$(ask camera '^camera ')
click "Menu/File" && click "Menu/File/Quit"
widget "Unsaved changes/Save" >/dev/null; check "File > Quit with unsaved changes asks first" $?
shot 08_quit_asks
click "Unsaved changes/Save"
for _ in $(seq 100); do alive || break; sleep 0.1; done
! alive; check "Save in that dialog saves and quits" $?
exec 3>&-
wait $app 2>/dev/null
start
click "Menu/File" && click "Menu/File/Open first.world"
ask_until info '^path=' "first.world" >/dev/null; check "reopened, File > Open first.world opens it" $?
[ "$(box)" = "$edited" ]; check "with the last stroke, saved on quitting" $?
line=$(ask camera '^camera ')
[ "$line" = "$cam" ]; check "and its camera as it was left ($line)" $?
wait_title "pending 0$" >/dev/null
shot 08_reopened

section "9"
# 9. Import through the dialog: a file that is no heightmap fails there, with its message
# in the window; a real one imports as one undo step.
echo "not a heightmap" >"$work/notes.png"
"$orogen" -c "new flat; export $work/hm.exr region=0,0,128,128" >/dev/null 2>&1
s0=$(steps)
click "Menu/File" && click "Menu/File/Import heightmap..."
fill "Import heightmap/Path" "$work/notes.png"
click "Import heightmap/Next"
wait_message "notes.png"; ok=$?; check "importing notes.png shows why it failed ($(messages | tr '\n' '|'))" $ok
shot 09_import_failed
[ "$(steps)" = "$s0" ]; check "and changes nothing" $?
for name in "Notices/Dismiss" "Import heightmap/Cancel" "Import options/Cancel"; do
    widget "$name" 1 >/dev/null && click "$name"
done
click "Menu/File" && click "Menu/File/Import heightmap..."
fill "Import heightmap/Path" "$work/hm.exr"
click "Import heightmap/Next"
fill "Import options/x" "$cx"
fill "Import options/z" "$cz"
click "Import options/Import"
line=$(step_line $((s0 + 1)))
case "$line" in *" import hm.exr"*) rc=0 ;; *) rc=1 ;; esac
check "hm.exr through the dialog is one undo step ($line)" $rc
shot 09_imported

section "10"
# 10. Export through the dialog: the name proposed comes from the world.
click "Menu/File" && click "Menu/File/Export heightmap..."
widget "Export heightmap/Path" >/dev/null
fill "Export heightmap/Path" "$work/out.png"
click "Export heightmap/Next"
for f in x0=$((cx - 64)) z0=$((cz - 64)) x1=$((cx + 64)) z1=$((cz + 64)); do
    fill "Export options/${f%%=*}" "${f#*=}"
done
click "Export options/Export"
for _ in $(seq 100); do [ -s "$work/out.png.json" ] && break; sleep 0.1; done
grep -q '"width": 65' "$work/out.png.json" 2>/dev/null
check "Export writes a 65 x 65 PNG with its sidecar" $?

section "11"
# 11. Carve: a volume drag makes a carve step with volume bricks.
click "Tools/Carve"
ask_until tool '^tool=' '^tool=carve$' >/dev/null
s0=$(steps)
drag -50 50
line=$(step_line $((s0 + 1)))
case "$line" in *" carve stroke"*) rc=0 ;; *) rc=1 ;; esac
check "Tools/Carve and a drag carve ($line)" $rc
ask_until info '^volume_bricks=' '^volume_bricks=[1-9]' >/dev/null; check "into volume bricks" $?
shot 11_carved

section "12"
# 12. 1024 x 640, UI scale 1.5 from the View menu.
xdotool windowsize --sync "$wid" 1024 640
click "Menu/View" && click "Menu/View/UI scale 150%"
ask_until ui_scale '^ui_scale' '1.5' >/dev/null; check "View > UI scale 150% at 1024 x 640" $?
read -r VX VY VW VH <<<"$(widget Viewport)"
# (The dock scrolls: what lies below its foot is reached with the wheel, so only its
# width must fit.)
bad=$(ask "ui_widgets /" '^Viewport ' >/dev/null; tail -n 200 "$work/out" |
    awk '/^[A-Z][a-z]+\/.* -?[0-9]+ -?[0-9]+ -?[0-9]+ -?[0-9]+$/ { n = NF; dock = /^Dock\//
        if ($(n-3) < 0 || $(n-3) + $(n-1) > 1024.5) print
        else if (!dock && ($(n-2) < 0 || $(n-2) + $n > 640.5)) print }')
[ -z "$bad" ]; ok=$?; check "every widget lies inside the window ($(printf '%s\n' "$bad" | sed -n 1,2p | tr '\n' '|'))" $ok
shot 12_small_scaled

section "13"
# 13. A new planet from its dialog; a drag on the brush's Radius changes the brush only.
click "Menu/File" && click "Menu/File/New planet..."
click "New planet/Create"
widget "Unsaved changes/Discard" 8 >/dev/null && click "Unsaved changes/Discard"
planet=$(ask_until nparams '^radius = ' '^radius = [0-9]*;$')
ask_until info '^kind=' '^kind=planet$' >/dev/null; check "File > New planet makes a planet ($planet)" $?
wait_title "pending 0$" >/dev/null
# It opens on the whole disc from the day side, north up (test_planet_first_view measures it).
line=$(ask camera '^camera_geo '); case "$line" in "camera_geo 15.000000 23.000000 "*" 0.000 -89.900 "*) true ;; *) false ;; esac
check "the new planet opens on the whole lit disc ($line)" $?
r0=$(ask tool '^radius=')
read -r x y w h <<<"$(widget "Dock/Radius")"
xdotool mousemove --window "$wid" $((x + w / 4)) $((y + h / 2)) mousedown 1 \
    mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)) \
    mousemove --window "$wid" $((x + 3 * w / 4)) $((y + h / 2)) mouseup 1
r1=$(ask_until tool '^radius=' "^radius=" >/dev/null; for _ in $(seq 30); do
    l=$(ask tool '^radius='); [ "$l" != "$r0" ] && break; sleep 0.2; done; echo "$l")
line=$(ask nparams '^radius = ')
[ "$r1" != "$r0" ] && [ "$line" = "$planet" ]
check "a drag on Dock/Radius changes the brush ($r0 -> $r1), not the planet ($line)" $?
shot 13_planet

section "14"
# 14. A bad slider value: Ctrl+click Strength, 'x', Enter: refused with a message, the
# strength as it was; Esc closes the field.
s0=$(ask tool '^strength=')
read -r x y w h <<<"$(widget "Dock/Strength")"
xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)) keydown ctrl click 1 keyup ctrl
sleep 0.3
xdotool type --delay 30 "x"
key Return
wait_message 'Dock/Strength: "x" is not a number'; ok=$?; check "a bad value in Strength says why ($(messages | tr '\n' '|'))" $ok
shot 14_bad_value
key Escape
wait_message '^messages 0$' && [ "$(ask tool '^strength=')" = "$s0" ]
check "Esc closes it, the strength unchanged ($s0)" $?
alive; ok=$?; check "the editor ran the whole session ($(tail -c 300 "$work/err"))" $ok

echo "$passes passed, $failures failed"
# What the editor printed, kept with the screenshots when something failed.
[ $failures = 0 ] || cp "$work/out" "$art/scenario_console.txt" 2>/dev/null
[ $failures = 0 ] || cp "$work/err" "$art/scenario_errors.txt" 2>/dev/null
[ $failures = 0 ]
