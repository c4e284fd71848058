#pragma once
// The film accumulates CIE 1931 XYZ per pixel (Y = 1 for a spectrally constant radiance of 1) and the coverage
// (alpha), both weighted by the reconstruction filter (filter.hpp: the pixel is sum(w L) / N). Developing it applies
// the white balance (Bradford, from a blackbody of the given temperature to D65, or none) and the exposure
// (2^stops); hdrfilm (films/hdrfilm.cpp) writes it as an OpenEXR in the scene's pixel_format and component_format,
// plus an 8-bit sRGB PNG.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <iterator>
#include <span>
#include <vector>

#include "surfscatter/io/image.hpp"
#include "surfscatter/render/scene.hpp"

namespace surfscatter::render {

// Per-pixel state kept in tile order: the kTileSize x kTileSize pixels of a tile are contiguous, tiles row by row, so
// that a thread rendering a tile walks a few consecutive KB (not kTileSize rows of the whole image), and, with tiles
// starting on cache lines, two threads never write the same line.
inline constexpr int kTileSize = 16;
class TileOrder {
public:
    TileOrder(int width, int height) : tiles_x_((width + kTileSize - 1) / kTileSize), tiles_y_((height + kTileSize - 1) / kTileSize) {}
    int tiles_x() const { return tiles_x_; }
    int tiles_y() const { return tiles_y_; }
    std::size_t size() const { return std::size_t(tiles_x_) * std::size_t(tiles_y_) * kTileSize * kTileSize; }
    std::size_t index(int x, int y) const {
        const std::size_t tile = std::size_t(y / kTileSize) * std::size_t(tiles_x_) + std::size_t(x / kTileSize);
        return tile * kTileSize * kTileSize + std::size_t(y % kTileSize) * kTileSize + std::size_t(x % kTileSize);
    }

private:
    int tiles_x_, tiles_y_;
};

// A vector of T with its elements in tile order and its data on a cache line (tiles of 256 elements of 16 or 40 bytes
// fill whole lines).
template <typename T>
class TiledPixels {
public:
    TiledPixels(int width, int height, const T& value = T()) : order_(width, height), cells_(order_.size() / kCell) {
        for (Cell& c : cells_) std::fill(std::begin(c.values), std::end(c.values), value);
    }
    T& operator()(int x, int y) { return at(order_.index(x, y)); }
    const T& operator()(int x, int y) const { return at(order_.index(x, y)); }
    const TileOrder& order() const { return order_; }

private:
    static constexpr std::size_t kCell = kTileSize * kTileSize;
    struct alignas(64) Cell { T values[kCell]; };
    T& at(std::size_t i) { return cells_[i / kCell].values[i % kCell]; }
    const T& at(std::size_t i) const { return cells_[i / kCell].values[i % kCell]; }
    TileOrder order_;
    std::vector<Cell> cells_;
};

class Film {
public:
    Film(int width, int height);  // throws Error beyond kMaxFilmSide or the memory available
    int width() const { return width_; }
    int height() const { return height_; }
    // One sample: its filter weight w, the XYZ it carries and whether it covers the pixel. Each pixel is owned by
    // one thread at a time (tiles), so no locking.
    void add(int x, int y, const Vec3& xyz, double weight, bool covered) {
        Pixel& p = pixels_(x, y);
        p.sum += xyz * weight;
        p.alpha += covered ? weight : 0.0;
        ++p.count;
    }
    // The accumulated state as one array, five numbers per pixel (the sums of w X, w Y, w Z, w covered, and the
    // sample count N), for summing films over processes (distributed/render.hpp). Films that hold disjoint pixels
    // sum exactly to the film of their union (x + 0 = x), in any order.
    static constexpr std::size_t kStateValues = 5;  // per pixel
    std::vector<double> state() const;
    void set_state(std::span<const double> state);  // a state() of a film of the same size
    void accumulate(const Film& other);               // pixel-wise sum of the states (same size)

    Vec3 xyz(int x, int y) const;    // sum(w XYZ) / N (0 if no sample)
    double alpha(int x, int y) const;
    std::uint32_t samples(int x, int y) const;  // samples taken at the pixel (an interrupted render has fewer)
    // Linear sRGB image after white balance and exposure (3 channels).
    io::Image develop(const FilmSettings& settings) const;
    // The image in the film's pixel_format (rgb, rgba, luminance, luminance_alpha, xyz, xyza), after white balance
    // and exposure, with the EXR channel names of each channel.
    io::Image develop_pixel_format(const FilmSettings& settings, std::vector<std::string>& channels) const;

private:
    struct Pixel {
        Vec3 sum;             // of w XYZ
        double alpha = 0;     // sum of w over covering samples
        std::uint32_t count = 0;
    };
    int width_, height_;
    TiledPixels<Pixel> pixels_;
};

// Writes `exr_path` in the film's pixel_format and component_format and `png_path` (default: the same path with
// extension .png): the linear sRGB image sRGB-encoded to 8 bits, with alpha for the *_alpha / rgba formats.
void write_film(const Film& film, const FilmSettings& settings, const std::filesystem::path& exr_path,
                std::filesystem::path png_path = {});

}  // namespace surfscatter::render
