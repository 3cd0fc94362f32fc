#include "bake/tetgen_guard.h"

#include <csetjmp>
#include <csignal>

#if defined(__SANITIZE_ADDRESS__)
#define TP_LEAK_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TP_LEAK_SANITIZER 1
#endif
#endif
#if defined(TP_LEAK_SANITIZER)
#include <sanitizer/lsan_interface.h>
#endif

namespace tetprobe {

namespace {

constexpr int kFatalSignals[] = {SIGABRT, SIGSEGV, SIGBUS, SIGFPE};
constexpr int kSignalCount = sizeof(kFatalSignals) / sizeof(kFatalSignals[0]);

thread_local sigjmp_buf* t_recovery = nullptr;

void on_fatal_signal(int signal) {
    if (sigjmp_buf* recovery = t_recovery) siglongjmp(*recovery, signal);
    // Another thread's fatal signal is not ours to swallow: die as it would have.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

}  // namespace

std::mutex& tetgen_mutex() {
    static std::mutex mutex;
    return mutex;
}

bool call_guarded_against_crashes(void (*fn)(void*), void* context) {
    struct sigaction action = {};
    action.sa_handler = &on_fatal_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_NODEFER;
    struct sigaction previous[kSignalCount];
    for (int i = 0; i < kSignalCount; ++i) sigaction(kFatalSignals[i], &action, &previous[i]);

#if defined(TP_LEAK_SANITIZER)
    __lsan_disable();  // what a crashed attempt leaves behind is leaked on purpose
#endif
    sigjmp_buf recovery;
    volatile bool survived = false;
    if (sigsetjmp(recovery, 1) == 0) {
        t_recovery = &recovery;
        fn(context);
        survived = true;
    }
    t_recovery = nullptr;
#if defined(TP_LEAK_SANITIZER)
    __lsan_enable();
#endif
    for (int i = 0; i < kSignalCount; ++i) sigaction(kFatalSignals[i], &previous[i], nullptr);
    return survived;
}

}  // namespace tetprobe
