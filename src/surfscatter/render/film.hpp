#pragma once
// The film accumulates CIE 1931 XYZ per pixel (Y = 1 for a spectrally constant radiance of 1). Developing it
// applies the white balance (Bradford, from a blackbody of the given temperature to D65, or none), the exposure
// (2^stops) and the XYZ -> linear sRGB matrix; outputs are an OpenEXR of linear sRGB and an 8-bit sRGB PNG.
#include <filesystem>
#include <vector>

#include "surfscatter/io/image.hpp"
#include "surfscatter/render/scene.hpp"

namespace surfscatter::render {

class Film {
public:
    Film(int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }
    // Each pixel is owned by one thread at a time (tiles), so no locking.
    void add(int x, int y, const Vec3& xyz) {
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
        sum_[i] += xyz;
        ++count_[i];
    }
    Vec3 xyz(int x, int y) const;  // mean of the samples (0 if none)
    // Linear sRGB image after white balance and exposure.
    io::Image develop(const FilmSettings& settings) const;

private:
    int width_, height_;
    std::vector<Vec3> sum_;
    std::vector<std::uint32_t> count_;
};

// Writes `exr_path` (linear sRGB, float) and the same path with extension .png (sRGB-encoded, 8 bit).
void write_film(const Film& film, const FilmSettings& settings, const std::filesystem::path& exr_path);

}  // namespace surfscatter::render
