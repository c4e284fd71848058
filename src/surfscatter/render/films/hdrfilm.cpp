// Mitsuba's `hdrfilm`: a high-dynamic-range image written as OpenEXR (film.cpp develops and writes it).
//
// Supported: `width`, `height` (default 768 x 576), `file_format` (openexr, the default; exr), `pixel_format`
// (luminance, luminance_alpha, rgb (default), rgba, xyz, xyza: linear sRGB / CIE XYZ / its Y, with alpha = the
// filter-weighted fraction of samples that met a surface or a visible environment), `component_format` (float16,
// Mitsuba's default, or float32), `crop_offset_x/y`, `crop_width/height` (only the window is rendered and written),
// `sample_border` (default false: samples stay inside the crop window, so border pixels see a truncated filter),
// a nested `rfilter` (default gaussian, stddev 0.5). surfscatter extensions: `exposure` (stops) and
// `white_balance` (`d65` = none, a blackbody temperature such as `2700`, or a CIE illuminant name), both also on the
// command line; an 8-bit sRGB PNG is written beside the EXR.
// Not supported (an error): file_format rgbe and pfm, component_format uint32, `banner`.
// Differences: colours are integrated spectrally against the CIE 1931 observer, then converted to linear sRGB (as
// Mitsuba's spectral variants do).
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

FilmSettings plugins::hdrfilm(Properties& props, FilterPtr filter) {
    FilmSettings f;
    f.filter = std::move(filter);
    f.width = props.get_int("width", f.width);
    f.height = props.get_int("height", f.height);
    const std::string file_format = props.get_string("file_format", "openexr");
    if (file_format != "openexr" && file_format != "exr")
        props.fail_param("file_format", "file_format must be openexr, got '{}' (rgbe and pfm are not supported)", file_format);
    f.pixel_format = props.get_string("pixel_format", f.pixel_format);
    if (f.pixel_format != "rgb" && f.pixel_format != "rgba" && f.pixel_format != "luminance" &&
        f.pixel_format != "luminance_alpha" && f.pixel_format != "xyz" && f.pixel_format != "xyza")
        props.fail_param("pixel_format", "pixel_format must be luminance, luminance_alpha, rgb, rgba, xyz or xyza, got '{}'",
                      f.pixel_format);
    f.component_format = props.get_string("component_format", f.component_format);
    if (f.component_format != "float16" && f.component_format != "float32")
        props.fail_param("component_format", "component_format must be float16 or float32, got '{}' (uint32 is not supported)",
                      f.component_format);
    f.crop_offset_x = props.get_int("crop_offset_x", 0);
    f.crop_offset_y = props.get_int("crop_offset_y", 0);
    f.crop_width = props.get_int("crop_width", 0);
    f.crop_height = props.get_int("crop_height", 0);
    f.sample_border = props.get_bool("sample_border", false);
    f.exposure = props.get_float("exposure", f.exposure);
    f.white_balance = props.get_string("white_balance", f.white_balance);
    try {
        f.check();  // sizes, crop window, memory, exposure, white balance
    } catch (const Error& e) {
        props.fail("{}", e.what());
    }
    return f;
}

}  // namespace surfscatter::render
