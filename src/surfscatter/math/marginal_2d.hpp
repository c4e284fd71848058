#pragma once
// A density on the unit square that interpolates a grid of non-negative values bilinearly, conditioned on up to
// three parameters between whose nodes it is interpolated linearly: the warp of Dupuy & Jakob, "An Adaptive
// Parameterization for Efficient Material Acquisition and Rendering" (ACM TOG 37(6), 2018), Sec. 5, that the RGL
// measured BSDF format prescribes for its VNDF, luminance and spectral tables (bsdf/rgl_measured.hpp).
//
// Grid: ny rows of nx values (row-major, x fastest), node (i, j) at (i / (nx - 1), j / (ny - 1)); the parameter
// slices are stored one after another, the first parameter slowest. Sampling inverts the marginal CDF in y and then
// the conditional CDF in x of the bilinear interpolant exactly (quadratic inversion per cell); invert() is its
// inverse, the map from a point to the uniform variates that draw it. A parameter outside its nodes takes the
// nearest slice (the format's rule: its nodes span the domain the file was measured on).
#include <array>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "surfscatter/math/vec.hpp"

namespace surfscatter {

class Marginal2D {
public:
    static constexpr std::size_t kMaxParams = 3;

    Marginal2D() = default;
    // `normalize`: each slice scaled to integrate to 1 over the unit square (needed for sample/invert); without it
    // eval() is the plain interpolation of the values. Throws Error on a size below 2, a count mismatch, a negative
    // or non-finite value, parameter nodes that do not increase, or (normalize) a slice that integrates to 0.
    Marginal2D(const std::vector<double>& data, std::size_t nx, std::size_t ny,
               std::vector<std::vector<double>> param_nodes, bool normalize);

    double eval(Vec2 p, std::span<const double> params = {}) const;
    // Point drawn from uniform variates u and its density; and the inverse map with the density at p.
    std::pair<Vec2, double> sample(Vec2 u, std::span<const double> params = {}) const;
    std::pair<Vec2, double> invert(Vec2 p, std::span<const double> params = {}) const;

    std::size_t nx() const { return nx_; }
    std::size_t ny() const { return ny_; }

private:
    struct Blend {  // the slices a parameter vector mixes and their weights
        std::array<std::size_t, 8> slice{};
        std::array<double, 8> weight{};
        int count = 0;
    };
    Blend blend(std::span<const double> params) const;
    static double fetch(const std::vector<double>& table, std::size_t slice_size, const Blend& b, std::size_t i) {
        double v = 0;
        for (int k = 0; k < b.count; ++k) v += b.weight[k] * table[b.slice[k] * slice_size + i];
        return v;
    }

    std::size_t nx_ = 0, ny_ = 0;
    std::vector<std::vector<double>> nodes_;
    std::vector<std::size_t> strides_;
    std::vector<double> data_;          // normalised values (times (nx-1)(ny-1) in eval)
    std::vector<double> conditional_;   // per row: cumulative integral along x, index units
    std::vector<double> marginal_;      // per slice: cumulative integral over rows, index units (total 1)
};

}  // namespace surfscatter
