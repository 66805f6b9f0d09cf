#pragma once
// CPU time of the parts of the work on updates (PipelineInstrumentation::time_phases).

#include <ctime>

#include "kew/pipeline/instrumentation.hpp"

namespace kew::pipeline {

/// CPU time of the calling thread (s): the split must not count time the thread waited.
inline double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Runs f, adding its CPU time to `phase` of `into` when `on`.
template <class F>
void timed(bool on, PhaseTimes& into, double PhaseTimes::*phase, F&& f) {
  if (!on) {
    f();
    return;
  }
  const double start = thread_cpu_s();
  f();
  into.*phase += thread_cpu_s() - start;
}

}  // namespace kew::pipeline
