// Shadow maps: build (rasterize, moments, separable box filter, storage) and lookups.
#include "refracta/raster/shadow_map.h"

#include "refracta/core/error.h"
#include "refracta/core/image.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace refracta {

ShadowMethod parse_shadow_method(const std::string& name) {
  if (name == "hard") return ShadowMethod::kHard;
  if (name == "pcf") return ShadowMethod::kPcf;
  if (name == "vsm") return ShadowMethod::kVsm;
  if (name == "hamburger") return ShadowMethod::kHamburger;
  if (name == "hausdorff") return ShadowMethod::kHausdorff;
  throw_invalid("shadow method must be 'hard', 'pcf', 'vsm', 'hamburger' or 'hausdorff' (got '", name, "')");
}

const char* shadow_method_name(ShadowMethod method) {
  switch (method) {
    case ShadowMethod::kHard: return "hard";
    case ShadowMethod::kPcf: return "pcf";
    case ShadowMethod::kVsm: return "vsm";
    case ShadowMethod::kHamburger: return "hamburger";
    case ShadowMethod::kHausdorff: return "hausdorff";
  }
  return "?";
}

namespace {

bool uses_moments(ShadowMethod m) {
  return m == ShadowMethod::kVsm || m == ShadowMethod::kHamburger || m == ShadowMethod::kHausdorff;
}

}  // namespace

void ShadowMapOptions::validate() const {
  // Peak memory at 8192^2 texels: 2.4 GB for moment maps (four doubles per texel, 2 GiB, filtered
  // in place, plus the depth buffer), 1.3 GB while rasterizing (20 bytes per texel); measured
  // with tests/hardening/test_05_raster_memory.py (before: 5.5 GB, the rows and the filtered
  // copy both held, and the whole visibility buffer kept).
  if (resolution < 2 || resolution > 8192) throw_invalid("resolution must be in [2, 8192] (got ", resolution, ")");
  check_image_memory(resolution, resolution, uses_moments(method) ? 36.0 : 20.0, "shadow map");
  if (kernel < 1 || kernel % 2 == 0 || kernel > resolution) {
    throw_invalid("kernel must be an odd size >= 1 and <= resolution (got ", kernel, ")");
  }
  moments.validate();
  if (!(depth_bias >= 0.0) || !std::isfinite(depth_bias)) throw_invalid("depth_bias must be >= 0 (got ", depth_bias, ")");
  if (!(normal_offset >= 0.0) || !std::isfinite(normal_offset)) {
    throw_invalid("normal_offset must be >= 0 (got ", normal_offset, ")");
  }
  if (!(bleeding_reduction >= 0.0 && bleeding_reduction < 1.0)) {
    throw_invalid("bleeding_reduction must be in [0, 1) (got ", bleeding_reduction, ")");
  }
}

