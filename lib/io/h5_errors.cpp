#include "io/h5_errors.hpp"

#include <string>

#include <hdf5.h>

namespace atssim::io {

namespace {

struct Innermost {
  std::string description;
  std::string system;  // "error message = '...'" of a file driver failure
};

herr_t keep_innermost(unsigned, const H5E_error2_t* e, void* data) {
  auto* out = static_cast<Innermost*>(data);
  if (e->desc == nullptr) return 0;
  const std::string desc = e->desc;
  if (out->description.empty()) out->description = desc;
  // The sec2 driver writes: "... errno = 28, error message = 'No space left on device', ..."
  if (const auto at = desc.find("error message = '"); at != std::string::npos && out->system.empty()) {
    const auto from = at + 17;
    const auto to = desc.find('\'', from);
    out->system = desc.substr(from, to == std::string::npos ? std::string::npos : to - from);
  }
  return 0;
}

}  // namespace

void quiet_hdf5() {
  static const bool done = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

void init_hdf5_for_command_line() {
  H5dont_atexit();
  quiet_hdf5();
}

std::string hdf5_failure() {
  Innermost found;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &found);
  H5Eclear2(H5E_DEFAULT);
  if (!found.system.empty()) return found.system;
  return found.description;
}

}  // namespace atssim::io
