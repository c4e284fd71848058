#pragma once
// Reconstruction filters (Mitsuba's rfilter plugins, filters/*.cpp): separable, f(x, y) = f(x) f(y), each 1-D
// profile normalised here to integrate to 1 over [-radius, radius].
//
// The film uses filter importance sampling (pbrt-v4): a sample for pixel p is placed at p + d with d drawn from
// |f(x)| |f(y)| (a 1 024-bin piecewise-constant table of |f| per axis) and carries the weight w = f(d) / pdf(d),
// whose expectation is the filter's integral, 1; the pixel is sum(w L) / N. (pbrt-v4 divides by sum(w) instead,
// which is unstable for filters with negative lobes.) Mitsuba splats each sample into all pixels under the filter
// instead, which has the same expectation.
//
// Without hdrfilm's sample_border, Mitsuba only places samples inside the film (crop window), so a pixel near the
// edge is the filter-weighted mean over the part of its footprint inside the window. sample() reproduces this: the
// offset is drawn from |f| restricted to the window [lo, hi] and the weight is divided by the filter's integral over
// the window (from a table of bin integrals, accurate to ~1e-6 relative).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/math/vec.hpp"

namespace surfscatter::render {

class ReconstructionFilter {
public:
    // `profile` is the unnormalised 1-D filter on [-radius, radius] (Mitsuba's eval()).
    ReconstructionFilter(std::string name, double radius, double (*profile)(double x, const double* params),
                         std::vector<double> params);

    const std::string& name() const { return name_; }
    double radius() const { return radius_; }
    // Normalised 1-D profile: integrates to 1 over [-radius, radius].
    double eval(double x) const;
    // Integral of |eval| (1 for non-negative filters).
    double absolute_integral() const { return absolute_integral_; }

    struct Sample {
        Vec2 offset;    // from the pixel centre, pixels
        double weight;  // f / (pdf times the filter's integral over the allowed offsets); expectation 1
    };
    // Offsets restricted to [lo, hi] per axis (the crop window seen from the pixel centre); the default is the whole
    // footprint.
    Sample sample(Vec2 u) const { return sample(u, {-radius_, -radius_}, {radius_, radius_}); }
    Sample sample(Vec2 u, Vec2 lo, Vec2 hi) const;
    // Density of sample() at offset (pixels): |f(x)| |f(y)| / absolute_integral^2 up to the table's resolution.
    double pdf(Vec2 offset) const;

private:
    double sample_1d(double u, double lo, double hi, double& weight) const;
    double pdf_1d(double x) const;
    double cdf_at(const std::vector<double>& cdf, double x) const;  // table value at x (linear within a bin)

    std::string name_;
    double radius_;
    double (*profile_)(double, const double*);
    std::vector<double> params_;
    double normalisation_ = 1;
    double absolute_integral_ = 1;
    std::vector<double> cdf_;         // of |f| over kBins equal bins of [-radius, radius], normalised to 1
    std::vector<double> signed_cdf_;  // of the normalised f
    std::vector<std::uint32_t> guide_;  // first bin for u in [k, k + 1) / kBins
    bool constant_ = false;  // the profile is constant on its support (box): uniform offsets of weight 1, exactly
};
using FilterPtr = std::shared_ptr<const ReconstructionFilter>;

// Mitsuba's defaults, for scenes built in code: the box filter and hdrfilm's default gaussian (stddev 0.5).
FilterPtr make_box_filter();
FilterPtr make_gaussian_filter(double stddev = 0.5);

}  // namespace surfscatter::render
