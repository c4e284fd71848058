#include "surfscatter/spectrum/color.hpp"

#include <charconv>
#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/spectrum/blackbody.hpp"
#include "surfscatter/spectrum/cie.hpp"

namespace surfscatter::spectrum {

namespace {

// IEC 61966-2-1 matrices (4 decimals as in the standard; the inverse pair is consistent to 1e-4).
constexpr Mat3 kXyzToSrgb{{3.2406, -1.5372, -0.4986, -0.9689, 1.8758, 0.0415, 0.0557, -0.2040, 1.0570}};
constexpr Mat3 kSrgbToXyz{{0.4124, 0.3576, 0.1805, 0.2126, 0.7152, 0.0722, 0.0193, 0.1192, 0.9505}};
constexpr Mat3 kBradford{{0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389, -0.0685, 1.0296}};

}  // namespace

Mat3 Mat3::operator*(const Mat3& o) const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double s = 0;
            for (int k = 0; k < 3; ++k) s += (*this)(i, k) * o(k, j);
            r.m[static_cast<std::size_t>(3 * i + j)] = s;
        }
    return r;
}

Mat3 Mat3::inverse() const {
    const auto& a = m;
    const double c00 = a[4] * a[8] - a[5] * a[7], c01 = a[5] * a[6] - a[3] * a[8], c02 = a[3] * a[7] - a[4] * a[6];
    const double det = a[0] * c00 + a[1] * c01 + a[2] * c02;
    if (!(std::abs(det) > 1e-300)) fail("cannot invert a singular 3x3 matrix (determinant {})", det);
    const double s = 1.0 / det;
    return Mat3{{c00 * s, (a[2] * a[7] - a[1] * a[8]) * s, (a[1] * a[5] - a[2] * a[4]) * s,
                 c01 * s, (a[0] * a[8] - a[2] * a[6]) * s, (a[2] * a[3] - a[0] * a[5]) * s,
                 c02 * s, (a[1] * a[6] - a[0] * a[7]) * s, (a[0] * a[4] - a[1] * a[3]) * s}};
}

Vec3 xyz_to_linear_srgb(const Vec3& xyz) { return kXyzToSrgb * xyz; }
Vec3 linear_srgb_to_xyz(const Vec3& rgb) { return kSrgbToXyz * rgb; }

double srgb_encode(double linear) {
    if (!(linear > 0.0)) return 0.0;  // also NaN
    if (linear >= 1.0) return 1.0;
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double encoded) {
    if (!(encoded > 0.0)) return 0.0;
    if (encoded >= 1.0) return 1.0;
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

Vec3 srgb_encode(const Vec3& linear) { return {srgb_encode(linear.x), srgb_encode(linear.y), srgb_encode(linear.z)}; }

Vec2 chromaticity(const Vec3& xyz) {
    const double sum = xyz.x + xyz.y + xyz.z;
    if (!(sum > 0.0)) fail("chromaticity of XYZ ({}, {}, {}) is undefined (X + Y + Z <= 0)", xyz.x, xyz.y, xyz.z);
    return {xyz.x / sum, xyz.y / sum};
}

Vec3 xyz_from_chromaticity(const Vec2& xy, double luminance) {
    if (!(xy.y > 0.0)) fail("chromaticity y must be positive, got {}", xy.y);
    return {xy.x / xy.y * luminance, luminance, (1.0 - xy.x - xy.y) / xy.y * luminance};
}

Vec3 srgb_white_xyz() { return xyz_from_chromaticity(kD65Chromaticity); }

Vec3 blackbody_white_xyz(double temperature_K) {
    require_blackbody_temperature(temperature_K, "blackbody temperature");
    const Vec3 xyz = spectrum_to_xyz([&](double l) { return blackbody_radiance(l, temperature_K); });
    if (!(xyz.y > 0.0)) fail("a black body at {} K emits no visible light", temperature_K);
    return xyz / xyz.y;
}

Vec3 white_point_xyz(const std::string& white) {
    std::string number = white;
    if (!number.empty() && (number.back() == 'K' || number.back() == 'k')) number.pop_back();
    double temperature = 0;
    const char* end = number.data() + number.size();
    const auto [ptr, ec] = std::from_chars(number.data(), end, temperature);
    if (!number.empty() && ec == std::errc() && ptr == end) {
        require_blackbody_temperature(temperature, "white balance temperature");
        return blackbody_white_xyz(temperature);
    }
    if (white == "D65" || white == "d65") return srgb_white_xyz();
    const Vec3 xyz = spectrum_to_xyz(cie_illuminant(white));
    return xyz / xyz.y;
}

Mat3 bradford_adaptation(const Vec3& source_white_xyz, const Vec3& destination_white_xyz) {
    const Vec3 s = kBradford * source_white_xyz;
    const Vec3 d = kBradford * destination_white_xyz;
    if (!(s.x > 0 && s.y > 0 && s.z > 0)) fail("source white ({}, {}, {}) is not a valid white", source_white_xyz.x,
                                                source_white_xyz.y, source_white_xyz.z);
    return kBradford.inverse() * Mat3::diagonal({d.x / s.x, d.y / s.y, d.z / s.z}) * kBradford;
}

Mat3 white_balance_to_d65(const Vec3& source_white_xyz) {
    return bradford_adaptation(source_white_xyz, srgb_white_xyz());
}

}  // namespace surfscatter::spectrum
