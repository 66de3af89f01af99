#include "continuum/problem_setup.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace isomuscle::continuum {

// automatic: mixed iff split and kappa >= threshold mu (no equation; the choice is argued in
// iga/problem.hpp ProblemOptions).
Formulation resolve_formulation(Formulation requested, const materials::MaterialLaw& law,
                                double mixed_threshold) {
  switch (requested) {
    case Formulation::automatic:
      return law.has_volumetric_split() &&
                     (mixed_threshold <= 0.0 ||
                      law.bulk_modulus() >= mixed_threshold * law.shear_modulus())
                 ? Formulation::mixed
                 : Formulation::displacement;
    case Formulation::displacement:
      return Formulation::displacement;
    case Formulation::mixed:
      if (!law.has_volumetric_split()) {
        throw std::invalid_argument("formulation 'mixed' needs a law with a volumetric split; '" +
                                    law.name() + "' has none (use 'displacement' or 'automatic')");
      }
      return Formulation::mixed;
  }
  return Formulation::displacement;
}

// |N| = 1 (the fibre direction is a unit vector in the reference configuration, thesis 5.30).
void check_unit_fibres(const std::vector<Eigen::Vector3d>& fibres, int num_points,
                       std::string_view owner) {
  const std::string who(owner);
  if (static_cast<int>(fibres.size()) != num_points) {
    throw std::invalid_argument(who + ": " + std::to_string(fibres.size()) +
                                " fibre directions for " + std::to_string(num_points) +
                                " quadrature points");
  }
  for (std::size_t i = 0; i < fibres.size(); ++i) {
    if (!fibres[i].allFinite() || std::abs(fibres[i].norm() - 1.0) > 1e-8) {
      throw std::invalid_argument(who + ": fibre direction " + std::to_string(i) +
                                  " is not a finite unit vector");
    }
  }
}

}  // namespace isomuscle::continuum
