#!/usr/bin/env python3
"""Run-time study of the isogeometric solver: a scene at several refinements, one CSV row each.

For every scene (the barrel's passive stretch, examples/barrel/passive.toml, and Cook's membrane,
examples/cook/*.toml when present) and every knot-insertion setting below, the scene is copied with
[geometry.refine] knot_insertion replaced, run with `isomuscle run --threads N`, and its
summary.json read back: DOFs, elements, steps, Newton iterations and the wall seconds per phase
(setup, assembly, factorisation, solve, output, total), plus the key results (max |u|, volume
change, the final value of every probe as probe:<name>) to see how they converge with refinement.

Usage: python3 validation/timing/run_timing.py [--exe build/release/app/isomuscle]
           [--out out/timing] [--threads 1] [--quick]
Writes OUT/timing.csv and prints it. Standard library only.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# knot_insertion per direction and scene (barrel: u around, v along, w radial; Cook: n - 1 new
# knots in u and v for n x n x 1 elements); degree elevation is the scene's own.
REFINEMENTS = {
    "barrel": [[0, 1, 0], [0, 3, 1], [1, 3, 1], [3, 5, 2], [3, 7, 3]],
    "cook": [[3, 3, 0], [7, 7, 0], [15, 15, 0], [31, 31, 0], [47, 47, 0]],
}
QUICK = {"barrel": [[0, 1, 0], [0, 3, 1]], "cook": [[3, 3, 0], [7, 7, 0]]}

COLUMNS = ["scene", "knot_insertion", "status", "elements", "dofs", "free_dofs", "steps",
           "newton_iterations", "newton_iterations_per_step", "setup_s", "assembly_s",
           "factorisation_s", "solve_s", "output_s", "total_s", "max_displacement_m",
           "volume_change_relative"]


def variant(scene_path, refine, folder):
    """The scene text with knot_insertion replaced and the IGES path made absolute."""
    with open(scene_path) as f:
        text = f.read()
    base = os.path.dirname(os.path.abspath(scene_path))

    def absolute(m):
        path = m.group(2)
        if not os.path.isabs(path):
            path = os.path.normpath(os.path.join(base, path))
        return m.group(1) + path + m.group(3)

    text = re.sub(r'^(iges\s*=\s*")([^"]+)(")', absolute, text, flags=re.M)
    line = "knot_insertion = [%d, %d, %d]" % tuple(refine)
    if re.search(r"^knot_insertion\s*=.*$", text, flags=re.M):
        text = re.sub(r"^knot_insertion\s*=.*$", line, text, flags=re.M)
    elif "[geometry.refine]" in text:
        text = text.replace("[geometry.refine]", "[geometry.refine]\n" + line, 1)
    else:
        raise SystemExit("%s: no [geometry.refine] table to vary" % scene_path)
    name = "%s-%d-%d-%d.toml" % ((os.path.splitext(os.path.basename(scene_path))[0],) +
                                 tuple(refine))
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def row_of(label, refine, summary):
    w = summary["wall_seconds"]
    v0, v1 = summary["volume_initial_m3"], summary["volume_final_m3"]
    steps = summary["steps"]
    return {
        "scene": label,
        "knot_insertion": " ".join(str(k) for k in refine),
        "status": summary["status"],
        "elements": summary["elements"],
        "dofs": summary["dofs"],
        "free_dofs": summary.get("free_dofs", ""),
        "steps": steps,
        "newton_iterations": summary["newton_iterations"],
        "newton_iterations_per_step": "%.2f" % (summary["newton_iterations"] / steps) if steps else "",
        "setup_s": "%.3f" % w["setup"],
        "assembly_s": "%.3f" % w["assembly"],
        "factorisation_s": "%.3f" % w["factorisation"],
        "solve_s": "%.3f" % w["solve"],
        "output_s": "%.3f" % w["output"],
        "total_s": "%.3f" % w["total"],
        "max_displacement_m": summary["max_displacement_m"],
        "volume_change_relative": "%.3e" % (v1 / v0 - 1.0) if v0 and v1 else "",
    } | {"probe:" + name: value for name, value in summary["probes"].items()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "release", "app", "isomuscle"))
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "timing"))
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--quick", action="store_true", help="two refinements only")
    args = parser.parse_args()
    if not os.access(args.exe, os.X_OK):
        raise SystemExit("no isomuscle executable at %s (build it, or pass --exe)" % args.exe)
    scenes = [("barrel-passive", os.path.join(ROOT, "examples", "barrel", "passive.toml"))]
    cook = os.path.join(ROOT, "examples", "cook")
    cook_scenes = sorted(f for f in os.listdir(cook) if f.endswith(".toml")) if os.path.isdir(cook) else []
    if cook_scenes:
        scenes.insert(0, ("cook-" + os.path.splitext(cook_scenes[0])[0],
                          os.path.join(cook, cook_scenes[0])))
    else:
        print("run_timing: no scene in examples/cook/, Cook's membrane skipped", file=sys.stderr)
    scene_dir = os.path.join(args.out, "scenes")
    os.makedirs(scene_dir, exist_ok=True)
    rows = []
    for label, scene in scenes:
        family = label.split("-")[0]
        for refine in (QUICK if args.quick else REFINEMENTS)[family]:
            path = variant(scene, refine, scene_dir)
            run_dir = os.path.join(args.out, "runs", os.path.splitext(os.path.basename(path))[0])
            result = subprocess.run([args.exe, "run", path, "--out", run_dir, "--threads",
                                     str(args.threads)], capture_output=True, text=True)
            summary_path = os.path.join(run_dir, "summary.json")
            if not os.path.exists(summary_path):
                print("run_timing: %s failed without a summary (exit %d):\n%s"
                      % (path, result.returncode, result.stderr), file=sys.stderr)
                continue
            with open(summary_path) as f:
                rows.append(row_of(label, refine, json.load(f)))
            print("run_timing: %s %s: %s s, %s DOFs" % (label, refine, rows[-1]["total_s"],
                                                      rows[-1]["dofs"]), file=sys.stderr)
    csv_path = os.path.join(args.out, "timing.csv")
    columns = COLUMNS + sorted({k for r in rows for k in r if k.startswith("probe:")})
    with open(csv_path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns, restval="")
        writer.writeheader()
        writer.writerows(rows)
    with open(csv_path) as f:
        sys.stdout.write(f.read())
    print("run_timing: written %s" % csv_path, file=sys.stderr)
    plot(rows, os.path.join(args.out, "timing.png"))


def plot(rows, path):
    """Seconds per phase against DOFs, one panel per scene (log-log). Needs matplotlib."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("run_timing: no matplotlib (use /usr/bin/python3): %s not drawn" % path,
              file=sys.stderr)
        return
    scenes = sorted({r["scene"] for r in rows})
    fig, axes = plt.subplots(1, len(scenes), figsize=(5.5 * len(scenes), 4.2), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        mine = sorted((r for r in rows if r["scene"] == scene), key=lambda r: r["dofs"])
        dofs = [r["dofs"] for r in mine]
        for phase in ["assembly_s", "factorisation_s", "solve_s", "output_s", "total_s"]:
            ax.loglog(dofs, [max(float(r[phase]), 1e-4) for r in mine], "o-",
                      label=phase[:-2], lw=2.0 if phase == "total_s" else 1.0)
        ax.set_xlabel("DOFs")
        ax.set_ylabel("wall seconds (whole run)")
        ax.set_title(scene)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print("run_timing: drew %s" % path, file=sys.stderr)


if __name__ == "__main__":
    main()
