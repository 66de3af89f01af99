#include "io/scene_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "io/csv_writer.hpp"
#include "io/iga_run_model.hpp"
#include "io/material_ellipticity.hpp"
#include "io/process_memory.hpp"
#include "io/run_model.hpp"
#include "io/surface_stability_check.hpp"
#include "io/tet_run_model.hpp"
#include "io/unstable_mode.hpp"
#include "isomuscle/version.hpp"
#include "solver/time_stepper.hpp"

namespace isomuscle::io {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

// A 3-vector as a JSON array [x, y, z] (the summary's positions, normals and directions).
Json xyz_json(const Eigen::Vector3d& v) {
  return Json{v.x(), v.y(), v.z()};
}

constexpr double kFloor = 10.0;  // round-off floors of the Newton tolerances, see newton_settings
constexpr double kCorrection = 1e-7;  // round-off correction tolerance / body size, ditto

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// "0.0181" (three significant digits), for messages.
std::string format_seconds(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", seconds);
  return text;
}

// "0.18984" (five significant digits, as the progress lines): a time of the run, for messages.
std::string format_run_time(double time) {
  char text[32];
  std::snprintf(text, sizeof text, "%.5g", time);
  return text;
}

// Accumulates the wall time of a scope into a total (s).
class ScopedSeconds {
 public:
  explicit ScopedSeconds(double& total) : total_(total), start_(Clock::now()) {}
  ~ScopedSeconds() { total_ += seconds_since(start_); }
  ScopedSeconds(const ScopedSeconds&) = delete;
  ScopedSeconds& operator=(const ScopedSeconds&) = delete;

 private:
  double& total_;
  Clock::time_point start_;
};

// The discretisation's problem as Newton and the time stepper see it, with two additions:
// * a linear-extrapolation predictor (as Abaqus's default): the unknowns are y = u - s, where the
//   shift s is advanced at every step start by v dt, v = (u_n - u_{n-1}) / dt_n the velocity of the
//   last converged step. The stepper starts each step from the last converged y, so Newton starts
//   from u_n + v dt instead of u_n: for a smooth motion (a contraction under way, a constant pull)
//   the initial residual is then that of the change in velocity, not of the whole increment. A
//   step that is cut back is restarted with s recomputed for the shorter dt. Residual and tangent
//   are those of u (dr/dy = dr/du). Where there is no velocity yet (the first step, or after a
//   held state) the problem's own predictor (iga::Problem::predict, linearised Dirichlet) instead:
//   it moves the interior with the prescribed increment, so the first iterate does not squeeze the
//   whole increment into the elements next to the moved face. A step is held when no entry of its
//   increment exceeds the round-off correction tolerance (NewtonSettings::correction_tolerance):
//   a held step's "velocity" is the round-off of its solve (not exactly zero even after a step
//   that starts in equilibrium and needs no iteration), and extrapolating it instead of predicting
//   skipped the predictor at an activation onset after inactive steps, where the first Newton step
//   from u_n is then rejected by the line search (it raises |r| 100-fold on its way into the
//   quadratic basin) and the step was cut four times (chapter-3 set-up 3,
//   examples/barrel/chapter3/README.md).
// * a hook that runs on the converged state just before it is committed (the exact reactions of
//   the probes).
class SteppedProblem final : public solver::NonlinearProblem {
 public:
  SteppedProblem(solver::NonlinearProblem& problem, double held_tolerance,
                 std::function<void(const Eigen::VectorXd&)> before_commit)
      : problem_(problem),
        held_tolerance_(held_tolerance),
        before_commit_(std::move(before_commit)),
        shift_committed_(Eigen::VectorXd::Zero(problem.size())),
        shift_(shift_committed_),
        velocity_(shift_committed_),
        u_committed_(shift_committed_),
        u_(shift_committed_) {}
  int size() const override { return problem_.size(); }
  void begin_step(double time, double dt) override {
    shift_ = shift_committed_;
    shift_.noalias() += dt * velocity_;
    dt_ = dt;
    problem_.begin_step(time, dt);
  }
  solver::EvaluationStatus evaluate(const Eigen::VectorXd& y, Eigen::VectorXd& residual,
                                    solver::SparseMatrix* tangent) override {
    u_ = y + shift_;
    return problem_.evaluate(u_, residual, tangent);
  }
  solver::EvaluationStatus predict(Eigen::VectorXd& y) override {
    if (velocity_.squaredNorm() > 0.0) {
      return solver::EvaluationStatus::success();  // the extrapolation shift predicts
    }
    Eigen::VectorXd u = y + shift_;
    const solver::EvaluationStatus status = problem_.predict(u);
    if (status.ok) {
      y = u - shift_;
    }
    return status;
  }
  void commit_step(const Eigen::VectorXd& y) override {
    u_ = y + shift_;
    if (before_commit_)
      before_commit_(u_);
    problem_.commit_step(u_);
    const Eigen::VectorXd increment = u_ - u_committed_;
    if (increment.size() > 0 && increment.lpNorm<Eigen::Infinity>() <= held_tolerance_)
      velocity_.setZero();  // held: predict the next step, do not extrapolate round-off
    else
      velocity_ = increment / dt_;
    u_committed_ = u_;
    shift_committed_ = shift_;
  }

