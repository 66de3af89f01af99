#pragma once
// Small nonlinear problems with known solutions, implemented as NonlinearProblem through the
// sparsity pattern and scatter assembly, for the Newton and time-stepper tests.
#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "solver/element_dofs.hpp"
#include "solver/nonlinear_problem.hpp"
#include "solver/sparsity_pattern.hpp"

namespace isomuscle::solver::testing {

// Nonlinear reaction–diffusion on the unit square, finite differences on an N x N grid of interior
// nodes (u = 0 on the boundary, prescribed):
//   r_i(u) = (A u)_i + lambda u_i^3 - t f_i,   A = 5-point Laplacian / h^2 (two-node edge
//   "elements" (1/h^2) [1 -1; -1 1], edges to the boundary keep only the interior DOF),
//   K = A + 3 lambda diag(u^2)   (symmetric positive definite).
// f = A u* + lambda u*^3 with u*_i = amplitude sin(pi x_i) sin(pi y_i), so u* is the exact discrete
// solution at t = 1. evaluate() fails when some |u_i| exceeds failure_bound (standing in for an
// inverted element).
class ReactionDiffusionProblem : public NonlinearProblem {
 public:
  ReactionDiffusionProblem(int n, double lambda, double amplitude)
      : n_(n), lambda_(lambda), h_(1.0 / (n + 1)) {
    ElementDofs elements;
    const auto node = [n](int i, int j) {
      return (i < 0 || j < 0 || i >= n || j >= n) ? kPrescribed : j * n + i;
    };
    for (int j = -1; j < n; ++j) {
      for (int i = -1; i < n; ++i) {
        if (j >= 0) {
          elements.add_element(std::vector<int>{node(i, j), node(i + 1, j)});
        }
        if (i >= 0) {
          elements.add_element(std::vector<int>{node(i, j), node(i, j + 1)});
        }
      }
    }
    pattern_ = SparsityPattern(std::move(elements), n * n);
    exact_.resize(n * n);
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        exact_[j * n + i] = amplitude * std::sin(std::numbers::pi * (i + 1) * h_) *
                            std::sin(std::numbers::pi * (j + 1) * h_);
      }
    }
    // f = A u* + lambda u*^3: the residual at u* with no load.
    load_.setZero(n * n);
    Eigen::VectorXd r;
    evaluate(exact_, r, nullptr);
    load_ = r;
    evaluations = 0;
  }

  int size() const override { return n_ * n_; }
  void begin_step(double time, double dt) override {
    load_factor = time;
    begun.push_back({time, dt});
  }
  EvaluationStatus evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& residual,
                            SparseMatrix* tangent) override {
    ++evaluations;
    for (int i = 0; i < size(); ++i) {
      if (std::abs(u[i]) > failure_bound) {
        std::ostringstream message;
        message.precision(17);
        message << "node " << i << ": |u| = " << std::abs(u[i]) << " exceeds " << failure_bound;
        return EvaluationStatus::failure(message.str());
      }
    }
    const double stiffness = 1.0 / (h_ * h_);
    Eigen::Matrix2d ke;
    ke << stiffness, -stiffness, -stiffness, stiffness;
    residual = -load_factor * load_;
    if (tangent != nullptr) {
      if (!pattern_.matches(*tangent)) {
        *tangent = pattern_.make_matrix();
      } else {
        Eigen::Map<Eigen::VectorXd>(tangent->valuePtr(), tangent->nonZeros()).setZero();
      }
    }
    const ElementDofs& elements = pattern_.elements();
    Eigen::Vector2d ue;
    for (int e = 0; e < elements.n_elements(); ++e) {
      const auto dofs = elements.dofs(e);
      for (int a = 0; a < 2; ++a) {
        ue[a] = dofs[a] >= 0 ? u[dofs[a]] : 0.0;
      }
      const Eigen::Vector2d fe = ke * ue;
      pattern_.add_element_vector(e, fe, residual);
      if (tangent != nullptr) {
        pattern_.add_element_matrix(e, ke, *tangent);
      }
    }
    for (int i = 0; i < size(); ++i) {
      residual[i] += lambda_ * u[i] * u[i] * u[i];
      if (tangent != nullptr) {
        tangent->coeffRef(i, i) += 3.0 * lambda_ * u[i] * u[i];
      }
    }
    return EvaluationStatus::success();
  }
  void commit_step(const Eigen::VectorXd& u) override { committed.push_back(u); }

  const Eigen::VectorXd& exact() const { return exact_; }

  double load_factor = 1.0;
  double failure_bound = 1e300;
  int evaluations = 0;
  std::vector<std::pair<double, double>> begun;
  std::vector<Eigen::VectorXd> committed;

 private:
  int n_;
  double lambda_;
  double h_;
  SparsityPattern pattern_;
  Eigen::VectorXd exact_;
  Eigen::VectorXd load_;
};

