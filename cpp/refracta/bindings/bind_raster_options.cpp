// Python classes of the raster renderer's options (raster/shadow_map.h, raster/oit.h,
// render/raster_renderer.h): fields under their C++ names, choices as strings, defaults C++'s.
#include "refracta/bindings/bind_raster_options.h"

#include "refracta/bindings/options_binding.h"
#include "refracta/render/raster_renderer.h"

#include <optional>
#include <string>

namespace refracta {

namespace {

// An enum field seen from Python as one of its names (parse raises ValueError listing them).
template <class Class, class Owner, class Enum>
void def_choice(Class& cls, const char* name, Enum Owner::*field, Enum (*parse)(const std::string&),
                const char* (*to_name)(Enum), const char* doc) {
  cls.def_property(
      name, [field, to_name](const Owner& o) { return std::string(to_name(o.*field)); },
      [field, parse](Owner& o, const std::string& v) { o.*field = parse(v); }, doc);
}

// What every options class has: a constructor taking fields as keywords (validated), repr,
// validate() and pickling through the fields.
template <class Options, class Class>
void def_options_common(Class& cls, const char* owner) {
  cls.def(py::init([owner](const py::kwargs& fields) { return options_from<Options>(py::none(), fields, owner); }),
          "The defaults, with any field set by keyword (then validated).")
      .def("__repr__",
           [owner](const py::object& self) { return std::string(owner) + "(" + options_repr(self) + ")"; })
      .def("validate", &Options::validate, "Raises ValueError listing every bad field (nested options included).");
  def_options_pickle<Options>(cls);
}

py::object optional_array(const std::optional<Moments4>& v) {
  if (!v) return py::none();
  return py::make_tuple((*v)[0], (*v)[1], (*v)[2], (*v)[3]);
}

void bind_moment_shadow_settings(py::module_& m) {
  py::class_<MomentShadowSettings> cls(m, "MomentShadowSettings", R"doc(
How a moment shadow map keeps its four power moments and biases them (shared/MOMENTS.md 2-3):
depth_range 'unit' ([0, 1], Peters & Klein I3D 2015) or 'signed' ([-1, 1], Peters et al. JCGT
2017); storage 'fp64', 'fp32' or 'unorm16' (16 bits through the optimised quantisation
transforms); bias (alpha) and bias_vector (b*): None means the published value for the depth
range and storage (published_bias, published_bias_vector).)doc");
  def_options_common<MomentShadowSettings>(cls, "MomentShadowSettings");
  def_choice(cls, "depth_range", &MomentShadowSettings::depth_range, parse_depth_range, depth_range_name,
             "'unit' ([0, 1]) or 'signed' ([-1, 1])");
  def_choice(cls, "storage", &MomentShadowSettings::storage, parse_storage, storage_name,
             "'fp64', 'fp32' or 'unorm16': how a GPU would keep the moments");
  cls.def_readwrite("bias", &MomentShadowSettings::bias,
                    "the weight of bias_vector (Peters & Klein's alpha) in [0, 1); None: published_bias(depth_range, storage)")
      .def_property(
          "bias_vector", [](const MomentShadowSettings& s) { return optional_array(s.bias_vector); },
          [](MomentShadowSettings& s, const py::object& v) {
            if (v.is_none()) {
              s.bias_vector.reset();
              return;
            }
            const std::vector<double> values = to_values(v, "bias_vector");
            if (values.size() != 4) throw_invalid("bias_vector must have 4 entries (got ", values.size(), ")");
            s.bias_vector = Moments4{values[0], values[1], values[2], values[3]};
          },
          "b*, the 4 moments biased toward; None: published_bias_vector(depth_range)")
      .def_static(
          "published_bias",
          [](const std::string& depth_range, const std::string& storage) {
            return MomentShadowSettings::published_bias(parse_depth_range(depth_range), parse_storage(storage));
          },
          py::arg("depth_range"), py::arg("storage"),
          "3e-6 (unit) / 3e-7 (signed) for fp32 and fp64; 3e-5 / 6e-5 for unorm16 (MOMENTS.md 2.5)")
      .def_static(
          "published_bias_vector",
          [](const std::string& depth_range) {
            return optional_array(MomentShadowSettings::published_bias_vector(parse_depth_range(depth_range)));
          },
          py::arg("depth_range"), "(0.5, 0.5, 0.5, 0.5) for unit depths, (0, 0.375, 0, 0.375) for signed ones");
}

void bind_shadow_map_options(py::module_& m) {
  py::class_<ShadowMapOptions> cls(m, "ShadowMapOptions", R"doc(
The shadow maps of render_raster (an orthographic map for the sun, a perspective one per spot light):
method 'hard' (one depth compare), 'pcf' (kernel x kernel compares), 'vsm', 'msm_hamburger',
'msm_hausdorff' (four moments box-filtered kernel x kernel, read through `moments`).)doc");
  def_options_common<ShadowMapOptions>(cls, "ShadowMapOptions");
  def_choice(cls, "method", &ShadowMapOptions::method, parse_shadow_method, shadow_method_name,
             "'hard', 'pcf', 'vsm', 'msm_hamburger' or 'msm_hausdorff'");
  cls.def_readwrite("resolution", &ShadowMapOptions::resolution, "texels per side, in [2, 8192]")
      .def_readwrite("kernel", &ShadowMapOptions::kernel, "k x k filter (odd) of PCF and of the moment map")
      .def_readwrite("depth_bias", &ShadowMapOptions::depth_bias,
                     "hard / pcf: compare against z - depth_bias (normalised depth)")
      .def_readwrite("normal_offset", &ShadowMapOptions::normal_offset,
                     "receivers are moved this many texels along their normal")
      .def_readwrite("bleeding_reduction", &ShadowMapOptions::bleeding_reduction,
                     "VSM light-bleeding reduction (Lauritzen) in [0, 1): less light than this becomes none")
      .def_readwrite("moments", &ShadowMapOptions::moments,
                     "MomentShadowSettings of the moment methods (vsm, msm_*): depth range, storage, bias");
}

void bind_oit_settings(py::module_& m) {
  py::class_<MboitSettings> mboit(m, "MboitSettings", R"doc(
Moment-based order-independent transparency (Muenstermann et al., I3D 2018; MOMENTS.md 4):
basis 'power' (moments 4, 6 or 8) or 'trigonometric' (2, 3 or 4); overestimation beta; bias
None: the published value for the basis, moment count and storage; storage 'fp32' or 'unorm16'
(the 16-bit ROV variant, re-quantised after every fragment); log-depth warp over [z_near, z_far]
[m] (z_far <= z_near: the fragments' own range, in render_raster the frame's).)doc");
  def_options_common<MboitSettings>(mboit, "MboitSettings");
  def_choice(mboit, "basis", &MboitSettings::basis, parse_moment_basis, moment_basis_name,
             "'power' or 'trigonometric'");
  mboit.def_readwrite("moments", &MboitSettings::moments, "4, 6 or 8 power moments; 2, 3 or 4 trigonometric")
      .def_readwrite("beta", &MboitSettings::beta, "overestimation in [0, 1]: the share of a fragment's own layer in front")
      .def_readwrite("bias", &MboitSettings::bias, "the weight of the bias vector in [0, 1), None for the published value (published_bias)")
      .def_readwrite("z_near", &MboitSettings::z_near, "[m] near end of the log-depth warp")
      .def_readwrite("z_far", &MboitSettings::z_far, "[m] far end of the log-depth warp (<= z_near: fitted)")
      .def_static(
          "published_bias",
          [](const std::string& basis, int moments, const std::string& storage) {
            return MboitSettings::published_bias(parse_moment_basis(basis), moments, parse_storage(storage));
          },
          py::arg("basis"), py::arg("moments"), py::arg("storage"),
          "fp32: 5e-7 / 5e-6 / 5e-5 (4 / 6 / 8 power moments); unorm16: 6e-5 / 5e-5 / 5e-4; trigonometric: 4e-4 (2), 2e-4");
  def_choice(mboit, "storage", &MboitSettings::storage, parse_storage, storage_name, "'fp32' or 'unorm16'");

  py::class_<OitSettings> cls(m, "OitSettings", R"doc(
How surfaces with alpha < 1 are composited: method 'exact' (sorted: depth peeling with enough
layers), 'peel' (the `layers` nearest), 'wboit' (McGuire & Bavoil, JCGT 2013, depth weight 'eq7' or
'eq9') or 'mboit' (moment-based, settings in `mboit`).)doc");
  def_options_common<OitSettings>(cls, "OitSettings");
  def_choice(cls, "method", &OitSettings::method, parse_oit_method, oit_method_name, "'exact', 'peel', 'wboit' or 'mboit'");
  cls.def_readwrite("layers", &OitSettings::layers, "peel: layers kept");
  def_choice(cls, "weight", &OitSettings::weight, parse_wboit_weight, wboit_weight_name, "wboit: 'eq7' or 'eq9'");
  cls.def_readwrite("mboit", &OitSettings::mboit, "MboitSettings (method 'mboit')")
      .def("bytes_per_pixel", &OitSettings::bytes_per_pixel, py::arg("fragments_per_pixel"),
           "Bytes per pixel a GPU would keep for this method at this mean fragment count.");
}

void bind_raster_render_options(py::module_& m) {
  py::class_<RasterRenderOptions> cls(m, "RasterRenderOptions", R"doc(
Options of refracta.render_raster, with their defaults (defined once, here). Set any field by
name, nested ones through .shadow_map (ShadowMapOptions) and .transparency (OitSettings or None);
validate() reports every bad value at once.)doc");
  def_options_common<RasterRenderOptions>(cls, "RasterRenderOptions");
  def_choice(cls, "shadows", &RasterRenderOptions::shadows, parse_shadow_source, shadow_source_name,
             "'map' (shadow maps: shadow_map), 'embree' (shadow rays: the reference) or 'none'");
  cls.def_readwrite("shadow_map", &RasterRenderOptions::shadow_map, "ShadowMapOptions of the sun's and spot lights' maps")
      .def_property(
          "shadow_centre",
          [](const RasterRenderOptions& o) -> py::object {
            if (!o.shadow_centre) return py::none();
            return py::make_tuple(o.shadow_centre->x(), o.shadow_centre->y(), o.shadow_centre->z());
          },
          [](RasterRenderOptions& o, const py::object& v) {
            if (v.is_none()) {
              o.shadow_centre.reset();
            } else {
              o.shadow_centre = to_point(v, "shadow_centre");
            }
          },
          "[m] centre of the sun's map; None: fitted to the visible points within shadow_distance")
      .def_readwrite("shadow_half_size", &RasterRenderOptions::shadow_half_size,
                     "[m] half the side of the sun's map; None: fitted to the visible points")
      .def_readwrite("shadow_distance", &RasterRenderOptions::shadow_distance,
                     "[m] the sun's map covers the visible points closer than this to the camera");
  def_choice(cls, "output", &RasterRenderOptions::output, parse_raster_output, raster_output_name,
             "'radiance' (linear RGB) or 'shadow' ((shadow intensity, 1, 0) where shadow_light reaches the surface)");
  cls.def_readwrite("shadow_light", &RasterRenderOptions::shadow_light,
                    "output 'shadow': -1 the sun, k >= 0 the scene's spot light k")
      .def_readwrite("use_sun", &RasterRenderOptions::use_sun, "the scene's sun shines")
      .def_readwrite("spots", &RasterRenderOptions::spots,
                     "indices of the spot lights that shine (in the scene's order of spot lights); None: all")
      .def_property(
          "transparency",
          [](RasterRenderOptions& o) -> OitSettings* { return o.transparency ? &*o.transparency : nullptr; },
          [](RasterRenderOptions& o, const py::object& v) {
            if (v.is_none()) {
              o.transparency.reset();
            } else if (py::isinstance<OitSettings>(v)) {
              o.transparency = py::cast<OitSettings>(v);
            } else {
              throw_invalid("transparency must be an OitSettings or None (got ",
                            py::cast<std::string>(py::type::handle_of(v).attr("__name__")), ")");
            }
          },
          py::return_value_policy::reference_internal,
          "OitSettings compositing surfaces with alpha < 1 over the opaque ones; None: every surface opaque")
      .def_readwrite("tile", &RasterRenderOptions::tile, "tile size [pixels] of the parallel loop")
      .def_readwrite("light_strata", &RasterRenderOptions::light_strata,
                     "stratified samples per axis of each light other than the sun and spots (1 .. 64)");
}

void bind_raster_render_stats(py::module_& m) {
  py::class_<RasterRenderStats>(m, "RasterRenderStats", "What render_raster measured (read-only).")
      .def_readonly("seconds", &RasterRenderStats::seconds, "[s] the whole render")
      .def_readonly("shadow_build_seconds", &RasterRenderStats::shadow_build_seconds,
                    "[s] rasterizing, filtering and storing the shadow maps")
      .def_readonly("bytes_per_texel", &RasterRenderStats::bytes_per_texel, "what the shadow method reads per texel")
      .def_readonly("transparent_fragments", &RasterRenderStats::transparent_fragments,
                    "transparent fragments in front of the opaque surfaces")
      .def_readonly("oit_bytes_per_pixel", &RasterRenderStats::oit_bytes_per_pixel,
                    "what the transparency method keeps per pixel (mean)")
      .def("__repr__", [](const py::object& self) { return "RasterRenderStats(" + options_repr(self) + ")"; })
      .def(py::pickle(
          [](const RasterRenderStats& s) {
            return py::make_tuple(s.seconds, s.shadow_build_seconds, s.bytes_per_texel, s.transparent_fragments,
                                  s.oit_bytes_per_pixel);
          },
          [](const py::tuple& t) {
            RasterRenderStats s;
            s.seconds = t[0].cast<double>(), s.shadow_build_seconds = t[1].cast<double>();
            s.bytes_per_texel = t[2].cast<int>(), s.transparent_fragments = t[3].cast<int64_t>();
            s.oit_bytes_per_pixel = t[4].cast<double>();
            return s;
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
