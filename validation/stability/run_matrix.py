#!/usr/bin/env python3
"""The robustness matrix (issue #7): the solver swept across the settings where it could break.

Four base runs -- the barrel and the half torus, each with the chapter-3 muscle (lu2010, Table
3.10) and the chapter-5 muscle (tang2009, Table 5.1), an isometric-start contraction with one end
fixed (examples/*/contract.toml) -- and, one factor at a time from each base, the cells

  compressibility  D = 1e-6, 1e-8, 1e-10, 1e-12 m^2/N, mixed and displacement formulation
  activation       level n2 = 0.1, 0.5, 1 x rate S = 10, 100, 1000 1/s (exponential onset 3.26)
  time step        fixed dt = 1e-4, 1e-3, 0.01, 0.05 s, and adaptive from 1e-3 up to 0.05 s
  refinement       degree 2, 3, 4; knot-insertion levels 0-3; knots concentrated at the axis
  large strain     passive stretch (activation off) to 10, 20, 40 %; contraction with 4 sigma0
  Hill tangent     consistent against the thesis's frozen-CE tangent (5.54 / 5.47)
  tetrahedra       (barrel) 10-node mixed, also at D = 1e-12 and stretched 40 %; 4-node

Each cell is a scene written from the base (OUT/cells/BASE/CELL/cell.toml), run by `isomuscle run` under a wall-time
limit, and read back from its summary.json, probes.csv and solution.h5. Recorded per cell: status
and the reason in words, Newton iterations per step, step cuts, CHOLMOD's smallest rcond, the
smallest J = det F over the quadrature points of the converged states, the volume change, the
wall time, and the checks that make a failure a *clear* one: the process exited (no signal, no
hang: the limit), no NaN/inf in any number it wrote, a failed run says why and keeps its last
converged state in solution.h5.

Writes OUT/matrix.csv, OUT/matrix.png (heat map), OUT/summary.md. Exit status 1 when any cell
failed unclearly (a crash, a hang, NaN in the outputs, a failure without reason or without its
last state); a cell that fails clearly is a result, not an error.

Usage: /usr/bin/python3 validation/stability/run_matrix.py [--exe build/release/app/isomuscle]
           [--out validation/output/stability] [--small] [--only barrel/tang2009 ...]
           [--axes compressibility ...] [--limit 900] [--reuse]
--small is the CI version: six cells on a coarse barrel, a short limit.
Needs numpy, matplotlib and h5py (Debian python3-numpy python3-matplotlib python3-h5py).
"""
import argparse
import copy
import csv
import json
import math
import os
import signal
import subprocess
import sys
import time
import tomllib

GRACE = 120.0  # s a stopped run may take to finish its step and write its results
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXAMPLES = os.path.join(ROOT, "examples")

# ---------------------------------------------------------------------------------------------
# Scenes: read a committed scene, change it, write it back (TOML subset of the scene format).


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {toml_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"no TOML form for {v!r}")


def toml_text(table, prefix=""):
    """Scalars first, then sub-tables [a.b], then arrays of tables [[a]] (the scene layout)."""
    lines, subs, arrays = [], [], []
    for k, v in table.items():
        if isinstance(v, dict):
            subs.append((k, v))
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            arrays.append((k, v))
        else:
            lines.append(f"{k} = {toml_value(v)}")
    out = "\n".join(lines) + ("\n" if lines else "")
    for k, v in subs:
        name = f"{prefix}{k}"
        out += f"\n[{name}]\n" + toml_text(v, name + ".")
    for k, items in arrays:
        for item in items:
            out += f"\n[[{prefix}{k}]]\n" + "\n".join(
                f"{a} = {toml_value(b)}" for a, b in item.items()) + "\n"
    return out


def load_scene(relative):
    path = os.path.join(EXAMPLES, relative)
    with open(path, "rb") as f:
        scene = tomllib.load(f)
    scene["geometry"]["iges"] = os.path.normpath(
        os.path.join(os.path.dirname(path), scene["geometry"]["iges"]))
    return scene


def params(scene):
    return scene["material"].setdefault("parameters", {})


def refine(scene):
    return scene["geometry"].setdefault("refine", {})


# ---------------------------------------------------------------------------------------------
# The bases. The half torus runs on 4 x 4 x 2 elements (its example has 4 x 8 x 2), the barrel on
# the uniform 4 x 4 x 2 (its example is graded towards the clamped end, 4 x 8 x 4 since
# 2026-12-02; the matrix was measured on the uniform mesh): the matrix asks where the solver
# breaks, not for the converged shape, and 36 cells per base must fit.

