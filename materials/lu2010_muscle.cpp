#include "materials/lu2010_muscle.hpp"

#include "materials/hill_muscle.hpp"
#include "materials/parameter_values.hpp"

namespace isomuscle::materials {

// Thesis Table 3.10 (and Table 3.7 for the activation constants P14–P19).
const std::vector<ParameterSpec>& lu2010_parameters() {
  static const std::vector<ParameterSpec> specs = {
      make_spec("b", 23.46, 0.0, kInfinity, true, false, "", "matrix exponent b (3.19)"),
      make_spec("c", 379.0, 0.0, kInfinity, true, false, "Pa", "matrix stiffness c (3.19)"),
      make_spec("D", 1.0e-9, 0.0, kInfinity, true, false, "m^2/N",
                "compressibility D of U_J = (J-1)^2/D (3.21)"),
      make_spec("alpha", 10.0, 0.0, kInfinity, true, false, "", "SEE exponent alpha (3.23)"),
      make_spec("beta", 1.0e3, 0.0, kInfinity, true, false, "Pa", "SEE stress scale beta (3.23)"),
      make_spec("A", 4.0, 0.0, kInfinity, false, false, "",
                "PE coefficient A: sigma_PE = sigma0 A (lambda_f-1)^2 (3.41)"),
      make_spec("sigma0", 7.0e5, 0.0, kInfinity, false, false, "Pa",
                "maximal isometric stress sigma0 (3.25; 0.16-1.0 MPa in the literature)"),
      make_spec("S", 50.0, 0.0, kInfinity, true, false, "1/s", "activation rate S (3.27)"),
      make_spec("k_c", 5.0, 0.0, kInfinity, false, false, "",
                "force-velocity shape k_c (3.29; 4-5.88 in the literature)"),
      make_spec("k_e", 5.0, 0.0, kInfinity, false, false, "",
                "force-velocity shape k_e (3.29; 3.14-7.56 in the literature)"),
      make_spec("d", 1.5, 1.0, kInfinity, false, false, "",
                "eccentric force-velocity offset d (3.29; 1.1-1.8 in the literature)"),
      make_spec("lambda_dot_min", -17.0, -kInfinity, 0.0, false, true, "1/s",
                "minimum (fastest shortening) CE stretch rate (3.29)"),
      make_spec("lambda_opt", 1.05, 0.0, kInfinity, true, false, "",
                "optimal fibre stretch lambda_opt (3.28)"),
      make_spec("k", 0.3, 0.0, kInfinity, true, false, "", "length ratio L_SEE0/L_CE0 (D.2)"),
      make_spec("n1", 0.0, 0.0, 1.0, false, false, "",
                "activation level before t0 and after t1 (3.26)"),
      make_spec("n2", 1.0, 0.0, 1.0, false, false, "", "activation level during activation (3.26)"),
      make_spec("t0", 0.0, 0.0, kInfinity, false, false, "s", "activation time t0 (3.26)"),
      make_spec("t1", kInfinity, 0.0, kInfinity, false, false, "s",
                "deactivation time t1 (3.26), >= t0; inf keeps the muscle active"),
      make_spec("ramp_time", 0.0, 0.0, kInfinity, false, false, "s",
                "0: exponential activation (3.26); > 0: linear rise/decay over ramp_time (ch. 5)"),
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
      make_flag(
          "explicit_lag", 0.0,
          "1: f_lambda and force-velocity branch from the previous step (Fortran); 0: current"),
  };
  return specs;
}

std::unique_ptr<MaterialLaw> make_lu2010(const ParameterValues& v) {
  if (v.get("t1") < v.get("t0"))
    v.fail("t1", "is before t0 = " + std::to_string(v.get("t0")) + " s; valid: t1 >= t0");
  HillMuscleParameters p;
  p.name = "lu2010";
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
  f.k_c = v.get("k_c");
  f.a_v = 0.0;
  f.k_e = v.get("k_e");
  f.d = v.get("d");
  f.v_max = -v.get("lambda_dot_min");
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
