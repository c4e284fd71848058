#include "surfscatter/surface/self_convolution_table.hpp"

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/surface/radial_table.hpp"

namespace surfscatter::surface {

struct SelfConvolutionTable::Data {
    std::shared_ptr<const detail::RadialFamily> family;  // row m-1 holds P-hat^{*m}
};

namespace {

detail::RadialFamily build(const RadialStatistics& stats, int max_order) {
    detail::RadialFamily family;
    const detail::TransformSetup setup = detail::make_transform_setup(stats, max_order);
    family.grid = detail::stored_grid(setup);
    family.set_base(stats);
    std::vector<double> power(setup.rho.size(), 1.0);
    family.rows.reserve(max_order);
    for (int m = 1; m <= max_order; ++m) {
        for (std::size_t j = 0; j < power.size(); ++j) power[j] *= setup.rho[j];
        family.rows.push_back(detail::make_row(setup, power, 1.0, m, family.grid));
    }
    return family;
}

}  // namespace

SelfConvolutionTable::SelfConvolutionTable(std::shared_ptr<const Data> data)
    : data_(std::move(data)), max_order_(static_cast<int>(data_->family->rows.size())) {}

std::shared_ptr<const SelfConvolutionTable> SelfConvolutionTable::get(const RadialStatistics& stats, int max_order) {
    if (max_order < 1 || max_order > 100000) fail("self-convolution order must be in [1, 100000], got {}", max_order);
    const std::string key = fmt::format("selfconv:{}:M={}", stats.cache_key(), max_order);
    auto family = detail::cached_family(key, max_order, [&] { return build(stats, max_order); });
    return std::make_shared<const SelfConvolutionTable>(std::make_shared<const Data>(Data{std::move(family)}));
}

namespace {
void check_order(int m, int max_order) {
    if (m < 1 || m > max_order) fail("self-convolution order {} outside the table's 1..{}", m, max_order);
}
}  // namespace

double SelfConvolutionTable::eval(int m, double zeta) const {
    check_order(m, max_order_);
    return data_->family->value(m - 1, zeta);
}

double SelfConvolutionTable::radial_cdf(int m, double zeta) const {
    check_order(m, max_order_);
    return data_->family->cdf(m - 1, zeta);
}

double SelfConvolutionTable::inverse_radial_cdf(int m, double u) const {
    check_order(m, max_order_);
    return data_->family->inverse_cdf(m - 1, u);
}

}  // namespace surfscatter::surface
