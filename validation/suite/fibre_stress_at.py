"""Cauchy stress along the fibre in the cells of a run's field output near a reference point.

Reads fields.h5 (needs the fields "displacement", "cauchy_stress", "J" and "fibre") at its last
output time, finds the tessellation cells whose reference centre lies within a box around the
point (half-widths in mm, default 0.35 across x, unlimited in y, 0.25 in z: a column through the
thickness) and prints, deepest first (ascending y), the cell's reference centre, J, the stress
along the deformed fibre a . sigma a and sigma_xx, sigma_yy (Pa). Used for the DAO's wrinkle site
(validation/suite/README.md, "Where the DAO's instability sits").

Usage: /usr/bin/python3 validation/suite/fibre_stress_at.py RUN_DIR X,Y,Z [--half-width HX,HY,HZ]
       [--cells N]
"""
import argparse
import os

import h5py
import numpy as np


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir")
    parser.add_argument("point", help="X,Y,Z in mm (reference configuration)")
    parser.add_argument("--half-width", default="0.35,inf,0.25", help="HX,HY,HZ in mm")
    parser.add_argument("--cells", type=int, default=12, help="how many cells to print")
    args = parser.parse_args()
    centre = np.array([float(c) for c in args.point.split(",")])
    half = np.array([float(c) for c in args.half_width.split(",")])
    f = h5py.File(os.path.join(args.run_dir, "fields.h5"), "r")
    steps = sorted(k for k in f if k.startswith("step_"))
    meshes = sorted(k for k in f if k.startswith("mesh_"))
    step, mesh = f[steps[-1]], f[meshes[-1]]
    u = step["point/displacement"][:]
    reference = (mesh["points"][:] - u) * 1e3  # the points are written deformed, mm
    cells = mesh["cells"][:]
    X = reference[cells].mean(axis=1)
    sigma = step["cell/cauchy_stress"][:].reshape(-1, 3, 3)
    a = step["cell/fibre"][:]
    J = step["cell/J"][:]
    along = np.einsum("ci,cij,cj->c", a, sigma, a)
    inside = np.where((np.abs(X - centre) <= half).all(axis=1))[0]
    inside = inside[np.argsort(X[inside, 1])]
    print("| reference centre (mm) | J | a·σa (Pa) | σ_xx (Pa) | σ_yy (Pa) |")
    print("|---|---|---|---|---|")
    for c in inside[:args.cells]:
        print("| (%.2f, %.2f, %.2f) | %.3f | %.0f | %.0f | %.0f |" % (
            *X[c], J[c], along[c], sigma[c, 0, 0], sigma[c, 1, 1]))


if __name__ == "__main__":
    main()
