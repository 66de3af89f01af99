#include "io/tet_run_model.hpp"

#include <algorithm>
#include <stdexcept>

#include "io/solution_file.hpp"
#include "io/tet_run_fields.hpp"
#include "io/tet_run_probes.hpp"
#include "io/tet_run_setup.hpp"
#include "io/tet_surface_point.hpp"
#include "tet/tet_mesh.hpp"

namespace isomuscle::io {

namespace {

class TetRunModel final : public RunModel {
 public:
  TetRunModel(const Scene& scene, int threads, const std::filesystem::path& out_dir)
      : model_(build_tet_model(scene, threads)) {
    probes_ = std::make_unique<TetProbes>(scene.probes, model_);
    if (!scene.output.fields.empty())
      fields_ = std::make_unique<TetFieldOutput>(out_dir / "fields.xdmf", scene.output.fields);
    solution_ = std::make_unique<SolutionWriter>(out_dir / "solution.h5", model_.solid.volume,
                                                 *model_.mesh);
    notes_ = model_.notes;
    for (const auto& note : probes_->notes())
      notes_.push_back(note);
  }

  solver::NonlinearProblem& problem() override { return *model_.problem; }
  double reference_volume() const override { return tet::mesh_volume(*model_.mesh); }
  double modulus_scale() const override {
    return std::max(model_.law->bulk_modulus(), model_.law->shear_modulus());
  }

  void describe(RunSummary& s) const override {
    const tet::TetMesh& mesh = *model_.mesh;
    s.discretisation = "tet";
    s.degrees = {mesh.order};
    s.elements = static_cast<std::size_t>(mesh.num_elements());
    s.dofs = static_cast<std::size_t>(3 * mesh.num_nodes());
    s.volume_initial_m3 = tet::mesh_volume(mesh);
    s.extra["free_dofs"] = model_.problem->size();
    s.extra["nodes"] = mesh.num_nodes();
    s.extra["quadrature_points"] = model_.space->num_points();
    s.extra["quadrature_degree"] = model_.space->rule().degree;
    s.extra["formulation"] = tet::to_string(model_.problem->formulation());
  }

  std::string setup_line() const override {
    const tet::TetMesh& mesh = *model_.mesh;
    return std::to_string(mesh.num_elements()) + " tetrahedra of " +
           std::to_string(mesh.nodes_per_element()) + " nodes, " +
           std::to_string(mesh.num_nodes()) + " nodes, " + std::to_string(model_.problem->size()) +
           " unknowns, " + tet::to_string(model_.problem->formulation()) + " formulation, law " +
           model_.law->name();
  }
  const std::vector<std::string>& notes() const override { return notes_; }
  const std::string& failure_hint() const override { return model_.failure_hint; }

  const std::vector<std::string>& probe_columns() const override { return probes_->columns(); }
  void before_commit(const Eigen::VectorXd& u) override {
    probes_->before_commit(*model_.problem, u);
  }
  void probe_values(std::vector<double>& out) override { probes_->values(*model_.problem, out); }
  std::vector<std::pair<std::string, Eigen::Vector3d>> probe_points() const override {
    return probes_->points();
  }

  void write_fields() override {
    if (fields_)
      fields_->write(*model_.problem);
  }
  std::size_t field_steps() const override { return fields_ ? fields_->writer().steps() : 0; }
  void write_solution() override {
    const Eigen::VectorXd& u = model_.problem->committed_displacement();
    DisplacementRows rows(model_.mesh->num_nodes(), 3);
    for (Eigen::Index i = 0; i < rows.rows(); ++i)
      rows.row(i) = u.segment<3>(3 * i).transpose();
    solution_->write_step(model_.problem->committed_time(), rows);
  }
  std::size_t solution_steps() const override { return solution_->steps(); }
  double solution_last_time() const override { return solution_->last_time(); }

  double committed_time() const override { return model_.problem->committed_time(); }
  std::optional<JacobianRangeAt> committed_jacobian_range() const override {
    return committed_jacobian_range_of(*model_.problem);
  }
  MaterialEllipticityScan committed_ellipticity(int normals) const override {
    return committed_ellipticity_of(*model_.problem, normals);
  }
  std::optional<SurfacePointAt> committed_surface_point(
      const Eigen::Vector3d& near) const override {
    return surface_point_at(*model_.problem, locate_surface_point(*model_.problem, near));
  }
  ElementLayerCheck committed_element_layer(const Eigen::Vector3d&) const override {
    throw std::runtime_error("it is made for the knot-span elements of NURBS solids");
  }
  FreeDofLayout free_dof_layout() const override {
    const tet::TetProblem& problem = *model_.problem;
    FreeDofLayout layout;
    layout.node_positions = model_.mesh->nodes;
    layout.node_volumes = problem.lumped_volumes();
    layout.node_of.assign(static_cast<std::size_t>(problem.size()), -1);
    layout.component_of.assign(static_cast<std::size_t>(problem.size()), -1);
    for (int node = 0; node < model_.mesh->num_nodes(); ++node) {
      for (int c = 0; c < 3; ++c) {
        if (const int i = problem.free_index(node, c); i >= 0) {
          layout.node_of[static_cast<std::size_t>(i)] = node;
          layout.component_of[static_cast<std::size_t>(i)] = c;
        }
      }
    }
    return layout;
  }
  double current_volume() const override {
    return model_.problem->current_volume(model_.problem->committed_displacement());
  }
  double max_displacement() const override {
    const Eigen::VectorXd& u = model_.problem->committed_displacement();
    double m = 0.0;
    for (Eigen::Index i = 0; i < u.size() / 3; ++i)
      m = std::max(m, u.segment<3>(3 * i).norm());
    return m;
  }

 private:
  TetModel model_;
  std::vector<std::string> notes_;  // the model's and the probes'
  std::unique_ptr<TetProbes> probes_;
  std::unique_ptr<TetFieldOutput> fields_;
  std::unique_ptr<SolutionWriter> solution_;
};

}  // namespace

std::unique_ptr<RunModel> make_tet_run_model(const Scene& scene, int threads,
                                             const std::filesystem::path& out_dir) {
  return std::make_unique<TetRunModel>(scene, threads, out_dir);
}

}  // namespace isomuscle::io
