"""Measures a fitted design against the face it was fitted to, with
OpenCascade (tests/reference_cli.rs, docs/fit.md): reads the STEP or IGES
file in metres, takes its face N, and projects every point of the design's
mesh on that face's surface (GeomAPI_ProjectPointOnSurf) and on its four
border curves (GeomAPI_ProjectPointOnCurve, for points whose closest point
is on the border), the smallest of these and of the corners' distances
being the distance to the face; prints one JSON line with the largest and
mean distance and every point's.

Usage: check_fit.py FILE FACE POINTS.xyz  (POINTS: one "x y z" per line, in
metres).
"""
import json
import math
import sys

from OCP.BRep import BRep_Tool
from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve, GeomAPI_ProjectPointOnSurf
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader
from OCP.Interface import Interface_Static
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Pnt


def faces(path):
    step = path.lower().endswith((".step", ".stp"))
    reader = STEPControl_Reader() if step else IGESControl_Reader()
    assert Interface_Static.SetCVal_s("xstep.cascade.unit", "M"), "cannot set xstep.cascade.unit"
    if reader.ReadFile(path) != IFSelect_RetDone:
        raise SystemExit(f"{path}: OpenCascade could not read the file")
    reader.TransferRoots()
    shape = reader.OneShape()
    out = []
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        out.append(TopoDS.Face(ex.Current()))
        ex.Next()
    return out


def main():
    path, index, points = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    surface = BRep_Tool.Surface_s(faces(path)[index])
    u0, u1, v0, v1 = surface.Bounds()
    # the face's border: its four iso-curves and corners, for points whose
    # closest point is on it (no orthogonal projection inside reaches it)
    borders = [surface.UIso(u0), surface.UIso(u1), surface.VIso(v0), surface.VIso(v1)]
    corners = [surface.Value(u, v) for u in (u0, u1) for v in (v0, v1)]
    dists = []
    with open(points) as f:
        for line in f:
            x, y, z = (float(c) for c in line.split())
            p = gp_Pnt(x, y, z)
            best = min(p.Distance(c) for c in corners)
            proj = GeomAPI_ProjectPointOnSurf(p, surface, u0, u1, v0, v1)
            if proj.NbPoints() > 0:
                best = min(best, proj.LowerDistance())
            for curve in borders:
                on = GeomAPI_ProjectPointOnCurve(p, curve)
                if on.NbPoints() > 0:
                    best = min(best, on.LowerDistance())
            dists.append(best)
    print(json.dumps({
        "file": path,
        "face": index,
        "points": len(dists),
        "max": max(dists),
        "mean": math.fsum(dists) / len(dists),
        "distances": dists,
    }))


if __name__ == "__main__":
    main()
