#!/usr/bin/env bash
# End-to-end: seed 004's planet commands through the real orogen binary: `export N
# FILE` (the cube's N-th subdivision as an OBJ with six height and six normal images),
# read back by tools nobody here wrote (assimp, OpenImageIO's iinfo) and checked for
# watertightness by walking its edges.
# Usage: e2e_planet.sh OROGEN TESTS_DIR
set -u
orogen=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
tests=$(cd "$2" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-e2e-planet-XXXXXX")
trap '[ -n "${KEEP:-}" ] || { umount "$work/full" 2>/dev/null; rm -rf "$work"; }' EXIT
failures=0
passes=0

check() { # name, status
    if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi
}
run() {
    "$orogen" "$@" >"$work/out" 2>"$work/err"
    status=$?
}
for tool in assimp iinfo python3; do
    command -v "$tool" >/dev/null || { echo "FAIL: $tool is missing (scripts/install-deps.sh)"; exit 1; }
done
seed004="$tests/data/params/seed004.planet"

# Watertight and consistently wound: every edge joins exactly two triangles, once in
# each direction; V - E + F = 2 (a sphere); the enclosed volume is positive (outward
# normals) and near the sphere's. Prints "ok" or what is wrong.
watertight() { # obj radius
    python3 - "$1" "$2" <<'EOF'
import math, sys
v, faces = [], []
for line in open(sys.argv[1]):
    p = line.split()
    if not p: continue
    if p[0] == 'v': v.append(tuple(map(float, p[1:4])))
    elif p[0] == 'f': faces.append([int(c.split('/')[0]) - 1 for c in p[1:]])
directed, undirected = {}, {}
for f in faces:
    for k in range(3):
        a, b = f[k], f[(k + 1) % 3]
        directed[(a, b)] = directed.get((a, b), 0) + 1
        e = (min(a, b), max(a, b))
        undirected[e] = undirected.get(e, 0) + 1
bad = [e for e, n in undirected.items() if n != 2]
twice = [e for e, n in directed.items() if n != 1]
used = {i for f in faces for i in f}
vol = sum(
    (v[a][0] * (v[b][1] * v[c][2] - v[b][2] * v[c][1]) - v[a][1] * (v[b][0] * v[c][2] - v[b][2] * v[c][0])
     + v[a][2] * (v[b][0] * v[c][1] - v[b][1] * v[c][0])) / 6 for a, b, c in faces)
r = float(sys.argv[2])
euler = len(v) - len(undirected) + len(faces)
if bad: print('edges not shared by two faces:', len(bad))
elif twice: print('edges wound the same way twice:', len(twice))
elif len(used) != len(v): print('unused vertices:', len(v) - len(used))
elif euler != 2: print('Euler characteristic', euler)
elif not (0 < vol < 4 / 3 * math.pi * r ** 3 * 1.01): print('volume', vol)
else: print('ok')
EOF
}

cd "$work" || exit 1

# 1. Seed 004's planet, even and odd subdivisions: ROAM's 12 x 2^N triangles and
#    6 x 2^N + 2 vertices, every one shared where faces meet.
for n in 0 5 6; do
    run -c "load $seed004; export $n $work/p$n.obj size=64"
    check "export $n exits 0 ($(cat "$work/err"))" $status
    t=$((12 << n)); nv=$(((6 << n) + 2))
    grep -q "subdivision $n of the cube, $nv vertices, $t triangles (watertight)" "$work/out"
    check "export $n reports $nv vertices and $t triangles" $?
    [ "$(grep -c '^v ' "$work/p$n.obj")" = "$nv" ] && [ "$(grep -c '^f ' "$work/p$n.obj")" = "$t" ]
    check "the OBJ of subdivision $n holds $nv vertices and $t faces" $?
    [ "$(grep -c '^vn ' "$work/p$n.obj")" = "$nv" ]; check "one normal per vertex ($n)" $?
    result=$(watertight "$work/p$n.obj" 10.5)
    [ "$result" = ok ]; check "subdivision $n is watertight and wound outward: $result" $?
done
# assimp: six meshes (one per face); its importer splits the vertices on face edges
# (each face has its own texture coordinates): (2^(N/2) + 1)^2 (+ 4^((N-1)/2) centres
# for odd N) per face.
assimp info "$work/p6.obj" >"$work/assimp6" 2>&1
grep -q '^Faces: *768$' "$work/assimp6" && grep -q '^Vertices: *486$' "$work/assimp6" &&
    grep -q '^Meshes: *6$' "$work/assimp6"
check "assimp reads subdivision 6: 768 faces, 486 vertices in 6 meshes" $?
assimp info "$work/p5.obj" >"$work/assimp5" 2>&1
grep -q '^Faces: *384$' "$work/assimp5" && grep -q '^Vertices: *246$' "$work/assimp5"
check "assimp reads subdivision 5: 384 faces, 246 vertices" $?

# The face images: 16-bit grey heights with a sidecar, 8-bit RGB normals; 64 pixels
# (the 256-sample faces at mip level 2).
ok=0
for f in 0 1 2 3 4 5; do
    iinfo "$work/p6_height_$f.png" | grep -q "64 x   64, 1 channel, uint16 png" || ok=1
    iinfo "$work/p6_normal_$f.png" | grep -q "64 x   64, 3 channel, uint8 png" || ok=1
    grep -q "\"face\": $f," "$work/p6_height_$f.png.json" || ok=1
done
check "six 16-bit height images with sidecars and six 8-bit normal maps" $ok
grep -q '"radius": 10,' "$work/p6_height_2.png.json" && grep -q '"level": 2,' "$work/p6_height_2.png.json"
check "the sidecar gives the radius and the face grid level" $?
# The sidecar's mapping gives metres: the extremes within the planet's max_height.
python3 - "$work/p6_height_0.png.json" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
lo = s['height_offset']; hi = lo + 65535 * s['height_scale']
sys.exit(0 if -0.5 <= lo < hi <= 0.5 and abs(lo - s['min_height']) < 1e-9 else 1)
EOF
check "the height sidecar maps 0..65535 onto the heights in metres" $?
[ -z "$(ls -A "$work" | grep '\.part-')" ]; check "no staging files left behind" $?

# 2. An Earth-sized planet: the images come from the coarsest mip that fits size=, and
#    every vertex lies within max_height of the radius.
run -c "new planet; export 4 $work/earth.obj size=400"
check "Earth-sized export exits 0 ($(cat "$work/err"))" $status
grep -q "images of 391 x 391 pixels (face grid level 8)" "$work/out"; check "Earth: 391-pixel faces from level 8" $?
python3 - "$work/earth.obj" <<'EOF'
import math, sys
r = [math.sqrt(sum(float(c) ** 2 for c in l.split()[1:4])) for l in open(sys.argv[1]) if l.startswith('v ')]
sys.exit(0 if len(r) == 98 and all(abs(x - 6371000) <= 8848 for x in r) else 1)
EOF
check "Earth's vertices lie within max_height of the radius" $?
result=$(watertight "$work/earth.obj" 6380000)
[ "$result" = ok ]; check "Earth's mesh is watertight: $result" $?

# 3. Refusals with the reason, and nothing written.
run -c "export 3 $work/flat.obj"
[ $status = 1 ] && grep -q "planets only" "$work/err" && [ ! -e "$work/flat.obj" ]
check "export N FILE on a flat world is refused" $?
run -c "new planet; export 21 $work/big.obj"
[ $status = 1 ] && grep -q "0 .. 20, got '21'" "$work/err"; check "N over 20 is refused" $?
run -c "new planet; export 3 $work/p.png"
[ $status = 1 ] && grep -q "writes an .obj" "$work/err"; check "a non-OBJ name is refused" $?
run -c "new planet; export 3 $work/p.obj size=0"
[ $status = 1 ] && grep -q "size: face image pixels per side, 1 .. 8192" "$work/err"
check "size=0 is refused" $?
run -c "new planet; export 3 $work/p.obj size=100"
[ $status = 1 ] && grep -q "size=391 or more" "$work/err"; check "a size below the coarsest mip names the smallest" $?
run -c "load $seed004; export 3 $work/p.obj colour=red"
[ $status = 1 ] && grep -q "unknown option 'colour'" "$work/err"; check "an unknown option is refused" $?
run -c "load $seed004; export 3 $work/no/such/dir/p.obj"
[ $status = 1 ] && grep -q "$work/no/such/dir" "$work/err"; check "an unwritable folder is named" $?

# 4. A full disk part way: the old files stay as they were and no staging file is left.
mkdir -p "$work/full"
if mount -t tmpfs -o size=200k tmpfs "$work/full" 2>/dev/null; then
    echo old >"$work/full/p.obj"
    run -c "load $seed004; export 6 $work/full/p.obj size=256"
    [ $status = 1 ] && grep -q "$work/full" "$work/err"; rc=$?; check "a full disk is reported ($(cat "$work/err"))" $rc
    [ "$(cat "$work/full/p.obj")" = old ] && [ -z "$(ls -A "$work/full" | grep -v '^p.obj$')" ]
    check "after a failed export only the old file is there" $?
    umount "$work/full"
else
    echo "note: cannot mount a tmpfs here; the full-disk case was skipped"
fi

echo "$passes passed, $failures failed"
[ "$failures" = 0 ]
