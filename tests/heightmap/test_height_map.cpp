// HeightMap validation, invalid points, form removal (plane .. poly4) and height moments.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Dense>

#include "height_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/form.hpp"

namespace hm = surfscatter::heightmap;
using surfscatter::heightmap::test::error_of;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

hm::HeightMap plane_map(std::size_t nx, std::size_t ny, double dx, double dy, double a, double bx, double by) {
    std::vector<double> h(nx * ny);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix)
            h[iy * nx + ix] = a + bx * dx * static_cast<double>(ix) + by * dy * static_cast<double>(iy);
    return hm::HeightMap(nx, ny, dx, dy, std::move(h));
}

// 1 = valid: about `fraction` of the points invalid at random plus rows [band_start, band_end) invalid.
std::vector<std::uint8_t> test_mask(std::size_t nx, std::size_t ny, double fraction, std::size_t band_start,
                                    std::size_t band_end, unsigned seed) {
    std::mt19937 engine(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<std::uint8_t> valid(nx * ny, 1);
    for (std::size_t i = 0; i < valid.size(); ++i) {
        const std::size_t row = i / nx;
        if (uniform(engine) < fraction || (row >= band_start && row < band_end)) valid[i] = 0;
    }
    return valid;
}

// Sum of random monomials x^i y^j, i + j <= degree, in um (x, y in um from the grid origin).
std::vector<double> polynomial_heights(std::size_t nx, std::size_t ny, double dx, double dy, int degree,
                                       unsigned seed) {
    std::mt19937 engine(seed);
    std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
    std::vector<double> c;
    for (int i = 0; i <= degree; ++i)
        for (int j = 0; i + j <= degree; ++j) c.push_back(coefficient(engine) * std::pow(0.05, i + j));
    std::vector<double> h(nx * ny, 0.0);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) {
            const double x = dx * static_cast<double>(ix), y = dy * static_cast<double>(iy);
            std::size_t k = 0;
            for (int i = 0; i <= degree; ++i)
                for (int j = 0; i + j <= degree; ++j) h[iy * nx + ix] += c[k++] * std::pow(x, i) * std::pow(y, j);
        }
    return h;
}

}  // namespace

TEST(HeightMap, RejectsBadGridsWithClearMessages) {
    EXPECT_THROW(hm::HeightMap(7, 8, 1.0, 1.0, std::vector<double>(56)), surfscatter::Error);
    EXPECT_THROW(hm::HeightMap(8, 8, 0.0, 1.0, std::vector<double>(64)), surfscatter::Error);
    EXPECT_THROW(hm::HeightMap(8, 8, 1.0, -1.0, std::vector<double>(64)), surfscatter::Error);
    EXPECT_THROW(hm::HeightMap(8, 8, kNaN, 1.0, std::vector<double>(64)), surfscatter::Error);
    EXPECT_THROW(hm::HeightMap(8, 8, 1.0, 1.0, std::vector<double>(63)), surfscatter::Error);
    std::vector<double> h(64, 0.0);
    h[9] = std::numeric_limits<double>::infinity();
    EXPECT_EQ(error_of([&] { hm::HeightMap(8, 8, 1.0, 1.0, h, "scan.csv"); }),
              "scan.csv: height at column 1, row 1 is inf um (every height must be finite and within +-1e+09 um)");
    // A NaN at a valid point is an error; at an invalid point it is what the mask is for.
    h[9] = kNaN;
    std::vector<std::uint8_t> valid(64, 1);
    EXPECT_NE(error_of([&] { hm::HeightMap(8, 8, 1.0, 1.0, h, valid, "m.gsf"); }).find("column 1, row 1 is nan"),
              std::string::npos);
    valid[9] = 0;
    const hm::HeightMap masked(8, 8, 1.0, 1.0, h, valid, "m.gsf");
    EXPECT_EQ(masked(1, 1), 0.0);
    EXPECT_EQ(error_of([&] { hm::HeightMap(8, 8, 1.0, 1.0, h, std::vector<std::uint8_t>(63, 1), "m.gsf"); }),
              "m.gsf: validity mask has 63 points for a 8 x 8 grid");
    EXPECT_EQ(error_of([&] { hm::HeightMap(8, 8, 1.0, 1.0, h, std::vector<std::uint8_t>(64, 0), "m.gsf"); }),
              "m.gsf: every one of the 8 x 8 points is invalid");
}

