#include "io/hdf5_support.hpp"

#include <cstdio>
#include <stdexcept>

namespace isomuscle::io::hdf5 {

Quiet::Quiet() {
  H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

Quiet::~Quiet() {
  H5Eset_auto2(H5E_DEFAULT, function_, data_);
}

std::string reason() {
  std::string text;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
        auto* out = static_cast<std::string*>(data);
        if (out->empty() && error->desc != nullptr)
          *out = error->desc;
        return 0;
      },
      &text);
  H5Eclear2(H5E_DEFAULT);
  return text.empty() ? "no reason given by HDF5" : text;
}

Handle::Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
  if (id_ < 0)
    throw std::runtime_error(what + " failed: " + reason());
}

Handle::~Handle() {
  if (id_ >= 0)
    close_(id_);
}

void Handle::close(const std::string& what) {
  const herr_t status = close_(id_);
  id_ = -1;
  if (status < 0)
    throw std::runtime_error(what + " failed: " + reason());
}

void check(herr_t status, const std::string& what) {
  if (status < 0)
    throw std::runtime_error(what + " failed: " + reason());
}

Handle create_file(const std::string& path) {
  return Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                "creating HDF5 file " + path);
}

Handle open_file(const std::string& path, bool write) {
  return Handle(H5Fopen(path.c_str(), write ? H5F_ACC_RDWR : H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
                "opening HDF5 file " + path);
}

Handle create_group(hid_t parent, const std::string& name, const std::string& file) {
  return Handle(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                "creating group " + name + " in " + file);
}

Handle open_group(hid_t parent, const std::string& name, const std::string& file) {
  return Handle(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), H5Gclose,
                "opening group " + name + " in " + file);
}

bool has_link(hid_t parent, const std::string& name) {
  return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0;
}

void write_dataset(hid_t group, const std::string& name, hsize_t rows, hsize_t columns,
                   bool one_dimensional, hid_t file_type, hid_t memory_type, const void* data,
                   const std::string& where) {
  const hsize_t dims[2] = {rows, columns};
  Handle space(H5Screate_simple(one_dimensional ? 1 : 2, dims, nullptr), H5Sclose,
               "creating the dataspace of " + where);
  Handle set(H5Dcreate2(group, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                        H5P_DEFAULT),
             H5Dclose, "creating dataset " + where);
  check(H5Dwrite(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
        "writing dataset " + where);
}

void write_doubles(hid_t group, const std::string& name, const std::vector<double>& values,
                   hsize_t columns, const std::string& where) {
  if (columns == 0 || values.size() % columns != 0)
    throw std::invalid_argument(where + ": " + std::to_string(values.size()) +
                                " values do not fill rows of " + std::to_string(columns));
  write_dataset(group, name, values.size() / columns, columns, columns == 1, H5T_IEEE_F64LE,
                H5T_NATIVE_DOUBLE, values.data(), where);
}

void write_scalar_attribute(hid_t object, const char* name, hid_t file_type, hid_t memory_type,
                            const void* value, const std::string& where) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "creating a scalar dataspace for " + where);
  Handle attribute(H5Acreate2(object, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose, "creating attribute '" + std::string(name) + "' of " + where);
  check(H5Awrite(attribute.get(), memory_type, value),
        "writing attribute '" + std::string(name) + "' of " + where);
}

void write_string_attribute(hid_t object, const char* name, const std::string& value,
                            const std::string& where) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "making a string type for " + where);
  check(H5Tset_size(type.get(), value.empty() ? 1 : value.size()), "sizing a string for " + where);
  check(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), "padding a string for " + where);
  write_scalar_attribute(object, name, type.get(), type.get(), value.empty() ? "" : value.data(),
                         where);
}

namespace {

template <class T>
Array<T> read_array(hid_t group, const std::string& name, hid_t memory_type,
                    const std::string& where) {
  if (!has_link(group, name))
    throw std::runtime_error(where + ": dataset '" + name + "' is missing");
  Handle set(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose,
             "opening dataset " + name + " of " + where);
  Handle space(H5Dget_space(set.get()), H5Sclose, "reading the shape of " + name + " of " + where);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank != 1 && rank != 2)
    throw std::runtime_error(where + ": dataset '" + name + "' has rank " + std::to_string(rank) +
                             ", expected 1 or 2");
  Array<T> out;
  out.dims.resize(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), out.dims.data(), nullptr);
  std::size_t count = 1;
  for (hsize_t d : out.dims)
    count *= static_cast<std::size_t>(d);
  out.values.resize(count);
  if (count > 0) {
    check(H5Dread(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()),
          "reading dataset " + name + " of " + where);
  }
  return out;
}

template <class T>
T read_attribute(hid_t object, const char* name, hid_t memory_type, const std::string& where) {
  if (H5Aexists(object, name) <= 0)
    throw std::runtime_error(where + ": attribute '" + std::string(name) + "' is missing");
  Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose,
                   "opening attribute '" + std::string(name) + "' of " + where);
  T value{};
  check(H5Aread(attribute.get(), memory_type, &value),
        "reading attribute '" + std::string(name) + "' of " + where);
  return value;
}

}  // namespace

Array<double> read_doubles(hid_t group, const std::string& name, const std::string& where) {
  return read_array<double>(group, name, H5T_NATIVE_DOUBLE, where);
}

Array<std::int64_t> read_ints(hid_t group, const std::string& name, const std::string& where) {
  return read_array<std::int64_t>(group, name, H5T_NATIVE_INT64, where);
}

double read_double_attribute(hid_t object, const char* name, const std::string& where) {
  return read_attribute<double>(object, name, H5T_NATIVE_DOUBLE, where);
}

std::int64_t read_int_attribute(hid_t object, const char* name, const std::string& where) {
  return read_attribute<std::int64_t>(object, name, H5T_NATIVE_INT64, where);
}

std::string read_string_attribute(hid_t object, const char* name, const std::string& where) {
  if (H5Aexists(object, name) <= 0)
    throw std::runtime_error(where + ": attribute '" + std::string(name) + "' is missing");
  Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose,
                   "opening attribute '" + std::string(name) + "' of " + where);
  Handle type(H5Aget_type(attribute.get()), H5Tclose, "reading the type of " + where);
  if (H5Tget_class(type.get()) != H5T_STRING)
    throw std::runtime_error(where + ": attribute '" + std::string(name) + "' is not a string");
  const std::size_t size = H5Tget_size(type.get());
  std::string value(size, '\0');
  check(H5Aread(attribute.get(), type.get(), value.data()),
        "reading attribute '" + std::string(name) + "' of " + where);
  value.resize(value.find('\0') == std::string::npos ? size : value.find('\0'));
  return value;
}

std::string numbered(const char* prefix, std::size_t index) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%s_%06zu", prefix, index);
  return buffer;
}

}  // namespace isomuscle::io::hdf5
