#include "surfscatter/render/film.hpp"

#include <algorithm>
#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::render {

Film::Film(int width, int height)
    : width_(width), height_(height), sum_(static_cast<std::size_t>(width) * height), count_(sum_.size(), 0) {
    if (width <= 0 || height <= 0) fail("film size must be positive, got {}x{}", width, height);
}

Vec3 Film::xyz(int x, int y) const {
    const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
    return count_[i] ? sum_[i] / count_[i] : Vec3();
}

namespace {

// XYZ -> linear sRGB with the film's white balance: the chosen white ("2700" for a blackbody in K, or a CIE
// illuminant name) is mapped to D65 by Bradford adaptation before the sRGB matrix; "d65" leaves XYZ as it is.
spectrum::Mat3 output_matrix(const FilmSettings& settings) {
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
    const spectrum::Mat3 adapt = output_matrix(settings);
    io::Image image(width_, height_, 3);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const Vec3 rgb = spectrum::xyz_to_linear_srgb(adapt * xyz(x, y));
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = static_cast<float>(rgb[c]);
        }
    return image;
}

void write_film(const Film& film, const FilmSettings& settings, const std::filesystem::path& exr_path) {
    io::Image image = film.develop(settings);
    io::write_exr(exr_path, image);
    for (float& v : image.pixels) v = static_cast<float>(spectrum::srgb_encode(std::clamp(static_cast<double>(v), 0.0, 1.0)));
    std::filesystem::path png = exr_path;
    png.replace_extension(".png");
    io::write_png(png, image);
}

}  // namespace surfscatter::render
