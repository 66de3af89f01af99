#pragma once
// Checks of a problem's set-up shared by the discretisations: which formulation a law gets, and
// that the fibre field holds one unit vector per quadrature point.
#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "continuum/formulation.hpp"
#include "materials/material_law.hpp"

namespace isomuscle::continuum {

// The formulation used for `law` when `requested` is asked for: automatic gives mixed when the law
// has a volumetric split and, if mixed_threshold > 0, bulk_modulus() >= mixed_threshold *
// shear_modulus() (kappa/mu; mixed_threshold <= 0: every split law); mixed with a law without a
// split throws std::invalid_argument naming the law and the valid choices.
Formulation resolve_formulation(Formulation requested, const materials::MaterialLaw& law,
                                double mixed_threshold);

// Throws std::invalid_argument, prefixed by `owner`, unless fibres holds num_points finite unit
// vectors (|N| = 1 to 1e-8).
void check_unit_fibres(const std::vector<Eigen::Vector3d>& fibres, int num_points,
                       std::string_view owner);

}  // namespace isomuscle::continuum
