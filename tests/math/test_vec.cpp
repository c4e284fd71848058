#include <gtest/gtest.h>

#include "surfscatter/math/vec.hpp"

namespace surfscatter {

TEST(Frame, IsOrthonormalAndRoundTrips) {
    const Vec3 normals[] = {{0, 0, 1}, {0, 0, -1}, normalize(Vec3{1, 2, 3}), normalize(Vec3{-0.3, 0.1, -0.9}),
                            {1, 0, 0}};
    for (const auto& n : normals) {
        Frame f(n);
        EXPECT_NEAR(dot(f.s, f.t), 0.0, 1e-14);
        EXPECT_NEAR(dot(f.s, f.n), 0.0, 1e-14);
        EXPECT_NEAR(dot(f.t, f.n), 0.0, 1e-14);
        EXPECT_NEAR(f.s.length(), 1.0, 1e-14);
        EXPECT_NEAR(f.t.length(), 1.0, 1e-14);
        // Right-handed: s x t = n.
        const Vec3 c = cross(f.s, f.t);
        EXPECT_NEAR((c - n).length(), 0.0, 1e-14);
        const Vec3 v{0.3, -0.7, 0.2};
        EXPECT_NEAR((f.to_world(f.to_local(v)) - v).length(), 0.0, 1e-14);
    }
}

TEST(Vec3, SphericalDirectionAndMirror) {
    const Vec3 w = spherical_direction(60 * kDegree, 30 * kDegree);
    EXPECT_NEAR(w.length(), 1.0, 1e-15);
    EXPECT_NEAR(cos_theta(w), 0.5, 1e-15);
    EXPECT_NEAR(sin2_theta(w), 0.75, 1e-15);
    EXPECT_NEAR(tan2_theta(w), 3.0, 1e-13);
    const Vec3 r = reflect_about_normal(w);
    EXPECT_NEAR(std::atan2(r.y, r.x), (30.0 - 180.0) * kDegree, 1e-14);
}

}  // namespace surfscatter
