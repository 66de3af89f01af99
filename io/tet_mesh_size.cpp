#include "io/tet_mesh_size.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <unordered_set>

namespace isomuscle::io {

namespace {

// Most points sampled along one parametric direction of a face (a 3 cm face at 0.05 mm spacing
// needs 600; more would only make meshing slow).
constexpr int kMaxSamplesPerDirection = 4000;

// Distance to one face: points sampled on it at most `spacing` apart along each parametric
// direction, thinned to one per grid cell of edge `spacing`, so that every point of the face lies
// within (1/sqrt 2 + sqrt 3) spacing of a kept one (half a grid diagonal to the nearest sample,
// a cell diagonal from a dropped sample to its cell's kept one). The distance to the nearest
// kept point less that bound is never more than the true distance: the refined zone may reach a
// little further than asked, never less far. Beyond the bounding box grown by `reach` the
// distance is not needed.
struct SampledFace {
  std::vector<Eigen::Vector3d> points;
  double sampling_error = 0.0;
  Eigen::Vector3d low, high;

  bool beyond(const Eigen::Vector3d& x) const {
    return (x.array() < low.array()).any() || (x.array() > high.array()).any();
  }
  double distance(const Eigen::Vector3d& x) const {
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : points)
      best = std::min(best, (p - x).squaredNorm());
    return std::max(std::sqrt(best) - sampling_error, 0.0);
  }
};

// An upper bound of the length of the face's isocurves in in-face direction `along` if each ran
// at its fastest parametric speed: 64 times the longest of their 64 chords, over 9 isocurves. n
// equal parameter steps of it are then at most bound / n long.
double isocurve_length_bound(const geometry::NurbsVolume& volume, int normal, double at,
                             int along) {
  const int across = 3 - normal - along;
  const auto [a0, a1] = volume.domain(along);
  const auto [c0, c1] = volume.domain(across);
  double longest_chord = 0.0;
  for (int j = 0; j <= 8; ++j) {
    Eigen::Vector3d xi;
    xi[normal] = at;
    xi[across] = c0 + (c1 - c0) * j / 8.0;
    Eigen::Vector3d previous;
    for (int i = 0; i <= 64; ++i) {
      xi[along] = a0 + (a1 - a0) * i / 64.0;
      const Eigen::Vector3d p = volume.evaluate(xi);
      if (i > 0)
        longest_chord = std::max(longest_chord, (p - previous).norm());
      previous = p;
    }
  }
  return 64.0 * longest_chord;
}

SampledFace sample_face(const SceneSolid& solid, Face face, double spacing, double reach) {
  const geometry::NurbsVolume& volume = solid.volume;
  const int side = static_cast<int>(solid.frame.solid_side(face));
  const int normal = side / 2;
  const auto [n0, n1] = volume.domain(normal);
  const double at = side % 2 == 0 ? n0 : n1;
  const int a = (normal + 1) % 3, b = (normal + 2) % 3;
  auto count = [&](int along) {
    const double n = std::ceil(isocurve_length_bound(volume, normal, at, along) / spacing) + 1.0;
    return static_cast<int>(std::clamp(n, 2.0, double(kMaxSamplesPerDirection)));
  };
  const int na = count(a), nb = count(b);
  const auto [a0, a1] = volume.domain(a);
  const auto [b0, b1] = volume.domain(b);
  SampledFace out;
  std::unordered_set<long long> cells;  // grid cells of edge `spacing` already holding a point
  auto cell_key = [spacing](const Eigen::Vector3d& p) {
    const Eigen::Array3d c = (p.array() / spacing).floor();
    // 2^20 cells per axis: unique for |x| < 2^19 spacing (50 m at 0.1 mm).
    return (static_cast<long long>(c[0]) & 0xFFFFF) |
           (static_cast<long long>(c[1]) & 0xFFFFF) << 20 |
           (static_cast<long long>(c[2]) & 0xFFFFF) << 40;
  };
  for (int j = 0; j < nb; ++j)
    for (int i = 0; i < na; ++i) {
      Eigen::Vector3d xi;
      xi[normal] = at;
      xi[a] = a0 + (a1 - a0) * i / (na - 1.0);
      xi[b] = b0 + (b1 - b0) * j / (nb - 1.0);
      const Eigen::Vector3d p = volume.evaluate(xi);
      if (cells.insert(cell_key(p)).second)
        out.points.push_back(p);
    }
  out.low = out.high = out.points.front();
  for (const Eigen::Vector3d& p : out.points) {
    out.low = out.low.cwiseMin(p);
    out.high = out.high.cwiseMax(p);
  }
  if ((out.high - out.low).norm() < spacing) {
    throw std::invalid_argument(std::string("[[tetrahedra.refine]] face ") + to_string(face) +
                                " is a single point of the solid: there is no face to refine at");
  }
  out.sampling_error = (1.0 / std::sqrt(2.0) + std::sqrt(3.0)) * spacing;
  out.low.array() -= reach + out.sampling_error;
  out.high.array() += reach + out.sampling_error;
  return out;
}

}  // namespace

void set_face_refinement(tet::MeshingOptions& options, const SceneSolid& solid,
                         const std::vector<TetRefinement>& refinements) {
  if (refinements.empty())
    return;
  struct Refined {
    SampledFace face;
    TetRefinement settings;
  };
  auto refined = std::make_shared<std::vector<Refined>>();
  double finest = options.element_size;
  for (const TetRefinement& r : refinements) {
    refined->push_back({sample_face(solid, r.face, 0.25 * r.size, r.distance), r});
    finest = std::min(finest, r.size);
  }
  const double coarse = options.element_size;
  options.finest_size = finest;
  options.local_size = [refined, coarse](const Eigen::Vector3d& x) {
    double h = coarse;
    for (const Refined& r : *refined) {
      if (r.face.beyond(x))
        continue;
      const double s = r.settings.size, t = std::min(r.face.distance(x) / r.settings.distance, 1.0);
      h = std::min(h, s + (coarse - s) * t);
    }
    return h;
  };
}

}  // namespace isomuscle::io
