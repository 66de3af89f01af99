#pragma once
// Record-level check of a fixed-format ASCII IGES file (IGES 5.3 §2): 80-column records whose
// column 73 names the section (S start, G global, D directory, P parameter, T terminate), in that
// order; the T record counts the others; each entity has two D records whose parameter pointer and
// line count must lie inside the P section; the parameters of every entity 128 (B-spline
// surface) and 126 (B-spline curve) must have the layout of IGES 5.3 §4.23 / §4.22 (integers,
// then as many reals as the sizes need); the pointers of every directory entry (view,
// transformation matrix, ...) must name entities of the types they allow. OpenCASCADE 7.6 crashes
// (segmentation fault) on truncated files and on a malformed entity 128 or 126, and leaks on a
// pointer to the wrong entity, instead of reporting them, so read_iges_surfaces runs this check
// first (fuzz/ searches for more: validation/fuzz/README.md).
#include <filesystem>

namespace isomuscle::geometry {

// Throws std::runtime_error naming the file, the line and what is wrong (missing, unreadable,
// empty, binary/compressed form, short or unlabelled record, sections out of order, truncated:
// no or inconsistent T record, parameter data past the end of the P section, malformed entity 128
// or 126 parameters, a directory pointer to no entity or to one of the wrong type).
void check_iges_structure(const std::filesystem::path& path);

}  // namespace isomuscle::geometry
