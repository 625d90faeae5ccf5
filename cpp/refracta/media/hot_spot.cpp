// Hot spots' names, parameter specs and validation (hot_spot.h).
#include "refracta/media/hot_spot.h"

#include <algorithm>
#include <utility>

namespace refracta {

Footprint parse_footprint(const std::string& name) {
  if (name == "gaussian") return Footprint::kGaussian;
  if (name == "compact") return Footprint::kCompact;
  throw_invalid("HotSpot: footprint must be 'gaussian' or 'compact' (got '", name, "')");
}

const char* footprint_name(Footprint footprint) {
  return footprint == Footprint::kCompact ? "compact" : "gaussian";
}

bool HotSpot::operator==(const HotSpot& o) const {
  return x == o.x && z == o.z && radius == o.radius && dt == o.dt && footprint == o.footprint &&
         (depth == o.depth || (std::isnan(depth) && std::isnan(o.depth)));
}

namespace {
// A spot narrower than a millimetre heats nothing a ray resolves, and 1 / radius^2 overflows for
// the tiniest (a trial's 1e-300 m made every ior NaN, 100 m away).
constexpr double kSmallestRadius = 1e-3;  // [m]
}  // namespace

HotSpot make_hot_spot(double x, double z, double radius, double dt, std::optional<double> depth,
                      const std::string& footprint) {
  HotSpot s;
  s.x = x, s.z = z, s.radius = radius, s.dt = dt, s.depth = depth.value_or(std::nan(""));
  s.footprint = parse_footprint(footprint);
  const std::pair<const char*, double> finite[] = {{"x", x}, {"z", z}, {"radius", radius}, {"dt", dt}};
  for (const auto& [what, value] : finite) {
    if (!std::isfinite(value)) throw_invalid("HotSpot: ", what, " must be finite (got ", value, ")");
  }
  if (!(radius >= kSmallestRadius)) {
    throw_invalid("HotSpot: radius must be >= ", kSmallestRadius, " m (got ", radius, ")");
  }
  for (const auto& [what, value] : {std::pair<const char*, double>{"x", x}, {"z", z}, {"radius", radius}}) {
    if (std::abs(value) > kSceneReach) {
      throw_invalid("HotSpot: ", what, " must be within the scene's reach, ", kSceneReach, " m (got ", value, ")");
    }
  }
  if (std::max(std::abs(x), std::abs(z)) + radius > kSceneReach) {
    throw_invalid("HotSpot: the spot must lie within the scene's reach: max(|x|, |z|) + radius <= ", kSceneReach,
                  " m (got ", std::max(std::abs(x), std::abs(z)) + radius, " m)");
  }
  if (depth && !(*depth >= kShallowestLayer && *depth <= kDeepestLayer)) {
    throw_invalid("HotSpot: depth must be in [", kShallowestLayer, ", ", kDeepestLayer, "] m (got ", *depth, ")");
  }
  return s;
}

std::string hot_spot_repr(const HotSpot& s) {
  return concat("HotSpot(x=", s.x, ", z=", s.z, ", radius=", s.radius, ", dt=", s.dt, ", depth=",
                std::isnan(s.depth) ? std::string("None") : concat(s.depth), ", footprint='",
                footprint_name(s.footprint), "')");
}

std::vector<ParamSpec> hot_spot_param_specs(const std::vector<HotSpot>& spots, bool with_depth,
                                            const ParamSpec& dt_spec) {
  std::vector<ParamSpec> specs;
  for (size_t i = 0; i < spots.size(); ++i) {
    const HotSpot& s = spots[i];
    const std::string name = "hot_spot" + std::to_string(i) + "_";
    // Search box: the spot may move 20 radii (at least 100 m) and grow or shrink 20-fold.
    const double travel = std::max(100.0, 20.0 * s.radius);
    specs.push_back({name + "x", s.x, s.x - travel, s.x + travel, "m", "x of the centre"});
    specs.push_back({name + "z", s.z, s.z - travel, s.z + travel, "m", "z of the centre"});
    specs.push_back({name + "radius", s.radius, std::max(kSmallestRadius, s.radius / 20.0), s.radius * 20.0, "m",
                     std::string(footprint_name(s.footprint)) + " footprint radius"});
    ParamSpec dt = dt_spec;
    dt.name = name + "dt";
    dt.default_value = s.dt;
    dt.lower = std::min(dt.lower, s.dt);
    dt.upper = std::max(dt.upper, s.dt);
    specs.push_back(dt);
    if (with_depth) {
      specs.push_back({name + "depth", s.depth, std::min(0.005, s.depth), std::max(10.0, s.depth), "m",
                       "e-folding depth of the excess"});
    }
  }
  return specs;
}

void validate_hot_spots(const char* model, const std::vector<double>& values, size_t first, size_t count,
                        bool with_depth) {
  const int per = hot_spot_param_count(with_depth);
  for (size_t i = 0; i < count; ++i) {
    const double* v = values.data() + first + per * i;
    if (!(v[2] >= kSmallestRadius)) {
      throw_invalid(model, ": hot_spot", i, "_radius must be >= ", kSmallestRadius, " m (got ", v[2], ")");
    }
    if (with_depth && !(v[4] >= kShallowestLayer && v[4] <= kDeepestLayer)) {
      throw_invalid(model, ": hot_spot", i, "_depth must be in [", kShallowestLayer, ", ", kDeepestLayer, "] m (got ",
                    v[4], ")");
    }
  }
}

std::vector<HotSpot> hot_spots_from(const std::vector<HotSpot>& made, const std::vector<double>& values, size_t first,
                                    bool with_depth) {
  std::vector<HotSpot> out = made;
  const int per = hot_spot_param_count(with_depth);
  for (size_t i = 0; i < out.size(); ++i) {
    const double* v = values.data() + first + per * i;
    out[i].x = v[0], out[i].z = v[1], out[i].radius = v[2], out[i].dt = v[3];
    if (with_depth) out[i].depth = v[4];
  }
  return out;
}

}  // namespace refracta
