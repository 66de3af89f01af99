#pragma once
// Material-point driver for the uniaxial tests of thesis §3.5 (SPEC §2, set-ups 1–4): a homogeneous
// specimen of length L0 with the fibres along the load axis z and traction-free lateral faces, so
// F = diag(λ_l1, λ_l2, λ) with the axial stretch λ(t) prescribed by the protocol and the lateral
// stretches solved at every step from S11 = S22 = 0. History is committed once per step. The driver
// only computes rows; writing them (CSV) is the caller's business (app/material_commands.cpp).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "materials/material_law.hpp"

namespace isomuscle::materials {

// One stage of a protocol: the moving end travels at a constant velocity (m/s, + lengthens,
// 0 holds the length) for a duration (s).
struct LoadingStage {
  std::string name;
  double duration_s = 0.0;
  double end_velocity_m_per_s = 0.0;
};

// A loading protocol: stages run back to back from t = 0 on a specimen of length length_m; the
// activation entries (n1, n2, t0, t1) are passed to the law when it has parameters of those names.
struct UniaxialProtocol {
  std::string name;
  double length_m = 0.05;  // undeformed specimen length L0 (thesis §3.5: 5.0 cm)
  std::vector<LoadingStage> stages;
  std::map<std::string, double> activation;

  double end_time() const;
  // Axial stretch λ(t) = 1 + (1/L0) ∫ v dt, piecewise linear in t; t is clamped to [0, end_time()].
  double stretch_at(double time_s) const;
};

// "passive", "activated", "isometric", "concentric".
std::vector<std::string> uniaxial_protocol_names();
// The thesis set-ups (SPEC §2, 1–4); throws std::invalid_argument naming the valid choices.
//  passive:    pull at 5 mm/s to 30 % strain (3 s), n1 = n2 = 0;
//  activated:  0.5 s isometric activation (n1 = 0, n2 = 1, t0 = 0, no deactivation), then pull at
//              5 mm/s to 30 % strain (3 s) at full activation;
//  isometric:  ends fixed for 1 s, n1 = 0, n2 = 1, t0 = 0.1 s, t1 = 0.4 s;
//  concentric: 0.4 s isometric activation (t0 = 0, no deactivation), then the moving end goes
//  inward
//              at 5 mm/s until t = 2.4 s (20 % shortening).
UniaxialProtocol make_uniaxial_protocol(const std::string& name);

// Parameters for make_material: the protocol's activation entries that the model has (by name in
// material_parameters(model)), overridden by the user's entries, which are passed on unchecked so
// that the factory reports unknown names and out-of-range values.
std::map<std::string, double> uniaxial_material_parameters(
    const std::string& model, const UniaxialProtocol& protocol,
    const std::map<std::string, double>& user_parameters);

struct UniaxialOptions {
  double dt = 1e-3;  // requested step, s; each stage takes ceil(duration/dt) equal steps <= dt
  int max_lateral_iterations = 50;
  // Lateral traction-free tolerance: |S11|, |S22| <= lateral_rtol * max(|S33|, shear modulus)
  // + 16 eps * bulk modulus (the last term is what a double can resolve when J - 1 is multiplied by
  // the bulk modulus).
  double lateral_rtol = 1e-10;
  long max_steps = 2'000'000;  // refuse runs that would hold more rows than this
};

// One output row (the CSV columns of `isomuscle material uniaxial`, then diagnostics). The Cauchy
// parts are the zz components of the law's cauchy_parts(): "see" (= CE, thesis 3.24), "pe",
// "matrix" (or "iso" for the isotropic laws: σ_I of 3.44), "vol"; a part the law does not have is
// empty (std::nullopt), as are lambda_s and lambda_m for laws without those history entries. Every
// part the law has, named or not, is in parts_zz_Pa and in the check that they sum to σ33.
struct UniaxialRow {
  double time_s = 0.0;
  double stretch = 1.0;        // axial stretch λ = F33
  double eng_strain = 0.0;     // λ - 1
  double eng_stress_Pa = 0.0;  // first Piola P33 = λ S33: axial force per undeformed area
  double sigma33_Pa = 0.0;     // Cauchy σ33 = λ² S33 / J
  std::optional<double> sigma_see_Pa, sigma_pe_Pa, sigma_matrix_Pa, sigma_vol_Pa;
  double activation = 0.0;  // law.activation(time)
  std::optional<double> lambda_s, lambda_m;

  // Diagnostics (not in the CSV).
  double lateral_stretch_1 = 1.0, lateral_stretch_2 = 1.0;  // F11, F22
  double jacobian = 1.0;                                    // J = det F
  double S11_Pa = 0.0, S22_Pa = 0.0;                        // lateral residuals after the solve
  std::vector<double> parts_zz_Pa;                          // every part, in law part-name order
  double parts_sum_error_Pa = 0.0;                          // |Σ parts_zz - σ33|
  int lateral_iterations = 0;
};

struct UniaxialResult {
  std::string law_name;
  std::string protocol_name;
  std::vector<std::string> part_names;  // law.cauchy_part_names()
  std::vector<UniaxialRow> rows;        // row 0: the reference state at t = 0 (see run_uniaxial)
  int safeguarded_steps = 0;  // steps where Newton with the law's tangent failed (see .cpp)
  int bisection_steps = 0;    // of those, steps solved by bisection on the symmetric path
  double max_lateral_residual_Pa = 0.0;
  double max_parts_sum_error_Pa = 0.0;
};

// Runs the protocol on one material point. Row 0 is the law evaluated at the reference length over
// a null step ending at t = 0 (history not committed): it shows what the law gives at zero strain.
// Rows k >= 1 are the ends of the steps. Throws std::invalid_argument for bad options or protocol,
// std::runtime_error when the lateral solve fails (naming the time and stretch) or the law's Cauchy
// parts do not sum to σ33.
UniaxialResult run_uniaxial(const MaterialLaw& law, const UniaxialProtocol& protocol,
                            const UniaxialOptions& options = {});

}  // namespace isomuscle::materials
