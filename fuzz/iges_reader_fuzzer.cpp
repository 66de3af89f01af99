// Fuzz target: geometry::read_iges_surfaces on arbitrary bytes, then the work a run does next with
// each surface it returns (seam check, shrink solid, extruded sheet, evaluation). Every
// std::exception is an accepted outcome (a clear error for a bad file); a crash, a sanitizer
// report, a hang, a leak, an escaping non-std exception (OpenCASCADE's Standard_Failure) or a
// broken promise of the reader (below) is a finding (validation/fuzz/README.md).
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "geometry/extrusion.hpp"
#include "geometry/iges.hpp"
#include "geometry/shrink.hpp"

namespace {

namespace geo = isomuscle::geometry;

// The reader takes a path (OpenCASCADE opens the file itself), so each input goes through one
// scratch file per process (the pid keeps parallel libFuzzer jobs apart); removed at exit.
class ScratchFile {
 public:
  ScratchFile()
      : path_(std::filesystem::temp_directory_path() /
              ("isomuscle-iges-fuzz-" + std::to_string(::getpid()) + ".igs")) {}
  ~ScratchFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  const std::filesystem::path& write(const std::uint8_t* data, std::size_t size) const {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) {
      std::perror(("iges_reader_fuzzer: cannot write " + path_.string()).c_str());
      std::abort();  // the harness is broken, not the reader
    }
    return path_;
  }

 private:
  std::filesystem::path path_;
};

[[noreturn]] void broken_promise(const char* what) {
  std::fprintf(stderr, "iges_reader_fuzzer: read_iges_surfaces returned a surface with %s\n", what);
  std::abort();
}

// What iges.hpp promises of a surface it returns: clamped knot vectors, finite control points
// within 1 km (the reader's limit, metres) and finite positive weights.
void check_promises(const geo::NurbsSurface& s) {
  if (!s.knots_u().is_clamped() || !s.knots_v().is_clamped())
    broken_promise("an unclamped knot vector");
  for (const Eigen::Vector3d& x : s.points()) {
    if (!(x.array().abs() <= 1e3).all())
      broken_promise("a control point that is not finite or beyond 1 km");
  }
  for (const double w : s.weights()) {
    if (!(std::isfinite(w) && w > 0.0))
      broken_promise("a weight that is not finite and positive");
  }
}

// Sample points of a domain [a, b]: its ends and an interior point.
constexpr double kSamples[] = {0.0, 0.37, 1.0};

double at(const geo::KnotVector& k, double t) {
  return k.domain_begin() + t * (k.domain_end() - k.domain_begin());
}

// The steps of a scene run up to the solid (io/scene_solid.cpp), each of which may reject the
// surface with an exception: both shrink directions, an extrusion, and evaluation of the results.
void use_surface(const geo::NurbsSurface& s) {
  for (const double a : kSamples) {
    for (const double b : kSamples) {
      Eigen::Vector3d x;
      Eigen::Matrix<double, 3, 2> d;
      s.evaluate_derivatives(at(s.knots_u(), a), at(s.knots_v(), b), x, d);
    }
  }
  for (int dir = 0; dir < 2; ++dir) {
    (void)geo::seam_gap(s, dir);
    try {
      const geo::NurbsVolume v = geo::shrink_to_centreline(s, dir);
      for (const double t : kSamples) {
        Eigen::Vector3d x;
        Eigen::Matrix3d j;
        const Eigen::Vector3d xi(v.domain(0)[0] + t * (v.domain(0)[1] - v.domain(0)[0]),
                                 v.domain(1)[0] + t * (v.domain(1)[1] - v.domain(1)[0]),
                                 v.domain(2)[0] + t * (v.domain(2)[1] - v.domain(2)[0]));
        v.evaluate_with_jacobian(xi, x, j);
      }
    } catch (const std::exception&) {
      // not closed in dir, or degenerate: the run reports it
    }
  }
  try {
    const geo::Extrusion sheet = geo::extrude(s, Eigen::Vector3d(0.0, 0.0, 1e-3));
    (void)sheet.volume.evaluate(Eigen::Vector3d(
        sheet.volume.domain(0)[0], sheet.volume.domain(1)[1], sheet.volume.domain(2)[1]));
  } catch (const std::exception&) {
    // a sheet that cannot be extruded (e.g. d in its plane): the run reports it
  }
}

// Downstream work only for surfaces of at most this many control points, so that a large valid
// surface does not read as a hang.
constexpr int kMaxControlPoints = 20000;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ScratchFile scratch;
  const std::filesystem::path& path = scratch.write(data, size);
  try {
    for (const geo::IgesSurface& read : geo::read_iges_surfaces(path)) {
      check_promises(read.surface);
      if (read.surface.count_u() * read.surface.count_v() <= kMaxControlPoints)
        use_surface(read.surface);
    }
  } catch (const std::exception&) {
    // a clear error for a bad file: accepted
  }
  return 0;
}
