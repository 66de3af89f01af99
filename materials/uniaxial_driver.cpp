// Material-point driver for the uniaxial set-ups of thesis §3.5 (see uniaxial_driver.hpp).
//
// Lateral solve. With F = diag(a, b, λ), E11 = (a² - 1)/2 and E22 = (b² - 1)/2, so the Jacobian of
// r = (S11, S22) with respect to (a, b) is J_ij = C_ij λ_j (i, j in {1, 2}), C the law's Voigt
// tangent dS/dE. Both lateral stretches are unknowns: a transversely isotropic law about z gives
// a = b, but the driver does not assume it (it reports both). The solve is, in order:
//   1. Newton with the law's tangent and a backtracking line search on |r|;
//   2. if that fails (bad tangent, status not ok, no descent): the same with a central-difference
//      Jacobian;
//   3. if that fails too: bisection on the symmetric path a = b (valid only for laws with
//      S11(a, a) = S22(a, a); checked at the end).
// A step solved by 2 or 3 is counted in UniaxialResult::safeguarded_steps.
#include "materials/uniaxial_driver.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "materials/material_factory.hpp"

namespace isomuscle::materials {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kMillimetrePerSecond = 1e-3;  // m/s
constexpr double kSpecimenLength = 0.05;       // m, thesis §3.5
constexpr double kPullSpeed = 5.0 * kMillimetrePerSecond;
constexpr double kNever = std::numeric_limits<double>::infinity();  // t1 of a held activation

// One material point at F = diag(a, b, λ); buffers are owned by run_uniaxial and reused.
class PointEvaluator {
 public:
  PointEvaluator(const MaterialLaw& law, std::span<const double> committed, std::span<double> trial)
      : law_(law), committed_(committed), trial_(trial) {
    result_.history = trial_;
  }

  void set_step(double time, double dt, double axial) {
    time_ = time;
    dt_ = dt;
    axial_ = axial;
  }

  // Evaluates the law at lateral stretches x; the result (S, tangent, trial history) stays here.
  PointStatus evaluate(const Eigen::Vector2d& x, bool tangent) {
    input_.F.setZero();
    input_.F(0, 0) = x(0);
    input_.F(1, 1) = x(1);
    input_.F(2, 2) = axial_;
    input_.fibre = Eigen::Vector3d::UnitZ();
    input_.time = time_;
    input_.dt = dt_;
    input_.history = committed_;
    result_.history = trial_;
    status_ = law_.evaluate(input_, result_, tangent);
    if (status_ == PointStatus::ok && !result_.S.allFinite()) {
      std::ostringstream msg;
      msg << "uniaxial driver: law '" << law_.name()
          << "' returned a non-finite stress with status "
          << "ok at t = " << time_ << " s";
      throw std::runtime_error(msg.str());
    }
    return status_;
  }

  Eigen::Vector2d residual() const { return {result_.S(0, 0), result_.S(1, 1)}; }

  // dr/dx from the law's tangent: dS_ii/dx_j = C_ij x_j since dE_jj = x_j dx_j.
  Eigen::Matrix2d law_jacobian(const Eigen::Vector2d& x) const {
    Eigen::Matrix2d jac;
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j)
        jac(i, j) = result_.tangent(i, j) * x(j);
    }
    return jac;
  }

  // Tolerance on |S11|, |S22| (see UniaxialOptions::lateral_rtol).
  double tolerance(double rtol) const {
    const double mu = std::max(law_.shear_modulus(), 0.0);
    const double kappa = std::max(law_.bulk_modulus(), 0.0);
    const double scale = std::max({std::abs(result_.S(2, 2)), mu, 1.0});
    return rtol * scale + 16.0 * kEps * kappa;
  }

  const MaterialLaw& law() const { return law_; }
  const PointInput& input() const { return input_; }
  const PointResult& result() const { return result_; }
  PointStatus status() const { return status_; }
  std::span<const double> trial() const { return trial_; }

 private:
  const MaterialLaw& law_;
  std::span<const double> committed_;
  std::span<double> trial_;
  double time_ = 0.0, dt_ = 0.0, axial_ = 1.0;
  PointInput input_;
  PointResult result_;
  PointStatus status_ = PointStatus::ok;
};

enum class JacobianSource { law_tangent, central_difference };

