// CPU time for the benches' timings: the calling thread's CPU seconds, which the other jobs of a shared machine
// distort far less than wall time (bench/README.md), and the best time per call over rounds.
#pragma once

#include <algorithm>
#include <cmath>
#include <ctime>

namespace prm::bench {

inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Best CPU time per call of `call` (single-threaded) over `rounds` rounds of at least 50 ms each.
template <typename F>
double best_cpu_time(F&& call, int rounds) {
  double best = HUGE_VAL;
  int inner = 1;
  for (int r = 0; r < rounds; ++r) {
    const double t0 = thread_cpu_seconds();
    for (int k = 0; k < inner; ++k) call();
    const double t = (thread_cpu_seconds() - t0) / inner;
    best = std::min(best, t);
    inner = static_cast<int>(std::clamp(std::ceil(0.05 / std::max(t, 1e-9)), 1.0, 1e5));
  }
  return best;
}

}  // namespace prm::bench
