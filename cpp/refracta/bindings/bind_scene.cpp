// Python bindings of scenes, cameras, lights and image files (cpp/refracta/scene, shading).
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/bindings/pickle_state.h"

#include "refracta/scene/image_io.h"
#include "refracta/scene/obj_loader.h"
#include "refracta/scene/texture_search.h"
#include "refracta/shading/area_light.h"
#include "refracta/shading/constant_environment.h"
#include "refracta/shading/dielectric.h"
#include "refracta/shading/environment_light.h"
#include "refracta/shading/phong.h"
#include "refracta/shading/physical_sky.h"
#include "refracta/shading/point_light.h"
#include "refracta/shading/principled.h"
#include "refracta/shading/scaled_light.h"
#include "refracta/shading/sphere_light.h"
#include "refracta/shading/spot_light.h"
#include "refracta/shading/sun_light.h"
#include "refracta/shading/tonemap.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>

namespace refracta {

namespace {

Vec3d to_rgb(const py::handle& value, const char* what) { return to_point(value, what); }

// The material of an add_* call: `material` when given, else the Blinn-Phong shorthand (kd, ks,
// ns, a kd texture, alpha), as the MTL files and the early API have it.
int material_of(RenderScene& s, const py::object& material, const py::object& kd, const py::object& ks, double ns,
                int texture = -1, double alpha = 1.0) {
  if (!material.is_none()) {
    std::shared_ptr<Material> m;
    try {
      m = py::cast<std::shared_ptr<Material>>(material);
    } catch (const py::cast_error&) {
      throw_invalid("material must be a refracta.shading material (got ", std::string(py::str(py::type::of(material))), ")");
    }
    return s.add_material(m);
  }
  return s.add_material(std::make_shared<BlinnPhong>(TexturedReflectance(to_rgb(kd, "kd"), "kd", texture), to_rgb(ks, "ks"), ns, alpha));
}

// A geometry id from Python (negative ids name nothing).
unsigned geometry_id(int geometry) {
  if (geometry < 0) throw_invalid("geometry must be an id returned by add_* (got ", geometry, ")");
  return unsigned(geometry);
}

// Progress of the textures an add_obj prepares: reports (done, total) distinct files to a
// callable, or to a refracta._progress.ProgressBar (progress=True) once preparing has taken
// kQuietSeconds: a model whose textures are cached, or has a few, loads without a bar.
class TextureProgress {
 public:
  // Portland's 236 textures take ~11 s to prepare, a small model's few well under a second.
  static constexpr double kQuietSeconds = 1.0;

  TextureProgress(const std::vector<std::string>& paths, const py::object& progress)
      : total_(std::set<std::string>(paths.begin(), paths.end()).size() - (std::count(paths.begin(), paths.end(), "") > 0)) {
    if (py::isinstance<py::bool_>(progress)) {
      if (progress.cast<bool>()) {
        callback_ = py::module_::import("refracta._progress")
                        .attr("ProgressBar")("preparing textures", py::arg("quiet_seconds") = kQuietSeconds);
      }
    } else if (PyCallable_Check(progress.ptr())) {
      callback_ = progress;
    } else {
      throw_invalid("progress must be True, False or a callable progress(done, total)");
    }
  }
  // A texture was registered (the same file again counts once).
  void added(const std::string& path) {
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C between textures
    if (!seen_.insert(path).second) return;
    if (callback_) callback_(seen_.size(), total_);
  }

 private:
  size_t total_;
  py::object callback_;
  std::set<std::string> seen_;
};

// A textured material needs texture coordinates: refuse it on geometry without uvs, saying how.
void check_uvs(const RenderScene& s, int material, bool has_uvs, const char* what) {
  if (has_uvs || !s.material(material).textured()) return;
  throw_invalid(what, ": ", s.material(material).describe(),
                " has a texture but this geometry has no texture coordinates; give the mesh uvs= (add_mesh),"
                " use add_ground (its texture_size sets the repeat) or an OBJ with vt lines, or drop the texture");
}

// An illuminant colour, its errors naming the argument.
Color illuminant_of(const py::handle& value, const char* what) {
  const Vec3d rgb = to_rgb(value, what);
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(rgb[i]) || rgb[i] < 0.0) throw_invalid(what, " must be finite and >= 0 (got ", rgb[i], ")");
  }
  return Color::illuminant(rgb);
}

// An emissive geometry's area light (emission: RGB radiance [W/(m^2 sr)] or None).
void add_emission(RenderScene& s, unsigned geometry, const py::object& emission, bool two_sided) {
  if (emission.is_none()) return;
  const Color radiance = illuminant_of(emission, "emission");
  if (s.geometry.is_spheres(geometry)) {
    throw_invalid("emissive spheres: use add_sphere(..., emission=...)");
  }
  s.add_light(std::make_shared<AreaLight>(s.geometry.meshes().at(geometry).mesh, radiance, two_sided), int(geometry));
}

Mesh mesh_from(const py::object& vertices, const py::object& triangles) {
  Mesh mesh;
  mesh.vertices = to_points(vertices, "vertices");
  py::array_t<long long, py::array::c_style | py::array::forcecast> t;
  try {
    t = py::cast<decltype(t)>(triangles);
  } catch (const py::cast_error&) {
    throw_invalid("triangles must be an integer array of shape (M, 3)");
  }
  if (t.ndim() != 2 || t.shape(1) != 3) throw_invalid("triangles must have shape (M, 3)");
  mesh.triangles.resize(size_t(t.shape(0)));
  for (py::ssize_t i = 0; i < t.shape(0); ++i) {
    for (int k = 0; k < 3; ++k) mesh.triangles[size_t(i)][k] = int(std::clamp<long long>(t.at(i, k), -1, 1LL << 30));
  }
  return mesh;
}

// A gradient sky as a small equirectangular map: linear in sin(elevation) from the horizon (and
// below) to the zenith, constant in azimuth (rows from the zenith down).
Image gradient_sky(const Vec3d& horizon, const Vec3d& zenith) {
  constexpr int kRows = 256, kColumns = 4;
  Image image(kColumns, kRows, 3);
  for (int y = 0; y < kRows; ++y) {
    const double theta = kPi * (y + 0.5) / kRows;  // from the zenith
    const double t = std::clamp(std::cos(theta), 0.0, 1.0);
    const Vec3d c = (1.0 - t) * horizon + t * zenith;
    for (int x = 0; x < kColumns; ++x) {
      for (int k = 0; k < 3; ++k) image.at(x, y)[k] = float(c[k]);
    }
  }
  return image;
}

// An environment map read from a file, remembering the file (a pickled scene refers to it).
std::shared_ptr<EnvironmentLight> environment_from_file(const std::string& path, double scale, const Mat3d& rotation) {
  auto light = std::make_shared<EnvironmentLight>(read_image(path), scale, rotation);
  light->set_source(std::filesystem::absolute(path).string());
  return light;
}

Mat3d rotation_from(const py::object& rotation) {
  if (rotation.is_none()) return Mat3d::Identity();
  if (py::isinstance<py::float_>(rotation) || py::isinstance<py::int_>(rotation)) {
    return EnvironmentLight::rotation_about_y(py::cast<double>(rotation));
  }
  DoubleArray array;
  try {
    array = real_array(rotation, "rotation");
  } catch (const py::cast_error&) {
    throw_invalid("rotation must be an angle about y [deg] or a 3 x 3 rotation matrix");
  }
  if (array.ndim() != 2 || array.shape(0) != 3 || array.shape(1) != 3) {
    throw_invalid("rotation must be an angle about y [deg] or a 3 x 3 rotation matrix");
  }
  Mat3d m;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m(i, j) = array.at(i, j);
  }
  return m;
}

