#include "continuum/jacobian_range.hpp"

namespace isomuscle::continuum {
namespace {

bool comes_first(const JacobianAtPoint& a, const JacobianAtPoint& b) {
  return a.element < b.element || (a.element == b.element && a.point < b.point);
}

// Replaces *kept by candidate when *kept is empty, when candidate is beyond it (beyond(c, k):
// c < k for the smallest, c > k for the largest) or, at an equal value, comes first.
template <class Beyond>
void keep_extreme(JacobianAtPoint& kept, const JacobianAtPoint& candidate, Beyond beyond) {
  if (!candidate.found())
    return;
  const bool tie_first = candidate.value == kept.value && comes_first(candidate, kept);
  if (!kept.found() || beyond(candidate.value, kept.value) || tie_first)
    kept = candidate;
}

}  // namespace

void JacobianRange::take_element(int e, std::span<const double> J) {
  for (std::size_t q = 0; q < J.size(); ++q) {
    const JacobianAtPoint p{J[q], e, static_cast<int>(q)};
    take(JacobianRange{p, p});
  }
}

void JacobianRange::take(const JacobianRange& other) {
  keep_extreme(smallest, other.smallest, [](double c, double k) { return c < k; });
  keep_extreme(largest, other.largest, [](double c, double k) { return c > k; });
}

JacobianRange JacobianRange::of(std::span<const JacobianRange> parts) {
  JacobianRange r;
  for (const JacobianRange& part : parts)
    r.take(part);
  return r;
}

}  // namespace isomuscle::continuum
