#!/usr/bin/env python3
"""Mean displacement of the half torus's free end face against the probe at its centre.

The free end's centre lies on the collapsed axis of the shrink solid; this checks that the
suite's end probe says the same as the whole face (validation/suite/README.md, half torus).
The face is the set of tessellation points of fields.h5 (last step) on the plane y = 0 with x < 0;
the mean is area-weighted over a Delaunay triangulation of them in the (x, z) plane (linear
interpolation of u on each triangle), so it approximates the face integral to the tessellation's
resolution.

Usage: /usr/bin/python3 validation/suite/end_face_mean.py RUN_DIR [RUN_DIR ...]   (mm)
"""
import os
import sys

import matplotlib.tri as mtri
import numpy as np

from run_suite import fields_last_step


def end_face(run_dir):
    """(number of face points, mean u, u at the point nearest the face's centroid), m."""
    X, u, _ = fields_last_step(run_dir)
    size = np.ptp(X, axis=0).max()
    on_face = (np.abs(X[:, 1]) < 1e-9 * size) & (X[:, 0] < 0.0)
    P, U = X[on_face], u[on_face]
    _, first = np.unique(np.round(P / (1e-9 * size)).astype(np.int64), axis=0, return_index=True)
    P, U = P[first], U[first]
    tri = mtri.Triangulation(P[:, 0], P[:, 2]).triangles
    a = P[tri][:, :, [0, 2]]
    area = 0.5 * np.abs((a[:, 1, 0] - a[:, 0, 0]) * (a[:, 2, 1] - a[:, 0, 1]) -
                        (a[:, 2, 0] - a[:, 0, 0]) * (a[:, 1, 1] - a[:, 0, 1]))
    mean = (U[tri].mean(axis=1) * area[:, None]).sum(axis=0) / area.sum()
    centre = U[np.argmin(np.linalg.norm(P - P.mean(axis=0), axis=1))]
    return len(P), mean, centre


def main():
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    for run_dir in sys.argv[1:]:
        n, mean, centre = end_face(run_dir)
        print("%s: %d face points, mean u = %s mm, centre u = %s mm" %
              (os.path.basename(os.path.normpath(run_dir)), n, np.round(mean * 1e3, 4),
               np.round(centre * 1e3, 4)))


if __name__ == "__main__":
    main()
