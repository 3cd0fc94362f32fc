// The C ABI boundary: every tp_ function body sits between TP_API_BEGIN and TP_API_END, which turn
// any C++ exception (and TetGen's int throws) into a status and a thread-local message.
#pragma once

#include "capi/tetprobe.h"
#include "core/error.h"

#include <new>
#include <string>

namespace tetprobe {

// Records the calling thread's message and returns status (so `return fail(...)` reads naturally).
tp_status fail(tp_status status, const std::string& message);
void clear_error();

}  // namespace tetprobe

#define TP_API_BEGIN                                                                                  \
    try {                                                                                             \
        ::tetprobe::clear_error();

#define TP_API_END                                                                                    \
    }                                                                                                 \
    catch (const ::tetprobe::Error& e) {                                                              \
        return ::tetprobe::fail(e.status(), e.what());                                                \
    }                                                                                                 \
    catch (const std::bad_alloc&) {                                                                   \
        return ::tetprobe::fail(TP_ERROR_OUT_OF_MEMORY, "out of memory");                             \
    }                                                                                                 \
    catch (const std::exception& e) {                                                                 \
        return ::tetprobe::fail(TP_ERROR_INTERNAL, std::string("internal error: ") + e.what());      \
    }                                                                                                 \
    catch (int code) {                                                                                \
        return ::tetprobe::fail(TP_ERROR_TETGEN, "TetGen failed with code " + std::to_string(code)); \
    }                                                                                                 \
    catch (...) {                                                                                     \
        return ::tetprobe::fail(TP_ERROR_INTERNAL, "internal error: unknown exception");              \
    }

// Returns TP_ERROR_INVALID_ARGUMENT naming the parameter when a required pointer is null.
#define TP_REQUIRE_NOT_NULL(p)                                                                        \
    do {                                                                                              \
        if (!(p)) return ::tetprobe::fail(TP_ERROR_INVALID_ARGUMENT, #p " is NULL");                  \
    } while (0)
