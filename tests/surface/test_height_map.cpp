// HeightMap validation and tilt removal.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "surfscatter/core/error.hpp"
#include "surfscatter/surface/height_map.hpp"

namespace ss = surfscatter::surface;

namespace {
ss::HeightMap plane_map(std::size_t nx, std::size_t ny, double dx, double dy, double a, double bx, double by) {
    std::vector<double> h(nx * ny);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix)
            h[iy * nx + ix] = a + bx * dx * static_cast<double>(ix) + by * dy * static_cast<double>(iy);
    return ss::HeightMap(nx, ny, dx, dy, std::move(h));
}
}  // namespace

TEST(HeightMap, RejectsBadGridsWithClearMessages) {
    EXPECT_THROW(ss::HeightMap(7, 8, 1.0, 1.0, std::vector<double>(56)), surfscatter::Error);
    EXPECT_THROW(ss::HeightMap(8, 8, 0.0, 1.0, std::vector<double>(64)), surfscatter::Error);
    EXPECT_THROW(ss::HeightMap(8, 8, 1.0, -1.0, std::vector<double>(64)), surfscatter::Error);
    EXPECT_THROW(ss::HeightMap(8, 8, std::numeric_limits<double>::quiet_NaN(), 1.0, std::vector<double>(64)),
                 surfscatter::Error);
    EXPECT_THROW(ss::HeightMap(8, 8, 1.0, 1.0, std::vector<double>(63)), surfscatter::Error);
    std::vector<double> h(64, 0.0);
    h[9] = std::numeric_limits<double>::infinity();
    try {
        ss::HeightMap(8, 8, 1.0, 1.0, h, "scan.csv");
        FAIL() << "infinite height accepted";
    } catch (const surfscatter::Error& e) {
        EXPECT_STREQ(e.what(), "scan.csv: height at column 1, row 1 is inf (every height must be finite)");
    }
}

TEST(HeightMap, PlaneIsRemovedExactly) {
    const ss::HeightMap map = plane_map(37, 23, 0.5, 0.8, 3.0, 0.02, -0.015);
    const ss::Plane plane = ss::fit_plane(map);
    EXPECT_NEAR(plane.slope_x, 0.02, 1e-15);
    EXPECT_NEAR(plane.slope_y, -0.015, 1e-15);
    // mean = height at the grid centre
    EXPECT_NEAR(plane.mean, 3.0 + 0.02 * 0.5 * 18 - 0.015 * 0.8 * 11, 1e-13);
    const ss::HeightMap flat = ss::remove_tilt(map);
    for (double h : flat.heights()) EXPECT_NEAR(h, 0.0, 1e-13);
    EXPECT_NEAR(ss::rms_height(map), 0.0, 1e-13);
}

TEST(HeightMap, TiltRemovalKeepsOrthogonalPartAndRmsHeight) {
    // A checkerboard (+-1) is orthogonal to the plane on an even grid: tilt removal leaves it untouched.
    const std::size_t n = 16;
    const ss::HeightMap tilt = plane_map(n, n, 1.0, 1.0, -2.0, 0.3, 0.1);
    std::vector<double> h(tilt.heights());
    for (std::size_t i = 0; i < h.size(); ++i) h[i] += ((i % n + i / n) % 2 ? 0.25 : -0.25);
    const ss::HeightMap map(n, n, 1.0, 1.0, std::move(h));
    EXPECT_NEAR(ss::rms_height(map), 0.25, 1e-14);
    const ss::HeightMap flat = ss::remove_tilt(map);
    EXPECT_NEAR(flat(3, 4), 0.25, 1e-14);
    EXPECT_NEAR(flat(4, 4), -0.25, 1e-14);
}
