#include "continuum/mixed_bases.hpp"

#include <utility>

namespace isomuscle::continuum {

void MixedBases::resize(int elements, int m, int n) {
  base_.resize(elements, m, n);
  next_base_.resize(elements, m, n);
  evaluated_.resize(elements, m, n);
  committed_.resize(elements, m, n);
  valid_ = anchor_pending_ = evaluated_in_base_ = have_committed_ = false;
}

void MixedBases::begin_step() {
  valid_ = have_committed_;
  if (valid_)
    base_ = committed_;
  anchor_pending_ = valid_;
}

MixedBases::Pass MixedBases::begin_pass(bool use_base, bool want_tangent) const {
  Pass pass;
  pass.from_base = use_base && valid_;
  pass.anchor = pass.from_base && anchor_pending_;
  pass.store_tangent = want_tangent;
  return pass;
}

const MixedBase* MixedBases::element_base(const Pass& pass, int e, const ElementWorkspace& ws,
                                          MixedBase& view) {
  if (!pass.from_base)
    return nullptr;
  if (pass.anchor)
    base_.anchor(e, ws.ue.data());
  view = base_.view(e);
  return &view;
}

void MixedBases::store(const Pass& pass, int e, const ElementWorkspace& ws) {
  if (pass.store_tangent)
    next_base_.store(e, ws);
  else
    evaluated_.store(e, ws);
}

void MixedBases::end_pass(const Pass& pass, bool ok) {
  if (!ok)
    return;  // a failed pass leaves the elements it reached half written: nothing is taken
  // A tangent pass that projects exactly (the linearised Dirichlet predictor at the committed
  // state) leaves the base the first iterate is linearised about: it is not anchored.
  if (pass.anchor || (pass.store_tangent && !pass.from_base))
    anchor_pending_ = false;
  if (pass.store_tangent) {
    std::swap(base_, next_base_);
    valid_ = true;
  }
  evaluated_in_base_ = pass.store_tangent;
}

// Swapped, not copied: base_ is rebuilt from committed_ at the next begin_step, and evaluated_ is
// written again by any pass before the next commit.
void MixedBases::commit() {
  std::swap(committed_, evaluated_in_base_ ? base_ : evaluated_);
  have_committed_ = true;
  valid_ = false;
  anchor_pending_ = false;
}

}  // namespace isomuscle::continuum
