// Embree 3 scene: triangle meshes, spheres (user geometry, intersected in double) and terrain grids,
// checked single-ray queries.
#include "refracta/scene/embree_scene.h"

#include "refracta/core/error.h"
#include "refracta/core/frame.h"
#include "refracta/core/rng.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <optional>
#include <string>

namespace refracta {

namespace {

void check_ray(const Vec3d& origin, const Vec3d& dir, double t_max) {
  if (!is_finite(origin) || origin.cwiseAbs().maxCoeff() > kSceneReach) {
    throw_numerical("ray origin (", origin.x(), ", ", origin.y(), ", ", origin.z(),
                    ") is not finite or beyond 1e7 m");
  }
  // |dir| within 1e-6 of 1, compared squared (no square root per ray).
  constexpr double kUnitLow = (1.0 - 1e-6) * (1.0 - 1e-6), kUnitHigh = (1.0 + 1e-6) * (1.0 + 1e-6);
  const double squared = dir.squaredNorm();
  if (!is_finite(dir) || !(squared >= kUnitLow && squared <= kUnitHigh)) {
    throw_numerical("ray direction (", dir.x(), ", ", dir.y(), ", ", dir.z(), ") is not a finite unit vector");
  }
  if (!(t_max > 0.0)) throw_numerical("ray length must be > 0 (got ", t_max, ")");
}

// Spheres are Embree user geometry: Embree's own RTC_GEOMETRY_TYPE_SPHERE_POINT (a point-curve
// primitive) cost 1.4-1.8x a user sphere per ray in a sphere-and-floor scene (measured: 128x128
// camera rays, intersect1 and occluded1; benchmarks/bench_shading.py), and the root is solved here
// in double anyway. The centres and radii are the Spheres of Scene::add_spheres.
float float_below(double x) {
  const float f = float(x);
  return double(f) <= x ? f : std::nextafter(f, -std::numeric_limits<float>::infinity());
}
float float_above(double x) {
  const float f = float(x);
  return double(f) >= x ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}

void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const auto& spheres = *static_cast<const Scene::Spheres*>(args->geometryUserPtr);
  const Vec3d& c = spheres.centres[args->primID];
  const double r = spheres.radii[args->primID];
  RTCBounds& b = *args->bounds_o;
  // Rounded outward: the box holds the double sphere whole.
  b.lower_x = float_below(c.x() - r), b.lower_y = float_below(c.y() - r), b.lower_z = float_below(c.z() - r);
  b.upper_x = float_above(c.x() + r), b.upper_y = float_above(c.y() + r), b.upper_z = float_above(c.z() + r);
}

// The roots t0 <= t1 of |o + t d - c| = r for a ray (o, d) with d not necessarily unit; false
// when it misses. The discriminant from the ray's closest approach to the centre, not b^2 - ac,
// which cancels catastrophically for small spheres far away (Haines et al. 2019, "Precision
// Improvements for Ray/Sphere Intersection", Ray Tracing Gems ch. 7, eqs. 7.5 and 7.7).
bool sphere_roots(const Vec3d& o, const Vec3d& d, const Vec3d& c, double r, double* t0, double* t1) {
  const Vec3d oc = o - c;
  const double a = d.squaredNorm(), b = oc.dot(d), r2 = r * r, l2 = oc.squaredNorm();
  // A clear miss without a division: a (squared distance of closest approach) = a l2 - b^2 exceeds
  // a r^2 by far more than its rounding (a few ulps of a l2 + b^2; 1e-12 of it is ~4500 ulps).
  constexpr double kClearMiss = 1e-12;
  if (a * l2 - b * b - a * r2 > kClearMiss * (a * l2 + b * b)) return false;
  const double inv_a = 1.0 / a;
  const Vec3d closest = oc - (b * inv_a) * d;  // the ray's nearest point to the centre, less the centre
  const double disc = a * (r2 - closest.squaredNorm());
  if (!(disc >= 0.0)) return false;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  const double x0 = q * inv_a, x1 = q != 0.0 ? (l2 - r2) / q : x0;
  *t0 = std::min(x0, x1), *t1 = std::max(x0, x1);
  return true;
}

Vec3d ray_origin(RTCRayN* ray, unsigned n, unsigned i) {
  return Vec3d(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i));
}
Vec3d ray_dir(RTCRayN* ray, unsigned n, unsigned i) {
  return Vec3d(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i));
}

// What Scene::intersect and Scene::occluded hand Embree as its context: the query's ray in
// double, and the nearest sphere root the callback accepted, solved from that double ray
// (Embree's ray is a float copy of it): Scene::intersect then need not solve the hit's sphere
// again. And the first error of a cut-out's filter in this query (Embree must not see an
// exception): the query throws it afterwards.
struct QueryContext {
  RTCIntersectContext context;  // first: Embree passes callbacks a pointer to it
  Vec3d origin, dir;
  double t = 0.0;
  unsigned geometry = RTC_INVALID_GEOMETRY_ID, primitive = 0;
  std::optional<std::string> filter_error;
};