std::vector<Eigen::Vector2d> to_uvs(const py::object& object, size_t count) {
  DoubleArray array;
  try {
    array = real_array(object, "uvs");
  } catch (const py::cast_error&) {
    throw_invalid("uvs must be a float array of shape (N, 2)");
  }
  if (array.ndim() != 2 || array.shape(1) != 2 || size_t(array.shape(0)) != count) {
    throw_invalid("uvs must have shape (", count, ", 2): one per vertex");
  }
  std::vector<Eigen::Vector2d> out(count);
  for (size_t i = 0; i < count; ++i) {
    out[i] = Eigen::Vector2d(array.at(i, 0), array.at(i, 1));
    if (!std::isfinite(out[i].x()) || !std::isfinite(out[i].y())) throw_invalid("uvs must be finite");
  }
  return out;
}

Image array_to_image(const py::object& object) {
  py::array_t<float, py::array::c_style | py::array::forcecast> array;
  try {
    array = py::cast<py::array_t<float, py::array::c_style | py::array::forcecast>>(object);
  } catch (const py::cast_error&) {
    throw_invalid("image must be a float array of shape (H, W, C)");
  }
  if (array.ndim() == 2) array = array.reshape({array.shape(0), array.shape(1), py::ssize_t(1)});
  if (array.ndim() != 3 || array.shape(2) < 1 || array.shape(2) > 4 || array.shape(0) < 1 || array.shape(1) < 1) {
    throw_invalid("image must have shape (H, W), (H, W, 1..4)");
  }
  Image image(int(array.shape(1)), int(array.shape(0)), int(array.shape(2)));
  std::copy(array.data(), array.data() + array.size(), image.pixels.begin());
  for (float v : image.pixels) {
    if (!std::isfinite(v)) throw_invalid("image must be finite (found ", v, ")");
  }
  return image;
}

// The display arguments io.write_image and io.to_display pass through (None: DisplaySettings'
// default), as DisplaySettings (shading/tonemap.h).
// gamma: 'srgb', 'linear' or a number g in [1, 3] (p = l^(1/g)).
struct DisplayArgs {
  std::optional<double> exposure, ev100, iso, shutter, f_number, key, white;
  std::optional<std::string> tonemap;
  py::object gamma;
  std::optional<double> luminous_efficacy;
};

DisplaySettings display_settings(const DisplayArgs& args) {
  DisplaySettings settings;
  settings.exposure = args.exposure;
  settings.ev100 = args.ev100;
  settings.iso = args.iso, settings.shutter = args.shutter, settings.f_number = args.f_number;
  if (args.luminous_efficacy) settings.luminous_efficacy = *args.luminous_efficacy;
  if (args.tonemap) settings.tonemap = parse_tonemap(*args.tonemap);
  settings.key = args.key;
  settings.white = args.white;
  const py::object& gamma = args.gamma;
  if (py::isinstance<py::str>(gamma)) {
    const std::string name = py::cast<std::string>(gamma);
    if (name == "srgb") {
      settings.transfer = Transfer::kSrgb;
    } else if (name == "linear") {
      settings.transfer = Transfer::kGamma, settings.gamma = 1.0;
    } else {
      throw_invalid("gamma must be 'srgb', 'linear' or a number in [1, 3] (got '", name, "')");
    }
  } else {
    try {
      settings.transfer = Transfer::kGamma, settings.gamma = py::cast<double>(gamma);
    } catch (const py::cast_error&) {
      throw_invalid("gamma must be 'srgb', 'linear' or a number in [1, 3]");
    }
  }
  settings.validate();
  return settings;
}

}  // namespace

py::array_t<float> image_to_float32(const Image& image) {
  py::array_t<float> out({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(image.channels)});
  std::copy(image.pixels.begin(), image.pixels.end(), out.mutable_data());
  return out;
}

