#pragma once
// FFTW's planner (plan creation and destruction) is not thread-safe, fftw_execute is: every FFTW user in the
// library holds this one mutex while planning or destroying plans.
#include <mutex>

namespace surfscatter::heightmap {

std::mutex& fftw_planner_mutex();

}  // namespace surfscatter::heightmap
