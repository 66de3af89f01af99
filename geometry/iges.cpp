// IGES entity 128 reading and writing through OpenCASCADE; see iges.hpp for what is taken as is.
#include "geometry/iges.hpp"

#include <Geom_BSplineSurface.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESEntity.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESGeom_BSplineSurface.hxx>
#include <IGESGeom_BoundedSurface.hxx>
#include <IGESGeom_TrimmedSurface.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <IGESSolid_Face.hxx>
#include <Interface_Check.hxx>
#include <Interface_FloatWriter.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <UnitsMethods.hxx>
#include <gp_GTrsf.hxx>

#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "geometry/bspline_basis.hpp"
#include "geometry/iges_structure.hpp"
#include "geometry/refinement.hpp"

namespace isomuscle::geometry {

namespace {

// OCCT reports through Message::DefaultMessenger() on stdout; silence it while we work.
class QuietOcct {
 public:
  QuietOcct() : saved_(Message::DefaultMessenger()->Printers()) {
    Message::DefaultMessenger()->ChangePrinters().Clear();
  }
  ~QuietOcct() { Message::DefaultMessenger()->ChangePrinters() = saved_; }
  QuietOcct(const QuietOcct&) = delete;
  QuietOcct& operator=(const QuietOcct&) = delete;

 private:
  Message_SequenceOfPrinters saved_;
};

std::string quoted(const std::filesystem::path& path) {
  std::string text(1, '\'');
  text += path.string();
  text += '\'';
  return text;
}

// IGES 5.3 global parameters 14 and 15: unit flag, and the unit name used when the flag is 3.
std::pair<double, std::string> file_unit(const IGESData_GlobalSection& global,
                                         const std::filesystem::path& path) {
  static const std::map<std::string, double> by_name = {
      {"IN", 0.0254}, {"INCH", 0.0254}, {"MM", 1e-3}, {"FT", 0.3048}, {"MI", 1609.344}, {"M", 1.0},
      {"KM", 1e3},    {"MIL", 2.54e-5}, {"UM", 1e-6}, {"CM", 1e-2},   {"UIN", 2.54e-8}};
  static const char* const by_flag[] = {"",  "IN", "MM",  "",   "FT", "MI",
                                        "M", "KM", "MIL", "UM", "CM", "UIN"};
  const int flag = global.UnitFlag();
  std::string name;
  if (flag == 3) {
    const Handle(TCollection_HAsciiString) written = global.UnitName();
    if (!written.IsNull())
      name = written->ToCString();
    for (char& c : name)
      c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  } else if (flag >= 1 && flag <= 11) {
    name = by_flag[flag];
  }
  const auto it = by_name.find(name);
  if (it == by_name.end()) {
    std::ostringstream msg;
    msg << "IGES file " << quoted(path) << ": unknown length unit (global parameter 14 unit flag "
        << flag << ", name '" << name
        << "'); expected flags 1..11 or flag 3 with IN, MM, FT, MI, M, KM, MIL, UM, CM, UIN";
    throw std::runtime_error(msg.str());
  }
  return {it->second, name};
}

std::string check_messages(const Handle(IGESData_IGESModel) & model, int number) {
  std::string text;
  const Handle(Interface_Check)& check = model->Check(number, true);
  if (check.IsNull())
    return text;
  for (int k = 1; k <= check->NbFails(); ++k) {
    if (!text.empty())
      text += "; ";
    text += check->CFail(k);
  }
  return text;
}

// Distinct knot values and multiplicities (exact comparison) of a full knot sequence.
void to_occt_knots(const std::vector<double>& full, TColStd_Array1OfReal& values,
                   TColStd_Array1OfInteger& mults) {
  std::vector<double> distinct;
  std::vector<int> counts;
  for (const double k : full) {
    if (!distinct.empty() && k == distinct.back()) {
      ++counts.back();
    } else {
      distinct.push_back(k);
      counts.push_back(1);
    }
  }
  values.Resize(1, static_cast<int>(distinct.size()), false);
  mults.Resize(1, static_cast<int>(distinct.size()), false);
  for (std::size_t k = 0; k < distinct.size(); ++k) {
    values(static_cast<int>(k) + 1) = distinct[k];
    mults(static_cast<int>(k) + 1) = counts[k];
  }
}

// A non-periodic OCCT surface with the same knot sequences; points scaled.
Handle(Geom_BSplineSurface)
    to_occt(const std::vector<double>& knots_u, const std::vector<double>& knots_v, int p, int q,
            const std::vector<Eigen::Vector3d>& points, const std::vector<double>& weights, int nu,
            int nv, double scale) {
  TColStd_Array1OfReal ku(1, 1);
  TColStd_Array1OfReal kv(1, 1);
  TColStd_Array1OfInteger mu(1, 1);
  TColStd_Array1OfInteger mv(1, 1);
  to_occt_knots(knots_u, ku, mu);
  to_occt_knots(knots_v, kv, mv);
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal w(1, nu, 1, nv);
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const Eigen::Vector3d x = scale * points[i + nu * j];
      poles(i + 1, j + 1) = gp_Pnt(x.x(), x.y(), x.z());
      w(i + 1, j + 1) = weights[i + nu * j];
    }
  }
  return new Geom_BSplineSurface(poles, w, ku, kv, mu, mv, p, q, false, false);
}

