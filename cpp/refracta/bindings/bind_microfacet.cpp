// Python bindings of the microfacet distributions (shading/microfacet.h, beckmann.h), the Fresnel
// functions (fresnel.h) and indices of refraction (ior.h), vectorised over numpy arrays.
#include "refracta/bindings/bind_shading.h"

#include "refracta/shading/beckmann.h"
#include "refracta/shading/fresnel.h"
#include "refracta/shading/microfacet.h"
#include "refracta/shading/thin_film.h"

#include <cmath>
#include <complex>

namespace refracta {

namespace {

void bind_fresnel(py::module_& m) {
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
      py::arg("cos_i"), py::arg("n1"), py::arg("n2"), py::arg("eta"), py::arg("k"), py::kw_only(), py::arg("thickness"),
      py::arg("wavelength"),
      "Airy reflectance of a film (index n2, thickness [nm]) between n1 and a base eta + i k at a wavelength [nm]. Vectorised.");
}

// f at each of the (N, 3) unit vectors `a`: an (N,) array.
template <class F>
DoubleArray per_direction(const py::object& a, const char* a_name, const F& f) {
  std::vector<double> out;
  for (const Vec3d& v : to_unit_vectors(a, a_name)) out.push_back(f(v));
  return values_to_array(out);
}

// f at each pair of (N, 3) unit vectors a and b, one of them possibly a single vector (broadcast).
template <class F>
DoubleArray per_direction_pair(const py::object& a, const char* a_name, const py::object& b, const char* b_name,
                               const F& f) {
  const auto va = to_unit_vectors(a, a_name), vb = to_unit_vectors(b, b_name);
  const size_t n = broadcast(va.size(), vb.size(), concat(a_name, " and ", b_name).c_str());
  std::vector<double> out(n);
  for (size_t i = 0; i < n; ++i) out[i] = f(va[va.size() == 1 ? 0 : i], vb[vb.size() == 1 ? 0 : i]);
  return values_to_array(out);
}

// The methods every microfacet distribution has: D(m), G1(w) and the height-correlated G(wo, wi).
template <class Distribution>
void def_masking(py::class_<Distribution>& cls) {
  cls.def("D", [](const Distribution& d, const py::object& m) {
       return per_direction(m, "m", [&](const Vec3d& v) { return d.D(v); });
     }, py::arg("m"))
      .def("G1", [](const Distribution& d, const py::object& w) {
        return per_direction(w, "w", [&](const Vec3d& v) { return d.G1(v); });
      }, py::arg("w"))
      .def("G", [](const Distribution& d, const py::object& wo, const py::object& wi) {
        return per_direction_pair(wo, "wo", wi, "wi", [&](const Vec3d& o, const Vec3d& i) { return d.G(o, i); });
      }, py::arg("wo"), py::arg("wi"));
}

}  // namespace

void bind_microfacet(py::module_& m) {
  bind_fresnel(m);
  py::class_<Beckmann> beckmann(m, "Beckmann",
                       "The isotropic Beckmann microfacet distribution (beckmann.h): D, Lambda (exact, with erf), G1 and\n"
                       "the height-correlated G. alpha^2 is the total mean-square slope. Directions: (N, 3) unit vectors.");
  beckmann.def(py::init([](double alpha) { return Beckmann(TrowbridgeReitz::checked_alpha(alpha, "alpha")); }), py::arg("alpha"))
      .def_property_readonly("alpha", &Beckmann::alpha)
      .def(py::pickle([](const Beckmann& d) { return py::make_tuple(d.alpha()); },
                      [](const py::tuple& t) {
                        if (t.size() != 1) throw_invalid("Beckmann: bad pickle state");
                        return Beckmann(TrowbridgeReitz::checked_alpha(py::cast<double>(t[0]), "alpha"));
                      }));
  def_masking(beckmann);

  py::class_<TrowbridgeReitz> ggx(m, "TrowbridgeReitz",
                              "The GGX microfacet distribution (microfacet.h): D, Lambda, G1, height-correlated G, the\n"
                              "visible-normal density and sampler. Directions: (N, 3) unit vectors in the local frame.");
  ggx.def(py::init([](double alpha_x, double alpha_y) {
             return TrowbridgeReitz(TrowbridgeReitz::checked_alpha(alpha_x, "alpha_x"), TrowbridgeReitz::checked_alpha(alpha_y, "alpha_y"));
           }),
           py::arg("alpha_x"), py::arg("alpha_y"))
      .def("D_visible", [](const TrowbridgeReitz& d, const py::object& w, const py::object& m) {
        return per_direction_pair(w, "w", m, "m", [&](const Vec3d& a, const Vec3d& b) { return d.D_visible(a, b); });
      }, py::arg("w"), py::arg("m"))
      .def("sample_wm", [](const TrowbridgeReitz& d, const py::object& w_, const py::object& u_) {
        const auto w = to_unit_vectors(w_, "w");
        const Samples u = to_samples(u_, "u", 2);
        const size_t n = broadcast(w.size(), u.rows, "w and u");
        std::vector<Vec3d> out(n);
        for (size_t i = 0; i < n; ++i) out[i] = d.sample_wm(w[w.size() == 1 ? 0 : i], u.pair(u.rows == 1 ? 0 : i));
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
  def_masking(ggx);

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
