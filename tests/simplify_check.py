#!/usr/bin/env python3
"""Checks a simplified heightfield mesh against the same region exported whole, from the
reader's side: the largest vertical deviation at every vertex of the whole mesh (the
border included, each found under the simplified triangle above it), the triangles
facing down or standing on edge (no area seen from above), and that it is no more than
the error the export reported.
Usage: simplify_check.py SIMPLIFIED WHOLE REPORTED_ERROR"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mesh_check  # noqa: E402

readers = {'obj': mesh_check.read_obj, 'ply': mesh_check.read_ply, 'glb': mesh_check.read_glb}
simple, whole, reported = sys.argv[1], sys.argv[2], float(sys.argv[3])
pos, faces = readers[simple.rsplit('.', 1)[1]](simple)
wpos, _ = readers[whole.rsplit('.', 1)[1]](whole)
xs = sorted(set(round(p[0], 3) for p in wpos))
zs = sorted(set(round(p[2], 3) for p in wpos))
step = (xs[-1] - xs[0]) / (len(xs) - 1)
grid = {(round((p[0] - xs[0]) / step), round((p[2] - zs[0]) / step)): p[1] for p in wpos}
down = edge_on = 0
worst, seen = 0.0, set()
for f in faces:
    q = [(round((pos[i][0] - xs[0]) / step), round((pos[i][2] - zs[0]) / step), pos[i][1]) for i in f]
    (u0, v0, y0), (u1, v1, y1), (u2, v2, y2) = q
    area = (u1 - u0) * (v2 - v0) - (u2 - u0) * (v1 - v0)  # negative: faces +Y
    if area == 0:
        edge_on += 1
        continue
    if area > 0:
        down += 1
        continue
    for v in range(min(v0, v1, v2), max(v0, v1, v2) + 1):
        for u in range(min(u0, u1, u2), max(u0, u1, u2) + 1):
            w1 = (u - u0) * (v2 - v0) - (u2 - u0) * (v - v0)
            w2 = (u1 - u0) * (v - v0) - (u - u0) * (v1 - v0)
            w0 = area - w1 - w2
            if w0 > 0 or w1 > 0 or w2 > 0:
                continue
            y = (w0 * y0 + w1 * y1 + w2 * y2) / area
            worst = max(worst, abs(y - grid[(u, v)]))
            seen.add((u, v))
missing = len(grid) - len(seen)
print('%s: %d triangles; vertical deviation %.3f m at most (reported %.3f); %d facing down, '
      '%d on edge, %d samples not covered' % (simple, len(faces), worst, reported, down, edge_on, missing))
sys.exit(0 if worst <= reported + 1e-3 and down == 0 and edge_on == 0 and missing == 0 else 1)
