// Mitsuba's `thinlens` sensor: a perspective camera with a thin lens, for depth of field.
//
// Supported: `aperture_radius` (required, scene units; the lens is a disk sampled by the concentric mapping),
// `focus_distance` (default far_clip: the plane z = focus_distance of the camera is in focus), `to_world` (without
// scale, as Mitsuba requires), `fov` / `fov_axis` or `focal_length`, `near_clip`, `far_clip` (as perspective.cpp).
// A ray through film point x and lens point l passes through the point where the pinhole ray of x meets the focal
// plane, so points on that plane image sharply (tests/render/test_sensors.cpp).
// Not supported (an error): `srf`, `shutter_open`, `shutter_close`, `principal_point_offset_x/y` (Mitsuba's
// thinlens has no principal point offset either).
// Differences: none.
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"
#include "surfscatter/render/shapes/analytic.hpp"

namespace surfscatter::render {

CameraSettings plugins::thinlens(Properties& props, int film_width, int film_height) {
    for (const char* name : {"srf", "shutter_open", "shutter_close"})
        if (props.has(name)) props.fail_param(name, "thinlens parameter '{}' is not supported", name);
    CameraSettings c;
    c.to_world = props.get_transform("to_world");
    const auto scale = similarity_scale(c.to_world);
    if (!scale || std::abs(*scale - 1) > 1e-9)
        props.fail_param("to_world", "thinlens to_world must not scale (Mitsuba forbids it too)");
    c.near_clip = props.get_float("near_clip", c.near_clip);
    c.far_clip = props.get_float("far_clip", c.far_clip);
    c.focus_distance = props.get_float("focus_distance", c.far_clip);
    c.aperture_radius = props.get_float_required("aperture_radius");
    if (!(c.aperture_radius > 0)) props.fail_param("aperture_radius", "aperture_radius must be positive, got {}", c.aperture_radius);
    if (!(c.focus_distance > 0)) props.fail_param("focus_distance", "focus_distance must be positive, got {}", c.focus_distance);
    read_field_of_view(props, c, film_width, film_height);
    return c;
}

}  // namespace surfscatter::render
