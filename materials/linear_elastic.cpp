#include "materials/linear_elastic.hpp"

#include "materials/neo_hookean.hpp"
#include "materials/parameter_values.hpp"

namespace isomuscle::materials {

const std::vector<ParameterSpec>& linear_elastic_parameters() {
  static const std::vector<ParameterSpec> specs = {
      make_spec("E", 6.2e3, 0.0, kInfinity, true, false, "Pa",
                "small-strain Young's modulus (thesis ch. 4: skin 15 kPa, passive muscle 6.2 kPa)"),
      make_spec("nu", 0.49, -1.0, 0.5, true, true, "",
                "small-strain Poisson's ratio (thesis ch. 4: 0.49 for soft tissue)"),
  };
  return specs;
}

// mu = E/(2(1+nu)), kappa = E/(3(1-2nu)) (thesis 3.42–3.43); Pa.
std::unique_ptr<MaterialLaw> make_linear_elastic(const ParameterValues& v) {
  const double E = v.get("E"), nu = v.get("nu");
  return std::make_unique<NeoHookean>("linear_elastic", E / (2.0 * (1.0 + nu)),
                                      E / (3.0 * (1.0 - 2.0 * nu)));
}

}  // namespace isomuscle::materials