 private:
  solver::NonlinearProblem& problem_;
  double held_tolerance_;  // m: a step whose increment is below this in every entry is held
  std::function<void(const Eigen::VectorXd&)> before_commit_;
  Eigen::VectorXd shift_committed_, shift_, velocity_, u_committed_, u_;
  double dt_ = 0.0;
};

// Output times of [output]: the listed times and every multiple of `every` up to end, ascending
// and distinct; empty means "every converged step".
std::vector<double> output_times(const OutputSettings& o, double end) {
  std::vector<double> t = o.times;
  if (o.every > 0.0) {
    const long n = static_cast<long>(std::floor(end / o.every * (1.0 + 1e-12)));
    for (long k = 1; k <= n; ++k)
      t.push_back(std::min(end, static_cast<double>(k) * o.every));
  }
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end(),
                      [end](double a, double b) { return std::abs(a - b) <= 1e-12 * end; }),
          t.end());
  return t;
}

// Newton settings of [solver], with absolute floors at round-off level: a relative tolerance of
// |r_0| cannot be met when |r_0| itself is tiny (a step in which little changes, such as the first
// instants of activation or a held state), because the residual of a nearly incompressible body
// carries round-off of about eps kappa |J - 1| per unit area. The floors are
//   residual  atol = kFloor eps max(kappa, mu) V^(2/3)    (N; V the reference volume)
//   energy    eatol = atol kFloor eps^(1/2) V^(1/3)       (J: atol times a displacement correction
//                                                          of ~1e-7 of the body size)
// far below any force or work of interest (for the barrel: atol ~ 2e-9 N against forces of ~10 N).
// The actual floor can still lie a few times above atol (measured on the 1/8 torus: |r| stalls at
// ~2e-9 N), so a residual that stagnates while the corrections are below
//   correction  kCorrection V^(1/3)                      (m: 1e-7 of the body size, nanometres)
// is accepted as converged at round-off (solver::NewtonSettings::correction_tolerance).
solver::NewtonSettings newton_settings(const SolverSettings& s, const RunModel& model) {
  solver::NewtonSettings n;
  n.max_iterations = s.newton_max_iterations;
  n.relative_residual_tolerance = s.tolerance_residual;
  n.relative_energy_tolerance = s.tolerance_energy;
  n.line_search = s.line_search;
  n.max_short_steps = s.stall_iterations;
  n.linear.method = s.linear_solver == LinearSolverKind::cholmod ? solver::LinearMethod::Cholesky
                                                                 : solver::LinearMethod::Lu;
  switch (s.indefinite_tangent) {
    case IndefiniteTangent::lu:
      n.linear.indefinite = solver::IndefiniteResponse::Lu;
      break;
    case IndefiniteTangent::shift:
      n.linear.indefinite = solver::IndefiniteResponse::Shift;
      break;
    case IndefiniteTangent::cut:
      n.linear.indefinite = solver::IndefiniteResponse::Fail;
      break;
  }
  n.linear.blas_threads = s.blas_threads;
  const double volume = model.reference_volume();
  const double modulus = model.modulus_scale();
  const double eps = std::numeric_limits<double>::epsilon();
  n.absolute_residual_tolerance = kFloor * eps * modulus * std::cbrt(volume * volume);
  n.absolute_energy_tolerance =
      n.absolute_residual_tolerance * kFloor * std::sqrt(eps) * std::cbrt(volume);
  n.correction_tolerance = kCorrection * std::cbrt(volume);
  return n;
}

