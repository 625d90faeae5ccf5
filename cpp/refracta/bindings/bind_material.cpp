// Python bindings of the Material interface (shading/material.h): vectorised evaluation f, pdf
// and sample in the local shading frame (shared/SHADING.md section 0), and BsdfSample, what
// sample returns.
#include "refracta/bindings/bind_shading.h"

#include "refracta/shading/material.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace refracta {

namespace {

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
  const auto wo = to_unit_vectors(wo_in, "wo"), wi = to_unit_vectors(wi_in, "wi");
  const size_t n = broadcast(wo.size(), wi.size(), "wo and wi");
  const Wavelengths w = to_wavelengths(wavelengths, n);
  const TransportMode tm = to_mode(mode);
  out->resize(n);
  for_rows(material, eta_outside, w, n, [&](size_t i, const Bsdf* bsdf, const SampledWavelengths&) {
    (*out)[i] = value(bsdf, wo[wo.size() == 1 ? 0 : i], wi[wi.size() == 1 ? 0 : i], tm);
  });
  return w.spectral();
}

const char* kEvalDoc =
    "wo, wi: unit directions in the local shading frame (z = shading normal), shape (N, 3) or (3,)\n"
    "(one side may be a single direction, broadcast), wo toward the viewer, wi toward the light.\n"
    "wavelengths: None for RGB rendering, or (4,) / (N, 4) hero wavelengths [nm] for spectral.\n"
    "eta_outside: index of the medium on the normal's side; mode: 'radiance' or 'importance'.";

// Material.sample's result: one array per field of BsdfSample (shading/bsdf.h), a row per sample.
struct BsdfSamples {
  DoubleArray wi, weight, f;
  py::array_t<double> pdf, eta;
  py::array_t<unsigned> flags;
  py::array_t<bool> is_delta, valid, terminated;
};

// Sample numbers in [0, 1) may be 1 - 2^-53; the samplers are written for u < 1 - 1e-16 (a
// float64 rounding of 1 - 1e-16 is the largest below 1 they are safe at).
constexpr double kBelowOne = 1.0 - 1e-16;

