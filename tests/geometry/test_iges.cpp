// IGES reading and writing (SPEC §1 "IGES input"): round trips through files written by
// OpenCASCADE (periodic, closed clamped, millimetres), a real CAD file, and bad files.
#include <gtest/gtest.h>

#include <Geom_BSplineSurface.hxx>
#include <Geom_Line.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESGeom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>

#include <unistd.h>

#include "geometry/iges.hpp"
#include "geometry/shapes.hpp"

namespace isomuscle::geometry {
namespace {

namespace fs = std::filesystem;

class Iges : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("isomuscle_test_iges_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path file(const std::string& name) const { return dir_ / name; }
  fs::path dir_;
};

// Surface from OCCT in metres (OCCT lengths are taken in mm here: the session unit).
NurbsSurface from_occt(const Handle(Geom_BSplineSurface) & s, double metres_per_unit) {
  const auto knots = [](const Handle(Geom_BSplineSurface) & b, bool u) {
    std::vector<double> k;
    for (int i = 1; i <= (u ? b->NbUKnots() : b->NbVKnots()); ++i) {
      k.insert(k.end(), static_cast<std::size_t>(u ? b->UMultiplicity(i) : b->VMultiplicity(i)),
               u ? b->UKnot(i) : b->VKnot(i));
    }
    return KnotVector(k, u ? b->UDegree() : b->VDegree());
  };
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  for (int j = 1; j <= s->NbVPoles(); ++j) {
    for (int i = 1; i <= s->NbUPoles(); ++i) {
      const gp_Pnt& p = s->Pole(i, j);
      points.emplace_back(metres_per_unit * p.X(), metres_per_unit * p.Y(),
                          metres_per_unit * p.Z());
      weights.push_back(s->Weights() != nullptr ? s->Weight(i, j) : 1.0);
    }
  }
  return NurbsSurface(knots(s, true), knots(s, false), points, weights);
}

// Same degrees, counts and knots; points within rel * (bounding-box diagonal); weights within rel
// after scaling by the ratio of the first weights (a NURBS is unchanged by a common factor).
void expect_same_nurbs(const NurbsSurface& a, const NurbsSurface& b, double rel) {
  ASSERT_EQ(a.knots_u().degree(), b.knots_u().degree());
  ASSERT_EQ(a.knots_v().degree(), b.knots_v().degree());
  ASSERT_EQ(a.count_u(), b.count_u());
  ASSERT_EQ(a.count_v(), b.count_v());
  for (int k = 0; k < a.knots_u().size(); ++k) {
    EXPECT_NEAR(a.knots_u()[k], b.knots_u()[k], rel * std::abs(a.knots_u().domain_end()));
  }
  for (int k = 0; k < a.knots_v().size(); ++k) {
    EXPECT_NEAR(a.knots_v()[k], b.knots_v()[k], rel * std::abs(a.knots_v().domain_end()));
  }
  Eigen::Vector3d lo = a.points()[0], hi = a.points()[0];
  for (const auto& x : a.points()) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double diagonal = (hi - lo).norm();
  const double scale = b.weights()[0] / a.weights()[0];
  for (std::size_t k = 0; k < a.points().size(); ++k) {
    EXPECT_LE((a.points()[k] - b.points()[k]).norm(), rel * diagonal) << "point " << k;
    EXPECT_NEAR(a.weights()[k] * scale, b.weights()[k], rel * b.weights()[k]) << "weight " << k;
  }
}

// Rational, closed in u, clamped: the cone of the example suite.
TEST_F(Iges, RoundTripInMillimetresAndMetresIsExact) {
  const NurbsSurface cone = cone_frustum(0.02, 0.004, 0.05);
  for (const IgesUnit unit : {IgesUnit::kMillimetre, IgesUnit::kMetre}) {
    const fs::path path = file(unit == IgesUnit::kMetre ? "cone_m.igs" : "cone_mm.igs");
    write_iges(path, {cone, barrel(0.05, 0.0045, 0.00875)}, unit);
    const auto read = read_iges_surfaces(path);
    ASSERT_EQ(read.size(), 2u);
    EXPECT_EQ(read[0].file_unit, unit == IgesUnit::kMetre ? "M" : "MM");
    EXPECT_EQ(read[0].metres_per_file_unit, unit == IgesUnit::kMetre ? 1.0 : 1e-3);
    EXPECT_EQ(read[0].directory_entry, 1);
    EXPECT_EQ(read[1].directory_entry, 3);
    EXPECT_EQ(read[0].parent_type, 0);
    EXPECT_TRUE(read[0].closed_flag[0]);
    EXPECT_FALSE(read[0].closed_flag[1]);
    EXPECT_FALSE(read[0].periodic_flag[0]);
    EXPECT_TRUE(read[0].clamped_in_file[0] && read[0].clamped_in_file[1]);
    EXPECT_TRUE(read[0].surface.is_rational());
    // 17 significant digits are written: the round trip is exact to rounding.
    expect_same_nurbs(cone, read[0].surface, 1e-15);
  }
  // The millimetre file holds millimetres: its raw pole (0, 0) is 20 (mm), read back as 0.02 m.
  IGESControl_Controller::Init();
  IGESControl_Reader raw;
  testing::internal::CaptureStdout();
  ASSERT_EQ(raw.ReadFile(file("cone_mm.igs").c_str()), IFSelect_RetDone);
  testing::internal::GetCapturedStdout();
  const auto entity = Handle(IGESGeom_BSplineSurface)::DownCast(raw.IGESModel()->Entity(1));
  ASSERT_FALSE(entity.IsNull());
  EXPECT_NEAR(entity->Pole(0, 0).X(), 20.0, 1e-12);
}

// A surface OCCT itself makes periodic in u, written by OCCT's own writer (9 significant digits,
// session unit mm): read back clamped, equal to OCCT's clamped form (SetUNotPeriodic + Segment)
// and to the periodic surface at random points.
TEST_F(Iges, PeriodicSurfaceComesBackClampedAndEqual) {
  const int nu = 7, nv = 3;
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i) {
    const double a = 2.0 * M_PI * (i - 1) / nu;
    for (int j = 1; j <= nv; ++j) {
      const double r = 10.0 + 3.0 * j + std::sin(3 * a) / 3.0;
      poles(i, j) = gp_Pnt(r * std::cos(a), r * std::sin(a), 7.0 * j + 0.1 * i);
      weights(i, j) = 1.0 + 0.3 * std::cos(i + 2.0 * j);
    }
  }
  TColStd_Array1OfReal ku(1, nu + 1);
  TColStd_Array1OfInteger mu(1, nu + 1);
  for (int k = 1; k <= nu + 1; ++k) {
    ku(k) = 0.4 * (k - 1) + 0.01 * k * k;  // non-uniform
    mu(k) = 1;
  }
  TColStd_Array1OfReal kv(1, 2);
  TColStd_Array1OfInteger mv(1, 2);
  kv(1) = 0.0;
  kv(2) = 2.0;
  mv(1) = mv(2) = 3;
  Handle(Geom_BSplineSurface) periodic =
      new Geom_BSplineSurface(poles, weights, ku, kv, mu, mv, 3, 2, true, false);
  ASSERT_TRUE(periodic->IsUPeriodic());
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", 0);
  ASSERT_TRUE(writer.AddGeom(periodic));
  ASSERT_TRUE(writer.Write(file("periodic.igs").c_str()));

