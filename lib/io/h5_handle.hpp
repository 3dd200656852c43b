#pragma once
// RAII ownership of HDF5 C API identifiers, and small typed writers.
#include <span>
#include <string>
#include <vector>

#include <hdf5.h>

namespace atssim::io {

class H5Handle {
 public:
  H5Handle() = default;
  H5Handle(hid_t id, herr_t (*close)(hid_t));
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  H5Handle(H5Handle&& other) noexcept;
  H5Handle& operator=(H5Handle&& other) noexcept;
  ~H5Handle();
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }
  void reset();
  // Gives up ownership without closing (a file whose writes failed is left
  // as its last flush made it: closing would write more).
  hid_t release();

 private:
  hid_t id_ = H5I_INVALID_HID;
  herr_t (*close_)(hid_t) = nullptr;
};

// Each throws atssim::Error (runtime) naming `what` and HDF5's innermost
// cause when HDF5 fails (io/h5_errors.hpp).
H5Handle h5_check(hid_t id, herr_t (*close)(hid_t), const std::string& what);
void h5_check(herr_t rc, const std::string& what);

H5Handle create_group(hid_t parent, const std::string& name);
void write_string_attribute(hid_t object, const std::string& name, const std::string& value);
void write_int_attribute(hid_t object, const std::string& name, long long value);
// An integer attribute, 0 when the object has none.
long long read_int_attribute(hid_t object, const char* name);
void write_string_dataset(hid_t parent, const std::string& name, const std::string& value);
void write_string_array(hid_t parent, const std::string& name, const std::vector<std::string>& values);
// Row-major [rows, cols] arrays (cols = 0: one dimension).
void write_float_array(hid_t parent, const std::string& name, std::span<const float> values, std::size_t cols);
void write_double_array(hid_t parent, const std::string& name, std::span<const double> values, std::size_t cols);
void write_int_array(hid_t parent, const std::string& name, std::span<const int> values, std::size_t cols);

}  // namespace atssim::io
