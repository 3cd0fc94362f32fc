// Caller buffers at the C ABI: count elements of a fixed size, stride bytes apart (0 = packed). Every
// entry point checks each buffer it is handed with checked_buffer (or checked_packed for a buffer
// without a stride) before touching it, and reads and writes the elements with memcpy, so that
// neither the pointer nor the stride needs any alignment.
#pragma once

#include "core/error.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace tetprobe {

// Whether count elements of element_bytes at stride bytes fit in one object starting at data: their
// span, (count - 1) * stride + element_bytes, is at most PTRDIFF_MAX (no object is larger) and does
// not run past the end of the address space.
inline bool buffer_fits(const void* data, size_t count, size_t stride, size_t element_bytes) {
    if (count == 0) return true;
    const size_t largest = size_t(PTRDIFF_MAX);
    if (element_bytes > largest || (count - 1) > (largest - element_bytes) / (stride ? stride : 1)) return false;
    const size_t span = (count - 1) * stride + element_bytes;
    return span - 1 <= UINTPTR_MAX - reinterpret_cast<uintptr_t>(data);
}

// Checks a caller's buffer of count elements of element_bytes at stride bytes (0 = packed) and returns
// the stride to use. Throws Error(Status::invalid_argument) naming the parameter: data NULL with
// count > 0, a stride smaller than one element, or count elements at that stride overflowing
// (buffer_fits). stride_name NULL: the buffer has no stride parameter (always packed).
inline size_t checked_buffer(const void* data, const char* data_name, size_t count, const char* count_name,
                             size_t stride, const char* stride_name, size_t element_bytes) {
    if (count == 0) return stride ? stride : element_bytes;
    if (!data) throw Error(Status::invalid_argument, std::string(data_name) + " is NULL");
    if (stride == 0) stride = element_bytes;
    if (stride < element_bytes)
        throw Error(Status::invalid_argument, std::string(stride_name) + " (" + std::to_string(stride) +
                                                  ") is smaller than one element of " + data_name + " (" +
                                                  std::to_string(element_bytes) + " bytes; use 0 for packed)");
    if (!buffer_fits(data, count, stride, element_bytes)) {
        std::string what = std::string(count_name) + " (" + std::to_string(count) + ") elements of " + data_name;
        what += stride_name ? " at " + std::string(stride_name) + " (" + std::to_string(stride) + " bytes)"
                            : " of " + std::to_string(element_bytes) + " bytes";
        throw Error(Status::invalid_argument, what + " overflow the address space");
    }
    return stride;
}

// checked_buffer for a buffer without a stride parameter.
inline void checked_packed(const void* data, const char* data_name, size_t count, const char* count_name,
                           size_t element_bytes) {
    checked_buffer(data, data_name, count, count_name, 0, nullptr, element_bytes);
}

// Element i of a checked buffer, as bytes (never as a typed pointer: it may be misaligned).
inline const unsigned char* element_at(const void* data, size_t i, size_t stride) {
    return static_cast<const unsigned char*>(data) + i * stride;
}
inline unsigned char* element_at(void* data, size_t i, size_t stride) {
    return static_cast<unsigned char*>(data) + i * stride;
}

// Copies count strided positions (3 floats each) into out; throws Error(Status::invalid_argument) for a
// bad buffer (checked_buffer) or a non-finite coordinate (naming the position).
inline void copy_finite_positions(const float* positions, size_t stride, size_t count, std::vector<float>& out,
                                  const char* count_name = "count") {
    stride = checked_buffer(positions, "positions", count, count_name, stride, "position_stride", 3 * sizeof(float));
    out.resize(3 * count);
    for (size_t i = 0; i < count; ++i) {
        float p[3];
        std::memcpy(p, element_at(positions, i, stride), sizeof p);
        for (int a = 0; a < 3; ++a) {
            if (!std::isfinite(p[a]))
                throw Error(Status::invalid_argument, "position " + std::to_string(i) + " is not finite");
            out[3 * i + a] = p[a];
        }
    }
}

}  // namespace tetprobe
