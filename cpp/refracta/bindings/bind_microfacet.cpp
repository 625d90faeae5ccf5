// Python bindings of the microfacet distributions (shading/microfacet.h, beckmann.h), the Fresnel
// functions (fresnel.h) and indices of refraction (ior.h), vectorised over numpy arrays.
#include "generated/docstrings.h"
#include "refracta/bindings/bind_shading.h"

#include "refracta/shading/beckmann.h"
#include "refracta/shading/fresnel.h"
#include "refracta/shading/microfacet.h"
#include "refracta/shading/microfacet_batch.h"
#include "refracta/shading/thin_film.h"

#include <pybind11/eigen.h>

namespace refracta {

namespace {

void bind_fresnel(py::module_& m) {
  // Fresnel and thin films, vectorised over numpy arrays.
  m.def("fresnel_dielectric", vectorize_real(&checked_fresnel_dielectric, {"cos_i", "eta"}), py::arg("cos_i"), py::arg("eta"),
        "Unpolarised Fresnel reflectance of a dielectric interface, eta = eta_t / eta_i on the side cos_i > 0\n"
        "(cos_i < 0: from inside, 1 / eta). Total internal reflection gives 1. Vectorised.");
  m.def("fresnel_conductor", vectorize_real(&checked_fresnel_conductor, {"cos_i", "eta", "k"}), py::arg("cos_i"), py::arg("eta"), py::arg("k"),
        "Unpolarised Fresnel reflectance of a conductor of relative complex index eta + i k at ``|cos_i|`` (exact). Vectorised.");
  m.def("fresnel_diffuse_reflectance", &checked_fresnel_diffuse_reflectance, py::arg("eta"),
        "Hemispherical reflectance 2 int F(mu) mu dmu of a dielectric seen from the side where eta = eta_t / eta_i.");
  m.def("thin_film_reflectance", vectorize_real(&checked_thin_film_reflectance,
                                       {"cos_i", "n1", "n2", "eta", "k", "thickness", "wavelength"}), py::arg("cos_i"), py::arg("n1"),
        py::arg("n2"), py::arg("eta"), py::arg("k"), py::kw_only(), py::arg("thickness"), py::arg("wavelength"),
        "Airy reflectance of a film (index n2, thickness [nm]) between n1 and a base eta + i k at a wavelength [nm]. Vectorised.");
}

// The methods every microfacet distribution has: D(m), G1(w) and the height-correlated G(wo, wi).
template <class Distribution>
void def_masking(py::class_<Distribution>& cls) {
  cls.def("D", [](const Distribution& d, const py::object& m) { return microfacet_D(d, to_unit_vectors(m, "m")); },
          py::arg("m"))
      .def("G1", [](const Distribution& d, const py::object& w) { return microfacet_G1(d, to_unit_vectors(w, "w")); },
           py::arg("w"))
      .def("G", [](const Distribution& d, const py::object& wo, const py::object& wi) {
        return microfacet_G(d, to_unit_vectors(wo, "wo"), to_unit_vectors(wi, "wi"));
      }, py::arg("wo"), py::arg("wi"));
}

}  // namespace

void bind_microfacet(py::module_& m) {
  bind_fresnel(m);
  py::class_<Beckmann> beckmann(m, "Beckmann", DOC(refracta, Beckmann));
  beckmann.def(py::init([](double alpha) { return Beckmann(TrowbridgeReitz::checked_alpha(alpha, "alpha")); }), py::arg("alpha"))
      .def_property_readonly("alpha", &Beckmann::alpha)
      .def("__repr__", [](const Beckmann& d) { return concat("Beckmann(alpha=", exact(d.alpha()), ")"); })
      .def(py::pickle([](const Beckmann& d) { return std::make_tuple(d.alpha()); },
                      [](std::tuple<double> t) {
                        return Beckmann(TrowbridgeReitz::checked_alpha(std::get<0>(t), "alpha"));
                      }));
  def_masking(beckmann);

  py::class_<TrowbridgeReitz> ggx(m, "TrowbridgeReitz", DOC(refracta, TrowbridgeReitz));
  ggx.def(py::init([](double alpha_x, double alpha_y) {
             return TrowbridgeReitz(TrowbridgeReitz::checked_alpha(alpha_x, "alpha_x"), TrowbridgeReitz::checked_alpha(alpha_y, "alpha_y"));
           }),
           py::arg("alpha_x"), py::arg("alpha_y"))
      .def("D_visible", [](const TrowbridgeReitz& d, const py::object& w, const py::object& m) {
        return visible_normal_density(d, to_unit_vectors(w, "w"), to_unit_vectors(m, "m"));
      }, py::arg("w"), py::arg("m"))
      .def("sample_wm", [](const TrowbridgeReitz& d, const py::object& w, const py::object& u) {
        return sample_visible_normals(d, to_unit_vectors(w, "w"), to_sample_rows(u, "u", 2));
      }, py::arg("w"), py::arg("u"))
      .def_property_readonly("alpha_x", &TrowbridgeReitz::alpha_x)
      .def_property_readonly("alpha_y", &TrowbridgeReitz::alpha_y)
      .def("__repr__", [](const TrowbridgeReitz& d) { return concat("TrowbridgeReitz(alpha_x=", exact(d.alpha_x()), ", alpha_y=", exact(d.alpha_y()), ")"); })
      .def(py::pickle([](const TrowbridgeReitz& d) { return std::make_pair(d.alpha_x(), d.alpha_y()); },
                      [](std::pair<double, double> t) {
                        return TrowbridgeReitz(TrowbridgeReitz::checked_alpha(t.first, "alpha_x"),
                                               TrowbridgeReitz::checked_alpha(t.second, "alpha_y"));
                      }));
  def_masking(ggx);

  py::class_<Ior>(m, "Ior", "An index of refraction: constant or Sellmeier (C in um^2).")
      .def(py::init(&to_ior), py::arg("ior") = py::none(), py::arg("sellmeier") = py::none())
      .def("at", [](const Ior& ior, const py::object& wavelength) {
             return per_value(wavelength, "wavelength",
                              [&](double x) { return ior.at(checked_wavelength(x, "Ior.at: wavelength")); });
           }, py::arg("wavelength"), "n at wavelength(s) [nm] in the rendered range [360, 830].")
      .def_property_readonly("dispersive", &Ior::dispersive)
      .def("__repr__", [](const Ior& ior) { return concat("Ior(", ior.describe(), ")"); })
      .def(py::pickle([](const Ior& ior) { return with_ior(py::dict(), ior); },
                      [](const py::dict& kwargs) { return py::cast<Ior>(py::type::of<Ior>()(**kwargs)); }));
}

}  // namespace refracta
