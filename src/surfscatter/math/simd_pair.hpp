#pragma once
// Two doubles in one SSE2 register (GNU vector extension), for interpolations that carry two independent quantities
// through the same weights: the lobe table's bicubic (g and zeta weights, pairs of taps) and the GHS incidence table
// (ln sigma and ln N). The x86-64 baseline has SSE2, so this needs no target flags.
#include <cstring>

namespace surfscatter::math {

using Pair = double __attribute__((vector_size(16)));

inline Pair load_pair(const double* p) {
    Pair v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

}  // namespace surfscatter::math
