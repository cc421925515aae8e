// The calling thread's CPU time: what a tick or a relight cost the thread itself, whatever the other threads and
// processes did meanwhile (wall time counts their turns on the core too).
#pragma once
#include <ctime>

namespace core {

inline double threadCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

} // namespace core
