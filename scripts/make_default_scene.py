#!/usr/bin/env python3
"""Writes data/default_scene.gltf: the bundled default scene (our own making).

It shows the papers' test situations: a jenga-like stack of blocks (the jenga
scene of Kenzel 2013), two crossed pipes in front of a wall (Bujnak 2004,
Fig. 9-11), an open ground plane, a point light
and a directional light (KHR_lights_punctual). One box mesh is instanced by
many nodes with translation/rotation/scale, so the importer's transforms are
exercised. Y is up, units are metres. Run: python3 scripts/make_default_scene.py
"""
import base64, json, math, struct, os

def box():
    p = [(x, y, z) for x in (-.5, .5) for y in (-.5, .5) for z in (-.5, .5)]
    # faces as quads, outward winding (counter-clockwise seen from outside)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    tris = []
    for a, b, c, d in quads:
        tris += [(a, b, c), (a, c, d)]
    return p, tris

def cylinder(n=32, r=0.25, h=1.0):
    """Closed cylinder along +X from -h/2 to h/2."""
    p = []
    for i in range(n):
        t = 2 * math.pi * i / n
        p += [(-h / 2, r * math.cos(t), r * math.sin(t)), (h / 2, r * math.cos(t), r * math.sin(t))]
    c0, c1 = len(p), len(p) + 1
    p += [(-h / 2, 0, 0), (h / 2, 0, 0)]
    tris = []
    for i in range(n):
        j = (i + 1) % n
        a, b, c, d = 2 * i, 2 * i + 1, 2 * j, 2 * j + 1
        tris += [(a, c, d), (a, d, b)]
        tris += [(c0, c, a), (c1, b, d)]
    return p, tris

def plane(s=10.0):
    return [(-s, 0, -s), (-s, 0, s), (s, 0, s), (s, 0, -s)], [(0, 1, 2), (0, 2, 3)]

def quat_axis(axis, deg):
    a = math.radians(deg) / 2
    return [axis[0] * math.sin(a), axis[1] * math.sin(a), axis[2] * math.sin(a), math.cos(a)]

def quat_from_to(u, v):
    """Rotation taking unit vector u to unit vector v, as [x, y, z, w]."""
    cx = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    w = 1 + sum(a * b for a, b in zip(u, v))
    q = [cx[0], cx[1], cx[2], w]
    n = math.sqrt(sum(c * c for c in q))
    return [c / n for c in q]

meshes = [("block", box()), ("pipe", cylinder()), ("ground", plane())]
buf = bytearray()
gltf = {"asset": {"version": "2.0", "generator": "geom scripts/make_default_scene.py"},
        "extensionsUsed": ["KHR_lights_punctual"], "buffers": [], "bufferViews": [], "accessors": [],
        "meshes": [], "nodes": [], "scenes": [{"name": "default", "nodes": []}], "scene": 0}
for name, (pos, tris) in meshes:
    pb = b"".join(struct.pack("<3f", *v) for v in pos)
    ib = b"".join(struct.pack("<3H", *t) for t in tris)
    for data, target in ((pb, 34962), (ib, 34963)):
        while len(buf) % 4:
            buf.append(0)
        gltf["bufferViews"].append({"buffer": 0, "byteOffset": len(buf), "byteLength": len(data), "target": target})
        buf += data
    lo = [min(v[i] for v in pos) for i in range(3)]
    hi = [max(v[i] for v in pos) for i in range(3)]
    bv = len(gltf["bufferViews"])
    gltf["accessors"].append({"bufferView": bv - 2, "componentType": 5126, "count": len(pos), "type": "VEC3", "min": lo, "max": hi})
    gltf["accessors"].append({"bufferView": bv - 1, "componentType": 5123, "count": 3 * len(tris), "type": "SCALAR"})
    gltf["meshes"].append({"name": name, "primitives": [{"attributes": {"POSITION": len(gltf["accessors"]) - 2},
                                                          "indices": len(gltf["accessors"]) - 1}]})
gltf["buffers"].append({"byteLength": len(buf), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()})

def node(**kw):
    gltf["nodes"].append(kw)
    return len(gltf["nodes"]) - 1

roots = gltf["scenes"][0]["nodes"]
roots.append(node(name="ground", mesh=2))
# Jenga: 8 layers of 3 blocks (1.5 x 0.3 x 0.5), alternating direction, under one parent node.
blocks = []
for layer in range(8):
    for k in range(3):
        off = (k - 1) * 0.5
        y = 0.15 + 0.3 * layer
        # even layers: long axis along X, side by side in Z; odd layers turned 90 degrees
        t = [0, y, off] if layer % 2 == 0 else [off, y, 0]
        rot = quat_axis((0, 1, 0), 0 if layer % 2 == 0 else 90)
        blocks.append(node(name=f"block{layer}_{k}", mesh=0, translation=t, rotation=rot, scale=[1.5, 0.3, 0.48]))
roots.append(node(name="jenga", translation=[-3.0, 0, 0], rotation=quat_axis((0, 1, 0), 20), children=blocks))
# Two crossed pipes in front of a wall (wall given as a matrix transform).
p1 = node(name="pipe_a", mesh=1, rotation=quat_axis((0, 0, 1), 35), scale=[4.0, 1, 1])
p2 = node(name="pipe_b", mesh=1, rotation=quat_axis((0, 0, 1), -35), scale=[4.0, 1, 1], translation=[0, 0, 0.6])
roots.append(node(name="pipes", translation=[3.0, 1.6, 0.0], children=[p1, p2]))
roots.append(node(name="wall", mesh=0, matrix=[6, 0, 0, 0, 0, 3.5, 0, 0, 0, 0, 0.2, 0, 3.0, 1.75, -1.2, 1]))
# Lights: a point light, and a directional light travelling along d.
d = (-0.35, -1.0, -0.45)
n = math.sqrt(sum(c * c for c in d))
d = tuple(c / n for c in d)
gltf["extensions"] = {"KHR_lights_punctual": {"lights": [
    {"name": "point", "type": "point", "color": [1, 0.95, 0.85], "intensity": 60},
    {"name": "sun", "type": "directional", "color": [1, 1, 1], "intensity": 3}]}}
roots.append(node(name="point_light", translation=[1.0, 5.5, 4.0], extensions={"KHR_lights_punctual": {"light": 0}}))
roots.append(node(name="sun", rotation=quat_from_to((0, 0, -1), d), extensions={"KHR_lights_punctual": {"light": 1}}))

out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "default_scene.gltf")
with open(out, "w") as f:
    json.dump(gltf, f, indent=1)
print(out, sum(len(t) for _, (p, t) in meshes), "triangles per mesh set,", len(gltf["nodes"]), "nodes")
