#pragma once
// The one project exception type. lib/ throws it; app/ catches it once,
// prints the message and exits with the code of its kind (DESIGN.md CLI).
// Every throw names its kind: there is no default, so a bug cannot leave as
// "bad input" (tests/build/error_without_kind.cpp shows it does not compile).
#include <stdexcept>
#include <string>

namespace atssim {

enum class ErrorKind {
  input,     // bad usage or bad input: exit 2; the message names file, line and fix
  runtime,   // a sound input whose run failed: device error, blow-up, I/O failure: exit 1
  internal,  // a bug in atssim (one stage broke a promise to another): exit 1, "internal error"
};

// The scene setting an input error is about, when the stage that throws it
// never saw the scene file (DeviceSet::open, a plan builder) and so cannot
// name the line: a caller that can re-throws it there (app/scene_checks)
// from detail(), without reading the message.
enum class Setting {
  none,
  devices,     // the device spec; detail() continues "devices …" (e.g. "'tpu': selects nothing; …")
  compliance,  // a constraint of compliance 0 (infinitely stiff); detail() is the whole message
};

class Error : public std::runtime_error {
 public:
  Error(std::string message, ErrorKind kind) : std::runtime_error(std::move(message)), kind_(kind) {}
  // An input error about `setting`: `message` is what the user reads where no
  // line is known, `detail` what follows the line where one is.
  Error(std::string message, Setting setting, std::string detail)
      : std::runtime_error(std::move(message)),
        kind_(ErrorKind::input),
        setting_(setting),
        detail_(std::move(detail)) {}

  ErrorKind kind() const { return kind_; }
  Setting setting() const { return setting_; }
  const std::string& detail() const { return detail_; }
  int exit_code() const { return kind_ == ErrorKind::input ? 2 : 1; }

 private:
  ErrorKind kind_;
  Setting setting_ = Setting::none;
  std::string detail_;
};

// Shorthands that read well at the throw site.
inline Error input_error(std::string message) { return Error(std::move(message), ErrorKind::input); }
inline Error runtime_error(std::string message) { return Error(std::move(message), ErrorKind::runtime); }
inline Error internal_error(std::string message) { return Error(std::move(message), ErrorKind::internal); }

// The kind of any exception: an atssim::Error's own, else internal (a
// library's or the standard library's exception escaping atssim is a bug).
inline ErrorKind error_kind(const std::exception& e) {
  const auto* error = dynamic_cast<const Error*>(&e);
  return error != nullptr ? error->kind() : ErrorKind::internal;
}

}  // namespace atssim
