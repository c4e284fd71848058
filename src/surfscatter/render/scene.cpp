#include "surfscatter/render/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <embree3/rtcore.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::render {

// What every hit on a triangle needs and only its vertices decide, computed once when the shape is added (32 bytes a
// triangle) instead of a cross product, a square root and two divisions on every hit.
struct TriangleConstants {
    Vec3 ng;              // unit geometric normal
    double inv_uv_det;    // 1 / det(uv1 - uv0, uv2 - uv0), 0 without uvs or when degenerate
};

struct Scene::Shape {
    TriangleMesh mesh;             // world space (meshes)
    std::vector<TriangleConstants> triangle_constants;  // meshes, one per triangle
    AnalyticShapePtr analytic;     // or an analytic shape
    std::vector<double> area_cdf;  // triangle areas, cumulative (mesh emitters only)
    double area = 0;
    MaterialPtr material;
    SpectrumPtr radiance;
};

struct Scene::Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    ~Embree() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

Frame Hit::shading_frame() const {
    if (!tangent_from_uv) return Frame(ns);
    const Vec3 s = dpdu - ns * dot(ns, dpdu);
    const double length2 = s.length_squared();
    if (!(length2 > 1e-24 * dpdu.length_squared())) return Frame(ns);  // |s| <= 1e-12 |dp/du|: no tangent
    const Vec3 sn = s * (1 / std::sqrt(length2));
    return Frame(sn, cross(ns, sn), ns);
}

Scene::Scene() : embree_(std::make_unique<Embree>()) {
    embree_->device = rtcNewDevice(nullptr);
    if (!embree_->device) fail("cannot create the Embree device (error {})", static_cast<int>(rtcGetDeviceError(nullptr)));
    embree_->scene = rtcNewScene(embree_->device);
    rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);
}

Scene::~Scene() = default;

namespace {

double triangle_area(const TriangleMesh& m, std::size_t i) {
    const auto& t = m.triangles[i];
    return 0.5 * cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]).length();
}

void require_in_scene(const Vec3& p, const char* what) {
    for (int c = 0; c < 3; ++c)
        if (!(std::abs(p[c]) <= kMaxSceneCoordinate))
            fail("{} ({}, {}, {}) is not finite or beyond the +-{:g} a scene may span", what, p.x, p.y, p.z,
                 kMaxSceneCoordinate);
}

// Every vertex inside the scene's range, normals and uvs finite, indices in range: nothing the tracer could turn
// into NaN or an out-of-bounds read.
void check_mesh(const TriangleMesh& mesh) {
    if (mesh.positions.size() > std::numeric_limits<std::uint32_t>::max() ||
        mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max())
        fail("a mesh may hold at most 2^32 - 1 vertices and triangles, got {} and {}", mesh.positions.size(),
             mesh.triangles.size());
    for (const Vec3& p : mesh.positions) require_in_scene(p, "vertex");
    for (const Vec3& n : mesh.normals)
        if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z) || !(n.length() > 0))
            fail("vertex normal ({}, {}, {}) is not a finite non-zero vector", n.x, n.y, n.z);
    for (const Vec2& uv : mesh.uvs)
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) fail("texture coordinate ({}, {}) is not finite", uv.x, uv.y);
    for (const auto& t : mesh.triangles)
        for (std::uint32_t index : t)
            if (index >= mesh.positions.size())
                fail("triangle vertex index {} out of range ({} vertices)", index, mesh.positions.size());
}

// Embree user-geometry callbacks: the analytic shape's own double-precision intersection.
void analytic_bounds(const RTCBoundsFunctionArguments* args) {
    const auto* shape = static_cast<const AnalyticShape*>(args->geometryUserPtr);
    Vec3 lo, hi;
    shape->bounds(lo, hi);
    // Widen by float round-off so that Embree's float boxes contain the double-precision surface.
    const double pad = 1e-5 * (1 + std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x),
                                             std::abs(hi.y), std::abs(hi.z)}));
    args->bounds_o->lower_x = static_cast<float>(lo.x - pad);
    args->bounds_o->lower_y = static_cast<float>(lo.y - pad);
    args->bounds_o->lower_z = static_cast<float>(lo.z - pad);
    args->bounds_o->upper_x = static_cast<float>(hi.x + pad);
    args->bounds_o->upper_y = static_cast<float>(hi.y + pad);
    args->bounds_o->upper_z = static_cast<float>(hi.z + pad);
}

