#include "surfscatter/heightmap/outliers.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::heightmap {

namespace {

constexpr long kRadius = 2;            // the 5 x 5 neighbourhood
constexpr long kMaxRadius = 8;         // of the local residual's, widened along an edge
constexpr std::size_t kMinPairs = 5;   // pairs the local residual's and a fill's medians need

// The midpoints (h(p + d) + h(p - d)) / 2 of the pairs of points symmetric about (ix, iy) at offsets d with
// max(|d_x|, |d_y|) in [1, radius], both inside the map, valid and accepted by `use`: a plane through the point gives
// its own height at every one, so slope and form do not enter the residuals, at the map's edges neither.
template <class Use>
void pair_midpoints(const HeightMap& map, long ix, long iy, long radius, Use&& use, std::vector<double>& out) {
    out.clear();
    const long nx = long(map.nx()), ny = long(map.ny());
    for (long dy = 0; dy <= radius; ++dy)
        for (long dx = -radius; dx <= radius; ++dx) {
            if (dy == 0 && dx <= 0) continue;  // each pair once
            const long ax = ix + dx, ay = iy + dy, bx = ix - dx, by = iy - dy;
            if (ax < 0 || bx < 0 || ay < 0 || by < 0 || ax >= nx || bx >= nx || ay >= ny || by >= ny) continue;
            const std::size_t a = std::size_t(ay * nx + ax), b = std::size_t(by * nx + bx);
            if (map.valid(a) && map.valid(b) && use(a) && use(b))
                out.push_back(0.5 * (map.heights()[a] + map.heights()[b]));
        }
}

double median_of(std::vector<double>& v) {
    const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    if (v.size() % 2 == 1) return *mid;
    return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

double mean_of(const std::vector<double>& v) {
    double sum = 0;
    for (double x : v) sum += x;
    return sum / double(v.size());
}

// Connected groups (8-neighbour) of the mask's points.
std::size_t count_spots(const std::vector<std::uint8_t>& mask, std::size_t nx, std::size_t ny) {
    std::vector<std::uint8_t> seen(mask.size(), 0);
    std::vector<std::size_t> stack;
    std::size_t spots = 0;
    for (std::size_t start = 0; start < mask.size(); ++start) {
        if (!mask[start] || seen[start]) continue;
        ++spots;
        stack.assign(1, start);
        seen[start] = 1;
        while (!stack.empty()) {
            const std::size_t p = stack.back();
            stack.pop_back();
            const long px = long(p % nx), py = long(p / nx);
            for (long dy = -1; dy <= 1; ++dy)
                for (long dx = -1; dx <= 1; ++dx) {
                    const long x = px + dx, y = py + dy;
                    if (x < 0 || y < 0 || x >= long(nx) || y >= long(ny)) continue;
                    const std::size_t q = std::size_t(y) * nx + std::size_t(x);
                    if (mask[q] && !seen[q]) {
                        seen[q] = 1;
                        stack.push_back(q);
                    }
                }
        }
    }
    return spots;
}

}  // namespace

OutlierPolicy parse_outlier_policy(const std::string& name, const std::string& where) {
    if (name == "keep") return OutlierPolicy::keep;
    if (name == "fill") return OutlierPolicy::fill;
    fail("{}: outliers must be keep or fill, got '{}'", where, name);
}

std::string to_string(OutlierPolicy policy) { return policy == OutlierPolicy::fill ? "fill" : "keep"; }

Outliers find_outliers(const HeightMap& map) {
    const std::size_t nx = map.nx(), ny = map.ny();
    const auto all = [](std::size_t) { return true; };
    // linear: h - the mean of the 3 x 3 pairs' midpoints; local: h - the median of the 5 x 5 pairs' midpoints.
    std::vector<double> linear(map.size(), 0.0), local(map.size(), 0.0), midpoints, spread;
    std::vector<std::uint8_t> tested(map.size(), 0);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) {
            const std::size_t i = iy * nx + ix;
            if (!map.valid(i)) continue;
            // Widened along an edge (2 pairs a radius there) until a spike's neighbour is outvoted; a point without
            // enough pairs (a corner and the points next to it) is not tested.
            for (long radius = kRadius; radius <= kMaxRadius; ++radius) {
                pair_midpoints(map, long(ix), long(iy), radius, all, midpoints);
                if (midpoints.size() >= kMinPairs) break;
            }
            if (midpoints.size() < kMinPairs) continue;
            local[i] = map.heights()[i] - median_of(midpoints);
            pair_midpoints(map, long(ix), long(iy), 1, all, midpoints);
            if (midpoints.empty()) continue;
            tested[i] = 1;
            linear[i] = map.heights()[i] - mean_of(midpoints);
            spread.push_back(linear[i]);
        }
    Outliers out;
    if (spread.empty()) return out;
    const double centre = median_of(spread);
    for (double& r : spread) r = std::abs(r - centre);
    out.robust_sigma_um = 1.4826 * median_of(spread);
    if (!(out.robust_sigma_um > 0)) return out;  // a flat or quantised map: nothing stands out of a zero spread
    const double limit = kOutlierThreshold * out.robust_sigma_um;
    double total = 0, outlying = 0;
    out.mask.assign(map.size(), 0);
    for (std::size_t i = 0; i < map.size(); ++i) {
        if (!tested[i]) continue;
        const double r2 = linear[i] * linear[i];
        total += r2;
        if (std::abs(linear[i]) > limit && std::abs(local[i]) > limit) {
            out.mask[i] = 1;
            ++out.count;
            outlying += r2;
            out.largest_um = std::max(out.largest_um, std::abs(local[i]));
        }
    }
    if (out.count == 0) {
        out.mask.clear();
        return out;
    }
    out.share = outlying / total;
    out.spots = count_spots(out.mask, nx, ny);
    return out;
}

