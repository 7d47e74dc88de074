"""Writes the shipped reference surfaces with OpenCascade, from formulas, as
another CAD system would hand them to a designer (docs/fit.md).

Usage (from the repository root, in the test virtual environment that
`bash scripts/setup.sh --tests` makes):

    ~/.cache/streamline-venv/bin/python scenes/references/make_references.py

Writes, next to this script:

- hood.step: a car hood panel, 1.4 m long and 1.1 m wide, crowned across and
  rising towards the windscreen with a soft swage line: the points of the
  formula below on a 29 x 23 grid approximated by a bicubic B-spline
  (GeomAPI_PointsToBSplineSurface, 1e-6 m), written as AP214 in
  millimetres, the unit most CAD systems write;
- duct.igs: a quarter of a torus (major radius 0.6 m, minor 0.25 m, 90 by 90
  degrees), exact as a rational biquadratic B-spline (GeomConvert), written
  as IGES entity 128 in metres;
- roof.step: a roof panel, 1.6 m by 1.2 m, curved both ways with a slight
  twist, approximated the same way as the hood, written as AP242 in metres;
- scan.obj: a grid of 21 x 31 points on a wavy sheet, 1.5 m by 1.0 m, as a
  scanner or a subdivided plane exported from Blender gives it (OBJ quads;
  written without OpenCascade).

The fitted designs beside them (hood.ron, duct.ron, roof.ron, scan.ron) are made by the
product itself:

    streamline-studio fit scenes/references/hood.step --out scenes/references/hood.ron

and so on for the other three. The files are committed; rerun this only to
change them.
"""
import math
import os

from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.GeomAPI import GeomAPI_PointsToBSplineSurface
from OCP.GeomAbs import GeomAbs_C2
from OCP.GeomConvert import GeomConvert
from OCP.Geom import Geom_RectangularTrimmedSurface, Geom_ToroidalSurface
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Writer
from OCP.Interface import Interface_Static
from OCP.OCP.collections import Array2_gp_Pnt
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
from OCP.gp import gp_Ax3, gp_Dir, gp_Pnt

HERE = os.path.dirname(os.path.abspath(__file__))


def approximated(f, nu, nv):
    """A bicubic B-spline through f(a, b), a, b in [0, 1], on an nu x nv grid."""
    pts = Array2_gp_Pnt(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            pts.SetValue(i + 1, j + 1, gp_Pnt(*f(i / (nu - 1), j / (nv - 1))))
    fit = GeomAPI_PointsToBSplineSurface(pts, 3, 3, GeomAbs_C2, 1e-6)
    assert fit.IsDone()
    return fit.Surface()


def hood(a, b):
    """a along the car (0 at the front), b across (0 at the left)."""
    length, width = 1.4, 1.1
    x = length * a
    y = width * (b - 0.5)
    crown = 0.06 * (1.0 - (2.0 * b - 1.0) ** 2)
    rise = 0.18 * a * a
    swage = 0.012 * math.exp(-((abs(2.0 * b - 1.0) - 0.55) / 0.12) ** 2)
    return (x, y, crown + rise + swage)


def roof(a, b):
    length, width = 1.6, 1.2
    x = length * a
    y = width * (b - 0.5)
    z = 0.09 * (1.0 - (2.0 * a - 1.0) ** 2) + 0.05 * (1.0 - (2.0 * b - 1.0) ** 2) + 0.02 * (a - 0.5) * (b - 0.5)
    return (x, y, z)


def duct():
    torus = Geom_ToroidalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 0.6, 0.25)
    quarter = Geom_RectangularTrimmedSurface(torus, 0.0, math.pi / 2, 0.0, math.pi / 2)
    return GeomConvert.SurfaceToBSplineSurface_s(quarter)


def face(surface):
    return BRepBuilderAPI_MakeFace(surface, 1e-9).Face()


def write_step(surface, name, unit, schema):
    # the writer first: making it registers (and resets) the settings
    w = STEPControl_Writer()
    Interface_Static.SetCVal_s("xstep.cascade.unit", "M")
    Interface_Static.SetCVal_s("write.step.unit", unit)
    Interface_Static.SetCVal_s("write.step.schema", schema)
    assert w.Transfer(face(surface), STEPControl_AsIs) == IFSelect_RetDone
    assert w.Write(os.path.join(HERE, name)) == IFSelect_RetDone


def write_iges(surface, name):
    Interface_Static.SetCVal_s("xstep.cascade.unit", "M")
    Interface_Static.SetCVal_s("write.iges.unit", "M")
    w = IGESControl_Writer("M", 0)
    gs = w.Model().GlobalSection()
    gs.SetCascadeUnit(1000.0)
    w.Model().SetGlobalSection(gs)
    w.AddShape(face(surface))
    w.ComputeModel()
    assert w.Write(os.path.join(HERE, name))


def scan():
    """A grid of points as OBJ quads, numbered row by row."""
    rows, cols = 21, 31
    lines = ["# a grid of 21 x 31 points (scenes/references/make_references.py)", "o scan"]
    for r in range(rows):
        for c in range(cols):
            x, y = 1.5 * c / (cols - 1), 1.0 * r / (rows - 1)
            z = 0.1 * math.sin(2.0 * x) * math.cos(1.5 * y) + 0.05 * x * y
            lines.append(f"v {x:.9f} {y:.9f} {z:.9f}")
    for r in range(rows - 1):
        for c in range(cols - 1):
            a = r * cols + c + 1
            lines.append(f"f {a} {a + 1} {a + cols + 1} {a + cols}")
    with open(os.path.join(HERE, "scan.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    scan()
    write_step(approximated(hood, 29, 23), "hood.step", "MM", "AP214IS")
    write_iges(duct(), "duct.igs")
    write_step(approximated(roof, 25, 21), "roof.step", "M", "AP242DIS")


if __name__ == "__main__":
    main()