solver::TimeStepperSettings stepper_settings(const TimeSettings& t,
                                             const std::vector<double>& outputs) {
  solver::TimeStepperSettings s;
  s.start_time = 0.0;
  s.end_time = t.end;
  s.initial_dt = t.dt;
  s.min_dt = t.dt_min;
  // Not adaptive: every step is dt, but a step that was cut back grows back to dt afterwards
  // (never beyond), with the same easy-step rule; without regrowth one hard step would leave the
  // rest of the run at the cut size (the robustness matrix's fixed dt = 0.01 s half torus: 3x the
  // time).
  s.max_dt = t.adaptive ? t.dt_max : t.dt;
  for (double x : outputs) {
    if (x > 0.0)
      s.output_times.push_back(x);
  }
  return s;
}

void copy_scene(const Scene& scene, const fs::path& out_dir) {
  std::error_code ec;
  if (!scene.file.empty() && fs::is_regular_file(scene.file, ec) &&
      !fs::equivalent(scene.file, out_dir / "scene.toml", ec)) {
    fs::copy_file(scene.file, out_dir / "scene.toml", fs::copy_options::overwrite_existing, ec);
  }
}

// Why a converged step whose last tangent is indefinite matters to the user (StepRecord::unstable).
constexpr const char* unstable_equilibrium_text =
    "the equilibrium reached is unstable (the potential energy falls along some direction: a "
    "bifurcation or a limit point was passed, e.g. buckling). The LU response of the linear "
    "solver ([solver] indefinite_tangent) follows such a path; a real muscle, with its mass or the "
    "smallest imperfection, leaves it. Results from there on lie on an unstable branch, and a "
    "quantity along the soft direction may change much with the mesh or the data";

}  // namespace

