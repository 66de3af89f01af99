#pragma once
// Compressible neo-Hookean solid (thesis 4.1, subcutaneous tissue after Tran et al. 2007):
//   U = C10 (Ī1 - 3) + K/2 (J - 1)²,   Ī1 = J^(-2/3) tr C.
// Reading chosen: the thesis prints I1, but with the plain I1 the energy has a stress 2 C10 I at
// F = I (a prestress in the undeformed face). Its coefficients are those of ABAQUS's NEO_HOOKE form
// C10 (Ī1 - 3) + (J - 1)²/D1 with K = 2/D1, which uses the isochoric Ī1, so Ī1 is used here:
// stress-free at F = I, small-strain shear modulus 2 C10 and bulk modulus K, and a volumetric
// split for the mixed u–p–J formulation. The same class serves "linear_elastic"
// (linear_elastic.hpp).
#include <memory>
#include <string>
#include <vector>

#include "materials/material_factory.hpp"
#include "materials/material_law.hpp"

namespace isomuscle::materials {

class ParameterValues;

class NeoHookean final : public MaterialLaw {
 public:
  // psi = mu/2 (Ī1 - 3) + kappa/2 (J - 1)²; mu, kappa in Pa (mu = 2 C10, kappa = K).
  NeoHookean(std::string name, double mu, double kappa);

  std::string name() const override { return name_; }
  PointStatus evaluate(const PointInput& in, PointResult& out,
                       bool compute_tangent = true) const override;
  bool has_volumetric_split() const override { return true; }
  PointStatus evaluate_isochoric(const PointInput& in, PointResult& out,
                                 bool compute_tangent = true) const override;
  Eigen::Vector3d volumetric(double J) const override;
  double shear_modulus() const override { return mu_; }
  double bulk_modulus() const override { return kappa_; }
  // {"iso", "vol"}: (mu/J)(B̄ - Ī1/3 I) and kappa (J - 1) I.
  std::vector<std::string> cauchy_part_names() const override;
  void cauchy_parts(const PointInput& in, std::span<const double> trial_history,
                    std::span<Eigen::Matrix3d> parts) const override;

 private:
  PointStatus evaluate_impl(const PointInput& in, PointResult& out, bool compute_tangent,
                            bool with_volume) const;
  std::string name_;
  double mu_, kappa_;
};

// Parameters "C10" (Pa, default 420) and "K" (Pa, default 36e3) (thesis 4.1, SPEC §4).
const std::vector<ParameterSpec>& neo_hookean_parameters();
std::unique_ptr<MaterialLaw> make_neo_hookean(const ParameterValues& values);

}  // namespace isomuscle::materials
