"""Reads every STEP and IGES file of a manifest back with OpenCascade (OCP)
and checks what Streamline Studio reported for it (tests/cad_export.rs,
docs/cad.md): one face; a non-rational B-spline surface of the reported
degree and pole counts; BRepCheck_Analyzer valid; and the largest distance
from the given mesh points to the face, by OpenCascade's projection
(GeomAPI_ProjectPointOnSurf), within the reported tolerance. An entry with
"names" also has the names read back: for STEP the PRODUCT's id and name,
the shape representation's name, the name XCAF gives the shape (what a CAD
application shows) and the header's FILE_NAME; for IGES the global
section's sender and receiver product names and file name.

Usage: check_cad.py MANIFEST.json  (prints one JSON line per file; exit 1 on
any failure, with the reason).
"""
import json
import sys

from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
from OCP.BRep import BRep_Tool
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.Extrema import Extrema_ExtAlgo_Tree
from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
from OCP.Geom import Geom_BSplineSurface
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader
from OCP.Interface import Interface_Static
from OCP.STEPCAFControl import STEPCAFControl_Reader
from OCP.STEPControl import STEPControl_Reader
from OCP.StepBasic import StepBasic_Product
from OCP.StepShape import StepShape_ShapeRepresentation
from OCP.TCollection import TCollection_ExtendedString
from OCP.TDataStd import TDataStd_Name
from OCP.TDF import TDF_ChildIterator
from OCP.TDocStd import TDocStd_Document
from OCP.XCAFDoc import XCAFDoc_DocumentTool
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Pnt


def is_step(path):
    return path.lower().endswith((".step", ".stp"))


def read(path):
    reader = STEPControl_Reader() if is_step(path) else IGESControl_Reader()
    # our files are in metres; OpenCascade converts to millimetres unless
    # told (the setting exists once a reader has registered it)
    assert Interface_Static.SetCVal_s("xstep.cascade.unit", "M"), "cannot set xstep.cascade.unit"
    if reader.ReadFile(path) != IFSelect_RetDone:
        raise AssertionError(f"{path}: OpenCascade could not read the file")
    reader.TransferRoots()
    return reader, reader.OneShape()


def text(h):
    """An OpenCascade string handle as Python text (a null one as "")."""
    return "" if h is None else h.ToCString()


def xcaf_names(path):
    """The names XCAF gives the shapes of a STEP file."""
    doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    assert reader.ReadFile(path) == IFSelect_RetDone, f"{path}: XCAF could not read the file"
    assert reader.Transfer(doc), f"{path}: XCAF could not transfer the file"
    out = []
    it = TDF_ChildIterator(XCAFDoc_DocumentTool.ShapeTool_s(doc.Main()).Label(), False)
    while it.More():
        name = TDataStd_Name()
        if it.Value().FindAttribute(TDataStd_Name.GetID_s(), name):
            out.append(name.Get().ToExtString())
        it.Next()
    return out


def names(path, reader):
    """The names written into the file, as OpenCascade reads them."""
    if not is_step(path):
        g = reader.IGESModel().GlobalSection()
        return {"sender": text(g.SendName()), "receiver": text(g.ReceiveName()), "file": text(g.FileName())}
    model = reader.StepModel()
    out = {"product id": [], "product name": [], "representation": []}
    for i in range(1, model.NbEntities() + 1):
        e = model.Value(i)
        if isinstance(e, StepBasic_Product):
            out["product id"].append(text(e.Id()))
            out["product name"].append(text(e.Name()))
        elif isinstance(e, StepShape_ShapeRepresentation):
            out["representation"].append(text(e.Name()))
    out["xcaf"] = xcaf_names(path)
    out["file"] = text(APIHeaderSection_MakeHeader(model).Name())
    return out


def faces(shape):
    out = []
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        out.append(TopoDS.Face(ex.Current()))
        ex.Next()
    return out


def points(path):
    with open(path) as f:
        return [tuple(float(x) for x in line.split()) for line in f if line.strip()]


def check(entry):
    path = entry["file"]
    reader, shape = read(path)
    fs = faces(shape)
    assert len(fs) == 1, f"{path}: {len(fs)} faces, want 1"
    face = fs[0]
    surf = BRep_Tool.Surface_s(face)
    bs = surf
    assert isinstance(bs, Geom_BSplineSurface), f"{path}: the face's surface is {type(surf).__name__}, not a B-spline surface"
    assert not bs.IsURational() and not bs.IsVRational(), f"{path}: the surface is rational"
    got = {"degree": [bs.UDegree(), bs.VDegree()], "poles": [bs.NbUPoles(), bs.NbVPoles()]}
    assert got["degree"] == entry["degree"], f"{path}: degree {got['degree']}, reported {entry['degree']}"
    assert got["poles"] == entry["poles"], f"{path}: poles {got['poles']}, reported {entry['poles']}"
    valid = BRepCheck_Analyzer(shape).IsValid()
    assert valid, f"{path}: BRepCheck_Analyzer says the shape is not valid"
    worst = {}
    for name, pts_file in entry["points"].items():
        d_max = 0.0
        u0, u1, v0, v1 = bs.Bounds()
        # Two of OpenCascade's projections: the tree algorithm (its
        # subdivision of the surface built once, fast) first; its nearest
        # point is a point of the face, so its distance is never below the
        # true one, and a point within the tolerance by it is within it. A
        # point over the tolerance is projected again by the default (global)
        # algorithm, whose distance is the one that counts.
        fast = GeomAPI_ProjectPointOnSurf()
        fast.Init(surf, u0, u1, v0, v1, Extrema_ExtAlgo_Tree)
        full = GeomAPI_ProjectPointOnSurf()
        full.Init(surf, u0, u1, v0, v1)
        for (x, y, z) in points(pts_file):
            p = gp_Pnt(x, y, z)
            fast.Perform(p)
            d = fast.LowerDistance() if fast.NbPoints() > 0 else float("inf")
            if d > entry["tolerance"]:
                full.Perform(p)
                assert full.NbPoints() > 0, f"{path}: OpenCascade found no projection of ({x}, {y}, {z})"
                d = full.LowerDistance()
            d_max = max(d_max, d)
        worst[name] = d_max
        assert d_max <= entry["tolerance"], f"{path}: a {name} point is {d_max:.3e} from the face, over the tolerance {entry['tolerance']:.3e}"
    result = {"file": path, **got, "valid": valid, "max_distance": worst, "tolerance": entry["tolerance"]}
    if "names" in entry:
        result["names"] = names(path, reader)
        assert result["names"] == entry["names"], f"{path}: names {result['names']!r}, written {entry['names']!r}"
    return result


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
