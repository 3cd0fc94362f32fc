// Version, thread-local errors and status names.
#include "boundary.h"

#include <cstdarg>
#include <cstdio>
#include <cstring>

namespace tetprobe {

namespace {
// The calling thread's message: a built one (t_last_error), or one without allocation (t_message:
// a static string, or t_formatted), which the queries use.
thread_local std::string t_last_error;
thread_local const char* t_message = nullptr;
thread_local char t_formatted[320];
}

tp_status fail(tp_status status, const std::string& message) {
    t_message = nullptr;
    try {
        t_last_error = message;
    } catch (...) {
        t_last_error.clear();  // out of memory while recording: an empty message is still safe
    }
    return status;
}

tp_status fail_static(tp_status status, const char* message) {
    t_message = message;
    return status;
}

tp_status fail_formatted(tp_status status, const char* format, ...) {
    va_list arguments;
    va_start(arguments, format);
    std::vsnprintf(t_formatted, sizeof t_formatted, format, arguments);
    va_end(arguments);
    t_message = t_formatted;
    return status;
}

void clear_error() {
    t_message = nullptr;
    t_last_error.clear();
}

}  // namespace tetprobe

extern "C" {

TP_API uint32_t tp_version(void) { return TP_VERSION; }

TP_API const char* tp_last_error(void) { return tetprobe::t_message ? tetprobe::t_message : tetprobe::t_last_error.c_str(); }

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
