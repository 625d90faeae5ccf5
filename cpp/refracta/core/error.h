// Errors refracta throws. Library code never aborts or exits: it throws one of these, and the
// bindings turn them into Python exceptions (ValueError, refracta.NumericalError, refracta.IoError).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace refracta {

// A computation met a value it cannot continue from: n <= 0, NaN, divergence.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A file could not be read or written.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <class... Parts>
std::string concat(const Parts&... parts) {
  std::ostringstream out;
  out.precision(10);
  (out << ... << parts);
  return out.str();
}

// Throws std::invalid_argument (Python ValueError) with the parts concatenated.
template <class... Parts>
[[noreturn]] void throw_invalid(const Parts&... parts) {
  throw std::invalid_argument(concat(parts...));
}

template <class... Parts>
[[noreturn]] void throw_numerical(const Parts&... parts) {
  throw NumericalError(concat(parts...));
}

}  // namespace refracta
