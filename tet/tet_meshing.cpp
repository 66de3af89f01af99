#include "tet/tet_meshing.hpp"

#include <gmsh.h>
#include <IGESControl_Controller.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "tet/curved_tet_repair.hpp"

namespace isomuscle::tet {

namespace {

constexpr int kGmshTet4 = 4;
constexpr int kGmshTet10 = 11;
constexpr int kGmshTri3 = 2;
constexpr int kGmshTri6 = 9;

std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

// RAII guard: one gmsh session at a time in this process, gmsh's messages off and OpenCASCADE's
// (its IGES import prints on stdout through Message::DefaultMessenger()) suspended, gmsh finalised
// and the OCCT printers restored on every path.
class GmshSession {
 public:
  GmshSession() : lock_(gmsh_mutex()), saved_(Message::DefaultMessenger()->Printers()) {
    Message::DefaultMessenger()->ChangePrinters().Clear();
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    // Errors only: with Terminal = 0 nothing is printed, and gmsh's logger (generate_contained)
    // records nothing at verbosity 0, which left a failed mesh without gmsh's reason.
    gmsh::option::setNumber("General.Verbosity", 1);
  }
  ~GmshSession() {
    try {
      gmsh::finalize();
    } catch (...) {  // nothing sensible to do in a destructor
    }
    Message::DefaultMessenger()->ChangePrinters() = saved_;
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  std::lock_guard<std::mutex> lock_;
  Message_SequenceOfPrinters saved_;
};

// Tag of the first physical group of each entity of dimension dim (entity tag when none), and the
// group names.
std::map<int, int> entity_groups(int dim, std::map<int, std::string>& names) {
  std::map<int, int> out;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim);
  for (const auto& [d, tag] : groups) {
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(d, tag, entities);
    for (int ent : entities) {
      out.emplace(ent, tag);
    }
    std::string name;
    gmsh::model::getPhysicalName(d, tag, name);
    if (!name.empty()) {
      names[tag] = name;
    }
  }
  return out;
}

// The current gmsh model's tetrahedra and boundary triangles as a TetMesh (lengths times scale).
TetMesh extract_mesh(const std::string& file, double scale) {
  TetMesh mesh;
  const std::map<int, int> volume_groups = entity_groups(3, mesh.group_names);
  const std::map<int, int> surface_groups = entity_groups(2, mesh.group_names);
  gmsh::vectorpair volumes;
  gmsh::model::getEntities(volumes, 3);
  std::vector<std::size_t> tet_tags;  // gmsh node tags, nodes_per_element per element
  std::vector<int> regions;
  int order = 0;
  for (const auto& [dim, ent] : volumes) {
    std::vector<int> types;
    gmsh::model::mesh::getElementTypes(types, dim, ent);
    for (int type : types) {
      if (type != kGmshTet4 && type != kGmshTet10) {
        continue;
      }
      const int this_order = type == kGmshTet4 ? 1 : 2;
      if (order != 0 && order != this_order) {
        throw std::runtime_error("'" + file + "' mixes 4-node and 10-node tetrahedra");
      }
      order = this_order;
      std::vector<std::size_t> elem_tags, node_tags;
      gmsh::model::mesh::getElementsByType(type, elem_tags, node_tags, ent);
      tet_tags.insert(tet_tags.end(), node_tags.begin(), node_tags.end());
      const auto g = volume_groups.find(ent);
      regions.insert(regions.end(), elem_tags.size(), g == volume_groups.end() ? ent : g->second);
    }
  }
  if (order == 0) {
    throw std::runtime_error("'" + file + "' holds no tetrahedra (4- or 10-node) in a volume");
  }
  mesh.order = order;
  // Nodes: those of the tetrahedra, numbered by ascending gmsh tag.
  std::vector<std::size_t> used = tet_tags;
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::unordered_map<std::size_t, int> index;
  index.reserve(used.size());
  for (std::size_t i = 0; i < used.size(); ++i) {
    index.emplace(used[i], static_cast<int>(i));
  }
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, params;
  gmsh::model::mesh::getNodes(node_tags, coords, params, -1, -1, false, false);
  mesh.nodes.assign(used.size(), Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < node_tags.size(); ++i) {
    const auto it = index.find(node_tags[i]);
    if (it != index.end()) {
      mesh.nodes[it->second] =
          scale * Eigen::Vector3d(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]);
    }
  }
  mesh.elements.reserve(tet_tags.size());
  for (std::size_t t : tet_tags) {
    mesh.elements.push_back(index.at(t));
  }
  mesh.element_region = std::move(regions);
  // Orientation: swap corners 1 and 2 (and edge nodes 4 <-> 6, 8 <-> 9) of negative elements.
  const int npe = mesh.nodes_per_element();
  for (int e = 0; e < mesh.num_elements(); ++e) {
    int* el = mesh.elements.data() + static_cast<std::size_t>(e) * npe;
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) {
      J.col(c) = mesh.nodes[el[c + 1]] - mesh.nodes[el[0]];
    }
    if (J.determinant() < 0.0) {
      std::swap(el[1], el[2]);
      if (order == 2) {
        std::swap(el[4], el[6]);
        std::swap(el[8], el[9]);
      }
    }
  }
  // Boundary triangles.
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  const int tri_type = order == 1 ? kGmshTri3 : kGmshTri6;
  for (const auto& [dim, ent] : surfaces) {
    std::vector<std::size_t> elem_tags, tri_nodes;
    gmsh::model::mesh::getElementsByType(tri_type, elem_tags, tri_nodes, ent);
    const auto g = surface_groups.find(ent);
    const int tag = g == surface_groups.end() ? ent : g->second;
    for (std::size_t n : tri_nodes) {
      const auto it = index.find(n);
      if (it == index.end()) {
        throw std::runtime_error("'" + file + "': a triangle of surface " + std::to_string(ent) +
                                 " has a node that belongs to no tetrahedron");
      }
      mesh.boundary.push_back(it->second);
    }
    mesh.boundary_tag.insert(mesh.boundary_tag.end(), elem_tags.size(), tag);
  }
  try {
    mesh.validate();
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("'" + file + "': " + e.what());
  }
  return mesh;
}

