"""OpenCascade's grid fitter beside our fit of a reference
(scripts/reference_peers.sh, docs/fit.md, docs/benchmarks.md).

For each shipped face (scenes/references/): our fit's time (the
`reference-fit/FACE/d5` row's median, with the kernel's helper thread and
on one thread), its net and its deviation both ways as `fit --json`
reports them; then GeomAPI_PointsToBSplineSurface (degree 3-8, C2, our
tolerance) on the face sampled on a grid of as many points as our design's
mesh at depth 5 (uniform in the face's parameters), timed (best of 5), and
its largest distance both ways measured by OpenCascade's projection
(GeomAPI_ProjectPointOnSurf, with the border curves and corners for the
points of the grid's outer ring): from its surface sampled on the same grid
to the face, and from the face sampled at the grid's points and the centres
of its cells (twice as dense, as our fit measures) to its surface. As a
check of our own measure, our depth-5 points to the face by the same
projection. It prints one JSON object a face, then a table; with `--json`
after the folder, the JSON only. In the JSON, `points` and `net` are rows x
columns (across x along the streamlines), OpenCascade's `degree` and
`poles` U x V (its U along the streamlines).

Usage: reference_peers.py FOLDER [--json]  (FOLDER: what reference_peers.sh
wrote: ours.jsonl, FACE.json (`fit --json`), FACE-d5.json and FACE-d5.obj
(`build --depth 5`))."""
import json
import os
import sys
import time

from OCP.BRep import BRep_Tool
from OCP.GeomAbs import GeomAbs_C2
from OCP.GeomAPI import GeomAPI_PointsToBSplineSurface, GeomAPI_ProjectPointOnCurve, GeomAPI_ProjectPointOnSurf
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader
from OCP.Interface import Interface_Static
from OCP.OCP.collections import Array2_gp_Pnt
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Pnt

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FACES = [("hood", "hood.step"), ("duct", "duct.igs"), ("roof", "roof.step")]


def face_surface(path):
    """Face 0 of a STEP or IGES file, in metres."""
    step = path.lower().endswith((".step", ".stp"))
    reader = STEPControl_Reader() if step else IGESControl_Reader()
    assert Interface_Static.SetCVal_s("xstep.cascade.unit", "M")
    assert reader.ReadFile(path) == IFSelect_RetDone, path
    reader.TransferRoots()
    ex = TopExp_Explorer(reader.OneShape(), TopAbs_FACE)
    return BRep_Tool.Surface_s(TopoDS.Face(ex.Current()))


def obj_points(path):
    return [tuple(map(float, l.split()[1:4])) for l in open(path) if l.startswith("v ")]


class Distance:
    """The distance from points to a surface: the orthogonal projection, and
    for points on the border of the grid they come from (`edge`), the
    distance to the surface's border curves and corners too (a point beyond
    the border has no orthogonal projection)."""

    def __init__(self, surf):
        u0, u1, v0, v1 = surf.Bounds()
        self.proj = GeomAPI_ProjectPointOnSurf()
        self.proj.Init(surf, u0, u1, v0, v1)
        self.borders = [surf.UIso(u0), surf.UIso(u1), surf.VIso(v0), surf.VIso(v1)]
        self.corners = [surf.Value(u, v) for u in (u0, u1) for v in (v0, v1)]

    def __call__(self, p, edge):
        q = gp_Pnt(*p)
        self.proj.Perform(q)
        best = self.proj.LowerDistance() if self.proj.NbPoints() > 0 else float("inf")
        if edge or best == float("inf"):
            best = min(best, *(q.Distance(c) for c in self.corners))
            for curve in self.borders:
                on = GeomAPI_ProjectPointOnCurve(q, curve)
                if on.NbPoints() > 0:
                    best = min(best, on.LowerDistance())
        return best


def largest(surf, points):
    """The largest distance from `points` ((xyz, on the grid's ring) pairs)
    to `surf`."""
    d = Distance(surf)
    return max(d(p, edge) for p, edge in points)


