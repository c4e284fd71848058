#include "surfscatter/render/film.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::render {

namespace {

// Bytes a rendered pixel holds at once: the film's XYZ sum (24), alpha (8) and sample count (4), the pixel's random
// stream (16), the developed images (up to 2 x 16) and the 8-bit PNG copy (4), rounded up for the libraries' own
// buffers. Counted over whole tiles (TileOrder), as the film and the streams store them.
constexpr double kBytesPerPixel = 128;

void check_size(int width, int height, const char* what) {
    if (width < 1 || height < 1 || width > kMaxFilmSide || height > kMaxFilmSide)
        fail("{} must be between 1x1 and {}x{} pixels, got {}x{}", what, kMaxFilmSide, kMaxFilmSide, width, height);
    require_memory(kBytesPerPixel * double(TileOrder(width, height).size()), fmt::format("a {}x{} {}", width, height, what));
}

// The largest value an EXR of the film's component format holds; beyond it the file would hold Inf.
double largest_component(const FilmSettings& settings) {
    return settings.component_format == "float16" ? 65504.0 : double(std::numeric_limits<float>::max());
}

void require_representable(double value, int x, int y, double largest, const FilmSettings& settings) {
    if (!(std::abs(value) <= largest))
        fail("pixel ({}, {}) is {}, beyond the {:g} a {} image holds: lower the exposure ({} stops) or the emitters{}",
             x, y, value, largest, largest == 65504.0 ? "float16" : "float32", settings.exposure,
             largest == 65504.0 ? ", or write component_format float32" : "");
}

int checked_width(int width, int height) {  // before the pixels are allocated
    check_size(width, height, "film");
    return width;
}

spectrum::Mat3 adaptation(const FilmSettings& settings);

}  // namespace

Film::Film(int width, int height) : width_(checked_width(width, height)), height_(height), pixels_(width, height) {}

std::uint32_t Film::samples(int x, int y) const { return pixels_(x, y).count; }

void FilmSettings::check() const {
    check_size(width, height, "film");
    const auto right = std::int64_t{crop_offset_x} + output_width(), bottom = std::int64_t{crop_offset_y} + output_height();
    if (crop_width < 0 || crop_height < 0 || crop_offset_x < 0 || crop_offset_y < 0 || right > width || bottom > height)
        fail("crop window {}x{} at ({}, {}) does not fit the {}x{} film", output_width(), output_height(), crop_offset_x,
             crop_offset_y, width, height);
    if (!(std::abs(exposure) <= kMaxExposureStops))
        fail("exposure must be between -{} and {} stops, got {}", kMaxExposureStops, kMaxExposureStops, exposure);
    if (component_format != "float16" && component_format != "float32")
        fail("component_format must be float16 or float32, got '{}'", component_format);
    adaptation(*this);  // validates the white balance
}

// The state is in row order (not the tile order of the storage), so that it means the same for any film layout.
std::vector<double> Film::state() const {
    std::vector<double> out(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * kStateValues);
    double* p = out.data();
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x, p += kStateValues) {
            const Pixel& pixel = pixels_(x, y);
            p[0] = pixel.sum.x;
            p[1] = pixel.sum.y;
            p[2] = pixel.sum.z;
            p[3] = pixel.alpha;
            p[4] = pixel.count;
        }
    return out;
}

void Film::set_state(std::span<const double> state) {
    if (state.size() != static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * kStateValues)
        fail("film state of {} values does not fit a {}x{} film", state.size(), width_, height_);
    const double* p = state.data();
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x, p += kStateValues)
            pixels_(x, y) = Pixel{Vec3(p[0], p[1], p[2]), p[3], static_cast<std::uint32_t>(p[4])};
}

void Film::accumulate(const Film& other) {
    if (other.width_ != width_ || other.height_ != height_)
        fail("cannot add a {}x{} film to a {}x{} one", other.width_, other.height_, width_, height_);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            Pixel& pixel = pixels_(x, y);
            const Pixel& added = other.pixels_(x, y);
            pixel.sum += added.sum;
            pixel.alpha += added.alpha;
            pixel.count += added.count;
        }
}

Vec3 Film::xyz(int x, int y) const {
    const Pixel& p = pixels_(x, y);
    return p.count ? p.sum / p.count : Vec3();
}

