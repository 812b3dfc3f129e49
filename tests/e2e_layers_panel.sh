#!/usr/bin/env bash
# End-to-end: the Layers panel in the real window (Xvfb, xdotool, widgets found by name,
# a fresh HOME): New layer twice, a stroke in each (dragged across the viewport), the
# upper one hidden with its eye (the composite's hash goes back to the first stroke's
# alone) and a stroke on it refused where the user acted, shown again, moved down by a
# drag of its name, renamed by a double click, masked by slope in the mask editor (a
# range dragged over the histogram, then typed), the context menu's Duplicate and
# Delete, the blend dropdown's items (by name), curvature and flow ranges over their histograms (flow's dragged), the layer
# menu's Export dialog (a refusal shown in it, then the stack up to the layer written),
# and the Materials panel's rule ranges typed in place. Every action is a layer or
# material_rule command read back through the console (`layers`, `history`, `hash`).
# At 1024 x 640 and UI scale 1.5 every row of the panel lies inside the dock (and the
# opacity's tooltip beside it, not over the next row: a screenshot). The UI
# runs strict (an id conflict stops the editor). Screenshots go to
# ${OROGEN_TEST_ARTIFACTS:-build/test-artifacts}/layers_*.png.
# Usage: e2e_layers_panel.sh OROGEN TESTS_DIR
set -u
orogen=$1
. "$2/support/window_session.sh"
begin_window_test layers
require_tools Xvfb xdotool import
start_xvfb 1400x900
open_editor "$orogen"
. "$2/support/gui_helpers.sh"
shot() { import -window "$wid" "$art/layers_$1.png" 2>/dev/null; }
xdotool windowsize --sync "$wid" 1024 640
xdotool windowfocus --sync "$wid" 2>/dev/null # typing goes to the window
for _ in $(seq 40); do
    read -r VX VY VW VH <<<"$(widget Viewport)"
    [ -n "${VW:-}" ] && [ "$VW" -le 800 ] && break
    sleep 0.25
done
wait_title "pending 0$" >/dev/null
echo "camera 0 -100 0 30 -18" >&3
wait_title "cam (0.0, -100.0, 0.0) yaw 30.0 pitch -18.0.* - pending 0$" >/dev/null
# Fewer clipmap levels draw the slow software frames faster; the tool's options
# folded leave the dock room for the layers and the mask editor.
echo "tool raise radius=25 strength=1; render levels=4" >&3

# The stack as `layers` lists it, top first: "NAME:visible NAME:visible ...", the active
# one starred.
stack() {
    local before
    before=$(wc -l <"$work/out")
    ask layers '^[ *] 0 ' >/dev/null || return 1
    sleep 0.2
    tail -n +$((before + 1)) "$work/out" | sed -n 's/^\([ *]\) [0-9]* \([^ ]*\) .*visible=\([01]\).*/\1\2:\3/p' |
        tr '\n' ' '
}
stack_until() { # want: waits about 10 s for the stack to read it; prints the last read
    local s
    for _ in $(seq 25); do s=$(stack); [ "$s" = "$1" ] && break; sleep 0.4; done
    echo "$s"
    [ "$s" = "$1" ]
}
read -r _ px py pz <<<"$(ask "pick $((VW / 2)) $((VH / 2)) $VW $VH" '^pick ')"
box() { awk -v x="$px" -v z="$pz" 'BEGIN { print x - 120, z - 120, x + 120, z + 120 }'; }
hash_now() { ask "hash $(box)" '^[0-9a-f]\{16\}$'; }
hash_is() { for _ in $(seq 30); do [ "$(hash_now)" = "$1" ] && return 0; sleep 0.3; done; return 1; }
sculpt() { # a left drag across the viewport's centre, dy pixels below it
    local cx=$((VX + VW / 2)) cy=$((VY + VH / 2 + ${1:-0}))
    xdotool mousemove --window "$wid" $((cx - 50)) $cy mousedown 1
    for dx in -25 0 25 50; do
        sleep 0.05
        xdotool mousemove --window "$wid" $((cx + dx)) $cy
    done
    xdotool mouseup 1
    sleep 0.5
}
h0=$(hash_now)
# A range's end dragged: NAME FROM MID TO OF [SHOT]: from FROM/OF of its width through
# MID/OF to TO/OF, the screenshot SHOT taken before the release.
drag_range() {
    local x y w h
    read -r x y w h <<<"$(widget "$1")"
    xdotool mousemove --window "$wid" $((x + w * $2 / $5)) $((y + h / 2)) mousedown 1
    sleep 0.2
    xdotool mousemove --window "$wid" $((x + w * $3 / $5)) $((y + h / 2))
    sleep 0.2
    xdotool mousemove --window "$wid" $((x + w * $4 / $5)) $((y + h / 2))
    sleep 0.4
    [ -n "${6:-}" ] && shot "$6"
    xdotool mouseup 1
}
# A click the slow software renderer may take a frame or two to see (or that landed
# where the widget was a frame before): again until the widget WANT appears.
click_until() { # NAME WANT
    for _ in 1 2 3; do click "$1" && widget "$2" 12 >/dev/null && return 0; done
    return 1
}

