"""Where the mode of a run's first unstable equilibrium sits (unstable_mode.csv, README.md "Solver").

Prints a Markdown table of the mode along one axis of the reference configuration, in equal bins:
the nodes in the bin, the largest nodal amplitude (the file scales the largest to 1), the bin's
share of the mode's mass-weighted square (sum of volume * |mode|^2; the file's volume column),
the share of that square in each displacement component, and the eigenvalues from summary.json.
A mode that buckles the body as a whole spreads over many bins; one of a singular layer (a
clamped edge) crowds into the bin next to it.

Usage: /usr/bin/python3 validation/suite/mode_profile.py RUN_DIR [--axis x|y|z] [--bins N]
       [--distance-to X,Y,Z]   (bins of the distance to a point instead of a coordinate, mm)
       [--nodes-near X,Z --within R]   (then also: the nodes within R mm of the line through
                                        (X, ., Z) along y, by z and y, with their mode vectors)
"""
import argparse
import json
import os
import sys

import numpy as np


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir")
    parser.add_argument("--axis", choices=["x", "y", "z"], default="z")
    parser.add_argument("--bins", type=int, default=10)
    parser.add_argument("--distance-to", default=None,
                        help="X,Y,Z in mm: bin by the distance to this point")
    parser.add_argument("--nodes-near", default=None,
                        help="X,Z in mm: list the nodes near the line along y through (X, Z)")
    parser.add_argument("--within", type=float, default=0.5, help="mm, for --nodes-near")
    args = parser.parse_args()
    path = os.path.join(args.run_dir, "unstable_mode.csv")
    if not os.path.exists(path):
        sys.exit("%s: no unstable_mode.csv (the run reached no unstable equilibrium)" % args.run_dir)
    d = np.genfromtxt(path, delimiter=",", names=True)
    if "volume" not in d.dtype.names:
        sys.exit("%s has no volume column (written by a build before the column existed); rerun "
                 "the scene" % path)
    X = np.stack([d["x"], d["y"], d["z"]], axis=1) * 1e3  # mm
    m = np.stack([d["mode_x"], d["mode_y"], d["mode_z"]], axis=1)
    volume = d["volume"]
    if args.distance_to:
        centre = np.array([float(c) for c in args.distance_to.split(",")])
        coordinate = np.linalg.norm(X - centre, axis=1)
        label = "distance to (%s) mm" % args.distance_to
    else:
        coordinate = X[:, "xyz".index(args.axis)]
        label = "%s (mm)" % args.axis
    weighted = volume[:, None] * m**2  # per component
    total = weighted.sum()
    edges = np.linspace(coordinate.min(), coordinate.max(), args.bins + 1)
    which = np.clip(np.searchsorted(edges, coordinate, side="right") - 1, 0, args.bins - 1)

    summary = json.load(open(os.path.join(args.run_dir, "summary.json")))
    mode = summary.get("stability", {}).get("unstable_mode", {})
    if mode.get("found"):
        print("t = %.5g s: eigenvalues %s Pa/m^2, largest at (%s) mm, %.2g %% of the volume" % (
            mode["time"], ", ".join("%.4g" % v for v in mode["eigenvalues"]),
            ", ".join("%.2f" % (1e3 * c) for c in mode["peak_position"]),
            100.0 * mode["volume_share"]))
    print()
    print("| %s | nodes | largest amplitude | share of V·|mode|² | of it in x / y / z |" % label)
    print("|---|---|---|---|---|")
    for b in range(args.bins):
        inside = which == b
        if not inside.any():
            continue
        w = weighted[inside].sum(axis=0)
        print("| %.2f–%.2f | %d | %.3f | %.1f %% | %.0f / %.0f / %.0f %% |" % (
            edges[b], edges[b + 1], inside.sum(), np.linalg.norm(m[inside], axis=1).max(),
            100.0 * w.sum() / total, *(100.0 * w / max(w.sum(), 1e-300))))

    if args.nodes_near:
        x0, z0 = (float(c) for c in args.nodes_near.split(","))
        near = np.where(np.hypot(X[:, 0] - x0, X[:, 2] - z0) <= args.within)[0]
        near = near[np.lexsort((X[near, 1], X[near, 2]))]
        print()
        print("| x, y, z (mm) | mode_x | mode_y | mode_z |")
        print("|---|---|---|---|")
        for i in near:
            print("| %.2f, %.2f, %.2f | %+.3f | %+.3f | %+.3f |" % (*X[i], *m[i]))


if __name__ == "__main__":
    main()