// The nearest root in (tnear, tfar): the hit, as Embree's sphere reported it (Ng = hit - centre).
void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  const auto& spheres = *static_cast<const Scene::Spheres*>(args->geometryUserPtr);
  const Vec3d& c = spheres.centres[args->primID];
  const double r = spheres.radii[args->primID];
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  // Scene::intersect's single rays: from the double ray (the float copy's roots, re-solved from
  // the double ray, gave the same root).
  auto* query = args->N == 1 ? reinterpret_cast<QueryContext*>(args->context) : nullptr;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3d o = query ? query->origin : ray_origin(ray, args->N, i);
    const Vec3d d = query ? query->dir : ray_dir(ray, args->N, i);
    double t0, t1;
    if (!sphere_roots(o, d, c, r, &t0, &t1)) continue;
    const double tnear = RTCRayN_tnear(ray, args->N, i);
    float& tfar = RTCRayN_tfar(ray, args->N, i);
    const double t = t0 > tnear ? t0 : t1;
    if (!(t > tnear && t < double(tfar))) continue;
    tfar = float(t);
    if (query) query->t = t, query->geometry = args->geomID, query->primitive = args->primID;
    const Vec3d ng = o + t * d - c;
    RTCHitN_Ng_x(hit, args->N, i) = float(ng.x());
    RTCHitN_Ng_y(hit, args->N, i) = float(ng.y());
    RTCHitN_Ng_z(hit, args->N, i) = float(ng.z());
    RTCHitN_u(hit, args->N, i) = 0.0f;
    RTCHitN_v(hit, args->N, i) = 0.0f;
    RTCHitN_primID(hit, args->N, i) = args->primID;
    RTCHitN_geomID(hit, args->N, i) = args->geomID;
    RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
  }
}

void sphere_occluded(const RTCOccludedFunctionNArguments* args) {
  const auto& spheres = *static_cast<const Scene::Spheres*>(args->geometryUserPtr);
  const Vec3d& c = spheres.centres[args->primID];
  const double r = spheres.radii[args->primID];
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    double t0, t1;
    if (!sphere_roots(ray_origin(args->ray, args->N, i), ray_dir(args->ray, args->N, i), c, r, &t0, &t1)) continue;
    const double tnear = RTCRayN_tnear(args->ray, args->N, i);
    float& tfar = RTCRayN_tfar(args->ray, args->N, i);
    if ((t0 > tnear && t0 < double(tfar)) || (t1 > tnear && t1 < double(tfar))) {
      tfar = -std::numeric_limits<float>::infinity();  // Embree's mark of an occluded ray
    }
  }
}

// A uniform number in [0, 1) from a ray's float origin and direction and the triangle it meets
// (pbrt-v4 hashes the ray for its stochastic alpha test, and leaves each surface by a new ray):
// the same ray draws the same number at a triangle, and independent ones at the layers behind
// it (one number for all, two cards of alpha 1/2 let half the rays through, not a quarter: a
// review).
double ray_uniform(RTCRayN* ray, unsigned n, unsigned i, unsigned geometry, unsigned primitive) {
  const float values[6] = {RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i),
                           RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i)};
  uint64_t hash = Rng::mix((uint64_t(geometry) << 32) ^ primitive ^ 0x9E3779B97F4A7C15ull);
  for (const float value : values) {
    uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    hash = Rng::mix(hash ^ bits);
  }
  return Rng::to_unit(hash);
}

// What a cut-out geometry's filter reads (its Embree user data): the scene and the geometry's id.
struct CutoutFilter {
  const Scene* scene;
  unsigned geometry;
};

// Embree's intersect and occluded filter of a cut-out mesh: a candidate hit is dropped (Embree
// goes on to the next) unless the ray's uniform number lies below the opacity there.
void cutout_filter(const RTCFilterFunctionNArguments* args) {
  const auto& filter = *static_cast<const CutoutFilter*>(args->geometryUserPtr);
  // Scene's queries are single rays with a QueryContext as their context.
  auto& query = *reinterpret_cast<QueryContext*>(const_cast<RTCIntersectContext*>(args->context));
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    try {
      const unsigned primitive = RTCHitN_primID(args->hit, args->N, i);
      const double opacity = filter.scene->opacity(filter.geometry, primitive, RTCHitN_u(args->hit, args->N, i),
                                                   RTCHitN_v(args->hit, args->N, i));
      if (!(ray_uniform(args->ray, args->N, i, filter.geometry, primitive) < opacity)) args->valid[i] = 0;
    } catch (const std::exception& error) {
      if (!query.filter_error) query.filter_error = error.what();
    }
  }
}

}  // namespace

struct Scene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  // Read by queries on many threads without the lock (commit() takes it to write): atomic, so a
  // query that sees false also sees the committed scene.
  mutable std::atomic<bool> dirty{true};
  mutable std::mutex commit_mutex;
  std::string error;
  // The user-geometry spheres' data (Embree holds raw pointers): kept while the scene lives, a
  // removed geometry's too.
  std::vector<std::shared_ptr<const Spheres>> sphere_data;
  // The cut-out filters' data (Embree holds raw pointers).
  std::vector<std::unique_ptr<CutoutFilter>> cutout_filters;

  Impl() {
    device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("Embree: cannot create a device");
    rtcSetDeviceErrorFunction(
        device, [](void* user, RTCError, const char* message) {
          static_cast<Impl*>(user)->error = message ? message : "unknown Embree error";
        },
        this);
    scene = rtcNewScene(device);
  }
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
  // Commits `geometry`, attaches it under `id` and releases our reference. By id: Embree would
  // hand out a removed geometry's id again; ours only grow.
  unsigned attach(RTCGeometry geometry, unsigned id) {
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(scene, geometry, id);
    rtcReleaseGeometry(geometry);
    check();
    return id;
  }
  void check() {
    if (!error.empty()) {
      const std::string message = "Embree: " + error;
      error.clear();
      throw std::runtime_error(message);
    }
  }
};

