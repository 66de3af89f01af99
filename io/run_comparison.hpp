#pragma once
// Two runs' final displacement fields compared at the same material points (`isomuscle compare
// RUN_A RUN_B`, issue "IGA versus tetrahedra"; the thesis's "almost the same deformation" made a
// number). The material points are a Gauss grid in the parameter space of run A's geometry
// (solution.h5 /geometry: every knot span cut into `subdivisions` sub-cells per direction,
// `points` Gauss points in each), mapped to the reference configuration X = H(xi). At each, u_A
// is evaluated at xi and u_B at X (point inversion of B's solid, or the element of B's
// tetrahedral mesh holding X: solution_sampler.hpp); points that lie outside B (a 1/8 model
// against a whole one, a chord of a straight-sided mesh beyond its tolerance) are counted and left
// out. Reported:
//   max |u_A - u_B| and its place, relative to max |u_A|;
//   L2:  (int |u_A - u_B|^2 dV)^(1/2) / (int |u_A|^2 dV)^(1/2), the integrals by the same Gauss
//        grid with weights det(dX/dxi) w (over the points inside B);
//   both runs' volumes, DOFs and wall times from their summary.json, and the time compared.
#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace isomuscle::io {

struct ComparisonOptions {
  int subdivisions = 4;  // sub-cells per knot span of A's geometry and direction, 1..64
  int points = 3;        // Gauss points per sub-cell and direction, 1..16
  // s: the output time to compare (both runs must have stored it); default A's last one.
  std::optional<double> time;
  void validate() const;  // std::invalid_argument naming the option
};

struct RunSide {
  std::filesystem::path run;
  std::string discretisation;
  std::string status;  // of summary.json
  std::size_t dofs = 0;
  double wall_seconds = 0.0;
  std::optional<double> volume_initial_m3, volume_final_m3;
};

struct RunComparison {
  RunSide a, b;
  double time = 0.0;  // s
  int samples = 0;    // material points of A's grid
  int outside_b = 0;  // of them outside B's solid or mesh (left out)
  int outside_a = 0;  // of them outside A's own mesh (a tetrahedral A: chords of the boundary)
  double max_difference_m = 0.0;
  Eigen::Vector3d max_difference_at = Eigen::Vector3d::Zero();  // X, m
  double max_displacement_a_m = 0.0;
  double l2_difference = 0.0;      // m (m^3)^(1/2)
  double l2_displacement_a = 0.0;  // m (m^3)^(1/2)
  double relative_max() const;     // max difference / max |u_A|
  double relative_l2() const;      // L2 difference / L2 |u_A|
};

// Reads RUN/solution.h5 and RUN/summary.json of both runs. std::runtime_error naming the file
// and the problem: a missing or unreadable file, no common output time, no material point of A
// inside B.
RunComparison compare_runs(const std::filesystem::path& run_a, const std::filesystem::path& run_b,
                           const ComparisonOptions& options = {});

nlohmann::ordered_json to_json(const RunComparison& c);

}  // namespace isomuscle::io
