// ElevationTable: adaptive construction over oneTBB, interpolated queries.
#include "refracta/rays/elevation_table.h"

#include "refracta/core/error.h"
#include "refracta/media/tabulated_height_field.h"
#include "refracta/rays/trace.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace refracta {

void ElevationTableOptions::validate() const {
  Problems problems("ElevationTable");
  trace.check(problems);
  problems.check(std::abs(eye_height) <= kSceneReach, "eye_height must be within the scene's reach, |h| <= ", kSceneReach,
                 " m (got ", eye_height, ")");
  const double limit = 0.5 * kPi;
  problems.check(min_elevation >= -limit && max_elevation <= limit && min_elevation < max_elevation,
                 "elevations must satisfy -90 deg <= min_elevation < max_elevation <= 90 deg (got ",
                 min_elevation * 180 / kPi, ", ", max_elevation * 180 / kPi, ")");
  problems.check(tol > 0.0 && std::isfinite(tol), "tol must be > 0 (got ", tol, ")");
  if (trace_tol) problems.check(*trace_tol > 0.0 && std::isfinite(*trace_tol), "trace_tol must be > 0 (got ", *trace_tol, ")");
  problems.check(initial_rays >= 2, "initial_rays must be >= 2 (got ", initial_rays, ")");
  problems.check(min_spacing > 0.0, "min_spacing must be > 0 (got ", min_spacing, ")");
  problems.check(angular_tol >= 0.0, "angular_tol must be >= 0 (got ", angular_tol, ")");
  problems.check(!std::isnan(ceiling), "ceiling must be a height or inf (got nan)");
  problems.check(max_rays >= initial_rays, "max_rays must be >= initial_rays (got ", max_rays, ")");
  if (trace.stop_height) {
    problems.check(!(eye_height < *trace.stop_height), "eye_height ", eye_height, " m is below stop_height ",
                   *trace.stop_height, " m");
  }
  problems.throw_if_any();
}

ElevationTable::Entry ElevationTable::trace_entry(double elevation, const std::atomic<bool>* cancel, double tol) const {
  TraceOptions trace = options_.trace;
  trace.trace = TraceMethod::kStratified;
  trace.tol = std::max(trace.tol, tol);
  trace.cancel = cancel;
  Entry entry;
  const Vec3d eye(0.0, options_.eye_height, 0.0), launch(std::cos(elevation), std::sin(elevation), 0.0);
  if (options_.escape) {
    // As trace_path, ending at the first node where the path escapes (its stop then kVisitor).
    std::vector<RayNode<double>> nodes;
    auto visit = [&](const RayNode<double>& a, const RayNode<double>& b) {
      if (nodes.empty()) nodes.push_back(a);
      nodes.push_back(b);
      entry.escape = options_.escape(b, trace.max_length - b.s);
      return !entry.escape;
    };
    const TraceEnd<double> end = refracta::trace(*field_, eye, launch, trace, visit);
    if (nodes.empty()) nodes.push_back(end.end);
    entry.path = std::make_shared<RayPath>(std::move(nodes), end.stop, end.evaluations);
  } else {
    entry.path = std::make_shared<RayPath>(trace_path(*field_, eye, launch, trace));
  }
  int turns = 0;
  const auto& nodes = entry.path->nodes();
  for (size_t i = 1; i < nodes.size(); ++i) {
    if ((nodes[i].v.y() > 0.0) != (nodes[i - 1].v.y() > 0.0) && nodes[i].v.y() != 0.0) ++turns;
  }
  entry.kind = int(entry.path->stop()) + 4 * turns;
  return entry;
}

PlaneState ElevationTable::state_of(const RayPath& path, double s) {
  Vec3d direction;
  const Vec3d x = path.point_at(std::clamp(s, 0.0, path.length()), &direction);
  return {x.x(), x.y(), std::min(s, path.length()), direction.x(), direction.y(), path.stop()};
}

