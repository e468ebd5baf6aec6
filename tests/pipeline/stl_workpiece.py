"""Workpieces from STL (issue 4): CGAL checks the facets bound a volume, gmsh meshes it. A closed
box gives the exact volume and runs; an open, a partly flipped and an inward-facing STL are each
one clear error naming the file."""
import json

import rkcase

tools = rkcase.tools_from_argv()
w = tools.work


def box_stl(name, lx, ly, lz, keep=None, flip_first=False, inward=False):
    v = [(x * lx, y * ly, z * lz) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    tris = [t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]
    if keep is not None:
        tris = tris[:keep]
    if flip_first:
        tris[0] = (tris[0][0], tris[0][2], tris[0][1])
    if inward:
        tris = [(a, c, b) for a, b, c in tris]
    lines = ["solid box"]
    for t in tris:
        lines += [" facet normal 0 0 0", "  outer loop"] + [f"   vertex {v[i][0]} {v[i][1]} {v[i][2]}" for i in t]
        lines += ["  endloop", " endfacet"]
    (w / f"{name}.stl").write_text("\n".join(lines + ["endsolid box", ""]))
    scene = w / f"{name}.yaml"
    scene.write_text(f"geometry: {{cad: {name}.stl, unit: mm}}\ndiscretization: {{spacing: 2.0e-3}}\n"
                     "material: {model: elastic, density: 2700, youngs_modulus: 70.0e9, poisson_ratio: 0.3}\n"
                     "initial_conditions: {velocity: [0, 0, 1]}\ntime: {end: 0.2e-6}\n")
    return scene


case = tools.case("stl_box")
tools.prep(case, 2, scene=box_stl("box", 10, 10, 20))
prep = json.loads((case / "prep.json").read_text())
rkcase.check(abs(prep["volume_m3"] / 2e-6 - 1) < 1e-9, f"box volume {prep['volume_m3']:.6g} m^3 (exact 2e-6)")
tools.solve(case, 2)
rkcase.check(json.loads((case / "solve.json").read_text())["steps"] > 0, "the STL workpiece runs on 2 ranks")
for name, kw, needle in (("open", {"keep": 11}, "is not watertight"),
                         ("flipped", {"flip_first": True}, "not a consistently oriented manifold"),
                         ("inward", {"inward": True}, "facets point inward")):
    p = tools.prep(tools.case(f"stl_{name}"), 1, scene=box_stl(name, 10, 10, 20, **kw), expect_ok=False)
    rkcase.check(p.returncode != 0 and f"{name}.stl: " in p.stderr and needle in p.stderr, f"{name} STL: {p.stderr.strip()}")
