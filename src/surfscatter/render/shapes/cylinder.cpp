// Mitsuba's `cylinder` shape: the open tube (no end caps) of radius `radius` around the segment p0 -> p1,
// intersected exactly (double precision, Embree user geometry).
//
// Supported: `p0` (default origin), `p1` (default (0, 0, 1)), `radius` (default 1), `to_world` (rotation,
// translation and uniform scale; applied after p0, p1 and radius), `flip_normals` (normals point outward unless
// flipped). uv = (phi / 2 pi, distance along the axis / length), phi measured in the frame Mitsuba builds around
// the axis (Duff et al. 2017). As an area emitter it is sampled uniformly by area.
// Not supported (an error): a to_world with non-uniform scale or shear.
// Differences: none.
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"
#include "surfscatter/render/shapes/analytic.hpp"

namespace surfscatter::render {

namespace {

// Object space: radius 1 around the z axis, 0 <= z <= 1.
class Cylinder final : public AnalyticShape {
public:
    Cylinder(const Transform& object_to_world, double radius, double length, bool flip)
        : to_world_(object_to_world), to_object_(object_to_world.inverse()), radius_(radius), length_(length),
          flip_(flip) {}

    std::optional<double> intersect(const Vec3& o, const Vec3& d, double t_min, double t_max) const override {
        const Vec3 lo = to_object_.point(o), ld = to_object_.vector(d);
        const double a = ld.x * ld.x + ld.y * ld.y;
        if (!(a > 0)) return std::nullopt;  // parallel to the axis
        double t0 = 0, t1 = 0;
        if (!solve_quadratic(a, 2 * (lo.x * ld.x + lo.y * ld.y), lo.x * lo.x + lo.y * lo.y - 1, t0, t1)) return std::nullopt;
        for (double t : {t0, t1}) {
            const double z = lo.z + t * ld.z;
            if (t > t_min && t < t_max && z >= 0 && z <= 1) return t;
        }
        return std::nullopt;
    }

    SurfaceGeometry surface(const Vec3& p) const override {
        const Vec3 local = to_object_.point(p);
        return at(std::atan2(local.y, local.x), std::clamp(local.z, 0.0, 1.0));
    }

    SurfaceGeometry sample(Vec2 u) const override { return at(kTwoPi * u.x, u.y); }
    double area() const override { return kTwoPi * radius_ * length_; }
    void bounds(Vec3& lo, Vec3& hi) const override {
        const Vec3 a = to_world_.point({0, 0, 0}), b = to_world_.point({0, 0, 1});
        for (int c = 0; c < 3; ++c) {
            lo[c] = std::min(a[c], b[c]) - radius_;
            hi[c] = std::max(a[c], b[c]) + radius_;
        }
    }

private:
    SurfaceGeometry at(double phi, double z) const {
        if (phi < 0) phi += kTwoPi;
        const double c = std::cos(phi), s = std::sin(phi);
        SurfaceGeometry g;
        g.p = to_world_.point({c, s, z});
        const Vec3 n = normalize(to_world_.vector({c, s, 0}));
        g.n = flip_ ? -n : n;
        g.uv = {phi / kTwoPi, z};
        g.dpdu = to_world_.vector(Vec3(-s, c, 0) * kTwoPi);
        g.dpdv = to_world_.vector({0, 0, 1});
        return g;
    }

    Transform to_world_, to_object_;
    double radius_, length_;
    bool flip_;
};

}  // namespace

ShapeGeometry plugins::cylinder(Properties& props) {
    const Vec3 p0 = props.get_point("p0").value_or(Vec3(0, 0, 0));
    const Vec3 p1 = props.get_point("p1").value_or(Vec3(0, 0, 1));
    const double radius = props.get_float("radius", 1.0);
    if (!(radius > 0)) props.fail_param("radius", "cylinder radius must be positive, got {}", radius);
    const Vec3 axis = p1 - p0;
    const double length = axis.length();
    if (!(length > 0)) props.fail("cylinder p0 and p1 coincide");
    const Frame frame(axis / length);
    Transform placement = Transform::from_rows({frame.s.x, frame.t.x, frame.n.x, p0.x,  //
                                                frame.s.y, frame.t.y, frame.n.y, p0.y,  //
                                                frame.s.z, frame.t.z, frame.n.z, p0.z,  //
                                                0, 0, 0, 1});
    const Transform to_world = props.get_transform("to_world");
    const auto scale = similarity_scale(to_world);
    if (!scale) props.fail_param("to_world", "cylinder to_world must be a rotation, translation and uniform scale");
    return std::make_shared<Cylinder>(to_world * placement * Transform::scale({radius, radius, length}), radius * *scale,
                                      length * *scale, props.get_bool("flip_normals", false));
}

}  // namespace surfscatter::render
