#include "surfscatter/render/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <embree3/rtcore.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::render {

struct Scene::Shape {
    bool is_sphere = false;
    TriangleMesh mesh;          // world space
    std::vector<double> area_cdf;  // triangle areas, cumulative (emitters only)
    double area = 0;
    Vec3 center;
    double radius = 0;
    bool flip_normals = false;
    MaterialPtr material;
    SpectrumPtr radiance;
};

struct Scene::Emitter {
    enum class Kind { point, area } kind = Kind::point;
    Vec3 position;
    SpectrumPtr spectrum;
    int shape = -1;
};

struct Scene::Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    ~Embree() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

void FilmSettings::check_crop() const {
    if (crop_width < 0 || crop_height < 0 || crop_offset_x < 0 || crop_offset_y < 0 ||
        crop_offset_x + output_width() > width || crop_offset_y + output_height() > height)
        fail("crop window {}x{} at ({}, {}) does not fit the {}x{} film", output_width(), output_height(), crop_offset_x,
             crop_offset_y, width, height);
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
}  // namespace

void Scene::add_mesh(TriangleMesh mesh, MaterialPtr material, SpectrumPtr radiance) {
    RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                  3 * sizeof(float), mesh.positions.size()));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        for (int c = 0; c < 3; ++c) vertices[3 * i + static_cast<std::size_t>(c)] = static_cast<float>(mesh.positions[i][c]);
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                    3 * sizeof(unsigned), mesh.triangles.size()));
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c) indices[3 * i + c] = mesh.triangles[i][c];
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(embree_->scene, geometry);
    rtcReleaseGeometry(geometry);
    if (id != shapes_.size()) fail("internal: Embree geometry ids out of order");

    Shape shape;
    shape.mesh = std::move(mesh);
    shape.material = std::move(material);
    shape.radiance = std::move(radiance);
    if (shape.radiance) {
        double sum = 0;
        for (std::size_t i = 0; i < shape.mesh.triangles.size(); ++i) {
            sum += triangle_area(shape.mesh, i);
            shape.area_cdf.push_back(sum);
        }
        shape.area = sum;
        emitters_.push_back({Emitter::Kind::area, {}, shape.radiance, static_cast<int>(shapes_.size())});
    }
    shapes_.push_back(std::move(shape));
}

void Scene::add_sphere(const Vec3& center, double radius, bool flip_normals, MaterialPtr material, SpectrumPtr radiance) {
    if (!(radius > 0)) fail("sphere radius must be positive, got {}", radius);
    RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* point = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
    point[0] = static_cast<float>(center.x);
    point[1] = static_cast<float>(center.y);
    point[2] = static_cast<float>(center.z);
    point[3] = static_cast<float>(radius);
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(embree_->scene, geometry);
    rtcReleaseGeometry(geometry);
    if (id != shapes_.size()) fail("internal: Embree geometry ids out of order");
    Shape shape;
    shape.is_sphere = true;
    shape.center = center;
    shape.radius = radius;
    shape.flip_normals = flip_normals;
    shape.area = 4 * kPi * radius * radius;
    shape.material = std::move(material);
    shape.radiance = std::move(radiance);
    if (shape.radiance) emitters_.push_back({Emitter::Kind::area, {}, shape.radiance, static_cast<int>(shapes_.size())});
    shapes_.push_back(std::move(shape));
}

void Scene::add_point_light(const Vec3& position, SpectrumPtr intensity) {
    emitters_.push_back({Emitter::Kind::point, position, std::move(intensity), -1});
}

