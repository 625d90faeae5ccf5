// Errors refracta throws. Library code never aborts or exits: it throws one of these, and the
// bindings turn them into Python exceptions (ValueError, refracta.NumericalError, refracta.IoError).
#pragma once

#include <charconv>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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

// A file that is not there (Python: refracta.MissingFileError, an IoError and a FileNotFoundError).
class MissingFile : public IoError {
 public:
  using IoError::IoError;
};

// A number written so that reading it back gives the same double (shortest round-trip digits:
// 0.1 as 0.1, 0.1 + 0.2 as 0.30000000000000004), for reprs that promise eval(repr(x)) == x;
// concat's 10 digits changed the value (a trial). concat(..., exact(x), ...).
struct Exact {
  double value;
};
inline Exact exact(double value) { return {value}; }
inline std::ostream& operator<<(std::ostream& out, Exact number) {
  char digits[32];
  const auto end = std::to_chars(digits, digits + sizeof(digits), number.value).ptr;
  return out << std::string_view(digits, size_t(end - digits));
}

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

// Collects every problem of a set of options, so one ValueError lists them all:
//   Problems problems("RenderOptions");
//   problems.check(spp >= 1, "spp must be >= 1 (got ", spp, ")");
//   problems.throw_if_any();   // "RenderOptions: spp must be >= 1 (got 0); tol must be > 0 (got nan)"
class Problems {
 public:
  explicit Problems(std::string owner) : owner_(std::move(owner)) {}

  template <class... Parts>
  void add(const Parts&... parts) {
    list_.push_back(concat(parts...));
  }

  // Records the message when the condition does not hold; NaN comparisons are false, so write
  // conditions as what must hold (`x > 0`), and NaN is reported.
  template <class... Parts>
  void check(bool holds, const Parts&... parts) {
    if (!holds) add(parts...);
  }

  // The problems of a nested options object, named as its fields: nested.check(problems)'s
  // "resolution must be ..." becomes "shadow_map.resolution must be ...".
  template <class Nested>
  void check_nested(const char* name, const Nested& nested) {
    const std::size_t first = list_.size();
    nested.check(*this);
    for (std::size_t i = first; i < list_.size(); ++i) list_[i] = std::string(name) + "." + list_[i];
  }

  bool empty() const { return list_.empty(); }
  const std::vector<std::string>& list() const { return list_; }

  void throw_if_any() const {
    if (list_.empty()) return;
    std::string message = owner_ + ": ";
    for (std::size_t i = 0; i < list_.size(); ++i) message += (i ? "; " : "") + list_[i];
    throw std::invalid_argument(message);
  }

 private:
  std::string owner_;
  std::vector<std::string> list_;
};

}  // namespace refracta