// r_i(u) = atan(u_i - a_i) + kappa (L u)_i with L the Laplacian of a chain (free ends): plain
// Newton on atan overshoots and diverges from more than ~1.39 away from the root (the classic
// example), a line search converges. K = diag(1 / (1 + (u_i - a_i)^2)) + kappa L (SPD).
class AtanChainProblem : public NonlinearProblem {
 public:
  AtanChainProblem(int n, double kappa) : kappa_(kappa) {
    ElementDofs elements;
    for (int i = 0; i + 1 < n; ++i) {
      elements.add_element(std::vector<int>{i, i + 1});
    }
    pattern_ = SparsityPattern(std::move(elements), n);
    shift_.resize(n);
    for (int i = 0; i < n; ++i) {
      shift_[i] = 3.0 + 0.5 * std::sin(i);
    }
  }
  int size() const override { return static_cast<int>(shift_.size()); }
  void begin_step(double, double) override {}
  EvaluationStatus evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& residual,
                            SparseMatrix* tangent) override {
    residual.resize(size());
    for (int i = 0; i < size(); ++i) {
      residual[i] = std::atan(u[i] - shift_[i]);
    }
    if (tangent != nullptr) {
      *tangent = pattern_.make_matrix();
    }
    Eigen::Matrix2d ke;
    ke << kappa_, -kappa_, -kappa_, kappa_;
    for (int e = 0; e < pattern_.elements().n_elements(); ++e) {
      const auto dofs = pattern_.elements().dofs(e);
      const Eigen::Vector2d fe = ke * Eigen::Vector2d(u[dofs[0]], u[dofs[1]]);
      pattern_.add_element_vector(e, fe, residual);
      if (tangent != nullptr) {
        pattern_.add_element_matrix(e, ke, *tangent);
      }
    }
    if (tangent != nullptr) {
      for (int i = 0; i < size(); ++i) {
        const double d = u[i] - shift_[i];
        tangent->coeffRef(i, i) += 1.0 / (1.0 + d * d);
      }
    }
    return EvaluationStatus::success();
  }
  void commit_step(const Eigen::VectorXd&) override {}

 private:
  double kappa_;
  SparsityPattern pattern_;
  Eigen::VectorXd shift_;
};

// r_i(u) = u_i^3 - u_i + kappa (L u)_i (a chain of double-well springs): near u = 0 the tangent
// K = diag(3 u_i^2 - 1) + kappa L is negative definite, so Cholesky fails and Newton runs on LU.
// u = 0 is a solution.
class DoubleWellChainProblem : public NonlinearProblem {
 public:
  DoubleWellChainProblem(int n, double kappa) : n_(n), kappa_(kappa) {
    ElementDofs elements;
    for (int i = 0; i + 1 < n; ++i) {
      elements.add_element(std::vector<int>{i, i + 1});
    }
    pattern_ = SparsityPattern(std::move(elements), n);
  }
  int size() const override { return n_; }
  void begin_step(double, double) override {}
  EvaluationStatus evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& residual,
                            SparseMatrix* tangent) override {
    residual = u.array().cube() - u.array();
    if (tangent != nullptr) {
      *tangent = pattern_.make_matrix();
    }
    Eigen::Matrix2d ke;
    ke << kappa_, -kappa_, -kappa_, kappa_;
    for (int e = 0; e < pattern_.elements().n_elements(); ++e) {
      const auto dofs = pattern_.elements().dofs(e);
      const Eigen::Vector2d fe = ke * Eigen::Vector2d(u[dofs[0]], u[dofs[1]]);
      pattern_.add_element_vector(e, fe, residual);
      if (tangent != nullptr) {
        pattern_.add_element_matrix(e, ke, *tangent);
      }
    }
    if (tangent != nullptr) {
      for (int i = 0; i < n_; ++i) {
        tangent->coeffRef(i, i) += 3.0 * u[i] * u[i] - 1.0;
      }
    }
    return EvaluationStatus::success();
  }
  void commit_step(const Eigen::VectorXd&) override {}

 private:
  int n_;
  double kappa_;
  SparsityPattern pattern_;
};

}  // namespace isomuscle::solver::testing
