"""Times Loop subdivision in trimesh and pymeshlab on the test meshes and
prints them beside ours (a JSON-lines file from `streamline-studio bench
--json --filter loop/`). Both peers use Loop's vertex weight, as we do
(docs/math.md §7); pymeshlab refines every edge only with threshold=PureValue(0).
With `--json` after the file it prints one JSON object a row instead of the
table: mesh, levels, vertices_out, and ours_s, pymeshlab_s, trimesh_s
(seconds; the peers' best of 3 runs, of 1 at level 3)."""
import json
import sys
import time

import numpy as np
import pymeshlab
import trimesh


def load(name):
    v, f = [], []
    for line in open(f"tests/data/meshes/{name}.obj"):
        w = line.split()
        if w and w[0] == "v":
            v.append([float(x) for x in w[1:4]])
        elif w and w[0] == "f":
            f.append([int(x.split("/")[0]) - 1 for x in w[1:4]])
    return np.array(v), np.array(f)


def best(fn, repeat):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), out


ours = {}
for line in open(sys.argv[1]):
    row = json.loads(line)
    ours[row["name"]] = row["median_ns"] * 1e-9

as_json = "--json" in sys.argv[2:]
if not as_json:
    print("| mesh | levels | vertices out | ours | pymeshlab | trimesh | pymeshlab ÷ ours | trimesh ÷ ours |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
for name in ["knight", "spot", "camelhead"]:
    v, f = load(name)
    for k in [1, 2, 3]:
        repeat = 3 if k < 3 else 1
        tt, (nv, _) = best(lambda: trimesh.remesh.subdivide_loop(v, f, iterations=k), repeat)

        def pml():
            ms = pymeshlab.MeshSet()
            ms.add_mesh(pymeshlab.Mesh(v, f))
            t = time.perf_counter()
            ms.meshing_surface_subdivision_loop(iterations=k, threshold=pymeshlab.PureValue(0))
            return time.perf_counter() - t

        tp = min(pml() for _ in range(repeat))
        o = ours.get(f"loop/subdivide/{name}/d{k}")
        if o is None:
            continue
        if as_json:
            row = {"mesh": name, "levels": k, "vertices_out": len(nv), "ours_s": o, "pymeshlab_s": tp, "trimesh_s": tt}
            print(json.dumps(row), flush=True)
            continue
        print(
            f"| {name} | {k} | {len(nv):,} | {o*1e3:.2f} ms | {tp*1e3:.1f} ms | {tt*1e3:.1f} ms "
            f"| {tp/o:.0f}× | {tt/o:.0f}× |"
        )