TEST(HeightMap, CountsValidPointsAndDropsAnAllValidMask) {
    std::vector<std::uint8_t> valid(100, 1);
    valid[3] = valid[57] = 0;
    const hm::HeightMap map(10, 10, 1.0, 1.0, std::vector<double>(100, 2.0), valid, "m");
    EXPECT_TRUE(map.has_invalid());
    EXPECT_EQ(map.valid_count(), 98u);
    EXPECT_DOUBLE_EQ(map.valid_fraction(), 0.98);
    EXPECT_FALSE(map.valid(3, 0));
    EXPECT_FALSE(map.valid(7, 5));
    EXPECT_TRUE(map.valid(4, 0));
    const hm::HeightMap full(10, 10, 1.0, 1.0, std::vector<double>(100, 2.0), std::vector<std::uint8_t>(100, 1), "m");
    EXPECT_FALSE(full.has_invalid());
    EXPECT_TRUE(full.validity().empty());
    // with_heights keeps grid, mask and metadata, and zeroes the invalid points again.
    std::vector<double> heights(100, 5.0);
    heights[3] = kNaN;
    const hm::HeightMap other = map.with_heights(heights);
    EXPECT_FALSE(other.valid(3, 0));
    EXPECT_EQ(other(3, 0), 0.0);
    EXPECT_EQ(other(4, 0), 5.0);
    EXPECT_THROW(map.with_heights(std::vector<double>(100, kNaN)).valid_count(), surfscatter::Error)
        << "valid points must stay finite";
    EXPECT_NE(error_of([&] { hm::require_valid_fraction(map, 0.99, "a KC fit"); }).find("98.0 % of the 10 x 10"),
              std::string::npos);
}

TEST(HeightMap, PlaneIsRemovedExactly) {
    const hm::HeightMap map = plane_map(37, 23, 0.5, 0.8, 3.0, 0.02, -0.015);
    const hm::HeightMap flat = hm::remove_form(map, hm::Form::plane);
    for (double h : flat.heights()) EXPECT_NEAR(h, 0.0, 1e-13);
    EXPECT_NEAR(hm::rms_height(map), 0.0, 1e-13);
    // --form none removes only the mean: the tilt stays.
    const double half_span = 0.02 * 0.5 * 36 / 2;  // the x ramp's half range, um
    EXPECT_NEAR(hm::remove_form(map, hm::Form::none)(0, 11), -half_span, 1e-12);
}

TEST(HeightMap, TiltRemovalKeepsOrthogonalPartAndRmsHeight) {
    // A checkerboard (+-1) is orthogonal to the plane on an even grid: tilt removal leaves it untouched.
    const std::size_t n = 16;
    const hm::HeightMap tilt = plane_map(n, n, 1.0, 1.0, -2.0, 0.3, 0.1);
    std::vector<double> h(tilt.heights());
    for (std::size_t i = 0; i < h.size(); ++i) h[i] += ((i % n + i / n) % 2 ? 0.25 : -0.25);
    const hm::HeightMap map(n, n, 1.0, 1.0, std::move(h));
    EXPECT_NEAR(hm::rms_height(map), 0.25, 1e-14);
    const hm::HeightMap flat = hm::remove_form(map, hm::Form::plane);
    EXPECT_NEAR(flat(3, 4), 0.25, 1e-14);
    EXPECT_NEAR(flat(4, 4), -0.25, 1e-14);
}

TEST(HeightMap, EachFormRemovesPolynomialsOfItsDegreeOverValidPoints) {
    const std::size_t nx = 61, ny = 47;
    const std::vector<std::uint8_t> mask = test_mask(nx, ny, 0.1, 20, 25, 3);
    const hm::Form forms[] = {hm::Form::none, hm::Form::plane, hm::Form::poly2, hm::Form::poly3, hm::Form::poly4};
    for (int degree = 0; degree <= 4; ++degree) {
        const std::vector<double> h = polynomial_heights(nx, ny, 0.7, 0.9, degree, 10u + static_cast<unsigned>(degree));
        for (bool masked : {false, true}) {
            const hm::HeightMap map(nx, ny, 0.7, 0.9, h, masked ? mask : std::vector<std::uint8_t>{}, "poly");
            for (int f = 0; f <= 4; ++f) {
                const double rms = hm::rms_height(map, forms[f]);
                if (f >= degree) EXPECT_LT(rms, 1e-11) << "degree " << degree << ", form " << f;
                else EXPECT_GT(rms, 1e-4) << "degree " << degree << ", form " << f;
            }
        }
    }
}

