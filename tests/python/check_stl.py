"""Reads STL files back with OpenCascade's own reader (RWStl, binary and
ASCII, every solid of a file) for tests/stl_read_back.rs: prints one JSON line
per file, {"file", "triangles", "nodes": [[x, y, z], ...], "corners":
[[i, j, k], ...]} (the reader merges coincident vertices into nodes;
corners are 0-based node indices; each coordinate is the bits of its
double as an integer, so that no decimal parsing on the other side can
move it). Exit 1 when a file is not read.

Usage: check_stl.py FILE.stl [FILE.stl ...]
"""
import json
import struct
import sys

from OCP.Message import Message_ProgressRange
from OCP.RWStl import RWStl


def bits(x):
    return struct.unpack("<Q", struct.pack("<d", x))[0]


def main(paths):
    ok = True
    for path in paths:
        t = RWStl.ReadFile_s(path, Message_ProgressRange())
        if t is None or t.NbTriangles() == 0:
            print(json.dumps({"file": path, "error": "OpenCascade read no triangle"}))
            ok = False
            continue
        nodes = []
        for i in range(1, t.NbNodes() + 1):
            p = t.Node(i)
            nodes.append([bits(p.X()), bits(p.Y()), bits(p.Z())])
        corners = []
        for i in range(1, t.NbTriangles() + 1):
            a, b, c = t.Triangle(i).Get()
            corners.append([a - 1, b - 1, c - 1])
        print(json.dumps({"file": path, "triangles": t.NbTriangles(), "nodes": nodes, "corners": corners}))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
