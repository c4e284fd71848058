// Mitsuba's `catmullrom` reconstruction filter: the Mitchell-Netravali cubic (mitchell.cpp) with B = 0, C = 1/2.
//
// Supported: no parameters (as Mitsuba). Radius 2 pixels, negative lobes (signed sample weights, filter.hpp).
// Differences: none in expectation.
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render::plugins {

FilterPtr catmullrom(Properties&) {
    return std::make_shared<ReconstructionFilter>("catmullrom", 2.0, mitchell_netravali_profile, std::vector<double>{0.0, 0.5});
}

}  // namespace surfscatter::render::plugins
