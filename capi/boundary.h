// The C ABI boundary: every tp_ function body sits between TP_API_BEGIN and TP_API_END, which turn
// any C++ exception (and TetGen's int throws) into a status and a thread-local message.
#pragma once

#include "capi/tetprobe.h"
#include "core/error.h"
#include "core/store.h"
#include "core/store_format.h"

#include <new>
#include <string>

namespace tetprobe {

// Records the calling thread's message and returns status (so `return fail(...)` reads naturally).
tp_status fail(tp_status status, const std::string& message);
// The same without allocating (the query paths): a message that lives for ever (a literal), or one
// printf-formatted into a fixed per-thread buffer (cut at 319 characters).
tp_status fail_static(tp_status status, const char* message);
tp_status fail_formatted(tp_status status, const char* format, ...) __attribute__((format(printf, 2, 3)));
void clear_error();

// The one translation of the run time's statuses and flags into the C ABI's: the values are equal.
#define TP_SAME_VALUE(c, core) static_assert(int(c) == int(core), #c " must equal " #core)
TP_SAME_VALUE(TP_OK, Status::ok);
TP_SAME_VALUE(TP_ERROR_INVALID_ARGUMENT, Status::invalid_argument);
TP_SAME_VALUE(TP_ERROR_OUT_OF_MEMORY, Status::out_of_memory);
TP_SAME_VALUE(TP_ERROR_IO, Status::io);
TP_SAME_VALUE(TP_ERROR_INVALID_BLOB, Status::invalid_blob);
TP_SAME_VALUE(TP_ERROR_VERSION, Status::version);
TP_SAME_VALUE(TP_ERROR_DEGENERATE, Status::degenerate);
TP_SAME_VALUE(TP_ERROR_TETGEN, Status::tetgen);
TP_SAME_VALUE(TP_ERROR_CANCELLED, Status::cancelled);
TP_SAME_VALUE(TP_ERROR_OUTSIDE, Status::outside);
TP_SAME_VALUE(TP_ERROR_SCENE, Status::scene);
TP_SAME_VALUE(TP_ERROR_UNSUPPORTED, Status::unsupported);
TP_SAME_VALUE(TP_ERROR_BUFFER_TOO_SMALL, Status::buffer_too_small);
TP_SAME_VALUE(TP_ERROR_INTERNAL, Status::internal);
TP_SAME_VALUE(TP_BUILD_NO_EXTRAPOLATION, kFlagNoExtrapolation);
TP_SAME_VALUE(TP_BUILD_INDEX32, kFlagIndex32);
TP_SAME_VALUE(TP_SH_ENCODING_HALF, kShHalf);
TP_SAME_VALUE(TP_SH_ENCODING_UNORM8, kShUnorm8);
TP_SAME_VALUE(TP_SH_ENCODING_HALF_L1, kShHalfL1);
TP_SAME_VALUE(TP_SH_ENCODING_UNORM8_L1, kShUnorm8L1);
TP_SAME_VALUE(TP_LAYOUT_FAST, kLayoutFast);
TP_SAME_VALUE(TP_LAYOUT_COMPACT, kLayoutCompact);
TP_SAME_VALUE(TP_LAYOUT_REBUILT, kLayoutRebuilt);
TP_SAME_VALUE(TP_CELL_INNER, CellKind::inner);
TP_SAME_VALUE(TP_CELL_OUTER, CellKind::outer);
#undef TP_SAME_VALUE

inline tp_status to_tp_status(Status status) { return static_cast<tp_status>(status); }
inline tp_status fail(Status status, const std::string& message) { return fail(to_tp_status(status), message); }

}  // namespace tetprobe

#define TP_API_BEGIN                                                                                  \
    try {                                                                                             \
        ::tetprobe::clear_error();

#define TP_API_END                                                                                    \
    }                                                                                                 \
    catch (const ::tetprobe::Error& e) {                                                              \
        return ::tetprobe::fail(::tetprobe::to_tp_status(e.status()), e.what());                                                \
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
