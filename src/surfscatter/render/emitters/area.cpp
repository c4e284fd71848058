// Mitsuba's `area` emitter, nested in a shape: the shape emits `radiance` from its front side (the side its normal
// points to; flip_normals turns it), is hit by BSDF sampling and sampled uniformly by area for next-event
// estimation (scene.cpp).
//
// Supported: `radiance` (spectrum or <rgb> upsampled and times D65; default 1).
// Differences: none (a textured radiance is an error).
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

SpectrumPtr plugins::area(Properties& props) { return props.get_spectrum("radiance", true, 1.0); }

}  // namespace surfscatter::render
