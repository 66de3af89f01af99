#pragma once
// IGES input and output of NURBS surfaces (IGES 5.3 entity 128, rational B-spline surface) through
// OpenCASCADE (SPEC §1 "IGES input"; TOOLING.md). Reading takes each entity 128 of the file as
// written: poles (with the entity's transformation matrix applied), weights, knots and
// multiplicities, converted to metres from the file's unit flag. It does not go through OCCT's
// shape transfer, which "heals" B-splines (removes knots and poles, forces closed surfaces to be
// periodic, converts lengths to the session unit). A knot vector in periodic (unclamped) form is
// clamped exactly by knot insertion (refinement.hpp make_clamped). Files written by CAD tools can
// be periodic, trimmed (144 over 128), in mm, and may close in v instead of u; all of that is
// reported.
#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/nurbs_surface.hpp"

namespace isomuscle::geometry {

struct IgesSurface {
  NurbsSurface surface;               // clamped knot vectors on the full knot domain, metres
  int directory_entry = 0;            // DE sequence number of the entity 128 (odd, 1-based)
  int form = 0;                       // form number of the entity 128 (0 = arbitrary)
  int parent_type = 0;                // 0: stands alone; 144 trimmed, 143 bounded surface, 510 face
  int parent_directory_entry = 0;     // DE of that parent, 0 when none
  std::array<bool, 2> closed_flag{};  // PROP1, PROP2 as written in the file (u, v)
  std::array<bool, 2> periodic_flag{};    // PROP4, PROP5 as written in the file
  std::array<bool, 2> clamped_in_file{};  // false where the file's knot vector was unclamped
  std::array<std::array<double, 2>, 2> parameter_range{};  // U(0), U(1) and V(0), V(1) of the file
  double metres_per_file_unit = 1.0;
  std::string file_unit;  // e.g. "MM", "M", "IN"
};

// All B-spline surfaces (entity 128) of an IGES file in file order, whether standing alone or used
// by a trimmed surface, bounded surface or B-rep face. Throws std::runtime_error naming the file
// and the problem when the file does not exist or cannot be read, is empty, truncated or not
// fixed-format ASCII IGES, has an unknown unit, holds a malformed entity 128, or holds none (the
// message then lists the entity types it does hold).
std::vector<IgesSurface> read_iges_surfaces(const std::filesystem::path& path);

enum class IgesUnit { kMetre, kMillimetre };

// "m" | "mm" -> IgesUnit; throws std::invalid_argument naming the choices.
IgesUnit parse_iges_unit(std::string_view name);

// Writes the surfaces (lengths in metres) as bare entities 128 in the given file unit, reals with
// 17 significant digits so that a round trip is exact to rounding. Throws std::runtime_error when
// the file cannot be written or OCCT rejects a surface.
void write_iges(const std::filesystem::path& path, const std::vector<NurbsSurface>& surfaces,
                IgesUnit unit = IgesUnit::kMillimetre);

}  // namespace isomuscle::geometry
