#pragma once
// An interpolation axis over positive numbers whose node interval is found without arithmetic: the exponent and the
// top kBits mantissa bits of x cut the axis into cells (256 per octave, uniform within one), every node lies on a
// cell edge, and one table entry per cell names the node interval it lies in. A query is then an integer subtraction
// and shift, two loads and a multiply, where a logarithm or an arccos before a float-to-int conversion made up most
// of the GHS lookup's latency. Between nodes the interpolation is linear in x.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

namespace surfscatter::bsdf {

class NodeAxis {
public:
    static constexpr int kBits = 8;

    // Nodes as close as the cells allow to `wanted` (increasing, positive, normal numbers; coincident roundings are
    // merged); the axis covers [wanted.front(), wanted.back()].
    explicit NodeAxis(const std::vector<double>& wanted);

    struct Position {
        int interval;  // nodes interval and interval + 1
        double t;      // in [0, 1] inside the axis
    };
    // x in [node(0), node(size() - 1)] (callers clamp or reject; outside, the end intervals extrapolate).
    Position position(double x) const {
        const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
        const std::uint64_t cell = bits >= first_ ? std::min((bits - first_) >> kShift, last_cell_) : 0;
        const int j = interval_[cell];
        return {j, (x - node_[j]) * inverse_width_[j]};
    }
    int size() const { return static_cast<int>(node_.size()); }
    double node(int j) const { return node_[j]; }

private:
    static constexpr int kShift = 52 - kBits;
    std::uint64_t first_;      // bits of the first node (a cell edge)
    std::uint64_t last_cell_;  // cell of the last node
    std::vector<std::uint16_t> interval_;
    std::vector<double> node_, inverse_width_;
};

}  // namespace surfscatter::bsdf
