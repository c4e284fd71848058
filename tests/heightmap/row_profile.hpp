#pragma once
// Row-level profiles for the row alignment tests: what the median of differences cannot tell from row offsets.
#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap::test {

// v minus its least-squares cubic in the index (what row alignment leaves of a row-level sequence as form).
inline std::vector<double> minus_cubic(const std::vector<double>& v) {
    const auto m = static_cast<Eigen::Index>(v.size());
    Eigen::MatrixXd a(m, 4);
    Eigen::VectorXd b(m);
    for (Eigen::Index i = 0; i < m; ++i) {
        const double t = 2.0 * double(i) / double(m - 1) - 1.0;
        a.row(i) << 1, t, t * t, t * t * t;
        b(i) = v[std::size_t(i)];
    }
    const Eigen::VectorXd r = b - a * a.colPivHouseholderQr().solve(b);
    return std::vector<double>(r.data(), r.data() + m);
}

inline double rms(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x * x;
    return std::sqrt(s / double(v.size()));
}

// The surface's own row-mean profile (mean of each row over its valid points, minus the cubic): what the median of
// differences cannot tell from offsets.
// Rows without a valid point get 0 and are left out of the cubic.
inline std::vector<double> row_means(const HeightMap& map) {
    std::vector<double> means;
    std::vector<std::size_t> rows;
    for (std::size_t iy = 0; iy < map.ny(); ++iy) {
        double sum = 0, n = 0;
        for (std::size_t ix = 0; ix < map.nx(); ++ix)
            if (map.valid(ix, iy)) sum += map(ix, iy), ++n;
        if (n > 0) means.push_back(sum / n), rows.push_back(iy);
    }
    const std::vector<double> detrended = minus_cubic(means);
    std::vector<double> profile(map.ny(), 0.0);
    for (std::size_t i = 0; i < rows.size(); ++i) profile[rows[i]] = detrended[i];
    return profile;
}

}  // namespace surfscatter::heightmap::test
