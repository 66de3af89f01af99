#pragma once
// Which base the mixed u–p–J kernel linearises p~, J~ about (mixed_base_storage.hpp), over the
// Newton iterations of a step and from one step to the next. Shared by iga::Problem and
// tet::TetProblem.
//
// Within a step: every tangent evaluation leaves the base of its state (written into a second
// copy, swapped in when the whole assembly succeeded); the evaluations after it update p~, J~ from
// that base (step-44's static condensation).
//
// From step to step: the base of the committed state is kept, and the first evaluation of the next
// step is anchored to it: p~ and J~ start from their committed values at whatever displacement the
// step starts from (J~ then follows the linearised constraint from there). Projecting J exactly at
// the start instead (the earlier rule) fails for a start extrapolated from the last step's
// velocity: u_n + v dt carries a second-order error of J of order |grad(v dt)|^2 (a linear
// extrapolation of a rotation or stretch is not volume-preserving), and p~ = kappa (J~ - 1) at
// kappa / mu ~ 1e4-1e6 turns it into pressures far above the stresses of the step (passive
// barrel example, second step: p~ = -3.6e4 Pa at the start against +1.3e2 Pa committed). The first
// iteration then overshoots, mostly with an indefinite tangent (LU fallback), and the second makes
// no progress: half torus example, 106 of 112 steps, 805 Newton iterations and 9 cuts; anchored 126
// iterations in 33 steps, no cut. The anchored start is the three-field iteration of Simo, Taylor &
// Pister (1985) with p~, J~ continued from the last converged values. A step started by the
// linearised Dirichlet predictor (a tangent pass at the committed state with the exact projection)
// is linearised about that pass's base instead, as before.
#include "continuum/element_kernels.hpp"
#include "continuum/element_workspace.hpp"
#include "continuum/mixed_base_storage.hpp"

namespace isomuscle::continuum {

class MixedBases {
 public:
  // What one assembly pass does with the bases.
  struct Pass {
    bool from_base = false;      // update p~, J~ from the current base (else project exactly)
    bool anchor = false;         // first evaluation of a step: move the base to this u first
    bool store_tangent = false;  // a tangent evaluation: its states become the next base,
                                 // else a residual one: kept in case it is committed
  };

  // Blocks for `elements` elements, m pressure functions and n = 3 n_en displacements each.
  void resize(int elements, int m, int n);

  // A step (or its retry after a cut) starts: the committed state's base, anchored at the first
  // evaluation (none before the first commit: that evaluation projects exactly).
  void begin_step();
  // The pass of an assembly: use_base false forces the exact projection.
  Pass begin_pass(bool use_base, bool want_tangent) const;
  // Element e's base for the kernel (anchored at ws.ue first where the pass anchors), or nullptr
  // for the exact projection; `view` holds the pointers.
  const MixedBase* element_base(const Pass& pass, int e, const ElementWorkspace& ws,
                                MixedBase& view);
  // Element e's state after its kernel ran in this pass.
  void store(const Pass& pass, int e, const ElementWorkspace& ws);
  // After all elements: ok is whether the whole pass succeeded.
  void end_pass(const Pass& pass, bool ok);

  // The state of the last successful pass is committed: its base is the next step's start.
  void commit();

 private:
  MixedBaseStorage base_, next_base_, evaluated_, committed_;
  bool valid_ = false;              // base_ describes a state of this step
  bool anchor_pending_ = false;     // base_ is the committed one, not yet anchored
  bool evaluated_in_base_ = false;  // the last pass's states are in base_ (else in evaluated_)
  bool have_committed_ = false;
};

}  // namespace isomuscle::continuum
