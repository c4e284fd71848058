#include "surfscatter/render/camera.hpp"

#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/render/material.hpp"

namespace surfscatter::render {

Camera::Camera(const CameraSettings& settings, int width, int height)
    : settings_(settings), width_(width), height_(height), inv_width_(1.0 / width), inv_height_(1.0 / height) {
    if (!(settings.fov_degrees > 0 && settings.fov_degrees < 180)) fail("fov must be in (0, 180) degrees, got {}", settings.fov_degrees);
    if (!(settings.near_clip > 0 && settings.far_clip > settings.near_clip))
        fail("need 0 < near_clip < far_clip, got {} and {}", settings.near_clip, settings.far_clip);
    const double t = std::tan(0.5 * settings.fov_degrees * kDegree);
    const double w = width, h = height;
    std::string axis = settings.fov_axis;
    if (axis == "smaller") axis = width <= height ? "x" : "y";
    if (axis == "larger") axis = width >= height ? "x" : "y";
    if (axis == "x") {
        tan_x_ = t;
        tan_y_ = t * h / w;
    } else if (axis == "y") {
        tan_y_ = t;
        tan_x_ = t * w / h;
    } else if (axis == "diagonal") {
        const double d = std::hypot(w, h);
        tan_x_ = t * w / d;
        tan_y_ = t * h / d;
    } else {
        fail("fov_axis must be x, y, diagonal, smaller or larger, got '{}'", settings.fov_axis);
    }
    if (settings.aperture_radius < 0 || !std::isfinite(settings.aperture_radius))
        fail("aperture_radius must be non-negative, got {}", settings.aperture_radius);
    if (settings.aperture_radius > 0 && !(settings.focus_distance > 0))
        fail("focus_distance must be positive, got {}", settings.focus_distance);
    inv_local_z_ = settings.aperture_radius > 0 ? 1 / settings.focus_distance : 1.0;
    origin_ = settings.to_world.point({0, 0, 0});
    to_local_ = settings.to_world.inverse();
}

std::optional<Vec2> Camera::project(const Vec3& p) const {
    const Vec3 local = to_local_.point(p);
    if (!(local.z > 0)) return std::nullopt;
    // Inverse of generate_ray.
    const double sx = -local.x / (local.z * tan_x_), sy = -local.y / (local.z * tan_y_);
    return Vec2(((sx + 1) / 2 - settings_.principal_point_offset_x) * width_,
                ((sy + 1) / 2 - settings_.principal_point_offset_y) * height_);
}

Ray Camera::generate_ray(double x, double y, Vec2 aperture) const {
    // Mitsuba 3: film position (u, v) is traced as if it were (u + offset_x, v + offset_y) of the centred frustum.
    const double sx = 2.0 * (x * inv_width_ + settings_.principal_point_offset_x) - 1.0;   // -1 left .. +1 right
    const double sy = 2.0 * (y * inv_height_ + settings_.principal_point_offset_y) - 1.0;  // -1 top .. +1 bottom
    Vec3 local(-sx * tan_x_, -sy * tan_y_, 1.0);  // on the plane z = 1
    Vec3 lens;                                     // ray origin on the lens (local)
    if (settings_.aperture_radius > 0) {
        // Thin lens: every ray through the lens point meets the pinhole ray on the plane z = focus_distance.
        const Vec2 d = square_to_uniform_disk_concentric(aperture) * settings_.aperture_radius;
        lens = {d.x, d.y, 0.0};
        local = local * settings_.focus_distance - lens;
    }
    Ray ray;
    ray.direction = normalize(settings_.to_world.vector(local));  // to_world may scale: normalised after it
    // Clip planes are distances along the optical axis: a ray at cos = local.z / |local| meets them 1 / cos further
    // (local.z is 1 for a pinhole and focus_distance through a lens).
    ray.origin = settings_.aperture_radius > 0 ? settings_.to_world.point(lens) : origin_;
    const double inv_cos = local.length() * inv_local_z_;
    ray.t_min = settings_.near_clip * inv_cos;
    ray.t_max = settings_.far_clip * inv_cos;
    return ray;
}

}  // namespace surfscatter::render