# 1. The panel: one layer, Sculpt, active. New layer twice.
click "Dock/Tool: raise"
click_until "Dock/Layers" "Dock/Stack/Sculpt/Sculpt"
check "the Layers section lists the world's layer Sculpt" $?
click "Dock/New layer"
s=$(stack_until "*Layer_2:1  Sculpt:1 "); check "New layer adds Layer_2 on top, active ($s)" $?
sculpt
h1=$(hash_now)
[ -n "$h1" ] && [ "$h1" != "$h0" ]; check "a stroke in Layer_2 changes the composite ($h0 -> $h1)" $?
click "Dock/New layer"
s=$(stack_until "*Layer_3:1  Layer_2:1  Sculpt:1 "); check "a second New layer: Layer_3 ($s)" $?
sculpt 25
h2=$(hash_now)
[ -n "$h2" ] && [ "$h2" != "$h1" ]; check "a stroke in Layer_3 changes it again ($h1 -> $h2)" $?
shot two_layers

# 2. The eye hides Layer_3: the composite is Layer_2's stroke alone; a stroke on the
# hidden layer is refused where the user acted (a notice) and the dock says why.
click "Dock/Stack/Layer_3/Visible"
s=$(stack_until "*Layer_3:0  Layer_2:1  Sculpt:1 "); check "the eye hides Layer_3 ($s)" $?
hash_is "$h1"; check "hidden, Layer_3 leaves the composite as after Layer_2's stroke" $?
widget "Dock/layer Layer_3 is hidden*" >/dev/null && widget "Status/layer Layer_3 is hidden: raise refused" >/dev/null
check "the dock and the status bar say the active layer refuses the tool" $?
sculpt
ask_until ui_messages "'Layer_3' is hidden" "is hidden: edits to it would not show" >/dev/null
check "a stroke on the hidden layer is refused with the reason, shown in the window" $?
hash_is "$h1"; check "the refused stroke changed nothing" $?
shot hidden
click "Dock/Stack/Layer_3/Visible"
hash_is "$h2"; check "the eye shows it again: the composite is back" $?

# 3. A drag of Layer_3's name down onto Sculpt's row moves it to the bottom (layer move).
drag_onto "Dock/Stack/Layer_3/Layer_3" "Dock/Stack/Sculpt/Sculpt"
s=$(stack_until " Layer_2:1  Sculpt:1 *Layer_3:1 "); check "a drag of its name moves Layer_3 to the bottom ($s)" $?
ask_until history 'layer move' 'layer move Layer_3' >/dev/null; check "the drag ran layer move: one undo step" $?

# 4. A double click on Layer_2's name types a new one: Hill.
# (Again when a loaded machine's slow frames took the two clicks for two single ones.)
for _ in 1 2 3; do
    read -r x y w h <<<"$(widget "Dock/Stack/Layer_2/Layer_2")"
    xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)) click --repeat 2 --delay 60 1
    widget "Dock/Stack/Layer_2/Rename" 12 >/dev/null && break
done
widget "Dock/Stack/Layer_2/Rename" >/dev/null; check "a double click opens the name for typing" $?
sleep 0.4
key ctrl+a
xdotool type --delay 20 "Hill"
key Return
s=$(stack_until "*Hill:1  Sculpt:1  Layer_3:1 "); check "Enter renames Layer_2 to Hill ($s)" $?

