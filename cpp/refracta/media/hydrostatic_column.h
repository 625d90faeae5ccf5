// Hydrostatic pressure of an air column with an arbitrary temperature profile:
//   ln P(h) = ln P(h_ref) - (g0/R_d) J(h),   J(h) = integral from h_ref to h of (g(z)/g0) dz / T(z),
// with gravity falling as g(z)/g0 = (r0 / (r0 + z))^2 (air.h).
// J is tabulated once at construction on a node set the profile chooses (fine where T varies
// fast), each interval by 4-point Gauss-Legendre, and read back by cubic Hermite interpolation
// with the exact J' = 1/T at the nodes; the interpolation error is below 1e-12 relative for the
// profiles refracta builds. Templated on the scalar so derivatives reach the parameters.
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/math.h"
#include "refracta/core/parallel.h"
#include "refracta/media/air.h"
#include "refracta/media/index_field.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace refracta {

// The hottest air a column holds [K]. Above ~1e5 K Edlen's density factor turns negative (n < 1);
// 1e4 K is far beyond any real air (a test's ducting lapse rate of -0.13 K/m reaches 1700 K at
// 11 km) and well inside it.
constexpr double kHottestAir = 1e4;
// The coldest [K]: the summer mesopause, the coldest air there is, reaches ~110 K. Below it a
// temperature is a mistake, most often Celsius given for kelvin (a trial's 15 "K" sounding gave
// n - 1 19 times the real one).
constexpr double kColdestAir = 100.0;

// A ground pressure [Pa] must be > 0 and not in [300, 1100]: every surface pressure on Earth in
// hectopascals (Everest's 337 to the record 1084), the air's 30-45 km up in pascals, which no
// ground has. The slip gave n - 1 a hundredth of the real one, and no mirage, without a word.
inline void check_ground_pressure(double pressure, const char* owner) {
  if (!(pressure > 0.0)) throw_invalid(owner, ": pressure must be > 0 Pa (got ", pressure, ")");
  constexpr double kLowestHectopascals = 300.0, kHighestHectopascals = 1100.0;
  if (pressure >= kLowestHectopascals && pressure <= kHighestHectopascals) {
    throw_invalid(owner, ": pressure must be in pascals (got ", pressure, " Pa, the air's some 30 km up; ", pressure,
                  " hPa is ", 100.0 * pressure, " Pa)");
  }
}

// Sorted, de-duplicated nodes: [lo, hi] every `step`, plus finer runs (from, to, step), plus
// `extra` nodes (kinks of the profile, where the interpolant must not straddle a jump of T').
struct NodeRun {
  double from, to, step;
};
inline std::vector<double> make_nodes(double lo, double hi, const std::vector<NodeRun>& runs,
                                      const std::vector<double>& extra = {}) {
  std::vector<double> nodes;
  for (double h : extra) {
    if (h > lo && h < hi) nodes.push_back(h);
  }
  for (const auto& run : runs) {
    const double from = std::max(lo, run.from), to = std::min(hi, run.to);
    if (!(to > from) || !(run.step > 0.0)) continue;
    const int count = static_cast<int>(std::ceil((to - from) / run.step));
    for (int i = 0; i <= count; ++i) nodes.push_back(from + (to - from) * i / count);
  }
  nodes.push_back(lo);
  nodes.push_back(hi);
  std::sort(nodes.begin(), nodes.end());
  std::vector<double> unique;
  for (double h : nodes) {
    if (unique.empty() || h - unique.back() > 1e-9 * (1.0 + std::abs(h))) unique.push_back(h);
  }
  return unique;
}

template <class T>
class HydrostaticColumn {
 public:
  HydrostaticColumn() = default;

  // temperature(h, &T, &dT_dh) gives the profile; h_ref is where `pressure_ref` [Pa] holds.
  template <class Profile>
  HydrostaticColumn(const Profile& temperature, std::vector<double> nodes, double h_ref,
                    const T& pressure_ref, const char* owner)
      : nodes_(std::move(nodes)), owner_(owner) {
    using std::log;
    j_.resize(nodes_.size());
    inv_t_.resize(nodes_.size());
    // A sounding of many levels gives millions of nodes (seconds of work): Ctrl-C is polled.
    constexpr size_t kPollEvery = 4096;  // nodes (~0.1 ms of work) between polls
    for (size_t i = 0; i < nodes_.size(); ++i) {
      if (i % kPollEvery == 0) poll_cancel();
      inv_t_[i] = integrand(temperature, nodes_[i]);
    }
    // J from the lowest node, then shifted so that J(h_ref) = 0.
    j_[0] = T(0.0);
    static const double kX[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                 0.8611363115940526};
    static const double kW[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                 0.3478548451374538};
    for (size_t i = 1; i < nodes_.size(); ++i) {
      if (i % kPollEvery == 0) poll_cancel();
      const double a = nodes_[i - 1], b = nodes_[i], half = 0.5 * (b - a), mid = 0.5 * (a + b);
      T sum(0.0);
      for (int q = 0; q < 4; ++q) sum += kW[q] * integrand(temperature, mid + half * kX[q]);
      j_[i] = j_[i - 1] + half * sum;
    }
    const T j_ref = integral(T(h_ref));
    for (auto& j : j_) j -= j_ref;
    log_p_ref_ = log(pressure_ref);
  }

