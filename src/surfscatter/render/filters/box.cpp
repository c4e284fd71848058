// Mitsuba's `box` reconstruction filter.
//
// Supported: no parameters (as Mitsuba). f(x) = 1 on [-1/2, 1/2), radius 1/2 pixel: each sample stays in its pixel.
// Differences: none in expectation (see filter.hpp on filter importance sampling versus Mitsuba's splatting).
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render::plugins {

double box_profile(double x, const double*) { return x >= -0.5 && x < 0.5 ? 1.0 : 0.0; }

FilterPtr box(Properties&) { return make_box_filter(); }

}  // namespace surfscatter::render::plugins

namespace surfscatter::render {
FilterPtr make_box_filter() {
    return std::make_shared<ReconstructionFilter>("box", 0.5, plugins::box_profile, std::vector<double>{});
}
}  // namespace surfscatter::render