void analytic_intersect(const RTCIntersectFunctionNArguments* args) {
    const auto* shape = static_cast<const AnalyticShape*>(args->geometryUserPtr);
    RTCRayHitN* rayhit = args->rayhit;
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        RTCRayN* ray = RTCRayHitN_RayN(rayhit, args->N);
        const Vec3 o(RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i), RTCRayN_org_z(ray, args->N, i));
        const Vec3 d(RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i), RTCRayN_dir_z(ray, args->N, i));
        float& tfar = RTCRayN_tfar(ray, args->N, i);
        const auto t = shape->intersect(o, d, RTCRayN_tnear(ray, args->N, i), tfar);
        if (!t) continue;
        tfar = static_cast<float>(*t);
        RTCHitN* hit = RTCRayHitN_HitN(rayhit, args->N);
        RTCHitN_geomID(hit, args->N, i) = args->geomID;
        RTCHitN_primID(hit, args->N, i) = args->primID;
        RTCHitN_instID(hit, args->N, i, 0) = RTC_INVALID_GEOMETRY_ID;
    }
}

void analytic_occluded(const RTCOccludedFunctionNArguments* args) {
    const auto* shape = static_cast<const AnalyticShape*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        RTCRayN* ray = args->ray;
        const Vec3 o(RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i), RTCRayN_org_z(ray, args->N, i));
        const Vec3 d(RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i), RTCRayN_dir_z(ray, args->N, i));
        float& tfar = RTCRayN_tfar(ray, args->N, i);
        if (shape->intersect(o, d, RTCRayN_tnear(ray, args->N, i), tfar)) tfar = -std::numeric_limits<float>::infinity();
    }
}

}  // namespace

void Scene::add_shape(ShapeGeometry geometry, MaterialPtr material, SpectrumPtr radiance) {
    Shape shape;
    RTCGeometry g = nullptr;
    if (auto* mesh = std::get_if<TriangleMesh>(&geometry)) {
        shape.mesh = std::move(*mesh);
        const TriangleMesh& m = shape.mesh;
        if (m.triangles.empty()) fail("a mesh shape has no triangles");
        check_mesh(m);
        g = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                      3 * sizeof(float), m.positions.size()));
        for (std::size_t i = 0; i < m.positions.size(); ++i)
            for (int c = 0; c < 3; ++c) vertices[3 * i + static_cast<std::size_t>(c)] = static_cast<float>(m.positions[i][c]);
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                        3 * sizeof(unsigned), m.triangles.size()));
        for (std::size_t i = 0; i < m.triangles.size(); ++i)
            for (std::size_t c = 0; c < 3; ++c) indices[3 * i + c] = m.triangles[i][c];
        shape.triangle_constants.reserve(m.triangles.size());
        for (const auto& t : m.triangles) {
            const Vec3& p0 = m.positions[t[0]];
            TriangleConstants c{normalize(cross(m.positions[t[1]] - p0, m.positions[t[2]] - p0)), 0.0};
            if (!m.uvs.empty()) {
                const Vec2 d1 = m.uvs[t[1]] - m.uvs[t[0]], d2 = m.uvs[t[2]] - m.uvs[t[0]];
                const double det = d1.x * d2.y - d1.y * d2.x;
                if (std::abs(det) > 1e-20) c.inv_uv_det = 1 / det;
            }
            shape.triangle_constants.push_back(c);
        }
        if (radiance) {
            double sum = 0;
            for (std::size_t i = 0; i < m.triangles.size(); ++i) {
                sum += triangle_area(m, i);
                shape.area_cdf.push_back(sum);
            }
            shape.area = sum;
        }
    } else {
        shape.analytic = std::get<AnalyticShapePtr>(geometry);
        shape.area = shape.analytic->area();
        Vec3 lo, hi;
        shape.analytic->bounds(lo, hi);
        require_in_scene(lo, "the shape's bounding box corner");
        require_in_scene(hi, "the shape's bounding box corner");
        g = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(g, 1);
        rtcSetGeometryUserData(g, const_cast<AnalyticShape*>(shape.analytic.get()));
        rtcSetGeometryBoundsFunction(g, analytic_bounds, nullptr);
        rtcSetGeometryIntersectFunction(g, analytic_intersect);
        rtcSetGeometryOccludedFunction(g, analytic_occluded);
    }
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(embree_->scene, g);
    rtcReleaseGeometry(g);
    if (id != shapes_.size()) fail("internal: Embree geometry ids out of order");
    if (radiance) {
        if (!(shape.area > 0)) fail("an area emitter's shape has zero area");
        area_emitters_.push_back(static_cast<int>(shapes_.size()));
    }
    shape.material = std::move(material);
    shape.radiance = std::move(radiance);
    shapes_.push_back(std::move(shape));
}

