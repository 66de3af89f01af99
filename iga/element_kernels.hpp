#pragma once
// Element kernels of the total Lagrangian formulation on NURBS knot-span elements: the
// discretisation-independent kernels of continuum/element_kernels.hpp ((a) displacement, (b)
// condensed mixed u–p–J, Simo, Taylor & Pister 1985) fed with the tabulated data of Space and the
// element pressure space of PressureSpace.
#include "continuum/element_kernels.hpp"
#include "iga/pressure_space.hpp"
#include "iga/space.hpp"

namespace isomuscle::iga {

using continuum::displacement_kernel;
using continuum::ElementView;
using continuum::ElementWorkspace;
using continuum::KernelStatus;
using continuum::MaterialContext;
using continuum::MixedBase;

// Element e's tabulated reference data (views into space; no pressure functions).
ElementView element_view(const Space& space, int e);

// (b) continuum::mixed_kernel with the element functions and mass matrices of `pressure` for
// element `element` (base, tangent, outputs as there).
KernelStatus mixed_kernel(const ElementView& el, const MaterialContext& mat,
                          const PressureSpace& pressure, int element, const MixedBase* base,
                          bool tangent, ElementWorkspace& ws);

}  // namespace isomuscle::iga
