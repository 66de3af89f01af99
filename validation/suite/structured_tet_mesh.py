#!/usr/bin/env python3
"""10-node tetrahedra on the NURBS solid's own parametrisation (validation/suite/README.md, DAO).

The tetrahedral comparison runs mesh the IGES boundary with gmsh; these tetrahedra are instead
cut from the shrink solid's parametric grid, so that they share the IGA's geometry (every node is
a point of the NURBS map), its element layout and its collapsed axis, and differ from the IGA
runs only in the space (piecewise quadratic on tetrahedra instead of the smooth spline). With
them a difference between the IGA and the gmsh tetrahedra can be told apart: geometry and mesh
layout (then these follow the IGA) or the space (then these follow the gmsh tetrahedra).

How: `isomuscle geometry solid --vtk` samples the map on a grid with D points per knot span and
direction; every parametric cell of CELLS = (around, along, radial) cells per knot span is split
into six tetrahedra along its main diagonal (the Kuhn / Freudenthal split, which is conforming
across cells, also across the closed seam), their edge midpoints are grid points too, so each
tetrahedron is a curved 10-node element interpolating the exact map. Coincident grid points (the
seam u0 = u1 and the collapsed centreline axis) are merged; tetrahedra with two corners on the
same merged point are dropped (the cells at the axis are wedges, three tetrahedra each). Edges
from the axis get straight midpoints: the parametric midpoints of such an edge differ with the
cell it is seen from, and one node per edge is what keeps the mesh conforming. Boundary
triangles are the faces that belong to one tetrahedron only; the runs find the solid's faces
(v0 ...) on them by point inversion, as they do on gmsh meshes.

Usage: /usr/bin/python3 validation/suite/structured_tet_mesh.py IGES OUT.msh
           --cells AROUND,ALONG,RADIAL [--surface 0] [--centreline v] [--check-volume TOL]
           [--exe ISOMUSCLE]
Writes a gmsh 2.2 ASCII mesh in the unit of the VTK points (metres) and prints its counts and
its volume against the NURBS solid's (--check-volume: fail beyond that relative difference).
"""
import argparse
import itertools
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MERGE_TOLERANCE = 1e-9  # m: the seam and the axis coincide to rounding
# gmsh's 10-node tetrahedron: corners 0-3, then the midpoints of these corner pairs.
TET10_EDGES = [(0, 1), (1, 2), (2, 0), (3, 0), (3, 2), (3, 1)]
# gmsh's 6-node triangle: corners 0-2, then midpoints of (0,1), (1,2), (2,0).
TRI6_EDGES = [(0, 1), (1, 2), (2, 0)]


def read_vtk_grid(path):
    """Points of `geometry solid --vtk` as an array of shape (n2, n1, n0, 3), index i fastest."""
    with open(path) as f:
        lines = f.read().split("\n")
    start = next(k for k, line in enumerate(lines) if line.startswith("POINTS"))
    count = int(lines[start].split()[1])
    points = np.array([[float(v) for v in lines[start + 1 + k].split()] for k in range(count)])
    cells = next(k for k, line in enumerate(lines) if line.startswith("CELLS"))
    first = [int(v) for v in lines[cells + 1].split()]
    # The first hexahedron is 8, id(0,0,0), id(1,0,0), id(1,1,0), id(0,1,0), id(0,0,1), ...
    n0, n01 = first[4], first[5]
    n1, n2 = n01 // n0, count // n01
    if n0 * n1 * n2 != count:
        raise SystemExit("structured_tet_mesh: %s is not a structured grid" % path)
    return points.reshape(n2, n1, n0, 3)


def sample_solid(exe, iges, surface, centreline, divisions):
    """The map on the grid (read_vtk_grid) and the solid's volume, m^3, from one call of
    `isomuscle geometry solid --vtk --json`."""
    with tempfile.TemporaryDirectory() as tmp:
        vtk = os.path.join(tmp, "solid.vtk")
        text = subprocess.run([exe, "geometry", "solid", iges, "--surface", str(surface),
                               "--centreline", centreline, "--vtk", vtk, "--vtk-divisions",
                               str(divisions), "--json"], check=True, capture_output=True,
                              text=True).stdout
        return read_vtk_grid(vtk), json.loads(text)["volume_m3"]


