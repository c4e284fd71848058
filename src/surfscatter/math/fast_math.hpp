#pragma once
// Inline exp and log for hot paths (GhsBsdf::eval -> ScatterLobeTable::eval_at_logs: two logarithms and one
// exponential per call; the renderer's blackbody emitters: one per wavelength of a
// path), table-driven like glibc's but without its call, errno and special-case overhead: about 25 instead of 50
// instructions each, which is a tenth of an exact-GHS eval. Accuracy (tests/math/test_fast_math.cpp,
// against std::exp / std::log over their whole ranges): fast_exp within 2.3e-16 relative, fast_log within 2.3e-16
// absolute (relative where |ln x| > 1). Arguments the tables do not cover (fast_log: zero, negative, subnormal, inf,
// NaN; fast_exp: |x| >= 700, NaN) go to std::log / std::exp, so every input gives what the standard functions give up
// to that rounding. The tables are computed at compile time (long double series), so they are usable during static
// initialisation too.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace surfscatter::math {

namespace fast_math_detail {

inline constexpr int kBits = 7;
inline constexpr int kCells = 1 << kBits;
inline constexpr long double kLn2 = 0.693147180559945309417232121458176568L;

constexpr long double exp_series(long double x) {  // |x| <= 1
    long double term = 1, sum = 1;
    for (int n = 1; n < 40; ++n) {
        term *= x / n;
        sum += term;
    }
    return sum;
}
constexpr long double log_series(long double y) {  // y in [0.5, 2]: 2 atanh((y - 1) / (y + 1))
    const long double s = (y - 1) / (y + 1), s2 = s * s;
    long double term = s, sum = 0;
    for (int n = 1; n < 200; n += 2) {
        sum += term / n;
        term *= s2;
    }
    return 2 * sum;
}

// exp: 2^(j/kCells) as bits, minus j << (52 - kBits) so that adding the shifted integer part of x kCells / ln 2
// gives the scale 2^(x / ln 2) rounded to a cell.
constexpr std::array<std::uint64_t, kCells> make_exp_table() {
    std::array<std::uint64_t, kCells> t{};
    for (int j = 0; j < kCells; ++j)
        t[j] = std::bit_cast<std::uint64_t>(double(exp_series(kLn2 * j / kCells))) - (std::uint64_t(j) << (52 - kBits));
    return t;
}
inline constexpr std::array<std::uint64_t, kCells> kExpScale = make_exp_table();

// log: x = 2^k z with z in [kOffset, 2 kOffset) split into kCells cells by its top mantissa bits; 1/c rounds the
// reciprocal of the cell centre and ln_c = ln(1 / inv_c) exactly, so ln z = ln_c + ln(1 + r), r = z inv_c - 1 small.
inline constexpr std::uint64_t kOffset = 0x3fe6000000000000ULL;  // 0.6875
struct LogCell {
    double inv_c, ln_c;
};
constexpr std::array<LogCell, kCells> make_log_table() {
    std::array<LogCell, kCells> t{};
    for (int i = 0; i < kCells; ++i) {
        const std::uint64_t lo = kOffset + (std::uint64_t(i) << (52 - kBits));
        const long double centre =
            0.5L * ((long double)std::bit_cast<double>(lo) + std::bit_cast<double>(lo + (1ULL << (52 - kBits))));
        const double inv_c = double(1.0L / centre);
        t[i] = {inv_c, double(-log_series(inv_c))};
    }
    return t;
}
inline constexpr std::array<LogCell, kCells> kLogCells = make_log_table();

}  // namespace fast_math_detail

inline double fast_exp(double x) {
    using namespace fast_math_detail;
    if (!(std::abs(x) < 700.0)) return std::exp(x);
    constexpr double kShift = 0x1.8p52;  // adding it rounds to an integer held in the low mantissa bits
    constexpr double kCellsPerLn2 = double(kCells / kLn2);
    constexpr double kLn2HiPerCell = 0x1.62e42fefa0000p-8;  // ln 2 / 128 with zero low bits: kd * it is exact
    constexpr double kLn2LoPerCell = double(kLn2 / kCells - (long double)kLn2HiPerCell);
    double kd = x * kCellsPerLn2 + kShift;
    const std::uint64_t ki = std::bit_cast<std::uint64_t>(kd);
    kd -= kShift;
    const double r = (x - kd * kLn2HiPerCell) - kd * kLn2LoPerCell;  // |r| <= ln 2 / 256
    const double scale = std::bit_cast<double>(kExpScale[ki % kCells] + (ki << (52 - kBits)));
    const double r2 = r * r;
    const double expm1_r = r + r2 * (0.5 + r * (1.0 / 6.0)) + r2 * r2 * (1.0 / 24.0 + r * (1.0 / 120.0));
    return scale + scale * expm1_r;
}

