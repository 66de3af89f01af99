// `isomuscle compare RUN_A RUN_B [--json] [--time T] [--subdivisions N] [--points N]`: two runs'
// displacement fields at the same material points (io/run_comparison.hpp), their volumes and run
// times. Exit codes: 0 compared; 1 a run folder cannot be read or the runs have nothing in
// common (the message says which file and why).
#include <iomanip>
#include <iostream>
#include <optional>
#include <string>

#include "app/command_registry.hpp"
#include "io/run_comparison.hpp"

namespace isomuscle::app {

namespace {

struct CompareArgs {
  std::string run_a, run_b;
  bool json = false;
  std::optional<double> time;
  int subdivisions = 4;
  int points = 3;
};

void print_side(const char* label, const io::RunSide& s) {
  std::cout << "  " << label << ": " << s.run.string() << " (" << s.discretisation << ", " << s.dofs
            << " DOFs, " << s.status << ", " << std::setprecision(3) << s.wall_seconds << " s";
  if (s.volume_initial_m3 && s.volume_final_m3) {
    std::cout << ", volume " << std::setprecision(8) << *s.volume_final_m3 << " m^3, change "
              << std::setprecision(3) << *s.volume_final_m3 / *s.volume_initial_m3 - 1.0;
  }
  std::cout << ")\n";
}

int compare(const CompareArgs& args) {
  io::ComparisonOptions options;
  options.time = args.time;
  options.subdivisions = args.subdivisions;
  options.points = args.points;
  io::RunComparison c;
  try {
    c = io::compare_runs(args.run_a, args.run_b, options);
  } catch (const std::exception& e) {
    std::cerr << "isomuscle compare: error: " << e.what() << "\n";
    return 1;
  }
  if (args.json) {
    std::cout << io::to_json(c).dump(2) << "\n";
    return 0;
  }
  std::cout << "isomuscle compare at t = " << c.time << " s: " << c.samples
            << " material points of A's solid";
  if (c.outside_b > 0)
    std::cout << ", " << c.outside_b << " of them outside B (left out)";
  if (c.outside_a > 0)
    std::cout << ", " << c.outside_a << " outside A's own mesh (left out)";
  std::cout << "\n";
  print_side("A", c.a);
  print_side("B", c.b);
  std::cout << std::setprecision(4) << "  max |u_A - u_B| = " << c.max_difference_m << " m at X = ("
            << c.max_difference_at.x() << ", " << c.max_difference_at.y() << ", "
            << c.max_difference_at.z() << "), " << 100.0 * c.relative_max()
            << " % of max |u_A| = " << c.max_displacement_a_m << " m\n"
            << "  L2 |u_A - u_B| / L2 |u_A| = " << 100.0 * c.relative_l2() << " %\n";
  if (c.a.wall_seconds > 0.0)
    std::cout << "  wall time B / A = " << c.b.wall_seconds / c.a.wall_seconds << "\n";
  return 0;
}

const CommandRegistration registration{[](CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Compare two runs' displacement fields at the same material points");
  cmd->add_option("run_a", args->run_a, "Results folder of run A (its solid gives the points)")
      ->required();
  cmd->add_option("run_b", args->run_b, "Results folder of run B")->required();
  cmd->add_flag("--json", args->json, "Print the comparison as JSON");
  cmd->add_option("--time", args->time, "Output time to compare, s (default: A's last)");
  cmd->add_option("--subdivisions", args->subdivisions,
                  "Sub-cells per knot span of A's geometry and direction")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--points", args->points, "Gauss points per sub-cell and direction")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  cmd->callback([args] { set_exit_code(compare(*args)); });
}};

}  // namespace

}  // namespace isomuscle::app
