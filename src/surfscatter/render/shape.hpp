#pragma once
// Shapes of the scene: triangle meshes (mesh.hpp: rectangle, cube, obj, ply, serialized) and analytic shapes
// intersected exactly in double precision (sphere, cylinder, disk; Embree user geometry in scene.cpp).
#include <memory>
#include <optional>
#include <variant>

#include "surfscatter/render/mesh.hpp"

namespace surfscatter::render {

// A point on a surface with its local parametrisation (world space).
struct SurfaceGeometry {
    Vec3 p;
    Vec3 n;      // unit normal on the shape's outward side (after flip_normals)
    Vec2 uv;
    Vec3 dpdu, dpdv;
};

class AnalyticShape {
public:
    virtual ~AnalyticShape() = default;
    // Smallest ray parameter t in (t_min, t_max) where origin + t direction meets the surface.
    virtual std::optional<double> intersect(const Vec3& origin, const Vec3& direction, double t_min,
                                            double t_max) const = 0;
    // The surface at a point found by intersect() (or within round-off of the surface).
    virtual SurfaceGeometry surface(const Vec3& p) const = 0;
    // A point distributed uniformly by area (area emitters).
    virtual SurfaceGeometry sample(Vec2 u) const = 0;
    virtual double area() const = 0;
    // Axis-aligned bounds (world).
    virtual void bounds(Vec3& lo, Vec3& hi) const = 0;
};
using AnalyticShapePtr = std::shared_ptr<const AnalyticShape>;

using ShapeGeometry = std::variant<TriangleMesh, AnalyticShapePtr>;

}  // namespace surfscatter::render
