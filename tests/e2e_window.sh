#!/usr/bin/env bash
# End-to-end: the real editor window under Xvfb, driven with real input (xdotool)
# and the console on standard input: the 3D viewport's camera modes, sculpting with
# undo and redo, saving, console screenshots. Usage: e2e_window.sh OROGEN TESTS_DIR
set -u
orogen=$1
. "$2/support/window_session.sh"
begin_window_test window
require_tools Xvfb xdotool

start_xvfb 1400x900
open_editor "$orogen" --record "$work/session.og"

title() { xdotool getwindowname "$wid"; }
wait_title() { # pattern: waits up to 30 s for the title to match
    for _ in $(seq 300); do title | grep -q -- "$1" && return 0; sleep 0.1; done
    return 1
}
# Runs a console command and prints the first new output line matching pattern
# (waits up to 30 s); nothing if none came.
ask() {
    local before
    before=$(wc -l <"$work/out")
    echo "$1" >&3
    for _ in $(seq 300); do
        local line
        line=$(tail -n +$((before + 1)) "$work/out" | grep -m 1 -- "$2")
        [ -n "$line" ] && { echo "$line"; return 0; }
        sleep 0.1
    done
    return 1
}
# The camera as the console reports it: X Y Z YAW PITCH. The window handles input
# before console lines, so this sees every event sent before it.
cam() { sleep 0.2; ask camera '^camera ' | awk '{ print $2, $3, $4, $5, $6 }'; }
# Waits until the camera is still and every level is current.
settle() { wait_title "pending 0$"; }
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; exit !(d <= t && -d <= t) }'; }

# A small viewport keeps software rendering (llvmpipe) fast: the window is sized so the
# 3D viewport (between the editor's panels, found by name with ui_widgets) is exactly
# 400 x 300; every position below is relative to the viewport's top-left (VX, VY).
viewport_rect() { ask "ui_widgets Viewport" '^Viewport ' | awk '{ print $2, $3, $4, $5 }'; }
# (The side panels may narrow with the window, so the size is corrected a few times.)
# Each correction waits for a frame laid out at the new size (a busy machine draws slowly).
read -r VX VY VW VH <<<"$(viewport_rect)"
for _ in $(seq 12); do
    [ "$VW" = 400 ] && [ "$VH" = 300 ] && break
    read -r WW WH <<<"$(xdotool getwindowgeometry --shell "$wid" | awk -F= '/WIDTH|HEIGHT/ { printf "%s ", $2 }')"
    xdotool windowsize --sync "$wid" $((WW + 400 - VW)) $((WH + 300 - VH))
    before="$VX $VY $VW $VH"
    for _ in $(seq 30); do
        sleep 0.2
        read -r VX VY VW VH <<<"$(viewport_rect)"
        [ "$VX $VY $VW $VH" != "$before" ] && break
    done