TEST(HeightMap, FormIsTheLeastSquaresFitOverValidPoints) {
    // Independent reference: Householder QR of the design matrix in plain monomials x^i y^j over the valid points.
    const std::size_t nx = 40, ny = 33;
    std::mt19937 engine(5);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<double> h(nx * ny);
    for (double& v : h) v = normal(engine);
    const hm::HeightMap map(nx, ny, 0.3, 0.45, h, test_mask(nx, ny, 0.15, 5, 9, 8), "noise");
    for (int degree = 1; degree <= 4; ++degree) {
        const hm::Form form = degree == 1 ? hm::Form::plane
                              : degree == 2 ? hm::Form::poly2
                              : degree == 3 ? hm::Form::poly3
                                            : hm::Form::poly4;
        const auto terms = static_cast<Eigen::Index>((degree + 1) * (degree + 2) / 2);
        Eigen::MatrixXd design(static_cast<Eigen::Index>(map.valid_count()), terms);
        Eigen::VectorXd rhs(design.rows());
        std::vector<std::size_t> index;
        for (std::size_t i = 0; i < map.size(); ++i) {
            if (!map.valid(i)) continue;
            const auto row = static_cast<Eigen::Index>(index.size());
            // Coordinates scaled to [0, 1] keep the monomial basis well conditioned; the fit does not depend on it.
            const double x = static_cast<double>(i % nx) / (nx - 1.0), y = static_cast<double>(i / nx) / (ny - 1.0);
            Eigen::Index k = 0;
            for (int a = 0; a <= degree; ++a)
                for (int b = 0; a + b <= degree; ++b) design(row, k++) = std::pow(x, a) * std::pow(y, b);
            rhs[row] = map.heights()[i];
            index.push_back(i);
        }
        const Eigen::VectorXd residual = rhs - design * design.colPivHouseholderQr().solve(rhs);
        const hm::HeightMap flat = hm::remove_form(map, form);
        for (std::size_t r = 0; r < index.size(); ++r)
            ASSERT_NEAR(flat.heights()[index[r]], residual[static_cast<Eigen::Index>(r)], 1e-9) << "degree " << degree;
        EXPECT_FALSE(flat.valid(0, 5)) << "the masked band stays invalid";
    }
}

TEST(HeightMap, UndeterminedFormsAreErrors) {
    // Valid points on two rows only: a plane is determined, a quadratic in y is not.
    std::vector<std::uint8_t> valid(20 * 20, 0);
    for (std::size_t ix = 0; ix < 20; ++ix) valid[3 * 20 + ix] = valid[11 * 20 + ix] = 1;
    const hm::HeightMap map(20, 20, 1.0, 1.0, std::vector<double>(400, 1.0), valid, "rows.x3p");
    EXPECT_NO_THROW(hm::remove_form(map, hm::Form::plane));
    EXPECT_EQ(error_of([&] { hm::remove_form(map, hm::Form::poly2); }),
              "rows.x3p: the valid points do not determine a poly2 form (they lie on too few rows or columns); "
              "choose a lower form (--form, Python form=): plane or none");
    std::vector<std::uint8_t> few(400, 0);
    for (std::size_t i = 0; i < 30; ++i) few[i * 13] = 1;
    EXPECT_EQ(error_of([&] {
                  hm::remove_form(hm::HeightMap(20, 20, 1.0, 1.0, std::vector<double>(400), few, "few.x3p"),
                                  hm::Form::poly4);
              }),
              "few.x3p: 30 valid points cannot determine a poly4 form (15 coefficients need 60); choose a lower form "
              "(--form, Python form=): poly3, poly2, plane or none");
}

TEST(HeightMap, ParsesFormNames) {
    EXPECT_EQ(hm::parse_form("poly3", "--form"), hm::Form::poly3);
    EXPECT_EQ(hm::to_string(hm::parse_form("none", "--form")), "none");
    EXPECT_EQ(error_of([] { hm::parse_form("cylinder", "--form"); }),
              "--form must be none, plane, poly2, poly3 or poly4, got 'cylinder'");
}

TEST(HeightMap, MomentsOfATwoValueSurfaceOverValidPointsOnly) {
    // Heights 1 on a quarter of the valid points, 0 elsewhere (Bernoulli, p = 1/4): rms sqrt(p(1-p)),
    // skewness (1 - 2p)/sqrt(p(1-p)), kurtosis 3 + (1 - 6p(1-p))/(p(1-p)). The invalid points (a third of the map,
    // all holding 0) would change every moment if they were counted.
    const std::size_t n = 24;
    std::vector<double> h(n * n, 0.0);
    std::vector<std::uint8_t> valid(n * n, 1);
    std::size_t counted = 0;
    for (std::size_t i = 0; i < h.size(); ++i) {
        if (i % 3 == 2) {
            valid[i] = 0;
            continue;
        }
        if (counted++ % 4 == 0) h[i] = 1.0;
    }
    const hm::HeightMoments m = hm::height_moments(hm::HeightMap(n, n, 1.0, 1.0, h, valid, "bernoulli"));
    const double p = 0.25, q = p * (1 - p);
    EXPECT_NEAR(m.rms, std::sqrt(q), 1e-14);
    EXPECT_NEAR(m.skewness, (1 - 2 * p) / std::sqrt(q), 1e-13);
    EXPECT_NEAR(m.kurtosis, 3 + (1 - 6 * q) / q, 1e-13);
}