namespace {

// The moment map in two passes, O(1) per texel whatever the kernel k (odd): along each row,
// running sums of (z, z^2, z^3, z^4) of the depths (clamped at the edges); then down blocks of
// columns, one running sum per column (memory read row by row), each result stored as `store`
// says (the storage emulation) on its way out, in place: each block keeps the row-pass values of
// the last r + 1 rows it overwrote (and of row 0), which the running sum still subtracts.
template <class Depth, class Store>
std::vector<Moments4> filtered_moments(int n, int k, WorkControl& control, const Depth& depth, const Store& store) {
  const int r = k / 2;
  auto add = [](Moments4& a, const Moments4& b, double sign) {
    for (int j = 0; j < 4; ++j) a[j] += sign * b[j];
  };
  std::vector<Moments4> rows(size_t(n) * n);
  parallel_for_each(n, 8, control, [&](int64_t y) {
    std::vector<Moments4> power(n);
    for (int x = 0; x < n; ++x) {
      const double z = depth(x, int(y));
      power[x] = {z, z * z, z * z * z, z * z * z * z};
    }
    Moments4* row = &rows[size_t(y) * n];
    if (k == 1) {
      std::copy(power.begin(), power.end(), row);
      return;
    }
    Moments4 sum{0, 0, 0, 0};
    for (int i = -r; i <= r; ++i) add(sum, power[std::clamp(i, 0, n - 1)], 1.0);
    for (int x = 0; x < n; ++x) {
      for (int j = 0; j < 4; ++j) row[x][j] = sum[j] / k;
      add(sum, power[std::min(x + r + 1, n - 1)], 1.0);
      add(sum, power[std::max(x - r, 0)], -1.0);
    }
  });
  constexpr int kBlock = 64;
  const int blocks = (n + kBlock - 1) / kBlock;
  parallel_for_each(blocks, 1, control, [&](int64_t b) {
    const int x0 = int(b) * kBlock, x1 = std::min(x0 + kBlock, n), w = x1 - x0;
    auto row = [&](int y) { return &rows[size_t(std::clamp(y, 0, n - 1)) * n]; };
    if (k == 1) {
      for (int y = 0; y < n; ++y) {
        for (int x = x0; x < x1; ++x) row(y)[x] = store(row(y)[x]);
      }
      return;
    }
    std::vector<Moments4> sum(w, Moments4{0, 0, 0, 0}), kept(size_t(r + 1) * w), first(row(0) + x0, row(0) + x1);
    for (int i = -r; i <= r; ++i) {
      for (int x = x0; x < x1; ++x) add(sum[x - x0], row(i)[x], 1.0);
    }
    for (int y = 0; y < n; ++y) {
      Moments4* current = row(y);
      Moments4* keep = &kept[size_t(y % (r + 1)) * w];
      // Row y + r + 1 is not overwritten yet (at the last row it is y itself, and unused after).
      const Moments4* enter = row(y + r + 1) + x0;
      // Row y - r was overwritten r steps ago; its row-pass values are in `kept` (r >= 1).
      const Moments4* leave = y - r <= 0 ? first.data() : &kept[size_t((y - r) % (r + 1)) * w];
      for (int i = 0; i < w; ++i) {
        Moments4& s = sum[i];
        Moments4 mean;
        for (int j = 0; j < 4; ++j) mean[j] = s[j] / k;
        keep[i] = current[x0 + i];
        current[x0 + i] = store(mean);
        add(s, enter[i], 1.0);
        add(s, leave[i], -1.0);
      }
    }
  });
  return rows;
}

}  // namespace

ShadowMap::ShadowMap(const Scene& scene, const Vec3d& toward_light, const Vec3d& centre, double half_size,
                     const ShadowMapOptions& options, WorkControl& control)
    : options_(options) {
  options_.validate();
  if (!is_finite(toward_light) || toward_light.norm() == 0.0) throw_invalid("the light direction must be finite and non-zero");
  if (!is_finite(centre) || !(half_size > 0.0) || !std::isfinite(half_size)) {
    throw_invalid("the shadow map needs a finite centre and half_size > 0 (got ", half_size, ")");
  }
  const Vec3d along = -toward_light.normalized();
  const Vec3d up = std::abs(along.y()) < 0.99 ? Vec3d::UnitY() : Vec3d::UnitX();
  const int n = options_.resolution;
  view_ = RasterView::orthographic(centre, along, up, half_size, half_size, n, n);
  build(scene, control);
}

ShadowMap::ShadowMap(const Scene& scene, const RasterView& light_view, const ShadowMapOptions& options,
                     WorkControl& control)
    : options_(options), view_(light_view) {
  options_.validate();
  if (view_.width() != options_.resolution || view_.height() != options_.resolution) {
    throw_invalid("the light view must be resolution x resolution texels");
  }
  build(scene, control);
}

