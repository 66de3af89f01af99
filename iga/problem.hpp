#pragma once
// The isogeometric nonlinear problem (DESIGN "The way data flows"): a NURBS solid as the mesh, a
// material law at every quadrature point, Dirichlet conditions on control points and dead loads,
// offered to Newton and the time stepper through solver::NonlinearProblem.
//
// * Unknowns: the free DOFs of ConstrainedDofs; prescribed values are set in begin_step.
// * evaluate(): r = f_int(u) - f_ext(t) on the free DOFs, and K = dr/du when asked, assembled with
//   a sparsity pattern and scatter map built once (solver::SparsityPattern) by element colouring
//   (solver::ElementColouring): deterministic whatever the thread count.
// * Formulation: (a) displacement, or (b) the mixed u–p–J three-field formulation condensed per
//   element (element_kernels.hpp), automatically (b) for laws with a volumetric split.
// * History: per quadrature point, committed copy + trial copy (laws with history_size() > 0);
//   evaluate() writes the trial copy, commit_step() makes it the committed one.
// * Failures (J <= 0 at a quadrature point, J~ <= 0, a failed local material solve) return a
//   failure status naming the element, the quadrature point, its position and the value.
#include <Eigen/Core>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "continuum/formulation.hpp"
#include "continuum/jacobian_range.hpp"
#include "continuum/mixed_bases.hpp"
#include "continuum/point_ellipticity.hpp"
#include "continuum/point_state.hpp"
#include "iga/boundary_conditions.hpp"
#include "iga/dof_map.hpp"
#include "iga/elastic_support.hpp"
#include "iga/element_kernels.hpp"
#include "iga/field_evaluation.hpp"
#include "iga/loads.hpp"
#include "iga/periodic_layer_stability.hpp"
#include "iga/pressure_space.hpp"
#include "iga/space.hpp"
#include "materials/material_law.hpp"
#include "solver/element_colouring.hpp"
#include "solver/linear_solver.hpp"
#include "solver/matrix_storage.hpp"
#include "solver/nonlinear_problem.hpp"
#include "solver/predictor_system.hpp"
#include "solver/sparsity_pattern.hpp"

namespace isomuscle::iga {

// The formulation is that of continuum/formulation.hpp (shared with tet/).
using continuum::Formulation;
using continuum::parse_formulation;
using continuum::to_string;

struct ProblemOptions {
  // automatic: mixed when the law has a volumetric split AND is nearly incompressible,
  // bulk_modulus() >= mixed_threshold * shear_modulus(); else displacement. mixed with a law
  // without split throws. Why the threshold: with p~, J~ constant per element the isochoric
  // energy does not see a dilatation of zero element mean at all, so for a compressible solid
  // the mixed element is too soft on coarse meshes (a 2 x 1 x 1 cantilever, p = 2, kappa/mu = 5:
  // smallest tangent eigenvalue 0.66 instead of 12.6, first Newton step 20 times too long),
  // while the displacement formulation only locks when kappa/mu is large.
  Formulation formulation = Formulation::automatic;
  double mixed_threshold = 100.0;  // kappa/mu; nu = 0.495
  // Degree k of the element-wise p~, J~ spaces (0 = mean dilatation; see pressure_space.hpp).
  int pressure_degree = 0;
  // Assembly threads; 0 = OpenMP default.
  int threads = 0;
  // Storage of the tangent (the linear solver's settings must agree).
  solver::MatrixStorage storage = solver::MatrixStorage::Upper;
  solver::ScatterMode scatter = solver::ScatterMode::Stored;
  // Throws std::invalid_argument naming the option.
  void validate() const;
};

// Material state at one point of the committed state, for outputs: the stress and fibre outputs of
// continuum::PointStress (J, J~, p~, S, sigma, N, a, lambda_f) and the field at the point.
struct PointState : continuum::PointStress {
  FieldPoint field;  // position, displacement, F
};

class Problem : public solver::NonlinearProblem {
 public:
  // space, dofs and law must outlive the problem. fibres: one unit vector per quadrature point
  // (fibre_directions(space, spec)). Throws std::invalid_argument for inconsistent sizes, bad
  // options or conditions.
  Problem(const Space& space, const DofMap& dofs, const materials::MaterialLaw& law,
          std::vector<Eigen::Vector3d> fibres, const DirichletConditions& conditions,
          Loads loads = {}, ProblemOptions options = {});
  ~Problem() override;

  // --- solver::NonlinearProblem ---
  int size() const override { return constraints_.num_free(); }
  void begin_step(double time, double dt) override;
  solver::EvaluationStatus evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& residual,
                                    solver::SparseMatrix* tangent) override;
  void commit_step(const Eigen::VectorXd& u) override;