# 5. The mask editor: Hill only on slopes within a range, dragged over the histogram,
# then its high end typed.
click_until "Dock/Stack/Hill/Mask" "Dock/Mask editor/Mask of Hill*"
check "Mask opens the mask editor on Hill" $?
hm0=$(hash_now)
reveal "Dock/Mask editor/slope/Slope (degrees)"
click_until "Dock/Mask editor/slope/Slope (degrees)" "Dock/Mask editor/slope/Range"
line=$(ask_until "layer mask Hill" 'slope=\|none' 'slope=20,45,5'); rc=$?
check "its Slope box gives Hill a slope term ($line; $(tail -n 2 "$work/err" | tr '\n' ' '))" $rc
reveal "Dock/Mask editor/slope/High"
# The low end (20 of 90 degrees) dragged to about 5.
drag_range "Dock/Mask editor/slope/Range" 20 12 5 90 mask_drag
line=$(ask_until "layer mask Hill" 'slope=' 'slope=[3-7]\(\.5\)\?,45,5'); check "dragging the range's low end sets it ($line)" $?
hmd=$(hash_now)
fill "Dock/Mask editor/slope/High" 12
key Return
line=$(ask_until "layer mask Hill" 'slope=' 'slope=[3-7]\(\.5\)\?,12,5'); check "typing the high end sets it ($line)" $?
hm1=$(hash_now)
[ -n "$hm1" ] && [ "$hm1" != "$hm0" ]; check "the slope mask changes the composite ($hm0 -> $hm1)" $?
shot mask
echo undo >&3
hash_is "$hmd"; check "undo takes the typed end back, and the composite with it" $?
echo redo >&3
hash_is "$hm1"; check "redo" $?

# 6. The right-click menu: Duplicate, then Delete the copy.
reveal "Dock/Stack/Hill/Hill"
read -r x y w h <<<"$(widget "Dock/Stack/Hill/Hill")"
xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)) click 3
sleep 0.4
click "Dock/Stack/Hill/Layer menu/Duplicate"
s=$(stack_until "*Hill_copy:1  Hill:1  Sculpt:1  Layer_3:1 "); check "Duplicate from the right-click menu ($s)" $?
read -r x y w h <<<"$(widget "Dock/Stack/Hill_copy/Hill_copy")"
xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)) click 3
sleep 0.4
click "Dock/Stack/Hill_copy/Layer menu/Delete"
s=$(stack_until "*Hill:1  Sculpt:1  Layer_3:1 "); check "Delete from the right-click menu ($s)" $?
hash_is "$hm1"; check "after duplicate and delete the composite is as before" $?

# 6a. The blend dropdown's items are named (Dock/Stack/Hill/Blend/max): a click on one
# runs layer set, one undo step.
reveal "Dock/Stack/Hill/Blend"
click "Dock/Stack/Hill/Blend"
click "Dock/Stack/Hill/Blend/max"
line=$(ask_until layers ' Hill ' ' Hill .*blend=max '); check "the Blend dropdown's item max sets Hill's blend ($line)" $?
echo undo >&3
line=$(ask_until layers ' Hill ' ' Hill .*blend=add '); check "undo puts it back to add ($line)" $?
hash_is "$hm1"; check "and the composite with it" $?

# 6b. Curvature and flow get their histograms too; the flow range's low end dragged
# over its log scale (the viewport tints the channels the range holds). Slope and
# curvature are switched off again first, so the picture shows flow alone.
reveal "Dock/Mask editor/slope/Slope (degrees)"
click "Dock/Mask editor/slope/Slope (degrees)"
reveal "Dock/Mask editor/curvature/Curvature (convex +)"
click_until "Dock/Mask editor/curvature/Curvature (convex +)" "Dock/Mask editor/curvature/Range"
check "Curvature's box shows its range over a histogram" $?
click "Dock/Mask editor/curvature/Curvature (convex +)"
line=$(ask_until "layer mask Hill" 'slope=\|curvature=\|^none' '^none$'); check "the boxes take the slope and curvature terms off ($line)" $?
reveal "Dock/Mask editor/flow/Flow (m2 upstream)"
click_until "Dock/Mask editor/flow/Flow (m2 upstream)" "Dock/Mask editor/flow/Range"
check "Flow's box shows its range over a histogram" $?
f0=$(ask_until "layer mask Hill" 'flow=' 'flow=[0-9.e+]*,inf'); check "flow starts at the view's channels, open above ($f0)" $?
reveal "Dock/Mask editor/flow/High"
drag_range "Dock/Mask editor/flow/Range" 6 4 3 10
f1=$(ask_until "layer mask Hill" 'flow=' 'flow=[0-9.e+]*,inf')
lo0=$(echo "$f0" | sed -n 's/.*flow=\([^,]*\),.*/\1/p'); lo1=$(echo "$f1" | sed -n 's/.*flow=\([^,]*\),.*/\1/p')
awk -v a="$lo0" -v b="$lo1" 'BEGIN { exit !(b > 0 && b < a) }'
check "dragging flow's low end left lowers it, the top stays open ($f0 -> $f1)" $?
shot mask_flow