void Scene::add_emitter(EmitterPtr emitter) {
    if (emitter->is_environment()) environments_.push_back(emitter.get());
    emitters_.push_back(std::move(emitter));
}

void Scene::commit() { rtcCommitScene(embree_->scene); }

std::optional<Hit> Scene::intersect(const Ray& ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray.org_x = static_cast<float>(ray.origin.x);
    rh.ray.org_y = static_cast<float>(ray.origin.y);
    rh.ray.org_z = static_cast<float>(ray.origin.z);
    rh.ray.dir_x = static_cast<float>(ray.direction.x);
    rh.ray.dir_y = static_cast<float>(ray.direction.y);
    rh.ray.dir_z = static_cast<float>(ray.direction.z);
    rh.ray.tnear = static_cast<float>(ray.t_min);
    rh.ray.tfar = static_cast<float>(std::min(ray.t_max, 3e38));
    rh.ray.time = 0;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_->scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

    Hit hit;
    hit.shape = static_cast<int>(rh.hit.geomID);
    const Shape& shape = shapes_[rh.hit.geomID];
    if (shape.analytic) {
        // Embree keeps the distance in float: find the same root again in double.
        const double t_float = rh.ray.tfar;
        const double t = shape.analytic->intersect(ray.origin, ray.direction, std::max(ray.t_min, t_float * (1 - 1e-5) - 1e-7),
                                                   t_float * (1 + 1e-5) + 1e-7).value_or(t_float);
        const SurfaceGeometry g = shape.analytic->surface(ray.origin + ray.direction * t);
        hit.p = g.p;
        hit.ng = hit.ns = g.n;
        hit.uv = g.uv;
        hit.dpdu = g.dpdu;
        hit.dpdv = g.dpdv;
        hit.t = (hit.p - ray.origin).length();
        return hit;
    }
    const auto& tri = shape.mesh.triangles[rh.hit.primID];
    const double b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1 - b1 - b2;
    const TriangleMesh& m = shape.mesh;
    const Vec3& p0 = m.positions[tri[0]];
    const Vec3& p1 = m.positions[tri[1]];
    const Vec3& p2 = m.positions[tri[2]];
    const TriangleConstants& constants = shape.triangle_constants[rh.hit.primID];
    hit.p = p0 * b0 + p1 * b1 + p2 * b2;
    hit.ng = constants.ng;
    if (!m.normals.empty()) {
        const Vec3 n = m.normals[tri[0]] * b0 + m.normals[tri[1]] * b1 + m.normals[tri[2]] * b2;
        const double n2 = n.length_squared();
        hit.ns = n2 > 0 ? n * (1 / std::sqrt(n2)) : hit.ng;
        if (dot(hit.ns, hit.ng) < 0) hit.ns = -hit.ns;
    } else {
        hit.ns = hit.ng;
    }
    // dp/du, dp/dv from the uv parametrisation (Mitsuba; the barycentrics stand in when the mesh has no uv).
    hit.dpdu = p1 - p0;
    hit.dpdv = p2 - p0;
    if (!m.uvs.empty()) {
        const Vec2 t0 = m.uvs[tri[0]], t1 = m.uvs[tri[1]], t2 = m.uvs[tri[2]];
        hit.uv = t0 * b0 + t1 * b1 + t2 * b2;
        if (constants.inv_uv_det != 0) {
            const Vec2 d1 = t1 - t0, d2 = t2 - t0;
            const Vec3 e1 = p1 - p0, e2 = p2 - p0;
            hit.dpdu = (e1 * d2.y - e2 * d1.y) * constants.inv_uv_det;
            hit.dpdv = (e2 * d1.x - e1 * d2.x) * constants.inv_uv_det;
        } else {
            hit.tangent_from_uv = false;
        }
    } else {
        hit.uv = {b1, b2};
        hit.tangent_from_uv = false;
    }
    hit.t = (hit.p - ray.origin).length();
    return hit;
}

bool Scene::occluded(const Vec3& origin, const Vec3& direction, double t_max) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    ray.org_x = static_cast<float>(origin.x);
    ray.org_y = static_cast<float>(origin.y);
    ray.org_z = static_cast<float>(origin.z);
    ray.dir_x = static_cast<float>(direction.x);
    ray.dir_y = static_cast<float>(direction.y);
    ray.dir_z = static_cast<float>(direction.z);
    ray.tnear = 0.0f;
    ray.tfar = static_cast<float>(std::min(t_max, 3e38));
    ray.time = 0;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
    rtcOccluded1(embree_->scene, &context, &ray);
    return ray.tfar < 0;
}

