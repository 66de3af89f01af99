#include "continuum/mixed_base_storage.hpp"

#include <algorithm>

namespace isomuscle::continuum {

void MixedBaseStorage::resize(int elements, int m, int n) {
  m_ = static_cast<std::size_t>(m);
  n_ = static_cast<std::size_t>(n);
  const std::size_t e = static_cast<std::size_t>(elements);
  ue_.assign(e * n_, 0.0);
  theta_.assign(e * m_, 0.0);
  pi_.assign(e * m_, 0.0);
  R_pi_.assign(e * m_, 0.0);
  R_theta_.assign(e * m_, 0.0);
  G_.assign(e * m_ * n_, 0.0);
  K_JJ_.assign(e * m_ * m_, 0.0);
}

MixedBase MixedBaseStorage::view(int e) const {
  const std::size_t E = static_cast<std::size_t>(e);
  MixedBase base;
  base.ue = ue_.data() + E * n_;
  base.theta = theta_.data() + E * m_;
  base.pi = pi_.data() + E * m_;
  base.R_pi = R_pi_.data() + E * m_;
  base.R_theta = R_theta_.data() + E * m_;
  base.G = G_.data() + E * m_ * n_;
  base.K_JJ = K_JJ_.data() + E * m_ * m_;
  return base;
}

void MixedBaseStorage::store(int e, const ElementWorkspace& ws) {
  const std::size_t E = static_cast<std::size_t>(e);
  std::copy_n(ws.ue.data(), n_, ue_.data() + E * n_);
  std::copy_n(ws.theta.data(), m_, theta_.data() + E * m_);
  std::copy_n(ws.pi.data(), m_, pi_.data() + E * m_);
  std::copy_n(ws.R_pi.data(), m_, R_pi_.data() + E * m_);
  std::copy_n(ws.R_theta.data(), m_, R_theta_.data() + E * m_);
  std::copy_n(ws.G.data(), m_ * n_, G_.data() + E * m_ * n_);
  std::copy_n(ws.K_JJ.data(), m_ * m_, K_JJ_.data() + E * m_ * m_);
}

void MixedBaseStorage::anchor(int e, const double* ue) {
  const std::size_t E = static_cast<std::size_t>(e);
  std::copy_n(ue, n_, ue_.data() + E * n_);
  std::fill_n(R_pi_.data() + E * m_, m_, 0.0);
}

}  // namespace isomuscle::continuum
