#pragma once
// summary.json: the machine-readable record of one run (DESIGN.md, "What the user does"): sizes,
// Newton statistics, step cuts, wall time per phase and key results. It is written atomically,
// also for a failed run (status "failed" with the reason), so scripts and `isomuscle compare`
// always find a complete file. Quantities that are unknown (a run that failed before the end) or
// not finite are written as null, never as numbers.
#include <cstddef>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace isomuscle::io {

// A step that failed and was retried with a smaller one (solver::TimeStepper cut-back).
struct StepCut {
  double time = 0.0;       // s, start of the step that failed
  double dt_failed = 0.0;  // s
  double dt_retry = 0.0;   // s
  std::string reason;      // "Newton did not converge in 25 iterations", "J <= 0 at ..."
};

// Wall-clock seconds per phase of the run.
struct WallSeconds {
  double setup = 0.0;          // geometry, refinement, DOF map, sparsity, symbolic analysis
  double assembly = 0.0;       // residual and tangent
  double factorisation = 0.0;  // numeric factorisation
  double solve = 0.0;          // triangular solves
  double output = 0.0;         // HDF5/XDMF, CSV, summary
  double total = 0.0;
};

struct RunSummary {
  bool converged = false;
  std::string failure_reason;  // empty when converged
  std::string scene;           // path of the scene file
  std::string discretisation;  // "iga" or "tet"
  std::vector<int> degrees;    // IGA: (p, q, r); tetrahedra: (order)
  std::size_t elements = 0;
  std::size_t dofs = 0;
  std::size_t steps = 0;              // converged time steps
  std::size_t newton_iterations = 0;  // over all steps, failed attempts included
  std::vector<StepCut> step_cuts;
  std::string linear_solver;  // "cholmod", "umfpack"
  WallSeconds wall_seconds;
  std::optional<double> volume_initial_m3;
  std::optional<double> volume_final_m3;
  std::optional<double> max_displacement_m;
  std::map<std::string, std::optional<double>> probes;  // final value of each probe column
  nlohmann::ordered_json extra = nlohmann::ordered_json::object();  // more top-level keys
};

// The keys every summary.json holds, in the order written.
const std::vector<std::string>& summary_required_keys();

// The JSON document, keys in the order of summary_required_keys() then extra's; throws
// std::invalid_argument when extra is not an object or repeats a required key.
nlohmann::ordered_json summary_to_json(const RunSummary& summary);
// Pretty-printed summary_to_json(summary), written atomically (atomic_file.hpp).
void write_summary(const RunSummary& summary, const std::filesystem::path& path);
// Reads a summary.json back; std::runtime_error naming the file and the missing or mistyped key.
RunSummary read_summary(const std::filesystem::path& path);

}  // namespace isomuscle::io
