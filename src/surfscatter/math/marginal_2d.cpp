#include "surfscatter/math/marginal_2d.hpp"

#include <algorithm>
#include <cmath>

#include "surfscatter/core/error.hpp"

namespace surfscatter {

namespace {

// Root t in [0, 1] of a0 t + (a1 - a0) t^2 / 2 = target: where the integral of the linear density a0 -> a1 over a
// unit cell reaches `target`.
double solve_linear_cdf(double a0, double a1, double target) {
    if (std::abs(a0 - a1) <= 1e-4 * (a0 + a1)) {  // <=: a0 = a1 = 0 too
        const double mean = 0.5 * (a0 + a1);
        return mean > 0 ? std::clamp(target / mean, 0.0, 1.0) : 0.0;
    }
    const double t = (a0 - std::sqrt(std::max(0.0, a0 * a0 + 2 * target * (a1 - a0)))) / (a0 - a1);
    return std::clamp(t, 0.0, 1.0);
}

// Largest index i in [0, n - 2] with value(i) <= x (value non-decreasing).
template <typename F>
std::size_t find_interval(std::size_t n, double x, F value) {
    std::size_t lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        const std::size_t mid = (lo + hi) / 2;
        if (value(mid) <= x) lo = mid; else hi = mid;
    }
    return lo;
}

}  // namespace

Marginal2D::Marginal2D(const std::vector<double>& data, std::size_t nx, std::size_t ny,
                       std::vector<std::vector<double>> param_nodes, bool normalize)
    : nx_(nx), ny_(ny), nodes_(std::move(param_nodes)) {
    if (nx < 2 || ny < 2) fail("2-D distribution: grid {} x {} (each side must be >= 2)", nx, ny);
    if (nodes_.size() > kMaxParams) fail("2-D distribution: {} parameters (at most {})", nodes_.size(), kMaxParams);
    std::size_t slices = 1;
    strides_.assign(nodes_.size(), 0);
    for (std::size_t d = nodes_.size(); d-- > 0;) {
        if (nodes_[d].empty()) fail("2-D distribution: parameter {} has no nodes", d);
        for (std::size_t k = 1; k < nodes_[d].size(); ++k)
            if (!(nodes_[d][k] > nodes_[d][k - 1]))
                fail("2-D distribution: nodes of parameter {} do not increase ({} then {})", d, nodes_[d][k - 1],
                     nodes_[d][k]);
        strides_[d] = slices;
        slices *= nodes_[d].size();
    }
    const std::size_t size = nx * ny;
    if (data.size() != slices * size)
        fail("2-D distribution: {} values for {} slices of {} x {}", data.size(), slices, nx, ny);
    for (double v : data)
        if (!(v >= 0) || !std::isfinite(v)) fail("2-D distribution: value {} (must be finite and >= 0)", v);
    data_ = data;
    if (!normalize) {
        for (double& v : data_) v /= static_cast<double>((nx - 1) * (ny - 1));
        return;
    }
    conditional_.assign(slices * size, 0.0);
    marginal_.assign(slices * ny, 0.0);
    for (std::size_t s = 0; s < slices; ++s) {
        double* d = data_.data() + s * size;
        double* c = conditional_.data() + s * size;
        double* m = marginal_.data() + s * ny;
        for (std::size_t y = 0; y < ny; ++y)
            for (std::size_t x = 1; x < nx; ++x)
                c[y * nx + x] = c[y * nx + x - 1] + 0.5 * (d[y * nx + x - 1] + d[y * nx + x]);
        for (std::size_t y = 1; y < ny; ++y)
            m[y] = m[y - 1] + 0.5 * (c[y * nx - 1] + c[(y + 1) * nx - 1]);
        const double total = m[ny - 1];
        if (!(total > 0)) fail("2-D distribution: slice {} integrates to 0", s);
        for (std::size_t i = 0; i < size; ++i) d[i] /= total, c[i] /= total;
        for (std::size_t y = 0; y < ny; ++y) m[y] /= total;
    }
}

Marginal2D::Blend Marginal2D::blend(std::span<const double> params) const {
    if (params.size() != nodes_.size())
        fail("2-D distribution: {} parameters given, {} expected", params.size(), nodes_.size());
    Blend b;
    b.count = 1;
    b.slice[0] = 0;
    b.weight[0] = 1;
    for (std::size_t d = 0; d < nodes_.size(); ++d) {
        const auto& n = nodes_[d];
        if (n.size() == 1) continue;
        const double x = std::clamp(params[d], n.front(), n.back());
        const std::size_t i = find_interval(n.size(), x, [&](std::size_t k) { return n[k]; });
        const double w1 = std::clamp((x - n[i]) / (n[i + 1] - n[i]), 0.0, 1.0);
        const int count = b.count;
        for (int k = 0; k < count; ++k) {
            b.slice[count + k] = b.slice[k] + (i + 1) * strides_[d];
            b.weight[count + k] = b.weight[k] * w1;
            b.slice[k] += i * strides_[d];
            b.weight[k] *= 1 - w1;
        }
        b.count = 2 * count;
    }
    return b;
}

