// Quasi-random points in the unit cube: the additive recurrence of Roberts (2018, "The
// Unreasonable Effectiveness of Quasirandom Sequences"), x_n = frac(1/2 + n alpha) with
// alpha_j = phi_d^-(j+1) and phi_d the positive root of x^(d+1) = x + 1 (the golden ratio in 1-D).
// Low discrepancy in any dimension, no table, no correlated axes as Halton's in high dimensions.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace refracta {

class QuasiRandom {
 public:
  explicit QuasiRandom(int dimensions) : alpha_(dimensions) {
    double phi = 2.0;  // Newton on x^(d+1) - x - 1 from 2 converges to phi_d in a few steps
    for (int it = 0; it < 50; ++it) {
      const double f = std::pow(phi, dimensions + 1) - phi - 1.0;
      const double df = (dimensions + 1) * std::pow(phi, dimensions) - 1.0;
      phi -= f / df;
    }
    double power = 1.0;
    for (double& a : alpha_) {
      power /= phi;
      a = power;
    }
  }

  // Point n (n = 0, 1, ...) in [0, 1)^d.
  std::vector<double> point(int64_t n) const {
    std::vector<double> x(alpha_.size());
    for (size_t j = 0; j < x.size(); ++j) {
      const double v = 0.5 + double(n) * alpha_[j];
      x[j] = v - std::floor(v);
    }
    return x;
  }

 private:
  std::vector<double> alpha_;
};

}  // namespace refracta
