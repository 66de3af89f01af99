#include "io/tet_run_fields.hpp"

#include <algorithm>

namespace isomuscle::io {

TetFieldOutput::TetFieldOutput(const std::filesystem::path& xdmf_path,
                               std::vector<std::string> fields)
    : writer_(xdmf_path), fields_(std::move(fields)) {}

bool TetFieldOutput::wants(const std::string& field) const {
  return std::find(fields_.begin(), fields_.end(), field) != fields_.end();
}

// gmsh's 10-node order (tet_mesh.hpp: edges 01, 12, 20, 30, 32, 31) to VTK's (edges 01, 12, 02, 03,
// 13, 23): the edge nodes 8 (3-2) and 9 (3-1) swap.
void TetFieldOutput::write(const tet::TetProblem& problem) {
  const tet::TetMesh& mesh = problem.space().mesh();
  const Eigen::VectorXd& u = problem.committed_displacement();
  const Eigen::Index n_points = mesh.num_nodes();
  const Eigen::Index n_cells = mesh.num_elements();
  const int nen = mesh.nodes_per_element();
  OutputMesh out_mesh;
  out_mesh.cell_type = mesh.order == 1 ? CellType::tetrahedron4 : CellType::tetrahedron10;
  out_mesh.points.resize(n_points, 3);
  for (Eigen::Index i = 0; i < n_points; ++i)
    out_mesh.points.row(i) = (mesh.nodes[i] + u.segment<3>(3 * i)).transpose();
  out_mesh.cells.resize(n_cells, nen);
  static constexpr int kVtkFromGmsh[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
  for (Eigen::Index c = 0; c < n_cells; ++c) {
    const auto el = mesh.element(static_cast<int>(c));
    for (int j = 0; j < nen; ++j)
      out_mesh.cells(c, j) = el[nen == 4 ? j : kVtkFromGmsh[j]];
  }
  writer_.set_mesh(out_mesh);

  std::vector<OutputField> out;
  if (wants("displacement")) {
    OutputField f{"displacement", FieldCentre::point, FieldMatrix(n_points, 3)};
    for (Eigen::Index i = 0; i < n_points; ++i)
      f.values.row(i) = u.segment<3>(3 * i).transpose();
    out.push_back(std::move(f));
  }
  const bool want_j = wants("J"), want_sigma = wants("cauchy_stress"), want_fibre = wants("fibre");
  if (want_j || want_sigma || want_fibre) {
    OutputField j{"J", FieldCentre::cell, FieldMatrix::Zero(want_j ? n_cells : 0, 1)};
    OutputField sigma{"cauchy_stress", FieldCentre::cell,
                      FieldMatrix::Zero(want_sigma ? n_cells : 0, 9)};
    OutputField fibre{"fibre", FieldCentre::cell, FieldMatrix::Zero(want_fibre ? n_cells : 0, 3)};
    const int nqp = problem.space().points_per_element();
    for (Eigen::Index c = 0; c < n_cells; ++c) {
      for (int q = 0; q < nqp; ++q) {
        const tet::TetPointState st = problem.state_at_point(static_cast<int>(c), q);
        if (want_j)
          j.values(c, 0) += st.J / nqp;
        if (want_sigma)
          for (int r = 0; r < 3; ++r)
            for (int s = 0; s < 3; ++s)
              sigma.values(c, 3 * r + s) += st.cauchy(r, s) / nqp;
        if (want_fibre && q == 0)
          fibre.values.row(c) = st.fibre_deformed.transpose();
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
