#pragma once
// The isogeometric discretisation of a scene as a RunModel (run_model.hpp): the model of
// iga_run_setup.hpp with its probes (iga_run_probes.hpp), fields (iga_run_fields.hpp) and
// solution.h5 (solution_file.hpp).
#include <filesystem>
#include <memory>

#include "io/run_model.hpp"
#include "io/scene.hpp"

namespace isomuscle::io {

// Builds the model and opens its output files in out_dir. Throws (std::runtime_error,
// std::invalid_argument) with a message naming the scene setting at fault.
std::unique_ptr<RunModel> make_iga_run_model(const Scene& scene, int threads,
                                             const std::filesystem::path& out_dir);

}  // namespace isomuscle::io
