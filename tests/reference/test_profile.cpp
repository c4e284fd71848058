// Profile CSV files (format and errors naming path:line) and the natural spline the solver runs on.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "surfscatter/core/error.hpp"
#include "surfscatter/reference/profile.hpp"

namespace sr = surfscatter::reference;

namespace {

std::string error_of(const std::string& text) {
    try {
        sr::parse_profile_csv(text, "p.csv");
    } catch (const surfscatter::Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Profile, ParsesUniformRows) {
    const auto p = sr::parse_profile_csv("# a comment\nx_um,h_um\n-1.5,0.1\n-0.5,0.2\r\n0.5,-0.1\n\n1.5,0\n", "p.csv");
    EXPECT_DOUBLE_EQ(p.x0_um, -1.5);
    EXPECT_DOUBLE_EQ(p.spacing_um, 1.0);
    ASSERT_EQ(p.h_um.size(), 4u);
    EXPECT_DOUBLE_EQ(p.h_um[2], -0.1);
    EXPECT_DOUBLE_EQ(p.x_end_um(), 1.5);
    // format_profile_csv writes what parse reads.
    const auto again = sr::parse_profile_csv(sr::format_profile_csv(p), "again.csv");
    EXPECT_EQ(again.h_um, p.h_um);
}

TEST(Profile, ErrorsNameTheLine) {
    EXPECT_NE(error_of("x,h\n0,0\n").find("p.csv:1: expected the header 'x_um,h_um'"), std::string::npos);
    EXPECT_NE(error_of("x_um,h_um\n0,0\n1,0\n2,x\n").find("p.csv:4: expected 'x_um,h_um' with two numbers"),
              std::string::npos);
    EXPECT_NE(error_of("x_um,h_um\n0,0\n1,0\n2.5,0\n3,0\n").find("p.csv:4: x = 2.5 um breaks the uniform step 1 um"),
              std::string::npos);
    EXPECT_NE(error_of("x_um,h_um\n0,0\n1,0\n0.5,0\n").find("p.csv:4: x = 0.5 um does not increase"), std::string::npos);
    EXPECT_NE(error_of("x_um,h_um\n0,0\n1,nan\n").find("p.csv:3: x = 1 um, h = nan um"), std::string::npos);
    EXPECT_NE(error_of("x_um,h_um\n0,0\n1,0\n2,0\n").find("p.csv: needs at least 4 rows"), std::string::npos);
    EXPECT_NE(error_of("").find("p.csv: no header"), std::string::npos);
    EXPECT_THROW(sr::read_profile_csv("/nonexistent/profile.csv"), surfscatter::Error);
}

// A natural spline through sin(x) sampled every 0.1: away from the ends (where the natural condition h'' = 0 is
// wrong for sin) h, h', h'' match the closed forms to the spline's O(dx^4), O(dx^3), O(dx^2).
TEST(Profile, SplineNodesFollowTheSamples) {
    sr::Profile p;
    p.x0_um = -5;
    p.spacing_um = 0.1;
    for (int j = 0; j <= 100; ++j) p.h_um.push_back(std::sin(-5 + 0.1 * j));
    const auto nodes = sr::spline_nodes(p, 4);
    ASSERT_EQ(nodes.h.size(), 401u);
    EXPECT_DOUBLE_EQ(nodes.step_um, 0.025);
    for (std::size_t q = 80; q <= 320; ++q) {
        const double x = nodes.x0_um + nodes.step_um * static_cast<double>(q);
        EXPECT_NEAR(nodes.h[q], std::sin(x), 3e-6) << x;
        EXPECT_NEAR(nodes.dh[q], std::cos(x), 1e-4) << x;
        EXPECT_NEAR(nodes.d2h[q], -std::sin(x), 3e-3) << x;
    }
    EXPECT_EQ(nodes.h[0], p.h_um[0]);  // the samples themselves
    EXPECT_NEAR(nodes.h[400], p.h_um[100], 1e-15);
}
