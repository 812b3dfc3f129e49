#!/usr/bin/env bash
# End-to-end: the Materials panel in the real window (Xvfb, xdotool, widgets found by
# name): the rule stack listed top first with each material's swatch and ranges, a rule
# picked and moved, Edit putting its command in the console, Delete, Add rule, Default
# rules, a rule's range typed in place and a rule dragged to another place; every
# click a material_rule command (echoed, one undo step each), read back through the
# console. On a planet the panel says the rules lay over its own look, and takes them. The
# UI runs strict (an id conflict would stop the editor). Screenshots go to
# ${OROGEN_TEST_ARTIFACTS:-build/test-artifacts}.
# Usage: e2e_materials_panel.sh OROGEN TESTS_DIR
set -u
orogen=$1
. "$2/support/window_session.sh"
begin_window_test materials
require_tools Xvfb xdotool import
start_xvfb 1400x900
open_editor "$orogen"
. "$2/support/gui_helpers.sh"
shot() { import -window "$wid" "$art/materials_$1.png" 2>/dev/null; }
xdotool windowsize --sync "$wid" 1100 760
# The rules bottom first as `material_rules` lists them: "sand grass rock ...".
stack() {
    local before
    before=$(wc -l <"$work/out")
    ask material_rules '^material_rules: ' >/dev/null || return 1
    sleep 0.3
    tail -n +$((before + 1)) "$work/out" | sed -n 's/^rule [0-9]*: \([a-z]*\).*/\1/p' | tr '\n' ' '
}
# Waits (about 10 s) for the stack to read want; prints what it read last.
stack_until() {
    local s
    for _ in $(seq 20); do s=$(stack); [ "$s" = "$1" ] && break; sleep 0.4; done
    echo "$s"
    [ "$s" = "$1" ]
}
# A click the slow software renderer may take a frame or two to see: again until
# the widget want appears.
click_until() { # NAME WANT
    for _ in 1 2 3; do click "$1" && widget "$2" 20 >/dev/null && return 0; done
    return 1
}

# 1. The panel lists the default stack, top first.
click_until "Dock/Materials" "Dock/Rules/5 snow"
check "the Materials section opens on the rules" $?
before=$(wc -l <"$work/out")
ask "ui_widgets Dock/Rules/" '^Viewport ' >/dev/null
sleep 0.3
order=$(tail -n +$((before + 1)) "$work/out" | sed -n 's|^Dock/Rules/\([0-9] [a-z]*\) .*|\1|p' | tr '\n' ',')
[ "$order" = "5 snow,4 cliff,3 rock,2 grass,1 sand," ]; check "top rule first ($order)" $?
widget "Dock/Rules/height=62%+40,inf,80" >/dev/null && widget "Dock/Rules/everywhere" >/dev/null
check "each rule shows its ranges (sand: everywhere)" $?
shot panel

# 2. Pick grass, move it up: one step, echoed.
click "Dock/Rules/2 grass"
sleep 1
click "Dock/Up"
s=$(stack_until "sand rock grass cliff snow "); check "Up moves the picked rule ($s)" $?
ask_until history 'material_rule move' 'material_rule move 2 up' >/dev/null
check "the click ran material_rule move 2 up: one undo step named after it" $?
click "Dock/Down"
s=$(stack_until "sand grass rock cliff snow "); check "Down moves it back ($s)" $?

# 3. Edit puts the rule's set command in the console; Return runs it.
click "Dock/Rules/5 snow"
sleep 1
click "Dock/Edit"
sleep 1
key Return
ask_until history 'material_rule set' 'material_rule set 5 height=62%+40,inf,80 slope=0,28.8108,9.849' >/dev/null
check "Edit fills the console with the rule's set command, which runs" $?
shot edit

# 3b. The picked rule edited in place: its height's low end typed; a drag of a rule's
# row onto another moves it there.
xdotool windowfocus --sync "$wid" 2>/dev/null # typing goes to the window
click "Dock/Rules/5 snow"
reveal "Dock/Rule editor/height/Low"
fill "Dock/Rule editor/height/Low" 500
key Return
ask_until material_rules '^rule 5: ' '^rule 5: snow height=500,inf,80 ' >/dev/null
check "typing the picked rule's height Low runs material_rule set 5 height=500,inf,80" $?
reveal "Dock/Rules/5 snow"
drag_onto "Dock/Rules/2 grass" "Dock/Rules/4 cliff"
s=$(stack_until "sand rock cliff grass snow "); check "dragging grass's row onto cliff's moves it there ($s)" $?
shot rule_editor
echo "undo; undo" >&3
s=$(stack_until "sand grass rock cliff snow "); check "undo twice: the default stack again ($s)" $?

# 4. Delete, Add rule, Default rules.
click "Dock/Rules/4 cliff"
sleep 1
click "Dock/Delete"
s=$(stack_until "sand grass rock snow "); check "Delete removes the picked rule ($s)" $?
click "Dock/Add rule"
s=$(stack_until "sand grass rock snow sand "); check "Add rule adds one on top ($s)" $?
click "Dock/Default rules"
s=$(stack_until "sand grass rock cliff snow "); check "Default rules brings the stack back ($s)" $?
echo "undo" >&3
s=$(stack_until "sand grass rock snow sand "); check "undo takes Default rules back ($s)" $?
shot after

# 5. A planet: no rules at first, over its own look; Add rule adds one; drawn without
# an id conflict.
echo "new planet preset=moon" >&3
widget "Dock/These rules lay over*" 40 >/dev/null
check "on a planet the panel says the rules lay over the planet's own look" $?
s=$(stack_until ""); check "a planet starts with no rules ($s)" $?
click "Dock/Add rule"
s=$(stack_until "sand "); check "Add rule adds one on a planet ($s)" $?
alive; ok=$?; check "the editor is alive: no widget id conflict ($(tail -c 300 "$work/err"))" $ok
shot planet

end_window_test