Scene::Scene() : impl_(std::make_unique<Impl>()) {}
Scene::~Scene() = default;

unsigned Scene::add_mesh(const Mesh& mesh, int material) {
  check_unchanging("add_mesh");
  const std::vector<Vec3d>& vertices = mesh.vertices;
  const std::vector<std::array<int, 3>>& triangles = mesh.triangles;
  if (material < 0) throw_invalid("add_mesh: material must be a material id (got ", material, ")");
  if (vertices.empty() || triangles.empty()) throw_invalid("add_mesh: vertices and triangles must not be empty");
  if (!mesh.uvs.empty() && mesh.uvs.size() != vertices.size()) {
    throw_invalid("add_mesh: uvs must have one entry per vertex (", mesh.uvs.size(), " vs ", vertices.size(), ")");
  }
  for (const auto& uv : mesh.uvs) {
    if (!std::isfinite(uv.x()) || !std::isfinite(uv.y())) throw_invalid("add_mesh: uvs must be finite");
  }
  if (!mesh.normals.empty() && mesh.normals.size() != vertices.size()) {
    throw_invalid("add_mesh: normals must have one entry per vertex (", mesh.normals.size(), " vs ", vertices.size(), ")");
  }
  for (size_t i = 0; i < mesh.normals.size(); ++i) {
    if (!is_finite(mesh.normals[i]) || std::abs(mesh.normals[i].norm() - 1.0) > 1e-6) {
      throw_invalid("add_mesh: normals[", i, "] must be a finite unit vector");
    }
  }
  for (size_t i = 0; i < vertices.size(); ++i) {
    if (!is_finite(vertices[i]) || vertices[i].cwiseAbs().maxCoeff() > kSceneReach) {
      throw_invalid("add_mesh: vertices[", i, "] must be finite and within 1e7 m");
    }
  }
  for (size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (triangles[i][k] < 0 || size_t(triangles[i][k]) >= vertices.size()) {
        throw_invalid("add_mesh: triangles[", i, "] refers to vertex ", triangles[i][k], " of ", vertices.size());
      }
    }
  }
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), vertices.size()));
  auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                           3 * sizeof(unsigned), triangles.size()));
  for (size_t i = 0; i < vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) v[3 * i + k] = float(vertices[i][k]);
  }
  for (size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) t[3 * i + k] = unsigned(triangles[i][k]);
  }
  const unsigned id = impl_->attach(geometry, unsigned(materials_.size()));
  materials_.push_back(material);
  meshes_.push_back({id, mesh});
  sphere_sets_.push_back(nullptr);
  for (const auto& v : vertices) lower_ = lower_.cwiseMin(v), upper_ = upper_.cwiseMax(v);
  impl_->dirty = true;
  return id;
}

unsigned Scene::add_spheres(const std::vector<Vec3d>& centres, const std::vector<double>& radii, int material) {
  check_unchanging("add_spheres");
  if (material < 0) throw_invalid("add_spheres: material must be a material id (got ", material, ")");
  if (centres.empty() || centres.size() != radii.size()) {
    throw_invalid("add_spheres: needs as many radii as centres (", centres.size(), " vs ", radii.size(), ")");
  }
  for (size_t i = 0; i < centres.size(); ++i) {
    if (!is_finite(centres[i]) || centres[i].cwiseAbs().maxCoeff() > kSceneReach) {
      throw_invalid("add_spheres: centres[", i, "] must be finite and within 1e7 m");
    }
    if (!(radii[i] > 0.0) || !std::isfinite(radii[i])) {
      throw_invalid("add_spheres: radii[", i, "] must be > 0 (got ", radii[i], ")");
    }
    // The whole sphere within Embree's float range, as every mesh vertex is.
    if (centres[i].cwiseAbs().maxCoeff() + radii[i] > kSceneReach) {
      throw_invalid("add_spheres: radii[", i, "] = ", radii[i], " m reaches beyond 1e7 m from the origin "
                    "(scene coordinates are limited to 1e7 m, Embree's single precision)");
    }
  }
  auto data = std::make_shared<const Spheres>(Spheres{centres, radii});
  impl_->sphere_data.push_back(data);
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, unsigned(centres.size()));
  rtcSetGeometryUserData(geometry, const_cast<Spheres*>(data.get()));  // read only, by the callbacks
  rtcSetGeometryBoundsFunction(geometry, sphere_bounds, nullptr);
  rtcSetGeometryIntersectFunction(geometry, sphere_intersect);
  rtcSetGeometryOccludedFunction(geometry, sphere_occluded);
  for (size_t i = 0; i < centres.size(); ++i) {
    lower_ = lower_.cwiseMin(centres[i] - Vec3d::Constant(radii[i]));
    upper_ = upper_.cwiseMax(centres[i] + Vec3d::Constant(radii[i]));
  }
  const unsigned id = impl_->attach(geometry, unsigned(materials_.size()));
  materials_.push_back(material);
  sphere_sets_.push_back(std::move(data));
  SceneMesh spheres{id, {}};
  for (size_t i = 0; i < centres.size(); ++i) {
    const Mesh sphere = sphere_mesh(centres[i], radii[i], 48, 24);
    const int offset = int(spheres.mesh.vertices.size());
    spheres.mesh.vertices.insert(spheres.mesh.vertices.end(), sphere.vertices.begin(), sphere.vertices.end());
    for (const auto& t : sphere.triangles) spheres.mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  meshes_.push_back(std::move(spheres));
  impl_->dirty = true;
  return id;
}