void Scene::set_environment(SpectrumPtr radiance) {
    if (environment_) fail("a scene may hold only one constant emitter");
    environment_ = std::move(radiance);
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
    hit.t = rh.ray.tfar;
    const Shape& shape = shapes_[rh.hit.geomID];
    if (shape.is_sphere) {
        // Refine in double: re-project onto the exact sphere.
        const Vec3 d = ray.origin + ray.direction * hit.t - shape.center;
        const Vec3 n = normalize(d);
        hit.p = shape.center + n * shape.radius;
        hit.ng = hit.ns = shape.flip_normals ? -n : n;
        const double theta = std::acos(std::clamp(n.z, -1.0, 1.0));
        double phi = std::atan2(n.y, n.x);
        if (phi < 0) phi += kTwoPi;
        hit.uv = {phi / kTwoPi, theta / kPi};
        return hit;
    }
    const auto& tri = shape.mesh.triangles[rh.hit.primID];
    const double b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1 - b1 - b2;
    const TriangleMesh& m = shape.mesh;
    const Vec3& p0 = m.positions[tri[0]];
    const Vec3& p1 = m.positions[tri[1]];
    const Vec3& p2 = m.positions[tri[2]];
    hit.p = p0 * b0 + p1 * b1 + p2 * b2;
    hit.ng = normalize(cross(p1 - p0, p2 - p0));
    if (!m.normals.empty()) {
        const Vec3 n = m.normals[tri[0]] * b0 + m.normals[tri[1]] * b1 + m.normals[tri[2]] * b2;
        hit.ns = n.length() > 0 ? normalize(n) : hit.ng;
        if (dot(hit.ns, hit.ng) < 0) hit.ns = -hit.ns;
    } else {
        hit.ns = hit.ng;
    }
    if (!m.uvs.empty()) hit.uv = m.uvs[tri[0]] * b0 + m.uvs[tri[1]] * b1 + m.uvs[tri[2]] * b2;
    else hit.uv = {b1, b2};
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

std::size_t Scene::emitter_count() const { return emitters_.size(); }

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
    return d2 / (cos_light * shape.area * static_cast<double>(emitters_.size() + (environment_ ? 1 : 0)));
}

SampledSpectrum Scene::environment(const SampledWavelengths& w) const {
    return environment_ ? environment_->eval(w) : SampledSpectrum(0.0);
}

double Scene::environment_pdf() const {
    if (!environment_) return 0.0;
    return 1.0 / (4 * kPi * static_cast<double>(emitters_.size() + 1));
}

std::optional<EmitterSample> Scene::sample_emitter(const Vec3& p, double u_choice, Vec2 u,
                                                  const SampledWavelengths& w) const {
    const std::size_t count = emitters_.size() + (environment_ ? 1 : 0);
    if (count == 0) return std::nullopt;
    const std::size_t index = std::min(static_cast<std::size_t>(u_choice * static_cast<double>(count)), count - 1);
    const double choice = 1.0 / static_cast<double>(count);
    EmitterSample s;
    if (index == emitters_.size()) {  // the constant environment: uniform directions
        const double z = 1 - 2 * u.x, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = kTwoPi * u.y;
        s.wi = {r * std::cos(phi), r * std::sin(phi), z};
        s.distance = std::numeric_limits<double>::infinity();
        s.radiance = environment_->eval(w);
        s.pdf = choice / (4 * kPi);
        return s;
    }
    const Emitter& e = emitters_[index];
    if (e.kind == Emitter::Kind::point) {
        const Vec3 d = e.position - p;
        const double d2 = d.length_squared();
        if (!(d2 > 0)) return std::nullopt;
        s.distance = std::sqrt(d2);
        s.wi = d / s.distance;
        s.radiance = e.spectrum->eval(w) * (1.0 / d2);
        s.pdf = choice;
        s.delta = true;
        return s;
    }
    const Shape& shape = shapes_[static_cast<std::size_t>(e.shape)];
    Vec3 q, n;
    if (shape.is_sphere) {
        const double z = 1 - 2 * u.x, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = kTwoPi * u.y;
        const Vec3 dir(r * std::cos(phi), r * std::sin(phi), z);
        q = shape.center + dir * shape.radius;
        n = shape.flip_normals ? -dir : dir;
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
    s.distance = std::sqrt(d2);
    s.wi = d / s.distance;
    const double cos_light = -dot(n, s.wi);
    if (cos_light <= 0) return std::nullopt;
    s.radiance = e.spectrum->eval(w);
    s.pdf = choice * d2 / (cos_light * shape.area);
    return s;
}

Vec3 Scene::offset_origin(const Hit& hit, const Vec3& direction) {
    const double scale = 1e-5 * (1.0 + std::max({std::abs(hit.p.x), std::abs(hit.p.y), std::abs(hit.p.z)}));
    return hit.p + hit.ng * (dot(hit.ng, direction) > 0 ? scale : -scale);
}

}  // namespace surfscatter::render