  // Predictor for the step set up by begin_step (the consistent-tangent / linearised Dirichlet
  // predictor of step-44 and FE codes): from the committed state u_n with the tangent there,
  //   K_ff du_f = -(f_int(u_n) + K_fp du_p - f_ext(t_n+1))_f,  du_p = prescribed increment,
  // and u <- u + du_f. Without it the first Newton iterate of a step sees the prescribed jump of
  // the boundary control points alone, with the interior at rest: for kappa/mu ~ 1e5 the
  // distorted boundary layer carries pressures ~ kappa du_p / h, its tangent is indefinite and
  // the full Newton step inverts elements (measured on the barrel). u must hold the committed
  // free values (size()); on failure u is unchanged and the status says why.
  solver::EvaluationStatus predict(Eigen::VectorXd& u) override;

  // --- set-up ---
  // Springs on parametric sides (elastic_support.hpp), in the residual and tangent of every
  // evaluation and the predictor from then on; internal_force leaves them out. Throws like
  // support_element_matrices.
  void set_elastic_supports(const std::vector<ElasticSupport>& supports);
  const std::vector<ElasticSupport>& elastic_supports() const { return support_settings_; }
  Formulation formulation() const { return formulation_; }  // resolved (never automatic)
  const ProblemOptions& options() const { return options_; }
  void set_threads(int threads);
  const Space& space() const { return space_; }
  const DofMap& dofs() const { return dofs_; }
  const materials::MaterialLaw& law() const { return law_; }
  const ConstrainedDofs& constraints() const { return constraints_; }
  const solver::SparsityPattern& pattern() const { return pattern_; }
  int num_colours() const { return colouring_.n_colours(); }
  double time() const { return time_; }
  double dt() const { return dt_; }

  // --- state ---
  // Full displacement (all DOFs, 3 node + c) of free values u at the current time.
  Eigen::VectorXd full_displacement(const Eigen::VectorXd& u) const;
  // Committed state (zero before the first commit).
  const Eigen::VectorXd& committed_free() const { return committed_free_; }
  const Eigen::VectorXd& committed_displacement() const { return committed_full_; }
  double committed_time() const { return committed_time_; }
  // The step size of the committed step (what the kernel passes of the outputs use).
  double committed_dt() const { return committed_dt_; }
  // Smallest and largest J = det F over the quadrature points of the committed state (with their
  // elements and local points; found() is false before the first commit).
  const continuum::JacobianRange& committed_jacobian_range() const { return committed_J_range_; }
  std::span<const double> committed_history(int element, int point) const;
  const std::vector<Eigen::Vector3d>& fibres() const { return fibres_; }
  // External force at the current time (all DOFs), N.
  const Eigen::VectorXd& external_force() const { return f_ext_; }

  // --- outputs ---
  // Internal force at ALL DOFs for free values u (an assembly pass without tangent). The trial
  // history is scratch and may change; the committed state does not. At the free values of the
  // last evaluation (the converged state, before commit_step) the law reads its trial history.
  solver::EvaluationStatus internal_force(const Eigen::VectorXd& u, Eigen::VectorXd& f_int);
  // Sum over nodes of the force components of a full force vector: the reaction on a supported
  // face is the internal force at its DOFs (N).
  Eigen::Vector3d sum_over_nodes(const Eigen::VectorXd& f_full, std::span<const int> nodes) const;
  // F at every quadrature point (element-major) of a full displacement vector.
  std::vector<Eigen::Matrix3d> deformation_gradients(const Eigen::VectorXd& u_full) const;
  // Current volume int J dV of a full displacement vector (m^3).
  double current_volume(const Eigen::VectorXd& u_full) const;
  // Lumped reference volume of every node, int R_a dV summed over its control points (m^3): the
  // row sums of the consistent mass per unit density, positive because the NURBS basis is. They
  // sum to the reference volume.
  Eigen::VectorXd lumped_volumes() const;
  // Displacement at a parametric point (m).
  Eigen::Vector3d displacement_at(const Eigen::VectorXd& u_full, const Eigen::Vector3d& xi) const;
  // Stress, J, fibre at a parametric point of the COMMITTED state: sigma, J~, p~ and the reference
  // fibre interpolated from the converged values at the quadrature points of its element
  // (quadrature_point_interpolation.hpp; exact at a quadrature point, also for rate-dependent
  // laws), u and F evaluated at xi. Throws std::invalid_argument on the collapsed axis
  // (det dX/dxi = 0, F undefined) and std::runtime_error when the committed state fails there.
  PointState state_at(const Eigen::Vector3d& xi) const;
  // The same at quadrature point q of element e (the converged values).
  PointState state_at_point(int e, int q) const;
  // The states at all quadrature points of element e, from one kernel pass over the element
  // (exactly the converged values).
  std::vector<PointState> element_states(int e) const;
  // state_at(xi) from element e's element_states (to evaluate many points of one element).
  PointState interpolate_state(int e, std::span<const PointState> states,
                               const Eigen::Vector3d& xi) const;
  Tessellation tessellate(const Eigen::VectorXd& u_full, int subdivisions) const;
  // Strong ellipticity of the law at every quadrature point of the committed state, evaluated as
  // the step that reached it evaluated the law (continuum/point_ellipticity.hpp); element-major.
  std::vector<continuum::PointEllipticity> committed_ellipticity(int normals = 96) const;
  // The law's response at quadrature point q of element e of the committed state, evaluated as for
  // committed_ellipticity, with the point's p~ (continuum::stepped_response). Throws like
  // state_at_point.
  continuum::SteppedResponse committed_response(int e, int q) const;
  // The same point as a homogeneous state of the periodic layer (periodic_layer_stability.hpp):
  // its F, reference fibre, pre-step history, the step's time and dt. F is scaled by
  // (J~ / det F)^(1/3), which keeps its isochoric part and gives the layer, whose J~ is det F, the
  // element's p~ = U'(J~). Throws like state_at_point.
  LayerState committed_layer_state(int e, int q) const;
  // Element e's tangent K_e (3 n_en square, its functions in space().control_points(e) order; in
  // the mixed formulation with p~, J~ condensed, as assembled) at the committed state, the law
  // evaluated as the step that reached it evaluated it. With `homogeneous`, on the element's own
  // geometry at that homogeneous state instead: u = (F - I) X at the control points (exactly
  // (F - I) X everywhere: the rational basis reproduces X), the state's fibre and history at every
  // quadrature point, its time and dt. Throws std::invalid_argument for an element out of range or
  // a history of the wrong size, std::runtime_error naming the failure when the kernel fails.
  Eigen::MatrixXd committed_element_tangent(int e, const LayerState* homogeneous = nullptr) const;

