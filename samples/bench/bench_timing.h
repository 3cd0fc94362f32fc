// Timing helpers shared by the store benchmark's peers: a steady clock and the median of repetitions.
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>
#include <vector>

namespace bench {

using Clock = std::chrono::steady_clock;

// Repetitions of every timed query loop (build timings use 3).
constexpr int kRepetitions = 5;

inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Median over `repetitions` runs of `run`, which returns its own elapsed seconds.
inline double median_seconds(const std::function<double()>& run, int repetitions = kRepetitions) {
    std::vector<double> times;
    for (int i = 0; i < repetitions; ++i) times.push_back(run());
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
}

}  // namespace bench