// A volume from the imported faces: the open boundary curves of the faces (a tube's two end
// circles: the shrink solids of thesis 5.13 have flat ends that the boundary surface lacks) are
// capped, and all faces are sewn into one shell. A planar end gets a plane surface, any other a
// filling surface: gmsh 4.8 cannot mesh the filling of the depressor anguli oris's flat 30 x 2 mm
// end ellipse ("Unable to recover the edge" at every element size from 0.5 to 1.2 mm), and meshes
// its plane cap.
void cap_open_curve(int curve, std::vector<int>& tags) {
  const int loop = gmsh::model::occ::addCurveLoop({std::abs(curve)});
  try {
    tags.push_back(gmsh::model::occ::addPlaneSurface({loop}));
  } catch (const std::string&) {  // not planar
    tags.push_back(gmsh::model::occ::addSurfaceFilling(loop));
  }
}

void make_volume_from_faces(const std::string& name) {
  gmsh::vectorpair faces;
  gmsh::model::occ::getEntities(faces, 2);
  if (faces.empty()) {
    throw std::runtime_error("cannot mesh '" + name + "': the file holds no surfaces");
  }
  gmsh::model::occ::synchronize();
  gmsh::vectorpair open_curves;
  gmsh::model::getBoundary(faces, open_curves, true, false, false);
  std::vector<int> tags;
  for (const auto& [dim, tag] : faces) {
    tags.push_back(tag);
  }
  for (const auto& [dim, curve] : open_curves) {
    cap_open_curve(curve, tags);
  }
  const int shell = gmsh::model::occ::addSurfaceLoop(tags, -1, true);
  gmsh::model::occ::addVolume({shell});
}

// gmsh::model::mesh::generate and setOrder with gmsh's errors turned into std::runtime_error.
// gmsh meshes surfaces inside an OpenMP parallel region (even on one thread), and an error there
// thrown as std::string cannot leave the region: the process ends in std::terminate (seen with
// the depressor anguli oris's filled end caps). With General.AbortOnError = 1 gmsh abandons the
// mesh instead of throwing; its error lines are read back from its logger (GmshSession keeps
// General.Verbosity at 1 so that the logger records them).
void generate_contained(const std::string& name, int order) {
  double abort_on_error = 2.0;
  gmsh::option::getNumber("General.AbortOnError", abort_on_error);
  gmsh::option::setNumber("General.AbortOnError", 1);
  gmsh::logger::start();
  gmsh::model::mesh::generate(3);
  if (order == 2) {
    gmsh::model::mesh::setOrder(2);
  }
  std::vector<std::string> log;
  gmsh::logger::get(log);
  gmsh::logger::stop();
  gmsh::option::setNumber("General.AbortOnError", abort_on_error);
  std::string errors;
  for (const std::string& line : log) {
    if (line.rfind("Error", 0) == 0 && errors.find(line) == std::string::npos) {
      errors += (errors.empty() ? "" : "; ") + line;
    }
  }
  if (!errors.empty()) {
    throw std::runtime_error("gmsh could not mesh '" + name + "': " + errors +
                             " (another element_size may mesh)");
  }
}

