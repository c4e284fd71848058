#include "surfscatter/heightmap/fftw_planner.hpp"

namespace surfscatter::heightmap {

std::mutex& fftw_planner_mutex() {
    static std::mutex mutex;
    return mutex;
}

}  // namespace surfscatter::heightmap