double Marginal2D::eval(Vec2 p, std::span<const double> params) const {
    const Blend b = blend(params);
    const double px = std::clamp(p.x, 0.0, 1.0) * static_cast<double>(nx_ - 1);
    const double py = std::clamp(p.y, 0.0, 1.0) * static_cast<double>(ny_ - 1);
    const std::size_t ix = std::min(static_cast<std::size_t>(px), nx_ - 2);
    const std::size_t iy = std::min(static_cast<std::size_t>(py), ny_ - 2);
    const double fx = px - static_cast<double>(ix), fy = py - static_cast<double>(iy);
    const std::size_t size = nx_ * ny_, i = iy * nx_ + ix;
    const double v00 = fetch(data_, size, b, i), v10 = fetch(data_, size, b, i + 1);
    const double v01 = fetch(data_, size, b, i + nx_), v11 = fetch(data_, size, b, i + nx_ + 1);
    const double v = (1 - fy) * ((1 - fx) * v00 + fx * v10) + fy * ((1 - fx) * v01 + fx * v11);
    return v * static_cast<double>((nx_ - 1) * (ny_ - 1));
}

std::pair<Vec2, double> Marginal2D::sample(Vec2 u, std::span<const double> params) const {
    if (marginal_.empty()) fail("2-D distribution: built without normalisation, cannot be sampled");
    const Blend b = blend(params);
    const std::size_t size = nx_ * ny_;
    const double uy = std::clamp(u.y, 0.0, 1.0), ux = std::clamp(u.x, 0.0, 1.0);
    // Row: the marginal CDF is piecewise quadratic; the row totals vary linearly across a row interval.
    const std::size_t row = find_interval(ny_, uy, [&](std::size_t k) { return fetch(marginal_, ny_, b, k); });
    const double r0 = fetch(conditional_, size, b, row * nx_ + nx_ - 1);
    const double r1 = fetch(conditional_, size, b, (row + 1) * nx_ + nx_ - 1);
    const double ty = solve_linear_cdf(r0, r1, uy - fetch(marginal_, ny_, b, row));
    // Column, on the conditional CDF blended at that height.
    const double target = ux * ((1 - ty) * r0 + ty * r1);
    auto conditional = [&](std::size_t k) {
        return (1 - ty) * fetch(conditional_, size, b, row * nx_ + k) +
               ty * fetch(conditional_, size, b, (row + 1) * nx_ + k);
    };
    const std::size_t col = find_interval(nx_, target, conditional);
    const std::size_t i = row * nx_ + col;
    const double c0 = (1 - ty) * fetch(data_, size, b, i) + ty * fetch(data_, size, b, i + nx_);
    const double c1 = (1 - ty) * fetch(data_, size, b, i + 1) + ty * fetch(data_, size, b, i + nx_ + 1);
    const double tx = solve_linear_cdf(c0, c1, target - conditional(col));
    const Vec2 p{(static_cast<double>(col) + tx) / static_cast<double>(nx_ - 1),
                 (static_cast<double>(row) + ty) / static_cast<double>(ny_ - 1)};
    return {p, ((1 - tx) * c0 + tx * c1) * static_cast<double>((nx_ - 1) * (ny_ - 1))};
}

std::pair<Vec2, double> Marginal2D::invert(Vec2 p, std::span<const double> params) const {
    if (marginal_.empty()) fail("2-D distribution: built without normalisation, cannot be inverted");
    const Blend b = blend(params);
    const std::size_t size = nx_ * ny_;
    const double px = std::clamp(p.x, 0.0, 1.0) * static_cast<double>(nx_ - 1);
    const double py = std::clamp(p.y, 0.0, 1.0) * static_cast<double>(ny_ - 1);
    const std::size_t ix = std::min(static_cast<std::size_t>(px), nx_ - 2);
    const std::size_t iy = std::min(static_cast<std::size_t>(py), ny_ - 2);
    const double fx = px - static_cast<double>(ix), fy = py - static_cast<double>(iy);
    const std::size_t i = iy * nx_ + ix;
    const double v00 = fetch(data_, size, b, i), v10 = fetch(data_, size, b, i + 1);
    const double v01 = fetch(data_, size, b, i + nx_), v11 = fetch(data_, size, b, i + nx_ + 1);
    const double c0 = (1 - fy) * v00 + fy * v01, c1 = (1 - fy) * v10 + fy * v11;
    const double density = (1 - fx) * c0 + fx * c1;
    const double r0 = fetch(conditional_, size, b, iy * nx_ + nx_ - 1);
    const double r1 = fetch(conditional_, size, b, (iy + 1) * nx_ + nx_ - 1);
    const double row_total = (1 - fy) * r0 + fy * r1;
    const double x_cdf = fx * (c0 + 0.5 * fx * (c1 - c0)) + (1 - fy) * fetch(conditional_, size, b, i) +
                         fy * fetch(conditional_, size, b, i + nx_);
    const double y_cdf = fy * (r0 + 0.5 * fy * (r1 - r0)) + fetch(marginal_, ny_, b, iy);
    const Vec2 u{row_total > 0 ? std::clamp(x_cdf / row_total, 0.0, 1.0) : 0.0, std::clamp(y_cdf, 0.0, 1.0)};
    return {u, density * static_cast<double>((nx_ - 1) * (ny_ - 1))};
}

}  // namespace surfscatter
