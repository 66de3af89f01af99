#pragma once
// Field output of an IGA run for ParaView: at each output time the solid is tessellated
// (iga::tessellate: `samples_per_element` hexahedra per knot span and direction) in its DEFORMED
// configuration X + u, and the requested fields — and only those — are written through
// Hdf5XdmfWriter:
//
//   displacement   point field, m
//   J              cell field, det F at the cell centre
//   cauchy_stress  cell field, Cauchy stress (thesis 5.41) at the cell centre, Pa, interpolated
//                  from the converged values at the span's quadrature points
//                  (iga::Problem::state_at); the mixed formulation's pressure p~ replaces U'(J)
//   fibre          cell field, deformed fibre direction a = F N / |F N| (thesis 5.30), N of the
//                  scene's fibre mode at the cell centre
//   activation     cell field, the law's activation level f_t(t) (uniform)
//
// Cell fields are evaluated at cell centres, which never lie on the collapsed axis of a shrink
// solid (where F is undefined), so every value written is a number.
#include <filesystem>
#include <string>
#include <vector>

#include "iga/fibre_directions.hpp"
#include "iga/problem.hpp"
#include "io/hdf5_xdmf_writer.hpp"

namespace isomuscle::io {

class IgaFieldOutput {
 public:
  // fields: names from OutputSettings::field_names(); samples in 1..16.
  IgaFieldOutput(const std::filesystem::path& xdmf_path, std::vector<std::string> fields,
                 int samples, iga::FibreSpec fibre_spec);

  // Writes the committed state of the problem at its committed time.
  void write(const iga::Problem& problem);

  const Hdf5XdmfWriter& writer() const { return writer_; }

 private:
  bool wants(const std::string& field) const;

  Hdf5XdmfWriter writer_;
  std::vector<std::string> fields_;
  int samples_;
  iga::FibreSpec fibre_spec_;
};

}  // namespace isomuscle::io
