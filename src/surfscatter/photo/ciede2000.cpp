#include "surfscatter/photo/ciede2000.hpp"

#include <cmath>

namespace surfscatter::photo {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double deg(double radians) { return radians * 180.0 / kPi; }
constexpr double rad(double degrees) { return degrees * kPi / 180.0; }

// Hue angle in degrees in [0, 360); 0 for the achromatic case (a = b = 0) as the notes prescribe.
double hue_degrees(double b, double a) {
    if (a == 0.0 && b == 0.0) return 0.0;
    double h = deg(std::atan2(b, a));
    return h < 0.0 ? h + 360.0 : h;
}
}  // namespace

double ciede2000(const Lab& reference, const Lab& sample) {
    const double c1 = std::hypot(reference.a, reference.b);
    const double c2 = std::hypot(sample.a, sample.b);
    const double c_mean = 0.5 * (c1 + c2);
    const double c_mean7 = std::pow(c_mean, 7.0);
    const double g = 0.5 * (1.0 - std::sqrt(c_mean7 / (c_mean7 + std::pow(25.0, 7.0))));
    const double a1 = (1.0 + g) * reference.a;
    const double a2 = (1.0 + g) * sample.a;
    const double cp1 = std::hypot(a1, reference.b);
    const double cp2 = std::hypot(a2, sample.b);
    const double hp1 = hue_degrees(reference.b, a1);
    const double hp2 = hue_degrees(sample.b, a2);

    const double dL = sample.L - reference.L;
    const double dC = cp2 - cp1;
    double dh = 0.0;
    if (cp1 * cp2 != 0.0) {
        dh = hp2 - hp1;
        if (dh > 180.0) dh -= 360.0;
        else if (dh < -180.0) dh += 360.0;
    }
    const double dH = 2.0 * std::sqrt(cp1 * cp2) * std::sin(rad(0.5 * dh));

    const double L_mean = 0.5 * (reference.L + sample.L);
    const double cp_mean = 0.5 * (cp1 + cp2);
    double hp_mean = hp1 + hp2;
    if (cp1 * cp2 != 0.0) {
        if (std::abs(hp1 - hp2) <= 180.0) hp_mean *= 0.5;
        else if (hp1 + hp2 < 360.0) hp_mean = 0.5 * (hp1 + hp2 + 360.0);
        else hp_mean = 0.5 * (hp1 + hp2 - 360.0);
    }
    const double t = 1.0 - 0.17 * std::cos(rad(hp_mean - 30.0)) + 0.24 * std::cos(rad(2.0 * hp_mean)) +
                     0.32 * std::cos(rad(3.0 * hp_mean + 6.0)) - 0.20 * std::cos(rad(4.0 * hp_mean - 63.0));
    const double d_theta = 30.0 * std::exp(-std::pow((hp_mean - 275.0) / 25.0, 2.0));
    const double cp_mean7 = std::pow(cp_mean, 7.0);
    const double rc = 2.0 * std::sqrt(cp_mean7 / (cp_mean7 + std::pow(25.0, 7.0)));
    const double L50 = (L_mean - 50.0) * (L_mean - 50.0);
    const double sl = 1.0 + 0.015 * L50 / std::sqrt(20.0 + L50);
    const double sc = 1.0 + 0.045 * cp_mean;
    const double sh = 1.0 + 0.015 * cp_mean * t;
    const double rt = -std::sin(rad(2.0 * d_theta)) * rc;

    const double l = dL / sl, c = dC / sc, h = dH / sh;
    return std::sqrt(l * l + c * c + h * h + rt * c * h);
}

namespace {
constexpr double kEpsilon = 216.0 / 24389.0;  // (6/29)^3
constexpr double kKappa = 24389.0 / 27.0;
double lab_f(double t) { return t > kEpsilon ? std::cbrt(t) : (kKappa * t + 16.0) / 116.0; }
double lab_f_inverse(double f) {
    const double t = f * f * f;
    return t > kEpsilon ? t : (116.0 * f - 16.0) / kKappa;
}
}  // namespace

Lab xyz_to_lab(const std::array<double, 3>& xyz, const std::array<double, 3>& white) {
    const double fx = lab_f(xyz[0] / white[0]);
    const double fy = lab_f(xyz[1] / white[1]);
    const double fz = lab_f(xyz[2] / white[2]);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

std::array<double, 3> lab_to_xyz(const Lab& lab, const std::array<double, 3>& white) {
    const double fy = (lab.L + 16.0) / 116.0;
    const double fx = fy + lab.a / 500.0;
    const double fz = fy - lab.b / 200.0;
    return {white[0] * lab_f_inverse(fx), white[1] * lab_f_inverse(fy), white[2] * lab_f_inverse(fz)};
}

}  // namespace surfscatter::photo
