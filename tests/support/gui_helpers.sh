# Sourced by the tests that drive the editor window through its console (e2e_gui,
# e2e_newcomer): ask the console, find widgets by name (ui_widgets), click them. Needs
# $work (the test's folder, with the console's output in $work/out), $app (the
# editor's pid), $wid (its window) and the console's input open on fd 3.

alive() { kill -0 $app 2>/dev/null; }
title() { xdotool getwindowname "$wid" 2>/dev/null; }
wait_title() { # pattern: waits up to 30 s for the title to match
    for _ in $(seq 300); do title | grep -q -- "$1" && return 0; sleep 0.1; done
    return 1
}
# Runs a console command and prints the first new output line matching pattern
# (waits up to 30 s); nothing if none came.
ask() {
    local before
    alive || return 1
    before=$(wc -l <"$work/out")
    echo "$1" >&3
    for _ in $(seq "${ask_tries:-300}"); do
        alive || return 1
        local line
        line=$(tail -n +$((before + 1)) "$work/out" | grep -m 1 -- "$2")
        [ -n "$line" ] && { echo "$line"; return 0; }
        sleep 0.1
    done
    return 1
}
# Asks until the line matching pattern also matches want (a click acts in the frame
# after it; up to about 10 s); prints the last line seen.
ask_until() { # command pattern want
    local line
    for _ in $(seq 30); do
        line=$(ask_tries=50 ask "$1" "$2") # a line that never comes: 5 s a try, not 30
        if echo "$line" | grep -q -- "$3"; then echo "$line"; return 0; fi
        sleep 0.3
    done
    echo "$line"
    return 1
}
# ui_widgets, filtered on the name: prints "X Y W H" of the widget called exactly NAME
# (or, for "NAME*", the first whose name starts with NAME) in the last frame; waits up
# to about 10 s, or TRIES quarter seconds, for it to appear. Names may hold spaces: the
# last 4 numbers are the rectangle, everything before them the name.
widget() { # NAME [TRIES]
    local name=$1 prefix=0 filter before l
    case $name in *\*) prefix=1 name=${name%\*} ;; esac
    filter=$(printf '%s' "$name" | sed 's/[\\"]/\\&/g')
    for _ in $(seq "${2:-40}"); do
        alive || return 1
        before=$(wc -l <"$work/out")
        echo "ui_widgets \"$filter\"" >&3
        # The listing is written at once, the Viewport line first.
        for _ in $(seq 100); do
            tail -n +$((before + 1)) "$work/out" | grep -q '^Viewport ' && break
            sleep 0.05
        done
        while IFS= read -r l; do
            [[ $l =~ ^(.*)\ (-?[0-9]+)\ (-?[0-9]+)\ (-?[0-9]+)\ (-?[0-9]+)$ ]] || continue
            local n=${BASH_REMATCH[1]}
            if [ "$n" = "$name" ] || { [ $prefix = 1 ] && [ "${n#"$name"}" != "$n" ]; }; then
                echo "${BASH_REMATCH[2]} ${BASH_REMATCH[3]} ${BASH_REMATCH[4]} ${BASH_REMATCH[5]}"
                return 0
            fi
        done < <(tail -n +$((before + 1)) "$work/out")
        sleep 0.2
    done
    return 1
}
# The full name of the first widget starting with PREFIX (as widget "PREFIX*" finds it).
widget_name() {
    local before
    before=$(wc -l <"$work/out")
    widget "$1*" >/dev/null || return 1
    tail -n +$((before + 1)) "$work/out" | grep -F -- "$1" | grep -m 1 -E ' -?[0-9]+ -?[0-9]+ -?[0-9]+ -?[0-9]+$' |
        sed -E 's/ -?[0-9]+ -?[0-9]+ -?[0-9]+ -?[0-9]+$//'
}
# Waits up to about 10 s for the widget NAME to be gone from the frame.
widget_gone() {
    local filter before
    filter=$(printf '%s' "$1" | sed 's/[\\"]/\\&/g')
    for _ in $(seq 40); do
        before=$(wc -l <"$work/out")
        ask "ui_widgets \"$filter\"" '^Viewport ' >/dev/null || return 1
        sleep 0.1 # the listing comes in one write; a margin all the same
        tail -n +$((before + 1)) "$work/out" | sed -E 's/ -?[0-9]+ -?[0-9]+ -?[0-9]+ -?[0-9]+$//' |
            grep -q -F -x -- "$1" || return 0
        sleep 0.25
    done
    return 1
}
# Waits (up to about 10 s) until the window has acted on every mouse and key event sent
# to it and run the commands they queued (ui_input_waiting 0, twice: the second answer
# comes from a later turn of its loop, after it read what the X server had for it).
settle() {
    local zeros=0 line
    for _ in $(seq 200); do
        line=$(ask_tries=100 ask ui_input_waiting '^ui_input_waiting ') || return 1
        if [ "$line" = "ui_input_waiting 0" ]; then
            zeros=$((zeros + 1))
            [ $zeros = 2 ] && return 0
        else
            zeros=0
            sleep 0.05
        fi
    done
    return 1
}
# Clicks the centre of the widget NAME (see widget), then waits for the UI to act on it.
click() {
    local x y w h
    read -r x y w h <<<"$(widget "$1")" || return 1
    [ -n "$h" ] || { echo "click: no widget '$1' in the window" >&2; return 1; }
    xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)) click 1
    settle
}
key() { xdotool key "$@" && settle; }
# The lines ui_messages lists now: "messages N", then each "WHERE: TEXT".
messages() { # the lines ui_messages lists now
    local before
    before=$(wc -l <"$work/out")
    ask ui_messages '^messages ' >/dev/null || return 1
    sleep 0.1
    tail -n +$((before + 1)) "$work/out" | sed -n '/^messages /,$p'
}
is_png() { [ -s "$1" ] && [ "$(head -c 4 "$1" | od -An -c | tr -d ' ')" = "211PNG" ]; }
# Types TEXT into the field NAME: a click focuses it and selects its text (the fields of
# these dialogs replace their text when typed into).
fill() {
    click "$1" || return 1
    key ctrl+a
    xdotool type --delay 20 -- "$2"
    settle
}
# Scrolls the dock (the wheel over it) until the widget NAME lies within the rows of
# the viewport (as tall as the dock), up to 12 notches.
reveal() {
    local x y w h vx vy vw vh
    read -r vx vy vw vh <<<"$(widget Viewport)"
    for _ in $(seq 12); do
        read -r x y w h <<<"$(widget "$1")"
        [ -n "${h:-}" ] || return 1
        [ $((y + h)) -le $((vy + vh)) ] && [ "$y" -ge "$vy" ] && return 0
        xdotool mousemove --window "$wid" $((x + w / 2)) $((vy + vh / 2)) click "$([ "$y" -ge "$vy" ] && echo 5 || echo 4)"
        sleep 0.3
    done
    return 1
}
# A left drag from the centre of the widget NAME down or up to the height of TARGET's
# centre, in four moves (a row dragged to another place in a list).
drag_onto() { # NAME TARGET
    local x y w h ty th
    read -r x y w h <<<"$(widget "$1")"
    read -r _ ty _ th <<<"$(widget "$2")"
    [ -n "${h:-}" ] && [ -n "${th:-}" ] || return 1
    xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)) mousedown 1
    for f in 1 2 3 4; do
        sleep 0.1
        xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2 + (ty + th / 2 - y - h / 2) * f / 4))
    done
    sleep 0.3
    xdotool mouseup 1
}
# Prints the names of the widgets whose name contains FILTER.
names() {
    local before
    before=$(wc -l <"$work/out")
    ask "ui_widgets \"$1\"" '^Viewport ' >/dev/null || return 1
    sleep 0.1
    tail -n +$((before + 1)) "$work/out" | grep -v '^Viewport ' | sed -E 's/ -?[0-9]+ -?[0-9]+ -?[0-9]+ -?[0-9]+$//'
}
