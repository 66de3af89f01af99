// HDF5 + XDMF output: what is written reads back equal through the HDF5 C API, the .xdmf is
// well-formed XML whose temporal grids point at datasets that exist with the stated sizes, every
// step leaves valid files, and non-finite values are refused.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "io/hdf5_xdmf_writer.hpp"
#include "io_test_util.hpp"

namespace isomuscle::io {
namespace {

using testing_util::fresh_directory;
using testing_util::read_text;
using testing_util::write_text;

// ---- a minimal XML reader: enough to check well-formedness and walk the XDMF tree -----------

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<XmlElement> children;

  std::vector<const XmlElement*> all(const std::string& child_name) const {
    std::vector<const XmlElement*> out;
    for (const auto& c : children) {
      if (c.name == child_name)
        out.push_back(&c);
    }
    return out;
  }
  const XmlElement& one(const std::string& child_name) const {
    const auto found = all(child_name);
    if (found.size() != 1) {
      throw std::runtime_error("<" + name + "> has " + std::to_string(found.size()) + " <" +
                               child_name + ">");
    }
    return *found.front();
  }
};

class XmlParser {
 public:
  explicit XmlParser(std::string text) : s_(std::move(text)) {}

  // Throws std::runtime_error at the first violation of (this subset of) XML well-formedness.
  XmlElement document() {
    skip_space();
    if (s_.compare(i_, 5, "<?xml") == 0) {
      const std::size_t end = s_.find("?>", i_);
      if (end == std::string::npos)
        fail("unterminated XML declaration");
      i_ = end + 2;
    }
    skip_space();
    XmlElement root = element();
    skip_space();
    if (i_ != s_.size())
      fail("text after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("XML error at offset " + std::to_string(i_) + ": " + what);
  }
  void skip_space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_])))
      ++i_;
  }
  std::string name() {
    const std::size_t start = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_' ||
                              s_[i_] == ':' || s_[i_] == '-' || s_[i_] == '.')) {
      ++i_;
    }
    if (i_ == start)
      fail("expected a name");
    return s_.substr(start, i_ - start);
  }
  void expect(char c) {
    if (i_ >= s_.size() || s_[i_] != c)
      fail(std::string("expected '") + c + "'");
    ++i_;
  }
  std::string text_until(char stop) {
    const std::size_t end = s_.find(stop, i_);
    if (end == std::string::npos)
      fail("unterminated text");
    std::string raw = s_.substr(i_, end - i_);
    i_ = end;
    if (raw.find('<') != std::string::npos)
      fail("'<' inside text or attribute");
    for (std::size_t amp = raw.find('&'); amp != std::string::npos; amp = raw.find('&', amp + 1)) {
      const std::size_t semi = raw.find(';', amp);
      const std::string entity = semi == std::string::npos ? "" : raw.substr(amp, semi - amp + 1);
      if (entity != "&amp;" && entity != "&lt;" && entity != "&gt;" && entity != "&quot;") {
        fail("bad entity");
      }
    }
    return raw;
  }
  XmlElement element() {
    XmlElement e;
    expect('<');
    e.name = name();
    while (true) {
      skip_space();
      if (i_ < s_.size() && s_[i_] == '/') {
        ++i_;
        expect('>');
        return e;
      }
      if (i_ < s_.size() && s_[i_] == '>') {
        ++i_;
        break;
      }
      const std::string key = name();
      expect('=');
      expect('"');
      const std::string value = text_until('"');
      expect('"');
      if (!e.attributes.emplace(key, value).second)
        fail("repeated attribute " + key);
    }
    while (true) {
      e.text += text_until('<');
      if (s_.compare(i_, 2, "</") == 0) {
        i_ += 2;
        if (name() != e.name)
          fail("closing tag does not match <" + e.name + ">");
        skip_space();
        expect('>');
        return e;
      }
      e.children.push_back(element());
    }
  }

  std::string s_;
  std::size_t i_ = 0;
};

// ---- HDF5 reading ---------------------------------------------------------------------------

struct Dataset {
  std::vector<hsize_t> dims;
  std::vector<double> values;      // when read as double
  std::vector<std::int64_t> ints;  // when read as int64
};

