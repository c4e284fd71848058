#include "surfscatter/bsdf/node_axis.hpp"

#include <limits>

#include "surfscatter/core/error.hpp"

namespace surfscatter::bsdf {

NodeAxis::NodeAxis(const std::vector<double>& wanted) {
    std::vector<std::uint64_t> edges;
    for (const double w : wanted) {
        if (!(w >= std::numeric_limits<double>::min() && w <= std::numeric_limits<double>::max()))
            fail("internal: axis node {} is not a positive normal number", w);
        const std::uint64_t lo = std::bit_cast<std::uint64_t>(w) >> kShift << kShift, hi = lo + (1ULL << kShift);
        const std::uint64_t e = w - std::bit_cast<double>(lo) <= std::bit_cast<double>(hi) - w ? lo : hi;
        if (edges.empty() || e > edges.back()) edges.push_back(e);
    }
    if (edges.size() < 2 || edges.size() > std::numeric_limits<std::uint16_t>::max())
        fail("internal: an axis needs 2 to 65535 nodes, got {}", edges.size());
    first_ = edges.front();
    last_cell_ = (edges.back() - first_) >> kShift;
    for (const std::uint64_t e : edges) node_.push_back(std::bit_cast<double>(e));
    for (std::size_t j = 0; j + 1 < node_.size(); ++j) inverse_width_.push_back(1.0 / (node_[j + 1] - node_[j]));
    inverse_width_.push_back(inverse_width_.back());
    interval_.resize(last_cell_ + 1);
    std::size_t j = 0;
    for (std::uint64_t cell = 0; cell <= last_cell_; ++cell) {
        while (j + 2 < edges.size() && edges[j + 1] <= first_ + (cell << kShift)) ++j;
        interval_[cell] = static_cast<std::uint16_t>(j);
    }
}

}  // namespace surfscatter::bsdf
