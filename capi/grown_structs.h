// Structs that grow at their end (tp_store_info, tp_location, tp_effects_plan): the library fills a full
// local copy and writes back only what the caller's struct_size holds, so an older caller's smaller
// struct is never written past its end.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace tetprobe {

// Writes the fields of T that fit in struct_size bytes from full (struct_size itself is left as given).
template <class T>
void copy_fitting_fields(T* out, const T& full, uint32_t struct_size) {
    const size_t n = struct_size < sizeof(T) ? struct_size : sizeof(T);
    std::memcpy(reinterpret_cast<unsigned char*>(out) + sizeof(uint32_t),
                reinterpret_cast<const unsigned char*>(&full) + sizeof(uint32_t), n - sizeof(uint32_t));
}

}  // namespace tetprobe