  const auto read = read_iges_surfaces(file("periodic.igs"));
  ASSERT_EQ(read.size(), 1u);
  EXPECT_TRUE(read[0].periodic_flag[0]);
  EXPECT_FALSE(read[0].clamped_in_file[0]);
  EXPECT_TRUE(read[0].clamped_in_file[1]);
  EXPECT_TRUE(read[0].surface.knots_u().is_clamped());
  EXPECT_TRUE(read[0].surface.is_closed(0, 1e-8));

  Handle(Geom_BSplineSurface) clamped = Handle(Geom_BSplineSurface)::DownCast(periodic->Copy());
  double u0, u1, v0, v1;
  periodic->Bounds(u0, u1, v0, v1);
  clamped->SetUNotPeriodic();
  clamped->Segment(u0, u1, v0, v1);
  expect_same_nurbs(from_occt(clamped, 1e-3), read[0].surface, 1e-8);

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 500; ++k) {
    const double u = u0 + (u1 - u0) * unit(rng), v = v0 + (v1 - v0) * unit(rng);
    const gp_Pnt p = periodic->Value(u, v);
    const Eigen::Vector3d x = read[0].surface.evaluate(u, v);
    worst = std::max(worst, (x - 1e-3 * Eigen::Vector3d(p.X(), p.Y(), p.Z())).norm() / 0.02);
  }
  std::printf("periodic surface through OCCT's 9-digit writer: worst relative deviation %.2e\n",
              worst);
  EXPECT_LT(worst, 1e-8);
}

