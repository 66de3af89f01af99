#include "io/solution_file.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "io/hdf5_support.hpp"
#include "io/setting_check.hpp"

namespace isomuscle::io {

namespace {

constexpr std::int64_t kFormat = 1;
const char* kKnotNames[3] = {"knots_u", "knots_v", "knots_w"};

void write_volume(hid_t file, const char* group_name, const geometry::NurbsVolume& v,
                  const std::string& where) {
  hdf5::Handle group = hdf5::create_group(file, group_name, where);
  const std::string at = where + ":/" + group_name;
  const std::int64_t degrees[3] = {v.degree(0), v.degree(1), v.degree(2)};
  hdf5::write_dataset(group.get(), "degrees", 3, 1, true, H5T_STD_I64LE, H5T_NATIVE_INT64, degrees,
                      at + "/degrees");
  for (int d = 0; d < 3; ++d)
    hdf5::write_doubles(group.get(), kKnotNames[d], v.knots(d).knots(), 1,
                        at + "/" + kKnotNames[d]);
  std::vector<double> points;
  points.reserve(3 * v.points().size());
  for (const Eigen::Vector3d& x : v.points())
    points.insert(points.end(), {x.x(), x.y(), x.z()});
  hdf5::write_doubles(group.get(), "points", points, 3, at + "/points");
  hdf5::write_doubles(group.get(), "weights", v.weights(), 1, at + "/weights");
}

geometry::NurbsVolume read_volume(hid_t file, const char* group_name, const std::string& where) {
  const std::string at = where + ":/" + group_name;
  hdf5::Handle group = hdf5::open_group(file, group_name, where);
  const hdf5::Array<std::int64_t> degrees = hdf5::read_ints(group.get(), "degrees", at);
  if (degrees.values.size() != 3)
    throw std::runtime_error(at + ": 'degrees' must hold 3 values");
  std::array<geometry::KnotVector, 3> knots;
  try {
    for (int d = 0; d < 3; ++d) {
      knots[d] = geometry::KnotVector(hdf5::read_doubles(group.get(), kKnotNames[d], at).values,
                                      static_cast<int>(degrees.values[d]));
    }
    const hdf5::Array<double> p = hdf5::read_doubles(group.get(), "points", at);
    if (p.columns() != 3)
      throw std::runtime_error("'points' must have 3 columns");
    std::vector<Eigen::Vector3d> points(p.rows());
    for (std::size_t i = 0; i < points.size(); ++i)
      points[i] = {p.values[3 * i], p.values[3 * i + 1], p.values[3 * i + 2]};
    return geometry::NurbsVolume(std::move(knots), std::move(points),
                                 hdf5::read_doubles(group.get(), "weights", at).values);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(at + ": not a valid NURBS volume: " + e.what());
  }
}

void write_mesh(hid_t file, const tet::TetMesh& mesh, const std::string& where) {
  hdf5::Handle group = hdf5::create_group(file, "tet", where);
  const std::string at = where + ":/tet";
  const std::int64_t order = mesh.order;
  hdf5::write_scalar_attribute(group.get(), "order", H5T_STD_I64LE, H5T_NATIVE_INT64, &order, at);
  std::vector<double> nodes;
  nodes.reserve(3 * mesh.nodes.size());
  for (const Eigen::Vector3d& x : mesh.nodes)
    nodes.insert(nodes.end(), {x.x(), x.y(), x.z()});
  hdf5::write_doubles(group.get(), "nodes", nodes, 3, at + "/nodes");
  const std::vector<std::int64_t> elements(mesh.elements.begin(), mesh.elements.end());
  hdf5::write_dataset(group.get(), "elements", static_cast<hsize_t>(mesh.num_elements()),
                      static_cast<hsize_t>(mesh.nodes_per_element()), false, H5T_STD_I64LE,
                      H5T_NATIVE_INT64, elements.data(), at + "/elements");
}

tet::TetMesh read_mesh(hid_t file, const std::string& where) {
  const std::string at = where + ":/tet";
  hdf5::Handle group = hdf5::open_group(file, "tet", where);
  tet::TetMesh mesh;
  mesh.order = static_cast<int>(hdf5::read_int_attribute(group.get(), "order", at));
  const hdf5::Array<double> nodes = hdf5::read_doubles(group.get(), "nodes", at);
  const hdf5::Array<std::int64_t> elements = hdf5::read_ints(group.get(), "elements", at);
  if (nodes.columns() != 3 || (mesh.order != 1 && mesh.order != 2) ||
      static_cast<int>(elements.columns()) != mesh.nodes_per_element()) {
    throw std::runtime_error(at + ": nodes must have 3 columns and elements 4 or 10 (order " +
                             std::to_string(mesh.order) + ")");
  }
  for (std::size_t i = 0; i < nodes.rows(); ++i)
    mesh.nodes.emplace_back(nodes.values[3 * i], nodes.values[3 * i + 1], nodes.values[3 * i + 2]);
  mesh.elements.assign(elements.values.begin(), elements.values.end());
  mesh.element_region.assign(elements.rows(), 0);
  try {
    mesh.validate();
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(at + ": not a valid mesh: " + e.what());
  }
  return mesh;
}

}  // namespace

SolutionWriter::SolutionWriter(std::filesystem::path path, const geometry::NurbsVolume& geometry,
                               const tet::TetMesh& mesh)
    : path_(std::move(path)), rows_(mesh.num_nodes()) {
  hdf5::Quiet quiet;
  hdf5::Handle file = hdf5::create_file(path_.string());
  const std::string where = path_.string();
  hdf5::write_string_attribute(file.get(), "discretisation", "tet", where);
  hdf5::write_scalar_attribute(file.get(), "format", H5T_STD_I64LE, H5T_NATIVE_INT64, &kFormat,
                               where);
  write_volume(file.get(), "geometry", geometry, where);
  write_mesh(file.get(), mesh, where);
  file.close("closing " + where);
}

SolutionWriter::SolutionWriter(std::filesystem::path path, const geometry::NurbsVolume& geometry,
                               const geometry::NurbsVolume& iga_space)
    : path_(std::move(path)), rows_(iga_space.num_control_points()) {
  hdf5::Quiet quiet;
  hdf5::Handle file = hdf5::create_file(path_.string());
  const std::string where = path_.string();
  hdf5::write_string_attribute(file.get(), "discretisation", "iga", where);
  hdf5::write_scalar_attribute(file.get(), "format", H5T_STD_I64LE, H5T_NATIVE_INT64, &kFormat,
                               where);
  write_volume(file.get(), "geometry", geometry, where);
  write_volume(file.get(), "iga", iga_space, where);
  file.close("closing " + where);
}

void SolutionWriter::write_step(double time, const DisplacementRows& displacement) {
  const std::string where = path_.string() + ", step " + std::to_string(steps_);
  if (displacement.rows() != rows_) {
    throw std::invalid_argument(where + ": " + std::to_string(displacement.rows()) +
                                " displacement rows for " + std::to_string(rows_) +
                                " control points or nodes");
  }
  if (!std::isfinite(time) || (steps_ > 0 && !(time > last_time_))) {
    throw std::invalid_argument(where + ": time " + format_number(time) +
                                " s must be finite and later than the previous step's");
  }
  for (Eigen::Index i = 0; i < displacement.rows(); ++i) {
    if (!displacement.row(i).allFinite()) {
      throw std::invalid_argument(where + ": the displacement of control point " +
                                  std::to_string(i) +
                                  " is not finite; refusing to write non-finite results");
    }
  }
  hdf5::Quiet quiet;
  hdf5::Handle file = hdf5::open_file(path_.string(), true);
  {
    hdf5::Handle group = hdf5::create_group(file.get(), hdf5::numbered("step", steps_), where);
    hdf5::write_scalar_attribute(group.get(), "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &time,
                                 where);
    hdf5::write_dataset(group.get(), "displacement", static_cast<hsize_t>(rows_), 3, false,
                        H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, displacement.data(),
                        where + " displacement");
  }
  file.close("closing " + path_.string());
  ++steps_;
  last_time_ = time;
}

StoredSolution read_solution(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw std::runtime_error(path.string() +
                             ": no such file (a run writes solution.h5 next to "
                             "summary.json)");
  const std::string where = path.string();
  hdf5::Quiet quiet;
  hdf5::Handle file = hdf5::open_file(where, false);
  StoredSolution s;
  s.path = path;
  s.discretisation = hdf5::read_string_attribute(file.get(), "discretisation", where);
  const std::int64_t format = hdf5::read_int_attribute(file.get(), "format", where);
  if (format != kFormat) {
    throw std::runtime_error(where + ": solution file format " + std::to_string(format) +
                             ", this isomuscle reads format " + std::to_string(kFormat));
  }
  if (s.discretisation != "iga" && s.discretisation != "tet") {
    throw std::runtime_error(where + ": discretisation '" + s.discretisation +
                             "' is not one this isomuscle reads (iga, tet)");
  }
  s.geometry = read_volume(file.get(), "geometry", where);
  if (s.discretisation == "iga")
    s.iga = read_volume(file.get(), "iga", where);
  else
    s.tet = read_mesh(file.get(), where);
  const Eigen::Index rows = s.iga ? s.iga->num_control_points() : s.tet->num_nodes();
  for (std::size_t k = 0;; ++k) {
    const std::string name = hdf5::numbered("step", k);
    if (!hdf5::has_link(file.get(), name))
      break;
    hdf5::Handle group = hdf5::open_group(file.get(), name, where);
    const std::string at = where + ":/" + name;
    s.times.push_back(hdf5::read_double_attribute(group.get(), "time", at));
    const hdf5::Array<double> u = hdf5::read_doubles(group.get(), "displacement", at);
    if (static_cast<Eigen::Index>(u.rows()) != rows || u.columns() != 3) {
      throw std::runtime_error(at + ": displacement is " + std::to_string(u.rows()) + " x " +
                               std::to_string(u.columns()) + ", expected " + std::to_string(rows) +
                               " x 3");
    }
    s.displacement.emplace_back(Eigen::Map<const DisplacementRows>(u.values.data(), rows, 3));
  }
  return s;
}

}  // namespace isomuscle::io