// Set-up, stepping and outputs of one scene (see scene_run.hpp); reads top to bottom.
RunResult run_scene(const Scene& scene, const RunOptions& options) {
  const Clock::time_point start = Clock::now();
  const auto log = [&](const std::string& line) {
    if (options.log)
      options.log(line);
  };
  RunResult result;
  result.out_dir = options.out_dir;
  result.summary_path = options.out_dir / "summary.json";
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec || !fs::is_directory(options.out_dir)) {
    throw std::runtime_error("cannot create the output folder " + options.out_dir.string() + ": " +
                             (ec ? ec.message() : "not a directory"));
  }
  copy_scene(scene, options.out_dir);

  RunSummary& s = result.summary;
  s.scene = scene.file.string();
  s.discretisation = to_string(scene.discretisation);
  s.linear_solver = to_string(scene.solver.linear_solver);
  s.extra["version"] = kVersion;
  s.extra["description"] = scene.description;
  s.extra["material"] = scene.material.model;
  const int threads = options.threads >= 0 ? options.threads : scene.solver.threads;
  s.extra["threads"] = threads;
  WallSeconds& wall = s.wall_seconds;
  const auto finish = [&](const std::string& failure) {
    s.converged = failure.empty();
    s.failure_reason = failure;
    result.converged = s.converged;
    result.failure_reason = failure;
    wall.total = seconds_since(start);
    s.extra["peak_memory_mib"] = peak_resident_mebibytes();
    write_summary(s, result.summary_path);
    return result;
  };

  // ---- Set-up: geometry, discretisation, law, conditions, problem, output files. ----
  std::unique_ptr<RunModel> model;
  std::unique_ptr<CsvWriter> probe_csv, newton_csv;
  const std::vector<double> out_times = output_times(scene.output, scene.time.end);
  try {
    ScopedSeconds timer(wall.setup);
    model = scene.discretisation == Discretisation::iga
                ? make_iga_run_model(scene, threads, options.out_dir)
                : make_tet_run_model(scene, threads, options.out_dir);
    std::vector<std::string> columns{"time", "step", "dt", "newton_iterations"};
    columns.insert(columns.end(), model->probe_columns().begin(), model->probe_columns().end());
    probe_csv = std::make_unique<CsvWriter>(options.out_dir / "probes.csv", columns);
    newton_csv = std::make_unique<CsvWriter>(
        options.out_dir / "newton.csv",
        std::vector<std::string>{"step", "time", "dt", "iteration", "initial_residual_norm",
                                 "residual_norm", "relative_residual", "energy", "relative_energy",
                                 "step_length", "line_search_halvings", "rcond", "lu_fallback",
                                 "shift", "converged"});
  } catch (const std::exception& e) {
    result.setup_failed = true;
    return finish(std::string("set-up failed: ") + e.what());
  }
  solver::NonlinearProblem& problem = model->problem();
  model->describe(s);
  s.extra["fibres"] = to_string(scene.fibres.mode);
  s.extra["notes"] = model->notes();
  Json probe_points = Json::object();
  for (const auto& [name, X] : model->probe_points())
    probe_points[name] = {X.x(), X.y(), X.z()};
  s.extra["probe_points"] = probe_points;
  log("set-up: " + model->setup_line() + ", " + format_seconds(wall.setup) + " s");
  for (const auto& note : model->notes())
    log("note: " + note);

  // ---- Stepping with outputs after every converged step. ----
  const bool every_step = out_times.empty();
  int steps = 0;
  double min_rcond = 1.0;
  bool factorised = false;
  // The smallest and the largest J over the converged steps, and when each was reached.
  std::optional<JacobianAt> min_jacobian, max_jacobian;
  double min_jacobian_time = 0.0, max_jacobian_time = 0.0;
  // Converged steps whose equilibrium is unstable (StepRecord::unstable), the first and last time.
  int unstable_steps = 0;
  std::optional<double> first_unstable, last_unstable;
  bool last_step_unstable = false;
  // The mode of the first unstable equilibrium (unstable_mode.hpp), computed before its commit.
  std::optional<UnstableMode> unstable_mode;
  const std::string mode_file = "unstable_mode.csv";
  // Whether the law itself lost stability there (material_ellipticity.hpp), or why not known.
  std::optional<MaterialEllipticity> material_ellipticity;
  std::string material_ellipticity_failure;
  // Whether the free surface nearest the mode's peak wrinkles as a deformed half-space
  // (surface_stability_check.hpp), or why not known.
  std::optional<SurfaceStabilityCheck> surface_stability;
  std::string surface_stability_failure;
  // Whether the run's element itself is unstable there (element_layer_check.hpp), or why not known.
  std::optional<ElementLayerCheck> element_layer;
  std::string element_layer_failure;
  std::vector<double> probe_row;
  std::optional<std::vector<double>> last_probes;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  std::string failure;
  std::optional<solver::TimeStepper> stepper;
  solver::TimeStepperResult stepped;
  // The cuts as they happen: a stop or an error thrown from a step's callback leaves `stepped`
  // unreturned, and the summary must still list the cuts before it.
  std::vector<solver::StepCut> cuts;
  try {
    const solver::NewtonSettings newton = newton_settings(scene.solver, *model);
    stepper.emplace(stepper_settings(scene.time, out_times), newton);
    if (!out_times.empty() && out_times.front() <= 0.0) {
      ScopedSeconds timer(wall.output);
      model->write_fields();  // the reference state at t = 0
    }
    // A diagnosis: its failure (even a file that cannot be written) is reported, never the run's.
    const auto find_mode = [&](const Eigen::VectorXd& converged) {
      try {
        return compute_unstable_mode(problem, converged, model->free_dof_layout(),
                                     options.out_dir / mode_file);
      } catch (const std::exception& e) {
        UnstableMode failed;
        failed.message = e.what();
        return failed;
      }
    };
    const auto assess_material = [&]() {
      try {
        const auto begin = Clock::now();
        constexpr int normals = 96;  // the coarse set; the refined search is exact to round-off
        MaterialEllipticity m = assess_material_ellipticity(
            model->committed_ellipticity(normals),
            unstable_mode && unstable_mode->ok ? &*unstable_mode : nullptr);
        m.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
        material_ellipticity = m;
      } catch (const std::exception& e) {
        material_ellipticity_failure = e.what();
      }
    };
    const auto assess_surface = [&]() {
      try {
        if (!unstable_mode || !unstable_mode->ok)
          throw std::runtime_error("no mode to place it");
        const std::optional<SurfacePointAt> point =
            model->committed_surface_point(unstable_mode->peak_position);
        if (!point)
          throw std::runtime_error("the body has no traction-free boundary");
        surface_stability = assess_surface_stability(*point);
      } catch (const std::exception& e) {
        surface_stability_failure = e.what();
      }
    };
    const auto assess_element = [&]() {
      try {
        if (!unstable_mode || !unstable_mode->ok)
          throw std::runtime_error("no mode to place it");
        element_layer = model->committed_element_layer(unstable_mode->peak_position);
      } catch (const std::exception& e) {
        element_layer_failure = e.what();
      }
    };
    SteppedProblem stepped_problem(
        problem, newton.correction_tolerance, [&](const Eigen::VectorXd& converged) {
          ScopedSeconds timer(wall.output);
          if (!unstable_mode && stepper->newton().last_solve_ends_on_indefinite_tangent())
            unstable_mode = find_mode(converged);
          model->before_commit(converged);
        });
    // One row per Newton iteration, of converged steps and of failed attempts (converged 0: the
    // step that was cut, numbered as the step it tried to be, at the time it tried to reach), so
    // that a stall before a cut can be read off the file.
    const auto write_newton_rows = [&](int step, double time, double dt,
                                       const solver::NewtonResult& n, bool converged) {
      for (const solver::NewtonIteration& it : n.history) {
        newton_csv->write_row(
            {static_cast<double>(step), time, dt, static_cast<double>(it.iteration),
             n.initial_residual_norm, it.residual_norm, it.relative_residual, it.energy,
             it.relative_energy, it.step_length, static_cast<double>(it.line_search_halvings),
             it.rcond, it.lu_fallback ? 1.0 : 0.0, it.shift, converged ? 1.0 : 0.0});
      }
    };
    const auto on_cut = [&](const solver::StepCut& cut, const solver::NewtonResult& n) {
      ScopedSeconds timer(wall.output);
      cuts.push_back(cut);
      write_newton_rows(steps + 1, cut.time + cut.dt, cut.dt, n, false);
    };
    const auto on_step = [&](const solver::StepInfo& info, const Eigen::VectorXd&) {
      ScopedSeconds timer(wall.output);
      ++steps;
      const solver::StepRecord& r = info.record;
      const solver::NewtonResult& n = info.newton;
      if (n.factorizations > 0) {
        factorised = true;
        min_rcond = std::min(min_rcond, n.min_rcond);
      }
      if (const std::optional<JacobianRangeAt> J = model->committed_jacobian_range()) {
        if (!min_jacobian || J->smallest.value < min_jacobian->value) {
          min_jacobian = J->smallest;
          min_jacobian_time = r.time;
        }
        if (!max_jacobian || J->largest.value > max_jacobian->value) {
          max_jacobian = J->largest;
          max_jacobian_time = r.time;
        }
      }
      last_step_unstable = r.unstable;
      if (r.unstable) {
        ++unstable_steps;
        last_unstable = r.time;
        if (!first_unstable) {
          first_unstable = r.time;
          log("note: t = " + format_run_time(r.time) + " s: " + unstable_equilibrium_text);
          if (unstable_mode)
            log("note: t = " + format_run_time(r.time) +
                " s: the tangent at this equilibrium: " + describe(*unstable_mode, mode_file));
          assess_material();
          log("note: t = " + format_run_time(r.time) + " s: " +
              (material_ellipticity ? describe(*material_ellipticity)
                                    : "the material's ellipticity could not be assessed: " +
                                          material_ellipticity_failure));
          assess_surface();
          log("note: t = " + format_run_time(r.time) + " s: " +
              (surface_stability ? describe(*surface_stability)
                                 : "the free surface's stability could not be assessed: " +
                                       surface_stability_failure));
          assess_element();
          log("note: t = " + format_run_time(r.time) + " s: " +
              (element_layer
                   ? describe(*element_layer)
                   : "the element's own stability was not assessed: " + element_layer_failure));
        }
      }
      write_newton_rows(r.step, r.time, r.dt, n, true);
      model->probe_values(probe_row);
      std::vector<double> row{r.time, static_cast<double>(r.step), r.dt,
                              static_cast<double>(r.newton_iterations)};
      row.insert(row.end(), probe_row.begin(), probe_row.end());
      probe_csv->write_row(row);
      last_probes = probe_row;
      if (every_step || r.output_time) {
        model->write_fields();
        model->write_solution();
      }
      if (options.progress) {
        const solver::NewtonStatistics& ns = stepper->newton().statistics();
        options.progress(RunProgress{steps, r.time, scene.time.end, r.dt, r.newton_iterations,
                                     n.initial_residual_norm, n.final_residual_norm,
                                     ns.solves - ns.converged_solves});
      }
      if (!info.final && options.stop_requested && options.stop_requested())
        throw std::runtime_error(
            "interrupted (SIGINT or SIGTERM); the results up to this step are written");
    };
    stepped = stepper->run(stepped_problem, u, on_step, on_cut);
    if (!stepped.completed)
      failure = stepped.message;
  } catch (const std::exception& e) {
    failure = "at t = " + std::to_string(model->committed_time()) + " s (after " +
              std::to_string(steps) + " converged steps): " + e.what();
  }

  // ---- Summary: statistics, timings, key results of the last converged state. ----
  result.time_reached = model->committed_time();
  s.steps = static_cast<std::size_t>(steps);
  for (const solver::StepCut& c : cuts) {
    s.step_cuts.push_back(StepCut{c.time, c.dt, c.next_dt, c.reason});
  }
  if (stepper) {
    const solver::NewtonStatistics& ns = stepper->newton().statistics();
    const solver::LinearSolverStatistics& ls = stepper->newton().linear_solver().statistics();
    s.newton_iterations = static_cast<std::size_t>(ns.iterations);
    wall.assembly = ns.residual_seconds + ns.tangent_seconds;
    wall.setup += ls.time.symbolic;
    wall.factorisation = ls.time.numeric;
    wall.solve = ls.time.solve;
    s.extra["linear_solver_statistics"] =
        Json{{"method", solver::to_string(stepper->newton().settings().linear.method)},
             {"cholesky_factorizations", ls.cholesky_factorizations},
             {"cholesky_failures", ls.cholesky_failures},
             {"lu_factorizations", ls.lu_factorizations},
             {"indefinite_tangent", to_string(scene.solver.indefinite_tangent)},
             {"lu_fallbacks", ls.lu_fallbacks},
             {"lu_seconds", ls.time.lu},
             {"shifted_factorizations", ls.shifted_factorizations},
             {"failed_shifts", ls.failed_shifts},
             {"max_shift", ls.max_shift},
             {"shifted_seconds", ls.time.shifted},
             {"failures", ls.failures},
             {"symbolic_analyses", ls.symbolic_analyses},
             {"factor_nonzeros", stepper->newton().linear_solver().cholesky().factor_nonzeros()},
             {"min_rcond", factorised ? Json(min_rcond) : Json(nullptr)}};
    const solver::NewtonSettings& nset = stepper->newton().settings();
    s.extra["newton_tolerances"] = Json{{"relative_residual", nset.relative_residual_tolerance},
                                        {"absolute_residual", nset.absolute_residual_tolerance},
                                        {"relative_energy", nset.relative_energy_tolerance},
                                        {"absolute_energy", nset.absolute_energy_tolerance}};
    s.extra["newton"] = Json{{"solves", ns.solves},
                             {"converged_solves", ns.converged_solves},
                             {"residual_evaluations", ns.residual_evaluations},
                             {"tangent_evaluations", ns.tangent_evaluations},
                             {"residual_seconds", ns.residual_seconds},
                             {"tangent_seconds", ns.tangent_seconds}};
  }
  s.extra["time"] = Json{{"end", scene.time.end}, {"reached", result.time_reached}};
  const auto optional_time = [](const std::optional<double>& t) {
    return t ? Json(*t) : Json(nullptr);
  };
  s.extra["stability"] = Json{{"unstable_steps", unstable_steps},
                              {"first_unstable_time", optional_time(first_unstable)},
                              {"last_unstable_time", optional_time(last_unstable)},
                              {"last_step_unstable", last_step_unstable}};
  if (unstable_mode) {
    const UnstableMode& m = *unstable_mode;
    Json mode{{"time", optional_time(first_unstable)}, {"found", m.ok}};
    if (m.ok) {
      mode["eigenvalues"] = std::vector<double>(m.eigenvalues.begin(), m.eigenvalues.end());
      mode["negative"] = m.negative;
      mode["peak_position"] = xyz_json(m.peak_position);
      mode["volume_share"] = m.volume_share;
      mode["radius"] = m.radius;
      mode["file"] = mode_file;
    } else {
      mode["reason"] = m.message;
    }
    mode["shift"] = m.shift;
    mode["factorizations"] = m.factorizations;
    mode["solves"] = m.solves;
    mode["seconds"] = m.seconds;
    s.extra["stability"]["unstable_mode"] = mode;
  }
  if (material_ellipticity) {
    const MaterialEllipticity& m = *material_ellipticity;
    const auto point = [&](const EllipticityAt& p) {
      return Json{{"smallest", p.smallest},
                  {"smallest_over_shear_modulus", p.smallest / m.shear_modulus},
                  {"position", xyz_json(p.position)},
                  {"normal", xyz_json(p.normal)}};
    };
    Json e{{"time", optional_time(first_unstable)},
           {"strongly_elliptic", m.not_elliptic == 0},
           {"points", m.points},
           {"not_elliptic", m.not_elliptic},
           {"not_evaluated", m.not_evaluated},
           {"shear_modulus", m.shear_modulus},
           {"normals", m.normals},
           {"smallest", point(m.smallest)},
           {"seconds", m.seconds}};
    if (m.near_mode) {
      e["near_mode"] = point(m.smallest_near_mode);
      e["near_mode"]["radius"] = m.radius;
      e["near_mode"]["points"] = m.near_mode_points;
    }
    s.extra["stability"]["material_ellipticity"] = e;
  } else if (first_unstable) {
    s.extra["stability"]["material_ellipticity"] =
        Json{{"time", optional_time(first_unstable)}, {"reason", material_ellipticity_failure}};
  }
  if (surface_stability) {
    const SurfaceStabilityCheck& c = *surface_stability;
    s.extra["stability"]["surface_stability"] =
        Json{{"time", optional_time(first_unstable)},
             {"position", xyz_json(c.point.surface_position)},
             {"reference_normal", xyz_json(c.point.normal)},
             {"normal", xyz_json(c.current_normal)},
             {"quadrature_point", xyz_json(c.point.position)},
             {"smallest", c.smallest},
             {"smallest_over_shear_modulus", c.smallest / c.point.shear_modulus},
             {"direction", xyz_json(c.direction)},
             {"free_surface_pressure", c.free_surface_pressure},
             {"element_pressure", c.point.response.pressure},
             {"shear_traction", c.shear_traction},
             {"seconds", c.seconds}};
  } else if (first_unstable) {
    s.extra["stability"]["surface_stability"] =
        Json{{"time", optional_time(first_unstable)}, {"reason", surface_stability_failure}};
  }
  if (element_layer) {
    const ElementLayerCheck& c = *element_layer;
    const auto mode = [](const iga::BlochMode& m) {
      return Json{{"eigenvalue", m.eigenvalue},
                  {"angles", Json{m.angles[0], m.angles[1]}},
                  {"depth_amplitude", m.depth_amplitude}};
    };
    Json same_wave = Json::array();
    for (const auto& [r, eigenvalue] : c.same_wave)
      same_wave.push_back(Json{{"subdivision", r}, {"eigenvalue", eigenvalue}});
    s.extra["stability"]["element_layer"] = Json{
        {"time", optional_time(first_unstable)},
        {"position", xyz_json(c.surface_position)},
        {"degrees", c.layer.degrees},
        {"edges",
         Json{xyz_json(c.layer.edges[0]), xyz_json(c.layer.edges[1]), xyz_json(c.layer.edges[2])}},
        {"depth_spans", c.layer.depth_spans},
        {"pressure_degree", c.layer.pressure_degree},
        {"lowest", mode(c.lowest)},
        {"lowest_halved", mode(c.lowest_halved)},
        {"same_wave", same_wave},
        {"body_column", Json{{"elements", c.column.elements},
                             {"lowest", mode(c.column.lowest)},
                             {"homogeneous", mode(c.column.homogeneous)}}},
        {"shear_modulus", c.shear_modulus},
        {"seconds", c.seconds}};
  } else if (first_unstable) {
    s.extra["stability"]["element_layer"] =
        Json{{"time", optional_time(first_unstable)}, {"reason", element_layer_failure}};
  }
  if (unstable_steps > 0) {
    s.extra["notes"].push_back(
        std::to_string(unstable_steps) + " of " + std::to_string(steps) +
        " converged steps, from t = " + format_run_time(*first_unstable) +
        " s to t = " + format_run_time(*last_unstable) +
        " s, ended on a tangent that is not positive definite: " + unstable_equilibrium_text);
  }
  const auto jacobian_json = [](const std::optional<JacobianAt>& J, double time) {
    if (!J)
      return Json(nullptr);
    return Json{{"value", J->value},
                {"time", time},
                {"position", {J->position.x(), J->position.y(), J->position.z()}}};
  };
  s.extra["min_jacobian"] = jacobian_json(min_jacobian, min_jacobian_time);
  s.extra["max_jacobian"] = jacobian_json(max_jacobian, max_jacobian_time);
  s.extra["outputs"] =
      Json{{"fields", model->field_steps() > 0 ? Json("fields.xdmf") : Json(nullptr)},
           {"field_steps", model->field_steps()},
           {"solution", "solution.h5"},
           {"probes", "probes.csv"},
           {"newton_log", "newton.csv"}};
  try {
    ScopedSeconds timer(wall.output);
    // The last converged state is always in solution.h5 (for comparisons), also when it is not an
    // output time (a failed run).
    if (steps > 0 &&
        (model->solution_steps() == 0 || model->solution_last_time() < model->committed_time()))
      model->write_solution();
    s.volume_final_m3 = model->current_volume();
    s.max_displacement_m = model->max_displacement();
  } catch (const std::exception& e) {
    if (failure.empty())
      failure = std::string("final results: ") + e.what();
  }
  for (std::size_t i = 0; i < model->probe_columns().size(); ++i) {
    s.probes[model->probe_columns()[i]] =
        last_probes ? std::optional<double>((*last_probes)[i]) : std::nullopt;
  }
  if (!failure.empty() && !model->failure_hint().empty())
    failure += " (" + model->failure_hint() + ")";
  return finish(failure);
}

}  // namespace isomuscle::io