// A closed clamped surface written by OCCT's own writer: OCCT's shape transfer would make it
// periodic; read_iges_surfaces returns the clamped original.
TEST_F(Iges, ClosedClampedSurfaceReadsBackAsTheClampedOriginal) {
  const NurbsSurface torus_surface = torus(0.013, 0.004);
  const NurbsSurface& s = torus_surface;
  TColgp_Array2OfPnt poles(1, s.count_u(), 1, s.count_v());
  TColStd_Array2OfReal weights(1, s.count_u(), 1, s.count_v());
  for (int j = 0; j < s.count_v(); ++j) {
    for (int i = 0; i < s.count_u(); ++i) {
      const Eigen::Vector3d x = 1e3 * s.point(i, j);  // mm
      poles(i + 1, j + 1) = gp_Pnt(x.x(), x.y(), x.z());
      weights(i + 1, j + 1) = s.weight(i, j);
    }
  }
  TColStd_Array1OfReal k(1, 5);
  TColStd_Array1OfInteger m(1, 5);
  for (int i = 1; i <= 5; ++i) {
    k(i) = 0.25 * (i - 1);
    m(i) = (i == 1 || i == 5) ? 3 : 2;
  }
  Handle(Geom_BSplineSurface) occt = new Geom_BSplineSurface(poles, weights, k, k, m, m, 2, 2);
  ASSERT_FALSE(occt->IsUPeriodic());
  ASSERT_TRUE(occt->IsUClosed());
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", 0);
  ASSERT_TRUE(writer.AddGeom(occt));
  ASSERT_TRUE(writer.Write(file("torus.igs").c_str()));
  const auto read = read_iges_surfaces(file("torus.igs"));
  ASSERT_EQ(read.size(), 1u);
  EXPECT_TRUE(read[0].closed_flag[0] && read[0].closed_flag[1]);
  EXPECT_TRUE(read[0].clamped_in_file[0] && read[0].clamped_in_file[1]);
  expect_same_nurbs(s, read[0].surface, 1e-8);
}

// OCCT 7.6 swaps the parameter-range accessors; the reader must report the file's U and V ranges.
TEST_F(Iges, ParameterRangeIsReportedPerDirection) {
  TColgp_Array2OfPnt poles(1, 3, 1, 3);
  for (int i = 1; i <= 3; ++i) {
    for (int j = 1; j <= 3; ++j)
      poles(i, j) = gp_Pnt(i, j, 0.1 * i * j);
  }
  TColStd_Array1OfReal ku(1, 2), kv(1, 2);
  TColStd_Array1OfInteger m(1, 2);
  ku(1) = 0.0;
  ku(2) = 2.0;
  kv(1) = 5.0;
  kv(2) = 7.0;
  m(1) = m(2) = 3;
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", 0);
  ASSERT_TRUE(writer.AddGeom(
      Handle(Geom_BSplineSurface)(new Geom_BSplineSurface(poles, ku, kv, m, m, 2, 2))));
  ASSERT_TRUE(writer.Write(file("range.igs").c_str()));
  const auto read = read_iges_surfaces(file("range.igs"));
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].parameter_range[0][0], 0.0);
  EXPECT_EQ(read[0].parameter_range[0][1], 2.0);
  EXPECT_EQ(read[0].parameter_range[1][0], 5.0);
  EXPECT_EQ(read[0].parameter_range[1][1], 7.0);
  EXPECT_FALSE(read[0].surface.is_rational());
}

