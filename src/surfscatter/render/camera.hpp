#pragma once
// Mitsuba's perspective and thinlens sensors (sensors/*.cpp): local +z looks forward, +y is up, +x points to the
// image's left. A positive aperture radius makes it a thin lens focused at focus_distance along the optical axis.
#include <optional>
#include <string>

#include "surfscatter/render/transform.hpp"

namespace surfscatter::render {

struct Ray {
    Vec3 origin;
    Vec3 direction;  // unit length
    double t_min = 0;
    double t_max = 1e30;
};

struct CameraSettings {
    Transform to_world;
    double fov_degrees = 39.3077;
    std::string fov_axis = "x";  // x, y, diagonal, smaller, larger
    double near_clip = 0.01;
    double far_clip = 10000;
    double aperture_radius = 0;    // 0: pinhole (perspective)
    double focus_distance = 10000; // thinlens: distance of the plane in focus (Mitsuba's default: far_clip)
    // Fractions of the film width / height; the optical axis meets the film at u = 0.5 - offset_x (v likewise).
    double principal_point_offset_x = 0;
    double principal_point_offset_y = 0;
};

class Camera {
public:
    Camera() = default;
    Camera(const CameraSettings& settings, int width, int height);
    // Ray through film position (x, y) in pixels, (0, 0) the top-left corner of the image; `aperture` (in [0, 1)^2)
    // picks the point on the lens of a thin-lens camera and is ignored by a pinhole.
    Ray generate_ray(double x, double y, Vec2 aperture = {0.5, 0.5}) const;
    bool has_aperture() const { return settings_.aperture_radius > 0; }
    // Film position (pixels) where world point `p` appears, or nothing if it is behind the camera.
    std::optional<Vec2> project(const Vec3& p) const;
    const CameraSettings& settings() const { return settings_; }

private:
    CameraSettings settings_;
    int width_ = 1, height_ = 1;
    double inv_width_ = 1, inv_height_ = 1;  // multiplications on every camera ray instead of divisions
    double tan_x_ = 1, tan_y_ = 1;
    double inv_local_z_ = 1;  // 1 / z of generate_ray's camera-space direction before normalisation
    Vec3 origin_;
    Transform to_local_;
};

}  // namespace surfscatter::render
