#include "continuum/formulation.hpp"

#include <stdexcept>
#include <string>

namespace isomuscle::continuum {

// Names of the formulations (no equation; the text used in scene files and reports).
const char* to_string(Formulation f) {
  switch (f) {
    case Formulation::automatic:
      return "automatic";
    case Formulation::displacement:
      return "displacement";
    case Formulation::mixed:
      return "mixed";
  }
  return "?";
}

// Inverse of to_string (no equation).
Formulation parse_formulation(std::string_view name) {
  if (name == "automatic") {
    return Formulation::automatic;
  }
  if (name == "displacement") {
    return Formulation::displacement;
  }
  if (name == "mixed") {
    return Formulation::mixed;
  }
  throw std::invalid_argument("unknown formulation '" + std::string(name) +
                              "' (valid: automatic, displacement, mixed)");
}

}  // namespace isomuscle::continuum