unsigned Scene::add_terrain(std::shared_ptr<const TerrainGrid> terrain, int material) {
  check_unchanging("add_terrain");
  if (material < 0) throw_invalid("add_terrain: material must be a material id (got ", material, ")");
  if (!terrain) throw_invalid("add_terrain: no terrain grid");
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_GRID);
  // Shared: the grid's own floats (with their padding) are Embree's vertex buffer.
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, terrain->vertex_buffer(), 0,
                             3 * sizeof(float), terrain->vertex_count());
  const std::vector<TerrainPatch>& patches = terrain->patches();
  auto* grids = static_cast<RTCGrid*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_GRID, 0, RTC_FORMAT_GRID, sizeof(RTCGrid), patches.size()));
  for (size_t i = 0; i < patches.size(); ++i) {
    const TerrainPatch& p = patches[i];
    grids[i].startVertexID = unsigned(size_t(p.row) * size_t(terrain->cols()) + p.col);
    grids[i].stride = unsigned(terrain->cols());
    grids[i].width = p.cols;
    grids[i].height = p.rows;
  }
  const unsigned id = impl_->attach(geometry, unsigned(materials_.size()));
  materials_.push_back(material);
  meshes_.push_back({id, {}});
  sphere_sets_.push_back(nullptr);
  terrains_.resize(materials_.size());
  lower_ = lower_.cwiseMin(terrain->lower()), upper_ = upper_.cwiseMax(terrain->upper());
  terrains_[id] = std::move(terrain);
  impl_->dirty = true;
  return id;
}

int Scene::add_texture(const std::string& path, bool mask) {
  check_unchanging("add_texture");
  return textures_->add(path, mask);
}

void Scene::set_cutout(unsigned geometry, int texture) {
  check_unchanging("set_cutout");
  check_geometry(geometry, "set_cutout");
  if (is_spheres(geometry) || terrain(geometry) || meshes_[geometry].mesh.uvs.empty()) {
    throw_invalid("set_cutout: geometry ", geometry, " is not a triangle mesh with texture coordinates (uvs)");
  }
  if (texture < 0 || size_t(texture) >= textures_->size()) {
    throw_invalid("set_cutout: no texture ", texture, " (the scene has ", textures_->size(), ")");
  }
  cutouts_.resize(materials_.size(), -1);
  cutouts_[geometry] = texture;
  impl_->cutout_filters.push_back(std::make_unique<CutoutFilter>(CutoutFilter{this, geometry}));
  RTCGeometry handle = rtcGetGeometry(impl_->scene, geometry);
  rtcSetGeometryUserData(handle, impl_->cutout_filters.back().get());
  rtcSetGeometryIntersectFilterFunction(handle, cutout_filter);
  rtcSetGeometryOccludedFilterFunction(handle, cutout_filter);
  rtcCommitGeometry(handle);
  impl_->check();
  impl_->dirty = true;
}

double Scene::opacity(unsigned geometry, unsigned primitive, double b1, double b2) const {
  const int texture = cutout(geometry);
  if (texture < 0) return 1.0;
  const Mesh& mesh = meshes_[geometry].mesh;
  const auto& tri = mesh.triangles.at(primitive);
  const Eigen::Vector2d uv = (1.0 - b1 - b2) * mesh.uvs[tri[0]] + b1 * mesh.uvs[tri[1]] + b2 * mesh.uvs[tri[2]];
  return textures_->opacity(texture, uv.x(), 1.0 - uv.y());  // OIIO's t runs down the image, OBJ's v up
}

void Scene::check_unchanging(const char* change) const {
  if (const int readers = readers_.load(); readers > 0) {
    // The change named last: a public call reaches it through internal ones (add_box adds a material).
    throw std::runtime_error(concat("Scene: the scene is being rendered (", readers,
                                    " render(s) running, on other threads or calling this from their progress "
                                    "callback) and cannot change; change it after they return, or build a second "
                                    "Scene (refused: ", change, ", or the call that made it)"));
  }
}

void Scene::check_geometry(unsigned geometry, const char* what) const {
  if (geometry >= materials_.size()) throw_invalid(what, ": no geometry ", geometry, " (the scene has ", materials_.size(), ")");
  if (removed(geometry)) throw_invalid(what, ": geometry ", geometry, " was removed");
}