# 6c. The layer menu's Export... opens the export dialog on Hill: a folder that is not
# there is refused in the dialog, which stays open; then the stack up to Hill (the
# Layers box) is written as an EXR with its sidecar, which oiiotool reads.
reveal "Dock/Stack/Hill/Hill"
read -r x y w h <<<"$(widget "Dock/Stack/Hill/Hill")"
xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)) click 3
sleep 0.4
click "Dock/Stack/Hill/Layer menu/Export..."
widget "Export options/Export to Hill.exr" >/dev/null && widget "Export options/Format" >/dev/null
check "Export... opens the export dialog on Hill.exr with its format and layers" $?
read -r bx0 bz0 bx1 bz1 <<<"$(box)"
if widget "Export options/x0" 2 >/dev/null; then # an unbounded world: the region asked
    for f in "x0=$bx0" "z0=$bz0" "x1=$bx1" "z1=$bz1"; do fill "Export options/${f%%=*}" "${f#*=}"; done
fi
fill "Export options/path" "$work/nowhere/Hill.exr"
click "Export options/Export"
widget "Export options/File: the folder*" >/dev/null && widget "Export options/path" >/dev/null
check "a folder that is not there is said in the dialog, which stays open" $?
shot export_refused
fill "Export options/path" "$work/Hill.exr"
click "Export options/Layers" && click "Export options/Layers/The stack up to Hill"
click "Export options/Export"
for _ in $(seq 100); do [ -s "$work/Hill.exr.json" ] && break; sleep 0.2; done
grep -q '"layers": "upto"' "$work/Hill.exr.json" && grep -q '"edit_layer": "Hill"' "$work/Hill.exr.json"
check "Export writes the stack up to Hill with its sidecar" $?
if command -v oiiotool >/dev/null; then
    oiiotool --info "$work/Hill.exr" 2>&1 | grep -q "float"; check "oiiotool reads the EXR as float" $?
fi

# 7. At 1024 x 640 and UI scale 1.5 every widget of the stack and the mask editor lies
# inside the dock (the Layers header's width).
ask "ui_scale 1.5; ui_scale" "^ui_scale 1.5" >/dev/null
sleep 1
read -r lx _ lw _ <<<"$(widget "Dock/Layers")"
before=$(wc -l <"$work/out")
ask "ui_widgets Dock/" '^Viewport ' >/dev/null
sleep 0.3
out=$(tail -n +$((before + 1)) "$work/out" | grep -E '^Dock/(Stack|Mask editor|New layer)')
bad=$(echo "$out" | awk -v l="$lx" -v r=$((lx + lw)) '{ n = NF; if ($(n-3) < l - 1 || $(n-3) + $(n-1) > r + 1) print }')
[ -n "$out" ] && [ -n "$lx" ] && [ -z "$bad" ]
ok=$?; check "at UI scale 1.5 the panel fits the dock ($(echo "$out" | wc -l) widgets; outside: ${bad:-none})" $ok
shot scale_1_5
# The opacity's tooltip lies beside the dock, not over the next layer's name.
reveal "Dock/Stack/Hill/Opacity"
read -r x y w h <<<"$(widget "Dock/Stack/Hill/Opacity")"
xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2))
sleep 1.5
shot opacity_tooltip
alive; ok=$?; check "the editor is alive: no widget id conflict ($(tail -c 300 "$work/err"))" $ok

end_window_test
