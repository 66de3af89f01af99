#include "materials/tang2009_muscle.hpp"

#include "materials/hill_muscle.hpp"
#include "materials/parameter_values.hpp"

namespace isomuscle::materials {

// Thesis Table 5.1 plus λopt (SPEC §3), the activation of 5.6 and the solver switches.
const std::vector<ParameterSpec>& tang2009_parameters() {
  static const std::vector<ParameterSpec> specs = {
      make_spec("b", 1.79, 0.0, kInfinity, true, false, "", "matrix exponent b (5.32)"),
      make_spec("c", 821.0, 0.0, kInfinity, true, false, "Pa", "matrix stiffness c (5.32)"),
      make_spec("D", 1.0e-9, 0.0, kInfinity, true, false, "m^2/N",
                "compressibility D of U_J = (J-1)^2/D (5.33)"),
      make_spec("alpha", 100.0, 0.0, kInfinity, true, false, "", "SEE exponent alpha (5.38)"),
      make_spec("beta", 0.1, 0.0, kInfinity, true, false, "Pa", "SEE stress scale beta (5.38)"),
      make_spec("A", 4.0, 0.0, kInfinity, false, false, "",
                "PE coefficient: sigma_PE = sigma0 A (lambda_f-1)^2 (5.37 has A = 4)"),
      make_spec("sigma0", 2.2e5, 0.0, kInfinity, false, false, "Pa",
                "maximal isometric stress sigma0 (5.37, 5.39)"),
      make_spec("a_v", 7.0e4, 0.0, kInfinity, true, false, "Pa",
                "force-velocity constant a_v: k_c = sigma0 f_lambda / a_v (5.39)"),
      make_spec("k_e", 3.14, 0.0, kInfinity, false, false, "", "force-velocity shape k_e (5.39)"),
      make_spec("d", 1.65, 1.0, kInfinity, false, false, "", "eccentric offset d (5.39)"),
      make_spec("lambda_dot_m0", 2.0, 0.0, kInfinity, true, false, "1/s",
                "reference CE stretch rate: Delta lambda_m0 = lambda_dot_m0 dt (5.39)"),
      make_spec("lambda_opt", 1.05, 0.0, kInfinity, true, false, "",
                "optimal fibre stretch of the force-length curve 3.28 (SPEC §3)"),
      make_spec("k", 0.3, 0.0, kInfinity, true, false, "", "length ratio L_SEE0/L_CE0 (5.54)"),
      make_spec("n1", 0.0, 0.0, 1.0, false, false, "", "activation level before t0 and after t1"),
      make_spec("n2", 1.0, 0.0, 1.0, false, false, "", "activation level during activation"),
      make_spec("t0", 0.0, 0.0, kInfinity, false, false, "s", "activation time t0"),
      make_spec("t1", kInfinity, 0.0, kInfinity, false, false, "s",
                "deactivation time t1, >= t0; inf keeps the muscle active (5.6)"),
      make_spec("S", 50.0, 0.0, kInfinity, true, false, "1/s",
                "activation rate S (3.27), used only when ramp_time = 0"),
      make_spec("ramp_time", 0.005, 0.0, kInfinity, false, false, "s",
                "linear rise to full activation over ramp_time (5.6: 0.005 s); 0: exponential"),
      make_flag("frozen_ce_tangent", 0.0,
                "1: thesis tangent 5.54 (CE length frozen in the step); 0: consistent tangent"),
      make_spec("substeps", 0.0, 0.0, 1000.0, false, false, "",
                "CE/SEE update substeps per time step (integer): 0 adaptive (hill_fibre.hpp), "
                "m >= 1 fixed"),
      make_spec("substep_tolerance", 0.01, 0.0, 1.0, true, false, "",
                "adaptive substeps: bound of alpha Delta lambda_s per substep (hill_fibre.hpp)"),
      make_spec("substep_rule", 0.0, 0.0, 1.0, false, false, "",
                "adaptive substeps from 0: an estimate of the step's SEE stretch, 1: its a-priori "
                "bound (hill_fibre.hpp)"),
      make_flag("explicit_lag", 0.0,
                "1: f_lambda, k_c and force-velocity branch from the previous step; 0: current"),
  };
  return specs;
}

std::unique_ptr<MaterialLaw> make_tang2009(const ParameterValues& v) {
  if (v.get("t1") < v.get("t0"))
    v.fail("t1", "is before t0 = " + std::to_string(v.get("t0")) + " s; valid: t1 >= t0");
  HillMuscleParameters p;
  p.name = "tang2009";
  p.b = v.get("b");
  p.c = v.get("c");
  p.D = v.get("D");
  HillFibreParameters& f = p.fibre;
  f.alpha = v.get("alpha");
  f.beta = v.get("beta");
  f.k = v.get("k");
  f.sigma0 = v.get("sigma0");
  f.A = v.get("A");
  f.lambda_opt = v.get("lambda_opt");
  f.k_c = 0.0;  // replaced by sigma0 f_lambda / a_v
  f.a_v = v.get("a_v");
  f.k_e = v.get("k_e");
  f.d = v.get("d");
  f.v_max = v.get("lambda_dot_m0");
  f.activation.n1 = v.get("n1");
  f.activation.n2 = v.get("n2");
  f.activation.t0 = v.get("t0");
  f.activation.t1 = v.get("t1");
  f.activation.rate = v.get("S");
  f.activation.ramp_time = v.get("ramp_time");
  f.frozen_ce_tangent = v.flag("frozen_ce_tangent");
  f.explicit_lag = v.flag("explicit_lag");
  f.substeps = v.integer("substeps");
  f.substep_see_strain = v.get("substep_tolerance");
  f.substep_rule = v.integer("substep_rule") == 0 ? SubstepRule::estimate : SubstepRule::bound;
  return std::make_unique<HillMuscle>(p);
}

}  // namespace isomuscle::materials
