// `isomuscle material ...`: one material point, no mesh.
//   isomuscle material list [--model NAME]
//   isomuscle material uniaxial --model lu2010|tang2009|neo_hookean|linear_elastic
//                               --protocol passive|activated|isometric|concentric
//                               [--dt S] [--param NAME=VALUE ...] --out FILE.csv
// The uniaxial command runs materials::run_uniaxial (thesis §3.5 set-ups, SPEC §2) and writes its
// rows as CSV; the columns are fixed (see kCsvHeader), a Cauchy part or history entry the law does
// not have is an empty field.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/command_registry.hpp"
#include "materials/material_factory.hpp"
#include "materials/uniaxial_driver.hpp"

namespace isomuscle::app {

namespace {

constexpr const char* kCsvHeader =
    "time_s,stretch,eng_strain,eng_stress_Pa,sigma33_Pa,sigma_see_Pa,sigma_pe_Pa,sigma_matrix_Pa,"
    "sigma_vol_Pa,activation,lambda_s,lambda_m";

struct UniaxialArgs {
  std::string model;
  std::string protocol;
  double dt = 1e-3;
  std::vector<std::string> params;
  std::string out;
};

// "NAME=VALUE" pairs from --param into a map; duplicates and non-numbers are errors.
std::map<std::string, double> parse_parameters(const std::vector<std::string>& items) {
  std::map<std::string, double> parameters;
  for (const auto& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size()) {
      throw std::invalid_argument("--param '" + item + "': expected NAME=VALUE, e.g. sigma0=7e5");
    }
    const std::string name = item.substr(0, eq);
    const std::string text = item.substr(eq + 1);
    double value = 0.0;
    std::size_t used = 0;
    try {
      value = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != text.size() || std::isnan(value)) {
      throw std::invalid_argument("--param '" + item + "': '" + text +
                                  "' is not a number (SI units, e.g. 7e5, or inf)");
    }
    if (!parameters.emplace(name, value).second) {
      throw std::invalid_argument("--param '" + name + "' is given twice");
    }
  }
  return parameters;
}

void write_field(std::ostream& os, const std::optional<double>& value) {
  if (value)
    os << *value;
}

void write_csv(std::ostream& os, const materials::UniaxialResult& result) {
  os << kCsvHeader << '\n' << std::setprecision(12);
  for (const auto& r : result.rows) {
    os << r.time_s << ',' << r.stretch << ',' << r.eng_strain << ',' << r.eng_stress_Pa << ','
       << r.sigma33_Pa << ',';
    write_field(os, r.sigma_see_Pa);
    os << ',';
    write_field(os, r.sigma_pe_Pa);
    os << ',';
    write_field(os, r.sigma_matrix_Pa);
    os << ',';
    write_field(os, r.sigma_vol_Pa);
    os << ',' << r.activation << ',';
    write_field(os, r.lambda_s);
    os << ',';
    write_field(os, r.lambda_m);
    os << '\n';
  }
}

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names)
    s += (s.empty() ? "" : ", ") + n;
  return s;
}

void run_uniaxial_command(const UniaxialArgs& args) {
  const auto user = parse_parameters(args.params);
  const auto protocol = materials::make_uniaxial_protocol(args.protocol);
  const auto parameters = materials::uniaxial_material_parameters(args.model, protocol, user);
  const auto law = materials::make_material(args.model, parameters);
  materials::UniaxialOptions options;
  options.dt = args.dt;
  // Open the file first, so that a bad path fails before the run rather than after it.
  std::ofstream file;
  if (args.out != "-") {
    file.open(args.out);
    if (!file)
      throw std::runtime_error("cannot open '" + args.out + "' for writing");
  }

  const auto start = std::chrono::steady_clock::now();
  materials::UniaxialResult result;
  try {
    result = materials::run_uniaxial(*law, protocol, options);
  } catch (...) {
    if (file.is_open()) {  // leave no empty CSV behind
      file.close();
      std::filesystem::remove(args.out);
    }
    throw;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (args.out == "-") {
    write_csv(std::cout, result);
    return;
  }
  write_csv(file, result);
  file.close();
  if (!file)
    throw std::runtime_error("writing '" + args.out + "' failed");
  std::cout << "material uniaxial: model " << args.model << ", protocol " << args.protocol << ", "
            << result.rows.size() - 1 << " steps to t = " << result.rows.back().time_s << " s in "
            << std::setprecision(3) << seconds
            << " s; max |S11|,|S22| = " << result.max_lateral_residual_Pa
            << " Pa; safeguarded steps " << result.safeguarded_steps << "; wrote " << args.out
            << "\n";
}

void list_models(const std::string& only) {
  const auto models = materials::material_models();
  if (!only.empty() && std::find(models.begin(), models.end(), only) == models.end()) {
    throw std::invalid_argument("unknown material model '" + only + "' (valid: " + join(models) +
                                ")");
  }
  for (const auto& model : models) {
    if (!only.empty() && model != only)
      continue;
    std::cout << model << "\n";
    const auto& specs = materials::material_parameters(model);
    std::size_t width = 0;
    for (const auto& p : specs)
      width = std::max(width, p.name.size());
    for (const auto& p : specs) {
      std::ostringstream def;
      def << p.default_value;
      std::cout << "  " << std::left << std::setw(static_cast<int>(width)) << p.name << "  default "
                << std::setw(8) << def.str() << "  range " << std::setw(12)
                << materials::describe_range(p) << "  unit " << std::setw(6)
                << (p.unit.empty() ? "-" : p.unit) << "  " << p.description << "\n";
    }
  }
  std::cout << "uniaxial protocols: " << join(materials::uniaxial_protocol_names()) << "\n";
}

// Runs a command body; errors become a message on stderr and exit code 1.
template <class Body>
void guarded(const char* command, Body body) {
  try {
    body();
    set_exit_code(0);
  } catch (const std::exception& e) {
    std::cerr << "isomuscle " << command << ": error: " << e.what() << "\n";
    set_exit_code(1);
  }
}

void install(CLI::App& app) {
  auto* material = app.add_subcommand("material", "One material point, no mesh (thesis ch. 3)");
  material->require_subcommand(1);

  auto list_model = std::make_shared<std::string>();
  auto* list = material->add_subcommand(
      "list", "Material models and their parameters (defaults, ranges, units)");
  list->add_option("--model", *list_model, "Only this model");
  list->callback([list_model] { guarded("material list", [&] { list_models(*list_model); }); });

  auto args = std::make_shared<UniaxialArgs>();
  auto* uniaxial = material->add_subcommand(
      "uniaxial",
      "Uniaxial test of one material point, lateral faces traction-free (thesis §3.5), CSV out");
  uniaxial->add_option("--model", args->model, "lu2010 | tang2009 | neo_hookean | linear_elastic")
      ->required();
  uniaxial->add_option("--protocol", args->protocol, "passive | activated | isometric | concentric")
      ->required();
  uniaxial->add_option("--dt", args->dt, "Time step in s (each stage takes equal steps <= dt)")
      ->capture_default_str();
  uniaxial->add_option("--param", args->params,
                       "NAME=VALUE (SI units), repeatable; overrides defaults and the protocol's "
                       "activation (n1, n2, t0, t1)");
  uniaxial->add_option("--out", args->out, "CSV file to write ('-' for stdout)")->required();
  uniaxial->callback(
      [args] { guarded("material uniaxial", [&] { run_uniaxial_command(*args); }); });
}

const CommandRegistration registration{install};

}  // namespace

}  // namespace isomuscle::app
