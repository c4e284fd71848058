#pragma once
// Colour spaces for output: CIE XYZ <-> linear sRGB (ITU-R BT.709 primaries, D65 white, IEC 61966-2-1), the sRGB
// transfer function, chromaticity, and white balance by Bradford chromatic adaptation from a chosen white (a CIE
// illuminant or a black body) to the sRGB white D65. XYZ is relative: Y = 1 for the white.
#include <array>
#include <string>

#include "surfscatter/math/vec.hpp"

namespace surfscatter::spectrum {

// Row-major 3x3 matrix acting on column vectors.
struct Mat3 {
    std::array<double, 9> m{1, 0, 0, 0, 1, 0, 0, 0, 1};
    double operator()(int row, int col) const { return m[static_cast<std::size_t>(3 * row + col)]; }
    Vec3 operator*(const Vec3& v) const {
        return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
                m[6] * v.x + m[7] * v.y + m[8] * v.z};
    }
    Mat3 operator*(const Mat3& o) const;
    Mat3 inverse() const;  // throws Error if singular
    static Mat3 diagonal(const Vec3& d) { return Mat3{{d.x, 0, 0, 0, d.y, 0, 0, 0, d.z}}; }
};

// sRGB / Rec. 709 white (D65 as defined by the sRGB standard: x = 0.3127, y = 0.3290).
inline constexpr Vec2 kD65Chromaticity{0.3127, 0.3290};

Vec3 xyz_to_linear_srgb(const Vec3& xyz);
Vec3 linear_srgb_to_xyz(const Vec3& rgb);

// IEC 61966-2-1 transfer function. encode: linear -> code value; values <= 0 map to 0 and values >= 1 to 1 (an
// 8-bit output cannot hold more; tone mapping, if any, happens before). decode: inverse on [0, 1].
double srgb_encode(double linear);
double srgb_decode(double encoded);
Vec3 srgb_encode(const Vec3& linear);

// (x, y) = (X, Y) / (X + Y + Z); throws Error if X + Y + Z <= 0.
Vec2 chromaticity(const Vec3& xyz);
// XYZ with the given chromaticity and luminance Y.
Vec3 xyz_from_chromaticity(const Vec2& xy, double luminance = 1.0);

// White points, normalised to Y = 1.
Vec3 srgb_white_xyz();
Vec3 blackbody_white_xyz(double temperature_K);
// "D65" is the sRGB white itself; other CIE illuminant names ("A", "D50", "F2", ...) are integrated from colord's
// tables; a number, optionally followed by K ("2700", "2700K"), is a black body of that temperature.
Vec3 white_point_xyz(const std::string& white);

// Bradford chromatic adaptation (Lam 1985, as in CIE 159 / ICC) mapping colours seen under source_white to
// destination_white: M^-1 diag(M d / M s) M.
Mat3 bradford_adaptation(const Vec3& source_white_xyz, const Vec3& destination_white_xyz);
// XYZ -> XYZ that makes source white appear as D65 white (then xyz_to_linear_srgb gives R = G = B).
Mat3 white_balance_to_d65(const Vec3& source_white_xyz);

}  // namespace surfscatter::spectrum
