#pragma once
// Builds a scattering model from its options, validating every option first (throws surfscatter::Error naming the
// option and the bad value, e.g. "gamma must be > 1, got 0.8").
#include <memory>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/model_options.hpp"

namespace surfscatter::bsdf {

void validate(const ModelOptions& options);
std::unique_ptr<Bsdf> make_bsdf(const ModelOptions& options);

}  // namespace surfscatter::bsdf