HeightMap fill_outliers(const HeightMap& map, const Outliers& outliers) {
    if (outliers.count == 0) return map;
    if (outliers.mask.size() != map.size()) fail("fill_outliers: the outliers were found on another map");
    std::vector<double> heights = map.heights(), midpoints;
    const long nx = long(map.nx()), ny = long(map.ny()), widest = std::max(nx, ny);
    const auto clean = [&](std::size_t j) { return outliers.mask[j] == 0; };
    for (std::size_t i = 0; i < map.size(); ++i) {
        if (!outliers.mask[i]) continue;
        for (long radius = kRadius; radius <= widest; ++radius) {
            pair_midpoints(map, long(i) % nx, long(i) / nx, radius, clean, midpoints);
            if (midpoints.size() >= kMinPairs) break;
        }
        if (midpoints.empty()) fail("{}: no valid pair of points that are not outliers to fill from", map.origin());
        heights[i] = median_of(midpoints);
    }
    return map.with_heights(std::move(heights));
}

HeightMap apply_outlier_policy(HeightMap map, OutlierPolicy policy, Outliers& found) {
    found = find_outliers(map);
    if (policy == OutlierPolicy::fill) map = fill_outliers(map, found);
    found.mask.clear();
    return map;
}

std::string describe(const Outliers& o) {
    if (o.count == 0)
        return fmt::format("no point stands out from its 5 x 5 neighbourhood by more than {:g} robust sigma ({:.3g} nm)",
                           kOutlierThreshold, 1e3 * o.robust_sigma_um);
    return fmt::format(
        "{} points in {} spots stand out from their 5 x 5 neighbourhood by more than {:g} robust sigma ({:.3g} nm), "
        "the largest by {:.4g} nm; they hold {:.3g} % of the map's pixel-scale roughness",
        o.count, o.spots, kOutlierThreshold, 1e3 * o.robust_sigma_um, 1e3 * o.largest_um, 100.0 * o.share);
}

std::string describe(const Outliers& o, OutlierPolicy policy) {
    if (policy == OutlierPolicy::fill) return describe(o) + (o.count > 0 ? "; filled from their neighbours" : "");
    if (o.count == 0) return describe(o);
    return describe(o) + (kept_and_dominant(o, policy) ? "; kept: the map's PSD at high frequencies and its BRDF at large angles "
                                         "describe them, not the surface (outliers fill replaces them)"
                                       : "; kept (outliers fill replaces them)");
}

std::string outliers_note(const std::string& name, const Outliers& outliers, OutlierPolicy policy) {
    return fmt::format("{}{}: {}", kept_and_dominant(outliers, policy) ? "warning: " : "", name, describe(outliers, policy));
}

}  // namespace surfscatter::heightmap