// A file nobody here wrote (Debian package occt-misc): 45 entity-128 surfaces, each the basis of a
// trimmed surface (144), 27 rational, in mm. Checked against OCCT's evaluation of the raw entities.
TEST_F(Iges, ReadsRealCadFileHammer) {
  const fs::path hammer = "/usr/share/opencascade/data/iges/hammer.iges";
  if (!fs::exists(hammer)) {
    GTEST_SKIP() << hammer << " is absent: install the Debian package occt-misc to run this test";
  }
  testing::internal::CaptureStdout();
  const auto read = read_iges_surfaces(hammer);
  const std::string printed = testing::internal::GetCapturedStdout();
  EXPECT_EQ(printed, "") << "OpenCASCADE messages must be silenced";
  ASSERT_EQ(read.size(), 45u);
  int rational = 0;
  for (const IgesSurface& s : read) {
    rational += s.surface.is_rational();
    EXPECT_EQ(s.parent_type, 144);
    EXPECT_EQ(s.file_unit, "MM");
  }
  EXPECT_EQ(rational, 27);
  // First surface (DE 5): knots and first pole as printed in the file.
  EXPECT_EQ(read[0].directory_entry, 5);
  EXPECT_EQ(read[0].parent_directory_entry, 3);
  EXPECT_EQ(
      read[0].surface.knots_u().knots(),
      (std::vector<double>{-2.93838206E-003, -2.93838206E-003, -2.93838206E-003, -2.220446E-015,
                           -2.220446E-015, 0.717049977, 0.717049977, 0.717049977}));
  EXPECT_EQ(read[0].surface.point(0, 0),
            Eigen::Vector3d(-7.945189943E+003, 1.930285535E+004, -1.306741845E+004) * 1e-3);
  EXPECT_NEAR(read[0].parameter_range[1][0], 3.141592654, 1e-12);

  // Every surface against OCCT's own evaluation of the raw entity data.
  IGESControl_Controller::Init();
  IGESControl_Reader raw;
  testing::internal::CaptureStdout();
  ASSERT_EQ(raw.ReadFile(hammer.c_str()), IFSelect_RetDone);
  testing::internal::GetCapturedStdout();
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (const IgesSurface& s : read) {
    const auto e = Handle(IGESGeom_BSplineSurface)::DownCast(
        raw.IGESModel()->Entity((s.directory_entry + 1) / 2));
    ASSERT_FALSE(e.IsNull());
    TColgp_Array2OfPnt poles(1, e->NbPolesU(), 1, e->NbPolesV());
    TColStd_Array2OfReal weights(1, e->NbPolesU(), 1, e->NbPolesV());
    for (int i = 0; i < e->NbPolesU(); ++i) {
      for (int j = 0; j < e->NbPolesV(); ++j) {
        poles(i + 1, j + 1) = e->TransformedPole(i, j);
        weights(i + 1, j + 1) = e->Weight(i, j);
      }
    }
    const auto distinct = [](const IGESGeom_BSplineSurface& b, bool u, TColStd_Array1OfReal& k,
                             TColStd_Array1OfInteger& m) {
      std::vector<double> values;
      std::vector<int> mults;
      const int p = u ? b.DegreeU() : b.DegreeV();
      const int n = u ? b.NbPolesU() : b.NbPolesV();
      for (int i = -p; i <= n; ++i) {
        const double x = u ? b.KnotU(i) : b.KnotV(i);
        if (!values.empty() && x == values.back()) {
          ++mults.back();
        } else {
          values.push_back(x);
          mults.push_back(1);
        }
      }
      k.Resize(1, static_cast<int>(values.size()), false);
      m.Resize(1, static_cast<int>(values.size()), false);
      for (std::size_t i = 0; i < values.size(); ++i) {
        k(static_cast<int>(i) + 1) = values[i];
        m(static_cast<int>(i) + 1) = mults[i];
      }
    };
    TColStd_Array1OfReal ku(1, 1), kv(1, 1);
    TColStd_Array1OfInteger mu(1, 1), mv(1, 1);
    distinct(*e, true, ku, mu);
    distinct(*e, false, kv, mv);
    Handle(Geom_BSplineSurface) occt =
        new Geom_BSplineSurface(poles, weights, ku, kv, mu, mv, e->DegreeU(), e->DegreeV());
    const KnotVector& u = s.surface.knots_u();
    const KnotVector& v = s.surface.knots_v();
    double size = 0.0;
    for (const auto& x : s.surface.points())
      size = std::max(size, x.norm());
    for (int k = 0; k < 40; ++k) {
      const double a = u.domain_begin() + (u.domain_end() - u.domain_begin()) * unit(rng);
      const double b = v.domain_begin() + (v.domain_end() - v.domain_begin()) * unit(rng);
      const gp_Pnt p = occt->Value(a, b);
      const Eigen::Vector3d x = s.surface.evaluate(a, b);
      worst = std::max(worst, (x - 1e-3 * Eigen::Vector3d(p.X(), p.Y(), p.Z())).norm() / size);
    }
  }
  std::printf("hammer.iges: worst deviation from OCCT's evaluation %.2e (relative)\n", worst);
  EXPECT_LT(worst, 1e-13);
}

