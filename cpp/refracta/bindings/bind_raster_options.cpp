// Python classes of the raster renderer's options (raster/shadow_map.h, raster/oit.h,
// render/raster_renderer.h): fields under their C++ names, choices as strings, defaults C++'s.
#include "generated/docstrings.h"
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/enum_property.h"
#include "refracta/bindings/options_binding.h"
#include "refracta/render/raster_renderer.h"

#include <optional>
#include <string>
#include <tuple>

namespace refracta {

namespace {

// A fixed-size vector (Moments4, Vec3d) as a tuple, None when unset.
template <class Vector>
py::object optional_tuple(const std::optional<Vector>& v) {
  if (!v) return py::none();
  py::tuple out(v->size());
  for (size_t i = 0; i < size_t(v->size()); ++i) out[i] = (*v)[i];
  return out;
}

void bind_moment_shadow_settings(py::module_& m) {
  using S = MomentShadowSettings;
  py::class_<S> cls(m, "MomentShadowSettings", DOC(refracta, MomentShadowSettings));
  def_options_common<S>(cls, "MomentShadowSettings");
  def_enum_property(cls, "depth_range", &S::depth_range, depth_range_name, parse_depth_range,
                    "'unit' ([0, 1]) or 'signed' ([-1, 1])");
  def_enum_property(cls, "storage", &S::storage, storage_name, parse_storage,
                    "'fp64', 'fp32' or 'unorm16': how a GPU would keep the moments")
      .def_readwrite("bias", &S::bias,
                     "the weight of bias_vector (Peters & Klein's alpha) in [0, 1); None: published_bias(depth_range, storage)")
      .def_property(
          "bias_vector", [](const S& s) { return optional_tuple(s.bias_vector); },
          [](S& s, const py::object& v) {
            const std::vector<double> b = v.is_none() ? std::vector<double>{} : to_values(v, "bias_vector");
            if (!v.is_none() && b.size() != 4) throw_invalid("bias_vector must have 4 entries (got ", b.size(), ")");
            s.bias_vector = v.is_none() ? std::nullopt : std::optional<Moments4>({b[0], b[1], b[2], b[3]});
          },
          "b*, the 4 moments biased toward; None: published_bias_vector(depth_range)")
      .def_static(
          "published_bias",
          [](const std::string& range, const std::string& storage) {
            return S::published_bias(parse_depth_range(range), parse_storage(storage));
          },
          py::arg("depth_range"), py::arg("storage"),
          "3e-6 (unit) / 3e-7 (signed) for fp32 and fp64; 3e-5 / 6e-5 for unorm16 (MOMENTS.md 2.5)")
      .def_static(
          "published_bias_vector",
          [](const std::string& range) {
            return optional_tuple(std::optional(S::published_bias_vector(parse_depth_range(range))));
          },
          py::arg("depth_range"), "(0.5, 0.5, 0.5, 0.5) for unit depths, (0, 0.375, 0, 0.375) for signed ones");
}

void bind_shadow_map_options(py::module_& m) {
  using O = ShadowMapOptions;
  py::class_<O> cls(m, "ShadowMapOptions", DOC(refracta, ShadowMapOptions));
  def_options_common<O>(cls, "ShadowMapOptions");
  def_enum_property(cls, "method", &O::method, shadow_method_name, parse_shadow_method,
                    "'hard', 'pcf', 'vsm', 'msm_hamburger' or 'msm_hausdorff'")
      .def_readwrite("resolution", &O::resolution, "texels per side, in [2, 8192]")
      .def_readwrite("kernel", &O::kernel, "k x k filter (odd) of PCF and of the moment map")
      .def_readwrite("depth_bias", &O::depth_bias, "hard / pcf: compare against z - depth_bias (normalised depth)")
      .def_readwrite("normal_offset", &O::normal_offset, "receivers are moved this many texels along their normal")
      .def_readwrite("bleeding_reduction", &O::bleeding_reduction,
                     "VSM light-bleeding reduction (Lauritzen) in [0, 1): less light than this becomes none")
      .def_readwrite("moments", &O::moments,
                     "MomentShadowSettings of the moment methods (vsm, msm_*): depth range, storage, bias");
}

void bind_oit_settings(py::module_& m) {
  using M = MboitSettings;
  py::class_<M> mboit(m, "MboitSettings", DOC(refracta, MboitSettings));
  def_options_common<M>(mboit, "MboitSettings");
  def_enum_property(mboit, "basis", &M::basis, moment_basis_name, parse_moment_basis, "'power' or 'trigonometric'")
      .def_readwrite("moments", &M::moments, "4, 6 or 8 power moments; 2, 3 or 4 trigonometric")
      .def_readwrite("beta", &M::beta, "overestimation in [0, 1]: the share of a fragment's own layer in front")
      .def_readwrite("bias", &M::bias, "the weight of the bias vector in [0, 1), None for the published value (published_bias)")
      .def_readwrite("z_near", &M::z_near, "[m] near end of the log-depth warp")
      .def_readwrite("z_far", &M::z_far, "[m] far end of the log-depth warp (<= z_near: fitted)")
      .def_static(
          "published_bias",
          [](const std::string& basis, int moments, const std::string& storage) {
            return M::published_bias(parse_moment_basis(basis), moments, parse_storage(storage));
          },
          py::arg("basis"), py::arg("moments"), py::arg("storage"),
          "fp32: 5e-7 / 5e-6 / 5e-5 (4 / 6 / 8 power moments); unorm16: 6e-5 / 5e-5 / 5e-4; trigonometric: 4e-4 (2), 2e-4");
  def_enum_property(mboit, "storage", &M::storage, storage_name, parse_storage, "'fp32' or 'unorm16'");

  using O = OitSettings;
  py::class_<O> cls(m, "OitSettings", DOC(refracta, OitSettings));
  def_options_common<O>(cls, "OitSettings");
  def_enum_property(cls, "method", &O::method, oit_method_name, parse_oit_method, "'exact', 'peel', 'wboit' or 'mboit'")
      .def_readwrite("layers", &O::layers, "peel: layers kept");
  def_enum_property(cls, "weight", &O::weight, wboit_weight_name, parse_wboit_weight, "wboit: 'eq7' or 'eq9'")
      .def_readwrite("mboit", &O::mboit, "MboitSettings (method 'mboit')")
      .def("bytes_per_pixel", &O::bytes_per_pixel, py::arg("fragments_per_pixel"),
           "Bytes per pixel a GPU would keep for this method at this mean fragment count.");
}

void bind_raster_render_options(py::module_& m) {
  using O = RasterRenderOptions;
  py::class_<O> cls(m, "RasterRenderOptions", DOC(refracta, RasterRenderOptions));
  def_options_common<O>(cls, "RasterRenderOptions");
  def_enum_property(cls, "shadows", &O::shadows, shadow_source_name, parse_shadow_source,
                    "'map' (shadow maps: shadow_map), 'embree' (shadow rays: the reference) or 'none'")
      .def_readwrite("shadow_map", &O::shadow_map, "ShadowMapOptions of the sun's and spot lights' maps")
      .def_property(
          "shadow_centre", [](const O& o) { return optional_tuple(o.shadow_centre); },
          [](O& o, const py::object& v) {
            o.shadow_centre = v.is_none() ? std::nullopt : std::optional<Vec3d>(to_point(v, "shadow_centre"));
          },
          "[m] centre of the sun's map; None: fitted to the visible points within shadow_distance")
      .def_readwrite("shadow_half_size", &O::shadow_half_size,
                     "[m] half the side of the sun's map; None: fitted to the visible points")
      .def_readwrite("shadow_distance", &O::shadow_distance,
                     "[m] the sun's map covers the visible points closer than this to the camera");
  def_enum_property(cls, "output", &O::output, raster_output_name, parse_raster_output,
                    "'radiance' (linear RGB) or 'shadow' ((shadow intensity, 1, 0) where shadow_light reaches the surface)")
      .def_readwrite("shadow_light", &O::shadow_light, "output 'shadow': -1 the sun, k >= 0 the scene's spot light k")
      .def_readwrite("use_sun", &O::use_sun, "the scene's sun shines")
      .def_readwrite("spots", &O::spots,
                     "indices of the spot lights that shine (in the scene's order of spot lights); None: all")
      .def_property(
          "transparency", [](O& o) -> OitSettings* { return o.transparency ? &*o.transparency : nullptr; },
          [](O& o, const py::object& v) {
            if (!v.is_none() && !py::isinstance<OitSettings>(v)) {
              throw_invalid("transparency must be an OitSettings or None (got ",
                            py::cast<std::string>(py::type::handle_of(v).attr("__name__")), ")");
            }
            o.transparency = v.is_none() ? std::nullopt : std::optional<OitSettings>(py::cast<OitSettings>(v));
          },
          py::return_value_policy::reference_internal,
          "OitSettings compositing surfaces with alpha < 1 over the opaque ones; None: every surface opaque")
      .def_readwrite("tile", &O::tile, "tile size [pixels] of the parallel loop")
      .def_readwrite("light_strata", &O::light_strata,
                     "stratified samples per axis of each light other than the sun and spots (1 .. 64)");
}

void bind_raster_render_stats(py::module_& m) {
  using S = RasterRenderStats;
  py::class_<S>(m, "RasterRenderStats", DOC(refracta, RasterRenderStats))
      .def_readonly("seconds", &S::seconds, "[s] the whole render")
      .def_readonly("shadow_build_seconds", &S::shadow_build_seconds,
                    "[s] rasterizing, filtering and storing the shadow maps")
      .def_readonly("bytes_per_texel", &S::bytes_per_texel, "what the shadow method reads per texel")
      .def_readonly("transparent_fragments", &S::transparent_fragments,
                    "transparent fragments in front of the opaque surfaces")
      .def_readonly("oit_bytes_per_pixel", &S::oit_bytes_per_pixel,
                    "what the transparency method keeps per pixel (mean)")
      .def("__repr__", [](const py::object& self) { return "RasterRenderStats(" + options_repr(self) + ")"; })
      .def(py::pickle(
          [](const S& s) {
            return std::make_tuple(s.seconds, s.shadow_build_seconds, s.bytes_per_texel, s.transparent_fragments,
                                   s.oit_bytes_per_pixel);
          },
          [](const std::tuple<double, double, int, int64_t, double>& t) {
            return S{std::get<0>(t), std::get<1>(t), std::get<2>(t), std::get<3>(t), std::get<4>(t)};
          }));
}

}  // namespace

void bind_raster_options(py::module_& m) {
  bind_moment_shadow_settings(m);
  bind_shadow_map_options(m);
  bind_oit_settings(m);
  bind_raster_render_options(m);
  bind_raster_render_stats(m);
}

}  // namespace refracta
