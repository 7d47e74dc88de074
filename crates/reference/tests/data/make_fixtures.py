"""Writes the reference reader's test fixtures with OpenCascade (OCP, the test
virtual environment of scripts/venv.sh) and the values the tests compare with.

Usage (from the repository root):

    ~/.cache/streamline-venv/bin/python crates/reference/tests/data/make_fixtures.py

Writes, next to this script:

- bicubic.step, bicubic.igs: one bicubic B-spline patch (5 x 4 poles,
  non-uniform knots in u), in metres;
- bicubic-mm.step, bicubic-mm.igs: the same patch written in millimetres;
- bicubic-inch.step, bicubic-inch.igs: the same patch written in inches;
- cylinder.step, cylinder.igs: a quarter of a cylinder (radius 0.5, height
  1), exact as a rational B-spline (weights 1, 1/sqrt(2), 1), in metres;
- two-faces.step: the bicubic patch and a planar rectangle, in metres;
- trimmed.step, trimmed.igs: the bicubic patch with a round hole, in metres;
- expected.json: for every file, its faces as OpenCascade reads them back
  (in metres): kind, degrees, full knot vectors, poles as rows (one per v
  index, one column per u index, as streamline_kernel's Grid holds them),
  weights (or null), and points evaluated by OpenCascade at a few (u, v).

The generated files are committed; rerun this only to change them.

Not written by this script: car1-streamline.step and car1-streamline.igs,
the files the project's own exporter writes for the built-in scene car1
(src/scene/export/step.rs, src/scene/export/iges.rs), made with

    cargo run --release -- build car1 --depth 3 --export car1-streamline.step
    cargo run --release -- build car1 --depth 3 --export car1-streamline.igs

(tests/read.rs checks that they read: one untrimmed B-spline face in metres).
"""
import json
import math
import os

from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.BRep import BRep_Builder
from OCP.Geom import Geom_BSplineSurface, Geom_Plane, Geom_Circle
from OCP.GeomAdaptor import GeomAdaptor_Surface
from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_Plane
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader, IGESControl_Writer
from OCP.Interface import Interface_Static
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader, STEPControl_Writer
from OCP.OCP.collections import Array1_double, Array1_int, Array2_double, Array2_gp_Pnt
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound
from OCP.gp import gp_Ax2, gp_Dir, gp_Pln, gp_Pnt

HERE = os.path.dirname(os.path.abspath(__file__))


def bspline(poles, weights, knots_u, mults_u, knots_v, mults_v, deg_u, deg_v):
    """A Geom_BSplineSurface; poles[i][j] with i along u, j along v (OCP's order)."""
    nu, nv = len(poles), len(poles[0])
    p = Array2_gp_Pnt(1, nu, 1, nv)
    w = Array2_double(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            p.SetValue(i + 1, j + 1, gp_Pnt(*poles[i][j]))
            w.SetValue(i + 1, j + 1, weights[i][j] if weights else 1.0)

    def arr(values, cls):
        a = cls(1, len(values))
        for k, x in enumerate(values):
            a.SetValue(k + 1, x)
        return a

    ku, mu = arr(knots_u, Array1_double), arr(mults_u, Array1_int)
    kv, mv = arr(knots_v, Array1_double), arr(mults_v, Array1_int)
    if weights:
        return Geom_BSplineSurface(p, w, ku, kv, mu, mv, deg_u, deg_v)
    return Geom_BSplineSurface(p, ku, kv, mu, mv, deg_u, deg_v)


def bicubic():
    """5 x 4 poles, degree 3 x 3, one interior knot at u = 0.4 (non-uniform)."""
    poles = []
    for i in range(5):
        row = []
        for j in range(4):
            x, y = 0.25 * i, 0.3 * j
            z = 0.1 * math.sin(1.3 * i + 0.7 * j) + 0.02 * i * j
            row.append((x, y, z))
        poles.append(row)
    return bspline(poles, None, [0.0, 0.4, 1.0], [4, 1, 4], [0.0, 2.0], [4, 4], 3, 3)


def cylinder():
    """A quarter of the cylinder x^2 + z^2 = 0.25 (axis y), y in [0, 1]: degree 2
    in u (the arc, weights 1, 1/sqrt(2), 1), degree 1 in v (the ruling)."""
    r, h = 0.5, 1.0
    arc = [(r, 0.0), (r, r), (0.0, r)]
    wts = [1.0, math.sqrt(0.5), 1.0]
    poles = [[(x, y, z) for y in (0.0, h)] for (x, z) in arc]
    weights = [[w, w] for w in wts]
    return bspline(poles, weights, [0.0, 1.0], [3, 3], [0.0, 1.0], [2, 2], 2, 1)


def face(surface):
    return BRepBuilderAPI_MakeFace(surface, 1e-9).Face()


def plane_face():
    pln = gp_Pln(gp_Pnt(0.0, 0.0, -0.5), gp_Dir(0.0, 0.0, 1.0))
    return BRepBuilderAPI_MakeFace(pln, 0.0, 1.0, 0.0, 0.9).Face()


def holed_face(surface):
    """The surface with a circular hole of radius 0.1 around its middle."""
    outer = face(surface)
    centre = surface.Value(0.5, 1.0)
    circle = Geom_Circle(gp_Ax2(gp_Pnt(centre.X(), centre.Y(), 0.0), gp_Dir(0.0, 0.0, 1.0)), 0.1)
    # project the circle onto the surface along z, as a closed wire on it
    from OCP.BRepProj import BRepProj_Projection
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder

    cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(centre.X(), centre.Y(), -1.0), gp_Dir(0.0, 0.0, 1.0)), 0.1, 2.0).Shape()
    cut = BRepAlgoAPI_Cut(outer, cyl)
    cut.Build()
    return cut.Shape()


