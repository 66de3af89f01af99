#include "io/iga_run_model.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "io/iga_run_fields.hpp"
#include "io/iga_run_probes.hpp"
#include "io/iga_run_setup.hpp"
#include "io/iga_surface_point.hpp"
#include "io/solution_file.hpp"

namespace isomuscle::io {

namespace {

using Json = nlohmann::ordered_json;

// The control-point displacements of the committed state (solution_file.hpp): merged control
// points repeat their node's value.
DisplacementRows control_displacements(const iga::Problem& problem) {
  const iga::DofMap& dofs = problem.dofs();
  const Eigen::VectorXd& u = problem.committed_displacement();
  DisplacementRows rows(dofs.num_control_points(), 3);
  for (int a = 0; a < dofs.num_control_points(); ++a)
    rows.row(a) = u.segment<3>(3 * dofs.node(a)).transpose();
  return rows;
}

class IgaRunModel final : public RunModel {
 public:
  IgaRunModel(const Scene& scene, int threads, const std::filesystem::path& out_dir)
      : scene_(scene), model_(build_iga_model(scene, threads)) {
    probes_ = std::make_unique<IgaProbes>(scene.probes, model_);
    if (!scene.output.fields.empty()) {
      fields_ =
          std::make_unique<IgaFieldOutput>(out_dir / "fields.xdmf", scene.output.fields,
                                           scene.output.samples_per_element, model_.fibre_spec);
    }
    solution_ = std::make_unique<SolutionWriter>(out_dir / "solution.h5", model_.unrefined,
                                                 model_.space->volume());
    notes_ = model_.notes;
    for (const auto& note : probes_->notes())
      notes_.push_back(note);
  }

  solver::NonlinearProblem& problem() override { return *model_.problem; }
  double reference_volume() const override { return model_.space->reference_volume(); }
  double modulus_scale() const override {
    return std::max(model_.law->bulk_modulus(), model_.law->shear_modulus());
  }

  void describe(RunSummary& s) const override {
    const iga::Space& space = *model_.space;
    const iga::Problem& problem = *model_.problem;
    s.discretisation = "iga";
    for (int d = 0; d < 3; ++d)
      s.degrees.push_back(space.volume().degree(d));
    s.elements = static_cast<std::size_t>(space.num_elements());
    s.dofs = static_cast<std::size_t>(model_.dofs->num_dofs());
    s.volume_initial_m3 = space.reference_volume();
    s.extra["free_dofs"] = problem.size();
    s.extra["control_points"] = model_.dofs->num_control_points();
    s.extra["nodes"] = model_.dofs->num_nodes();
    s.extra["quadrature_points"] = space.num_points();
    s.extra["formulation"] = iga::to_string(problem.formulation());
    const char* solid_names = "uvw";
    const SceneFrame& frame = model_.frame;
    s.extra["parametric_frame"] =
        Json{{"scene_u_is_solid", std::string(1, solid_names[frame.solid_direction[0]])},
             {"scene_v_is_solid", std::string(1, solid_names[frame.solid_direction[1]])},
             {"around_centreline_reversed", frame.reversed[0]}};
  }

  std::string setup_line() const override {
    const iga::Space& space = *model_.space;
    return std::to_string(space.num_elements()) + " elements of degree (" +
           std::to_string(space.volume().degree(0)) + ", " +
           std::to_string(space.volume().degree(1)) + ", " +
           std::to_string(space.volume().degree(2)) + "), " +
           std::to_string(model_.dofs->num_nodes()) + " nodes, " +
           std::to_string(model_.problem->size()) + " unknowns, " +
           iga::to_string(model_.problem->formulation()) + " formulation, law " +
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
    solution_->write_step(model_.problem->committed_time(), control_displacements(*model_.problem));
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
  ElementLayerCheck committed_element_layer(const Eigen::Vector3d& near) const override {
    const std::optional<SurfaceLocation> where = locate_surface_point(*model_.problem, near);
    if (!where)
      throw std::runtime_error("the body has no traction-free boundary");
    return assess_element_layer(*model_.problem, *where);
  }
  FreeDofLayout free_dof_layout() const override {
    const iga::DofMap& dofs = *model_.dofs;
    FreeDofLayout layout;
    for (int node = 0; node < dofs.num_nodes(); ++node)
      layout.node_positions.push_back(dofs.position(node));
    layout.node_volumes = model_.problem->lumped_volumes();
    for (int dof : model_.problem->constraints().free_dofs()) {
      layout.node_of.push_back(dof / 3);
      layout.component_of.push_back(dof % 3);
    }
    return layout;
  }
  double current_volume() const override {
    return model_.problem->current_volume(model_.problem->committed_displacement());
  }
  // Largest |u| over the tessellation points of the committed state.
  double max_displacement() const override {
    const iga::Tessellation t = model_.problem->tessellate(model_.problem->committed_displacement(),
                                                           scene_.output.samples_per_element);
    double m = 0.0;
    for (const Eigen::Vector3d& u : t.displacement)
      m = std::max(m, u.norm());
    return m;
  }

 private:
  const Scene& scene_;
  IgaModel model_;
  std::unique_ptr<IgaProbes> probes_;
  std::unique_ptr<IgaFieldOutput> fields_;
  std::unique_ptr<SolutionWriter> solution_;
  std::vector<std::string> notes_;
};

}  // namespace

std::unique_ptr<RunModel> make_iga_run_model(const Scene& scene, int threads,
                                             const std::filesystem::path& out_dir) {
  return std::make_unique<IgaRunModel>(scene, threads, out_dir);
}

}  // namespace isomuscle::io