std::string error_of(const fs::path& path) {
  try {
    read_iges_surfaces(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST_F(Iges, BadFilesGiveClearErrors) {
  EXPECT_NE(error_of(file("missing.igs")).find("does not exist"), std::string::npos);
  EXPECT_NE(error_of(file("missing.igs")).find("missing.igs"), std::string::npos);
  std::ofstream(file("empty.igs")).close();
  EXPECT_NE(error_of(file("empty.igs")).find("is empty"), std::string::npos);
  std::ofstream(file("text.igs")) << "solid cube\n  facet normal 0 0 1\nendsolid\n";
  EXPECT_NE(error_of(file("text.igs")).find("columns"), std::string::npos)
      << error_of(file("text.igs"));
  EXPECT_NE(error_of(dir_).find("directory"), std::string::npos);

  // No surfaces: a file with one line (entity 110).
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", 0);
  ASSERT_TRUE(writer.AddGeom(Handle(Geom_Line)(new Geom_Line(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)))));
  ASSERT_TRUE(writer.Write(file("line.igs").c_str()));
  const std::string no_surface = error_of(file("line.igs"));
  EXPECT_NE(no_surface.find("holds no B-spline surface"), std::string::npos) << no_surface;
  EXPECT_NE(no_surface.find("110 line"), std::string::npos) << no_surface;
}

// Truncation after every line and inside lines: always a clear error, never a crash (OCCT 7.6
// alone crashes on some of these).
TEST_F(Iges, TruncatedFilesAreRejectedNeverCrash) {
  write_iges(file("full.igs"), {cone_frustum(0.02, 0.004, 0.05)});
  std::ifstream in(file("full.igs"), std::ios::binary);
  const std::string full((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(full.size(), 1000u);
  int rejected = 0, cuts = 0;
  for (std::size_t cut = 0; cut < full.size(); cut += 37) {
    std::ofstream(file("cut.igs"), std::ios::binary) << full.substr(0, cut);
    ++cuts;
    const std::string message = error_of(file("cut.igs"));
    EXPECT_FALSE(message.empty()) << "cut at byte " << cut;
    rejected += !message.empty();
  }
  EXPECT_EQ(rejected, cuts);
  // Cut at a record boundary just before the T record: named as truncated.
  const std::size_t last_record = full.rfind('\n', full.size() - 2) + 1;
  std::ofstream(file("cut.igs"), std::ios::binary) << full.substr(0, last_record);
  EXPECT_NE(error_of(file("cut.igs")).find("truncated"), std::string::npos);
}

// Damaged parameter data with intact records: the entity is reported, not crashed on.
TEST_F(Iges, DamagedParameterDataNamesTheEntity) {
  write_iges(file("full.igs"), {cone_frustum(0.02, 0.004, 0.05)});
  std::ifstream in(file("full.igs"), std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The first parameter-data record (column 73 'P'), not the first "128," of the file: the
  // global section before it holds the writing time, which contains "128," at hh:m1:28.
  std::size_t p = 0;
  while (p < text.size() && !(text.size() > p + 72 && text[p + 72] == 'P')) {
    const std::size_t end_of_line = text.find('\n', p);
    p = end_of_line == std::string::npos ? text.size() : end_of_line + 1;
  }
  ASSERT_LT(p, text.size());
  ASSERT_EQ(text.compare(p, 4, "128,"), 0) << text.substr(p, 80);
  text.replace(p, 6, "128,Q,");  // K1 is no longer an integer
  std::ofstream(file("bad.igs"), std::ios::binary) << text;
  const std::string message = error_of(file("bad.igs"));
  EXPECT_NE(message.find("directory entry 1"), std::string::npos)
      << message << "\ndamaged record: " << text.substr(p, 80);
}

// A seed of fuzz/iges_reader_fuzzer: one trimmed B-spline face of hammer.iges (occt-misc) as
// OpenCASCADE writes it, as a trimmed surface (144 over 128, 142, 102, 126) or as a B-rep (510
// over 128, 508 loops, 504 edges, 502 vertices, 126 curves).
fs::path hammer_face(bool brep) {
  return fs::path(ISOMUSCLE_SOURCE_DIR) / "fuzz" / "corpus" / "iges_reader" /
         (brep ? "occt_hammer_face_brep.igs" : "occt_hammer_face.igs");
}

// The error of reading a copy of `source` that `damage` changed in place (columns intact).
std::string error_of_damaged(const fs::path& source, const fs::path& copy,
                             const std::function<void(std::string&)>& damage) {
  std::ifstream in(source, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  damage(text);
  std::ofstream(copy, std::ios::binary) << text;
  return error_of(copy);
}

// The trimming curves (entity 126) of a CAD face are checked as well: fuzz/iges_reader_fuzzer found
// OpenCASCADE 7.6 dereferencing a null array on a 126 whose degree exceeds its poles
// (fuzz/regressions/iges_reader/occt-126-degree-beyond-poles.igs). The check names the entity.
TEST_F(Iges, DamagedTrimmingCurveIsNamedBeforeOpenCascadeReadsIt) {
  ASSERT_EQ(read_iges_surfaces(hammer_face(false)).at(0).parent_type, 144);
  const std::string message =
      error_of_damaged(hammer_face(false), file("bad_curve.igs"), [](std::string& text) {
        const std::size_t record = text.rfind('\n', text.find("0000019P0000100")) + 1;
        ASSERT_EQ(text.compare(record, 9, "126,21,3,"), 0);
        text.replace(record, 9, "126,2,31,");  // degree 31 with 3 poles
      });
  EXPECT_NE(message.find("directory entry 19 (type 126)"), std::string::npos) << message;
  EXPECT_NE(message.find("impossible sizes K = 2, M = 31"), std::string::npos) << message;
}

// A directory-entry pointer must name an entity of the type its field allows: OpenCASCADE 7.6
// follows them unchecked, and a view pointer to a B-rep face made a reference cycle it never frees
// (found by fuzz/iges_reader_fuzzer:
// fuzz/regressions/iges_reader/occt-leak-view-pointer-to-face.igs).
TEST_F(Iges, DirectoryPointerToAnEntityOfTheWrongTypeIsNamed) {
  ASSERT_EQ(read_iges_surfaces(hammer_face(true)).at(0).parent_type, 510);
  const std::string message =
      error_of_damaged(hammer_face(true), file("bad_view.igs"), [](std::string& text) {
        const std::size_t record = text.rfind('\n', text.find("D0000019")) + 1;
        ASSERT_EQ(text.compare(record, 8, "     126"), 0);
        text.replace(record + 40, 8, "       1");  // the view field (columns 41-48): the face
      });
  EXPECT_NE(message.find("directory entry 19 (type 126): view pointer names directory entry 1 "
                         "of type 510"),
            std::string::npos)
      << message;
}

// The pointers inside the B-rep entities' parameters must name entities: OpenCASCADE 7.6
// dereferences the null entity it makes of one that does not (found by fuzz/iges_reader_fuzzer:
// fuzz/regressions/iges_reader/occt-508-loop-edge-pointer-empty.igs).
TEST_F(Iges, BrepPointerToNoEntityIsNamed) {
  const std::string message =
      error_of_damaged(hammer_face(true), file("bad_loop.igs"), [](std::string& text) {
        const std::size_t loop = text.find("508,3,0,7,");
        ASSERT_NE(loop, std::string::npos);
        text.replace(loop, 10, "508,3,0,8,");  // the first edge list: 8 is no directory entry
      });
  EXPECT_NE(message.find("directory entry 5 (type 508): parameter 4: pointer '8' names no "
                         "directory entry"),
            std::string::npos)
      << message;
}

TEST(IgesUnits, ParseUnit) {
  EXPECT_EQ(parse_iges_unit("m"), IgesUnit::kMetre);
  EXPECT_EQ(parse_iges_unit("mm"), IgesUnit::kMillimetre);
  EXPECT_THROW(parse_iges_unit("cm"), std::invalid_argument);
  EXPECT_THROW(write_iges("/nonexistent_dir/x.igs", {cone_frustum(0.02, 0.004, 0.05)}),
               std::runtime_error);
}

}  // namespace
}  // namespace isomuscle::geometry
