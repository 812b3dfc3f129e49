#!/usr/bin/env bash
# End-to-end from the reader's side: Blender (Debian's, headless) imports what Orogen
# exports, and what it finds must be what Orogen said it wrote: glb, OBJ and PLY of
# plain ground and of ground with a tunnel (vertex and face counts, bounds in metres
# on each axis after Blender's own axis conversion), and the .vdb level set with its
# fog (grid names and types; bounds within a leaf node of the region and the stated
# floor). Every mesh also passes tests/mesh_check.py (manifold, no degenerate faces).
# Usage: e2e_blender.sh OROGEN TESTS_DIR
set -u
orogen=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
tests=$(cd "$2" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-e2e-blender-XXXXXX")
trap '[ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
failures=0
passes=0
check() { # name, status
    if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi
}
command -v blender >/dev/null || { echo "FAIL: blender is missing (scripts/install-deps.sh)"; exit 1; }
cd "$work" || exit 1

cat >exports.txt <<'EOF'
new flat
set size 257
generate
export plain.glb
export plain.obj
export plain.ply
export part.obj region=100,40,300,500
new flat
seed 3
generate
tool carve radius=8
tunnel 100 -20 100 300 -20 300 radius=10
export tunnel.glb region=0,0,256,256
export tunnel.obj region=0,0,256,256
export tunnel.ply region=0,0,256,256
export tunnel.vdb region=0,0,256,256 fog=1
EOF
"$orogen" --batch exports.txt >out.txt 2>err.txt
rc=$?
check "exports run ($(head -c 300 err.txt))" $rc

# Blender's importers, one fresh scene per file; glTF and OBJ turn +Y up into +Z up.
cat >import.py <<'EOF'
import numpy
numpy.bool = bool  # Blender 3.4's glTF importer still uses numpy.bool (gone in numpy 1.24)
import bpy, mathutils, sys
for path in sys.argv[sys.argv.index('--') + 1:]:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    ext = path.rsplit('.', 1)[1]
    {'glb': lambda: bpy.ops.import_scene.gltf(filepath=path),
     'obj': lambda: bpy.ops.wm.obj_import(filepath=path),
     'ply': lambda: bpy.ops.import_mesh.ply(filepath=path),
     'vdb': lambda: bpy.ops.object.volume_import(filepath=path)}[ext]()
    for o in bpy.context.scene.objects:
        vs = [o.matrix_world @ mathutils.Vector(c) for c in o.bound_box]
        lo = [min(v[k] for v in vs) for k in range(3)]
        hi = [max(v[k] for v in vs) for k in range(3)]
        if o.type == 'MESH':
            what = '%d %d' % (len(o.data.vertices), len(o.data.polygons))
        elif o.type == 'VOLUME':
            o.data.grids.load()
            what = ','.join(sorted('%s:%s' % (g.name, g.data_type) for g in o.data.grids))
        else:
            continue
        print('BLENDER', path, o.type, what, *('%.3f' % v for v in lo + hi))
EOF
blender -b --python import.py -- plain.glb plain.obj plain.ply part.obj tunnel.glb tunnel.obj \
    tunnel.ply tunnel.vdb >blender.txt 2>&1
rc=$?
check "blender -b imports the files (exit $rc, $(grep -c '^BLENDER' blender.txt) objects)" $rc

for f in plain.glb plain.obj plain.ply part.obj tunnel.glb tunnel.obj tunnel.ply; do
    region=$(sed -n "s/^export $f region=\([-0-9.,]*\).*/\1/p" exports.txt)
    [ -n "$region" ] || region=0,0,512,512
    python3 - "$f" "$region" out.txt blender.txt >cmp.txt 2>&1 <<'EOF'
import re, sys
f, region, out, blender = sys.argv[1], [float(v) for v in sys.argv[2].split(',')], sys.argv[3], sys.argv[4]
line = next(l for l in open(out) if l.startswith('exported %s:' % f))
verts, tris = map(int, re.search(r'(\d+) vertices, (\d+) triangles', line).groups())
b = [float(v) for v in re.search(r'bounds ([^ ]+), ([^ ]+), ([^ ]+) \.\. ([^ ]+), ([^ ]+), ([^ ]+) m', line).groups()]
got = [l.split() for l in open(blender) if l.startswith('BLENDER %s MESH' % f)]
if len(got) != 1: sys.exit('%s: Blender made %d meshes' % (f, len(got)))
bv, bf = int(got[0][3]), int(got[0][4])
lo, hi = [float(v) for v in got[0][5:8]], [float(v) for v in got[0][8:11]]
if not f.endswith('.ply'):  # +Y up -> +Z up: Blender (x, -z, y)
    lo, hi = [lo[0], lo[2], -hi[1]], [hi[0], hi[2], -lo[1]]
want_lo, want_hi = [region[0], b[1], region[1]], [region[2], b[4], region[3]]
ok = bv == verts and bf == tris and all(abs(x - y) < 1e-3 for x, y in zip(lo + hi, want_lo + want_hi))
print('%s: Blender %d vertices, %d faces, X %.3f..%.3f, height %.3f..%.3f, Z %.3f..%.3f; Orogen %d, %d, '
      'region %s, height %.3f..%.3f' % (f, bv, bf, lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], verts, tris,
                                        sys.argv[2], b[1], b[4]))
