#pragma once
// Model "tang2009": the chapter-5 skeletal muscle of Tang et al. (2009) as used in the thesis's
// ABAQUS UMAT (5.31–5.55, Table 5.1) as a HillMuscle (hill_muscle.hpp): PE 4 σ0 (λ̄f - 1)² (5.37),
// CE 5.39 with k_c = ^tσ0 / a_v and ^tσ0 = σ0 f_λ(λ̄f) using the smooth force–length curve 3.28
// with λopt = 1.05 (Tang et al. used a piecewise-linear curve whose parameters the thesis does not
// give; SPEC §3). Activation default: from t = 0, linear to full at 0.005 s, held (5.6).
#include <memory>
#include <vector>

#include "materials/material_factory.hpp"

namespace isomuscle::materials {

class ParameterValues;

const std::vector<ParameterSpec>& tang2009_parameters();
// Throws std::invalid_argument when t1 < t0.
std::unique_ptr<MaterialLaw> make_tang2009(const ParameterValues& values);

}  // namespace isomuscle::materials