def base_scene(shape, law):
    scene = load_scene(f"{shape}/contract.toml")
    scene["material"] = {"model": law}
    if shape == "half_torus":
        refine(scene)["knot_insertion"] = [0, 1, 1]
    if shape == "barrel":
        refine(scene)["knot_insertion"] = [0, 3, 1]
        refine(scene).pop("knots", None)
    scene["output"] = {"times": [scene["time"]["end"]]}  # no fields: only the probes and the end
    scene["solver"]["threads"] = 1
    return scene


BASES = [("barrel", "tang2009"), ("barrel", "lu2010"), ("half_torus", "tang2009"),
         ("half_torus", "lu2010")]

# The free end (face v1) and its pull direction for the passive stretch cells.
FREE_END = {"barrel": ([0.0, 0.0, 1.0], 0.05),           # axis z, length 5 cm
            "half_torus": ([0.0, -1.0, 0.0], math.pi * 0.01)}  # tangent at (-1 cm, 0, 0), arc


def set_activation(scene, level, rate):
    p = params(scene)
    p["n2"] = level
    p["S"] = float(rate)
    if scene["material"]["model"] == "tang2009":
        p["ramp_time"] = 0.0  # S drives the onset only without the linear ramp (Table 5.1)


def set_fixed_dt(scene, dt):
    t = scene["time"]
    t["dt"] = dt
    t["dt_max"] = dt
    t["dt_min"] = dt / 1024.0
    t["adaptive"] = False
    if dt < 1e-3:
        t["end"] = 0.02  # 200 steps: the activation onset and the first shortening
        scene["output"] = {"times": [0.02]}


def set_degree(scene, p):
    # The shrink solid is (2, 2, 1) before refinement (radial degree 1); the base elevates w to 2.
    refine(scene)["degree_elevation"] = [p - 2, p - 2, p - 1]


