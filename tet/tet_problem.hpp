#pragma once
// The nonlinear problem on a tetrahedral mesh (DESIGN "The way data flows", tet side): a material
// law at every quadrature point, Dirichlet conditions on node sets and a dead body force, offered
// to Newton and the time stepper through solver::NonlinearProblem. Mirrors iga::Problem:
// * unknowns: the free DOFs (3 per node, DOF 3 n + k), prescribed values set in begin_step;
// * evaluate(): r = f_int(u) - f_ext(t), K = dr/du, assembled with a pattern and scatter map built
//   once, by element colouring (deterministic whatever the thread count);
// * formulation: displacement, or the condensed mixed u–p–J (continuum/element_kernels.hpp),
// automatically
//   mixed for laws with a volumetric split (use 10-node elements: 4-node elements with a constant
//   dilatation are the displacement formulation again and lock);
// * history per quadrature point, committed + trial; failures (J <= 0, J~ <= 0, a failed local
//   material solve) return a failure status naming the element, point, position and value.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "continuum/element_kernels.hpp"
#include "continuum/formulation.hpp"
#include "continuum/jacobian_range.hpp"
#include "continuum/mixed_bases.hpp"
#include "continuum/point_ellipticity.hpp"
#include "continuum/point_state.hpp"
#include "materials/material_law.hpp"
#include "solver/element_colouring.hpp"
#include "solver/linear_solver.hpp"
#include "solver/matrix_storage.hpp"
#include "solver/nonlinear_problem.hpp"
#include "solver/predictor_system.hpp"
#include "solver/sparsity_pattern.hpp"
#include "tet/tet_space.hpp"
#include "tet/tet_surface_loads.hpp"

namespace isomuscle::tet {

// The formulation and the element kernels are those of continuum/ (shared with iga/).
using continuum::ElementView;
using continuum::ElementWorkspace;
using continuum::Formulation;
using continuum::KernelStatus;
using continuum::MaterialContext;
using continuum::parse_formulation;
using continuum::to_string;

// A field of the reference position X (m) and time t (s).
using VectorField = std::function<Eigen::Vector3d(const Eigen::Vector3d& X, double t)>;

// Prescribed displacement (m) on the components marked true of the nodes listed; value empty
// means zero. A later condition overrides an earlier one on the same DOF.
struct TetDirichlet {
  std::vector<int> nodes;
  std::array<bool, 3> components{true, true, true};
  VectorField value;
};

struct TetProblemOptions {
  Formulation formulation = Formulation::automatic;
  // p~, J~ per element: 0 = constant (mean dilatation), 1 = linear discontinuous.
  int pressure_degree = 0;
  int threads = 0;  // 0 = OpenMP default
  solver::MatrixStorage storage = solver::MatrixStorage::Upper;
  solver::ScatterMode scatter = solver::ScatterMode::Stored;
  // Throws std::invalid_argument naming the option.
  void validate() const;
};

// Material state at one quadrature point of the committed state, for outputs: the stress and
// fibre outputs of continuum::PointStress (J, J~, p~, S, sigma, N, a, lambda_f) and the field.
struct TetPointState : continuum::PointStress {
  Eigen::Vector3d X = Eigen::Vector3d::Zero();             // reference position, m
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  // m
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
};

class TetProblem : public solver::NonlinearProblem {
 public:
  // space and law must outlive the problem. fibres: one unit vector per quadrature point
  // (tet_fibres.hpp). body_force: dead load per unit reference volume (N/m^3), may be empty.
  // Throws std::invalid_argument for inconsistent sizes, bad options or node indices.
  TetProblem(const TetSpace& space, const materials::MaterialLaw& law,
             std::vector<Eigen::Vector3d> fibres, std::vector<TetDirichlet> conditions,
             VectorField body_force = {}, TetProblemOptions options = {});

  // --- solver::NonlinearProblem ---
  int size() const override { return num_free_; }
  void begin_step(double time, double dt) override;
  solver::EvaluationStatus evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& residual,
                                    solver::SparseMatrix* tangent) override;
  void commit_step(const Eigen::VectorXd& u) override;
  // Dead surface tractions (tet_surface_loads.hpp), added to f_ext from the next begin_step on.
  void set_surface_loads(std::vector<TetSurfaceLoad> loads) { surface_loads_ = std::move(loads); }
  // The linearised Dirichlet predictor of iga::Problem::predict: from the committed state with its
  // tangent, K_ff du_f = -(f_int(u_n) + K_fp du_p - f_ext)_f for the prescribed increment du_p of
  // the step, u <- u + du_f, so the first iterate does not squeeze the whole increment into the
  // elements next to a moved face. u holds the committed free values; unchanged on failure.
  solver::EvaluationStatus predict(Eigen::VectorXd& u) override;

  Formulation formulation() const { return formulation_; }  // resolved, never automatic
  const TetSpace& space() const { return space_; }
  const materials::MaterialLaw& law() const { return law_; }
  int num_colours() const { return colouring_.n_colours(); }
  const solver::SparsityPattern& pattern() const { return pattern_; }
  // Free index of DOF 3 node + component, or solver::kPrescribed.
  int free_index(int node, int component) const { return free_index_[3 * node + component]; }

