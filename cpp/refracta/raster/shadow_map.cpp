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
  if (name == "msm_hamburger") return ShadowMethod::kHamburger;
  if (name == "msm_hausdorff") return ShadowMethod::kHausdorff;
  throw_invalid("shadow method must be 'hard', 'pcf', 'vsm', 'msm_hamburger' or 'msm_hausdorff' (got '", name, "')");
}

const char* shadow_method_name(ShadowMethod method) {
  switch (method) {
    case ShadowMethod::kHard: return "hard";
    case ShadowMethod::kPcf: return "pcf";
    case ShadowMethod::kVsm: return "vsm";
    case ShadowMethod::kHamburger: return "msm_hamburger";
    case ShadowMethod::kHausdorff: return "msm_hausdorff";
  }
  return "?";
}

namespace {

bool uses_moments(ShadowMethod m) {
  return m == ShadowMethod::kVsm || m == ShadowMethod::kHamburger || m == ShadowMethod::kHausdorff;
}

}  // namespace

void ShadowMapOptions::check(Problems& problems) const {
  // Peak memory at 8192^2 texels: 2.4 GB for moment maps (fp64: four doubles per texel, 2 GiB,
  // written once by the one-pass filter, plus the depth buffer; fp32 and unorm16 half / a
  // quarter); the depths alone (4 bytes per texel: rasterize_depth) for the others. Measured with
  // tests/hardening/test_05_raster_memory.py (before: 5.5 GB, the rows and the filtered copy both
  // held, and the whole visibility buffer kept).
  const bool resolution_ok = resolution >= 2 && resolution <= 8192;
  problems.check(resolution_ok, "resolution must be in [2, 8192] (got ", resolution, ")");
  // Against the resolution only when that is valid: a bad resolution is one problem, not two.
  problems.check(kernel >= 1 && kernel % 2 == 1 && (!resolution_ok || kernel <= resolution),
                 "kernel must be an odd size >= 1 and <= resolution (got ", kernel, ")");
  problems.check_nested("moments", moments);
  // Depths are normalised to [0, 1]: a bias of 1 or more lights every receiver; an offset of more
  // texels than the map has moves every receiver off it (a trial's 1e300s removed every shadow).
  problems.check(depth_bias >= 0.0 && depth_bias < 1.0,
                 "depth_bias must be in [0, 1), a share of the map's normalised depth range (got ", depth_bias, ")");
  problems.check(normal_offset >= 0.0 && (!resolution_ok || normal_offset <= resolution),
                 "normal_offset must be >= 0 and at most the map's resolution of ", resolution, " texels (got ",
                 normal_offset, ")");
  problems.check(bleeding_reduction >= 0.0 && bleeding_reduction < 1.0,
                 "bleeding_reduction must be in [0, 1) (got ", bleeding_reduction, ")");
  if (resolution_ok) {
    try {
      check_image_memory(resolution, resolution, bytes_per_texel(), "shadow map");
    } catch (const std::invalid_argument& error) {
      problems.add(error.what());
    }
  }
}

double ShadowMapOptions::bytes_per_texel() const { return uses_moments(method) ? 36.0 : 4.0; }

void ShadowMapOptions::validate() const {
  Problems problems("ShadowMapOptions");
  check(problems);
  problems.throw_if_any();
}