namespace {

// Stencil of interval i: four neighbours of one kind when they exist, else the interval's ends.
template <class Entries>
std::pair<size_t, size_t> stencil_of(const Entries& entries, size_t i) {
  if (i >= 1 && i + 2 < entries.size()) {
    const int kind = entries[i].kind;
    if (entries[i - 1].kind == kind && entries[i + 1].kind == kind && entries[i + 2].kind == kind) return {i - 1, 4};
  }
  return {i, 2};
}

// Lagrange weights at `elevation` on the stencil's (uneven) elevations.
void lagrange_weights(const std::vector<double>& elevations, size_t first, size_t count, double elevation,
                      double* weights) {
  for (size_t k = 0; k < count; ++k) {
    double w = 1.0;
    for (size_t j = 0; j < count; ++j) {
      if (j != k) w *= (elevation - elevations[first + j]) / (elevations[first + k] - elevations[first + j]);
    }
    weights[k] = w;
  }
}

// The weighted state of a stencil (directions renormalised) at arc length s.
PlaneState blend(const double* weights, const PlaneState* states, size_t count, double s, TraceStop stop) {
  PlaneState out{0, 0, s, 0, 0, stop};
  for (size_t k = 0; k < count; ++k) {
    out.r += weights[k] * states[k].r;
    out.h += weights[k] * states[k].h;
    out.cos_e += weights[k] * states[k].cos_e;
    out.sin_e += weights[k] * states[k].sin_e;
  }
  const double norm = std::sqrt(out.cos_e * out.cos_e + out.sin_e * out.sin_e);  // ~1: no hypot's care needed
  out.cos_e /= norm;
  out.sin_e /= norm;
  return out;
}

}  // namespace

std::pair<size_t, size_t> ElevationTable::stencil(size_t i) const { return stencil_of(entries_, i); }

PlaneState ElevationTable::interpolate(const std::vector<double>& elevations,
                                       const std::vector<Entry>& entries, size_t i, double elevation,
                                       double fraction) {
  const auto [first, count] = stencil_of(entries, i);
  double length = 0.0, weights[4];
  lagrange_weights(elevations, first, count, elevation, weights);
  for (size_t k = 0; k < count; ++k) length += weights[k] * entries[first + k].path->length();
  PlaneState states[4];
  for (size_t k = 0; k < count; ++k) {
    const RayPath& path = *entries[first + k].path;
    states[k] = state_of(path, fraction * path.length());
  }
  return blend(weights, states, count, fraction * length, entries[i].path->stop());
}

double ElevationTable::excess(const std::vector<double>& elevations, const std::vector<Entry>& entries, size_t i,
                              const Entry& mid, double elevation, double scale) const {
  double worst = -std::numeric_limits<double>::infinity();
  for (double fraction : {0.25, 0.5, 0.75, 1.0}) {
    const PlaneState m = state_of(*mid.path, fraction * mid.path->length());
    if (mid.escape && m.h > options_.ceiling) {  // above everything from here on? (options.ceiling)
      const auto& nodes = mid.path->nodes();
      bool above = true;
      for (size_t k = nodes.size(); k-- > 0 && above && nodes[k].s >= m.s;) above = nodes[k].x.y() > options_.ceiling;
      if (above) continue;
    }
    const PlaneState p = interpolate(elevations, entries, i, elevation, fraction);
    const double allowed = scale * (options_.tol + options_.angular_tol * m.s);
    worst = std::max(worst, std::hypot(p.r - m.r, p.h - m.h) - allowed);
  }
  if (mid.escape) {
    // Where the path leaves the air, to the tolerance at its whole length, and the direction it
    // leaves along (its sky) to angular_tol.
    const auto [first, count] = stencil_of(entries, i);
    double weights[4];
    lagrange_weights(elevations, first, count, elevation, weights);
    PlaneState states[4];
    double s = 0.0;
    for (size_t k = 0; k < count; ++k) {
      if (!entries[first + k].escape) return std::numeric_limits<double>::infinity();
      states[k] = *entries[first + k].escape;
      s += weights[k] * states[k].s;
    }
    const PlaneState p = blend(weights, states, count, s, mid.escape->stop);
    const PlaneState& m = *mid.escape;
    worst = std::max(worst, std::hypot(p.r - m.r, p.h - m.h) - scale * (options_.tol + options_.angular_tol * m.s));
    const double turn =
        std::abs(std::atan2(p.sin_e * m.cos_e - p.cos_e * m.sin_e, p.cos_e * m.cos_e + p.sin_e * m.sin_e));
    worst = std::max(worst, (turn - scale * options_.angular_tol) * m.s);  // in metres at the escape's length
  }
  return worst;
}

ElevationTableOptions ElevationTable::built_options() const {
  ElevationTableOptions options = options_;
  options.trace.cancel = nullptr;
  options.trace.ior_floor.reset();
  return options;
}