 private:
  // The history of quadrature point q of element e before the last commit (history_size()
  // values): what the step that reached the committed state evaluated the law from.
  std::span<const double> history_before_step(int e, int q) const;
  // use_base: mixed formulation, update p~, J~ from the current base (when there is one) instead
  // of projecting exactly (element_kernels.hpp, continuum/mixed_bases.hpp). trial_is_current:
  // the trial history is that of the last evaluation, at this same u_full (trial_is_at), so the
  // law need not update it again (materials::PointInput::trial_is_current). With increment
  // (full vector), also K_increment = K_all increment (all DOFs, element by element).
  solver::EvaluationStatus assemble(const Eigen::VectorXd& u_full, bool want_tangent,
                                    double* tangent_values, bool use_base, bool trial_is_current,
                                    const Eigen::VectorXd* increment = nullptr,
                                    Eigen::VectorXd* K_increment = nullptr);
  // The springs' force K u_full into f_int_ and their matrix into the tangent values (when given);
  // with increment, also K increment into K_increment (as assemble).
  void add_supports(const Eigen::VectorXd& u_full, double* tangent_values,
                    const Eigen::VectorXd* increment = nullptr,
                    Eigen::VectorXd* K_increment = nullptr);
  std::string describe_failure(int e, const KernelStatus& s) const;
  // Whether the trial history is that of a successful evaluation at free values u in this step.
  bool trial_is_at(const Eigen::VectorXd& u) const;
  // Runs the element kernel (with the tangent when asked) at the committed state with the pre-step
  // history into a workspace of its own; throws std::runtime_error when the kernel fails.
  void committed_element_pass(int e, ElementWorkspace& ws, bool want_tangent = false) const;

  const Space& space_;
  const DofMap& dofs_;
  const materials::MaterialLaw& law_;
  std::vector<Eigen::Vector3d> fibres_;
  Loads loads_;
  std::vector<ElasticSupport> support_settings_;
  std::vector<SupportElementMatrix> supports_;
  ProblemOptions options_;
  Formulation formulation_ = Formulation::displacement;
  ConstrainedDofs constraints_;
  PressureSpace pressure_;
  std::vector<std::vector<int>> element_all_dofs_;
  solver::SparsityPattern pattern_;
  solver::ElementColouring colouring_;
  std::vector<ElementWorkspace> workspaces_;
  // Per thread during an assembly pass; of the last successful evaluate(); of the committed state.
  std::vector<continuum::JacobianRange> thread_J_range_;
  continuum::JacobianRange evaluated_J_range_, committed_J_range_;
  int history_size_ = 0;
  std::vector<double> history_committed_;
  std::vector<double> history_trial_;
  std::vector<double> history_previous_;  // committed history before the last commit
  double time_ = 0.0;
  double dt_ = 0.0;
  double committed_time_ = 0.0;
  double committed_dt_ = 0.0;
  Eigen::VectorXd f_ext_;
  Eigen::VectorXd f_int_;
  Eigen::VectorXd u_full_;
  Eigen::VectorXd committed_full_;
  Eigen::VectorXd committed_free_;
  Eigen::VectorXd last_u_;  // free values of the last successful evaluation (trial history)
  // Mixed formulation: the bases p~, J~ are linearised about, within a step and from the
  // committed state into the next (continuum/mixed_bases.hpp).
  continuum::MixedBases bases_;
  solver::PredictorSystem predictor_;
  double last_time_ = 0.0;
  bool trial_valid_ = false;
};

}  // namespace isomuscle::iga
