"""OpenCascade's grid fitter beside ours (scripts/cad_peers.sh, docs/cad.md).

For each scene: our fit's time (the `bench` row's median), net and reported
deviation; GeomAPI_PointsToBSplineSurface on the same 161 x 258 grid
(degree 3-8, C2, our tolerance), timed (best of 5); and both surfaces'
largest and mean distance from the depth-5 and depth-6 points by
OpenCascade's projection (GeomAPI_ProjectPointOnSurf). It prints one JSON
object a scene, then a table; with `--json` after the folder, the JSON only.

Usage: cad_peers.py FOLDER [--json]"""
import json
import os
import sys
import time

from OCP.BRep import BRep_Tool
from OCP.GeomAbs import GeomAbs_C2
from OCP.GeomAPI import GeomAPI_PointsToBSplineSurface, GeomAPI_ProjectPointOnSurf
from OCP.IFSelect import IFSelect_RetDone
from OCP.Interface import Interface_Static
from OCP.OCP.collections import Array2_gp_Pnt
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Pnt

out = sys.argv[1]
ours = {json.loads(l)["name"]: json.loads(l)["median_ns"] * 1e-9 for l in open(os.path.join(out, "ours.jsonl"))}


def obj_points(path):
    return [tuple(map(float, l.split()[1:4])) for l in open(path) if l.startswith("v ")]


def step_surface(path):
    r = STEPControl_Reader()
    Interface_Static.SetCVal_s("xstep.cascade.unit", "M")
    assert r.ReadFile(path) == IFSelect_RetDone
    r.TransferRoots()
    ex = TopExp_Explorer(r.OneShape(), TopAbs_FACE)
    return BRep_Tool.Surface_s(TopoDS.Face(ex.Current()))


def distances(surf, pts):
    u0, u1, v0, v1 = surf.Bounds()
    pr = GeomAPI_ProjectPointOnSurf()
    pr.Init(surf, u0, u1, v0, v1)
    worst, total = 0.0, 0.0
    for p in pts:
        pr.Perform(gp_Pnt(*p))
        d = pr.LowerDistance() if pr.NbPoints() > 0 else float("inf")
        worst, total = max(worst, d), total + d
    return worst, total / len(pts)


as_json = "--json" in sys.argv[2:]
rows = []
for scene, row in [("car1", "fit/car/d5"), ("car2", "fit/car2/d5")]:
    rep = json.load(open(os.path.join(out, f"{scene}.json")))
    fit = rep["fit"]
    tol = fit["tolerance"]
    info = json.load(open(os.path.join(out, f"{scene}-d5.json")))
    nr, nc = info["streamlines"], info["points_per_streamline"]
    d5 = obj_points(os.path.join(out, f"{scene}-d5.obj"))
    d6 = obj_points(os.path.join(out, f"{scene}-d6.obj"))
    assert len(d5) == nr * nc
    grid = Array2_gp_Pnt(1, nc, 1, nr)
    for j in range(nr):
        for i in range(nc):
            grid.SetValue(i + 1, j + 1, gp_Pnt(*d5[j * nc + i]))
    best = float("inf")
    for _ in range(5):
        t = time.perf_counter()
        occ = GeomAPI_PointsToBSplineSurface(grid, 3, 8, GeomAbs_C2, tol)
        best = min(best, time.perf_counter() - t)
    s_occ = occ.Surface()
    s_ours = step_surface(os.path.join(out, f"{scene}.step"))
    r = {
        "scene": scene, "points": [nr, nc], "tolerance": tol,
        "ours": {"seconds": ours[row], "degree": fit["degree"], "poles": fit["poles"],
                 "reported_max": fit["max_deviation"],
                 "d5": distances(s_ours, d5), "d6": distances(s_ours, d6)},
        "occ": {"seconds": best, "degree": [s_occ.UDegree(), s_occ.VDegree()],
                "poles": [s_occ.NbUPoles(), s_occ.NbVPoles()],
                "d5": distances(s_occ, d5), "d6": distances(s_occ, d6)},
    }
    print(json.dumps(r), flush=True)
    rows.append(r)

if as_json:
    sys.exit(0)
print()
print("| scene | fitter | time | degree | poles | largest distance d5 / d6 | mean d6 | within tolerance |")
print("|---|---|---:|---|---|---|---:|---|")
for r in rows:
    for who, name in [("ours", "ours"), ("occ", "OpenCascade")]:
        x = r[who]
        ok = "yes" if max(x["d5"][0], x["d6"][0]) <= r["tolerance"] else "no"
        print(f"| {r['scene']} | {name} | {x['seconds'] * 1e3:.2f} ms | {x['degree'][0]}×{x['degree'][1]} "
              f"| {x['poles'][0]}×{x['poles'][1]} | {x['d5'][0]:.2e} / {x['d6'][0]:.2e} | {x['d6'][1]:.2e} | {ok} |")
    print(f"| {r['scene']} | OpenCascade ÷ ours | {r['occ']['seconds'] / r['ours']['seconds']:.1f}× | | | | | tolerance {r['tolerance']:.2e} |")