def sampled(surf, nr, nc, centres=False):
    """`surf` at an nc x nr grid uniform in its parameters (u along a row),
    or at the centres of that grid's cells; each point with whether it is on
    the grid's outer ring."""
    u0, u1, v0, v1 = surf.Bounds()
    out = []
    if centres:
        for j in range(nr - 1):
            for i in range(nc - 1):
                p = surf.Value(u0 + (u1 - u0) * (i + 0.5) / (nc - 1), v0 + (v1 - v0) * (j + 0.5) / (nr - 1))
                out.append(((p.X(), p.Y(), p.Z()), i in (0, nc - 2) or j in (0, nr - 2)))
        return out
    for j in range(nr):
        for i in range(nc):
            p = surf.Value(u0 + (u1 - u0) * i / (nc - 1), v0 + (v1 - v0) * j / (nr - 1))
            out.append(((p.X(), p.Y(), p.Z()), i in (0, nc - 1) or j in (0, nr - 1)))
    return out


def main():
    folder = sys.argv[1]
    as_json = "--json" in sys.argv[2:]
    ours = {}
    for line in open(os.path.join(folder, "ours.jsonl")):
        if line.strip().startswith("{"):
            r = json.loads(line)
            ours[r["name"]] = r["median_ns"] * 1e-9
    rows = []
    for name, file in FACES:
        path = os.path.join(ROOT, "scenes/references", file)
        fit = json.load(open(os.path.join(folder, f"{name}.json")))
        info = json.load(open(os.path.join(folder, f"{name}-d5.json")))
        nr, nc = info["streamlines"], info["points_per_streamline"]
        mesh = obj_points(os.path.join(folder, f"{name}-d5.obj"))
        assert len(mesh) == nr * nc, (len(mesh), nr, nc)
        tol = fit["tolerance"]
        face = face_surface(path)
        data = sampled(face, nr, nc)
        grid = Array2_gp_Pnt(1, nc, 1, nr)
        for k, (p, _) in enumerate(data):
            grid.SetValue(k % nc + 1, k // nc + 1, gp_Pnt(*p))
        best = float("inf")
        for _ in range(5):
            t = time.perf_counter()
            occ = GeomAPI_PointsToBSplineSurface(grid, 3, 8, GeomAbs_C2, tol)
            best = min(best, time.perf_counter() - t)
        assert occ.IsDone(), name
        s = occ.Surface()
        ring = [(p, j in (0, nr - 1) or i in (0, nc - 1)) for k, p in enumerate(mesh) for j, i in [divmod(k, nc)]]
        r = {
            "face": name, "file": file, "points": [nr, nc], "tolerance": tol,
            "ours": {
                "seconds": ours[f"reference-fit/{name}/d5"],
                "seconds_1t": ours[f"reference-fit/{name}/d5/1t"],
                "net": [fit["net"]["rows"], fit["net"]["cols"]],
                "to_face": fit["deviation"]["to_reference"]["max"],
                "from_face": fit["deviation"]["from_reference"]["max"],
                "to_face_by_occ": largest(face, ring),
            },
            "occ": {
                "seconds": best,
                "degree": [s.UDegree(), s.VDegree()],
                "poles": [s.NbUPoles(), s.NbVPoles()],
                "to_face": largest(face, sampled(s, nr, nc)),
                "from_face": max(largest(s, data), largest(s, sampled(face, nr, nc, centres=True))),
            },
        }
        print(json.dumps(r), flush=True)
        rows.append(r)
    if as_json:
        return
    print()
    print("| face | grid | tolerance | ours (1 thread) | net | to / from the face | OpenCascade | poles | to / from the face "
          "| OpenCascade ÷ ours (1 thread) |")
    print("|---|---|---:|---:|---|---|---:|---|---|---:|")
    for r in rows:
        o, c = r["ours"], r["occ"]
        print(f"| {r['face']} | {r['points'][0]}×{r['points'][1]} | {r['tolerance']:.2e} "
              f"| {o['seconds'] * 1e3:.1f} ms ({o['seconds_1t'] * 1e3:.1f} ms) | {o['net'][0]}×{o['net'][1]} "
              f"| {o['to_face']:.2e} / {o['from_face']:.2e} | {c['seconds'] * 1e3:.1f} ms "
              f"| {c['poles'][1]}×{c['poles'][0]} | {c['to_face']:.2e} / {c['from_face']:.2e} "
              f"| {c['seconds'] / o['seconds_1t']:.2f}× |")


if __name__ == "__main__":
    main()