ElevationTable::ElevationTable(FieldPtr field, const ElevationTableOptions& options, WorkControl& control)
    : field_(std::move(field)), options_(options) {
  if (!field_) throw_invalid("ElevationTable needs a field");
  if (!field_->height_only()) {
    throw_invalid("ElevationTable needs a field that depends on height only; ", field_->type_name(),
                  " does not");
  }
  options_.trace.trace = TraceMethod::kStratified;
  options_.trace.tol = options_.trace_tol.value_or(options_.tol);
  options_.validate();
  // Between an entry's nodes the quintic is read (the renderers' chord plans): held to half of the
  // larger term of the table's own accuracy, tol or angular_tol s, not to the traces' tol (trace_tol
  // may be far tighter).
  options_.trace.hold_between_nodes = true;
  options_.trace.between_nodes = TraceOptions::GrowingTolerance{0.5 * options_.tol, 0.5 * options_.angular_tol, 0.0};
  // Every height a path can reach, tabulated once (to 1e-12 in n: far below any tolerance).
  const double reach = options_.trace.max_length;
  const double lowest = std::max(options_.eye_height - reach, options_.trace.stop_height.value_or(-reach) - 1.0);
  field_ = tabulate_heights(field_, lowest, options_.eye_height + reach);
  // Rays that cannot turn are traced in whole panels (TraceOptions::ior_floor); sampling the
  // tabulated field over the reach costs well under a millisecond.
  if (!options_.trace.ior_floor) {
    if (const double floor = lowest_ior_sampled(*field_, lowest, options_.eye_height + reach); floor > 0.0) {
      options_.trace.ior_floor = floor;
    }
  }
  std::atomic<int64_t> evaluations{0};
  auto trace_all = [&](const std::vector<double>& e) {
    std::vector<Entry> out(e.size());
    WorkControl inner;
    parallel_for_each(int64_t(e.size()), 1, inner, [&](int64_t i) {
      if (control.cancel) throw Cancelled();
      out[i] = trace_entry(e[i], &control.cancel);
      evaluations += out[i].path->evaluations();
      control.done.fetch_add(1);
    });
    return out;
  };

  const int n0 = options_.initial_rays;
  std::vector<double> e(n0);
  for (int i = 0; i < n0; ++i) {
    e[i] = options_.min_elevation + (options_.max_elevation - options_.min_elevation) * i / (n0 - 1);
  }
  control.total = n0;
  std::vector<Entry> entries = trace_all(e);
  std::vector<int> open(n0 - 1, 1);  // 1: interval still to check; 0: accepted; 2: exact
  while (true) {
    std::vector<double> mids;
    std::vector<size_t> which;
    for (size_t i = 0; i + 1 < e.size(); ++i) {
      if (open[i] == 1) {
        mids.push_back(0.5 * (e[i] + e[i + 1]));
        which.push_back(i);
      }
    }
    if (mids.empty()) break;
    if (int64_t(e.size() + mids.size()) > options_.max_rays) {  // give up refining: trace those exactly
      for (auto& state : open) state = state == 1 ? 2 : state;
      break;
    }
    control.total += int64_t(mids.size());
    std::vector<Entry> traced = trace_all(mids);
    std::vector<double> next_e;
    std::vector<Entry> next_entries;
    std::vector<int> next_open;
    size_t k = 0;
    for (size_t i = 0; i < e.size(); ++i) {
      next_e.push_back(e[i]);
      next_entries.push_back(entries[i]);
      if (i + 1 == e.size()) break;
      if (k < which.size() && which[k] == i) {
        const Entry& mid = traced[k++];
        const bool same_kind = entries[i].kind == mid.kind && mid.kind == entries[i + 1].kind;
        // The check measures the interpolation *before* the midpoint joins the table; cubic
        // interpolation's error falls 16x when the spacing halves, so 4 tol leaves a 4x margin.
        const bool close = same_kind && excess(e, entries, i, mid, 0.5 * (e[i] + e[i + 1]), 4.0) <= 0.0;
        const bool narrow = e[i + 1] - e[i] <= 2.0 * options_.min_spacing;
        const int state = close ? 0 : (narrow ? (same_kind ? 0 : 2) : 1);
        next_e.push_back(0.5 * (e[i] + e[i + 1]));
        next_entries.push_back(mid);
        next_open.push_back(state);
        next_open.push_back(state);
      } else {
        next_open.push_back(open[i]);
      }
    }
    e.swap(next_e);
    entries.swap(next_entries);
    open.swap(next_open);
  }
  elevations_ = std::move(e);
  entries_ = std::move(entries);
  for (Entry& entry : entries_) {
    const auto& nodes = entry.path->nodes();
    entry.lowest.resize(nodes.size());
    double low = std::numeric_limits<double>::infinity();
    for (size_t k = nodes.size(); k-- > 0;) entry.lowest[k] = low = std::min(low, nodes[k].x.y());
  }
  exact_.resize(open.size());
  for (size_t i = 0; i < open.size(); ++i) exact_[i] = open[i] == 2;
  evaluations_ = evaluations;
  precompute_stencils();
}

