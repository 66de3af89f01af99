#include "io/iga_run_fields.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <stdexcept>

#include "iga/field_evaluation.hpp"

namespace isomuscle::io {

IgaFieldOutput::IgaFieldOutput(const std::filesystem::path& xdmf_path,
                               std::vector<std::string> fields, int samples,
                               iga::FibreSpec fibre_spec)
    : writer_(xdmf_path),
      fields_(std::move(fields)),
      samples_(samples),
      fibre_spec_(std::move(fibre_spec)) {}

bool IgaFieldOutput::wants(const std::string& field) const {
  return std::find(fields_.begin(), fields_.end(), field) != fields_.end();
}

// Deformed tessellation X + u and the requested fields at the committed state (thesis 5.30, 5.41).
void IgaFieldOutput::write(const iga::Problem& problem) {
  const Eigen::VectorXd& u_full = problem.committed_displacement();
  const iga::Tessellation tess = problem.tessellate(u_full, samples_);
  const Eigen::Index n_points = static_cast<Eigen::Index>(tess.reference.size());
  const Eigen::Index n_cells = static_cast<Eigen::Index>(tess.hexahedra.size());

  OutputMesh mesh;
  mesh.cell_type = CellType::hexahedron8;
  mesh.points.resize(n_points, 3);
  for (Eigen::Index i = 0; i < n_points; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    mesh.points.row(i) = (tess.reference[k] + tess.displacement[k]).transpose();
  }
  mesh.cells.resize(n_cells, 8);
  for (Eigen::Index c = 0; c < n_cells; ++c) {
    for (int j = 0; j < 8; ++j)
      mesh.cells(c, j) = tess.hexahedra[static_cast<std::size_t>(c)][static_cast<std::size_t>(j)];
  }
  writer_.set_mesh(mesh);

  std::vector<OutputField> out;
  if (wants("displacement")) {
    OutputField f{"displacement", FieldCentre::point, FieldMatrix(n_points, 3)};
    for (Eigen::Index i = 0; i < n_points; ++i)
      f.values.row(i) = tess.displacement[static_cast<std::size_t>(i)].transpose();
    out.push_back(std::move(f));
  }
  const bool want_j = wants("J"), want_sigma = wants("cauchy_stress"), want_fibre = wants("fibre");
  if (want_j || want_sigma || want_fibre) {
    OutputField j{"J", FieldCentre::cell, FieldMatrix(want_j ? n_cells : 0, 1)};
    OutputField sigma{"cauchy_stress", FieldCentre::cell, FieldMatrix(want_sigma ? n_cells : 0, 9)};
    OutputField fibre{"fibre", FieldCentre::cell, FieldMatrix(want_fibre ? n_cells : 0, 3)};
    // The cells of one knot span come one after another: its quadrature point states are
    // computed once (one kernel pass) and interpolated to each cell centre.
    int states_element = -1;
    std::vector<iga::PointState> states;
    for (Eigen::Index c = 0; c < n_cells; ++c) {
      Eigen::Vector3d xi = Eigen::Vector3d::Zero();
      for (int k : tess.hexahedra[static_cast<std::size_t>(c)])
        xi += tess.parametric[static_cast<std::size_t>(k)];
      xi /= 8.0;
      const iga::FieldPoint p = iga::evaluate_field(problem.space(), problem.dofs(), u_full, xi);
      if (!p.regular) {
        throw std::runtime_error("field output: the cell centre xi = (" + std::to_string(xi[0]) +
                                 ", " + std::to_string(xi[1]) + ", " + std::to_string(xi[2]) +
                                 ") is a singular point of the parametrisation");
      }
      if (want_j)
        j.values(c, 0) = p.F.determinant();
      if (want_sigma) {
        if (p.element != states_element) {
          states = problem.element_states(p.element);
          states_element = p.element;
        }
        const iga::PointState st = problem.interpolate_state(p.element, states, xi);
        for (int r = 0; r < 3; ++r)
          for (int s = 0; s < 3; ++s)
            sigma.values(c, 3 * r + s) = st.cauchy(r, s);
      }
      if (want_fibre) {
        const Eigen::Vector3d N = iga::fibre_direction(fibre_spec_, p.jacobian, p.X, xi);
        const Eigen::Vector3d FN = p.F * N;
        fibre.values.row(c) = (FN / FN.norm()).transpose();
      }
    }
    if (want_j)
      out.push_back(std::move(j));
    if (want_sigma)
      out.push_back(std::move(sigma));
    if (want_fibre)
      out.push_back(std::move(fibre));
  }
  if (wants("activation")) {
    const double level = problem.law().activation(problem.committed_time());
    out.push_back({"activation", FieldCentre::cell, FieldMatrix::Constant(n_cells, 1, level)});
  }
  writer_.write_step(problem.committed_time(), out);
}

}  // namespace isomuscle::io