Dataset read_dataset(const std::filesystem::path& file, const std::string& path, bool integer) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  Dataset out;
  const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << "no dataset " << path;
  if (d >= 0) {
    const hid_t space = H5Dget_space(d);
    out.dims.resize(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
    H5Sget_simple_extent_dims(space, out.dims.data(), nullptr);
    hsize_t count = 1;
    for (hsize_t n : out.dims)
      count *= n;
    if (integer) {
      out.ints.resize(count);
      EXPECT_GE(H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.ints.data()), 0);
    } else {
      out.values.resize(count);
      EXPECT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()), 0);
    }
    H5Sclose(space);
    H5Dclose(d);
  }
  H5Fclose(f);
  return out;
}

double read_time_attribute(const std::filesystem::path& file, const std::string& group) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t g = H5Gopen2(f, group.c_str(), H5P_DEFAULT);
  const hid_t a = H5Aopen(g, "time", H5P_DEFAULT);
  double t = std::numeric_limits<double>::quiet_NaN();
  EXPECT_GE(H5Aread(a, H5T_NATIVE_DOUBLE, &t), 0);
  H5Aclose(a);
  H5Gclose(g);
  H5Fclose(f);
  return t;
}

bool link_exists(const std::filesystem::path& file, const std::string& path) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const htri_t exists = H5Lexists(f, path.c_str(), H5P_DEFAULT);
  H5Fclose(f);
  return exists > 0;
}

// ---- fixtures -------------------------------------------------------------------------------

// Two unit hexahedra side by side along x (12 points, VTK node order).
OutputMesh two_hexahedra() {
  OutputMesh mesh;
  mesh.points.resize(12, 3);
  int p = 0;
  for (int z = 0; z < 2; ++z) {
    for (int y = 0; y < 2; ++y) {
      for (int x = 0; x < 3; ++x)
        mesh.points.row(p++) << 0.01 * x, 0.01 * y, 0.01 * z;
    }
  }
  auto id = [](int x, int y, int z) { return static_cast<std::int64_t>(x + 3 * y + 6 * z); };
  mesh.cells.resize(2, 8);
  for (int c = 0; c < 2; ++c) {
    mesh.cells.row(c) << id(c, 0, 0), id(c + 1, 0, 0), id(c + 1, 1, 0), id(c, 1, 0), id(c, 0, 1),
        id(c + 1, 0, 1), id(c + 1, 1, 1), id(c, 1, 1);
  }
  mesh.cell_type = CellType::hexahedron8;
  return mesh;
}

// Fields of step k: distinct, non-trivial values (including ones that need all 17 digits).
std::vector<OutputField> fields_at(int k, const OutputMesh& mesh) {
  OutputField u{"displacement", FieldCentre::point, FieldMatrix(mesh.points.rows(), 3)};
  OutputField J{"J", FieldCentre::point, FieldMatrix(mesh.points.rows(), 1)};
  for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) {
    u.values.row(i) << 1e-3 * k * i, -0.1 / 3.0 * k, std::sqrt(2.0) * i;
    J.values(i, 0) = 1.0 + 1e-9 * k * i;
  }
  OutputField stress{"cauchy_stress", FieldCentre::cell, FieldMatrix(mesh.cells.rows(), 9)};
  OutputField activation{"activation", FieldCentre::cell, FieldMatrix(mesh.cells.rows(), 1)};
  for (Eigen::Index c = 0; c < mesh.cells.rows(); ++c) {
    for (int m = 0; m < 9; ++m)
      stress.values(c, m) = 1e5 * k + 10.0 * m + c / 7.0;
    activation.values(c, 0) = 0.25 * k;
  }
  return {u, J, stress, activation};
}

