#include "io/ellipticity_probe.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "io/material_ellipticity.hpp"

namespace isomuscle::io {

std::vector<std::string> ellipticity_probe_columns(const std::string& name) {
  return {name, name + ".not_elliptic", name + ".x", name + ".y", name + ".z"};
}

void ellipticity_probe_values(const MaterialEllipticityScan& scan, std::span<double> out) {
  if (out.size() != kEllipticityProbeColumns)
    throw std::invalid_argument(
        "ellipticity_probe_values: " + std::to_string(kEllipticityProbeColumns) + " columns, got " +
        std::to_string(out.size()));
  try {
    const MaterialEllipticity e = assess_material_ellipticity(scan, nullptr);
    out[0] = e.smallest.smallest;
    out[1] = static_cast<double>(e.not_elliptic);
    for (int i = 0; i < 3; ++i)
      out[2 + static_cast<std::size_t>(i)] = e.smallest.position[i];
  } catch (const std::invalid_argument&) {  // no point could be evaluated
    std::fill(out.begin(), out.end(), std::numeric_limits<double>::quiet_NaN());
  }
}

}  // namespace isomuscle::io
