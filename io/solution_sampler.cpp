#include "io/solution_sampler.hpp"

#include <stdexcept>
#include <string>

namespace isomuscle::io {

SolutionSampler::SolutionSampler(const StoredSolution& solution) : solution_(solution) {
  if (solution_.iga) {
    inverter_ = std::make_unique<geometry::PointInverter>(*solution_.iga);
  } else if (solution_.tet) {
    locator_ = std::make_unique<tet::TetLocator>(*solution_.tet);
    for (const DisplacementRows& u : solution_.displacement) {
      Eigen::VectorXd flat(3 * u.rows());
      for (Eigen::Index i = 0; i < u.rows(); ++i)
        flat.segment<3>(3 * i) = u.row(i).transpose();
      nodal_.push_back(std::move(flat));
    }
  } else {
    throw std::invalid_argument(solution_.path.string() + ": no discretisation to evaluate");
  }
}

// u(xi) = sum_a R_a(xi) u_a over the functions non-zero at xi (IGA), or at X = H(xi) (tet).
std::optional<Eigen::Vector3d> SolutionSampler::at_parameter(const Eigen::Vector3d& xi,
                                                             std::size_t step) const {
  if (step >= solution_.displacement.size()) {
    throw std::out_of_range(solution_.path.string() + ": step " + std::to_string(step) +
                            " does not exist (" + std::to_string(solution_.displacement.size()) +
                            " steps)");
  }
  if (locator_)
    return at_point(solution_.geometry.evaluate(xi), step);
  geometry::VolumeBasis basis;
  solution_.iga->evaluate_basis(xi, basis);
  const DisplacementRows& u = solution_.displacement[step];
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t a = 0; a < basis.index.size(); ++a)
    sum += basis.value[a] * u.row(basis.index[a]).transpose();
  return sum;
}

std::optional<Eigen::Vector3d> SolutionSampler::at_point(const Eigen::Vector3d& X,
                                                         std::size_t step) const {
  if (locator_) {
    if (step >= nodal_.size())
      throw std::out_of_range(solution_.path.string() + ": step " + std::to_string(step) +
                              " does not exist");
    const std::optional<tet::TetLocation> at = locator_->locate(X);
    if (!at)
      return std::nullopt;
    return locator_->interpolate(*at, nodal_[step]);
  }
  const geometry::InversionResult r = inverter_->invert(X);
  if (!r.inside)
    return std::nullopt;
  return at_parameter(r.xi, step);
}

}  // namespace isomuscle::io
