#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"

namespace surfscatter {

TEST(Error, FailFormatsOneLineNamingTheValue) {
    try {
        fail("gamma must be > 1, got {}", 0.5);
        FAIL() << "fail() returned";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "gamma must be > 1, got 0.5");
    }
}

TEST(Error, RequireRejectsNaNInfinityAndSign) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_THROW(require_finite(nan, "--x"), Error);
    EXPECT_THROW(require_finite(inf, "--x"), Error);
    EXPECT_NO_THROW(require_finite(-3.0, "--x"));
    EXPECT_THROW(require_positive(0.0, "--sigma"), Error);
    EXPECT_THROW(require_positive(inf, "--sigma"), Error);
    EXPECT_NO_THROW(require_positive(1e-300, "--sigma"));
    EXPECT_THROW(require_non_negative(-1e-300, "--sigma"), Error);
    EXPECT_NO_THROW(require_non_negative(0.0, "--sigma"));
    try {
        require_positive(-2.0, "--corr-length");
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "--corr-length must be positive, got -2");
    }
}

TEST(Progress, CountsAndFormatsDurations) {
    Progress p("test", 4, false);
    p.advance(1);
    EXPECT_DOUBLE_EQ(p.fraction(), 0.25);
    p.advance(3);
    EXPECT_DOUBLE_EQ(p.fraction(), 1.0);
    EXPECT_EQ(format_duration(12.34), "12.3s");
    EXPECT_EQ(format_duration(185.0), "3m05s");
    EXPECT_EQ(format_duration(3720.0), "1h02m");
}

TEST(Interrupt, FlagCanBeRaisedAndCleared) {
    clear_interrupt();
    EXPECT_FALSE(interrupt_requested());
    request_interrupt();
    EXPECT_TRUE(interrupt_requested());
    clear_interrupt();
    EXPECT_FALSE(interrupt_requested());
}

}  // namespace surfscatter
