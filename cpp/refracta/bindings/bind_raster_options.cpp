// Python classes of the raster renderer's options (raster/shadow_map.h, raster/oit.h,
// render/raster_renderer.h): fields under their C++ names, choices as strings, defaults C++'s.
#include "generated/docstrings.h"
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/enum_property.h"
#include "refracta/bindings/options_binding.h"
#include "refracta/render/raster_renderer.h"

#include <optional>
#include <string>

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
      .def_readwrite("bias", &S::bias, DOC(refracta, MomentShadowSettings, bias))
      .def_property(
          "bias_vector", [](const S& s) { return optional_tuple(s.bias_vector); },
          [](S& s, const py::object& v) {
            const std::vector<double> b = v.is_none() ? std::vector<double>{} : to_values(v, "bias_vector");
            if (!v.is_none() && b.size() != 4) throw_invalid("bias_vector must have 4 entries (got ", b.size(), ")");
            s.bias_vector = v.is_none() ? std::nullopt : std::optional<Moments4>({b[0], b[1], b[2], b[3]});
          },
          DOC(refracta, MomentShadowSettings, bias_vector))
      .def_static(
          "published_bias",
          [](const std::string& range, const std::string& storage) {
            return S::published_bias(parse_depth_range(range), parse_storage(storage));
          },
          py::arg("depth_range"), py::arg("storage"), DOC(refracta, MomentShadowSettings, published_bias))
      .def_static(
          "published_bias_vector",
          [](const std::string& range, const std::string& storage) {
            return optional_tuple(std::optional(S::published_bias_vector(parse_depth_range(range), parse_storage(storage))));
          },
          py::arg("depth_range"), py::arg("storage") = storage_name(S{}.storage),
          DOC(refracta, MomentShadowSettings, published_bias_vector));
}

void bind_shadow_map_options(py::module_& m) {
  using O = ShadowMapOptions;
  py::class_<O> cls(m, "ShadowMapOptions", DOC(refracta, ShadowMapOptions));
  def_options_common<O>(cls, "ShadowMapOptions");
  def_enum_property(cls, "method", &O::method, shadow_method_name, parse_shadow_method,
                    "'hard', 'pcf', 'vsm', 'msm_hamburger' or 'msm_hausdorff'")
      .def_readwrite("resolution", &O::resolution, DOC(refracta, ShadowMapOptions, resolution))
      .def_readwrite("kernel", &O::kernel, DOC(refracta, ShadowMapOptions, kernel))
      .def_readwrite("depth_bias", &O::depth_bias, DOC(refracta, ShadowMapOptions, depth_bias))
      .def_readwrite("normal_offset", &O::normal_offset, DOC(refracta, ShadowMapOptions, normal_offset))
      .def_readwrite("bleeding_reduction", &O::bleeding_reduction, DOC(refracta, ShadowMapOptions, bleeding_reduction))
      .def_readwrite("moments", &O::moments, DOC(refracta, ShadowMapOptions, moments));
}

void bind_oit_settings(py::module_& m) {
  using M = MboitSettings;
  py::class_<M> mboit(m, "MboitSettings", DOC(refracta, MboitSettings));
  def_options_common<M>(mboit, "MboitSettings");
  def_enum_property(mboit, "basis", &M::basis, moment_basis_name, parse_moment_basis, "'power' or 'trigonometric'")
      .def_readwrite("moments", &M::moments, DOC(refracta, MboitSettings, moments))
      .def_readwrite("beta", &M::beta, DOC(refracta, MboitSettings, beta))
      .def_readwrite("bias", &M::bias, DOC(refracta, MboitSettings, bias))
      .def_readwrite("z_near", &M::z_near, DOC(refracta, MboitSettings, z_near))
      .def_readwrite("z_far", &M::z_far, DOC(refracta, MboitSettings, z_far))
      .def_static(
          "published_bias",
          [](const std::string& basis, int moments, const std::string& storage) {
            return M::published_bias(parse_moment_basis(basis), moments, parse_storage(storage));
          },
          py::arg("basis"), py::arg("moments"), py::arg("storage"), DOC(refracta, MboitSettings, published_bias));
  def_enum_property(mboit, "storage", &M::storage, storage_name, parse_storage,
                    "'fp32', 'unorm16' (a GPU's storage) or 'fp64' (the method itself)");

  using O = OitSettings;
  py::class_<O> cls(m, "OitSettings", DOC(refracta, OitSettings));
  def_options_common<O>(cls, "OitSettings");
  def_enum_property(cls, "method", &O::method, oit_method_name, parse_oit_method, "'exact', 'peel', 'wboit' or 'mboit'")
      .def_readwrite("layers", &O::layers, DOC(refracta, OitSettings, layers));
  def_enum_property(cls, "weight", &O::weight, wboit_weight_name, parse_wboit_weight, "wboit: 'eq7' or 'eq9'")
      .def_readwrite("mboit", &O::mboit, DOC(refracta, OitSettings, mboit))
      .def("bytes_per_pixel", &O::bytes_per_pixel, py::arg("fragments_per_pixel"), DOC(refracta, OitSettings, bytes_per_pixel));
}

