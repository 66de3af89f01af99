#!/usr/bin/env python3
"""Run time against error: isogeometric analysis (p = 2, 3, 4) against 4- and 10-node tetrahedra.

For the barrel and the cone (examples/geometry), each under a passive stretch (lu2010 without
activation, the top pulled along the axis) and an active contraction (tang2009, Table 5.1, one end
fixed), the same scene is run
  * by IGA with degree p = 2, 3, 4 under h-refinement (knot spans doubled along and across the
    axis at each level; the four spans around the axis are kept: the load is axisymmetric), and
  * on 4-node (displacement formulation: the mixed one is the same on linear tetrahedra) and
    10-node tetrahedra (mixed u-p-J) at a sequence of element sizes,
each `--repeat` times (the median wall time counts). All runs take the same fixed time steps, so that they share the
time-integration error and the differences are those of the spatial discretisations. The
reference is the finest IGA run (its own convergence is in the table: the errors of the IGA runs
against it fall steadily with refinement).
Errors against the reference: the relative L2 difference of the final displacement fields
(`isomuscle compare REF RUN`), the tip displacement and, for the stretch, the pull force.

Writes OUT/study.csv, OUT/error_vs_time.png (log-log, one panel per case) and OUT/report.md with
the time each method needs to reach 1 % and 0.1 % L2 error (log-log interpolation between runs).

Usage: /usr/bin/python3 validation/run_time_error/run_study.py [--exe build/release/app/isomuscle]
           [--out validation/output/run_time_error] [--repeat 3] [--quick]
"""
import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GEOMETRY = os.path.join(ROOT, "examples", "geometry")

SHAPES = {
    # name: (IGES file, length along the axis in m)
    "barrel": ("barrel.igs", 0.05),
    "cone": ("cone.igs", 0.05),
}

PASSIVE = """description = "{shape} passive stretch (lu2010 without activation), run-time study"
{discretisation}
[geometry]
iges = "{iges}"
centreline = "v"
[geometry.refine]
degree_elevation = {elevation}
knot_insertion = {insertion}
[material]
model = "lu2010"
[material.parameters]
n2 = 0.0
[fibres]
mode = "constant"
vector = [0.0, 0.0, 1.0]
[[boundary]]
face = "v0"
type = "fixed"
[[boundary]]
face = "v1"
type = "displacement"
velocity = [0.0, 0.0, 0.005]
[time]
end = 0.4
dt = 0.05
adaptive = false
[solver]
threads = 1
[output]
times = [0.4]
fields = []
[[probe]]
name = "tip"
kind = "point_displacement"
point = [0.0, 0.0, {half_length}]
component = "z"
[[probe]]
name = "force"
kind = "face_reaction"
face = "v1"
component = "z"
{tet}"""

ACTIVE = """description = "{shape} active contraction (tang2009), run-time study"
{discretisation}
[geometry]
iges = "{iges}"
centreline = "v"
[geometry.refine]
degree_elevation = {elevation}
knot_insertion = {insertion}
[material]
model = "tang2009"
[fibres]
mode = "isocurve"
direction = "v"
[[boundary]]
face = "v0"
type = "fixed"
[time]
end = 0.05
dt = 0.0025
adaptive = false
[solver]
threads = 1
[output]
times = [0.05]
fields = []
[[probe]]
name = "tip"
kind = "point_displacement"
point = [0.0, 0.0, {length}]
component = "z"
{tet}"""

# Degree elevation of the (2, 2, 1) shrink solid for p = 2, 3, 4, and h-refinement levels: knot
# insertion [around, along, radial].
IGA_DEGREES = {2: [0, 0, 1], 3: [1, 1, 2], 4: [2, 2, 3]}
IGA_LEVELS = {2: [[0, 1, 0], [0, 3, 1], [0, 7, 3], [0, 15, 7]],
              3: [[0, 1, 0], [0, 3, 1], [0, 7, 3]],
              4: [[0, 1, 0], [0, 3, 1]]}
REFERENCE = (3, [0, 15, 7])  # p, knot insertion of the reference run
# Element sizes per shape and order (the cone, 4 cm across at the base, has ~2.5 times the barrel's
# tetrahedra at a size: its 10-node mesh at 3 mm has 24k DOFs and takes minutes).
TET_SIZES = {"barrel": {1: [0.004, 0.003, 0.002], 2: [0.005, 0.004, 0.003, 0.0025]},
             "cone": {1: [0.004, 0.003, 0.002], 2: [0.005, 0.004, 0.003]}}
