// Python bindings of the BSDF library (shading/): the Material base and one class per material,
// vectorised evaluation (f, pdf, sample) in the local shading frame, Fresnel functions, the GGX
// distribution and indices of refraction. Conventions: shared/SHADING.md section 0.
#include "refracta/bindings/bindings.h"
#include "refracta/shading/beckmann.h"
#include "refracta/shading/conductor.h"
#include "refracta/shading/dielectric.h"
#include "refracta/shading/diffuse.h"
#include "refracta/shading/fresnel.h"
#include "refracta/shading/ior.h"
#include "refracta/shading/microfacet.h"
#include "refracta/shading/phong.h"
#include "refracta/shading/plastic.h"
#include "refracta/shading/principled.h"
#include "refracta/shading/thin_film.h"
#include "refracta/shading/water.h"
#include "refracta/shading/water_surface.h"

#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <optional>

namespace refracta {

namespace {

// Directions must be unit to this tolerance (float64 normalisation gives ~1e-16).
constexpr double kUnitTolerance = 1e-6;

Vec3d to_rgb(const py::handle& value, const char* name) {
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) return Vec3d::Constant(value.cast<double>());
  DoubleArray a;
  try {
    a = real_array(value, name);
  } catch (const py::cast_error&) {
    throw_invalid(name, " must be a number or an (r, g, b) triple");
  }
  if (a.ndim() == 0) return Vec3d::Constant(a.data()[0]);
  if (a.ndim() != 1 || a.shape(0) != 3) throw_invalid(name, " must be a number or an (r, g, b) triple (got ", a.size(), " values)");
  return Vec3d(a.data()[0], a.data()[1], a.data()[2]);
}

std::optional<Vec3d> to_optional_rgb(const py::object& value, const char* name) {
  if (value.is_none()) return std::nullopt;
  return to_rgb(value, name);
}

// A colour with its texture= argument (material_util.h's TexturedReflectance): None; an image
// file (str or os.PathLike), made absolute from the working directory and registered in each
// scene the material is added to; or the id of a texture a scene already holds.
TexturedReflectance to_textured(const py::object& color, const char* name, const py::object& texture) {
  const Vec3d rgb = to_rgb(color, name);
  if (texture.is_none()) return TexturedReflectance(rgb, name);
  if (py::isinstance<py::str>(texture) || py::hasattr(texture, "__fspath__")) {
    const py::object path_object = py::module_::import("os").attr("fspath")(texture);
    if (!py::isinstance<py::str>(path_object)) throw_invalid("texture must be a str path (got bytes)");
    const std::string path = py::cast<std::string>(path_object);
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) throw IoError(concat("no such texture file: '", path, "'"));
    return TexturedReflectance(rgb, name, -1, std::filesystem::absolute(path).string());
  }
  if (py::isinstance<py::int_>(texture) && !py::isinstance<py::bool_>(texture)) {
    const int id = texture.cast<int>();
    if (id < 0) throw_invalid("texture must be an image file, a scene texture id >= 0 or None (got ", id, ")");
    return TexturedReflectance(rgb, name, id);
  }
  throw_invalid("texture must be an image file path (str or os.PathLike), a scene texture id >= 0 or None (got ",
                std::string(py::str(py::type::of(texture).attr("__name__"))), ")");
}

Ior to_ior(const py::object& ior, const py::object& sellmeier) {
  if (!sellmeier.is_none()) {
    const std::vector<double> c = sellmeier.cast<std::vector<double>>();
    if (c.size() != 6) throw_invalid("sellmeier must be (B1, B2, B3, C1, C2, C3) with C in um^2 (got ", c.size(), " values)");
    return Ior::sellmeier({c[0], c[1], c[2]}, {c[3], c[4], c[5]});
  }
  if (py::isinstance<py::str>(ior)) {
    const std::string name = ior.cast<std::string>();
    if (name == "bk7" || name == "BK7") return Ior::bk7();
    throw_invalid("ior must be a number, 'bk7' or given by sellmeier= (got '", name, "')");
  }
  return Ior(ior.cast<double>());
}

// (alpha) or (alpha_u, alpha_v): exactly one form.
std::pair<double, double> to_alphas(const py::object& alpha, const py::object& alpha_u, const py::object& alpha_v, bool required,
                                    double fallback) {
  const bool has_alpha = !alpha.is_none(), has_uv = !alpha_u.is_none() || !alpha_v.is_none();
  if (has_alpha && has_uv) throw_invalid("give either alpha or alpha_u and alpha_v, not both");
  if (has_uv) {
    if (alpha_u.is_none() || alpha_v.is_none()) throw_invalid("alpha_u and alpha_v must be given together");
    return {alpha_u.cast<double>(), alpha_v.cast<double>()};
  }
  if (!has_alpha) {
    if (required) throw_invalid("alpha (or alpha_u and alpha_v) is required");
    return {fallback, fallback};
  }
  const double a = alpha.cast<double>();
  return {a, a};
}

std::vector<Vec3d> to_directions(const py::handle& object, const char* name) {
  std::vector<Vec3d> w = to_points(object, name);
  for (size_t i = 0; i < w.size(); ++i) {
    if (!(std::abs(w[i].norm() - 1.0) <= kUnitTolerance)) {
      throw_invalid(name, "[", i, "] must be a unit vector (got norm ", w[i].norm(), ")");
    }
  }
  return w;
}

TransportMode to_mode(const std::string& mode) {
  if (mode == "radiance") return TransportMode::kRadiance;
  if (mode == "importance") return TransportMode::kImportance;
  throw_invalid("mode must be 'radiance' or 'importance' (got '", mode, "')");
}

// Wavelengths per row: None (RGB), (4,) or (N, 4) [nm] in [kLambdaMin, kLambdaMax].
struct Wavelengths {
  std::vector<SampledWavelengths> rows;  // empty: RGB
  bool spectral() const { return !rows.empty(); }
  SampledWavelengths at(size_t i) const {
    if (rows.empty()) return SampledWavelengths::rgb();
    return rows.size() == 1 ? rows[0] : rows[i];
  }
};

Wavelengths to_wavelengths(const py::object& object, size_t n) {
  Wavelengths w;
  if (object.is_none()) return w;
  DoubleArray a = real_array(object, "wavelengths");
  const bool one = a.ndim() == 1 && a.shape(0) == 4;
  if (!(one || (a.ndim() == 2 && a.shape(1) == 4 && size_t(a.shape(0)) == n))) {
    throw_invalid("wavelengths must have shape (4,) or (N, 4) with N = ", n, " [nm]");
  }
  const size_t rows = one ? 1 : n;
  for (size_t i = 0; i < rows; ++i) {
    SampledWavelengths s;
    s.spectral = true;
    for (int j = 0; j < 4; ++j) {
      const double l = a.data()[4 * i + j];
      if (!(l >= kLambdaMin && l <= kLambdaMax)) throw_invalid("wavelengths must be in [", kLambdaMin, ", ", kLambdaMax, "] nm (got ", l, ")");
      s.lambda[j] = l;
    }
    s.pdf.setConstant(1.0 / (kLambdaMax - kLambdaMin));
    w.rows.push_back(s);
  }
  return w;
}