done
[ "$VW" = 400 ] && [ "$VH" = 300 ]; check "the viewport is found by name and sized 400 x 300 (at $VX $VY, $VW x $VH)" $?
xdotool windowfocus --sync "$wid" 2>/dev/null
home() { echo "camera 0 -100 0 30 -40" >&3; wait_title "cam (0.0, -100.0, 0.0) yaw 30.0 pitch -40.0" && settle; }
settle; rc=$?; check "every tile of the first view arrives (title says pending 0): $(title)" $rc
home; check "console 'camera' places the camera (title shows it)" $?
# The pointer leaves the window and comes back over the terrain: the status bar names the
# ground under it only while it is there.
status_item() { # PATTERN: the status bar's item matching it, within about 6 s
    local l
    for _ in $(seq 30); do
        l=$(ask "ui_widgets Status/" '^Status/ ' >/dev/null; sleep 0.1; grep '^Status/' "$work/out" | tail -n 5 | grep -m 1 -- "$1")
        [ -n "$l" ] && { echo "$l"; return 0; }
        sleep 0.1
    done
    return 1
}
xdotool mousemove --window "$wid" $((VX + 100)) $((VY + 100)) sleep 0.3 mousemove 1399 899
line=$(status_item '^Status/no terrain under the pointer ')
rc=$?; check "the pointer off the window: no point in the status bar ($line)" $rc
xdotool mousemove --window "$wid" $((VX + 200)) $((VY + 200))
line=$(status_item '^Status/x ')
rc=$?; check "the pointer over the terrain shows where it is in the status bar ($line)" $rc
hash_box() { ask "hash $(awk -v x="$1" -v z="$2" 'BEGIN { print x - 150, z - 150, x + 150, z + 150 }')" '^[0-9a-f]\{16\}$'; }
# The brush ring leaves with the pointer: over the terrain it is drawn; moved on to the
# status bar it is gone from the next frame (it stayed drawn there: the view was not
# redrawn for a pointer outside it).
read -r _ SX SY SW SH <<<"$(ask "ui_widgets Status/" '^Status/ ')"
view_crop() { # NAME: the viewport's pixels now, as $work/NAME.png
    sleep 0.8; settle
    import -window root "$work/screen.png" && convert "$work/screen.png" -crop "${VW}x${VH}+$VX+$VY" +repage "$work/$1.png"
}
xdotool mousemove --window "$wid" $((SX + SW / 2)) $((SY + SH / 2)); view_crop ring_never
xdotool mousemove --window "$wid" $((VX + 200)) $((VY + 150)); view_crop ring_over
xdotool mousemove --window "$wid" $((SX + SW / 2)) $((SY + SH / 2)); view_crop ring_left
rmse_tool="$(dirname "$orogen")/image_rmse"
shown=$("$rmse_tool" "$work/ring_never.png" "$work/ring_over.png" | sed -n 's/^rmse=//p')
left=$("$rmse_tool" "$work/ring_never.png" "$work/ring_left.png" | sed -n 's/^rmse=//p')
awk -v s="$shown" -v l="$left" 'BEGIN { exit !(s > 0.3 && l < 0.05) }'
check "the brush ring shows over the terrain and goes when the pointer moves on to the status bar (RMSE with the ring $shown, after $left)" $?

# Fly: right button held, W held for about a second: forward along the view (yaw 30,
# pitch -40: east, down and north).
xdotool mousemove --window "$wid" $((VX + 200)) $((VY + 150)) mousedown 3
xdotool keydown w; sleep 1; xdotool keyup w
xdotool mouseup 3
read -r x y z yaw pitch <<<"$(cam)"
awk -v x="$x" -v y="$y" -v z="$z" 'BEGIN { exit !(x > 5 && y < -110 && z < -5) }'
check "right button + W flies forward (cam $x $y $z)" $?
home

# Wheel: one notch toward the point under the cursor brings the camera to 0.8 of the distance.
p0=$(ask "pick 200 150 400 300" '^pick ')
xdotool mousemove --window "$wid" $((VX + 200)) $((VY + 150)) click 4
read -r x y z yaw pitch <<<"$(cam)"
ratio=$(echo "$p0" | awk -v x="$x" -v y="$y" -v z="$z" '{
    d0 = sqrt($2 * $2 + ($3 + 100) * ($3 + 100) + $4 * $4)
    d1 = sqrt(($2 - x) ^ 2 + ($3 - y) ^ 2 + ($4 - z) ^ 2); print d1 / d0 }')
near "$ratio" 0.8 0.02; check "the wheel dollies toward the point under the cursor (distance x $ratio)" $?
home

# Orbit: middle drag and Alt+left drag turn the view around the picked point; they
# must not sculpt.
pick=$(ask "pick 200 150 400 300" '^pick ')
read -r _ px py pz <<<"$pick"
h0=$(hash_box "$px" "$pz")
xdotool mousemove --window "$wid" $((VX + 200)) $((VY + 150)) mousedown 2 mousemove --window "$wid" $((VX + 250)) $((VY + 150)) \
    mousemove --window "$wid" $((VX + 300)) $((VY + 150)) mouseup 2
read -r x y z yaw pitch <<<"$(cam)"
near "$yaw" 60 0.5; check "middle drag 100 px orbits 30 degrees (yaw $yaw)" $?
xdotool mousemove --window "$wid" $((VX + 200)) $((VY + 150)) keydown alt mousedown 1 mousemove --window "$wid" $((VX + 200)) $((VY + 120)) \
    mousemove --window "$wid" $((VX + 200)) $((VY + 100)) mouseup 1 keyup alt
