// Independent jobs on a few threads, with progress and cancel reported on the calling thread (so a
// callback never runs on a worker). Each job writes only its own results, so the outcome does not
// depend on the thread count.
#pragma once

#include "bake/progress.h"

#include <cstddef>
#include <cstdint>
#include <functional>

namespace tetprobe {

// Runs job(i) for every i in [0, count) on up to `threads` threads (0 = all cores), reporting the
// fraction of jobs done under `stage`. Rethrows the first exception of a job; throws
// Error(Status::cancelled) when the progress callback returns non-zero (the remaining jobs are skipped).
void run_jobs(size_t count, uint32_t threads, const std::function<void(size_t)>& job, const Progress& progress,
              const char* stage);

}  // namespace tetprobe