void Scene::set_material(unsigned geometry, int material) {
  check_unchanging("set_material");
  check_geometry(geometry, "set_material");
  if (material < 0) throw_invalid("set_material: material must be a material id (got ", material, ")");
  materials_[geometry] = material;
}

void Scene::remove(unsigned geometry) {
  check_unchanging("remove");
  check_geometry(geometry, "remove");
  rtcDetachGeometry(impl_->scene, geometry);
  impl_->check();
  impl_->dirty = true;  // the next query commits the scene without it
  meshes_[geometry].mesh = Mesh{};
  sphere_sets_[geometry] = nullptr;
  if (geometry < terrains_.size()) terrains_[geometry] = nullptr;
  if (geometry < cutouts_.size()) cutouts_[geometry] = -1;
  removed_.resize(materials_.size(), false);
  removed_[geometry] = true;
  // The bounds of what is left.
  lower_ = Vec3d::Constant(std::numeric_limits<double>::infinity()), upper_ = -lower_;
  for (unsigned g = 0; g < materials_.size(); ++g) {
    if (const auto& spheres = sphere_sets_[g]) {
      for (size_t i = 0; i < spheres->centres.size(); ++i) {
        lower_ = lower_.cwiseMin(spheres->centres[i] - Vec3d::Constant(spheres->radii[i]));
        upper_ = upper_.cwiseMax(spheres->centres[i] + Vec3d::Constant(spheres->radii[i]));
      }
    } else if (const TerrainGrid* grid = terrain(g)) {
      lower_ = lower_.cwiseMin(grid->lower()), upper_ = upper_.cwiseMax(grid->upper());
    } else {
      for (const auto& v : meshes_[g].mesh.vertices) lower_ = lower_.cwiseMin(v), upper_ = upper_.cwiseMax(v);
    }
  }
}

void Scene::commit() const {
  std::lock_guard<std::mutex> lock(impl_->commit_mutex);
  if (!impl_->dirty) return;
  rtcCommitScene(impl_->scene);
  impl_->check();
  impl_->dirty = false;
}

namespace {

void fill_ray(RTCRay& ray, const Vec3d& origin, const Vec3d& dir, double t_max) {
  ray.org_x = float(origin.x()), ray.org_y = float(origin.y()), ray.org_z = float(origin.z());
  ray.dir_x = float(dir.x()), ray.dir_y = float(dir.y()), ray.dir_z = float(dir.z());
  ray.tnear = 0.0f;
  ray.tfar = float(std::min(t_max, 3e38));
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
}

// Float hits are within ~1e-6 relative of the double solution; farther means a grazing or
// degenerate case where the float answer is kept.
constexpr double kRefineWindow = 1e-4;

// A terrain hit: Embree's patch and grid coordinates (u, v) give the cell; the ray is re-solved in
// double against the cell's two triangles (Moller & Trumbore 1997), as mesh hits are below, and
// the triangle whose barycentric weights are least outside [0, 1] is the one met.
void terrain_hit(const TerrainGrid& grid, const Vec3d& origin, const Vec3d& dir, unsigned patch, double u, double v,
                 Hit* hit) {
  const auto [row, col] = grid.cell_of(patch, u, v);
  const TerrainPatch& p = grid.patches()[patch];
  // Fractions across the cell from Embree's own coordinates: the fallback when both triangles
  // lie along the ray.
  const double fc = std::clamp(u * (p.cols - 1) - (col - int(p.col)), 0.0, 1.0);
  const double fr = std::clamp(v * (p.rows - 1) - (row - int(p.row)), 0.0, 1.0);
  int best = fc + fr <= 1.0 ? 0 : 1;
  double b1 = best == 0 ? fr : 1.0 - fr, b2 = best == 0 ? fc : 1.0 - fc, t = hit->t;
  double least_outside = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2; ++k) {
    const auto tri = grid.triangle(row, col, k);
    const Vec3d p0 = grid.position(tri[0][0], tri[0][1]);
    const Vec3d e1 = grid.position(tri[1][0], tri[1][1]) - p0, e2 = grid.position(tri[2][0], tri[2][1]) - p0;
    const Vec3d pv = dir.cross(e2);
    const double det = e1.dot(pv);
    if (!(std::abs(det) > 1e-300)) continue;
    const Vec3d tv = origin - p0, qv = tv.cross(e1);
    const double c1 = tv.dot(pv) / det, c2 = dir.dot(qv) / det, ct = e2.dot(qv) / det;
    const double outside = std::max(0.0, -c1) + std::max(0.0, -c2) + std::max(0.0, c1 + c2 - 1.0);
    if (outside < least_outside) least_outside = outside, best = k, b1 = c1, b2 = c2, t = ct;
  }
  if (t > 0.0 && std::abs(t - hit->t) <= kRefineWindow * (1.0 + hit->t)) hit->t = t;  // not at grazing
  b1 = std::clamp(b1, 0.0, 1.0), b2 = std::clamp(b2, 0.0, 1.0);
  if (b1 + b2 > 1.0) {
    const double sum = b1 + b2;
    b1 /= sum, b2 /= sum;
  }
  const auto tri = grid.triangle(row, col, best);
  const Vec3d p0 = grid.position(tri[0][0], tri[0][1]);
  const Vec3d normal =
      (grid.position(tri[1][0], tri[1][1]) - p0).cross(grid.position(tri[2][0], tri[2][1]) - p0).normalized();
  hit->point = origin + hit->t * dir;
  hit->front_face = normal.dot(dir) < 0.0;  // the front is up (terrain.h)
  hit->normal = hit->front_face ? normal : Vec3d(-normal);
  hit->primitive = unsigned(2 * (size_t(row) * size_t(grid.cols() - 1) + size_t(col)) + size_t(best));
  hit->b1 = b1, hit->b2 = b2;
}

}  // namespace

