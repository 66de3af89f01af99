#!/usr/bin/env python3
"""The DAO's anterior y on IGA and tetrahedral meshes (validation/suite/README.md, 2026-12-04).

Runs copies of examples/dao/contract.toml (IGA, `knot_insertion` changed and, unless a mesh names
its grading, the committed scene's graded knots along left out) and contract-tet.toml
(`element_size` changed) with four more point probes on the mouth-corner end face, at half its
semi-axes (+-1.5 mm across the width, +-1 mm across the thickness from the centre (4, 2, 34) mm),
and writes OUT/dao_mesh_study.md with these tables:

* the end's y at the centre probe (on the shrink solid's collapsed axis) and the mean of the four
  off-axis probes, with the smallest pointwise J of the run (summary.json's min_jacobian);
* u_y along the centreline (IGA: the tessellation points of fields.h5 that are shared by the
  cells around the collapsed axis; tetrahedra: the mean of the nodes within 0.4 mm of the finest
  IGA run's axis, at the same reference heights z);
* the fibre stretch in the first 2 mm next to the clamped jaw face, IGA runs only (hexahedra of fields.h5,
  F of the trilinear tessellation cell, lambda = 1 / |F^-1 a| with a the deformed fibre).

* the end's y against time (probes.csv, interpolated; "." past the last converged step);
* u_y across the width at four heights (the mean over the tessellation or mesh points within
  0.5 mm of the height, in 2 mm bins of x): the fan's cupping, and whether it wrinkles;
* the Newton and linear-solver work of each run (summary.json), with the converged steps whose
  equilibrium is unstable, the mode of the first and whether the law stayed strongly elliptic
  there (summary.json's stability).

Usage: /usr/bin/python3 validation/suite/dao_mesh_study.py [--out OUT] [--jobs N] [--reuse]
       [--meshes iga:3,15,7 iga:3,15,3:1,0,2 iga:3,15,3::1536 tet:0.00075
                 tet:0.00075:v0,0.0003,0.002 grid:4,8,8 ...]
       [--jaw clamped|sliding|elastic] [--jaw-stiffness K] [--end T]
       [--indefinite-tangent lu|shift|cut] [--stall-iterations N]
       [--material KEY=VALUE ...] [--constant-fibres X Y Z] [--continuity C]
       [--tet-quadrature DEGREE]
A mesh is iga:KNOT_INSERTION[:DEGREE_ELEVATION[:GRADED]], tet:ELEMENT_SIZE[:FACE,SIZE,DISTANCE] (one
[[tetrahedra.refine]]) or grid:AROUND,ALONG,RADIAL (10-node tetrahedra cut from the shrink
solid's parametric grid with that many cells per knot span of the unrefined solid, 4 x 3 x 1
spans: structured_tet_mesh.py; grid:4,4,4 has the cells of IGA level 1, grid:4,8,8 of level 2);
the scene's own values where a part is left out. GRADED = N grades the IGA spans along the muscle
towards the jaw face: knots at 1/(2n), 1/(4n), ... down to 1/N of v are added to the n uniform
spans along (n = 3 (k + 1) for the knot insertion k along; iga:3,15,3::1536 puts 1/96 ... 1/1536
into 48 spans), so the first span is 1/N (a power-of-two fraction of 1/n) and each next one twice
as long; N ends the scene and run names (dao_iga_3_15_3_1536).
The default meshes are those of the README table (about 3 h on one core; --jobs 2 halves it).
--jaw sliding replaces the clamped jaw face by one held only along z (free to move in x and y, so
free to widen as the fibres next to it shorten) and two point constraints against the rigid
motions left: x and y at the face's centre, y at the end of its major axis (the stand-in's section
frame, below); the scenes and runs are named dao_sliding_*.
--jaw elastic puts the jaw face on springs instead ([[boundary]] type = "elastic", README.md
"Elastic supports"): a traction -K u per unit reference area, K = --jaw-stiffness (Pa/m, default
1e8, about a 1 mm layer of a 100 kPa tissue; the 2026-12-07 section of validation/suite/README.md);
the names start dao_elastic<K>_. IGA meshes only (tetrahedra refuse elastic supports).
--end T runs to T seconds instead of 0.2 s (the report's tables then end at T).
--indefinite-tangent and --stall-iterations set the [solver] keys of those names (README.md,
"Solver"; the scenes' defaults lu and 4 when left out) and add _shift, _cut, _stall0 ... to the
scene names; the report's last table is the Newton and linear-solver work of each run.
The variants of the 2026-12-05 section: --material D=1e-5 adds a [material.parameters] table
(tang2009 parameters; _D1e-5 in the names), --constant-fibres 0 0 1 replaces the NURBS isocurve
fibres by one direction (_fibre_0_0_1), --continuity 0 gives the IGA meshes C^0 element faces
([geometry.refine] continuity, the Lagrange space on the same elements; _C0).
--tet-quadrature 4 integrates the tetrahedral meshes with the 14-point rule instead of the
10-node default's 4 points ([tetrahedra] quadrature_degree; _q4 in the names).
"""
import argparse
import concurrent.futures
import os
import re

