// Mitsuba's `sphere` shape, intersected exactly (double precision, Embree user geometry).
//
// Supported: `center` (default origin), `radius` (default 1), `to_world` (rotation, translation and uniform scale;
// applied after center and radius, as in Mitsuba), `flip_normals`. uv = (phi / 2 pi, theta / pi) in the sphere's
// own frame (theta from its +z). As an area emitter it is sampled uniformly by area.
// Not supported (an error): a to_world with non-uniform scale or shear (the surface would be an ellipsoid).
// Differences: none.
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"
#include "surfscatter/render/shapes/analytic.hpp"

namespace surfscatter::render {

namespace {

class Sphere final : public AnalyticShape {
public:
    Sphere(const Transform& object_to_world, double scale, bool flip)
        : to_world_(object_to_world), to_object_(object_to_world.inverse()), center_(object_to_world.point({0, 0, 0})),
          radius_(scale), flip_(flip) {}

    std::optional<double> intersect(const Vec3& o, const Vec3& d, double t_min, double t_max) const override {
        const Vec3 oc = o - center_;
        double t0 = 0, t1 = 0;
        if (!solve_quadratic(d.length_squared(), 2 * dot(oc, d), oc.length_squared() - radius_ * radius_, t0, t1))
            return std::nullopt;
        if (t0 > t_min && t0 < t_max) return t0;
        if (t1 > t_min && t1 < t_max) return t1;
        return std::nullopt;
    }

    SurfaceGeometry surface(const Vec3& p) const override {
        return at(normalize(to_object_.vector(p - center_)));
    }

    SurfaceGeometry sample(Vec2 u) const override { return at(square_to_uniform_sphere(u)); }
    double area() const override { return 4 * kPi * radius_ * radius_; }
    void bounds(Vec3& lo, Vec3& hi) const override {
        lo = center_ - Vec3(radius_, radius_, radius_);
        hi = center_ + Vec3(radius_, radius_, radius_);
    }

private:
    // The surface at object-space unit direction `local`.
    SurfaceGeometry at(const Vec3& local) const {
        SurfaceGeometry g;
        g.p = to_world_.point(local);
        const Vec3 n = normalize(g.p - center_);
        g.n = flip_ ? -n : n;
        const double theta = std::acos(std::clamp(local.z, -1.0, 1.0));
        double phi = std::atan2(local.y, local.x);
        if (phi < 0) phi += kTwoPi;
        g.uv = {phi / kTwoPi, theta / kPi};
        g.dpdu = to_world_.vector(Vec3(-local.y, local.x, 0) * kTwoPi);
        g.dpdv = to_world_.vector(Vec3(local.z * std::cos(phi), local.z * std::sin(phi), -std::sin(theta)) * kPi);
        return g;
    }

    Transform to_world_, to_object_;
    Vec3 center_;
    double radius_;
    bool flip_;
};

}  // namespace

ShapeGeometry plugins::sphere(Properties& props) {
    const Vec3 center = props.get_point("center").value_or(Vec3(0, 0, 0));
    const double radius = props.get_float("radius", 1.0);
    if (!(radius > 0)) props.fail_param("radius", "sphere radius must be positive, got {}", radius);
    const Transform to_world = props.get_transform("to_world") * Transform::translate(center) *
                               Transform::scale({radius, radius, radius});
    const auto scale = similarity_scale(to_world);
    if (!scale) props.fail_param("to_world", "sphere to_world must be a rotation, translation and uniform scale");
    return std::make_shared<Sphere>(to_world, *scale, props.get_bool("flip_normals", false));
}

}  // namespace surfscatter::render
