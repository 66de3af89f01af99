#pragma once
// The finite element formulation of the total Lagrangian problem, shared by the NURBS (iga) and
// tetrahedral (tet) discretisations: the pure displacement formulation, the condensed mixed
// u–p–J formulation of nearly incompressible laws (Simo, Taylor & Pister 1985), or the automatic
// choice between them (mixed when the law splits off a volumetric part and is stiff in volume).
#include <string_view>

namespace isomuscle::continuum {

enum class Formulation { automatic, displacement, mixed };

// "automatic", "displacement" or "mixed".
const char* to_string(Formulation f);
// Inverse of to_string; throws std::invalid_argument naming the valid choices.
Formulation parse_formulation(std::string_view name);

}  // namespace isomuscle::continuum
