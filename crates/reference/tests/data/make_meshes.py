#!/usr/bin/env python3
"""Writes the triangle-mesh fixtures of tests/mesh.rs: one small mesh (a
tent of 3 x 3 vertices, 8 triangles, coordinates exact in f32) as an OBJ of
triangles, an ASCII STL and a binary STL whose 80-byte header starts with
`solid` (as some exporters write it), and an OBJ of quads and triangles
mixed. Run it here: python3 make_meshes.py"""
import struct

Z = [[0.0, 0.25, 0.0], [0.25, 0.75, 0.25], [0.0, 0.25, 0.0]]
V = [(0.5 * i, 0.5 * j, Z[j][i]) for j in range(3) for i in range(3)]
T = []
for j in range(2):
    for i in range(2):
        a, b, c, d = 3 * j + i, 3 * j + i + 1, 3 * (j + 1) + i + 1, 3 * (j + 1) + i
        T += [(a, b, c), (a, c, d)]


def normal(t):
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = (V[k] for k in t)
    u, v = (bx - ax, by - ay, bz - az), (cx - ax, cy - ay, cz - az)
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    l = sum(x * x for x in n) ** 0.5
    return tuple(x / l for x in n)


with open("tent.obj", "w") as f:
    f.write("# a tent of 8 triangles (make_meshes.py)\no tent\n")
    for v in V:
        f.write("v %r %r %r\n" % v)
    for t in T:
        f.write("f %d %d %d\n" % tuple(k + 1 for k in t))

with open("tent-ascii.stl", "w") as f:
    f.write("solid tent\n")
    for t in T:
        f.write("  facet normal %r %r %r\n    outer loop\n" % normal(t))
        for k in t:
            f.write("      vertex %r %r %r\n" % V[k])
        f.write("    endloop\n  endfacet\n")
    f.write("endsolid tent\n")

with open("tent-binary.stl", "wb") as f:
    f.write(b"solid tent, binary all the same (make_meshes.py)".ljust(80, b" "))
    f.write(struct.pack("<I", len(T)))
    for t in T:
        f.write(struct.pack("<3f", *normal(t)))
        for k in t:
            f.write(struct.pack("<3f", *V[k]))
        f.write(struct.pack("<H", 0))

with open("mixed.obj", "w") as f:
    f.write("# the tent as 2 quads and 4 triangles (make_meshes.py)\n")
    for v in V:
        f.write("v %r %r %r\n" % v)
    f.write("f 1 2 5 4\nf 2 3 6 5\n")
    for t in T[4:]:
        f.write("f %d %d %d\n" % tuple(k + 1 for k in t))
