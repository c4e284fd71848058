#pragma once
// The film accumulates CIE 1931 XYZ per pixel (Y = 1 for a spectrally constant radiance of 1) and the coverage
// (alpha), both weighted by the reconstruction filter (filter.hpp: the pixel is sum(w L) / N). Developing it applies
// the white balance (Bradford, from a blackbody of the given temperature to D65, or none) and the exposure
// (2^stops); hdrfilm (films/hdrfilm.cpp) writes it as an OpenEXR in the scene's pixel_format and component_format,
// plus an 8-bit sRGB PNG.
#include <filesystem>
#include <vector>

#include "surfscatter/io/image.hpp"
#include "surfscatter/render/scene.hpp"

namespace surfscatter::render {

class Film {
public:
    Film(int width, int height);  // throws Error beyond kMaxFilmSide or the memory available
    int width() const { return width_; }
    int height() const { return height_; }
    // One sample: its filter weight w, the XYZ it carries and whether it covers the pixel. Each pixel is owned by
    // one thread at a time (tiles), so no locking.
    void add(int x, int y, const Vec3& xyz, double weight, bool covered) {
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
        sum_[i] += xyz * weight;
        alpha_[i] += covered ? weight : 0.0;
        ++count_[i];
    }
    Vec3 xyz(int x, int y) const;    // sum(w XYZ) / N (0 if no sample)
    double alpha(int x, int y) const;
    std::uint32_t samples(int x, int y) const;  // samples taken at the pixel (an interrupted render has fewer)
    // Linear sRGB image after white balance and exposure (3 channels).
    io::Image develop(const FilmSettings& settings) const;
    // The image in the film's pixel_format (rgb, rgba, luminance, luminance_alpha, xyz, xyza), after white balance
    // and exposure, with the EXR channel names of each channel.
    io::Image develop_pixel_format(const FilmSettings& settings, std::vector<std::string>& channels) const;

private:
    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
    }
    int width_, height_;
    std::vector<Vec3> sum_;
    std::vector<double> alpha_;
    std::vector<std::uint32_t> count_;
};

// Writes `exr_path` in the film's pixel_format and component_format and the same path with extension .png (the
// linear sRGB image sRGB-encoded to 8 bits, with alpha for the *_alpha / rgba formats).
void write_film(const Film& film, const FilmSettings& settings, const std::filesystem::path& exr_path);

}  // namespace surfscatter::render