import numpy as np

from run_suite import EXAMPLES, ROOT, fields_last_step, run
from structured_tet_mesh import structured_mesh

DEFAULT_MESHES = ["iga:3,1,1", "iga:3,3,3", "iga:3,7,7", "iga:3,7,15", "iga:3,15,7", "iga:3,15,15",
                  "iga:3,31,3", "tet:0.001", "tet:0.00075", "tet:0.0006"]
END_CENTRE = np.array([0.004, 0.002, 0.034])
BEFORE_END = np.array([0.0035, 0.004, 0.029])  # the centreline's last two section centres:
HALF_WIDTH, HALF_THICKNESS = 0.0015, 0.001  # geometry/shapes.cpp, depressor_anguli_oris
JAW_CHORD = np.array([0.0010, 0.0025, 0.0070])  # first section's chord, and its half width
JAW_HALF_WIDTH = 0.0150
# Scene-name parts of the [solver] keys --indefinite-tangent and --stall-iterations set.
SOLVER_SUFFIX = {"indefinite_tangent": "", "stall_iterations": "stall"}
CLAMPED_JAW = '[[boundary]]\nface = "v0"                       # the origin on the jaw\ntype = "fixed"\n'
# The point constraints catch the control points there (IGA: the collapsed axis, the section's
# interpolated corner) or the mesh nodes within 0.4 mm (tetrahedra: gmsh need not put one there).
SLIDING_JAW = """[[boundary]]
face = "v0"                       # the jaw face, held along z only
type = "fixed"
components = ["z"]

[[boundary]]
at = [0.0, 0.0, 0.0]
type = "fixed"
components = ["x", "y"]
tolerance = %s

[[boundary]]
at = [%.17g, %.17g, %.17g]
type = "fixed"
components = ["y"]
tolerance = %s
"""
ELASTIC_JAW = """[[boundary]]
face = "v0"                       # the jaw face, on springs
type = "elastic"
stiffness = %s
"""
# The stand-in's uniform knot spans along before refinement, as the suite reads them.
SPANS_ALONG = next(e for e in EXAMPLES if e["name"] == "dao")["base_spans"]["v"]
HEIGHTS_MM = [2, 3, 5, 8, 12, 17, 22, 27, 31, 34]
HISTORY_TIMES = [0.02, 0.05, 0.07, 0.09, 0.0975, 0.125, 0.15, 0.175, 0.2]
WIDTH_HEIGHTS_MM = [3, 10, 15, 22]
WIDTH_BINS_MM = np.arange(-14.0, 16.0, 2.0)


def section_frame(chord):
    """(e1, e2): a section's major and minor axis directions as geometry/shapes.cpp builds them from
    the chord through its neighbouring centres: e1 the x axis made normal to the chord."""
    t = chord / np.linalg.norm(chord)
    e1 = np.array([1.0, 0.0, 0.0]) - t[0] * t
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(t, e1)


def end_face_points():
    """The four off-axis points of the end face."""
    e1, e2 = section_frame(END_CENTRE - BEFORE_END)
    return {"a": END_CENTRE + HALF_WIDTH * e1, "b": END_CENTRE - HALF_WIDTH * e1,
            "c": END_CENTRE + HALF_THICKNESS * e2, "d": END_CENTRE - HALF_THICKNESS * e2}


