#include "continuum/jacobian_minimum.hpp"

namespace isomuscle::continuum {

void JacobianMinimum::take_element(int e, std::span<const double> J) {
  for (std::size_t q = 0; q < J.size(); ++q)
    take(JacobianMinimum{J[q], e, static_cast<int>(q)});
}

void JacobianMinimum::take(const JacobianMinimum& other) {
  if (!other.found())
    return;
  const bool smaller = other.value < value;
  const bool tie_first =
      other.value == value &&
      (other.element < element || (other.element == element && other.point < point));
  if (!found() || smaller || tie_first)
    *this = other;
}

JacobianMinimum JacobianMinimum::of(std::span<const JacobianMinimum> parts) {
  JacobianMinimum m;
  for (const JacobianMinimum& part : parts)
    m.take(part);
  return m;
}

}  // namespace isomuscle::continuum