def set_level(scene, shape, level):
    # Knot spans (around, along, radial) per level; level 1 is the base (32 elements).
    spans = [(4, 2, 1), (4, 4, 2), (8, 8, 2), (8, 8, 4)][level]
    unrefined = {"barrel": (4, 1, 1), "half_torus": (4, 2, 1)}[shape]  # spans before refinement
    refine(scene)["knot_insertion"] = [s // u - 1 for s, u in zip(spans, unrefined)]
    return "x".join(map(str, spans))


def set_stretch(scene, shape, strain):
    params(scene)["n2"] = 0.0  # passive
    direction, length = FREE_END[shape]
    speed = strain * length  # over 1 s
    scene["boundary"].append({"face": "v1", "type": "displacement",
                              "components": ["x", "y", "z"],
                              "velocity": [speed * d for d in direction]})
    scene["time"] = {"end": 1.0, "dt": 0.05, "dt_max": 0.05, "adaptive": True}
    scene["output"] = {"times": [1.0]}


def cells_for(shape, law):
    """(axis, label, formulation, change) for one base; change(scene) edits a copy of it."""
    cells = [("base", "base", "mixed", lambda s: None)]
    for D in (1e-6, 1e-8, 1e-10, 1e-12):
        for form in ("mixed", "displacement"):
            def change(s, D=D, form=form):
                params(s)["D"] = D
                s["solver"]["formulation"] = form
            cells.append(("compressibility", f"D={D:g} {form[:4]}", form, change))
    for level in (0.1, 0.5, 1.0):
        for rate in (10, 100, 1000):
            cells.append(("activation", f"a={level:g} S={rate}", "mixed",
                          lambda s, a=level, r=rate: set_activation(s, a, r)))
    for dt in (1e-4, 1e-3, 0.01, 0.05):
        cells.append(("time step", f"dt={dt:g} fixed", "mixed",
                      lambda s, dt=dt: set_fixed_dt(s, dt)))
    cells.append(("time step", "adaptive 1e-3..0.05", "mixed",
                  lambda s: s["time"].update({"dt": 1e-3, "dt_max": 0.05, "adaptive": True})))
    for p in (2, 3, 4):
        cells.append(("refinement", f"p={p}", "mixed", lambda s, p=p: set_degree(s, p)))
    for level in (0, 1, 2, 3):
        spans = set_level(load_scene(f"{shape}/contract.toml"), shape, level)
        cells.append(("refinement", f"level {level} ({spans})", "mixed",
                      lambda s, lv=level: set_level(s, shape, lv)))
    cells.append(("refinement", "axis-graded w", "mixed",
                  lambda s: refine(s).update({"knots": {"w": [0.9, 0.97, 0.99]}})))
    for strain in (0.1, 0.2, 0.4):
        cells.append(("large strain", f"stretch {strain:.0%}", "mixed",
                      lambda s, e=strain: set_stretch(s, shape, e)))
    cells.append(("large strain", "contraction 4 sigma0", "mixed",
                  lambda s: params(s).update({"sigma0": 4 * {"tang2009": 2.2e5,
                                                             "lu2010": 7.0e5}[law]})))
    cells.append(("Hill tangent", "frozen CE", "mixed",
                  lambda s: s["solver"].update({"tangent": "frozen_ce"})))
    if shape == "barrel":
        # The tetrahedral module on the same scene (examples/barrel/contract-tet.toml's mesh).
        def tet(s, order=2):
            s["discretisation"] = "tet"
            s["tetrahedra"] = {"element_size": 0.004, "order": order}
        cells.append(("tetrahedra", "tet10", "mixed", tet))
        cells.append(("tetrahedra", "tet10 D=1e-12", "mixed",
                      lambda s: (tet(s), params(s).update({"D": 1e-12}))))
        cells.append(("tetrahedra", "tet10 stretch 40%", "mixed",
                      lambda s: (tet(s), set_stretch(s, shape, 0.4))))
        cells.append(("tetrahedra", "tet4", "mixed", lambda s: tet(s, 1)))
    return cells


def small_cells():
    """The CI version: a coarse barrel (8 elements) at the corners where things break."""
    def coarse(s):
        refine(s)["knot_insertion"] = [0, 1, 0]
    picks = []

    def add(label, form, change):
        picks.append(("barrel", "tang2009", "small", label, form,
                      lambda s: (coarse(s), change(s))))
    add("D=1e-12 disp", "displacement",
        lambda s: (params(s).update({"D": 1e-12}), s["solver"].update(
            {"formulation": "displacement"})))
    add("D=1e-12 mixed", "mixed", lambda s: params(s).update({"D": 1e-12}))
    add("dt=0.05 fixed", "mixed", lambda s: set_fixed_dt(s, 0.05))
    add("a=1 S=1000", "mixed", lambda s: set_activation(s, 1.0, 1000))
    add("stretch 40%", "mixed", lambda s: set_stretch(s, "barrel", 0.4))
    add("frozen CE", "mixed", lambda s: s["solver"].update({"tangent": "frozen_ce"}))
    return picks


# ---------------------------------------------------------------------------------------------
# Running a cell and reading what it left.

def non_finite_in_csv(path):
    if not os.path.exists(path):
        return False
    with open(path) as f:
        for row in csv.reader(f):
            for x in row:
                if x.strip().lower() in ("nan", "-nan", "inf", "-inf", "+inf"):
                    return True
    return False


def non_finite_in_json(x):
    if isinstance(x, float):
        return not math.isfinite(x)
    if isinstance(x, dict):
        return any(non_finite_in_json(v) for v in x.values())
    if isinstance(x, list):
        return any(non_finite_in_json(v) for v in x)
    return False


def solution_steps(path):
    """(output steps in solution.h5, whether all its reals are finite); (0, True) without one: a
    missing file is not a NaN (a failure that loses its last state is caught by clear_failure)."""
    import h5py
    import numpy as np
    if not os.path.exists(path):
        return 0, True
    with h5py.File(path, "r") as f:
        finite = True

        def visit(name, obj):
            nonlocal finite
            if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f":
                finite = finite and bool(np.all(np.isfinite(obj[()])))
        f.visititems(visit)
        return sum(1 for key in f.keys() if key.startswith("step_")), finite


def run_cell(exe, scene, out_dir, limit):
    os.makedirs(out_dir, exist_ok=True)
    scene_path = os.path.join(out_dir, "cell.toml")
    with open(scene_path, "w") as f:
        f.write(toml_text(scene))
    start = time.monotonic()
    proc = subprocess.Popen([exe, "run", scene_path, "--out", os.path.join(out_dir, "run")],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    # At the limit: SIGTERM, which `isomuscle run` answers by stopping after the step under way
    # with its summary and results written ("interrupted"); SIGKILL only when it does not stop
    # within GRACE seconds (a hang inside a step).
    stopped = killed = False
    try:
        out, err = proc.communicate(timeout=limit)
    except subprocess.TimeoutExpired:
        stopped = True
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            out, err = proc.communicate(timeout=GRACE)
        except subprocess.TimeoutExpired:
            killed = True
            os.killpg(proc.pid, signal.SIGKILL)
            out, err = proc.communicate()
    wall = time.monotonic() - start
    with open(os.path.join(out_dir, "stderr.txt"), "w") as f:
        f.write(err)
    return {"returncode": proc.returncode, "hung": killed, "stopped": stopped, "wall": wall,
            "stderr": err}


def read_cell(out_dir, proc):
    run = os.path.join(out_dir, "run")
    row = {"exit": proc["returncode"], "hung": proc["hung"], "stopped": proc.get("stopped", False),
           "process_seconds": proc["wall"]}
    summary_path = os.path.join(run, "summary.json")
    s = None
    if os.path.exists(summary_path):
        with open(summary_path) as f:
            text = f.read()
        s = json.loads(text)
        row["nan_in_outputs"] = non_finite_in_json(s) or "NaN" in text
    else:
        row["nan_in_outputs"] = False
    row["nan_in_outputs"] = row["nan_in_outputs"] or non_finite_in_csv(
        os.path.join(run, "probes.csv")) or non_finite_in_csv(os.path.join(run, "newton.csv"))
    steps_kept, h5_finite = solution_steps(os.path.join(run, "solution.h5"))
    row["nan_in_outputs"] = row["nan_in_outputs"] or not h5_finite
    row["solution_steps"] = steps_kept
    if s is None:
        lines = proc["stderr"].strip().splitlines()
        row.update(status="no summary", reason=lines[-1] if lines else "")
        return row
    row["status"] = s["status"]
    row["reason"] = s.get("reason") or ""
    if row["stopped"] and "interrupted" in row["reason"]:
        row["status"] = "time limit"  # stopped at the matrix's limit, still progressing
    row["steps"] = s["steps"]
    row["newton_iterations"] = s["newton_iterations"]
    row["iterations_per_step"] = s["newton_iterations"] / s["steps"] if s["steps"] else None
    row["step_cuts"] = len(s["step_cuts"])
    row["min_rcond"] = (s.get("linear_solver_statistics") or {}).get("min_rcond")
    ls = s.get("linear_solver_statistics") or {}
    row["lu_fallbacks"] = ls.get("lu_fallbacks")
    # Cholesky failures: the tangents found indefinite, whatever the response (the LU fallbacks of
    # runs before [solver] indefinite_tangent, 2026-12-05, counted the same).
    row["indefinite_tangents"] = ls.get("cholesky_failures")
    row["shifted_factorizations"] = ls.get("shifted_factorizations")
    mj = s.get("min_jacobian")
    row["min_J"] = mj["value"] if mj else None
    vi, vf = s.get("volume_initial_m3"), s.get("volume_final_m3")
    row["volume_change"] = (vf - vi) / vi if vi and vf is not None else None
    row["wall_seconds"] = s["wall_seconds"]["total"]
    row["time_reached"] = s["time"]["reached"]
    row["time_end"] = s["time"]["end"]
    row["dofs"] = s["dofs"]
    row["max_displacement"] = s.get("max_displacement_m")
    return row


def clear_failure(row):
    """'' when the cell converged or failed clearly; else what is unclear about it."""
    problems = []
    if row["hung"]:
        problems.append("hung (killed at the limit)")
    elif row["exit"] is None or row["exit"] < 0:
        problems.append(f"killed by signal {-row['exit'] if row['exit'] else '?'}")
    elif row["exit"] not in (0, 1):
        problems.append(f"exit code {row['exit']}")
    if row.get("nan_in_outputs"):
        problems.append("NaN or inf in the outputs")
    status = row.get("status")
    if status == "time limit" and row["exit"] != 1:
        problems.append(f"exit code {row['exit']} after SIGTERM")
    if status == "failed":
        if not row.get("reason"):
            problems.append("failed without a reason")
        if row.get("steps", 0) > 0 and row.get("solution_steps", 0) == 0:
            problems.append("last converged state not in solution.h5")
        if row["exit"] == 0:
            problems.append("exit code 0 for a failed run")
    elif status == "converged":
        if row["exit"] != 0:
            problems.append(f"converged but exit code {row['exit']}")
    elif status != "time limit" and not row["hung"]:
        problems.append(f"status {status!r}")
    return "; ".join(problems)


FIELDS = ["base", "axis", "cell", "formulation", "status", "clear", "reason", "steps",
          "newton_iterations", "iterations_per_step", "step_cuts", "lu_fallbacks",
          "indefinite_tangents", "shifted_factorizations", "min_rcond",
          "min_J", "volume_change", "max_displacement", "wall_seconds", "time_reached", "time_end", "dofs", "exit",
          "stopped", "hung", "nan_in_outputs", "solution_steps"]


def write_csv(rows, path):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in FIELDS})


