#!/usr/bin/env bash
# End-to-end in the real window (Xvfb, xdotool): a world made by `new flat from=FILE`
# holds nothing of the user's until it is edited (the file on disk has it all, as an
# image opened in GIMP or a heightmap read into a new Gaea graph), so Ctrl+Q quits
# without asking and leaves no recovery journal; once edited, Ctrl+Q asks, and Discard
# quits and drops the journal.
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
sleep 0.5
title | grep -q '^Orogen - unsaved world - '; check "the title does not mark it modified ($(title))" $?
key ctrl+q
status=$(exit_status)
[ "$status" = 0 ]; check "Ctrl+Q quits without asking (status $status)" $?
[ "$(journals)" = 0 ]; check "no recovery journal is left to offer at the next start ($(journals))" $?
exec 3>&-

# 2. Edited: '*', Ctrl+Q asks; Discard quits and drops the journal.
session edited
echo "dab 50000 50000" >&3
wait_title "unsaved world \* - "; check "a dab marks it modified ($(title))" $?
key ctrl+q
widget "Unsaved changes/Discard" >/dev/null; check "Ctrl+Q asks once it is edited" $?
alive; check "and the window stays while it asks" $?
click "Unsaved changes/Discard"
status=$(exit_status)
[ "$status" = 0 ]; check "Discard quits (status $status)" $?
[ "$(journals)" = 0 ]; check "Discard drops the journal ($(journals))" $?

end_window_test