size_t broadcast(size_t a, size_t b, const char* what) {
  if (a == b || b == 1) return a;
  if (a == 1) return b;
  throw_invalid(what, ": row counts differ (", a, " and ", b, ")");
}

// Builds the BSDF at a neutral surface point (no textures: constant colours) for one row.
class Evaluator {
 public:
  Evaluator(const Material& material, double eta_outside) : material_(material), eta_outside_(eta_outside) {
    if (!std::isfinite(eta_outside) || eta_outside <= 0.0) throw_invalid("eta_outside must be finite and > 0 (got ", eta_outside, ")");
  }
  const Bsdf* build(SampledWavelengths* lambda) {
    scratch_.reset();
    MaterialContext context;
    context.lambda = lambda;
    context.eta_outside = eta_outside_;
    return material_.bsdf(si_, context, scratch_);
  }

 private:
  const Material& material_;
  double eta_outside_;
  SurfaceInteraction si_;
  ScratchBuffer scratch_;
};

DoubleArray spectra_array(const std::vector<Spectrum>& values, int channels) {
  DoubleArray out({py::ssize_t(values.size()), py::ssize_t(channels)});
  double* d = out.mutable_data();
  for (size_t i = 0; i < values.size(); ++i) {
    for (int c = 0; c < channels; ++c) d[channels * i + c] = values[i][c];
  }
  return out;
}

template <class Fn>
void for_rows(const Material& material, double eta_outside, const Wavelengths& wavelengths, size_t n, Fn&& fn) {
  Evaluator evaluator(material, eta_outside);
  SampledWavelengths lambda = wavelengths.at(0);
  const Bsdf* bsdf = evaluator.build(&lambda);
  for (size_t i = 0; i < n; ++i) {
    if (wavelengths.spectral() && (i > 0)) {  // spectral: fresh wavelengths (a dielectric may terminate them)
      lambda = wavelengths.at(i);
      bsdf = evaluator.build(&lambda);
    }
    fn(i, bsdf, lambda);
  }
}

// Evaluates value(bsdf, wo, wi, mode) for every (wo, wi) row (one side may be a single
// direction, broadcast) into *out; returns whether the evaluation was spectral.
template <class T, class Value>
bool for_pairs(const Material& material, const py::object& wo_in, const py::object& wi_in, const py::object& wavelengths,
               double eta_outside, const std::string& mode, std::vector<T>* out, Value&& value) {
  const auto wo = to_directions(wo_in, "wo"), wi = to_directions(wi_in, "wi");
  const size_t n = broadcast(wo.size(), wi.size(), "wo and wi");
  const Wavelengths w = to_wavelengths(wavelengths, n);
  const TransportMode tm = to_mode(mode);
  out->resize(n);
  for_rows(material, eta_outside, w, n, [&](size_t i, const Bsdf* bsdf, const SampledWavelengths&) {
    (*out)[i] = value(bsdf, wo[wo.size() == 1 ? 0 : i], wi[wi.size() == 1 ? 0 : i], tm);
  });
  return w.spectral();
}

// Pickling and `parameters` of a material: its constructor's keyword arguments, read back from
// the C++ object; unpickling calls the Python constructor with them (its checks included).
py::tuple rgb_tuple(const Vec3d& v) { return py::make_tuple(v.x(), v.y(), v.z()); }
py::object optional_rgb_tuple(const std::optional<Vec3d>& v) { return v ? py::object(rgb_tuple(*v)) : py::object(py::none()); }
py::object texture_argument(const TexturedReflectance& r) {
  if (!r.path().empty()) return py::str(r.path());
  return r.texture() >= 0 ? py::object(py::int_(r.texture())) : py::object(py::none());
}

// ior= or sellmeier= as the constructors take them.
void add_ior_arguments(py::dict& kwargs, const Ior& ior) {
  if (ior.dispersive()) {
    const auto& b = ior.sellmeier_b();
    const auto& c = ior.sellmeier_c();
    kwargs["sellmeier"] = py::make_tuple(b[0], b[1], b[2], c[0], c[1], c[2]);
  } else {
    kwargs["ior"] = ior.rgb_value();
  }
}

template <class T, class Class>
void add_parameters(Class& cls, py::dict (*parameters)(const T&)) {
  cls.def_property_readonly("parameters", parameters,
                            "The constructor's keyword arguments that rebuild this material (pickling uses them).");
  cls.def(py::pickle(parameters, [](const py::dict& kwargs) { return py::cast<std::shared_ptr<T>>(py::type::of<T>()(**kwargs)); }));
}

// The texture= argument of the materials with a textured reflectance.
#define TEXTURE_DOC                                                                                          \
  "texture: an image file (str or os.PathLike;\n"                                                          \
  "any format OpenImageIO reads, 8/16-bit files decoded from sRGB) whose linear RGB, clamped to [0, 1],\n"  \
  "multiplies the colour at the surface's uvs (OBJ texcoords, add_mesh(uvs=), add_ground's repeat);\n"     \
  "relative paths are from the working directory when the material is made. Each scene the material\n"    \
  "is added to registers the file (prepared once into the texture cache). An int is the id of a\n"       \
  "texture the scene already holds. f/pdf/sample evaluate the untextured colour."

const char* kEvalDoc =
    "wo, wi: unit directions in the local shading frame (z = shading normal), shape (N, 3) or (3,)\n"
    "(one side may be a single direction, broadcast), wo toward the viewer, wi toward the light.\n"
    "wavelengths: None for RGB rendering, or (4,) / (N, 4) hero wavelengths [nm] for spectral.\n"
    "eta_outside: index of the medium on the normal's side; mode: 'radiance' or 'importance'.";

}  // namespace

