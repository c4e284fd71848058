// sRGB, chromaticity and white balance.
#include <gtest/gtest.h>

#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/spectrum/blackbody.hpp"
#include "surfscatter/spectrum/cie.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace ss = surfscatter::spectrum;
using surfscatter::Vec3;

TEST(Color, SrgbWhiteAndPrimaries) {
    const Vec3 white = ss::srgb_white_xyz();
    EXPECT_NEAR(white.x, 0.95046, 1e-5);
    EXPECT_NEAR(white.z, 1.08906, 1e-5);
    const Vec3 rgb = ss::xyz_to_linear_srgb(white);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(rgb[i], 1.0, 2e-4);
    // Red primary of Rec. 709: x = 0.64, y = 0.33.
    const auto red = ss::chromaticity(ss::linear_srgb_to_xyz({1, 0, 0}));
    EXPECT_NEAR(red.x, 0.64, 1e-4);
    EXPECT_NEAR(red.y, 0.33, 1e-4);
    const Vec3 back = ss::xyz_to_linear_srgb(ss::linear_srgb_to_xyz({0.2, 0.5, 0.8}));
    EXPECT_NEAR(back.x, 0.2, 2e-4);
    EXPECT_NEAR(back.y, 0.5, 2e-4);
    EXPECT_NEAR(back.z, 0.8, 2e-4);
}

TEST(Color, TransferFunction) {
    // IEC 61966-2-1: linear 0.0031308 <-> 0.04045 (both branches meet), 0.5 linear -> 0.735357.
    EXPECT_NEAR(ss::srgb_encode(0.0031308), 0.0404500, 1e-6);
    EXPECT_NEAR(ss::srgb_encode(0.5), 0.7353570, 1e-6);
    EXPECT_NEAR(ss::srgb_encode(0.18), 0.4613561, 1e-6);
    for (double v = 0; v <= 1.0; v += 0.01) EXPECT_NEAR(ss::srgb_decode(ss::srgb_encode(v)), v, 1e-12);
    EXPECT_EQ(ss::srgb_encode(-1.0), 0.0);
    EXPECT_EQ(ss::srgb_encode(2.0), 1.0);
    EXPECT_EQ(ss::srgb_encode(std::nan("")), 0.0);
}

TEST(Color, MatrixInverse) {
    const ss::Mat3 a{{2, 1, 0, 1, 3, 1, 0, 1, 4}};
    const ss::Mat3 i = a * a.inverse();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(i(r, c), r == c ? 1.0 : 0.0, 1e-14);
    EXPECT_THROW((ss::Mat3{{1, 2, 3, 2, 4, 6, 0, 0, 1}}.inverse()), surfscatter::Error);
}

TEST(Color, BlackbodyWhiteChromaticity) {
    // Planckian locus (CIE 15:2004, c2 = 1.4388e-2 m K): 2856 K -> (0.4476, 0.4074) (illuminant A's nominal
    // temperature with today's c2 gives the same point to 1e-4); 6504 K -> (0.3135, 0.3237).
    auto xy = ss::chromaticity(ss::blackbody_white_xyz(2856));
    EXPECT_NEAR(xy.x, 0.4476, 3e-4);
    EXPECT_NEAR(xy.y, 0.4074, 3e-4);
    xy = ss::chromaticity(ss::blackbody_white_xyz(6504));
    EXPECT_NEAR(xy.x, 0.3135, 3e-4);
    EXPECT_NEAR(xy.y, 0.3237, 3e-4);
    EXPECT_DOUBLE_EQ(ss::blackbody_white_xyz(2700).y, 1.0);
}

TEST(Color, WhitePointByName) {
    const Vec3 a = ss::white_point_xyz("2700K");
    const Vec3 b = ss::white_point_xyz("2700");
    EXPECT_EQ(a, b);
    EXPECT_EQ(ss::white_point_xyz("D65"), ss::srgb_white_xyz());
    const auto xy = ss::chromaticity(ss::white_point_xyz("D50"));
    EXPECT_NEAR(xy.x, 0.3457, 2e-4);
    EXPECT_NEAR(xy.y, 0.3585, 2e-4);
    EXPECT_THROW(ss::white_point_xyz("-300"), surfscatter::Error);
    EXPECT_THROW(ss::white_point_xyz("bogus"), surfscatter::Error);
}

TEST(Color, WhiteBalanceMakesTheSourceWhiteNeutral) {
    for (const char* white : {"2700", "A", "D50", "F2"}) {
        const Vec3 source = ss::white_point_xyz(white);
        const Vec3 rgb = ss::xyz_to_linear_srgb(ss::white_balance_to_d65(source) * source);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(rgb[i], 1.0, 2e-4) << white;
    }
    // Bradford D65 -> D50 (Lindbloom's table): first row 1.0478112, 0.0228866, -0.0501270.
    const ss::Mat3 m = ss::bradford_adaptation(ss::xyz_from_chromaticity({0.31271, 0.32902}),
                                               ss::xyz_from_chromaticity({0.34567, 0.35850}));
    EXPECT_NEAR(m(0, 0), 1.0478112, 2e-4);
    EXPECT_NEAR(m(0, 1), 0.0228866, 2e-4);
    EXPECT_NEAR(m(0, 2), -0.0501270, 2e-4);
}
