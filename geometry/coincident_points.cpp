// Grouping of coincident points by spatial hashing (see coincident_points.hpp for why).
#include "geometry/coincident_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <compare>
#include <cstdint>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace isomuscle::geometry {

namespace {

// Disjoint sets with path halving; the root of a set is not necessarily its smallest member.
class DisjointSets {
 public:
  explicit DisjointSets(int n) : parent_(static_cast<std::size_t>(n)) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int find(int a) {
    while (parent_[a] != a) {
      parent_[a] = parent_[parent_[a]];
      a = parent_[a];
    }
    return a;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b)
      parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey&) const = default;
  auto operator<=>(const CellKey&) const = default;
};

// splitmix64 finaliser over the three cell coordinates: regular control nets give regular cell
// keys, which simple XOR-of-products hashes map onto few buckets.
struct CellHash {
  static std::uint64_t mix(std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::size_t operator()(const CellKey& k) const {
    return static_cast<std::size_t>(
        mix(static_cast<std::uint64_t>(k.x) ^
            mix(static_cast<std::uint64_t>(k.y) ^ mix(static_cast<std::uint64_t>(k.z)))));
  }
};

// Turns the disjoint sets into representatives (smallest member) and dense group numbers.
CoincidentPoints collect(DisjointSets& sets, int n) {
  CoincidentPoints out;
  out.representative.assign(static_cast<std::size_t>(n), -1);
  out.group.assign(static_cast<std::size_t>(n), -1);
  std::vector<int> smallest_of_root(static_cast<std::size_t>(n), -1);
  std::vector<int> group_of_root(static_cast<std::size_t>(n), -1);
  for (int a = 0; a < n; ++a) {
    const int root = sets.find(a);
    if (smallest_of_root[root] < 0) {
      smallest_of_root[root] = a;  // points are visited in ascending order
      group_of_root[root] = out.num_distinct++;
    }
    out.representative[a] = smallest_of_root[root];
    out.group[a] = group_of_root[root];
  }
  return out;
}

}  // namespace

// Distance test |x_a - x_b| <= tol with tol = relative_tolerance * |bbox diagonal| (metres when
// the points are in metres); every pair within tol is found (cells below), O(n log n) for the sort
// and O(n) expected for the search.
CoincidentPoints find_coincident_points(const std::vector<Eigen::Vector3d>& points,
                                        double relative_tolerance) {
  if (!(relative_tolerance >= 0.0 && relative_tolerance <= 1e-3)) {
    throw std::invalid_argument("find_coincident_points: relative tolerance " +
                                std::to_string(relative_tolerance) +
                                " must lie in [0, 1e-3] (a fraction of the bounding-box diagonal)");
  }
  const int n = static_cast<int>(points.size());
  DisjointSets sets(n);
  if (n == 0)
    return collect(sets, n);
  Eigen::Vector3d lo = points.front();
  Eigen::Vector3d hi = points.front();
  for (int a = 0; a < n; ++a) {
    if (!points[a].allFinite()) {
      throw std::invalid_argument("find_coincident_points: point " + std::to_string(a) +
                                  " is not finite");
    }
    lo = lo.cwiseMin(points[a]);
    hi = hi.cwiseMax(points[a]);
  }
  const double tol = relative_tolerance * (hi - lo).norm();

  if (tol == 0.0) {
    // Exact equality only: sort-free grouping through an ordered map of coordinates.
    std::map<std::array<double, 3>, int> first;
    for (int a = 0; a < n; ++a) {
      const auto [it, inserted] =
          first.emplace(std::array<double, 3>{points[a].x(), points[a].y(), points[a].z()}, a);
      if (!inserted)
        sets.unite(it->second, a);
    }
    return collect(sets, n);
  }

  // Cells of edge h = 2 tol, stored as runs of a sorted index array. A point closer than tol to
  // another differs from it by less than h / 2 per axis, so the other lies in the point's own cell
  // or, per axis, in the neighbour on the side of the nearer cell face: 8 cells to search.
  const double h = 2.0 * tol;
  std::vector<CellKey> key(static_cast<std::size_t>(n));
  std::vector<std::array<int, 3>> side(static_cast<std::size_t>(n));
  for (int a = 0; a < n; ++a) {
    const Eigen::Vector3d s = (points[a] - lo) / h;
    const Eigen::Vector3d f = s.array().floor();
    key[a] = CellKey{static_cast<std::int64_t>(f.x()), static_cast<std::int64_t>(f.y()),
                     static_cast<std::int64_t>(f.z())};
    for (int d = 0; d < 3; ++d)
      side[a][d] = s[d] - f[d] < 0.5 ? -1 : 1;
  }
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  std::unordered_map<CellKey, std::pair<int, int>, CellHash> cells;  // key -> [begin, end)
  cells.reserve(static_cast<std::size_t>(n));
  for (int r = 0; r < n;) {
    int e = r + 1;
    while (e < n && key[order[e]] == key[order[r]])
      ++e;
    cells.emplace(key[order[r]], std::make_pair(r, e));
    r = e;
  }
  const double tol2 = tol * tol;
  for (int a = 0; a < n; ++a) {
    for (int m = 0; m < 8; ++m) {
      const CellKey k{key[a].x + ((m & 1) ? side[a][0] : 0), key[a].y + ((m & 2) ? side[a][1] : 0),
                      key[a].z + ((m & 4) ? side[a][2] : 0)};
      const auto it = cells.find(k);
      if (it == cells.end())
        continue;
      for (int r = it->second.first; r < it->second.second; ++r) {
        const int b = order[r];
        if (b < a && (points[a] - points[b]).squaredNorm() <= tol2)
          sets.unite(a, b);
      }
    }
  }
  return collect(sets, n);
}

CoincidentPoints find_coincident_points(const NurbsVolume& volume, double relative_tolerance) {
  return find_coincident_points(volume.points(), relative_tolerance);
}

}  // namespace isomuscle::geometry
