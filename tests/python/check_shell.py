"""Reads STEP shells of several patches back with OpenCascade (OCP) for
tests/cad_shell.rs (docs/cad.md, "Several patches"): the number of shells and
faces, BRepCheck_Analyzer's verdict, the free edges (edges used by one face
only, counted over OpenCascade's faces and their edges, `IsSame`), every face's largest
distance to its patch's points (GeomAPI_ProjectPointOnSurf), and across every
edge shared by two faces the largest angle between the faces' normals
(GeomLProp_SLProps, each face's orientation applied) at `samples` points
along the edge, each point projected onto both faces.

An IGES file (.igs/.iges, tests/cad_document.rs) is read with the IGES
reader: no shell, every entity 128 a face of its own. Each shared edge names
its two faces (their indices in the file's order).

Every distance is from a point to a point of the face as read, so none is
below the true distance: the tree algorithm's, the global one's for a point
over the tolerance, and where both stay over it and the points file gives
the point's parameters on the face (`x y z u v`), the nearest point found
from those (ShapeAnalysis_Surface), the least of them.

Usage: check_shell.py MANIFEST.json, entries {"file", "tolerance" (the smallest face's), "points": [one file of
"x y z" or "x y z u v" lines per face, in the faces' order], "samples"}. Prints one JSON
line per file; exit 1 when a file is not read.
"""
import json
import math
import sys

from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.Extrema import Extrema_ExtAlgo_Tree
from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
from OCP.GeomLProp import GeomLProp_SLProps
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader
from OCP.ShapeAnalysis import ShapeAnalysis_Surface
from OCP.Interface import Interface_Static
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_REVERSED, TopAbs_SHELL
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Pnt, gp_Pnt2d


def read(path):
    is_iges = path.lower().endswith((".igs", ".iges"))
    reader = IGESControl_Reader() if is_iges else STEPControl_Reader()
    assert Interface_Static.SetCVal_s("xstep.cascade.unit", "M"), "cannot set xstep.cascade.unit"
    if reader.ReadFile(path) != IFSelect_RetDone:
        raise AssertionError(f"{path}: OpenCascade could not read the file")
    reader.TransferRoots()
    return reader.OneShape()


def explore(shape, kind):
    out = []
    ex = TopExp_Explorer(shape, kind)
    while ex.More():
        out.append(ex.Current())
        ex.Next()
    return out


def points(path):
    with open(path) as f:
        return [tuple(float(x) for x in line.split()) for line in f if line.strip()]


def normal(face, surf, p):
    proj = GeomAPI_ProjectPointOnSurf(p, surf)
    if proj.NbPoints() == 0 or proj.LowerDistance() > 1e-9:
        # the default extrema can settle on a far local minimum of a curved
        # face (a side seam's point read 0.015 m off a face it lies on):
        # the tree algorithm, whichever is nearer
        tree = GeomAPI_ProjectPointOnSurf()
        u0, u1, v0, v1 = surf.Bounds()
        tree.Init(surf, u0, u1, v0, v1, Extrema_ExtAlgo_Tree)
        tree.Perform(p)
        if tree.NbPoints() > 0 and (proj.NbPoints() == 0 or tree.LowerDistance() < proj.LowerDistance()):
            proj = tree
    u, v = proj.LowerDistanceParameters()
    props = GeomLProp_SLProps(surf, u, v, 1, 1e-12)
    assert props.IsNormalDefined(), "no normal at a seam point"
    n = props.Normal()
    s = -1.0 if face.Orientation() == TopAbs_REVERSED else 1.0
    return (s * n.X(), s * n.Y(), s * n.Z()), proj.LowerDistance()


def check(entry):
    path = entry["file"]
    shape = read(path)
    shells = explore(shape, TopAbs_SHELL)
    fs = [TopoDS.Face(f) for f in explore(shape, TopAbs_FACE)]
    valid = BRepCheck_Analyzer(shape).IsValid()
    # every edge with the faces that use it (IsSame: the same TShape and location)
    edges = []
    for face in fs:
        for e in explore(face, TopAbs_EDGE):
            for rec in edges:
                if rec[0].IsSame(e):
                    if not any(f.IsSame(face) for f in rec[1]):
                        rec[1].append(face)
                    break
            else:
                edges.append((TopoDS.Edge(e), [face]))
    free = sum(1 for _, owners in edges if len(owners) == 1)
    shared = [(e, owners) for e, owners in edges if len(owners) == 2]
    deviation = []
    for face, pts_file in zip(fs, entry["points"]):
        surf = BRep_Tool.Surface_s(face)
        u0, u1, v0, v1 = surf.Bounds()
        # the tree algorithm first (never below the true distance), the
        # global one for a point over the tolerance (as check_cad.py)
        fast = GeomAPI_ProjectPointOnSurf()
        fast.Init(surf, u0, u1, v0, v1, Extrema_ExtAlgo_Tree)
        full = GeomAPI_ProjectPointOnSurf()
        full.Init(surf, u0, u1, v0, v1)
        near = ShapeAnalysis_Surface(surf)
        d_max = 0.0
        for q in points(pts_file):
            p = gp_Pnt(*q[:3])
            fast.Perform(p)
            d = fast.LowerDistance() if fast.NbPoints() > 0 else float("inf")
            if d > entry["tolerance"]:
                full.Perform(p)
                if full.NbPoints() > 0:
                    d = min(d, full.LowerDistance())
            if d > entry["tolerance"] and len(q) == 5:
                # both can settle on a local minimum where the face comes
                # back close to itself (a rough random face 2 cm across read
                # 3.9e-6 at a point 6.5e-8 from it): the nearest point found
                # from the point's own parameters, when the file gives them
                uv = near.NextValueOfUV(gp_Pnt2d(q[3], q[4]), p, 1e-12, -1.0)
                d = min(d, p.Distance(surf.Value(uv.X(), uv.Y())))
            d_max = max(d_max, d)
        deviation.append(d_max)
    seams = []
    n = entry.get("samples", 40)
    for edge, (fa, fb) in shared:
        curve = BRepAdaptor_Curve(edge)
        t0, t1 = curve.FirstParameter(), curve.LastParameter()
        sa, sb = BRep_Tool.Surface_s(fa), BRep_Tool.Surface_s(fb)
        worst, gap = 0.0, 0.0
        for k in range(n):
            t = t0 + (t1 - t0) * (k + 0.5) / n
            p = curve.Value(t)
            na, da = normal(fa, sa, p)
            nb, db = normal(fb, sb, p)
            dot = max(-1.0, min(1.0, sum(x * y for x, y in zip(na, nb))))
            worst = max(worst, math.degrees(math.acos(dot)))
            gap = max(gap, da, db)
        index = [next(i for i, f in enumerate(fs) if f.IsSame(x)) for x in (fa, fb)]
        seams.append({"max_angle_deg": worst, "max_gap": gap, "samples": n, "faces": sorted(index)})
    return {
        "file": path,
        "shells": len(shells),
        "faces": len(fs),
        "valid": valid,
        "free_edges": free,
        "shared_edges": len(shared),
        "deviation": deviation,
        "seams": seams,
    }


def main():
    with open(sys.argv[1]) as f:
        manifest = json.load(f)
    failed = False
    for entry in manifest:
        try:
            print(json.dumps(check(entry)), flush=True)
        except AssertionError as e:
            print(json.dumps({"file": entry["file"], "error": str(e)}), flush=True)
            failed = True
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
