// Mitsuba's `perspective` sensor: a pinhole camera.
//
// Supported: `to_world` (lookat, ...), `fov` with `fov_axis` (x (default), y, diagonal, smaller, larger), or
// `focal_length` (35 mm film equivalent, default 50mm, as a diagonal field of view; exclusive with fov, as in
// Mitsuba), `near_clip` (default 0.01), `far_clip` (default 10000; distances along the optical axis),
// `focus_distance` (accepted; no effect for a pinhole, as in Mitsuba), `principal_point_offset_x/y` (fractions of
// the film size: film position (u, v) is traced as (u + offset_x, v + offset_y) of the centred frustum, the same
// convention as photo/pose.hpp), and the nested film and sampler.
// Local frame: +z forward, +y up, +x toward the image's left (Mitsuba).
// Not supported (an error): `srf`, `shutter_open`, `shutter_close` (no motion blur).
// Differences: none.
#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

void plugins::read_field_of_view(Properties& props, CameraSettings& camera, int film_width, int film_height) {
    if (props.has("fov") && props.has("focal_length")) props.fail("give either fov or focal_length, not both");
    if (props.has("fov")) {
        camera.fov_degrees = props.get_float_required("fov");
        camera.fov_axis = props.get_string("fov_axis", "x");
    } else {
        if (props.has("fov_axis")) props.fail_param("fov_axis", "fov_axis applies to fov, which is not given");
        std::string focal = props.get_string("focal_length", "50mm");
        if (focal.size() > 2 && focal.substr(focal.size() - 2) == "mm") focal.resize(focal.size() - 2);
        double millimetres = 0;
        try {
            std::size_t used = 0;
            millimetres = std::stod(focal, &used);
            if (used != focal.size()) millimetres = 0;
        } catch (const std::exception&) {
            millimetres = 0;
        }
        if (!(millimetres > 0)) props.fail_param("focal_length", "focal_length must be '<value>mm' with a positive value");
        camera.fov_degrees = 2 * std::atan(std::hypot(36.0, 24.0) / (2 * millimetres)) / kDegree;
        camera.fov_axis = "diagonal";
    }
    try {
        Camera check(camera, film_width, film_height);
    } catch (const Error& e) {
        props.fail("{}", e.what());
    }
}

CameraSettings plugins::perspective(Properties& props, int film_width, int film_height) {
    for (const char* name : {"srf", "shutter_open", "shutter_close"})
        if (props.has(name)) props.fail_param(name, "perspective parameter '{}' is not supported", name);
    CameraSettings c;
    c.to_world = props.get_transform("to_world");
    c.near_clip = props.get_float("near_clip", c.near_clip);
    c.far_clip = props.get_float("far_clip", c.far_clip);
    c.focus_distance = props.get_float("focus_distance", c.far_clip);  // no effect for a pinhole
    c.principal_point_offset_x = props.get_float("principal_point_offset_x", 0.0);
    c.principal_point_offset_y = props.get_float("principal_point_offset_y", 0.0);
    read_field_of_view(props, c, film_width, film_height);
    return c;
}

}  // namespace surfscatter::render