def jaw_major_axis_end():
    """The end of the jaw section's major axis (the jaw face's centre is the origin)."""
    return JAW_HALF_WIDTH * section_frame(JAW_CHORD)[0]


def name_part(value):
    """A setting's value as part of a scene or run name (a '.' would end the name early)."""
    return re.sub(r"[^A-Za-z0-9-]", "p", value)


ISOCURVE_FIBRES = '[fibres]\nmode = "isocurve"\ndirection = "v"\n'


def graded_knots(knot_insertion_along, first_span):
    """Knots 1/(2n), 1/(4n), ... 1/first_span of v for the n uniform spans along of the knot
    insertion (the stand-in's SPANS_ALONG spans along, each split k + 1 times)."""
    n = SPANS_ALONG * (knot_insertion_along + 1)
    if first_span < 2 * n or first_span % n or (first_span // n) & (first_span // n - 1):
        raise SystemExit("dao_mesh_study: a graded first span of 1/%d is not 1/(2^m %d)" %
                         (first_span, n))
    knots, d = [], 2 * n
    while d <= first_span:
        knots.append(1.0 / d)
        d *= 2
    return sorted(knots)


def scene(mesh, folder, exe, jaw="clamped", solver=(), material=(), fibre_vector=None,
          continuity=None, tet_quadrature=None, stiffness="1e8", end=None):
    """Scene copy for 'iga:i,j,k[:a,b,c[:N]]' (knot insertion, degree elevation, spans along
    graded to a first one of 1/N),
    'tet:h[:face,size,distance]' (element size, m; one local refinement) or 'grid:a,b,c' (a
    mesh of the solid's own cells, written next to the scene with exe), with the jaw face
    clamped (the committed scenes), sliding or on springs of stiffness (Pa/m) (module doc), run
    to end (s; the scene's 0.2 s when None), the [solver] keys of solver and the
    [material] parameters of material, each a sequence of (key, TOML value) pairs, and the
    NURBS isocurve fibres or, with fibre_vector, one constant fibre direction; IGA meshes with
    continuity set get [geometry.refine] continuity (0: C^0 element faces), tetrahedral meshes
    with tet_quadrature set [tetrahedra] quadrature_degree; returns its path."""
    kind, value, *extra = mesh.split(":")
    if kind not in ("iga", "tet", "grid"):
        raise SystemExit("dao_mesh_study: mesh '%s': use iga:..., tet:... or grid:..." % mesh)
    base = os.path.join(ROOT, "examples", "dao", "contract.toml" if kind == "iga" else
                        "contract-tet.toml")
    text = open(base).read().replace("../geometry/dao.igs",
                                     os.path.join(ROOT, "examples", "geometry", "dao.igs"))
    if kind == "iga":
        # The committed scene's mesh is graded towards the jaw (its `knots` line, since
        # 2026-12-07); the meshes here are uniform along unless GRADED is given, as they were
        # when the README's tables were measured.
        text, m = re.subn(r"(knot_insertion = \[[^\]]*\])[^\n]*(\n#[^\n]*)*\nknots = \{[^\n]*\}",
                          lambda g: g.group(1), text)
        if m != 1:
            raise SystemExit("dao_mesh_study: no knots line to replace in %s" % base)
        # The line's own comment stays on it; continuity, when set, goes on the next line.
        text, n = re.subn(r"knot_insertion = \[[^\]]*\]([^\n]*)", lambda m: (
            "knot_insertion = [%s]%s" % (value.replace(",", ", "), m.group(1)) +
            ("" if continuity is None else "\ncontinuity = %d" % continuity)), text)
        if extra and extra[0]:
            text, m = re.subn(r"degree_elevation = \[[^\]]*\]", "degree_elevation = [%s]" %
                              extra[0].replace(",", ", "), text)
            n = min(n, m)
        if len(extra) == 2:
            # The explicit knots go on the line after the knot insertion's (and continuity's).
            knots = graded_knots(int(value.split(",")[1]), int(extra[1]))
            text, m = re.subn(r"(knot_insertion = [^\n]*(\ncontinuity = [0-9]+)?)", lambda g: (
                g.group(1) + "\nknots = { v = [%s] }" % ", ".join(repr(x) for x in knots)), text)
            n = min(n, m)
            extra = extra[:1]
    elif kind == "grid":
        # 10-node tetrahedra cut from the solid's parametric grid (structured_tet_mesh.py).
        msh = os.path.join(folder, "dao_grid_%s.msh" % value.replace(",", "_"))
        structured_mesh(exe, os.path.join(ROOT, "examples", "geometry", "dao.igs"), msh,
                        [int(c) for c in value.split(",")])
        text, n = re.subn(r"element_size = [0-9.e-]+", 'mesh = "%s"' % msh, text)
    else:
        text, n = re.subn(r"element_size = [0-9.e-]+", "element_size = %s" % value, text)
        if extra:
            face, size, distance = extra[0].split(",")
            text += ('\n[[tetrahedra.refine]]\nface = "%s"\nsize = %s\ndistance = %s\n' %
                     (face, size, distance))
    if n != 1 or len(extra) > 1:
        raise SystemExit("dao_mesh_study: cannot set the mesh '%s' in %s" % (mesh, base))
    if tet_quadrature is not None and kind != "iga":
        text = text.replace("\n[tetrahedra]\n", "\n[tetrahedra]\nquadrature_degree = %d\n" %
                            tet_quadrature)
        if "quadrature_degree" not in text:
            raise SystemExit("dao_mesh_study: no [tetrahedra] table in %s" % base)
    if jaw != "clamped" and CLAMPED_JAW not in text:
        raise SystemExit("dao_mesh_study: no clamped jaw face to replace in %s" % base)
    if jaw == "sliding":
        tolerance = "1e-06" if kind == "iga" else "0.0004"
        text = text.replace(CLAMPED_JAW, SLIDING_JAW % (tolerance, *jaw_major_axis_end(), tolerance))
    elif jaw == "elastic":
        if kind != "iga":
            raise SystemExit("dao_mesh_study: mesh '%s': elastic supports are for NURBS solids "
                             "only (IGA meshes)" % mesh)
        text = text.replace(CLAMPED_JAW, ELASTIC_JAW % stiffness)
    if end is not None:
        text, n = re.subn(r"\nend = [0-9.e-]+", "\nend = %s" % end, text)
        if n != 1:
            raise SystemExit("dao_mesh_study: no [time] end to set in %s" % base)
    text = re.sub(r"times = \[[^\]]*\]", "times = [%s]" % (end or "0.2"), text)
    if "\n[solver]\n" not in text:
        raise SystemExit("dao_mesh_study: no [solver] table in %s" % base)
    text = text.replace("\n[solver]\n", "\n[solver]\n" + "".join(
        "%s = %s\n" % (key, value) for key, value in solver))
    if material:
        # A [material.parameters] table of its own, before the next table after [material].
        if "[material.parameters]" in text or "\n[fibres]\n" not in text:
            raise SystemExit("dao_mesh_study: cannot add [material.parameters] to %s" % base)
        text = text.replace("\n[fibres]\n", "\n[material.parameters]\n" + "".join(
            "%s = %s\n" % (key, value) for key, value in material) + "\n[fibres]\n")
    if fibre_vector is not None:
        if ISOCURVE_FIBRES not in text:
            raise SystemExit("dao_mesh_study: no isocurve [fibres] table in %s" % base)
        text = text.replace(ISOCURVE_FIBRES, '[fibres]\nmode = "constant"\nvector = [%s]\n' %
                            ", ".join("%.12g" % c for c in fibre_vector))
    for name, p in end_face_points().items():
        for c in "xyz":
            text += ('\n[[probe]]\nname = "end_%s_%s"\nkind = "point_displacement"\n'
                     'point = [%.17g, %.17g, %.17g]\ncomponent = "%s"\n' % (name, c, *p, c))
    suffix = "".join("_" + SOLVER_SUFFIX[key] + value.strip('"') for key, value in solver)
    suffix += "".join("_%s%s" % (key, name_part(value)) for key, value in material)
    if continuity is not None and kind == "iga":
        suffix += "_C%d" % continuity
    if tet_quadrature is not None and kind != "iga":
        suffix += "_q%d" % tet_quadrature
    if fibre_vector is not None:
        suffix += "_fibre_" + "_".join(name_part("%g" % c) for c in fibre_vector)
    if end is not None:
        suffix += "_end" + name_part(end)
    prefix = {"clamped": "", "sliding": "sliding_", "elastic": "elastic%s_" % name_part(stiffness)}
    path = os.path.join(folder, "dao_%s%s%s.toml" % (prefix[jaw], re.sub(
        r"[:,]", "_", mesh.replace("::", ":").rstrip(":")), suffix))
    with open(path, "w") as f:
        f.write(text)
    return path


def axis_points(points):
    """Indices of the tessellation points on the collapsed axis, ordered by z."""
    key = np.round(points * 1e8).astype(np.int64)
    _, first, counts = np.unique(key, axis=0, return_index=True, return_counts=True)
    on_axis = first[counts >= 8]
    return on_axis[np.argsort(points[on_axis, 2])]


def centreline_uy(run_dir, is_iga, axis):
    """u_y (mm) at HEIGHTS_MM on the centreline; axis: reference axis points of an IGA run."""
    x, u, _ = fields_last_step(run_dir)
    z = np.array(HEIGHTS_MM) / 1000.0
    if is_iga:
        own = axis_points(x)
        return 1000.0 * np.interp(z, x[own, 2], u[own, 1])
    row = []
    for h in z:
        p = np.array([np.interp(h, axis[:, 2], axis[:, i]) for i in range(3)])
        near = np.linalg.norm(x - p, axis=1) < 0.4e-3
        row.append(1000.0 * u[near, 1].mean() if near.any() else float("nan"))
    return np.array(row)


def y_history(run_dir):
    """The end centre's y (mm) at HISTORY_TIMES from probes.csv; "." past the run's last step."""
    import csv
    rows = list(csv.DictReader(open(os.path.join(run_dir, "probes.csv"))))
    t = np.array([float(r["time"]) for r in rows])
    y = 1e3 * np.array([float(r["free_end_y"]) for r in rows])
    return ["%+.3f" % np.interp(h, t, y) if h <= t[-1] + 1e-12 else "." for h in HISTORY_TIMES]


def width_uy(run_dir, height_mm):
    """Mean u_y (mm) of the points within 0.5 mm of the reference height, per 2 mm bin of x."""
    x, u, _ = fields_last_step(run_dir)
    x, u = 1e3 * x, 1e3 * u
    level = np.abs(x[:, 2] - height_mm) < 0.5
    row = []
    for a, b in zip(WIDTH_BINS_MM[:-1], WIDTH_BINS_MM[1:]):
        inside = level & (x[:, 0] >= a) & (x[:, 0] < b)
        row.append("%+.2f" % u[inside, 1].mean() if inside.any() else ".")
    return row


def root_fibre_stretch(run_dir):
    """(min, max) fibre stretch of the IGA tessellation's hexahedra centred within 2 mm of the jaw
    face; None when no cell is centred there."""
    import h5py
    x, u, cells = fields_last_step(run_dir)
    with h5py.File(os.path.join(run_dir, "fields.h5"), "r") as f:
        step = sorted(k for k in f.keys() if k.startswith("step_"))[-1]
        fibre = np.array(f[step]["cell/fibre"])
    corners = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1], [-1, -1, 1],
                        [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float) / 8.0
    stretches = []
    for cell, a in zip(cells, fibre):
        if x[cell, 2].mean() > 0.002:
            continue
        F = (x[cell] + u[cell]).T @ corners @ np.linalg.inv(x[cell].T @ corners)
        stretches.append(1.0 / np.linalg.norm(np.linalg.solve(F, a)))
    return (min(stretches), max(stretches)) if stretches else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "release", "app", "isomuscle"))
    parser.add_argument("--out", default=os.path.join(ROOT, "runs", "dao_mesh_study"))
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--reuse", action="store_true")
    parser.add_argument("--meshes", nargs="+", default=DEFAULT_MESHES)
    parser.add_argument("--jaw", choices=["clamped", "sliding", "elastic"], default="clamped")
    parser.add_argument("--jaw-stiffness", default="1e8", metavar="K",
                        help="--jaw elastic: the springs' stiffness per unit area, Pa/m")
    parser.add_argument("--end", metavar="T", help="run to T seconds instead of 0.2 s")
    parser.add_argument("--indefinite-tangent", choices=["lu", "shift", "cut"])
    parser.add_argument("--stall-iterations", type=int)
    parser.add_argument("--material", nargs="+", default=[], metavar="KEY=VALUE",
                        help="tang2009 parameters to override in every scene, e.g. D=1e-5")
    parser.add_argument("--constant-fibres", nargs=3, type=float, metavar=("X", "Y", "Z"),
                        help="one fibre direction everywhere instead of the NURBS isocurves")
    parser.add_argument("--continuity", type=int,
                        help="IGA meshes: [geometry.refine] continuity (0: C^0 element faces, the "
                        "Lagrange FE space on the same elements)")
    parser.add_argument("--tet-quadrature", type=int, metavar="DEGREE",
                        help="tetrahedral meshes: [tetrahedra] quadrature_degree (the 10-node "
                        "default is 2, 4 points; 4 takes 14 points)")
    args = parser.parse_args()
    material = []
    for item in args.material:
        key, sep, value = item.partition("=")
        if not sep or not key or not value:
            parser.error("--material expects KEY=VALUE, got '%s'" % item)
        material.append((key, value))
    solver = []
    if args.indefinite_tangent:
        solver.append(("indefinite_tangent", '"%s"' % args.indefinite_tangent))
    if args.stall_iterations is not None:
        solver.append(("stall_iterations", str(args.stall_iterations)))
    os.makedirs(args.out, exist_ok=True)
    for value in (args.jaw_stiffness, args.end):
        if value is not None and not re.fullmatch(r"[0-9.]+(e[+-]?[0-9]+)?", value):
            parser.error("'%s' is not a positive number" % value)
    paths = {m: scene(m, args.out, args.exe, args.jaw, solver, material, args.constant_fibres,
                      args.continuity, args.tet_quadrature, args.jaw_stiffness, args.end)
             for m in args.meshes}
    dirs = {m: os.path.splitext(p)[0] for m, p in paths.items()}
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        results = dict(zip(args.meshes, pool.map(
            lambda m: run(args.exe, paths[m], dirs[m], args.reuse), args.meshes)))
    iga = [m for m in args.meshes if m.startswith("iga")]
    finest = max(iga, key=lambda m: results[m]["summary"]["elements"]) if iga else None
    axis = None
    if finest:
        x, _, _ = fields_last_step(dirs[finest])
        axis = x[axis_points(x)]
    lines = ["| mesh | elements / DOFs | wall | centre y | mean y of the 4 | centre x, z | min J | "
             "root fibre stretch |", "|---|---|---|---|---|---|---|---|"]
    profile = ["| mesh | " + " | ".join("z = %g" % z for z in HEIGHTS_MM) + " |",
               "|---" * (len(HEIGHTS_MM) + 1) + "|"]
    for m in args.meshes:
        s, p = results[m]["summary"], results[m]["probes"]
        mean4 = np.mean([p["end_%s_y" % k] for k in "abcd"])
        root = root_fibre_stretch(dirs[m]) if m.startswith("iga") else None
        lines.append("| %s | %d / %d | %.0f s | %+.3f | %+.3f | %+.3f, %+.3f | %.3f | %s |" % (
            m, s["elements"], s["dofs"], s["wall_seconds"]["total"], 1e3 * p["free_end_y"],
            1e3 * mean4, 1e3 * p["free_end_x"], 1e3 * p["free_end_z"], s["min_jacobian"]["value"],
            "%.2f-%.2f" % root if root else "-"))
        if axis is not None:
            profile.append("| %s | " % m + " | ".join(
                "%+.3f" % v for v in centreline_uy(dirs[m], m.startswith("iga"), axis)) + " |")
    history = ["| mesh | " + " | ".join("t = %g s" % t for t in HISTORY_TIMES) + " |",
               "|---" * (len(HISTORY_TIMES) + 1) + "|"]
    history += ["| %s | " % m + " | ".join(y_history(dirs[m])) + " |" for m in args.meshes]
    work = ["| mesh | steps | Newton iterations | step cuts | Cholesky failures | LU fallbacks (s) | "
            "shifted factorisations (largest tau, s) | unstable steps (from t) | wall |",
            "|---" * 9 + "|"]
    for m in args.meshes:
        s = results[m]["summary"]
        ls = s.get("linear_solver_statistics", {})
        st = s.get("stability", {})  # runs before 2026-12-06 have none
        unstable = ("%d (%.4g s)" % (st["unstable_steps"], st["first_unstable_time"])
                    if st.get("unstable_steps") else "0" if st else "-")
        mode = st.get("unstable_mode")  # runs made before the mode was computed have none
        if mode and mode.get("found"):
            unstable += "; mode: lambda %.3g Pa/m^2 (%d of %d negative), largest at (%s) mm, %.2g %% of V" % (
                mode["eigenvalues"][0], mode["negative"], len(mode["eigenvalues"]),
                ", ".join("%.1f" % (1e3 * c) for c in mode["peak_position"]),
                100.0 * mode["volume_share"])
        elif mode:
            unstable += "; no mode: " + mode.get("reason", "")
        material = st.get("material_ellipticity")  # runs before it was computed have none
        if material and "smallest" in material:
            unstable += "; law %s, smallest e %.3g mu" % (
                "strongly elliptic" if material["strongly_elliptic"] else
                "NOT elliptic at %d points" % material["not_elliptic"],
                material["smallest"]["smallest_over_shear_modulus"])
            if "near_mode" in material:
                unstable += " (%.3g mu near the mode)" % material["near_mode"]["smallest_over_shear_modulus"]
        elif material:
            unstable += "; ellipticity not assessed: " + material.get("reason", "")
        surface = st.get("surface_stability")  # runs before 2026-12-06 (fourth session) have none
        if surface and "smallest" in surface:
            unstable += "; free surface at the mode %s as a half-space (rho c^2 %.3g mu)" % (
                "stable" if surface["smallest"] > 0 else "WRINKLES",
                surface["smallest_over_shear_modulus"])
        elif surface:
            unstable += "; surface not assessed: " + surface.get("reason", "")
        work.append("| %s | %d | %d | %d | %d | %d (%.0f s) | %d (%.0e, %.0f s) | %s | %.0f s |" % (
            m, s["steps"], s["newton_iterations"], len(s["step_cuts"]), ls.get("cholesky_failures", 0),
            ls.get("lu_fallbacks", 0), ls.get("lu_seconds", 0.0),
            ls.get("shifted_factorizations", 0), ls.get("max_shift", 0.0),
            ls.get("shifted_seconds", 0.0), unstable, s["wall_seconds"]["total"]))
    width = []
    for h in WIDTH_HEIGHTS_MM:
        width += ["", "z = %g mm:" % h, "",
                  "| mesh | " + " | ".join("%+g..%+g" % (a, a + 2) for a in WIDTH_BINS_MM[:-1]) +
                  " |", "|---" * len(WIDTH_BINS_MM) + "|"]
        width += ["| %s | " % m + " | ".join(width_uy(dirs[m], h)) + " |" for m in args.meshes]
    report = os.path.join(args.out, "dao_mesh_study.md")
    with open(report, "w") as f:
        jaw = args.jaw + (" (%s Pa/m)" % args.jaw_stiffness if args.jaw == "elastic" else "")
        f.write("# DAO mouth corner, y at %s s (mm), jaw face %s\n\n" % (args.end or "0.2", jaw) +
                "\n".join(lines) +
                "\n\n## u_y on the centreline (mm)\n\n" + "\n".join(profile) +
                "\n\n## The end's y against time (mm)\n\n" + "\n".join(history) +
                "\n\n## u_y across the width (mm; x bins in mm)\n" + "\n".join(width) +
                "\n\n## Newton and linear-solver work\n\n" + "\n".join(work) + "\n")
    print(report)


if __name__ == "__main__":
    main()