std::optional<Hit> Scene::intersect(const Vec3d& origin, const Vec3d& dir, double t_max) const {
  check_ray(origin, dir, t_max);
  if (impl_->dirty) commit();
  QueryContext context;
  rtcInitIntersectContext(&context.context);
  context.origin = origin, context.dir = dir;
  RTCRayHit query;
  fill_ray(query.ray, origin, dir, t_max);
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context.context, &query);
  if (context.filter_error) throw IoError(*context.filter_error);
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  Hit hit;
  hit.t = query.ray.tfar;
  if (const TerrainGrid* grid = terrain(query.hit.geomID)) {
    terrain_hit(*grid, origin, dir, query.hit.primID, query.hit.u, query.hit.v, &hit);
    hit.geometry = query.hit.geomID;
    return hit;
  }
  // The hit re-solved in double against the primitive: Embree's float t carries an error of
  // about 6e-8 of the distance, which beyond a few hundred metres exceeds the offsets that keep
  // secondary rays off the surface (a glass seen from 1 km lost all its transmission).
  if (const auto& spheres = sphere_sets_.at(query.hit.geomID)) {
    // The callback's root, solved from the double ray; the normal from the centre in double.
    const Vec3d& centre = spheres->centres.at(query.hit.primID);
    if (context.geometry == query.hit.geomID && context.primitive == query.hit.primID) hit.t = context.t;
    hit.point = origin + hit.t * dir;
    hit.extent = centre.cwiseAbs().array() + spheres->radii.at(query.hit.primID);
    const Vec3d normal = (hit.point - centre).normalized();  // unit also where the float t was kept
    hit.front_face = normal.dot(dir) < 0.0;
    hit.normal = hit.front_face ? normal : Vec3d(-normal);
    hit.geometry = query.hit.geomID;
    hit.primitive = query.hit.primID;
    return hit;
  } else {
    const Mesh& mesh = meshes_.at(query.hit.geomID).mesh;
    const auto& tri = mesh.triangles.at(query.hit.primID);
    const Vec3d& v0 = mesh.vertices[tri[0]];
    for (int k = 0; k < 3; ++k) hit.extent = hit.extent.cwiseMax(mesh.vertices[tri[k]].cwiseAbs());
    const Vec3d n = (mesh.vertices[tri[1]] - v0).cross(mesh.vertices[tri[2]] - v0);
    const double along = n.dot(dir);
    if (along != 0.0) {
      const double t = n.dot(v0 - origin) / along;
      if (t > 0.0 && std::abs(t - hit.t) <= kRefineWindow * (1.0 + hit.t)) hit.t = t;  // not at grazing
    }
  }
  hit.point = origin + hit.t * dir;
  Vec3d normal(query.hit.Ng_x, query.hit.Ng_y, query.hit.Ng_z);
  normal.normalize();
  // Embree's triangle Ng points along (v1 - v0) x (v2 - v0): refracta's counter-clockwise front
  // (checked by tests/render: a one-sided emitter is seen from its front only).
  hit.front_face = normal.dot(dir) < 0.0;
  hit.normal = hit.front_face ? normal : Vec3d(-normal);
  hit.geometry = query.hit.geomID;
  hit.primitive = query.hit.primID;
  hit.b1 = query.hit.u;
  hit.b2 = query.hit.v;
  return hit;
}

