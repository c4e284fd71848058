#include "surfscatter/render/filter.hpp"

#include <algorithm>
#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"

namespace surfscatter::render {

namespace {
constexpr int kBins = 1024;
}

ReconstructionFilter::ReconstructionFilter(std::string name, double radius, double (*profile)(double, const double*),
                                           std::vector<double> params)
    : name_(std::move(name)), radius_(radius), profile_(profile), params_(std::move(params)) {
    if (!(radius > 0) || !std::isfinite(radius)) fail("rfilter '{}': radius must be positive, got {}", name_, radius);
    // Bin integrals of the profile and of its magnitude (8-point Gauss-Legendre per bin: the profiles are smooth or
    // piecewise polynomial of degree <= 3 between their kinks, which sit on bin edges for every built-in filter).
    std::vector<double> nodes, weights;
    math::gauss_legendre(8, nodes, weights);
    const double width = 2 * radius_ / kBins;
    double signed_total = 0, absolute_total = 0;
    cdf_.assign(kBins + 1, 0.0);
    signed_cdf_.assign(kBins + 1, 0.0);
    for (int i = 0; i < kBins; ++i) {
        const double a = -radius_ + i * width;
        double s = 0, m = 0;
        for (std::size_t k = 0; k < nodes.size(); ++k) {
            const double v = profile_(a + 0.5 * width * (nodes[k] + 1), params_.data());
            s += weights[k] * v;
            m += weights[k] * std::abs(v);
        }
        signed_total += 0.5 * width * s;
        absolute_total += 0.5 * width * m;
        cdf_[static_cast<std::size_t>(i) + 1] = absolute_total;
        signed_cdf_[static_cast<std::size_t>(i) + 1] = signed_total;
    }
    if (!(signed_total > 0)) fail("rfilter '{}': the filter integrates to {}, not a positive value", name_, signed_total);
    normalisation_ = 1 / signed_total;
    absolute_integral_ = absolute_total / signed_total;
    for (double& c : cdf_) c /= absolute_total;
    for (double& c : signed_cdf_) c /= signed_total;
    constant_ = true;
    for (int i = 0; i < kBins && constant_; ++i)
        constant_ = profile_(-radius_ + (i + 0.5) * width, params_.data()) == profile_(0.0, params_.data());
    // Guide table: for u in [k, k + 1) / kBins the bin to search from (sampling is on every camera ray).
    guide_.resize(kBins + 1);
    std::size_t bin = 0;
    for (int k = 0; k <= kBins; ++k) {
        const double u = static_cast<double>(k) / kBins;
        while (bin + 1 < kBins && cdf_[bin + 1] <= u) ++bin;
        guide_[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(bin);
    }
}

double ReconstructionFilter::eval(double x) const {
    if (std::abs(x) > radius_) return 0.0;
    return profile_(x, params_.data()) * normalisation_;
}

double ReconstructionFilter::cdf_at(const std::vector<double>& cdf, double x) const {
    const double width = 2 * radius_ / kBins;
    const double position = std::clamp((x + radius_) / width, 0.0, static_cast<double>(kBins));
    const auto i = std::min<std::size_t>(static_cast<std::size_t>(position), kBins - 1);
    const double t = position - static_cast<double>(i);
    return cdf[i] + t * (cdf[i + 1] - cdf[i]);
}

double ReconstructionFilter::sample_1d(double u, double lo, double hi, double& weight) const {
    if (constant_) {  // f / (pdf times the integral over the window) = 1 wherever the window is not empty
        lo = std::max(lo, -radius_);
        hi = std::min(hi, radius_);
        weight = hi > lo ? 1.0 : 0.0;
        return hi > lo ? lo + u * (hi - lo) : 0.5 * (lo + hi);
    }
    double p_lo = 0, mass = 1, integral = 1;  // the whole footprint
    if (lo > -radius_ || hi < radius_) {
        lo = std::max(lo, -radius_);
        hi = std::min(hi, radius_);
        p_lo = cdf_at(cdf_, lo);
        mass = cdf_at(cdf_, hi) - p_lo;
        integral = cdf_at(signed_cdf_, hi) - cdf_at(signed_cdf_, lo);
        if (!(mass > 0) || !(std::abs(integral) > 1e-12)) {
            weight = 0;
            return 0.5 * (lo + hi);
        }
    } else {
        lo = -radius_;
        hi = radius_;
    }
    const double target = p_lo + u * mass;
    std::size_t i = guide_[std::min<std::size_t>(static_cast<std::size_t>(target * kBins), kBins)];
    while (i + 1 < kBins && cdf_[i + 1] <= target) ++i;
    const double c0 = cdf_[i], c1 = cdf_[i + 1];
    const double t = c1 > c0 ? std::clamp((target - c0) / (c1 - c0), 0.0, 1.0) : 0.5;
    const double width = 2 * radius_ / kBins;
    const double x = std::clamp(-radius_ + (static_cast<double>(i) + t) * width, lo, hi);
    const double p = pdf_1d(x) / mass;
    weight = p > 0 ? eval(x) / (p * integral) : 0.0;
    return x;
}

double ReconstructionFilter::pdf_1d(double x) const {
    if (std::abs(x) > radius_) return 0.0;
    const double width = 2 * radius_ / kBins;
    const auto i = std::min<std::size_t>(static_cast<std::size_t>((x + radius_) / width), kBins - 1);
    return (cdf_[i + 1] - cdf_[i]) / width;
}

ReconstructionFilter::Sample ReconstructionFilter::sample(Vec2 u, Vec2 lo, Vec2 hi) const {
    double wx = 0, wy = 0;
    Sample s;
    s.offset = {sample_1d(u.x, lo.x, hi.x, wx), sample_1d(u.y, lo.y, hi.y, wy)};
    s.weight = wx * wy;
    return s;
}

double ReconstructionFilter::pdf(Vec2 offset) const { return pdf_1d(offset.x) * pdf_1d(offset.y); }

}  // namespace surfscatter::render
