#pragma once
// The one interface between a constitutive law at a quadrature point and the discretisations (IGA
// and tetrahedra). A law is a function (F, N, t, dt, committed history) -> (S, dS/dE, trial
// history, status); it knows no DOFs, no elements and no quadrature (DESIGN.md, line 3).
//
// Conventions (used by every law and every caller):
// * S is the second Piola–Kirchhoff stress, Pa.
// * The tangent is the 6x6 Voigt matrix of dS/dE (E the Green–Lagrange strain) in the order
//   11, 22, 33, 12, 23, 13: S_voigt = [S11 S22 S33 S12 S23 S13], and dS_voigt = C * dE_voigt with
//   dE_voigt = [dE11 dE22 dE33 2dE12 2dE23 2dE13] (engineering shear). For hyperelastic laws and
//   for the Hill muscle laws (an incremental potential within a step) C is symmetric.
// * History is a flat array of history_size() doubles per quadrature point; the caller keeps the
//   committed copy and passes a scratch copy for the trial values, committing it at convergence.
#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

namespace isomuscle::materials {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

struct PointInput {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();   // deformation gradient at t + dt
  Eigen::Vector3d fibre = Eigen::Vector3d::UnitZ();  // unit undeformed fibre direction N
  double time = 0.0;                                 // t + dt, s
  double dt = 0.0;                                   // step size, s
  std::span<const double> history;                   // committed at the end of the last step
  // true: PointResult::history already holds the trial history that this law wrote, with status
  // ok, for this same input (e.g. Newton's tangent pass at the state its line search has just
  // evaluated). A law with a local update may take its state from it instead of updating again,
  // and leaves it as it is; S and the tangent are the same numbers as without.
  bool trial_is_current = false;
};

enum class PointStatus {
  ok,
  inverted,            // J <= 0: the law is not defined there
  local_solve_failed,  // the law's own iteration (e.g. the Hill series element) did not converge
};

const char* to_string(PointStatus s);

struct PointResult {
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  Matrix6d tangent = Matrix6d::Zero();
  std::span<double> history;  // trial history written by the law (size history_size())
};

class MaterialLaw {
 public:
  virtual ~MaterialLaw() = default;

  virtual std::string name() const = 0;
  virtual int history_size() const { return 0; }
  virtual bool uses_fibre() const { return false; }
  // History of an undeformed, unactivated point at t = 0.
  virtual void initial_history(std::span<double> /*history*/) const {}

  // Full response: S and dS/dE. Never returns NaN with status ok.
  // compute_tangent = false lets a residual-only evaluation skip the tangent.
  // (Implementations in this folder: with compute_tangent = false out.tangent is left untouched;
  // with a status other than ok, out.S is zero and out.history holds the committed values.)
  virtual PointStatus evaluate(const PointInput& in, PointResult& out,
                               bool compute_tangent = true) const = 0;

  // Decoupled laws psi = psi_iso(C_bar, N, history) + U(J) (thesis 3.18, 5.31) expose the two
  // parts, so that a mixed u–p–J formulation can replace U'(J) by an independent pressure.
  virtual bool has_volumetric_split() const { return false; }
  // S and tangent of psi_iso alone. Default: throws std::logic_error.
  virtual PointStatus evaluate_isochoric(const PointInput& in, PointResult& out,
                                         bool compute_tangent = true) const;
  // (U(J), U'(J), U''(J)). Default: throws std::logic_error.
  virtual Eigen::Vector3d volumetric(double J) const;
  // Initial shear and bulk moduli (Pa), for stabilisation scales, penalty sizes and reports.
  virtual double shear_modulus() const = 0;
  virtual double bulk_modulus() const = 0;

  // Reporting (material driver, probes, outputs); none of it is needed by assembly.
  // Names of the history entries, in storage order (e.g. "lambda_s", "lambda_m").
  virtual std::vector<std::string> history_names() const { return {}; }
  // Activation level f_t(time) in [0, 1]; 0 for passive laws.
  virtual double activation(double /*time*/) const { return 0.0; }
  // The Cauchy stress split into the law's named parts, which sum to the total (thesis 3.44), e.g.
  // {"see", "pe", "matrix", "vol"} for the Hill laws. history is the trial history that evaluate()
  // wrote for the same input. Default: one part, "total".
  virtual std::vector<std::string> cauchy_part_names() const { return {"total"}; }
  virtual void cauchy_parts(const PointInput& in, std::span<const double> trial_history,
                            std::span<Eigen::Matrix3d> parts) const;
};

// Voigt helpers shared by laws and callers.
Vector6d to_voigt_stress(const Eigen::Matrix3d& S);
Eigen::Matrix3d from_voigt_stress(const Vector6d& s);

}  // namespace isomuscle::materials
