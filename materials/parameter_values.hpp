#pragma once
// Checked parameter lookup for the factory: every given name must be one of the model's
// parameters and every value must lie in its range, else std::invalid_argument with a message
// naming the model, the parameter, the value and the valid range or names.
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "materials/material_factory.hpp"

namespace isomuscle::materials {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

ParameterSpec make_spec(std::string name, double default_value, double min, double max,
                        bool min_exclusive, bool max_exclusive, std::string unit,
                        std::string description);
// An on/off switch: 0 or 1.
ParameterSpec make_flag(std::string name, double default_value, std::string description);

class ParameterValues {
 public:
  ParameterValues(std::string model, const std::vector<ParameterSpec>& specs,
                  const std::map<std::string, double>& given);

  const std::string& model() const { return model_; }
  // The given value, or the default; throws std::logic_error for a name not in the specs.
  double get(const std::string& name) const;
  bool flag(const std::string& name) const { return get(name) != 0.0; }
  // get(name) as an int; throws std::invalid_argument when it is not a whole number.
  int integer(const std::string& name) const;
  // Throws std::invalid_argument("<model>: parameter '<name>' = <value> ...<why>") (cross checks).
  [[noreturn]] void fail(const std::string& name, const std::string& why) const;

 private:
  std::string model_;
  std::map<std::string, double> values_;
};

}  // namespace isomuscle::materials