void ShadowMap::build(const Scene& scene, WorkControl& control) {
  const auto start = std::chrono::steady_clock::now();
  const int n = options_.resolution;
  buffer_ = rasterize(scene, view_, control);
  // Lookups read depths only: the rest of the visibility buffer (16 of its 20 bytes per texel) goes.
  std::vector<uint32_t>().swap(buffer_.geometry);
  std::vector<uint32_t>().swap(buffer_.primitive);
  std::vector<float>().swap(buffer_.b1);
  std::vector<float>().swap(buffer_.b2);
  near_ = std::numeric_limits<double>::infinity(), far_ = -near_;
  for (float d : buffer_.depth) {
    if (std::isfinite(d)) near_ = std::min(near_, double(d)), far_ = std::max(far_, double(d));
  }
  if (!(far_ > near_)) near_ = 0.0, far_ = 1.0;
  const double margin = 1e-3 * (far_ - near_) + 1e-6;
  near_ -= margin, far_ += margin;

  if (uses_moments(options_.method)) {
    const MomentStorage storage = options_.moments.storage;
    const bool signed_depth = options_.moments.signed_depth;
    moments_ = filtered_moments(
        n, options_.kernel, control, [&](int x, int y) { return depth_at(x, y); },
        [&](const Moments4& b) { return storage == MomentStorage::kFp64 ? b : stored_moments(b, storage, signed_depth); });
    std::vector<float>().swap(buffer_.depth);  // moment lookups read the moments only
  }
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double ShadowMap::normalised(double depth) const {
  const double z = (depth - near_) / (far_ - near_);
  return options_.moments.signed_depth ? 2.0 * z - 1.0 : z;
}

double ShadowMap::depth_at(int x, int y) const {
  const float d = buffer_.depth[buffer_.index(x, y)];
  return std::isfinite(d) ? normalised(d) : 1.0;
}

int ShadowMap::bytes_per_texel() const {
  if (!uses_moments(options_.method)) return 4;
  switch (options_.moments.storage) {
    case MomentStorage::kFp64: return 32;
    case MomentStorage::kFp32: return 16;
    case MomentStorage::kUnorm16: return 8;
  }
  return 0;
}

double ShadowMap::shadow(const Vec3d& point, const Vec3d& normal) const {
  const double receiver_depth = view_.to_view(point).z();
  if (view_.perspective() && receiver_depth <= view_.near()) return 0.0;  // behind the light: lit
  const double texel = view_.pixel_width(receiver_depth);
  const Vec3d p = view_.to_view(point + normal * (options_.normal_offset * texel));
  if (view_.perspective() && p.z() <= view_.near()) return 0.0;
  double u, v;
  view_.to_pixel(p, &u, &v);
  const int n = options_.resolution;
  if (!(u >= 0.0 && v >= 0.0 && u < n && v < n)) return 0.0;  // outside the map: lit
  const double z = normalised(p.z());
  if (!uses_moments(options_.method)) {
    // Receiver-plane depth bias: each texel of the window is compared with the receiver's plane
    // extended to it (depth slopes from its normal in the light's frame), so a sloped receiver
    // does not shadow itself over a wide kernel.
    const Vec3d nl = view_.to_view(normal) - view_.to_view(Vec3d::Zero());  // the normal in the light's frame
    const double scale = texel / (far_ - near_) * (options_.moments.signed_depth ? 2.0 : 1.0);
    const double nz = std::max(std::abs(nl.z()), 0.05) * (nl.z() < 0 ? -1.0 : 1.0);
    const double slope_x = -nl.x() / nz * scale, slope_y = nl.y() / nz * scale;  // per texel (v down)
    const int cx = int(u), cy = int(v), r = options_.method == ShadowMethod::kPcf ? options_.kernel / 2 : 0;
    int blocked = 0;
    for (int y = cy - r; y <= cy + r; ++y) {
      for (int x = cx - r; x <= cx + r; ++x) {
        const double plane = z + slope_x * (x + 0.5 - u) + slope_y * (y + 0.5 - v);
        blocked += depth_at(std::clamp(x, 0, n - 1), std::clamp(y, 0, n - 1)) < plane - options_.depth_bias;
      }
    }
    return double(blocked) / double((2 * r + 1) * (2 * r + 1));
  }
  // Bilinear filtering between texel centres, as texture hardware reads the moment map.
  const double fx = std::clamp(u - 0.5, 0.0, n - 1.0), fy = std::clamp(v - 0.5, 0.0, n - 1.0);
  const int x0 = std::min(int(fx), n - 2), y0 = std::min(int(fy), n - 2);  // resolution >= 2
  const double tx = fx - x0, ty = fy - y0;
  Moments4 b{0, 0, 0, 0};
  for (int k = 0; k < 4; ++k) {
    const int x = x0 + (k & 1), y = y0 + (k >> 1);
    const double w = ((k & 1) ? tx : 1.0 - tx) * ((k >> 1) ? ty : 1.0 - ty);
    const Moments4& m = moments_[size_t(y) * n + x];
    for (int j = 0; j < 4; ++j) b[j] += w * m[j];
  }
  MomentShadowSettings settings = options_.moments;
  settings.storage = MomentStorage::kFp64;  // already stored at build time
  settings.method = options_.method == ShadowMethod::kVsm         ? MomentShadowMethod::kVsm
                    : options_.method == ShadowMethod::kHausdorff ? MomentShadowMethod::kHausdorff
                                                                  : MomentShadowMethod::kHamburger;
  double s = moment_shadow(b, z, settings);
  if (options_.method == ShadowMethod::kVsm && options_.bleeding_reduction > 0.0) {
    const double lit = std::clamp((1.0 - s - options_.bleeding_reduction) / (1.0 - options_.bleeding_reduction), 0.0, 1.0);
    s = 1.0 - lit;
  }
  return std::clamp(s, 0.0, 1.0);
}

}  // namespace refracta
