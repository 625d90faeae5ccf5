// Python bindings of the Material interface (shading/material.h): vectorised evaluation f, pdf
// and sample in the local shading frame (shading/material_batch.h), and BsdfSample, what sample
// returns.
#include "generated/docstrings.h"
#include "refracta/bindings/bind_shading.h"
#include "refracta/shading/material_batch.h"

#include <pybind11/eigen.h>

#include <algorithm>

namespace refracta {

namespace {

BsdfQuery to_query(const py::object& wavelengths, double eta_outside, const std::string& mode) {
  std::optional<RowMatrixX4d> rows;
  if (!wavelengths.is_none()) rows = to_rows4(wavelengths, "wavelengths");
  return BsdfQuery{rows, eta_outside, transport_mode_from(mode)};
}

const char* kEvalDoc =
    "wo, wi: unit directions in the local shading frame (z = shading normal), shape (N, 3) or (3,)\n"
    "(one side may be a single direction, broadcast), wo toward the viewer, wi toward the light.\n"
    "wavelengths: None for RGB rendering, or (4,) / (N, 4) hero wavelengths [nm] for spectral.\n"
    "eta_outside: index of the medium on the normal's side; mode: 'radiance' or 'importance'.";

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
  py::class_<BsdfSamples>(m, "BsdfSample", DOC(refracta, BsdfSamples))
      .def_readonly("wi", &BsdfSamples::wi, DOC(refracta, BsdfSamples, wi))
      .def_readonly("weight", &BsdfSamples::weight, DOC(refracta, BsdfSamples, weight))
      .def_readonly("f", &BsdfSamples::f, DOC(refracta, BsdfSamples, f))
      .def_readonly("pdf", &BsdfSamples::pdf, DOC(refracta, BsdfSamples, pdf))
      .def_readonly("flags", &BsdfSamples::flags, DOC(refracta, BsdfSamples, flags))
      .def_readonly("is_delta", &BsdfSamples::is_delta, DOC(refracta, BsdfSamples, is_delta))
      .def_readonly("eta", &BsdfSamples::eta, DOC(refracta, BsdfSamples, eta))
      .def_readonly("valid", &BsdfSamples::valid, DOC(refracta, BsdfSamples, valid))
      .def_readonly("terminated", &BsdfSamples::terminated, DOC(refracta, BsdfSamples, terminated))
      .def_property_readonly_static("fields", [](const py::object&) { return sample_fields(); },
                                    "The names of the fields, in order.")
      .def(py::pickle(  // through the fields, in order
          [](const BsdfSamples& s) { return s.fields(); },
          [](const decltype(BsdfSamples{}.fields())& t) {
            return std::apply([](const auto&... fields) { return BsdfSamples{fields...}; }, t);
          }))
      .def("__getitem__", &sample_field, py::arg("key"))
      .def("__iter__", [](const py::object&) {
        warn_dict_use(" iteration", "BsdfSample.fields");
        return py::iter(sample_fields());
      })
      .def("__repr__", [](const BsdfSamples& s) { return concat("BsdfSample(", s.valid.size(), " samples)"); });
}

}  // namespace

void bind_material_base(py::module_& m) {
  bind_bsdf_sample(m);
  py::class_<Material, std::shared_ptr<Material>>(m, "Material",
                                                 "A surface material (shading/material.h): builds a BSDF at a hit. Evaluate it in\n"
                                                 "the local shading frame with f, pdf and sample (z along the shading normal).")
      .def(
          "f",
          [](const Material& material, const py::object& wo, const py::object& wi, const py::object& wavelengths,
             double eta_outside, const std::string& mode) {
            return bsdf_f(material, to_unit_vectors(wo, "wo"), to_unit_vectors(wi, "wi"),
                          to_query(wavelengths, eta_outside, mode));
          },
          py::arg("wo"), py::arg("wi"), py::arg("wavelengths") = py::none(), py::arg("eta_outside") = 1.0,
          py::arg("mode") = "radiance",
          (std::string(DOC(refracta, bsdf_f)) + "\n" + kEvalDoc).c_str())
      .def(
          "pdf",
          [](const Material& material, const py::object& wo, const py::object& wi, const py::object& wavelengths,
             double eta_outside, const std::string& mode) {
            return bsdf_pdf(material, to_unit_vectors(wo, "wo"), to_unit_vectors(wi, "wi"),
                            to_query(wavelengths, eta_outside, mode));
          },
          py::arg("wo"), py::arg("wi"), py::arg("wavelengths") = py::none(), py::arg("eta_outside") = 1.0,
          py::arg("mode") = "radiance",
          (std::string(DOC(refracta, bsdf_pdf)) + "\n" + kEvalDoc).c_str())
      .def(
          "sample",
          [](const Material& material, const py::object& wo, const py::object& u, const py::object& wavelengths,
             double eta_outside, const std::string& mode) {
            return bsdf_sample(material, to_unit_vectors(wo, "wo"), to_sample_rows(u, "u", 3),
                               to_query(wavelengths, eta_outside, mode));
          },
          py::arg("wo"), py::arg("u"), py::arg("wavelengths") = py::none(), py::arg("eta_outside") = 1.0,
          py::arg("mode") = "radiance",
          (std::string(DOC(refracta, bsdf_sample)) + " Other arguments as for f.").c_str())
      .def("describe", &Material::describe)
      .def("__repr__", &Material::describe)
      .def_property_readonly("priority", &Material::priority, "Nested-dielectric priority (larger wins).")
      .def_property_readonly("alpha", &Material::alpha,
                             "Opacity for raster transparency, in [0, 1] (BlinnPhong's alpha=; 1 for the others). Not a\n"
                             "roughness: the alpha= of RoughDielectric, RoughConductor, Plastic and ThinFilm is their\n"
                             "microfacet roughness, read back as parameters['alpha_u'] and ['alpha_v'].")
      .def("interior_ior", &interior_ior_at, py::arg("wavelength") = py::none(),
           "Index of refraction of the medium a dielectric bounds, at the given wavelength [nm] (None: RGB\n"
           "rendering's 550 nm), or None for materials that bound no medium.");
}

}  // namespace refracta
