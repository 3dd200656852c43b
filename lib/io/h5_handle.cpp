#include "io/h5_handle.hpp"

#include <fmt/format.h>

#include "io/h5_errors.hpp"
#include "util/error.hpp"

namespace atssim::io {

H5Handle::H5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
H5Handle::H5Handle(H5Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = H5I_INVALID_HID; }
H5Handle& H5Handle::operator=(H5Handle&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = other.id_;
    close_ = other.close_;
    other.id_ = H5I_INVALID_HID;
  }
  return *this;
}
H5Handle::~H5Handle() { reset(); }
hid_t H5Handle::release() {
  const hid_t id = id_;
  id_ = H5I_INVALID_HID;
  return id;
}
void H5Handle::reset() {
  if (id_ >= 0 && close_ != nullptr) close_(id_);
  id_ = H5I_INVALID_HID;
}

namespace {

[[noreturn]] void throw_failure(const std::string& what) {
  const std::string cause = hdf5_failure();
  throw runtime_error(cause.empty() ? fmt::format("HDF5: {} failed", what)
                                    : fmt::format("HDF5: {} failed: {}", what, cause));
}

}  // namespace

H5Handle h5_check(hid_t id, herr_t (*close)(hid_t), const std::string& what) {
  if (id < 0) throw_failure(what);
  return H5Handle(id, close);
}

void h5_check(herr_t rc, const std::string& what) {
  if (rc < 0) throw_failure(what);
}

H5Handle create_group(hid_t parent, const std::string& name) {
  return h5_check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                  "creating group " + name);
}

namespace {

H5Handle string_type(std::size_t size) {
  H5Handle type = h5_check(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  h5_check(H5Tset_size(type, std::max<std::size_t>(size, 1)), "string size");
  h5_check(H5Tset_cset(type, H5T_CSET_UTF8), "string charset");
  return type;
}

H5Handle simple_space(std::size_t rows, std::size_t cols) {
  hsize_t dims[2] = {rows, cols};
  return h5_check(H5Screate_simple(cols == 0 ? 1 : 2, dims, nullptr), H5Sclose, "dataspace");
}

template <typename T>
void write_array(hid_t parent, const std::string& name, std::span<const T> values, std::size_t cols, hid_t mem_type,
                 hid_t file_type) {
  const std::size_t rows = cols == 0 ? values.size() : values.size() / cols;
  H5Handle space = simple_space(rows, cols);
  H5Handle set = h5_check(H5Dcreate2(parent, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                          H5Dclose, "creating " + name);
  if (!values.empty())
    h5_check(H5Dwrite(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "writing " + name);
}

}  // namespace

void write_string_attribute(hid_t object, const std::string& name, const std::string& value) {
  H5Handle type = string_type(value.size());
  H5Handle space = h5_check(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  H5Handle attr = h5_check(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                           "creating attribute " + name);
  h5_check(H5Awrite(attr, type, value.c_str()), "writing attribute " + name);
}

void write_int_attribute(hid_t object, const std::string& name, long long value) {
  H5Handle space = h5_check(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  H5Handle attr = h5_check(H5Acreate2(object, name.c_str(), H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                           "creating attribute " + name);
  h5_check(H5Awrite(attr, H5T_NATIVE_LLONG, &value), "writing attribute " + name);
}

long long read_int_attribute(hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return 0;
  H5Handle attr = h5_check(H5Aopen(object, name, H5P_DEFAULT), H5Aclose, name);
  long long v = 0;
  h5_check(H5Aread(attr, H5T_NATIVE_LLONG, &v), name);
  return v;
}

void write_string_dataset(hid_t parent, const std::string& name, const std::string& value) {
  H5Handle type = string_type(value.size());
  H5Handle space = h5_check(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  H5Handle set = h5_check(H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                          H5Dclose, "creating " + name);
  h5_check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, value.c_str()), "writing " + name);
}

void write_string_array(hid_t parent, const std::string& name, const std::vector<std::string>& values) {
  std::size_t width = 1;
  for (const auto& v : values) width = std::max(width, v.size());
  std::vector<char> packed(width * values.size(), '\0');
  for (std::size_t i = 0; i < values.size(); ++i) values[i].copy(packed.data() + i * width, width);
  H5Handle type = string_type(width);
  h5_check(H5Tset_strpad(type, H5T_STR_NULLPAD), "string padding");
  H5Handle space = simple_space(values.size(), 0);
  H5Handle set = h5_check(H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                          H5Dclose, "creating " + name);
  if (!values.empty()) h5_check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, packed.data()), "writing " + name);
}

void write_float_array(hid_t parent, const std::string& name, std::span<const float> values, std::size_t cols) {
  write_array(parent, name, values, cols, H5T_NATIVE_FLOAT, H5T_IEEE_F32LE);
}
void write_double_array(hid_t parent, const std::string& name, std::span<const double> values, std::size_t cols) {
  write_array(parent, name, values, cols, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE);
}
void write_int_array(hid_t parent, const std::string& name, std::span<const int> values, std::size_t cols) {
  write_array(parent, name, values, cols, H5T_NATIVE_INT, H5T_STD_I32LE);
}

}  // namespace atssim::io
