#!/usr/bin/env python3
"""Writes a tiny Quake 3 map (IBSP 46), the seed of fuzz_bsp: a polygon face
(the unit square, two triangles through mesh vertices), a 3x3 Bezier patch, a
billboard, and a second model holding one mesh face; the lumps the importer
does not read are empty. Same layout as tests/test_quake3.cpp's tiny map."""
import struct
import sys

vertices = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
vertices += [(x, y, 1) for y in range(3) for x in range(3)]
vertices += [(5, 0, 0), (5, 1, 0), (6, 0, 0)]
meshverts = [0, 2, 1, 0, 3, 2, 0, 1, 2]
# texture, type, vertex, n_vertexes, meshvert, n_meshverts, width, height
faces = [(0, 1, 0, 4, 0, 6, 0, 0), (0, 2, 4, 9, 0, 0, 3, 3), (0, 4, 0, 4, 0, 0, 0, 0), (0, 3, 13, 3, 6, 3, 0, 0)]
models = [(0, 3), (3, 1)]

lumps = [b""] * 17
lumps[1] = b"textures/tiny".ljust(64, b"\0") + struct.pack("<ii", 0, 1)
lumps[7] = b"".join(b"\0" * 24 + struct.pack("<iiii", f, n, 0, 0) for f, n in models)
lumps[10] = b"".join(struct.pack("<3f", *v) + b"\0" * 32 for v in vertices)
lumps[11] = struct.pack("<%di" % len(meshverts), *meshverts)
lumps[13] = b"".join(
    struct.pack("<8i", t, -1, ty, v, nv, m, nm, -1) + b"\0" * 64 + struct.pack("<2i", w, h)
    for t, ty, v, nv, m, nm, w, h in faces)
header, body, offset = b"IBSP" + struct.pack("<i", 46), b"", 8 + 17 * 8
for lump in lumps:
    header += struct.pack("<ii", offset + len(body), len(lump))
    body += lump
open(sys.argv[1], "wb").write(header + body)