void ElevationTable::precompute_stencils() {
  stencils_.assign(exact_.size(), {});
  for (size_t i = 0; i < exact_.size(); ++i) {
    if (exact_[i]) continue;
    const auto [first, count] = stencil(i);
    for (int t = 0; t < 2; ++t) {
      const RayPath& nearest = *entries_[i + t].path;
      auto& states = stencils_[i].at_nodes[t];
      states.reserve(nearest.nodes().size() * count);
      for (const auto& node : nearest.nodes()) {
        const double fraction = nearest.length() > 0 ? node.s / nearest.length() : 0.0;
        for (size_t k = 0; k < count; ++k) {
          const RayPath& path = *entries_[first + k].path;
          states.push_back(state_of(path, fraction * path.length()));
        }
      }
    }
  }
}

size_t ElevationTable::exact_intervals() const {
  return size_t(std::count(exact_.begin(), exact_.end(), true));
}

size_t ElevationTable::interval(double elevation) const {
  if (!(elevation >= elevations_.front() && elevation <= elevations_.back())) {
    throw_invalid("elevation ", elevation * 180 / kPi, " deg is outside the table [",
                  elevations_.front() * 180 / kPi, ", ", elevations_.back() * 180 / kPi, "] deg");
  }
  const size_t i = size_t(std::upper_bound(elevations_.begin(), elevations_.end(), elevation) -
                          elevations_.begin());
  return std::clamp<size_t>(i, 1, elevations_.size() - 1) - 1;
}

PlaneState ElevationTable::at(double elevation, double s) const {
  const size_t i = interval(elevation);
  if (exact_[i] && elevation != elevations_[i] && elevation != elevations_[i + 1]) {
    return state_of(*trace_entry(elevation).path, s);
  }
  // Paths of one kind end alike: at max_length (same s) or on the stop height (s interpolated).
  const PlaneState whole = interpolate(elevations_, entries_, i, elevation, 1.0);
  if (s >= whole.s) return whole;
  return interpolate(elevations_, entries_, i, elevation, std::max(s, 0.0) / whole.s);
}

RayNode<double> ElevationTable::node_of(const PlaneState& p) const {
  RayNode<double> node;
  node.s = p.s;
  node.x = Vec3d(p.r, p.h, 0.0);
  double dn;
  field_->evaluate_height(p.h, &node.n, &dn);
  node.grad = Vec3d(0.0, dn, 0.0);
  node.v = node.n * Vec3d(p.cos_e, p.sin_e, 0.0);
  return node;
}

ElevationTable::LazyPath ElevationTable::lazy_path(double elevation, double tol) const {
  LazyPath lazy;
  lazy.table_ = this;
  lazy.elevation_ = elevation;
  lazy.interval_ = interval(elevation);
  const size_t i = lazy.interval_;
  if (exact_[i]) {
    // An exact interval has no precomputed stencil: its ends are traced entries, inside is traced.
    if (elevation == elevations_[i] || elevation == elevations_[i + 1]) {
      const Entry& entry = entries_[elevation == elevations_[i] ? i : i + 1];
      lazy.exact_ = entry.path;
      lazy.exact_escape_ = entry.escape;
    } else {
      Entry entry = trace_entry(elevation, nullptr, tol);
      lazy.exact_ = std::move(entry.path);
      lazy.exact_escape_ = entry.escape;
    }
    const auto& nodes = lazy.exact_->nodes();
    lazy.exact_lowest_.resize(nodes.size());
    double low = std::numeric_limits<double>::infinity();
    for (size_t k = nodes.size(); k-- > 0;) lazy.exact_lowest_[k] = low = std::min(low, nodes[k].x.y());
    return lazy;
  }
  const double w = (elevation - elevations_[i]) / (elevations_[i + 1] - elevations_[i]);
  lazy.template_ = w < 0.5 ? i : i + 1;
  const auto [first, count] = stencil(i);
  lagrange_weights(elevations_, first, count, elevation, lazy.weights_);
  lazy.count_ = count;
  for (size_t k = 0; k < count; ++k) lazy.length_ += lazy.weights_[k] * entries_[first + k].path->length();
  return lazy;
}

size_t ElevationTable::LazyPath::size() const {
  return exact_ ? exact_->nodes().size() : table_->entries_[template_].path->nodes().size();
}

