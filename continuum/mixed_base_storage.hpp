#pragma once
// The per-element base states of the mixed u–p–J formulation (element_kernels.hpp): at every
// tangent evaluation each element's kernel leaves u_e, theta, pi, R_pi, R_theta, G and K_JJ in its
// workspace; the next evaluations update theta, pi by the linearised local equations from them
// (step-44's static condensation), instead of projecting exactly, which with kappa/mu ~ 1e5 makes
// Newton crawl. Storage for all elements, written during a tangent assembly into a second copy
// and swapped in when the whole assembly succeeded. Shared by iga::Problem and tet::TetProblem.
#include <cstddef>
#include <vector>

#include "continuum/element_kernels.hpp"
#include "continuum/element_workspace.hpp"

namespace isomuscle::continuum {

class MixedBaseStorage {
 public:
  // Blocks of n = 3 n_en or m doubles per element (m: pressure size), G m x n, K_JJ m x m.
  void resize(int elements, int m, int n);
  // The views of element e's base.
  MixedBase view(int e) const;
  // Copies element e's next base from a mixed kernel pass with tangent.
  void store(int e, const ElementWorkspace& ws);
  // Moves element e's base to the displacements ue (3 n_en doubles), keeping theta and pi and
  // taking the constraint residual R_pi there as zero: the next evaluation at ue then sees the
  // base's p~, J~ (the start of a step, mixed_bases.hpp).
  void anchor(int e, const double* ue);

 private:
  std::size_t m_ = 0, n_ = 0;
  std::vector<double> ue_, theta_, pi_, R_pi_, R_theta_, G_, K_JJ_;
};

}  // namespace isomuscle::continuum