sys.exit(0 if ok else 1)
EOF
    rc=$?
    check "$(cat cmp.txt)" $rc
    closed=""
    case $f in tunnel.*) closed="--closed-inside 0,0,256,256" ;; esac
    python3 "$tests/mesh_check.py" "$f" $closed >manifold.txt 2>&1
    rc=$?
    check "manifold: $(cat manifold.txt)" $rc
done

# The .vdb: both grids, and bounds that hold the region and the solid's floor to its top,
# no more than a leaf node (8 voxels) past them (Blender reports whole leaves).
python3 - out.txt blender.txt >vdb.txt 2>&1 <<'EOF'
import re, sys
line = next(l for l in open(sys.argv[1]) if l.startswith('exported tunnel.vdb:'))
floor = float(re.search(r'solid down to ([-0-9.e+]+) m', line).group(1))
top = 2 * int(re.search(r'index bounds [-0-9]+,[-0-9]+,[-0-9]+ \.\. [-0-9]+,([-0-9]+),', line).group(1))
got = [l.split() for l in open(sys.argv[2]) if l.startswith('BLENDER tunnel.vdb VOLUME')]
if len(got) != 1: sys.exit('Blender made %d volumes' % len(got))
grids = got[0][3]
lo, hi = [float(v) for v in got[0][4:7]], [float(v) for v in got[0][7:10]]
leaf = 16.0  # 8 voxels of 2 m
want_lo, want_hi = [0, floor, 0], [256, top, 256]
ok = grids == 'density:FLOAT,surface:FLOAT' and all(
    w - leaf <= l <= w for l, w in zip(lo, want_lo)) and all(w <= h <= w + leaf + 2 for h, w in zip(hi, want_hi))
print('tunnel.vdb: Blender grids %s, bounds %s .. %s (Y up as written); Orogen region 0..256, solid %g..%g m'
      % (grids, lo, hi, floor, top))
sys.exit(0 if ok else 1)
EOF
rc=$?
check "$(cat vdb.txt)" $rc

# A planet's OBJ links its face images through its .mtl: Blender finds all six.
"$orogen" -c "new planet; export 3 planet.obj size=400" >planet.txt 2>&1
rc=$?
check "planet export ($(head -c 200 planet.txt))" $rc
blender -b --python-expr "
import bpy
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.obj_import(filepath='planet.obj')
o = [x for x in bpy.context.scene.objects if x.type == 'MESH'][0]
print('IMAGES', ' '.join(sorted(n.image.name for m in o.data.materials for n in m.node_tree.nodes
                                if n.type == 'TEX_IMAGE' and n.image and n.image.size[0] == 391)))
" >planet_blender.txt 2>&1
images=$(sed -n 's/^IMAGES //p' planet_blender.txt)
[ "$images" = "planet_height_0.png planet_height_1.png planet_height_2.png planet_height_3.png planet_height_4.png planet_height_5.png" ]
check "Blender loads the planet's six face images through planet.mtl ($images)" $?

echo "e2e_blender: $passes passed, $failures failed"
[ $failures = 0 ]
