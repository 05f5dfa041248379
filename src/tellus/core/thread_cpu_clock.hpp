#pragma once
// CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID), for work done on worker threads:
// the harness reports how much CPU a renderer's background threads spend per frame (tile
// loads, data reorganisation), apart from the render thread's.
#include <ctime>

namespace tellus {

// Seconds of CPU the calling thread has used since it started.
inline double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

}  // namespace tellus