# ---------------------------------------------------------------------------------------------
# Figure and summary.

def heat_map(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    bases = list(dict.fromkeys(r["base"] for r in rows))
    cells = list(dict.fromkeys((r["axis"], r["cell"]) for r in rows))
    grid = [[math.nan] * len(bases) for _ in cells]
    text = [[""] * len(bases) for _ in cells]
    for r in rows:
        i, j = cells.index((r["axis"], r["cell"])), bases.index(r["base"])
        if r["clear"]:
            grid[i][j], text[i][j] = 3, "!"
        elif r.get("status") == "converged":
            grid[i][j] = 1 if r.get("step_cuts") else 0
            text[i][j] = f"{r['iterations_per_step']:.1f}" if r.get("iterations_per_step") else ""
        else:
            grid[i][j] = 4 if r.get("status") == "time limit" else 2
            text[i][j] = f"{r.get('time_reached', 0):.3g}s"
    fig, ax = plt.subplots(figsize=(2.0 + 1.6 * len(bases), 0.8 + 0.26 * len(cells)))
    cmap = ListedColormap(["#4daf4a", "#ffd92f", "#e41a1c", "#000000", "#999999"])
    ax.imshow(grid, cmap=cmap, vmin=-0.5, vmax=4.5, aspect="auto")
    for i in range(len(cells)):
        for j in range(len(bases)):
            ax.text(j, i, text[i][j], ha="center", va="center", fontsize=7,
                    color="white" if grid[i][j] in (2, 3) else "black")
    ax.set_xticks(range(len(bases)), bases, fontsize=8)
    ax.set_yticks(range(len(cells)), [f"{a}: {c}" for a, c in cells], fontsize=7)
    ax.set_title("robustness matrix: green converged (Newton its/step), yellow converged after "
                 "cuts,\nred failed clearly, grey stopped at the time limit (model time "
                 "reached), black failed unclearly", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def fraction(rows, pred):
    sel = [r for r in rows if pred(r)]
    ok = sum(1 for r in sel if r.get("status") == "converged")
    return ok, len(sel)


def write_summary(rows, path, command):
    lines = ["# Robustness matrix: generated summary", "",
             f"Regenerate: `{command}`", ""]
    ok, n = fraction(rows, lambda r: True)
    unclear = [r for r in rows if r["clear"]]
    lines.append(f"{ok} of {n} cells converge; {len(unclear)} fail unclearly "
                 "(crash, hang, NaN, no reason, last state lost).")
    lines.append("")
    lines.append("| formulation | converged | cells |")
    lines.append("|---|---|---|")
    for form in sorted(set(r["formulation"] for r in rows)):
        ok, n = fraction(rows, lambda r, f=form: r["formulation"] == f)
        lines.append(f"| {form} | {ok} | {n} |")
    lines.append("")
    lines.append("| axis | base | converged | cells |")
    lines.append("|---|---|---|---|")
    for axis in dict.fromkeys(r["axis"] for r in rows):
        for base in dict.fromkeys(r["base"] for r in rows):
            ok, n = fraction(rows, lambda r, a=axis, b=base: r["axis"] == a and r["base"] == b)
            if n:
                lines.append(f"| {axis} | {base} | {ok} | {n} |")
    lines.append("")
    lines.append("## Cells that did not converge")
    lines.append("")
    lines.append("| base | cell | reached / end (s) | steps | cuts | reason |")
    lines.append("|---|---|---|---|---|---|")
    for r in rows:
        if r.get("status") != "converged":
            reason = (r.get("reason") or r["clear"]).replace("|", "/")
            if len(reason) > 300:
                reason = reason[:300] + " ..."
            lines.append(f"| {r['base']} | {r['cell']} | {r.get('time_reached', '')} / "
                         f"{r.get('time_end', '')} | {r.get('steps', '')} | "
                         f"{r.get('step_cuts', '')} | {reason} |")
    lines.append("")
    lines.append("## Extremes over the converged cells")
    lines.append("")
    conv = [r for r in rows if r.get("status") == "converged"]
    for key, label in (("min_J", "smallest J"), ("min_rcond", "smallest rcond"),
                       ("iterations_per_step", "most Newton iterations per step"),
                       ("step_cuts", "most step cuts")):
        vals = [r for r in conv if r.get(key) is not None]
        if not vals:
            continue
        pick = (min if key in ("min_J", "min_rcond") else max)(vals, key=lambda r: r[key])
        lines.append(f"* {label}: {pick[key]:.3g} ({pick['base']}, {pick['cell']})")
    worst_dv = max((r for r in conv if r.get("volume_change") is not None),
                   key=lambda r: abs(r["volume_change"]), default=None)
    if worst_dv:
        lines.append(f"* largest |dV/V|: {abs(worst_dv['volume_change']):.3g} "
                     f"({worst_dv['base']}, {worst_dv['cell']})")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


# ---------------------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--exe", default=os.path.join(ROOT, "build/release/app/isomuscle"))
    ap.add_argument("--out", default=os.path.join(ROOT, "validation/output/stability"))
    ap.add_argument("--small", action="store_true", help="the CI version (six cells)")
    ap.add_argument("--only", nargs="*", help="bases as shape/law, e.g. barrel/tang2009")
    ap.add_argument("--axes", nargs="*", help="only these axes (base always runs)")
    ap.add_argument("--limit", type=float, default=900.0, help="wall seconds per cell")
    ap.add_argument("--reuse", action="store_true", help="keep cells whose summary exists")
    args = ap.parse_args()
    exe = os.path.abspath(args.exe)
    if not os.path.exists(exe):
        sys.exit(f"run_matrix: no isomuscle at {exe} (build with scripts/build.sh release)")
    os.makedirs(args.out, exist_ok=True)

    work = []
    if args.small:
        work = small_cells()
    else:
        for shape, law in BASES:
            if args.only and f"{shape}/{law}" not in args.only:
                continue
            for axis, label, form, change in cells_for(shape, law):
                if args.axes and axis not in args.axes and axis != "base":
                    continue
                work.append((shape, law, axis, label, form, change))

    rows = []
    for n, (shape, law, axis, label, form, change) in enumerate(work, 1):
        scene = copy.deepcopy(base_scene(shape, law))
        change(scene)
        base = f"{shape}/{law}"
        slug = "".join(c if c.isalnum() else "_" for c in f"{axis}_{label}")
        out_dir = os.path.join(args.out, "cells", shape + "_" + law, slug)
        if args.reuse and os.path.exists(os.path.join(out_dir, "run", "summary.json")) and \
                os.path.exists(os.path.join(out_dir, "process.json")):
            with open(os.path.join(out_dir, "process.json")) as f:
                proc = json.load(f)
        else:
            proc = run_cell(exe, scene, out_dir, args.limit)
            with open(os.path.join(out_dir, "process.json"), "w") as f:
                json.dump(proc, f)
        row = read_cell(out_dir, proc)
        row.update(base=base, axis=axis, cell=label, formulation=form)
        row["clear"] = clear_failure(row)
        rows.append(row)
        print(f"[{n}/{len(work)}] {base:20s} {axis:15s} {label:24s} {row.get('status', '?'):9s} "
              f"its/step {row.get('iterations_per_step') or 0:5.2f} cuts {row.get('step_cuts', 0):3d} "
              f"minJ {row.get('min_J') or 0:.3g} {row['process_seconds']:7.1f} s "
              f"{'UNCLEAR: ' + row['clear'] if row['clear'] else ''}", flush=True)
        write_csv(rows, os.path.join(args.out, "matrix.csv"))

    command = "/usr/bin/python3 validation/stability/run_matrix.py" + (" --small" if args.small
                                                                       else "")
    write_summary(rows, os.path.join(args.out, "summary.md"), command)
    heat_map(rows, os.path.join(args.out, "matrix.png"))
    unclear = [r for r in rows if r["clear"]]
    ok, n = fraction(rows, lambda r: True)
    print(f"{ok} of {n} cells converged; {len(unclear)} failed unclearly; "
          f"written {args.out}/matrix.csv, matrix.png, summary.md")
    return 1 if unclear else 0


if __name__ == "__main__":
    sys.exit(main())