// Largest coordinate magnitude accepted from a file, m (1 km: far beyond any muscle).
constexpr double kMaxCoordinate = 1e3;

bool is_clamped(const std::vector<double>& knots, int degree) {
  const std::size_t n = knots.size();
  for (int k = 1; k <= degree; ++k) {
    if (knots[k] != knots[0] || knots[n - 1 - k] != knots[n - 1])
      return false;
  }
  return true;
}

// One entity 128 as written: knots T(-p)..T(n) in u and v, poles with the entity's (compound)
// transformation applied, weights (all 1 when PROP3 declares the surface polynomial), lengths
// converted to metres. Unclamped knot vectors are clamped on the domain [T(0), T(n - p)] by knot
// insertion to multiplicity p + 1 at its ends (refinement.hpp make_clamped: exact).
IgesSurface convert(const Handle(IGESGeom_BSplineSurface) & e, double metres_per_unit) {
  IgesSurface out;
  const int p = e->DegreeU();
  const int q = e->DegreeV();
  const int nu = e->NbPolesU();
  const int nv = e->NbPolesV();
  if (p < 1 || q < 1 || p > kMaxDegree || q > kMaxDegree) {
    throw std::runtime_error("degrees (" + std::to_string(p) + ", " + std::to_string(q) +
                             ") are outside 1.." + std::to_string(kMaxDegree));
  }
  if (nu < p + 1 || nv < q + 1 || e->NbKnotsU() != nu + p + 1 || e->NbKnotsV() != nv + q + 1) {
    throw std::runtime_error("inconsistent counts: " + std::to_string(nu) + " x " +
                             std::to_string(nv) + " control points, " +
                             std::to_string(e->NbKnotsU()) + " + " + std::to_string(e->NbKnotsV()) +
                             " knots");
  }
  std::vector<double> knots_u;
  std::vector<double> knots_v;
  for (int k = -p; k <= nu; ++k)
    knots_u.push_back(e->KnotU(k));
  for (int k = -q; k <= nv; ++k)
    knots_v.push_back(e->KnotV(k));
  const bool polynomial = e->IsPolynomial(true);
  const gp_GTrsf transformation = e->CompoundLocation();
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      gp_XYZ x = e->Pole(i, j).XYZ();
      if (e->HasTransf())
        transformation.Transforms(x);
      points.emplace_back(metres_per_unit * x.X(), metres_per_unit * x.Y(),
                          metres_per_unit * x.Z());
      // A damaged coordinate (1e300) passes the syntax check but overflows every later volume and
      // Jacobian to inf/NaN; a muscle is centimetres, so anything beyond kMaxCoordinate is
      // reported here, naming the control point.
      if (!(points.back().array().abs() <= kMaxCoordinate).all()) {
        std::ostringstream msg;
        msg << "control point (" << i << ", " << j << ") = (" << points.back().x() << ", "
            << points.back().y() << ", " << points.back().z() << ") m lies beyond "
            << kMaxCoordinate << " m of the origin (wrong unit or damaged coordinates)";
        throw std::runtime_error(msg.str());
      }
      const double w = polynomial ? 1.0 : e->Weight(i, j);
      if (!(std::isfinite(w) && w > 0.0)) {
        throw std::runtime_error("weight (" + std::to_string(i) + ", " + std::to_string(j) +
                                 ") = " + std::to_string(w) + " is not positive");
      }
      weights.push_back(w);
    }
  }
  out.clamped_in_file = {is_clamped(knots_u, p), is_clamped(knots_v, q)};
  out.surface = NurbsSurface(KnotVector(std::move(knots_u), p), KnotVector(std::move(knots_v), q),
                             std::move(points), std::move(weights));
  if (!out.clamped_in_file[0])
    out.surface = make_clamped(out.surface, 0);
  if (!out.clamped_in_file[1])
    out.surface = make_clamped(out.surface, 1);
  out.form = e->FormNumber();
  out.closed_flag = {e->IsClosedU() == Standard_True, e->IsClosedV() == Standard_True};
  out.periodic_flag = {e->IsPeriodicU() == Standard_True, e->IsPeriodicV() == Standard_True};
  // OCCT 7.6 stores the file's U(0), U(1), V(0), V(1) as UMin, VMin, UMax, VMax (checked by
  // tests/geometry/test_iges.cpp with distinct u and v ranges).
  out.parameter_range = {{{e->UMin(), e->VMin()}, {e->UMax(), e->VMax()}}};
  return out;
}

