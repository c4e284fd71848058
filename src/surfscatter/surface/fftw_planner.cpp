#include "surfscatter/surface/fftw_planner.hpp"

namespace surfscatter::surface {

std::mutex& fftw_planner_mutex() {
    static std::mutex mutex;
    return mutex;
}

}  // namespace surfscatter::surface
