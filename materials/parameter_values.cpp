#include "materials/parameter_values.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace isomuscle::materials {

namespace {
std::string number(double v) {
  if (std::isinf(v))
    return v > 0 ? "inf" : "-inf";
  std::ostringstream os;
  os << v;
  return os.str();
}
}  // namespace

ParameterSpec make_spec(std::string name, double default_value, double min, double max,
                        bool min_exclusive, bool max_exclusive, std::string unit,
                        std::string description) {
  ParameterSpec s{std::move(name), default_value,         min, max, min_exclusive,
                  std::move(unit), std::move(description)};
  s.max_exclusive = max_exclusive;
  return s;
}

ParameterSpec make_flag(std::string name, double default_value, std::string description) {
  ParameterSpec s =
      make_spec(std::move(name), default_value, 0.0, 1.0, false, false, "", std::move(description));
  s.integer_flag = true;
  return s;
}

std::string describe_range(const ParameterSpec& s) {
  if (s.integer_flag)
    return "0 or 1";
  const bool open_lo = s.min_exclusive || std::isinf(s.min);
  const bool open_hi = s.max_exclusive || std::isinf(s.max);
  return std::string(open_lo ? "(" : "[") + number(s.min) + ", " + number(s.max) +
         (open_hi ? ")" : "]");
}

bool in_range(const ParameterSpec& s, double v) {
  if (std::isnan(v))
    return false;
  if (s.integer_flag)
    return v == 0.0 || v == 1.0;
  const bool lo_ok = s.min_exclusive ? v > s.min : v >= s.min;
  const bool hi_ok = s.max_exclusive ? v < s.max : v <= s.max;
  return lo_ok && hi_ok;
}

ParameterValues::ParameterValues(std::string model, const std::vector<ParameterSpec>& specs,
                                 const std::map<std::string, double>& given)
    : model_(std::move(model)) {
  for (const ParameterSpec& s : specs)
    values_[s.name] = s.default_value;
  for (const auto& [name, value] : given) {
    const ParameterSpec* spec = nullptr;
    for (const ParameterSpec& s : specs)
      if (s.name == name)
        spec = &s;
    if (spec == nullptr) {
      std::string valid;
      for (const ParameterSpec& s : specs)
        valid += (valid.empty() ? "" : ", ") + s.name;
      throw std::invalid_argument("material '" + model_ + "': unknown parameter '" + name +
                                  "'; valid parameters: " + valid);
    }
    if (!in_range(*spec, value))
      throw std::invalid_argument(
          "material '" + model_ + "': parameter '" + name + "' = " + number(value) +
          " is out of range; valid: " + describe_range(*spec) +
          (spec->unit.empty() ? "" : " " + spec->unit) + " (" + spec->description + ")");
    values_[name] = value;
  }
}

double ParameterValues::get(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end())
    throw std::logic_error("material '" + model_ + "': no parameter '" + name + "' in its table");
  return it->second;
}

int ParameterValues::integer(const std::string& name) const {
  const double value = get(name);
  if (value != std::floor(value) || std::abs(value) > 1e9)
    fail(name, "is not an integer; valid: a whole number in the parameter's range");
  return static_cast<int>(value);
}

void ParameterValues::fail(const std::string& name, const std::string& why) const {
  throw std::invalid_argument("material '" + model_ + "': parameter '" + name +
                              "' = " + number(get(name)) + " " + why);
}

}  // namespace isomuscle::materials