TraceStop ElevationTable::LazyPath::stop() const {
  return exact_ ? exact_->stop() : table_->entries_[template_].path->stop();
}

std::optional<PlaneState> ElevationTable::LazyPath::escape() const {
  if (exact_) return exact_escape_;
  const auto [first, count] = table_->stencil(interval_);
  PlaneState states[4];
  double s = 0.0;
  for (size_t k = 0; k < count; ++k) {
    const auto& state = table_->entries_[first + k].escape;
    if (!state) return std::nullopt;  // one kind: all escape or none
    states[k] = *state;
    s += weights_[k] * state->s;
  }
  return blend(weights_, states, count, s, TraceStop::kVisitor);
}

RayNode<double> ElevationTable::LazyPath::node(size_t k) const {
  if (exact_) return exact_->nodes()[k];
  return table_->node_of(state(k));
}

PlaneState ElevationTable::LazyPath::state(size_t k) const {
  if (exact_) {
    const RayNode<double>& node = exact_->nodes()[k];
    const double speed = std::sqrt(node.v.x() * node.v.x() + node.v.y() * node.v.y());
    return {node.x.x(), node.x.y(), node.s, node.v.x() / speed, node.v.y() / speed, exact_->stop()};
  }
  // The same interpolation as interpolate(), from the states precomputed at the template's nodes.
  const RayPath& nearest = *table_->entries_[template_].path;
  const PlaneState* states = &table_->stencils_[interval_].at_nodes[template_ - interval_][k * count_];
  const double fraction = nearest.length() > 0 ? nearest.nodes()[k].s / nearest.length() : 0.0;
  return blend(weights_, states, count_, fraction * length_, table_->entries_[interval_].path->stop());
}

double ElevationTable::LazyPath::lowest_from(size_t k) const {
  if (exact_) return exact_lowest_[k];
  // The interpolated path lies between its bracketing paths up to the error the table was refined
  // to (accepted at 4 (tol + angular_tol s), see the constructor); bound it by the
  // lowest of the two from one node earlier on, less that error.
  const auto& a = table_->entries_[interval_];
  const auto& b = table_->entries_[interval_ + 1];
  const auto& t = table_->entries_[template_];
  const double fraction = double(k) / std::max<size_t>(t.lowest.size() - 1, 1);
  auto at = [&](const Entry& entry) {
    const size_t index = std::min(entry.lowest.size() - 1, size_t(std::floor(fraction * (entry.lowest.size() - 1))));
    return entry.lowest[index > 0 ? index - 1 : 0];
  };
  const double length = std::max(a.path->length(), b.path->length());
  const double margin = 4.0 * (table_->options_.tol + table_->options_.angular_tol * length);
  return std::min(at(a), at(b)) - margin;
}

RayPath ElevationTable::path(double elevation) const {
  const LazyPath lazy = lazy_path(elevation);
  std::vector<RayNode<double>> nodes;
  for (size_t k = 0; k < lazy.size(); ++k) nodes.push_back(lazy.node(k));
  return RayPath(std::move(nodes), lazy.stop(), 0);
}

PlaneState ElevationTable::end(double elevation) const {
  return at(elevation, std::numeric_limits<double>::infinity());
}

TableRayEnd ElevationTable::end(double elevation, double azimuth) const {
  const PlaneState p = end(elevation);
  const double ca = std::cos(azimuth), sa = std::sin(azimuth);
  return {Vec3d(p.r * ca, p.h, p.r * sa), Vec3d(p.cos_e * ca, p.sin_e, p.cos_e * sa), p.s, p.stop};
}

RayBatchEnds ElevationTable::ends(const std::vector<double>& elevations, std::vector<double> azimuths,
                                  WorkControl& control) const {
  const size_t count = elevations.size();
  if (azimuths.size() == 1 && count != 1) azimuths.assign(count, azimuths[0]);
  if (azimuths.size() != count) {
    throw_invalid("azimuths must be one value or one per elevation (", azimuths.size(), " vs ", count, ")");
  }
  RayBatchEnds out{std::vector<Vec3d>(count), std::vector<Vec3d>(count), std::vector<double>(count),
                   std::vector<int>(count), std::vector<int64_t>(count, 0)};
  parallel_for_each(int64_t(count), 64, control, [&](int64_t i) {
    const TableRayEnd e = end(elevations[size_t(i)], azimuths[size_t(i)]);
    out.points[size_t(i)] = e.point;
    out.directions[size_t(i)] = e.direction;
    out.lengths[size_t(i)] = e.length;
    out.stops[size_t(i)] = int(e.stop);
  });
  return out;
}

}  // namespace refracta
