# Run inside Blender: blender -b --python blender_surface_check.py -- FILE:X0,Z0,X1,Z1[:WHOLE] ...
# Imports each simplified FILE with Blender's own importers and checks it from the
# reader's side: bmesh's edges (none in more than two faces, none whose two faces
# disagree in winding, open edges only on the region's sides X0..X1, Z0..Z1), no loose
# vertices, no face of no area; with WHOLE (the same region exported unsimplified), the
# distance both ways with Blender's BVH trees: from every vertex of WHOLE to FILE's
# surface, from points 1 m apart on every face of FILE to WHOLE's surface. Prints one
# line per FILE:
#   SURFACE FILE vertices V faces F crowded C unwound U open_inside O loose L degenerate D
#           [distance M]
import numpy

numpy.bool = bool  # Blender 3.4's glTF importer still uses numpy.bool (gone in numpy 1.24)
import bmesh  # noqa: E402
import bpy  # noqa: E402
import sys  # noqa: E402
from mathutils import Vector  # noqa: E402
from mathutils.bvhtree import BVHTree  # noqa: E402


def load(path):
    """The file's mesh in its own axes (metres, +Y up) as a bmesh."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    ext = path.rsplit('.', 1)[1]
    {'glb': lambda: bpy.ops.import_scene.gltf(filepath=path),
     'obj': lambda: bpy.ops.wm.obj_import(filepath=path),
     'ply': lambda: bpy.ops.import_mesh.ply(filepath=path)}[ext]()
    objects = [o for o in bpy.context.scene.objects if o.type == 'MESH']
    if len(objects) != 1:
        sys.exit('%s: Blender made %d meshes' % (path, len(objects)))
    o = objects[0]
    bm = bmesh.new()
    bm.from_mesh(o.data)
    for v in bm.verts:
        p = o.matrix_world @ v.co
        # glTF and OBJ come in Z up (x, -z, y); PLY as written.
        v.co = p if ext == 'ply' else Vector((p[0], p[2], -p[1]))
    bm.faces.ensure_lookup_table()
    return bm


def samples(face, step):
    a, b, c = (v.co for v in face.verts)
    n = max(1, int(max((b - a).length, (c - b).length, (a - c).length) / step) + 1)
    for i in range(n + 1):
        for j in range(n + 1 - i):
            yield a + (b - a) * (i / n) + (c - a) * (j / n)


for spec in sys.argv[sys.argv.index('--') + 1:]:
    path, region, whole_path = (spec.split(':') + [''])[:3]
    x0, z0, x1, z1 = (float(v) for v in region.split(','))
    distance = ''
    if whole_path:
        whole = load(whole_path)
        whole_tree = BVHTree.FromBMesh(whole)
    bm = load(path)

    def side(v):
        return min(abs(v.co.x - x0), abs(v.co.x - x1), abs(v.co.z - z0), abs(v.co.z - z1)) < 1e-3

    crowded = sum(1 for e in bm.edges if len(e.link_faces) > 2)
    unwound = sum(1 for e in bm.edges if len(e.link_faces) == 2 and not e.is_contiguous)
    open_inside = sum(1 for e in bm.edges
                      if len(e.link_faces) == 1 and not (side(e.verts[0]) and side(e.verts[1])))
    loose = sum(1 for v in bm.verts if not v.link_faces)
    degenerate = sum(1 for f in bm.faces if f.calc_area() < 1e-9)
    if whole_path:
        tree = BVHTree.FromBMesh(bm)
        worst = 0.0
        for v in whole.verts:
            hit = tree.find_nearest(v.co)
            worst = max(worst, (hit[0] - v.co).length)
        for f in bm.faces:
            for p in samples(f, 1.0):
                hit = whole_tree.find_nearest(p)
                worst = max(worst, (hit[0] - p).length)
        distance = ' distance %.4f' % worst
        whole.free()
    print('SURFACE %s vertices %d faces %d crowded %d unwound %d open_inside %d loose %d '
          'degenerate %d%s' % (path, len(bm.verts), len(bm.faces), crowded, unwound, open_inside,
                               loose, degenerate, distance))
    bm.free()
