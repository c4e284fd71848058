#pragma once
// A measured or synthesized height map h(x, y) on a regular grid, lengths and heights in micrometres, with an
// optional mask of invalid points (instrument drop-outs, NaN in the file, a mask stored with the data).
//
// Storage is row-major: height(ix, iy) = heights()[iy * nx() + ix], x along a row, y down the rows (the order of
// Gwyddion Simple Field files). Every height is finite and at most kMaxHeightUm in size, and both spacings are
// positive; the constructor checks this so that no later computation sees NaN, overflow or a degenerate grid.
// Invalid points hold height 0 and are skipped by every statistic (form fit, rms, slopes, PSD, ACV);
// valid_fraction() says how much of the map they left.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace surfscatter::heightmap {

// Smallest grid side accepted anywhere (a tilt fit and a PSD need a few samples per axis).
inline constexpr std::size_t kMinHeightMapSize = 8;
// Accepted pixel spacings (um): 1 pm to 1 m. Beyond that, products like dx dy dzeta^2 leave the double range.
inline constexpr double kMinSpacingUm = 1e-6;
inline constexpr double kMaxSpacingUm = 1e6;

// Largest |height| accepted (um, 1 km): squares and sums of squares over any map stay far inside the double range.
inline constexpr double kMaxHeightUm = 1e9;

// Throws Error "<what> must be between 1e-06 and 1000000 um, got <spacing>" unless the spacing is accepted.
void require_valid_spacing(double spacing_um, const std::string& what);

// Where a map came from, for reports (`surfscatter surface info`): filled by read_height_map().
struct HeightMapSource {
    std::string format;                 // e.g. "Zygo MetroPro (.dat)", "Gwyddion Simple Field (.gsf)"
    std::string reader;                 // "gwyddion:metropro", "native:x3p", ...
    std::string channel;                // channel title when the file holds several (empty otherwise)
    std::vector<std::string> warnings;  // what the reader had to say about the file (one line each)
    double height_unit_um = 0.0;        // um per height unit the file states its heights in (0: states none)
    // Whether the map wraps around seamlessly, as judged on it as read by heightmap::prepare() (prepare.hpp), for the
    // statistics of the prepared map, whose form is removed since; unset: judge the map as it is.
    std::optional<bool> periodic;
};

class HeightMap {
public:
    // `origin` names where the data came from ("h.gsf", "--size") for error messages. All heights must be finite.
    HeightMap(std::size_t nx, std::size_t ny, double spacing_x_um, double spacing_y_um, std::vector<double> heights_um,
              const std::string& origin = "height map");
    // With a validity mask (1 = valid, 0 = invalid, one byte per point; empty = all valid). Heights at invalid
    // points may be anything, NaN included (they are set to 0); valid heights must be finite, and at least one
    // point must be valid.
    HeightMap(std::size_t nx, std::size_t ny, double spacing_x_um, double spacing_y_um, std::vector<double> heights_um,
              std::vector<std::uint8_t> validity, const std::string& origin);

    std::size_t nx() const { return nx_; }
    std::size_t ny() const { return ny_; }
    std::size_t size() const { return heights_.size(); }
    double spacing_x() const { return spacing_x_; }  // um
    double spacing_y() const { return spacing_y_; }  // um
    double width() const { return spacing_x_ * static_cast<double>(nx_); }   // um (XReal)
    double height() const { return spacing_y_ * static_cast<double>(ny_); }  // um (YReal)

    double operator()(std::size_t ix, std::size_t iy) const { return heights_[iy * nx_ + ix]; }
    const std::vector<double>& heights() const { return heights_; }

    // What the constructor was told the data came from (a file name, "--size"): for error messages.
    const std::string& origin() const { return origin_; }

    bool has_invalid() const { return !valid_.empty(); }
    bool valid(std::size_t ix, std::size_t iy) const { return valid_.empty() || valid_[iy * nx_ + ix] != 0; }
    bool valid(std::size_t index) const { return valid_.empty() || valid_[index] != 0; }
    // One byte per point (1 = valid); empty when every point is valid.
    const std::vector<std::uint8_t>& validity() const { return valid_; }
    std::size_t valid_count() const { return valid_count_; }
    double valid_fraction() const { return static_cast<double>(valid_count_) / static_cast<double>(size()); }

    // The same grid, mask and metadata with new heights (invalid points are set to 0 again).
    HeightMap with_heights(std::vector<double> heights_um) const;

    // Optional metadata carried through .gsf files (XOffset, YOffset, Title).
    double offset_x = 0.0;  // um
    double offset_y = 0.0;  // um
    std::string title;
    HeightMapSource source;

private:
    std::size_t nx_;
    std::size_t ny_;
    double spacing_x_;
    double spacing_y_;
    std::vector<double> heights_;
    std::vector<std::uint8_t> valid_;
    std::size_t valid_count_ = 0;
    std::string origin_;
};

// One line for reports: "<file>: <format>, 640 x 480 points of 0.1967 x 0.1967 um, 99.96 % valid".
std::string describe(const HeightMap& map);

// Throws Error naming `what` unless at least `minimum` of the map's points are valid: the PSD and ACV estimators
// stay unbiased for any mask, but their scatter grows as the valid part shrinks (see psd_estimate.hpp).
void require_valid_fraction(const HeightMap& map, double minimum, const std::string& what);

// Smallest valid fraction a PSD fit (KC fit, tabulated PSD) accepts.
inline constexpr double kMinFitValidFraction = 0.5;

}  // namespace surfscatter::heightmap
