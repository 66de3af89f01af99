#pragma once
// The active skeletal muscle law shared by "lu2010" (thesis chapter 3, LS-DYNA UMAT, Appendix E)
// and "tang2009" (chapter 5, ABAQUS UMAT): decoupled energy (3.18, 5.31)
//   U = c{exp[b(Ī1 - 3)] - 1} + U_f(λ̄f; history) + (J - 1)²/D,   U'_f = σ_SEE + σ_PE,
// stress 5.40, Cauchy stress 5.41, fibre as in hill_fibre.hpp. The two models differ only in their
// parameters (lu2010_muscle.hpp, tang2009_muscle.hpp). PointInput::fibre is normalised here (a
// zero or non-finite fibre throws std::invalid_argument); the history spans must hold
// kHillHistorySize doubles (else std::invalid_argument). The consistent tangent costs no extra
// local iterations (one implicit-function-theorem division after each substep's solve, chained
// through the substeps by forward sensitivity; hill_fibre.hpp).
#include <string>

#include "materials/hill_fibre.hpp"
#include "materials/material_law.hpp"

namespace isomuscle::materials {

struct HillMuscleParameters {
  std::string name = "lu2010";
  double b = 23.46;   // matrix exponent (3.19), dimensionless
  double c = 379.0;   // matrix stiffness (3.19), Pa
  double D = 1.0e-9;  // compressibility (3.21), m²/N = 1/Pa
  HillFibreParameters fibre;
};

class HillMuscle final : public MaterialLaw {
 public:
  explicit HillMuscle(const HillMuscleParameters& p) : p_(p), fibre_(p.fibre) {}

  const HillMuscleParameters& parameters() const { return p_; }
  const HillFibre& fibre() const { return fibre_; }

  std::string name() const override { return p_.name; }
  int history_size() const override { return kHillHistorySize; }
  bool uses_fibre() const override { return true; }
  void initial_history(std::span<double> history) const override;

  PointStatus evaluate(const PointInput& in, PointResult& out,
                       bool compute_tangent = true) const override;
  bool has_volumetric_split() const override { return true; }
  PointStatus evaluate_isochoric(const PointInput& in, PointResult& out,
                                 bool compute_tangent = true) const override;
  Eigen::Vector3d volumetric(double J) const override;
  // 2bc (small-strain shear modulus of 3.19) and 2/D, Pa.
  double shear_modulus() const override { return 2.0 * p_.b * p_.c; }
  double bulk_modulus() const override { return 2.0 / p_.D; }

  std::vector<std::string> history_names() const override;
  double activation(double time) const override { return fibre_.activation(time); }
  // {"see", "pe", "matrix", "vol"}: σ_SEE (= σ_CE) and σ_PE parts (1/J) σ_x λ̄f (n⊗n - I/3), the
  // matrix part (1/J) U'_I (2B̄ - 2/3 Ī1 I) and the volumetric part U'_J I (5.41, 3.44).
  std::vector<std::string> cauchy_part_names() const override;
  void cauchy_parts(const PointInput& in, std::span<const double> trial_history,
                    std::span<Eigen::Matrix3d> parts) const override;

 private:
  PointStatus evaluate_impl(const PointInput& in, PointResult& out, bool compute_tangent,
                            bool with_volume) const;

  HillMuscleParameters p_;
  HillFibre fibre_;
};

}  // namespace isomuscle::materials