// Central-difference Jacobian of r(x); leaves the evaluator at x again.
bool central_difference_jacobian(PointEvaluator& ev, const Eigen::Vector2d& x,
                                 Eigen::Matrix2d& jac) {
  for (int j = 0; j < 2; ++j) {
    const double h = 1e-6 * x(j);
    Eigen::Vector2d xp = x, xm = x;
    xp(j) += h;
    xm(j) -= h;
    if (ev.evaluate(xp, false) != PointStatus::ok)
      return false;
    const Eigen::Vector2d rp = ev.residual();
    if (ev.evaluate(xm, false) != PointStatus::ok)
      return false;
    const Eigen::Vector2d rm = ev.residual();
    jac.col(j) = (rp - rm) / (2.0 * h);
  }
  return ev.evaluate(x, false) == PointStatus::ok;
}

// Newton on r(x) = (S11, S22) = 0 with a backtracking line search on |r|. On success x holds the
// solution and the evaluator holds the law's result at x. Line-search points are evaluated without
// the tangent, which is computed only where another Newton step is needed (most steps converge
// after one Newton step from the predictor).
bool newton_lateral(PointEvaluator& ev, Eigen::Vector2d& x, JacobianSource source, double rtol,
                    int max_iterations, int& iterations) {
  const bool use_law_tangent = source == JacobianSource::law_tangent;
  if (ev.evaluate(x, use_law_tangent) != PointStatus::ok)
    return false;
  bool have_tangent = use_law_tangent;
  for (int it = 0; it <= max_iterations; ++it) {
    const Eigen::Vector2d r = ev.residual();
    if (r.lpNorm<Eigen::Infinity>() <= ev.tolerance(rtol))
      return true;
    if (it == max_iterations)
      break;
    ++iterations;
    Eigen::Matrix2d jac;
    if (use_law_tangent) {
      if (!have_tangent && ev.evaluate(x, true) != PointStatus::ok)
        return false;
      jac = ev.law_jacobian(x);
    } else if (!central_difference_jacobian(ev, x, jac)) {
      return false;
    }
    const double det = jac.determinant();
    if (!std::isfinite(det) || det == 0.0)
      return false;
    const Eigen::Vector2d dx = -jac.inverse() * r;
    if (!dx.allFinite())
      return false;
    const double merit = r.norm();
    double step = 1.0;
    bool accepted = false;
    for (int k = 0; k < 40 && !accepted; ++k, step *= 0.5) {
      const Eigen::Vector2d xt = x + step * dx;
      if ((xt.array() <= 0.0).any())
        continue;
      if (ev.evaluate(xt, false) != PointStatus::ok)
        continue;
      if (ev.residual().norm() <= (1.0 - 1e-4 * step) * merit) {
        x = xt;
        accepted = true;
      }
    }
    if (!accepted)
      return false;
    have_tangent = false;
  }
  return false;
}

// Bisection on a = b for S11(a, a) = 0, bracketing outwards from the guess. Succeeds only when the
// law is symmetric about z on that path (S22 within tolerance at the root).
bool bisect_symmetric_lateral(PointEvaluator& ev, Eigen::Vector2d& x, double rtol,
                              int& iterations) {
  const double guess = std::sqrt(x(0) * x(1));
  auto g = [&](double s, double& value) {
    if (ev.evaluate(Eigen::Vector2d(s, s), false) != PointStatus::ok)
      return false;
    value = ev.residual()(0);
    return true;
  };
  double lo = guess, hi = guess, glo = 0.0, ghi = 0.0;
  if (!g(guess, glo))
    return false;
  ghi = glo;
  for (double spread = 1e-6; spread < 0.9 && glo * ghi > 0.0; spread *= 2.0) {
    lo = guess * (1.0 - spread);
    hi = guess * (1.0 + spread);
    if (!g(lo, glo) || !g(hi, ghi))
      return false;
    ++iterations;
  }
  if (glo * ghi > 0.0)
    return false;
  for (int k = 0; k < 200 && hi - lo > 4.0 * kEps * hi; ++k) {
    ++iterations;
    const double mid = 0.5 * (lo + hi);
    double gmid = 0.0;
    if (!g(mid, gmid))
      return false;
    if (std::abs(gmid) <= ev.tolerance(rtol)) {
      lo = hi = mid;
      break;
    }
    if ((gmid < 0.0) == (glo < 0.0)) {
      lo = mid;
      glo = gmid;
    } else {
      hi = mid;
    }
  }
  x = Eigen::Vector2d::Constant(0.5 * (lo + hi));
  if (ev.evaluate(x, false) != PointStatus::ok)
    return false;
  return ev.residual().lpNorm<Eigen::Infinity>() <= ev.tolerance(rtol);
}