QUICK_LEVELS = {2: [[0, 1, 0], [0, 3, 1]], 3: [[0, 1, 0]], 4: [[0, 1, 0]]}
QUICK_REFERENCE = (3, [0, 7, 3])
QUICK_SIZES = {"barrel": {1: [0.004, 0.003], 2: [0.005, 0.004]},
               "cone": {1: [0.004, 0.003], 2: [0.005, 0.004]}}


def scene_text(case, shape, method):
    """The scene of a run: method = ("iga", p, insertion) or ("tet", order, size)."""
    iges, length = SHAPES[shape]
    template = PASSIVE if case == "passive" else ACTIVE
    if method[0] == "iga":
        _, p, insertion = method
        return template.format(shape=shape, discretisation="", iges=os.path.join(GEOMETRY, iges),
                               elevation=IGA_DEGREES[p], insertion=insertion,
                               half_length=length / 2, length=length, tet="")
    _, order, size = method
    tet = "[tetrahedra]\nelement_size = %g\norder = %d\n" % (size, order)
    text = template.format(shape=shape, discretisation='discretisation = "tet"',
                           iges=os.path.join(GEOMETRY, iges), elevation=[0, 0, 0],
                           insertion=[0, 0, 0], half_length=length / 2, length=length, tet=tet)
    if order == 1:  # linear tetrahedra: the displacement formulation (mixed is the same, locking)
        text = text.replace("[solver]\n", '[solver]\nformulation = "displacement"\n')
    return text


def label(method):
    return ("iga-p%d-%s" % (method[1], "-".join(map(str, method[2]))) if method[0] == "iga"
            else "tet%d-h%g" % (4 if method[1] == 1 else 10, 1e3 * method[2]))


def run(exe, out, case, shape, method, repeat, reuse=False):
    """Runs the scene `repeat` times (median wall time); with reuse a finished run of the same
    scene text counts once, as it is."""
    name = "%s-%s-%s" % (shape, case, label(method))
    scene = os.path.join(out, "scenes", name + ".toml")
    os.makedirs(os.path.dirname(scene), exist_ok=True)
    text = scene_text(case, shape, method)
    with open(scene, "w") as f:
        f.write(text)
    walls = []
    run_dir = os.path.join(out, "runs", name)
    summary_path = os.path.join(run_dir, "summary.json")
    copy = os.path.join(run_dir, "scene.toml")
    if reuse and os.path.exists(summary_path) and os.path.exists(copy) and open(copy).read() == text:
        with open(summary_path) as f:
            summary = json.load(f)
        print("run_study: %s: reused" % name, file=sys.stderr)
        return {"name": name, "dir": run_dir, "summary": summary,
                "wall": summary["wall_seconds"]["total"]}
    for _ in range(repeat):
        subprocess.run([exe, "run", scene, "--out", run_dir], capture_output=True, text=True)
        with open(os.path.join(run_dir, "summary.json")) as f:
            summary = json.load(f)
        walls.append(summary["wall_seconds"]["total"])
    print("run_study: %s: %s, %d DOFs, %.2f s" % (name, summary["status"], summary["dofs"],
                                                  statistics.median(walls)), file=sys.stderr)
    return {"name": name, "dir": run_dir, "summary": summary, "wall": statistics.median(walls)}


def compare(exe, a, b):
    r = subprocess.run([exe, "compare", a, b, "--json"], capture_output=True, text=True)
    if r.returncode != 0:
        return None
    return json.loads(r.stdout)