  // Full displacement (3 per node) of free values u at the current time.
  Eigen::VectorXd full_displacement(const Eigen::VectorXd& u) const;
  const Eigen::VectorXd& committed_displacement() const { return committed_full_; }
  std::span<const double> committed_history(int element, int point) const;
  double committed_time() const { return committed_time_; }
  // Smallest and largest J = det F over the quadrature points of the committed state (with their
  // elements and local points; found() is false before the first commit).
  const continuum::JacobianRange& committed_jacobian_range() const { return committed_J_range_; }
  // State at quadrature point q of element e in the committed state: the element kernel re-run at
  // the committed displacement with the history from before the committed step (so the converged
  // stress is reproduced exactly, also for rate-dependent laws). Throws std::invalid_argument for
  // indices out of range, std::runtime_error when the law fails there.
  TetPointState state_at_point(int e, int q) const;
  // F at every quadrature point (element-major) of a full displacement vector.
  std::vector<Eigen::Matrix3d> deformation_gradients(const Eigen::VectorXd& u_full) const;
  // Current volume int J dV (m^3).
  double current_volume(const Eigen::VectorXd& u_full) const;
  // Lumped reference volume of every node (m^3), by the diagonal scaling of Hinton, Rock and
  // Zienkiewicz (Earthquake Eng. Struct. Dyn. 4, 1976): element e gives node a the share
  // V_e int N_a^2 dV / sum_b int N_b^2 dV. Row sums would give the vertices of a 10-node
  // tetrahedron negative volumes; these are positive, and they sum to the mesh volume.
  Eigen::VectorXd lumped_volumes() const;
  // Strong ellipticity of the law at every quadrature point of the committed state, evaluated as
  // the step that reached it evaluated the law (continuum/point_ellipticity.hpp); element-major.
  std::vector<continuum::PointEllipticity> committed_ellipticity(int normals = 96) const;
  // The law's response at quadrature point q of element e of the committed state, evaluated as for
  // committed_ellipticity, with the point's p~ (continuum::stepped_response). Throws like
  // state_at_point.
  continuum::SteppedResponse committed_response(int e, int q) const;
  const Eigen::VectorXd& external_force() const { return f_ext_; }
  // Internal force at ALL DOFs (3 per node, N) for free values u: an assembly pass without
  // tangent. The trial history is scratch; the committed state does not change. At the free
  // values of the last evaluation (the converged state, before commit_step) the law reads its
  // trial history.
  solver::EvaluationStatus internal_force(const Eigen::VectorXd& u, Eigen::VectorXd& f_int);
  // Sum over nodes of a full force vector (N): with f_int - f_ext it is the reaction on a
  // supported node set.
  Eigen::Vector3d sum_over_nodes(const Eigen::VectorXd& f_full, std::span<const int> nodes) const;

 private:
  // use_base: mixed formulation, update p~, J~ from the current base (when there is one) instead
  // of projecting exactly (continuum/mixed_bases.hpp). trial_is_current: the trial history is
  // that of the last evaluation, at this same u_full (materials::PointInput::trial_is_current).
  // With increment (all DOFs), also K_increment = K_all increment element by element.
  solver::EvaluationStatus assemble(const Eigen::VectorXd& u_full, bool want_tangent,
                                    double* values, bool use_base, bool trial_is_current,
                                    const Eigen::VectorXd* increment = nullptr,
                                    Eigen::VectorXd* K_increment = nullptr);
  // Element e's kernel (displacement or mixed, by formulation_) at ws.ue into ws; base: the
  // element's mixed base or nullptr (exact projection).
  KernelStatus element_kernel(int e, const MaterialContext& ctx, bool tangent, ElementWorkspace& ws,
                              const continuum::MixedBase* base = nullptr) const;
  std::string describe_failure(int e, const KernelStatus& s) const;
  // Whether the trial history is that of a successful evaluation at free values u in this step.
  bool trial_is_at(const Eigen::VectorXd& u) const;

  const TetSpace& space_;
  const materials::MaterialLaw& law_;
  std::vector<Eigen::Vector3d> fibres_;
  std::vector<TetDirichlet> conditions_;
  VectorField body_force_;
  std::vector<TetSurfaceLoad> surface_loads_;
  TetProblemOptions options_;
  Formulation formulation_ = Formulation::displacement;
  int num_free_ = 0;
  std::vector<int> free_index_;  // per DOF
  int pressure_size_ = 1;
  std::vector<double> pressure_values_;            // nel x nqp x m
  std::vector<Eigen::LLT<Eigen::MatrixXd>> mass_;  // Cholesky factors of M_e
  std::vector<Eigen::MatrixXd> mass_matrix_;       // M_e = int phi phi^T dV
  std::vector<std::vector<int>> element_dofs_;
  solver::SparsityPattern pattern_;
  solver::ElementColouring colouring_;
  std::vector<ElementWorkspace> workspaces_;
  // Per thread during an assembly pass; of the last successful evaluate(); of the committed state.
  std::vector<continuum::JacobianRange> thread_J_range_;
  continuum::JacobianRange evaluated_J_range_, committed_J_range_;
  int history_size_ = 0;
  std::vector<double> history_committed_, history_trial_;
  std::vector<double> history_previous_;  // committed history before the last commit
  double time_ = 0.0, dt_ = 0.0;
  double committed_time_ = 0.0, committed_dt_ = 0.0;
  Eigen::VectorXd prescribed_;  // full vector: prescribed values at time_, zero elsewhere
  Eigen::VectorXd f_ext_, f_int_, u_full_, committed_full_, last_u_;
  bool trial_valid_ = false;
  // Mixed formulation: the bases p~, J~ are linearised about, within a step and from the
  // committed state into the next (continuum/mixed_bases.hpp), as in iga::Problem.
  continuum::MixedBases bases_;
  solver::PredictorSystem predictor_;
};

}  // namespace isomuscle::tet