// Checks the whole .xdmf against the .h5: structure, times, and every referenced dataset.
void check_xdmf(const std::filesystem::path& xdmf, const std::vector<double>& times,
                const char* topology) {
  const XmlElement root = XmlParser(read_text(xdmf)).document();
  ASSERT_EQ(root.name, "Xdmf");
  EXPECT_EQ(root.attributes.at("Version"), "3.0");
  const XmlElement& collection = root.one("Domain").one("Grid");
  EXPECT_EQ(collection.attributes.at("GridType"), "Collection");
  EXPECT_EQ(collection.attributes.at("CollectionType"), "Temporal");
  const auto grids = collection.all("Grid");
  ASSERT_EQ(grids.size(), times.size());
  const std::filesystem::path folder = xdmf.parent_path();
  for (std::size_t k = 0; k < grids.size(); ++k) {
    const XmlElement& grid = *grids[k];
    EXPECT_EQ(grid.attributes.at("GridType"), "Uniform");
    EXPECT_EQ(std::stod(grid.one("Time").attributes.at("Value")), times[k]);
    EXPECT_EQ(grid.one("Topology").attributes.at("TopologyType"), topology);
    std::vector<const XmlElement*> items{&grid.one("Topology").one("DataItem"),
                                         &grid.one("Geometry").one("DataItem")};
    for (const XmlElement* a : grid.all("Attribute"))
      items.push_back(&a->one("DataItem"));
    for (const XmlElement* item : items) {
      const std::string& ref = item->text;
      const std::size_t colon = ref.find(':');
      ASSERT_NE(colon, std::string::npos) << ref;
      const std::filesystem::path h5 = folder / ref.substr(0, colon);
      const std::string path = ref.substr(colon + 1);
      ASSERT_TRUE(link_exists(h5, path.substr(0, path.find('/', 1)))) << path;
      const bool integer = item->attributes.at("NumberType") == "Int";
      const Dataset d = read_dataset(h5, path, integer);
      std::ostringstream dims;
      for (std::size_t n = 0; n < d.dims.size(); ++n)
        dims << (n ? " " : "") << d.dims[n];
      EXPECT_EQ(item->attributes.at("Dimensions"), dims.str()) << path;
    }
  }
}

TEST(Hdf5XdmfWriter, StepsReadBackEqualAndTheIndexMatchesTheFile) {
  const auto dir = fresh_directory("out");
  const OutputMesh mesh = two_hexahedra();
  Hdf5XdmfWriter writer(dir / "fields.xdmf");
  EXPECT_EQ(writer.h5_path(), dir / "fields.h5");
  writer.set_mesh(mesh);
  const std::vector<double> times{0.0, 0.1, 0.30000000000000004};
  for (int k = 0; k < 3; ++k)
    writer.write_step(times[k], fields_at(k, mesh));
  EXPECT_EQ(writer.steps(), 3u);

  const Dataset points = read_dataset(dir / "fields.h5", "/mesh_000000/points", false);
  EXPECT_EQ(points.dims, (std::vector<hsize_t>{12, 3}));
  EXPECT_EQ(points.values, std::vector<double>(mesh.points.data(), mesh.points.data() + 36));
  const Dataset cells = read_dataset(dir / "fields.h5", "/mesh_000000/cells", true);
  EXPECT_EQ(cells.dims, (std::vector<hsize_t>{2, 8}));
  EXPECT_EQ(cells.ints, std::vector<std::int64_t>(mesh.cells.data(), mesh.cells.data() + 16));
  for (int k = 0; k < 3; ++k) {
    const std::string step = "/step_00000" + std::to_string(k);
    EXPECT_EQ(read_time_attribute(dir / "fields.h5", step), times[k]);
    for (const OutputField& f : fields_at(k, mesh)) {
      const std::string path =
          step + (f.centre == FieldCentre::point ? "/point/" : "/cell/") + f.name;
      const Dataset d = read_dataset(dir / "fields.h5", path, false);
      std::vector<hsize_t> dims{static_cast<hsize_t>(f.values.rows())};
      if (f.values.cols() > 1)
        dims.push_back(static_cast<hsize_t>(f.values.cols()));
      EXPECT_EQ(d.dims, dims) << path;
      EXPECT_EQ(d.values, std::vector<double>(f.values.data(), f.values.data() + f.values.size()))
          << path;
    }
  }
  check_xdmf(dir / "fields.xdmf", times, "Hexahedron");
  const XmlElement root = XmlParser(read_text(dir / "fields.xdmf")).document();
  const XmlElement& last = *root.one("Domain").one("Grid").all("Grid").back();
  std::map<std::string, std::string> kinds;
  for (const XmlElement* a : last.all("Attribute")) {
    kinds[a->attributes.at("Name")] =
        a->attributes.at("AttributeType") + "/" + a->attributes.at("Center");
  }
  EXPECT_EQ(kinds, (std::map<std::string, std::string>{{"J", "Scalar/Node"},
                                                       {"activation", "Scalar/Cell"},
                                                       {"cauchy_stress", "Tensor/Cell"},
                                                       {"displacement", "Vector/Node"}}));
}