double Film::alpha(int x, int y) const {
    const Pixel& p = pixels_(x, y);
    return p.count ? p.alpha / p.count : 0.0;
}

namespace {

// XYZ -> XYZ with the film's white balance and exposure: the chosen white ("2700" for a blackbody in K, or a CIE
// illuminant name) is mapped to D65 by Bradford adaptation; "d65" leaves XYZ as it is.
spectrum::Mat3 adaptation(const FilmSettings& settings) {
    const double gain = std::exp2(settings.exposure);
    spectrum::Mat3 adapt;
    if (settings.white_balance != "d65" && settings.white_balance != "D65" && settings.white_balance != "none") {
        try {
            adapt = spectrum::white_balance_to_d65(spectrum::white_point_xyz(settings.white_balance));
        } catch (const Error& e) {
            fail("white_balance '{}': {}", settings.white_balance, e.what());
        }
    }
    return spectrum::Mat3::diagonal({gain, gain, gain}) * adapt;
}

}  // namespace

io::Image Film::develop(const FilmSettings& settings) const {
    const spectrum::Mat3 adapt = adaptation(settings);
    io::Image image(width_, height_, 3);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const Vec3 rgb = spectrum::xyz_to_linear_srgb(adapt * xyz(x, y));
            for (int c = 0; c < 3; ++c) {
                // Only an absurdly bright emitter times a large exposure gets here; never write Inf or NaN.
                require_representable(rgb[c], x, y, std::numeric_limits<float>::max(), settings);
                image.at(x, y, c) = static_cast<float>(rgb[c]);
            }
        }
    return image;
}

io::Image Film::develop_pixel_format(const FilmSettings& settings, std::vector<std::string>& channels) const {
    const std::string& format = settings.pixel_format;
    const bool with_alpha = format == "rgba" || format == "xyza" || format == "luminance_alpha";
    if (format == "rgb" || format == "rgba") channels = {"R", "G", "B"};
    else if (format == "xyz" || format == "xyza") channels = {"X", "Y", "Z"};
    else if (format == "luminance" || format == "luminance_alpha") channels = {"Y"};
    else fail("pixel_format must be luminance, luminance_alpha, rgb, rgba, xyz or xyza, got '{}'", format);
    if (with_alpha) channels.push_back("A");
    const spectrum::Mat3 adapt = adaptation(settings);
    io::Image image(width_, height_, static_cast<int>(channels.size()));
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const Vec3 v = adapt * xyz(x, y);
            const Vec3 out = channels[0] == "R" ? spectrum::xyz_to_linear_srgb(v) : v;
            for (int c = 0; c < 3; ++c) require_representable(out[c], x, y, largest_component(settings), settings);
            if (channels[0] == "Y") image.at(x, y, 0) = static_cast<float>(out.y);
            else
                for (int c = 0; c < 3; ++c) image.at(x, y, c) = static_cast<float>(out[c]);
            if (with_alpha) image.at(x, y, image.channels - 1) = static_cast<float>(alpha(x, y));
        }
    return image;
}

void write_film(const Film& film, const FilmSettings& settings, const std::filesystem::path& exr_path,
                std::filesystem::path png_path) {
    std::vector<std::string> channels;
    const io::Image exr = film.develop_pixel_format(settings, channels);
    io::ExrPixelType type = io::ExrPixelType::half;
    if (settings.component_format == "float32") type = io::ExrPixelType::float32;
    else if (settings.component_format != "float16")
        fail("component_format must be float16 or float32, got '{}'", settings.component_format);
    io::write_exr(exr_path, exr, channels, type);

    const bool with_alpha = channels.back() == "A";
    const io::Image rgb = film.develop(settings);
    io::Image png(rgb.width, rgb.height, with_alpha ? 4 : 3);
    for (int y = 0; y < rgb.height; ++y)
        for (int x = 0; x < rgb.width; ++x) {
            for (int c = 0; c < 3; ++c)
                png.at(x, y, c) = static_cast<float>(spectrum::srgb_encode(std::clamp(static_cast<double>(rgb.at(x, y, c)), 0.0, 1.0)));
            if (with_alpha) png.at(x, y, 3) = static_cast<float>(std::clamp(film.alpha(x, y), 0.0, 1.0));
        }
    if (png_path.empty()) png_path = std::filesystem::path(exr_path).replace_extension(".png");
    io::write_png(png_path, png);
}

}  // namespace surfscatter::render