def time_to_reach(points, target):
    """Wall time at which error falls to target, interpolated log-log along the refinement
    sequence (points sorted by wall time); None when never reached."""
    pts = sorted(points)
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e0 > target >= e1:
            w = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + w * (math.log(t1) - math.log(t0)))
    if pts and pts[0][1] <= target:
        return pts[0][0]
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "release", "app", "isomuscle"))
    parser.add_argument("--out", default=os.path.join(ROOT, "validation", "output", "run_time_error"))
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="two levels, a coarser reference")
    parser.add_argument("--reuse", action="store_true",
                        help="keep finished runs of unchanged scenes (their single wall time)")
    parser.add_argument("--coarse-cases", nargs="*", default=[],
                        help="cases run with the --quick ladder and reference (costly ones)")
    parser.add_argument("--cases", nargs="+", default=["barrel-passive", "barrel-active",
                                                       "cone-passive", "cone-active"])
    args = parser.parse_args()
    levels = QUICK_LEVELS if args.quick else IGA_LEVELS
    reference = QUICK_REFERENCE if args.quick else REFERENCE
    sizes = QUICK_SIZES if args.quick else TET_SIZES
    rows = []
    references = {}
    for case_name in args.cases:
        shape, case = case_name.split("-")
        coarse = case_name in args.coarse_cases
        case_levels = QUICK_LEVELS if coarse else levels
        case_reference = QUICK_REFERENCE if coarse else reference
        case_sizes = QUICK_SIZES if coarse else sizes
        references[case_name] = case_reference
        ref = run(args.exe, args.out, case, shape, ("iga",) + case_reference, 1, args.reuse)
        methods = [("iga", p, k) for p in IGA_DEGREES for k in case_levels[p]]
        methods += [("tet", order, h) for order in (1, 2) for h in case_sizes[shape][order]]
        ref_probes = ref["summary"]["probes"]
        for m in methods:
            r = run(args.exe, args.out, case, shape, m, args.repeat, args.reuse)
            s = r["summary"]
            c = compare(args.exe, ref["dir"], r["dir"]) if s["status"] == "converged" else None
            row = {"case": case_name, "method": "iga" if m[0] == "iga" else "tet%d" %
                   (4 if m[1] == 1 else 10), "degree_or_order": m[1],
                   "refinement": "-".join(map(str, m[2])) if m[0] == "iga" else "%g" % m[2],
                   "status": s["status"], "dofs": s["dofs"], "steps": s["steps"],
                   "newton_iterations": s["newton_iterations"], "wall_s": r["wall"],
                   "l2_error": c["relative_l2_difference"] if c else float("nan"),
                   "max_error": c["relative_max_difference"] if c else float("nan")}
            for probe in ("tip", "force"):
                if probe in ref_probes and ref_probes[probe] is not None and s["probes"].get(probe) is not None:
                    row[probe + "_error"] = abs(s["probes"][probe] / ref_probes[probe] - 1.0)
            rows.append(row)
    columns = []
    for r in rows:
        columns += [k for k in r if k not in columns]
    with open(os.path.join(args.out, "study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, restval="")
        w.writeheader()
        w.writerows(rows)
    plot(rows, os.path.join(args.out, "error_vs_time.png"))
    report(rows, args, references)


def series(rows, case):
    """(method label, [(wall, l2 error)]) per method of a case."""
    out = {}
    for r in rows:
        if r["case"] != case or not (r["l2_error"] > 0):
            continue
        key = "IGA p=%d" % r["degree_or_order"] if r["method"] == "iga" else r["method"]
        out.setdefault(key, []).append((r["wall_s"], r["l2_error"]))
    return out


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cases = sorted({r["case"] for r in rows})
    fig, axes = plt.subplots(1, len(cases), figsize=(5 * len(cases), 4.2), squeeze=False)
    for ax, case in zip(axes[0], cases):
        for key, pts in sorted(series(rows, case).items()):
            pts = sorted(pts)
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=key)
        for target in (1e-2, 1e-3):
            ax.axhline(target, color="0.7", lw=0.8, ls="--")
        ax.set_xlabel("wall seconds (median)")
        ax.set_ylabel("relative L2 error of u")
        ax.set_title(case)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def report(rows, args, references):
    lines = ["# Run time against error (`validation/run_time_error/run_study.py`)", "",
             "References (the finest IGA run of each case): " +
             "; ".join("%s: p = %d, knot insertion %s" % (c, r[0], r[1])
                       for c, r in references.items()) +
             ". Errors are relative to them; wall times are the median of %d runs on this machine "
             "(one thread)." % args.repeat, "", "![error against time](error_vs_time.png)",
             "", "## Time to reach a relative L2 error", "",
             "| case | method | 1 % | 0.1 % |", "|---|---|---|---|"]
    for case in sorted({r["case"] for r in rows}):
        for key, pts in sorted(series(rows, case).items()):
            t1, t2 = time_to_reach(pts, 1e-2), time_to_reach(pts, 1e-3)
            lines.append("| %s | %s | %s | %s |" % (case, key, "%.2f s" % t1 if t1 else "not reached",
                                                   "%.2f s" % t2 if t2 else "not reached"))
    lines += ["", "## Runs", "", "| case | method | p / order | refinement | DOFs | steps | Newton | "
              "wall s | L2 error | max error | tip error | force error |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %s | %s | %s | %d | %d | %d | %.2f | %.2e | %.2e | %s | %s |" % (
            r["case"], r["method"], r["degree_or_order"], r["refinement"], r["dofs"], r["steps"],
            r["newton_iterations"], r["wall_s"], r["l2_error"], r["max_error"],
            "%.2e" % r["tip_error"] if "tip_error" in r else "",
            "%.2e" % r["force_error"] if "force_error" in r else ""))
    with open(os.path.join(args.out, "report.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("run_study: wrote %s" % os.path.join(args.out, "report.md"), file=sys.stderr)


if __name__ == "__main__":
    main()
