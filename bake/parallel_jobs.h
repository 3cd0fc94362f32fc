// Independent jobs on a few threads, with progress and cancel reported on the calling thread (so a
// callback never runs on a worker). Each job writes only its own results, so the outcome does not
// depend on the thread count.
#pragma once

#include "capi/tetprobe.h"

#include <cstddef>
#include <cstdint>
#include <functional>

namespace tetprobe {

// A slice [from, to] of a caller's progress: long work made of stages reports each stage's own
// fraction through it.
struct ProgressRange {
    tp_progress_fn callback = nullptr;
    void* user = nullptr;
    float from = 0.0f, to = 1.0f;

    // Reports `fraction` of this slice; throws Error(Status::cancelled) when the callback asks to stop.
    void report(double fraction, const char* stage) const;
    // The sub-slice [a, b] of this one (a, b in [0, 1]).
    ProgressRange part(double a, double b) const;
};

// Runs job(i) for every i in [0, count) on up to `threads` threads (0 = all cores). Rethrows the
// first exception of a job; throws Error(Status::cancelled) when the progress callback returns
// non-zero (the remaining jobs are skipped).
void run_jobs(size_t count, uint32_t threads, const std::function<void(size_t)>& job, const ProgressRange& progress,
              const char* stage);

}  // namespace tetprobe