def merged_ids(half):
    """One id per group of coincident grid points, and each point's group size. Two kinds of
    coincidence occur in a shrink solid, and both are checked rather than assumed: the closed
    seam (the first and last points around, u0 = u1) and the collapsed axis (a whole ring around
    at one point)."""
    nw, nv, nu = half.shape[:3]
    ids = np.arange(nw * nv * nu).reshape(nw, nv, nu)
    for k, j in itertools.product(range(nw), range(nv)):
        ring = half[k, j]
        if np.linalg.norm(ring - ring[0], axis=1).max() <= MERGE_TOLERANCE:
            ids[k, j, :] = ids[k, j, 0]
        elif np.linalg.norm(ring[-1] - ring[0]) <= MERGE_TOLERANCE:
            ids[k, j, -1] = ids[k, j, 0]
    _, ids, sizes = np.unique(ids.ravel(), return_inverse=True, return_counts=True)
    return ids, sizes[ids]


# Corners, edge midpoints and centroid: where a folded curved element shows a det J <= 0.
CHECK_POINTS = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (0.5, 0, 0), (0.5, 0.5, 0),
                (0, 0.5, 0), (0, 0, 0.5), (0, 0.5, 0.5), (0.5, 0, 0.5), (0.25, 0.25, 0.25)]