BsdfSamples sample(const Material& material, const py::object& wo_in, const py::object& u_in,
                   const py::object& wavelengths, double eta_outside, const std::string& mode) {
  const auto wo = to_unit_vectors(wo_in, "wo");
  const Samples u = to_samples(u_in, "u", 3);
  const size_t n = broadcast(wo.size(), u.rows, "wo and u");
  const Wavelengths w = to_wavelengths(wavelengths, n);
  const TransportMode tm = to_mode(mode);
  std::vector<Vec3d> wi(n, Vec3d::Zero());
  std::vector<Spectrum> weight(n, Spectrum::Zero()), f(n, Spectrum::Zero());
  const std::vector<py::ssize_t> shape{py::ssize_t(n)};
  BsdfSamples out{{}, {}, {}, py::array_t<double>(shape), py::array_t<double>(shape), py::array_t<unsigned>(shape),
                  py::array_t<bool>(shape), py::array_t<bool>(shape), py::array_t<bool>(shape)};
  auto P = out.pdf.mutable_unchecked<1>(), E = out.eta.mutable_unchecked<1>();
  auto F = out.flags.mutable_unchecked<1>();
  auto D = out.is_delta.mutable_unchecked<1>(), V = out.valid.mutable_unchecked<1>(), T = out.terminated.mutable_unchecked<1>();
  Evaluator evaluator(material, eta_outside);
  for (size_t i = 0; i < n; ++i) {  // fresh wavelengths per sample: a dielectric may terminate them
    SampledWavelengths lambda = w.at(i);
    const Bsdf* bsdf = evaluator.build(&lambda);
    const double* ui = u.row(u.rows == 1 ? 0 : i);
    std::optional<BsdfSample> s;
    const Vec3d& o = wo[wo.size() == 1 ? 0 : i];
    if (bsdf && o.z() != 0.0) s = bsdf->sample(o, std::min(ui[0], kBelowOne), Vec2d(std::min(ui[1], kBelowOne), std::min(ui[2], kBelowOne)), tm);
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
  out.wi = points_to_array(wi), out.weight = spectra_array(weight, channels), out.f = spectra_array(f, channels);
  return out;
}

// The fields of BsdfSample, in the order the former dict had them.
constexpr const char* kSampleFields[] = {"wi", "weight", "f", "pdf", "flags", "is_delta", "eta", "valid", "terminated"};

// Material.sample returned a dict before it returned a BsdfSample: s["wi"] and iterating over the
// keys still work, with a DeprecationWarning.
void warn_dict_use(const std::string& use, const std::string& instead) {
  const std::string message = concat("BsdfSample", use, " is deprecated (Material.sample returns a BsdfSample, no longer a dict): use ", instead);
  if (PyErr_WarnEx(PyExc_DeprecationWarning, message.c_str(), 1) != 0) throw py::error_already_set();
}

py::object sample_field(const py::object& self, const std::string& key) {
  if (std::none_of(std::begin(kSampleFields), std::end(kSampleFields), [&](const char* k) { return key == k; })) {
    throw py::key_error(key);
  }
  warn_dict_use(concat("['", key, "']"), concat("the attribute BsdfSample.", key));
  return self.attr(key.c_str());
}

py::tuple sample_fields() {
  py::tuple names(std::size(kSampleFields));
  for (size_t i = 0; i < std::size(kSampleFields); ++i) names[i] = py::str(kSampleFields[i]);
  return names;
}

void bind_bsdf_sample(py::module_& m) {
  py::class_<BsdfSamples>(m, "BsdfSample",
                          "What Material.sample returns, one row per sample (read-only arrays): wi (N, 3), weight (N, C),\n"
                          "f (N, C), pdf (N,), flags (N,) uint32, is_delta (N,), eta (N,), valid (N,), terminated (N,);\n"
                          "C = 3 (RGB) or 4 (spectral). See Material.sample. s['wi'] (the former dict) still works\n"
                          "and iteration over the names are deprecated (DeprecationWarning).")
      .def_readonly("wi", &BsdfSamples::wi, "Sampled unit directions (N, 3), 0 where invalid.")
      .def_readonly("weight", &BsdfSamples::weight, "``f |cos theta_i| / pdf`` (N, C) (delta lobes: albedo / probability).")
      .def_readonly("f", &BsdfSamples::f, "The BSDF value (N, C) [1/sr] (delta lobes: as weight's numerator).")
      .def_readonly("pdf", &BsdfSamples::pdf, "Density (N,) [1/sr] (delta lobes: the lobe's selection probability).")
      .def_readonly("flags", &BsdfSamples::flags, "1 reflection, 2 transmission, 4 diffuse, 8 glossy, 16 specular (N,).")
      .def_readonly("is_delta", &BsdfSamples::is_delta, "Whether a delta lobe was sampled (N,).")
      .def_readonly("eta", &BsdfSamples::eta, "The relative index crossed (N,), 1 for reflection.")
      .def_readonly("valid", &BsdfSamples::valid, "False where no direction was produced (N,).")
      .def_readonly("terminated", &BsdfSamples::terminated,
                    "True where a dispersive refraction kept the hero wavelength only (N,).")
      .def_property_readonly_static("fields", [](const py::object&) { return sample_fields(); },
                                    "The names of the fields, in order.")
      .def(py::pickle(  // through the fields, in order
          [](const BsdfSamples& s) {
            return py::make_tuple(s.wi, s.weight, s.f, s.pdf, s.flags, s.is_delta, s.eta, s.valid, s.terminated);
          },
          [](const py::tuple& t) {
            if (t.size() != std::size(kSampleFields)) throw_invalid("BsdfSample: bad pickle state (", t.size(), " items)");
            return BsdfSamples{t[0].cast<DoubleArray>(),          t[1].cast<DoubleArray>(),
                               t[2].cast<DoubleArray>(),          t[3].cast<py::array_t<double>>(),
                               t[6].cast<py::array_t<double>>(),  t[4].cast<py::array_t<unsigned>>(),
                               t[5].cast<py::array_t<bool>>(),    t[7].cast<py::array_t<bool>>(),
                               t[8].cast<py::array_t<bool>>()};
          }))
      .def("__getitem__", &sample_field, py::arg("key"))
      .def("__iter__", [](const py::object&) {
        warn_dict_use(" iteration", "BsdfSample.fields");
        return py::iter(sample_fields());
      })
      .def("__repr__", [](const BsdfSamples& s) { return concat("BsdfSample(", s.valid.size(), " samples)"); });
}

}  // namespace

size_t broadcast(size_t a, size_t b, const char* what) {
  if (a == b || b == 1) return a;
  if (a == 1) return b;
  throw_invalid(what, ": row counts differ (", a, " and ", b, ")");
}

void bind_material_base(py::module_& m) {
  bind_bsdf_sample(m);
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
      .def("sample", &sample, py::arg("wo"), py::arg("u"), py::arg("wavelengths") = py::none(), py::arg("eta_outside") = 1.0,
           py::arg("mode") = "radiance",
           "Sample incident directions for wo (N, 3) from uniform numbers u (N, 3) in [0, 1): u[:, 0] picks\n"
           "the lobe, u[:, 1:] the direction. Returns a BsdfSample of arrays: wi (N, 3) (0 where invalid),\n"
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

}

}  // namespace refracta