TEST(Hdf5XdmfWriter, EveryStepLeavesValidFilesWhenTheRunStopsEarly) {
  const auto dir = fresh_directory("out");
  write_text(dir / "fields.xdmf", "stale index of an earlier run");
  const OutputMesh mesh = two_hexahedra();
  {
    Hdf5XdmfWriter writer(dir / "fields.xdmf");
    EXPECT_FALSE(std::filesystem::exists(dir / "fields.xdmf"));  // no steps, no index
    writer.set_mesh(mesh);
    writer.write_step(0.5, fields_at(1, mesh));
    check_xdmf(dir / "fields.xdmf", {0.5}, "Hexahedron");  // readable while the writer lives
    writer.write_step(1.0, fields_at(2, mesh));
    check_xdmf(dir / "fields.xdmf", {0.5, 1.0}, "Hexahedron");
    // The run "fails" here: the writer goes away without any closing call.
  }
  check_xdmf(dir / "fields.xdmf", {0.5, 1.0}, "Hexahedron");
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    EXPECT_TRUE(entry.path().filename() == "fields.h5" || entry.path().filename() == "fields.xdmf")
        << "left behind: " << entry.path();
  }
}

TEST(Hdf5XdmfWriter, NonFiniteValuesAreRefusedAndNothingIsWritten) {
  const auto dir = fresh_directory("out");
  const OutputMesh mesh = two_hexahedra();
  Hdf5XdmfWriter writer(dir / "fields.xdmf");
  writer.set_mesh(mesh);
  writer.write_step(0.1, fields_at(1, mesh));
  const std::string index_before = read_text(dir / "fields.xdmf");

  std::vector<OutputField> bad = fields_at(2, mesh);
  bad[2].values(1, 4) = std::numeric_limits<double>::quiet_NaN();
  try {
    writer.write_step(0.2, bad);
    ADD_FAILURE() << "NaN accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("field 'cauchy_stress' is nan at cell 1, component 4"),
              std::string::npos)
        << e.what();
  }
  bad = fields_at(2, mesh);
  bad[0].values(3, 0) = -std::numeric_limits<double>::infinity();
  EXPECT_THROW(writer.write_step(0.2, bad), std::invalid_argument);
  EXPECT_EQ(writer.steps(), 1u);
  EXPECT_EQ(read_text(dir / "fields.xdmf"), index_before);
  EXPECT_FALSE(link_exists(dir / "fields.h5", "/step_000001"));

  OutputMesh nan_mesh = mesh;
  nan_mesh.points(5, 1) = std::numeric_limits<double>::quiet_NaN();
  try {
    writer.set_mesh(nan_mesh);
    ADD_FAILURE() << "NaN point accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("point 5 has a non-finite coordinate"), std::string::npos)
        << e.what();
  }
  // The writer still works after refusing.
  writer.write_step(0.2, fields_at(2, mesh));
  check_xdmf(dir / "fields.xdmf", {0.1, 0.2}, "Hexahedron");
}

