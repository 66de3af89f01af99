#pragma once
// Exact refinement and restructuring of NURBS curves, surfaces and volumes: the geometry never
// moves (thesis 5.3, h-, p- and k-refinement; The NURBS Book ch. 5). Every operation works on the
// homogeneous control points (w P, w), one parametric direction at a time (dir 0 = u, 1 = v,
// 2 = w), and returns a new object.
//
// * Knot insertion / refinement (NURBS Book A5.4): new knots may coincide with existing ones up to
//   multiplicity p + 1.
// * Degree elevation by t (NURBS Book A5.9): every knot multiplicity grows by t, so the continuity
//   across knots is kept (k-refinement = elevate first, then insert).
// * make_clamped: an unclamped (e.g. periodic) knot vector and control net become the clamped
//   (open) representation of the same geometry on the domain [u_p, u_{n+1}]: the end knots are
//   inserted to multiplicity p + 1 and the poles outside are dropped.
// * split / extract: a piece of the geometry over [a, b] with its own clamped knot vector (the
//   parameter values are kept, not rescaled).
//
// Errors (std::invalid_argument) name the function, the direction and the valid range.
#include <array>
#include <utility>
#include <vector>

#include "geometry/knot_vector.hpp"
#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"
#include "geometry/nurbs_volume.hpp"

namespace isomuscle::geometry {

// Knots that cut every non-empty span of kv into n_per_span + 1 equal parts (n_per_span >= 0).
std::vector<double> uniform_refinement_knots(const KnotVector& kv, int n_per_span);

// ---- Curves ----
NurbsCurve insert_knot(const NurbsCurve& curve, double u, int times = 1);
// Inserts all values of new_knots (any order, repeats allowed).
NurbsCurve refine_knots(const NurbsCurve& curve, const std::vector<double>& new_knots);
NurbsCurve refine_uniform(const NurbsCurve& curve, int n_per_span);
NurbsCurve elevate_degree(const NurbsCurve& curve, int t);
NurbsCurve make_clamped(const NurbsCurve& curve);
std::pair<NurbsCurve, NurbsCurve> split(const NurbsCurve& curve, double u);
NurbsCurve extract(const NurbsCurve& curve, double a, double b);

// ---- Surfaces (dir 0 = u, 1 = v) ----
NurbsSurface insert_knot(const NurbsSurface& surface, int dir, double u, int times = 1);
NurbsSurface refine_knots(const NurbsSurface& surface, int dir,
                          const std::vector<double>& new_knots);
NurbsSurface refine_uniform(const NurbsSurface& surface, int dir, int n_per_span);
NurbsSurface elevate_degree(const NurbsSurface& surface, int dir, int t);
NurbsSurface make_clamped(const NurbsSurface& surface, int dir);
NurbsSurface make_clamped(const NurbsSurface& surface);  // both directions
std::pair<NurbsSurface, NurbsSurface> split(const NurbsSurface& surface, int dir, double u);
NurbsSurface extract(const NurbsSurface& surface, int dir, double a, double b);

// ---- Volumes (dir 0 = u, 1 = v, 2 = w) ----
NurbsVolume insert_knot(const NurbsVolume& volume, int dir, double u, int times = 1);
NurbsVolume refine_knots(const NurbsVolume& volume, int dir, const std::vector<double>& new_knots);
// h-refinement: n_per_span new knots in every span of direction dir.
NurbsVolume refine_uniform(const NurbsVolume& volume, int dir, int n_per_span);
// h-refinement in all three directions at once.
NurbsVolume refine_uniform(const NurbsVolume& volume, const std::array<int, 3>& n_per_span);
// p-refinement: degree in direction dir raised by t >= 0.
NurbsVolume elevate_degree(const NurbsVolume& volume, int dir, int t);
// Raises each direction to at least the given degree (a no-op where the degree is already higher).
NurbsVolume elevate_to(const NurbsVolume& volume, const std::array<int, 3>& degrees);
NurbsVolume make_clamped(const NurbsVolume& volume, int dir);
NurbsVolume make_clamped(const NurbsVolume& volume);  // all directions
// Two volumes over [begin, u] and [u, end] in direction dir (u strictly inside the domain).
std::pair<NurbsVolume, NurbsVolume> split(const NurbsVolume& volume, int dir, double u);
// The volume restricted to [a, b] in direction dir (begin <= a < b <= end).
NurbsVolume extract(const NurbsVolume& volume, int dir, double a, double b);

}  // namespace isomuscle::geometry