read -r x2 y2 z2 yaw2 pitch2 <<<"$(cam)"
near "$pitch2" -55 0.5 && awk -v a="$y2" -v b="$y" 'BEGIN { exit !(a > b) }'
check "Alt + drag up orbits up over the pivot (pitch $pitch2, height $y -> $y2)" $?
[ "$(hash_box "$px" "$pz")" = "$h0" ]; check "orbit drags leave the terrain alone" $?
home

# Walk mode: G puts the eye 1.8 m above the ground; W walks and it stays there.
xdotool key g
wait_title " - walk "; check "G switches to walk mode" $?
ground_gap() { # prints X and the eye's height above the ground there
    local x y z yaw pitch h
    read -r x y z yaw pitch <<<"$(cam)"
    h=$(ask "sample $x $z" '^-\?[0-9]')
    awk -v x="$x" -v y="$y" -v h="$h" 'BEGIN { printf "%s %.2f", x, y - h }'
}
sleep 0.5; settle
read -r x0 gap <<<"$(ground_gap)"
near "$gap" 1.8 0.5; check "walk mode: eye 1.8 m above the ground (gap $gap)" $?
xdotool keydown w; sleep 1; xdotool keyup w
sleep 0.5; settle
read -r x1 gap <<<"$(ground_gap)"
awk -v a="$x1" -v b="$x0" 'BEGIN { exit !(a - b > 1) }' && near "$gap" 1.8 0.5
check "walking on W follows the ground (x $x0 -> $x1, gap $gap)" $?
xdotool key g
wait_title " - fly "; check "G again leaves walk mode" $?
home

# Ctrl+S before the world has a file: a message, no crash.
xdotool key ctrl+s
for _ in $(seq 50); do grep -q "type save FILE" "$work/err" && break; sleep 0.1; done
grep -q "type save FILE" "$work/err"; check "Ctrl+S on a never-saved world says to type save FILE" $?

# Sculpting: a left drag raises the terrain as one undo step.
h0=$(hash_box "$px" "$pz")
xdotool mousemove --window "$wid" $((VX + 170)) $((VY + 150)) mousedown 1 mousemove --window "$wid" $((VX + 185)) $((VY + 150)) \
    mousemove --window "$wid" $((VX + 200)) $((VY + 150)) mousemove --window "$wid" $((VX + 215)) $((VY + 150)) \
    mousemove --window "$wid" $((VX + 230)) $((VY + 150)) mouseup 1
wait_title "unsaved world \* - "; check "the title marks the world modified" $?
# On a loaded machine the console's question can come before the window has taken the
# last moves and the release: the stroke's hash is the one that stays.
h1=$(hash_box "$px" "$pz")
for _ in $(seq 20); do
    sleep 0.5
    h=$(hash_box "$px" "$pz")
    [ "$h" = "$h1" ] && break
    h1=$h
done
[ -n "$h1" ] && [ "$h1" != "$h0" ]; check "left drag sculpts ($h0 -> $h1)" $?
# A key acts in the next frame, which may come after the console's question: ask again.
hash_is() { for _ in $(seq 30); do [ "$(hash_box "$px" "$pz")" = "$1" ] && return 0; sleep 0.3; done; return 1; }
xdotool key ctrl+z
hash_is "$h0"; check "Ctrl+Z restores the heights exactly" $?
xdotool key ctrl+shift+z
hash_is "$h1"; check "Ctrl+Shift+Z redoes the stroke" $?

# Console screenshots render offscreen through the window's context.
line=$(ask "screenshot $work/shot.png 320 240" '^screenshot ')
[ -n "$line" ] && [ "$(head -c 4 "$work/shot.png" | od -An -c | tr -d ' ')" = "211PNG" ]
check "console screenshot writes a PNG while the window runs ($line)" $?

# Saving: from the console once, then Ctrl+S after another stroke.
line=$(ask "save $work/saved.world" '^saved ')
[ -s "$work/saved.world" ] && wait_title "saved.world - "; check "save from the console ($line)" $?
xdotool mousemove --window "$wid" $((VX + 200)) $((VY + 130)) mousedown 1 mousemove --window "$wid" $((VX + 200)) $((VY + 170)) mouseup 1
wait_title "saved.world \* - "; check "a new stroke marks the saved world modified" $?
saves=$(grep -c '^saved ' "$work/out")
xdotool key ctrl+s
wait_title "saved.world - " && [ "$(grep -c '^saved ' "$work/out")" -gt "$saves" ]
rc=$?; check "Ctrl+S saves again ($(title))" $rc