// MeshingOptions::local_size as gmsh's size callback while it lives: gmsh keeps the callback in
// its global context past gmsh::finalize, where it would outlive the options it refers to.
class LocalSizeCallback {
 public:
  explicit LocalSizeCallback(const MeshingOptions& options) : active_(bool(options.local_size)) {
    if (!active_)
      return;
    gmsh::model::mesh::setSizeCallback([&options](int, int, double x, double y, double z) {
      return std::min(options.element_size, options.local_size(Eigen::Vector3d(x, y, z)));
    });
  }
  ~LocalSizeCallback() {
    if (!active_)
      return;
    try {
      gmsh::model::mesh::removeSizeCallback();
    } catch (...) {  // nothing sensible to do in a destructor
    }
  }
  LocalSizeCallback(const LocalSizeCallback&) = delete;
  LocalSizeCallback& operator=(const LocalSizeCallback&) = delete;

 private:
  bool active_;
};

}  // namespace

void MeshingOptions::validate() const {
  if (!(element_size > 0.0) || !std::isfinite(element_size)) {
    throw std::invalid_argument("element_size " + std::to_string(element_size) +
                                " must be a finite length > 0 (m)");
  }
  if (order != 1 && order != 2) {
    throw std::invalid_argument("order " + std::to_string(order) +
                                " is not supported (valid: 1 = 4-node, 2 = 10-node)");
  }
  if (threads < 1) {
    throw std::invalid_argument("threads must be >= 1");
  }
  if (local_size && !(finest_size > 0.0 && finest_size <= element_size)) {
    throw std::invalid_argument("finest_size " + std::to_string(finest_size) +
                                " of the local size must lie in (0, element_size]");
  }
}

// Import, heal and sew the faces, make a volume, mesh it (TOOLING.md, gmsh 4.8).
TetMesh mesh_iges(const std::filesystem::path& file, const MeshingOptions& options,
                  int* straightened) {
  options.validate();
  const std::string name = file.string();
  if (!std::filesystem::is_regular_file(file)) {
    throw std::runtime_error("cannot mesh '" + name + "': no such file");
  }
  GmshSession session;
  try {
    gmsh::model::add("isomuscle");
    // gmsh sets the unit through OCCT's IGES/STEP static parameters, which exist only once an
    // IGES controller is initialised: as the process's first OCCT work (no IGES read before it)
    // the option failed with "Could not set OpenCASCADE target unit 'M'".
    IGESControl_Controller::Init();
    gmsh::option::setString("Geometry.OCCTargetUnit", "M");
    gmsh::vectorpair imported;
    gmsh::model::occ::importShapes(name, imported, true, "iges");
    gmsh::vectorpair solids;
    gmsh::model::occ::getEntities(solids, 3);
    if (solids.empty()) {
      gmsh::vectorpair healed;
      gmsh::model::occ::healShapes(healed, {}, 1e-8, true, true, true, true, true);
      gmsh::model::occ::getEntities(solids, 3);
    }
    if (solids.empty()) {
      make_volume_from_faces(name);
    }
    gmsh::model::occ::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", options.element_size);
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0.1 * (options.local_size ? options.finest_size
                                                                          : options.element_size));
    gmsh::option::setNumber("General.NumThreads", options.threads);
    const LocalSizeCallback local_size(options);
    generate_contained(name, options.order);
    TetMesh mesh = extract_mesh(name, 1.0);
    const int repaired =
        straighten_folded_elements(mesh, analysis_tet_rule(mesh.order, options.quadrature_degree));
    if (straightened)
      *straightened = repaired;
    return mesh;
  } catch (const std::string& what) {
    throw std::runtime_error("gmsh could not mesh '" + name + "': " + what);
  }
}

TetMesh read_msh(const std::filesystem::path& file, double metres_per_unit) {
  const std::string name = file.string();
  if (!(metres_per_unit > 0.0) || !std::isfinite(metres_per_unit)) {
    throw std::invalid_argument("read_msh: metres_per_unit must be > 0");
  }
  if (!std::filesystem::is_regular_file(file)) {
    throw std::runtime_error("cannot read mesh '" + name + "': no such file");
  }
  GmshSession session;
  try {
    gmsh::open(name);
    return extract_mesh(name, metres_per_unit);
  } catch (const std::string& what) {
    throw std::runtime_error("gmsh could not read '" + name + "': " + what);
  }
}

}  // namespace isomuscle::tet