def tet10_jacobians(x, pts=CHECK_POINTS):
    """det(dX/dxi) of a 10-node tetrahedron (x: 10 x 3) at the reference points pts."""
    dl = np.array([[-1, -1, -1], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)  # dL_c / d(r, s, t)
    dets = []
    for r, s, t in pts:
        l = [1 - r - s - t, r, s, t]
        # dN/d(r, s, t) of the quadratic Lagrange basis in barycentric form.
        grad = np.zeros((10, 3))
        for c in range(4):
            grad[c] = (4 * l[c] - 1) * dl[c]
        for e, (a, b) in enumerate(TET10_EDGES):
            grad[4 + e] = 4 * (l[a] * dl[b] + l[b] * dl[a])
        dets.append(np.linalg.det(x.T @ grad))
    return np.array(dets)


def build(grid, cells_per_span, divisions):
    """Nodes (N x 3), tetrahedra (M x 10, gmsh order), boundary triangles (K x 6) and the count of
    elements made straight-sided because their curved map folded."""
    strides = []
    for c in cells_per_span:
        if divisions % (2 * c):
            raise SystemExit("structured_tet_mesh: %d divisions per span do not hold %d cells "
                             "with midpoints" % (divisions, c))
        strides.append(divisions // (2 * c))
    half = grid[::strides[2], ::strides[1], ::strides[0]]  # (w, v, u) half-cell grid
    shape = half.shape[:3]
    flat = half.reshape(-1, 3)
    ids, group_size = merged_ids(half)

    def index(i, j, k):
        return (k * shape[1] + j) * shape[2] + i

    tets, axis_edge_node = [], {}
    nodes = [None] * (ids.max() + 1)
    for p, g in enumerate(ids):
        if nodes[g] is None:
            nodes[g] = flat[p]
    straightened = 0
    for k, j, i in itertools.product(range(0, shape[0] - 1, 2), range(0, shape[1] - 1, 2),
                                     range(0, shape[2] - 1, 2)):
        for perm in itertools.permutations(range(3)):
            corner = np.zeros(3, int)
            path = [corner.copy()]
            for axis in perm:
                corner[axis] += 2
                path.append(corner.copy())
            half_index = [(i + c[0], j + c[1], k + c[2]) for c in path]
            flat_index = [index(*h) for h in half_index]
            merged = [ids[f] for f in flat_index]
            if len(set(merged)) < 4:
                continue  # a wedge cell at the axis: this tetrahedron has collapsed
            element = list(merged)
            for a, b in TET10_EDGES:
                if group_size[flat_index[a]] > 2 or group_size[flat_index[b]] > 2:
                    # An edge from the axis: one straight midpoint node per pair of corners.
                    key = (min(merged[a], merged[b]), max(merged[a], merged[b]))
                    if key not in axis_edge_node:
                        axis_edge_node[key] = len(nodes)
                        nodes.append(0.5 * (flat[flat_index[a]] + flat[flat_index[b]]))
                    element.append(axis_edge_node[key])
                else:
                    # The parametric midpoint is a grid point; its merged id is shared across
                    # the seam and by every tetrahedron on the edge.
                    m = [(half_index[a][d] + half_index[b][d]) // 2 for d in range(3)]
                    element.append(ids[index(*m)])
            x = np.array([nodes[n] for n in element])
            if np.linalg.det((x[1:4] - x[0]).T) < 0:
                element[1], element[2] = element[2], element[1]
                element[4], element[6] = element[6], element[4]
                element[8], element[9] = element[9], element[8]
                x = np.array([nodes[n] for n in element])
            if tet10_jacobians(x).min() <= 0:
                # As tet/curved_tet_repair does for gmsh's meshes: a straight-sided element.
                straightened += 1
                for e, (a, b) in enumerate(TET10_EDGES):
                    nodes[element[4 + e]] = 0.5 * (x[a] + x[b])
            tets.append(element)
    # Only the grid points and axis midpoints that the tetrahedra use, renumbered in that order.
    used, tets = np.unique(np.array(tets), return_inverse=True)
    tets = tets.reshape(-1, 10)
    nodes = [nodes[n] for n in used]
    # Boundary: corner triples that belong to one tetrahedron only (outward orientation).
    faces = {}
    for t in tets:
        for opposite in range(4):
            tri = [c for c in range(4) if c != opposite]
            key = tuple(sorted(t[tri]))
            faces.setdefault(key, []).append((t, tri, opposite))
    triangles = []
    for owners in faces.values():
        if len(owners) != 1:
            continue
        t, tri, opposite = owners[0]
        x = np.array([nodes[n] for n in t[:4]])
        normal = np.cross(x[tri[1]] - x[tri[0]], x[tri[2]] - x[tri[0]])
        if normal.dot(x[opposite] - x[tri[0]]) > 0:
            tri = [tri[0], tri[2], tri[1]]
        edge_of = {frozenset(TET10_EDGES[e]): t[4 + e] for e in range(6)}
        triangles.append([t[c] for c in tri] +
                         [edge_of[frozenset((tri[a], tri[b]))] for a, b in TRI6_EDGES])
    return np.array(nodes), tets, np.array(triangles), straightened


def mesh_volume(nodes, tets):
    """Sum over the tetrahedra of det(dX/dxi) integrated by a degree-3 rule (Keast, as
    tet::tet_rule(3)), exact for the cubic det J of a 10-node map."""
    s = 1 / 6
    points = [(0.25, 0.25, 0.25), (s, s, s), (0.5, s, s), (s, 0.5, s), (s, s, 0.5)]
    weights = np.array([-4 / 30, 9 / 120, 9 / 120, 9 / 120, 9 / 120])
    return sum(weights @ tet10_jacobians(nodes[t], points) for t in tets)


def write_msh(path, nodes, tets, triangles):
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
        for n, x in enumerate(nodes):
            f.write("%d %.17g %.17g %.17g\n" % (n + 1, *x))
        f.write("$EndNodes\n$Elements\n%d\n" % (len(triangles) + len(tets)))
        number = 0
        for tri in triangles:
            number += 1
            f.write("%d 9 2 1 1 %s\n" % (number, " ".join(str(n + 1) for n in tri)))
        for tet in tets:
            number += 1
            f.write("%d 11 2 2 1 %s\n" % (number, " ".join(str(n + 1) for n in tet)))
        f.write("$EndElements\n")


def structured_mesh(exe, iges, out, cells, surface=0, centreline="v"):
    """Writes OUT (gmsh 2.2) for CELLS per knot span; returns (nodes, tetrahedra, straightened,
    the NURBS solid's volume)."""
    divisions = 2 * int(np.lcm.reduce(cells))
    grid, solid_volume = sample_solid(exe, iges, surface, centreline, divisions)
    nodes, tets, triangles, straightened = build(grid, cells, divisions)
    write_msh(out, nodes, tets, triangles)
    return nodes, tets, straightened, solid_volume


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("iges")
    parser.add_argument("out")
    parser.add_argument("--cells", required=True, help="AROUND,ALONG,RADIAL cells per knot span")
    parser.add_argument("--surface", type=int, default=0)
    parser.add_argument("--centreline", default="v")
    parser.add_argument("--check-volume", type=float, metavar="TOL",
                        help="fail when |V_mesh / V_solid - 1| > TOL")
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "release", "app", "isomuscle"))
    args = parser.parse_args()
    cells = [int(c) for c in args.cells.split(",")]
    if len(cells) != 3 or min(cells) < 1:
        parser.error("--cells expects three positive integers, got '%s'" % args.cells)
    nodes, tets, s, exact = structured_mesh(args.exe, args.iges, args.out, cells, args.surface,
                                            args.centreline)
    volume = mesh_volume(nodes, tets)
    change = volume / exact - 1.0
    print("%s: %d nodes, %d 10-node tetrahedra (%d made straight-sided), volume %.9g m^3, "
          "%+.2e of the NURBS solid's" % (args.out, len(nodes), len(tets), s, volume, change))
    if args.check_volume is not None and not abs(change) <= args.check_volume:
        raise SystemExit("structured_tet_mesh: the mesh's volume is %+.2e of the solid's, beyond "
                         "--check-volume %g" % (change, args.check_volume))


if __name__ == "__main__":
    sys.exit(main())
