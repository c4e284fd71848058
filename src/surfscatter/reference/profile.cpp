#include "surfscatter/reference/profile.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"

namespace surfscatter::reference {

void require_valid_profile(const Profile& profile, const std::string& what) {
    if (profile.h_um.size() < kMinProfileSamples)
        fail("{}: needs at least {} samples, got {}", what, kMinProfileSamples, profile.h_um.size());
    if (!(profile.spacing_um > 0) || !std::isfinite(profile.spacing_um) || !std::isfinite(profile.x0_um) ||
        !std::isfinite(profile.x_end_um()))
        fail("{}: sample spacing {} um from x = {} um is not a positive finite step", what, profile.spacing_um,
             profile.x0_um);
    for (std::size_t j = 0; j < profile.h_um.size(); ++j)
        if (!(std::abs(profile.h_um[j]) <= kMaxProfileHeightUm))
            fail("{}: height {} um of sample {} is not finite within +-{:g} um", what, profile.h_um[j], j + 1,
                 kMaxProfileHeightUm);
}

Profile read_profile_csv(const std::string& path) {
    return parse_profile_csv(read_input_file(path, "profile file"), path);
}

Profile parse_profile_csv(const std::string& text, const std::string& path) {
    std::vector<double> x, h;
    bool header_seen = false;
    for_each_data_line(text, [&](std::string_view line, int line_number) {
        if (!header_seen) {
            if (line != "x_um,h_um")
                fail("{}:{}: expected the header 'x_um,h_um', got '{}'", path, line_number, printable(line));
            header_seen = true;
            return;
        }
        const auto comma = line.find(',');
        const auto xv = comma == std::string_view::npos ? std::nullopt : to_double(line.substr(0, comma));
        const auto hv = comma == std::string_view::npos ? std::nullopt : to_double(line.substr(comma + 1));
        if (!xv || !hv) fail("{}:{}: expected 'x_um,h_um' with two numbers, got '{}'", path, line_number, printable(line));
        if (!std::isfinite(*xv) || !(std::abs(*hv) <= kMaxProfileHeightUm))
            fail("{}:{}: x = {} um, h = {} um (need finite x and |h| <= {:g} um)", path, line_number, *xv, *hv,
                 kMaxProfileHeightUm);
        if (!x.empty() && !(*xv > x.back()))
            fail("{}:{}: x = {} um does not increase (previous row {} um)", path, line_number, *xv, x.back());
        if (x.size() >= 2) {
            const double step = x[1] - x[0], expected = x[0] + step * static_cast<double>(x.size());
            if (std::abs(*xv - expected) > 1e-6 * std::max(step, std::abs(*xv)))
                fail("{}:{}: x = {} um breaks the uniform step {} um of the first two rows (expected {} um)", path,
                     line_number, *xv, step, expected);
        }
        x.push_back(*xv);
        h.push_back(*hv);
    });
    if (!header_seen) fail("{}: no header 'x_um,h_um'", path);
    if (x.size() < kMinProfileSamples)
        fail("{}: needs at least {} rows 'x_um,h_um', found {}", path, kMinProfileSamples, x.size());
    Profile profile{x.front(), (x.back() - x.front()) / static_cast<double>(x.size() - 1), std::move(h)};
    require_valid_profile(profile, path);
    return profile;
}

std::string format_profile_csv(const Profile& profile) {
    std::string out = "x_um,h_um\n";
    for (std::size_t j = 0; j < profile.h_um.size(); ++j)
        out += fmt::format("{:.10g},{:.10g}\n", profile.x0_um + profile.spacing_um * static_cast<double>(j),
                           profile.h_um[j]);
    return out;
}

SplineNodes spline_nodes(const Profile& profile, std::size_t subdivisions) {
    require_valid_profile(profile, "profile");
    if (subdivisions < 1) fail("spline subdivisions must be >= 1, got {}", subdivisions);
    const std::size_t n = profile.h_um.size();
    const double dx = profile.spacing_um;
    const auto& y = profile.h_um;
    // Natural spline: second derivatives M with M_0 = M_{n-1} = 0, M_{j-1} + 4 M_j + M_{j+1} = 6 (y_{j-1} - 2 y_j +
    // y_{j+1}) / dx^2, by the Thomas algorithm (diagonally dominant, stable).
    // (one buffer: GCC 12 warns falsely about freeing three separate vectors here)
    std::vector<double> buffer(3 * n, 0.0);
    double* m = buffer.data();
    double* c = m + n;
    double* d = c + n;
    for (std::size_t j = 1; j + 1 < n; ++j) {
        const double rhs = 6.0 * (y[j - 1] - 2.0 * y[j] + y[j + 1]) / (dx * dx);
        const double denom = 4.0 - c[j - 1];
        c[j] = 1.0 / denom;
        d[j] = (rhs - d[j - 1]) / denom;
    }
    for (std::size_t j = n - 1; j-- > 1;) m[j] = d[j] - c[j] * m[j + 1];
    SplineNodes nodes;
    nodes.x0_um = profile.x0_um;
    nodes.step_um = dx / static_cast<double>(subdivisions);
    const std::size_t count = (n - 1) * subdivisions + 1;
    nodes.h.resize(count);
    nodes.dh.resize(count);
    nodes.d2h.resize(count);
    for (std::size_t q = 0; q < count; ++q) {
        const std::size_t j = std::min(q / subdivisions, n - 2);
        const double t = static_cast<double>(q - j * subdivisions) / static_cast<double>(subdivisions);
        const double a = 1.0 - t, b = t;  // weights of samples j and j+1
        nodes.h[q] = a * y[j] + b * y[j + 1] + ((a * a * a - a) * m[j] + (b * b * b - b) * m[j + 1]) * dx * dx / 6.0;
        nodes.dh[q] = (y[j + 1] - y[j]) / dx + ((1.0 - 3.0 * a * a) * m[j] + (3.0 * b * b - 1.0) * m[j + 1]) * dx / 6.0;
        nodes.d2h[q] = a * m[j] + b * m[j + 1];
    }
    return nodes;
}

}  // namespace surfscatter::reference