TEST(Hdf5XdmfWriter, BadInputIsRejectedWithTheReason) {
  const auto dir = fresh_directory("out");
  const OutputMesh mesh = two_hexahedra();
  EXPECT_THROW(Hdf5XdmfWriter(dir / "fields.vtu"), std::invalid_argument);
  EXPECT_THROW(Hdf5XdmfWriter(dir / "no" / "such" / "folder.xdmf"), std::runtime_error);
  Hdf5XdmfWriter writer(dir / "fields.xdmf");
  EXPECT_THROW(writer.write_step(0.0, {}), std::logic_error);  // no mesh yet

  OutputMesh out_of_range = mesh;
  out_of_range.cells(1, 7) = 12;
  try {
    writer.set_mesh(out_of_range);
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cell 1 refers to point 12, but the mesh has 12 points"),
              std::string::npos)
        << e.what();
  }
  OutputMesh wrong_nodes = mesh;
  wrong_nodes.cell_type = CellType::tetrahedron4;
  EXPECT_THROW(writer.set_mesh(wrong_nodes), std::invalid_argument);

  writer.set_mesh(mesh);
  writer.write_step(1.0, fields_at(1, mesh));
  EXPECT_THROW(writer.write_step(1.0, fields_at(1, mesh)), std::invalid_argument);  // not later
  auto rows = fields_at(2, mesh);
  rows[1].values.conservativeResize(11, 1);
  EXPECT_THROW(writer.write_step(2.0, rows), std::invalid_argument);
  auto columns = fields_at(2, mesh);
  columns[0].values.conservativeResize(12, 2);
  EXPECT_THROW(writer.write_step(2.0, columns), std::invalid_argument);
  auto named = fields_at(2, mesh);
  named[1].name = "J/x";
  EXPECT_THROW(writer.write_step(2.0, named), std::invalid_argument);
  auto twice = fields_at(2, mesh);
  twice.push_back(twice[0]);
  EXPECT_THROW(writer.write_step(2.0, twice), std::invalid_argument);
  EXPECT_EQ(writer.steps(), 1u);
}

TEST(Hdf5XdmfWriter, QuadraticTetrahedraAndANewMeshMidRun) {
  const auto dir = fresh_directory("out");
  Hdf5XdmfWriter writer(dir / "tets.xdmf");
  writer.set_mesh(two_hexahedra());
  writer.write_step(0.0, {});
  // One 10-node tetrahedron: corners then mid-edge nodes 01, 12, 02, 03, 13, 23.
  OutputMesh tet;
  tet.cell_type = CellType::tetrahedron10;
  tet.points.resize(10, 3);
  tet.points.topRows(4) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  const int edges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
  for (int e = 0; e < 6; ++e) {
    tet.points.row(4 + e) = 0.5 * (tet.points.row(edges[e][0]) + tet.points.row(edges[e][1]));
  }
  tet.cells.resize(1, 10);
  for (int i = 0; i < 10; ++i)
    tet.cells(0, i) = i;
  writer.set_mesh(tet);
  OutputField volume{"J", FieldCentre::cell, FieldMatrix::Constant(1, 1, 1.0)};
  writer.write_step(0.5, {volume});
  const XmlElement root = XmlParser(read_text(dir / "tets.xdmf")).document();
  const auto grids = root.one("Domain").one("Grid").all("Grid");
  ASSERT_EQ(grids.size(), 2u);
  EXPECT_EQ(grids[0]->one("Topology").attributes.at("TopologyType"), "Hexahedron");
  EXPECT_EQ(grids[1]->one("Topology").attributes.at("TopologyType"), "Tetrahedron_10");
  EXPECT_EQ(grids[1]->one("Topology").attributes.at("NodesPerElement"), "10");
  EXPECT_EQ(grids[1]->one("Geometry").one("DataItem").text, "tets.h5:/mesh_000001/points");
  const Dataset cells = read_dataset(dir / "tets.h5", "/mesh_000001/cells", true);
  EXPECT_EQ(cells.dims, (std::vector<hsize_t>{1, 10}));
}

TEST(XmlParser, RejectsMalformedDocuments) {
  EXPECT_NO_THROW(XmlParser("<a x=\"1\"><b/>t&amp;</a>").document());
  EXPECT_THROW(XmlParser("<a><b></a>").document(), std::runtime_error);
  EXPECT_THROW(XmlParser("<a x=1></a>").document(), std::runtime_error);
  EXPECT_THROW(XmlParser("<a>&</a>").document(), std::runtime_error);
  EXPECT_THROW(XmlParser("<a></a><b/>").document(), std::runtime_error);
}

}  // namespace
}  // namespace isomuscle::io