# The drags ran as commands: the recorded session replays, in batch mode, to the same terrain.
hf=$(hash_box "$px" "$pz")
grep -q '^stroke_begin$' "$work/session.og" && grep -q '^stroke_to ' "$work/session.og" &&
    grep -q '^stroke_end$' "$work/session.og"
check "sculpting drags are recorded as stroke_begin / stroke_to / stroke_end commands" $?
line=$(ask "history script $work/script.og" '^wrote ')
[ "$line" = "wrote $work/script.og" ] && grep -q '^stroke_to ' "$work/script.og" &&
    ! grep -q '^history script' "$work/script.og"
check "history script FILE writes the session's commands, strokes with every point ($line)" $?

# Bad commands are reported; the window stays.
echo "frobnicate" >&3
for _ in $(seq 100); do grep -q "console:1: error: unknown command 'frobnicate'" "$work/err" && break; sleep 0.1; done
grep -q "console:1: error: unknown command 'frobnicate'" "$work/err"; check "console errors are reported" $?
echo "camera 1 2" >&3
sleep 0.3
kill -0 $app 2>/dev/null && [ -n "$(ask "camera" '^camera ')" ]; check "the editor survives bad commands" $?

# Each tool keeps its own settings; radius and strength are shared by all tools unless
# memory=per_tool; and they are kept between runs.
echo "tool smooth radius=33 falloff=tip strength=0.25; tool raise radius=12" >&3
ask "tool smooth; tool" '^memory=' >/dev/null
line=$(tail -n 40 "$work/out" | grep -E '^(radius|strength|falloff|memory)=' | tail -n 4 | tr '\n' ' ')
[ "$line" = "radius=12 strength=0.25 falloff=tip memory=shared " ]
check "by default a tool picked again has the shared radius and strength, and its own falloff ($line)" $?
echo "tool smooth memory=per_tool radius=33; tool raise radius=12" >&3
line=$(ask "tool smooth; tool" '^radius=')
[ "$line" = "radius=33" ]; check "with memory=per_tool a tool picked again has its own radius back ($line)" $?
echo "tool raise" >&3

echo "exit" >&3
status=1
for _ in $(seq 200); do kill -0 $app 2>/dev/null || break; sleep 0.1; done
if ! kill -0 $app 2>/dev/null; then wait $app; status=$?; fi
[ $status = 0 ]; check "exit closes the editor with status 0" $?
grep -q "^recent_0 = $work/saved.world;" "$work/config/orogen/settings" && grep -q '^width = ' "$work/config/orogen/settings" &&
    grep -q '^fly_speed = ' "$work/config/orogen/settings"
rc=$?; check "the editor's settings are kept for the next run (window size, recent worlds, fly speed): $(tr "\n" " " <"$work/config/orogen/settings" 2>&1)" $rc
grep -q '^tool_smooth = radius=33 .*falloff=tip' "$work/config/orogen/settings" &&
    grep -q '^tool = raise;' "$work/config/orogen/settings"
check "each tool's settings are written to the settings" $?
printf 'tool\ntool smooth; tool\nexit\n' | "$orogen" >"$work/rerun.out" 2>"$work/rerun.err"
grep -q '^radius=12$' "$work/rerun.out" && grep -q '^radius=33$' "$work/rerun.out" &&
    grep -q '^falloff=tip$' "$work/rerun.out"
rc=$?; check "the next run starts with each tool as it was left ($(grep -E '^(tool|radius|falloff)=' "$work/rerun.out" | tr '\n' ' '); $(head -c 200 "$work/rerun.err"))" $rc
# Seed 004's level-of-detail keys in the settings: enable_dynamic_LOD and the planet's
# split threshold (lod_pixels) are written, and read by the next run.
grep -q '^enable_dynamic_LOD = 1;$' "$work/config/orogen/settings" &&
    grep -q '^lod_pixels = 6;$' "$work/config/orogen/settings"
