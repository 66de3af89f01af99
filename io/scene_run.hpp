#pragma once
// One run of a scene, from the IGES file to a results folder (DESIGN "What the user does";
// `isomuscle run SCENE.toml`), on either discretisation (run_model.hpp):
//
//   set-up   discretisation = "iga" (iga_run_setup.hpp): IGES -> shrink solid -> refinement ->
//            space, DOFs, fibres, law, boundary conditions -> iga::Problem; "tet"
//            (tet_run_setup.hpp): the same solid, the IGES boundary meshed by gmsh -> tetrahedra,
//            fibres by point inversion of the solid, law, conditions -> tet::TetProblem
//   stepping solver::TimeStepper over [0, time.end] with Newton (scene [solver]), steps landing on
//            every output time, cut back on failure down to time.dt_min
//   outputs  after every converged step: a row of probes.csv (iga_run_probes.hpp) and the step's
//            Newton iterations in newton.csv (and those of each failed attempt); at each output
//            time the fields (iga_run_fields.hpp) in fields.h5 + fields.xdmf; at the end
//            summary.json (run_summary.hpp)
//
// The folder then holds:
//   summary.json   status "converged" | "failed" (+ reason), sizes, Newton statistics, step cuts,
//                  linear solver statistics, wall seconds per phase, volumes, max |u|, the
//                  smallest and largest J over the quadrature points (min_jacobian,
//                  max_jacobian: value, time, reference position), probes
//   fields.xdmf    ParaView index of fields.h5 (deformed tessellation per output time)
//   solution.h5    the geometry, the refined solid and its control-point displacements at each
//                  output time and at the last converged one (solution_file.hpp): what
//                  `isomuscle compare` evaluates
//   probes.csv     time, step, dt, newton_iterations, then one column per probe value
//   newton.csv     step, time, dt, iteration, initial_residual_norm, residual_norm, ...,
//                  converged per Newton iteration of every converged step (quadratic convergence
//                  can be read off it) and of every failed attempt (converged 0, before its cut)
//   scene.toml     a copy of the scene
//
// Every file is written as the run goes (HDF5/XDMF and CSV incrementally), so a run that fails
// leaves the results of every converged step, and summary.json says "failed" with the reason.
#include <filesystem>
#include <functional>
#include <string>

#include "io/run_summary.hpp"
#include "io/scene.hpp"

namespace isomuscle::io {

// What a progress display needs after each converged step.
struct RunProgress {
  int step = 0;       // converged steps so far
  double time = 0.0;  // s, end of the step
  double end_time = 0.0;
  double dt = 0.0;                // s
  int newton_iterations = 0;      // of this step
  double initial_residual = 0.0;  // |r_0| of this step
  double residual = 0.0;          // final |r| of this step
  int step_cuts = 0;              // failed attempts before this step converged (all so far)
};

struct RunOptions {
  std::filesystem::path out_dir;  // created when missing; files of an earlier run are replaced
  int threads = -1;               // assembly threads; -1: the scene's [solver] threads (0: all)
  // Set-up and output messages (one line each, no newline); empty: silent.
  std::function<void(const std::string&)> log;
  // Called after every converged step; empty: none.
  std::function<void(const RunProgress&)> progress;
  // Asked after every converged step (its outputs written): true stops the run there as a failure
  // "interrupted", with the summary and the results up to that step written (a user's Ctrl-C, a
  // batch system's time limit). Empty: never.
  std::function<bool()> stop_requested;
};

struct RunResult {
  bool converged = false;
  bool setup_failed = false;  // the run did not start (bad geometry, material, conditions)
  std::string failure_reason;
  double time_reached = 0.0;  // s, last converged time
  std::filesystem::path out_dir;
  std::filesystem::path summary_path;
  RunSummary summary;
};

// Runs the scene (already validated, e.g. by load_scene). Never throws for problems of the model
// or the run: they end in RunResult (converged = false) and summary.json. Throws std::runtime_error
// only when the output folder cannot be created or summary.json cannot be written.
RunResult run_scene(const Scene& scene, const RunOptions& options);

}  // namespace isomuscle::io