std::size_t Scene::emitter_count() const { return emitter_choices(); }

const Material* Scene::material(int shape) const { return shapes_[static_cast<std::size_t>(shape)].material.get(); }

SampledSpectrum Scene::emitted(const Hit& hit, const Vec3& direction, const SampledWavelengths& w) const {
    const Shape& shape = shapes_[static_cast<std::size_t>(hit.shape)];
    if (!shape.radiance || dot(hit.ng, direction) >= 0) return SampledSpectrum(0.0);
    return shape.radiance->eval(w);
}

double Scene::emitter_pdf(const Vec3& from, const Hit& hit, const Vec3& direction) const {
    const Shape& shape = shapes_[static_cast<std::size_t>(hit.shape)];
    const double cos_light = -dot(hit.ng, direction);
    if (!shape.radiance || cos_light <= 0) return 0.0;
    const double d2 = (hit.p - from).length_squared();
    return d2 / (cos_light * shape.area * static_cast<double>(emitter_choices()));
}

SampledSpectrum Scene::environment(const Vec3& direction, const SampledWavelengths& w) const {
    SampledSpectrum sum(0.0);
    for (const Emitter* e : environments_) sum += e->environment(direction, w);
    return sum;
}

double Scene::environment_pdf(const Vec3& direction) const {
    double sum = 0;
    for (const Emitter* e : environments_) sum += e->environment_pdf(direction);
    return sum / static_cast<double>(emitter_choices());
}

std::optional<EmitterSample> Scene::sample_emitter(const Vec3& p, double u_choice, Vec2 u,
                                                  const SampledWavelengths& w) const {
    const std::size_t count = emitter_choices();
    if (count == 0) return std::nullopt;
    const std::size_t index = std::min(static_cast<std::size_t>(u_choice * static_cast<double>(count)), count - 1);
    const double choice = 1.0 / static_cast<double>(count);
    if (index >= area_emitters_.size()) {
        auto s = emitters_[index - area_emitters_.size()]->sample(p, u, w);
        if (s) s->pdf *= choice;
        return s;
    }
    const Shape& shape = shapes_[static_cast<std::size_t>(area_emitters_[index])];
    Vec3 q, n;
    if (shape.analytic) {
        const SurfaceGeometry g = shape.analytic->sample(u);
        q = g.p;
        n = g.n;
    } else {
        // Pick a triangle by area (u.x reused after rescaling), then a uniform point in it.
        const double target = u.x * shape.area;
        const auto it = std::lower_bound(shape.area_cdf.begin(), shape.area_cdf.end(), target);
        const std::size_t i = std::min(static_cast<std::size_t>(it - shape.area_cdf.begin()), shape.area_cdf.size() - 1);
        const double lo = i == 0 ? 0.0 : shape.area_cdf[i - 1];
        const double ux = std::clamp((target - lo) / std::max(shape.area_cdf[i] - lo, 1e-300), 0.0, 1.0);
        const double su = std::sqrt(ux);
        const double b0 = 1 - su, b1 = u.y * su;
        const auto& t = shape.mesh.triangles[i];
        const Vec3& p0 = shape.mesh.positions[t[0]];
        const Vec3& p1 = shape.mesh.positions[t[1]];
        const Vec3& p2 = shape.mesh.positions[t[2]];
        q = p0 * b0 + p1 * b1 + p2 * (1 - b0 - b1);
        n = normalize(cross(p1 - p0, p2 - p0));
    }
    const Vec3 d = q - p;
    const double d2 = d.length_squared();
    if (!(d2 > 0)) return std::nullopt;
    EmitterSample s;
    s.distance = std::sqrt(d2);
    s.wi = d / s.distance;
    const double cos_light = -dot(n, s.wi);
    if (cos_light <= 0) return std::nullopt;
    s.radiance = shape.radiance->eval(w);
    s.pdf = choice * d2 / (cos_light * shape.area);
    return s;
}

Vec3 Scene::offset_origin(const Hit& hit, const Vec3& direction) {
    const double scale = 1e-5 * (1.0 + std::max({std::abs(hit.p.x), std::abs(hit.p.y), std::abs(hit.p.z)}));
    return hit.p + hit.ng * (dot(hit.ng, direction) > 0 ? scale : -scale);
}

}  // namespace surfscatter::render
