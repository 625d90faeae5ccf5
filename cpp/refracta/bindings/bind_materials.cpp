// Python bindings of the materials (shading/*.h): one class per BSDF, each pickled through its
// constructor's keyword arguments (bind_shading.h's def_material).
#include "generated/docstrings.h"
#include "refracta/bindings/bind_shading.h"

#include "refracta/core/error.h"
#include "refracta/scene/textures.h"
#include "refracta/shading/conductor.h"
#include "refracta/shading/dielectric.h"
#include "refracta/shading/diffuse.h"
#include "refracta/shading/phong.h"
#include "refracta/shading/plastic.h"
#include "refracta/shading/principled.h"
#include "refracta/shading/thin_film.h"

#include <filesystem>

namespace refracta {

TexturedReflectance to_textured(const py::object& color, const char* name, const py::object& texture) {
  const Vec3d rgb = to_rgb(color, name);
  if (texture.is_none()) return TexturedReflectance(rgb, name);
  if (py::isinstance<py::str>(texture) || py::hasattr(texture, "__fspath__")) {
    const py::object path_object = py::module_::import("os").attr("fspath")(texture);
    if (!py::isinstance<py::str>(path_object)) throw_invalid("texture must be a str path (got bytes)");
    const std::string path = py::cast<std::string>(path_object);
    check_texture_file(path);
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

// ior= (a number or a glass's name; None: Ior's default) or sellmeier= (six numbers), not both.
Ior to_ior(const py::object& ior, const py::object& sellmeier) {
  if (!sellmeier.is_none()) {
    if (!ior.is_none()) {
      throw_invalid("give ior or sellmeier, not both (got ior=", py::repr(ior).cast<std::string>(), ")");
    }
    if (py::isinstance<py::str>(sellmeier)) {
      throw_invalid("sellmeier must be six numbers (B1, B2, B3, C1, C2, C3), C in um^2 (got a string; a glass by "
                    "name is ior='bk7')");
    }
    std::vector<double> values;
    try {
      values = to_values(sellmeier, "sellmeier");
    } catch (const std::invalid_argument&) {  // its message would offer "a number"
      throw_invalid("sellmeier must be six numbers (B1, B2, B3, C1, C2, C3), C in um^2 (got ",
                    py::repr(sellmeier).cast<std::string>(), ")");
    }
    return Ior::sellmeier(values);
  }
  if (ior.is_none()) return Ior();
  return py::isinstance<py::str>(ior) ? Ior::named(ior.cast<std::string>()) : Ior(to_number(ior, "ior"));
}

py::tuple rgb_tuple(const Vec3d& v) { return py::make_tuple(v.x(), v.y(), v.z()); }
py::object optional_rgb_tuple(const std::optional<Vec3d>& v) { return v ? py::object(rgb_tuple(*v)) : py::object(py::none()); }
py::object texture_argument(const TexturedReflectance& r) {
  if (!r.path().empty()) return py::str(r.path());
  return r.texture() >= 0 ? py::object(py::int_(r.texture())) : py::object(py::none());
}

py::dict with_ior(py::dict kwargs, const Ior& ior) {
  const auto& b = ior.sellmeier_b();
  const auto& c = ior.sellmeier_c();
  if (ior.dispersive()) {
    kwargs["sellmeier"] = py::make_tuple(b[0], b[1], b[2], c[0], c[1], c[2]);
  } else {
    kwargs["ior"] = ior.rgb_value();
  }
  return kwargs;
}

namespace {

// Glass: smooth, rough and thin.
void bind_dielectrics(py::module_& m) {
  def_material<Dielectric>(m, "Dielectric", DOC(refracta, Dielectric),
      py::init([](const py::object& ior, const py::object& sellmeier, int priority) {
        return std::make_shared<Dielectric>(to_ior(ior, sellmeier), priority);
      }),
      [](const Dielectric& m) { return with_ior(py::dict(py::arg("priority") = m.priority()), m.ior()); },
      py::arg("ior") = py::none(), py::arg("sellmeier") = py::none(), py::arg("priority") = 0);

  def_material<RoughDielectric>(m, "RoughDielectric", DOC(refracta, RoughDielectric),
      py::init([](std::optional<double> alpha, const py::object& ior, const py::object& sellmeier, int priority,
                  std::optional<double> alpha_u, std::optional<double> alpha_v) {
        const auto a = alphas_from(alpha, alpha_u, alpha_v, true, 0.0);
        return std::make_shared<RoughDielectric>(a.first, a.second, to_ior(ior, sellmeier), priority);
      }),
      [](const RoughDielectric& m) {
        return with_ior(py::dict(py::arg("alpha_u") = m.alpha_u(), py::arg("alpha_v") = m.alpha_v(),
                                 py::arg("priority") = m.priority()),
                        m.ior());
      },
      py::arg("alpha") = py::none(), py::arg("ior") = py::none(), py::arg("sellmeier") = py::none(),
      py::arg("priority") = 0,
      py::arg("alpha_u") = py::none(), py::arg("alpha_v") = py::none());

  def_material<ThinDielectric>(m, "ThinDielectric", DOC(refracta, ThinDielectric),
      py::init([](const py::object& ior, const py::object& sellmeier) { return std::make_shared<ThinDielectric>(to_ior(ior, sellmeier)); }),
      [](const ThinDielectric& m) { return with_ior(py::dict(), m.ior()); },
      py::arg("ior") = py::none(), py::arg("sellmeier") = py::none());
}

}  // namespace

void bind_materials(py::module_& m) {
  bind_dielectrics(m);
  const PrincipledParameters kPrincipled;  // Principled's defaults
  def_material<Diffuse>(m, "Diffuse", textured_doc(DOC(refracta, Diffuse)).c_str(),
      py::init([](const py::object& reflectance, const py::object& texture) {
        return std::make_shared<Diffuse>(to_textured(reflectance, "reflectance", texture));
      }),
      [](const Diffuse& m) {
        return py::dict(py::arg("reflectance") = rgb_tuple(m.reflectance().rgb()), py::arg("texture") = texture_argument(m.reflectance()));
  },
      py::arg("reflectance") = 0.5, py::arg("texture") = py::none());

  def_material<BlinnPhong>(m, "BlinnPhong", textured_doc(DOC(refracta, BlinnPhong)).c_str(),
      py::init([](const py::object& kd, const py::object& ks, double ns, const py::object& texture, double alpha) {
        return std::make_shared<BlinnPhong>(to_textured(kd, "kd", texture), to_rgb(ks, "ks"), ns, alpha);
      }),
      [](const BlinnPhong& m) {
        return py::dict(py::arg("kd") = rgb_tuple(m.kd().rgb()), py::arg("ks") = rgb_tuple(m.ks()), py::arg("ns") = m.ns(),
                    py::arg("texture") = texture_argument(m.kd()), py::arg("alpha") = m.alpha());
  },
      py::arg("kd") = BlinnPhong::kDefaultKd, py::arg("ks") = 0.0, py::arg("ns") = BlinnPhong::kDefaultNs,
      py::arg("texture") = py::none(), py::arg("alpha") = 1.0);

  def_material<Conductor>(m, "Conductor", DOC(refracta, Conductor),
      py::init([](const py::object& eta, const py::object& k) {
        return std::make_shared<Conductor>(to_optional_rgb(eta, "eta"), to_optional_rgb(k, "k"));
      }),
      [](const Conductor& m) {
        return py::dict(py::arg("eta") = optional_rgb_tuple(m.index().eta()), py::arg("k") = optional_rgb_tuple(m.index().k()));
  },
      py::arg("eta") = py::none(), py::arg("k") = py::none());

  def_material<RoughConductor>(m, "RoughConductor", DOC(refracta, RoughConductor),
      py::init([](std::optional<double> alpha, std::optional<double> alpha_u, std::optional<double> alpha_v,
                       const py::object& eta, const py::object& k) {
        const auto a = alphas_from(alpha, alpha_u, alpha_v, true, 0.0);
        return std::make_shared<RoughConductor>(a.first, a.second, to_optional_rgb(eta, "eta"), to_optional_rgb(k, "k"));
      }),
      [](const RoughConductor& m) {
        return py::dict(py::arg("alpha_u") = m.alpha_u(), py::arg("alpha_v") = m.alpha_v(),
                    py::arg("eta") = optional_rgb_tuple(m.index().eta()), py::arg("k") = optional_rgb_tuple(m.index().k()));
  },
      py::arg("alpha") = py::none(), py::arg("alpha_u") = py::none(), py::arg("alpha_v") = py::none(),
           py::arg("eta") = py::none(), py::arg("k") = py::none());

  def_material<Plastic>(m, "Plastic", textured_doc(DOC(refracta, Plastic)).c_str(),
      py::init([](const py::object& reflectance, double ior, std::optional<double> alpha, std::optional<double> alpha_u,
                  std::optional<double> alpha_v, const py::object& texture) {
        const auto a = alphas_from(alpha, alpha_u, alpha_v, false, 0.0);
        return std::make_shared<Plastic>(to_textured(reflectance, "reflectance", texture), ior, a.first, a.second);
      }),
      [](const Plastic& m) {
        return py::dict(py::arg("reflectance") = rgb_tuple(m.reflectance().rgb()), py::arg("ior") = m.ior(), py::arg("alpha_u") = m.alpha_u(),
                    py::arg("alpha_v") = m.alpha_v(), py::arg("texture") = texture_argument(m.reflectance()));
  },
      py::arg("reflectance") = 0.5, py::arg("ior") = Plastic::kDefaultIor, py::arg("alpha") = py::none(), py::arg("alpha_u") = py::none(),
           py::arg("alpha_v") = py::none(), py::arg("texture") = py::none());

  def_material<Principled>(m, "Principled", textured_doc(DOC(refracta, Principled)).c_str(),
      py::init([](const py::object& base_color, double metallic, double roughness, double anisotropic, double specular,
                       double specular_tint, double sheen, double sheen_tint, double clearcoat, double clearcoat_gloss,
                       const py::object& texture) {
        const PrincipledParameters p{metallic, roughness, anisotropic, specular, specular_tint,
                                          sheen,    sheen_tint, clearcoat,  clearcoat_gloss};
        return std::make_shared<Principled>(to_textured(base_color, "base_color", texture), p);
      }),
      [](const Principled& m) {
        const PrincipledParameters& p = m.parameters();
        return py::dict(py::arg("base_color") = rgb_tuple(m.base_color().rgb()), py::arg("metallic") = p.metallic,
                    py::arg("roughness") = p.roughness, py::arg("anisotropic") = p.anisotropic, py::arg("specular") = p.specular,
                    py::arg("specular_tint") = p.specular_tint, py::arg("sheen") = p.sheen, py::arg("sheen_tint") = p.sheen_tint,
                    py::arg("clearcoat") = p.clearcoat, py::arg("clearcoat_gloss") = p.clearcoat_gloss,
                    py::arg("texture") = texture_argument(m.base_color()));
  },
      py::arg("base_color") = 0.5, py::arg("metallic") = kPrincipled.metallic, py::arg("roughness") = kPrincipled.roughness,
           py::arg("anisotropic") = kPrincipled.anisotropic, py::arg("specular") = kPrincipled.specular,
           py::arg("specular_tint") = kPrincipled.specular_tint, py::kw_only(), py::arg("sheen") = kPrincipled.sheen,
           py::arg("sheen_tint") = kPrincipled.sheen_tint, py::arg("clearcoat") = kPrincipled.clearcoat,
           py::arg("clearcoat_gloss") = kPrincipled.clearcoat_gloss, py::arg("texture") = py::none());

  def_material<ThinFilm>(m, "ThinFilm", DOC(refracta, ThinFilm),
      py::init([](double thickness, double film_ior, const py::object& eta, const py::object& k, std::optional<double> alpha,
                  std::optional<double> alpha_u, std::optional<double> alpha_v) {
        const auto a = alphas_from(alpha, alpha_u, alpha_v, false, ThinFilm::kDefaultAlpha);
        return std::make_shared<ThinFilm>(thickness, film_ior, to_rgb(eta, "eta"), to_rgb(k, "k"), a.first, a.second);
      }),
      [](const ThinFilm& m) {
        return py::dict(py::arg("thickness") = m.thickness(), py::arg("film_ior") = m.film_ior(), py::arg("eta") = rgb_tuple(m.eta()),
                    py::arg("k") = rgb_tuple(m.k()), py::arg("alpha_u") = m.alpha_u(), py::arg("alpha_v") = m.alpha_v());
  },
      py::arg("thickness"), py::arg("film_ior") = ThinFilm::kDefaultFilmIor, py::arg("eta") = ThinFilm::kDefaultEta,
           py::arg("k") = ThinFilm::kDefaultK, py::arg("alpha") = py::none(),
           py::kw_only(), py::arg("alpha_u") = py::none(), py::arg("alpha_v") = py::none());

}

}  // namespace refracta
