// `isomuscle run SCENE.toml [--out DIR] [--threads N]`: one isogeometric run of a scene into a
// results folder (io/scene_run.hpp), IGA or tetrahedra, by default runs/<scene name> under the
// current directory. Exit codes: 0 converged; 1 the run failed (set-up or a step that would not
// converge: the folder holds the results up to the last converged step and summary.json the
// reason); 2 the scene file is wrong (the message reads "scene.toml:LINE: ...").
//
// Progress: on a terminal one line, rewritten in place after every step (time, step, Newton
// iterations, residual); otherwise (a log file, a pipe) one plain line per step.
//
// SIGINT (Ctrl-C) or SIGTERM (a batch system's time limit) stops the run after the step under
// way, as a failure "interrupted" with everything up to that step written (exit code 1); a second
// signal ends the process at once.
#include <signal.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

#include "app/command_registry.hpp"
#include "io/scene_loader.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_run.hpp"

namespace isomuscle::app {

namespace {

namespace fs = std::filesystem;

volatile std::sig_atomic_t stop_signal = 0;
// CLOCK_MONOTONIC seconds of the first stop signal (clock_gettime is async-signal-safe).
volatile double first_signal_seconds = 0.0;

double monotonic_seconds() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// A signal within this time of the first is the same request delivered twice (GNU timeout sends
// its signal to the command and then to its whole process group), not a second Ctrl-C.
constexpr double kDuplicateSignalSeconds = 1.0;

extern "C" void on_stop_signal(int signal_number) {
  if (stop_signal != 0) {  // the second one: stop now, unless it is the first one again
    if (monotonic_seconds() - first_signal_seconds < kDuplicateSignalSeconds)
      return;
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
    return;
  }
  first_signal_seconds = monotonic_seconds();
  stop_signal = signal_number;
}

// Installs on_stop_signal for SIGINT and SIGTERM for the lifetime of the object.
class StopOnSignal {
 public:
  StopOnSignal() {
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~StopOnSignal() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
  static bool requested() { return stop_signal != 0; }

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

struct RunArgs {
  std::string scene;
  std::string out;
  int threads = -1;
};

std::string progress_text(const io::RunProgress& p) {
  std::ostringstream line;
  line << "t = " << std::setprecision(4) << std::defaultfloat << p.time << " / " << p.end_time
       << " s  step " << p.step << "  dt " << std::setprecision(3) << p.dt << "  Newton "
       << p.newton_iterations << "  |r| " << std::scientific << std::setprecision(2)
       << p.initial_residual << " -> " << p.residual;
  if (p.step_cuts > 0)
    line << "  cuts " << p.step_cuts;
  return line.str();
}

// One line on the tangents Cholesky found not positive definite (none: nothing), so that the time
// spent on them shows without opening summary.json:
//   indefinite tangents: Cholesky failed 29 times (indefinite_tangent = "lu": 29 LU
//   factorisations, 118 s of the 262 s of factorisation)
void print_indefinite_tangents(const io::RunSummary& s, std::ostream& out) {
  const auto stats = s.extra.find("linear_solver_statistics");
  if (stats == s.extra.end() || !stats->is_object() || !stats->contains("cholesky_failures"))
    return;
  const int failures = stats->at("cholesky_failures").get<int>();
  if (failures == 0)
    return;
  const std::string response = stats->value("indefinite_tangent", std::string("lu"));
  out << "indefinite tangents: Cholesky failed " << failures << " times (indefinite_tangent = \""
      << response << "\": ";
  const auto share = [&](double seconds) {
    out << ", " << std::setprecision(3) << seconds << " s of the " << s.wall_seconds.factorisation
        << " s of factorisation)\n";
  };
  if (response == "lu") {
    out << stats->value("lu_fallbacks", 0) << " LU factorisations";
    share(stats->value("lu_seconds", 0.0));
  } else if (response == "shift") {
    out << stats->value("shifted_factorizations", 0) << " shifted Cholesky factorisations and "
        << stats->value("failed_shifts", 0) << " too small shifts, tau up to "
        << std::setprecision(2) << stats->value("max_shift", 0.0);
    share(stats->value("shifted_seconds", 0.0));
  } else {
    out << "each ended its Newton solve and the step was cut)\n";
  }
}

// One line on the converged steps whose equilibrium is unstable (none: nothing), so that a result
// on an unstable branch is not read as the muscle's response without a warning:
//   unstable equilibria: 12 of 20 converged steps, t = 0.45 to 1 s (...)
void print_unstable_equilibria(const io::RunSummary& s, std::ostream& out) {
  const auto stability = s.extra.find("stability");
  if (stability == s.extra.end() || !stability->is_object() ||
      stability->value("unstable_steps", 0) == 0)
    return;
  out << "unstable equilibria: " << stability->at("unstable_steps").get<int>() << " of " << s.steps
      << " converged steps, t = " << std::setprecision(4)
      << stability->at("first_unstable_time").get<double>() << " to "
      << stability->at("last_unstable_time").get<double>()
      << " s (the tangent of their last Newton iteration is not positive definite: past a "
         "bifurcation or a limit point; see the note in summary.json)\n";
}

int run(const RunArgs& args) {
  // First of all, so that a signal during the set-up (a slow start under load) is a request to
  // stop, not the end of the process without a summary.
  const StopOnSignal stop_on_signal;
  io::Scene scene;
  try {
    scene = io::load_scene(args.scene);
  } catch (const io::SceneError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << args.scene << ": " << e.what() << "\n";
    return 2;
  }
  io::RunOptions options;
  options.out_dir =
      args.out.empty() ? fs::path("runs") / fs::path(args.scene).stem() : fs::path(args.out);
  options.threads = args.threads;
  const bool terminal = isatty(fileno(stderr)) != 0;
  bool line_open = false;
  options.log = [&](const std::string& message) {
    if (line_open) {
      std::cerr << "\n";
      line_open = false;
    }
    std::cerr << message << "\n";
  };
  options.progress = [&](const io::RunProgress& p) {
    if (terminal) {
      std::cerr << "\r\033[K" << progress_text(p) << std::flush;
      line_open = true;
    } else {
      std::cerr << progress_text(p) << "\n";
    }
  };
  std::cout << "isomuscle run: " << args.scene << " -> " << options.out_dir.string() << std::endl;
  io::RunResult result;
  options.stop_requested = [] { return StopOnSignal::requested(); };
  try {
    result = io::run_scene(scene, options);
  } catch (const std::exception& e) {
    if (line_open)
      std::cerr << "\n";
    std::cerr << "isomuscle run: error: " << e.what() << "\n";
    return 1;
  }
  if (line_open)
    std::cerr << "\n";
  const io::RunSummary& s = result.summary;
  if (result.setup_failed) {
    std::cerr << "isomuscle run: error: " << result.failure_reason << "\n"
              << "(summary: " << result.summary_path.string() << ")\n";
    return 1;
  }
  if (!result.converged) {
    std::cerr << "isomuscle run: FAILED at t = " << result.time_reached
              << " s: " << result.failure_reason << "\n"
              << "partial results (" << s.steps
              << " converged steps, up to t = " << result.time_reached << " s) in "
              << result.out_dir.string() << "\n";
    print_indefinite_tangents(s, std::cerr);
    print_unstable_equilibria(s, std::cerr);
    return 1;
  }
  std::cout << "converged: " << s.steps << " steps, " << s.newton_iterations
            << " Newton iterations, " << s.step_cuts.size() << " step cuts, " << s.dofs << " DOFs, "
            << std::setprecision(3) << s.wall_seconds.total << " s\n";
  print_indefinite_tangents(s, std::cout);
  print_unstable_equilibria(s, std::cout);
  if (s.max_displacement_m)
    std::cout << "max |u| = " << std::setprecision(6) << *s.max_displacement_m << " m\n";
  if (s.volume_initial_m3 && s.volume_final_m3) {
    std::cout << "volume " << std::setprecision(8) << *s.volume_initial_m3 << " -> "
              << *s.volume_final_m3 << " m^3 (change " << std::setprecision(3)
              << 100.0 * (*s.volume_final_m3 / *s.volume_initial_m3 - 1.0) << " %)\n";
  }
  // The pointwise volume change, which the whole-body volume above does not show (the mixed
  // formulation holds each element's mean J~, not J at every point).
  const auto j_min = s.extra.find("min_jacobian");
  const auto j_max = s.extra.find("max_jacobian");
  if (j_min != s.extra.end() && j_max != s.extra.end() && j_min->is_object() &&
      j_max->is_object()) {
    std::cout << "J = det F at the quadrature points of the converged steps: "
              << std::setprecision(4) << j_min->at("value").get<double>() << " to "
              << j_max->at("value").get<double>() << "\n";
  }
  std::cout << "results in " << result.out_dir.string()
            << " (summary.json, fields.xdmf for ParaView, probes.csv, newton.csv)\n";
  return 0;
}

const CommandRegistration registration{[](CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand("run", "Run a scene (TOML) into a results folder");
  cmd->add_option("scene", args->scene, "Scene file (.toml)")->required();
  cmd->add_option("--out", args->out, "Results folder (default: runs/<scene name>)");
  cmd->add_option("--threads", args->threads, "Assembly threads (0: all cores; default: scene)")
      ->check(CLI::Range(0, 4096));
  cmd->callback([args] { set_exit_code(run(*args)); });
}};

}  // namespace

}  // namespace isomuscle::app
