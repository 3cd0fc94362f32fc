// Version, thread-local errors and status names.
#include "boundary.h"

#include <atomic>
#include <cstdarg>
#include <cstdio>
#include <cstring>

namespace tetprobe {

namespace {
// The calling thread's message, or null for none: a literal, t_formatted, or t_built's text. Every
// call clears it with this one thread-local write at most (each thread-local access from a shared library
// is a call into the dynamic linker, and a std::string's costs more: a guard and an init check).
thread_local const char* t_message = nullptr;
thread_local char t_formatted[320];
thread_local std::string t_built;
// Set for good when any thread first records a message. Until then every thread's t_message is null,
// so clearing can skip the thread-local access (about 3 ns of a 35 ns query). A thread that records one
// sets this itself first, so it always sees it when it next clears (program order; relaxed is enough).
std::atomic<bool> g_recorded{false};

void record(const char* message) {
    g_recorded.store(true, std::memory_order_relaxed);
    t_message = message;
}
}

tp_status fail(tp_status status, const std::string& message) {
    record(nullptr);
    try {
        t_built = message;
        record(t_built.c_str());
    } catch (...) {
        // out of memory while recording: no message (tp_last_error gives "") is still safe
    }
    return status;
}

tp_status fail_static(tp_status status, const char* message) {
    record(message);
    return status;
}

tp_status fail_formatted(tp_status status, const char* format, ...) {
    va_list arguments;
    va_start(arguments, format);
    std::vsnprintf(t_formatted, sizeof t_formatted, format, arguments);
    va_end(arguments);
    record(t_formatted);
    return status;
}

void clear_error() {
    if (g_recorded.load(std::memory_order_relaxed)) t_message = nullptr;
}

}  // namespace tetprobe

extern "C" {

TP_API uint32_t tp_version(void) { return TP_VERSION; }

TP_API const char* tp_last_error(void) { return tetprobe::t_message ? tetprobe::t_message : ""; }

TP_API const char* tp_status_name(tp_status status) {
    // C callers may pass any int; reading it as the enum would be undefined in C++ when out of range.
    int value;
    std::memcpy(&value, &status, sizeof value);
    switch (value) {
        case TP_OK: return "TP_OK";
        case TP_ERROR_INVALID_ARGUMENT: return "TP_ERROR_INVALID_ARGUMENT";
        case TP_ERROR_OUT_OF_MEMORY: return "TP_ERROR_OUT_OF_MEMORY";
        case TP_ERROR_IO: return "TP_ERROR_IO";
        case TP_ERROR_INVALID_BLOB: return "TP_ERROR_INVALID_BLOB";
        case TP_ERROR_VERSION: return "TP_ERROR_VERSION";
        case TP_ERROR_DEGENERATE: return "TP_ERROR_DEGENERATE";
        case TP_ERROR_TETGEN: return "TP_ERROR_TETGEN";
        case TP_ERROR_CANCELLED: return "TP_ERROR_CANCELLED";
        case TP_ERROR_OUTSIDE: return "TP_ERROR_OUTSIDE";
        case TP_ERROR_SCENE: return "TP_ERROR_SCENE";
        case TP_ERROR_UNSUPPORTED: return "TP_ERROR_UNSUPPORTED";
        case TP_ERROR_BUFFER_TOO_SMALL: return "TP_ERROR_BUFFER_TOO_SMALL";
        case TP_ERROR_INTERNAL: return "TP_ERROR_INTERNAL";
    }
    return "TP_ERROR_UNKNOWN";
}

}  // extern "C"