def compound(*shapes):
    b = BRep_Builder()
    c = TopoDS_Compound()
    b.MakeCompound(c)
    for s in shapes:
        b.Add(c, s)
    return c


def write_step(shape, name, unit):
    w = STEPControl_Writer()
    Interface_Static.SetCVal_s("xstep.cascade.unit", "M")
    Interface_Static.SetCVal_s("write.step.unit", unit)
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    assert w.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone
    assert w.Write(os.path.join(HERE, name)) == IFSelect_RetDone


def write_iges(shape, name, unit):
    Interface_Static.SetCVal_s("xstep.cascade.unit", "M")
    Interface_Static.SetCVal_s("write.iges.unit", unit)
    w = IGESControl_Writer(unit, 0)
    # the shapes are in metres (OpenCascade's writer assumes millimetres)
    gs = w.Model().GlobalSection()
    gs.SetCascadeUnit(1000.0)
    w.Model().SetGlobalSection(gs)
    w.AddShape(shape)
    w.ComputeModel()
    assert w.Write(os.path.join(HERE, name))


def read_back(name):
    path = os.path.join(HERE, name)
    reader = STEPControl_Reader() if name.endswith(".step") else IGESControl_Reader()
    Interface_Static.SetCVal_s("xstep.cascade.unit", "M")
    assert reader.ReadFile(path) == IFSelect_RetDone, path
    reader.TransferRoots()
    return reader.OneShape()


def describe(f):
    """One face as the Rust reader is expected to see it."""
    surf = BRep_Tool.Surface_s(f)
    kind = GeomAdaptor_Surface(surf).GetType()
    if kind == GeomAbs_Plane:
        return {"kind": "plane"}
    if kind != GeomAbs_BSplineSurface:
        return {"kind": "other"}
    s = GeomAdaptor_Surface(surf).BSpline()
    nu, nv = s.NbUPoles(), s.NbVPoles()
    poles = [[list(s.Pole(i + 1, j + 1).Coord()) for i in range(nu)] for j in range(nv)]
    rational = s.IsURational() or s.IsVRational()
    weights = [[s.Weight(i + 1, j + 1) for i in range(nu)] for j in range(nv)] if rational else None
    ku = [s.UKnotSequence().Value(k) for k in range(1, s.UKnotSequence().Length() + 1)]
    kv = [s.VKnotSequence().Value(k) for k in range(1, s.VKnotSequence().Length() + 1)]
    u0, u1, v0, v1 = s.Bounds()
    points = []
    for a in (0.0, 0.3, 0.5, 0.77, 1.0):
        for b in (0.0, 0.45, 1.0):
            u, v = u0 + a * (u1 - u0), v0 + b * (v1 - v0)
            points.append({"u": u, "v": v, "point": list(s.Value(u, v).Coord())})
    return {
        "kind": "rational" if rational else "bspline",
        "degrees": [s.UDegree(), s.VDegree()],
        "knots_u": ku,
        "knots_v": kv,
        "poles": poles,
        "weights": weights,
        "points": points,
    }


def faces_of(name):
    shape = read_back(name)
    out = []
    e = TopExp_Explorer(shape, TopAbs_FACE)
    while e.More():
        out.append(describe(TopoDS.Face(e.Current())))
        e.Next()
    return out


def main():
    b, c = bicubic(), cylinder()
    fb, fc = face(b), face(c)
    files = {
        "bicubic.step": (fb, "M"),
        "bicubic-mm.step": (fb, "MM"),
        "bicubic-inch.step": (fb, "INCH"),
        "cylinder.step": (fc, "M"),
        "two-faces.step": (compound(fb, plane_face()), "M"),
        "trimmed.step": (holed_face(b), "M"),
        "bicubic.igs": (fb, "M"),
        "bicubic-mm.igs": (fb, "MM"),
        "bicubic-inch.igs": (fb, "IN"),
        "cylinder.igs": (fc, "M"),
        "trimmed.igs": (holed_face(b), "M"),
    }
    expected = {}
    for name, (shape, unit) in files.items():
        if name.endswith(".step"):
            write_step(shape, name, unit)
        else:
            write_iges(shape, name, unit)
        expected[name] = faces_of(name)
    with open(os.path.join(HERE, "expected.json"), "w") as f:
        json.dump(expected, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
