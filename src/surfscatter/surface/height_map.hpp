#pragma once
// A measured or synthesized height map h(x, y) on a regular grid, lengths and heights in micrometres.
//
// Storage is row-major: height(ix, iy) = heights()[iy * nx() + ix], x along a row, y down the rows (the order of
// Gwyddion Simple Field files). Every height is finite and both spacings are positive; the constructor checks this
// so that no later computation sees NaN or a degenerate grid.
#include <cstddef>
#include <string>
#include <vector>

namespace surfscatter::surface {

// Smallest grid side accepted anywhere (a tilt fit and a PSD need a few samples per axis).
inline constexpr std::size_t kMinHeightMapSize = 8;
// Accepted pixel spacings (um): 1 pm to 1 m. Beyond that, products like dx dy dzeta^2 leave the double range.
inline constexpr double kMinSpacingUm = 1e-6;
inline constexpr double kMaxSpacingUm = 1e6;

// Throws Error "<what> must be between 1e-06 and 1000000 um, got <spacing>" unless the spacing is accepted.
void require_valid_spacing(double spacing_um, const std::string& what);

class HeightMap {
public:
    // `origin` names where the data came from ("h.gsf", "--size") for error messages.
    HeightMap(std::size_t nx, std::size_t ny, double spacing_x_um, double spacing_y_um, std::vector<double> heights_um,
              const std::string& origin = "height map");

    std::size_t nx() const { return nx_; }
    std::size_t ny() const { return ny_; }
    std::size_t size() const { return heights_.size(); }
    double spacing_x() const { return spacing_x_; }  // um
    double spacing_y() const { return spacing_y_; }  // um
    double width() const { return spacing_x_ * static_cast<double>(nx_); }   // um (XReal)
    double height() const { return spacing_y_ * static_cast<double>(ny_); }  // um (YReal)

    double operator()(std::size_t ix, std::size_t iy) const { return heights_[iy * nx_ + ix]; }
    const std::vector<double>& heights() const { return heights_; }

    // Optional metadata carried through .gsf files (XOffset, YOffset, Title).
    double offset_x = 0.0;  // um
    double offset_y = 0.0;  // um
    std::string title;

private:
    std::size_t nx_;
    std::size_t ny_;
    double spacing_x_;
    double spacing_y_;
    std::vector<double> heights_;
};

// Least-squares plane h ~ mean + slope_x (x - x_c) + slope_y (y - y_c) about the grid centre (x_c, y_c).
struct Plane {
    double mean = 0.0;     // um
    double slope_x = 0.0;  // dh/dx, dimensionless
    double slope_y = 0.0;  // dh/dy
};

// The least-squares plane through the map. On a regular grid the centred coordinates are orthogonal to each other
// and to the constant, so the normal equations decouple and the fit is exact in closed form.
Plane fit_plane(const HeightMap& map);

// The map minus its least-squares plane (zero mean, zero mean slope): "tilt removal".
HeightMap remove_tilt(const HeightMap& map);

// Root-mean-square height of the map about its least-squares plane (um). A finite patch misses wavelengths longer
// than itself, so this underestimates the sigma_h of the process the patch was drawn from (see kc_fit.hpp).
double rms_height(const HeightMap& map);

}  // namespace surfscatter::surface
