// An index of refraction as a dielectric holds it: a constant, or Sellmeier's dispersion formula
// n^2(lambda) = 1 + sum_j B_j lambda^2 / (lambda^2 - C_j), lambda in micrometres, C_j in um^2
// (e.g. Schott N-BK7: B = 1.03961212, 0.231792344, 1.01046945; C = 0.00600069867,
// 0.0200179144, 103.560653 um^2, giving n = 1.516798 at 587.6 nm; shared/SHADING.md section 7).
#pragma once

#include "refracta/core/error.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace refracta {

class Ior {
 public:
  // RGB rendering evaluates dispersive indices here (the middle of the visible range).
  static constexpr double kRgbWavelength = 550.0;  // [nm]

  explicit Ior(double value = 1.5) : constant_(value) {
    if (!std::isfinite(value) || value <= 0.0) throw_invalid("ior must be finite and > 0 (got ", value, ")");
  }
  static Ior sellmeier(const std::array<double, 3>& b, const std::array<double, 3>& c) {
    Ior ior;
    for (int j = 0; j < 3; ++j) {
      if (!std::isfinite(b[j]) || b[j] < 0.0) throw_invalid("sellmeier B", j + 1, " must be finite and >= 0 (got ", b[j], ")");
      if (!std::isfinite(c[j]) || c[j] < 0.0) throw_invalid("sellmeier C", j + 1, " must be finite and >= 0 [um^2] (got ", c[j], ")");
    }
    ior.dispersive_ = true;
    ior.b_ = b;
    ior.c_ = c;
    // The formula has poles at lambda^2 = C_j, n^2 < 0 just below each: refuse coefficients with
    // one inside the sampled range (sampling whole nanometres missed a pole at 600.5 nm).
    for (int j = 0; j < 3; ++j) {
      const double pole_nm = 1e3 * std::sqrt(c[j]);
      if (b[j] > 0.0 && pole_nm >= 360.0 && pole_nm <= 830.0) {
        throw_invalid("sellmeier term ", j + 1, " has its pole at ", pole_nm, " nm (sqrt(C", j + 1,
                      ")), inside 360-830 nm");
      }
    }
    for (double lambda = 360.0; lambda <= 830.0; lambda += 1.0) {
      const double n = ior.at(lambda);
      if (!std::isfinite(n) || n <= 0.0) throw_invalid("sellmeier coefficients give n(", lambda, " nm) = ", n, " (must be > 0 over 360-830 nm)");
    }
    ior.constant_ = ior.at(kRgbWavelength);
    return ior;
  }
  // Schott N-BK7 (Schott data sheet coefficients).
  static Ior bk7() { return sellmeier({1.03961212, 0.231792344, 1.01046945}, {0.00600069867, 0.0200179144, 103.560653}); }
  // A glass by name: 'bk7' (or 'BK7').
  static Ior named(const std::string& name) {
    if (name == "bk7" || name == "BK7") return bk7();
    throw_invalid("ior must be a number, 'bk7' or given by sellmeier= (got '", name, "')");
  }
  // Sellmeier's coefficients as one list (B1, B2, B3, C1, C2, C3), C in um^2.
  static Ior sellmeier(const std::vector<double>& c) {
    if (c.size() != 6) throw_invalid("sellmeier must be (B1, B2, B3, C1, C2, C3) with C in um^2 (got ", c.size(), " values)");
    return sellmeier({c[0], c[1], c[2]}, {c[3], c[4], c[5]});
  }

  // n at a wavelength [nm].
  double at(double lambda_nm) const {
    if (!dispersive_) return constant_;
    const double l2 = (lambda_nm * 1e-3) * (lambda_nm * 1e-3);  // [um^2]
    double n2 = 1.0;
    for (int j = 0; j < 3; ++j) n2 += b_[j] * l2 / (l2 - c_[j]);
    return n2 > 0.0 ? std::sqrt(n2) : std::nan("");
  }
  // n in RGB rendering (at kRgbWavelength for a dispersive index).
  double rgb_value() const { return constant_; }
  bool dispersive() const { return dispersive_; }
  // Sellmeier's B_j and C_j [um^2] (zero for a constant index).
  const std::array<double, 3>& sellmeier_b() const { return b_; }
  const std::array<double, 3>& sellmeier_c() const { return c_; }
  std::string describe() const {
    if (!dispersive_) return concat(constant_);
    return concat("sellmeier(B=(", b_[0], ", ", b_[1], ", ", b_[2], "), C=(", c_[0], ", ", c_[1], ", ", c_[2], "))");
  }

 private:
  double constant_ = 1.5;
  bool dispersive_ = false;
  std::array<double, 3> b_{}, c_{};
};

}  // namespace refracta
