#pragma once
// The HDF5 C API with errors as exceptions, shared by the files io/ writes and reads (fields.h5,
// solution.h5): scoped identifiers, silenced automatic error printing, datasets and attributes of
// float64 / int64 in row-major order, and their reading back with the shape checked.
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace isomuscle::io::hdf5 {

// Silences HDF5's automatic error printing while alive; failures are reported by exceptions.
class Quiet {
 public:
  Quiet();
  ~Quiet();
  Quiet(const Quiet&) = delete;
  Quiet& operator=(const Quiet&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

// The innermost message of HDF5's error stack ("unable to open file"), for exceptions.
std::string reason();

// An HDF5 identifier closed by its close function when it goes out of scope. Throws
// std::runtime_error("<what> failed: <reason>") when id < 0.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what);
  ~Handle();
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  // Closes now and reports a failure (closing the file flushes it).
  void close(const std::string& what);

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// Throws std::runtime_error("<what> failed: <reason>") when status < 0.
void check(herr_t status, const std::string& what);

Handle create_file(const std::string& path);            // truncates
Handle open_file(const std::string& path, bool write);  // read-only unless write
Handle create_group(hid_t parent, const std::string& name, const std::string& file);
Handle open_group(hid_t parent, const std::string& name, const std::string& file);
bool has_link(hid_t parent, const std::string& name);

// A rows x columns dataset (1-D when columns == 1 and one_dimensional) written from row-major
// data of the given memory type.
void write_dataset(hid_t group, const std::string& name, hsize_t rows, hsize_t columns,
                   bool one_dimensional, hid_t file_type, hid_t memory_type, const void* data,
                   const std::string& where);
void write_doubles(hid_t group, const std::string& name, const std::vector<double>& values,
                   hsize_t columns, const std::string& where);
void write_scalar_attribute(hid_t object, const char* name, hid_t file_type, hid_t memory_type,
                            const void* value, const std::string& where);
void write_string_attribute(hid_t object, const char* name, const std::string& value,
                            const std::string& where);

// A dataset read back: its dimensions (1 or 2) and values in row-major order.
template <class T>
struct Array {
  std::vector<hsize_t> dims;
  std::vector<T> values;
  hsize_t rows() const { return dims.empty() ? 0 : dims[0]; }
  hsize_t columns() const { return dims.size() < 2 ? 1 : dims[1]; }
};
// Throw std::runtime_error naming `where` when the dataset is missing or not 1-/2-D.
Array<double> read_doubles(hid_t group, const std::string& name, const std::string& where);
Array<std::int64_t> read_ints(hid_t group, const std::string& name, const std::string& where);
double read_double_attribute(hid_t object, const char* name, const std::string& where);
std::int64_t read_int_attribute(hid_t object, const char* name, const std::string& where);
std::string read_string_attribute(hid_t object, const char* name, const std::string& where);

// "step_000012".
std::string numbered(const char* prefix, std::size_t index);

}  // namespace isomuscle::io::hdf5