inline double fast_log(double x) {
    using namespace fast_math_detail;
    const std::uint64_t ix = std::bit_cast<std::uint64_t>(x);
    constexpr std::uint64_t kMinNormal = 0x0010000000000000ULL, kInf = 0x7ff0000000000000ULL;
    if (ix - kMinNormal >= kInf - kMinNormal) return std::log(x);  // not a positive normal number
    const std::uint64_t tmp = ix - kOffset;
    const LogCell& cell = kLogCells[(tmp >> (52 - kBits)) % kCells];
    const double kd = double(std::int64_t(tmp) >> 52);
    const double z = std::bit_cast<double>(ix - (tmp & (0xfffULL << 52)));
    const double r = z * cell.inv_c - 1.0;  // |r| <= 1/256
    constexpr double kLn2Hi = 0x1.62e42fefa3800p-1;  // low bits zero: kd * it is exact
    constexpr double kLn2Lo = double(kLn2 - (long double)kLn2Hi);
    const double r2 = r * r;
    const double log1p_r_minus_r = r2 * (-0.5 + r * (1.0 / 3.0)) + r2 * r2 * (-0.25 + r * (0.2 - r * (1.0 / 6.0)));
    return (kd * kLn2Hi + cell.ln_c) + (r + (log1p_r_minus_r + kd * kLn2Lo));
}

// atan2(y, x) in [-pi, pi] within 1e-9 rad (8.94e-10 measured; tests/math/test_fast_math.cpp, against std::atan2 over every quadrant):
// the octant's ratio z = min(|x|, |y|) / max(|x|, |y|) in [0, 1] and atan z = z P(z^2), P the degree-9 minimax
// (Remez, absolute error) polynomial, then the octant's reflections. A third of glibc's atan2 (MapGhsBsdf's incidence
// azimuth, on every eval). Zeros, infinities and NaN go to std::atan2, so the signed zeros and edge cases are its.
inline double fast_atan2(double y, double x) {
    const double ax = std::abs(x), ay = std::abs(y);
    if (!(ax + ay > 0.0 && ax + ay < HUGE_VAL)) return std::atan2(y, x);  // also NaN, and sums beyond DBL_MAX
    const double hi = std::max(ax, ay);
    const double z = std::min(ax, ay) / hi, t = z * z, t2 = t * t, t4 = t2 * t2;
    constexpr double c[10] = {0.99999998056031815712,  -0.33333180376885619904,  0.19996436812513175613,
                              -0.14247222674301783143, 0.10878009916188606927,   -0.082137616747470228738,
                              0.055028100815473714368, -0.028490775974468663629, 0.0095673402519408957001,
                              -0.0015093031774495805392};
    const double p = ((c[0] + c[1] * t) + (c[2] + c[3] * t) * t2) + ((c[4] + c[5] * t) + (c[6] + c[7] * t) * t2) * t4 +
                     (c[8] + c[9] * t) * (t4 * t4);
    double a = z * p;
    if (ay > ax) a = 0.5 * 3.14159265358979323846 - a;
    if (x < 0) a = 3.14159265358979323846 - a;
    return std::copysign(a, y);
}

// 1 - e^{-x} for x >= 0: expm1 below 1e-4 (no cancellation), else through fast_exp (relative error <= 1.2e-12, and
// twice as fast as expm1); exactly 1 in double precision beyond x = 38.
inline double one_minus_exp(double x) { return x < 1e-4 ? -std::expm1(-x) : x < 40.0 ? 1.0 - fast_exp(-x) : 1.0; }

}  // namespace surfscatter::math
