// Mitsuba's `disk` shape: the unit disk in the plane z = 0, normal +z, intersected exactly (Embree user geometry).
//
// Supported: `to_world` (any affine map: a scaled disk is an ellipse), `flip_normals`. uv = (r, phi / 2 pi) as in
// Mitsuba. As an area emitter it is sampled uniformly by area (concentric mapping).
// Differences: none.
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"
#include "surfscatter/render/shapes/analytic.hpp"

namespace surfscatter::render {

namespace {

class Disk final : public AnalyticShape {
public:
    Disk(const Transform& to_world, bool flip)
        : to_world_(to_world), to_object_(to_world.inverse()),
          normal_(to_world.normal({0, 0, 1})),
          area_(kPi * cross(to_world.vector({1, 0, 0}), to_world.vector({0, 1, 0})).length()), flip_(flip) {}

    std::optional<double> intersect(const Vec3& o, const Vec3& d, double t_min, double t_max) const override {
        const Vec3 lo = to_object_.point(o), ld = to_object_.vector(d);
        if (ld.z == 0) return std::nullopt;
        const double t = -lo.z / ld.z;
        if (!(t > t_min && t < t_max)) return std::nullopt;
        const double x = lo.x + t * ld.x, y = lo.y + t * ld.y;
        if (x * x + y * y > 1) return std::nullopt;
        return t;
    }

    SurfaceGeometry surface(const Vec3& p) const override {
        const Vec3 local = to_object_.point(p);
        return at(local.x, local.y);
    }

    SurfaceGeometry sample(Vec2 u) const override {
        const Vec2 d = square_to_uniform_disk_concentric(u);
        return at(d.x, d.y);
    }
    double area() const override { return area_; }
    void bounds(Vec3& lo, Vec3& hi) const override {
        // The ellipse's extent along each world axis: centre +- |row of the 2x2 part|.
        const Vec3 c = to_world_.point({0, 0, 0}), ex = to_world_.vector({1, 0, 0}), ey = to_world_.vector({0, 1, 0});
        for (int k = 0; k < 3; ++k) {
            const double r = std::hypot(ex[k], ey[k]);
            lo[k] = c[k] - r;
            hi[k] = c[k] + r;
        }
    }

private:
    SurfaceGeometry at(double x, double y) const {
        const double r = std::hypot(x, y);
        double phi = std::atan2(y, x);
        if (phi < 0) phi += kTwoPi;
        SurfaceGeometry g;
        g.p = to_world_.point({x, y, 0});
        g.n = flip_ ? -normal_ : normal_;
        g.uv = {r, phi / kTwoPi};
        g.dpdu = to_world_.vector({std::cos(phi), std::sin(phi), 0});
        g.dpdv = to_world_.vector(Vec3(-y, x, 0) * kTwoPi);
        return g;
    }

    Transform to_world_, to_object_;
    Vec3 normal_;
    double area_;
    bool flip_;
};

}  // namespace

ShapeGeometry plugins::disk(Properties& props) {
    const Transform to_world = props.get_transform("to_world");
    if (!(cross(to_world.vector({1, 0, 0}), to_world.vector({0, 1, 0})).length() > 0))
        props.fail_param("to_world", "disk to_world collapses the disk");
    return std::make_shared<Disk>(to_world, props.get_bool("flip_normals", false));
}

}  // namespace surfscatter::render
