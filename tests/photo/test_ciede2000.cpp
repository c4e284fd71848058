#include <gtest/gtest.h>

#include "surfscatter/photo/ciede2000.hpp"
#include "surfscatter/photo/colour_space.hpp"

namespace surfscatter::photo {
namespace {

// Sharma, Wu & Dalal (2005), Table 1: L1 a1 b1 L2 a2 b2 dE00, published to four decimals.
constexpr double kSharma[34][7] = {
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
};

TEST(Ciede2000, MatchesSharmaWuDalalPairsBothWays) {
    for (const auto& row : kSharma) {
        const Lab a{row[0], row[1], row[2]}, b{row[3], row[4], row[5]};
        EXPECT_NEAR(ciede2000(a, b), row[6], 5e-5) << row[0] << " " << row[1] << " " << row[2];
        EXPECT_NEAR(ciede2000(b, a), row[6], 5e-5);
    }
}

TEST(Ciede2000, ZeroForIdenticalColoursAndFiniteForExtremes) {
    EXPECT_EQ(ciede2000({40, 10, -20}, {40, 10, -20}), 0.0);
    EXPECT_EQ(ciede2000({0, 0, 0}, {0, 0, 0}), 0.0);
    for (double L : {0.0, 50.0, 100.0, 1e4})
        for (double a : {-1e3, 0.0, 1e3}) EXPECT_TRUE(std::isfinite(ciede2000({L, a, -a}, {0, 0, 0})));
}

TEST(Lab, WhiteIsHundredAndRoundTrips) {
    const Lab white = xyz_to_lab(white_d65(), white_d65());
    EXPECT_NEAR(white.L, 100.0, 1e-12);
    EXPECT_NEAR(white.a, 0.0, 1e-12);
    EXPECT_NEAR(white.b, 0.0, 1e-12);
    for (const Vec3d xyz : {Vec3d{0.2, 0.3, 0.1}, Vec3d{0.001, 0.002, 0.003}, Vec3d{0.9, 0.8, 1.2}}) {
        const Vec3d back = lab_to_xyz(xyz_to_lab(xyz, kWhiteD50), kWhiteD50);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], xyz[i], 1e-12);
    }
    // sRGB red (linear 1, 0, 0) is L* 53.2408, a* 80.0925, b* 67.2032 with the 4-digit IEC matrix; spectrum/ derives
    // its matrix from the primaries' chromaticities, which moves these by ~0.01.
    const Lab red = xyz_to_lab(linear_srgb_to_xyz({1.0, 0.0, 0.0}), white_d65());
    EXPECT_NEAR(red.L, 53.2408, 0.02);
    EXPECT_NEAR(red.a, 80.0925, 0.05);
    EXPECT_NEAR(red.b, 67.2032, 0.05);
}

TEST(ColourSpace, AdaptersMapWhitesAndImagesRoundTrip) {
    const Vec3d w = bradford_adapt(kWhiteD50, kWhiteD50, white_d65());
    for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(w[i], white_d65()[i], 1e-6);
    const Vec3d rgb_white = xyz_to_linear_srgb(white_d65());
    for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(rgb_white[i], 1.0, 3e-4);
    const cv::Mat image(2, 3, CV_32FC3, cv::Scalar(0.0, 0.18, 1.0));
    const cv::Mat encoded = srgb_encode_image(image);
    EXPECT_NEAR(encoded.at<cv::Vec3f>(1, 2)[1], 0.4613561, 1e-6);
    const cv::Mat back = srgb_decode_image(encoded);
    EXPECT_LT(cv::norm(back, image, cv::NORM_INF), 1e-6);
}

}  // namespace
}  // namespace surfscatter::photo
