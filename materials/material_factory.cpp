#include "materials/material_factory.hpp"

#include <stdexcept>

#include "materials/linear_elastic.hpp"
#include "materials/lu2010_muscle.hpp"
#include "materials/neo_hookean.hpp"
#include "materials/parameter_values.hpp"
#include "materials/tang2009_muscle.hpp"

namespace isomuscle::materials {

namespace {

struct ModelEntry {
  const char* name;
  const std::vector<ParameterSpec>& (*parameters)();
  std::unique_ptr<MaterialLaw> (*make)(const ParameterValues&);
};

constexpr ModelEntry kModels[] = {
    {"lu2010", &lu2010_parameters, &make_lu2010},
    {"tang2009", &tang2009_parameters, &make_tang2009},
    {"neo_hookean", &neo_hookean_parameters, &make_neo_hookean},
    {"linear_elastic", &linear_elastic_parameters, &make_linear_elastic},
};

const ModelEntry& find_model(const std::string& model) {
  for (const ModelEntry& m : kModels)
    if (model == m.name)
      return m;
  std::string valid;
  for (const ModelEntry& m : kModels)
    valid += (valid.empty() ? "" : ", ") + std::string(m.name);
  throw std::invalid_argument("unknown material model '" + model + "'; valid models: " + valid);
}

}  // namespace

std::vector<std::string> material_models() {
  std::vector<std::string> names;
  for (const ModelEntry& m : kModels)
    names.emplace_back(m.name);
  return names;
}

const std::vector<ParameterSpec>& material_parameters(const std::string& model) {
  return find_model(model).parameters();
}

std::unique_ptr<MaterialLaw> make_material(const std::string& model,
                                           const std::map<std::string, double>& parameters) {
  const ModelEntry& entry = find_model(model);
  return entry.make(ParameterValues(model, entry.parameters(), parameters));
}

}  // namespace isomuscle::materials