void bind_raster_render_options(py::module_& m) {
  using O = RasterRenderOptions;
  py::class_<O> cls(m, "RasterRenderOptions", DOC(refracta, RasterRenderOptions));
  def_options_common<O>(cls, "RasterRenderOptions");
  def_enum_property(cls, "shadows", &O::shadows, shadow_source_name, parse_shadow_source,
                    "'map' (shadow maps: shadow_map), 'embree' (shadow rays: the reference) or 'none'")
      .def_readwrite("shadow_map", &O::shadow_map, DOC(refracta, RasterRenderOptions, shadow_map))
      .def_property(
          "shadow_centre", [](const O& o) { return optional_tuple(o.shadow_centre); },
          [](O& o, const py::object& v) {
            o.shadow_centre = v.is_none() ? std::nullopt : std::optional<Vec3d>(to_point(v, "shadow_centre"));
          },
          DOC(refracta, RasterRenderOptions, shadow_centre))
      .def_readwrite("shadow_half_size", &O::shadow_half_size, DOC(refracta, RasterRenderOptions, shadow_half_size))
      .def_readwrite("shadow_distance", &O::shadow_distance, DOC(refracta, RasterRenderOptions, shadow_distance));
  def_enum_property(cls, "output", &O::output, raster_output_name, parse_raster_output,
                    "'radiance' (linear RGB) or 'shadow' ((shadow intensity, 1, 0) where shadow_light reaches the surface)")
      .def_readwrite("shadow_light", &O::shadow_light, DOC(refracta, RasterRenderOptions, shadow_light))
      .def_readwrite("use_sun", &O::use_sun, DOC(refracta, RasterRenderOptions, use_sun))
      .def_readwrite("spots", &O::spots, DOC(refracta, RasterRenderOptions, spots))
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
          DOC(refracta, RasterRenderOptions, transparency))
      .def_readwrite("tile", &O::tile, DOC(refracta, RasterRenderOptions, tile))
      .def_readwrite("light_strata", &O::light_strata, DOC(refracta, RasterRenderOptions, light_strata));
}

void bind_raster_render_stats(py::module_& m) {
  using S = RasterRenderStats;
  py::class_<S> cls(m, "RasterRenderStats", DOC(refracta, RasterRenderStats));
  cls
      .def_readonly("seconds", &S::seconds, DOC(refracta, RasterRenderStats, seconds))
      .def_readonly("shadow_build_seconds", &S::shadow_build_seconds, DOC(refracta, RasterRenderStats, shadow_build_seconds))
      .def_readonly("bytes_per_texel", &S::bytes_per_texel, DOC(refracta, RasterRenderStats, bytes_per_texel))
      .def_readonly("transparent_fragments", &S::transparent_fragments, DOC(refracta, RasterRenderStats, transparent_fragments))
      .def_readonly("oit_bytes_per_pixel", &S::oit_bytes_per_pixel, DOC(refracta, RasterRenderStats, oit_bytes_per_pixel))
      .def("__repr__", [](const py::object& self) { return "RasterRenderStats(" + options_repr(self) + ")"; });
  def_options_eq(cls);
  def_fields_pickle(cls, &S::seconds, &S::shadow_build_seconds, &S::bytes_per_texel, &S::transparent_fragments,
                    &S::oit_bytes_per_pixel);
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
