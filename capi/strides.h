// Caller buffers at the C ABI come with strides in bytes: 0 means tightly packed, anything else
// must hold a whole element, and count elements must fit in the address space.
#pragma once

#include "core/error.h"

#include <cstddef>
#include <cstdint>
#include <cmath>
#include <string>
#include <vector>

namespace tetprobe {

// The stride to use; throws Error(Status::invalid_argument) naming the parameter when it is too small.
inline size_t resolve_stride(size_t stride, size_t element, const char* name) {
    if (stride == 0) return element;
    if (stride < element)
        throw Error(Status::invalid_argument, std::string(name) + " (" + std::to_string(stride) +
                                                   ") is smaller than one element (" + std::to_string(element) +
                                                   " bytes; use 0 for packed)");
    return stride;
}

// Throws Error(Status::invalid_argument) when count records of record_bytes at stride overflow size_t.
inline void require_addressable(size_t count, size_t stride, size_t record_bytes, const char* what) {
    if (count > 0 && (count - 1) > (SIZE_MAX - record_bytes) / stride)
        throw Error(Status::invalid_argument, std::string(what) + ": count times stride overflows");
}

// Copies count strided positions (3 floats each) into out; throws Error(Status::invalid_argument) for a
// NULL buffer, a bad stride, or a non-finite coordinate (naming the position).
inline void copy_finite_positions(const float* positions, size_t stride, size_t count, std::vector<float>& out) {
    if (count > 0 && !positions) throw Error(Status::invalid_argument, "positions is NULL");
    stride = resolve_stride(stride, 3 * sizeof(float), "position_stride");
    require_addressable(count, stride, 3 * sizeof(float), "positions");
    out.resize(3 * count);
    for (size_t i = 0; i < count; ++i) {
        const float* p = reinterpret_cast<const float*>(reinterpret_cast<const char*>(positions) + i * stride);
        for (int a = 0; a < 3; ++a) {
            if (!std::isfinite(p[a]))
                throw Error(Status::invalid_argument, "position " + std::to_string(i) + " is not finite");
            out[3 * i + a] = p[a];
        }
    }
}

}  // namespace tetprobe
