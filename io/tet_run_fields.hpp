#pragma once
// Field output of a tetrahedral run for ParaView: at each output time the mesh itself in its
// DEFORMED configuration X + u (4- or 10-node tetrahedra, Hdf5XdmfWriter) with the requested
// fields, the same names as on an IGA run (iga_run_fields.hpp):
//   displacement   point field, m
//   J              cell field, det F averaged over the element's quadrature points
//   cauchy_stress  cell field, sigma (thesis 5.41) averaged over the quadrature points, Pa
//   fibre          cell field, the deformed fibre a = F N / |F N| (thesis 5.30) of the first point
//   activation     cell field, f_t(t)
#include <filesystem>
#include <string>
#include <vector>

#include "io/hdf5_xdmf_writer.hpp"
#include "tet/tet_problem.hpp"

namespace isomuscle::io {

class TetFieldOutput {
 public:
  TetFieldOutput(const std::filesystem::path& xdmf_path, std::vector<std::string> fields);

  // Writes the committed state of the problem at its committed time.
  void write(const tet::TetProblem& problem);
  const Hdf5XdmfWriter& writer() const { return writer_; }

 private:
  bool wants(const std::string& field) const;

  Hdf5XdmfWriter writer_;
  std::vector<std::string> fields_;
};

}  // namespace isomuscle::io