namespace {

// The moment map in one pass, O(1) per texel whatever the kernel k (odd): the map is cut into
// blocks of kBlock columns; each block walks down its rows keeping the horizontal box sums of
// (z, z^2, z^3, z^4) of the last k rows (a ring, edges clamped) and their running vertical sum,
// and writes each texel once, stored as `store` says (the storage emulation). The block's working
// set (k rows of kBlock + k - 1 texels) stays in cache; the only full-size array is the result.
// depth_row(y, x0, count, out): the normalised depths of row y, columns x0 .. x0 + count - 1.
// store(mean) gives the stored texel (type Texel).
template <class Texel, class DepthRow, class Store>
UninitializedVector<Texel> filtered_moments(int n, int k, WorkControl& control, const DepthRow& depth_row,
                                            const Store& store) {
  const int r = k / 2;
  constexpr int kBlock = 64;
  const int blocks = (n + kBlock - 1) / kBlock;
  const double inv_area = 1.0 / (double(k) * double(k));
  UninitializedVector<Texel> out(size_t(n) * n);  // every texel written below, by one block
  parallel_for_each(blocks, 1, control, [&](int64_t block) {
    const int x0 = int(block) * kBlock, w = std::min(kBlock, n - x0), span = w + 2 * r;
    std::vector<double> z(static_cast<size_t>(span));
    std::vector<Moments4> power(static_cast<size_t>(span)), ring(static_cast<size_t>(k) * w), entering(static_cast<size_t>(w));
    std::vector<Moments4> column(static_cast<size_t>(w), Moments4{0, 0, 0, 0});
    // Horizontal box sums of row y (clamped) for the block's columns.
    auto row_sums = [&](int y, Moments4* sums) {
      // Columns x0 - r .. x0 + w + r - 1, clamped to the map: the in-range part read at once.
      const int lo = std::max(x0 - r, 0), hi = std::min(x0 + w + r, n);
      depth_row(std::clamp(y, 0, n - 1), lo, hi - lo, &z[size_t(lo - (x0 - r))]);
      for (int i = 0; i < lo - (x0 - r); ++i) z[size_t(i)] = z[size_t(lo - (x0 - r))];
      for (int i = hi - (x0 - r); i < span; ++i) z[size_t(i)] = z[size_t(hi - 1 - (x0 - r))];
      for (int i = 0; i < span; ++i) {
        const double v = z[size_t(i)], v2 = v * v;
        power[size_t(i)] = {v, v2, v2 * v, v2 * v2};
      }
      Moments4 s{0, 0, 0, 0};
      for (int i = 0; i < k; ++i) {
        for (int j = 0; j < 4; ++j) s[j] += power[size_t(i)][j];
      }
      for (int i = 0; i < w; ++i) {
        sums[i] = s;
        if (i + 1 == w) break;
        for (int j = 0; j < 4; ++j) s[j] += power[size_t(i) + size_t(k)][j] - power[size_t(i)][j];
      }
    };
    // The ring holds rows y - r .. y + r (slot = row mod k, rows above 0 clamped to row 0).
    for (int i = -r; i <= r; ++i) {
      Moments4* slot = &ring[size_t((i + k) % k) * w];
      row_sums(i, slot);
      for (int x = 0; x < w; ++x) {
        for (int j = 0; j < 4; ++j) column[size_t(x)][j] += slot[x][j];
      }
    }
    for (int y = 0; y < n; ++y) {
      if (y % 256 == 0) poll_cancel();  // a block walks every row of the map
      Texel* dst = &out[size_t(y) * n + size_t(x0)];
      for (int x = 0; x < w; ++x) {
        Moments4 mean;
        for (int j = 0; j < 4; ++j) mean[j] = column[size_t(x)][j] * inv_area;
        dst[x] = store(mean);
      }
      if (y + 1 == n) break;
      // Row y - r leaves, row y + r + 1 enters (same slot).
      Moments4* slot = &ring[size_t((y - r + k) % k) * w];
      row_sums(y + r + 1, entering.data());
      for (int x = 0; x < w; ++x) {
        for (int j = 0; j < 4; ++j) column[size_t(x)][j] += entering[size_t(x)][j] - slot[x][j];
        slot[x] = entering[size_t(x)];
      }
    }
  });
  return out;
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
  buffer_ = rasterize_depth(scene, view_, control);  // lookups read depths only
  near_ = std::numeric_limits<double>::infinity(), far_ = -near_;
  for (float d : buffer_.depth) {
    if (std::isfinite(d)) near_ = std::min(near_, double(d)), far_ = std::max(far_, double(d));
  }
  if (!(far_ > near_)) near_ = 0.0, far_ = 1.0;
  const double margin = 1e-3 * (far_ - near_) + 1e-6;
  near_ -= margin, far_ += margin;

  if (uses_moments(options_.method)) {
    const Storage storage = options_.moments.storage;
    const bool signed_depth = options_.moments.depth_range == DepthRange::kSigned;
    // normalised(d), and 1 (the far end) where nothing is drawn, as depth_at.
    const double inv_range = 1.0 / (far_ - near_), near = near_;
    auto depth_row = [&](int y, int x0, int count, double* z) {
      const float* row = &buffer_.depth[buffer_.index(x0, y)];
      for (int i = 0; i < count; ++i) {
        const double u = (double(row[i]) - near) * inv_range;
        z[i] = !std::isfinite(row[i]) ? 1.0 : signed_depth ? 2.0 * u - 1.0 : u;
      }
    };
    const int k = options_.kernel;
    if (storage == Storage::kFp64) {
      moments_ = filtered_moments<Moments4>(n, k, control, depth_row, [](const Moments4& b) { return b; });
    } else if (storage == Storage::kFp32) {
      moments_fp32_ = filtered_moments<std::array<float, 4>>(n, k, control, depth_row, [](const Moments4& b) {
        return std::array<float, 4>{float(b[0]), float(b[1]), float(b[2]), float(b[3])};
      });
    } else {  // unorm16: q = A b + offset rounded to 16 bits (stored_moments before its inverse transform)
      moments_unorm16_ = filtered_moments<std::array<uint16_t, 4>>(n, k, control, depth_row, [&](const Moments4& b) {
        const Moments4 q = quantization_transform(b, signed_depth);
        std::array<uint16_t, 4> out;
        for (int j = 0; j < 4; ++j) out[j] = uint16_t(std::lround(std::clamp(q[j], 0.0, 1.0) * 65535.0));
        return out;
      });
    }
    std::vector<float>().swap(buffer_.depth);  // moment lookups read the moments only
  }
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double ShadowMap::normalised(double depth) const {
  const double z = (depth - near_) / (far_ - near_);
  return options_.moments.depth_range == DepthRange::kSigned ? 2.0 * z - 1.0 : z;
}

double ShadowMap::depth_at(int x, int y) const {
  const float d = buffer_.depth[buffer_.index(x, y)];
  return std::isfinite(d) ? normalised(d) : 1.0;
}

int ShadowMap::bytes_per_texel() const {
  if (!uses_moments(options_.method)) return 4;
  // What the method reads: four moments, or VSM's two (E[z], E[z^2]; MOMENTS.md 3.2) of the four
  // this map keeps for every moment method (it was reported as 4MSM's, a trial).
  const int moments = options_.method == ShadowMethod::kVsm ? 2 : 4;
  switch (options_.moments.storage) {
    case Storage::kFp64: return 8 * moments;
    case Storage::kFp32: return 4 * moments;
    case Storage::kUnorm16: return 2 * moments;
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
    const double scale = texel / (far_ - near_) * (options_.moments.depth_range == DepthRange::kSigned ? 2.0 : 1.0);
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
  auto bilinear = [&](const auto& map, double unit) {
    for (int k = 0; k < 4; ++k) {
      const int x = x0 + (k & 1), y = y0 + (k >> 1);
      const double w = ((k & 1) ? tx : 1.0 - tx) * ((k >> 1) ? ty : 1.0 - ty) * unit;
      const auto& m = map[size_t(y) * n + x];
      for (int j = 0; j < 4; ++j) b[j] += w * double(m[j]);
    }
  };
  switch (options_.moments.storage) {
    case Storage::kFp64: bilinear(moments_, 1.0); break;
    case Storage::kFp32: bilinear(moments_fp32_, 1.0); break;
    case Storage::kUnorm16:
      bilinear(moments_unorm16_, 1.0 / 65535.0);
      b = inverse_quantization_transform(b, options_.moments.depth_range == DepthRange::kSigned);
      break;
  }
  MomentShadowSettings settings = options_.moments;
  settings.bias = options_.moments.bias_or_published();  // the published value for the storage kept
  settings.storage = Storage::kFp64;                     // already stored at build time
  const MomentShadowMethod method = options_.method == ShadowMethod::kVsm         ? MomentShadowMethod::kVsm
                                    : options_.method == ShadowMethod::kHausdorff ? MomentShadowMethod::kHausdorff
                                                                                  : MomentShadowMethod::kHamburger;
  double s = moment_shadow(b, z, method, settings);
  if (options_.method == ShadowMethod::kVsm && options_.bleeding_reduction > 0.0) {
    const double lit = std::clamp((1.0 - s - options_.bleeding_reduction) / (1.0 - options_.bleeding_reduction), 0.0, 1.0);
    s = 1.0 - lit;
  }
  return std::clamp(s, 0.0, 1.0);
}

}  // namespace refracta