py::array_t<float> image_to_float32(Image&& image) {
  // The pixels move into the array's owner: a 4K frame is not held twice.
  auto* pixels = new std::vector<float>(std::move(image.pixels));
  py::capsule owner(pixels, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array_t<float>({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(image.channels)},
                            pixels->data(), owner);
}

namespace {

// set_physical_sky: the sky light and the sun it implies. Both are spectral radiance
// [W/(m^2 sr nm)] in spectral renders and its CIE-Y-weighted mean over wavelength in RGB (linear
// sRGB of XYZ / integral ybar), the convention of Color::illuminant: RGB (1, 1, 1) is D65 at
// 1 W/(m^2 sr nm) mean; multiply by integral ybar = 106.86 nm for W/(m^2 sr).
void set_physical_sky(RenderScene& s, const PhysicalSkySettings& settings, double sun_diameter, double limb_darkening,
                      double scale) {
  settings.validate();
  if (!(sun_diameter > 0.0 && sun_diameter < 180.0)) throw_invalid("sun_angular_diameter must be in (0, 180) deg (got ", sun_diameter, ")");
  if (!(limb_darkening >= 0.0 && limb_darkening <= 1.0)) throw_invalid("limb_darkening must be in [0, 1] (got ", limb_darkening, ")");
  if (!(scale >= 0.0) || !std::isfinite(scale)) throw_invalid("scale must be >= 0 and finite (got ", scale, ")");
  std::shared_ptr<PhysicalSkyLight> sky;
  WorkControl control;  // the table: ~0.5 s over oneTBB, stopped by Ctrl-C
  run_interruptible(control, py::none(), [&] { sky = std::make_shared<PhysicalSkyLight>(settings); });
  // The sun's disc radiance at the sky's 10 nm nodes (Color::tabulated interpolates to 1 nm).
  std::vector<double> lambda, radiance;
  for (int i = 0; i < PhysicalSky::kWavelengths; ++i) {
    lambda.push_back(PhysicalSky::wavelength(i));
    radiance.push_back(scale * sky->sky().sun_radiance(lambda.back(), sun_diameter));
  }
  const Color sun_colour = Color::tabulated(lambda, radiance, Color::Kind::kIlluminant);
  s.remove_lights_if([](const Light& l) { return l.is_infinite(); });
  if (scale > 0.0) s.add_light(scale == 1.0 ? LightPtr(sky) : std::make_shared<ScaledInfiniteLight>(sky, scale));
  if (!sun_colour.is_black() && sun_colour.rgb().maxCoeff() > 0.0) {
    s.add_light(std::make_shared<SunLight>(settings.sun_direction, sun_colour, sun_diameter, limb_darkening));
  }
}

// Folders given as one path or a sequence of paths (str or os.PathLike).
std::vector<std::string> to_folders(const py::object& dirs) {
  const py::object fspath = py::module_::import("os").attr("fspath");
  if (py::isinstance<py::str>(dirs) || py::hasattr(dirs, "__fspath__")) return {py::cast<std::string>(fspath(dirs))};
  std::vector<std::string> out;
  try {
    for (const auto& item : dirs) out.push_back(py::cast<std::string>(fspath(item)));
  } catch (const py::error_already_set& error) {
    if (!error.matches(PyExc_TypeError)) throw;
    throw_invalid("texture_dirs must be a folder or a sequence of folders (str or os.PathLike)");
  }
  return out;
}

// refracta.TextureNotFoundError, created by bind_scene: both a refracta.IoError (what every missing
// file raises) and a FileNotFoundError. Kept for the life of the process, as pybind11's exceptions.
PyObject* texture_not_found_error = nullptr;

// The texture file of each part of an OBJ ("" for none): map_Kd searched by find_texture. A
// texture found nowhere raises FileNotFoundError, or with `warn` a UserWarning (once per name)
// and "" (the material keeps Kd).
std::vector<std::string> obj_texture_paths(const std::vector<MaterialMesh>& parts,
                                           const std::vector<std::string>& texture_dirs, bool warn) {
  std::vector<std::string> out;
  std::set<std::string> warned;
  for (const MaterialMesh& part : parts) {
    const MtlMaterial& mtl = part.material;
    if (mtl.texture_name.empty()) {
      out.emplace_back();
      continue;
    }
    std::vector<std::string> searched;
    const auto found = find_texture(mtl.texture_name, mtl.folder, texture_dirs, &searched);
    if (found) {
      out.push_back(*found);
      continue;
    }
    std::string folders;
    for (const auto& folder : searched) folders += concat(folders.empty() ? "" : ", ", "'", folder, "'");
    const std::string message = concat("texture '", mtl.texture_name, "' of material '", mtl.name,
                                       "' not found in ", folders);
    if (!warn) {
      PyErr_SetString(texture_not_found_error, message.c_str());
      throw py::error_already_set();
    }
    if (warned.insert(mtl.texture_name).second &&
        PyErr_WarnEx(PyExc_UserWarning, (message + "; its material uses Kd").c_str(), 1) != 0) {
      throw py::error_already_set();  // warnings turned into errors
    }
    out.emplace_back();
  }
  return out;
}

}  // namespace

void bind_scene(py::module_& m) {
  if (!texture_not_found_error) {
    py::tuple bases = py::make_tuple(m.attr("IoError"), py::handle(PyExc_FileNotFoundError));  // IoError: bind_core
    texture_not_found_error = PyErr_NewExceptionWithDoc(
        "refracta._core.TextureNotFoundError",
        "A texture an MTL file names is in none of the folders searched (a refracta.IoError and a FileNotFoundError).",
        bases.ptr(), nullptr);
    if (!texture_not_found_error) throw py::error_already_set();
  }
  m.attr("TextureNotFoundError") = py::handle(texture_not_found_error);
  py::class_<RenderScene, std::shared_ptr<RenderScene>>(m, "Scene", R"doc(
Geometry (Embree), materials (refracta.shading) and lights. Scene() starts empty: no sun, no sky,
black. Every add_* takes material= (any refracta.shading material); without it the Blinn-Phong
shorthand kd (diffuse albedo, RGB in [0, 1]), ks (specular albedo), ns (Phong exponent) applies.
Meshes and spheres with emission= [W/(m^2 sr), RGB] are area lights (one-sided on the triangles'
counter-clockwise front unless two_sided). Units: metres, y up.)doc")
      .def(py::init<>())
      .def("add_mesh",
           [](RenderScene& s, const py::object& vertices, const py::object& triangles, const py::object& material,
              const py::object& emission, bool two_sided, const py::object& normals, const py::object& uvs,
              const py::object& kd, const py::object& ks, double ns, std::optional<std::string> texture, double alpha) {
             Mesh mesh = mesh_from(vertices, triangles);
             if (!uvs.is_none()) mesh.uvs = to_uvs(uvs, mesh.vertices.size());
             if (!normals.is_none()) {
               mesh.normals = to_points(normals, "normals");
               if (mesh.normals.size() != mesh.vertices.size()) throw_invalid("normals must have one entry per vertex");
               for (auto& n : mesh.normals) {
                 if (!(n.norm() > 0.0)) throw_invalid("normals must be non-zero");
                 n.normalize();
               }
             }
             const int tex = texture ? s.geometry.textures().add(*texture) : -1;
             if (tex >= 0 && mesh.uvs.empty()) throw_invalid("add_mesh: a texture needs uvs");
             const int material_id = material_of(s, material, kd, ks, ns, tex, alpha);
             check_uvs(s, material_id, !mesh.uvs.empty(), "add_mesh");
             const unsigned id = s.geometry.add_mesh(mesh, material_id);
             add_emission(s, id, emission, two_sided);
             return id;
           },
           py::arg("vertices"), py::arg("triangles"), py::arg("material") = py::none(), py::arg("emission") = py::none(),
           py::arg("two_sided") = false, py::arg("normals") = py::none(), py::arg("uvs") = py::none(),
           py::arg("kd") = py::make_tuple(0.5, 0.5, 0.5), py::arg("ks") = py::make_tuple(0.0, 0.0, 0.0),
           py::arg("ns") = 1.0, py::arg("texture") = py::none(), py::arg("alpha") = 1.0,
           "Add a triangle mesh: vertices (N, 3) [m], triangles (M, 3) indices (front: counter-clockwise);\n"
           "optional per-vertex normals (N, 3) (shading normals, interpolated) and uvs (N, 2) texture\n"
           "coordinates (u right, v up); emission makes it an area light. The kd/ks/ns/texture/alpha\n"
           "shorthand (texture multiplies kd; alpha < 1: transparent in render_raster) applies without\n"
           "material. Returns its id.")
      .def("add_obj",
           [](RenderScene& s, const std::string& path, const py::object& offset, double scale,
              const py::object& texture_dirs, const std::string& missing_textures, const py::object& progress) {
             const Vec3d shift = to_point(offset, "offset");
             if (!(scale > 0.0) || !std::isfinite(scale)) throw_invalid("scale must be > 0 (got ", scale, ")");
             if (missing_textures != "error" && missing_textures != "warn") {
               throw_invalid("missing_textures must be 'error' or 'warn' (got '", missing_textures, "')");
             }
             std::vector<MaterialMesh> parts = load_obj(path);
             const std::vector<std::string> textures = obj_texture_paths(parts, to_folders(texture_dirs), missing_textures == "warn");
             TextureProgress preparing(textures, progress);
             py::list ids;
             for (size_t p = 0; p < parts.size(); ++p) {
               MaterialMesh& part = parts[p];
               for (auto& v : part.mesh.vertices) v = v * scale + shift;
               const MtlMaterial& mtl = part.material;
               const int tex = textures[p].empty() ? -1 : s.geometry.add_texture(textures[p]);
               if (tex >= 0) preparing.added(textures[p]);
               MaterialPtr material;
               if ((mtl.illum == 4 || mtl.illum == 6 || mtl.illum == 7) && mtl.alpha < 1.0 && mtl.ni > 1.0) {
                 material = std::make_shared<Dielectric>(Ior(mtl.ni));  // MTL glass
               } else if (mtl.pr >= 0.0 || mtl.pm >= 0.0) {  // the PBR extension: Pr, Pm
                 PrincipledParameters p;
                 p.roughness = mtl.pr >= 0.0 ? mtl.pr : 0.5;
                 p.metallic = mtl.pm >= 0.0 ? mtl.pm : 0.0;
                 material = std::make_shared<Principled>(TexturedReflectance(mtl.kd, "Kd", tex), p);
               } else {
                 material = std::make_shared<BlinnPhong>(TexturedReflectance(mtl.kd, "Kd", tex), mtl.ks, mtl.ns, mtl.alpha);
               }
               const unsigned id = s.geometry.add_mesh(part.mesh, s.add_material(material));
               if (mtl.ke.maxCoeff() > 0.0) {
                 s.add_light(std::make_shared<AreaLight>(part.mesh, Color::illuminant(mtl.ke), false), int(id));
               }
               ids.append(id);
             }
             return ids;
           },
           py::arg("path"), py::arg("offset") = py::make_tuple(0.0, 0.0, 0.0), py::arg("scale") = 1.0,
           py::kw_only(), py::arg("texture_dirs") = py::tuple(), py::arg("missing_textures") = "error",
           py::arg("progress") = true,
           R"doc(Add a Wavefront OBJ file with its MTL materials, scaled then offset.

Kd, Ks, Ns, d, map_Kd become BlinnPhong; Pr/Pm (PBR extension) Principled; illum 4/6/7 with
d < 1 and Ni > 1 Dielectric(Ni); Ke an area light. Vertex normals are kept as shading normals.

A texture the MTL names (map_Kd) is looked for in the MTL's folder, then in each of
``texture_dirs`` in order (relative folders from the working directory), as written and by its
file name alone (a path from the author's machine). A texture found nowhere raises
refracta.TextureNotFoundError (a refracta.IoError and a FileNotFoundError) naming it and the
folders searched (``missing_textures='error'``), or, with
``missing_textures='warn'``, issues a UserWarning (Python's warnings) and its material uses Kd.

Each texture is prepared once (MIP-mapped, linear) into the texture cache folder
($REFRACTA_TEXTURE_CACHE, else refracta-textures in the temporary folder); a model with hundreds of
textures takes seconds the first time. progress: True shows a bar on stderr once preparing has
taken over a second, a callable gets progress(done, total) textures, False shows nothing.

Returns the geometry ids. A missing OBJ or MTL raises refracta.IoError.)doc")
      .def("add_ground",
           [](RenderScene& s, double height, double size, const py::object& material, const py::object& kd,
              const py::object& ks, double ns, std::optional<std::string> texture, double texture_size) {
             Mesh mesh = ground_mesh(height, 0.5 * size);
             int tex = -1;
             const bool textured_material = !material.is_none() && py::isinstance<Material>(material) &&
                                            py::cast<const Material&>(material).textured();
             if (texture || textured_material) {
               // float texture coordinates keep no fraction of a repeat beyond 2^23 repeats (1e40
               // repeats gave NaN pixels): at most 1e6 across the ground keeps 4 fractional bits.
               if (!(texture_size > 0.0) || !std::isfinite(texture_size) || !(0.5 * size / texture_size <= 1e6)) {
                 throw_invalid("texture_size must be > 0 and at least size / 2e6 = ", 0.5 * size / 1e6,
                               " m (got ", texture_size, ")");
               }
               if (texture) tex = s.geometry.add_texture(*texture);
               for (const auto& v : mesh.vertices) mesh.uvs.emplace_back(v.x() / texture_size, -v.z() / texture_size);
             }
             return s.geometry.add_mesh(mesh, material_of(s, material, kd, ks, ns, tex));
           },
           py::arg("height") = 0.0, py::arg("size") = 20000.0, py::arg("material") = py::none(),
           py::arg("kd") = py::make_tuple(0.3, 0.3, 0.3), py::arg("ks") = py::make_tuple(0.0, 0.0, 0.0),
           py::arg("ns") = 1.0, py::arg("texture") = py::none(), py::arg("texture_size") = 1.0,
           "Add a square ground of side `size` [m] at y = height, centred on the origin, facing up; an optional\n"
           "texture (or a textured material's) repeats every texture_size [m] (u along +x, v along -z) and\n"
           "multiplies kd (or that material's colour).")
      .def("add_billboard",
           [](RenderScene& s, const py::object& centre, double width, double height, const std::string& texture,
              const py::object& facing, const py::object& kd) {
             const Vec3d c = to_point(centre, "centre"), f = to_point(facing, "facing");
             Vec3d across(f.z(), 0.0, -f.x());
             if (across.norm() == 0.0) throw_invalid("facing must have a horizontal component");
             if (!(width > 0.0) || !(height > 0.0)) throw_invalid("width and height must be > 0");
             across = across.normalized() * (0.5 * width);
             const Vec3d up(0.0, 0.5 * height, 0.0);
             Mesh mesh;
             mesh.vertices = {c - across - up, c + across - up, c + across + up, c - across + up};
             mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
             mesh.uvs = {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}};
             const int tex = s.geometry.textures().add(texture);
             return s.geometry.add_mesh(mesh, s.add_material(std::make_shared<BlinnPhong>(TexturedReflectance(to_rgb(kd, "kd"), "kd", tex), Vec3d::Zero(), 1.0)));
           },
           py::arg("centre"), py::arg("width"), py::arg("height"), py::arg("texture"),
           py::arg("facing") = py::make_tuple(-1.0, 0.0, 0.0), py::arg("kd") = py::make_tuple(1.0, 1.0, 1.0),
           "Add a vertical textured rectangle (a photo standing in the scene: a ship, a building) centred at\n"
           "`centre`, width x height [m], its picture facing `facing` (default -x, toward a camera on the\n"
           "-x side), upright.")
      .def("add_box",
           [](RenderScene& s, const py::object& centre, const py::object& size, const py::object& material,
              const py::object& emission, const py::object& kd, const py::object& ks, double ns, double alpha) {
             const Mesh mesh = box_mesh(to_point(centre, "centre"), to_point(size, "size"));
             const int material_id = material_of(s, material, kd, ks, ns, -1, alpha);
             check_uvs(s, material_id, false, "add_box");
             const unsigned id = s.geometry.add_mesh(mesh, material_id);
             add_emission(s, id, emission, false);
             return id;
           },
           py::arg("centre"), py::arg("size"), py::arg("material") = py::none(), py::arg("emission") = py::none(),
           py::arg("kd") = py::make_tuple(0.5, 0.5, 0.5), py::arg("ks") = py::make_tuple(0.0, 0.0, 0.0),
           py::arg("ns") = 1.0, py::arg("alpha") = 1.0,
           "Add an axis-aligned box (faces outward): centre (3,) and size (3,) [m]; alpha < 1: transparent in\n"
           "render_raster.")
      .def("add_sphere",
           [](RenderScene& s, const py::object& centre, double radius, const py::object& material,
              const py::object& emission, const py::object& kd, const py::object& ks, double ns) {
             const Vec3d c = to_point(centre, "centre");
             const int material_id = material_of(s, material, kd, ks, ns);
             check_uvs(s, material_id, false, "add_sphere");
             const unsigned id = s.geometry.add_spheres({c}, {radius}, material_id);
             if (!emission.is_none()) {
               s.add_light(std::make_shared<SphereLight>(c, radius, illuminant_of(emission, "emission")), int(id));
             }
             return id;
           },
           py::arg("centre"), py::arg("radius"), py::arg("material") = py::none(), py::arg("emission") = py::none(),
           py::arg("kd") = py::make_tuple(0.5, 0.5, 0.5), py::arg("ks") = py::make_tuple(0.0, 0.0, 0.0),
           py::arg("ns") = 1.0, "Add a sphere (exact, not tessellated); emission makes it a spherical light.")
      .def("set_sun",
           [](RenderScene& s, const py::object& direction, const py::object& radiance, double angular_diameter,
              double limb_darkening, const py::object& wavelengths) {
             const Color colour = wavelengths.is_none()
                                      ? illuminant_of(radiance, "radiance")
                                      : Color::tabulated(to_values(wavelengths, "wavelengths"),
                                                         to_values(radiance, "radiance"), Color::Kind::kIlluminant);
             auto sun = std::make_shared<SunLight>(to_point(direction, "direction"), colour, angular_diameter,
                                                   limb_darkening);
             s.remove_lights_if([](const Light& l) { return dynamic_cast<const SunLight*>(&l) != nullptr; });
             s.add_light(sun);
           },
           py::arg("direction"), py::arg("radiance"), py::arg("angular_diameter") = 0.53, py::arg("limb_darkening") = 0.0,
           py::arg("wavelengths") = py::none(),
           "The sun (replacing any): direction toward it, disc radiance [W/(m^2 sr), RGB], angular diameter [deg],\n"
           "limb darkening u (I(mu) = 1 - u (1 - mu)). Seen through the air along curved rays.\n"
           "With wavelengths (M,) [nm, increasing], radiance is a spectrum (M,) [W/(m^2 sr nm)] instead (e.g.\n"
           "refracta.spectrum.PhysicalSky(...).sun_radiance(wavelengths): the sun through the air's extinction).")
      .def("set_sky",
           [](RenderScene& s, const py::object& horizon, const py::object& zenith, std::optional<std::string> environment,
              double scale) {
             s.remove_lights_if([](const Light& l) { return l.is_infinite() && !dynamic_cast<const SunLight*>(&l); });
             if (environment) {
               s.add_light(environment_from_file(*environment, scale, Mat3d::Identity()));
               return;
             }
             const Vec3d h = horizon.is_none() ? Vec3d(0.7, 0.8, 0.95) : to_rgb(horizon, "horizon");
             const Vec3d z = zenith.is_none() ? h : to_rgb(zenith, "zenith");
             if (!(scale >= 0.0) || !std::isfinite(scale)) throw_invalid("scale must be >= 0 (got ", scale, ")");
             if (zenith.is_none() || z == h) {  // a constant sky, sampled by cosine
               if (h.maxCoeff() > 0.0) s.add_light(std::make_shared<ConstantEnvironment>(illuminant_of(py::cast(std::vector<double>{h.x() * scale, h.y() * scale, h.z() * scale}), "horizon")));
             } else if (h.maxCoeff() > 0.0 || z.maxCoeff() > 0.0) {
               s.add_light(std::make_shared<EnvironmentLight>(gradient_sky(h, z), scale));
             }
           },
           py::arg("horizon") = py::none(), py::arg("zenith") = py::none(), py::arg("environment") = py::none(),
           py::arg("scale") = 1.0,
           "A sky (replacing any environment): radiance toward the horizon (and below) and straight up, linear in\n"
           "the sine of the elevation (zenith default: the horizon's, a constant sky), or an equirectangular\n"
           "environment map file (refracta.lights.EnvironmentLight's orientation), times `scale`.")
      .def("set_physical_sky",
           [](RenderScene& s, const py::object& sun_direction, double aerosol, double ozone_du, double ground_albedo,
              double sun_angular_diameter, double limb_darkening, double scale, double altitude,
              const std::string& below_horizon, bool aerial_perspective, const std::optional<double>& visibility) {
             PhysicalSkySettings settings;
             const Vec3d sun = to_point(sun_direction, "sun_direction");
             if (!(sun.norm() > 0.0)) throw_invalid("sun_direction must be non-zero (got (", sun.x(), ", ", sun.y(), ", ", sun.z(), "))");
             settings.sun_direction = sun.normalized();
             settings.aerosol = aerosol, settings.ozone_du = ozone_du, settings.ground_albedo = ground_albedo;
             settings.altitude = altitude;
             settings.below_horizon = below_horizon_from(below_horizon);
             if (visibility) set_visibility(&settings, *visibility);
             set_physical_sky(s, settings, sun_angular_diameter, limb_darkening, scale);
             if (aerial_perspective && scale > 0.0) s.enable_aerial_perspective();
           },
           py::arg("sun_direction"), py::arg("aerosol") = PhysicalSkySettings{}.aerosol,
           py::arg("ozone_du") = PhysicalSkySettings{}.ozone_du, py::arg("ground_albedo") = PhysicalSkySettings{}.ground_albedo,
           py::arg("sun_angular_diameter") = 0.53, py::arg("limb_darkening") = 0.0, py::arg("scale") = 1.0,
           py::arg("altitude") = PhysicalSkySettings{}.altitude, py::arg("below_horizon") = "horizon",
           py::arg("aerial_perspective") = true, py::arg("visibility") = py::none(),
           "The physical sky (replacing every environment, sky and sun): refracta.spectrum.PhysicalSky's\n"
           "single scattering (Nishita et al. 1993) for the sun toward `sun_direction` (normalised, y up),\n"
           "`aerosol` (Mie density scale), `ozone_du` [Dobson units], observer `altitude` [m]. Below the horizon\n"
           "`below_horizon`: 'horizon' (default) continues the sky from the horizon at each azimuth (Scene.set_sky's\n"
           "convention: the ground is geometry, and a ray ending its max_length still heading slightly down sees\n"
           "the horizon sky, importance-sampled over the whole sphere); 'ground' shows the Lambertian ground of\n"
           "`ground_albedo` (which must be 0 with 'horizon'). And the sun: a disc of `sun_angular_diameter` [deg]\n"
           "with linear limb darkening u, its radiance the 5778 K solar spectrum through the atmosphere's extinction (reddened\n"
           "toward the horizon; none below it). Units: spectral radiance W/(m^2 sr nm) in spectral renders,\n"
           "its CIE-Y-weighted mean in RGB (linear sRGB of XYZ / integral ybar, as Color.illuminant: times\n"
           "106.86 nm gives W/(m^2 sr)); RGB and spectral renders agree. `scale` multiplies sky and sun\n"
           "(e.g. an exposure). Builds the sky's table (~0.5 s).\n"
           "aerial_perspective (default True): the same air dims and lights every segment the renderers cast\n"
           "(refracta.spectrum.AerialPerspective: transmittance and single-scattered sunlight), so distant\n"
           "objects grey and blue into the sky; False keeps surfaces as seen through empty space.\n"
           "visibility [km]: meteorological visibility at the ground (Koschmieder: extinction at 550 nm =\n"
           "3.912 / V), setting the aerosol in its place (give one of them). The scene's y = 0 lies `altitude`\n"
           "above the sky's sea level.")
      .def_property_readonly(
          "aerial_perspective",
          [](const RenderScene& s) -> py::object {
            const AerialPerspective* air = s.aerial_perspective();
            if (!air) return py::none();
            return py::cast(s.aerial_perspective_ptr());
          },
          "The scene's refracta.spectrum.AerialPerspective (set_physical_sky(aerial_perspective=True)), or None.")
      .def(
          "set_aerial_perspective",
          [](RenderScene& s, bool enabled) {
            if (enabled) {
              s.enable_aerial_perspective();
            } else {
              s.disable_aerial_perspective();
            }
          },
          py::arg("enabled"),
          "Turn aerial perspective on (from the scene's physical sky; ValueError without one) or off, keeping the sky.")
      .def("set_environment",
           [](RenderScene& s, const py::object& source, const py::object& rotation, double scale) {
             s.remove_lights_if([](const Light& l) { return l.is_infinite() && !dynamic_cast<const SunLight*>(&l); });
             if (py::isinstance<py::str>(source)) {
               s.add_light(environment_from_file(py::cast<std::string>(source), scale, rotation_from(rotation)));
             } else if (py::isinstance<py::array>(source) && py::cast<py::array>(source).ndim() >= 2) {
               s.add_light(std::make_shared<EnvironmentLight>(array_to_image(source), scale, rotation_from(rotation)));
             } else {
               const Vec3d radiance = to_rgb(source, "radiance") * scale;
               s.add_light(std::make_shared<ConstantEnvironment>(Color::illuminant(radiance)));
             }
           },
           py::arg("source"), py::arg("rotation") = py::none(), py::arg("scale") = 1.0,
           "The environment (replacing any sky): an RGB radiance (a constant environment), an equirectangular\n"
           "map file (EXR/HDR/PNG through OpenImageIO) or a float array (H, W, 3), times `scale`, turned by\n"
           "`rotation` (degrees about y, or a 3 x 3 matrix). Orientation: refracta.lights.EnvironmentLight.")
      .def("add_light",
           [](RenderScene& s, const std::shared_ptr<Light>& light) {
             if (!light) throw_invalid("light must be a refracta.lights light");
             return s.add_light(light);
           },
           py::arg("light"), "Add any refracta.lights light (not area lights of geometry: use emission=). Returns its index.")
      .def("add_point_light",
           [](RenderScene& s, const py::object& position, const py::object& intensity) {
             return s.add_light(std::make_shared<PointLight>(to_point(position, "position"), illuminant_of(intensity, "intensity")));
           },
           py::arg("position"), py::arg("intensity"),
           "Add a point light at `position` [m] of `intensity` [W/sr, RGB] (irradiance I cos / d^2). Returns its index.")
      .def("add_spot_light",
           [](RenderScene& s, const py::object& position, const py::object& direction, double angle,
              const py::object& intensity, double radius) {
             if (!(angle > 0.0 && angle <= 170.0)) throw_invalid("spot light angle must be in (0, 170] deg (got ", angle, ")");
             if (!(radius >= 0.0) || !std::isfinite(radius)) throw_invalid("spot light radius must be >= 0 (got ", radius, ")");
             const size_t index = s.add_light(std::make_shared<SpotLight>(
                 to_point(position, "position"), to_point(direction, "direction"), angle,
                 illuminant_of(intensity, "intensity")));
             if (radius > 0.0) s.set_shadow_radius(index, radius);
             size_t spots = 0;
             for (const auto& l : s.lights()) spots += dynamic_cast<const SpotLight*>(l.get()) != nullptr;
             return spots - 1;
           },
           py::arg("position"), py::arg("direction"), py::arg("angle") = 60.0,
           py::arg("intensity") = py::make_tuple(100.0, 100.0, 100.0), py::arg("radius") = 0.0,
           "Add a spot light at `position` [m] shining along `direction` into a cone of full `angle` [deg] with\n"
           "`intensity` [W/sr per channel] (irradiance I cos / d^2); radius > 0 gives render_raster's 'embree'\n"
           "reference soft shadows of a disc that size. Returns its index among the spot lights.")
      .def_property_readonly("lights", [](const RenderScene& s) { return s.lights(); })
      .def_property_readonly("geometry_count", [](const RenderScene& s) { return s.geometry.geometry_count(); })
      .def_property_readonly(
          "bounds",
          [](const RenderScene& s) {
            if (s.geometry.geometry_count() == 0) throw_invalid("Scene.bounds: the scene is empty");
            return py::make_tuple(points_to_array({s.geometry.lower()}).reshape({py::ssize_t(3)}),
                                  points_to_array({s.geometry.upper()}).reshape({py::ssize_t(3)}));
          },
          "(lower, upper): corners (3,) [m] of the axis-aligned box around every geometry (spheres\n"
          "exact; a ground counts at its full size). ValueError for an empty scene.")
      .def("material",
           [](const RenderScene& s, int geometry) {
             s.geometry.check_geometry(geometry_id(geometry), "material");
             return std::const_pointer_cast<Material>(s.material_ptr(s.geometry.material(unsigned(geometry))));
           },
           py::arg("geometry"),
           "The material of a geometry (an id returned by add_*), as a refracta.shading object (a material\n"
           "with a texture file: the scene's copy, its file registered here).")
      .def("set_material",
           [](RenderScene& s, int geometry, const py::object& material) {
             const unsigned g = geometry_id(geometry);
             s.geometry.check_geometry(g, "set_material");
             std::shared_ptr<Material> m;
             try {
               m = py::cast<std::shared_ptr<Material>>(material);
             } catch (const py::cast_error&) {
               throw_invalid("set_material: material must be a refracta.shading material (got ",
                             std::string(py::str(py::type::of(material))), ")");
             }
             if (!m) throw_invalid("set_material: material must be a refracta.shading material (got None)");
             if (m->textured() && !s.geometry.has_uvs(g)) {
               throw_invalid("set_material: ", m->describe(), " has a texture but geometry ", g,
                             " has no texture coordinates (uvs)");
             }
             s.set_material(g, m);
           },
           py::arg("geometry"), py::arg("material"),
           "Give a geometry (an id returned by add_*, e.g. one part of add_obj) another refracta.shading material.\n"
           "Its emission, if any, stays. Not while a render of this scene runs (RuntimeError).")
      .def("remove",
           [](RenderScene& s, int geometry) { s.remove(geometry_id(geometry)); },
           py::arg("geometry"),
           "Remove a geometry (an id returned by add_*, e.g. an OBJ's terrain) and the area light it emits.\n"
           "The other ids stay valid (a removed id is not reused; geometry_count still counts it); the\n"
           "acceleration structure is rebuilt before the next render. Not while a render of this scene runs.")
      .def("intersect",
           [](const RenderScene& s, const py::object& origin, const py::object& direction) -> py::object {
             const Vec3d d = to_point(direction, "direction");
             if (d.norm() == 0.0) throw_invalid("direction must be non-zero");
             const auto hit = s.geometry.intersect(to_point(origin, "origin"), d.normalized(), 1e7);
             if (!hit) return py::none();
             return py::make_tuple(points_to_array({hit->point}).reshape({py::ssize_t(3)}), hit->t, hit->geometry);
           },
           py::arg("origin"), py::arg("direction"),
           "First hit of a straight ray: (point, distance, geometry id), or None.")
      // Pickled as its content (pickle_state.h): meshes, materials, lights, texture paths.
      .def(py::pickle(&scene_state, &scene_from_state));

  py::class_<Camera>(m, "Camera", R"doc(
Pinhole camera. Camera(position, look_at, up=(0, 1, 0), vfov=45, width=640, height=360): vfov is the
vertical field of view [deg]. Pixel coordinates (u, v): u right, v down, pixel (i, j) centred at
(i + 0.5, j + 0.5). A photographer's camera with depth of field: Camera.photographic(..., f_number=)
or Camera.eye_level(..., f_number=); any camera through a thin lens: with_lens.)doc")
      .def(py::init([](const py::object& position, const py::object& look_at, const py::object& up, double vfov,
                       int width, int height) {
             return Camera(to_point(position, "position"), to_point(look_at, "look_at"), to_point(up, "up"), vfov,
                           width, height);
           }),
           py::arg("position"), py::arg("look_at"), py::arg("up") = py::make_tuple(0.0, 1.0, 0.0),
           py::arg("vfov") = 45.0, py::arg("width") = 640, py::arg("height") = 360)
      .def("ray",
           [](const Camera& c, double u, double v) {
             if (!std::isfinite(u) || !std::isfinite(v)) throw_invalid("u and v must be finite");
             return py::make_tuple(points_to_array({c.position()}).reshape({py::ssize_t(3)}),
                                   points_to_array({c.direction(u, v)}).reshape({py::ssize_t(3)}));
           },
           py::arg("u"), py::arg("v"), "(origin, unit direction) of the ray through pixel coordinates (u, v).")
      .def("project",
           [](const Camera& c, const py::object& points) {
             bool single = false;
             std::vector<Vec3d> p = to_points(points, "points", &single);
             for (auto& x : p) x = c.project(x);
             DoubleArray out = points_to_array(p);
             return single ? py::object(out.reshape({py::ssize_t(3)})) : py::object(out);
           },
           py::arg("points"), "(u, v, depth) per point (N, 3); depth [m] along the view axis, <= 0 behind.")
      .def("pick",
           [](const Camera& c, const RenderScene& s, double u, double v) -> py::object {
             if (!std::isfinite(u) || !std::isfinite(v)) throw_invalid("u and v must be finite");
             const auto hit = s.geometry.intersect(c.position(), c.direction(u, v), 1e7);
             if (!hit) return py::none();
             return points_to_array({hit->point}).reshape({py::ssize_t(3)});
           },
           py::arg("scene"), py::arg("u"), py::arg("v"),
           "The scene point seen at pixel (u, v) without atmosphere (straight ray), or None.")
      .def_property_readonly("position", [](const Camera& c) { return points_to_array({c.position()}).reshape({py::ssize_t(3)}); })
      .def_property_readonly("look_at", [](const Camera& c) { return points_to_array({c.look_at()}).reshape({py::ssize_t(3)}); })
      .def_property_readonly("up", [](const Camera& c) { return points_to_array({c.up_hint()}).reshape({py::ssize_t(3)}); },
                             "The up vector given to the constructor.")
      .def(
          "jittered",
          [](const Camera& c, const py::object& angles) {
            using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
            const FloatArray map = py::cast<FloatArray>(angles);
            if (map.ndim() != 3 || map.shape(0) != c.height() || map.shape(1) != c.width() || map.shape(2) != 2) {
              throw_invalid("Camera.jittered: angles must have shape (height, width, 2) = (", c.height(), ", ", c.width(),
                            ", 2)");
            }
            return c.jittered(std::vector<float>(map.data(), map.data() + map.size()));
          },
          py::arg("angles"), R"doc(
The same camera with every ray turned by small angles [rad] toward the image's right and up: a
map (height, width, 2) at the pixel centres, bilinear between them. Non-physical "geometric noise"
(the follow-up editor's cheap shimmer); project() ignores it.)doc")
      .def_property_readonly("jitter", [](const Camera& c) -> py::object {
        if (c.jitter().empty()) return py::none();
        py::array_t<float> out({py::ssize_t(c.height()), py::ssize_t(c.width()), py::ssize_t(2)});
        std::copy(c.jitter().begin(), c.jitter().end(), out.mutable_data());
        return py::object(out);
      }, "The angle map (height, width, 2) [rad] of a jittered camera, or None.")
      // Pickled as its constructor's arguments (and jitter): the copy's rays are bit-identical.
      .def(py::pickle(
          [](const Camera& c) {
            auto xyz = [](const Vec3d& v) { return py::make_tuple(v.x(), v.y(), v.z()); };
            return py::make_tuple(xyz(c.position()), xyz(c.look_at()), xyz(c.up_hint()), c.vfov(), c.width(), c.height(),
                                  c.jitter(), c.aperture_diameter(), c.focus_distance());
          },
          [](const py::tuple& t) {
            if (t.size() != 6 && t.size() != 7 && t.size() != 9) throw_invalid("Camera: bad pickle state (", t.size(), " items)");
            Camera camera(to_point(t[0], "position"), to_point(t[1], "look_at"), to_point(t[2], "up"), py::cast<double>(t[3]),
                          py::cast<int>(t[4]), py::cast<int>(t[5]));
            if (t.size() == 7) {
              auto angles = py::cast<std::vector<float>>(t[6]);
              if (!angles.empty()) camera = camera.jittered(std::move(angles));
            }
            if (t.size() == 9 && py::cast<double>(t[7]) > 0.0) {
              camera = camera.with_lens(py::cast<double>(t[7]), py::cast<double>(t[8]));
            }
            return camera;
          }))
      .def_static(
          "framing",
          [](const py::object& scene_or_bounds, const py::object& direction, double vfov, int width, int height,
             const py::object& up) {
            Vec3d lower, upper;
            if (py::isinstance<RenderScene>(scene_or_bounds)) {
              const py::tuple bounds = scene_or_bounds.attr("bounds");
              lower = to_point(bounds[0], "bounds[0]"), upper = to_point(bounds[1], "bounds[1]");
            } else {
              py::sequence bounds;
              try {
                bounds = py::cast<py::sequence>(scene_or_bounds);
              } catch (const py::cast_error&) {
                throw_invalid("Camera.framing: give a Scene or its bounds (lower, upper)");
              }
              if (bounds.size() != 2) throw_invalid("Camera.framing: bounds must be (lower, upper)");
              lower = to_point(bounds[0], "bounds[0]"), upper = to_point(bounds[1], "bounds[1]");
            }
            return Camera::framing(lower, upper, to_point(direction, "direction"), to_point(up, "up"), vfov, width,
                                   height);
          },
          py::arg("scene_or_bounds"), py::arg("direction") = py::make_tuple(-1.0, -0.5, -1.0), py::arg("vfov") = 45.0,
          py::arg("width") = 640, py::arg("height") = 360, py::arg("up") = py::make_tuple(0.0, 1.0, 0.0),
          R"doc(A camera that shows a whole scene (or box): it looks along ``direction`` (default: down
onto the box from its +x, +y, +z side) at the centre of the scene's bounds, from the distance at
which the bounding sphere fills the narrower of the two fields of view.

    scene.add_obj("city.obj", texture_dirs=["textures"])
    camera = refracta.Camera.framing(scene, width=800, height=450)

scene_or_bounds: a Scene or (lower, upper) corners (3,) [m]; vfov [deg].)doc")
      .def_static(
          "photographic",
          [](const py::object& position, const py::object& look_at, double focal_length_mm, const std::pair<double, double>& sensor_mm,
             int width, int height, const py::object& up, std::optional<double> f_number,
             std::optional<double> focus_distance) {
            return Camera::photographic(to_point(position, "position"), to_point(look_at, "look_at"), to_point(up, "up"),
                                        focal_length_mm, sensor_mm.first, sensor_mm.second, width, height, f_number,
                                        focus_distance);
          },
          py::arg("position"), py::arg("look_at"), py::arg("focal_length_mm"),
          py::arg("sensor_mm") = std::make_pair(36.0, 24.0), py::arg("width") = 960, py::arg("height") = 640,
          py::arg("up") = py::make_tuple(0.0, 1.0, 0.0), py::arg("f_number") = py::none(),
          py::arg("focus_distance") = py::none(),
          R"doc(A camera described by its lens and sensor: focal_length_mm on a sensor of
sensor_mm = (width, height) [mm] (full frame 36 x 24; APS-C about 23.5 x 15.6). The image spans the
sensor's width when it is relatively wider than the sensor, else its height; vfov follows as
2 atan(h / 2f). A 300 mm telephoto on full frame at 960 x 640 sees 4.58 deg vertically:

    camera = refracta.Camera.photographic((0, 5, 0), (28000, 5, 0), 300.0, width=960, height=640)

position, look_at [m]; up as for Camera.

Depth of field: with f_number N a thin lens of aperture diameter A = f / N, focused at
focus_distance [m] (None: the distance to look_at); None: a pinhole, everything sharp. A point at
depth d [m] then blurs to the thin-lens circle of confusion ``c = A f abs(d - d_f) / (d (d_f - f))``
on the sensor; the image keeps the field of view of focus at infinity (no focus breathing, as
Blender, Mitsuba and pbrt), so in pixels c (d_f - f) / d_f x width / (sensor width used) [mm].
Each pixel sample takes its own lens point; through a field those rays are traced from the lens
(not served by the eye's table), which costs what table=False costs. Only the ray-traced methods
('straight', 'curved') render it. f_number or focus_distance <= 0 or NaN: ValueError.)doc")
      .def_static(
          "eye_level",
          [](const py::object& eye, const py::object& target, double eye_height, double focal_length_mm,
             const std::pair<double, double>& sensor_mm, int width, int height, std::optional<double> f_number,
             std::optional<double> focus_distance) {
            return Camera::eye_level(to_point(eye, "eye"), to_point(target, "target"), eye_height, focal_length_mm,
                                     sensor_mm.first, sensor_mm.second, width, height, f_number, focus_distance);
          },
          py::arg("eye"), py::arg("target"), py::arg("eye_height") = 1.6, py::arg("focal_length_mm") = 50.0,
          py::arg("sensor_mm") = std::make_pair(36.0, 24.0), py::arg("width") = 960, py::arg("height") = 640,
          py::arg("f_number") = py::none(), py::arg("focus_distance") = py::none(),
          R"doc(A photographer's view: standing at ``eye`` (the ground point under the feet [m]) with the
lens eye_height [m] above it (1.6: a standing adult), the camera level, aimed at the horizon in the
horizontal direction of ``target``. Over flat ground the horizon runs through the image's centre
row, where mirages are: a hot road's "wet" band and the inverted images under cars sit just below
it (Camera.framing's 45 deg aerial view shows none of them). Over a curved Earth the sea horizon
dips sqrt(2 h / R) below it (0.041 deg at 1.6 m). Lens, sensor, f_number and focus_distance as
for Camera.photographic (focus by default at the target's horizontal distance):

    camera = refracta.Camera.eye_level((0, 0, 0), (0, 0, -200), eye_height=1.6, focal_length_mm=200)
)doc")
      .def("with_lens", &Camera::with_lens, py::arg("aperture_diameter"), py::arg("focus_distance"),
           "The same view through a thin lens of aperture_diameter [m] (0: a pinhole) focused on the plane at\n"
           "depth focus_distance [m] (Camera.photographic's f_number gives f / N). ValueError for a negative\n"
           "diameter or a focus distance <= 0.")
      .def_property_readonly("aperture_diameter", &Camera::aperture_diameter,
                             "The thin lens's aperture diameter [m] (f / N), 0 for a pinhole.")
      .def_property_readonly("focus_distance", &Camera::focus_distance,
                             "The depth [m] of the plane in focus, 0 for a pinhole.")
      .def("resized", &Camera::resized, py::arg("width"), py::arg("height"),
           "The same view at another image size (vertical field of view kept).")
      .def_property_readonly("width", &Camera::width)
      .def_property_readonly("height", &Camera::height)
      .def_property_readonly("vfov", &Camera::vfov)
      .def_property_readonly("pixel_angle", &Camera::pixel_angle,
                             "The angle [rad] one pixel subtends at the image centre (vertical field of view / height).")
      .def("__repr__", [](const Camera& c) {
        return concat("Camera(position=(", c.position().x(), ", ", c.position().y(), ", ", c.position().z(),
                      "), vfov=", c.vfov(), ", size=", c.width(), "x", c.height(),
                      c.aperture_diameter() > 0.0
                          ? concat(", aperture_diameter=", c.aperture_diameter(), ", focus_distance=", c.focus_distance())
                          : std::string(),
                      ")");
      });

  // Display arguments after the image: exposure, tonemap, gamma, key, white, ev100, iso, shutter,
  // f_number, luminous_efficacy (io.py passes them through; None: the C++ default).
  auto display_args = [](std::optional<double> exposure, std::optional<std::string> tonemap, const py::object& gamma,
                         std::optional<double> key, std::optional<double> white, std::optional<double> ev100,
                         std::optional<double> iso, std::optional<double> shutter, std::optional<double> f_number,
                         std::optional<double> luminous_efficacy) {
    return DisplayArgs{exposure, ev100, iso, shutter, f_number, key, white, std::move(tonemap),
                       gamma.is_none() ? py::str("srgb") : gamma, luminous_efficacy};
  };
  m.def("_write_image",
        [display_args](const std::string& path, const py::object& array, std::optional<double> exposure,
                       std::optional<std::string> tonemap, const py::object& gamma, std::optional<double> key,
                       std::optional<double> white, std::optional<double> ev100, std::optional<double> iso,
                       std::optional<double> shutter, std::optional<double> f_number,
                       std::optional<double> luminous_efficacy) {
          Image image = array_to_image(array);
          const DisplaySettings settings = display_settings(
              display_args(exposure, tonemap, gamma, key, white, ev100, iso, shutter, f_number, luminous_efficacy));
          if (is_float_format(path)) {
            // Linear files: the manual exposure only (1 without one; no automatic exposure).
            const double c = manual_exposure(settings);
            for (float& v : image.pixels) v *= float(c);
          } else {
            tonemap_image(image, settings);
          }
          py::gil_scoped_release release;
          write_image(path, image);
        },
        py::arg("path"), py::arg("image"), py::arg("exposure") = py::none(), py::arg("tonemap") = py::none(),
        py::arg("gamma") = py::none(), py::arg("key") = py::none(), py::arg("white") = py::none(),
        py::arg("ev100") = py::none(), py::arg("iso") = py::none(), py::arg("shutter") = py::none(),
        py::arg("f_number") = py::none(), py::arg("luminous_efficacy") = py::none());
  m.def("_display",
        [display_args](const py::object& array, std::optional<double> exposure, std::optional<std::string> tonemap,
                       const py::object& gamma, std::optional<double> key, std::optional<double> white,
                       std::optional<double> ev100, std::optional<double> iso, std::optional<double> shutter,
                       std::optional<double> f_number, std::optional<double> luminous_efficacy) {
          Image image = array_to_image(array);
          tonemap_image(image, display_settings(display_args(exposure, tonemap, gamma, key, white, ev100, iso, shutter,
                                                             f_number, luminous_efficacy)));
          return image_to_float32(image);
        },
        py::arg("image"), py::arg("exposure") = py::none(), py::arg("tonemap") = py::none(), py::arg("gamma") = py::none(),
        py::arg("key") = py::none(), py::arg("white") = py::none(), py::arg("ev100") = py::none(),
        py::arg("iso") = py::none(), py::arg("shutter") = py::none(), py::arg("f_number") = py::none(),
        py::arg("luminous_efficacy") = py::none());
  m.def("_display_exposure",
        [display_args](const py::object& array, std::optional<double> exposure, std::optional<double> key,
                       std::optional<double> ev100, std::optional<double> iso, std::optional<double> shutter,
                       std::optional<double> f_number, std::optional<double> luminous_efficacy) {
          const Image image = array_to_image(array);
          return display_exposure(image, display_settings(display_args(exposure, std::nullopt, py::none(), key,
                                                                       std::nullopt, ev100, iso, shutter, f_number,
                                                                       luminous_efficacy)));
        },
        py::arg("image"), py::arg("exposure") = py::none(), py::arg("key") = py::none(), py::arg("ev100") = py::none(),
        py::arg("iso") = py::none(), py::arg("shutter") = py::none(), py::arg("f_number") = py::none(),
        py::arg("luminous_efficacy") = py::none(),
        "The exposure c the display settings give this image (io.exposure_of).");
  m.def("_ev100", &ev100_of, py::arg("f_number"), py::arg("shutter"), py::arg("iso") = kDefaultIso,
        "EV100 = log2(N^2 / t) - log2(ISO / 100) of a camera's f-number, shutter time [s] and ISO.");
  m.def("_read_image", [](const std::string& path) { return image_to_float32(read_image(path)); }, py::arg("path"));
  bind_ocean(m);  // OceanWaves and Scene.add_sea
}

}  // namespace refracta