// Solves the lateral traction-free conditions; returns false when every method failed.
bool solve_lateral(PointEvaluator& ev, Eigen::Vector2d& x, const UniaxialOptions& options,
                   int& iterations, bool& safeguarded, bool& bisected) {
  const Eigen::Vector2d start = x;
  safeguarded = false;
  bisected = false;
  if (newton_lateral(ev, x, JacobianSource::law_tangent, options.lateral_rtol,
                     options.max_lateral_iterations, iterations)) {
    return true;
  }
  safeguarded = true;
  x = start;
  if (newton_lateral(ev, x, JacobianSource::central_difference, options.lateral_rtol,
                     options.max_lateral_iterations, iterations)) {
    return true;
  }
  x = start;
  bisected = true;
  return bisect_symmetric_lateral(ev, x, options.lateral_rtol, iterations);
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

void check_options(const UniaxialOptions& options, const UniaxialProtocol& protocol) {
  if (!(options.dt > 0.0) || !std::isfinite(options.dt)) {
    std::ostringstream msg;
    msg << "uniaxial driver: dt must be a positive number of seconds, got " << options.dt;
    throw std::invalid_argument(msg.str());
  }
  if (options.max_lateral_iterations < 1 || !(options.lateral_rtol > 0.0)) {
    throw std::invalid_argument(
        "uniaxial driver: max_lateral_iterations must be >= 1 and lateral_rtol > 0");
  }
  if (!(protocol.length_m > 0.0) || !std::isfinite(protocol.length_m)) {
    throw std::invalid_argument("uniaxial driver: protocol '" + protocol.name +
                                "' needs a positive specimen length");
  }
  double elapsed = 0.0;
  for (const auto& stage : protocol.stages) {
    if (!(stage.duration_s >= 0.0) || !std::isfinite(stage.duration_s) ||
        !std::isfinite(stage.end_velocity_m_per_s)) {
      throw std::invalid_argument("uniaxial driver: stage '" + stage.name + "' of protocol '" +
                                  protocol.name +
                                  "' needs a finite duration >= 0 and a finite velocity");
    }
    elapsed += stage.duration_s;
    if (!(protocol.stretch_at(elapsed) > 0.0)) {
      throw std::invalid_argument("uniaxial driver: stage '" + stage.name + "' of protocol '" +
                                  protocol.name + "' compresses the specimen to zero length");
    }
  }
  if (!(protocol.end_time() > 0.0)) {
    throw std::invalid_argument("uniaxial driver: protocol '" + protocol.name +
                                "' has no stage of positive duration");
  }
  double steps = 0.0;
  for (const auto& stage : protocol.stages)
    steps += std::ceil(stage.duration_s / options.dt);
  if (steps > static_cast<double>(options.max_steps)) {
    std::ostringstream msg;
    msg << "uniaxial driver: dt = " << options.dt << " s gives " << steps << " steps over "
        << protocol.end_time() << " s, more than max_steps = " << options.max_steps
        << "; use a larger dt";
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace

double UniaxialProtocol::end_time() const {
  double t = 0.0;
  for (const auto& stage : stages)
    t += stage.duration_s;
  return t;
}

// λ(t) = 1 + (1/L0) Σ v_i τ_i, τ_i the time spent in stage i up to t.
double UniaxialProtocol::stretch_at(double time_s) const {
  double travel = 0.0, start = 0.0;
  for (const auto& stage : stages) {
    const double tau = std::clamp(time_s - start, 0.0, stage.duration_s);
    travel += stage.end_velocity_m_per_s * tau;
    start += stage.duration_s;
  }
  return 1.0 + travel / length_m;
}

std::vector<std::string> uniaxial_protocol_names() {
  return {"passive", "activated", "isometric", "concentric"};
}

// Thesis §3.5.1–3.5.4 (SPEC §2, set-ups 1–4). 30 % strain at 5 mm/s on 5 cm takes 3 s. "No
// deactivation" is t1 = inf.
UniaxialProtocol make_uniaxial_protocol(const std::string& name) {
  UniaxialProtocol p;
  p.name = name;
  p.length_m = kSpecimenLength;
  const double pull_time = 0.30 * kSpecimenLength / kPullSpeed;  // 3 s
  if (name == "passive") {
    p.stages = {{"pull", pull_time, kPullSpeed}};
    p.activation = {{"n1", 0.0}, {"n2", 0.0}};
  } else if (name == "activated") {
    p.stages = {{"isometric activation", 0.5, 0.0}, {"pull", pull_time, kPullSpeed}};
    p.activation = {{"n1", 0.0}, {"n2", 1.0}, {"t0", 0.0}, {"t1", kNever}};
  } else if (name == "isometric") {
    p.stages = {{"isometric", 1.0, 0.0}};
    p.activation = {{"n1", 0.0}, {"n2", 1.0}, {"t0", 0.1}, {"t1", 0.4}};
  } else if (name == "concentric") {
    p.stages = {{"isometric activation", 0.4, 0.0}, {"shorten", 2.0, -kPullSpeed}};
    p.activation = {{"n1", 0.0}, {"n2", 1.0}, {"t0", 0.0}, {"t1", kNever}};
  } else {
    throw std::invalid_argument("unknown uniaxial protocol '" + name +
                                "' (valid: passive, activated, isometric, concentric)");
  }
  return p;
}

std::map<std::string, double> uniaxial_material_parameters(
    const std::string& model, const UniaxialProtocol& protocol,
    const std::map<std::string, double>& user_parameters) {
  std::map<std::string, double> parameters;
  const auto& specs = material_parameters(model);
  // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda.
  for (const auto& entry : protocol.activation) {
    const std::string& name = entry.first;
    const bool known = std::any_of(specs.begin(), specs.end(),
                                   [&](const ParameterSpec& s) { return s.name == name; });
    if (known)
      parameters[name] = entry.second;
  }
  for (const auto& [name, value] : user_parameters)
    parameters.insert_or_assign(name, value);
  return parameters;
}

UniaxialResult run_uniaxial(const MaterialLaw& law, const UniaxialProtocol& protocol,
                            const UniaxialOptions& options) {
  check_options(options, protocol);

  UniaxialResult out;
  out.law_name = law.name();
  out.protocol_name = protocol.name;
  out.part_names = law.cauchy_part_names();
  const auto history_names = law.history_names();
  const int n_history = law.history_size();
  const int n_parts = static_cast<int>(out.part_names.size());
  const int i_see = index_of(out.part_names, "see");
  const int i_pe = index_of(out.part_names, "pe");
  // The isotropic laws call their matrix part "iso" (the σ_I of thesis 3.44).
  const int i_matrix = index_of(out.part_names, "matrix") >= 0 ? index_of(out.part_names, "matrix")
                                                               : index_of(out.part_names, "iso");
  const int i_vol = index_of(out.part_names, "vol");
  const int i_lambda_s = index_of(history_names, "lambda_s");
  const int i_lambda_m = index_of(history_names, "lambda_m");

  std::vector<double> committed(static_cast<std::size_t>(n_history), 0.0);
  std::vector<double> trial(committed.size(), 0.0);
  std::vector<Eigen::Matrix3d> parts(static_cast<std::size_t>(n_parts), Eigen::Matrix3d::Zero());
  law.initial_history(committed);
  trial = committed;
  PointEvaluator ev(law, committed, trial);

  // Builds a row from the evaluator's converged state at lateral stretches x.
  auto make_row = [&](double time, const Eigen::Vector2d& x, int iterations) {
    UniaxialRow row;
    const Eigen::Matrix3d& F = ev.input().F;
    const Eigen::Matrix3d& S = ev.result().S;
    const double J = F.determinant();
    const Eigen::Matrix3d sigma = F * S * F.transpose() / J;  // Cauchy stress, Pa
    row.time_s = time;
    row.stretch = F(2, 2);
    row.eng_strain = F(2, 2) - 1.0;
    row.eng_stress_Pa = (F * S)(2, 2);  // first Piola P = F S
    row.sigma33_Pa = sigma(2, 2);
    row.activation = law.activation(time);
    row.lateral_stretch_1 = x(0);
    row.lateral_stretch_2 = x(1);
    row.jacobian = J;
    row.S11_Pa = S(0, 0);
    row.S22_Pa = S(1, 1);
    row.lateral_iterations = iterations;
    law.cauchy_parts(ev.input(), ev.trial(), parts);
    row.parts_zz_Pa.resize(parts.size());
    double sum = 0.0, largest = std::max(std::abs(row.sigma33_Pa), law.shear_modulus());
    for (std::size_t i = 0; i < parts.size(); ++i) {
      row.parts_zz_Pa[i] = parts[i](2, 2);
      sum += parts[i](2, 2);
      largest = std::max(largest, std::abs(parts[i](2, 2)));
    }
    row.parts_sum_error_Pa = std::abs(sum - row.sigma33_Pa);
    if (!(row.parts_sum_error_Pa <= 1e-9 * largest)) {
      std::ostringstream msg;
      msg << "uniaxial driver: the Cauchy parts of law '" << law.name() << "' sum to " << sum
          << " Pa but sigma33 = " << row.sigma33_Pa << " Pa at t = " << time
          << " s (thesis 3.44 requires equality)";
      throw std::runtime_error(msg.str());
    }
    auto part = [&](int i) {
      return i < 0 ? std::optional<double>() : std::optional<double>(row.parts_zz_Pa[i]);
    };
    row.sigma_see_Pa = part(i_see);
    row.sigma_pe_Pa = part(i_pe);
    row.sigma_matrix_Pa = part(i_matrix);
    row.sigma_vol_Pa = part(i_vol);
    const auto hist = ev.trial();
    if (i_lambda_s >= 0)
      row.lambda_s = hist[i_lambda_s];
    if (i_lambda_m >= 0)
      row.lambda_m = hist[i_lambda_m];
    out.max_lateral_residual_Pa =
        std::max({out.max_lateral_residual_Pa, std::abs(row.S11_Pa), std::abs(row.S22_Pa)});
    out.max_parts_sum_error_Pa = std::max(out.max_parts_sum_error_Pa, row.parts_sum_error_Pa);
    return row;
  };

  auto fail = [&](double time, double stretch) {
    std::ostringstream msg;
    msg << "uniaxial driver: the lateral traction-free solve (S11 = S22 = 0) failed for law '"
        << law.name() << "' in protocol '" << protocol.name << "' at t = " << time
        << " s, axial stretch " << stretch << " (last law status: " << to_string(ev.status())
        << "); try a smaller --dt";
    throw std::runtime_error(msg.str());
  };

  long total_steps = 0;
  for (const auto& stage : protocol.stages) {
    if (stage.duration_s > 0.0) {
      total_steps +=
          std::max(1L, static_cast<long>(std::ceil(stage.duration_s / options.dt - 1e-9)));
    }
  }
  out.rows.reserve(static_cast<std::size_t>(total_steps) + 1);

  // Row 0: the reference length over a null step ending at t = 0; history not committed.
  Eigen::Vector2d x(1.0, 1.0);
  {
    const double first_dt = std::min(options.dt, protocol.end_time());
    ev.set_step(0.0, first_dt, protocol.stretch_at(0.0));
    int iterations = 0;
    bool safeguarded = false, bisected = false;
    if (!solve_lateral(ev, x, options, iterations, safeguarded, bisected))
      fail(0.0, 1.0);
    out.safeguarded_steps += safeguarded ? 1 : 0;
    out.bisection_steps += bisected ? 1 : 0;
    out.rows.push_back(make_row(0.0, x, iterations));
    x = Eigen::Vector2d(1.0, 1.0);
  }

  double stage_start = 0.0;
  double previous_stretch = protocol.stretch_at(0.0);
  for (const auto& stage : protocol.stages) {
    if (stage.duration_s <= 0.0)
      continue;
    const long n = std::max(1L, static_cast<long>(std::ceil(stage.duration_s / options.dt - 1e-9)));
    const double h = stage.duration_s / static_cast<double>(n);
    for (long k = 1; k <= n; ++k) {
      const double time =
          stage_start + stage.duration_s * static_cast<double>(k) / static_cast<double>(n);
      const double stretch = protocol.stretch_at(time);
      // Predictor: volume-preserving lateral contraction from the last converged state.
      x *= std::sqrt(previous_stretch / stretch);
      ev.set_step(time, h, stretch);
      int iterations = 0;
      bool safeguarded = false, bisected = false;
      if (!solve_lateral(ev, x, options, iterations, safeguarded, bisected))
        fail(time, stretch);
      out.safeguarded_steps += safeguarded ? 1 : 0;
      out.bisection_steps += bisected ? 1 : 0;
      out.rows.push_back(make_row(time, x, iterations));
      std::copy(trial.begin(), trial.end(), committed.begin());  // commit the step
      previous_stretch = stretch;
    }
    stage_start += stage.duration_s;
  }
  return out;
}

}  // namespace isomuscle::materials