std::string entity_type_name(int type) {
  static const std::map<int, const char*> names = {{100, "circular arc"},
                                                   {102, "composite curve"},
                                                   {104, "conic arc"},
                                                   {106, "copious data"},
                                                   {108, "plane"},
                                                   {110, "line"},
                                                   {112, "spline curve"},
                                                   {114, "spline surface"},
                                                   {116, "point"},
                                                   {118, "ruled surface"},
                                                   {120, "surface of revolution"},
                                                   {122, "tabulated cylinder"},
                                                   {124, "transformation matrix"},
                                                   {126, "B-spline curve"},
                                                   {128, "B-spline surface"},
                                                   {140, "offset surface"},
                                                   {141, "boundary"},
                                                   {142, "curve on surface"},
                                                   {143, "bounded surface"},
                                                   {144, "trimmed surface"},
                                                   {186, "B-rep solid"},
                                                   {190, "plane surface"},
                                                   {192, "cylindrical surface"},
                                                   {194, "conical surface"},
                                                   {196, "spherical surface"},
                                                   {198, "toroidal surface"},
                                                   {308, "subfigure"},
                                                   {314, "colour"},
                                                   {402, "associativity"},
                                                   {406, "property"},
                                                   {502, "vertex list"},
                                                   {504, "edge list"},
                                                   {508, "loop"},
                                                   {510, "face"},
                                                   {514, "shell"}};
  const auto it = names.find(type);
  return it == names.end() ? std::string() : std::string(" ") + it->second;
}

}  // namespace

