#include "bake/parallel_jobs.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace tetprobe {

void run_jobs(size_t count, uint32_t threads, const std::function<void(size_t)>& job, const Progress& progress,
              const char* stage) {
    size_t workers = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
    workers = std::max<size_t>(1, std::min(workers, count));
    std::atomic<size_t> next{0}, done{0};
    std::atomic<bool> stop{false};
    std::mutex mutex;
    std::condition_variable progressed;
    std::exception_ptr failure;
    auto work = [&]() {
        try {
            for (size_t i; !stop.load(std::memory_order_relaxed) && (i = next.fetch_add(1)) < count;) {
                job(i);
                if (done.fetch_add(1) + 1 == count) progressed.notify_one();
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex);
            if (!failure) failure = std::current_exception();
            stop = true;
        }
        progressed.notify_one();
    };
    std::vector<std::thread> pool;
    for (size_t t = 0; t < workers; ++t) pool.emplace_back(work);
    std::exception_ptr cancelled;
    while (true) {
        const size_t finished = done.load();
        try {
            progress.report(count ? double(finished) / double(count) : 1.0, stage);
        } catch (...) {
            cancelled = std::current_exception();
            stop = true;
        }
        if (finished == count || stop.load()) break;
        std::unique_lock<std::mutex> lock(mutex);
        progressed.wait_for(lock, std::chrono::milliseconds(20));
    }
    for (std::thread& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
    if (cancelled) std::rethrow_exception(cancelled);
}

}  // namespace tetprobe