  double lowest() const { return nodes_.front(); }
  double highest() const { return nodes_.back(); }

  // ln P [ln Pa] at h; NumericalError outside the tabulated range.
  T log_pressure(const T& h) const {
    return log_p_ref_ - T(kGravity / kGasConstantDryAir) * integral(h);
  }

 private:
  // J'(h) = (g(h)/g0) / T(h).
  template <class Profile>
  T integrand(const Profile& temperature, double h) const {
    return T(gravity_ratio(h)) / checked(temperature, h);
  }

  template <class Profile>
  T checked(const Profile& temperature, double h) const {
    T t, slope;
    temperature(T(h), &t, &slope);
    if (!(value_of(t) > 0.0 && value_of(t) <= kHottestAir)) {
      throw_invalid(owner_, ": temperature is ", value_of(t), " K at h = ", h, " m; it must stay in (0, ", kHottestAir,
                    "] K over [", nodes_.front(), ", ", nodes_.back(), "] m");
    }
    return t;
  }

  T integral(const T& h) const {
    const double hv = value_of(h);
    if (!std::isfinite(hv)) throw_numerical(owner_, ": asked for the air at a non-finite height (", hv, " m)");
    if (!(hv >= nodes_.front() && hv <= nodes_.back())) {
      throw_numerical(owner_, ": height ", hv, " m is ", hv < nodes_.front() ? "below" : "above",
                      " the modelled range [", nodes_.front(), ", ", nodes_.back(), "] m",
                      hv < nodes_.front() ? " (a ray went below it: add a ground, or stop_height, above it)" : "");
    }
    size_t i = std::upper_bound(nodes_.begin(), nodes_.end(), hv) - nodes_.begin();
    i = std::clamp<size_t>(i, 1, nodes_.size() - 1);
    const double a = nodes_[i - 1], width = nodes_[i] - a;
    const T u = (h - a) / width;
    const T u2 = u * u, u3 = u2 * u;
    // Cubic Hermite basis on [0, 1].
    const T h00 = T(2.0) * u3 - T(3.0) * u2 + T(1.0), h10 = u3 - T(2.0) * u2 + u;
    const T h01 = T(-2.0) * u3 + T(3.0) * u2, h11 = u3 - u2;
    return h00 * j_[i - 1] + h10 * width * inv_t_[i - 1] + h01 * j_[i] + h11 * width * inv_t_[i];
  }

  std::vector<double> nodes_;
  std::vector<T> j_, inv_t_;  // J and J' at the nodes
  T log_p_ref_;
  const char* owner_ = "";
};

}  // namespace refracta

namespace refracta {

// Shared by the models of air in hydrostatic balance: Derived provides temperature(h, &t, &dt),
// column(), humidity() and dispersion() (its wavelength's edlen_dispersion); this gives pressure(h) and n(h), dn/dh.
template <class Derived, class T>
struct HydrostaticAirModel : HeightOnlyModel<Derived, T> {
  T pressure(const T& h) const {
    using std::exp;
    return exp(self().column().log_pressure(h));
  }
  // The column's pressure P [Pa], its temperature t [K] and their height slopes at h, clamped to
  // the modelled top (above it the air is uniform: slopes 0).
  void column_state(const T& h, T* p, T* dp_dh, T* t, T* dt_dh) const {
    const double top = self().column().highest();
    const T at = value_of(h) > top ? T(top) : h;
    self().temperature(at, t, dt_dh);
    *p = pressure(at);
    *dp_dh = hydrostatic_pressure_slope(at, *p, *t);
    if (value_of(h) > top) *dp_dh = *dt_dh = T(0.0);
  }

  // Above the modelled column the air is taken as uniform at its top state: n(top), no gradient.
  // A ray climbing out of the column then leaves straight along its direction at the top, as it
  // nearly does in real air (n - 1 is 4e-6 at 32 km and falls e-fold every 7 km). Below the
  // column's bottom n stays an error (NumericalError naming the height): there is ground there.
  double uniform_above() const { return self().column().highest(); }

  void evaluate_height(const T& h, T* n, T* dn_dh) const {
    T p, dp, t, dt, dn_dp, dn_dt;
    column_state(h, &p, &dp, &t, &dt);
    air_index_at(p, t, self().humidity(), self().dispersion(), n, &dn_dp, &dn_dt);
    *dn_dh = dn_dp * dp + dn_dt * dt;
  }

 private:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
};

}  // namespace refracta
