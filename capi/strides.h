// Caller buffers at the C ABI come with strides in bytes: 0 means tightly packed, anything else
// must hold a whole element, and count elements must fit in the address space.
#pragma once

#include "core/error.h"

#include <cstddef>
#include <cstdint>
#include <string>

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

}  // namespace tetprobe