bool Scene::occluded(const Vec3d& origin, const Vec3d& dir, double t_max) const {
  check_ray(origin, dir, t_max);
  if (impl_->dirty) commit();
  QueryContext query;  // the context cut-out filters expect (the sphere fields unused)
  rtcInitIntersectContext(&query.context);
  RTCRay ray;
  fill_ray(ray, origin, dir, t_max);
  rtcOccluded1(impl_->scene, &query.context, &ray);
  if (query.filter_error) throw IoError(*query.filter_error);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

Mesh ground_mesh(double height, double half_size) {
  // Named as add_ground and scene files take them: the side `size` = 2 half_size, and the height.
  if (!(half_size > 0.0 && half_size <= kSceneReach)) {
    throw_invalid("ground: size must be > 0 and at most ", 2.0 * kSceneReach, " m (got ", 2.0 * half_size, ")");
  }
  if (!(std::abs(height) <= kSceneReach)) {
    throw_invalid("ground: height must be finite and within ", kSceneReach, " m of 0 (got ", height, ")");
  }
  Mesh mesh;
  mesh.vertices = {{-half_size, height, -half_size}, {half_size, height, -half_size},
                   {half_size, height, half_size}, {-half_size, height, half_size}};
  mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
  return mesh;
}

Mesh ground_mesh(double height, double half_size, double texture_size) {
  // float texture coordinates keep no fraction of a repeat beyond 2^23 repeats (1e40 repeats gave
  // NaN pixels): at most 1e6 across the ground keeps 4 fractional bits.
  if (!(texture_size > 0.0) || !std::isfinite(texture_size) || !(half_size / texture_size <= 1e6)) {
    throw_invalid("texture_size must be > 0 and at least size / 2e6 = ", half_size / 1e6, " m (got ", texture_size, ")");
  }
  Mesh mesh = ground_mesh(height, half_size);
  for (const auto& v : mesh.vertices) mesh.uvs.emplace_back(v.x() / texture_size, -v.z() / texture_size);
  return mesh;
}

Mesh box_mesh(const Vec3d& centre, const Vec3d& size) {
  if (!is_finite(centre) || !(size.minCoeff() > 0.0)) throw_invalid("box: size must be > 0 and centre finite");
  Mesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.push_back(centre + 0.5 * Vec3d((i & 1) ? size.x() : -size.x(), (i & 2) ? size.y() : -size.y(),
                                                 (i & 4) ? size.z() : -size.z()));
  }
  mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return mesh;
}

Mesh billboard_mesh(const Vec3d& centre, double width, double height, const Vec3d& facing) {
  Vec3d across(facing.z(), 0.0, -facing.x());  // horizontal, perpendicular to facing
  if (!(across.norm() > 0.0)) throw_invalid("facing must have a horizontal component");
  if (!(width > 0.0) || !(height > 0.0)) throw_invalid("width and height must be > 0");
  across = across.normalized() * (0.5 * width);
  const Vec3d up(0.0, 0.5 * height, 0.0);
  Mesh mesh;
  mesh.vertices = {centre - across - up, centre + across - up, centre + across + up, centre - across + up};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.uvs = {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}};
  return mesh;
}

bool Scene::has_uvs(unsigned geometry) const {
  if (terrain(geometry)) return true;  // an affine map of the grid's (column, row)
  return !sphere_sets_.at(geometry) && !meshes_.at(geometry).mesh.uvs.empty();
}

namespace {

// The shading part of a hit on triangle p (barycentric weights b1, b2 of p[1], p[2]): the
// interpolated shading normal (when normals are given; a zero one counts for nothing), uv, dp/du
// and the texture footprint (Scene::interaction). si's point and geometric normal are set.
void triangle_surface(const std::array<Vec3d, 3>& p, const std::array<Vec3d, 3>* normals,
                      const std::array<Eigen::Vector2d, 3>* uvs, double b1, double b2, const Vec3d& dir,
                      const std::array<Vec3d, 2>& footprint, SurfaceInteraction* out) {
  SurfaceInteraction& si = *out;
  const double b0 = 1.0 - b1 - b2;
  const Vec3d& p0 = p[0];
  const Vec3d e1 = p[1] - p0, e2 = p[2] - p0;
  if (normals) {
    Vec3d ns = b0 * (*normals)[0] + b1 * (*normals)[1] + b2 * (*normals)[2];
    if (ns.norm() > 1e-12) {
      ns.normalize();
      si.ns = ns.dot(si.n) < 0.0 ? Vec3d(-ns) : ns;  // on the geometric normal's side
    }
  }
  si.dpdu = e1.norm() > 0.0 ? Vec3d(e1.normalized()) : Vec3d::UnitX();
  if (!uvs) return;
  const std::array<Eigen::Vector2d, 3>& uv = *uvs;
  si.uv = b0 * uv[0] + b1 * uv[1] + b2 * uv[2];
  Eigen::Matrix2d uv_edges;
  uv_edges << uv[1] - uv[0], uv[2] - uv[0];
  // dp/du from the uv parametrisation when it is not degenerate.
  if (std::abs(uv_edges.determinant()) > 1e-300) {
    const Eigen::Matrix2d inverse = uv_edges.inverse();
    const Vec3d dpdu = e1 * inverse(0, 0) + e2 * inverse(1, 0);
    if (is_finite(dpdu) && dpdu.norm() > 0.0) si.dpdu = dpdu.normalized();
  }
  TextureLookup& at = si.texture;
  at.s = si.uv.x();
  at.t = 1.0 - si.uv.y();  // OIIO's t runs down the image, OBJ's v up
  if (footprint[0].squaredNorm() + footprint[1].squaredNorm() > 0.0) {
    // Footprint axes across the ray, projected along it onto the plane; then barycentric
    // offsets by the pseudo-inverse of the edge matrix, and uv offsets by the uv edges.
    Eigen::Matrix<double, 3, 2> edges;
    edges << e1, e2;
    const Vec3d n = e1.cross(e2);
    const Vec3d d = dir.normalized();
    const Eigen::Matrix<double, 2, 3> to_bary = (edges.transpose() * edges).inverse() * edges.transpose();
    Eigen::Vector2d duv[2];
    for (int k = 0; k < 2; ++k) {
      const double along = n.dot(d);
      const Vec3d& axis = footprint[k];
      const Vec3d on_plane = std::abs(along) > 1e-12 * n.norm() ? Vec3d(axis - d * (n.dot(axis) / along)) : axis;
      duv[k] = uv_edges * (to_bary * on_plane);
    }
    // A grazing view stretches the footprint without bound: cap it at a few texture repeats.
    at.dsdx = std::clamp(duv[0].x(), -4.0, 4.0), at.dtdx = std::clamp(-duv[0].y(), -4.0, 4.0);
    at.dsdy = std::clamp(duv[1].x(), -4.0, 4.0), at.dtdy = std::clamp(-duv[1].y(), -4.0, 4.0);
  }
}

}  // namespace