void bind_shading(py::module_& m) {
  py::class_<Material, std::shared_ptr<Material>>(m, "Material",
                                                 "A surface material (shading/material.h): builds a BSDF at a hit. Evaluate it in\n"
                                                 "the local shading frame with f, pdf and sample (shared/SHADING.md section 0).")
      .def(
          "f",
          [](const Material& material, const py::object& wo, const py::object& wi, const py::object& wavelengths,
             double eta_outside, const std::string& mode) {
            std::vector<Spectrum> out;
            const bool spectral = for_pairs(material, wo, wi, wavelengths, eta_outside, mode, &out,
                                            [](const Bsdf* bsdf, const Vec3d& o, const Vec3d& i, TransportMode tm) {
                                              return bsdf ? bsdf->f(o, i, tm) : Spectrum::Zero().eval();
                                            });
            return spectra_array(out, spectral ? 4 : 3);
          },
          py::arg("wo"), py::arg("wi"), py::arg("wavelengths") = py::none(), py::arg("eta_outside") = 1.0,
          py::arg("mode") = "radiance",
          (std::string("The BSDF value f(wo, wi) without the cosine [1/sr]: (N, 3) linear RGB, or (N, 4) per\n"
                       "wavelength. Delta lobes give 0.\n") + kEvalDoc).c_str())
      .def(
          "pdf",
          [](const Material& material, const py::object& wo, const py::object& wi, const py::object& wavelengths,
             double eta_outside, const std::string& mode) {
            std::vector<double> out;
            for_pairs(material, wo, wi, wavelengths, eta_outside, mode, &out,
                      [](const Bsdf* bsdf, const Vec3d& o, const Vec3d& i, TransportMode tm) {
                        return bsdf ? bsdf->pdf(o, i, tm) : 0.0;
                      });
            return values_to_array(out);
          },
          py::arg("wo"), py::arg("wi"), py::arg("wavelengths") = py::none(), py::arg("eta_outside") = 1.0,
          py::arg("mode") = "radiance",
          (std::string("Density [1/sr] with which sample(wo, u) produces wi: (N,). It includes the lobe\n"
                       "selection probabilities; delta lobes contribute 0.\n") + kEvalDoc).c_str())
      .def(
          "sample",
          [](const Material& material, const py::object& wo_in, const py::object& u_in, const py::object& wavelengths,
             double eta_outside, const std::string& mode) {
            const auto wo = to_directions(wo_in, "wo");
            DoubleArray u = real_array(u_in, "u");
            if (!(u.ndim() == 2 && u.shape(1) == 3) && !(u.ndim() == 1 && u.shape(0) == 3)) throw_invalid("u must have shape (N, 3) or (3,)");
            const size_t nu = u.ndim() == 1 ? 1 : size_t(u.shape(0));
            for (py::ssize_t i = 0; i < u.size(); ++i) {
              if (!(u.data()[i] >= 0.0 && u.data()[i] <= 1.0)) throw_invalid("u must be in [0, 1] (got ", u.data()[i], ")");
            }
            const size_t n = broadcast(wo.size(), nu, "wo and u");
            const Wavelengths w = to_wavelengths(wavelengths, n);
            const TransportMode tm = to_mode(mode);
            std::vector<Vec3d> wi(n, Vec3d::Zero());
            std::vector<Spectrum> weight(n, Spectrum::Zero()), f(n, Spectrum::Zero());
            const std::vector<py::ssize_t> shape{py::ssize_t(n)};
            py::array_t<double> pdf(shape), eta(shape);
            py::array_t<unsigned> flags(shape);
            py::array_t<bool> is_delta(shape), valid(shape), terminated(shape);
            auto P = pdf.mutable_unchecked<1>(), E = eta.mutable_unchecked<1>();
            auto F = flags.mutable_unchecked<1>();
            auto D = is_delta.mutable_unchecked<1>(), V = valid.mutable_unchecked<1>(), T = terminated.mutable_unchecked<1>();
            Evaluator evaluator(material, eta_outside);
            for (size_t i = 0; i < n; ++i) {  // fresh wavelengths per sample: a dielectric may terminate them
              SampledWavelengths lambda = w.at(i);
              const Bsdf* bsdf = evaluator.build(&lambda);
              const double* ui = u.data() + 3 * (nu == 1 ? 0 : i);
              std::optional<BsdfSample> s;
              const Vec3d& o = wo[wo.size() == 1 ? 0 : i];
              if (bsdf && o.z() != 0.0) s = bsdf->sample(o, std::min(ui[0], 1.0 - 1e-16), Vec2d(std::min(ui[1], 1.0 - 1e-16), std::min(ui[2], 1.0 - 1e-16)), tm);
              const bool ok = s && s->pdf > 0.0 && s->weight.maxCoeff() > 0.0;
              V(i) = ok;
              P(i) = ok ? s->pdf : 0.0;
              E(i) = ok ? s->eta : 1.0;
              F(i) = ok ? s->flags : 0u;
              D(i) = ok && s->is_specular();
              T(i) = lambda.secondary_terminated();
              if (ok) wi[i] = s->wi, weight[i] = s->weight, f[i] = s->f;
            }
            const int channels = w.spectral() ? 4 : 3;
            py::dict out;
            out["wi"] = points_to_array(wi);
            out["weight"] = spectra_array(weight, channels);
            out["f"] = spectra_array(f, channels);
            out["pdf"] = pdf;
            out["flags"] = flags;
            out["is_delta"] = is_delta;
            out["eta"] = eta;
            out["valid"] = valid;
            out["terminated"] = terminated;
            return out;
          },
          py::arg("wo"), py::arg("u"), py::arg("wavelengths") = py::none(), py::arg("eta_outside") = 1.0,
          py::arg("mode") = "radiance",
          "Sample incident directions for wo (N, 3) from uniform numbers u (N, 3) in [0, 1): u[:, 0] picks\n"
          "the lobe, u[:, 1:] the direction. Returns a dict of arrays: wi (N, 3) (0 where invalid),\n"
          "weight (N, C) = ``f |cos theta_i| / pdf`` (delta lobes: the lobe's albedo over its probability),\n"
          "f (N, C), pdf (N,) (delta lobes: the lobe's selection probability), flags (N,) uint32\n"
          "(1 reflection, 2 transmission, 4 diffuse, 8 glossy, 16 specular/delta), is_delta (N,),\n"
          "eta (N,) the relative index crossed (1 for reflection), valid (N,) False where no direction\n"
          "was produced, terminated (N,) True where a dispersive refraction kept the hero wavelength\n"
          "only. C = 3 (RGB) or 4 (spectral). Other arguments as for f.")
      .def("describe", &Material::describe)
      .def("__repr__", &Material::describe)
      .def_property_readonly("priority", &Material::priority, "Nested-dielectric priority (larger wins).")
      .def_property_readonly("alpha", &Material::alpha, "Opacity for raster transparency, in [0, 1].")
      .def(
          "interior_ior",
          [](const Material& material, std::optional<double> wavelength) {
            SampledWavelengths l = SampledWavelengths::rgb();
            if (wavelength) {
              if (!(*wavelength >= kLambdaMin && *wavelength <= kLambdaMax)) {
                throw_invalid("interior_ior: wavelength must be in [", kLambdaMin, ", ", kLambdaMax, "] nm (got ", *wavelength, ")");
              }
              l = SampledWavelengths::sample_uniform(0.0);
              l.lambda[0] = *wavelength;
            }
            return material.interior_ior(l);
          },
          py::arg("wavelength") = py::none(),
          "Index of refraction of the medium a dielectric bounds, at the given wavelength [nm] (None: RGB\n"
          "rendering's 550 nm), or None for materials that bound no medium.");

  py::class_<Diffuse, Material, std::shared_ptr<Diffuse>> diffuse_class(m, "Diffuse",
                                                        "Lambertian reflection f = R / pi (two-sided). reflectance: a number or (r, g, b)\n"
                                                        "in [0, 1] (> 1 is refused: it would create energy). " TEXTURE_DOC);
  diffuse_class
      .def(py::init([](const py::object& reflectance, const py::object& texture) {
             return std::make_shared<Diffuse>(to_textured(reflectance, "reflectance", texture));
           }),
           py::arg("reflectance") = 0.5, py::arg("texture") = py::none());
  add_parameters<Diffuse>(diffuse_class, [](const Diffuse& m) {
    return py::dict(py::arg("reflectance") = rgb_tuple(m.reflectance().rgb()), py::arg("texture") = texture_argument(m.reflectance()));
  });

  py::class_<BlinnPhong, Material, std::shared_ptr<BlinnPhong>> blinn_phong_class(
      m, "BlinnPhong",
      "Normalised Blinn-Phong: f = kd / pi + ks (ns + 8) / (8 pi) (n.h)^ns (the MTL model). kd, ks in [0, 1]\n"
      "(numbers or (r, g, b)), ns >= 0; alpha in [0, 1] is the raster opacity (MTL d). Sampled by a\n"
      "mixture of the cosine hemisphere and the (n.h)^ns lobe; pdf exact. A texture multiplies kd. " TEXTURE_DOC);
  blinn_phong_class
      .def(py::init([](const py::object& kd, const py::object& ks, double ns, const py::object& texture, double alpha) {
             return std::make_shared<BlinnPhong>(to_textured(kd, "kd", texture), to_rgb(ks, "ks"), ns, alpha);
           }),
           py::arg("kd") = 0.5, py::arg("ks") = 0.0, py::arg("ns") = 1.0, py::arg("texture") = py::none(), py::arg("alpha") = 1.0);
  add_parameters<BlinnPhong>(blinn_phong_class, [](const BlinnPhong& m) {
    return py::dict(py::arg("kd") = rgb_tuple(m.kd().rgb()), py::arg("ks") = rgb_tuple(m.ks()), py::arg("ns") = m.ns(),
                    py::arg("texture") = texture_argument(m.kd()), py::arg("alpha") = m.alpha());
  });

  py::class_<Conductor, Material, std::shared_ptr<Conductor>> conductor_class(
      m, "Conductor",
      "A smooth metal mirror with the exact complex Fresnel reflectance of eta + i k (numbers or (r, g, b),\n"
      "relative to vacuum). eta and k unset: a perfect mirror, F = 1; eta without k: k = 0.");
  conductor_class
      .def(py::init([](const py::object& eta, const py::object& k) {
             return std::make_shared<Conductor>(to_optional_rgb(eta, "eta"), to_optional_rgb(k, "k"));
           }),
           py::arg("eta") = py::none(), py::arg("k") = py::none());
  add_parameters<Conductor>(conductor_class, [](const Conductor& m) {
    return py::dict(py::arg("eta") = optional_rgb_tuple(m.index().eta()), py::arg("k") = optional_rgb_tuple(m.index().k()));
  });

  py::class_<RoughConductor, Material, std::shared_ptr<RoughConductor>> rough_conductor_class(
      m, "RoughConductor",
      "A rough metal: GGX microfacets (alpha, or alpha_u along the tangent and alpha_v along the bitangent;\n"
      ">= 0, raised to 1e-4), height-correlated Smith masking, exact complex Fresnel of eta + i k (unset: F = 1),\n"
      "visible-normal sampling.");
  rough_conductor_class
      .def(py::init([](const py::object& alpha, const py::object& alpha_u, const py::object& alpha_v, const py::object& eta,
                       const py::object& k) {
             const auto a = to_alphas(alpha, alpha_u, alpha_v, true, 0.0);
             return std::make_shared<RoughConductor>(a.first, a.second, to_optional_rgb(eta, "eta"), to_optional_rgb(k, "k"));
           }),
           py::arg("alpha") = py::none(), py::arg("alpha_u") = py::none(), py::arg("alpha_v") = py::none(),
           py::arg("eta") = py::none(), py::arg("k") = py::none());
  add_parameters<RoughConductor>(rough_conductor_class, [](const RoughConductor& m) {
    return py::dict(py::arg("alpha_u") = m.alpha_u(), py::arg("alpha_v") = m.alpha_v(),
                    py::arg("eta") = optional_rgb_tuple(m.index().eta()), py::arg("k") = optional_rgb_tuple(m.index().k()));
  });

  py::class_<Dielectric, Material, std::shared_ptr<Dielectric>> dielectric_class(
      m, "Dielectric",
      "Smooth glass: reflect with probability F, refract with 1 - F (TIR: reflect), radiance scaled by\n"
      "(eta_i / eta_t)^2 on refraction. ior: a number > 0 or 'bk7'; or sellmeier=(B1, B2, B3, C1, C2, C3), C in\n"
      "um^2 (dispersive: spectral rendering keeps the hero wavelength on refraction). priority: nested\n"
      "dielectrics (larger wins).");
  dielectric_class
      .def(py::init([](const py::object& ior, const py::object& sellmeier, int priority) {
             return std::make_shared<Dielectric>(to_ior(ior, sellmeier), priority);
           }),
           py::arg("ior") = 1.5, py::arg("sellmeier") = py::none(), py::arg("priority") = 0);
  add_parameters<Dielectric>(dielectric_class, [](const Dielectric& m) {
    py::dict kwargs(py::arg("priority") = m.priority());
    add_ior_arguments(kwargs, m.ior());
    return kwargs;
  });

  py::class_<RoughDielectric, Material, std::shared_ptr<RoughDielectric>> rough_dielectric_class(
      m, "RoughDielectric",
      "Rough glass (Walter et al. 2007): GGX alpha (or alpha_u, alpha_v), ior as for Dielectric, priority.");
  rough_dielectric_class
      .def(py::init([](const py::object& alpha, const py::object& ior, const py::object& sellmeier, int priority,
                       const py::object& alpha_u, const py::object& alpha_v) {
             const auto a = to_alphas(alpha, alpha_u, alpha_v, true, 0.0);
             return std::make_shared<RoughDielectric>(a.first, a.second, to_ior(ior, sellmeier), priority);
           }),
           py::arg("alpha") = py::none(), py::arg("ior") = 1.5, py::arg("sellmeier") = py::none(), py::arg("priority") = 0,
           py::arg("alpha_u") = py::none(), py::arg("alpha_v") = py::none());
  add_parameters<RoughDielectric>(rough_dielectric_class, [](const RoughDielectric& m) {
    py::dict kwargs(py::arg("alpha_u") = m.alpha_u(), py::arg("alpha_v") = m.alpha_v(), py::arg("priority") = m.priority());
    add_ior_arguments(kwargs, m.ior());
    return kwargs;
  });

  py::class_<ThinDielectric, Material, std::shared_ptr<ThinDielectric>> thin_dielectric_class(
      m, "ThinDielectric",
      "A thin pane (window): reflection R' = R + T^2 R / (1 - R^2), transmission 1 - R' straight through\n"
      "(no offset, no medium inside: interior_ior is None). ior as for Dielectric.");
  thin_dielectric_class
      .def(py::init([](const py::object& ior, const py::object& sellmeier) { return std::make_shared<ThinDielectric>(to_ior(ior, sellmeier)); }),
           py::arg("ior") = 1.5, py::arg("sellmeier") = py::none());
  add_parameters<ThinDielectric>(thin_dielectric_class, [](const ThinDielectric& m) {
    py::dict kwargs;
    add_ior_arguments(kwargs, m.ior());
    return kwargs;
  });

  py::class_<Plastic, Material, std::shared_ptr<Plastic>> plastic_class(
      m, "Plastic",
      "Coated diffuse (Weidlich & Wilkie 2007; Mitsuba's plastic / roughplastic): a dielectric coat of index\n"
      "ior over a Lambertian base of reflectance in [0, 1]; alpha = 0: smooth coat (a delta lobe), > 0: GGX\n"
      "(or alpha_u, alpha_v). A texture multiplies the reflectance. " TEXTURE_DOC);
  plastic_class
      .def(py::init([](const py::object& reflectance, double ior, const py::object& alpha, const py::object& alpha_u,
                       const py::object& alpha_v, const py::object& texture) {
             const auto a = to_alphas(alpha, alpha_u, alpha_v, false, 0.0);
             return std::make_shared<Plastic>(to_textured(reflectance, "reflectance", texture), ior, a.first, a.second);
           }),
           py::arg("reflectance") = 0.5, py::arg("ior") = 1.5, py::arg("alpha") = py::none(), py::arg("alpha_u") = py::none(),
           py::arg("alpha_v") = py::none(), py::arg("texture") = py::none());
  add_parameters<Plastic>(plastic_class, [](const Plastic& m) {
    return py::dict(py::arg("reflectance") = rgb_tuple(m.reflectance().rgb()), py::arg("ior") = m.ior(), py::arg("alpha_u") = m.alpha_u(),
                    py::arg("alpha_v") = m.alpha_v(), py::arg("texture") = texture_argument(m.reflectance()));
  });

  py::class_<Principled, Material, std::shared_ptr<Principled>> principled_class(
      m, "Principled",
      "Burley 2012's principled BRDF (disney.brdf without subsurface): base_color (r, g, b) in [0, 1], and\n"
      "metallic, roughness (alpha = roughness^2), anisotropic, specular, specular_tint, sheen, sheen_tint,\n"
      "clearcoat, clearcoat_gloss, all in [0, 1]. A texture multiplies base_color. " TEXTURE_DOC);
  principled_class
      .def(py::init([](const py::object& base_color, double metallic, double roughness, double anisotropic, double specular,
                       double specular_tint, double sheen, double sheen_tint, double clearcoat, double clearcoat_gloss,
                       const py::object& texture) {
             PrincipledParameters p;
             p.metallic = metallic, p.roughness = roughness, p.anisotropic = anisotropic, p.specular = specular;
             p.specular_tint = specular_tint, p.sheen = sheen, p.sheen_tint = sheen_tint, p.clearcoat = clearcoat;
             p.clearcoat_gloss = clearcoat_gloss;
             return std::make_shared<Principled>(to_textured(base_color, "base_color", texture), p);
           }),
           py::arg("base_color") = 0.5, py::arg("metallic") = 0.0, py::arg("roughness") = 0.5, py::arg("anisotropic") = 0.0,
           py::arg("specular") = 0.5, py::arg("specular_tint") = 0.0, py::arg("sheen") = 0.0, py::arg("sheen_tint") = 0.5,
           py::arg("clearcoat") = 0.0, py::arg("clearcoat_gloss") = 1.0, py::arg("texture") = py::none());
  add_parameters<Principled>(principled_class, [](const Principled& m) {
    const PrincipledParameters& p = m.parameters();
    return py::dict(py::arg("base_color") = rgb_tuple(m.base_color().rgb()), py::arg("metallic") = p.metallic,
                    py::arg("roughness") = p.roughness, py::arg("anisotropic") = p.anisotropic, py::arg("specular") = p.specular,
                    py::arg("specular_tint") = p.specular_tint, py::arg("sheen") = p.sheen, py::arg("sheen_tint") = p.sheen_tint,
                    py::arg("clearcoat") = p.clearcoat, py::arg("clearcoat_gloss") = p.clearcoat_gloss,
                    py::arg("texture") = texture_argument(m.base_color()));
  });

  py::class_<ThinFilm, Material, std::shared_ptr<ThinFilm>> thin_film_class(
      m, "ThinFilm",
      "Thin-film iridescence (Belcour & Barla 2017): a film of thickness [nm] and index film_ior on a base\n"
      "of complex index eta + i k, with GGX roughness alpha (or alpha_u, alpha_v; 0 = smooth mirror). The\n"
      "Fresnel term is the film's exact Airy reflectance (RGB: at 630, 532, 465 nm). Reflection only.");
  thin_film_class
      .def(py::init([](double thickness, double film_ior, const py::object& eta, const py::object& k, const py::object& alpha,
                       const py::object& alpha_u, const py::object& alpha_v) {
             const auto a = to_alphas(alpha, alpha_u, alpha_v, false, 0.1);
             return std::make_shared<ThinFilm>(thickness, film_ior, to_rgb(eta, "eta"), to_rgb(k, "k"), a.first, a.second);
           }),
           py::arg("thickness"), py::arg("film_ior") = 1.33, py::arg("eta") = 1.5, py::arg("k") = 0.0, py::arg("alpha") = py::none(),
           py::arg("alpha_u") = py::none(), py::arg("alpha_v") = py::none());
  add_parameters<ThinFilm>(thin_film_class, [](const ThinFilm& m) {
    return py::dict(py::arg("thickness") = m.thickness(), py::arg("film_ior") = m.film_ior(), py::arg("eta") = rgb_tuple(m.eta()),
                    py::arg("k") = rgb_tuple(m.k()), py::arg("alpha_u") = m.alpha_u(), py::arg("alpha_v") = m.alpha_v());
  });

  m.def("water_ior", py::vectorize([](double wavelength, double temperature_c, double salinity) {
          return water_ior(wavelength, temperature_c, salinity);
        }),
        py::arg("wavelength_nm"), py::arg("temperature_c") = 20.0, py::arg("salinity") = 0.0,
        "Refractive index of water relative to vacuum: pure water by IAPWS R9-97 at the density of\n"
        "Tanaka et al. 2001 (atmospheric pressure), plus Quan & Fry 1995's salinity terms. wavelength_nm\n"
        "in [200, 1100], temperature_c in [0, 40] deg C, salinity [g/kg] in [0, 40]. Vectorised.");
  m.def("water_density", py::vectorize([](double temperature_c) { return water_density(temperature_c); }),
        py::arg("temperature_c"),
        "Density of air-free pure water at 101 325 Pa [kg/m^3] (Tanaka et al. 2001), temperature_c in\n"
        "[0, 40] deg C. Vectorised.");
  m.def("water_absorption", py::vectorize([](double wavelength) { return water_absorption(wavelength); }),
        py::arg("wavelength_nm"),
        "Absorption coefficient of pure water [1/m] at wavelength_nm in [360, 830]: Pope & Fry 1997 (380-725 nm),\n"
        "Smith & Baker 1981 below, Kou et al. 1993 above; linear between 5 nm nodes. Vectorised.");
  m.def("water_backscattering", py::vectorize([](double wavelength, double salinity) { return water_backscattering(wavelength, salinity); }),
        py::arg("wavelength_nm"), py::arg("salinity") = 0.0,
        "Backscattering coefficient of pure (sea) water [1/m]: half of Morel 1974's molecular scattering\n"
        "0.00222 (1 + 0.3 S / 37) (lambda / 500)^-4.32, salinity S [g/kg] in [0, 40]. Vectorised.");
  m.def("water_body_reflectance",
        py::vectorize([](double wavelength, double salinity) { return water_body_reflectance(wavelength, salinity); }),
        py::arg("wavelength_nm"), py::arg("salinity") = 0.0,
        "Irradiance reflectance just beneath the surface of deep pure (sea) water, R = 0.33 b_b / (a + b_b)\n"
        "(Morel & Prieur 1977; Gordon et al. 1975), from water_absorption and water_backscattering. Vectorised.");
  m.def("cox_munk_mean_square_slope", py::vectorize([](double wind_speed) { return cox_munk_mean_square_slope(wind_speed); }),
        py::arg("wind_speed"),
        "Total mean-square slope of a clean sea surface, 0.003 + 5.12e-3 U (Cox & Munk 1954), wind_speed U\n"
        "[m/s] 12.5 m above the sea in [0, 30]. The Water material's Beckmann alpha^2. Vectorised.");

  const WaterParameters water_defaults;
  py::class_<Water, Material, std::shared_ptr<Water>> water_class(
      m, "Water",
      "The sea: a wind-roughened water surface over a deep water body (water_surface.h).\n\n"
      "The interface is a Beckmann microfacet dielectric (Walter et al. 2007; Mitsuba 3's roughdielectric\n"
      "with distribution='beckmann') whose alpha^2 is Cox & Munk 1954's total mean-square slope\n"
      "0.003 + 5.12e-3 wind_speed (alpha = 0.17 at 5 m/s) and whose index is water_ior(lambda, temperature_c,\n"
      "salinity): per wavelength in spectral rendering, at 630, 532 and 465 nm per RGB channel (directions\n"
      "sampled at 550 nm). body=True (default): the deep water under it absorbs (Pope & Fry 1997) and\n"
      "backscatters (Morel 1974) the light refracted in and returns R = 0.33 b_b / (a + b_b) of it as\n"
      "isotropic light leaving through the rough interface, T(cos_i) T(cos_o) R / (pi eta^2 (1 - R Fbar_int))\n"
      "(T = transmittance(mu), Fbar_int = internal_reflectance());\n"
      "reflection-only and two-sided, nothing continues below. body=False: the bare interface, reflecting\n"
      "and transmitting, bounding a medium of the water's index (priority for nested dielectrics).\n"
      "Defaults: wind_speed 5 m/s (a gentle breeze), temperature_c 20 deg C, salinity 35 g/kg (the open ocean).\n"
      "resolved_slope_variance: the mean-square slope a displaced wave mesh under it already resolves\n"
      "(Scene.add_sea sets it): alpha^2 = Cox-Munk's total - it, so that resolved + unresolved = total.\n"
      "wind_speed in [0, 30] m/s, temperature_c in [0, 40], salinity in [0, 40] g/kg.");
  water_class
      .def(py::init([](double wind_speed, double temperature_c, double salinity, bool body, int priority, double resolved_slope_variance) {
             WaterParameters p;
             p.wind_speed = wind_speed, p.temperature_c = temperature_c, p.salinity = salinity, p.body = body, p.priority = priority;
             p.resolved_slope_variance = resolved_slope_variance;
             return std::make_shared<Water>(p);
           }),
           py::arg("wind_speed") = water_defaults.wind_speed, py::arg("temperature_c") = water_defaults.temperature_c,
           py::arg("salinity") = water_defaults.salinity, py::arg("body") = water_defaults.body,
           py::arg("priority") = water_defaults.priority, py::arg("resolved_slope_variance") = water_defaults.resolved_slope_variance)
      .def_property_readonly("wind_speed", [](const Water& w) { return w.parameters().wind_speed; }, "[m/s] 12.5 m above the sea")
      .def_property_readonly("temperature_c", [](const Water& w) { return w.parameters().temperature_c; }, "[deg C]")
      .def_property_readonly("salinity", [](const Water& w) { return w.parameters().salinity; }, "[g/kg]")
      .def_property_readonly("body", [](const Water& w) { return w.parameters().body; }, "Whether a deep water body is under the surface.")
      .def_property_readonly("mean_square_slope", &Water::mean_square_slope, "Cox & Munk's total sigma^2.")
      .def_property_readonly("resolved_slope_variance", [](const Water& w) { return w.parameters().resolved_slope_variance; },
                             "The mean-square slope a displaced wave mesh already shows (Scene.add_sea); the microfacets keep\n"
                             "alpha^2 = mean_square_slope - resolved_slope_variance.")
      .def_property_readonly("alpha", &Water::alpha, "The Beckmann roughness alpha = sqrt(mean_square_slope - resolved_slope_variance).")
      .def("ior", [](const Water& w, const py::object& wavelength) {
             bool single = false;
             std::vector<double> l = to_values(wavelength, "wavelength_nm", &single);
             for (double& x : l) {
               if (!(x >= kLambdaMin && x <= kLambdaMax)) {
                 throw_invalid("Water.ior: wavelength_nm must be in [", kLambdaMin, ", ", kLambdaMax, "] (got ", x, ")");
               }
               x = w.ior(x);
             }
             return single ? py::object(py::float_(l[0])) : py::object(values_to_array(l));
           },
           py::arg("wavelength_nm"), "The water's index relative to vacuum at wavelength_nm [nm] (a number or an array).")
      .def("transmittance", [](const Water& w, const py::object& mu, double wavelength) {
             if (!(wavelength >= kLambdaMin && wavelength <= kLambdaMax)) {
               throw_invalid("Water.transmittance: wavelength_nm must be in [", kLambdaMin, ", ", kLambdaMax, "] (got ", wavelength, ")");
             }
             bool single = false;
             std::vector<double> m = to_values(mu, "mu", &single);
             for (double& x : m) {
               if (!(std::abs(x) <= 1.0)) throw_invalid("Water.transmittance: mu must be in [-1, 1] (got ", x, ")");
               x = w.transmittance()(x, w.ior(wavelength));
             }
             return single ? py::object(py::float_(m[0])) : py::object(values_to_array(m));
           },
           py::arg("mu"), py::arg("wavelength_nm") = Ior::kRgbWavelength,
           "The rough interface's directional transmittance T(mu) from above (the share of the energy arriving at\n"
           "cos theta = mu that crosses into the water), as the water body's term uses it, at the water's index\n"
           "at wavelength_nm under vacuum. Tabulated (33 mu x 5 eta nodes).")
      .def("internal_reflectance", [](const Water& w, double wavelength) {
             if (!(wavelength >= kLambdaMin && wavelength <= kLambdaMax)) {
               throw_invalid("Water.internal_reflectance: wavelength_nm must be in [", kLambdaMin, ", ", kLambdaMax, "] (got ", wavelength, ")");
             }
             const double eta = w.ior(wavelength);
             return 1.0 - w.transmittance().hemispherical(eta) / (eta * eta);
           },
           py::arg("wavelength_nm") = Ior::kRgbWavelength,
           "Fbar_int = 1 - 2 int T(mu) mu dmu / eta^2: what of isotropic light under the rough surface is sent\n"
           "back down (the flat surface's fresnel_diffuse_reflectance(1 / eta) when alpha -> 0).");
  add_parameters<Water>(water_class, [](const Water& w) {
    const WaterParameters& p = w.parameters();
    return py::dict(py::arg("wind_speed") = p.wind_speed, py::arg("temperature_c") = p.temperature_c, py::arg("salinity") = p.salinity,
                    py::arg("body") = p.body, py::arg("priority") = p.priority,
                    py::arg("resolved_slope_variance") = p.resolved_slope_variance);
  });

  py::class_<Beckmann>(m, "Beckmann",
                       "The isotropic Beckmann microfacet distribution (beckmann.h): D, Lambda (exact, with erf), G1 and\n"
                       "the height-correlated G. alpha^2 is the total mean-square slope. Directions: (N, 3) unit vectors.")
      .def(py::init([](double alpha) { return Beckmann(TrowbridgeReitz::checked_alpha(alpha, "alpha")); }), py::arg("alpha"))
      .def("D", [](const Beckmann& d, const py::object& m_) {
        std::vector<double> out;
        for (const Vec3d& m : to_directions(m_, "m")) out.push_back(d.D(m));
        return values_to_array(out);
      }, py::arg("m"))
      .def("G1", [](const Beckmann& d, const py::object& w_) {
        std::vector<double> out;
        for (const Vec3d& w : to_directions(w_, "w")) out.push_back(d.G1(w));
        return values_to_array(out);
      }, py::arg("w"))
      .def("G", [](const Beckmann& d, const py::object& wo_, const py::object& wi_) {
        const auto wo = to_directions(wo_, "wo"), wi = to_directions(wi_, "wi");
        const size_t n = broadcast(wo.size(), wi.size(), "wo and wi");
        std::vector<double> out(n);
        for (size_t i = 0; i < n; ++i) out[i] = d.G(wo[wo.size() == 1 ? 0 : i], wi[wi.size() == 1 ? 0 : i]);
        return values_to_array(out);
      }, py::arg("wo"), py::arg("wi"))
      .def_property_readonly("alpha", &Beckmann::alpha)
      .def(py::pickle([](const Beckmann& d) { return py::make_tuple(d.alpha()); },
                      [](const py::tuple& t) {
                        if (t.size() != 1) throw_invalid("Beckmann: bad pickle state");
                        return Beckmann(TrowbridgeReitz::checked_alpha(py::cast<double>(t[0]), "alpha"));
                      }));

  // Fresnel and thin films, vectorised over numpy arrays.
  m.def(
      "fresnel_dielectric",
      py::vectorize([](double cos_i, double eta) {
        if (!(eta > 0.0) || !std::isfinite(eta)) throw_invalid("eta must be finite and > 0 (got ", eta, ")");
        if (!(std::abs(cos_i) <= 1.0)) throw_invalid("cos_i must be in [-1, 1] (got ", cos_i, ")");
        return fresnel_dielectric(cos_i, eta);
      }),
      py::arg("cos_i"), py::arg("eta"),
      "Unpolarised Fresnel reflectance of a dielectric interface, eta = eta_t / eta_i on the side cos_i > 0\n"
      "(cos_i < 0: from inside, 1 / eta). Total internal reflection gives 1. Vectorised.");
  m.def(
      "fresnel_conductor",
      py::vectorize([](double cos_i, double eta, double k) {
        if (!(eta > 0.0) || !std::isfinite(eta)) throw_invalid("eta must be finite and > 0 (got ", eta, ")");
        if (!(k >= 0.0) || !std::isfinite(k)) throw_invalid("k must be finite and >= 0 (got ", k, ")");
        if (!(std::abs(cos_i) <= 1.0)) throw_invalid("cos_i must be in [-1, 1] (got ", cos_i, ")");
        return fresnel_complex(cos_i, std::complex<double>(eta, k));
      }),
      py::arg("cos_i"), py::arg("eta"), py::arg("k"),
      "Unpolarised Fresnel reflectance of a conductor of relative complex index eta + i k at ``|cos_i|`` (exact). Vectorised.");
  m.def(
      "fresnel_diffuse_reflectance",
      [](double eta) {
        if (!(eta > 0.0) || !std::isfinite(eta)) throw_invalid("eta must be finite and > 0 (got ", eta, ")");
        return fresnel_diffuse_reflectance(eta);
      },
      py::arg("eta"), "Hemispherical reflectance 2 int F(mu) mu dmu of a dielectric seen from the side where eta = eta_t / eta_i.");
  m.def(
      "thin_film_reflectance",
      py::vectorize([](double cos_i, double n1, double n2, double eta, double k, double thickness, double wavelength) {
        if (!(n1 > 0.0 && n2 > 0.0 && eta > 0.0 && k >= 0.0 && thickness >= 0.0 && wavelength > 0.0)) {
          throw_invalid("thin_film_reflectance needs n1, n2, eta, wavelength > 0 and k, thickness >= 0");
        }
        return thin_film_reflectance(cos_i, n1, n2, {eta, k}, thickness, wavelength);
      }),
      py::arg("cos_i"), py::arg("n1"), py::arg("n2"), py::arg("eta"), py::arg("k"), py::arg("thickness"), py::arg("wavelength"),
      "Airy reflectance of a film (index n2, thickness [nm]) between n1 and a base eta + i k at a wavelength [nm]. Vectorised.");

  py::class_<TrowbridgeReitz>(m, "TrowbridgeReitz",
                              "The GGX microfacet distribution (microfacet.h): D, Lambda, G1, height-correlated G, the\n"
                              "visible-normal density and sampler. Directions: (N, 3) unit vectors in the local frame.")
      .def(py::init([](double alpha_x, double alpha_y) {
             return TrowbridgeReitz(TrowbridgeReitz::checked_alpha(alpha_x, "alpha_x"), TrowbridgeReitz::checked_alpha(alpha_y, "alpha_y"));
           }),
           py::arg("alpha_x"), py::arg("alpha_y"))
      .def("D", [](const TrowbridgeReitz& d, const py::object& m_) {
        std::vector<double> out;
        for (const Vec3d& m : to_directions(m_, "m")) out.push_back(d.D(m));
        return values_to_array(out);
      }, py::arg("m"))
      .def("G1", [](const TrowbridgeReitz& d, const py::object& w_) {
        std::vector<double> out;
        for (const Vec3d& w : to_directions(w_, "w")) out.push_back(d.G1(w));
        return values_to_array(out);
      }, py::arg("w"))
      .def("G", [](const TrowbridgeReitz& d, const py::object& wo_, const py::object& wi_) {
        const auto wo = to_directions(wo_, "wo"), wi = to_directions(wi_, "wi");
        const size_t n = broadcast(wo.size(), wi.size(), "wo and wi");
        std::vector<double> out(n);
        for (size_t i = 0; i < n; ++i) out[i] = d.G(wo[wo.size() == 1 ? 0 : i], wi[wi.size() == 1 ? 0 : i]);
        return values_to_array(out);
      }, py::arg("wo"), py::arg("wi"))
      .def("D_visible", [](const TrowbridgeReitz& d, const py::object& w_, const py::object& m_) {
        const auto w = to_directions(w_, "w"), m = to_directions(m_, "m");
        const size_t n = broadcast(w.size(), m.size(), "w and m");
        std::vector<double> out(n);
        for (size_t i = 0; i < n; ++i) out[i] = d.D_visible(w[w.size() == 1 ? 0 : i], m[m.size() == 1 ? 0 : i]);
        return values_to_array(out);
      }, py::arg("w"), py::arg("m"))
      .def("sample_wm", [](const TrowbridgeReitz& d, const py::object& w_, const py::object& u_) {
        const auto w = to_directions(w_, "w");
        DoubleArray u = real_array(u_, "u");
        if (u.ndim() != 2 || u.shape(1) != 2) throw_invalid("u must have shape (N, 2)");
        const size_t n = broadcast(w.size(), size_t(u.shape(0)), "w and u");
        std::vector<Vec3d> out(n);
        for (size_t i = 0; i < n; ++i) out[i] = d.sample_wm(w[w.size() == 1 ? 0 : i], Vec2d(u.at(i, 0), u.at(i, 1)));
        return points_to_array(out);
      }, py::arg("w"), py::arg("u"))
      .def_property_readonly("alpha_x", &TrowbridgeReitz::alpha_x)
      .def_property_readonly("alpha_y", &TrowbridgeReitz::alpha_y)
      .def(py::pickle([](const TrowbridgeReitz& d) { return py::make_tuple(d.alpha_x(), d.alpha_y()); },
                      [](const py::tuple& t) {
                        if (t.size() != 2) throw_invalid("TrowbridgeReitz: bad pickle state");
                        return TrowbridgeReitz(TrowbridgeReitz::checked_alpha(py::cast<double>(t[0]), "alpha_x"),
                                               TrowbridgeReitz::checked_alpha(py::cast<double>(t[1]), "alpha_y"));
                      }));

  py::class_<Ior>(m, "Ior", "An index of refraction: constant or Sellmeier (C in um^2).")
      .def(py::init([](const py::object& ior, const py::object& sellmeier) { return to_ior(ior, sellmeier); }),
           py::arg("ior") = 1.5, py::arg("sellmeier") = py::none())
      .def("at", [](const Ior& ior, const py::object& wavelength) {
             bool single = false;
             std::vector<double> l = to_values(wavelength, "wavelength", &single);
             for (double& x : l) x = ior.at(x);
             return single ? py::object(py::float_(l[0])) : py::object(values_to_array(l));
           }, py::arg("wavelength"),
           "n at wavelength(s) [nm].")
      .def_property_readonly("dispersive", &Ior::dispersive)
      .def("__repr__", [](const Ior& ior) { return concat("Ior(", ior.describe(), ")"); })
      .def(py::pickle(
          [](const Ior& ior) {
            py::dict kwargs;
            add_ior_arguments(kwargs, ior);
            return kwargs;
          },
          [](const py::dict& kwargs) {
            return to_ior(kwargs.contains("ior") ? py::object(kwargs["ior"]) : py::object(py::float_(1.5)),
                          kwargs.contains("sellmeier") ? py::object(kwargs["sellmeier"]) : py::object(py::none()));
          }));
}

}  // namespace refracta
