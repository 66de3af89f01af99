#pragma once
// Creating laws by name with checked parameters: the one place that scene files, the material
// driver and tests use to make a law. Unknown model or parameter names and out-of-range values
// throw std::invalid_argument with a message naming the parameter, its valid range and the valid
// choices.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "materials/material_law.hpp"

namespace isomuscle::materials {

struct ParameterSpec {
  std::string name;            // as written in scenes and on the command line, e.g. "sigma0"
  double default_value;        // SI units
  double min, max;             // valid closed range (use +-infinity for open ends)
  bool min_exclusive;          // true when min itself is not allowed (e.g. D > 0)
  std::string unit;            // "Pa", "1/s", "m^2/N", "" ...
  std::string description;     // one line, with the thesis symbol and equation
  bool max_exclusive = false;  // true when max itself is not allowed (e.g. nu < 0.5)
  bool integer_flag = false;   // true for on/off switches: only 0 and 1 are valid
};

// The valid values of a parameter as text, e.g. "(0, inf)", "[1, 1.8]" or "0 or 1".
std::string describe_range(const ParameterSpec& spec);
// True when value lies in the spec's range (never for NaN).
bool in_range(const ParameterSpec& spec, double value);

// Model names: "lu2010", "tang2009", "neo_hookean", "linear_elastic" (frame-invariant, see its
// file).
std::vector<std::string> material_models();
// Parameters of a model with their defaults (thesis Table 3.10 / Table 5.1 / SPEC §4).
const std::vector<ParameterSpec>& material_parameters(const std::string& model);
// Makes a law; every parameter not given takes its default.
std::unique_ptr<MaterialLaw> make_material(const std::string& model,
                                           const std::map<std::string, double>& parameters = {});

}  // namespace isomuscle::materials