std::vector<IgesSurface> read_iges_surfaces(const std::filesystem::path& path) {
  check_iges_structure(path);  // guards OCCT, which crashes on truncated files
  IGESControl_Controller::Init();
  const QuietOcct quiet;
  IGESControl_Reader reader;
  if (reader.ReadFile(path.string().c_str()) != IFSelect_RetDone) {
    throw std::runtime_error("IGES file " + quoted(path) +
                             " could not be parsed by OpenCASCADE (not an IGES file?)");
  }
  const Handle(IGESData_IGESModel) model = reader.IGESModel();
  if (model.IsNull() || model->NbEntities() == 0) {
    throw std::runtime_error("IGES file " + quoted(path) + " holds no entities");
  }
  const auto [metres_per_unit, unit_name] = file_unit(model->GlobalSection(), path);

  // Parents: trimmed (144) and bounded (143) surfaces and B-rep faces (510) name their surface.
  std::map<int, std::pair<int, int>> parent_of;  // DE of the surface -> (parent type, parent DE)
  std::map<int, int> type_counts;
  for (int n = 1; n <= model->NbEntities(); ++n) {
    const Handle(IGESData_IGESEntity) entity = model->Entity(n);
    type_counts[entity->TypeNumber()]++;
    if (model->IsErrorEntity(n))
      continue;  // its content may be incomplete: never touch it
    Handle(IGESData_IGESEntity) basis;
    if (const auto t = Handle(IGESGeom_TrimmedSurface)::DownCast(entity); !t.IsNull()) {
      basis = t->Surface();
    } else if (const auto b = Handle(IGESGeom_BoundedSurface)::DownCast(entity); !b.IsNull()) {
      basis = b->Surface();
    } else if (const auto f = Handle(IGESSolid_Face)::DownCast(entity); !f.IsNull()) {
      basis = f->Surface();
    }
    if (!basis.IsNull()) {
      parent_of.emplace(model->DNum(basis), std::make_pair(entity->TypeNumber(), 2 * n - 1));
    }
  }

  std::vector<IgesSurface> surfaces;
  for (int n = 1; n <= model->NbEntities(); ++n) {
    const Handle(IGESData_IGESEntity) entity = model->Entity(n);
    if (entity->TypeNumber() != 128)
      continue;
    const int de = 2 * n - 1;
    const std::string where = "IGES file " + quoted(path) + ", entity 128 at directory entry " +
                              std::to_string(de) + ": ";
    const auto e = Handle(IGESGeom_BSplineSurface)::DownCast(entity);
    const std::string fails = check_messages(model, n);
    if (model->IsErrorEntity(n) || e.IsNull() || !fails.empty()) {
      throw std::runtime_error(where + "malformed parameter data" +
                               (fails.empty() ? std::string() : " (" + fails + ")"));
    }
    IgesSurface surface;
    try {
      surface = convert(e, metres_per_unit);
    } catch (const Standard_Failure& failure) {
      throw std::runtime_error(where + "OpenCASCADE rejected it: " + failure.GetMessageString());
    } catch (const std::exception& error) {
      throw std::runtime_error(where + error.what());
    }
    surface.directory_entry = de;
    if (const auto it = parent_of.find(de); it != parent_of.end()) {
      surface.parent_type = it->second.first;
      surface.parent_directory_entry = it->second.second;
    }
    surface.metres_per_file_unit = metres_per_unit;
    surface.file_unit = unit_name;
    surfaces.push_back(std::move(surface));
  }
  if (surfaces.empty()) {
    std::ostringstream msg;
    msg << "IGES file " << quoted(path) << " holds no B-spline surface (entity 128); it holds:";
    for (const auto& [type, count] : type_counts) {
      msg << " " << count << " x " << type << entity_type_name(type) << ";";
    }
    msg << " export the muscle surface as a NURBS surface (entity 128)";
    throw std::runtime_error(msg.str());
  }
  return surfaces;
}

IgesUnit parse_iges_unit(std::string_view name) {
  if (name == "m")
    return IgesUnit::kMetre;
  if (name == "mm")
    return IgesUnit::kMillimetre;
  throw std::invalid_argument("IGES unit '" + std::string(name) + "' is not one of m, mm");
}

// AddGeom of a Geom_BSplineSurface writes a bare entity 128 (TOOLING.md). OCCT takes the geometry
// in its session length unit (mm unless changed) and converts to the file unit; the real format
// %.16E keeps 17 significant digits (OCCT's default keeps 9).
void write_iges(const std::filesystem::path& path, const std::vector<NurbsSurface>& surfaces,
                IgesUnit unit) {
  if (surfaces.empty()) {
    throw std::invalid_argument("write_iges: no surfaces to write to " + quoted(path));
  }
  IGESControl_Controller::Init();
  const QuietOcct quiet;
  IGESControl_Writer writer(unit == IgesUnit::kMetre ? "M" : "MM", 0);
  const double session_unit_in_metres = UnitsMethods::GetCasCadeLengthUnit() * 1e-3;
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const NurbsSurface& s = surfaces[k];
    try {
      const Handle(Geom_BSplineSurface) occt = to_occt(
          s.knots_u().knots(), s.knots_v().knots(), s.knots_u().degree(), s.knots_v().degree(),
          s.points(), s.weights(), s.count_u(), s.count_v(), 1.0 / session_unit_in_metres);
      if (!writer.AddGeom(occt))
        throw std::runtime_error("AddGeom failed");
    } catch (const Standard_Failure& failure) {
      throw std::runtime_error("write_iges " + quoted(path) + ": surface " + std::to_string(k) +
                               " rejected by OpenCASCADE: " + failure.GetMessageString());
    }
  }
  writer.ComputeModel();
  IGESData_IGESWriter iges(writer.Model());
  iges.FloatWriter().SetFormat("%.16E");
  iges.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
  std::ofstream out(path, std::ios::binary);
  if (!out) {
    throw std::runtime_error("write_iges: cannot open " + quoted(path) +
                             " for writing (does the directory exist and is it writable?)");
  }
  if (!iges.Print(out))
    throw std::runtime_error("write_iges: OpenCASCADE failed writing " + quoted(path));
  out.close();
  if (!out)
    throw std::runtime_error("write_iges: error while writing " + quoted(path));
}

}  // namespace isomuscle::geometry