check "the level-of-detail keys are written with their defaults" $?
sed -i 's/^lod_pixels = .*/lod_pixels = 12;/; s/^enable_dynamic_LOD = .*/enable_dynamic_LOD = 0;/' \
    "$work/config/orogen/settings"
printf 'render\ndynamic_resolution\nexit\n' | "$orogen" >"$work/rerun2.out" 2>"$work/rerun2.err"
grep -q 'lod_pixels=12 ' "$work/rerun2.out" && grep -q '^dynamic_resolution off' "$work/rerun2.out"
rc=$?; check "enable_dynamic_LOD = 0 and lod_pixels = 12 are honoured ($(grep -E '^(render|dynamic)' "$work/rerun2.out" | tr '\n' ' '))" $rc
# Commands that arrive together: the screenshot after `new planet` shows the new world
# from its own camera (it showed the planet from the old world's camera, at its centre).
mkfifo "$work/batch-in"
"$orogen" <"$work/batch-in" >"$work/out" 2>"$work/batch.err" &
app=$!
exec 3>"$work/batch-in"
ask "camera" '^camera ' >/dev/null
# A script piping hundreds of commands at once loses none: the console reads no more
# while the work queue is nearly full (it held 256: 738 lines gave 256 answers).
before=$(wc -l <"$work/out")
for _ in $(seq 700); do echo "sample 10 10"; done >&3
for _ in $(seq 600); do
    answers=$(tail -n +$((before + 1)) "$work/out" | grep -c '^-\?[0-9]')
    [ "$answers" -ge 700 ] && break
    sleep 0.1
done
[ "$answers" = 700 ] && ! grep -q "too much work waiting" "$work/batch.err"
ok=$?; check "700 commands piped at once get 700 answers (got $answers; $(grep -m 1 dropped "$work/batch.err"))" $ok
line=$(ask "$(printf 'new planet preset=moon\nwindow_screenshot %s\nui_widgets Viewport' "$work/batch.png")" '^Viewport ')
echo "exit" >&3
exec 3>&-
wait $app
read -r _ vx vy vw vh <<<"$line"
centre=$(convert "$work/batch.png" -crop "40x40+$((vx + vw / 2 - 20))+$((vy + vh / 2 - 20))" +repage \
    -colorspace gray -format '%[fx:int(255*mean)]' info: 2>&1)
corner=$(convert "$work/batch.png" -crop "40x40+$((vx + 4))+$((vy + 4))" +repage \
    -colorspace gray -format '%[fx:int(255*mean)]' info: 2>&1)
[ -n "$vw" ] && [ "$centre" -gt 40 ] 2>/dev/null && [ "$corner" -lt 15 ] 2>/dev/null
rc=$?; check "a screenshot in the same batch as 'new planet' shows the globe in space (centre $centre, corner $corner; $(head -c 200 "$work/batch.err"))" $rc
cp "$work/session.og" "$work/replay.og"
echo "hash $(awk -v x="$px" -v z="$pz" 'BEGIN { print x - 150, z - 150, x + 150, z + 150 }')" >>"$work/replay.og"
"$orogen" --batch "$work/replay.og" >"$work/replay.out" 2>"$work/replay.err"
rc=$?
[ $rc = 0 ] && [ -n "$hf" ] && [ "$(tail -n 1 "$work/replay.out")" = "$hf" ]
rc2=$?; check "the recorded session replays to the same hash (status $rc, $hf vs $(tail -n 1 "$work/replay.out"))" $rc2
cp "$work/script.og" "$work/replay2.og"
echo "hash $(awk -v x="$px" -v z="$pz" 'BEGIN { print x - 150, z - 150, x + 150, z + 150 }')" >>"$work/replay2.og"
"$orogen" --batch "$work/replay2.og" >"$work/replay2.out" 2>"$work/replay2.err"
rc=$?
[ $rc = 0 ] && [ -n "$hf" ] && [ "$(tail -n 1 "$work/replay2.out")" = "$hf" ]
rc2=$?; check "the history script replays to the same hash (status $rc, $hf vs $(tail -n 1 "$work/replay2.out"); $(head -c 300 "$work/replay2.err"))" $rc2
[ $status = 0 ] && [ $failures = 0 ] || tail -n 30 "$work/err"

end_window_test
