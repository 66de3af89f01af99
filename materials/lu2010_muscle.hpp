#pragma once
// Model "lu2010": the chapter-3 skeletal muscle (thesis 3.18–3.41, Table 3.10, LS-DYNA UMAT of
// Appendix E) as a HillMuscle (hill_muscle.hpp). Parameter names, defaults and ranges are in
// lu2010_parameters(); activation defaults n1 = 0, n2 = 1, t0 = 0, t1 = inf are those of the
// thesis's expression runs (4.x, SPEC §6; the example card of Figure 3.16 has t0 = 0).
#include <memory>
#include <vector>

#include "materials/material_factory.hpp"

namespace isomuscle::materials {

class ParameterValues;

const std::vector<ParameterSpec>& lu2010_parameters();
// Throws std::invalid_argument when t1 < t0.
std::unique_ptr<MaterialLaw> make_lu2010(const ParameterValues& values);

}  // namespace isomuscle::materials