SurfaceInteraction Scene::interaction(const Hit& hit, const Vec3d& dir, double footprint) const {
  // The cone's axes only where a footprint is used: textured geometry (uvs) and a cone.
  if (!(footprint > 0.0) || !has_uvs(hit.geometry)) return interaction(hit, dir, std::array<Vec3d, 2>{Vec3d::Zero(), Vec3d::Zero()});
  const Frame across = Frame::from_z(dir.normalized());
  return interaction(hit, dir, std::array<Vec3d, 2>{across.s * footprint, across.t * footprint});
}

SurfaceInteraction Scene::interaction(const Hit& hit, const Vec3d& dir, const std::array<Vec3d, 2>& footprint) const {
  SurfaceInteraction si;
  si.p = hit.point;
  si.extent = hit.extent;
  si.t = hit.t;
  si.geometry = hit.geometry;
  si.primitive = hit.primitive;
  si.material = materials_.at(hit.geometry);
  si.front_face = hit.front_face;
  si.n = hit.front_face ? hit.normal : Vec3d(-hit.normal);
  si.ns = si.n;
  si.wo = -dir.normalized();
  if (const auto& spheres = sphere_sets_[hit.geometry]) {
    // dp/du along the parallel through the hit (around y). Spheres have no texture coordinates
    // (has_uvs; add_sphere and set_material refuse textured materials for them): uv stays zero.
    const Vec3d c = spheres->centres.at(hit.primitive);
    const Vec3d d = (si.p - c).normalized();
    si.dpdu = Vec3d(-d.z(), 0.0, d.x());
    if (!(si.dpdu.norm() > 1e-12)) si.dpdu = Vec3d::UnitX();
    si.dpdu.normalize();
    return si;
  }
  if (const TerrainGrid* grid = terrain(hit.geometry)) {
    // The hit's triangle of its cell (Hit's primitive), normals and uvs from the grid.
    const size_t cell = hit.primitive / 2;
    const int row = int(cell / size_t(grid->cols() - 1)), col = int(cell % size_t(grid->cols() - 1));
    const auto tri = grid->triangle(row, col, int(hit.primitive % 2));
    std::array<Vec3d, 3> p, normals;
    std::array<Eigen::Vector2d, 3> uvs;
    for (int k = 0; k < 3; ++k) {
      p[k] = grid->position(tri[k][0], tri[k][1]);
      normals[k] = grid->normal(tri[k][0], tri[k][1]);
      uvs[k] = grid->uv(tri[k][0], tri[k][1]);
    }
    triangle_surface(p, &normals, &uvs, hit.b1, hit.b2, dir, footprint, &si);
    return si;
  }
  const Mesh& mesh = meshes_.at(hit.geometry).mesh;
  const auto& tri = mesh.triangles.at(hit.primitive);
  const std::array<Vec3d, 3> p{mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]};
  std::array<Vec3d, 3> normals;
  std::array<Eigen::Vector2d, 3> uvs;
  if (!mesh.normals.empty()) normals = {mesh.normals[tri[0]], mesh.normals[tri[1]], mesh.normals[tri[2]]};
  if (!mesh.uvs.empty()) uvs = {mesh.uvs[tri[0]], mesh.uvs[tri[1]], mesh.uvs[tri[2]]};
  triangle_surface(p, mesh.normals.empty() ? nullptr : &normals, mesh.uvs.empty() ? nullptr : &uvs, hit.b1, hit.b2, dir,
                   footprint, &si);
  return si;
}

Mesh sphere_mesh(const Vec3d& centre, double radius, int segments, int rings) {
  if (!is_finite(centre) || !(radius > 0.0) || segments < 3 || rings < 2) {
    throw_invalid("sphere: radius must be > 0, centre finite, segments >= 3, rings >= 2");
  }
  Mesh mesh;
  for (int j = 0; j <= rings; ++j) {
    const double theta = kPi * j / rings;
    for (int i = 0; i < segments; ++i) {
      const double phi = 2.0 * kPi * i / segments;
      mesh.vertices.push_back(centre + radius * Vec3d(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                      std::sin(theta) * std::sin(phi)));
    }
  }
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      const int a = j * segments + i, b = j * segments + (i + 1) % segments;
      const int c = a + segments, d = b + segments;
      if (j > 0) mesh.triangles.push_back({a, b, c});
      if (j + 1 < rings) mesh.triangles.push_back({b, d, c});
    }
  }
  return mesh;
}

}  // namespace refracta
