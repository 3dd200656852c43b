#pragma once
// The one project exception type. lib/ throws it; app/ catches it once,
// prints the message and exits with the code it carries (DESIGN.md CLI).
#include <stdexcept>
#include <string>

namespace atssim {

enum class ErrorKind {
  input = 2,    // bad usage or bad input: the message names file, line and fix
  runtime = 1,  // the run failed: device error, blow-up, I/O failure
};

class Error : public std::runtime_error {
 public:
  explicit Error(std::string message, ErrorKind kind = ErrorKind::input)
      : std::runtime_error(std::move(message)), kind_(kind) {}
  ErrorKind kind() const { return kind_; }
  int exit_code() const { return static_cast<int>(kind_); }

 private:
  ErrorKind kind_;
};

// Shorthands that read well at the throw site.
inline Error input_error(std::string message) { return Error(std::move(message), ErrorKind::input); }
inline Error runtime_error(std::string message) { return Error(std::move(message), ErrorKind::runtime); }

}  // namespace atssim
