#!/usr/bin/env python3
"""Checks an exported mesh (.obj .ply .glb) from the reader's side: every edge in at most
two faces, each direction of an edge at most once (consistent winding), no degenerate
face (repeated vertex or zero area), no two faces on the same vertices, no vertex that no face uses. Prints one line with
the counts and the bounds; exits 1 if any check fails.
Usage: mesh_check.py FILE [--closed-inside X0,Z0,X1,Z1 | --closed]
  --closed-inside: also every edge not on the region's sides has exactly two faces;
  --closed: every edge has exactly two faces (a solid)."""
import json
import struct
import sys
from collections import Counter


def read_obj(path):
    pos, faces = [], []
    for line in open(path):
        if line.startswith('v '):
            pos.append(tuple(float(t) for t in line.split()[1:4]))
        elif line.startswith('f '):
            ids = [int(t.split('/')[0]) for t in line.split()[1:]]
            faces.append([i - 1 if i > 0 else len(pos) + i for i in ids])
    return pos, faces


def read_ply(path):
    data = open(path, 'rb').read()
    end = data.index(b'end_header\n') + len(b'end_header\n')
    header = data[:end].decode().splitlines()
    if 'format binary_little_endian 1.0' not in header:
        sys.exit('%s: not a binary little-endian PLY' % path)
    sizes = {'float': 'f', 'float32': 'f', 'uchar': 'B', 'uint8': 'B', 'int': 'i', 'uint': 'I',
             'int32': 'i', 'uint32': 'I', 'ushort': 'H', 'short': 'h', 'double': 'd'}
    elements, current = [], None
    for line in header:
        t = line.split()
        if t[0] == 'element':
            current = [t[1], int(t[2]), []]
            elements.append(current)
        elif t[0] == 'property':
            current[2].append(t[1:])
    off, pos, faces = end, [], []
    for name, count, props in elements:
        for _ in range(count):
            values = []
            for p in props:
                if p[0] == 'list':
                    n = struct.unpack_from('<' + sizes[p[1]], data, off)[0]
                    off += struct.calcsize(sizes[p[1]])
                    fmt = '<%d%s' % (n, sizes[p[2]])
                    values.append(list(struct.unpack_from(fmt, data, off)))
                    off += struct.calcsize(fmt)
                else:
                    values.append(struct.unpack_from('<' + sizes[p[0]], data, off)[0])
                    off += struct.calcsize(sizes[p[0]])
            if name == 'vertex':
                pos.append(tuple(values[:3]))
            elif name == 'face':
                faces.append(values[0])
    return pos, faces


def read_glb(path):
    data = open(path, 'rb').read()
    jlen = struct.unpack_from('<I', data, 12)[0]
    doc = json.loads(data[20:20 + jlen])
    binary = data[20 + jlen + 8:]
    pos, faces = [], []

    def accessor(i):
        a = doc['accessors'][i]
        v = doc['bufferViews'][a['bufferView']]
        comps = {'SCALAR': 1, 'VEC2': 2, 'VEC3': 3, 'VEC4': 4}[a['type']]
        fmt = {5126: 'f', 5125: 'I', 5123: 'H', 5121: 'B'}[a['componentType']]
        start = v.get('byteOffset', 0) + a.get('byteOffset', 0)
        flat = struct.unpack_from('<%d%s' % (a['count'] * comps, fmt), binary, start)
        return [flat[k:k + comps] for k in range(0, len(flat), comps)] if comps > 1 else list(flat)

    for mesh in doc['meshes']:
        for prim in mesh['primitives']:
            base = len(pos)
            pos += [tuple(p) for p in accessor(prim['attributes']['POSITION'])]
            idx = accessor(prim['indices'])
            faces += [[base + idx[k], base + idx[k + 1], base + idx[k + 2]]
                      for k in range(0, len(idx), 3)]
    return pos, faces


def main():
    path = sys.argv[1]
    region = None
    if len(sys.argv) > 3 and sys.argv[2] == '--closed-inside':
        region = [float(v) for v in sys.argv[3].split(',')]
    elif len(sys.argv) > 2 and sys.argv[2] == '--closed':
        region = [float('inf')] * 4  # no edge lies on a side
    reader = {'obj': read_obj, 'ply': read_ply, 'glb': read_glb}[path.rsplit('.', 1)[-1].lower()]
    pos, faces = reader(path)
    directed, undirected, used = Counter(), Counter(), set()
    degenerate = 0
    twins = sum(n - 1 for n in Counter(tuple(sorted(f)) for f in faces).values())
    for f in faces:
        used.update(f)
        if len(set(f)) != len(f):
            degenerate += 1
            continue
        a, b, c = (pos[i] for i in f[:3])
        u = [b[k] - a[k] for k in range(3)]
        v = [c[k] - a[k] for k in range(3)]
        cross = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        if len(f) == 3 and sum(x * x for x in cross) == 0:
            degenerate += 1
        for i, j in zip(f, f[1:] + f[:1]):
            directed[(i, j)] += 1
            undirected[(min(i, j), max(i, j))] += 1
    crowded = sum(1 for n in undirected.values() if n > 2)
    flipped = sum(1 for n in directed.values() if n > 1)
    unused = len(pos) - len(used)
    open_inside = 0
    if region:
        def side(p):
            return min(abs(p[0] - region[0]), abs(p[0] - region[2]), abs(p[2] - region[1]),
                       abs(p[2] - region[3])) < 1e-3
        open_inside = sum(1 for (i, j), n in undirected.items()
                          if n == 1 and not (side(pos[i]) and side(pos[j])))
    lo = [min(p[k] for p in pos) for k in range(3)] if pos else [0, 0, 0]
    hi = [max(p[k] for p in pos) for k in range(3)] if pos else [0, 0, 0]
    print('%s: %d vertices, %d faces; edges in >2 faces %d, repeated directed edges %d, '
          'degenerate faces %d, twin faces %d, unused vertices %d%s; bounds %.3f,%.3f,%.3f .. %.3f,%.3f,%.3f' %
          (path, len(pos), len(faces), crowded, flipped, degenerate, twins, unused,
           ', open edges inside the region %d' % open_inside if region else '', *lo, *hi))
    sys.exit(1 if crowded or flipped or degenerate or twins or unused or open_inside or not faces else 0)


if __name__ == '__main__':
    main()
