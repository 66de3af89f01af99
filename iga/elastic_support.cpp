#include "iga/elastic_support.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "iga/side_quadrature.hpp"

namespace isomuscle::iga {

std::vector<SupportElementMatrix> support_element_matrices(
    const Space& space, const std::vector<ElasticSupport>& supports) {
  const int nen = space.functions_per_element();
  std::map<int, Eigen::MatrixXd> by_element;
  for (const ElasticSupport& s : supports) {
    if (!(std::isfinite(s.stiffness) && s.stiffness > 0.0)) {
      throw std::invalid_argument("elastic support '" + s.label +
                                  "': the stiffness must be finite and > 0 (Pa/m)");
    }
    if (!(s.components[0] || s.components[1] || s.components[2])) {
      throw std::invalid_argument("elastic support '" + s.label + "' holds no component");
    }
    double area = 0.0;
    std::vector<int> local;
    for_each_side_point(
        space, s.side,
        [&](int e, const geometry::VolumeBasis& basis, const Eigen::Vector3d&, double dA) {
          if (dA == 0.0)
            return;
          area += dA;
          // The basis's functions as the element's local functions a.
          const auto cps = space.control_points(e);
          local.resize(basis.index.size());
          for (std::size_t i = 0; i < basis.index.size(); ++i) {
            const auto it = std::find(cps.begin(), cps.end(), basis.index[i]);
            if (it == cps.end())
              throw std::logic_error(
                  "support_element_matrices: a function of "
                  "the side is not the element's");
            local[i] = static_cast<int>(it - cps.begin());
          }
          auto [entry, fresh] = by_element.try_emplace(e);
          if (fresh)
            entry->second.setZero(3 * nen, 3 * nen);
          Eigen::MatrixXd& k = entry->second;
          // K_ab += k R_a R_b dA on each held component (the side's term).
          for (std::size_t i = 0; i < local.size(); ++i) {
            const double ri = s.stiffness * basis.value[i] * dA;
            for (std::size_t j = 0; j < local.size(); ++j) {
              const double v = ri * basis.value[j];
              for (int c = 0; c < 3; ++c) {
                if (s.components[static_cast<std::size_t>(c)])
                  k(3 * local[i] + c, 3 * local[j] + c) += v;
              }
            }
          }
        });
    if (!(area > 0.0)) {
      throw std::invalid_argument("elastic support '" + s.label +
                                  "': its side has no area (the collapsed centreline of a "
                                  "shrink solid cannot carry springs)");
    }
  }
  std::vector<SupportElementMatrix> out;
  out.reserve(by_element.size());
  for (auto& [e, k] : by_element)
    out.push_back({e, std::move(k)});
  return out;
}

}  // namespace isomuscle::iga
